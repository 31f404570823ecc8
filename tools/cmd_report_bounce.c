/* tools/cmd_report_bounce.c - voxgi report rsm and report sh: the one-bounce methods' error
 * against run time, as Markdown and CSV, and how the voxel traversals compare. */
#include "report.h"
#include <stdlib.h>
#include <string.h>

enum { BOUNCE_RSM, BOUNCE_SH };
static const char *const bounce_names[] = {"rsm", "sh"};
static const char *const visibility_names[] = {"hierarchical", "dda", "none", NULL}; /* voxgi_traversal's order */

static const char *const rsm_help =
    "usage: voxgi report rsm [options]\n"
    "Error against run time of reflective shadow maps (voxgi render --method rsm). For each built-in\n"
    "scene it renders the reference's one bounce (converged, --spp samples per pixel), then the\n"
    "image for every combination of map size, samples, radius, points on the area lights, gather\n"
    "stride and visibility, and measures the relative RMSE by the tools' rule (render --compare's)\n"
    "and the red light in excess of the reference's (the colour bleeding through walls). It also\n"
    "sends segments between random pairs of the image's surfaces through the voxels by 3D-DDA and\n"
    "by the hierarchical traversal: how many each blocks, its steps and time, and where they\n"
    "disagree. Writes DIR/rsm.md and DIR/rsm.csv, the Pareto front marked. Wall clock on this\n"
    "machine.\n";

static const char *const sh_help =
    "usage: voxgi report sh [options]\n"
    "Error against run time of the SH volume of the direct light (voxgi render --method sh). For\n"
    "each built-in scene it renders the reference's one bounce (converged, --spp samples per\n"
    "pixel), then the image for every combination of resolution, opening, gather stride and\n"
    "visibility, and measures the relative RMSE by the tools' rule (render --compare's) and the\n"
    "red light in excess of the reference's. Writes DIR/sh.md and DIR/sh.csv, the Pareto front\n"
    "marked. Wall clock on this machine.\n";

#define BOUNCE_MAX_SCENES 8
#define BOUNCE_MAX_LIST 16
#define BOUNCE_PARAMS 6

typedef struct bounce_args {
    cli_common common;
    int method;
    const char *out_dir, *scene_list;
    double map_sizes[BOUNCE_MAX_LIST], samples[BOUNCE_MAX_LIST], radii[BOUNCE_MAX_LIST], points[BOUNCE_MAX_LIST], strides[BOUNCE_MAX_LIST];
    double res[BOUNCE_MAX_LIST], openings[BOUNCE_MAX_LIST];
    int visibility[3];
    int nmap_sizes, nsamples, nradii, npoints, nstrides, nres, nopenings, nvisibility, size, spp, segments;
} bounce_args;

/* One image: its parameters (rsm: map size, samples, radius, points, stride, the visibility's
   resolution; sh: resolution, opening, stride), what it took and how far it is. */
typedef struct bounce_row {
    int scene, visibility, pareto;
    double p[BOUNCE_PARAMS];
    size_t gathered;
    double ms, ms_gather, rmse, red, ref_ms;
    double ms_passes[3]; /* the maps or the SH volume, the voxels, the direct light */
} bounce_row;

/* DDA against the hierarchy on one scene's segments. */
typedef struct bounce_traversal {
    size_t segments, blocked[2], disagree;
    uint64_t steps[2];
    double ms[2];
} bounce_traversal;

typedef struct bounce_report {
    char scenes[BOUNCE_MAX_SCENES][64];
    int scene_count, nrows;
    double ref_c[BOUNCE_MAX_SCENES], ref_ms_per_spp[BOUNCE_MAX_SCENES];
    size_t masked[BOUNCE_MAX_SCENES];
    bounce_traversal traversal[BOUNCE_MAX_SCENES];
    bounce_row *rows;
} bounce_report;

/* Segments between random pairs of the view's surfaces, each end 1.5 voxels off its own along
   its normal (as the gathers test them), through a conservative grid of 64 voxels along the
   scene's longest side, by both traversals. */
