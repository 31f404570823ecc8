/* tools/cmd_report.c - voxgi report: the reports' table; and voxgi report vct, the cone tracer's
 * error against run time, as Markdown, CSV and SVG. */
#include "report.h"
#include <stdlib.h>
#include <string.h>

static const char *const vct_help =
    "usage: voxgi report vct [options]\n"
    "Error against run time of voxel cone tracing. For each built-in scene it renders the one-bounce\n"
    "reference (converged, --spp samples per pixel), then the cone-traced image for every\n"
    "combination of grid resolution, cone count, aperture, step, cone stride and mips, and measures the\n"
    "relative RMSE of the lighting (the RMS difference over pixels and channels / the reference's\n"
    "mean) over the pixels farther than 3 pixels from any pixel whose centre sees an emitter, both\n"
    "images without the emission the camera sees. The reference's own convergence\n"
    "(4, 16 and 64 spp against the converged image; error ~ 1/sqrt(spp)) gives the time it needs\n"
    "to reach each error, and so the cone tracer's speed-up. Writes DIR/vct.md (tables),\n"
    "DIR/vct.csv and DIR/vct.svg (error against time, log scales, the Pareto front marked).\n"
    "It also times each stage of the tool's default configuration on the CPU and on GL, where a GL\n"
    "4.5 context can be made (--no-stages: not). Times are wall clock on this machine; GL times on a\n"
    "software rasteriser are not GPU times. The other reports: voxgi report tsm|rsm|sh|ao|ssgi|linespace\n"
    "--help, every method at once: voxgi report all --help, and stiff input: voxgi report stiff --help.\n";

/* mips: 0 isotropic, 1 anisotropic, 2 octree (the --filters bits 1, 2, 4) */
static const char *const mips_names[] = {"isotropic", "anisotropic", "octree", NULL}, *const mips_short[3] = {"iso", "aniso", "octree"},
                         *const mips_mark[3] = {"", "a", "o"};
static const int mips_bits[3] = {1, 2, 4};

typedef struct vct_report {
    report_opts o;
    report_list res, cones, apertures, steps, strides;
    unsigned filters;
    int direct_spp, no_stages, stage_res;
    double bvh_ms[REPORT_MAX_SCENES], floor[REPORT_MAX_SCENES]; /* each reference's BVH, and its own error at its spp */
    /* the stages of the tool's defaults: [0] the CPU, [1] GL (each the faster of two runs) */
    cli_context stage_c;          /* the other backend's context */
    voxgi_context *stage_ctx[2];  /* NULL: that backend is not timed */
    voxgi_info stage_ci[2];
    double stages[REPORT_MAX_SCENES][2][5]; /* voxelize, inject (with the mips), cones, direct, all */
} vct_report;

/* A row's values (report_item.v). */
enum { V_RES, V_CONES, V_APERTURE, V_HALF_ANGLE, V_STEP, V_STRIDE, V_MIPS, V_VOXELS, V_VOXELIZE, V_INJECT, V_OCTREE, V_CONES_MS, V_DIRECT };

static const report_column vct_columns[] = {
    REPORT_COL_SCENE, REPORT_COL_INT("res", "res", V_RES), REPORT_COL_INT("cones", "cones", V_CONES), REPORT_COL(NULL, "aperture", V_APERTURE, NULL, "%g"),
    REPORT_COL("half-angle", "half_angle_deg", V_HALF_ANGLE, "%.1f°", "%.2f"), REPORT_COL("step", "step", V_STEP, "%g", "%g"),
    REPORT_COL_INT("stride", "stride", V_STRIDE), {.md = "mips", .align = "---", .csv = "filter", .at = V_MIPS, .names = mips_short, .csv_names = mips_names},
    REPORT_COL_INT("voxels", "voxels", V_VOXELS),
    {.md = "radiance MB", .align = "---:", .csv = "radiance_bytes", .at = REPORT_AT_BYTES, .md_fmt = "%.1f", .csv_fmt = "%.0f", .md_unit = 'M'},
    REPORT_COL("voxelize ms", "voxelize_ms", V_VOXELIZE, "%.1f", "%.2f"), REPORT_COL("inject ms", "inject_ms", V_INJECT, "%.1f", "%.2f"),
    REPORT_COL("octree ms", "octree_ms", V_OCTREE, "%.1f", "%.2f"), REPORT_COL("cones ms", "cones_ms", V_CONES_MS, "%.1f", "%.2f"),
    REPORT_COL("direct ms", "direct_ms", V_DIRECT, "%.1f", "%.2f"), REPORT_COL("total ms", "ms", REPORT_AT_MS, "%.1f", "%.2f"),
    {.md = "rel. RMSE", .align = "---:", .csv = "rel_rmse", .at = REPORT_AT_ERROR, .md_fmt = "%.2f%%", .csv_fmt = "%.5f", .md_unit = '%'},
    REPORT_COL("reference at the same error", "reference_ms_same_error", REPORT_AT_REF_MS, "%.0f ms", "%.1f"),
    REPORT_COL("speed-up", "speedup", REPORT_AT_SPEEDUP, "%.1fx", "%.2f"), REPORT_COL_FRONT};

