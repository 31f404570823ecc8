/* tools/cmd_report.c - voxgi report vct: the cone tracer's error against run time, as Markdown, CSV and SVG. */
#include "report.h"
#include <stdlib.h>
#include <string.h>

static const char *const report_help =
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

#define REPORT_MAX_SCENES 9 /* 8 of --scenes and --cornell-mesh's */
#define REPORT_MAX_LIST 16

typedef struct report_args {
    cli_common common; /* --backend, --threads */
    const char *out_dir, *scene_list, *cornell_mesh;
    double res[REPORT_MAX_LIST], cones[REPORT_MAX_LIST], apertures[REPORT_MAX_LIST], steps[REPORT_MAX_LIST], strides[REPORT_MAX_LIST];
    int nres, ncones, naps, nsteps, nstrides, size, spp, direct_spp, no_stages, stage_res;
    unsigned filters;
} report_args;

/* What a cone-traced image measured (voxgi_render_info's VCT stages and sizes). */
typedef struct vct_times {
    uint64_t voxels;              /* info.voxels */
    size_t radiance_bytes;        /* info.bytes: what the cones gather from, the radiance volume or the octree */
    double ms_voxelize, ms_inject, ms_octree, ms_cones, ms_direct, ms; /* the stages (inject: with the mips), all */
} vct_times;

static void vct_times_of(const voxgi_render_info *i, vct_times *t)
{
    t->voxels = i->voxels;
    t->radiance_bytes = i->bytes;
    t->ms_voxelize = voxgi_render_stage_ms(i, "voxelize");
    t->ms_inject = voxgi_render_stage_ms(i, "inject");
    t->ms_octree = voxgi_render_stage_ms(i, "octree");
    t->ms_cones = voxgi_render_stage_ms(i, "cones");
    t->ms_direct = voxgi_render_stage_ms(i, "direct");
    t->ms = i->ms;
}

typedef struct report_row {
    const char *scene;
    int res, cones, mips, stride;
    double aperture, half_angle_deg, step;
    vct_times info;
    double rmse, ref_ms;
    int pareto;
} report_row;

/* The measurements: per scene the reference's convergence, and a row per configuration. */
typedef struct report {
    char scene_buf[REPORT_MAX_SCENES][64];
    const char *scenes[REPORT_MAX_SCENES];
    int scene_count, nrows;
    int cornell_mesh_scene;       /* the index of --cornell-mesh's scene, or -1 */
    size_t masked[REPORT_MAX_SCENES]; /* pixels left out of each scene's errors */
    double ref_c[REPORT_MAX_SCENES], ref_ms_per_spp[REPORT_MAX_SCENES], ref_bvh_ms[REPORT_MAX_SCENES], ref_floor[REPORT_MAX_SCENES];
    report_row *rows;
    voxgi_info ci;
    const report_args *args;
    /* the stages of the tool's defaults: [0] the CPU, [1] GL (each the faster of two runs) */
    voxgi_context *stage_ctx[2];  /* NULL: that backend is not timed */
    voxgi_info stage_ci[2];
    vct_times stages[REPORT_MAX_SCENES][2];
} report;

/* The tools' one rule (cli_masked_error); 0 for a black reference. */
static double rel_rmse(const cli_error_mask *m, const float *a, const float *ref)
{
    double e = cli_masked_error(m, a, ref, NULL, NULL);
    return isfinite(e) ? e : 0;
}

