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

#define TSM_MAX_SCENES 8
#define TSM_MAX_LIST 16

typedef struct tsm_args {
    cli_common common;
    const char *out_dir, *scene_list;
    double sizes[TSM_MAX_LIST], slices[TSM_MAX_LIST], samples[TSM_MAX_LIST];
    int nsizes, nslices, nsamples, size, spp;
} tsm_args;

/* What an image with maps measured (voxgi_render_info's TSM stages and sizes). */
typedef struct tsm_times {
    int maps;                     /* directional and spot lights, one map each */
    size_t bytes;                 /* their memory */
    double ms_maps, ms_shade, ms; /* building the maps, shading the pixels, all */
} tsm_times;

typedef struct tsm_row {
    int scene, map_size, slices, samples, pareto;
    tsm_times info;
    double rmse, ref_ms;
} tsm_row;

typedef struct tsm_report {
    char scenes[TSM_MAX_SCENES][64];
    int scene_count, nrows;
    double ref_c[TSM_MAX_SCENES], ref_ms_per_spp[TSM_MAX_SCENES];
    size_t masked[TSM_MAX_SCENES];
    tsm_row *rows;
} tsm_report;


/* The image with maps for every combination of a's lists, of scene (seen by cam, its index si)
   against R, appended to rep's rows; with run, each also handed to report all. 0, or says why and
   returns 1. */
static int tsm_sweep(cli_session *s, voxgi_context *ctx, const tsm_args *a, const voxgi_scene *scene, const char *name, const voxgi_camera *cam,
                     const cli_reference *R, tsm_report *rep, int si, float *img, report_run *run)
{
    int i, j, k;
    for (i = 0; i < a->nsizes; i++)
        for (j = 0; j < a->nslices; j++)
            for (k = 0; k < a->nsamples; k++) {
                tsm_row *r = &rep->rows[rep->nrows];
                voxgi_render_desc td;
                voxgi_render_info ti;
                memset(&td, 0, sizeof td);
                td.method = VOXGI_RENDER_TSM;
                td.camera = *cam;
                td.hide_emitters = 1;
                td.seed = 1;
                td.tsm.maps.size = (int)a->sizes[i];
                td.tsm.maps.slices = (int)a->slices[j];
                td.samples = (int)a->samples[k];
                cli_status(s, "%s: maps of %d texels, %d slices, %d rays per pixel", name, td.tsm.maps.size, td.tsm.maps.slices, td.samples);
                if (voxgi_render(ctx, scene, &td, img, (size_t)cam->width * (size_t)cam->height * 12, &ti) != VOXGI_OK)
                    return cli_fail_lib(s, ctx, "tsm");
                r->info.maps = ti.maps;
                r->info.bytes = ti.bytes;
                r->info.ms_maps = voxgi_render_stage_ms(&ti, "maps");
                r->info.ms_shade = voxgi_render_stage_ms(&ti, "shade");
                r->info.ms = ti.ms;
                r->scene = si;
                r->map_size = td.tsm.maps.size;
                r->slices = td.tsm.maps.slices;
                r->samples = td.samples;
                r->rmse = cli_masked_error(&R->mask, img, R->image, NULL, NULL);
                r->ref_ms = cli_reference_ms(R, r->rmse);
                rep->nrows++;
                if (run) {
                    report_item it;
                    memset(&it, 0, sizeof it);
                    it.method = "tsm";
                    snprintf(it.settings, sizeof it.settings, "maps of %d texels, %d slices, %d rays per pixel", r->map_size, r->slices, r->samples);
                    snprintf(it.passes, sizeof it.passes, "maps %.1f, shading %.1f", r->info.ms_maps, r->info.ms_shade);
                    it.ms = r->info.ms;
                    it.bytes = (double)r->info.bytes;
                    it.error = r->rmse;
                    run->emit(run, &it, img);
                }
            }
    return 0;
}

static int tsm_scene(cli_session *s, voxgi_context *ctx, const tsm_args *a, tsm_report *rep, int si, float *img)
{
    voxgi_builtin_scene bs;
    voxgi_camera cam;
    cli_reference R;
    int rc = 1;
    if (voxgi_builtin_scene_create(ctx, rep->scenes[si], &bs) != VOXGI_OK) return cli_fail_lib(s, ctx, rep->scenes[si]);
    cam = bs.camera;
    cam.width = cam.height = a->size;
    if (cli_reference_make(s, ctx, &bs.scene, &cam, a->spp, 0, 0, &R) == 0) {
        rep->masked[si] = R.mask.masked_pixels;
        rep->ref_c[si] = R.c;
        rep->ref_ms_per_spp[si] = R.ms_per_spp;
        rc = tsm_sweep(s, ctx, a, &bs.scene, rep->scenes[si], &cam, &R, rep, si, img, NULL);
    }
    cli_reference_free(&R);
    voxgi_builtin_scene_destroy(ctx, &bs);
    return rc;
}