/* The cone-traced image for every configuration of run->args' lists. */
static int vct_sweep(report_run *run)
{
    static const voxgi_vct_radiance radiance[3] = {VOXGI_VCT_ISOTROPIC, VOXGI_VCT_ANISOTROPIC, VOXGI_VCT_OCTREE};
    const vct_report *a = (const vct_report *)run->args;
    const report_list *lists[5] = {&a->res, &a->cones, &a->apertures, &a->steps, &a->strides};
    const size_t bytes = (size_t)run->camera.width * (size_t)run->camera.height * 12;
    int at[5], f;
    for (f = 0; f < 3; f++) {
        if (!(a->filters & (1u << f))) continue;
        memset(at, 0, sizeof at);
        do {
            const double aperture = a->apertures.v[at[2]], step = a->steps.v[at[3]];
            voxgi_render_desc vd;
            voxgi_render_info vi;
            report_item it;
            double *v = it.v;
            memset(&vd, 0, sizeof vd);
            vd.method = VOXGI_RENDER_VCT;
            vd.camera = run->camera;
            vd.resolution = (int)a->res.v[at[0]];
            vd.vct.radiance = radiance[f];
            vd.vct.cones.cones = (int)a->cones.v[at[1]];
            vd.vct.cones.half_angle = (float)(aperture * acos(1 - 1.0 / vd.vct.cones.cones));
            vd.vct.cones.step = (float)step;
            vd.samples = a->direct_spp;
            vd.seed = 1;
            vd.hide_emitters = 1;
            vd.vct.cone_stride = (int)a->strides.v[at[4]];
            if (!(vd.vct.cones.half_angle < 1.5f)) continue;
            cli_status(run->s, "%s: %d^3, %d cones x %.2f, step %.2f, stride %d, %s", run->scene_name, vd.resolution, vd.vct.cones.cones, aperture, step,
                       vd.vct.cone_stride, mips_names[f]);
            if (voxgi_render(run->ctx, run->scene, &vd, run->img, bytes, &vi) != VOXGI_OK) return cli_fail_lib(run->s, run->ctx, NULL);
            memset(&it, 0, sizeof it);
            v[V_RES] = vd.resolution;
            v[V_CONES] = vd.vct.cones.cones;
            v[V_APERTURE] = aperture;
            v[V_HALF_ANGLE] = vd.vct.cones.half_angle * 180 / 3.14159265358979323846;
            v[V_STEP] = step;
            v[V_STRIDE] = vd.vct.cone_stride;
            v[V_MIPS] = f;
            v[V_VOXELS] = (double)vi.voxels;
            v[V_VOXELIZE] = voxgi_render_stage_ms(&vi, "voxelize");
            v[V_INJECT] = voxgi_render_stage_ms(&vi, "inject");
            v[V_OCTREE] = voxgi_render_stage_ms(&vi, "octree");
            v[V_CONES_MS] = voxgi_render_stage_ms(&vi, "cones");
            v[V_DIRECT] = voxgi_render_stage_ms(&vi, "direct");
            it.method = "vct";
            snprintf(it.settings, sizeof it.settings, "%d^3, %d cones (%.1f deg), step %g, stride %d, %s", vd.resolution, vd.vct.cones.cones, v[V_HALF_ANGLE],
                     step, vd.vct.cone_stride, mips_names[f]);
            report_append(it.passes, sizeof it.passes, "voxelize %.1f, inject + mips %.1f", v[V_VOXELIZE], v[V_INJECT]);
            if (f == 2) report_append(it.passes, sizeof it.passes, ", octree %.1f", v[V_OCTREE]);
            report_append(it.passes, sizeof it.passes, ", cones %.1f, direct %.1f", v[V_CONES_MS], v[V_DIRECT]);
            it.ms = vi.ms;
            it.bytes = (double)vi.bytes;
            report_measured(run, &it);
        } while (report_next(lists, 5, at));
    }
    return 0;
}

