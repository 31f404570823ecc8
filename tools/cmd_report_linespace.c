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

#define LS_MAX 8
#define LS_MAX_ITEMS 16

typedef struct ls_args {
    cli_common common;
    const char *out_dir, *scene_list, *mesh_list;
    double ns[LS_MAX_ITEMS], depths[LS_MAX_ITEMS], samples[LS_MAX_ITEMS], supersample[LS_MAX_ITEMS], ends[LS_MAX_ITEMS];
    int nns, ndepths, nsamples, nsuper, nends, size, spp;
} ls_args;

/* A relative error as a table's cell: "black" where the reference is (the error is relative to
   nothing; the image's mean tells the rest). */
static const char *error_cell(char *cell, size_t size, double e)
{
    if (isfinite(e)) snprintf(cell, size, "%.2f%%", 100 * e);
    else snprintf(cell, size, "black");
    return cell;
}

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

/* The line-space image of scene (its name, seen by cam) for every tree, supersampling, sample count
   and mode of a's lists, against R: a row each into md and csv (when not NULL) and, with run,
   handed to report all. 0, or says why and returns 1. */
static int ls_images(cli_session *s, voxgi_context *ctx, const ls_args *a, const voxgi_scene *scene, const char *name, const voxgi_camera *cam,
                     const cli_reference *R, FILE *md, FILE *csv, report_run *run)
{
    size_t pixels = (size_t)cam->width * (size_t)cam->height, p;
    float *img = (float *)malloc(pixels * 12), *vis[2] = {(float *)malloc(pixels * 4), (float *)malloc(pixels * 4)};
    int i, j, k, m, rc = 1;
    if (!img || !vis[0] || !vis[1]) { cli_fail(s, "out of memory"); goto done; }
    for (i = 0; i < a->nns; i++)
        for (j = 0; j < a->ndepths; j++) {
            voxgi_linespace_desc td;
            voxgi_linespace *L = NULL;
            voxgi_linespace_info info;
            voxgi_result r;
            memset(&td, 0, sizeof td);
            td.n = (int)a->ns[i];
            td.depth = (int)a->depths[j];
            cli_status(s, "%s: line space n %d depth %d", name, td.n, td.depth);
            if ((r = voxgi_linespace_create(ctx, scene, &td, &L)) == VOXGI_ERR_TOO_LARGE || r == VOXGI_ERR_INVALID_ARGUMENT) {
                if (md) fprintf(md, "| %d | %d | - | - | - | refused: %s | | | | | | | |\n", td.n, td.depth, voxgi_last_error(ctx));
                continue;
            }
            if (r != VOXGI_OK) { cli_fail_lib(s, ctx, "line space"); goto done; }
            voxgi_linespace_query(L, &info);
            td.depth = info.depth; /* 0 asked for the scene's */
            for (k = 0; k < a->nsamples * a->nsuper; k++) {
                int ss = (int)a->supersample[k / a->nsamples], spl = (int)a->samples[k % a->nsamples];
                for (m = 0; m <= a->nends; m++) { /* exact, then fast with each exact zone */
                    voxgi_render_desc d;
                    voxgi_render_info li;
                    double err, blk, mean, mae = 0, wrong = 0, ms_gbuffer, ms_shadows, ms_build;
                    float *v = vis[m ? 1 : 0];
                    memset(&d, 0, sizeof d);
                    d.method = VOXGI_RENDER_LINESPACE;
                    d.camera = *cam;
                    d.linespace.ls = L;
                    d.linespace.mode = m ? VOXGI_LINESPACE_FAST : VOXGI_LINESPACE_EXACT;
                    d.linespace.exact_ends = m ? (int)a->ends[m - 1] : 0;
                    d.linespace.samples = spl;      /* >= 1 (--samples) */
                    d.linespace.supersample = ss;   /* >= 1 (--supersample): 1 the pixel's centre */
                    d.linespace.visible = v;
                    d.seed = 1;
                    d.hide_emitters = 1;
                    cli_status(s, "%s: n %d depth %d, %d x %d points, %d samples, %s", name, td.n, td.depth, ss, ss, d.linespace.samples, m ? "fast" : "exact");
                    if ((r = voxgi_render(ctx, scene, &d, img, pixels * 12, &li)) != VOXGI_OK) {
                        voxgi_linespace_destroy(ctx, L);
                        if (r == VOXGI_ERR_UNSUPPORTED && run) { /* no area light */
                            snprintf(run->why, sizeof run->why, "%s", voxgi_last_error(ctx));
                            rc = REPORT_NOT_APPLICABLE;
                        } else cli_fail_lib(s, ctx, "linespace");
                        goto done;
                    }
                    ms_gbuffer = voxgi_render_stage_ms(&li, "gbuffer");
                    ms_shadows = voxgi_render_stage_ms(&li, "shadows");
                    ms_build = voxgi_render_stage_ms(&li, "build");
                    err = cli_masked_error(&R->mask, img, R->image, NULL, NULL);
                    blk = block_error(&R->mask, img, R->image);
                    mean = image_mean(img, 3 * pixels);
                    for (p = 0; m && p < pixels; p++) { /* fast against exact, the same samples */
                        mae += fabs((double)vis[1][p] - vis[0][p]);
                        wrong += (double)vis[0][p] - vis[1][p];
                    }
                    mae /= (double)pixels;
                    wrong /= (double)pixels;
                    if (md) {
                        char e1[32], e2[32];
                        fprintf(md, "| %d | %d | %.2f | %.0f | %d | %d | %d | %s | %.1f | %.1f | %s | %s | %.4g |", td.n, td.depth, info.bytes / 1e6, info.ms,
                                ss * ss, spl, ss * ss * spl, m ? "fast" : "exact", ms_shadows, li.ms - ms_build, error_cell(e1, sizeof e1, err),
                                error_cell(e2, sizeof e2, blk), mean);
                        if (m) fprintf(md, " %d | %.4f | %.2f%% |\n", d.linespace.exact_ends, mae, 100 * wrong);
                        else fprintf(md, " | | |\n");
                    }
                    if (csv)
                        fprintf(csv, "image,%s,%d,%d,%lu,%.3f,%d,%d,%s,%d,0,%.3f,%.3f,%.6g,%.6g,%.6g,%.6g,%.6g,,,\n", name, td.n, td.depth, (unsigned long)info.bytes,
                                info.ms, ss, spl, m ? "fast" : "exact", d.linespace.exact_ends, ms_shadows, li.ms - ms_build, err, blk, mean, mae, wrong);
                    if (run) { /* the tree is built once for every image: its time counts in each */
                        report_item it;
                        memset(&it, 0, sizeof it);
                        it.method = m ? "linespace-fast" : "linespace-exact";
                        snprintf(it.settings, sizeof it.settings, "n %d, depth %d, %d x %d points per pixel, %d samples", td.n, td.depth, ss, ss, spl);
                        if (m) report_append(it.settings, sizeof it.settings, ", exact ends %d", d.linespace.exact_ends);
                        snprintf(it.passes, sizeof it.passes, "tree %.1f, G-buffer %.1f, shadows %.1f", info.ms, ms_gbuffer, ms_shadows);
                        it.ms = li.ms - ms_build + info.ms;
                        it.bytes = (double)info.bytes;
                        it.error = err;
                        run->emit(run, &it, img);
                    }
                }
            }
            voxgi_linespace_destroy(ctx, L);
        }
    rc = 0;
done:
    free(img);
    free(vis[0]);
    free(vis[1]);
    return rc;
}

