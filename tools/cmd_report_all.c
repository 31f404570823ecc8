/* tools/cmd_report_all.c - voxgi report all: every method's error against its run time, on the same
 * scenes and against the same references, in one report: DIR/report.md (a summary of the fastest
 * method reaching each error first), DIR/report.csv, a plot per scene and quantity with the
 * Pareto front across the methods, and a picture per scene and method. Each method's sweep is
 * its own report's (tools/report.h). */
#include "report.h"
#include <stdlib.h>
#include <string.h>

static const char *const all_help =
    "usage: voxgi report all [options]\n"
    "Every method's error against its run time, in one report. For each built-in scene (and the\n"
    "Cornell box with each mesh of --meshes in place of its tall block) it renders the path\n"
    "tracer's references on the CPU (direct light and one bounce; direct light; ambient occlusion\n"
    "within 0.1 of the scene's longest side), then runs each method's sweep, as its own report\n"
    "has it (voxgi report vct|rsm|sh|ssgi|tsm|linespace|ao --help), over a few settings: cone\n"
    "tracing, reflective shadow maps and the SH volume, SSGI and Hybrid-GI (one bounce);\n"
    "transmittance shadow maps and the line space (direct light); SSAO and voxel AO (ambient\n"
    "occlusion); and the surface voxelizers' sets against the exact conservative set (missed and\n"
    "extra voxels). Each image is measured against the reference of what it computes, by the\n"
    "tools' rule (render --compare's: the relative RMSE over the pixels farther than 3 pixels from\n"
    "one that sees an emitter, both images without the emission the camera sees). Writes\n"
    "DIR/report.md (the fastest method reaching each of a few errors first; the cone tracer's\n"
    "light-only update of a static scene against its full image; per scene and quantity a table\n"
    "with each pass's time and the memory; the stiff and extreme cases of 'voxgi report stiff'),\n"
    "DIR/report.csv, DIR/SCENE-QUANTITY.svg\n"
    "(error against time, log scales, the Pareto front across the methods, the path tracer's own\n"
    "curve dashed) and DIR/SCENE-METHOD.png (each method's closest image, the reference and the\n"
    "error's heat map). Progress on stderr. Times are wall clock on this machine; GL on a software\n"
    "rasteriser (llvmpipe) is labelled: not GPU timings.\n";

#define ALL_MAX_SCENES 16
#define ALL_MAX_PICTURES 16 /* series per scene */
#define ALL_MAX_NOTES 8

typedef struct all_args {
    cli_common common;
    const char *out_dir, *scene_list, *mesh_list;
    int size, spp, quick;
} all_args;

/* The methods in the report's order, each sweep in its own report's file. */
typedef struct all_method {
    const char *name;
    int quantity;
    int (*sweep)(report_run *run);
} all_method;
static const all_method all_methods[] = {
    {"vct", REPORT_BOUNCE, report_vct_all},       {"rsm", REPORT_BOUNCE, report_rsm_all},
    {"sh", REPORT_BOUNCE, report_sh_all},         {"ssgi, hybrid, hybrid+light", REPORT_BOUNCE, report_ssgi_all},
    {"tsm", REPORT_DIRECT, report_tsm_all},       {"linespace", REPORT_DIRECT, report_linespace_all},
    {"ssao, vao", REPORT_AO, report_ao_all},      {"voxelizers", REPORT_VOXELS, report_voxels_all}};

/* What each quantity is measured against, and the errors the summary looks for. */
typedef struct all_quantity {
    const char *key, *title, *methods, *reference;
    double targets[4];
    int ntargets;
} all_quantity;
static const all_quantity quantities[REPORT_QUANTITIES] = {
    {"bounce", "direct light and one bounce", "vct, rsm, sh, ssgi, hybrid, hybrid+light",
     "the path tracer's direct light and one bounce (`voxgi render --bounces 1`); every method adds the same exact direct light by shadow rays "
     "to its own bounce (the screen methods cannot see light from surfaces off screen)",
     {0.4, 0.2, 0.1, 0.05}, 4},
    {"direct", "direct light", "tsm, linespace-exact, linespace-fast",
     "the path tracer's direct light (`--bounces 0`); tsm maps directional and spot lights only (the rest by exact shadow rays), the line "
     "space shadows area lights only: each appears where its lights are the scene's",
     {0.2, 0.1, 0.05, 0.02}, 4},
    {"ao", "ambient occlusion", "ssao, ssao-points, vao",
     "the path tracer's ambient occlusion within 0.1 of the scene's longest side (`--ao-radius`): occlusion, not light; its error is "
     "relative to the mean occlusion, which is small",
     {1, 0.5, 0.3}, 3},
    {"voxels", "voxel sets", "conservative, thin, slicemap, atlas, atlas-compute, geometry, volume-buffer (on GL also slicemap-atomic, "
     "volume-buffer-m1)",
     "the exact conservative voxelization on the CPU on the same grid, N^3 fitted around the scene: error = (missed + extra voxels) / its voxels. "
     "Not light, and each method has its own definition: thin is 6-separating (a subset by design), the raster methods sample",
     {0, 0.05, 0.25}, 3}};

