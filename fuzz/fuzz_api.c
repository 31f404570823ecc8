/* fuzz/fuzz_api.c - libFuzzer harness: the public API on a CPU context, fed descs built from the
 * fuzzer's bytes. A scene (meshes with float or double positions at any stride, aligned or not,
 * NaN, infinite, denormal and huge coordinates, indices in and out of range, material ids,
 * materials and lights with odd values and unknown enum values), then a voxelization (a small
 * grid, given or fitted, every enum of the desc including unknown values), what is built on its
 * voxels (reduction, volume, octree, light and cones, segments), rays, and an image of a few
 * pixels (every method and unknown ones, each method's part). Every call must succeed or return an
 * error; ASan and UBSan watch the rest. The arrays are allocated to the exact bytes the desc
 * describes, so a read past them is caught. Grids stay within 32 voxels a side and images within
 * 8 x 8 pixels, so that one execution stays short. */
#include "fuzz.h"

#define MAX_MESHES 2
#define MAX_VERTICES 16

typedef struct scene_storage {
    voxgi_mesh meshes[MAX_MESHES];
    void *arrays[MAX_MESHES][5]; /* positions, normals, uvs, indices, material ids */
    voxgi_material materials[4];
    voxgi_light lights[4];
} scene_storage;

/* A value in [0, 1] most of the time (a valid albedo), else any float. */
static float unit_or_odd(fuzz_bytes *b)
{
    unsigned k = fuzz_u8(b);
    return k < 200 ? (float)k / 199.0f : fuzz_float(b);
}

/* Bytes between elements: 0 (the default), the tight size, more, too little, or not a multiple
   of the element's alignment. */
static size_t pick_stride(fuzz_bytes *b, size_t element)
{
    static const size_t extra[8] = {0, 0, 4, 1, 2, 20, 0, 3};
    unsigned k = fuzz_below(b, 10);
    if (k == 0) return 0;
    if (k == 9) return element / 2; /* too small: refused */
    return element + extra[k % 8];
}

/* count elements of `width` values of `size` bytes each at `stride` (0: tight), in exactly the
   bytes they need; a float or double per value from the fuzzer. */
static void *fill_array(fuzz_bytes *b, size_t count, size_t stride, int width, size_t size)
{
    size_t step = stride ? stride : (size_t)width * size, bytes = count ? (count - 1) * step + (size_t)width * size : 1, i;
    unsigned char *p = (unsigned char *)malloc(bytes);
    int k;
    FUZZ_CHECK(p != NULL);
    memset(p, 0, bytes);
    for (i = 0; i < count; i++)
        for (k = 0; k < width; k++) {
            unsigned char *at = p + i * step + (size_t)k * size;
            if (size == sizeof(double)) {
                double d = fuzz_double(b);
                memcpy(at, &d, sizeof d);
            } else {
                float f = fuzz_float(b);
                memcpy(at, &f, sizeof f);
            }
        }
    return p;
}

static void build_mesh(fuzz_bytes *b, voxgi_mesh *m, void *arrays[5], size_t material_count)
{
    size_t triangles, i;
    int doubles = fuzz_below(b, 4) == 0;
    memset(m, 0, sizeof *m);
    m->vertex_count = fuzz_below(b, MAX_VERTICES + 1);
    m->position_stride = pick_stride(b, doubles ? 3 * sizeof(double) : 3 * sizeof(float));
    arrays[0] = fill_array(b, m->vertex_count, m->position_stride, 3, doubles ? sizeof(double) : sizeof(float));
    if (doubles) m->positions_double = (const double *)arrays[0];
    else m->positions = (const float *)arrays[0];
    if (fuzz_below(b, 3) == 0) {
        m->normal_stride = pick_stride(b, 3 * sizeof(float));
        m->normals = (const float *)(arrays[1] = fill_array(b, m->vertex_count, m->normal_stride, 3, sizeof(float)));
    }
    if (fuzz_below(b, 3) == 0) {
        m->uv_stride = pick_stride(b, 2 * sizeof(float));
        m->uvs = (const float *)(arrays[2] = fill_array(b, m->vertex_count, m->uv_stride, 2, sizeof(float)));
    }
    if (fuzz_below(b, 4) != 0) {
        uint32_t *idx;
        m->index_count = fuzz_below(b, 25);
        FUZZ_CHECK((idx = (uint32_t *)malloc(m->index_count ? m->index_count * sizeof *idx : 1)) != NULL);
        for (i = 0; i < m->index_count; i++) {
            unsigned k = fuzz_u8(b);
            idx[i] = k < 240 ? (uint32_t)(k % (m->vertex_count + 2)) : k < 248 ? UINT32_MAX : 0x80000000u;
        }
        m->indices = idx;
        arrays[3] = idx;
    }
    triangles = m->indices ? m->index_count / 3 : m->vertex_count / 3;
    if (fuzz_below(b, 3) == 0) {
        uint32_t *ids;
        FUZZ_CHECK((ids = (uint32_t *)malloc(triangles ? triangles * sizeof *ids : 1)) != NULL);
        for (i = 0; i < triangles; i++) {
            unsigned k = fuzz_u8(b);
            ids[i] = k < 250 ? (uint32_t)(k % (material_count + 2)) : UINT32_MAX;
        }
        m->material_ids = ids;
        arrays[4] = ids;
    }
    m->material = fuzz_below(b, 8) == 0 ? UINT32_MAX : fuzz_below(b, 3);
}

