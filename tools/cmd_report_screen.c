/* tools/cmd_report_screen.c - voxgi report ao and report ssgi: the screen-space passes' error
 * against run time (one parameter at a time around a base configuration), as Markdown and CSV;
 * for ambient occlusion how much it changes at fixed points over a camera orbit, for the bounce
 * the light the screen cannot see and a red wall at the edge of the view. */
#include "report.h"
#include <stdlib.h>
#include <string.h>

#define SCREEN_PI 3.14159265358979323846

enum { SCREEN_AO, SCREEN_SSGI };
static const char *const report_names[] = {"ao", "ssgi"};

/* The methods, as the rows name them. */
enum { M_SSAO, M_SSAO_POINTS, M_VAO, M_SSGI, M_HYBRID, M_HYBRID_LIGHT };
static const char *const method_names[] = {"ssao", "ssao-points", "vao", "ssgi", "hybrid", "hybrid+light"};
static const int ao_methods[] = {M_SSAO, M_SSAO_POINTS, M_VAO}, gi_methods[] = {M_SSGI, M_HYBRID, M_HYBRID_LIGHT};

static const char *const ao_help =
    "usage: voxgi report ao [options]\n"
    "Error against run time of ambient occlusion from the depth buffer (SSAO: ray marching, and\n"
    "point sampling) and from the voxels (voxgi render --method ssao|vao). For each built-in scene\n"
    "it renders the reference's ambient occlusion (converged, --spp samples per pixel) at every\n"
    "radius, then varies one parameter at a time around a base (16 rays, 16 steps, radius 0.1 of\n"
    "the scene's longest side, 128 voxels, full resolution, no blur) over the lists below, and\n"
    "half resolution with each blur; each image is measured against the reference at its radius\n"
    "by the tools' rule (render --compare's). Then the view-independence: the Cornell box from 9\n"
    "cameras on an arc before its open front, each method's occlusion at the same surface points\n"
    "(every 4th pixel of the middle view) and how far it spreads over the views (the largest\n"
    "--rays), against its spread over 9 seeds of one view. Writes DIR/ao.md and DIR/ao.csv, the\n"
    "Pareto front of each scene and radius marked. Wall clock on this machine.\n";

static const char *const ssgi_help =
    "usage: voxgi report ssgi [options]\n"
    "Error against run time of one bounce from the screen: SSGI (through the depth buffer),\n"
    "Hybrid-GI (through the voxels) and Hybrid-GI with the hidden light (hybrid+light: hits the\n"
    "camera does not see send the light injected into their voxels) (voxgi render --method\n"
    "ssgi|hybrid, --hidden-light off|on). For each built-in scene\n"
    "it renders the reference's one bounce (converged, --spp samples per pixel), then varies one\n"
    "parameter at a time around a base (16 rays, 16 steps, radius 1 x the scene's longest side, 128\n"
    "voxels, full resolution, no blur) over the lists below, and half resolution with each blur,\n"
    "and measures the relative RMSE by the tools' rule (render --compare's) and the red light in\n"
    "excess of the reference's. Per scene also the direct light alone, the reference's bounce from\n"
    "the surfaces the camera sees alone (the floor of the screen's error: light from surfaces the\n"
    "camera does not see is missing), Hybrid-GI converged (256 rays, the finest --res, radius 1.75),\n"
    "also with the hidden light, and cone tracing's defaults. Then a wall barely in view: the\n"
    "Cornell box turned until its red wall is a sliver at the image's edge, then off screen, and\n"
    "the red light each method bleeds onto the rest, a share of the reference's. Writes\n"
    "DIR/ssgi.md and DIR/ssgi.csv, the Pareto front marked. Wall clock on this machine.\n";

#define SCREEN_MAX_SCENES 8
#define SCREEN_MAX_LIST 16
#define SCREEN_MAX_RADII (SCREEN_MAX_LIST + 1) /* the base's and --radii's */

typedef struct screen_args {
    cli_common common;
    int which;
    const char *out_dir, *scene_list;
    double rays[SCREEN_MAX_LIST], steps[SCREEN_MAX_LIST], radii[SCREEN_MAX_LIST], res[SCREEN_MAX_LIST], blurs[SCREEN_MAX_LIST];
    int nrays, nsteps, nradii, nres, nblurs, size[2], spp;
} screen_args;

/* One configuration; a parameter its method does not use is 0 (steps for the voxels and for point
   sampling, res for the depth buffer). radius: a share of the scene's longest side. */
typedef struct screen_config {
    int method, rays, steps, res, half, blur, hidden; /* hidden: hybrid+light's hidden light */
    double radius;
} screen_config;

typedef struct screen_row {
    int scene, pareto, group; /* group: the front's (the scene's, and for ao its radius's) */
    screen_config c;
    size_t gathered;
    double ms_pass, ms, rmse, red, ref_ms; /* ms_pass: the occlusion's or the gathers' */
    double ms_parts[3], bytes;             /* ao: G-buffer, voxels; ssgi: direct light, voxels, their light; the memory */
} screen_row;

/* AO at fixed points over several passes (views or seeds): the points seen by two passes or more,
   the passes that see each (mean), and the spread (max - min) of each point's AO over them. */
typedef struct view_spread {
    size_t points;
    double passes, mean, p95;
} view_spread;

#define VIEW_COUNT 9  /* cameras on the arc, and seeds of the middle one */
#define VIEW_STRIDE 4 /* the points: the middle view's surfaces at every 4th pixel across and down */
#define VIEW_RES 128  /* the voxels of the voxels' AO */

/* The red wall of the Cornell box from three views: the reference's one bounce, the direct light
   alone, SSGI and Hybrid-GI (and Hybrid-GI with the hidden light, the extension that lets hits the
   camera does not see send the light injected into their voxels); each one's error and red light
   bled onto the rest of the image. */
enum { WALL_REFERENCE, WALL_DIRECT, WALL_SSGI, WALL_HYBRID, WALL_HIDDEN, WALL_METHODS };
static const char *const wall_view_names[3] = {"in view", "a sliver at the edge", "just off screen"};
static const char *const wall_method_names[WALL_METHODS] = {"reference, one bounce", "direct light alone", "SSGI", "Hybrid-GI",
                                                             "Hybrid-GI, hidden light"};
#define WALL_SLIVER 3      /* a sliver: no row holds more of the wall's pixels */
#define WALL_YAW_STEP 0.25 /* degrees */
#define WALL_RAYS 64
#define WALL_FINE 4        /* the wall's pixels: those any of 4 x 4 points sees it from */
typedef struct wall_view {
    double yaw;
    size_t red_pixels;
    int widest;
    /* bleed: the indirect light's red minus green; colour: the part of it the wall's colour makes
       (the image minus the same view with the wall grey) */
    double rmse[WALL_METHODS], bleed[WALL_METHODS], colour[WALL_METHODS];
} wall_view;

typedef struct screen_report {
    char scenes[SCREEN_MAX_SCENES][64];
    int scene_count, nrows, nradii;
    double radii[SCREEN_MAX_RADII];        /* ao: the references' radii (shares), the base's first */
    double longest[SCREEN_MAX_SCENES];
    double ref_c[SCREEN_MAX_SCENES][SCREEN_MAX_RADII], ref_ms_per_spp[SCREEN_MAX_SCENES][SCREEN_MAX_RADII];
    size_t masked[SCREEN_MAX_SCENES];
    double direct_rmse[SCREEN_MAX_SCENES];  /* ssgi: the direct light alone */
    double screen_rmse[SCREEN_MAX_SCENES];  /* ssgi: the reference's bounce from the surfaces the camera sees alone */
    screen_row converged[SCREEN_MAX_SCENES], hidden[SCREEN_MAX_SCENES]; /* ssgi: Hybrid-GI converged, without and with the hidden light */
    double vct_rmse[SCREEN_MAX_SCENES], vct_ms[SCREEN_MAX_SCENES];
    view_spread views[2][2][2];             /* ao: [the orbit, the seeds][at the pixel, at the point][depth buffer, voxels] */
    int view_rays;
    double view_radius;
    wall_view walls[3];                     /* ssgi */
    voxgi_info ci;
    screen_row *rows;
} screen_report;

/* ------------------------------------------------------------------ configurations */
static int uses_steps(int m) { return m == M_SSAO || m == M_SSGI; }
static int uses_res(int m) { return m == M_VAO || m == M_HYBRID || m == M_HYBRID_LIGHT; }

static screen_config base_config(int which, int method)
{
    screen_config c;
    memset(&c, 0, sizeof c);
    c.method = method;
    c.rays = 16;
    c.steps = uses_steps(method) ? 16 : 0;
    c.res = uses_res(method) ? 128 : 0;
    c.radius = which == SCREEN_AO ? REPORT_AO_RADIUS : 1; /* report all measures ao at this one */
    c.hidden = method == M_HYBRID_LIGHT;
    return c;
}