/* A method's closest image of a scene, and where it went. */
typedef struct all_picture {
    const char *method;
    int quantity;
    double error;
    char settings[160], file[400];
    float *img;
} all_picture;

typedef struct all_scene {
    char name[300];
    size_t masked;                       /* pixels left out near an emitter */
    int have[REPORT_AO + 1];             /* the references made */
    double c[REPORT_AO + 1], ms_per_spp[REPORT_AO + 1];
    char notes[ALL_MAX_NOTES][320];      /* the methods left out, and why */
    int nnotes;
    all_picture pictures[ALL_MAX_PICTURES];
    int npictures;
    double update_ms[3];                 /* the cone tracer's image making all; re-injecting into kept voxels with a kept BVH; the two made alone */
    int have_update;
} all_scene;

typedef struct all_state {
    cli_session *s;
    const all_args *a;
    voxgi_info ci;           /* the passes' context */
    all_scene scenes[ALL_MAX_SCENES];
    int nscenes, quantity, stage, stages, discard, out_of_memory;
    report_stiff stiff;      /* the stiff and extreme cases' section */
    report_row *rows;
    size_t nrows, cap;
    size_t pixels;
} all_state;

/* ------------------------------------------------------------------ measuring */
/* Each configuration a sweep measured: a row, and the image when it is its method's closest yet. */
static void all_emit(report_run *run, const report_item *it, const float *img)
{
    all_state *st = (all_state *)run->user;
    all_scene *sc = &st->scenes[st->nscenes];
    report_row *r;
    int k;
    if (st->discard || it->note[0]) return;
    if (!(r = report_row_add(&st->rows, &st->nrows, &st->cap))) {
        st->out_of_memory = 1;
        return;
    }
    r->scene = st->nscenes;
    r->quantity = st->quantity;
    r->group = st->nscenes * REPORT_QUANTITIES + st->quantity;
    r->it = *it;
    r->ref_ms = run->R ? cli_reference_ms(run->R, it->error) : NAN;
    if (!img || !isfinite(it->error)) return;
    for (k = 0; k < sc->npictures && strcmp(sc->pictures[k].method, it->method) != 0; k++) {}
    if (k == ALL_MAX_PICTURES) return;
    if (k == sc->npictures) {
        if (!(sc->pictures[k].img = (float *)malloc(st->pixels * 12))) {
            st->out_of_memory = 1;
            return;
        }
        sc->pictures[k].method = it->method;
        sc->pictures[k].quantity = st->quantity;
        sc->pictures[k].error = HUGE_VAL;
        sc->npictures++;
    }
    if (it->error < sc->pictures[k].error) {
        sc->pictures[k].error = it->error;
        snprintf(sc->pictures[k].settings, sizeof sc->pictures[k].settings, "%s", it->settings);
        memcpy(sc->pictures[k].img, img, st->pixels * 12);
    }
}

/* A name fit for a file: letters, digits and . _ + - kept, the rest '_'. */
static void file_name(char *out, size_t size, const char *a, const char *b, const char *ext)
{
    size_t i;
    snprintf(out, size, "%s-%s.%s", a, b, ext);
    for (i = 0; out[i]; i++)
        if (!((out[i] >= 'a' && out[i] <= 'z') || (out[i] >= 'A' && out[i] <= 'Z') || (out[i] >= '0' && out[i] <= '9') || strchr("._+-", out[i]))) out[i] = '_';
}

/* The stage and the fraction done, before every progress line; a line of its own when stderr is
   not a terminal. */
static void all_stage(all_state *st, const char *what)
{
    if (st->discard) return;
    st->stage++;
    snprintf(st->s->prefix, sizeof st->s->prefix, "[%d/%d %3.0f%%] ", st->stage, st->stages, 100.0 * (st->stage - 1) / st->stages);
    if (st->s->interactive) cli_status(st->s, "%s", what);
    else cli_note(st->s, "%s%s", st->s->prefix, what);
}

/* A static scene's light-only update against the full image: the cone tracer at the tool's
   defaults (96^3, 24 cones, stride 6, anisotropic) making its voxels and BVH per image, and
   re-injecting the light into voxels kept from voxgi_render_voxelize with the BVH kept from
   voxgi_ray_scene_create; the faster of two runs each. */