static void build_scene(fuzz_bytes *b, voxgi_scene *scene, scene_storage *s)
{
    size_t i;
    int c;
    memset(scene, 0, sizeof *scene);
    memset(s, 0, sizeof *s);
    scene->material_count = fuzz_below(b, 5);
    for (i = 0; i < scene->material_count; i++) {
        for (c = 0; c < 3; c++) {
            s->materials[i].albedo[c] = unit_or_odd(b);
            s->materials[i].emission[c] = fuzz_below(b, 4) ? 0 : unit_or_odd(b);
        }
        s->materials[i].transparency = fuzz_below(b, 2) ? 0 : unit_or_odd(b);
    }
    scene->materials = scene->material_count || fuzz_below(b, 2) ? s->materials : NULL;
    scene->mesh_count = 1 + fuzz_below(b, MAX_MESHES);
    for (i = 0; i < scene->mesh_count; i++) build_mesh(b, &s->meshes[i], s->arrays[i], scene->material_count);
    scene->meshes = s->meshes;
    scene->light_count = fuzz_below(b, 5);
    for (i = 0; i < scene->light_count; i++) {
        voxgi_light *L = &s->lights[i];
        L->type = (voxgi_light_type)fuzz_int(b, 6); /* 4 and 5 are no type */
        for (c = 0; c < 3; c++) {
            L->position[c] = fuzz_float(b);
            L->direction[c] = fuzz_float(b);
            L->intensity[c] = unit_or_odd(b) * 4;
            L->edge_u[c] = fuzz_float(b);
            L->edge_v[c] = fuzz_float(b);
        }
        L->spot_inner = unit_or_odd(b);
        L->spot_outer = unit_or_odd(b) * 3;
    }
    scene->lights = scene->light_count || fuzz_below(b, 2) ? s->lights : NULL;
    if (fuzz_below(b, 8) == 0)
        for (c = 0; c < 3; c++) scene->origin[c] = fuzz_double(b);
}

static void free_scene(scene_storage *s)
{
    int i, k;
    for (i = 0; i < MAX_MESHES; i++)
        for (k = 0; k < 5; k++) free(s->arrays[i][k]);
}

/* A voxgi_attribute set or a single one: known bits mostly, unknown ones sometimes. */
static unsigned pick_attributes(fuzz_bytes *b) { return fuzz_below(b, 8) ? fuzz_u8(b) & 0x7Fu : fuzz_u32(b); }

/* Segments, rays, samples and cones at a few points of the grid's box (or anywhere). */
static void probe_points(fuzz_bytes *b, const voxgi_grid *g, float points[12])
{
    int i, a;
    for (i = 0; i < 4; i++)
        for (a = 0; a < 3; a++)
            points[3 * i + a] = fuzz_below(b, 4) ? (float)(g->origin[a] + g->voxel_size * g->res[a] * (float)fuzz_u8(b) / 255.0f) : fuzz_float(b);
}