static int bounce_traversals(cli_session *s, voxgi_context *ctx, const voxgi_scene *scene, const voxgi_camera *cam, int count, bounce_traversal *T)
{
    size_t pixels = (size_t)cam->width * (size_t)cam->height, n = 0, i, k, *lit = NULL;
    float *pos = (float *)malloc(pixels * 12), *nrm = (float *)malloc(pixels * 12), *from = (float *)malloc((size_t)count * 12),
          *to = (float *)malloc((size_t)count * 12);
    uint32_t *tri = (uint32_t *)malloc(pixels * 4);
    unsigned char *blocked[2] = {(unsigned char *)malloc((size_t)count), (unsigned char *)malloc((size_t)count)};
    voxgi_voxelize_desc vd;
    voxgi_voxels *vox = NULL;
    uint64_t state = 0x9E3779B97F4A7C15ull;
    int rc = 1, how, a;
    memset(T, 0, sizeof *T);
    memset(&vd, 0, sizeof vd);
    lit = (size_t *)malloc(pixels * sizeof *lit);
    if (!pos || !nrm || !from || !to || !tri || !blocked[0] || !blocked[1] || !lit) {
        cli_fail(s, "the traversals: out of memory");
        goto done;
    }
    if (voxgi_gbuffer_render(ctx, scene, cam, pos, nrm, tri) != VOXGI_OK || cli_fit_grid(ctx, scene, 64, 0, 0, &vd.grid) != VOXGI_OK ||
        voxgi_voxelize(ctx, scene, &vd, &vox) != VOXGI_OK) {
        cli_fail_lib(s, ctx, "the traversals' voxels");
        goto done;
    }
    for (i = 0; i < pixels; i++)
        if (tri[i] != UINT32_MAX) lit[n++] = i;
    if (n < 2) {
        rc = 0;
        goto done;
    }
    for (k = 0; k < (size_t)count; k++) { /* a fixed sequence: the same segments every run */
        size_t e[2];
        int end;
        for (end = 0; end < 2; end++) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            e[end] = lit[(size_t)(state >> 33) % n];
        }
        for (a = 0; a < 3; a++) {
            from[3 * k + (size_t)a] = (float)(pos[3 * e[0] + (size_t)a] + 1.5 * vd.grid.voxel_size * nrm[3 * e[0] + (size_t)a]);
            to[3 * k + (size_t)a] = (float)(pos[3 * e[1] + (size_t)a] + 1.5 * vd.grid.voxel_size * nrm[3 * e[1] + (size_t)a]);
        }
    }
    T->segments = (size_t)count;
    for (how = 0; how < 2; how++) {
        double t0 = cli_now_ms();
        if (voxgi_voxels_occluded(ctx, vox, how ? VOXGI_TRAVERSAL_HIERARCHICAL : VOXGI_TRAVERSAL_DDA, (size_t)count, from, to, blocked[how], &T->steps[how]) !=
            VOXGI_OK) {
            cli_fail_lib(s, ctx, "the traversal");
            goto done;
        }
        T->ms[how] = cli_now_ms() - t0;
        for (k = 0; k < (size_t)count; k++) T->blocked[how] += blocked[how][k];
    }
    for (k = 0; k < (size_t)count; k++) T->disagree += blocked[0][k] != blocked[1][k];
    rc = 0;
done:
    voxgi_voxels_destroy(ctx, vox);
    free(pos);
    free(nrm);
    free(from);
    free(to);
    free(tri);
    free(blocked[0]);
    free(blocked[1]);
    free(lit);
    return rc;
}