static int all_light_update(all_state *st, voxgi_context *ctx, const voxgi_scene *scene, const voxgi_camera *view, all_scene *sc)
{
    voxgi_render_desc d;
    voxgi_render_info vi;
    voxgi_voxels *vox = NULL;
    voxgi_ray_scene *rays = NULL;
    const size_t pixels = (size_t)view->width * (size_t)view->height;
    float *img = (float *)malloc(pixels * 12);
    double t0;
    int k, run;
    if (!img) return cli_fail(st->s, "out of memory");
    memset(&d, 0, sizeof d);
    d.method = VOXGI_RENDER_VCT;
    d.camera = *view;
    d.resolution = 96;
    d.vct.cones.cones = 24;
    d.vct.cone_stride = 6;
    d.vct.radiance = VOXGI_VCT_ANISOTROPIC;
    d.samples = 16; /* the old zero's: the cone tracer's direct-light rays (the default is now 24) */
    d.hide_emitters = 1;
    t0 = cli_now_ms();
    if (voxgi_render_voxelize(ctx, scene, &d, &vox) != VOXGI_OK || voxgi_ray_scene_create(ctx, scene, &rays) != VOXGI_OK) {
        voxgi_voxels_destroy(ctx, vox);
        free(img);
        return cli_fail_lib(st->s, ctx, "vct voxels and rays");
    }
    sc->update_ms[2] = cli_now_ms() - t0;
    sc->update_ms[0] = sc->update_ms[1] = HUGE_VAL;
    for (run = 0; run < 2; run++)
        for (k = 0; k < 2; k++) {
            d.voxels = k ? vox : NULL;
            d.rays = k ? rays : NULL;
            if (voxgi_render(ctx, scene, &d, img, pixels * 12, &vi) != VOXGI_OK) {
                voxgi_voxels_destroy(ctx, vox);
                voxgi_ray_scene_destroy(ctx, rays);
                free(img);
                return cli_fail_lib(st->s, ctx, "vct image");
            }
            if (vi.ms < sc->update_ms[k]) sc->update_ms[k] = vi.ms;
        }
    voxgi_voxels_destroy(ctx, vox);
    voxgi_ray_scene_destroy(ctx, rays);
    free(img);
    sc->have_update = 1;
    return 0;
}

/* One scene (view: its camera at the report's size): the references, every method's sweep, the
   pictures. With st->discard (GL's shaders compiled before anything is timed) nothing is kept. */
static int all_one_scene(all_state *st, voxgi_context *ctx, voxgi_context *cpu, const char *name, const voxgi_scene *scene, const voxgi_camera *view,
                         int spp, int quick)
{
    all_scene *sc = &st->scenes[st->nscenes];
    cli_reference R[REPORT_AO + 1];
    report_run run;
    char what[400];
    const size_t pixels = (size_t)view->width * (size_t)view->height;
    size_t m;
    int q, k, rc = 0;
    memset(R, 0, sizeof R);
    memset(sc, 0, sizeof *sc);
    snprintf(sc->name, sizeof sc->name, "%s", name);
    memset(&run, 0, sizeof run);
    run.s = st->s;
    run.ctx = ctx;
    run.cpu = cpu;
    run.scene = scene;
    run.scene_name = sc->name;
    run.camera = *view;
    run.quick = quick;
    run.emit = all_emit;
    run.user = st;
    st->pixels = pixels;
    if (!(run.img = (float *)malloc(pixels * 12))) return cli_fail(st->s, "out of memory");
    for (m = 0; m < (size_t)CLI_COUNT(all_methods) && rc == 0; m++) {
        q = all_methods[m].quantity;
        if (q != REPORT_VOXELS && !sc->have[q]) { /* the quantity's reference, made when a method first needs it */
            snprintf(what, sizeof what, "%s: the reference of the %s, %d spp", name, quantities[q].title, spp);
            all_stage(st, what);
            if (cli_reference_make(st->s, cpu, scene, view, spp, q == REPORT_BOUNCE, q == REPORT_AO ? REPORT_AO_RADIUS * cli_scene_longest_side(scene) : 0,
                                   &R[q])) {
                rc = CLI_EXIT_FAILURE;
                break;
            }
            sc->have[q] = 1;
            sc->c[q] = R[q].c;
            sc->ms_per_spp[q] = R[q].ms_per_spp;
            sc->masked = R[q].mask.masked_pixels;
        }
        snprintf(what, sizeof what, "%s: %s", name, all_methods[m].name);
        all_stage(st, what);
        st->quantity = q;
        run.R = q == REPORT_VOXELS ? NULL : &R[q];
        run.why[0] = 0;
        rc = all_methods[m].sweep(&run);
        if (rc == REPORT_NOT_APPLICABLE) {
            if (sc->nnotes < ALL_MAX_NOTES) snprintf(sc->notes[sc->nnotes++], sizeof sc->notes[0], "%s: %s", all_methods[m].name, run.why);
            rc = 0;
        }
        if (st->out_of_memory) rc = cli_fail(st->s, "out of memory");
    }
    if (rc == 0 && !st->discard) {
        snprintf(what, sizeof what, "%s: a light-only update", name);
        all_stage(st, what);
        rc = all_light_update(st, ctx, scene, view, sc);
    }
    for (k = 0; k < sc->npictures && rc == 0 && !st->discard; k++) { /* the pictures, while the references are here */
        all_picture *p = &sc->pictures[k];
        char path[1400];
        file_name(p->file, sizeof p->file, name, p->method, "png");
        snprintf(path, sizeof path, "%s/%s", st->a->out_dir, p->file);
        if (report_png_compare(path, p->img, R[p->quantity].image, &R[p->quantity].mask, report_exposure(R[p->quantity].image, &R[p->quantity].mask), p->method) != 0)
            rc = cli_fail(st->s, "cannot write %s: %s", path, cli_io_why(errno));
    }
    for (k = 0; k < sc->npictures; k++) {
        free(sc->pictures[k].img);
        sc->pictures[k].img = NULL;
    }
    for (q = 0; q <= REPORT_AO; q++) cli_reference_free(&R[q]);
    free(run.img);
    return rc;
}

