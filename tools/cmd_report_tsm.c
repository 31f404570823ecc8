/* tools/cmd_report_tsm.c - voxgi report tsm: transmittance shadow maps' error against run time, as Markdown and CSV. */
#include "report.h"
#include <stdlib.h>
#include <string.h>

static const char *const tsm_help =
    "usage: voxgi report tsm [options]\n"
    "Error against run time of transmittance shadow maps (voxgi render --method tsm). For each\n"
    "built-in scene it renders the reference's direct light (converged, --spp samples per pixel;\n"
    "shadow rays through translucent surfaces), then the image with maps for every combination of\n"
    "map size, slices and camera rays per pixel, and measures the relative RMSE by the tools' rule\n"
    "(render --compare's). The reference's own convergence (16 spp against the converged image)\n"
    "gives the time it needs for each error. Writes DIR/tsm.md and DIR/tsm.csv, the Pareto front\n"
    "marked. Times are wall clock on this machine.\n";

typedef struct tsm_report {
    report_opts o;
    report_list sizes, slices, samples;
} tsm_report;

/* A row's values (report_item.v). */
enum { V_SIZE, V_SLICES, V_SAMPLES, V_MAPS, V_MAPS_MS, V_SHADE_MS };

static const report_column tsm_columns[] = {
    REPORT_COL_SCENE, REPORT_COL_INT("map size", "map_size", V_SIZE), REPORT_COL_INT("slices", "slices", V_SLICES),
    REPORT_COL_INT("rays per pixel", "samples", V_SAMPLES), REPORT_COL_INT(NULL, "maps", V_MAPS),
    {.md = "map MB", .align = "---:", .csv = "map_bytes", .at = REPORT_AT_BYTES, .md_fmt = "%.1f", .csv_fmt = "%.0f", .md_unit = 'M'},
    REPORT_COL("maps ms", "maps_ms", V_MAPS_MS, "%.1f", "%.3f"), REPORT_COL("shading ms", "shade_ms", V_SHADE_MS, "%.1f", "%.3f"),
    REPORT_COL("total ms", "ms", REPORT_AT_MS, "%.1f", "%.3f"), REPORT_COL_ERROR(NULL), REPORT_COL_REF,
    {.md = "speed-up", .align = "---:", .at = REPORT_AT_SPEEDUP, .md_fmt = "%.1fx", .md_none = "-"}, REPORT_COL_FRONT};

/* The image with maps for every combination of run->args' lists. */
static int tsm_sweep(report_run *run)
{
    const tsm_report *a = (const tsm_report *)run->args;
    const report_list *lists[3] = {&a->sizes, &a->slices, &a->samples};
    int at[3] = {0, 0, 0};
    do {
        voxgi_render_desc td;
        voxgi_render_info ti;
        report_item it;
        memset(&td, 0, sizeof td);
        td.method = VOXGI_RENDER_TSM;
        td.camera = run->camera;
        td.hide_emitters = 1;
        td.seed = 1;
        td.tsm.maps.size = (int)a->sizes.v[at[0]];
        td.tsm.maps.slices = (int)a->slices.v[at[1]];
        td.samples = (int)a->samples.v[at[2]];
        cli_status(run->s, "%s: maps of %d texels, %d slices, %d rays per pixel", run->scene_name, td.tsm.maps.size, td.tsm.maps.slices, td.samples);
        if (voxgi_render(run->ctx, run->scene, &td, run->img, (size_t)td.camera.width * (size_t)td.camera.height * 12, &ti) != VOXGI_OK)
            return cli_fail_lib(run->s, run->ctx, "tsm");
        memset(&it, 0, sizeof it);
        it.method = "tsm";
        it.v[V_SIZE] = td.tsm.maps.size;
        it.v[V_SLICES] = td.tsm.maps.slices;
        it.v[V_SAMPLES] = td.samples;
        it.v[V_MAPS] = ti.maps;
        it.v[V_MAPS_MS] = voxgi_render_stage_ms(&ti, "maps");
        it.v[V_SHADE_MS] = voxgi_render_stage_ms(&ti, "shade");
        snprintf(it.settings, sizeof it.settings, "maps of %d texels, %d slices, %d rays per pixel", td.tsm.maps.size, td.tsm.maps.slices, td.samples);
        snprintf(it.passes, sizeof it.passes, "maps %.1f, shading %.1f", it.v[V_MAPS_MS], it.v[V_SHADE_MS]);
        it.ms = ti.ms;
        it.bytes = (double)ti.bytes;
        report_measured(run, &it);
    } while (report_next(lists, 3, at));
    return 0;
}