/* Error against time, log scales: every configuration, each scene's Pareto front joined, the reference dashed. */
static void report_svg(FILE *f, const report *rep)
{
    report_plot_point *points = (report_plot_point *)calloc((size_t)rep->nrows + 1, sizeof *points);
    char (*labels)[32] = (char (*)[32])calloc((size_t)rep->nrows + 1, sizeof *labels);
    char legend_text[REPORT_MAX_SCENES][160];
    const char *legend[REPORT_MAX_SCENES];
    double curve_ms[REPORT_MAX_SCENES][41], curve_error[REPORT_MAX_SCENES][41];
    report_plot_curve curves[REPORT_MAX_SCENES];
    report_plot plot;
    int i, s, k;
    if (!points || !labels) {
        free(points);
        free(labels);
        return;
    }
    for (i = 0; i < rep->nrows; i++) {
        const report_row *r = &rep->rows[i];
        for (s = 0; s < rep->scene_count && strcmp(r->scene, rep->scenes[s]) != 0; s++) {}
        snprintf(labels[i], sizeof labels[i], "%d/%d%s", r->res, r->cones, mips_mark[r->mips]);
        points[i].ms = r->info.ms;
        points[i].error = r->rmse;
        points[i].series = s;
        points[i].front = r->pareto;
        points[i].label = r->pareto ? labels[i] : NULL;
    }
    for (s = 0; s < rep->scene_count; s++) {
        for (k = 0; k <= 40; k++) { /* the path tracer at spp k: its error c / sqrt(k) measured against the reference (with its floor), at time bvh + k x per-spp */
            double spp = pow(2, k / 2.0);
            curve_ms[s][k] = rep->ref_bvh_ms[s] + spp * rep->ref_ms_per_spp[s];
            curve_error[s][k] = sqrt(rep->ref_c[s] * rep->ref_c[s] / spp + rep->ref_floor[s] * rep->ref_floor[s]);
        }
        curves[s].ms = curve_ms[s];
        curves[s].error = curve_error[s];
        curves[s].count = 41;
        curves[s].series = s;
        snprintf(legend_text[s], sizeof legend_text[s], "%s: cone tracing (filled: Pareto front, label res/cones, a = anisotropic, o = octree); dashed: the reference",
                 rep->scenes[s]);
        legend[s] = legend_text[s];
    }
    memset(&plot, 0, sizeof plot);
    plot.y_title = "relative RMSE against the one-bounce reference";
    plot.x_title = "time per image (wall clock)";
    plot.legend = legend;
    plot.series_count = rep->scene_count;
    plot.points = points;
    plot.count = (size_t)rep->nrows;
    plot.front_per_series = 1;
    plot.curves = curves;
    plot.curve_count = rep->scene_count;
    report_plot_svg(f, &plot);
    free(points);
    free(labels);
}

/* The cone-traced image of scene (its name, seen by cam) for every configuration of a's lists,
   each measured against ref (by mask) and appended to rows[*nrows] (ref_ms left to the caller);
   with run, also handed to report all. 0, or says why and returns 1. */
static int vct_sweep(cli_session *s, voxgi_context *ctx, const report_args *a, const voxgi_scene *scene, const voxgi_camera *cam, const char *name,
                     const cli_error_mask *mask, const float *ref, float *img, report_row *rows, int *nrows, report_run *run)
{
    size_t nv = (size_t)cam->width * (size_t)cam->height * 3;
    int ir, ic, ia, is, ist, f;
    for (f = 0; f < 3; f++)
        for (ir = 0; ir < a->nres; ir++)
            for (ic = 0; ic < a->ncones; ic++)
                for (ia = 0; ia < a->naps; ia++)
                    for (is = 0; is < a->nsteps; is++)
                        for (ist = 0; ist < a->nstrides; ist++) {
                            static const voxgi_vct_radiance radiance[3] = {VOXGI_VCT_ISOTROPIC, VOXGI_VCT_ANISOTROPIC, VOXGI_VCT_OCTREE};
                            voxgi_render_desc vd;
                            voxgi_render_info vi;
                            report_row *row = &rows[*nrows];
                            if (!(a->filters & (1u << f))) continue;
                            memset(&vd, 0, sizeof vd);
                            vd.method = VOXGI_RENDER_VCT;
                            vd.camera = *cam;
                            vd.resolution = (int)a->res[ir];
                            vd.vct.radiance = radiance[f];
                            vd.vct.cones.cones = (int)a->cones[ic];
                            vd.vct.cones.half_angle = (float)(a->apertures[ia] * acos(1 - 1.0 / vd.vct.cones.cones));
                            vd.vct.cones.step = (float)a->steps[is];
                            vd.samples = a->direct_spp;
                            vd.seed = 1;
                            vd.hide_emitters = 1;
                            vd.vct.cone_stride = (int)a->strides[ist];
                            if (!(vd.vct.cones.half_angle < 1.5f)) continue;
                            cli_status(s, "%s: %d^3, %d cones x %.2f, step %.2f, stride %d, %s", name, vd.resolution, vd.vct.cones.cones, a->apertures[ia],
                                       a->steps[is], vd.vct.cone_stride, mips_names[f]);
                            if (voxgi_render(ctx, scene, &vd, img, nv * 4, &vi) != VOXGI_OK) return cli_fail_lib(s, ctx, NULL);
                            vct_times_of(&vi, &row->info);
                            row->scene = name;
                            row->res = vd.resolution;
                            row->cones = vd.vct.cones.cones;
                            row->mips = f;
                            row->aperture = a->apertures[ia];
                            row->half_angle_deg = vd.vct.cones.half_angle * 180 / 3.14159265358979323846;
                            row->step = a->steps[is];
                            row->stride = vd.vct.cone_stride;
                            row->rmse = rel_rmse(mask, img, ref);
                            (*nrows)++;
                            if (run) {
                                const vct_times *v = &row->info;
                                report_item it;
                                memset(&it, 0, sizeof it);
                                it.method = "vct";
                                snprintf(it.settings, sizeof it.settings, "%d^3, %d cones (%.1f deg), step %g, stride %d, %s", row->res, row->cones,
                                         row->half_angle_deg, row->step, row->stride, mips_names[f]);
                                report_append(it.passes, sizeof it.passes, "voxelize %.1f, inject + mips %.1f", v->ms_voxelize, v->ms_inject);
                                if (f == 2) report_append(it.passes, sizeof it.passes, ", octree %.1f", v->ms_octree);
                                report_append(it.passes, sizeof it.passes, ", cones %.1f, direct %.1f", v->ms_cones, v->ms_direct);
                                it.ms = v->ms;
                                it.bytes = (double)v->radiance_bytes;
                                it.error = cli_masked_error(mask, img, ref, NULL, NULL);
                                run->emit(run, &it, img);
                            }
                        }
    return 0;
}