/* Renders one configuration of scene (its name) into img; its row, and its memory into *bytes. */
static int bounce_image(cli_session *s, voxgi_context *ctx, const bounce_args *a, const voxgi_scene *scene, const char *name, const voxgi_camera *cam,
                        const cli_reference *R, bounce_row *row, float *img, double *bytes)
{
    size_t img_bytes = (size_t)cam->width * (size_t)cam->height * 12;
    voxgi_render_desc d;
    voxgi_render_info info;
    voxgi_result r;
    memset(&d, 0, sizeof d);
    memset(&info, 0, sizeof info);
    d.camera = *cam;
    d.hide_emitters = 1;
    d.seed = 1;
    if (a->method == BOUNCE_RSM) {
        d.method = VOXGI_RENDER_RSM;
        d.rsm.maps.seed = 1;
        d.rsm.maps.size = (int)row->p[0];
        d.rsm.maps.samples = (int)row->p[1];
        d.rsm.maps.radius = (float)row->p[2];
        d.rsm.maps.points = (int)row->p[3];
        d.rsm.gather_stride = (int)row->p[4];
        d.resolution = (int)row->p[5];
        d.rsm.visibility = (voxgi_traversal)row->visibility;
        cli_status(s, "%s: rsm, %d texels, %d samples, radius %g, %d points, stride %d, %d voxels, %s", name, d.rsm.maps.size, d.rsm.maps.samples, row->p[2],
                   d.rsm.maps.points, d.rsm.gather_stride, d.resolution, visibility_names[row->visibility]);
    } else {
        d.method = VOXGI_RENDER_SH;
        d.sh.volume.seed = 1;
        d.resolution = (int)row->p[0];
        d.sh.opening = (float)row->p[1];
        d.sh.gather_stride = (int)row->p[2];
        d.sh.visibility = (voxgi_traversal)row->visibility;
        cli_status(s, "%s: sh, %d voxels, opening %g, stride %d, %s", name, d.resolution, row->p[1], d.sh.gather_stride, visibility_names[row->visibility]);
    }
    r = voxgi_render(ctx, scene, &d, img, img_bytes, &info);
    *bytes = (double)info.bytes;
    row->ms = info.ms;
    row->ms_gather = voxgi_render_stage_ms(&info, "gather");
    row->gathered = info.gathered;
    row->ms_passes[0] = voxgi_render_stage_ms(&info, a->method == BOUNCE_RSM ? "maps" : "sh");
    row->ms_passes[1] = voxgi_render_stage_ms(&info, "voxels");
    row->ms_passes[2] = voxgi_render_stage_ms(&info, "direct");
    if (r != VOXGI_OK) return cli_fail_lib(s, ctx, bounce_names[a->method]);
    row->rmse = cli_masked_error(&R->mask, img, R->image, NULL, NULL);
    row->red = cli_red_excess(R, img);
    row->ref_ms = cli_reference_ms(R, row->rmse);
    return 0;
}

/* Every configuration of scene (its name, its index si; the parameter lists' product, the last
   varying fastest) against R, appended to rep's rows; with run, each also handed to report all. */
