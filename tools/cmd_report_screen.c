/* tools/cmd_report_screen.c - voxgi report ao and report ssgi: the screen-space passes' error
 * against run time (one parameter at a time around a base configuration), as Markdown and CSV;
 * for ambient occlusion how much it changes at fixed points over a camera orbit, for the bounce
 * the light the screen cannot see and a red wall at the edge of the view. */
#include "report.h"
#include <stdlib.h>
#include <string.h>

#define SCREEN_PI 3.14159265358979323846

enum { SCREEN_AO, SCREEN_SSGI };

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

/* One configuration; a parameter its method does not use is 0 (steps for the voxels and for point
   sampling, res for the depth buffer). radius: a share of the scene's longest side. */
typedef struct screen_config {
    int method, rays, steps, res, half, blur, hidden; /* hidden: hybrid+light's hidden light */
    double radius;
} screen_config;

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

typedef struct screen_measure { /* an image beside the rows: its error and time */
    double rmse, ms;
} screen_measure;

typedef struct screen_report {
    report_opts o;
    int which;
    report_list rays, steps, radii, res, blurs;
    double ref_radii[REPORT_MAX_REFS];      /* the references' radii (shares): ao the base's first, then --radii's; ssgi the base's */
    int nref_radii;
    double longest[REPORT_MAX_SCENES];
    double direct_rmse[REPORT_MAX_SCENES];  /* ssgi: the direct light alone */
    double screen_rmse[REPORT_MAX_SCENES];  /* ssgi: the reference's bounce from the surfaces the camera sees alone */
    screen_measure converged[REPORT_MAX_SCENES][2]; /* ssgi: Hybrid-GI converged, without and with the hidden light */
    screen_measure vct[REPORT_MAX_SCENES];          /* ssgi: cone tracing's defaults */
    int converged_res;                              /* ssgi: Hybrid-GI converged's voxels, the finest of --res */
    view_spread views[2][2][2];             /* ao: [the orbit, the seeds][at the pixel, at the point][depth buffer, voxels] */
    int view_rays;
    double view_radius;
    wall_view walls[3];                     /* ssgi */
} screen_report;

/* A row's values (report_item.v). */
enum { V_METHOD, V_RAYS, V_STEPS, V_RADIUS, V_RADIUS_ABS, V_RES, V_HALF, V_BLUR, V_GATHERED, V_PASS_MS, V_RED };
static const char *const half_csv[] = {"0", "1"};
#define SCREEN_COLUMNS(pass_md, pass_csv) \
    REPORT_COL_SCENE, {.md = "method", .align = "---", .csv = "method", .at = V_METHOD, .names = method_names, .csv_names = method_names}, \
        REPORT_COL_INT("rays", "rays", V_RAYS), \
        {.md = "steps", .align = "---:", .csv = "steps", .at = V_STEPS, .md_fmt = "%.0f", .csv_fmt = "%.0f", .md_none = "-", .csv_none = ""}, \
        REPORT_COL("radius", "radius_share", V_RADIUS, "%g", "%g"), REPORT_COL(NULL, "radius", V_RADIUS_ABS, NULL, "%.6g"), \
        {.md = "voxels", .align = "---:", .csv = "res", .at = V_RES, .md_fmt = "%.0f", .csv_fmt = "%.0f", .md_none = "-", .csv_none = ""}, \
        {.md = "half res.", .align = ":-:", .csv = "half_res", .at = V_HALF, .names = report_yes, .csv_names = half_csv}, \
        REPORT_COL_INT("blur", "blur", V_BLUR), REPORT_COL_INT("pixels computed", "gathered", V_GATHERED), \
        REPORT_COL(pass_md, pass_csv, V_PASS_MS, "%.1f", "%.3f"), REPORT_COL("total ms", "ms", REPORT_AT_MS, "%.1f", "%.3f"), \
        REPORT_COL_ERROR("-")
static const report_column ao_columns[] = {SCREEN_COLUMNS("occlusion ms", "ao_ms"), REPORT_COL_REF, REPORT_COL_FRONT};
static const report_column ssgi_columns[] = {
    SCREEN_COLUMNS("gathers ms", "gather_ms"),
    {.md = "red excess", .align = "---:", .csv = "red_excess", .at = V_RED, .md_fmt = "%.2f%%", .csv_fmt = "%.6g", .md_unit = '%', .md_none = "-"},
    REPORT_COL_REF, REPORT_COL_FRONT};

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