static int same_config(const screen_config *p, const screen_config *q)
{
    return p->method == q->method && p->rays == q->rays && p->steps == q->steps && p->res == q->res && p->half == q->half && p->blur == q->blur &&
           p->hidden == q->hidden && p->radius == q->radius;
}

/* c appended to list[0..n) unless it is there already; the new count. */
static int add_config(screen_config *list, int n, const screen_config *c)
{
    int i;
    for (i = 0; i < n; i++)
        if (same_config(&list[i], c)) return n;
    list[n] = *c;
    return n + 1;
}

#define SWEEP_MAX (6 * SCREEN_MAX_LIST)

/* The configurations of a method: each list's values with the rest at the base (the lists of
   parameters it does not use left out), then half resolution with each blur; each once. */
static int sweep(const screen_args *a, int method, screen_config *out)
{
    const screen_config base = base_config(a->which, method);
    screen_config c;
    int i, half, n = 0;
    for (i = 0; i < a->nrays; i++) { c = base; c.rays = (int)a->rays[i]; n = add_config(out, n, &c); }
    for (i = 0; i < a->nsteps && uses_steps(method); i++) { c = base; c.steps = (int)a->steps[i]; n = add_config(out, n, &c); }
    for (i = 0; i < a->nradii; i++) { c = base; c.radius = a->radii[i]; n = add_config(out, n, &c); }
    for (i = 0; i < a->nres && uses_res(method); i++) { c = base; c.res = (int)a->res[i]; n = add_config(out, n, &c); }
    for (half = 0; half < 2; half++)
        for (i = 0; i < a->nblurs; i++) { c = base; c.half = half; c.blur = (int)a->blurs[i]; n = add_config(out, n, &c); }
    return n;
}

/* "ssao, 16 rays, 16 steps, radius 0.1, half resolution, blur 2" */
static void config_text(const screen_config *c, char *buf, size_t size)
{
    int n = snprintf(buf, size, "%s, %d rays", method_names[c->method], c->rays);
    if (c->steps && n >= 0 && (size_t)n < size) n += snprintf(buf + n, size - (size_t)n, ", %d steps", c->steps);
    if (c->res && n >= 0 && (size_t)n < size) n += snprintf(buf + n, size - (size_t)n, ", %d voxels", c->res);
    if (n >= 0 && (size_t)n < size)
        snprintf(buf + n, size - (size_t)n, ", radius %g%s, blur %d%s", c->radius, c->half ? ", half resolution" : "", c->blur, c->hidden ? ", hidden light" : "");
}

/* The parameter columns of a row, for Markdown (sep " | ", "-" where unused) or CSV (sep ",", empty). */
static void config_columns(FILE *f, const screen_config *c, double longest, const char *sep, int csv)
{
    const char *none = csv ? "" : "-";
    fprintf(f, "%s%s%d%s", method_names[c->method], sep, c->rays, sep);
    if (c->steps) fprintf(f, "%d%s", c->steps, sep);
    else fprintf(f, "%s%s", none, sep);
    if (csv) fprintf(f, "%g,%.6g,", c->radius, c->radius * longest);
    else fprintf(f, "%g%s", c->radius, sep);
    if (c->res) fprintf(f, "%d%s", c->res, sep);
    else fprintf(f, "%s%s", none, sep);
    fprintf(f, "%s%s%d", csv ? (c->half ? "1" : "0") : (c->half ? "yes" : ""), sep, c->blur);
}

/* Renders configuration c of scene (its longest side `longest`) seen by cam into img; its
   measures of time into row. Every setting is given (a zero field of voxgi_render_desc is the
   method's measured default, not the configuration's): half resolution off or on, blur -1 for
   none, the hidden light off or on. */
static voxgi_result render_config(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_camera *cam, double longest, const screen_config *c, float *img,
                                  screen_row *row)
{
    size_t bytes = (size_t)cam->width * (size_t)cam->height * 12;
    int ao = c->method == M_SSAO || c->method == M_SSAO_POINTS || c->method == M_VAO;
    voxgi_render_desc d;
    voxgi_render_info info;
    voxgi_result r;
    memset(&d, 0, sizeof d);
    memset(&info, 0, sizeof info);
    d.camera = *cam;
    d.resolution = c->res;
    d.seed = 1;
    d.screen.rays = c->rays;
    d.screen.steps = c->steps;
    d.screen.radius = (float)(c->radius * longest);
    d.screen.half_resolution = c->half ? VOXGI_TOGGLE_ON : VOXGI_TOGGLE_OFF;
    d.screen.blur = c->blur > 0 ? c->blur : -1;
    if (ao) {
        d.method = c->method == M_VAO ? VOXGI_RENDER_VAO : VOXGI_RENDER_SSAO;
        d.screen.point_sampling = c->method == M_SSAO_POINTS;
    } else {
        d.method = c->method == M_SSGI ? VOXGI_RENDER_SSGI : VOXGI_RENDER_HYBRID;
        d.hide_emitters = 1;
        d.screen.hidden_light = c->hidden ? VOXGI_TOGGLE_ON : VOXGI_TOGGLE_OFF;
    }
    r = voxgi_render(ctx, scene, &d, img, bytes, &info);
    row->gathered = info.gathered;
    row->ms = info.ms;
    row->ms_parts[1] = voxgi_render_stage_ms(&info, "voxels");
    if (ao) {
        row->ms_pass = voxgi_render_stage_ms(&info, "ao");
        row->ms_parts[0] = voxgi_render_stage_ms(&info, "gbuffer");
    } else {
        row->ms_pass = voxgi_render_stage_ms(&info, "gather");
        row->ms_parts[0] = voxgi_render_stage_ms(&info, "direct");
        row->ms_parts[2] = voxgi_render_stage_ms(&info, "inject");
    }
    row->bytes = (double)info.bytes;
    row->c = *c;
    return r;
}

/* ------------------------------------------------------------------ the sweeps */
/* Every configuration of each of the report's methods on scene si (its name, seen by cam), each
   measured against the reference at its radius (R[k] at rep->radii[k] for ao; R[0] for ssgi),
   appended to rep's rows; with run, each also handed to report all. 0, or says why and returns 1. */
static int screen_sweep(cli_session *s, voxgi_context *ctx, const screen_args *a, screen_report *rep, int si, const voxgi_scene *scene, const char *name,
                        const voxgi_camera *cam, const cli_reference *R, float *img, report_run *run)
{
    screen_config configs[SWEEP_MAX];
    const int *methods = a->which == SCREEN_AO ? ao_methods : gi_methods;
    int nmethods = a->which == SCREEN_AO ? CLI_COUNT(ao_methods) : CLI_COUNT(gi_methods), m, i, k, n;
    char text[160];
    for (m = 0; m < nmethods; m++) {
        n = sweep(a, methods[m], configs);
        for (i = 0; i < n; i++) {
            screen_row *row = &rep->rows[rep->nrows];
            for (k = 0; a->which == SCREEN_AO && rep->radii[k] != configs[i].radius; k++) {}
            config_text(&configs[i], text, sizeof text);
            cli_status(s, "%s: %s", name, text);
            memset(row, 0, sizeof *row);
            if (render_config(ctx, scene, cam, rep->longest[si], &configs[i], img, row) != VOXGI_OK) return cli_fail_lib(s, ctx, text);
            row->scene = si;
            row->rmse = cli_masked_error(&R[k].mask, img, R[k].image, NULL, NULL);
            row->ref_ms = cli_reference_ms(&R[k], row->rmse);
            row->red = a->which == SCREEN_SSGI ? cli_red_excess(&R[k], img) : 0;
            rep->nrows++;
            if (run) {
                report_item it;
                memset(&it, 0, sizeof it);
                it.method = method_names[configs[i].method];
                config_text(&configs[i], text, sizeof text);
                snprintf(it.settings, sizeof it.settings, "%s", text + strlen(it.method) + 2); /* without "method, " */
                if (a->which == SCREEN_AO)
                    snprintf(it.passes, sizeof it.passes, "G-buffer %.1f, voxels %.1f, occlusion %.1f", row->ms_parts[0], row->ms_parts[1], row->ms_pass);
                else
                    snprintf(it.passes, sizeof it.passes, "direct %.1f, voxels %.1f, their light %.1f, gathers %.1f", row->ms_parts[0], row->ms_parts[1],
                             row->ms_parts[2], row->ms_pass);
                it.ms = row->ms;
                it.bytes = row->bytes;
                it.error = row->rmse;
                run->emit(run, &it, img);
            }
        }
    }
    return 0;
}

/* Scene si: its references, then a row per configuration of each method; for ssgi also the
   direct light alone, Hybrid-GI converged and cone tracing's defaults. */
