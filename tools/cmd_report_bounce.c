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

/* DDA against the hierarchy on one scene's segments. */
typedef struct bounce_traversal {
    size_t segments, blocked[2], disagree;
    uint64_t steps[2];
    double ms[2];
} bounce_traversal;

typedef struct bounce_report {
    report_opts o;
    int method;
    report_list map_sizes, samples, radii, points, strides, res, openings;
    int visibility[3], nvisibility, segments;
    bounce_traversal traversal[REPORT_MAX_SCENES];
} bounce_report;

/* A row's values (report_item.v): the parameters (rsm: map size, samples, radius, points, stride,
   the visibility's resolution; sh: resolution, opening, stride), then the visibility, what it
   took and the red light beyond the reference's. */
enum { V_PARAMS = 6, V_VISIBILITY = V_PARAMS, V_GATHERED, V_GATHER_MS, V_RED };

#define BOUNCE_TAIL \
    {.md = "visibility", .align = ":-:", .csv = "visibility", .at = V_VISIBILITY, .names = visibility_names, .csv_names = visibility_names}, \
        REPORT_COL_INT("pixels gathering", "gathered", V_GATHERED), REPORT_COL("gathers ms", "gather_ms", V_GATHER_MS, "%.1f", "%.3f"), \
        REPORT_COL("total ms", "ms", REPORT_AT_MS, "%.1f", "%.3f"), REPORT_COL_ERROR(NULL), \
        {.md = "red excess", .align = "---:", .csv = "red_excess", .at = V_RED, .md_fmt = "%.2f%%", .csv_fmt = "%.6g", .md_unit = '%'}, \
        REPORT_COL_REF, REPORT_COL_FRONT
static const report_column rsm_columns[] = {REPORT_COL_SCENE,
                                            REPORT_COL_INT("map size", "map_size", 0),
                                            REPORT_COL_INT("samples", "samples", 1),
                                            REPORT_COL("radius", "radius", 2, "%g", "%g"),
                                            REPORT_COL_INT("points", "points", 3),
                                            REPORT_COL_INT("stride", "stride", 4),
                                            REPORT_COL_INT("voxels", "res", 5),
                                            BOUNCE_TAIL};
static const report_column sh_columns[] = {REPORT_COL_SCENE, REPORT_COL_INT("resolution", "res", 0), REPORT_COL("opening", "opening", 1, "%g", "%g"),
                                           REPORT_COL_INT("stride", "stride", 2), BOUNCE_TAIL};

/* Segments between random pairs of the view's surfaces, each end 1.5 voxels off its own along
   its normal (as the gathers test them), through a conservative grid of 64 voxels along the
   scene's longest side, by both traversals. */
static int bounce_traversals(cli_session *s, voxgi_context *ctx, const voxgi_scene *scene, const voxgi_camera *cam, int count, bounce_traversal *T)
{
    size_t pixels = (size_t)cam->width * (size_t)cam->height, n = 0, i, k, *lit = NULL;
    float *pos = (float *)malloc(pixels * 12), *nrm = (float *)malloc(pixels * 12), *from = (float *)malloc((size_t)count * 12),
          *to = (float *)malloc((size_t)count * 12);
    uint32_t *tri = (uint32_t *)malloc(pixels * 4);
    unsigned char *both = (unsigned char *)malloc(2 * (size_t)count), *blocked[2]; /* each traversal's answers */
    voxgi_voxelize_desc vd;
    voxgi_voxels *vox = NULL;
    uint64_t state = 0x9E3779B97F4A7C15ull;
    int rc = 1, how, a;
    memset(T, 0, sizeof *T);
    memset(&vd, 0, sizeof vd);
    lit = (size_t *)malloc(pixels * sizeof *lit);
    if (!pos || !nrm || !from || !to || !tri || !both || !lit) {
        cli_fail(s, "the traversals: out of memory");
        goto done;
    }
    blocked[0] = both;
    blocked[1] = both + count;
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
    free(both);
    free(lit);
    return rc;
}

