/* tools/cmd_render.c - voxgi render: an image of a built-in scene or a mesh, path-traced or cone-traced. */
#include "cli.h"
#include "image_io.h"
#include <stdlib.h>
#include <string.h>

static const char *const render_methods[] = {"reference", "vct", "tsm", "rsm", "sh", "ssao", "vao", "ssgi", "hybrid", "linespace", NULL};
enum { METHOD_REFERENCE, METHOD_VCT, METHOD_TSM, METHOD_RSM, METHOD_SH, METHOD_SSAO, METHOD_VAO, METHOD_SSGI, METHOD_HYBRID, METHOD_LINESPACE };
static const char *const ls_mode_names[] = {"exact", "fast", NULL}; /* voxgi_linespace_mode's order */
static const char *const visibility_names[] = {"hierarchical", "dda", "none", NULL}; /* voxgi_visibility's order */
static const char *const off_on_names[] = {"off", "on", NULL};

/* The screen passes' defaults, from `voxgi report ao` and `voxgi report ssgi` on the Cornell box
   (docs/screen-space.md): ambient occlusion at full resolution, its sharp bands along the edges
   blurred little; one bounce at half resolution, blurred more, Hybrid-GI with its hidden light. */
enum { AO_BLUR = 2, GI_BLUR = 8, GI_HALF_RES = 1, HYBRID_HIDDEN_LIGHT = 1 };

/* The line space's defaults, from `voxgi report linespace` (docs/line-space.md). */
enum { LS_MODE = VOXGI_LINESPACE_EXACT, LS_N = 4, LS_SAMPLES = 4, LS_SUPERSAMPLE = 2 }; /* the depth: the library's, from the scene */

static const char *const render_help =
    "usage: voxgi render SCENE|MESH [options] -o OUT.png|OUT.pfm\n"
    "Renders a built-in scene (cornell-box, rsm-walls, leak-box, furnace, leak-room, foliage) or a mesh\n"
    "file (OBJ+MTL: Kd is the albedo, Ke the emitted radiance) with the reference path tracer on\n"
    "the CPU. A PFM pixel is the mean linear radiance over the pixel's square; a PNG is that\n"
    "times --exposure, clamped and sRGB encoded. --compare's error: the relative RMSE over the\n"
    "pixels farther than 3 pixels from any pixel whose centre sees an emitter, both images\n"
    "without the emission the camera sees.\n";

typedef struct render_args {
    cli_common common;
    const char *what, *out, *cornell_mesh, *reference;
    int method, res, cones, anisotropic, no_gi, inject_samples, compare, bounces, spp, spp_given, seed, size[2], cone_stride;
    int bounce_cones, bounce_block, isotropic;
    int octree, octree_format, bricks, have_camera, have_sun, tsm_size, slices, rsm_size, rsm_samples, rsm_points, gather_stride, visibility, res_given;
    double step, camera[7], sun[4], exposure, sigma, rsm_radius, opening, ao_radius, radius;
    int rays, march_steps, point_sampling, half_res, half_res_given, blur, blur_given, screen_light_only, hidden_light, hidden_light_given;
    int ls_mode, ls_mode_given, ls_n, ls_depth, ls_budget, samples, packets, supersample, exact_ends;
} render_args;

/* What is rendered: a built-in scene or a mesh, the camera, and the scene's lights plus --sun. */
typedef struct render_scene {
    const char *name;             /* in what is printed */
    voxgi_builtin_scene bs;
    cli_mesh tm;
    cli_cornell_mesh cm;
    voxgi_scene with_sun;
    voxgi_light *lights;
    const voxgi_scene *scene;
} render_scene;

/* The view of a mesh: its bounds' centre from behind and a little above. */
static void mesh_camera(const cli_mesh *tm, voxgi_camera *cam)
{
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    size_t v;
    double c[3], r = 0;
    int a;
    for (v = 0; v < tm->vm.vertex_count; v++)
        for (a = 0; a < 3; a++) { lo[a] = fminf(lo[a], tm->vm.positions[3 * v + a]); hi[a] = fmaxf(hi[a], tm->vm.positions[3 * v + a]); }
    for (a = 0; a < 3; a++) { c[a] = 0.5 * ((double)lo[a] + hi[a]); r = fmax(r, 0.5 * ((double)hi[a] - lo[a])); }
    cam->eye[0] = c[0]; cam->eye[1] = c[1] + 0.6 * r; cam->eye[2] = c[2] - 3.2 * r;
    memcpy(cam->target, c, sizeof c);
    cam->fovy_degrees = 40;
}

/* Sets up rs and the camera d->camera; 0, or says why and returns 1. */
static int scene_open(cli_session *s, voxgi_context *ctx, const render_args *a, render_scene *rs, voxgi_reference_desc *d)
{
    int i;
    rs->name = a->what;
    if (a->cornell_mesh) { /* the Cornell box with the mesh for its tall block */
        if (cli_cornell_mesh_open(s, ctx, a->cornell_mesh, &rs->cm)) return CLI_EXIT_FAILURE;
        rs->scene = &rs->cm.scene;
        rs->name = rs->cm.name;
        d->camera = rs->cm.bs.camera;
    } else if (strchr(a->what, '.') == NULL && strncmp(a->what, "builtin:", 8) != 0) { /* a built-in scene */
        if (voxgi_builtin_scene_create(ctx, a->what, &rs->bs) != VOXGI_OK) return cli_fail_lib(s, ctx, NULL);
        rs->scene = &rs->bs.scene;
        d->camera = rs->bs.camera;
    } else {
        if (cli_mesh_open(s, a->what, &rs->tm)) return CLI_EXIT_FAILURE;
        rs->scene = &rs->tm.scene;
        mesh_camera(&rs->tm, &d->camera);
    }
    if (a->have_camera) {
        memcpy(d->camera.eye, a->camera, 3 * sizeof(double));
        memcpy(d->camera.target, a->camera + 3, 3 * sizeof(double));
        d->camera.fovy_degrees = a->camera[6];
    }
    d->camera.width = a->size[0];
    d->camera.height = a->size[1];
    if (a->have_sun) { /* the scene's lights and one more */
        const voxgi_scene *scene = rs->scene;
        rs->with_sun = *scene;
        rs->lights = (voxgi_light *)calloc(scene->light_count + 1, sizeof *rs->lights);
        if (!rs->lights) return cli_fail(s, "out of memory");
        if (scene->light_count) memcpy(rs->lights, scene->lights, scene->light_count * sizeof *rs->lights);
        rs->lights[scene->light_count].type = VOXGI_LIGHT_DIRECTIONAL;
        for (i = 0; i < 3; i++) {
            rs->lights[scene->light_count].direction[i] = (float)a->sun[i];
            rs->lights[scene->light_count].intensity[i] = (float)a->sun[3];
        }
        rs->with_sun.lights = rs->lights;
        rs->with_sun.light_count = scene->light_count + 1;
        rs->scene = &rs->with_sun;
    }
    return 0;
}

static void scene_close(voxgi_context *ctx, render_scene *rs)
{
    free(rs->lights);
    voxgi_builtin_scene_destroy(ctx, &rs->bs);
    if (rs->tm.name[0]) cli_mesh_close(&rs->tm);
    if (rs->cm.name[0]) cli_cornell_mesh_close(ctx, &rs->cm);
}