/* One scene (cm: its scene when it is --cornell-mesh's): the converged reference into ref and its
   convergence, then a row per configuration (img: scratch); 0, or says why and returns 1. */
static int report_scene(cli_session *s, voxgi_context *ctx, const report_args *a, report *rep, int si, const cli_cornell_mesh *cm, float *ref,
                        float *img)
{
    voxgi_builtin_scene bs;
    const voxgi_scene *scene;
    cli_error_mask mask;
    voxgi_render_desc rd;
    voxgi_render_info ri;
    size_t nv = (size_t)a->size * (size_t)a->size * 3;
    const char *name = rep->scenes[si];
    int k, i, first_row = rep->nrows, rc = CLI_EXIT_FAILURE;
    double c2 = 0;
    memset(&bs, 0, sizeof bs);
    memset(&mask, 0, sizeof mask);
    memset(&rd, 0, sizeof rd);
    rd.method = VOXGI_RENDER_REFERENCE;
    if (cm) {
        scene = &cm->scene;
        rd.camera = cm->bs.camera;
    } else {
        if (voxgi_builtin_scene_create(ctx, name, &bs) != VOXGI_OK) return cli_fail_lib(s, ctx, NULL);
        scene = &bs.scene;
        rd.camera = bs.camera;
    }
    rd.camera.width = rd.camera.height = a->size;
    if (cli_error_mask_make(s, ctx, scene, &rd.camera, &mask)) goto done;
    if (mask.masked_pixels == (size_t)a->size * (size_t)a->size) {
        cli_fail(s, "%s: every pixel is within %d pixels of one that sees an emitter: no error to measure", name, CLI_EMITTER_MARGIN);
        goto done;
    }
    rep->masked[si] = mask.masked_pixels;
    rd.bounces = 1;
    rd.hide_emitters = 1;
    rd.samples = a->spp;
    rd.seed = 1000;
    cli_note(s, "%s: the reference, %d spp", name, a->spp);
    if (voxgi_render(ctx, scene, &rd, ref, nv * 4, &ri) != VOXGI_OK) {
        cli_fail_lib(s, ctx, NULL);
        goto done;
    }
    for (k = 4; k <= 64; k *= 4) { /* the reference's convergence: a difference of two independent estimates has variance c^2 (1/k + 1/spp) */
        rd.samples = k;
        rd.seed = 7 + (uint64_t)k;
        if (voxgi_render(ctx, scene, &rd, img, nv * 4, &ri) != VOXGI_OK) {
            cli_fail_lib(s, ctx, NULL);
            goto done;
        }
        c2 += rel_rmse(&mask, img, ref) * rel_rmse(&mask, img, ref) / (1.0 / k + 1.0 / a->spp) / 3;
    }
    rep->ref_c[si] = sqrt(c2);
    rep->ref_ms_per_spp[si] = voxgi_render_stage_ms(&ri, "render") / 64;
    rep->ref_bvh_ms[si] = voxgi_render_stage_ms(&ri, "bvh");
    rep->ref_floor[si] = rep->ref_c[si] / sqrt((double)a->spp);
    if (vct_sweep(s, ctx, a, scene, &rd.camera, name, &mask, ref, img, rep->rows, &rep->nrows, NULL)) goto done;
    for (i = first_row; i < rep->nrows; i++) { /* the path tracer's spp k whose image measures the same error against the same
                                                  reference: c^2 (1/k + 1/spp) = rmse^2 (the reference's own noise is in both) */
        report_row *row = &rep->rows[i];
        double inv = row->rmse * row->rmse / (rep->ref_c[si] * rep->ref_c[si]) - 1.0 / a->spp, need = inv > 1.0 / (1024.0 * a->spp) ? 1 / inv : 1024.0 * a->spp;
        row->ref_ms = rep->ref_bvh_ms[si] + rep->ref_ms_per_spp[si] * (need > 1.0 ? need : 1.0);
    }
    for (k = 0; k < 2; k++) { /* the stages on each backend, the faster of two runs (the first compiles GL's shaders) */
        voxgi_render_desc vd;
        int run;
        if (!rep->stage_ctx[k]) continue;
        cli_vct_defaults(&vd, &rd.camera); /* the tool's defaults at the report's size, the grid --stage-res */
        vd.resolution = a->stage_res;
        cli_note(s, "%s: the defaults' stages on %s", name, voxgi_backend_name(rep->stage_ci[k].backend));
        for (run = 0; run < 2; run++) {
            voxgi_render_info ri_stage;
            vct_times vi;
            if (voxgi_render(rep->stage_ctx[k], scene, &vd, img, nv * 4, &ri_stage) != VOXGI_OK) {
                cli_fail_lib(s, rep->stage_ctx[k], NULL);
                goto done;
            }
            vct_times_of(&ri_stage, &vi);
            if (run == 0 || vi.ms < rep->stages[si][k].ms) rep->stages[si][k] = vi;
        }
    }
    pareto_mark_rows(rep->rows + first_row, (size_t)(rep->nrows - first_row), sizeof(report_row), offsetof(report_row, info.ms), offsetof(report_row, rmse),
                     PARETO_NO_GROUP, offsetof(report_row, pareto)); /* the scene's front */
    rc = CLI_EXIT_OK;
done:
    cli_error_mask_free(&mask);
    voxgi_builtin_scene_destroy(ctx, &bs);
    return rc;
}