static int screen_scene(cli_session *s, voxgi_context *ctx, const screen_args *a, screen_report *rep, int si, float *img)
{
    cli_reference R[SCREEN_MAX_RADII], direct;
    voxgi_builtin_scene bs;
    voxgi_camera cam;
    const char *name = rep->scenes[si];
    size_t pixels = (size_t)a->size[0] * (size_t)a->size[1];
    int nrefs = a->which == SCREEN_AO ? rep->nradii : 1, k, rc = 1;
    double longest;
    memset(R, 0, sizeof R);
    memset(&direct, 0, sizeof direct);
    if (voxgi_builtin_scene_create(ctx, name, &bs) != VOXGI_OK) return cli_fail_lib(s, ctx, name);
    cam = bs.camera;
    cam.width = a->size[0];
    cam.height = a->size[1];
    longest = rep->longest[si] = cli_scene_longest_side(&bs.scene);
    for (k = 0; k < nrefs; k++) { /* ao: one reference per radius, each method measured at its own */
        if (cli_reference_make(s, ctx, &bs.scene, &cam, a->spp, 1, a->which == SCREEN_AO ? rep->radii[k] * longest : 0, &R[k])) goto done;
        if (R[k].mask.masked_pixels == pixels) {
            cli_fail(s, "%s: every pixel is within %d pixels of one that sees an emitter: no error to measure", name, CLI_EMITTER_MARGIN);
            goto done;
        }
        rep->ref_c[si][k] = R[k].c;
        rep->ref_ms_per_spp[si][k] = R[k].ms_per_spp;
    }
    rep->masked[si] = R[0].mask.masked_pixels;
    if (screen_sweep(s, ctx, a, rep, si, &bs.scene, name, &cam, R, img, NULL)) goto done;
    if (a->which == SCREEN_SSGI) {
        screen_config c = base_config(SCREEN_SSGI, M_HYBRID);
        voxgi_render_desc rd, vd;
        voxgi_render_info vi;
        /* the direct light alone: the reference's, converged */
        if (cli_reference_make(s, ctx, &bs.scene, &cam, a->spp, 0, 0, &direct)) goto done;
        rep->direct_rmse[si] = cli_masked_error(&R[0].mask, direct.image, R[0].image, NULL, NULL);
        /* the most a bounce from the screen can find: the reference's bounce from the surfaces the camera sees alone */
        memset(&rd, 0, sizeof rd);
        rd.method = VOXGI_RENDER_REFERENCE;
        rd.camera = cam;
        rd.samples = a->spp;
        rd.bounces = 1;
        rd.seed = 1000003; /* cli_reference_make's: the same noise as the full bounce's where they agree */
        rd.hide_emitters = 1;
        rd.reference.screen_light_only = 1;
        cli_status(s, "%s: the reference's bounce from the screen alone, %d spp", name, a->spp);
        if (voxgi_render(ctx, &bs.scene, &rd, img, pixels * 12, NULL) != VOXGI_OK) {
            cli_fail_lib(s, ctx, "the reference's bounce from the screen alone");
            goto done;
        }
        rep->screen_rmse[si] = cli_masked_error(&R[0].mask, img, R[0].image, NULL, NULL);
        /* Hybrid-GI converged: what it still misses is light from surfaces the camera does not see;
           with the hidden light, what the voxels' injected light gives of it */
        c.rays = 256;
        c.res = 0;
        for (k = 0; k < a->nres; k++) c.res = c.res > (int)a->res[k] ? c.res : (int)a->res[k]; /* the finest of --res: 256 by default */
        c.radius = 1.75;
        for (k = 0; k < 2; k++) {
            screen_row *row = k ? &rep->hidden[si] : &rep->converged[si];
            c.hidden = k;
            cli_status(s, "%s: Hybrid-GI converged%s", name, k ? ", hidden light" : "");
            if (render_config(ctx, &bs.scene, &cam, longest, &c, img, row) != VOXGI_OK) {
                cli_fail_lib(s, ctx, "Hybrid-GI converged");
                goto done;
            }
            row->scene = si;
            row->rmse = cli_masked_error(&R[0].mask, img, R[0].image, NULL, NULL);
            row->red = cli_red_excess(&R[0], img);
        }
        cli_vct_defaults(&vd, &cam);
        cli_status(s, "%s: cone tracing, the tool's defaults", name);
        if (voxgi_render(ctx, &bs.scene, &vd, img, pixels * 12, &vi) != VOXGI_OK) {
            cli_fail_lib(s, ctx, "cone tracing");
            goto done;
        }
        rep->vct_rmse[si] = cli_masked_error(&R[0].mask, img, R[0].image, NULL, NULL);
        rep->vct_ms[si] = vi.ms;
    }
    rc = 0;
done:
    for (k = 0; k < nrefs; k++) cli_reference_free(&R[k]);
    cli_reference_free(&direct);
    voxgi_builtin_scene_destroy(ctx, &bs);
    return rc;
}

/* A row is on the front when no other row of its scene (and for ao of its radius: another
   reference) is at once faster and better. */
static void screen_pareto(screen_report *rep, int by_radius)
{
    int i, k;
    for (i = 0; i < rep->nrows; i++) {
        screen_row *r = &rep->rows[i];
        for (k = 0; by_radius && k < rep->nradii - 1 && rep->radii[k] != r->c.radius; k++) {}
        r->group = r->scene * SCREEN_MAX_RADII + k;
    }
    PARETO_MARK(rep->rows, (size_t)rep->nrows, screen_row, ms, rmse, group, pareto);
}

/* ------------------------------------------------------------------ view-independence of AO */
/* Camera k of VIEW_COUNT on an arc before the Cornell box's open front: the default eye's
   distance from the box's centre, yawed -20..20 degrees about it and 5 cm lower to 5 cm higher,
   looking at the centre. */
static voxgi_camera orbit_camera(const voxgi_camera *def, int k)
{
    static const double centre[3] = {0.278, 0.273, 0.2796};
    const double d = sqrt((def->eye[0] - centre[0]) * (def->eye[0] - centre[0]) + (def->eye[2] - centre[2]) * (def->eye[2] - centre[2]));
    const double t = (double)k / (VIEW_COUNT - 1) * 2 - 1, yaw = 20 * t * SCREEN_PI / 180; /* t in [-1, 1] */
    voxgi_camera c = *def;
    c.eye[0] = centre[0] + d * sin(yaw);
    c.eye[1] = centre[1] + 0.05 * t;
    c.eye[2] = centre[2] - d * cos(yaw);
    memcpy(c.target, centre, sizeof centre);
    return c;
}

/* The pixel of cam that shows point p (normal n; pos, nrm, tri: cam's G-buffer): the one p
   projects into, when the surface it shows lies within 1% of p's distance from the eye and faces
   the same way (normals within 25 degrees: not the other wall at a corner); else -1. Pixel
   centres and the frame as the library's cameras have them. */
static long pixel_showing(const voxgi_camera *cam, const float *pos, const float *nrm, const uint32_t *tri, const double p[3], const double n[3])
{
    double f[3], r[3], u[3], v[3], len = 0, z = 0, x = 0, y = 0, dist2 = 0, off2 = 0, facing = 0, th = tan(cam->fovy_degrees * SCREEN_PI / 360);
    long at;
    int c;
    for (c = 0; c < 3; c++) {
        f[c] = cam->target[c] - cam->eye[c];
        len += f[c] * f[c];
    }
    len = sqrt(len);
    for (c = 0; c < 3; c++) f[c] /= len;
    len = sqrt(f[0] * f[0] + f[2] * f[2]);
    r[0] = -f[2] / len; r[1] = 0; r[2] = f[0] / len; /* forward x (0, 1, 0) */
    u[0] = r[1] * f[2] - r[2] * f[1];
    u[1] = r[2] * f[0] - r[0] * f[2];
    u[2] = r[0] * f[1] - r[1] * f[0];
    for (c = 0; c < 3; c++) {
        v[c] = p[c] - cam->eye[c];
        z += v[c] * f[c];
        x += v[c] * r[c];
        y += v[c] * u[c];
        dist2 += v[c] * v[c];
    }
    if (!(z > 0)) return -1;
    x = (x / z / (th * cam->width / cam->height) + 1) * cam->width / 2;
    y = (1 - y / z / th) * cam->height / 2;
    if (!(x >= 0 && x < cam->width && y >= 0 && y < cam->height)) return -1;
    at = (long)y * cam->width + (long)x;
    if (tri[at] == UINT32_MAX) return -1;
    for (c = 0; c < 3; c++) {
        off2 += (pos[3 * at + c] - p[c]) * (pos[3 * at + c] - p[c]);
        facing += nrm[3 * at + c] * n[c];
    }
    return off2 <= 1e-4 * dist2 && facing > 0.9 ? at : -1;
}

static int compare_doubles(const void *p, const void *q)
{
    double a = *(const double *)p, b = *(const double *)q;
    return a < b ? -1 : a > b;
}