/* Every method's settings and what it reports (the chosen method's alone are used). */
typedef struct render_jobs {
    voxgi_reference_desc d;
    voxgi_reference_info info;
    voxgi_vct_desc vd;
    voxgi_vct_info vinfo;
    voxgi_tsm_image_desc td;
    voxgi_tsm_image_info tinfo;
    voxgi_rsm_image_desc qd;
    voxgi_rsm_image_info qinfo;
    voxgi_sh_image_desc hd;
    voxgi_sh_image_info hinfo;
    voxgi_ao_image_desc ad;
    voxgi_ao_image_info ainfo;
    voxgi_ssgi_image_desc gd;
    voxgi_ssgi_image_info ginfo;
    voxgi_linespace_image_desc ld;
    voxgi_linespace_image_info linfo;
} render_jobs;

/* The image of `method` with J's settings into rgb (bytes), its report into J. */
static voxgi_result render_method(voxgi_context *ctx, int method, const voxgi_scene *scene, render_jobs *J, float *rgb, size_t bytes)
{
    switch (method) {
    case METHOD_VCT: return voxgi_vct_render(ctx, scene, &J->vd, rgb, bytes, &J->vinfo);
    case METHOD_TSM: return voxgi_tsm_render(ctx, scene, &J->td, rgb, bytes, &J->tinfo);
    case METHOD_RSM: return voxgi_rsm_render(ctx, scene, &J->qd, rgb, bytes, &J->qinfo);
    case METHOD_SH: return voxgi_sh_render(ctx, scene, &J->hd, rgb, bytes, &J->hinfo);
    case METHOD_SSAO:
    case METHOD_VAO: return voxgi_ao_render(ctx, scene, &J->ad, rgb, bytes, &J->ainfo);
    case METHOD_SSGI:
    case METHOD_HYBRID: return voxgi_ssgi_render(ctx, scene, &J->gd, rgb, bytes, &J->ginfo);
    case METHOD_LINESPACE: return voxgi_linespace_render(ctx, scene, &J->ld, rgb, bytes, NULL, &J->linfo);
    default: return voxgi_reference_render(ctx, scene, &J->d, rgb, bytes, &J->info);
    }
}

/* What --compare measured. */
typedef struct render_compare {
    double rmse;                  /* NaN: nothing to relate to (a black reference, or every pixel masked) */
    double rms, ref_ms;
    size_t masked, pixels;        /* pixels left out of the error, of all */
} render_compare;

/* --compare: the relative RMSE of the lighting against the reference with `compare` spp (rendered
   with an independent seed) by the tools' one rule (cli_masked_error): both without the emission
   the camera sees, and the pixels within 3 of one whose centre sees an emitter left out (the
   noise at the emitters' edges would swamp the lighting). */
static int compare_with_reference(cli_session *s, voxgi_context *ctx, const render_args *a, const voxgi_scene *scene, const render_jobs *J,
                                  render_compare *cmp)
{
    size_t n = (size_t)a->size[0] * (size_t)a->size[1] * 3;
    float *ref = (float *)malloc(n * 8), *mine = ref ? ref + n : NULL;
    render_jobs hidden = *J, reference = *J;
    voxgi_result r;
    cli_error_mask mask;
    reference.d.samples = a->compare;
    reference.d.seed = J->d.seed + 1000003; /* independent of the image's own noise */
    reference.d.hide_emitters = hidden.d.hide_emitters = hidden.vd.hide_emitters = hidden.td.hide_emitters = hidden.qd.hide_emitters =
        hidden.hd.hide_emitters = hidden.gd.hide_emitters = hidden.ld.hide_emitters = 1;
    r = ref ? render_method(ctx, METHOD_REFERENCE, scene, &reference, ref, n * 4) : VOXGI_ERR_OUT_OF_MEMORY;
    if (r == VOXGI_OK) r = render_method(ctx, a->method, scene, &hidden, mine, n * 4);
    if (r != VOXGI_OK) {
        free(ref);
        return ref ? cli_fail_lib(s, ctx, "the reference") : cli_fail(s, "the reference: out of memory");
    }
    if (cli_error_mask_make(s, ctx, scene, &J->d.camera, &mask)) {
        free(ref);
        return CLI_EXIT_FAILURE;
    }
    cmp->rmse = cli_masked_error(&mask, mine, ref, &cmp->rms, NULL); /* a black reference (the leak box): NaN, the RMS says it */
    cmp->masked = mask.masked_pixels;
    cmp->pixels = (size_t)a->size[0] * (size_t)a->size[1];
    cmp->ref_ms = reference.info.ms_bvh + reference.info.ms_render;
    cli_error_mask_free(&mask);
    free(ref);
    return 0;
}

/* --reference: the same error against an image the caller rendered before (a converged reference
   of the same view and size, e.g. `voxgi render SCENE --spp 4096 -o ref.pfm`). Both images hold
   the emission the camera sees, which the mask leaves out with its ring. */
static int compare_with_file(cli_session *s, voxgi_context *ctx, const render_args *a, const voxgi_scene *scene, const voxgi_camera *camera,
                             const float *mine, render_compare *cmp)
{
    float *ref = NULL;
    int w = 0, h = 0;
    cli_error_mask mask;
    char err[600];
    if (vxt_read_pfm(a->reference, &ref, &w, &h, err, sizeof err)) return cli_fail(s, "--reference %s", err);
    if (w != a->size[0] || h != a->size[1]) {
        free(ref);
        return cli_fail(s, "--reference %s is %d x %d, the image %d x %d (render it with the same --size and view)", a->reference, w, h, a->size[0],
                        a->size[1]);
    }
    if (cli_error_mask_make(s, ctx, scene, camera, &mask)) {
        free(ref);
        return CLI_EXIT_FAILURE;
    }
    cmp->rmse = cli_masked_error(&mask, mine, ref, &cmp->rms, NULL);
    cmp->masked = mask.masked_pixels;
    cmp->pixels = (size_t)w * (size_t)h;
    cmp->ref_ms = 0;
    cli_error_mask_free(&mask);
    free(ref);
    return 0;
}

/* The --compare (or --reference) line of the text output. */
static void print_compare(const render_args *a, const voxgi_reference_desc *d, const render_compare *cmp)
{
    if (a->reference) printf("against %s: ", a->reference);
    else if (d->ao_radius > 0) printf("against the reference (ambient occlusion within %.4g, %d spp, %.1f ms): ", (double)d->ao_radius, a->compare, cmp->ref_ms);
    else printf("against the reference (%d bounce%s, %d spp, %.1f ms): ", d->bounces, d->bounces == 1 ? "" : "s", a->compare, cmp->ref_ms);
    if (cmp->masked == cmp->pixels) {
        printf("no error measured: all %lu pixels are within %d of one that sees an emitter\n", (unsigned long)cmp->pixels, CLI_EMITTER_MARGIN);
        return;
    }
    if (isfinite(cmp->rmse)) printf("relative RMSE %.2f%%", 100 * cmp->rmse);
    else printf("the reference is black, RMS difference %.4g", cmp->rms);
    printf(" (%lu of %lu pixels, those within %d of one that sees an emitter, left out)\n", (unsigned long)cmp->masked, (unsigned long)cmp->pixels,
           CLI_EMITTER_MARGIN);
}

/* The --compare fields of the JSON output (rel_rmse null without a relative error). */
static void print_compare_json(const render_compare *cmp)
{
    if (isfinite(cmp->rmse)) printf("\"rel_rmse\":%.6g,", cmp->rmse);
    else printf("\"rel_rmse\":null,");
    if (isfinite(cmp->rms)) printf("\"rms\":%.6g,", cmp->rms);
    else printf("\"rms\":null,");
    printf("\"masked_pixels\":%lu,\"reference_ms\":%.3f,", (unsigned long)cmp->masked, cmp->ref_ms);
}

