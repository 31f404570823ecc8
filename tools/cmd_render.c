/* tools/cmd_render.c - voxgi render: an image of a built-in scene or a mesh, path-traced or cone-traced. */
#include "cli.h"
#include "image_io.h"
#include <stdlib.h>
#include <string.h>

static const char *const render_methods[] = {"reference", "vct", "tsm", "rsm", "sh", "ssao", "vao", "ssgi", "hybrid", "linespace", NULL};
enum { METHOD_REFERENCE, METHOD_VCT, METHOD_TSM, METHOD_RSM, METHOD_SH, METHOD_SSAO, METHOD_VAO, METHOD_SSGI, METHOD_HYBRID, METHOD_LINESPACE };
static const char *const ls_mode_names[] = {"exact", "fast", NULL}; /* voxgi_linespace_mode's order */
static const char *const visibility_names[] = {"hierarchical", "dda", "none", NULL}; /* voxgi_traversal's order */
static const char *const off_on_names[] = {"off", "on", NULL};
static const char *const up_names[] = {"x", "y", "z", "-x", "-y", "-z", NULL};
enum { UP_Y = 1 };

static const char *const plan_help =
    "usage: voxgi plan SCENE|MESH [render's options]\n"
    "Prints the settings voxgi render runs with for the same options (every default resolved by the\n"
    "library) and the library's plan: what the scene holds, and each channel, structure and pass\n"
    "kept or left out with the reason and the memory it costs, before anything is allocated (bytes\n"
    "marked ~ are estimated from the scene's surface). The image follows the same plan.\n";

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
    double error, budget_mb;      /* the render desc's error and memory budget */
    int dynamic, everything;      /* voxgi plan only: its flags */
    int up;                       /* a mesh's up axis, an index of up_names */
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

/* Turns a mesh so that its up axis (an index of up_names) points along +Y, the camera's up: a
   rotation (determinant 1), so nothing is mirrored and the faces keep their sides. */
static void mesh_turn_up(float *v, size_t count, int up)
{
    size_t i;
    for (i = 0; v && i < count; i++, v += 3) {
        float x = v[0], y = v[1], z = v[2];
        switch (up) {
        case 0: v[0] = -y; v[1] = x; break;          /* +X up */
        case 2: v[1] = z; v[2] = -y; break;          /* +Z up: -Y, the front, toward the viewer */
        case 3: v[0] = y; v[1] = -x; break;          /* -X up */
        case 4: v[1] = -y; v[2] = -z; break;         /* -Y up */
        case 5: v[1] = -z; v[2] = y; break;          /* -Z up */
        default: break;
        }
    }
}

/* The view of a mesh without --camera: its bounds framed as voxgi_camera_frame_bounds does. */
static void mesh_frame(const voxgi_mesh *m, voxgi_camera *cam)
{
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    size_t i;
    int k;
    for (i = 0; i < m->vertex_count; i++)
        for (k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], m->positions[3 * i + (size_t)k]);
            hi[k] = fmax(hi[k], m->positions[3 * i + (size_t)k]);
        }
    voxgi_camera_frame_bounds(lo, hi, cam);
}

/* 1 when something lights the scene: a light, or a triangle of an emissive material. */
static int scene_lit(const voxgi_scene *sc)
{
    size_t i, t;
    int k;
    if (sc->light_count) return 1;
    for (i = 0; i < sc->mesh_count && sc->materials; i++) {
        const voxgi_mesh *m = &sc->meshes[i];
        size_t n = m->indices ? m->index_count / 3 : m->vertex_count / 3;
        for (t = 0; t < n; t++) {
            uint32_t id = m->material_ids ? m->material_ids[t] : m->material;
            for (k = 0; k < 3 && id < sc->material_count; k++)
                if (sc->materials[id].emission[k] > 0) return 1;
        }
    }
    return 0;
}

/* The sun added to an unlit scene: from above, left of and behind the camera (the usual studio
   key light), irradiance pi (a surface of albedo a facing it has radiance a). */
static void default_sun(const voxgi_camera *cam, double sun[4])
{
    double fw[3], rt[3], up[3], len = 0;
    int k;
    for (k = 0; k < 3; k++) fw[k] = cam->target[k] - cam->eye[k];
    rt[0] = -fw[2]; rt[1] = 0; rt[2] = fw[0]; /* fw x +Y, as the library's camera frame */
    up[0] = rt[1] * fw[2] - rt[2] * fw[1];
    up[1] = rt[2] * fw[0] - rt[0] * fw[2];
    up[2] = rt[0] * fw[1] - rt[1] * fw[0];
    for (k = 0; k < 3; k++) { /* each unit: the light travels forward, to the right and down */
        double f = sqrt(fw[0] * fw[0] + fw[1] * fw[1] + fw[2] * fw[2]), r = sqrt(rt[0] * rt[0] + rt[2] * rt[2]);
        double u = sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]);
        sun[k] = fw[k] / f + (r > 0 ? rt[k] / r : 0) - (u > 0 ? up[k] / u : 0); /* along +-Y the library refuses the camera */
        len += sun[k] * sun[k];
    }
    for (k = 0; k < 3; k++) sun[k] /= sqrt(len);
    sun[3] = 3.14159265358979;
}

