/* tools/cmd_report_linespace.c - voxgi report linespace: the line space's soft shadows, error
   against run time (images against the reference, fast mode's visibility against exact rays, the
   shadow rays against the ray core), as Markdown and CSV. */
#include "report.h"
#include <stdlib.h>
#include <string.h>

static const char *const ls_help =
    "usage: voxgi report linespace [options]\n"
    "Error against run time of the line space's soft shadows (voxgi render --method linespace).\n"
    "Images: for each built-in scene the reference's direct light (converged, --spp), then the\n"
    "line-space image for every tree (n x depth), mode, supersampling and sample count; the\n"
    "relative RMSE by the tools' rule and on 4 x 4 block means, and fast mode's visibility against\n"
    "exact mode's (the same samples): mean absolute error of the visible share and the share of\n"
    "samples it blocks wrongly. Rays: for each mesh on a floor under a square light, 16 shadow\n"
    "rays per pixel cast by the line space (exact, fast) and by the ray core (the BVH), the same\n"
    "segments; packets against rays alone (the source's Table 3) and line-space lookups against\n"
    "triangle tests (Table 2). Writes DIR/linespace.md and DIR/linespace.csv. Times are wall\n"
    "clock on this machine's CPU.\n";

typedef struct ls_report {
    report_opts o;
    const char *mesh_list;
    report_list ns, depths, samples, supersample, ends;
} ls_report;

/* A row's values (report_item.v). */
enum { V_N, V_DEPTH, V_BUILD_MS, V_SUPERSAMPLE, V_POINTS, V_SAMPLES, V_RAYS, V_MODE, V_ENDS, V_SHADOWS_MS, V_MS, V_BLOCK, V_MEAN, V_MAE, V_WRONG };
static const char *const mode_names[] = {"exact", "fast"};

/* Exact mode's rows leave fast mode's columns blank (0 in the CSV); the image rows have had one
   field more than the head, as the rays' rows below have. */
static const report_column ls_columns[] = {
    {.csv = "part", .at = REPORT_AT_NONE, .csv_none = "image"}, REPORT_COL_SCENE, REPORT_COL_INT("n", "n", V_N), REPORT_COL_INT("depth", "depth", V_DEPTH),
    {.md = "tree MB", .align = "---:", .csv = "bytes", .at = REPORT_AT_BYTES, .md_fmt = "%.2f", .csv_fmt = "%.0f", .md_unit = 'M'},
    REPORT_COL("build ms", "build_ms", V_BUILD_MS, "%.0f", "%.3f"), REPORT_COL_INT(NULL, "supersample", V_SUPERSAMPLE),
    REPORT_COL_INT("points per pixel", NULL, V_POINTS), REPORT_COL_INT("samples", "samples", V_SAMPLES), REPORT_COL_INT("rays per pixel", NULL, V_RAYS),
    {.md = "mode", .align = "---", .csv = "mode", .at = V_MODE, .names = mode_names, .csv_names = mode_names},
    {.csv = "exact_ends", .at = V_ENDS, .csv_fmt = "%.0f", .csv_none = "0"}, {.csv = "packets", .at = REPORT_AT_NONE, .csv_none = "0"},
    REPORT_COL("shadows ms", "shadows_ms", V_SHADOWS_MS, "%.1f", "%.3f"), REPORT_COL("total ms", "ms", V_MS, "%.1f", "%.3f"), REPORT_COL_ERROR("black"),
    {.md = "4x4", .align = "---:", .csv = "block_rmse", .at = V_BLOCK, .md_fmt = "%.2f%%", .csv_fmt = "%.6g", .md_unit = '%', .md_none = "black"},
    REPORT_COL("mean", "mean", V_MEAN, "%.4g", "%.6g"), {.md = "exact ends", .align = "---:", .at = V_ENDS, .md_fmt = "%.0f", .md_none = ""},
    {.md = "MAE", .align = "---:", .csv = "mae", .at = V_MAE, .md_fmt = "%.4f", .csv_fmt = "%.6g", .md_none = "", .csv_none = "0"},
    {.md = "wrong", .align = "---:", .csv = "wrong", .at = V_WRONG, .md_fmt = "%.2f%%", .csv_fmt = "%.6g", .md_unit = '%', .md_none = "", .csv_none = "0"},
    {.csv = "agree_with_core", .at = REPORT_AT_NONE, .csv_none = ""}, {.csv = "core_ms", .at = REPORT_AT_NONE, .csv_none = ","}};