/* The one-bounce reference (seed 1000) and its convergence: a difference of two independent
   estimates, at 4, 16 and 64 spp against it, has variance c^2 (1/k + 1/spp). */
static int vct_references(report *rep, report_run *run, cli_reference *R)
{
    vct_report *a = (vct_report *)rep->own;
    const int spp = a->o.spp, pixels = run->camera.width * run->camera.height;
    voxgi_render_desc rd;
    voxgi_render_info ri;
    double c2 = 0, e;
    int k;
    if (cli_error_mask_make(run->s, run->ctx, run->scene, &run->camera, &R->mask)) return 1;
    if (R->mask.masked_pixels == (size_t)pixels)
        return cli_fail(run->s, "%s: every pixel is within %d pixels of one that sees an emitter: no error to measure", run->scene_name, CLI_EMITTER_MARGIN);
    if (!(R->image = (float *)malloc((size_t)pixels * 12))) return cli_fail(run->s, "out of memory");
    memset(&rd, 0, sizeof rd);
    rd.method = VOXGI_RENDER_REFERENCE;
    rd.camera = run->camera;
    rd.bounces = 1;
    rd.hide_emitters = 1;
    rd.samples = spp;
    rd.seed = 1000;
    cli_note(run->s, "%s: the reference, %d spp", run->scene_name, spp);
    if (voxgi_render(run->ctx, run->scene, &rd, R->image, (size_t)pixels * 12, &ri) != VOXGI_OK) return cli_fail_lib(run->s, run->ctx, NULL);
    for (k = 4; k <= 64; k *= 4) {
        rd.samples = k;
        rd.seed = 7 + (uint64_t)k;
        if (voxgi_render(run->ctx, run->scene, &rd, run->img, (size_t)pixels * 12, &ri) != VOXGI_OK) return cli_fail_lib(run->s, run->ctx, NULL);
        e = cli_masked_error(&R->mask, run->img, R->image, NULL, NULL);
        e = isfinite(e) ? e : 0;
        c2 += e * e / (1.0 / k + 1.0 / spp) / 3;
    }
    R->c = sqrt(c2);
    R->spp = spp;
    R->ms_per_spp = voxgi_render_stage_ms(&ri, "render") / 64;
    a->bvh_ms[rep->si] = voxgi_render_stage_ms(&ri, "bvh");
    a->floor[rep->si] = R->c / sqrt((double)spp);
    return 0;
}

/* A black reference measures 0; the path tracer's spp k whose image measures the same error
   against the same reference: c^2 (1/k + 1/spp) = rmse^2 (the reference's own noise in both),
   at most 1024 x its spp, its BVH included. */
static void vct_row(report *rep, report_row *r)
{
    const vct_report *a = (const vct_report *)rep->own;
    const report_scene *sc = &rep->scenes[r->scene];
    double inv, need;
    if (!isfinite(r->it.error)) r->it.error = 0;
    inv = r->it.error * r->it.error / (sc->c[0] * sc->c[0]) - 1.0 / a->o.spp;
    need = inv > 1.0 / (1024.0 * a->o.spp) ? 1 / inv : 1024.0 * a->o.spp;
    r->ref_ms = a->bvh_ms[r->scene] + sc->ms_per_spp[0] * (need > 1.0 ? need : 1.0);
}