static int bounce_sweep(cli_session *s, voxgi_context *ctx, const bounce_args *a, const voxgi_scene *scene, const char *name, const voxgi_camera *cam,
                        const cli_reference *R, bounce_report *rep, int si, float *img, report_run *run)
{
    const double *lists[BOUNCE_PARAMS];
    int counts[BOUNCE_PARAMS], at[BOUNCE_PARAMS], np, v, k;
    if (a->method == BOUNCE_RSM) {
        lists[0] = a->map_sizes; counts[0] = a->nmap_sizes;
        lists[1] = a->samples; counts[1] = a->nsamples;
        lists[2] = a->radii; counts[2] = a->nradii;
        lists[3] = a->points; counts[3] = a->npoints;
        lists[4] = a->strides; counts[4] = a->nstrides;
        lists[5] = a->res; counts[5] = a->nres;
        np = 6;
    } else {
        lists[0] = a->res; counts[0] = a->nres;
        lists[1] = a->openings; counts[1] = a->nopenings;
        lists[2] = a->strides; counts[2] = a->nstrides;
        np = 3;
    }
    for (v = 0; v < a->nvisibility; v++) {
        memset(at, 0, sizeof at);
        for (;;) {
            bounce_row *row = &rep->rows[rep->nrows];
            double bytes = 0;
            memset(row, 0, sizeof *row);
            row->scene = si;
            row->visibility = a->visibility[v];
            for (k = 0; k < np; k++) row->p[k] = lists[k][at[k]];
            if (bounce_image(s, ctx, a, scene, name, cam, R, row, img, &bytes)) return 1;
            rep->nrows++;
            if (run) {
                report_item it;
                memset(&it, 0, sizeof it);
                it.method = bounce_names[a->method];
                if (a->method == BOUNCE_RSM)
                    snprintf(it.settings, sizeof it.settings, "maps of %d texels, %d samples, radius %g, %d points, stride %d, %d voxels, %s", (int)row->p[0],
                             (int)row->p[1], row->p[2], (int)row->p[3], (int)row->p[4], (int)row->p[5], visibility_names[row->visibility]);
                else
                    snprintf(it.settings, sizeof it.settings, "%d voxels, opening %g, stride %d, %s", (int)row->p[0], row->p[1], (int)row->p[2],
                             visibility_names[row->visibility]);
                snprintf(it.passes, sizeof it.passes, "%s %.1f, voxels %.1f, direct %.1f, gathers %.1f", a->method == BOUNCE_RSM ? "maps" : "SH volume",
                         row->ms_passes[0], row->ms_passes[1], row->ms_passes[2], row->ms_gather);
                it.ms = row->ms;
                it.bytes = bytes;
                it.error = row->rmse;
                run->emit(run, &it, img);
            }
            for (k = np - 1; k >= 0 && ++at[k] == counts[k]; k--) at[k] = 0; /* the next combination */
            if (k < 0) break;
        }
    }
    return 0;
}

/* Scene si: its reference, every configuration, and for rsm the traversals. */
static int bounce_scene(cli_session *s, voxgi_context *ctx, const bounce_args *a, bounce_report *rep, int si, float *img)
{
    voxgi_builtin_scene bs;
    voxgi_camera cam;
    cli_reference R;
    int rc = 1;
    if (voxgi_builtin_scene_create(ctx, rep->scenes[si], &bs) != VOXGI_OK) return cli_fail_lib(s, ctx, rep->scenes[si]);
    cam = bs.camera;
    cam.width = cam.height = a->size;
    if (cli_reference_make(s, ctx, &bs.scene, &cam, a->spp, 1, 0, &R)) goto done;
    rep->masked[si] = R.mask.masked_pixels;
    rep->ref_c[si] = R.c;
    rep->ref_ms_per_spp[si] = R.ms_per_spp;
    if (bounce_sweep(s, ctx, a, &bs.scene, rep->scenes[si], &cam, &R, rep, si, img, NULL)) goto done;
    if (a->method == BOUNCE_RSM && a->segments > 0) {
        cli_status(s, "%s: the traversals, %d segments", rep->scenes[si], a->segments);
        if (bounce_traversals(s, ctx, &bs.scene, &cam, a->segments, &rep->traversal[si])) goto done;
    }
    rc = 0;
done:
    cli_reference_free(&R);
    voxgi_builtin_scene_destroy(ctx, &bs);
    return rc;
}

/* A row is on its scene's front when no other row is at once faster and better. */
static void bounce_pareto(bounce_report *rep) { PARETO_MARK(rep->rows, (size_t)rep->nrows, bounce_row, ms, rmse, scene, pareto); }

/* The parameter columns of a row, for Markdown (sep " | ") or CSV (sep ","). */
static void bounce_params(FILE *f, const bounce_args *a, const bounce_row *r, const char *sep)
{
    if (a->method == BOUNCE_RSM)
        fprintf(f, "%d%s%d%s%g%s%d%s%d%s%d%s%s", (int)r->p[0], sep, (int)r->p[1], sep, r->p[2], sep, (int)r->p[3], sep, (int)r->p[4], sep,
                (int)r->p[5], sep, visibility_names[r->visibility]);
    else fprintf(f, "%d%s%g%s%d%s%s", (int)r->p[0], sep, r->p[1], sep, (int)r->p[2], sep, visibility_names[r->visibility]);
}