/* A row is on its scene's front when no other row is at once faster and better. */
static void tsm_pareto(tsm_report *rep) { PARETO_MARK(rep->rows, (size_t)rep->nrows, tsm_row, info.ms, rmse, scene, pareto); }

static int tsm_write(cli_session *s, const tsm_args *a, const tsm_report *rep)
{
    char path[1100];
    FILE *md, *csv;
    int si, i;
    snprintf(path, sizeof path, "%s/tsm.md", a->out_dir);
    if (!(md = fopen(path, "w"))) return cli_fail(s, "cannot write %s", path);
    snprintf(path, sizeof path, "%s/tsm.csv", a->out_dir);
    if (!(csv = fopen(path, "w"))) {
        fclose(md);
        return cli_fail(s, "cannot write %s", path);
    }
    fprintf(md, "# Transmittance shadow maps: error against run time\n\n%d x %d pixels; direct light against the reference's (%d spp, shadow rays "
                "through translucent surfaces); CPU. Error: relative RMSE by the tools' rule (`voxgi render --compare`). *Reference at the same "
                "error*: the time the path tracer needs for an image that measures that error (from its own convergence). Wall clock on this "
                "machine.\n",
            a->size, a->size, a->spp);
    fprintf(csv, "scene,map_size,slices,samples,maps,map_bytes,maps_ms,shade_ms,ms,rel_rmse,reference_ms,pareto\n");
    for (si = 0; si < rep->scene_count; si++) {
        fprintf(md, "\n## %s\n\nReference: its error is %.2f%% / sqrt(spp), %.2f ms per sample per pixel; %lu pixels near an emitter left out.\n\n",
                rep->scenes[si], 100 * rep->ref_c[si], rep->ref_ms_per_spp[si], (unsigned long)rep->masked[si]);
        fprintf(md, "| map size | slices | rays per pixel | map MB | maps ms | shading ms | total ms | rel. RMSE | reference at the same error | speed-up | "
                    "Pareto |\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|:-:|\n");
        for (i = 0; i < rep->nrows; i++) {
            const tsm_row *r = &rep->rows[i];
            if (r->scene != si) continue;
            fprintf(md, "| %d | %d | %d | %.1f | %.1f | %.1f | %.1f | %.2f%% | ", r->map_size, r->slices, r->samples, r->info.bytes / 1e6, r->info.ms_maps,
                    r->info.ms_shade, r->info.ms, 100 * r->rmse);
            if (isfinite(r->ref_ms)) fprintf(md, "%.0f ms | %.1fx | %s |\n", r->ref_ms, r->ref_ms / r->info.ms, r->pareto ? "yes" : "");
            else fprintf(md, "beyond its reference | - | %s |\n", r->pareto ? "yes" : "");
            fprintf(csv, "%s,%d,%d,%d,%d,%lu,%.3f,%.3f,%.3f,%.6g,%.6g,%d\n", rep->scenes[si], r->map_size, r->slices, r->samples, r->info.maps,
                    (unsigned long)r->info.bytes, r->info.ms_maps, r->info.ms_shade, r->info.ms, r->rmse, isfinite(r->ref_ms) ? r->ref_ms : -1.0, r->pareto);
        }
    }
    i = ferror(md) || ferror(csv);
    i |= fclose(md) != 0;
    i |= fclose(csv) != 0;
    return i ? cli_fail(s, "cannot write to %s", a->out_dir) : 0;
}

/* report all's transmittance shadow maps: where the scene has a directional or spot light (the
   others' direct light is the exact shadow rays'). */
int report_tsm_all(report_run *run)
{
    static const double sizes[] = {256, 512, 1024}, slices[] = {16, 64}, quick_sizes[] = {256, 512}, quick_slices[] = {32};
    tsm_args a;
    tsm_report rep;
    size_t li;
    int rc, maps = 0;
    for (li = 0; li < run->scene->light_count; li++)
        maps += run->scene->lights[li].type == VOXGI_LIGHT_DIRECTIONAL || run->scene->lights[li].type == VOXGI_LIGHT_SPOT;
    if (!maps) {
        snprintf(run->why, sizeof run->why, "no directional or spot light: no map to make");
        return REPORT_NOT_APPLICABLE;
    }
    memset(&a, 0, sizeof a);
    memset(&rep, 0, sizeof rep);
#define SET(field, count, from) (memcpy(a.field, from, sizeof from), a.count = CLI_COUNT(from))
    if (run->quick) SET(sizes, nsizes, quick_sizes), SET(slices, nslices, quick_slices);
    else SET(sizes, nsizes, sizes), SET(slices, nslices, slices);
#undef SET
    a.samples[0] = 4;
    a.nsamples = 1;
    if (!(rep.rows = (tsm_row *)calloc((size_t)(a.nsizes * a.nslices), sizeof *rep.rows))) return cli_fail(run->s, "out of memory");
    rc = tsm_sweep(run->s, run->ctx, &a, run->scene, run->scene_name, &run->camera, run->R, &rep, 0, run->img, run);
    free(rep.rows);
    return rc;
}