/* ------------------------------------------------------------------ writing */
/* A CSV field: quoted when it holds a comma or a quote. */
static void csv_field(FILE *f, const char *v)
{
    if (!strpbrk(v, ",\"\n")) {
        fputs(v, f);
        return;
    }
    fputc('"', f);
    for (; *v; v++) {
        if (*v == '"') fputc('"', f);
        fputc(*v, f);
    }
    fputc('"', f);
}

static void write_csv(FILE *f, const all_state *st)
{
    size_t i;
    fprintf(f, "scene,quantity,method,settings,backend,ms,passes_ms,bytes,rel_error,detail,reference_ms,pareto\n");
    for (i = 0; i < st->nrows; i++) {
        const report_row *r = &st->rows[i];
        csv_field(f, st->scenes[r->scene].name);
        fprintf(f, ",%s,%s,", quantities[r->quantity].key, r->it.method);
        csv_field(f, r->it.settings);
        fprintf(f, ",%s,%.6f,", voxgi_backend_name(st->ci.backend), r->it.ms);
        csv_field(f, r->it.passes);
        fprintf(f, ",%.0f,%.9g,", r->it.bytes, r->it.error);
        csv_field(f, r->it.detail);
        fprintf(f, ",%.1f,%d\n", isfinite(r->ref_ms) ? r->ref_ms : -1.0, r->front);
    }
}

/* "12.3 ms", "1.23 s" */
static void put_time(FILE *f, double ms)
{
    if (!isfinite(ms)) fprintf(f, "beyond its reference");
    else if (ms < 1000) fprintf(f, "%.1f ms", ms);
    else fprintf(f, "%.2f s", ms / 1000);
}

/* The summary: per scene and quantity, for each target error the fastest row reaching it (on the
   front; targets with the same answer on one line), and the path tracer's time for that error. */
static void write_summary(FILE *f, const all_state *st, const pareto_point *pts)
{
    int si, q, t, u;
    fprintf(f, "| scene | measured against | error at most | fastest | settings | time | its error | path tracer at that error |\n"
               "|---|---|---:|---|---|---:|---:|---:|\n");
    for (si = 0; si < st->nscenes; si++)
        for (q = 0; q < REPORT_QUANTITIES; q++) {
            const all_scene *sc = &st->scenes[si];
            const int g = si * REPORT_QUANTITIES + q;
            size_t i;
            int any = 0;
            for (i = 0; i < st->nrows && !any; i++) any = st->rows[i].group == g;
            for (t = 0; any && t < quantities[q].ntargets; t = u) {
                const long b = pareto_fastest(pts, st->nrows, g, quantities[q].targets[t]);
                for (u = t + 1; u < quantities[q].ntargets && pareto_fastest(pts, st->nrows, g, quantities[q].targets[u]) == b; u++) {}
                fprintf(f, "| %s | %s | ", sc->name, quantities[q].title);
                for (i = (size_t)t; i < (size_t)u; i++) {
                    if (quantities[q].targets[i] > 0) fprintf(f, "%s%g%%", i > (size_t)t ? ", " : "", 100 * quantities[q].targets[i]);
                    else fprintf(f, "%s0 (exact)", i > (size_t)t ? ", " : "");
                }
                if (b < 0) fprintf(f, " | none reaches it | | | | ");
                else {
                    const report_row *r = &st->rows[b];
                    fprintf(f, " | %s | %s | ", r->it.method, r->it.settings);
                    put_time(f, r->it.ms);
                    fprintf(f, " | ");
                    report_percent(f, r->it.error, "");
                    fprintf(f, " | ");
                }
                for (i = (size_t)t; i < (size_t)u && q != REPORT_VOXELS; i++) { /* c^2 (1/k + 1/spp) = target^2 */
                    cli_reference R;
                    memset(&R, 0, sizeof R);
                    R.c = sc->c[q];
                    R.ms_per_spp = sc->ms_per_spp[q];
                    R.spp = st->a->spp;
                    if (i > (size_t)t) fprintf(f, ", ");
                    put_time(f, cli_reference_ms(&R, quantities[q].targets[i]));
                }
                fprintf(f, "%s |\n", q == REPORT_VOXELS ? "-" : "");
            }
        }
}