static int bounce_write(cli_session *s, const bounce_args *a, const bounce_report *rep)
{
    const char *name = bounce_names[a->method];
    char path[1100];
    FILE *md, *csv;
    int si, i;
    snprintf(path, sizeof path, "%s/%s.md", a->out_dir, name);
    if (!(md = fopen(path, "w"))) return cli_fail(s, "cannot write %s", path);
    snprintf(path, sizeof path, "%s/%s.csv", a->out_dir, name);
    if (!(csv = fopen(path, "w"))) {
        fclose(md);
        return cli_fail(s, "cannot write %s", path);
    }
    fprintf(md, "# %s: error against run time\n\n%d x %d pixels; direct light and one bounce against the reference's one bounce (%d spp); CPU. Error: "
                "relative RMSE by the tools' rule (`voxgi render --compare`). *Red excess*: red light beyond the reference's, a share of its mean "
                "(colour bleeding through walls). *Reference at the same error*: the time the path tracer needs for an image that measures that "
                "error (from its own convergence). Wall clock on this machine.\n",
            a->method == BOUNCE_RSM ? "Reflective shadow maps" : "The SH volume of the direct light", a->size, a->size, a->spp);
    fprintf(csv, "%s,visibility,gathered,gather_ms,ms,rel_rmse,red_excess,reference_ms,pareto\n",
            a->method == BOUNCE_RSM ? "scene,map_size,samples,radius,points,stride,res" : "scene,res,opening,stride");
    for (si = 0; si < rep->scene_count; si++) {
        const bounce_traversal *T = &rep->traversal[si];
        fprintf(md, "\n## %s\n\nReference: its error is %.2f%% / sqrt(spp), %.2f ms per sample per pixel; %lu pixels near an emitter left out.\n\n",
                rep->scenes[si], 100 * rep->ref_c[si], rep->ref_ms_per_spp[si], (unsigned long)rep->masked[si]);
        fprintf(md, "%s | pixels gathering | gathers ms | total ms | rel. RMSE | red excess | reference at the same error | Pareto |\n%s|---:|---:|---:|---:|---:|---:|:-:|\n",
                a->method == BOUNCE_RSM ? "| map size | samples | radius | points | stride | voxels | visibility" : "| resolution | opening | stride | visibility",
                a->method == BOUNCE_RSM ? "|---:|---:|---:|---:|---:|---:|:-:" : "|---:|---:|---:|:-:");
        for (i = 0; i < rep->nrows; i++) {
            const bounce_row *r = &rep->rows[i];
            if (r->scene != si) continue;
            fprintf(md, "| ");
            bounce_params(md, a, r, " | ");
            fprintf(md, " | %lu | %.1f | %.1f | %.2f%% | %.2f%% | ", (unsigned long)r->gathered, r->ms_gather, r->ms, 100 * r->rmse, 100 * r->red);
            if (isfinite(r->ref_ms)) fprintf(md, "%.0f ms | %s |\n", r->ref_ms, r->pareto ? "yes" : "");
            else fprintf(md, "beyond its reference | %s |\n", r->pareto ? "yes" : "");
            fprintf(csv, "%s,", rep->scenes[si]);
            bounce_params(csv, a, r, ",");
            fprintf(csv, ",%lu,%.3f,%.3f,%.6g,%.6g,%.6g,%d\n", (unsigned long)r->gathered, r->ms_gather, r->ms, r->rmse, r->red,
                    isfinite(r->ref_ms) ? r->ref_ms : -1.0, r->pareto);
        }
        if (T->segments)
            fprintf(md, "\nVoxel visibility of %lu segments between random pairs of the view's surfaces (ends 1.5 voxels off them; 64 voxels "
                        "across):\n\n| traversal | blocked | steps | ms |\n|---|---:|---:|---:|\n| 3D-DDA | %lu | %llu voxels | %.1f |\n"
                        "| hierarchical | %lu | %llu cells | %.1f |\n\nThey disagree on %lu segments.\n",
                    (unsigned long)T->segments, (unsigned long)T->blocked[0], (unsigned long long)T->steps[0], T->ms[0], (unsigned long)T->blocked[1],
                    (unsigned long long)T->steps[1], T->ms[1], (unsigned long)T->disagree);
    }
    i = ferror(md) || ferror(csv);
    i |= fclose(md) != 0;
    i |= fclose(csv) != 0;
    return i ? cli_fail(s, "cannot write to %s", a->out_dir) : 0;
}