/* Where a point's smallest and largest AO are kept: per point, group (the orbit, the seeds),
   reading (the pixel's own surface, the point itself) and method (depth buffer, voxels). */
#define VIEW_AT(k, group, reading, method) ((((size_t)(k) * 2 + (size_t)(group)) * 2 + (size_t)(reading)) * 2 + (size_t)(method))

/* The Cornell box's AO at the middle view's points, from the orbit's views (group 0) and from the
   middle view with VIEW_COUNT seeds (group 1), by the depth buffer and by the voxels, read two
   ways: at the surface of the pixel that shows the point (what an image shows there), and at the
   point itself, put in that pixel's G-buffer in place of its surface (the same world point in
   every view: what differs is what the view shows and the pixel's random rotation). */
static int ao_views(cli_session *s, voxgi_context *ctx, const screen_args *a, screen_report *rep)
{
    const int w = a->size[0], h = a->size[1];
    const size_t pixels = (size_t)w * (size_t)h;
    voxgi_builtin_scene bs;
    voxgi_voxelize_desc vd;
    voxgi_voxels *vox = NULL;
    voxgi_camera def;
    float *pos = (float *)malloc(pixels * 12), *nrm = (float *)malloc(pixels * 12), *moved = (float *)malloc(pixels * 12),
          *turned = (float *)malloc(pixels * 12), *sparse = (float *)malloc(pixels * 12), *ao = (float *)malloc(pixels * 4);
    uint32_t *tri = (uint32_t *)malloc(pixels * 4);
    double *pts = NULL, *pnrm = NULL, *lo = NULL, *hi = NULL, *spread = NULL;
    long *pix = NULL;
    int *seen = NULL, pass, g, m, reading, i, rc = 1;
    size_t np = 0, x, y, most = (size_t)((w + VIEW_STRIDE - 1) / VIEW_STRIDE) * (size_t)((h + VIEW_STRIDE - 1) / VIEW_STRIDE);
    memset(&bs, 0, sizeof bs);
    memset(&vd, 0, sizeof vd);
    rep->view_rays = 0;
    for (i = 0; i < a->nrays; i++) rep->view_rays = rep->view_rays > (int)a->rays[i] ? rep->view_rays : (int)a->rays[i];
    pts = (double *)malloc(most * 3 * sizeof *pts);
    pnrm = (double *)malloc(most * 3 * sizeof *pnrm);
    lo = (double *)malloc(most * 8 * sizeof *lo);
    hi = (double *)malloc(most * 8 * sizeof *hi);
    spread = (double *)malloc(most * sizeof *spread);
    pix = (long *)malloc(most * sizeof *pix);
    seen = (int *)calloc(most * 2, sizeof *seen);
    if (!pos || !nrm || !moved || !turned || !sparse || !ao || !tri || !pts || !pnrm || !lo || !hi || !spread || !pix || !seen) {
        cli_fail(s, "the views: out of memory");
        goto done;
    }
    if (voxgi_builtin_scene_create(ctx, "cornell-box", &bs) != VOXGI_OK) {
        cli_fail_lib(s, ctx, "cornell-box");
        goto done;
    }
    def = bs.camera;
    def.width = w;
    def.height = h;
    rep->view_radius = 0.1 * cli_scene_longest_side(&bs.scene);
    cli_status(s, "the views: %d^3 voxels", VIEW_RES);
    if (cli_fit_grid(ctx, &bs.scene, VIEW_RES, 0, 0, &vd.grid) != VOXGI_OK || voxgi_voxelize(ctx, &bs.scene, &vd, &vox) != VOXGI_OK) {
        cli_fail_lib(s, ctx, "the views' voxels");
        goto done;
    }
    {
        voxgi_camera mid = orbit_camera(&def, VIEW_COUNT / 2);
        if (voxgi_gbuffer_render(ctx, &bs.scene, &mid, pos, nrm, tri) != VOXGI_OK) {
            cli_fail_lib(s, ctx, "the middle view's G-buffer");
            goto done;
        }
    }
    for (y = 0; y < (size_t)h; y += VIEW_STRIDE)
        for (x = 0; x < (size_t)w; x += VIEW_STRIDE) {
            size_t p = y * (size_t)w + x;
            const voxgi_material *mt;
            if (tri[p] == UINT32_MAX) continue;
            mt = cli_triangle_material(&bs.scene, tri[p]);
            if (mt && (mt->emission[0] > 0 || mt->emission[1] > 0 || mt->emission[2] > 0)) continue; /* the light: as the errors leave it out */
            for (i = 0; i < 3; i++) {
                pts[3 * np + (size_t)i] = pos[3 * p + (size_t)i];
                pnrm[3 * np + (size_t)i] = nrm[3 * p + (size_t)i];
            }
            np++;
        }
    for (x = 0; x < 8 * np; x++) {
        lo[x] = HUGE_VAL;
        hi[x] = -HUGE_VAL;
    }
    for (pass = 0; pass < 2 * VIEW_COUNT; pass++) {
        const int group = pass >= VIEW_COUNT;
        const voxgi_camera cam = orbit_camera(&def, group ? VIEW_COUNT / 2 : pass);
        size_t k;
        if (voxgi_gbuffer_render(ctx, &bs.scene, &cam, pos, nrm, tri) != VOXGI_OK) {
            cli_fail_lib(s, ctx, "a view's G-buffer");
            goto done;
        }
        memcpy(moved, pos, pixels * 12);
        memcpy(turned, nrm, pixels * 12);
        for (k = 0; k < np; k++)
            if ((pix[k] = pixel_showing(&cam, pos, nrm, tri, pts + 3 * k, pnrm + 3 * k)) >= 0) {
                for (i = 0; i < 3; i++) {
                    moved[3 * pix[k] + i] = (float)pts[3 * k + (size_t)i];
                    turned[3 * pix[k] + i] = (float)pnrm[3 * k + (size_t)i];
                }
                seen[2 * k + (size_t)group]++;
            }
        for (reading = 0; reading < 2; reading++)
            for (m = 0; m < 2; m++) {
                const float *normals = reading ? turned : nrm;
                voxgi_ao_desc d;
                memset(&d, 0, sizeof d);
                if (m) { /* the voxels need only the pixels that show a point: the rest, without a normal, are skipped */
                    memset(sparse, 0, pixels * 12);
                    for (k = 0; k < np; k++)
                        if (pix[k] >= 0) memcpy(sparse + 3 * pix[k], normals + 3 * pix[k], 12);
                }
                d.camera = cam;
                d.positions = reading ? moved : pos;
                d.normals = m ? sparse : normals; /* the depth buffer needs every pixel's surface */
                d.method = m ? VOXGI_AO_VOXELS : VOXGI_AO_SCREEN;
                d.voxels = vox;
                d.traversal = VOXGI_TRAVERSAL_HIERARCHICAL;
                d.rays = rep->view_rays;
                d.steps = 16;
                d.radius = (float)rep->view_radius;
                d.seed = group ? (uint64_t)(pass - VIEW_COUNT + 1) : 1;
                cli_status(s, "the views: %s %d of %d, %s, %s", group ? "seed" : "view", pass % VIEW_COUNT + 1, VIEW_COUNT, m ? "voxels" : "depth buffer",
                           reading ? "at the points" : "at the pixels");
                if (voxgi_ao(ctx, &d, ao, pixels * 4) != VOXGI_OK) {
                    cli_fail_lib(s, ctx, "the views' ambient occlusion");
                    goto done;
                }
                for (k = 0; k < np; k++)
                    if (pix[k] >= 0) {
                        size_t at = VIEW_AT(k, group, reading, m);
                        lo[at] = fmin(lo[at], ao[pix[k]]);
                        hi[at] = fmax(hi[at], ao[pix[k]]);
                    }
            }
    }
    for (g = 0; g < 2; g++)
        for (reading = 0; reading < 2; reading++)
            for (m = 0; m < 2; m++) {
                view_spread *V = &rep->views[g][reading][m];
                size_t k, n = 0, passes = 0;
                double sum = 0;
                for (k = 0; k < np; k++)
                    if (seen[2 * k + (size_t)g] >= 2) {
                        spread[n] = hi[VIEW_AT(k, g, reading, m)] - lo[VIEW_AT(k, g, reading, m)];
                        sum += spread[n++];
                        passes += (size_t)seen[2 * k + (size_t)g];
                    }
                memset(V, 0, sizeof *V);
                V->points = n;
                if (!n) continue;
                qsort(spread, n, sizeof *spread, compare_doubles);
                V->passes = (double)passes / (double)n;
                V->mean = sum / (double)n;
                V->p95 = spread[(size_t)ceil(0.95 * (double)n) - 1];
            }
    rc = 0;
done:
    voxgi_voxels_destroy(ctx, vox);
    voxgi_builtin_scene_destroy(ctx, &bs);
    free(pos);
    free(nrm);
    free(moved);
    free(turned);
    free(sparse);
    free(ao);
    free(tri);
    free(pts);
    free(pnrm);
    free(lo);
    free(hi);
    free(spread);
    free(pix);
    free(seen);
    return rc;
}