static void write_csv(FILE *csv, const report *rep)
{
    int i;
    fprintf(csv, "scene,res,cones,aperture,half_angle_deg,step,stride,filter,voxels,radiance_bytes,voxelize_ms,inject_ms,octree_ms,cones_ms,direct_ms,ms,rel_rmse,"
                 "reference_ms_same_error,speedup,pareto\n");
    for (i = 0; i < rep->nrows; i++) {
        const report_row *r = &rep->rows[i];
        fprintf(csv, "%s,%d,%d,%g,%.2f,%g,%d,%s,%llu,%llu,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.5f,%.1f,%.2f,%d\n", r->scene, r->res, r->cones, r->aperture,
                r->half_angle_deg, r->step, r->stride, mips_names[r->mips], (unsigned long long)r->info.voxels, (unsigned long long)r->info.radiance_bytes,
                r->info.ms_voxelize, r->info.ms_inject, r->info.ms_octree, r->info.ms_cones, r->info.ms_direct, r->info.ms, r->rmse, r->ref_ms,
                r->ref_ms / r->info.ms, r->pareto);
    }
}

static void write_markdown(FILE *md, const report *rep)
{
    const report_args *a = rep->args;
    const voxgi_info *ci = &rep->ci;
    int i, s;
    fprintf(md, "# Voxel cone tracing: error against run time\n\n%d x %d pixels; cone tracer on %s%s%s, %d direct-light rays per pixel; the "
                "reference is the one-bounce path tracer (CPU). Error: relative RMSE of the lighting against the converged reference "
                "over the pixels farther than %d pixels from any pixel whose centre sees an emitter, both images without the emission the "
                "camera sees. *Reference at the same error*: the time the path tracer needs for an image that "
                "measures that error against the same reference (from its measured convergence, the reference's own noise in both). Wall clock on this machine%s.\n\n",
            a->size, a->size, voxgi_backend_name(ci->backend), ci->backend == VOXGI_BACKEND_GL ? ", " : "", ci->backend == VOXGI_BACKEND_GL ? ci->gl_renderer : "",
            a->direct_spp, CLI_EMITTER_MARGIN, ci->backend == VOXGI_BACKEND_GL && ci->gl_software ? " (GL on a software rasteriser: not GPU timings)" : "");
    for (s = 0; s < rep->scene_count; s++) {
        fprintf(md, "## %s\n\nReference: %d spp; its error is %.2f%% / sqrt(spp) (%.3f%% at %d spp: the floor of every error below), %.2f ms per "
                    "sample per pixel. Pixels left out of the errors (near an emitter the camera sees): %lu of %d.\n\n| res | cones | half-angle | step | stride | mips | voxels | radiance MB | voxelize ms | inject ms | octree ms | cones ms | "
                    "direct ms | total ms | rel. RMSE | reference at the same error | speed-up | Pareto |\n"
                    "|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|:-:|\n",
                rep->scenes[s], a->spp, 100 * rep->ref_c[s], 100 * rep->ref_floor[s], a->spp, rep->ref_ms_per_spp[s], (unsigned long)rep->masked[s],
                a->size * a->size);
        for (i = 0; i < rep->nrows; i++) {
            const report_row *r = &rep->rows[i];
            if (r->scene == rep->scenes[s])
                fprintf(md, "| %d | %d | %.1f° | %g | %d | %s | %llu | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.2f%% | %.0f ms | %.1fx | %s |\n", r->res,
                        r->cones, r->half_angle_deg, r->step, r->stride, mips_short[r->mips], (unsigned long long)r->info.voxels,
                        r->info.radiance_bytes / 1e6, r->info.ms_voxelize, r->info.ms_inject, r->info.ms_octree, r->info.ms_cones, r->info.ms_direct,
                        r->info.ms, 100 * r->rmse, r->ref_ms, r->ref_ms / r->info.ms, r->pareto ? "yes" : "");
        }
        fprintf(md, "\n");
    }
    fprintf(md, "![error against time](vct.svg)\n");
    if (!rep->stage_ctx[0]) return;
    fprintf(md, "\n## Stages: the CPU against GL\n\nThe tool's defaults (%d^3%s, anisotropic, %d cones at stride %d, %d direct-light rays per pixel) "
                "at %d x %d, each stage's time (ms) on the CPU (%d threads) and on GL (%s), the faster of two runs.%s\n\n"
                "| scene | stage | CPU | GL | CPU faster by |\n|---|---|---:|---:|---:|\n",
            a->stage_res, a->stage_res == CLI_VCT_RES ? "" : " (the tool's: 96^3)", CLI_VCT_CONES, CLI_VCT_STRIDE, CLI_VCT_DIRECT_SPP, a->size, a->size, rep->stage_ci[0].thread_count,
            rep->stage_ctx[1] ? rep->stage_ci[1].gl_renderer : "no GL 4.5 context could be made: not timed",
            rep->stage_ctx[1] && rep->stage_ci[1].gl_software ? " GL runs on a software rasteriser on the same cores: these are not GPU timings." : "");
    for (s = 0; s < rep->scene_count; s++) {
        static const char *const stage_names[5] = {"voxelize", "inject + mips", "cones", "direct light (CPU rays on both)", "total"};
        const vct_times *c = &rep->stages[s][0], *g = &rep->stages[s][1];
        const double cpu[5] = {c->ms_voxelize, c->ms_inject, c->ms_cones, c->ms_direct, c->ms}, gl[5] = {g->ms_voxelize, g->ms_inject, g->ms_cones, g->ms_direct, g->ms};
        int k;
        for (k = 0; k < 5; k++) {
            if (rep->stage_ctx[1])
                fprintf(md, "| %s | %s | %.1f | %.1f | %.1fx |\n", rep->scenes[s], stage_names[k], cpu[k], gl[k], cpu[k] > 0 ? gl[k] / cpu[k] : 0);
            else
                fprintf(md, "| %s | %s | %.1f | - | - |\n", rep->scenes[s], stage_names[k], cpu[k]);
        }
    }
}