#define SWEEP_MAX (6 * REPORT_MAX_LIST)

/* The configurations of a method: each list's values with the rest at the base (the lists of
   parameters it does not use left out), then half resolution with each blur; each once. */
static int sweep(const screen_report *a, int method, screen_config *out)
{
    const screen_config base = base_config(a->which, method);
    screen_config c;
    int i, half, n = 0;
    for (i = 0; i < a->rays.n; i++) { c = base; c.rays = (int)a->rays.v[i]; n = add_config(out, n, &c); }
    for (i = 0; i < a->steps.n && uses_steps(method); i++) { c = base; c.steps = (int)a->steps.v[i]; n = add_config(out, n, &c); }
    for (i = 0; i < a->radii.n; i++) { c = base; c.radius = a->radii.v[i]; n = add_config(out, n, &c); }
    for (i = 0; i < a->res.n && uses_res(method); i++) { c = base; c.res = (int)a->res.v[i]; n = add_config(out, n, &c); }
    for (half = 0; half < 2; half++)
        for (i = 0; i < a->blurs.n; i++) { c = base; c.half = half; c.blur = (int)a->blurs.v[i]; n = add_config(out, n, &c); }
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

/* Renders configuration c of scene (its longest side `longest`) seen by cam into img; what it
   is and took into it. Every setting is given (a zero field of voxgi_render_desc is the method's
   measured default, not the configuration's): half resolution off or on, blur -1 for none, the
   hidden light off or on. */
static voxgi_result render_config(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_camera *cam, double longest, const screen_config *c, float *img,
                                  report_item *it)
{
    size_t bytes = (size_t)cam->width * (size_t)cam->height * 12;
    int ao = c->method == M_SSAO || c->method == M_SSAO_POINTS || c->method == M_VAO;
    voxgi_render_desc d;
    voxgi_render_info info;
    voxgi_result r;
    double *v = it->v, voxels;
    char text[160];
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
    it->method = method_names[c->method];
    config_text(c, text, sizeof text);
    snprintf(it->settings, sizeof it->settings, "%s", text + strlen(it->method) + 2); /* without "method, " */
    it->ms = info.ms;
    it->bytes = (double)info.bytes;
    v[V_METHOD] = c->method;
    v[V_RAYS] = c->rays;
    v[V_STEPS] = c->steps ? c->steps : NAN;
    v[V_RADIUS] = c->radius;
    v[V_RADIUS_ABS] = c->radius * longest;
    v[V_RES] = c->res ? c->res : NAN;
    v[V_HALF] = c->half;
    v[V_BLUR] = c->blur;
    v[V_GATHERED] = (double)info.gathered;
    v[V_PASS_MS] = voxgi_render_stage_ms(&info, ao ? "ao" : "gather");
    voxels = voxgi_render_stage_ms(&info, "voxels");
    if (ao)
        snprintf(it->passes, sizeof it->passes, "G-buffer %.1f, voxels %.1f, occlusion %.1f", voxgi_render_stage_ms(&info, "gbuffer"), voxels, v[V_PASS_MS]);
    else
        snprintf(it->passes, sizeof it->passes, "direct %.1f, voxels %.1f, their light %.1f, gathers %.1f", voxgi_render_stage_ms(&info, "direct"), voxels,
                 voxgi_render_stage_ms(&info, "inject"), v[V_PASS_MS]);
    return r;
}

/* ------------------------------------------------------------------ the sweeps */
/* Every configuration of each of the report's methods, each measured against the reference at its
   radius (ao: R[k] at ref_radii[k]; ssgi: R[0]). */
static int screen_sweep(report_run *run)
{
    const screen_report *a = (const screen_report *)run->args;
    const double longest = cli_scene_longest_side(run->scene);
    const int *methods = a->which == SCREEN_AO ? ao_methods : gi_methods;
    const int nmethods = a->which == SCREEN_AO ? CLI_COUNT(ao_methods) : CLI_COUNT(gi_methods);
    screen_config configs[SWEEP_MAX];
    char text[160];
    int m, i, k, n;
    for (m = 0; m < nmethods; m++) {
        n = sweep(a, methods[m], configs);
        for (i = 0; i < n; i++) {
            report_item it;
            for (k = 0; a->which == SCREEN_AO && a->ref_radii[k] != configs[i].radius; k++) {}
            config_text(&configs[i], text, sizeof text);
            cli_status(run->s, "%s: %s", run->scene_name, text);
            memset(&it, 0, sizeof it);
            if (render_config(run->ctx, run->scene, &run->camera, longest, &configs[i], run->img, &it) != VOXGI_OK) return cli_fail_lib(run->s, run->ctx, text);
            it.ref = k;
            it.v[V_RED] = a->which == SCREEN_SSGI ? cli_red_excess(&run->R[k], run->img) : 0;
            report_measured(run, &it);
        }
    }
    return 0;
}

/* ao: the references' radii, the base's first, then --radii's. */
static int screen_open(report *rep)
{
    screen_report *a = (screen_report *)rep->own;
    int i, k;
    a->ref_radii[0] = base_config(a->which, M_SSAO).radius;
    a->nref_radii = 1;
    for (i = 0; i < a->radii.n && a->which == SCREEN_AO; i++) {
        for (k = 0; k < a->nref_radii && a->ref_radii[k] != a->radii.v[i]; k++) {}
        if (k == a->nref_radii) a->ref_radii[a->nref_radii++] = a->radii.v[i];
    }
    return 0;
}

/* ao: a reference per radius, each method measured at its own; ssgi: the one bounce. */
static int screen_references(report *rep, report_run *run, cli_reference *R)
{
    screen_report *a = (screen_report *)rep->own;
    const double longest = a->longest[rep->si] = cli_scene_longest_side(run->scene);
    int k;
    for (k = 0; k < a->nref_radii; k++) {
        if (cli_reference_make(run->s, run->ctx, run->scene, &run->camera, a->o.spp, 1, a->which == SCREEN_AO ? a->ref_radii[k] * longest : 0, &R[k]))
            return 1;
        if (R[k].mask.masked_pixels == (size_t)run->camera.width * (size_t)run->camera.height)
            return cli_fail(run->s, "%s: every pixel is within %d pixels of one that sees an emitter: no error to measure", run->scene_name, CLI_EMITTER_MARGIN);
    }
    rep->nrefs = a->nref_radii;
    return 0;
}

/* ssgi: the direct light alone, the reference's bounce from the screen alone, Hybrid-GI converged
   (with and without the hidden light) and cone tracing's defaults, against R[0]. */
static int screen_scene_done(report *rep, report_run *run)
{
    screen_report *a = (screen_report *)rep->own;
    const int si = rep->si;
    const size_t bytes = (size_t)run->camera.width * (size_t)run->camera.height * 12;
    const cli_reference *R = run->R;
    screen_config c = base_config(SCREEN_SSGI, M_HYBRID);
    cli_reference direct;
    voxgi_render_desc rd, vd;
    voxgi_render_info vi;
    int k;
    if (a->which != SCREEN_SSGI) return 0;
    /* the direct light alone: the reference's, converged */
    if (cli_reference_make(run->s, run->ctx, run->scene, &run->camera, a->o.spp, 0, 0, &direct)) return 1;
    a->direct_rmse[si] = cli_masked_error(&R[0].mask, direct.image, R[0].image, NULL, NULL);
    cli_reference_free(&direct);
    /* the most a bounce from the screen can find: the reference's bounce from the surfaces the camera sees alone */
    memset(&rd, 0, sizeof rd);
    rd.method = VOXGI_RENDER_REFERENCE;
    rd.camera = run->camera;
    rd.samples = a->o.spp;
    rd.bounces = 1;
    rd.seed = 1000003; /* cli_reference_make's: the same noise as the full bounce's where they agree */
    rd.hide_emitters = 1;
    rd.reference.screen_light_only = 1;
    cli_status(run->s, "%s: the reference's bounce from the screen alone, %d spp", run->scene_name, a->o.spp);
    if (voxgi_render(run->ctx, run->scene, &rd, run->img, bytes, NULL) != VOXGI_OK)
        return cli_fail_lib(run->s, run->ctx, "the reference's bounce from the screen alone");
    a->screen_rmse[si] = cli_masked_error(&R[0].mask, run->img, R[0].image, NULL, NULL);
    /* Hybrid-GI converged: what it still misses is light from surfaces the camera does not see;
       with the hidden light, what the voxels' injected light gives of it */
    c.rays = 256;
    c.res = 0;
    for (k = 0; k < a->res.n; k++) c.res = c.res > (int)a->res.v[k] ? c.res : (int)a->res.v[k]; /* the finest of --res: 256 by default */
    c.radius = 1.75;
    a->converged_res = c.res;
    for (k = 0; k < 2; k++) {
        report_item it;
        c.hidden = k;
        cli_status(run->s, "%s: Hybrid-GI converged%s", run->scene_name, k ? ", hidden light" : "");
        if (render_config(run->ctx, run->scene, &run->camera, a->longest[si], &c, run->img, &it) != VOXGI_OK)
            return cli_fail_lib(run->s, run->ctx, "Hybrid-GI converged");
        a->converged[si][k].rmse = cli_masked_error(&R[0].mask, run->img, R[0].image, NULL, NULL);
        a->converged[si][k].ms = it.ms;
    }
    cli_vct_defaults(&vd, &run->camera);
    cli_status(run->s, "%s: cone tracing, the tool's defaults", run->scene_name);
    if (voxgi_render(run->ctx, run->scene, &vd, run->img, bytes, &vi) != VOXGI_OK) return cli_fail_lib(run->s, run->ctx, "cone tracing");
    a->vct[si].rmse = cli_masked_error(&R[0].mask, run->img, R[0].image, NULL, NULL);
    a->vct[si].ms = vi.ms;
    return 0;
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
static int ao_views(cli_session *s, voxgi_context *ctx, screen_report *a)
{
    const int w = a->o.size[0], h = a->o.size[1];
    const size_t pixels = (size_t)w * (size_t)h;
    voxgi_builtin_scene bs;
    voxgi_voxelize_desc vd;
    voxgi_voxels *vox = NULL;
    const voxgi_scene *box;
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
    a->view_rays = 0;
    for (i = 0; i < a->rays.n; i++) a->view_rays = a->view_rays > (int)a->rays.v[i] ? a->view_rays : (int)a->rays.v[i];
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
    if (report_scene_open(s, ctx, "cornell-box", NULL, &bs, &box, &def, w, h)) goto done;
    a->view_radius = 0.1 * cli_scene_longest_side(&bs.scene);
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
                d.rays = a->view_rays;
                d.steps = 16;
                d.radius = (float)a->view_radius;
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
                view_spread *V = &a->views[g][reading][m];
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
static int ssgi_wall(cli_session *s, voxgi_context *ctx, screen_report *a, float *img)
{
    const int w = a->o.size[0], h = a->o.size[1];
    const size_t pixels = (size_t)w * (size_t)h;
    voxgi_builtin_scene bs;
    const voxgi_scene *box;
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
    if (report_scene_open(s, ctx, "cornell-box", NULL, &bs, &box, &def, w, h)) goto done;
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
    a->walls[0].yaw = 0;
    a->walls[1].yaw = a->walls[2].yaw = -1;
    for (step = 0; step * WALL_YAW_STEP <= 90 && a->walls[2].yaw < 0; step++) { /* the first yaws at which the wall is a sliver, then gone */
        const double yaw = step * WALL_YAW_STEP;
        size_t count;
        int widest;
        if (wall_gbuffer(s, ctx, &bs.scene, &def, yaw, tri)) goto done;
        red_pixels(&bs.scene, tri, w, h, WALL_FINE, NULL, &count, &widest);
        if (step == 0 && count == 0) {
            cli_fail(s, "the Cornell box's red wall is not in its view");
            goto done;
        }
        if (count && widest <= WALL_SLIVER && a->walls[1].yaw < 0) a->walls[1].yaw = yaw;
        if (count) last_seen = yaw;
        else a->walls[2].yaw = yaw;
    }
    if (a->walls[2].yaw < 0) {
        cli_fail(s, "the Cornell box's red wall stays in view however far the camera turns");
        goto done;
    }
    if (a->walls[1].yaw < 0) a->walls[1].yaw = last_seen; /* it left between two steps: its last sight */
    a->walls[2].yaw += def.fovy_degrees / h; /* a pixel further: no ray of the direct light, spread over the pixel, meets it */
    for (v = 0; v < 3; v++) {
        wall_view *W = &a->walls[v];
        const voxgi_camera cam = turned_camera(&def, W->yaw);
        if (wall_gbuffer(s, ctx, &bs.scene, &def, W->yaw, tri)) goto done;
        red_pixels(&bs.scene, tri, w, h, WALL_FINE, red, &W->red_pixels, &W->widest);
        if (cli_reference_make(s, ctx, &bs.scene, &cam, a->o.spp, 1, 0, &R1) || cli_reference_make(s, ctx, &bs.scene, &cam, a->o.spp, 0, 0, &R0) ||
            cli_reference_make(s, ctx, &grey_scene, &cam, a->o.spp, 1, 0, &G1))
            goto done;
        W->rmse[WALL_REFERENCE] = 0;
        W->bleed[WALL_REFERENCE] = red_bleeding(R1.image, R0.image, red, &R1.mask);
        W->colour[WALL_REFERENCE] = red_bleeding(R1.image, G1.image, red, &R1.mask);
        W->rmse[WALL_DIRECT] = cli_masked_error(&R1.mask, R0.image, R1.image, NULL, NULL);
        W->bleed[WALL_DIRECT] = W->colour[WALL_DIRECT] = 0;
        for (k = WALL_SSGI; k < WALL_METHODS; k++) {
            screen_config c = base_config(SCREEN_SSGI, k == WALL_SSGI ? M_SSGI : M_HYBRID);
            report_item it;
            c.rays = WALL_RAYS;
            c.hidden = k == WALL_HIDDEN;
            cli_status(s, "the wall %s: %s", wall_view_names[v], wall_method_names[k]);
            if (render_config(ctx, &grey_scene, &cam, longest, &c, grey, &it) != VOXGI_OK ||
                render_config(ctx, &bs.scene, &cam, longest, &c, img, &it) != VOXGI_OK) {
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
static const char *const view_method_names[2] = {"SSAO (ray marching, 16 steps)", "voxel AO (128^3)"}, *const view_reading_names[2] = {"the pixel's surface", "the point"};

static void write_views(FILE *f, const screen_report *a)
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
            a->o.size[0], a->o.size[1], VIEW_STRIDE, a->view_rays, a->view_radius);
    for (reading = 0; reading < 2; reading++)
        for (m = 0; m < 2; m++) {
            const view_spread *O = &a->views[0][reading][m], *S = &a->views[1][reading][m];
            fprintf(f, "| %s | %s | %lu | %.1f | %.4f | %.4f | %.4f | %.4f |\n", view_method_names[m], view_reading_names[reading], (unsigned long)O->points,
                    O->passes, O->mean, O->p95, S->mean, S->p95);
        }
}

/* x / of, a percentage; "-" without a share. */
static void put_share(FILE *f, double x, double of, const char *after) { report_percent(f, of != 0 ? x / of : NAN, after); }

static void write_wall(FILE *f, const screen_report *a)
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
            a->o.size[0], a->o.size[1], WALL_YAW_STEP, WALL_SLIVER, WALL_FINE, WALL_FINE, a->o.spp, WALL_RAYS);
    for (v = 0; v < 3; v++) {
        const wall_view *W = &a->walls[v];
        for (k = 0; k < WALL_METHODS; k++) {
            if (k == 0) fprintf(f, "| %s | %g° | %lu (%d) | ", wall_view_names[v], W->yaw, (unsigned long)W->red_pixels, W->widest);
            else fprintf(f, "| | | | ");
            fprintf(f, "%s | ", wall_method_names[k]);
            if (k == WALL_REFERENCE) fprintf(f, "- | ");
            else report_percent(f, W->rmse[k], " | ");
            fprintf(f, "%.5f | ", W->bleed[k]);
            put_share(f, W->bleed[k], W->bleed[WALL_REFERENCE], " | ");
            fprintf(f, "%.5f | ", W->colour[k]);
            put_share(f, W->colour[k], W->colour[WALL_REFERENCE], " |\n");
        }
    }
}

static void screen_md_head(FILE *md, const report *rep)
{
    const screen_report *a = (const screen_report *)rep->own;
    const voxgi_info *ci = &rep->ci;
    fprintf(md,
            a->which == SCREEN_AO
                ? "# Ambient occlusion from the screen and from the voxels: error against run time\n\n%d x %d pixels; occlusion against the "
                  "reference's ambient occlusion at the same radius (%d spp); %s%s%s (%d threads). One parameter at a time around the base (16 "
                  "rays, 16 steps, radius 0.1 of the scene's longest side, 128 voxels, full resolution, no blur), and half resolution with each "
                  "blur. *Radius*: a share of the scene's longest side. Error: relative RMSE by the tools' rule (`voxgi render --compare`); it "
                  "is relative to the mean occlusion, which is small: small absolute errors weigh heavily. *Reference at the same error*: the "
                  "time the path tracer's AO needs for an image that measures that error (from its own convergence). The Pareto front: of each "
                  "scene and radius. Wall clock on this machine%s.\n"
                : "# One bounce from the screen (SSGI, Hybrid-GI): error against run time\n\n%d x %d pixels; direct light and one bounce against "
                  "the reference's one bounce (%d spp); %s%s%s (%d threads). One parameter at a time around the base (16 rays, 16 steps, radius "
                  "1 x the scene's longest side, 128 voxels, full resolution, no blur), and half resolution with each blur. *Radius*: a share of "
                  "the scene's longest side. Error: relative RMSE by the tools' rule (`voxgi render --compare`). *Red excess*: red light beyond "
                  "the reference's, a share of its mean. *Reference at the same error*: the time the path tracer needs for an image that "
                  "measures that error (from its own convergence). Wall clock on this machine%s.\n",
            a->o.size[0], a->o.size[1], a->o.spp, voxgi_backend_name(ci->backend), ci->backend == VOXGI_BACKEND_GL ? ", " : "",
            ci->backend == VOXGI_BACKEND_GL ? ci->gl_renderer : "", ci->thread_count,
            ci->backend == VOXGI_BACKEND_GL && ci->gl_software ? " (GL on a software rasteriser: not GPU timings)" : "");
}

static void screen_md_scene(FILE *md, const report *rep, int si, int end)
{
    const screen_report *a = (const screen_report *)rep->own;
    const report_scene *sc = &rep->scenes[si];
    int k;
    if (end) return;
    fprintf(md, "\n## %s\n\nThe longest side: %.4g. %lu pixels near an emitter left out. Reference: ", sc->name, a->longest[si], (unsigned long)sc->masked);
    for (k = 0; k < a->nref_radii; k++) {
        if (a->which == SCREEN_AO) fprintf(md, "%sradius %g (%.4g): ", k ? "; " : "", a->ref_radii[k], a->ref_radii[k] * a->longest[si]);
        fprintf(md, "its error is %.2f%% / sqrt(spp), %.2f ms per sample per pixel", 100 * sc->c[k], sc->ms_per_spp[k]);
    }
    if (a->which == SCREEN_SSGI) {
        fprintf(md, ". The direct light alone measures ");
        report_percent(md, a->direct_rmse[si], "");
    }
    fprintf(md, ".\n\n");
}

static int screen_md_end(report *rep, FILE *md, FILE *csv)
{
    const screen_report *a = (const screen_report *)rep->own;
    int si;
    (void)csv;
    if (a->which == SCREEN_AO) {
        write_views(md, a);
        return 0;
    }
    fprintf(md, "\n## Light the screen cannot see\n\nWhat no bounce from the screen can find is light from surfaces the camera does "
                "not see. *Screen light alone*: the reference's bounce from the surfaces the camera sees only (`voxgi render "
                "--screen-light-only`, %d spp), the floor of every screen method's error. *Hybrid-GI converged*: 256 rays, %d voxels (the finest of "
                "--res), radius 1.75, full resolution, no blur; *with the hidden light*: the same with hits the camera does not see sending the direct light "
                "injected into their voxels (`--hidden-light`, an extension beyond the screen). Beside them the direct light alone and cone "
                "tracing with the tool's defaults (`voxgi render --method vct`: %d^3, anisotropic, %d cones at every %dth pixel, %d "
                "direct-light rays per pixel), the same scene and size.\n\n| scene | direct light alone | screen light alone | Hybrid-GI "
                "converged | its time | with the hidden light | its time | cone tracing | its time |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n",
            a->o.spp, a->converged_res, CLI_VCT_RES, CLI_VCT_CONES, CLI_VCT_STRIDE, CLI_VCT_DIRECT_SPP);
    for (si = 0; si < rep->nscenes; si++) {
        fprintf(md, "| %s | ", rep->scenes[si].name);
        report_percent(md, a->direct_rmse[si], " | ");
        report_percent(md, a->screen_rmse[si], " | ");
        report_percent(md, a->converged[si][0].rmse, "");
        fprintf(md, " | %.0f ms | ", a->converged[si][0].ms);
        report_percent(md, a->converged[si][1].rmse, "");
        fprintf(md, " | %.0f ms | ", a->converged[si][1].ms);
        report_percent(md, a->vct[si].rmse, "");
        fprintf(md, " | %.0f ms |\n", a->vct[si].ms);
    }
    write_wall(md, a);
    return 0;
}

static void screen_print_scene(const report *rep, int si, int end)
{
    const screen_report *a = (const screen_report *)rep->own;
    if (!end) {
        printf("%s (%lu pixels near an emitter left out)", rep->scenes[si].name, (unsigned long)rep->scenes[si].masked);
        if (a->which == SCREEN_SSGI) {
            printf("; direct light alone ");
            report_percent(stdout, a->direct_rmse[si], "");
        }
        printf("; the front%s:\n", a->which == SCREEN_AO ? " of each radius" : "");
    } else if (a->which == SCREEN_SSGI) {
        printf("  screen light alone (the reference's) ");
        report_percent(stdout, a->screen_rmse[si], "");
        printf("; Hybrid-GI converged %.1f ms  ", a->converged[si][0].ms);
        report_percent(stdout, a->converged[si][0].rmse, "");
        printf(", with the hidden light %.1f ms  ", a->converged[si][1].ms);
        report_percent(stdout, a->converged[si][1].rmse, "");
        printf("; cone tracing (the tool's defaults) %.1f ms  ", a->vct[si].ms);
        report_percent(stdout, a->vct[si].rmse, "\n");
    }
}

static void screen_print_row(const report *rep, const report_row *q)
{
    char text[200];
    (void)rep;
    snprintf(text, sizeof text, "%s, %s", q->it.method, q->it.settings);
    printf("  %-62s %8.1f ms  ", text, q->it.ms);
    report_percent(stdout, q->it.error, "\n");
}

static void screen_print_end(const report *rep)
{
    const screen_report *a = (const screen_report *)rep->own;
    int v, k;
    if (a->which == SCREEN_AO)
        for (k = 0; k < 4; k++) {
            const view_spread *O = &a->views[0][k / 2][k % 2], *S = &a->views[1][k / 2][k % 2];
            printf("view-independence (cornell-box, %d rays), %s at %s: %lu points, spread over 9 views mean %.4f, 95th percentile %.4f; over 9 seeds %.4f, %.4f\n",
                   a->view_rays, view_method_names[k % 2], view_reading_names[k / 2], (unsigned long)O->points, O->mean, O->p95, S->mean, S->p95);
        }
    else
        for (v = 0; v < 3; v++) {
            const wall_view *W = &a->walls[v];
            printf("red wall %s (yaw %g, %lu pixels), a share of the reference's: red - green SSGI ", wall_view_names[v], W->yaw, (unsigned long)W->red_pixels);
            put_share(stdout, W->bleed[WALL_SSGI], W->bleed[WALL_REFERENCE], ", Hybrid-GI ");
            put_share(stdout, W->bleed[WALL_HYBRID], W->bleed[WALL_REFERENCE], "; from the wall's colour SSGI ");
            put_share(stdout, W->colour[WALL_SSGI], W->colour[WALL_REFERENCE], ", Hybrid-GI ");
            put_share(stdout, W->colour[WALL_HYBRID], W->colour[WALL_REFERENCE], ", with the hidden light ");
            put_share(stdout, W->colour[WALL_HIDDEN], W->colour[WALL_REFERENCE], "\n");
        }
}

/* ao: the view-independence; ssgi: the red wall. */
static int screen_done(report *rep)
{
    screen_report *a = (screen_report *)rep->own;
    return a->which == SCREEN_AO ? ao_views(&rep->s, rep->c.vx, a) : ssgi_wall(&rep->s, rep->c.vx, a, rep->img);
}

static const report_def screen_defs[2] = {
    {.name = "ao", .help = ao_help, .columns = ao_columns, .ncolumns = CLI_COUNT(ao_columns), .sweep = screen_sweep, .open = screen_open,
     .references = screen_references, .done = screen_done, .md_head = screen_md_head, .md_scene = screen_md_scene, .md_end = screen_md_end,
     .print_scene = screen_print_scene, .print_row = screen_print_row, .print_end = screen_print_end},
    {.name = "ssgi", .help = ssgi_help, .columns = ssgi_columns, .ncolumns = CLI_COUNT(ssgi_columns), .sweep = screen_sweep, .open = screen_open,
     .references = screen_references, .scene_done = screen_scene_done, .done = screen_done, .md_head = screen_md_head, .md_scene = screen_md_scene,
     .md_end = screen_md_end, .print_scene = screen_print_scene, .print_row = screen_print_row, .print_end = screen_print_end}};

/* report all's screen passes: the one-parameter sweeps around the base over rays and voxels, at
   the base's radius (its reference's), and half resolution with the tools' blur (ao 2, ssgi 8). */
static int screen_all(report_run *run, int which)
{
    screen_report a;
    memset(&a, 0, sizeof a);
    a.which = which;
    a.rays = run->quick ? (report_list)REPORT_L(16) : (report_list)REPORT_L(4, 16, 64);
    a.res = run->quick ? (report_list)REPORT_L(64) : (report_list)REPORT_L(64, 128);
    a.steps = (report_list)REPORT_L(16);
    a.blurs = which == SCREEN_AO ? (report_list)REPORT_L(2) : (report_list)REPORT_L(8);
    a.radii.v[0] = a.ref_radii[0] = base_config(which, M_SSAO).radius;
    a.radii.n = a.nref_radii = 1;
    run->args = &a;
    return screen_sweep(run);
}

int report_ao_all(report_run *run) { return screen_all(run, SCREEN_AO); }
int report_ssgi_all(report_run *run) { return screen_all(run, SCREEN_SSGI); }

static int screen_main(int which, int argc, char **argv)
{
    static const screen_report defaults[2] = {
        {.o = REPORT_OPTS("cornell-box", 128, 1024), .which = SCREEN_AO, .rays = REPORT_L(4, 16, 64, 256), .steps = REPORT_L(8, 16, 32),
         .radii = REPORT_L(0.05, 0.1, 0.2), .res = REPORT_L(64, 128, 256, 512), .blurs = REPORT_L(0, 2, 4)},
        {.o = REPORT_OPTS("cornell-box,rsm-walls", 128, 4096), .which = SCREEN_SSGI, .rays = REPORT_L(4, 16, 64), .steps = REPORT_L(8, 16, 32),
         .radii = REPORT_L(0.5, 1, 1.75), .res = REPORT_L(64, 128, 256), .blurs = REPORT_L(0, 2, 4, 8)}};
    const int ao = which == SCREEN_AO;
    screen_report *a = (screen_report *)malloc(sizeof *a);
    int rc;
    if (!a) return CLI_EXIT_FAILURE;
    *a = defaults[which];
    {
        const cli_option options[] = {
            REPORT_OPT_SCENES(&a->o, ao ? "built-in scenes, comma-separated (default cornell-box)" : "built-in scenes, comma-separated (default cornell-box,rsm-walls)"),
            {.name = "--size", .arg = "W H", .kind = CLI_INT, .count = 2, .dst = a->o.size, .lo = 1, .hi = 4096, .help = "image size (default 128 128)"},
            REPORT_OPT_SPP(&a->o, 64, ao ? "samples per pixel of the converged references (default 1024)" : "samples per pixel of the converged references (default 4096)"),
            REPORT_LIST("--rays", a->rays, 0, 1, 65536, 1, ao ? "rays per pixel (default 4,16,64,256; the largest also for the views)" : "rays per pixel (default 4,16,64)"),
            REPORT_LIST("--steps", a->steps, 0, 1, 4096, 1, ao ? "ssao: steps along each ray (default 8,16,32)" : "ssgi: steps along each ray (default 8,16,32)"),
            REPORT_LIST("--radii", a->radii, 0, 1, 10, 0,
                        ao ? "radii, shares of the scene's longest side (default 0.05,0.1,0.2)" : "radii, shares of the scene's longest side (default 0.5,1,1.75)"),
            REPORT_LIST("--res", a->res, 0, 1, 4096, 1,
                        ao ? "vao: voxels along the scene's longest side (default 64,128,256,512)"
                           : "hybrid: voxels along the scene's longest side (default 64,128,256; the\nfinest also for Hybrid-GI converged)"),
            REPORT_LIST("--blurs", a->blurs, 0, 0, 64, 1,
                        ao ? "edge-aware blur radii in pixels, at full and at half resolution (default\n0,2,4)"
                           : "edge-aware blur radii in pixels, at full and at half resolution (default\n0,2,4,8)"),
            CLI_OPT_BACKEND(&a->o.common, "where the passes run (default cpu; the references always on the CPU)"), REPORT_OPT_OUT(&a->o),
            CLI_OPT_THREADS(&a->o.common)};
        rc = report_main(&screen_defs[which], &a->o, a, options, CLI_COUNT(options), argc, argv);
    }
    free(a);
    return rc;
}

int cmd_report_ao(int argc, char **argv) { return screen_main(SCREEN_AO, argc, argv); }
int cmd_report_ssgi(int argc, char **argv) { return screen_main(SCREEN_SSGI, argc, argv); }