/* The configurations of a scene: the visibilities times the lists' product. */
static size_t bounce_combos(const bounce_args *a)
{
    return (size_t)a->nvisibility * (size_t)a->nstrides * (size_t)a->nres *
           (a->method == BOUNCE_RSM ? (size_t)a->nmap_sizes * (size_t)a->nsamples * (size_t)a->nradii * (size_t)a->npoints : (size_t)a->nopenings);
}

/* report all's rsm and sh: hierarchical visibility, gathers at every 4th pixel (the tool's); rsm
   over samples and radii with 4 points on an area light, sh over resolutions and openings. */
static int bounce_all(report_run *run, int method)
{
    static const double samples[] = {50, 200}, radii[] = {0.3, 1}, sh_res[] = {32, 64, 96}, quick_sh_res[] = {16, 32}, openings[] = {0.5, 1};
    bounce_args a;
    bounce_report rep;
    int rc;
    memset(&a, 0, sizeof a);
    memset(&rep, 0, sizeof rep);
    a.method = method;
#define SET(field, count, from) (memcpy(a.field, from, sizeof from), a.count = CLI_COUNT(from))
    SET(samples, nsamples, samples);
    if (run->quick) a.radii[0] = 1, a.nradii = 1;
    else SET(radii, nradii, radii);
    if (method == BOUNCE_SH && run->quick) SET(res, nres, quick_sh_res), a.openings[0] = 0.5, a.nopenings = 1;
    else if (method == BOUNCE_SH) SET(res, nres, sh_res), SET(openings, nopenings, openings);
    else a.res[0] = 64, a.nres = 1;
#undef SET
    a.map_sizes[0] = run->quick ? 128 : 256;
    a.points[0] = run->quick ? 1 : 4;
    a.strides[0] = 4;
    a.visibility[0] = VOXGI_TRAVERSAL_HIERARCHICAL;
    a.nmap_sizes = a.npoints = a.nstrides = a.nvisibility = 1;
    if (!(rep.rows = (bounce_row *)calloc(bounce_combos(&a), sizeof *rep.rows))) return cli_fail(run->s, "out of memory");
    rc = bounce_sweep(run->s, run->ctx, &a, run->scene, run->scene_name, &run->camera, run->R, &rep, 0, run->img, run);
    free(rep.rows);
    return rc;
}

int report_rsm_all(report_run *run) { return bounce_all(run, BOUNCE_RSM); }
int report_sh_all(report_run *run) { return bounce_all(run, BOUNCE_SH); }