/* The report's context for its backend, one more for the other (a GL one where it can be made). */
static int vct_open(report *rep)
{
    vct_report *a = (vct_report *)rep->own;
    const int mine = rep->ci.backend == VOXGI_BACKEND_GL, other = !mine;
    cli_common o = a->o.common;
    if (a->no_stages) return 0;
    a->stage_ctx[mine] = rep->c.vx;
    a->stage_ci[mine] = rep->ci;
    o.backend = other ? VOXGI_BACKEND_GL : VOXGI_BACKEND_CPU;
    if (cli_context_open_options(&rep->s, &a->stage_c, &o) == 0) {
        a->stage_ctx[other] = a->stage_c.vx;
        voxgi_query_info(a->stage_c.vx, &a->stage_ci[other]);
    } else if (other) {
        cli_note(&rep->s, "no GL context (%s): the stages are timed on the CPU alone", rep->s.error);
        rep->s.error[0] = 0;
    } else
        return CLI_EXIT_FAILURE;
    return 0;
}

static void vct_close(report *rep)
{
    vct_report *a = (vct_report *)rep->own;
    if (a->stage_c.vx) cli_context_close(&rep->s, &a->stage_c);
}

/* The stages on each backend, the faster of two runs (the first compiles GL's shaders): the tool's
   defaults at the report's size, the grid --stage-res. */
static int vct_scene_done(report *rep, report_run *run)
{
    vct_report *a = (vct_report *)rep->own;
    int k, n;
    for (k = 0; k < 2; k++) {
        voxgi_render_desc vd;
        if (!a->stage_ctx[k]) continue;
        cli_vct_defaults(&vd, &run->camera);
        vd.resolution = a->stage_res;
        cli_note(run->s, "%s: the defaults' stages on %s", run->scene_name, voxgi_backend_name(a->stage_ci[k].backend));
        for (n = 0; n < 2; n++) {
            voxgi_render_info ri;
            double *t = a->stages[rep->si][k];
            if (voxgi_render(a->stage_ctx[k], run->scene, &vd, run->img, (size_t)run->camera.width * (size_t)run->camera.height * 12, &ri) != VOXGI_OK)
                return cli_fail_lib(run->s, a->stage_ctx[k], NULL);
            if (n == 0 || ri.ms < t[4]) {
                t[0] = voxgi_render_stage_ms(&ri, "voxelize");
                t[1] = voxgi_render_stage_ms(&ri, "inject");
                t[2] = voxgi_render_stage_ms(&ri, "cones");
                t[3] = voxgi_render_stage_ms(&ri, "direct");
                t[4] = ri.ms;
            }
        }
    }
    return 0;
}

static void vct_md_head(FILE *md, const report *rep)
{
    const vct_report *a = (const vct_report *)rep->own;
    const voxgi_info *ci = &rep->ci;
    fprintf(md, "# Voxel cone tracing: error against run time\n\n%d x %d pixels; cone tracer on %s%s%s, %d direct-light rays per pixel; the "
                "reference is the one-bounce path tracer (CPU). Error: relative RMSE of the lighting against the converged reference "
                "over the pixels farther than %d pixels from any pixel whose centre sees an emitter, both images without the emission the "
                "camera sees. *Reference at the same error*: the time the path tracer needs for an image that "
                "measures that error against the same reference (from its measured convergence, the reference's own noise in both). Wall clock on this machine%s.\n\n",
            a->o.size[0], a->o.size[0], voxgi_backend_name(ci->backend), ci->backend == VOXGI_BACKEND_GL ? ", " : "", ci->backend == VOXGI_BACKEND_GL ? ci->gl_renderer : "",
            a->direct_spp, CLI_EMITTER_MARGIN, ci->backend == VOXGI_BACKEND_GL && ci->gl_software ? " (GL on a software rasteriser: not GPU timings)" : "");
}

static void vct_md_scene(FILE *md, const report *rep, int si, int end)
{
    const vct_report *a = (const vct_report *)rep->own;
    const report_scene *sc = &rep->scenes[si];
    if (end) fprintf(md, "\n");
    else
        fprintf(md, "## %s\n\nReference: %d spp; its error is %.2f%% / sqrt(spp) (%.3f%% at %d spp: the floor of every error below), %.2f ms per "
                    "sample per pixel. Pixels left out of the errors (near an emitter the camera sees): %lu of %d.\n\n",
                sc->name, a->o.spp, 100 * sc->c[0], 100 * a->floor[si], a->o.spp, sc->ms_per_spp[0], (unsigned long)sc->masked, a->o.size[0] * a->o.size[0]);
}