static void on_voxels(fuzz_bytes *b, voxgi_context *ctx, const voxgi_scene *scene, voxgi_voxels *vox)
{
    voxgi_voxels_info info;
    size_t needed = 0;
    void *buf;
    float points[12], normals[12], irradiance[12], occlusion[4];
    unsigned char occluded[2];
    int factor[3], a;
    voxgi_voxels *reduced = NULL;
    voxgi_volume *volume = NULL, *radiance = NULL;
    voxgi_svo *svo = NULL;
    voxgi_volume_desc vd;
    voxgi_svo_desc sd;
    voxgi_inject_desc id;
    voxgi_radiance_source source;
    voxgi_cone_desc cd;
    voxgi_voxels_query(vox, &info);
    FUZZ_CHECK(voxgi_voxels_read(ctx, vox, NULL, 0, &needed) == VOXGI_OK);
    FUZZ_CHECK((buf = malloc(needed ? needed : 1)) != NULL);
    FUZZ_CHECK(voxgi_voxels_read(ctx, vox, (uint32_t *)buf, needed, NULL) == VOXGI_OK);
    free(buf);
    for (a = 0; a < 4; a++) {
        voxgi_attribute which = (voxgi_attribute)(1u << a);
        if (!(info.attributes & (unsigned)which)) continue;
        FUZZ_CHECK(voxgi_voxels_read_attribute(ctx, vox, which, NULL, 0, &needed) == VOXGI_OK);
        FUZZ_CHECK((buf = malloc(needed ? needed : 1)) != NULL);
        FUZZ_CHECK(voxgi_voxels_read_attribute(ctx, vox, which, (float *)buf, needed, NULL) == VOXGI_OK);
        free(buf);
    }
    probe_points(b, &info.grid, points);
    (void)voxgi_voxels_occluded(ctx, vox, (voxgi_traversal)fuzz_int(b, 4), 2, points, points + 6, occluded, NULL);
    for (a = 0; a < 3; a++) factor[a] = fuzz_int(b, 4);
    if (voxgi_voxels_reduce(ctx, vox, factor, &reduced) == VOXGI_OK) voxgi_voxels_destroy(ctx, reduced);
    memset(&vd, 0, sizeof vd);
    vd.attributes = pick_attributes(b);
    vd.filter = (voxgi_mip_filter)fuzz_int(b, 3);
    vd.levels = fuzz_int(b, 8);
    if (voxgi_volume_create(ctx, vox, &vd, &volume) == VOXGI_OK) {
        float lods[4], out[16];
        for (a = 0; a < 4; a++) lods[a] = fuzz_float(b);
        (void)voxgi_volume_sample(ctx, volume, (voxgi_attribute)pick_attributes(b), (voxgi_direction)fuzz_int(b, 7), 4, points, lods, out);
    }
    memset(&id, 0, sizeof id);
    id.volume = vd;
    id.samples = fuzz_count(b, 5);
    id.seed = fuzz_u8(b);
    id.bounces = fuzz_int(b, 4) - 1;
    id.gather.cones = fuzz_int(b, 5);
    id.gather.half_angle = fuzz_below(b, 2) ? 0 : fuzz_float(b);
    id.gather_block = fuzz_int(b, 5);
    id.one_sided = fuzz_int(b, 3);
    if (voxgi_inject_light(ctx, scene, vox, &id, &radiance) == VOXGI_OK) {
        memset(&sd, 0, sizeof sd);
        sd.attributes = pick_attributes(b);
        sd.neighbours = fuzz_int(b, 3);
        sd.bricks = fuzz_int(b, 3);
        sd.format = (voxgi_svo_format)fuzz_int(b, 3);
        sd.radiance = radiance;
        memset(&source, 0, sizeof source);
        if (voxgi_svo_create(ctx, vox, &sd, &svo) == VOXGI_OK && fuzz_below(b, 2)) source.octree = svo;
        else source.volume = radiance;
        memset(&cd, 0, sizeof cd);
        cd.cones = fuzz_int(b, 9);
        cd.half_angle = fuzz_below(b, 2) ? 0 : fuzz_float(b);
        cd.step = fuzz_below(b, 2) ? 0 : fuzz_float(b);
        cd.offset = fuzz_below(b, 2) ? 0 : fuzz_float(b);
        cd.max_distance = fuzz_below(b, 2) ? 0 : fuzz_float(b);
        cd.seen_from_eye = fuzz_int(b, 2);
        for (a = 0; a < 3; a++) cd.eye[a] = fuzz_double(b);
        for (a = 0; a < 12; a++) normals[a] = fuzz_float(b);
        (void)voxgi_cone_trace(ctx, &source, &cd, 4, points, normals, irradiance, occlusion);
    }
    voxgi_svo_destroy(ctx, svo);
    voxgi_volume_destroy(ctx, radiance);
    voxgi_volume_destroy(ctx, volume);
}