/* Renders the configuration of it->v's parameters and visibility into run->img: what it took, its red light. */
static int bounce_image(report_run *run, const bounce_report *a, report_item *it)
{
    const double *p = it->v;
    voxgi_render_desc d;
    voxgi_render_info info;
    voxgi_result r;
    memset(&d, 0, sizeof d);
    memset(&info, 0, sizeof info);
    d.camera = run->camera;
    d.hide_emitters = 1;
    d.seed = 1;
    if (a->method == BOUNCE_RSM) {
        d.method = VOXGI_RENDER_RSM;
        d.rsm.maps.seed = 1;
        d.rsm.maps.size = (int)p[0];
        d.rsm.maps.samples = (int)p[1];
        d.rsm.maps.radius = (float)p[2];
        d.rsm.maps.points = (int)p[3];
        d.rsm.gather_stride = (int)p[4];
        d.resolution = (int)p[5];
        d.rsm.visibility = (voxgi_traversal)p[V_VISIBILITY];
        snprintf(it->settings, sizeof it->settings, "maps of %d texels, %d samples, radius %g, %d points, stride %d, %d voxels, %s", d.rsm.maps.size,
                 d.rsm.maps.samples, p[2], d.rsm.maps.points, d.rsm.gather_stride, d.resolution, visibility_names[d.rsm.visibility]);
        cli_status(run->s, "%s: rsm, %d texels, %d samples, radius %g, %d points, stride %d, %d voxels, %s", run->scene_name, d.rsm.maps.size,
                   d.rsm.maps.samples, p[2], d.rsm.maps.points, d.rsm.gather_stride, d.resolution, visibility_names[d.rsm.visibility]);
    } else {
        d.method = VOXGI_RENDER_SH;
        d.sh.volume.seed = 1;
        d.resolution = (int)p[0];
        d.sh.opening = (float)p[1];
        d.sh.gather_stride = (int)p[2];
        d.sh.visibility = (voxgi_traversal)p[V_VISIBILITY];
        snprintf(it->settings, sizeof it->settings, "%d voxels, opening %g, stride %d, %s", d.resolution, p[1], d.sh.gather_stride,
                 visibility_names[d.sh.visibility]);
        cli_status(run->s, "%s: sh, %d voxels, opening %g, stride %d, %s", run->scene_name, d.resolution, p[1], d.sh.gather_stride,
                   visibility_names[d.sh.visibility]);
    }
    r = voxgi_render(run->ctx, run->scene, &d, run->img, (size_t)d.camera.width * (size_t)d.camera.height * 12, &info);
    it->method = bounce_names[a->method];
    it->bytes = (double)info.bytes;
    it->ms = info.ms;
    it->v[V_GATHERED] = (double)info.gathered;
    it->v[V_GATHER_MS] = voxgi_render_stage_ms(&info, "gather");
    snprintf(it->passes, sizeof it->passes, "%s %.1f, voxels %.1f, direct %.1f, gathers %.1f", a->method == BOUNCE_RSM ? "maps" : "SH volume",
             voxgi_render_stage_ms(&info, a->method == BOUNCE_RSM ? "maps" : "sh"), voxgi_render_stage_ms(&info, "voxels"),
             voxgi_render_stage_ms(&info, "direct"), it->v[V_GATHER_MS]);
    if (r != VOXGI_OK) return cli_fail_lib(run->s, run->ctx, bounce_names[a->method]);
    it->v[V_RED] = cli_red_excess(run->R, run->img);
    return 0;
}

/* Every configuration of run->args: the visibilities times the parameter lists' product, the last
   varying fastest. */
static int bounce_sweep(report_run *run)
{
    const bounce_report *a = (const bounce_report *)run->args;
    const report_list *rsm[V_PARAMS] = {&a->map_sizes, &a->samples, &a->radii, &a->points, &a->strides, &a->res},
                      *sh[3] = {&a->res, &a->openings, &a->strides};
    const report_list *const *lists = a->method == BOUNCE_RSM ? rsm : sh;
    const int np = a->method == BOUNCE_RSM ? V_PARAMS : 3;
    int at[V_PARAMS], v, k;
    for (v = 0; v < a->nvisibility; v++) {
        memset(at, 0, sizeof at);
        do {
            report_item it;
            memset(&it, 0, sizeof it);
            for (k = 0; k < np; k++) it.v[k] = lists[k]->v[at[k]];
            it.v[V_VISIBILITY] = a->visibility[v];
            if (bounce_image(run, a, &it)) return 1;
            report_measured(run, &it);
        } while (report_next(lists, np, at));
    }
    return 0;
}

/* rsm: the traversals on the scene's view. */
static int bounce_scene_done(report *rep, report_run *run)
{
    bounce_report *a = (bounce_report *)rep->own;
    if (a->method != BOUNCE_RSM || a->segments <= 0) return 0;
    cli_status(run->s, "%s: the traversals, %d segments", run->scene_name, a->segments);
    return bounce_traversals(run->s, run->ctx, run->scene, &run->camera, a->segments, &a->traversal[rep->si]);
}