static int vct_md_end(report *rep, FILE *md, FILE *csv)
{
    static const char *const stage_names[5] = {"voxelize", "inject + mips", "cones", "direct light (CPU rays on both)", "total"};
    const vct_report *a = (const vct_report *)rep->own;
    int s, k;
    (void)csv;
    fprintf(md, "![error against time](vct.svg)\n");
    if (!a->stage_ctx[0]) return 0;
    fprintf(md, "\n## Stages: the CPU against GL\n\nThe tool's defaults (%d^3%s, anisotropic, %d cones at stride %d, %d direct-light rays per pixel) "
                "at %d x %d, each stage's time (ms) on the CPU (%d threads) and on GL (%s), the faster of two runs.%s\n\n"
                "| scene | stage | CPU | GL | CPU faster by |\n|---|---|---:|---:|---:|\n",
            a->stage_res, a->stage_res == CLI_VCT_RES ? "" : " (the tool's: 96^3)", CLI_VCT_CONES, CLI_VCT_STRIDE, CLI_VCT_DIRECT_SPP, a->o.size[0], a->o.size[0],
            a->stage_ci[0].thread_count, a->stage_ctx[1] ? a->stage_ci[1].gl_renderer : "no GL 4.5 context could be made: not timed",
            a->stage_ctx[1] && a->stage_ci[1].gl_software ? " GL runs on a software rasteriser on the same cores: these are not GPU timings." : "");
    for (s = 0; s < rep->nscenes; s++)
        for (k = 0; k < 5; k++) {
            const double cpu = a->stages[s][0][k], gl = a->stages[s][1][k];
            if (a->stage_ctx[1]) fprintf(md, "| %s | %s | %.1f | %.1f | %.1fx |\n", rep->scenes[s].name, stage_names[k], cpu, gl, cpu > 0 ? gl / cpu : 0);
            else fprintf(md, "| %s | %s | %.1f | - | - |\n", rep->scenes[s].name, stage_names[k], cpu);
        }
    return 0;
}

/* Error against time, log scales: every configuration, each scene's Pareto front joined, the reference dashed. */
static void vct_svg(FILE *f, const report *rep)
{
    const vct_report *a = (const vct_report *)rep->own;
    report_plot_point *points = (report_plot_point *)calloc(rep->nrows + 1, sizeof *points);
    char (*labels)[32] = (char (*)[32])calloc(rep->nrows + 1, sizeof *labels);
    char legend_text[REPORT_MAX_SCENES][400]; /* the scene's name (up to 287 bytes) and the text */
    const char *legend[REPORT_MAX_SCENES];
    double curve_ms[REPORT_MAX_SCENES][41], curve_error[REPORT_MAX_SCENES][41];
    report_plot_curve curves[REPORT_MAX_SCENES];
    report_plot plot;
    size_t i;
    int s, k;
    if (!points || !labels) {
        free(points);
        free(labels);
        return;
    }
    for (i = 0; i < rep->nrows; i++) {
        const report_row *r = &rep->rows[i];
        snprintf(labels[i], sizeof labels[i], "%d/%d%s", (int)r->it.v[V_RES], (int)r->it.v[V_CONES], mips_mark[(int)r->it.v[V_MIPS]]);
        points[i].ms = r->it.ms;
        points[i].error = r->it.error;
        points[i].series = r->scene;
        points[i].front = r->front;
        points[i].label = r->front ? labels[i] : NULL;
    }
    for (s = 0; s < rep->nscenes; s++) {
        const report_scene *sc = &rep->scenes[s];
        for (k = 0; k <= 40; k++) { /* the path tracer at spp k: its error c / sqrt(k) measured against the reference (with its floor), at time bvh + k x per-spp */
            double spp = pow(2, k / 2.0);
            curve_ms[s][k] = a->bvh_ms[s] + spp * sc->ms_per_spp[0];
            curve_error[s][k] = sqrt(sc->c[0] * sc->c[0] / spp + a->floor[s] * a->floor[s]);
        }
        curves[s].ms = curve_ms[s];
        curves[s].error = curve_error[s];
        curves[s].count = 41;
        curves[s].series = s;
        snprintf(legend_text[s], sizeof legend_text[s], "%s: cone tracing (filled: Pareto front, label res/cones, a = anisotropic, o = octree); dashed: the reference",
                 sc->name);
        legend[s] = legend_text[s];
    }
    memset(&plot, 0, sizeof plot);
    plot.y_title = "relative RMSE against the one-bounce reference";
    plot.x_title = "time per image (wall clock)";
    plot.legend = legend;
    plot.series_count = rep->nscenes;
    plot.points = points;
    plot.count = rep->nrows;
    plot.front_per_series = 1;
    plot.curves = curves;
    plot.curve_count = rep->nscenes;
    report_plot_svg(f, &plot);
    free(points);
    free(labels);
}