/* ------------------------------------------------------------------ a wall barely in view */
static int is_red(const voxgi_material *m) { return m && m->albedo[0] > 2 * m->albedo[1] && m->albedo[0] > 2 * m->albedo[2]; }

/* The camera at def's eye turned by yaw degrees about +Y, from +Z towards -X: in the Cornell box
   towards the green wall, the red one leaving the image at its left edge. */
static voxgi_camera turned_camera(const voxgi_camera *def, double yaw_deg)
{
    voxgi_camera c = *def;
    double f[3], t = yaw_deg * SCREEN_PI / 180;
    int k;
    for (k = 0; k < 3; k++) f[k] = def->target[k] - def->eye[k];
    c.target[0] = def->eye[0] + f[0] * cos(t) - f[2] * sin(t);
    c.target[1] = def->target[1];
    c.target[2] = def->eye[2] + f[0] * sin(t) + f[2] * cos(t);
    return c;
}

/* The red wall's pixels, from the triangles of a G-buffer of fine x fine points per pixel (the
   direct light's rays spread over the pixel): 1 into red (may be NULL) where any point sees it;
   how many and the most in one row. */
static void red_pixels(const voxgi_scene *scene, const uint32_t *tri, int w, int h, int fine, unsigned char *red, size_t *count, int *widest)
{
    const size_t fw = (size_t)w * (size_t)fine;
    int x, y, i, j;
    *count = 0;
    *widest = 0;
    for (y = 0; y < h; y++) {
        int row = 0;
        for (x = 0; x < w; x++) {
            int r = 0;
            for (j = 0; j < fine && !r; j++)
                for (i = 0; i < fine && !r; i++) {
                    uint32_t t = tri[((size_t)y * (size_t)fine + (size_t)j) * fw + (size_t)x * (size_t)fine + (size_t)i];
                    r = t != UINT32_MAX && is_red(cli_triangle_material(scene, t));
                }
            if (red) red[(size_t)y * (size_t)w + (size_t)x] = (unsigned char)r;
            row += r;
        }
        *count += (size_t)row;
        *widest = row > *widest ? row : *widest;
    }
}

/* The mean of (img - base)'s red minus green over the pixels that are neither the red wall nor
   left out near an emitter. */
static double red_bleeding(const float *img, const float *base, const unsigned char *red, const cli_error_mask *mask)
{
    size_t p, n = (size_t)mask->width * (size_t)mask->height, kept = 0;
    double sum = 0;
    for (p = 0; p < n; p++) {
        if (red[p] || mask->masked[p]) continue;
        sum += ((double)img[3 * p] - base[3 * p]) - ((double)img[3 * p + 1] - base[3 * p + 1]);
        kept++;
    }
    return kept ? sum / (double)kept : NAN;
}

/* The triangles def's view turned by yaw degrees sees at WALL_FINE x WALL_FINE points per pixel. */
static int wall_gbuffer(cli_session *s, voxgi_context *ctx, const voxgi_scene *scene, const voxgi_camera *def, double yaw, uint32_t *tri)
{
    voxgi_camera fine = turned_camera(def, yaw);
    fine.width *= WALL_FINE;
    fine.height *= WALL_FINE;
    return voxgi_gbuffer_render(ctx, scene, &fine, NULL, NULL, tri) != VOXGI_OK ? cli_fail_lib(s, ctx, "the wall's G-buffer") : 0;
}

/* The Cornell box in view, with its red wall a sliver at the image's edge, and turned just past
   it: the reference's one bounce and direct light, SSGI and Hybrid-GI, each also of the box with
   the wall grey (its albedo's mean in every channel): the difference is the wall's colour alone
   (the light's own tint, red over green, bounces off every white surface too; the green wall
   bleeds green). The direct light elsewhere does not depend on the wall's albedo: with the same
   seeds it cancels. */
static int ssgi_wall(cli_session *s, voxgi_context *ctx, const screen_args *a, screen_report *rep, float *img)
{
    const int w = a->size[0], h = a->size[1];
    const size_t pixels = (size_t)w * (size_t)h;
    voxgi_builtin_scene bs;
    voxgi_scene grey_scene;
    voxgi_material *grey_materials = NULL;
    voxgi_camera def;
    cli_reference R1, R0, G1;
    uint32_t *tri = (uint32_t *)malloc(pixels * WALL_FINE * WALL_FINE * 4);
    unsigned char *red = (unsigned char *)malloc(pixels);
    float *grey = (float *)malloc(pixels * 12);
    double last_seen = 0, longest;
    size_t i;
    int v, k, step, rc = 1;
    memset(&bs, 0, sizeof bs);
    memset(&R1, 0, sizeof R1);
    memset(&R0, 0, sizeof R0);
    memset(&G1, 0, sizeof G1);
    if (!tri || !red || !grey) {
        cli_fail(s, "the wall: out of memory");
        goto done;
    }
    if (voxgi_builtin_scene_create(ctx, "cornell-box", &bs) != VOXGI_OK) {
        cli_fail_lib(s, ctx, "cornell-box");
        goto done;
    }
    def = bs.camera;
    def.width = w;
    def.height = h;
    longest = cli_scene_longest_side(&bs.scene);
    grey_scene = bs.scene;
    if (!(grey_materials = (voxgi_material *)malloc((bs.scene.material_count ? bs.scene.material_count : 1) * sizeof *grey_materials))) {
        cli_fail(s, "the wall: out of memory");
        goto done;
    }
    for (i = 0; i < bs.scene.material_count; i++) {
        grey_materials[i] = bs.scene.materials[i];
        if (is_red(&grey_materials[i])) {
            const float mean = (grey_materials[i].albedo[0] + grey_materials[i].albedo[1] + grey_materials[i].albedo[2]) / 3;
            grey_materials[i].albedo[0] = grey_materials[i].albedo[1] = grey_materials[i].albedo[2] = mean;
        }
    }
    grey_scene.materials = grey_materials;
    rep->walls[0].yaw = 0;
    rep->walls[1].yaw = rep->walls[2].yaw = -1;
    for (step = 0; step * WALL_YAW_STEP <= 90 && rep->walls[2].yaw < 0; step++) { /* the first yaws at which the wall is a sliver, then gone */
        const double yaw = step * WALL_YAW_STEP;
        size_t count;
        int widest;
        if (wall_gbuffer(s, ctx, &bs.scene, &def, yaw, tri)) goto done;
        red_pixels(&bs.scene, tri, w, h, WALL_FINE, NULL, &count, &widest);
        if (step == 0 && count == 0) {
            cli_fail(s, "the Cornell box's red wall is not in its view");
            goto done;
        }
        if (count && widest <= WALL_SLIVER && rep->walls[1].yaw < 0) rep->walls[1].yaw = yaw;
        if (count) last_seen = yaw;
        else rep->walls[2].yaw = yaw;
    }
    if (rep->walls[2].yaw < 0) {
        cli_fail(s, "the Cornell box's red wall stays in view however far the camera turns");
        goto done;
    }
    if (rep->walls[1].yaw < 0) rep->walls[1].yaw = last_seen; /* it left between two steps: its last sight */
    rep->walls[2].yaw += def.fovy_degrees / h; /* a pixel further: no ray of the direct light, spread over the pixel, meets it */
    for (v = 0; v < 3; v++) {
        wall_view *W = &rep->walls[v];
        const voxgi_camera cam = turned_camera(&def, W->yaw);
        if (wall_gbuffer(s, ctx, &bs.scene, &def, W->yaw, tri)) goto done;
        red_pixels(&bs.scene, tri, w, h, WALL_FINE, red, &W->red_pixels, &W->widest);
        if (cli_reference_make(s, ctx, &bs.scene, &cam, a->spp, 1, 0, &R1) || cli_reference_make(s, ctx, &bs.scene, &cam, a->spp, 0, 0, &R0) ||
            cli_reference_make(s, ctx, &grey_scene, &cam, a->spp, 1, 0, &G1))
            goto done;
        W->rmse[WALL_REFERENCE] = 0;
        W->bleed[WALL_REFERENCE] = red_bleeding(R1.image, R0.image, red, &R1.mask);
        W->colour[WALL_REFERENCE] = red_bleeding(R1.image, G1.image, red, &R1.mask);
        W->rmse[WALL_DIRECT] = cli_masked_error(&R1.mask, R0.image, R1.image, NULL, NULL);
        W->bleed[WALL_DIRECT] = W->colour[WALL_DIRECT] = 0;
        for (k = WALL_SSGI; k < WALL_METHODS; k++) {
            screen_config c = base_config(SCREEN_SSGI, k == WALL_SSGI ? M_SSGI : M_HYBRID);
            screen_row row;
            memset(&row, 0, sizeof row);
            c.rays = WALL_RAYS;
            c.hidden = k == WALL_HIDDEN;
            cli_status(s, "the wall %s: %s", wall_view_names[v], wall_method_names[k]);
            if (render_config(ctx, &grey_scene, &cam, longest, &c, grey, &row) != VOXGI_OK ||
                render_config(ctx, &bs.scene, &cam, longest, &c, img, &row) != VOXGI_OK) {
                cli_fail_lib(s, ctx, wall_method_names[k]);
                goto done;
            }
            W->rmse[k] = cli_masked_error(&R1.mask, img, R1.image, NULL, NULL);
            W->bleed[k] = red_bleeding(img, R0.image, red, &R1.mask);
            W->colour[k] = red_bleeding(img, grey, red, &R1.mask);
        }
        cli_reference_free(&R1);
        cli_reference_free(&R0);
        cli_reference_free(&G1);
    }
    rc = 0;
done:
    cli_reference_free(&R1);
    cli_reference_free(&R0);
    cli_reference_free(&G1);
    voxgi_builtin_scene_destroy(ctx, &bs);
    free(grey_materials);
    free(tri);
    free(red);
    free(grey);
    return rc;
}