/* The --method tsm lines, text or JSON. */
static void print_tsm(const render_args *a, const char *name, const double mean[3], const voxgi_tsm_image_desc *td, const voxgi_tsm_image_info *ti,
                      const voxgi_reference_desc *d, const render_compare *cmp)
{
    int w = a->size[0], h = a->size[1], size = td->tsm.size ? td->tsm.size : 512, slices = td->tsm.slices ? td->tsm.slices : 64;
    if (a->common.json) {
        printf("{\"scene\":\"%s\",\"method\":\"tsm\",\"size\":[%d,%d],\"spp\":%d,\"maps\":%d,\"map_size\":%d,\"slices\":%d,\"sigma\":%.6g,"
               "\"map_bytes\":%lu,\"maps_ms\":%.3f,\"shade_ms\":%.3f,\"ms\":%.3f,\"mean\":[%.6g,%.6g,%.6g],",
               name, w, h, td->samples, ti->maps, size, slices, (double)td->tsm.sigma, (unsigned long)ti->bytes, ti->ms_maps, ti->ms_shade, ti->ms, mean[0],
               mean[1], mean[2]);
        if (a->compare || a->reference) print_compare_json(cmp);
        printf("\"output\":\"%s\"}\n", a->out);
        return;
    }
    printf("%s: %d x %d, direct light with transmittance shadow maps (%d map%s of %d x %d texels, %d slices, %.1f MB): maps %.1f ms, "
           "shading %.1f ms (%d rays per pixel), total %.1f ms; mean radiance %.4g %.4g %.4g -> %s\n",
           name, w, h, ti->maps, ti->maps == 1 ? "" : "s", size, size, slices, ti->bytes / 1e6, ti->ms_maps, ti->ms_shade, td->samples, ti->ms, mean[0],
           mean[1], mean[2], a->out);
    if (a->compare || a->reference) print_compare(a, d, cmp);
}

/* The --method rsm lines, text or JSON. */
static void print_rsm(const render_args *a, const char *name, const double mean[3], const voxgi_rsm_image_desc *qd, const voxgi_rsm_image_info *qi,
                      const voxgi_reference_desc *d, const render_compare *cmp)
{
    int w = a->size[0], h = a->size[1], size = qd->rsm.size ? qd->rsm.size : 256, samples = qd->rsm.samples ? qd->rsm.samples : 100;
    if (a->common.json) {
        printf("{\"scene\":\"%s\",\"method\":\"rsm\",\"size\":[%d,%d],\"maps\":%d,\"map_size\":%d,\"samples\":%d,\"visibility\":\"%s\",\"res\":%d,"
               "\"gather_stride\":%d,\"gathered\":%lu,\"maps_ms\":%.3f,\"voxels_ms\":%.3f,\"direct_ms\":%.3f,\"gather_ms\":%.3f,\"ms\":%.3f,"
               "\"mean\":[%.6g,%.6g,%.6g],",
               name, w, h, qi->maps, size, samples, visibility_names[qd->visibility], qd->resolution ? qd->resolution : 64,
               qd->gather_stride ? qd->gather_stride : 4, (unsigned long)qi->gathered, qi->ms_maps, qi->ms_voxels, qi->ms_direct, qi->ms_gather, qi->ms,
               mean[0], mean[1], mean[2]);
        if (a->compare || a->reference) print_compare_json(cmp);
        printf("\"output\":\"%s\"}\n", a->out);
        return;
    }
    printf("%s: %d x %d, direct light and one bounce from reflective shadow maps (%d map%s of %d x %d texels, %d samples, visibility %s, "
           "%lu pixels gathering): maps %.1f ms, voxels %.1f ms, direct light %.1f ms, gathers %.1f ms, total %.1f ms; mean radiance %.4g %.4g %.4g -> %s\n",
           name, w, h, qi->maps, qi->maps == 1 ? "" : "s", size, size, samples, visibility_names[qd->visibility], (unsigned long)qi->gathered, qi->ms_maps,
           qi->ms_voxels, qi->ms_direct, qi->ms_gather, qi->ms, mean[0], mean[1], mean[2], a->out);
    if (a->compare || a->reference) print_compare(a, d, cmp);
}

/* The --method ssao and vao lines, text or JSON. */
static void print_ao(const render_args *a, const char *name, const double mean[3], const voxgi_ao_image_desc *ad, const voxgi_ao_image_info *ai,
                     const voxgi_reference_desc *d, const render_compare *cmp)
{
    int w = a->size[0], h = a->size[1], rays = ad->rays ? ad->rays : 16, steps = ad->steps ? ad->steps : 16;
    const char *method = ad->method == VOXGI_AO_VOXELS ? "vao" : "ssao";
    if (a->common.json) {
        printf("{\"scene\":\"%s\",\"method\":\"%s\",\"size\":[%d,%d],\"radius\":%.6g,\"rays\":%d,\"steps\":%d,\"point_sampling\":%d,\"res\":%d,"
               "\"gbuffer_ms\":%.3f,\"voxels_ms\":%.3f,\"ao_ms\":%.3f,\"ms\":%.3f,\"mean\":%.6g,",
               name, method, w, h, (double)ai->radius, rays, steps, ad->point_sampling, ad->resolution ? ad->resolution : 128, ai->ms_gbuffer, ai->ms_voxels, ai->ms_ao, ai->ms,
               mean[0]);
        if (a->compare || a->reference) print_compare_json(cmp);
        printf("\"output\":\"%s\"}\n", a->out);
        return;
    }
    printf("%s: %d x %d, ambient occlusion from %s (radius %.4g, %d %s%s): G-buffer %.1f ms, voxels %.1f ms, occlusion %.1f ms, total %.1f ms; "
           "mean %.4g -> %s\n",
           name, w, h, ad->method == VOXGI_AO_VOXELS ? "the voxels" : "the depth buffer", (double)ai->radius, rays, ad->point_sampling ? "points" : "rays",
           ad->method == VOXGI_AO_VOXELS || ad->point_sampling ? "" : " marched in steps", ai->ms_gbuffer, ai->ms_voxels, ai->ms_ao, ai->ms, mean[0], a->out);
    if (a->compare || a->reference) print_compare(a, d, cmp);
}