static void bounce_md_head(FILE *md, const report *rep)
{
    const bounce_report *a = (const bounce_report *)rep->own;
    fprintf(md, "# %s: error against run time\n\n%d x %d pixels; direct light and one bounce against the reference's one bounce (%d spp); CPU. Error: "
                "relative RMSE by the tools' rule (`voxgi render --compare`). *Red excess*: red light beyond the reference's, a share of its mean "
                "(colour bleeding through walls). *Reference at the same error*: the time the path tracer needs for an image that measures that "
                "error (from its own convergence). Wall clock on this machine.\n",
            a->method == BOUNCE_RSM ? "Reflective shadow maps" : "The SH volume of the direct light", a->o.size[0], a->o.size[0], a->o.spp);
}

static void bounce_md_scene(FILE *md, const report *rep, int si, int end)
{
    const bounce_traversal *T = &((const bounce_report *)rep->own)->traversal[si];
    if (!end) report_md_scene(md, rep, si, end);
    else if (T->segments)
        fprintf(md, "\nVoxel visibility of %lu segments between random pairs of the view's surfaces (ends 1.5 voxels off them; 64 voxels "
                    "across):\n\n| traversal | blocked | steps | ms |\n|---|---:|---:|---:|\n| 3D-DDA | %lu | %llu voxels | %.1f |\n"
                    "| hierarchical | %lu | %llu cells | %.1f |\n\nThey disagree on %lu segments.\n",
                (unsigned long)T->segments, (unsigned long)T->blocked[0], (unsigned long long)T->steps[0], T->ms[0], (unsigned long)T->blocked[1],
                (unsigned long long)T->steps[1], T->ms[1], (unsigned long)T->disagree);
}

static void bounce_print_scene(const report *rep, int si, int end)
{
    const report_scene *sc = &rep->scenes[si];
    const bounce_traversal *T = &((const bounce_report *)rep->own)->traversal[si];
    if (!end) printf("%s (reference error %.2f%% / sqrt(spp), %.2f ms per spp); the front:\n", sc->name, 100 * sc->c[0], sc->ms_per_spp[0]);
    else if (T->segments)
        printf("  traversals over %lu segments: DDA blocks %lu (%llu voxels, %.1f ms), hierarchical %lu (%llu cells, %.1f ms), %lu disagree\n",
               (unsigned long)T->segments, (unsigned long)T->blocked[0], (unsigned long long)T->steps[0], T->ms[0], (unsigned long)T->blocked[1],
               (unsigned long long)T->steps[1], T->ms[1], (unsigned long)T->disagree);
}

static void bounce_print_row(const report *rep, const report_row *q)
{
    const double *p = q->it.v;
    const char *vis = visibility_names[(int)p[V_VISIBILITY]];
    if (((const bounce_report *)rep->own)->method == BOUNCE_RSM)
        printf("  %d %d %g %d %d %d %s", (int)p[0], (int)p[1], p[2], (int)p[3], (int)p[4], (int)p[5], vis);
    else printf("  %d %g %d %s", (int)p[0], p[1], (int)p[2], vis);
    printf("  %8.1f ms  %6.2f%%  red excess %.2f%%\n", q->it.ms, 100 * q->it.error, 100 * p[V_RED]);
}

static const report_def bounce_defs[2] = {
    {.name = "rsm", .help = rsm_help, .bounces = 1, .columns = rsm_columns, .ncolumns = CLI_COUNT(rsm_columns), .sweep = bounce_sweep,
     .scene_done = bounce_scene_done, .md_head = bounce_md_head, .md_scene = bounce_md_scene, .print_scene = bounce_print_scene,
     .print_row = bounce_print_row},
    {.name = "sh", .help = sh_help, .bounces = 1, .columns = sh_columns, .ncolumns = CLI_COUNT(sh_columns), .sweep = bounce_sweep,
     .md_head = bounce_md_head, .md_scene = bounce_md_scene, .print_scene = bounce_print_scene, .print_row = bounce_print_row}};

/* report all's rsm and sh: hierarchical visibility, gathers at every 4th pixel (the tool's); rsm
   over samples and radii with 4 points on an area light, sh over resolutions and openings. */
static int bounce_all(report_run *run, int method)
{
#define BOUNCE_ALL .strides = REPORT_L(4), .visibility = {VOXGI_TRAVERSAL_HIERARCHICAL}, .nvisibility = 1
    static const bounce_report all[2][2] = { /* [method][quick] */
        {{.method = BOUNCE_RSM, .map_sizes = REPORT_L(256), .samples = REPORT_L(50, 200), .radii = REPORT_L(0.3, 1), .points = REPORT_L(4),
          .res = REPORT_L(64), BOUNCE_ALL},
         {.method = BOUNCE_RSM, .map_sizes = REPORT_L(128), .samples = REPORT_L(50, 200), .radii = REPORT_L(1), .points = REPORT_L(1),
          .res = REPORT_L(64), BOUNCE_ALL}},
        {{.method = BOUNCE_SH, .res = REPORT_L(32, 64, 96), .openings = REPORT_L(0.5, 1), BOUNCE_ALL},
         {.method = BOUNCE_SH, .res = REPORT_L(16, 32), .openings = REPORT_L(0.5), BOUNCE_ALL}}};
#undef BOUNCE_ALL
    run->args = &all[method][run->quick != 0];
    return bounce_sweep(run);
}