static void write_markdown(FILE *f, const all_state *st, const pareto_point *pts)
{
    const all_args *a = st->a;
    const voxgi_info *ci = &st->ci;
    int si, q, k;
    size_t i;
    fprintf(f, "# Every method: error against run time\n\n");
    fprintf(f, "%d x %d pixels%s. References: voxgi's path tracer on the CPU, %d samples per pixel. The methods on %s%s%s%s, %d CPU threads. "
               "Times are wall clock on this machine, one run each: other work on the machine slows them, so compare them within one run. "
               "Error: the relative RMSE by the tools' rule (`voxgi render --compare`): the RMS difference over pixels and channels over the "
               "reference's mean, over the pixels farther than %d pixels from any pixel whose centre sees an emitter, both images without the "
               "emission the camera sees. *Path tracer at that error*: the time voxgi's path tracer needs for an image that measures that error "
               "against the same reference (from its own convergence: c / sqrt(spp), the reference's own noise in both). *Memory*: what the "
               "method builds from the scene (maps, voxels and their mipmaps, volumes, trees), not its image buffers.\n\n",
            a->size, a->size, a->quick ? " (`--quick`: few settings, a small image and a noisy reference)" : "", a->spp, voxgi_backend_name(ci->backend),
            ci->backend == VOXGI_BACKEND_GL ? " (" : "", ci->backend == VOXGI_BACKEND_GL ? ci->gl_renderer : "", ci->backend == VOXGI_BACKEND_GL
                ? (ci->gl_software ? "; a software rasteriser on the CPU's cores: not GPU timings)" : ")") : "",
            ci->thread_count, CLI_EMITTER_MARGIN);
    fprintf(f, "## The fastest method reaching each error\n\nPer scene and quantity, the fastest configuration of any method whose error is at "
               "most the target (it is on the Pareto front across the methods).\n\n");
    write_summary(f, st, pts);
    fprintf(f, "\n## Static scenes: a light-only update\n\nWhere the geometry stands still the cone tracer's voxels and its shadow rays' BVH are "
               "made once (`voxgi_render_voxelize`, `voxgi_ray_scene_create`) and each image re-injects the light into them (`voxgi_render_desc.voxels`, "
               "`.rays`): the same image, bit for bit. The tool's defaults (96^3, 24 cones, stride 6, anisotropic), the faster of two runs each."
               "\n\n| scene | image, making both | image, both kept | saved | voxels and BVH made alone |\n|---|---:|---:|---:|---:|\n");
    for (si = 0; si < st->nscenes; si++) {
        const all_scene *sc = &st->scenes[si];
        if (!sc->have_update) continue;
        fprintf(f, "| %s | %.1f ms | %.1f ms | %.0f%% | %.1f ms |\n", sc->name, sc->update_ms[0], sc->update_ms[1],
                100 * (1 - sc->update_ms[1] / sc->update_ms[0]), sc->update_ms[2]);
    }
    fprintf(f, "\n## What each row is measured against\n\nErrors of different quantities are not comparable: each scene has a plot and a "
               "front per quantity.\n\n| quantity | methods | reference |\n|---|---|---|\n");
    for (q = 0; q < REPORT_QUANTITIES; q++) fprintf(f, "| %s | %s | %s |\n", quantities[q].title, quantities[q].methods, quantities[q].reference);
    for (si = 0; si < st->nscenes; si++) {
        const all_scene *sc = &st->scenes[si];
        fprintf(f, "\n## %s\n\n%lu of %d pixels near an emitter left out of the image errors. References' own error: ", sc->name, (unsigned long)sc->masked,
                a->size * a->size);
        for (q = k = 0; q <= REPORT_AO; q++)
            if (sc->have[q]) fprintf(f, "%s%s %.1f%% / sqrt(spp) at %.2f ms per sample per pixel", k++ ? "; " : "", quantities[q].title, 100 * sc->c[q], sc->ms_per_spp[q]);
        fprintf(f, ".\n");
        for (k = 0; k < sc->nnotes; k++) fprintf(f, "%sNot here: %s", k ? "; " : "\n", sc->notes[k]);
        if (sc->nnotes) fprintf(f, ".\n");
        for (q = 0; q < REPORT_QUANTITIES; q++) {
            char svg[400];
            int any = 0;
            for (i = 0; i < st->nrows && !any; i++) any = st->rows[i].group == si * REPORT_QUANTITIES + q;
            if (!any) continue;
            file_name(svg, sizeof svg, sc->name, quantities[q].key, "svg");
            fprintf(f, "\n### %s: %s\n\nAgainst %s.\n\n![%s, %s: error against time](%s)\n\n| method | settings | time | passes (ms) | memory MB | %s | "
                       "path tracer at that error | front |\n|---|---|---:|---|---:|---:|---:|:-:|\n",
                    sc->name, quantities[q].title, quantities[q].reference, sc->name, quantities[q].key, svg,
                    q == REPORT_VOXELS ? "missed + extra" : "rel. RMSE");
            for (i = 0; i < st->nrows; i++) {
                const report_row *r = &st->rows[i];
                if (r->group != si * REPORT_QUANTITIES + q) continue;
                fprintf(f, "| %s | %s | %.1f ms | %s | %.3g | ", r->it.method, r->it.settings, r->it.ms, r->it.passes, r->it.bytes / 1e6);
                report_percent(f, r->it.error, "");
                if (r->it.detail[0]) fprintf(f, " (%s)", r->it.detail);
                fprintf(f, " | ");
                if (q == REPORT_VOXELS) fprintf(f, "-");
                else put_time(f, r->ref_ms);
                fprintf(f, " | %s |\n", r->front ? "yes" : "");
            }
            for (k = 0; k < sc->npictures; k++)
                if (sc->pictures[k].quantity == q) {
                    if (k == 0 || sc->pictures[k - 1].quantity != q)
                        fprintf(f, "\nEach method's closest image: the method, the reference, the error (per pixel the RMS difference over the reference's "
                                   "mean: black 0, red, yellow, white %g%% and above; grey: left out near an emitter).\n\n",
                                100 * REPORT_HEAT_WHITE);
                    fprintf(f, "- %s (%s): ", sc->pictures[k].method, sc->pictures[k].settings);
                    report_percent(f, sc->pictures[k].error, "");
                    fprintf(f, "\n\n  ![%s, %s](%s)\n", sc->name, sc->pictures[k].method, sc->pictures[k].file);
                }
        }
    }
    if (st->stiff.measured) {
        fprintf(f, "\n## Stiff and extreme input\n\n");
        report_stiff_markdown(f, &st->stiff, ci);
    }
}