/* The images of one scene. */
static int ls_scene(cli_session *s, voxgi_context *ctx, const ls_args *a, const char *name, FILE *md, FILE *csv)
{
    voxgi_builtin_scene bs;
    voxgi_camera cam;
    cli_reference R;
    char ref_error[64] = "black";
    int rc = 1;
    memset(&R, 0, sizeof R);
    if (voxgi_builtin_scene_create(ctx, name, &bs) != VOXGI_OK) return cli_fail_lib(s, ctx, name);
    cam = bs.camera;
    cam.width = cam.height = a->size;
    cli_status(s, "%s: the reference's direct light, %d spp", name, a->spp);
    if (cli_reference_make(s, ctx, &bs.scene, &cam, a->spp, 0, 0, &R)) goto done;
    if (isfinite(R.c)) snprintf(ref_error, sizeof ref_error, "its error %.2f%% / sqrt(spp)", 100 * R.c);
    fprintf(md, "\n## %s\n\n%d x %d pixels; the reference's direct light at %d spp (%s); %lu pixels near an emitter left "
                "out. *rel. RMSE*: the tools' rule (*black*: the reference is, and the mean says the rest); *4x4*: on 4 x 4 block means "
                "without a masked pixel. Fast mode against exact, the same samples: "
                "*MAE* of the pixels' visible share, *wrong*: the share of samples fast mode blocks where exact mode sees the light; *exact ends*: fast mode's "
                "exact zone at each end of a ray, in leaves' edges.\n\n",
            name, a->size, a->size, a->spp, ref_error, (unsigned long)R.mask.masked_pixels);
    fprintf(md, "| n | depth | tree MB | build ms | points per pixel | samples | rays per pixel | mode | shadows ms | total ms | rel. RMSE | 4x4 | mean "
                "| exact ends | MAE | wrong |\n|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    rc = ls_images(s, ctx, a, &bs.scene, name, &cam, &R, md, csv, NULL);
done:
    cli_reference_free(&R);
    voxgi_builtin_scene_destroy(ctx, &bs);
    return rc;
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

static int ls_mesh(cli_session *s, voxgi_context *ctx, const ls_args *a, const char *path, FILE *md, FILE *csv)
{
    ls_mesh_scene M;
    size_t pixels = (size_t)a->size * (size_t)a->size, nrays = 0, i;
    float *pos = (float *)malloc(pixels * 12), *nrm = (float *)malloc(pixels * 12), *vis = (float *)malloc(pixels * 4);
    voxgi_ray *rays = (voxgi_ray *)malloc(pixels * 16 * sizeof *rays);
    unsigned char *occ[3];
    voxgi_ray_scene *rs = NULL;
    double core_ms = 0, t;
    int j, k, rc = 1;
    const char *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    occ[0] = (unsigned char *)malloc(pixels * 16);
    occ[1] = (unsigned char *)malloc(pixels * 16);
    occ[2] = (unsigned char *)malloc(pixels * 16);
    if (!pos || !nrm || !vis || !rays || !occ[0] || !occ[1] || !occ[2]) { cli_fail(s, "out of memory"); goto out; }
    if (ls_mesh_open(s, path, a->size, &M)) goto out;
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
            base, (unsigned long)(M.tm.vm.index_count ? M.tm.vm.index_count / 3 : M.tm.vm.vertex_count / 3) + 2, a->size, a->size, (unsigned long)nrays,
            core_ms, nrays / core_ms / 1000);
    fprintf(md, "| n | depth | tree MB | build ms | exact ms | exact M rays/s | vs core | exact = core | fast ms | fast M rays/s | vs core | wrong "
                "| fast light ms: rays alone, packets, at 4 / 9 / 16 / 100 samples |\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
    for (i = 0; i < (size_t)a->nns; i++)
        for (j = 0; j < a->ndepths; j++) {
            voxgi_linespace_desc td;
            voxgi_linespace *L = NULL;
            voxgi_linespace_info info;
            voxgi_result r;
            double ms[2];
            size_t agree = 0, wrong = 0, q;
            memset(&td, 0, sizeof td);
            td.n = (int)a->ns[i];
            td.depth = (int)a->depths[j];
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
    free(occ[0]);
    free(occ[1]);
    free(occ[2]);
    return rc;
}

/* report all's line space: one tree (the tool's: n 4, the scene's depth; quick: depth 2), 1 x 1
   and 2 x 2 points per pixel, 4 and 16 samples, exact and fast (3 leaves exact at each end). */
int report_linespace_all(report_run *run)
{
    ls_args a;
    memset(&a, 0, sizeof a);
    a.ns[0] = 4;
    a.depths[0] = run->quick ? 2 : 0;
    a.samples[0] = 4;
    a.samples[1] = 16;
    a.supersample[0] = 1;
    a.supersample[1] = 2;
    a.ends[0] = 3;
    a.nns = a.ndepths = a.nends = 1;
    a.nsamples = run->quick ? 1 : 2;
    a.nsuper = 2;
    return ls_images(run->s, run->ctx, &a, run->scene, run->scene_name, &run->camera, run->R, NULL, NULL, run);
}

int cmd_report_linespace(int argc, char **argv)
{
    static const double ns[] = {4, 8}, depths[] = {2, 3}, samples[] = {4, 16, 64}, supersample[] = {1, 4}, ends[] = {3, 12};
    ls_args a;
    cli_session s;
    cli_context c;
    char item[1024], path[1100];
    const char *list;
    FILE *md = NULL, *csv = NULL;
    voxgi_info ci;
    int r, rc;
    memset(&a, 0, sizeof a);
    a.common.backend = VOXGI_BACKEND_CPU;
    a.out_dir = "build/report";
    a.scene_list = "cornell-box";
    a.mesh_list = "../shared/meshes/bunny.obj,../shared/meshes/dragon.obj";
    a.size = 128;
    a.spp = 1024;
    memcpy(a.ns, ns, sizeof ns);
    memcpy(a.depths, depths, sizeof depths);
    memcpy(a.samples, samples, sizeof samples);
    memcpy(a.supersample, supersample, sizeof supersample);
    memcpy(a.ends, ends, sizeof ends);
    a.nends = 2;
    a.nsuper = 2;
    a.nns = 2;
    a.ndepths = 2;
    a.nsamples = 3;
    {
#define LIST(opt, field, count, lo_, top, text) \
    {.name = opt, .arg = "LIST", .kind = CLI_NUMBERS, .dst = a.field, .items = &a.count, .min_items = 1, .max_items = LS_MAX_ITEMS, \
     .lo = lo_, .hi = top, .whole = 1, .help = text}
        const cli_option options[] = {
            {.name = "--scenes", .arg = "LIST", .kind = CLI_STRING, .dst = &a.scene_list,
             .help = "built-in scenes with area lights, comma-separated (default cornell-box;\n'' for none)"},
            {.name = "--meshes", .arg = "LIST", .kind = CLI_STRING, .dst = &a.mesh_list,
             .help = "mesh files, comma-separated (default the bunny and the dragon of\n../shared/meshes, where present; '' for none)"},
            {.name = "--size", .arg = "N", .kind = CLI_INT, .dst = &a.size, .lo = 4, .hi = 4096, .help = "N x N pixels (default 128)"},
            {.name = "--spp", .arg = "S", .kind = CLI_INT, .dst = &a.spp, .lo = 16, .hi = 1 << 20,
             .help = "samples per pixel of the converged reference (default 1024)"},
            LIST("--ns", ns, nns, 2, 16, "children per axis (default 4,8)"),
            LIST("--depths", depths, ndepths, 1, 8, "levels below the root (default 2,3)"),
            LIST("--samples", samples, nsamples, 1, 4096, "the images' shadow rays per shading point (default 4,16,64)"),
            LIST("--supersample", supersample, nsuper, 1, 16, "the images' shading points, K x K per pixel (default 1,4)"),
            LIST("--exact-ends", ends, nends, 1, 1 << 20, "fast mode's exact zones, leaves' edges at each end (default 3,12)"),
            {.name = "--out", .arg = "DIR", .kind = CLI_STRING, .dst = &a.out_dir, .help = "where the files go (default build/report)"},
            CLI_OPT_THREADS(&a.common)};
#undef LIST
        const cli_command cmd = {.name = "report linespace", .help = ls_help, .column = 27, .options = options, .option_count = CLI_COUNT(options)};
        if ((rc = cli_parse(&cmd, argc, argv)) != CLI_CONTINUE) return rc;
    }
    cli_session_init(&s, "report");
    if (cli_context_open_options(&s, &c, &a.common)) return CLI_EXIT_FAILURE;
    rc = CLI_EXIT_FAILURE;
    snprintf(path, sizeof path, "%s/linespace.md", a.out_dir);
    if (cli_make_dirs(a.out_dir) != 0 || !(md = fopen(path, "w"))) {
        cli_fail(&s, "cannot write %s", path);
        goto done;
    }
    snprintf(path, sizeof path, "%s/linespace.csv", a.out_dir);
    if (!(csv = fopen(path, "w"))) {
        cli_fail(&s, "cannot write %s", path);
        goto done;
    }
    voxgi_query_info(c.vx, &ci);
    fprintf(md, "# Line space: soft shadows, error against run time\n\nCPU, %d threads; wall clock on this machine.\n", ci.thread_count);
    fprintf(csv, "part,scene,n,depth,bytes,build_ms,supersample,samples,mode,exact_ends,packets,shadows_ms,ms,rel_rmse,block_rmse,mean,mae,wrong,agree_with_core,core_ms\n");
    for (list = a.scene_list; *a.scene_list && (r = cli_next_item(&list, item, sizeof item)) != 0;) { /* '' : none */
        if (r < 0) { cli_usage("report", "--scenes: '%s'", a.scene_list); goto done; }
        if (ls_scene(&s, c.vx, &a, item, md, csv)) goto done;
    }
    for (list = a.mesh_list; *a.mesh_list && (r = cli_next_item(&list, item, sizeof item)) != 0;) {
        FILE *f;
        if (r < 0) { cli_usage("report", "--meshes: '%s'", a.mesh_list); goto done; }
        if (!(f = fopen(item, "rb"))) { fprintf(md, "\n(%s: not found, left out)\n", item); continue; }
        fclose(f);
        if (ls_mesh(&s, c.vx, &a, item, md, csv)) goto done;
    }
    if (ferror(md) || ferror(csv)) { cli_fail(&s, "cannot write to %s", a.out_dir); goto done; }
    cli_status_clear(&s);
    printf("wrote %s/linespace.md, %s/linespace.csv\n", a.out_dir, a.out_dir);
    rc = CLI_EXIT_OK;
done:
    if (md) fclose(md);
    if (csv) fclose(csv);
    cli_context_close(&s, &c);
    return rc;
}