static void voxelize(fuzz_bytes *b, voxgi_context *ctx, const voxgi_scene *scene)
{
    voxgi_voxelize_desc d;
    voxgi_voxels *vox = NULL;
    voxgi_result r;
    int a;
    memset(&d, 0, sizeof d);
    if (fuzz_below(b, 2)) {
        voxgi_fit_desc fit;
        memset(&fit, 0, sizeof fit);
        fit.res = fuzz_int_from(b, 1, 32);
        fit.per_axis = fuzz_int(b, 2);
        fit.padding = fuzz_below(b, 2) ? 0 : fuzz_double(b);
        if (voxgi_fit_grid(ctx, scene, &fit, &d.grid) != VOXGI_OK) return;
        if (d.grid.res[0] > 32 || d.grid.res[1] > 32 || d.grid.res[2] > 32) return; /* padding made it large */
    } else {
        for (a = 0; a < 3; a++) {
            d.grid.origin[a] = fuzz_double(b);
            d.grid.res[a] = fuzz_int_from(b, 1, 32);
        }
        d.grid.voxel_size = fuzz_double(b);
    }
    d.method = (voxgi_method)fuzz_int(b, VOXGI_METHOD_COUNT_ + 1);
    d.axis = (voxgi_axis)fuzz_int(b, 5);
    d.solid_mode = (voxgi_solid_mode)fuzz_int(b, 4);
    d.atomic = fuzz_int(b, 2);
    d.atlas_size = fuzz_int(b, 64);
    d.atlas_uv = (voxgi_atlas_uv)fuzz_int(b, 3);
    d.attributes = fuzz_below(b, 2) ? 0 : pick_attributes(b);
    for (a = 0; a < 4; a++) d.blend[a] = (voxgi_blend)fuzz_int(b, 4);
    d.volume_slicing = fuzz_int(b, 4);
    r = voxgi_voxelize(ctx, scene, &d, &vox);
    FUZZ_CHECK((r == VOXGI_OK) == (vox != NULL));
    if (r != VOXGI_OK) return;
    on_voxels(b, ctx, scene, vox);
    voxgi_voxels_destroy(ctx, vox);
}

static void rays(fuzz_bytes *b, voxgi_context *ctx, const voxgi_scene *scene)
{
    voxgi_ray_scene *rs = NULL;
    voxgi_ray ray[2];
    voxgi_ray_hit hits[2];
    unsigned char occluded[2];
    int i, a;
    if (voxgi_ray_scene_create(ctx, scene, &rs) != VOXGI_OK) return;
    for (i = 0; i < 2; i++) {
        for (a = 0; a < 3; a++) {
            ray[i].origin[a] = fuzz_float(b);
            ray[i].direction[a] = fuzz_float(b);
        }
        ray[i].tmin = fuzz_below(b, 2) ? 0 : fuzz_float(b);
        ray[i].tmax = fuzz_below(b, 2) ? INFINITY : fuzz_float(b);
    }
    (void)voxgi_ray_intersect(ctx, rs, 2, ray, hits);
    (void)voxgi_ray_occluded(ctx, rs, 2, ray, occluded);
    voxgi_ray_scene_destroy(ctx, rs);
}