/* The plot of scene si's quantity q: its methods in the order they came, the front across them,
   the path tracer's curve. */
static void write_svg(FILE *f, const all_state *st, int si, int q)
{
    const all_scene *sc = &st->scenes[si];
    report_plot_point *points = (report_plot_point *)calloc(st->nrows + 1, sizeof *points);
    const char *legend[ALL_MAX_PICTURES + 2];
    char titles[2][400];
    double curve_ms[40], curve_error[40];
    report_plot_curve curve;
    report_plot plot;
    size_t i, n = 0;
    int k, series = 0;
    if (!points) return;
    for (i = 0; i < st->nrows; i++) {
        const report_row *r = &st->rows[i];
        if (r->group != si * REPORT_QUANTITIES + q) continue;
        for (k = 0; k < series && strcmp(legend[k], r->it.method) != 0; k++) {}
        if (k == series && series < ALL_MAX_PICTURES) legend[series++] = r->it.method;
        points[n].ms = r->it.ms;
        points[n].error = r->it.error;
        points[n].series = k;
        points[n].front = r->front;
        points[n].label = r->front ? r->it.method : NULL;
        n++;
    }
    memset(&plot, 0, sizeof plot);
    if (q != REPORT_VOXELS) { /* k spp of the path tracer: c sqrt(1/k + 1/spp) against the reference, k times the time per spp */
        for (k = 0; k < 40; k++) {
            double spp = pow(2, k / 2.0);
            curve_ms[k] = spp * sc->ms_per_spp[q];
            curve_error[k] = sc->c[q] * sqrt(1 / spp + 1.0 / st->a->spp);
        }
        curve.ms = curve_ms;
        curve.error = curve_error;
        curve.count = 40;
        curve.series = series;
        legend[series++] = "voxgi's path tracer (dashed: its error against its time)";
        plot.curves = &curve;
        plot.curve_count = 1;
    }
    snprintf(titles[0], sizeof titles[0], "%s: %s against %s", sc->name, q == REPORT_VOXELS ? "(missed + extra) / exact" : "relative RMSE",
             q == REPORT_VOXELS ? "the exact conservative set" : q == REPORT_BOUNCE ? "one bounce" : q == REPORT_DIRECT ? "the direct light" : "the AO");
    snprintf(titles[1], sizeof titles[1], "time (wall clock, %s%s; filled: the Pareto front across the methods)", voxgi_backend_name(st->ci.backend),
             st->ci.backend == VOXGI_BACKEND_GL && st->ci.gl_software ? " on llvmpipe: not GPU timings" : "");
    plot.y_title = titles[0];
    plot.x_title = titles[1];
    plot.legend = legend;
    plot.series_count = series;
    plot.points = points;
    plot.count = n;
    report_plot_svg(f, &plot);
    free(points);
}