static void tsm_md_head(FILE *md, const report *rep)
{
    fprintf(md, "# Transmittance shadow maps: error against run time\n\n%d x %d pixels; direct light against the reference's (%d spp, shadow rays "
                "through translucent surfaces); CPU. Error: relative RMSE by the tools' rule (`voxgi render --compare`). *Reference at the same "
                "error*: the time the path tracer needs for an image that measures that error (from its own convergence). Wall clock on this "
                "machine.\n",
            rep->o->size[0], rep->o->size[0], rep->o->spp);
}

static void tsm_print_scene(const report *rep, int si, int end)
{
    const report_scene *sc = &rep->scenes[si];
    if (!end) printf("%s (reference error %.2f%% / sqrt(spp), %.2f ms per spp)\n", sc->name, 100 * sc->c[0], sc->ms_per_spp[0]);
}

static void tsm_print_row(const report *rep, const report_row *q)
{
    (void)rep;
    printf("  map %5d  %4d slices  %3d rays  %8.1f ms  %6.2f%%  reference %9.0f ms\n", (int)q->it.v[V_SIZE], (int)q->it.v[V_SLICES], (int)q->it.v[V_SAMPLES],
           q->it.ms, 100 * q->it.error, isfinite(q->ref_ms) ? q->ref_ms : -1.0);
}

/* report all's transmittance shadow maps: where the scene has a directional or spot light (the
   others' direct light is the exact shadow rays'). */
int report_tsm_all(report_run *run)
{
    static const tsm_report all = {.sizes = REPORT_L(256, 512, 1024), .slices = REPORT_L(16, 64), .samples = REPORT_L(4)},
                            quick = {.sizes = REPORT_L(256, 512), .slices = REPORT_L(32), .samples = REPORT_L(4)};
    size_t li;
    int maps = 0;
    for (li = 0; li < run->scene->light_count; li++)
        maps += run->scene->lights[li].type == VOXGI_LIGHT_DIRECTIONAL || run->scene->lights[li].type == VOXGI_LIGHT_SPOT;
    if (!maps) {
        snprintf(run->why, sizeof run->why, "no directional or spot light: no map to make");
        return REPORT_NOT_APPLICABLE;
    }
    run->args = run->quick ? &quick : &all;
    return tsm_sweep(run);
}

int cmd_report_tsm(int argc, char **argv)
{
    static const report_def def = {.name = "tsm", .help = tsm_help, .bounces = 0, .columns = tsm_columns, .ncolumns = CLI_COUNT(tsm_columns),
                                   .sweep = tsm_sweep, .md_head = tsm_md_head, .md_scene = report_md_scene, .print_scene = tsm_print_scene,
                                   .print_row = tsm_print_row};
    tsm_report a = {.o = REPORT_OPTS("foliage", 256, 1024), .sizes = REPORT_L(256, 512, 1024, 2048), .slices = REPORT_L(16, 32, 64, 128),
                    .samples = REPORT_L(4)};
    const cli_option options[] = {
        REPORT_OPT_SCENES(&a.o, "built-in scenes, comma-separated (default foliage)"),
        REPORT_OPT_SIZE(&a.o, 1, "N x N pixels (default 256)"),
        REPORT_OPT_SPP(&a.o, 64, "samples per pixel of the converged reference (default 1024)"),
        REPORT_LIST("--map-sizes", a.sizes, 0, 1, 16384, 1, "texels across the maps (default 256,512,1024,2048)"),
        REPORT_LIST("--slices", a.slices, 0, 1, 4096, 1, "slices along the light (default 16,32,64,128)"),
        REPORT_LIST("--samples", a.samples, 0, 1, 65536, 1, "camera rays per pixel (default 4)"),
        CLI_OPT_BACKEND(&a.o.common, "where the maps are built (default cpu)"), REPORT_OPT_OUT(&a.o), CLI_OPT_THREADS(&a.o.common)};
    return report_main(&def, &a.o, &a, options, CLI_COUNT(options), argc, argv);
}