static void vct_print_scene(const report *rep, int si, int end)
{
    const vct_report *a = (const vct_report *)rep->own;
    const report_scene *sc = &rep->scenes[si];
    if (!end)
        printf("%s (reference error %.2f%% / sqrt(spp), %.2f ms per spp; floor %.3f%%; %lu of %d pixels near an emitter left out)\n", sc->name,
               100 * sc->c[0], sc->ms_per_spp[0], 100 * a->floor[si], (unsigned long)sc->masked, a->o.size[0] * a->o.size[0]);
}

static void vct_print_row(const report *rep, const report_row *r)
{
    const double *v = r->it.v;
    (void)rep;
    printf("  %4d^3 %3d cones %5.1f deg step %-4g stride %d %-5s %9.1f ms  %6.2f%%  reference %9.0f ms  %6.1fx\n", (int)v[V_RES], (int)v[V_CONES], v[V_HALF_ANGLE],
           v[V_STEP], (int)v[V_STRIDE], mips_short[(int)v[V_MIPS]], r->it.ms, 100 * r->it.error, r->ref_ms, r->ref_ms / r->it.ms);
}

static const report_def vct_def = {.name = "vct", .help = vct_help, .columns = vct_columns, .ncolumns = CLI_COUNT(vct_columns), .sweep = vct_sweep,
                                   .open = vct_open, .references = vct_references, .row = vct_row, .scene_done = vct_scene_done, .close = vct_close,
                                   .md_head = vct_md_head, .md_scene = vct_md_scene, .md_end = vct_md_end, .svg = vct_svg,
                                   .print_scene = vct_print_scene, .print_row = vct_print_row};

/* report all's cone tracing: anisotropic mips (every point of this report's fronts has them), step
   0.5, stride 6 and 24 direct-light rays (the tool's), over grids and cone counts. */
int report_vct_all(report_run *run)
{
    static const vct_report all = {.res = REPORT_L(32, 64, 96, 128), .cones = REPORT_L(8, 24), .apertures = REPORT_L(1), .steps = REPORT_L(0.5),
                                   .strides = REPORT_L(CLI_VCT_STRIDE), .filters = 2, .direct_spp = CLI_VCT_DIRECT_SPP};
    vct_report a = all;
    if (run->quick) a.res = (report_list)REPORT_L(32, 64);
    run->args = &a;
    return vct_sweep(run);
}