static void render(fuzz_bytes *b, voxgi_context *ctx, const voxgi_scene *scene)
{
    voxgi_render_desc d;
    voxgi_render_info info;
    voxgi_voxels *vox = NULL;
    voxgi_ray_scene *rs = NULL;
    size_t pixels, rgb_bytes;
    float *rgb, *visible = NULL;
    int a, valid_size;
    memset(&d, 0, sizeof d);
    d.method = (voxgi_render_method)fuzz_int(b, VOXGI_RENDER_METHOD_COUNT + 1);
    d.camera.width = fuzz_int_from(b, 1, 8);
    d.camera.height = fuzz_int_from(b, 1, 8);
    if (fuzz_below(b, 2))
        for (a = 0; a < 3; a++) {
            d.camera.eye[a] = fuzz_double(b);
            d.camera.target[a] = fuzz_double(b);
        }
    d.camera.fovy_degrees = fuzz_below(b, 2) ? 0 : fuzz_double(b);
    d.samples = fuzz_count(b, 5);
    d.seed = fuzz_u8(b);
    d.resolution = fuzz_int(b, 25);
    if (d.resolution == 0) d.resolution = 1 + fuzz_below(b, 16); /* the defaults (64 to 128) take too long here */
    d.bounces = fuzz_int(b, 4) - 1;
    d.direct_only = fuzz_int(b, 2);
    d.hide_emitters = fuzz_int(b, 2);
    d.error = fuzz_below(b, 4) ? 0 : fuzz_double(b);
    d.memory_budget = fuzz_below(b, 4) ? 0 : (size_t)fuzz_u32(b);
    d.vct.radiance = (voxgi_vct_radiance)fuzz_int(b, 5);
    d.vct.cones.cones = fuzz_int(b, 9);
    d.vct.cone_stride = fuzz_int(b, 4);
    d.vct.inject_samples = fuzz_count(b, 5);
    d.vct.sampled_direct = fuzz_int(b, 2);
    d.vct.one_sided = fuzz_int(b, 2);
    d.vct.bounce_cones.cones = fuzz_int(b, 5);
    d.vct.bounce_block = fuzz_int(b, 5);
    d.vct.octree_format = (voxgi_svo_format)fuzz_int(b, 3);
    d.vct.octree_bricks = fuzz_int(b, 2);
    d.tsm.maps.light = fuzz_below(b, 5);
    d.tsm.maps.size = fuzz_int_from(b, 1, 32);
    d.tsm.maps.slices = fuzz_int_from(b, 1, 16);
    d.tsm.maps.sigma = fuzz_below(b, 2) ? 0 : fuzz_float(b);
    d.rsm.maps.size = fuzz_int_from(b, 1, 32);
    d.rsm.maps.samples = fuzz_int(b, 16);
    d.rsm.maps.radius = fuzz_below(b, 2) ? 0 : fuzz_float(b);
    d.rsm.maps.emitters = fuzz_int(b, 2);
    d.rsm.maps.points = fuzz_int(b, 5);
    d.rsm.visibility = (voxgi_traversal)fuzz_int(b, 4);
    d.rsm.gather_stride = fuzz_int(b, 5);
    d.sh.volume.samples = fuzz_int(b, 5);
    d.sh.visibility = (voxgi_traversal)fuzz_int(b, 4);
    d.sh.opening = fuzz_below(b, 2) ? 0 : fuzz_float(b);
    d.sh.gather_stride = fuzz_int(b, 5);
    d.screen.rays = fuzz_count(b, 9);
    d.screen.steps = fuzz_count(b, 9);
    d.screen.radius = fuzz_below(b, 2) ? 0 : fuzz_float(b);
    d.screen.point_sampling = fuzz_int(b, 2);
    d.screen.half_resolution = (voxgi_toggle)fuzz_int(b, 4);
    d.screen.blur = fuzz_int(b, 6) - 1;
    d.screen.hidden_light = (voxgi_toggle)fuzz_int(b, 4);
    d.screen.inject_samples = fuzz_count(b, 5);
    d.linespace.tree.n = fuzz_int(b, 6);
    d.linespace.tree.depth = fuzz_int(b, 4);
    d.linespace.mode = (voxgi_linespace_mode)fuzz_int(b, 3);
    d.linespace.samples = fuzz_int(b, 9);
    d.linespace.packets = fuzz_int(b, 2);
    d.linespace.exact_ends = fuzz_count(b, 5);
    d.linespace.supersample = fuzz_int(b, 3);
    d.reference.ao_radius = fuzz_below(b, 2) ? 0 : fuzz_float(b);
    d.reference.screen_light_only = fuzz_int(b, 2);
    valid_size = d.camera.width >= 1 && d.camera.width <= 8 && d.camera.height >= 1 && d.camera.height <= 8;
    pixels = valid_size ? (size_t)d.camera.width * (size_t)d.camera.height : 64;
    if (fuzz_below(b, 4) == 0) FUZZ_CHECK((d.linespace.visible = visible = (float *)malloc(pixels * sizeof *visible)) != NULL);
    if (fuzz_below(b, 4) == 0 && voxgi_render_voxelize(ctx, scene, &d, &vox) == VOXGI_OK) d.voxels = vox;
    if (fuzz_below(b, 4) == 0 && voxgi_ray_scene_create(ctx, scene, &rs) == VOXGI_OK) d.rays = rs;
    rgb_bytes = pixels * 12 - (fuzz_below(b, 8) == 0 ? 4 : 0); /* sometimes a byte short: refused */
    FUZZ_CHECK((rgb = (float *)malloc(rgb_bytes)) != NULL);
    (void)voxgi_render(ctx, scene, &d, rgb, rgb_bytes, &info);
    free(rgb);
    free(visible);
    voxgi_ray_scene_destroy(ctx, rs);
    voxgi_voxels_destroy(ctx, vox);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    voxgi_context *ctx = fuzz_context();
    fuzz_bytes b;
    voxgi_scene scene;
    scene_storage storage;
    unsigned what;
    b.p = data;
    b.left = size;
    build_scene(&b, &scene, &storage);
    what = fuzz_u8(&b);
    (void)voxgi_validate_scene(ctx, &scene);
    if (what & 1) voxelize(&b, ctx, &scene);
    if (what & 2) rays(&b, ctx, &scene);
    if (what & 4) render(&b, ctx, &scene);
    free_scene(&storage);
    return 0;
}