int report_rsm_all(report_run *run) { return bounce_all(run, BOUNCE_RSM); }
int report_sh_all(report_run *run) { return bounce_all(run, BOUNCE_SH); }

static int bounce_main(int method, int argc, char **argv)
{
    bounce_report a = {.o = REPORT_OPTS("cornell-box,rsm-walls", 128, 1024), .method = method, .map_sizes = REPORT_L(256),
                       .samples = REPORT_L(50, 100, 200), .radii = REPORT_L(0.1, 0.3, 1), .points = REPORT_L(1, 4), .strides = REPORT_L(1, 4),
                       .res = REPORT_L(64), .openings = REPORT_L(0.25, 0.5, 1), .visibility = {0, 2} /* hierarchical, none */, .nvisibility = 2,
                       .segments = 20000};
    if (method == BOUNCE_SH) a.res = (report_list)REPORT_L(32, 64, 96);
    {
#define BOUNCE_HEAD \
    REPORT_OPT_SCENES(&a.o, "built-in scenes, comma-separated (default cornell-box,rsm-walls)"), \
        REPORT_OPT_SIZE(&a.o, 1, "N x N pixels (default 128)"), \
        REPORT_OPT_SPP(&a.o, 64, "samples per pixel of the converged reference (default 1024)")
#define BOUNCE_VISIBILITY \
    {.name = "--visibility", .arg = "LIST", .kind = CLI_ENUMS, .dst = a.visibility, .items = &a.nvisibility, .names = visibility_names, \
     .min_items = 1, .max_items = 3, .help = "visibilities through the voxels (default hierarchical,none)"}
        const cli_option rsm_options[] = {
            BOUNCE_HEAD,
            REPORT_LIST("--map-sizes", a.map_sizes, 0, 1, 16384, 1, "texels across the maps (default 256)"),
            REPORT_LIST("--samples", a.samples, 0, 1, 65536, 1, "texels gathered per pixel and map (default 50,100,200)"),
            REPORT_LIST("--radii", a.radii, 0, 1, 2, 0, "the sample disc's radius, a share of the map (default 0.1,0.3,1)"),
            REPORT_LIST("--points", a.points, 0, 1, 4096, 1, "points on each area light and on the emitters (default 1,4)"),
            REPORT_LIST("--strides", a.strides, 0, 1, 64, 1, "gather strides (default 1,4)"),
            REPORT_LIST("--res", a.res, 0, 1, 4096, 1, "the visibility's voxels along the scene's longest side (default 64)"),
            BOUNCE_VISIBILITY,
            {.name = "--segments", .arg = "N", .kind = CLI_INT, .dst = &a.segments, .lo = 0, .hi = 1 << 24,
             .help = "segments the two traversals compare on (default 20000; 0: none)"},
            REPORT_OPT_OUT(&a.o), CLI_OPT_THREADS(&a.o.common)};
        const cli_option sh_options[] = {
            BOUNCE_HEAD,
            REPORT_LIST("--res", a.res, 0, 1, 1024, 1, "voxels along the scene's longest side (default 32,64,96)"),
            REPORT_LIST("--openings", a.openings, 0, 1, 4, 0, "the estimator's openings (default 0.25,0.5,1)"),
            REPORT_LIST("--strides", a.strides, 0, 1, 64, 1, "gather strides (default 1,4)"),
            BOUNCE_VISIBILITY, REPORT_OPT_OUT(&a.o), CLI_OPT_THREADS(&a.o.common)};
#undef BOUNCE_HEAD
#undef BOUNCE_VISIBILITY
        if (method == BOUNCE_RSM) return report_main(&bounce_defs[0], &a.o, &a, rsm_options, CLI_COUNT(rsm_options), argc, argv);
        return report_main(&bounce_defs[1], &a.o, &a, sh_options, CLI_COUNT(sh_options), argc, argv);
    }
}

int cmd_report_rsm(int argc, char **argv) { return bounce_main(BOUNCE_RSM, argc, argv); }
int cmd_report_sh(int argc, char **argv) { return bounce_main(BOUNCE_SH, argc, argv); }