static int cmd_report_vct(int argc, char **argv)
{
    vct_report a = {.o = REPORT_OPTS("cornell-box,rsm-walls", 128, 1024), .res = REPORT_L(32, 64, 128), .cones = REPORT_L(8, 16, 32),
                    .apertures = REPORT_L(1), .steps = REPORT_L(0.5, 1), .strides = REPORT_L(1, 2), .filters = 3, .direct_spp = 16, .stage_res = CLI_VCT_RES};
    const cli_option options[] = {
        REPORT_OPT_SCENES(&a.o, "built-in scenes, comma-separated (default cornell-box,rsm-walls)"),
        {.name = "--cornell-mesh", .arg = "MESH", .kind = CLI_STRING, .dst = &a.o.cornell_mesh,
         .help = "also the Cornell box with MESH (a file or builtin:NAME) in place of its\n"
                 "tall block (scaled uniformly to fit inside the block's bounding box, on\n"
                 "the floor at its centre, white), named cornell-box+NAME"},
        REPORT_OPT_SIZE(&a.o, 1, "N x N pixels (default 128)"),
        REPORT_OPT_SPP(&a.o, 64, "samples per pixel of the converged reference (default 1024)"),
        {.name = "--direct-spp", .arg = "S", .kind = CLI_INT, .dst = &a.direct_spp, .lo = 1, .hi = 65536,
         .help = "the cone tracer's direct-light rays per pixel (default 16)"},
        REPORT_LIST("--res", a.res, 0, 1, 4096, 0, "voxels along the longest side (default 32,64,128)"),
        REPORT_LIST("--cones", a.cones, 0, 1, 1024, 0, "diffuse cones (default 8,16,32)"),
        REPORT_LIST("--apertures", a.apertures, 0, 1, HUGE_VAL, 0, "half-angle as a multiple of each cone count's gap-free default (default 1)"),
        REPORT_LIST("--steps", a.steps, 0.01, 0, 4, 0, "step as a fraction of the diameter, 0.01..4 (default 0.5,1)"),
        {.name = "--filters", .arg = "LIST", .kind = CLI_SET, .dst = &a.filters, .names = mips_names, .values = mips_bits,
         .help = "isotropic, anisotropic (dense mips) and/or octree (an octree of the\n"
                 "radiance, isotropic mips) (default isotropic,anisotropic)"},
        REPORT_LIST("--strides", a.strides, 0, 1, 64, 1, "cone strides: cones at every S-th pixel, the rest interpolated (default 1,2)"),
        CLI_OPT_BACKEND(&a.o.common, "where the cone tracer runs (default cpu)"),
        {.name = "--no-stages", .kind = CLI_FLAG, .dst = &a.no_stages,
         .help = "leave out the timing of the defaults' stages on the CPU and on GL"},
        {.name = "--stage-res", .arg = "N", .kind = CLI_INT, .dst = &a.stage_res, .lo = 1, .hi = 4096,
         .help = "the grid of the stages' timing (default 96, the tool's)"},
        REPORT_OPT_OUT(&a.o), CLI_OPT_THREADS(&a.o.common)};
    return report_main(&vct_def, &a.o, &a, options, CLI_COUNT(options), argc, argv);
}

/* ------------------------------------------------------------------ the reports */
static const struct {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *help;
} reports[] = {
    {"vct", cmd_report_vct, "cone tracing's error against run time (Markdown, CSV, SVG)"},
    {"tsm", cmd_report_tsm, "transmittance shadow maps' error against run time (Markdown, CSV)"},
    {"rsm", cmd_report_rsm, "reflective shadow maps' error against run time, and the voxel traversals"},
    {"sh", cmd_report_sh, "the SH volume's error against run time (Markdown, CSV)"},
    {"ao", cmd_report_ao, "ambient occlusion's error against run time, and its view-independence"},
    {"ssgi", cmd_report_ssgi, "one bounce from the screen: error against run time, a wall barely in view"},
    {"linespace", cmd_report_linespace, "the line space's soft shadows: error, run time, rays (Markdown, CSV)"},
    {"stiff", cmd_report_stiff, "every image method on stiff and extreme input against what is expected"},
    {"all", cmd_report_all, "every method's error against run time in one report"}};

int cmd_report(int argc, char **argv)
{
    char names[256] = "";
    int i, n = CLI_COUNT(reports);
    if (argc >= 1 && (strcmp(argv[0], "--help") == 0 || strcmp(argv[0], "-h") == 0)) {
        printf("usage: voxgi report NAME [options]      (voxgi report NAME --help for each)\n");
        for (i = 0; i < n; i++) printf("  %-10s %s\n", reports[i].name, reports[i].help);
        return CLI_EXIT_OK;
    }
    for (i = 0; i < n; i++)
        if (argc >= 1 && strcmp(argv[0], reports[i].name) == 0) return reports[i].run(argc - 1, argv + 1);
    for (i = 0; i < n; i++) report_append(names, sizeof names, "%s'%s'", i == 0 ? "" : i < n - 1 ? ", " : " and ", reports[i].name);
    return cli_usage("report", "the reports to make are %s", names);
}