/* 4 x 4 block means of img and ref (3 floats per pixel), the blocks without a masked pixel: the
   relative RMSE of the means. */
static double block_error(const cli_error_mask *m, const float *img, const float *ref)
{
    double num = 0, den = 0;
    int bx, by, x, y, c;
    for (by = 0; by + 4 <= m->height; by += 4)
        for (bx = 0; bx + 4 <= m->width; bx += 4) {
            double a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
            int skip = 0;
            for (y = by; y < by + 4; y++)
                for (x = bx; x < bx + 4; x++) {
                    size_t p = (size_t)y * (size_t)m->width + (size_t)x;
                    skip |= m->masked[p];
                    for (c = 0; c < 3; c++) { a[c] += img[3 * p + (size_t)c]; b[c] += ref[3 * p + (size_t)c]; }
                }
            if (skip) continue;
            for (c = 0; c < 3; c++) { num += (a[c] - b[c]) * (a[c] - b[c]); den += b[c] * b[c]; }
        }
    return den > 0 ? sqrt(num / den) : NAN;
}

static double image_mean(const float *img, size_t values)
{
    double s = 0;
    size_t i;
    for (i = 0; i < values; i++) s += img[i];
    return s / (double)values;
}

/* The line-space image for every tree, supersampling, sample count and mode of run->args' lists;
   a tree the library refuses is a row of its own. */