/* The --method ssgi and hybrid lines, text or JSON. */
static void print_ssgi(const render_args *a, const char *name, const double mean[3], const voxgi_ssgi_image_desc *gd, const voxgi_ssgi_image_info *gi,
                       const voxgi_reference_desc *d, const render_compare *cmp)
{
    int w = a->size[0], h = a->size[1], rays = gd->rays ? gd->rays : 16, steps = gd->steps ? gd->steps : 16;
    const char *method = gd->method == VOXGI_AO_VOXELS ? "hybrid" : "ssgi";
    if (a->common.json) {
        printf("{\"scene\":\"%s\",\"method\":\"%s\",\"size\":[%d,%d],\"radius\":%.6g,\"rays\":%d,\"steps\":%d,\"half_res\":%d,\"blur\":%d,"
               "\"hidden_light\":%d,\"gathered\":%lu,\"direct_ms\":%.3f,\"voxels_ms\":%.3f,\"inject_ms\":%.3f,\"gather_ms\":%.3f,\"ms\":%.3f,"
               "\"mean\":[%.6g,%.6g,%.6g],",
               name, method, w, h, (double)gi->radius, rays, steps, gd->half_resolution, gd->blur, gd->hidden_light, (unsigned long)gi->gathered, gi->ms_direct,
               gi->ms_voxels, gi->ms_inject, gi->ms_gather, gi->ms, mean[0], mean[1], mean[2]);
        if (a->compare || a->reference) print_compare_json(cmp);
        printf("\"output\":\"%s\"}\n", a->out);
        return;
    }
    printf("%s: %d x %d, direct light and one bounce from the screen, visibility %s%s (radius %.4g, %d rays, %lu pixels gathering%s, blur %d): "
           "direct light %.1f ms, voxels %.1f ms, their light %.1f ms, gathers %.1f ms, total %.1f ms; mean radiance %.4g %.4g %.4g -> %s\n",
           name, w, h, gd->method == VOXGI_AO_VOXELS ? "through the voxels (Hybrid-GI)" : "through the depth buffer (SSGI)",
           gd->hidden_light ? ", hidden hits sending the voxels' light" : "", (double)gi->radius, rays, (unsigned long)gi->gathered,
           gd->half_resolution ? " at half resolution" : "", gd->blur, gi->ms_direct, gi->ms_voxels, gi->ms_inject, gi->ms_gather, gi->ms, mean[0], mean[1], mean[2],
           a->out);
    if (a->compare || a->reference) print_compare(a, d, cmp);
}

/* The --method sh lines, text or JSON. */
static void print_sh(const render_args *a, const char *name, const double mean[3], const voxgi_sh_image_desc *hd, const voxgi_sh_image_info *hi,
                     const voxgi_reference_desc *d, const render_compare *cmp)
{
    int w = a->size[0], h = a->size[1], res = hd->resolution ? hd->resolution : 64, stride = hd->gather_stride ? hd->gather_stride : 4;
    double opening = hd->opening > 0 ? hd->opening : 0.5;
    if (a->common.json) {
        printf("{\"scene\":\"%s\",\"method\":\"sh\",\"size\":[%d,%d],\"res\":%d,\"opening\":%.6g,\"visibility\":\"%s\",\"gather_stride\":%d,"
               "\"gathered\":%lu,\"sh_ms\":%.3f,\"voxels_ms\":%.3f,\"direct_ms\":%.3f,\"gather_ms\":%.3f,\"ms\":%.3f,\"mean\":[%.6g,%.6g,%.6g],",
               name, w, h, res, opening, visibility_names[hd->visibility], stride, (unsigned long)hi->gathered, hi->ms_sh, hi->ms_voxels, hi->ms_direct,
               hi->ms_gather, hi->ms, mean[0], mean[1], mean[2]);
        if (a->compare || a->reference) print_compare_json(cmp);
        printf("\"output\":\"%s\"}\n", a->out);
        return;
    }
    printf("%s: %d x %d, direct light and one bounce from an SH volume (%d voxels across, opening %.2g, visibility %s, %lu pixels gathering): "
           "SH volume %.1f ms, voxels %.1f ms, direct light %.1f ms, gathers %.1f ms, total %.1f ms; mean radiance %.4g %.4g %.4g -> %s\n",
           name, w, h, res, opening, visibility_names[hd->visibility], (unsigned long)hi->gathered, hi->ms_sh, hi->ms_voxels, hi->ms_direct, hi->ms_gather,
           hi->ms, mean[0], mean[1], mean[2], a->out);
    if (a->compare || a->reference) print_compare(a, d, cmp);
}

/* The --method linespace lines, text or JSON. */
static void print_linespace(const render_args *a, const char *name, const voxgi_info *ci, const double mean[3], const voxgi_linespace_image_desc *ld,
                            const voxgi_linespace_image_info *li, const voxgi_reference_desc *d, const render_compare *cmp)
{
    int w = a->size[0], h = a->size[1];
    const voxgi_linespace_info *t = &li->tree;
    const voxgi_linespace_stats *r = &li->rays;
    double mrays = li->ms_shadows > 0 ? (double)r->rays / li->ms_shadows / 1000 : 0;
    if (a->common.json) {
        printf("{\"scene\":\"%s\",\"method\":\"linespace\",\"backend\":\"%s\",\"size\":[%d,%d],\"mode\":\"%s\",\"packets\":%d,\"n\":%d,\"depth\":%d,\"samples\":%d,\"supersample\":%d,"
               "\"lights\":%d,\"nodes\":%lu,\"line_spaces\":%lu,\"leaves\":%lu,\"triangle_refs\":%lu,\"bytes\":%lu,\"allocated\":%lu,"
               "\"rays\":%llu,\"nodes_entered\":%llu,\"bits_read\":%llu,\"triangle_tests\":%llu,\"build_ms\":%.3f,\"gbuffer_ms\":%.3f,"
               "\"shadows_ms\":%.3f,\"ms\":%.3f,\"mrays_per_s\":%.4g,\"mean\":[%.6g,%.6g,%.6g],",
               name, voxgi_backend_name(ci->backend), w, h, ls_mode_names[ld->mode], ld->packets, t->n, t->depth, r->samples, ld->supersample, li->lights, (unsigned long)t->nodes, (unsigned long)t->line_spaces,
               (unsigned long)t->leaves, (unsigned long)t->triangle_refs, (unsigned long)t->bytes, (unsigned long)t->allocated, (unsigned long long)r->rays,
               (unsigned long long)r->nodes, (unsigned long long)r->bits, (unsigned long long)r->triangle_tests, li->ms_build, li->ms_gbuffer, li->ms_shadows,
               li->ms, mrays, mean[0], mean[1], mean[2]);
        if (a->compare || a->reference) print_compare_json(cmp);
        printf("\"output\":\"%s\"}\n", a->out);
        return;
    }
    printf("%s: %d x %d, direct light of %d area light%s, soft shadows through the line space (%s mode, %s; n %d, depth %d, %d x %d points "
           "per pixel, %d samples per point and light): tree %lu nodes, %lu line spaces, %lu leaves, %lu triangle references, %.2f MB by the formula, %.2f MB allocated, "
           "built in %.1f ms; G-buffer %.1f ms; %llu shadow rays in %.1f ms (%.2f Mrays/s, %s) reading %llu bits, testing %llu triangles; "
           "total %.1f ms; mean radiance %.4g %.4g %.4g -> %s\n",
           name, w, h, li->lights, li->lights == 1 ? "" : "s", ls_mode_names[ld->mode],
           ld->packets && ci->backend != VOXGI_BACKEND_GL ? "packets" : "rays alone", t->n, t->depth, ld->supersample, ld->supersample, r->samples,
           (unsigned long)t->nodes, (unsigned long)t->line_spaces, (unsigned long)t->leaves, (unsigned long)t->triangle_refs, t->bytes / 1e6,
           t->allocated / 1e6, li->ms_build, li->ms_gbuffer, (unsigned long long)r->rays, li->ms_shadows, mrays, voxgi_backend_name(ci->backend), (unsigned long long)r->bits,
           (unsigned long long)r->triangle_tests, li->ms, mean[0], mean[1], mean[2], a->out);
    if (a->compare || a->reference) print_compare(a, d, cmp);
}