static int write_files(all_state *st, const pareto_point *pts)
{
    char path[1400];
    FILE *f;
    int si, q, bad = 0;
    size_t i;
    snprintf(path, sizeof path, "%s/report.csv", st->a->out_dir);
    if (!(f = fopen(path, "w"))) return cli_fail(st->s, "cannot write %s: %s", path, cli_io_why(errno));
    write_csv(f, st);
    bad |= ferror(f) | (fclose(f) != 0);
    snprintf(path, sizeof path, "%s/report.md", st->a->out_dir);
    if (bad || !(f = fopen(path, "w"))) return cli_fail(st->s, "cannot write %s: %s", path, cli_io_why(errno));
    write_markdown(f, st, pts);
    bad |= ferror(f) | (fclose(f) != 0);
    for (si = 0; si < st->nscenes && !bad; si++)
        for (q = 0; q < REPORT_QUANTITIES && !bad; q++) {
            char name[400];
            int any = 0;
            for (i = 0; i < st->nrows && !any; i++) any = st->rows[i].group == si * REPORT_QUANTITIES + q;
            if (!any) continue;
            file_name(name, sizeof name, st->scenes[si].name, quantities[q].key, "svg");
            snprintf(path, sizeof path, "%s/%s", st->a->out_dir, name);
            if (!(f = fopen(path, "w"))) return cli_fail(st->s, "cannot write %s: %s", path, cli_io_why(errno));
            write_svg(f, st, si, q);
            bad |= ferror(f) | (fclose(f) != 0);
        }
    return bad ? cli_fail(st->s, "cannot write %s: %s", path, cli_io_why(errno)) : 0;
}

/* ------------------------------------------------------------------ the command */
static int all_run(cli_session *s, const all_args *a, const char names[][256], int nbuiltin, int nmeshes)
{
    all_state *st = (all_state *)calloc(1, sizeof *st);
    cli_context c, cpu;
    cli_cornell_mesh *cm = NULL;
    pareto_point *pts = NULL;
    size_t i;
    int si, rc = CLI_EXIT_FAILURE;
    memset(&c, 0, sizeof c);
    memset(&cpu, 0, sizeof cpu);
    if (!st) return cli_fail(s, "out of memory");
    st->s = s;
    st->a = a;
    st->stages = (nbuiltin + nmeshes) * (CLI_COUNT(all_methods) + 4) + 1;
    if (cli_context_open(s, &cpu, VOXGI_BACKEND_CPU, VXT_GL_AUTO, a->common.threads, 0) || cli_context_open(s, &c, (voxgi_backend)a->common.backend, VXT_GL_AUTO, a->common.threads, 0))
        goto done;
    voxgi_query_info(c.vx, &st->ci);
    if (!(cm = (cli_cornell_mesh *)calloc((size_t)nmeshes + 1, sizeof *cm))) {
        cli_fail(s, "out of memory");
        goto done;
    }
    for (si = 0; si < nmeshes; si++) /* first: a bad mesh fails before any rendering */
        if (cli_cornell_mesh_open(s, cpu.vx, names[nbuiltin + si], &cm[si])) goto done;
    if (cli_make_dirs(a->out_dir) != 0) {
        cli_fail(s, "cannot make %s", a->out_dir);
        goto done;
    }
    for (si = 0; si < nbuiltin + nmeshes; si++) {
        const char *name = si < nbuiltin ? names[si] : cm[si - nbuiltin].name;
        voxgi_builtin_scene bs;
        const voxgi_scene *scene;
        voxgi_camera view, warm;
        int r = 0;
        if (report_scene_open(s, cpu.vx, names[si], si < nbuiltin ? NULL : &cm[si - nbuiltin], &bs, &scene, &view, a->size, a->size)) goto done;
        if (st->ci.backend == VOXGI_BACKEND_GL) { /* every method once at 8 x 8 first: no time includes compiling GL's shaders */
            warm = view;
            warm.width = warm.height = 8;
            st->discard = 1;
            cli_status(s, "%s: GL's shaders", name);
            r = all_one_scene(st, c.vx, cpu.vx, "warm-up", scene, &warm, 16, 1);
            st->discard = 0;
        }
        if (r == 0) r = all_one_scene(st, c.vx, cpu.vx, name, scene, &view, a->spp, a->quick);
        voxgi_builtin_scene_destroy(cpu.vx, &bs);
        if (r) goto done;
        st->nscenes++;
    }
    all_stage(st, "stiff and extreme input");
    if (report_stiff_measure(s, c.vx, &st->stiff)) goto done;
    s->prefix[0] = 0;
    if (!(pts = (pareto_point *)calloc(st->nrows + 1, sizeof *pts))) {
        cli_fail(s, "out of memory");
        goto done;
    }
    for (i = 0; i < st->nrows; i++) { /* the fronts across the methods, per scene and quantity */
        pts[i].ms = st->rows[i].it.ms;
        pts[i].error = st->rows[i].it.error;
        pts[i].group = st->rows[i].group;
    }
    pareto_mark(pts, st->nrows);
    for (i = 0; i < st->nrows; i++) st->rows[i].front = pts[i].front;
    if (write_files(st, pts)) goto done;
    cli_status_clear(s);
    write_summary(stdout, st, pts);
    printf("wrote %s/report.md, %s/report.csv, the plots (%s/SCENE-QUANTITY.svg) and the pictures (%s/SCENE-METHOD.png)\n", a->out_dir, a->out_dir,
           a->out_dir, a->out_dir);
    rc = CLI_EXIT_OK;
done:
    s->prefix[0] = 0;
    for (si = 0; cm && si < nmeshes; si++)
        if (cm[si].name[0]) cli_cornell_mesh_close(cpu.vx, &cm[si]);
    free(cm);
    free(pts);
    free(st->rows);
    free(st);
    if (c.vx) cli_context_close(s, &c);
    if (cpu.vx) cli_context_close(s, &cpu);
    return rc;
}