static int ls_images(report_run *run)
{
    const ls_report *a = (const ls_report *)run->args;
    const voxgi_camera *cam = &run->camera;
    size_t pixels = (size_t)cam->width * (size_t)cam->height, p;
    float *vis[2] = {(float *)malloc(pixels * 4), (float *)malloc(pixels * 4)};
    int i, j, k, m, rc = 1;
    if (!vis[0] || !vis[1]) { cli_fail(run->s, "out of memory"); goto done; }
    for (i = 0; i < a->ns.n; i++)
        for (j = 0; j < a->depths.n; j++) {
            voxgi_linespace_desc td;
            voxgi_linespace *L = NULL;
            voxgi_linespace_info info;
            voxgi_result r;
            memset(&td, 0, sizeof td);
            td.n = (int)a->ns.v[i];
            td.depth = (int)a->depths.v[j];
            cli_status(run->s, "%s: line space n %d depth %d", run->scene_name, td.n, td.depth);
            if ((r = voxgi_linespace_create(run->ctx, run->scene, &td, &L)) == VOXGI_ERR_TOO_LARGE || r == VOXGI_ERR_INVALID_ARGUMENT) {
                report_item it;
                memset(&it, 0, sizeof it);
                it.ms = it.error = NAN;
                snprintf(it.note, sizeof it.note, "| %d | %d | - | - | - | refused: %s | | | | | | | |", td.n, td.depth, voxgi_last_error(run->ctx));
                run->emit(run, &it, NULL);
                continue;
            }
            if (r != VOXGI_OK) { cli_fail_lib(run->s, run->ctx, "line space"); goto done; }
            voxgi_linespace_query(L, &info);
            td.depth = info.depth; /* 0 asked for the scene's */
            for (k = 0; k < a->samples.n * a->supersample.n; k++) {
                int ss = (int)a->supersample.v[k / a->samples.n], spl = (int)a->samples.v[k % a->samples.n];
                for (m = 0; m <= a->ends.n; m++) { /* exact, then fast with each exact zone */
                    voxgi_render_desc d;
                    voxgi_render_info li;
                    report_item it;
                    double *v = it.v, mae = 0, wrong = 0, ms_gbuffer, ms_build;
                    memset(&d, 0, sizeof d);
                    d.method = VOXGI_RENDER_LINESPACE;
                    d.camera = *cam;
                    d.linespace.ls = L;
                    d.linespace.mode = m ? VOXGI_LINESPACE_FAST : VOXGI_LINESPACE_EXACT;
                    d.linespace.exact_ends = m ? (int)a->ends.v[m - 1] : 0;
                    d.linespace.samples = spl;      /* >= 1 (--samples) */
                    d.linespace.supersample = ss;   /* >= 1 (--supersample): 1 the pixel's centre */
                    d.linespace.visible = vis[m ? 1 : 0];
                    d.seed = 1;
                    d.hide_emitters = 1;
                    cli_status(run->s, "%s: n %d depth %d, %d x %d points, %d samples, %s", run->scene_name, td.n, td.depth, ss, ss, d.linespace.samples,
                               m ? "fast" : "exact");
                    if ((r = voxgi_render(run->ctx, run->scene, &d, run->img, pixels * 12, &li)) != VOXGI_OK) {
                        voxgi_linespace_destroy(run->ctx, L);
                        if (r == VOXGI_ERR_UNSUPPORTED) { /* no area light */
                            snprintf(run->why, sizeof run->why, "%s", voxgi_last_error(run->ctx));
                            rc = REPORT_NOT_APPLICABLE;
                        } else cli_fail_lib(run->s, run->ctx, "linespace");
                        goto done;
                    }
                    memset(&it, 0, sizeof it);
                    ms_gbuffer = voxgi_render_stage_ms(&li, "gbuffer");
                    ms_build = voxgi_render_stage_ms(&li, "build");
                    for (p = 0; m && p < pixels; p++) { /* fast against exact, the same samples */
                        mae += fabs((double)vis[1][p] - vis[0][p]);
                        wrong += (double)vis[0][p] - vis[1][p];
                    }
                    v[V_N] = td.n;
                    v[V_DEPTH] = td.depth;
                    v[V_BUILD_MS] = info.ms;
                    v[V_SUPERSAMPLE] = ss;
                    v[V_POINTS] = ss * ss;
                    v[V_SAMPLES] = spl;
                    v[V_RAYS] = ss * ss * spl;
                    v[V_MODE] = m != 0;
                    v[V_ENDS] = m ? d.linespace.exact_ends : NAN;
                    v[V_SHADOWS_MS] = voxgi_render_stage_ms(&li, "shadows");
                    v[V_MS] = li.ms - ms_build;
                    v[V_BLOCK] = block_error(&run->R->mask, run->img, run->R->image);
                    v[V_MEAN] = image_mean(run->img, 3 * pixels);
                    v[V_MAE] = m ? mae / (double)pixels : NAN;
                    v[V_WRONG] = m ? wrong / (double)pixels : NAN;
                    /* the tree is built once for every image: its time counts in each */
                    it.method = m ? "linespace-fast" : "linespace-exact";
                    snprintf(it.settings, sizeof it.settings, "n %d, depth %d, %d x %d points per pixel, %d samples", td.n, td.depth, ss, ss, spl);
                    if (m) report_append(it.settings, sizeof it.settings, ", exact ends %d", d.linespace.exact_ends);
                    snprintf(it.passes, sizeof it.passes, "tree %.1f, G-buffer %.1f, shadows %.1f", info.ms, ms_gbuffer, v[V_SHADOWS_MS]);
                    it.ms = li.ms - ms_build + info.ms;
                    it.bytes = (double)info.bytes;
                    report_measured(run, &it);
                }
            }
            voxgi_linespace_destroy(run->ctx, L);
        }
    rc = 0;
done:
    free(vis[0]);
    free(vis[1]);
    return rc;
}

static void ls_md_head(FILE *md, const report *rep)
{
    fprintf(md, "# Line space: soft shadows, error against run time\n\nCPU, %d threads; wall clock on this machine.\n", rep->ci.thread_count);
}