static void print_result(const render_args *a, const char *name, const voxgi_info *ci, const float *rgb, const render_jobs *J, const render_compare *cmp)
{
    const voxgi_reference_desc *d = &J->d;
    const voxgi_reference_info *info = &J->info;
    const voxgi_vct_desc *vd = &J->vd;
    const voxgi_vct_info *vinfo = &J->vinfo;
    double mean[3] = {0, 0, 0};
    size_t p;
    int i, w = a->size[0], h = a->size[1];
    for (p = 0; p < (size_t)w * (size_t)h; p++)
        for (i = 0; i < 3; i++) mean[i] += rgb[3 * p + (size_t)i];
    for (i = 0; i < 3; i++) mean[i] /= (double)w * h;
    if (a->method == METHOD_TSM) print_tsm(a, name, mean, &J->td, &J->tinfo, d, cmp);
    else if (a->method == METHOD_RSM) print_rsm(a, name, mean, &J->qd, &J->qinfo, d, cmp);
    else if (a->method == METHOD_SH) print_sh(a, name, mean, &J->hd, &J->hinfo, d, cmp);
    else if (a->method == METHOD_SSAO || a->method == METHOD_VAO) print_ao(a, name, mean, &J->ad, &J->ainfo, d, cmp);
    else if (a->method == METHOD_SSGI || a->method == METHOD_HYBRID) print_ssgi(a, name, mean, &J->gd, &J->ginfo, d, cmp);
    else if (a->method == METHOD_LINESPACE) print_linespace(a, name, ci, mean, &J->ld, &J->linfo, d, cmp);
    else if (a->method == METHOD_VCT && a->common.json) {
        printf("{\"scene\":\"%s\",\"method\":\"vct\",\"backend\":\"%s\",\"size\":[%d,%d],\"res\":%d,\"cones\":%d,\"gi\":%d,\"voxels\":%llu,\"voxelize_ms\":%.3f,"
               "\"inject_ms\":%.3f,\"octree_ms\":%.3f,\"radiance_bytes\":%llu,\"cones_ms\":%.3f,\"direct_ms\":%.3f,\"ms\":%.3f,\"mean\":[%.6g,%.6g,%.6g],",
               name, voxgi_backend_name(ci->backend), w, h, vd->resolution ? vd->resolution : 128, vd->cones.cones ? vd->cones.cones : 16, !vd->no_gi,
               (unsigned long long)vinfo->voxels, vinfo->ms_voxelize, vinfo->ms_inject, vinfo->ms_octree, (unsigned long long)vinfo->radiance_bytes,
               vinfo->ms_cones, vinfo->ms_direct, vinfo->ms, mean[0], mean[1], mean[2]);
        if (a->compare || a->reference) print_compare_json(cmp);
        else printf("\"rel_rmse\":-1,\"rms\":0,\"reference_ms\":0.000,"); /* nothing compared */
        printf("\"output\":\"%s\"}\n", a->out);
    } else if (a->method == METHOD_VCT) {
        printf("%s: %d x %d cone-traced (%s%s%s), %llu voxels: voxelize %.1f ms, inject + mips %.1f ms, ", name, w, h, voxgi_backend_name(ci->backend),
               ci->backend == VOXGI_BACKEND_GL ? ", " : "", ci->backend == VOXGI_BACKEND_GL ? ci->gl_renderer : "", (unsigned long long)vinfo->voxels,
               vinfo->ms_voxelize, vinfo->ms_inject);
        if (vd->octree) printf("octree %.1f ms, ", vinfo->ms_octree);
        printf("cones %.1f ms (over %.1f MB of %s), direct light %.1f ms, total %.1f ms; mean radiance %.4g %.4g %.4g -> %s\n", vinfo->ms_cones,
               vinfo->radiance_bytes / 1e6, vd->octree ? "octree" : "volume", vinfo->ms_direct, vinfo->ms, mean[0], mean[1], mean[2], a->out);
        if (a->compare || a->reference) print_compare(a, d, cmp);
    } else if (a->common.json) {
        printf("{\"scene\":\"%s\",\"method\":\"reference\",\"size\":[%d,%d],\"spp\":%d,\"bounces\":%d,\"seed\":%llu,\"triangles\":%lu,"
               "\"bvh_nodes\":%lu,\"rays\":%llu,\"bvh_ms\":%.3f,\"render_ms\":%.3f,\"mean\":[%.6g,%.6g,%.6g],",
               name, w, h, d->samples, d->bounces, (unsigned long long)d->seed, (unsigned long)info->triangles, (unsigned long)info->bvh_nodes,
               (unsigned long long)info->rays, info->ms_bvh, info->ms_render, mean[0], mean[1], mean[2]);
        if (a->compare || a->reference) print_compare_json(cmp);
        printf("\"output\":\"%s\"}\n", a->out);
    } else {
        printf("%s: %d x %d, %d spp, bounces %d: %lu triangles, BVH %lu nodes in %.1f ms, %llu rays in %.1f ms (%.2f Mrays/s, CPU); "
               "mean radiance %.4g %.4g %.4g -> %s\n",
               name, w, h, d->samples, d->bounces, (unsigned long)info->triangles, (unsigned long)info->bvh_nodes, info->ms_bvh,
               (unsigned long long)info->rays, info->ms_render, info->ms_render > 0 ? (double)info->rays / info->ms_render / 1000 : 0.0, mean[0],
               mean[1], mean[2], a->out);
        if (a->compare || a->reference) print_compare(a, d, cmp);
    }
}