/* Sets up rs and the camera d->camera (a mesh's left zero: the library fits it); 0, or says why and returns 1. */
static int scene_open(cli_session *s, voxgi_context *ctx, const render_args *a, render_scene *rs, voxgi_render_desc *d)
{
    double sun[4];
    int i, add_sun;
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
        mesh_turn_up(rs->tm.m.positions ? rs->tm.m.positions : rs->tm.shape.pos, rs->tm.vm.vertex_count, a->up);
        mesh_turn_up(rs->tm.m.normals, rs->tm.vm.vertex_count, a->up);
        rs->scene = &rs->tm.scene;
        if (!a->have_camera) { /* the whole mesh, from a three-quarter view above its front */
            d->camera.width = a->size[0];
            d->camera.height = a->size[1];
            mesh_frame(&rs->tm.vm, &d->camera);
        }
    }
    if (a->have_camera) {
        memcpy(d->camera.eye, a->camera, 3 * sizeof(double));
        memcpy(d->camera.target, a->camera + 3, 3 * sizeof(double));
        d->camera.fovy_degrees = a->camera[6];
    }
    d->camera.width = a->size[0];
    d->camera.height = a->size[1];
    sun[0] = a->sun[0]; sun[1] = a->sun[1]; sun[2] = a->sun[2]; sun[3] = a->sun[3];
    add_sun = a->have_sun;
    if (!add_sun && !scene_lit(rs->scene) && a->method != METHOD_SSAO && a->method != METHOD_VAO && !(a->ao_radius > 0)) {
        /* a black image would say nothing: light it, and say how to choose the light */
        default_sun(&d->camera, sun);
        add_sun = 1;
        cli_note(s, "no light or emitter in the scene: added a sun from the camera's upper left; give --sun or an emissive material to choose");
    }
    if (add_sun) { /* the scene's lights and one more */
        const voxgi_scene *scene = rs->scene;
        rs->with_sun = *scene;
        rs->lights = (voxgi_light *)calloc(scene->light_count + 1, sizeof *rs->lights);
        if (!rs->lights) return cli_fail(s, "out of memory");
        if (scene->light_count) memcpy(rs->lights, scene->lights, scene->light_count * sizeof *rs->lights);
        rs->lights[scene->light_count].type = VOXGI_LIGHT_DIRECTIONAL;
        for (i = 0; i < 3; i++) {
            rs->lights[scene->light_count].direction[i] = (float)sun[i];
            rs->lights[scene->light_count].intensity[i] = (float)sun[3];
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

/* What --compare measured. */
typedef struct render_compare {
    double rmse;                  /* NaN: nothing to relate to (a black reference, or every pixel masked) */
    double rms, ref_ms;
    size_t masked, pixels;        /* pixels left out of the error, of all */
} render_compare;

/* The reference an image is compared with: the path tracer at the image's view with what the
   method computes (its bounces, or ambient occlusion within the radius it used). */
static voxgi_render_desc reference_for(const voxgi_render_desc *used)
{
    voxgi_render_desc r;
    int m = (int)used->method;
    memset(&r, 0, sizeof r);
    r.method = VOXGI_RENDER_REFERENCE;
    r.camera = used->camera;
    r.seed = used->seed;
    r.rays = used->rays;
    if (m == VOXGI_RENDER_REFERENCE) {
        r.bounces = used->bounces;
        r.reference = used->reference;
    } else if (m == VOXGI_RENDER_VCT)
        r.bounces = used->bounces;
    else if (m == VOXGI_RENDER_SSAO || m == VOXGI_RENDER_VAO) {
        r.bounces = 1;
        r.reference.ao_radius = used->screen.radius;
    } else
        r.bounces = m == VOXGI_RENDER_TSM || m == VOXGI_RENDER_LINESPACE ? 0 : used->bounces;
    r.direct_only = r.bounces == 0;
    return r;
}

/* --compare: the relative RMSE of the lighting against the reference with `compare` spp (rendered
   with an independent seed) by the tools' one rule (cli_masked_error): both without the emission
   the camera sees, and the pixels within 3 of one whose centre sees an emitter left out (the
   noise at the emitters' edges would swamp the lighting). */
static int compare_with_reference(cli_session *s, voxgi_context *ctx, const render_args *a, const voxgi_scene *scene, const voxgi_render_desc *used,
                                  render_compare *cmp)
{
    size_t n = (size_t)used->camera.width * (size_t)used->camera.height * 3;
    float *ref = (float *)malloc(n * 8), *mine = ref ? ref + n : NULL;
    voxgi_render_desc hidden = *used, reference = reference_for(used);
    voxgi_render_info ri;
    voxgi_result r;
    cli_error_mask mask;
    reference.samples = a->compare;
    reference.seed = used->seed + 1000003; /* independent of the image's own noise */
    reference.hide_emitters = hidden.hide_emitters = 1;
    r = ref ? voxgi_render(ctx, scene, &reference, ref, n * 4, &ri) : VOXGI_ERR_OUT_OF_MEMORY;
    if (r == VOXGI_OK) r = voxgi_render(ctx, scene, &hidden, mine, n * 4, NULL);
    if (r != VOXGI_OK) {
        free(ref);
        return ref ? cli_fail_lib(s, ctx, "the reference") : cli_fail(s, "the reference: out of memory");
    }
    if (cli_error_mask_make(s, ctx, scene, &used->camera, &mask)) {
        free(ref);
        return CLI_EXIT_FAILURE;
    }
    cmp->rmse = cli_masked_error(&mask, mine, ref, &cmp->rms, NULL); /* a black reference (the leak box): NaN, the RMS says it */
    cmp->masked = mask.masked_pixels;
    cmp->pixels = n / 3;
    cmp->ref_ms = ri.ms;
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
    if (w != camera->width || h != camera->height) {
        free(ref);
        return cli_fail(s, "--reference %s is %d x %d, the image %d x %d (render it with the same --size and view)", a->reference, w, h, camera->width,
                        camera->height);
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
static void print_compare(const render_args *a, const voxgi_render_desc *d, const render_compare *cmp)
{
    if (a->reference) printf("against %s: ", a->reference);
    else if (d->reference.ao_radius > 0) printf("against the reference (ambient occlusion within %.4g, %d spp, %.1f ms): ", (double)d->reference.ao_radius, a->compare, cmp->ref_ms);
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

/* The method's own JSON fields after "size" (the settings it ran with and what it reports). */
static void print_json_fields(const voxgi_render_info *f)
{
    const voxgi_render_desc *u = &f->used;
    const voxgi_render_screen *sc = &u->screen;
    switch (u->method) {
    case VOXGI_RENDER_VCT:
        printf("\"res\":%d,\"cones\":%d,\"gi\":%d,\"voxels\":%llu,\"voxelize_ms\":%.3f,\"inject_ms\":%.3f,\"octree_ms\":%.3f,\"radiance_bytes\":%llu,"
               "\"cones_ms\":%.3f,\"direct_ms\":%.3f,\"ms\":%.3f,",
               u->resolution, u->vct.cones.cones, !u->direct_only, (unsigned long long)f->voxels, voxgi_render_stage_ms(f, "voxelize"), voxgi_render_stage_ms(f, "inject"),
               voxgi_render_stage_ms(f, "octree"), (unsigned long long)f->bytes, voxgi_render_stage_ms(f, "cones"), voxgi_render_stage_ms(f, "direct"), f->ms);
        break;
    case VOXGI_RENDER_TSM:
        printf("\"spp\":%d,\"maps\":%d,\"map_size\":%d,\"slices\":%d,\"sigma\":%.6g,\"map_bytes\":%lu,\"maps_ms\":%.3f,\"shade_ms\":%.3f,\"ms\":%.3f,", u->samples,
               f->maps, u->tsm.maps.size ? u->tsm.maps.size : 512, u->tsm.maps.slices ? u->tsm.maps.slices : 64, (double)u->tsm.maps.sigma, (unsigned long)f->bytes,
               voxgi_render_stage_ms(f, "maps"), voxgi_render_stage_ms(f, "shade"), f->ms);
        break;
    case VOXGI_RENDER_RSM:
        printf("\"maps\":%d,\"map_size\":%d,\"samples\":%d,\"visibility\":%s,\"res\":%d,\"gather_stride\":%d,\"gathered\":%lu,\"maps_ms\":%.3f,"
               "\"voxels_ms\":%.3f,\"direct_ms\":%.3f,\"gather_ms\":%.3f,\"ms\":%.3f,",
               f->maps, u->rsm.maps.size ? u->rsm.maps.size : 256, u->rsm.maps.samples ? u->rsm.maps.samples : 100, cli_json(visibility_names[u->rsm.visibility]),
               u->resolution, u->rsm.gather_stride, (unsigned long)f->gathered, voxgi_render_stage_ms(f, "maps"), voxgi_render_stage_ms(f, "voxels"), voxgi_render_stage_ms(f, "direct"),
               voxgi_render_stage_ms(f, "gather"), f->ms);
        break;
    case VOXGI_RENDER_SH:
        printf("\"res\":%d,\"opening\":%.6g,\"visibility\":%s,\"gather_stride\":%d,\"gathered\":%lu,\"sh_ms\":%.3f,\"voxels_ms\":%.3f,\"direct_ms\":%.3f,"
               "\"gather_ms\":%.3f,\"ms\":%.3f,",
               u->resolution, (double)u->sh.opening, cli_json(visibility_names[u->sh.visibility]), u->sh.gather_stride, (unsigned long)f->gathered, voxgi_render_stage_ms(f, "sh"),
               voxgi_render_stage_ms(f, "voxels"), voxgi_render_stage_ms(f, "direct"), voxgi_render_stage_ms(f, "gather"), f->ms);
        break;
    case VOXGI_RENDER_SSAO:
    case VOXGI_RENDER_VAO:
        printf("\"radius\":%.6g,\"rays\":%d,\"steps\":%d,\"point_sampling\":%d,\"res\":%d,\"gbuffer_ms\":%.3f,\"voxels_ms\":%.3f,\"ao_ms\":%.3f,\"ms\":%.3f,",
               (double)sc->radius, sc->rays, sc->steps, sc->point_sampling, u->resolution ? u->resolution : 128, voxgi_render_stage_ms(f, "gbuffer"), voxgi_render_stage_ms(f, "voxels"),
               voxgi_render_stage_ms(f, "ao"), f->ms);
        break;
    case VOXGI_RENDER_SSGI:
    case VOXGI_RENDER_HYBRID:
        printf("\"radius\":%.6g,\"rays\":%d,\"steps\":%d,\"half_res\":%d,\"blur\":%d,\"hidden_light\":%d,\"gathered\":%lu,\"direct_ms\":%.3f,\"voxels_ms\":%.3f,"
               "\"inject_ms\":%.3f,\"gather_ms\":%.3f,\"ms\":%.3f,",
               (double)sc->radius, sc->rays, sc->steps, sc->half_resolution == VOXGI_TOGGLE_ON, sc->blur > 0 ? sc->blur : 0, sc->hidden_light == VOXGI_TOGGLE_ON,
               (unsigned long)f->gathered, voxgi_render_stage_ms(f, "direct"), voxgi_render_stage_ms(f, "voxels"), voxgi_render_stage_ms(f, "inject"), voxgi_render_stage_ms(f, "gather"), f->ms);
        break;
    case VOXGI_RENDER_LINESPACE: {
        const voxgi_linespace_info *t = &f->tree;
        const voxgi_linespace_stats *r = &f->shadow_rays;
        double shadows = voxgi_render_stage_ms(f, "shadows");
        printf("\"mode\":%s,\"packets\":%d,\"n\":%d,\"depth\":%d,\"samples\":%d,\"supersample\":%d,\"lights\":%d,\"nodes\":%lu,\"line_spaces\":%lu,\"leaves\":%lu,"
               "\"triangle_refs\":%lu,\"bytes\":%lu,\"allocated\":%lu,\"rays\":%llu,\"nodes_entered\":%llu,\"bits_read\":%llu,\"triangle_tests\":%llu,"
               "\"build_ms\":%.3f,\"gbuffer_ms\":%.3f,\"shadows_ms\":%.3f,\"ms\":%.3f,\"mrays_per_s\":%.4g,",
               cli_json(ls_mode_names[u->linespace.mode]), u->linespace.packets, t->n, t->depth, r->samples, u->linespace.supersample, f->lights, (unsigned long)t->nodes,
               (unsigned long)t->line_spaces, (unsigned long)t->leaves, (unsigned long)t->triangle_refs, (unsigned long)t->bytes, (unsigned long)t->allocated,
               (unsigned long long)r->rays, (unsigned long long)r->nodes, (unsigned long long)r->bits, (unsigned long long)r->triangle_tests, voxgi_render_stage_ms(f, "build"),
               voxgi_render_stage_ms(f, "gbuffer"), shadows, f->ms, shadows > 0 ? (double)r->rays / shadows / 1000 : 0);
        break;
    }
    default:
        printf("\"spp\":%d,\"bounces\":%d,\"seed\":%llu,\"triangles\":%lu,\"bvh_nodes\":%lu,\"rays\":%llu,\"bvh_ms\":%.3f,\"render_ms\":%.3f,", u->samples,
               u->bounces, (unsigned long long)u->seed, (unsigned long)f->triangles, (unsigned long)f->bvh_nodes, (unsigned long long)f->rays, voxgi_render_stage_ms(f, "bvh"),
               voxgi_render_stage_ms(f, "render"));
    }
}

/* The view as the option that gives it back. */
static void print_camera(const char *indent, const voxgi_camera *c)
{
    printf("%scamera: --camera %.9g %.9g %.9g %.9g %.9g %.9g %.9g\n", indent, c->eye[0], c->eye[1], c->eye[2], c->target[0], c->target[1], c->target[2],
           c->fovy_degrees);
}

static void print_result(const render_args *a, const char *name, const voxgi_info *ci, const float *rgb, const voxgi_render_info *f, const render_compare *cmp)
{
    const voxgi_render_desc *u = &f->used;
    voxgi_render_desc ref = reference_for(u);
    double mean[3] = {0, 0, 0};
    size_t p;
    int i, w = u->camera.width, h = u->camera.height, m = (int)u->method, backend = m == VOXGI_RENDER_VCT || m == VOXGI_RENDER_LINESPACE;
    char settings[1024];
    for (p = 0; p < (size_t)w * (size_t)h; p++)
        for (i = 0; i < 3; i++) mean[i] += rgb[3 * p + (size_t)i];
    for (i = 0; i < 3; i++) mean[i] /= (double)w * h;
    if (a->common.json) {
        printf("{\"scene\":%s,\"method\":%s,", cli_json(name), cli_json(voxgi_render_method_name(u->method)));
        if (backend) printf("\"backend\":%s,", cli_json(voxgi_backend_name(ci->backend)));
        printf("\"size\":[%d,%d],\"camera\":[%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g],", w, h, u->camera.eye[0], u->camera.eye[1], u->camera.eye[2],
               u->camera.target[0], u->camera.target[1], u->camera.target[2], u->camera.fovy_degrees);
        print_json_fields(f);
        if (m == VOXGI_RENDER_SSAO || m == VOXGI_RENDER_VAO) printf("\"mean\":%.6g,", mean[0]);
        else printf("\"mean\":[%.6g,%.6g,%.6g],", mean[0], mean[1], mean[2]);
        if (a->compare || a->reference) print_compare_json(cmp);
        else if (m == VOXGI_RENDER_VCT) printf("\"rel_rmse\":-1,\"rms\":0,\"reference_ms\":0.000,"); /* nothing compared */
        printf("\"output\":%s}\n", cli_json(a->out));
        return;
    }
    voxgi_render_describe(u, settings, sizeof settings);
    printf("%s: %s\n", name, settings);
    print_camera("  ", &u->camera);
    printf("  %s: ", voxgi_backend_name(ci->backend));
    for (i = 0; i < f->stage_count; i++) printf("%s %.1f ms, ", f->stages[i].name, f->stages[i].ms);
    printf("total %.1f ms", f->ms);
    if (f->bytes) printf("; built %.2f MB", f->bytes / 1e6);
    if (f->gathered) printf("; %lu pixels gathering", (unsigned long)f->gathered);
    if (f->rays) printf("; %llu rays", (unsigned long long)f->rays);
    if (m == VOXGI_RENDER_LINESPACE) printf("; %d area light%s, %llu shadow rays", f->lights, f->lights == 1 ? "" : "s", (unsigned long long)f->shadow_rays.rays);
    printf("\n  mean %s %.4g %.4g %.4g -> %s\n", m == VOXGI_RENDER_SSAO || m == VOXGI_RENDER_VAO ? "occlusion" : "radiance", mean[0], mean[1], mean[2], a->out);
    if (a->compare || a->reference) print_compare(a, &ref, cmp);
}

/* The render desc of the command line: what was given, every other field zero (the library's
   default, which the plan and the info report). */
static void render_desc_of(const render_args *a, voxgi_render_desc *d)
{
    static const voxgi_render_method methods[] = {VOXGI_RENDER_REFERENCE, VOXGI_RENDER_VCT,  VOXGI_RENDER_TSM,    VOXGI_RENDER_RSM,   VOXGI_RENDER_SH,
                                                  VOXGI_RENDER_SSAO,      VOXGI_RENDER_VAO,  VOXGI_RENDER_SSGI,   VOXGI_RENDER_HYBRID, VOXGI_RENDER_LINESPACE};
    d->method = methods[a->method];
    d->camera.width = a->size[0];
    d->camera.height = a->size[1];
    d->samples = a->spp_given ? a->spp : 0;
    d->seed = (uint64_t)a->seed;
    d->resolution = a->res_given ? a->res : 0;
    d->bounces = a->bounces;
    d->direct_only = a->bounces == 0 || a->no_gi;
    d->vct.radiance = a->octree ? VOXGI_VCT_OCTREE : a->isotropic ? VOXGI_VCT_ISOTROPIC : a->anisotropic ? VOXGI_VCT_ANISOTROPIC : VOXGI_VCT_RADIANCE_DEFAULT;
    d->vct.cones.cones = a->cones;
    d->vct.cones.step = (float)a->step;
    d->vct.cone_stride = a->cone_stride;
    d->vct.inject_samples = a->inject_samples;
    d->vct.bounce_cones.cones = a->bounce_cones;
    d->vct.bounce_block = a->bounce_block;
    d->vct.octree_format = (voxgi_svo_format)a->octree_format;
    d->vct.octree_bricks = a->bricks;
    d->tsm.maps.size = a->tsm_size;
    d->tsm.maps.slices = a->slices;
    d->tsm.maps.sigma = (float)a->sigma;
    d->rsm.maps.size = a->rsm_size;
    d->rsm.maps.samples = a->rsm_samples;
    d->rsm.maps.radius = (float)a->rsm_radius;
    d->rsm.maps.points = a->rsm_points;
    d->rsm.visibility = d->sh.visibility = (voxgi_traversal)a->visibility;
    d->rsm.gather_stride = d->sh.gather_stride = a->gather_stride;
    d->sh.opening = (float)a->opening;
    d->screen.rays = a->rays;
    d->screen.steps = a->march_steps;
    d->screen.radius = (float)a->radius;
    d->screen.point_sampling = a->point_sampling;
    d->screen.half_resolution = !a->half_res_given ? VOXGI_TOGGLE_DEFAULT : a->half_res ? VOXGI_TOGGLE_ON : VOXGI_TOGGLE_OFF;
    d->screen.blur = !a->blur_given ? 0 : a->blur ? a->blur : -1;
    d->screen.hidden_light = !a->hidden_light_given ? VOXGI_TOGGLE_DEFAULT : a->hidden_light ? VOXGI_TOGGLE_ON : VOXGI_TOGGLE_OFF;
    d->screen.inject_samples = a->inject_samples;
    d->linespace.mode = (voxgi_linespace_mode)a->ls_mode;
    d->linespace.samples = a->samples;
    d->linespace.packets = a->packets;
    d->linespace.exact_ends = a->exact_ends;
    d->linespace.supersample = a->supersample;
    d->linespace.tree.n = a->ls_n;
    d->linespace.tree.depth = a->ls_depth;
    d->linespace.tree.memory_budget = (size_t)a->ls_budget << 20;
    d->reference.ao_radius = (float)a->ao_radius;
    d->reference.screen_light_only = a->screen_light_only;
    d->error = a->error;
    d->memory_budget = (size_t)(a->budget_mb * 1048576.0);
}

static int render_run(cli_session *s, const render_args *a)
{
    voxgi_render_desc d;
    voxgi_render_info info;
    voxgi_info ci;
    render_scene rs;
    cli_context c;
    cli_common options = a->common;
    float *rgb = NULL;
    size_t bytes;
    render_compare cmp;
    int rc = CLI_EXIT_FAILURE, i;
    memset(&d, 0, sizeof d);
    memset(&rs, 0, sizeof rs);
    memset(&cmp, 0, sizeof cmp);
    if (a->method == 0) options.backend = VOXGI_BACKEND_CPU; /* the path tracer runs on the CPU */
    if (cli_context_open_options(s, &c, &options)) return CLI_EXIT_FAILURE;
    voxgi_query_info(c.vx, &ci);
    if (scene_open(s, c.vx, a, &rs, &d)) goto done;
    render_desc_of(a, &d);
    if (voxgi_render_resolve(c.vx, rs.scene, &d, &info.used) != VOXGI_OK) {
        cli_fail_lib(s, c.vx, NULL);
        goto done;
    }
    bytes = (size_t)info.used.camera.width * (size_t)info.used.camera.height * 12;
    if (!(rgb = (float *)malloc(bytes))) {
        cli_fail(s, "out of memory");
        goto done;
    }
    if (voxgi_render(c.vx, rs.scene, &d, rgb, bytes, &info) != VOXGI_OK) {
        cli_fail_lib(s, c.vx, NULL);
        goto done;
    }
    for (i = 0; i < info.plan.item_count; i++) /* the plan, once: what the image left out, and why */
        if (!info.plan.items[i].kept) cli_note(s, "plan: %s: left out - %s", info.plan.items[i].name, info.plan.items[i].why);
    if (a->compare && compare_with_reference(s, c.vx, a, rs.scene, &info.used, &cmp)) goto done;
    if (a->reference && compare_with_file(s, c.vx, a, rs.scene, &info.used.camera, rgb, &cmp)) goto done;
    errno = 0; /* a short write may leave none */
    if ((cli_has_extension(a->out, ".pfm") ? vxt_write_pfm(a->out, rgb, info.used.camera.width, info.used.camera.height)
                                           : vxt_write_png(a->out, rgb, info.used.camera.width, info.used.camera.height, (float)a->exposure)) != 0) {
        cli_fail(s, "cannot write %s: %s", a->out, cli_io_why(errno));
        goto done;
    }
    cli_status_clear(s);
    print_result(a, rs.name, &ci, rgb, &info, &cmp);
    rc = CLI_EXIT_OK;
done:
    free(rgb);
    scene_close(c.vx, &rs);
    cli_context_close(s, &c);
    return rc;
}

/* The command line of `voxgi render` (plan 0) or `voxgi plan` (plan 1: the same options, no image,
   and the plan's flags): CLI_CONTINUE, or the exit code. */
static int render_parse(int argc, char **argv, render_args *ap, int plan)
{
    render_args a;
    int rc;
    memset(&a, 0, sizeof a);
    a.bounces = 1;
    a.spp = 64;
    a.up = UP_Y;
    a.size[0] = a.size[1] = 256;
    a.exposure = 1;
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
            {.name = "--step", .arg = "S", .kind = CLI_DOUBLE, .dst = &a.step, .lo = 0.01, .hi = 4,
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
             .help = "random seed (default 0); the same seed gives the same image"},
            {.name = "--camera", .arg = "EX EY EZ TX TY TZ FOVY", .kind = CLI_DOUBLE, .count = 7, .dst = a.camera, .lo = -HUGE_VAL, .hi = HUGE_VAL,
             .given = &a.have_camera,
             .help = "eye, target (up +Y) and vertical field of view in degrees\n"
                     "(default: the scene's view; for a mesh, a view of its bounds)"},
            {.name = "--size", .arg = "W H", .kind = CLI_INT, .count = 2, .dst = a.size, .lo = 1, .hi = 16384, .help = "image size (default 256 256)"},
            {.name = "--sun", .arg = "DX DY DZ E", .kind = CLI_DOUBLE, .count = 4, .dst = a.sun, .lo = -HUGE_VAL, .hi = HUGE_VAL, .given = &a.have_sun,
             .help = "add a directional light travelling along D with irradiance E (without\nit an unlit scene gets a sun from the camera's upper left, said on stderr)"},
            {.name = "--up", .arg = "x|y|z|-x|-y|-z", .kind = CLI_ENUM, .dst = &a.up, .names = up_names,
             .help = "a mesh's up axis (default y): the mesh is turned so that it points up, and\nwithout --camera seen from a three-quarter view above its front (+Z for\ny up, -Y for z up) framing its whole bounding sphere"},
            {.name = "--exposure", .arg = "X", .kind = CLI_DOUBLE, .dst = &a.exposure, .lo = 0, .hi = HUGE_VAL,
             .help = "PNG only: scale before clamping (default 1)"},
            {.name = "--error", .arg = "E", .kind = CLI_DOUBLE, .dst = &a.error, .lo = 0, .hi = 1, .lo_open = 1,
             .help = "vct: the relative RMSE wanted (e.g. 0.08): the grid, cones and stride\nnot given come from the cone tracer's measured front"},
            {.name = "--budget", .arg = "MB", .kind = CLI_DOUBLE, .dst = &a.budget_mb, .lo = 0, .hi = 1e9, .lo_open = 1,
             .help = "the memory budget (vct: the octree when the dense volume is over it)"},
            {.name = "--dynamic", .kind = CLI_FLAG, .dst = &a.dynamic, .help = "plan: the geometry moves every frame (default: a static scene)"},
            {.name = "--everything", .kind = CLI_FLAG, .dst = &a.everything, .help = "plan: keep every item the method has (what the plan saves)"},
            CLI_OPT_THREADS(&a.common),
            CLI_OPT_JSON(&a.common, "print one JSON object (timings, rays, mean radiance) instead of text"),
            {.name = "-o", .arg = "OUT.png|OUT.pfm", .kind = CLI_STRING, .dst = &a.out,
             .help = "the image (required): PNG, 8-bit sRGB, or PFM, linear float radiance"}};
        const cli_command cmd = {.name = plan ? "plan" : "render", .help = plan ? plan_help : render_help, .column = 27, .options = options, .option_count = CLI_COUNT(options),
                                 .operand = "scene or mesh", .operands = &a.what, .min_operands = 1, .max_operands = 1};
        if ((rc = cli_parse(&cmd, argc, argv)) != CLI_CONTINUE) return rc;
    }
    /* the file type is checked before any work: a typo must not cost a long render */
    if (!plan && !a.out) return cli_usage("render", "-o OUT.png or OUT.pfm is needed");
    if (!plan && !cli_has_extension(a.out, ".png") && !cli_has_extension(a.out, ".pfm"))
        return cli_usage("render", "-o %s: render writes .png or .pfm images only", a.out);
    if (!plan && (a.dynamic || a.everything)) return cli_usage("render", "--dynamic and --everything are voxgi plan's");
    if (a.method == METHOD_VCT && a.bounces == 0 && !a.no_gi) return cli_usage(plan ? "plan" : "render", "--method vct needs --bounces 1 or more, or -1 (or --no-gi)");
    if (a.method == METHOD_VCT && a.bounces > 64) return cli_usage(plan ? "plan" : "render", "--method vct: --bounces %d, at most 64", a.bounces);
    if (a.anisotropic && a.isotropic) return cli_usage(plan ? "plan" : "render", "--anisotropic and --isotropic: one or the other");
    if (a.compare && a.reference) return cli_usage(plan ? "plan" : "render", "--compare and --reference: one or the other");
    if (a.cornell_mesh && strcmp(a.what, "cornell-box") != 0)
        return cli_usage(plan ? "plan" : "render", "--cornell-mesh replaces the tall block of the scene cornell-box, not of '%s'", a.what);
    *ap = a;
    return CLI_CONTINUE;
}

int cmd_render(int argc, char **argv)
{
    render_args a;
    cli_session s;
    int rc;
    if ((rc = render_parse(argc, argv, &a, 0)) != CLI_CONTINUE) return rc;
    cli_session_init(&s, "render");
    return render_run(&s, &a);
}

static void print_plan_bytes(uint64_t b, int estimated)
{
    if (b >= 1048576) printf(" (%s%.1f MB)", estimated ? "~" : "", (double)b / 1048576.0);
    else if (b >= 1024) printf(" (%s%.1f KB)", estimated ? "~" : "", (double)b / 1024.0);
    else if (b) printf(" (%s%lu bytes)", estimated ? "~" : "", (unsigned long)b);
}

/* voxgi plan: the settings and the plan voxgi render would run with for the same options. */
int cmd_plan(int argc, char **argv)
{
    static const char *const kinds[] = {"channel", "structure", "pass"};
    render_args a;
    cli_session s;
    cli_context c;
    render_scene rs;
    voxgi_render_desc d, used;
    voxgi_plan_info p;
    char settings[1024];
    int rc, i;
    if ((rc = render_parse(argc, argv, &a, 1)) != CLI_CONTINUE) return rc;
    cli_session_init(&s, "plan");
    memset(&d, 0, sizeof d);
    memset(&rs, 0, sizeof rs);
    if (a.method == 0) a.common.backend = VOXGI_BACKEND_CPU;
    if (cli_context_open_options(&s, &c, &a.common)) return CLI_EXIT_FAILURE;
    rc = CLI_EXIT_FAILURE;
    if (scene_open(&s, c.vx, &a, &rs, &d)) goto done;
    render_desc_of(&a, &d);
    if (voxgi_render_resolve(c.vx, rs.scene, &d, &used) != VOXGI_OK ||
        voxgi_plan(c.vx, rs.scene, &d, (a.dynamic ? VOXGI_PLAN_DYNAMIC : 0u) | (a.everything ? VOXGI_PLAN_EVERYTHING : 0u), &p) != VOXGI_OK) {
        cli_fail_lib(&s, c.vx, "planning");
        goto done;
    }
    voxgi_render_describe(&used, settings, sizeof settings);
    printf("%s: %s\n", rs.name, settings);
    printf("scene: %lu triangles (%lu emissive, %lu translucent, %lu reflective), surface %.4g\n", (unsigned long)p.triangles, (unsigned long)p.emissive_triangles,
           (unsigned long)p.translucent_triangles, (unsigned long)p.reflective_triangles, p.surface_area);
    printf("lights: %d point, %d spot, %d directional, %d rect; area lights %d; the camera %s\n", p.point_lights, p.spot_lights, p.directional_lights,
           p.rect_lights, p.area_lights, p.emitters_in_view ? "sees an emitter" : "sees no emitter");
    print_camera("", &used.camera);
    if (used.resolution)
        printf("grid: %d voxels along the longest side (%d x %d x %d with a voxel of padding), ~%llu set (%.2f%%)\n", used.resolution, p.grid.res[0],
               p.grid.res[1], p.grid.res[2], (unsigned long long)p.voxels, 100 * p.occupancy);
    if (used.error > 0)
        printf("error: %.2f%% on the Cornell box against %.2f%% asked%s\n", 100 * p.expected_error, 100 * used.error, p.error_reachable ? "" : " (not reached: the closest)");
    for (i = 0; i < p.item_count; i++) {
        const voxgi_plan_item *it = &p.items[i];
        printf("  %-22s %-9s %s - %s", it->name, kinds[it->kind], it->kept ? "kept" : "left out", it->why);
        if (it->kept) print_plan_bytes(it->bytes, it->estimated);
        printf("\n");
    }
    printf("memory of what is kept: %.1f MB\n", (double)p.bytes / 1048576.0);
    rc = CLI_EXIT_OK;
done:
    scene_close(c.vx, &rs);
    cli_context_close(&s, &c);
    return rc;
}