static void ls_md_scene(FILE *md, const report *rep, int si, int end)
{
    const report_scene *sc = &rep->scenes[si];
    char ref_error[64] = "black";
    if (end) return;
    if (isfinite(sc->c[0])) snprintf(ref_error, sizeof ref_error, "its error %.2f%% / sqrt(spp)", 100 * sc->c[0]);
    fprintf(md, "\n## %s\n\n%d x %d pixels; the reference's direct light at %d spp (%s); %lu pixels near an emitter left "
                "out. *rel. RMSE*: the tools' rule (*black*: the reference is, and the mean says the rest); *4x4*: on 4 x 4 block means "
                "without a masked pixel. Fast mode against exact, the same samples: "
                "*MAE* of the pixels' visible share, *wrong*: the share of samples fast mode blocks where exact mode sees the light; *exact ends*: fast mode's "
                "exact zone at each end of a ray, in leaves' edges.\n\n",
            sc->name, rep->o->size[0], rep->o->size[0], rep->o->spp, ref_error, (unsigned long)sc->masked);
}

/* A mesh on a floor (3 x its longest side, under it) and a square light (half its longest side)
   above it, shining down; the view from behind and above. */
typedef struct ls_mesh_scene {
    cli_mesh tm;
    voxgi_mesh meshes[2];
    float floor[12];
    uint32_t floor_idx[6];
    voxgi_scene scene;
    voxgi_camera cam;
    double light[9];              /* corner, edge_u, edge_v */
    double size;
} ls_mesh_scene;

static int ls_mesh_open(cli_session *s, const char *path, int pixels, ls_mesh_scene *M)
{
    static const uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    double c[3];
    size_t v;
    int a;
    memset(M, 0, sizeof *M);
    if (cli_mesh_open(s, path, &M->tm)) return 1;
    for (v = 0; v < M->tm.vm.vertex_count; v++)
        for (a = 0; a < 3; a++) {
            lo[a] = fminf(lo[a], M->tm.vm.positions[3 * v + (size_t)a]);
            hi[a] = fmaxf(hi[a], M->tm.vm.positions[3 * v + (size_t)a]);
        }
    for (a = 0; a < 3; a++) {
        c[a] = 0.5 * ((double)lo[a] + hi[a]);
        M->size = fmax(M->size, (double)hi[a] - lo[a]);
    }
    for (v = 0; v < 4; v++) { /* counter-clockwise from above */
        M->floor[3 * v] = (float)(c[0] + ((v == 1 || v == 2) ? -1.5 : 1.5) * M->size);
        M->floor[3 * v + 1] = lo[1];
        M->floor[3 * v + 2] = (float)(c[2] + (v >= 2 ? 1.5 : -1.5) * M->size);
    }
    memcpy(M->floor_idx, idx, sizeof idx);
    M->meshes[0] = M->tm.vm;
    M->meshes[1].positions = M->floor;
    M->meshes[1].vertex_count = 4;
    M->meshes[1].indices = M->floor_idx;
    M->meshes[1].index_count = 6;
    M->scene.meshes = M->meshes;
    M->scene.mesh_count = 2;
    M->scene.materials = M->tm.scene.materials; /* the file's (the floor takes the first) */
    M->scene.material_count = M->tm.scene.material_count;
    M->light[0] = c[0] - 0.25 * M->size; M->light[1] = hi[1] + 0.8 * M->size; M->light[2] = c[2] - 0.25 * M->size;
    M->light[5] = 0.5 * M->size; /* edge_u along z, edge_v along x: facing down */
    M->light[6] = 0.5 * M->size;
    M->cam.eye[0] = c[0] + 0.8 * M->size; M->cam.eye[1] = c[1] + 1.2 * M->size; M->cam.eye[2] = c[2] - 1.8 * M->size;
    memcpy(M->cam.target, c, sizeof c);
    M->cam.target[1] = lo[1];
    M->cam.fovy_degrees = 50;
    M->cam.width = M->cam.height = pixels;
    return 0;
}

/* Shadow rays from the G-buffer's surfaces to `samples` random points of the light each (a hair
   off the surface, ending short of the light): their count. */