static int render_run(cli_session *s, const render_args *a)
{
    render_jobs J;
    voxgi_reference_desc *d = &J.d;
    voxgi_vct_desc *vd = &J.vd;
    voxgi_tsm_image_desc *td = &J.td;
    voxgi_rsm_image_desc *qd = &J.qd;
    voxgi_sh_image_desc *hd = &J.hd;
    voxgi_info ci;
    render_scene rs;
    cli_context c;
    cli_common options = a->common;
    float *rgb = NULL;
    size_t bytes = (size_t)a->size[0] * (size_t)a->size[1] * 12;
    render_compare cmp;
    int rc = CLI_EXIT_FAILURE;
    memset(&J, 0, sizeof J);
    memset(&rs, 0, sizeof rs);
    memset(&cmp, 0, sizeof cmp);
    d->bounces = a->bounces;
    d->samples = a->spp;
    d->seed = (uint64_t)a->seed;
    vd->resolution = a->res;
    vd->cones.cones = a->cones;
    vd->cones.step = (float)a->step;
    vd->filter = a->isotropic ? VOXGI_MIPS_ISOTROPIC : VOXGI_MIPS_ANISOTROPIC;
    vd->no_gi = a->no_gi;
    vd->inject_samples = a->inject_samples;
    vd->cone_stride = a->cone_stride;
    vd->bounce_cones.cones = a->bounce_cones;
    vd->bounce_block = a->bounce_block;
    vd->octree = a->octree;
    vd->octree_format = (voxgi_svo_format)a->octree_format;
    vd->octree_bricks = a->bricks;
    if (a->method == METHOD_REFERENCE) options.backend = VOXGI_BACKEND_CPU; /* the path tracer runs on the CPU */
    if (cli_context_open_options(s, &c, &options)) return CLI_EXIT_FAILURE;
    voxgi_query_info(c.vx, &ci);
    if (scene_open(s, c.vx, a, &rs, d)) goto done;
    if (!(rgb = (float *)malloc(bytes))) {
        cli_fail(s, "out of memory");
        goto done;
    }
    if (a->method == METHOD_TSM) { /* direct light: compared with the reference's */
        td->camera = d->camera;
        td->seed = d->seed;
        td->samples = a->spp_given ? d->samples : 4;
        td->tsm.size = a->tsm_size;
        td->tsm.slices = a->slices;
        td->tsm.sigma = (float)a->sigma;
        d->bounces = 0;
    }
    if (a->method == METHOD_RSM) { /* direct light and one bounce: compared with the reference's one bounce */
        qd->camera = d->camera;
        qd->seed = d->seed;
        qd->samples = a->spp_given ? d->samples : 0;
        qd->rsm.size = a->rsm_size;
        qd->rsm.samples = a->rsm_samples;
        qd->rsm.radius = (float)a->rsm_radius;
        qd->rsm.points = a->rsm_points;
        qd->gather_stride = a->gather_stride;
        qd->rsm.seed = d->seed;
        qd->visibility = (voxgi_visibility)a->visibility;
        qd->resolution = a->res_given ? a->res : 64;
        d->bounces = 1;
    }
    if (a->method == METHOD_SH) { /* direct light and one bounce: compared with the reference's one bounce */
        hd->camera = d->camera;
        hd->seed = d->seed;
        hd->samples = a->spp_given ? d->samples : 0;
        hd->sh.seed = d->seed;
        hd->visibility = (voxgi_visibility)a->visibility;
        hd->resolution = a->res_given ? a->res : 64;
        hd->opening = (float)a->opening;
        hd->gather_stride = a->gather_stride;
        d->bounces = 1;
    }
    if (a->method == METHOD_SSAO || a->method == METHOD_VAO) { /* compared with the reference's AO mode at the radius used */
        J.ad.camera = d->camera;
        J.ad.seed = d->seed;
        J.ad.method = a->method == METHOD_VAO ? VOXGI_AO_VOXELS : VOXGI_AO_SCREEN;
        J.ad.resolution = a->res_given ? a->res : 0;
        J.ad.rays = a->rays;
        J.ad.steps = a->march_steps;
        J.ad.radius = (float)a->radius;
        J.ad.point_sampling = a->point_sampling;
        J.ad.half_resolution = a->half_res_given ? a->half_res : 0;
        J.ad.blur = a->blur_given ? a->blur : AO_BLUR;
    }
    if (a->method == METHOD_SSGI || a->method == METHOD_HYBRID) { /* direct light and one bounce: compared with the reference's one bounce */
        J.gd.camera = d->camera;
        J.gd.seed = d->seed;
        J.gd.samples = a->spp_given ? d->samples : 0;
        J.gd.method = a->method == METHOD_HYBRID ? VOXGI_AO_VOXELS : VOXGI_AO_SCREEN;
        J.gd.resolution = a->res_given ? a->res : 0;
        J.gd.rays = a->rays;
        J.gd.steps = a->march_steps;
        J.gd.radius = (float)a->radius;
        J.gd.half_resolution = a->half_res_given ? a->half_res : GI_HALF_RES;
        J.gd.hidden_light = a->method == METHOD_HYBRID && (a->hidden_light_given ? a->hidden_light : HYBRID_HIDDEN_LIGHT);
        J.gd.inject_samples = a->inject_samples;
        J.gd.blur = a->blur_given ? a->blur : GI_BLUR;
        d->bounces = 1;
    }
    if (a->method == METHOD_LINESPACE) { /* direct light of the area lights: compared with the reference's */
        J.ld.camera = d->camera;
        J.ld.seed = (uint32_t)d->seed;
        J.ld.mode = (voxgi_linespace_mode)(a->ls_mode_given ? a->ls_mode : LS_MODE);
        J.ld.samples = a->samples ? a->samples : LS_SAMPLES;
        J.ld.packets = a->packets;
        J.ld.exact_ends = a->exact_ends;
        J.ld.supersample = a->supersample ? a->supersample : LS_SUPERSAMPLE;
        J.ld.tree.n = a->ls_n ? a->ls_n : LS_N;
        J.ld.tree.depth = a->ls_depth;
        J.ld.tree.memory_budget = (size_t)a->ls_budget << 20;
        d->bounces = 0;
    }
    if (a->method == METHOD_REFERENCE) {
        d->ao_radius = (float)a->ao_radius; /* > 0: the AO mode */
        d->screen_light_only = a->screen_light_only;
    }
    if (a->method == METHOD_VCT) { /* the same view and seed; the direct light takes --spp rays per pixel (default 24) */
        vd->camera = d->camera;
        vd->seed = d->seed;
        vd->samples = a->spp_given ? d->samples : 24;
        vd->bounces = d->bounces;
        if (vd->no_gi) d->bounces = 0; /* what it is compared against */
    }
    if (render_method(c.vx, a->method, rs.scene, &J, rgb, bytes) != VOXGI_OK) {
        cli_fail_lib(s, c.vx, NULL);
        goto done;
    }
    if (a->method == METHOD_SSAO || a->method == METHOD_VAO) d->ao_radius = J.ainfo.radius;
    if (a->compare && compare_with_reference(s, c.vx, a, rs.scene, &J, &cmp)) goto done;
    if (a->reference && compare_with_file(s, c.vx, a, rs.scene, &d->camera, rgb, &cmp)) goto done;
    if ((cli_has_extension(a->out, ".pfm") ? vxt_write_pfm(a->out, rgb, a->size[0], a->size[1])
                                           : vxt_write_png(a->out, rgb, a->size[0], a->size[1], (float)a->exposure)) != 0) {
        cli_fail(s, "cannot write %s", a->out);
        goto done;
    }
    cli_status_clear(s);
    print_result(a, rs.name, &ci, rgb, &J, &cmp);
    rc = CLI_EXIT_OK;
done:
    free(rgb);
    scene_close(c.vx, &rs);
    cli_context_close(s, &c);
    return rc;
}