/* ------------------------------------------------------------------ output */
/* A percentage, or "-" when there is none. */
static void put_percent(FILE *f, double v, const char *after)
{
    if (isfinite(v)) fprintf(f, "%.2f%%%s", 100 * v, after);
    else fprintf(f, "-%s", after);
}

static const char *const view_method_names[2] = {"SSAO (ray marching, 16 steps)", "voxel AO (128^3)"}, *const view_reading_names[2] = {"the pixel's surface", "the point"};

static void write_views(FILE *f, const screen_args *a, const screen_report *rep)
{
    int m, reading;
    fprintf(f, "\n## View-independence: the Cornell box from 9 views\n\nNine cameras on an arc before the box's open front: the default eye's "
               "distance from the box's centre (0.278, 0.273, 0.2796), yawed -20 to 20 degrees about it and 5 cm lower to 5 cm higher, each "
               "looking at the centre (fovy 39.3077, %d x %d). The points: the middle view's surfaces at every %dth pixel across and down (not the "
               "light). Each view's occlusion (`voxgi_ao` on that view's G-buffer; %d rays, radius %.4g) is read at the pixel that shows the point "
               "(its surface within 1%% of the point's distance from the eye, its normal within 25 degrees of the point's): *at the pixel's "
               "surface*, what the image shows there (the pixel's centre meets the surface up to a pixel's width from the point), and *at the "
               "point*, the point and its normal put in that pixel's G-buffer in place of its surface (the same world point in every view). "
               "*Spread*: a point's largest minus smallest occlusion over the views that show it, over the points two views or more show. The "
               "last columns: the middle view alone with 9 seeds, the part of the spread that is Monte Carlo noise (each pixel rotates its "
               "rays by its own random numbers).\n\n| occlusion | read at | points | views per point | mean spread | 95th percentile | 9 seeds: "
               "mean spread | 95th percentile |\n|---|---|---:|---:|---:|---:|---:|---:|\n",
            a->size[0], a->size[1], VIEW_STRIDE, rep->view_rays, rep->view_radius);
    for (reading = 0; reading < 2; reading++)
        for (m = 0; m < 2; m++) {
            const view_spread *O = &rep->views[0][reading][m], *S = &rep->views[1][reading][m];
            fprintf(f, "| %s | %s | %lu | %.1f | %.4f | %.4f | %.4f | %.4f |\n", view_method_names[m], view_reading_names[reading], (unsigned long)O->points,
                    O->passes, O->mean, O->p95, S->mean, S->p95);
        }
}

/* x / of, a percentage; "-" without a share. */
static void put_share(FILE *f, double x, double of, const char *after) { put_percent(f, of != 0 ? x / of : NAN, after); }

static void write_wall(FILE *f, const screen_args *a, const screen_report *rep)
{
    int v, k;
    fprintf(f, "\n## A wall barely in view: the Cornell box\n\nThe camera at the box's eye turned towards the green wall (about +Y, %d x %d): "
               "in view (the default), the red wall a sliver at the image's left edge (the first yaw, in steps of %g degrees, at which no row "
               "holds more than %d of its pixels), and just off screen (a pixel's angle beyond the first yaw with none). The wall's pixels: those any of %d x %d "
               "points in them see it from (the direct light's rays spread over the pixel). Over the pixels that are neither the red "
               "wall nor near an emitter: *red - green*, the mean of the indirect light's red minus green (the indirect light: the image minus "
               "the reference's direct light, bounces 0, %d spp, the same view); it holds the light's own tint (red over green) bounced off "
               "the white surfaces and the green wall's bleeding too. *From the wall's colour*: the same mean of the image minus the image of "
               "the same view and method with the wall grey (its albedo's mean in every channel): the red the wall's colour alone puts on the "
               "rest. Each also as a share of the reference's one bounce. SSGI and Hybrid-GI (also with the hidden light): %d rays, the rest the "
               "base. Error: against the reference's one bounce.\n\n| view | yaw | red wall pixels (widest row) | method | rel. RMSE | red - green | share | from the "
               "wall's colour | share |\n|---|---:|---:|---|---:|---:|---:|---:|---:|\n",
            a->size[0], a->size[1], WALL_YAW_STEP, WALL_SLIVER, WALL_FINE, WALL_FINE, a->spp, WALL_RAYS);
    for (v = 0; v < 3; v++) {
        const wall_view *W = &rep->walls[v];
        for (k = 0; k < WALL_METHODS; k++) {
            if (k == 0) fprintf(f, "| %s | %g° | %lu (%d) | ", wall_view_names[v], W->yaw, (unsigned long)W->red_pixels, W->widest);
            else fprintf(f, "| | | | ");
            fprintf(f, "%s | ", wall_method_names[k]);
            if (k == WALL_REFERENCE) fprintf(f, "- | ");
            else put_percent(f, W->rmse[k], " | ");
            fprintf(f, "%.5f | ", W->bleed[k]);
            put_share(f, W->bleed[k], W->bleed[WALL_REFERENCE], " | ");
            fprintf(f, "%.5f | ", W->colour[k]);
            put_share(f, W->colour[k], W->colour[WALL_REFERENCE], " |\n");
        }
    }
}