int cmd_report_tsm(int argc, char **argv)
{
    static const double sizes[] = {256, 512, 1024, 2048}, slices[] = {16, 32, 64, 128};
    tsm_args a;
    tsm_report rep;
    cli_session s;
    cli_context c;
    const char *list;
    float *img = NULL;
    int r, rc, i, si;
    memset(&a, 0, sizeof a);
    memset(&rep, 0, sizeof rep);
    a.common.backend = VOXGI_BACKEND_CPU;
    a.out_dir = "build/report";
    a.scene_list = "foliage";
    a.size = 256;
    a.spp = 1024;
    memcpy(a.sizes, sizes, sizeof sizes);
    memcpy(a.slices, slices, sizeof slices);
    a.samples[0] = 4;
    a.nsizes = a.nslices = 4;
    a.nsamples = 1;
    {
#define LIST(opt, field, count, top, text) \
    {.name = opt, .arg = "LIST", .kind = CLI_NUMBERS, .dst = a.field, .items = &a.count, .min_items = 1, .max_items = TSM_MAX_LIST, \
     .lo = 0, .lo_open = 1, .hi = top, .whole = 1, .help = text}
        const cli_option options[] = {
            {.name = "--scenes", .arg = "LIST", .kind = CLI_STRING, .dst = &a.scene_list, .help = "built-in scenes, comma-separated (default foliage)"},
            {.name = "--size", .arg = "N", .kind = CLI_INT, .dst = &a.size, .lo = 1, .hi = 4096, .help = "N x N pixels (default 256)"},
            {.name = "--spp", .arg = "S", .kind = CLI_INT, .dst = &a.spp, .lo = 64, .hi = 1 << 20,
             .help = "samples per pixel of the converged reference (default 1024)"},
            LIST("--map-sizes", sizes, nsizes, 16384, "texels across the maps (default 256,512,1024,2048)"),
            LIST("--slices", slices, nslices, 4096, "slices along the light (default 16,32,64,128)"),
            LIST("--samples", samples, nsamples, 65536, "camera rays per pixel (default 4)"),
            CLI_OPT_BACKEND(&a.common, "where the maps are built (default cpu)"),
            {.name = "--out", .arg = "DIR", .kind = CLI_STRING, .dst = &a.out_dir, .help = "where the files go (default build/report)"},
            CLI_OPT_THREADS(&a.common)};
#undef LIST
        const cli_command cmd = {.name = "report tsm", .help = tsm_help, .column = 27, .options = options, .option_count = CLI_COUNT(options)};
        if ((rc = cli_parse(&cmd, argc, argv)) != CLI_CONTINUE) return rc;
    }
    for (list = a.scene_list; (r = cli_next_item(&list, rep.scenes[rep.scene_count], sizeof rep.scenes[0])) != 0; rep.scene_count++)
        if (r < 0 || rep.scene_count == TSM_MAX_SCENES)
            return cli_usage("report", "--scenes needs 1 to %d comma-separated built-in scenes, got '%s'", TSM_MAX_SCENES, a.scene_list);
    cli_session_init(&s, "report");
    if (cli_context_open_options(&s, &c, &a.common)) return CLI_EXIT_FAILURE;
    rc = CLI_EXIT_FAILURE;
    rep.rows = (tsm_row *)calloc((size_t)rep.scene_count * (size_t)(a.nsizes * a.nslices * a.nsamples), sizeof *rep.rows);
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
        if (tsm_scene(&s, c.vx, &a, &rep, si, img)) goto done;
    tsm_pareto(&rep);
    if (tsm_write(&s, &a, &rep)) goto done;
    cli_status_clear(&s);
    for (si = 0; si < rep.scene_count; si++) { /* the front on stdout */
        printf("%s (reference error %.2f%% / sqrt(spp), %.2f ms per spp)\n", rep.scenes[si], 100 * rep.ref_c[si], rep.ref_ms_per_spp[si]);
        for (i = 0; i < rep.nrows; i++) {
            const tsm_row *q = &rep.rows[i];
            if (q->scene == si && q->pareto)
                printf("  map %5d  %4d slices  %3d rays  %8.1f ms  %6.2f%%  reference %9.0f ms\n", q->map_size, q->slices, q->samples, q->info.ms, 100 * q->rmse,
                       isfinite(q->ref_ms) ? q->ref_ms : -1.0);
        }
    }
    printf("wrote %s/tsm.md, %s/tsm.csv\n", a.out_dir, a.out_dir);
    rc = CLI_EXIT_OK;
done:
    free(rep.rows);
    free(img);
    cli_context_close(&s, &c);
    return rc;
}