int cmd_render(int argc, char **argv)
{
    render_args a;
    cli_session s;
    int rc;
    memset(&a, 0, sizeof a);
    a.bounces = 1;
    a.spp = 64;
    a.seed = 1;
    a.size[0] = a.size[1] = 256;
    a.exposure = 1;
    a.res = 96; /* vct: the defaults sit on the Pareto front of `voxgi report vct` (docs/cone-tracing.md) */
    a.cones = 24;
    a.cone_stride = 6;
    {
        const cli_option options[] = {
            {.name = "--method", .arg = "reference|vct|tsm|rsm|sh|ssao|vao|ssgi|hybrid|linespace", .kind = CLI_ENUM, .dst = &a.method, .names = render_methods,
             .help = "the Monte Carlo path tracer (default), or voxel cone tracing: direct\n"
                     "light through shadow rays plus one bounce gathered by cones from\n"
                     "the voxels, or transmittance shadow maps: direct light, each\n"
                     "directional light through its map (compared with --bounces 0), or\n"
                     "reflective shadow maps: direct light and one bounce from the maps of\n"
                     "every light and the emitters (compared with --bounces 1), or an SH\n"
                     "volume: direct light and one bounce from the voxels' SH (--bounces 1),\n"
                     "or ambient occlusion from the depth buffer (ssao) or the voxels (vao),\n"
                     "compared with the reference's AO mode, or direct light and one bounce\n"
                     "from the screen through the depth buffer (ssgi) or the voxels (hybrid),\n"
                     "or the area lights' direct light with soft shadows through the line\n"
                     "space (linespace; compared with --bounces 0)"},
            CLI_OPT_BACKEND(&a.common, "vct: where voxelization, mips and cones run (default auto: GL when a\n"
                                       "headless GL 4.5 context works); the reference runs on the CPU"),
            CLI_OPT_GL(&a.common, "which headless GL to try"),
            {.name = "--res", .arg = "N", .kind = CLI_INT, .dst = &a.res, .lo = 1, .hi = 4096, .given = &a.res_given,
             .help = "vct: voxels along the scene's longest side (default 96); rsm: of the\nvisibility's voxels (default 64); sh: of the SH volume (default 64);\nvao, hybrid: of the voxels (default 128)"},
            {.name = "--cones", .arg = "N", .kind = CLI_INT, .dst = &a.cones, .lo = 1, .hi = 1024, .help = "vct: diffuse cones (default 24)"},
            {.name = "--step", .arg = "S", .kind = CLI_DOUBLE, .dst = &a.step, .lo = 0, .lo_open = 1, .hi = 4,
             .help = "vct: step as a fraction of the cone diameter (default 0.5)"},
            {.name = "--anisotropic", .kind = CLI_FLAG, .dst = &a.anisotropic, .help = "vct: six-direction mips (the default)"},
            {.name = "--isotropic", .kind = CLI_FLAG, .dst = &a.isotropic,
             .help = "vct: one mip chain (less memory, more light through thin walls)"},
            {.name = "--cone-stride", .arg = "S", .kind = CLI_INT, .dst = &a.cone_stride, .lo = 1, .hi = 64,
             .help = "vct: cones at every S-th pixel across and down, the pixels between\n"
                     "interpolated where they share a surface (default 6; 1: every pixel)"},
            {.name = "--octree", .arg = "[float32|float16]", .kind = CLI_ENUM, .optional = 1, .dst = &a.octree_format, .names = cli_svo_format_names,
             .given = &a.octree,
             .help = "vct: the cones gather from a sparse voxel octree of the radiance\n"
                     "(isotropic mips) instead of the volume (default float32)"},
            {.name = "--bricks", .kind = CLI_FLAG, .dst = &a.bricks, .help = "vct with --octree: sample the octree through its bricks"},
            {.name = "--inject-samples", .arg = "N", .kind = CLI_INT, .dst = &a.inject_samples, .lo = 1, .hi = 4096,
             .help = "vct, hybrid with --hidden-light: points on each area light and emitter\nper voxel's light (default 4 on the CPU, 16 on GL)"},
            {.name = "--no-gi", .kind = CLI_FLAG, .dst = &a.no_gi, .help = "vct: direct light only"},
            {.name = "--rsm-size", .arg = "N", .kind = CLI_INT, .dst = &a.rsm_size, .lo = 1, .hi = 16384,
             .help = "rsm: texels across each light's map (default 256)"},
            {.name = "--rsm-samples", .arg = "N", .kind = CLI_INT, .dst = &a.rsm_samples, .lo = 1, .hi = 65536,
             .help = "rsm: texels gathered per pixel and map (default 100 for a light's map,\n200 for an area's points)"},
            {.name = "--rsm-radius", .arg = "R", .kind = CLI_DOUBLE, .dst = &a.rsm_radius, .lo = 0, .lo_open = 1, .hi = 2,
             .help = "rsm: the sample disc's radius, a share of the map's width (default 0.3\nfor a light's map, 1 for an area's points)"},
            {.name = "--rsm-points", .arg = "N", .kind = CLI_INT, .dst = &a.rsm_points, .lo = 1, .hi = 4096,
             .help = "rsm: points on each rectangular light and on the emitters, one map each\n(default 4)"},
            {.name = "--gather-stride", .arg = "S", .kind = CLI_INT, .dst = &a.gather_stride, .lo = 1, .hi = 64,
             .help = "rsm, sh: gathers at every S-th pixel across and down, the pixels between\ninterpolated where three of the four around share their surface (default 4)"},
            {.name = "--opening", .arg = "T", .kind = CLI_DOUBLE, .dst = &a.opening, .lo = 0, .lo_open = 1, .hi = 4,
             .help = "sh: a cell counts as one point where its size is at most T times its\ndistance (default 0.5)"},
            {.name = "--ao-radius", .arg = "R", .kind = CLI_DOUBLE, .dst = &a.ao_radius, .lo = 0, .lo_open = 1, .hi = 1e30,
             .help = "reference: render ambient occlusion within R instead of light"},
            {.name = "--screen-light-only", .kind = CLI_FLAG, .dst = &a.screen_light_only,
             .help = "reference with --bounces 1: the bounce takes light only from surfaces the\ncamera sees (the most one bounce from the screen can find)"},
            {.name = "--radius", .arg = "R", .kind = CLI_DOUBLE, .dst = &a.radius, .lo = 0, .lo_open = 1, .hi = 1e30,
             .help = "ssao, vao: the occlusion's radius (default a tenth of the scene's longest\nside); ssgi, hybrid: the rays' reach (default sqrt(3) x the scene's longest side)"},
            {.name = "--rays", .arg = "N", .kind = CLI_INT, .dst = &a.rays, .lo = 1, .hi = 65536, .help = "ssao, vao, ssgi, hybrid: rays per pixel (default 16)"},
            {.name = "--steps", .arg = "N", .kind = CLI_INT, .dst = &a.march_steps, .lo = 1, .hi = 4096, .help = "ssao, ssgi: steps along each ray (default 16)"},
            {.name = "--point-sampling", .kind = CLI_FLAG, .dst = &a.point_sampling,
             .help = "ssao: one point per ray instead of the march (occlusion with a linear\nfalloff: a hit at d counts 1 - d / radius)"},
            {.name = "--hidden-light", .arg = "on|off", .kind = CLI_ENUM, .dst = &a.hidden_light, .names = off_on_names, .given = &a.hidden_light_given,
             .help = "hybrid: rays that meet a voxel the camera does not see take the direct\nlight injected into it (default on; off: they send nothing, as in the source)"},
            {.name = "--half-res", .arg = "on|off", .kind = CLI_ENUM, .dst = &a.half_res, .names = off_on_names, .given = &a.half_res_given,
             .help = "ssao, vao, ssgi, hybrid: rays at every other pixel across and down, upsampled\nalong the surfaces by an edge-aware filter (default off for ssao and vao, on\nfor ssgi and hybrid)"},
            {.name = "--blur", .arg = "N", .kind = CLI_INT, .dst = &a.blur, .lo = 0, .hi = 64, .given = &a.blur_given,
             .help = "ssao, vao, ssgi, hybrid: the edge-aware blur's radius in pixels (0: none;\ndefault 2 for ssao and vao, 8 for ssgi and hybrid)"},
            {.name = "--ls-mode", .arg = "exact|fast", .kind = CLI_ENUM, .dst = &a.ls_mode, .names = ls_mode_names, .given = &a.ls_mode_given,
             .help = "linespace: exact (the triangles decide) or fast (a set bit of the last\nline-space level blocks the ray) (default exact)"},
            {.name = "--ls-n", .arg = "N", .kind = CLI_INT, .dst = &a.ls_n, .lo = 2, .hi = 16, .help = "linespace: children per axis of a split node (default 4)"},
            {.name = "--ls-depth", .arg = "D", .kind = CLI_INT, .dst = &a.ls_depth, .lo = 1, .hi = 8, .help = "linespace: the tree's levels below the root (default 2 under 256\ntriangles, else 3)"},
            {.name = "--ls-exact-ends", .arg = "E", .kind = CLI_INT, .dst = &a.exact_ends, .lo = 1, .hi = 1 << 20,
             .help = "linespace, fast: the triangles decide within E leaves' edges of each end\nof a shadow ray (default 3; more: closer to exact, slower)"},
            {.name = "--ls-budget", .arg = "MB", .kind = CLI_INT, .dst = &a.ls_budget, .lo = 1, .hi = 1 << 20,
             .help = "linespace: the most memory the tree may take, MiB (default 1024)"},
            {.name = "--samples", .arg = "S", .kind = CLI_INT, .dst = &a.samples, .lo = 1, .hi = 4096,
             .help = "linespace: shadow rays per shading point and light, jittered in a grid\nover the light (default 4)"},
            {.name = "--supersample", .arg = "K", .kind = CLI_INT, .dst = &a.supersample, .lo = 1, .hi = 16,
             .help = "linespace: K x K shading points per pixel, averaged (default 2; 1: the\npixel's centre)"},
            {.name = "--packets", .arg = "on|off", .kind = CLI_ENUM, .dst = &a.packets, .names = off_on_names,
             .help = "linespace: a pixel's rays walk the tree together slice by slice (on), or\neach alone by 3D DDA (off; the default); the same image"},
            {.name = "--visibility", .arg = "hierarchical|dda|none", .kind = CLI_ENUM, .dst = &a.visibility, .names = visibility_names,
             .help = "rsm and sh: each gather's visibility through the voxels (default hierarchical)"},
            {.name = "--tsm-size", .arg = "N", .kind = CLI_INT, .dst = &a.tsm_size, .lo = 1, .hi = 16384,
             .help = "tsm: texels across each light's map (default 512)"},
            {.name = "--slices", .arg = "N", .kind = CLI_INT, .dst = &a.slices, .lo = 1, .hi = 4096, .help = "tsm: slices along the light (default 64)"},
            {.name = "--sigma", .arg = "S", .kind = CLI_DOUBLE, .dst = &a.sigma, .lo = 0, .lo_open = 1, .hi = 1,
             .help = "tsm: every translucent material's absorption per slice\n(default: each material's 1 - transparency)"},
            {.name = "--reference", .arg = "REF.pfm", .kind = CLI_STRING, .dst = &a.reference,
             .help = "print the error by --compare's rule against an image rendered before\n"
                     "(same view and --size, e.g. a converged `render SCENE --spp 4096 -o REF.pfm`)"},
            {.name = "--compare", .arg = "SPP", .kind = CLI_INT, .dst = &a.compare, .lo = 1, .hi = 1 << 24,
             .help = "also render the reference (same bounces) with SPP samples per pixel and\n"
                     "print the relative RMSE of the lighting over the pixels farther than 3\n"
                     "pixels from any pixel whose centre sees an emitter, both images without\n"
                     "the emission the camera sees; the pixels left out (JSON masked_pixels)\n"
                     "and both times; the image written is the one with the emission"},
            {.name = "--cornell-mesh", .arg = "MESH", .kind = CLI_STRING, .dst = &a.cornell_mesh,
             .help = "scene cornell-box only: the mesh (a file or builtin:NAME) in place of\n"
                     "the tall block, scaled uniformly to fit inside its bounding box, on\n"
                     "the floor at its centre, in its white; named cornell-box+NAME"},
            {.name = "--bounces", .arg = "B", .kind = CLI_INT, .dst = &a.bounces, .lo = -1, .hi = 1000,
             .help = "indirect bounces: 0 = direct light only, -1 = unlimited (default 1);\n"
                     "vct: B >= 1, the light bouncing B - 1 times among the voxels first;\n"
                     "-1, until the bounces still to come add less than 1% of the light"},
            {.name = "--bounce-cones", .arg = "N", .kind = CLI_INT, .dst = &a.bounce_cones, .lo = 1, .hi = 1024,
             .help = "vct with --bounces B > 1: cones per gather among the voxels (default 4)"},
            {.name = "--bounce-block", .arg = "N", .kind = CLI_INT, .dst = &a.bounce_block, .lo = 1, .hi = 64,
             .help = "vct with --bounces B > 1: the voxels gather once per block of N^3 of them\n"
                     "facing the same way (default 4; 1: every voxel)"},
            {.name = "--spp", .arg = "S", .kind = CLI_INT, .dst = &a.spp, .lo = 1, .hi = 1 << 24, .given = &a.spp_given,
             .help = "samples per pixel (default 64); vct: the direct light's rays per pixel\n"
                     "(default 24), as rsm and sh; tsm: camera rays per pixel (default 4)"},
            {.name = "--seed", .arg = "N", .kind = CLI_INT, .dst = &a.seed, .lo = 0, .hi = 2147483647,
             .help = "random seed (default 1); the same seed gives the same image"},
            {.name = "--camera", .arg = "EX EY EZ TX TY TZ FOVY", .kind = CLI_DOUBLE, .count = 7, .dst = a.camera, .lo = -HUGE_VAL, .hi = HUGE_VAL,
             .given = &a.have_camera,
             .help = "eye, target (up +Y) and vertical field of view in degrees\n"
                     "(default: the scene's view; for a mesh, a view of its bounds)"},
            {.name = "--size", .arg = "W H", .kind = CLI_INT, .count = 2, .dst = a.size, .lo = 1, .hi = 16384, .help = "image size (default 256 256)"},
            {.name = "--sun", .arg = "DX DY DZ E", .kind = CLI_DOUBLE, .count = 4, .dst = a.sun, .lo = -HUGE_VAL, .hi = HUGE_VAL, .given = &a.have_sun,
             .help = "add a directional light travelling along D with irradiance E"},
            {.name = "--exposure", .arg = "X", .kind = CLI_DOUBLE, .dst = &a.exposure, .lo = 0, .hi = HUGE_VAL,
             .help = "PNG only: scale before clamping (default 1)"},
            CLI_OPT_THREADS(&a.common),
            CLI_OPT_JSON(&a.common, "print one JSON object (timings, rays, mean radiance) instead of text"),
            {.name = "-o", .arg = "OUT.png|OUT.pfm", .kind = CLI_STRING, .dst = &a.out,
             .help = "the image (required): PNG, 8-bit sRGB, or PFM, linear float radiance"}};
        const cli_command cmd = {.name = "render", .help = render_help, .column = 27, .options = options, .option_count = CLI_COUNT(options),
                                 .operand = "scene or mesh", .operands = &a.what, .min_operands = 1, .max_operands = 1};
        if ((rc = cli_parse(&cmd, argc, argv)) != CLI_CONTINUE) return rc;
    }
    /* the file type is checked before any work: a typo must not cost a long render */
    if (!a.out) return cli_usage("render", "-o OUT.png or OUT.pfm is needed");
    if (!cli_has_extension(a.out, ".png") && !cli_has_extension(a.out, ".pfm"))
        return cli_usage("render", "-o %s: render writes .png or .pfm images only", a.out);
    if (a.method == METHOD_VCT && a.bounces == 0 && !a.no_gi) return cli_usage("render", "--method vct needs --bounces 1 or more, or -1 (or --no-gi)");
    if (a.method == METHOD_VCT && a.bounces > 64) return cli_usage("render", "--method vct: --bounces %d, at most 64", a.bounces);
    if (a.anisotropic && a.isotropic) return cli_usage("render", "--anisotropic and --isotropic: one or the other");
    if (a.compare && a.reference) return cli_usage("render", "--compare and --reference: one or the other");
    if (a.cornell_mesh && strcmp(a.what, "cornell-box") != 0)
        return cli_usage("render", "--cornell-mesh replaces the tall block of the scene cornell-box, not of '%s'", a.what);
    cli_session_init(&s, "render");
    return render_run(&s, &a);
}