static int screen_write(cli_session *s, const screen_args *a, const screen_report *rep)
{
    const int ao = a->which == SCREEN_AO;
    const voxgi_info *ci = &rep->ci;
    const char *name = report_names[a->which];
    char path[1100];
    FILE *md, *csv;
    int si, i, k;
    snprintf(path, sizeof path, "%s/%s.md", a->out_dir, name);
    if (!(md = fopen(path, "w"))) return cli_fail(s, "cannot write %s", path);
    snprintf(path, sizeof path, "%s/%s.csv", a->out_dir, name);
    if (!(csv = fopen(path, "w"))) {
        fclose(md);
        return cli_fail(s, "cannot write %s", path);
    }
    if (ao)
        fprintf(md, "# Ambient occlusion from the screen and from the voxels: error against run time\n\n%d x %d pixels; occlusion against the "
                    "reference's ambient occlusion at the same radius (%d spp); %s%s%s (%d threads). One parameter at a time around the base (16 "
                    "rays, 16 steps, radius 0.1 of the scene's longest side, 128 voxels, full resolution, no blur), and half resolution with each "
                    "blur. *Radius*: a share of the scene's longest side. Error: relative RMSE by the tools' rule (`voxgi render --compare`); it "
                    "is relative to the mean occlusion, which is small: small absolute errors weigh heavily. *Reference at the same error*: the "
                    "time the path tracer's AO needs for an image that measures that error (from its own convergence). The Pareto front: of each "
                    "scene and radius. Wall clock on this machine%s.\n",
                a->size[0], a->size[1], a->spp, voxgi_backend_name(ci->backend), ci->backend == VOXGI_BACKEND_GL ? ", " : "",
                ci->backend == VOXGI_BACKEND_GL ? ci->gl_renderer : "", ci->thread_count,
                ci->backend == VOXGI_BACKEND_GL && ci->gl_software ? " (GL on a software rasteriser: not GPU timings)" : "");
    else
        fprintf(md, "# One bounce from the screen (SSGI, Hybrid-GI): error against run time\n\n%d x %d pixels; direct light and one bounce against "
                    "the reference's one bounce (%d spp); %s%s%s (%d threads). One parameter at a time around the base (16 rays, 16 steps, radius "
                    "1 x the scene's longest side, 128 voxels, full resolution, no blur), and half resolution with each blur. *Radius*: a share of "
                    "the scene's longest side. Error: relative RMSE by the tools' rule (`voxgi render --compare`). *Red excess*: red light beyond "
                    "the reference's, a share of its mean. *Reference at the same error*: the time the path tracer needs for an image that "
                    "measures that error (from its own convergence). Wall clock on this machine%s.\n",
                a->size[0], a->size[1], a->spp, voxgi_backend_name(ci->backend), ci->backend == VOXGI_BACKEND_GL ? ", " : "",
                ci->backend == VOXGI_BACKEND_GL ? ci->gl_renderer : "", ci->thread_count,
                ci->backend == VOXGI_BACKEND_GL && ci->gl_software ? " (GL on a software rasteriser: not GPU timings)" : "");
    fprintf(csv, "scene,method,rays,steps,radius_share,radius,res,half_res,blur,gathered,%s,ms,rel_rmse,%sreference_ms,pareto\n", ao ? "ao_ms" : "gather_ms",
            ao ? "" : "red_excess,");
    for (si = 0; si < rep->scene_count; si++) {
        fprintf(md, "\n## %s\n\nThe longest side: %.4g. %lu pixels near an emitter left out. Reference: ", rep->scenes[si], rep->longest[si],
                (unsigned long)rep->masked[si]);
        for (k = 0; k < (ao ? rep->nradii : 1); k++) {
            if (ao) fprintf(md, "%sradius %g (%.4g): ", k ? "; " : "", rep->radii[k], rep->radii[k] * rep->longest[si]);
            fprintf(md, "its error is %.2f%% / sqrt(spp), %.2f ms per sample per pixel", 100 * rep->ref_c[si][k], rep->ref_ms_per_spp[si][k]);
        }
        if (!ao) {
            fprintf(md, ". The direct light alone measures ");
            put_percent(md, rep->direct_rmse[si], "");
        }
        fprintf(md, ".\n\n| method | rays | steps | radius | voxels | half res. | blur | pixels computed | %s ms | total ms | rel. RMSE | %sreference at the "
                    "same error | Pareto |\n|---|---:|---:|---:|---:|:-:|---:|---:|---:|---:|---:|%s---:|:-:|\n",
                ao ? "occlusion" : "gathers", ao ? "" : "red excess | ", ao ? "" : "---:|");
        for (i = 0; i < rep->nrows; i++) {
            const screen_row *r = &rep->rows[i];
            if (r->scene != si) continue;
            fprintf(md, "| ");
            config_columns(md, &r->c, rep->longest[si], " | ", 0);
            fprintf(md, " | %lu | %.1f | %.1f | ", (unsigned long)r->gathered, r->ms_pass, r->ms);
            put_percent(md, r->rmse, " | ");
            if (!ao) put_percent(md, r->red, " | ");
            if (isfinite(r->ref_ms)) fprintf(md, "%.0f ms | %s |\n", r->ref_ms, r->pareto ? "yes" : "");
            else fprintf(md, "beyond its reference | %s |\n", r->pareto ? "yes" : "");
            fprintf(csv, "%s,", rep->scenes[si]);
            config_columns(csv, &r->c, rep->longest[si], ",", 1);
            fprintf(csv, ",%lu,%.3f,%.3f,%.6g,", (unsigned long)r->gathered, r->ms_pass, r->ms, r->rmse);
            if (!ao) fprintf(csv, "%.6g,", r->red);
            fprintf(csv, "%.6g,%d\n", isfinite(r->ref_ms) ? r->ref_ms : -1.0, r->pareto);
        }
    }
    if (ao) write_views(md, a, rep);
    else {
        fprintf(md, "\n## Light the screen cannot see\n\nWhat no bounce from the screen can find is light from surfaces the camera does "
                    "not see. *Screen light alone*: the reference's bounce from the surfaces the camera sees only (`voxgi render "
                    "--screen-light-only`, %d spp), the floor of every screen method's error. *Hybrid-GI converged*: 256 rays, %d voxels (the finest of "
                    "--res), radius 1.75, full resolution, no blur; *with the hidden light*: the same with hits the camera does not see sending the direct light "
                    "injected into their voxels (`--hidden-light`, an extension beyond the screen). Beside them the direct light alone and cone "
                    "tracing with the tool's defaults (`voxgi render --method vct`: %d^3, anisotropic, %d cones at every %dth pixel, %d "
                    "direct-light rays per pixel), the same scene and size.\n\n| scene | direct light alone | screen light alone | Hybrid-GI "
                    "converged | its time | with the hidden light | its time | cone tracing | its time |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n",
                a->spp, rep->scene_count ? rep->converged[0].c.res : 0, CLI_VCT_RES, CLI_VCT_CONES, CLI_VCT_STRIDE, CLI_VCT_DIRECT_SPP);
        for (si = 0; si < rep->scene_count; si++) {
            fprintf(md, "| %s | ", rep->scenes[si]);
            put_percent(md, rep->direct_rmse[si], " | ");
            put_percent(md, rep->screen_rmse[si], " | ");
            put_percent(md, rep->converged[si].rmse, "");
            fprintf(md, " | %.0f ms | ", rep->converged[si].ms);
            put_percent(md, rep->hidden[si].rmse, "");
            fprintf(md, " | %.0f ms | ", rep->hidden[si].ms);
            put_percent(md, rep->vct_rmse[si], "");
            fprintf(md, " | %.0f ms |\n", rep->vct_ms[si]);
        }
        write_wall(md, a, rep);
    }
    i = ferror(md) || ferror(csv);
    i |= fclose(md) != 0;
    i |= fclose(csv) != 0;
    return i ? cli_fail(s, "cannot write to %s", a->out_dir) : 0;
}

/* The fronts and the sections' numbers on stdout. */
static void screen_print(const screen_args *a, const screen_report *rep)
{
    char text[160];
    int si, i, v, k;
    for (si = 0; si < rep->scene_count; si++) {
        printf("%s (%lu pixels near an emitter left out)", rep->scenes[si], (unsigned long)rep->masked[si]);
        if (a->which == SCREEN_SSGI) {
            printf("; direct light alone ");
            put_percent(stdout, rep->direct_rmse[si], "");
        }
        printf("; the front%s:\n", a->which == SCREEN_AO ? " of each radius" : "");
        for (i = 0; i < rep->nrows; i++) {
            const screen_row *q = &rep->rows[i];
            if (q->scene != si || !q->pareto) continue;
            config_text(&q->c, text, sizeof text);
            printf("  %-62s %8.1f ms  ", text, q->ms);
            put_percent(stdout, q->rmse, "\n");
        }
        if (a->which == SCREEN_SSGI) {
            printf("  screen light alone (the reference's) ");
            put_percent(stdout, rep->screen_rmse[si], "");
            printf("; Hybrid-GI converged %.1f ms  ", rep->converged[si].ms);
            put_percent(stdout, rep->converged[si].rmse, "");
            printf(", with the hidden light %.1f ms  ", rep->hidden[si].ms);
            put_percent(stdout, rep->hidden[si].rmse, "");
            printf("; cone tracing (the tool's defaults) %.1f ms  ", rep->vct_ms[si]);
            put_percent(stdout, rep->vct_rmse[si], "\n");
        }
    }
    if (a->which == SCREEN_AO)
        for (k = 0; k < 4; k++) {
            const view_spread *O = &rep->views[0][k / 2][k % 2], *S = &rep->views[1][k / 2][k % 2];
            printf("view-independence (cornell-box, %d rays), %s at %s: %lu points, spread over 9 views mean %.4f, 95th percentile %.4f; over 9 seeds %.4f, %.4f\n",
                   rep->view_rays, view_method_names[k % 2], view_reading_names[k / 2], (unsigned long)O->points, O->mean, O->p95, S->mean, S->p95);
        }
    else
        for (v = 0; v < 3; v++) {
            const wall_view *W = &rep->walls[v];
            printf("red wall %s (yaw %g, %lu pixels), a share of the reference's: red - green SSGI ", wall_view_names[v], W->yaw, (unsigned long)W->red_pixels);
            put_share(stdout, W->bleed[WALL_SSGI], W->bleed[WALL_REFERENCE], ", Hybrid-GI ");
            put_share(stdout, W->bleed[WALL_HYBRID], W->bleed[WALL_REFERENCE], "; from the wall's colour SSGI ");
            put_share(stdout, W->colour[WALL_SSGI], W->colour[WALL_REFERENCE], ", Hybrid-GI ");
            put_share(stdout, W->colour[WALL_HYBRID], W->colour[WALL_REFERENCE], ", with the hidden light ");
            put_share(stdout, W->colour[WALL_HIDDEN], W->colour[WALL_REFERENCE], "\n");
        }
}

/* report all's screen passes: the one-parameter sweeps around the base over rays and voxels, at
   the base's radius (its reference's), and half resolution with the tools' blur (ao 2, ssgi 8). */