/* DIR/NAME, written by fn; 0, or says why and returns 1. */
static int write_file(cli_session *s, const report *rep, const char *name, void (*fn)(FILE *, const report *))
{
    char path[1024];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s", rep->args->out_dir, name);
    if (!(f = fopen(path, "w"))) return cli_fail(s, "cannot write %s", path);
    fn(f, rep);
    if (fclose(f) != 0) return cli_fail(s, "cannot write %s", path);
    return 0;
}

static int vct_run(cli_session *s, const report_args *a, report *rep)
{
    cli_context c, stage_c; /* stage_c: the other backend's, for the stages */
    cli_cornell_mesh cm;
    float *ref = NULL, *img = NULL;
    int i, si, rc = CLI_EXIT_FAILURE;
    memset(&cm, 0, sizeof cm);
    if (cli_context_open_options(s, &c, &a->common)) return CLI_EXIT_FAILURE;
    voxgi_query_info(c.vx, &rep->ci);
    memset(&stage_c, 0, sizeof stage_c);
    if (!a->no_stages) { /* the report's context for its backend, one more for the other (a GL one where it can be made) */
        int mine = rep->ci.backend == VOXGI_BACKEND_GL, other = !mine;
        cli_common o = a->common;
        rep->stage_ctx[mine] = c.vx;
        rep->stage_ci[mine] = rep->ci;
        o.backend = other ? VOXGI_BACKEND_GL : VOXGI_BACKEND_CPU;
        if (cli_context_open_options(s, &stage_c, &o) == 0) {
            rep->stage_ctx[other] = stage_c.vx;
            voxgi_query_info(stage_c.vx, &rep->stage_ci[other]);
        } else if (other) {
            cli_note(s, "no GL context (%s): the stages are timed on the CPU alone", s->error);
            s->error[0] = 0;
        } else
            goto done;
    }
    if (a->cornell_mesh) { /* first: a bad mesh fails before any rendering */
        if (cli_cornell_mesh_open(s, c.vx, a->cornell_mesh, &cm)) goto done;
        rep->cornell_mesh_scene = rep->scene_count++;
        rep->scenes[rep->cornell_mesh_scene] = cm.name;
    }
    rep->rows = (report_row *)calloc((size_t)rep->scene_count * (size_t)(a->nres * a->ncones * a->naps * a->nsteps * a->nstrides * 3), sizeof *rep->rows);
    ref = (float *)malloc((size_t)a->size * (size_t)a->size * 12);
    img = (float *)malloc((size_t)a->size * (size_t)a->size * 12);
    if (!rep->rows || !ref || !img) {
        cli_fail(s, "out of memory");
        goto done;
    }
    if (cli_make_dirs(a->out_dir) != 0) {
        cli_fail(s, "cannot make %s", a->out_dir);
        goto done;
    }
    for (si = 0; si < rep->scene_count; si++)
        if (report_scene(s, c.vx, a, rep, si, si == rep->cornell_mesh_scene ? &cm : NULL, ref, img)) goto done;
    if (write_file(s, rep, "vct.csv", write_csv) || write_file(s, rep, "vct.md", write_markdown) || write_file(s, rep, "vct.svg", report_svg)) goto done;
    cli_status_clear(s);
    for (si = 0; si < rep->scene_count; si++) { /* the front on stdout */
        printf("%s (reference error %.2f%% / sqrt(spp), %.2f ms per spp; floor %.3f%%; %lu of %d pixels near an emitter left out)\n", rep->scenes[si],
               100 * rep->ref_c[si], rep->ref_ms_per_spp[si], 100 * rep->ref_floor[si], (unsigned long)rep->masked[si], a->size * a->size);
        for (i = 0; i < rep->nrows; i++) {
            const report_row *r = &rep->rows[i];
            if (r->scene == rep->scenes[si] && r->pareto)
                printf("  %4d^3 %3d cones %5.1f deg step %-4g stride %d %-5s %9.1f ms  %6.2f%%  reference %9.0f ms  %6.1fx\n", r->res, r->cones,
                       r->half_angle_deg, r->step, r->stride, mips_short[r->mips], r->info.ms, 100 * r->rmse, r->ref_ms, r->ref_ms / r->info.ms);
        }
    }
    printf("wrote %s/vct.md, %s/vct.csv, %s/vct.svg\n", a->out_dir, a->out_dir, a->out_dir);
    rc = CLI_EXIT_OK;
done:
    free(rep->rows);
    free(ref);
    free(img);
    if (cm.name[0]) cli_cornell_mesh_close(c.vx, &cm);
    if (stage_c.vx) cli_context_close(s, &stage_c);
    cli_context_close(s, &c);
    return rc;
}