int cmd_report_all(int argc, char **argv)
{
    static char names[ALL_MAX_SCENES][256];
    all_args a;
    cli_session s;
    const char *list;
    int r, rc, nbuiltin = 0, nmeshes = 0, size_given = 0, spp_given = 0, scenes_given = 0;
    memset(&a, 0, sizeof a);
    a.common.backend = VOXGI_BACKEND_CPU;
    a.out_dir = "build/report";
    a.scene_list = "cornell-box,rsm-walls,foliage";
    a.mesh_list = "";
    a.size = 128;
    a.spp = 1024;
    {
        const cli_option options[] = {
            {.name = "--out", .arg = "DIR", .kind = CLI_STRING, .dst = &a.out_dir, .synopsis = "-o, --out DIR", .help = "where the files go (default build/report)"},
            {.name = "-o", .arg = "DIR", .kind = CLI_STRING, .dst = &a.out_dir}, /* listed with --out */
            {.name = "--quick", .kind = CLI_FLAG, .dst = &a.quick,
             .help = "a few settings per method, 64 x 64 pixels, 256-spp references and the\n"
                     "scenes cornell-box,rsm-walls (where every method appears): well under a\n"
                     "minute on two cores (--size, --spp and --scenes given still apply)"},
            {.name = "--scenes", .arg = "LIST", .kind = CLI_STRING, .dst = &a.scene_list, .given = &scenes_given,
             .help = "built-in scenes, comma-separated (default cornell-box,rsm-walls,foliage;\n'' for none)"},
            {.name = "--meshes", .arg = "LIST", .kind = CLI_STRING, .dst = &a.mesh_list,
             .help = "mesh files or builtin:NAME shapes, comma-separated: each also as the\n"
                     "Cornell box with the mesh in place of its tall block (report vct\n"
                     "--cornell-mesh's scene, named cornell-box+NAME) (default none)"},
            {.name = "--size", .arg = "N", .kind = CLI_INT, .dst = &a.size, .lo = 8, .hi = 4096, .given = &size_given,
             .help = "N x N pixels (default 128)"},
            {.name = "--spp", .arg = "S", .kind = CLI_INT, .dst = &a.spp, .lo = 16, .hi = 1 << 20, .given = &spp_given,
             .help = "samples per pixel of the references (default 1024)"},
            CLI_OPT_THREADS(&a.common),
            CLI_OPT_BACKEND(&a.common, "where the methods run (default cpu; the references always on the CPU)")};
        const cli_command cmd = {.name = "report all", .help = all_help, .column = 27, .options = options, .option_count = CLI_COUNT(options)};
        if ((rc = cli_parse(&cmd, argc, argv)) != CLI_CONTINUE) return rc;
    }
    if (a.quick) {
        if (!size_given) a.size = 64;
        if (!spp_given) a.spp = 256;
        if (!scenes_given) a.scene_list = "cornell-box,rsm-walls";
    }
    for (list = a.scene_list; *a.scene_list && (r = cli_next_item(&list, names[nbuiltin], sizeof names[0])) != 0; nbuiltin++)
        if (r < 0 || nbuiltin == ALL_MAX_SCENES)
            return cli_usage("report all", "--scenes needs up to %d comma-separated built-in scenes, got '%s'", ALL_MAX_SCENES, a.scene_list);
    for (list = a.mesh_list; *a.mesh_list && (r = cli_next_item(&list, names[nbuiltin + nmeshes], sizeof names[0])) != 0; nmeshes++)
        if (r < 0 || nbuiltin + nmeshes == ALL_MAX_SCENES)
            return cli_usage("report all", "--scenes and --meshes need up to %d scenes in all, got '%s'", ALL_MAX_SCENES, a.mesh_list);
    if (nbuiltin + nmeshes == 0) return cli_usage("report all", "no scene: --scenes and --meshes are both empty");
    cli_session_init(&s, "report");
    return all_run(&s, &a, (const char(*)[256])names, nbuiltin, nmeshes);
}