static int screen_all(report_run *run, int which)
{
    static const double rays[] = {4, 16, 64}, quick_rays[] = {16}, res[] = {64, 128}, quick_res[] = {64};
    screen_args a;
    screen_report *rep = (screen_report *)calloc(1, sizeof *rep);
    int rc;
    if (!rep || !(rep->rows = (screen_row *)calloc(CLI_COUNT(ao_methods) * SWEEP_MAX, sizeof *rep->rows))) {
        free(rep);
        return cli_fail(run->s, "out of memory");
    }
    memset(&a, 0, sizeof a);
    a.which = which;
#define SET(field, count, from) (memcpy(a.field, from, sizeof from), a.count = CLI_COUNT(from))
    if (run->quick) SET(rays, nrays, quick_rays), SET(res, nres, quick_res);
    else SET(rays, nrays, rays), SET(res, nres, res);
#undef SET
    a.steps[0] = 16;
    a.blurs[0] = which == SCREEN_AO ? 2 : 8;
    a.radii[0] = rep->radii[0] = base_config(which, M_SSAO).radius;
    a.nsteps = a.nblurs = a.nradii = rep->nradii = 1;
    rep->longest[0] = cli_scene_longest_side(run->scene);
    rc = screen_sweep(run->s, run->ctx, &a, rep, 0, run->scene, run->scene_name, &run->camera, run->R, run->img, run);
    free(rep->rows);
    free(rep);
    return rc;
}

int report_ao_all(report_run *run) { return screen_all(run, SCREEN_AO); }
int report_ssgi_all(report_run *run) { return screen_all(run, SCREEN_SSGI); }

int cmd_report_screen(int which, int argc, char **argv)
{
    static const double ao_rays[] = {4, 16, 64, 256}, ao_steps[] = {8, 16, 32}, ao_radii[] = {0.05, 0.1, 0.2}, ao_res[] = {64, 128, 256, 512}, ao_blurs[] = {0, 2, 4};
    static const double gi_rays[] = {4, 16, 64}, gi_steps[] = {8, 16, 32}, gi_radii[] = {0.5, 1, 1.75}, gi_res[] = {64, 128, 256}, gi_blurs[] = {0, 2, 4, 8};
    const int ao = which == SCREEN_AO;
    screen_args a;
    screen_report rep;
    cli_session s;
    cli_context c;
    const char *list;
    float *img = NULL;
    size_t per_scene;
    int r, rc, i, si;
    memset(&a, 0, sizeof a);
    memset(&rep, 0, sizeof rep);
    a.which = which;
    a.common.backend = VOXGI_BACKEND_CPU;
    a.out_dir = "build/report";
    a.scene_list = ao ? "cornell-box" : "cornell-box,rsm-walls";
    a.size[0] = a.size[1] = 128;
    a.spp = ao ? 1024 : 4096;
#define SET(field, count, from) (memcpy(a.field, from, sizeof from), a.count = (int)(sizeof from / sizeof from[0]))
    if (ao) {
        SET(rays, nrays, ao_rays);
        SET(steps, nsteps, ao_steps);
        SET(radii, nradii, ao_radii);
        SET(res, nres, ao_res);
        SET(blurs, nblurs, ao_blurs);
    } else {
        SET(rays, nrays, gi_rays);
        SET(steps, nsteps, gi_steps);
        SET(radii, nradii, gi_radii);
        SET(res, nres, gi_res);
        SET(blurs, nblurs, gi_blurs);
    }
#undef SET
    {
#define LIST(opt, field, count, lo_, open_, top, whole_, text) \
    {.name = opt, .arg = "LIST", .kind = CLI_NUMBERS, .dst = a.field, .items = &a.count, .min_items = 1, .max_items = SCREEN_MAX_LIST, \
     .lo = lo_, .lo_open = open_, .hi = top, .whole = whole_, .help = text}
        const cli_option options[] = {
            {.name = "--scenes", .arg = "LIST", .kind = CLI_STRING, .dst = &a.scene_list,
             .help = ao ? "built-in scenes, comma-separated (default cornell-box)" : "built-in scenes, comma-separated (default cornell-box,rsm-walls)"},
            {.name = "--size", .arg = "W H", .kind = CLI_INT, .count = 2, .dst = a.size, .lo = 1, .hi = 4096, .help = "image size (default 128 128)"},
            {.name = "--spp", .arg = "S", .kind = CLI_INT, .dst = &a.spp, .lo = 64, .hi = 1 << 20,
             .help = ao ? "samples per pixel of the converged references (default 1024)" : "samples per pixel of the converged references (default 4096)"},
            LIST("--rays", rays, nrays, 0, 1, 65536, 1,
                 ao ? "rays per pixel (default 4,16,64,256; the largest also for the views)" : "rays per pixel (default 4,16,64)"),
            LIST("--steps", steps, nsteps, 0, 1, 4096, 1, ao ? "ssao: steps along each ray (default 8,16,32)" : "ssgi: steps along each ray (default 8,16,32)"),
            LIST("--radii", radii, nradii, 0, 1, 10, 0,
                 ao ? "radii, shares of the scene's longest side (default 0.05,0.1,0.2)" : "radii, shares of the scene's longest side (default 0.5,1,1.75)"),
            LIST("--res", res, nres, 0, 1, 4096, 1,
                 ao ? "vao: voxels along the scene's longest side (default 64,128,256,512)"
                    : "hybrid: voxels along the scene's longest side (default 64,128,256; the\nfinest also for Hybrid-GI converged)"),
            LIST("--blurs", blurs, nblurs, 0, 0, 64, 1,
                 ao ? "edge-aware blur radii in pixels, at full and at half resolution (default\n0,2,4)"
                    : "edge-aware blur radii in pixels, at full and at half resolution (default\n0,2,4,8)"),
            CLI_OPT_BACKEND(&a.common, "where the passes run (default cpu; the references always on the CPU)"),
            {.name = "--out", .arg = "DIR", .kind = CLI_STRING, .dst = &a.out_dir, .help = "where the files go (default build/report)"},
            CLI_OPT_THREADS(&a.common)};
#undef LIST
        const cli_command cmd = {.name = ao ? "report ao" : "report ssgi", .help = ao ? ao_help : ssgi_help, .column = 27, .options = options,
                                 .option_count = CLI_COUNT(options)};
        if ((rc = cli_parse(&cmd, argc, argv)) != CLI_CONTINUE) return rc;
    }
    for (list = a.scene_list; (r = cli_next_item(&list, rep.scenes[rep.scene_count], sizeof rep.scenes[0])) != 0; rep.scene_count++)
        if (r < 0 || rep.scene_count == SCREEN_MAX_SCENES)
            return cli_usage("report", "--scenes needs 1 to %d comma-separated built-in scenes, got '%s'", SCREEN_MAX_SCENES, a.scene_list);
    rep.radii[rep.nradii++] = base_config(which, M_SSAO).radius; /* the references' radii: the base's, then --radii's */
    for (i = 0; i < a.nradii; i++) {
        int k;
        for (k = 0; k < rep.nradii && rep.radii[k] != a.radii[i]; k++) {}
        if (k == rep.nradii) rep.radii[rep.nradii++] = a.radii[i];
    }
    per_scene = (size_t)(ao ? CLI_COUNT(ao_methods) : CLI_COUNT(gi_methods)) * SWEEP_MAX;
    cli_session_init(&s, "report");
    if (cli_context_open_options(&s, &c, &a.common)) return CLI_EXIT_FAILURE;
    voxgi_query_info(c.vx, &rep.ci);
    rc = CLI_EXIT_FAILURE;
    rep.rows = (screen_row *)calloc((size_t)rep.scene_count * per_scene, sizeof *rep.rows);
    img = (float *)malloc((size_t)a.size[0] * (size_t)a.size[1] * 12);
    if (!rep.rows || !img) {
        cli_fail(&s, "out of memory");
        goto done;
    }
    if (cli_make_dirs(a.out_dir) != 0) {
        cli_fail(&s, "cannot make %s", a.out_dir);
        goto done;
    }
    for (si = 0; si < rep.scene_count; si++)
        if (screen_scene(&s, c.vx, &a, &rep, si, img)) goto done;
    if (ao ? ao_views(&s, c.vx, &a, &rep) : ssgi_wall(&s, c.vx, &a, &rep, img)) goto done;
    screen_pareto(&rep, ao);
    if (screen_write(&s, &a, &rep)) goto done;
    cli_status_clear(&s);
    screen_print(&a, &rep);
    printf("wrote %s/%s.md, %s/%s.csv\n", a.out_dir, report_names[which], a.out_dir, report_names[which]);
    rc = CLI_EXIT_OK;
done:
    free(rep.rows);
    free(img);
    cli_context_close(&s, &c);
    return rc;
}