/* report all's cone tracing: anisotropic mips (every point of this report's fronts has them), step
   0.5, stride 6 and 24 direct-light rays (the tool's), over grids and cone counts. */
int report_vct_all(report_run *run)
{
    static const double res[] = {32, 64, 96, 128}, cones[] = {8, 24}, quick_res[] = {32, 64};
    report_args a;
    report_row *rows;
    int n = 0, rc;
    memset(&a, 0, sizeof a);
    if (run->quick) memcpy(a.res, quick_res, sizeof quick_res), a.nres = CLI_COUNT(quick_res);
    else memcpy(a.res, res, sizeof res), a.nres = CLI_COUNT(res);
    memcpy(a.cones, cones, sizeof cones);
    a.ncones = CLI_COUNT(cones);
    a.apertures[0] = 1;
    a.steps[0] = 0.5;
    a.strides[0] = CLI_VCT_STRIDE;
    a.naps = a.nsteps = a.nstrides = 1;
    a.filters = 2; /* anisotropic */
    a.direct_spp = CLI_VCT_DIRECT_SPP;
    if (!(rows = (report_row *)calloc((size_t)(a.nres * a.ncones), sizeof *rows))) return cli_fail(run->s, "out of memory");
    rc = vct_sweep(run->s, run->ctx, &a, run->scene, &run->camera, run->scene_name, &run->R->mask, run->R->image, run->img, rows, &n, run);
    free(rows);
    return rc;
}