static size_t ls_mesh_rays(const ls_mesh_scene *M, const float *pos, const float *nrm, size_t pixels, int samples, voxgi_ray *rays)
{
    unsigned rnd = 12345;
    size_t p, n = 0;
    int k, a;
    for (p = 0; p < pixels; p++) {
        if (nrm[3 * p] == 0 && nrm[3 * p + 1] == 0 && nrm[3 * p + 2] == 0) continue;
        for (k = 0; k < samples; k++) {
            double u, w, hair = ldexp(M->size, -18);
            voxgi_ray *r = &rays[n++];
            rnd = rnd * 1664525u + 1013904223u;
            u = (rnd >> 8) / 16777216.0;
            rnd = rnd * 1664525u + 1013904223u;
            w = (rnd >> 8) / 16777216.0;
            for (a = 0; a < 3; a++) {
                r->origin[a] = (float)(pos[3 * p + (size_t)a] + hair * nrm[3 * p + (size_t)a]);
                r->direction[a] = (float)(M->light[a] + u * M->light[3 + a] + w * M->light[6 + a] - r->origin[a]);
            }
            r->tmin = 0;
            r->tmax = 1.0f - 1.52587890625e-5f;
        }
    }
    return n;
}

static int ls_mesh(cli_session *s, voxgi_context *ctx, const ls_report *a, const char *path, FILE *md, FILE *csv)
{
    ls_mesh_scene M;
    size_t pixels = (size_t)a->o.size[0] * (size_t)a->o.size[0], nrays = 0, i;
    float *pos = (float *)malloc(pixels * 12), *nrm = (float *)malloc(pixels * 12), *vis = (float *)malloc(pixels * 4);
    voxgi_ray *rays = (voxgi_ray *)malloc(pixels * 16 * sizeof *rays);
    unsigned char *occ[3], *all = (unsigned char *)malloc(pixels * 48); /* exact, fast, the ray core */
    voxgi_ray_scene *rs = NULL;
    double core_ms = 0, t;
    int j, k, rc = 1;
    const char *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    if (!pos || !nrm || !vis || !rays || !all) { cli_fail(s, "out of memory"); goto out; }
    for (j = 0; j < 3; j++) occ[j] = all + (size_t)j * pixels * 16;
    if (ls_mesh_open(s, path, a->o.size[0], &M)) goto out;
    cli_status(s, "%s: G-buffer and the ray core", base);
    if (voxgi_gbuffer_render(ctx, &M.scene, &M.cam, pos, nrm, NULL) != VOXGI_OK || voxgi_ray_scene_create(ctx, &M.scene, &rs) != VOXGI_OK) {
        cli_fail_lib(s, ctx, base);
        goto done;
    }
    nrays = ls_mesh_rays(&M, pos, nrm, pixels, 16, rays);
    t = cli_now_ms();
    if (voxgi_ray_occluded(ctx, rs, nrays, rays, occ[2]) != VOXGI_OK) { cli_fail_lib(s, ctx, "rays"); goto done; }
    core_ms = cli_now_ms() - t;
    fprintf(md, "\n## %s on a floor (%lu triangles)\n\n%d x %d pixels, 16 shadow rays per pixel to random points of a square light "
                "above it (%lu rays). The ray core (4-wide BVH, packets) casts them in %.1f ms: %.2f M rays/s.\n\n",
            base, (unsigned long)(M.tm.vm.index_count ? M.tm.vm.index_count / 3 : M.tm.vm.vertex_count / 3) + 2, a->o.size[0], a->o.size[0], (unsigned long)nrays,
            core_ms, nrays / core_ms / 1000);
    fprintf(md, "| n | depth | tree MB | build ms | exact ms | exact M rays/s | vs core | exact = core | fast ms | fast M rays/s | vs core | wrong "
                "| fast light ms: rays alone, packets, at 4 / 9 / 16 / 100 samples |\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
    for (i = 0; i < (size_t)a->ns.n; i++)
        for (j = 0; j < a->depths.n; j++) {
            voxgi_linespace_desc td;
            voxgi_linespace *L = NULL;
            voxgi_linespace_info info;
            voxgi_result r;
            double ms[2];
            size_t agree = 0, wrong = 0, q;
            memset(&td, 0, sizeof td);
            td.n = (int)a->ns.v[i];
            td.depth = (int)a->depths.v[j];
            cli_status(s, "%s: line space n %d depth %d", base, td.n, td.depth);
            if ((r = voxgi_linespace_create(ctx, &M.scene, &td, &L)) == VOXGI_ERR_TOO_LARGE || r == VOXGI_ERR_INVALID_ARGUMENT) {
                fprintf(md, "| %d | %d | refused: %s | | | | | | | | | | |\n", td.n, td.depth, voxgi_last_error(ctx));
                continue;
            }
            if (r != VOXGI_OK) { cli_fail_lib(s, ctx, "line space"); goto done; }
            voxgi_linespace_query(L, &info);
            for (k = 0; k < 2; k++) {
                t = cli_now_ms();
                if (voxgi_linespace_occluded(ctx, L, (voxgi_linespace_mode)k, nrays, rays, occ[k]) != VOXGI_OK) {
                    voxgi_linespace_destroy(ctx, L);
                    cli_fail_lib(s, ctx, "line space rays");
                    goto done;
                }
                ms[k] = cli_now_ms() - t;
            }
            for (q = 0; q < nrays; q++) {
                agree += occ[0][q] == occ[2][q];
                wrong += occ[1][q] && !occ[0][q];
            }
            fprintf(md, "| %d | %d | %.2f | %.0f | %.1f | %.2f | %.3fx | %.4f%% | %.1f | %.2f | %.3fx | %.2f%% |", td.n, td.depth, info.bytes / 1e6, info.ms,
                    ms[0], nrays / ms[0] / 1000, core_ms / ms[0], 100.0 * agree / nrays, ms[1], nrays / ms[1] / 1000, core_ms / ms[1], 100.0 * wrong / nrays);
            fprintf(csv, "rays,%s,%d,%d,%lu,%.3f,1,16,exact,0,0,%.3f,%.3f,,,,,,%.6g,%.6g,%.3f\n", base, td.n, td.depth, (unsigned long)info.bytes, info.ms, ms[0],
                    ms[0], (double)agree / nrays, 0.0, core_ms);
            fprintf(csv, "rays,%s,%d,%d,%lu,%.3f,1,16,fast,3,0,%.3f,%.3f,,,,,,%.6g,%.6g,%.3f\n", base, td.n, td.depth, (unsigned long)info.bytes, info.ms, ms[1],
                    ms[1], 1.0, (double)wrong / nrays, core_ms);
            for (k = 0; k < 4; k++) { /* Table 3: the light's rays alone and in packets */
                static const int counts[4] = {4, 9, 16, 100};
                voxgi_linespace_light_desc d;
                voxgi_linespace_stats st[2];
                int pk;
                memset(&d, 0, sizeof d);
                d.mode = VOXGI_LINESPACE_FAST;
                d.samples = counts[k];
                memcpy(d.corner, M.light, sizeof d.corner);
                memcpy(d.edge_u, M.light + 3, sizeof d.edge_u);
                memcpy(d.edge_v, M.light + 6, sizeof d.edge_v);
                for (pk = 0; pk < 2; pk++) {
                    d.packets = pk;
                    if (voxgi_linespace_light(ctx, L, &d, pixels, pos, nrm, vis, NULL, &st[pk]) != VOXGI_OK) {
                        voxgi_linespace_destroy(ctx, L);
                        cli_fail_lib(s, ctx, "line space light");
                        goto done;
                    }
                    fprintf(csv, "light,%s,%d,%d,%lu,%.3f,1,%d,fast,3,%d,%.3f,%.3f,,,,,,,,\n", base, td.n, td.depth, (unsigned long)info.bytes, info.ms, counts[k], pk,
                            st[pk].ms, st[pk].ms);
                }
                fprintf(md, "%s %.0f / %.0f", k ? "," : "", st[0].ms, st[1].ms);
            }
            fprintf(md, " |\n");
            voxgi_linespace_destroy(ctx, L);
        }
    rc = 0;
done:
    voxgi_ray_scene_destroy(ctx, rs);
    cli_mesh_close(&M.tm);
out:
    free(pos);
    free(nrm);
    free(vis);
    free(rays);
    free(all);
    return rc;
}

/* After the scenes' tables: the rays of each mesh of --meshes (measured here, as they are written). */
static int ls_md_end(report *rep, FILE *md, FILE *csv)
{
    const ls_report *a = (const ls_report *)rep->own;
    char item[1024];
    const char *list;
    int r;
    for (list = a->mesh_list; *a->mesh_list && (r = cli_next_item(&list, item, sizeof item)) != 0;) {
        FILE *f;
        if (r < 0) return cli_usage("report", "--meshes: '%s'", a->mesh_list) != 0;
        if (!(f = fopen(item, "rb"))) {
            fprintf(md, "\n(%s: not found, left out)\n", item);
            continue;
        }
        fclose(f);
        if (ls_mesh(&rep->s, rep->c.vx, a, item, md, csv)) return 1;
    }
    return 0;
}

/* report all's line space: one tree (the tool's: n 4, the scene's depth; quick: depth 2), 1 x 1
   and 2 x 2 points per pixel, 4 and 16 samples, exact and fast (3 leaves exact at each end). */
int report_linespace_all(report_run *run)
{
    static const ls_report all = {.ns = REPORT_L(4), .depths = REPORT_L(0), .samples = REPORT_L(4, 16), .supersample = REPORT_L(1, 2), .ends = REPORT_L(3)},
                           quick = {.ns = REPORT_L(4), .depths = REPORT_L(2), .samples = REPORT_L(4), .supersample = REPORT_L(1, 2), .ends = REPORT_L(3)};
    run->args = run->quick ? &quick : &all;
    return ls_images(run);
}

int cmd_report_linespace(int argc, char **argv)
{
    static const report_def def = {.name = "linespace", .help = ls_help, .bounces = 0, .scenes_optional = 1, .columns = ls_columns,
                                   .ncolumns = CLI_COUNT(ls_columns), .sweep = ls_images, .md_head = ls_md_head, .md_scene = ls_md_scene,
                                   .md_end = ls_md_end};
    ls_report a = {.o = REPORT_OPTS("cornell-box", 128, 1024), .mesh_list = "../shared/meshes/bunny.obj,../shared/meshes/dragon.obj", .ns = REPORT_L(4, 8),
                   .depths = REPORT_L(2, 3), .samples = REPORT_L(4, 16, 64), .supersample = REPORT_L(1, 4), .ends = REPORT_L(3, 12)};
    const cli_option options[] = {
        REPORT_OPT_SCENES(&a.o, "built-in scenes with area lights, comma-separated (default cornell-box;\n'' for none)"),
        {.name = "--meshes", .arg = "LIST", .kind = CLI_STRING, .dst = &a.mesh_list,
         .help = "mesh files, comma-separated (default the bunny and the dragon of\n../shared/meshes, where present; '' for none)"},
        REPORT_OPT_SIZE(&a.o, 4, "N x N pixels (default 128)"),
        REPORT_OPT_SPP(&a.o, 16, "samples per pixel of the converged reference (default 1024)"),
        REPORT_LIST("--ns", a.ns, 2, 0, 16, 1, "children per axis (default 4,8)"),
        REPORT_LIST("--depths", a.depths, 1, 0, 8, 1, "levels below the root (default 2,3)"),
        REPORT_LIST("--samples", a.samples, 1, 0, 4096, 1, "the images' shadow rays per shading point (default 4,16,64)"),
        REPORT_LIST("--supersample", a.supersample, 1, 0, 16, 1, "the images' shading points, K x K per pixel (default 1,4)"),
        REPORT_LIST("--exact-ends", a.ends, 1, 0, 1 << 20, 1, "fast mode's exact zones, leaves' edges at each end (default 3,12)"),
        REPORT_OPT_OUT(&a.o), CLI_OPT_THREADS(&a.o.common)};
    return report_main(&def, &a.o, &a, options, CLI_COUNT(options), argc, argv);
}