int cmd_report_bounce(int method, int argc, char **argv)
{
    static const double map_sizes[] = {256}, samples[] = {50, 100, 200}, radii[] = {0.1, 0.3, 1}, points[] = {1, 4}, strides[] = {1, 4};
    static const double res[] = {32, 64, 96}, openings[] = {0.25, 0.5, 1};
    bounce_args a;
    bounce_report rep;
    cli_session s;
    cli_context c;
    const char *list;
    float *img = NULL;
    size_t combos;
    int r, rc, i, si;
    memset(&a, 0, sizeof a);
    memset(&rep, 0, sizeof rep);
    a.method = method;
    a.common.backend = VOXGI_BACKEND_CPU;
    a.out_dir = "build/report";
    a.scene_list = "cornell-box,rsm-walls";
    a.size = 128;
    a.spp = 1024;
    a.segments = 20000;
#define SET(field, count, from) (memcpy(a.field, from, sizeof from), a.count = (int)(sizeof from / sizeof from[0]))
    SET(map_sizes, nmap_sizes, map_sizes);
    SET(samples, nsamples, samples);
    SET(radii, nradii, radii);
    SET(points, npoints, points);
    SET(strides, nstrides, strides);
    if (method == BOUNCE_SH) SET(res, nres, res);
    else a.res[0] = 64, a.nres = 1;
    SET(openings, nopenings, openings);
#undef SET
    a.visibility[0] = 0; /* hierarchical, none */
    a.visibility[1] = 2;
    a.nvisibility = 2;
    {
#define LIST(opt, field, count, lo_, top, whole_, text) \
    {.name = opt, .arg = "LIST", .kind = CLI_NUMBERS, .dst = a.field, .items = &a.count, .min_items = 1, .max_items = BOUNCE_MAX_LIST, \
     .lo = lo_, .lo_open = 1, .hi = top, .whole = whole_, .help = text}
        const cli_option rsm_options[] = {
            {.name = "--scenes", .arg = "LIST", .kind = CLI_STRING, .dst = &a.scene_list, .help = "built-in scenes, comma-separated (default cornell-box,rsm-walls)"},
            {.name = "--size", .arg = "N", .kind = CLI_INT, .dst = &a.size, .lo = 1, .hi = 4096, .help = "N x N pixels (default 128)"},
            {.name = "--spp", .arg = "S", .kind = CLI_INT, .dst = &a.spp, .lo = 64, .hi = 1 << 20,
             .help = "samples per pixel of the converged reference (default 1024)"},
            LIST("--map-sizes", map_sizes, nmap_sizes, 0, 16384, 1, "texels across the maps (default 256)"),
            LIST("--samples", samples, nsamples, 0, 65536, 1, "texels gathered per pixel and map (default 50,100,200)"),
            LIST("--radii", radii, nradii, 0, 2, 0, "the sample disc's radius, a share of the map (default 0.1,0.3,1)"),
            LIST("--points", points, npoints, 0, 4096, 1, "points on each area light and on the emitters (default 1,4)"),
            LIST("--strides", strides, nstrides, 0, 64, 1, "gather strides (default 1,4)"),
            LIST("--res", res, nres, 0, 4096, 1, "the visibility's voxels along the scene's longest side (default 64)"),
            {.name = "--visibility", .arg = "LIST", .kind = CLI_ENUMS, .dst = a.visibility, .items = &a.nvisibility, .names = visibility_names,
             .min_items = 1, .max_items = 3, .help = "visibilities through the voxels (default hierarchical,none)"},
            {.name = "--segments", .arg = "N", .kind = CLI_INT, .dst = &a.segments, .lo = 0, .hi = 1 << 24,
             .help = "segments the two traversals compare on (default 20000; 0: none)"},
            {.name = "--out", .arg = "DIR", .kind = CLI_STRING, .dst = &a.out_dir, .help = "where the files go (default build/report)"},
            CLI_OPT_THREADS(&a.common)};
        const cli_option sh_options[] = {
            {.name = "--scenes", .arg = "LIST", .kind = CLI_STRING, .dst = &a.scene_list, .help = "built-in scenes, comma-separated (default cornell-box,rsm-walls)"},
            {.name = "--size", .arg = "N", .kind = CLI_INT, .dst = &a.size, .lo = 1, .hi = 4096, .help = "N x N pixels (default 128)"},
            {.name = "--spp", .arg = "S", .kind = CLI_INT, .dst = &a.spp, .lo = 64, .hi = 1 << 20,
             .help = "samples per pixel of the converged reference (default 1024)"},
            LIST("--res", res, nres, 0, 1024, 1, "voxels along the scene's longest side (default 32,64,96)"),
            LIST("--openings", openings, nopenings, 0, 4, 0, "the estimator's openings (default 0.25,0.5,1)"),
            LIST("--strides", strides, nstrides, 0, 64, 1, "gather strides (default 1,4)"),
            {.name = "--visibility", .arg = "LIST", .kind = CLI_ENUMS, .dst = a.visibility, .items = &a.nvisibility, .names = visibility_names,
             .min_items = 1, .max_items = 3, .help = "visibilities through the voxels (default hierarchical,none)"},
            {.name = "--out", .arg = "DIR", .kind = CLI_STRING, .dst = &a.out_dir, .help = "where the files go (default build/report)"},
            CLI_OPT_THREADS(&a.common)};
#undef LIST
        const cli_command rsm_cmd = {.name = "report rsm", .help = rsm_help, .column = 27, .options = rsm_options, .option_count = CLI_COUNT(rsm_options)};
        const cli_command sh_cmd = {.name = "report sh", .help = sh_help, .column = 27, .options = sh_options, .option_count = CLI_COUNT(sh_options)};
        if ((rc = cli_parse(method == BOUNCE_RSM ? &rsm_cmd : &sh_cmd, argc, argv)) != CLI_CONTINUE) return rc;
    }
    for (list = a.scene_list; (r = cli_next_item(&list, rep.scenes[rep.scene_count], sizeof rep.scenes[0])) != 0; rep.scene_count++)
        if (r < 0 || rep.scene_count == BOUNCE_MAX_SCENES)
            return cli_usage("report", "--scenes needs 1 to %d comma-separated built-in scenes, got '%s'", BOUNCE_MAX_SCENES, a.scene_list);
    combos = bounce_combos(&a);
    cli_session_init(&s, "report");
    if (cli_context_open_options(&s, &c, &a.common)) return CLI_EXIT_FAILURE;
    rc = CLI_EXIT_FAILURE;
    rep.rows = (bounce_row *)calloc((size_t)rep.scene_count * combos, sizeof *rep.rows);
    img = (float *)malloc((size_t)a.size * (size_t)a.size * 12);
    if (!rep.rows || !img) {
        cli_fail(&s, "out of memory");
        goto done;
    }
    if (cli_make_dirs(a.out_dir) != 0) {
        cli_fail(&s, "cannot make %s", a.out_dir);
        goto done;
    }
    for (si = 0; si < rep.scene_count; si++)
        if (bounce_scene(&s, c.vx, &a, &rep, si, img)) goto done;
    bounce_pareto(&rep);
    if (bounce_write(&s, &a, &rep)) goto done;
    cli_status_clear(&s);
    for (si = 0; si < rep.scene_count; si++) { /* the front on stdout */
        const bounce_traversal *T = &rep.traversal[si];
        printf("%s (reference error %.2f%% / sqrt(spp), %.2f ms per spp); the front:\n", rep.scenes[si], 100 * rep.ref_c[si], rep.ref_ms_per_spp[si]);
        for (i = 0; i < rep.nrows; i++) {
            const bounce_row *q = &rep.rows[i];
            if (q->scene != si || !q->pareto) continue;
            printf("  ");
            bounce_params(stdout, &a, q, " ");
            printf("  %8.1f ms  %6.2f%%  red excess %.2f%%\n", q->ms, 100 * q->rmse, 100 * q->red);
        }
        if (T->segments)
            printf("  traversals over %lu segments: DDA blocks %lu (%llu voxels, %.1f ms), hierarchical %lu (%llu cells, %.1f ms), %lu disagree\n",
                   (unsigned long)T->segments, (unsigned long)T->blocked[0], (unsigned long long)T->steps[0], T->ms[0], (unsigned long)T->blocked[1],
                   (unsigned long long)T->steps[1], T->ms[1], (unsigned long)T->disagree);
    }
    printf("wrote %s/%s.md, %s/%s.csv\n", a.out_dir, bounce_names[method], a.out_dir, bounce_names[method]);
    rc = CLI_EXIT_OK;
done:
    free(rep.rows);
    free(img);
    cli_context_close(&s, &c);
    return rc;
}