int cmd_report(int argc, char **argv)
{
    static const double res[] = {32, 64, 128}, cones[] = {8, 16, 32}, steps[] = {0.5, 1}, strides[] = {1, 2};
    report_args a;
    report rep;
    cli_session s;
    const char *list;
    int r, rc;
    memset(&a, 0, sizeof a);
    memset(&rep, 0, sizeof rep);
    a.common.backend = VOXGI_BACKEND_CPU;
    a.out_dir = "build/report";
    a.scene_list = "cornell-box,rsm-walls";
    a.size = 128;
    a.spp = 1024;
    a.direct_spp = 16;
    a.stage_res = CLI_VCT_RES;
    a.filters = 3;
    memcpy(a.res, res, sizeof res);
    memcpy(a.cones, cones, sizeof cones);
    memcpy(a.steps, steps, sizeof steps);
    memcpy(a.strides, strides, sizeof strides);
    a.apertures[0] = 1;
    a.nres = a.ncones = 3;
    a.nsteps = a.nstrides = 2;
    a.naps = 1;
    {
#define LIST(opt, field, count, top, is_whole, text) \
    {.name = opt, .arg = "LIST", .kind = CLI_NUMBERS, .dst = a.field, .items = &a.count, .min_items = 1, .max_items = REPORT_MAX_LIST, \
     .lo = 0, .lo_open = 1, .hi = top, .whole = is_whole, .help = text}
        const cli_option options[] = {
            {.name = "--scenes", .arg = "LIST", .kind = CLI_STRING, .dst = &a.scene_list,
             .help = "built-in scenes, comma-separated (default cornell-box,rsm-walls)"},
            {.name = "--cornell-mesh", .arg = "MESH", .kind = CLI_STRING, .dst = &a.cornell_mesh,
             .help = "also the Cornell box with MESH (a file or builtin:NAME) in place of its\n"
                     "tall block (scaled uniformly to fit inside the block's bounding box, on\n"
                     "the floor at its centre, white), named cornell-box+NAME"},
            {.name = "--size", .arg = "N", .kind = CLI_INT, .dst = &a.size, .lo = 1, .hi = 4096, .help = "N x N pixels (default 128)"},
            {.name = "--spp", .arg = "S", .kind = CLI_INT, .dst = &a.spp, .lo = 64, .hi = 1 << 20,
             .help = "samples per pixel of the converged reference (default 1024)"},
            {.name = "--direct-spp", .arg = "S", .kind = CLI_INT, .dst = &a.direct_spp, .lo = 1, .hi = 65536,
             .help = "the cone tracer's direct-light rays per pixel (default 16)"},
            LIST("--res", res, nres, 4096, 0, "voxels along the longest side (default 32,64,128)"),
            LIST("--cones", cones, ncones, 1024, 0, "diffuse cones (default 8,16,32)"),
            LIST("--apertures", apertures, naps, HUGE_VAL, 0, "half-angle as a multiple of each cone count's gap-free default (default 1)"),
            LIST("--steps", steps, nsteps, 4, 0, "step as a fraction of the diameter (default 0.5,1)"),
            {.name = "--filters", .arg = "LIST", .kind = CLI_SET, .dst = &a.filters, .names = mips_names, .values = mips_bits,
             .help = "isotropic, anisotropic (dense mips) and/or octree (an octree of the\n"
                     "radiance, isotropic mips) (default isotropic,anisotropic)"},
            LIST("--strides", strides, nstrides, 64, 1, "cone strides: cones at every S-th pixel, the rest interpolated (default 1,2)"),
            CLI_OPT_BACKEND(&a.common, "where the cone tracer runs (default cpu)"),
            {.name = "--no-stages", .kind = CLI_FLAG, .dst = &a.no_stages,
             .help = "leave out the timing of the defaults' stages on the CPU and on GL"},
            {.name = "--stage-res", .arg = "N", .kind = CLI_INT, .dst = &a.stage_res, .lo = 1, .hi = 4096,
             .help = "the grid of the stages' timing (default 96, the tool's)"},
            {.name = "--out", .arg = "DIR", .kind = CLI_STRING, .dst = &a.out_dir, .help = "where the files go (default build/report)"},
            CLI_OPT_THREADS(&a.common)};
#undef LIST
        const cli_command cmd = {.name = "report", .help = report_help, .column = 27, .options = options, .option_count = CLI_COUNT(options)};
        if (argc >= 1 && (strcmp(argv[0], "--help") == 0 || strcmp(argv[0], "-h") == 0)) {
            cli_help(&cmd, stdout);
            return CLI_EXIT_OK;
        }
        if (argc >= 1 && strcmp(argv[0], "tsm") == 0) return cmd_report_tsm(argc - 1, argv + 1);
        if (argc >= 1 && strcmp(argv[0], "rsm") == 0) return cmd_report_bounce(0, argc - 1, argv + 1);
        if (argc >= 1 && strcmp(argv[0], "sh") == 0) return cmd_report_bounce(1, argc - 1, argv + 1);
        if (argc >= 1 && strcmp(argv[0], "ao") == 0) return cmd_report_screen(0, argc - 1, argv + 1);
        if (argc >= 1 && strcmp(argv[0], "ssgi") == 0) return cmd_report_screen(1, argc - 1, argv + 1);
        if (argc >= 1 && strcmp(argv[0], "linespace") == 0) return cmd_report_linespace(argc - 1, argv + 1);
        if (argc >= 1 && strcmp(argv[0], "all") == 0) return cmd_report_all(argc - 1, argv + 1);
        if (argc >= 1 && strcmp(argv[0], "stiff") == 0) return cmd_report_stiff(argc - 1, argv + 1);
        if (argc < 1 || strcmp(argv[0], "vct") != 0)
            return cli_usage("report", "the reports to make are 'vct', 'tsm', 'rsm', 'sh', 'ao', 'ssgi', 'linespace', 'stiff' and 'all'");
        if ((rc = cli_parse(&cmd, argc - 1, argv + 1)) != CLI_CONTINUE) return rc;
    }
    for (list = a.scene_list; (r = cli_next_item(&list, rep.scene_buf[rep.scene_count], sizeof rep.scene_buf[0])) != 0; rep.scene_count++)
        if (r < 0 || rep.scene_count == REPORT_MAX_SCENES - 1)
            return cli_usage("report", "--scenes needs 1 to %d comma-separated built-in scenes, got '%s'", REPORT_MAX_SCENES - 1, a.scene_list);
    rep.cornell_mesh_scene = -1;
    for (r = 0; r < rep.scene_count; r++) rep.scenes[r] = rep.scene_buf[r];
    rep.args = &a;
    cli_session_init(&s, "report");
    return vct_run(&s, &a, &rep);
}
