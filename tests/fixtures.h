/* tests/fixtures.h - what the test programs set up alike: voxgi contexts, the program's headless
 * GL context, one-mesh scenes (of a shape, of quads, the two-material sphere) and cubic grids.
 *
 * Include it after voxgi.h (tests/test_internals.c defines VOXGI_IMPLEMENTATION first; every
 * other program links the implementation). Every function is static inline, so a program may
 * use any subset of them without unused-function warnings. A program that needs GL calls
 * gl_open() at the start of main() and gl_close() at the end; its tests begin with have_gl(). */
#ifndef VOXGI_TESTS_FIXTURES_H
#define VOXGI_TESTS_FIXTURES_H
#include "../voxgi.h"
#include "../tools/headless_gl.h"
#include "../tools/shapes.h"
#include "harness.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

/* 1 in the AddressSanitizer build and the unoptimised one (-O0). Every test runs in every build;
   an oracle sweep that costs seconds there (a winding number at every voxel centre, a 4000^2 atlas
   in llvmpipe, a 256^3 leak test) runs whole in the optimised builds and on a share of its cases in
   these two, whose job is memory errors and the code as written, not more cases. */
#if defined(__SANITIZE_ADDRESS__)
#define FX_REDUCED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FX_REDUCED 1
#endif
#endif
#if !defined(FX_REDUCED) && (defined(__GNUC__) || defined(__clang__)) && !defined(__OPTIMIZE__)
#define FX_REDUCED 1
#endif
#ifndef FX_REDUCED
#define FX_REDUCED 0
#endif

/* ---------------------------------------------------------------- random numbers
   The tests' one generator (SplitMix64): seeded explicitly, so every test draws the same numbers
   on every C library and in any test order (rand() gives neither). */
typedef struct fx_rng { uint64_t state; } fx_rng;
static inline fx_rng fx_rng_seeded(uint64_t seed) { fx_rng g; g.state = seed; return g; }
static inline uint64_t fx_rng_u64(fx_rng *g)
{
    uint64_t z = (g->state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
/* Uniform in [0, 1), 53 bits. */
static inline double fx_rng_unit(fx_rng *g) { return (double)(fx_rng_u64(g) >> 11) * (1.0 / 9007199254740992.0); }
/* Uniform in [lo, hi). */
static inline double fx_rng_range(fx_rng *g, double lo, double hi) { return lo + (hi - lo) * fx_rng_unit(g); }

/* ---------------------------------------------------------------- GL and voxgi contexts */
/* The program's GL 4.5 context: NULL until gl_open(), and when none could be made (g_gl_error says why). */
static vxt_gl *g_gl;
static char g_gl_error[512];
static int g_gl_bad_kind; /* VOXGI_TEST_GL names no kind (nor none): every GL test fails */

/* Makes the program's GL context: the kind VOXGI_TEST_GL names (egl or osmesa; none: no context,
   as on a machine without GL), else the first that works; prints which, or why there is none. */
static inline void gl_open(void)
{
    vxt_gl_kind kind = VXT_GL_AUTO;
    const char *want = getenv("VOXGI_TEST_GL");
    if (want && !strcmp(want, "none")) {
        snprintf(g_gl_error, sizeof g_gl_error, "VOXGI_TEST_GL=none");
        printf("NO GL CONTEXT: %s\n", g_gl_error);
        return;
    }
    if (want && *want && vxt_gl_kind_parse(want, &kind) != 0) { /* a typo must not test another kind */
        g_gl_bad_kind = 1;
        snprintf(g_gl_error, sizeof g_gl_error, "VOXGI_TEST_GL=%s is not egl, osmesa or auto", want);
        printf("NO GL CONTEXT: %s\n", g_gl_error);
        return;
    }
    g_gl = vxt_gl_create(kind, g_gl_error, sizeof g_gl_error);
    if (g_gl) printf("GL context: %s, %s\n", vxt_gl_kind_name(g_gl), vxt_gl_renderer(g_gl));
    else printf("NO GL CONTEXT: %s\n", g_gl_error);
}

static inline void gl_close(void)
{
    if (g_gl) vxt_gl_destroy(g_gl);
    g_gl = NULL;
}

/* 1 when the program has its GL context. Else 0, and the running test is skipped (loudly), or
   fails when VOXGI_REQUIRE_GL=1 (CI, where a GL context must exist) or VOXGI_TEST_GL is a typo
   (not egl, osmesa, auto or none). */
static inline int have_gl(void)
{
    if (g_gl) return 1;
    if (th_gl_required() || g_gl_bad_kind)
        TH_CHECK(0, "no GL 4.5 context: %s", g_gl_error);
    else th_skip("no GL 4.5 context could be made: %s", g_gl_error);
    return 0;
}

/* A context description for backend, all else zero; with the program's GL context as the GL
   loader when there is one. */
static inline void ctx_desc(voxgi_desc *d, voxgi_backend backend)
{
    memset(d, 0, sizeof *d);
    d->backend = backend;
    if (g_gl) {
        d->gl_get_proc_address_user = vxt_gl_get_proc;
        d->gl_user = g_gl;
    }
}

/* A voxgi context on backend with threads worker threads (0: the default), or NULL. */
static inline voxgi_context *make_ctx(voxgi_backend backend, int threads)
{
    voxgi_desc d;
    voxgi_context *ctx = NULL;
    ctx_desc(&d, backend);
    d.thread_count = threads;
    if (voxgi_create(&d, &ctx) != VOXGI_OK) return NULL;
    return ctx;
}

/* ---------------------------------------------------------------- scenes */
/* sc: one mesh, *mesh, of the given triangles (idx NULL: unindexed, ntri 0); nothing else set. */
static inline void scene_of_triangles(voxgi_scene *sc, voxgi_mesh *mesh, const float *pos, size_t nv, const uint32_t *idx, size_t ntri)
{
    memset(sc, 0, sizeof *sc);
    memset(mesh, 0, sizeof *mesh);
    mesh->positions = pos;
    mesh->vertex_count = nv;
    mesh->indices = idx;
    mesh->index_count = 3 * ntri;
    sc->meshes = mesh;
    sc->mesh_count = 1;
}

/* sc: one mesh, *mesh, of the shape's triangles; nothing else set. */
static inline void scene_of_shape(voxgi_scene *sc, voxgi_mesh *mesh, const vxt_shape *m)
{
    scene_of_triangles(sc, mesh, m->pos, m->vertex_count, m->idx, m->triangle_count);
}

/* The scene's materials and lights. */
static inline void scene_lighting(voxgi_scene *sc, const voxgi_material *mats, size_t nm, const voxgi_light *lights, size_t nl)
{
    sc->materials = mats;
    sc->material_count = nm;
    sc->lights = lights;
    sc->light_count = nl;
}

/* Material ids for a shape's triangles, 0, 1, ..., n - 1 in turn (malloc'd: free them). */
static inline uint32_t *material_ids_in_turn(const vxt_shape *m, uint32_t n)
{
    uint32_t *ids = (uint32_t *)malloc(m->triangle_count * 4);
    size_t t;
    for (t = 0; t < m->triangle_count; t++) ids[t] = (uint32_t)(t % n);
    return ids;
}

/* sc: one mesh, *mesh, of the shape's triangles, each with its material id (ids) into mats. */
static inline void scene_of_materials(voxgi_scene *sc, voxgi_mesh *mesh, const vxt_shape *m, const uint32_t *ids, const voxgi_material *mats,
                                      size_t nm)
{
    scene_of_shape(sc, mesh, m);
    mesh->material_ids = ids;
    scene_lighting(sc, mats, nm, NULL, 0);
}

/* Quads (4 corners each, counter-clockwise seen from the front) into one mesh: start with n = 0. */
typedef struct quads { float pos[12 * 16]; uint32_t idx[6 * 16], mat[2 * 16]; int n; } quads;

static inline void quad(quads *q, const float c[12], uint32_t mat)
{
    int k;
    memcpy(q->pos + 12 * q->n, c, 12 * sizeof(float));
    for (k = 0; k < 6; k++) q->idx[6 * q->n + k] = (uint32_t)(4 * q->n) + (uint32_t)"\0\1\2\0\2\3"[k];
    q->mat[2 * q->n] = q->mat[2 * q->n + 1] = mat;
    q->n++;
}

/* sc: the quads as one mesh, *mesh, with their materials, and the lights. */
static inline void scene_of_quads(voxgi_scene *sc, voxgi_mesh *mesh, quads *q, const voxgi_material *mats, size_t nm, const voxgi_light *lights,
                                  size_t nl)
{
    scene_of_triangles(sc, mesh, q->pos, (size_t)(4 * q->n), q->idx, (size_t)(2 * q->n));
    mesh->material_ids = q->mat;
    scene_lighting(sc, mats, nm, lights, nl);
}

/* The octree and volume tests' scene: a UV sphere of radius 1 (30 x 15) just off the origin, its
   triangles taking two materials in turn (the first emits). Free it with material_sphere_free. */
typedef struct material_sphere {
    vxt_shape shape;
    uint32_t *ids;
    voxgi_material mats[2];
    voxgi_mesh mesh;
    voxgi_scene scene;
} material_sphere;

static inline void material_sphere_make(material_sphere *s)
{
    static const voxgi_material mats[2] = {{{0.9f, 0.1f, 0.2f}, {3, 2, 1}, 0.5f}, {{0.3f, 0.7f, 0.5f}, {0, 0, 0}, 0.0f}};
    vxt_shape_sphere(&s->shape, 30, 15, 1.0, 0.013, -0.021, 0.007);
    s->ids = material_ids_in_turn(&s->shape, 2);
    memcpy(s->mats, mats, sizeof mats);
    scene_of_materials(&s->scene, &s->mesh, &s->shape, s->ids, s->mats, 2);
}

static inline void material_sphere_free(material_sphere *s)
{
    free(s->ids);
    vxt_shape_free(&s->shape);
}

/* The OR-reduction tests' scene: a sphere (30 x 20) on a 45 x 37 x 50 grid of 0.05 (vd: that
   grid, all else zero). Free m with vxt_shape_free. */
static inline void reduce_scene(vxt_shape *m, voxgi_scene *sc, voxgi_mesh *mesh, voxgi_voxelize_desc *vd)
{
    vxt_shape_sphere(m, 30, 20, 1.0, 0.1, 0.0, -0.05);
    scene_of_shape(sc, mesh, m);
    memset(vd, 0, sizeof *vd);
    vd->grid.origin[0] = -1.2; vd->grid.origin[1] = -1.1; vd->grid.origin[2] = -1.3;
    vd->grid.voxel_size = 0.05;
    vd->grid.res[0] = 45; vd->grid.res[1] = 37; vd->grid.res[2] = 50;
}

/* ---------------------------------------------------------------- runs */
/* Voxelizes sc with vd on ctx: the bits (malloc'd: free them; *info filled when info is not
   NULL), or NULL with the error printed. */
static inline uint32_t *voxelized_bits(voxgi_context *ctx, const voxgi_scene *sc, const voxgi_voxelize_desc *vd, voxgi_voxels_info *info)
{
    voxgi_voxels *vox = NULL;
    uint32_t *bits;
    size_t need = 0;
    if (voxgi_voxelize(ctx, sc, vd, &vox) != VOXGI_OK) { printf("    voxelize: %s\n", voxgi_last_error(ctx)); return NULL; }
    voxgi_voxels_read(ctx, vox, NULL, 0, &need);
    bits = (uint32_t *)malloc(need);
    if (voxgi_voxels_read(ctx, vox, bits, need, NULL) != VOXGI_OK) { printf("    read: %s\n", voxgi_last_error(ctx)); free(bits); bits = NULL; }
    if (info) voxgi_voxels_query(vox, info);
    voxgi_voxels_destroy(ctx, vox);
    return bits;
}

/* The shape voxelized with vd (its grid, method and all) on ctx, with uvs unless NULL: as voxelized_bits. */
static inline uint32_t *shape_bits(voxgi_context *ctx, const vxt_shape *m, const float *uvs, const voxgi_voxelize_desc *vd, voxgi_voxels_info *info)
{
    voxgi_mesh mesh;
    voxgi_scene sc;
    scene_of_shape(&sc, &mesh, m);
    mesh.uvs = uvs;
    return voxelized_bits(ctx, &sc, vd, info);
}

/* The triangles at pos (idx NULL: unindexed) voxelized on grid g by method on ctx: as voxelized_bits. */
static inline uint32_t *voxelize_bits_method(voxgi_context *ctx, const float *pos, size_t nv, const uint32_t *idx, size_t ntri,
                                             const voxgi_grid *g, voxgi_method method, voxgi_voxels_info *info)
{
    voxgi_mesh m;
    voxgi_scene sc;
    voxgi_voxelize_desc vd;
    scene_of_triangles(&sc, &m, pos, nv, idx, ntri);
    memset(&vd, 0, sizeof vd);
    vd.grid = *g;
    vd.method = method;
    return voxelized_bits(ctx, &sc, &vd, info);
}

/* The same by the conservative method. */
static inline uint32_t *voxelize_bits(voxgi_context *ctx, const float *pos, size_t nv, const uint32_t *idx, size_t ntri,
                                      const voxgi_grid *g, voxgi_voxels_info *info)
{
    return voxelize_bits_method(ctx, pos, nv, idx, ntri, g, VOXGI_METHOD_CONSERVATIVE, info);
}

/* One attribute of voxels read back (malloc'd: free it), or NULL. */
static inline float *attr_read(voxgi_context *ctx, const voxgi_voxels *vox, voxgi_attribute which)
{
    size_t need = 0;
    float *out;
    if (voxgi_voxels_read_attribute(ctx, vox, which, NULL, 0, &need) != VOXGI_OK) return NULL;
    out = (float *)malloc(need ? need : 4);
    if (voxgi_voxels_read_attribute(ctx, vox, which, out, need, NULL) != VOXGI_OK) { free(out); return NULL; }
    return out;
}

/* vd: a cone-traced image (method VCT) through camera, with the settings of the old
   voxgi_vct_desc's zeros (voxgi_render's zeros are the measured defaults): 128 voxels, 16 rays per
   pixel, 16 cones at every pixel, isotropic mips; all else zero. */
static inline void vct_desc_old(voxgi_render_desc *vd, const voxgi_camera *camera)
{
    memset(vd, 0, sizeof *vd);
    vd->method = VOXGI_RENDER_VCT;
    vd->camera = *camera;
    vd->resolution = 128;
    vd->samples = 16;
    vd->vct.cones.cones = 16;
    vd->vct.cone_stride = 1;
    vd->vct.radiance = VOXGI_VCT_ISOTROPIC;
}

/* vd: vct_desc_old of a w x w view through the built-in scene's camera. */
static inline void vct_view(voxgi_render_desc *vd, const voxgi_builtin_scene *bs, int w)
{
    vct_desc_old(vd, &bs->camera);
    vd->camera.width = vd->camera.height = w;
}

/* The radiance store of the old voxgi_vct_desc's filter and octree flag. */
static inline voxgi_vct_radiance vct_radiance(voxgi_mip_filter filter, int octree)
{
    return octree ? VOXGI_VCT_OCTREE : filter == VOXGI_MIPS_ANISOTROPIC ? VOXGI_VCT_ANISOTROPIC : VOXGI_VCT_ISOTROPIC;
}

/* The leak-room scene (a closed box of zero-thickness faces on the floor of a closed room with a
   lamp) cone traced at res^3 from inside the box, where the exact image is black, and from the
   room: the mean and largest radiance inside over the room view's mean (emitters hidden). With
   rect = 1 a rectangular light under the lamp lights the room instead (the lights' path of the
   injection, not the emitters'); octree = 1: the cones gather from an octree. 0 on success. */
static inline int leak_room_ratios(voxgi_context *ctx, int res, voxgi_mip_filter filter, int octree, int rect, double *mean_ratio, double *max_ratio)
{
    enum { W = 24 };
    voxgi_builtin_scene bs;
    voxgi_render_desc vd;
    voxgi_light lamp;
    float img[W * W * 3];
    double mean[2] = {0, 0}, top = 0;
    int v, i, bad = 0;
    if (voxgi_builtin_scene_create(ctx, "leak-room", &bs) != VOXGI_OK) return 1;
    memset(&lamp, 0, sizeof lamp);
    lamp.type = VOXGI_LIGHT_RECT;
    lamp.position[0] = -0.2f; lamp.position[1] = 1.94f; lamp.position[2] = -0.2f;
    lamp.edge_u[0] = 0.4f; lamp.edge_v[2] = 0.4f; /* facing down */
    lamp.intensity[0] = lamp.intensity[1] = lamp.intensity[2] = 10;
    if (rect) { /* the light in place of the lamp's emission (the struct owns its materials) */
        voxgi_material *lamp_material = (voxgi_material *)(uintptr_t)&bs.scene.materials[1];
        lamp_material->emission[0] = lamp_material->emission[1] = lamp_material->emission[2] = 0;
        bs.scene.lights = &lamp;
        bs.scene.light_count = 1;
    }
    for (v = 0; v < 2 && !bad; v++) { /* inside the box, then the room from a corner */
        vct_view(&vd, &bs, W);
        vd.resolution = res;
        vd.vct.radiance = vct_radiance(filter, octree);
        vd.samples = 1;
        vd.hide_emitters = 1;
        if (v) {
            vd.camera.eye[0] = 0.85; vd.camera.eye[1] = 1.6; vd.camera.eye[2] = -0.85;
            vd.camera.target[0] = 0; vd.camera.target[1] = 0.4; vd.camera.target[2] = 0;
            vd.camera.fovy_degrees = 75;
        }
        bad = voxgi_render(ctx, &bs.scene, &vd, img, sizeof img, NULL) != VOXGI_OK;
        for (i = 0; i < W * W && !bad; i++) {
            double px = (img[3 * i] + img[3 * i + 1] + img[3 * i + 2]) / 3;
            mean[v] += px / (W * W);
            if (!v && px > top) top = px;
        }
    }
    voxgi_builtin_scene_destroy(ctx, &bs);
    *mean_ratio = mean[1] > 0 ? mean[0] / mean[1] : 1;
    *max_ratio = mean[1] > 0 ? top / mean[1] : 1;
    return bad;
}

/* Points on the leak room's inner faces (16 on each of the floor, two walls and the ceiling,
   0.3 m to 0.9 m from the room's axes) and their normals, into the room. */
#define LEAK_ROOM_POINTS 64
static inline void leak_room_points(float pos[3 * LEAK_ROOM_POINTS], float nrm[3 * LEAK_ROOM_POINTS])
{
    int i;
    for (i = 0; i < LEAK_ROOM_POINTS; i++) {
        int face = i / 16;
        float u = -0.9f + 0.6f * (float)(i % 4), w = -0.9f + 0.6f * (float)(i / 4 % 4), *q = pos + 3 * i, *n = nrm + 3 * i;
        n[0] = n[1] = n[2] = 0;
        if (face == 0) { q[0] = u; q[1] = 0; q[2] = w; n[1] = 1; }
        else if (face == 1) { q[0] = -1; q[1] = 1 + w; q[2] = u; n[0] = 1; }
        else if (face == 2) { q[0] = u; q[1] = 1 + w; q[2] = 1; n[2] = -1; }
        else { q[0] = u; q[1] = 2; q[2] = w; n[1] = -1; }
    }
}

/* The leak-box scene (a closed box of zero-thickness faces on sunlit ground, a point light
   beside it; with area = 1 a rectangular light there instead) cone traced at res^3 from inside,
   where the exact image is black: the mean and largest radiance inside over the lit ground's
   (albedo / pi x the sun's irradiance); octree = 1: the cones gather from an octree. 0 on success. */
static inline int leak_box_ratios(voxgi_context *ctx, int res, voxgi_mip_filter filter, int octree, int area, double *mean_ratio, double *max_ratio)
{
    enum { W = 64 }; /* fine enough to meet the box's corners, where a point's region is hardest to find */
    voxgi_builtin_scene bs;
    voxgi_render_desc vd;
    voxgi_light lights[2];
    float img[W * W * 3];
    double mean = 0, top = 0, ground;
    int i, bad;
    if (voxgi_builtin_scene_create(ctx, "leak-box", &bs) != VOXGI_OK) return 1;
    memcpy(lights, bs.scene.lights, sizeof lights);
    { /* the ground under the sun */
        const float *d = lights[0].direction;
        ground = 0.8 / PI * lights[0].intensity[0] * -d[1] / sqrt((double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2]);
    }
    if (area) { /* 0.6 m square, 1 m off the box's -z face, facing it */
        memset(&lights[1], 0, sizeof lights[1]);
        lights[1].type = VOXGI_LIGHT_RECT;
        lights[1].position[0] = -0.3f; lights[1].position[1] = 0.2f; lights[1].position[2] = -1.5f;
        lights[1].edge_u[0] = 0.6f; lights[1].edge_v[1] = 0.6f;
        lights[1].intensity[0] = lights[1].intensity[1] = lights[1].intensity[2] = 20;
    }
    bs.scene.lights = lights;
    vct_view(&vd, &bs, W);
    vd.resolution = res;
    vd.vct.radiance = vct_radiance(filter, octree);
    vd.samples = 1;
    bad = voxgi_render(ctx, &bs.scene, &vd, img, sizeof img, NULL) != VOXGI_OK;
    for (i = 0; i < W * W && !bad; i++) {
        double px = (img[3 * i] + img[3 * i + 1] + img[3 * i + 2]) / 3;
        mean += px / (W * W);
        top = fmax(top, px);
    }
    voxgi_builtin_scene_destroy(ctx, &bs);
    *mean_ratio = mean / ground;
    *max_ratio = top / ground;
    return bad;
}

/* A scene voxelized (albedo, normal) on a fitted grid of res voxels with `padding` empty ones
   around it and lit (voxgi_inject_light with id); 1 when it all worked, else the error is printed. */
static inline int lit_voxels_padded(voxgi_context *ctx, const voxgi_scene *sc, int res, int padding, const voxgi_inject_desc *id, voxgi_voxels **vx,
                                    voxgi_volume **vol)
{
    voxgi_fit_desc fit;
    voxgi_voxelize_desc xd;
    memset(&fit, 0, sizeof fit);
    memset(&xd, 0, sizeof xd);
    fit.res = res;
    fit.padding = padding;
    xd.attributes = VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_NORMAL;
    *vx = NULL;
    *vol = NULL;
    if (voxgi_fit_grid(ctx, sc, &fit, &xd.grid) == VOXGI_OK && voxgi_voxelize(ctx, sc, &xd, vx) == VOXGI_OK && voxgi_inject_light(ctx, sc, *vx, id, vol) == VOXGI_OK)
        return 1;
    printf("    %s\n", voxgi_last_error(ctx));
    return 0;
}

static inline int lit_voxels(voxgi_context *ctx, const voxgi_scene *sc, int res, const voxgi_inject_desc *id, voxgi_voxels **vx, voxgi_volume **vol)
{
    return lit_voxels_padded(ctx, sc, res, 1, id, vx, vol);
}

/* The leak box with a lamp inside its closed box as well (lights: 3, the scene's two and the lamp). */
static inline voxgi_result leak_box_with_lamp(voxgi_context *ctx, voxgi_builtin_scene *box, voxgi_light lights[3])
{
    voxgi_result r = voxgi_builtin_scene_create(ctx, "leak-box", box);
    if (r != VOXGI_OK) return r;
    memcpy(lights, box->scene.lights, 2 * sizeof *lights);
    memset(&lights[2], 0, sizeof lights[2]);
    lights[2].type = VOXGI_LIGHT_POINT;
    lights[2].position[0] = -0.2f; lights[2].position[1] = 0.7f; lights[2].position[2] = 0.1f;
    lights[2].intensity[0] = lights[2].intensity[1] = lights[2].intensity[2] = 0.5f;
    box->scene.lights = lights;
    box->scene.light_count = 3;
    return VOXGI_OK;
}

/* Where cones gather from: a volume's radiance, or an octree's. */
#define VOLUME_SOURCE(vol) (&(const voxgi_radiance_source){.volume = (vol)})
#define OCTREE_SOURCE(svo) (&(const voxgi_radiance_source){.octree = (svo)})

/* ---------------------------------------------------------------- cameras
   Where the ray through image point (sx, sy) (pixels from the top left, continuous) meets the
   floor y = 0, with the camera's frame rebuilt here (gluLookAt, up +Y), independent of the
   library's: the tests' own camera for analytic images of a floor. The ray must go down. */
static inline void fx_floor_point(const voxgi_camera *c, double sx, double sy, double p[3])
{
    double f[3], r[3], u[3], d[3], len, th = tan(c->fovy_degrees * PI / 360), x, y, t;
    int a;
    for (a = 0; a < 3; a++) f[a] = c->target[a] - c->eye[a];
    len = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (a = 0; a < 3; a++) f[a] /= len;
    r[0] = -f[2]; r[1] = 0; r[2] = f[0];
    len = sqrt(r[0] * r[0] + r[2] * r[2]);
    r[0] /= len; r[2] /= len;
    u[0] = r[1] * f[2] - r[2] * f[1]; u[1] = r[2] * f[0] - r[0] * f[2]; u[2] = r[0] * f[1] - r[1] * f[0];
    x = (2 * sx / c->width - 1) * th * c->width / c->height;
    y = (1 - 2 * sy / c->height) * th;
    for (a = 0; a < 3; a++) d[a] = f[a] + x * r[a] + y * u[a];
    t = -c->eye[1] / d[1];
    for (a = 0; a < 3; a++) p[a] = c->eye[a] + t * d[a];
}

/* ---------------------------------------------------------------- grids */
/* n^3 voxels over the cube from lo to lo + size on each axis. */
static inline void cubic(voxgi_grid *g, double lo, double size, int n)
{
    g->origin[0] = g->origin[1] = g->origin[2] = lo;
    g->voxel_size = size / n;
    g->res[0] = g->res[1] = g->res[2] = n;
}

/* ---------------------------------------------------------------- held-out closed spaces */
/* Scenes the cone tracer's leak defences were not built on, made here: HELD_ROOMS, two closed
   rooms of one building (floor, ceiling and the long walls run through both) split by one wall of
   no thickness, a rectangular lamp under the ceiling of the first, the camera in the second;
   HELD_BOX, a closed box of zero-thickness faces standing on a lit room's floor (its bottom face
   on the floor), the camera inside; HELD_RESTING, that box with its bottom 1 mm above the floor
   and a 4 cm square hole in the middle of its top, the lamp over it, the camera inside looking at
   a wall (lit by what the hole lets onto the box's floor, whose voxels also hold the room's
   floor). Each turned by `turn` degrees about the vertical (their walls then cross the voxels).
   The second view sees the lit space. */
enum { HELD_ROOMS, HELD_BOX, HELD_RESTING };
typedef struct held_scene {
    float pos[3 * 4 * 16];
    uint32_t idx[6 * 16];
    int quads;
    voxgi_mesh mesh;
    voxgi_material mat;
    voxgi_light lamp;
    voxgi_scene scene;
    voxgi_camera dark, lit;
} held_scene;

/* A quad a b c d (counter-clockwise from its front) turned by (c, s) about the vertical. */
static inline void held_quad(held_scene *h, const float q[12], double c, double s)
{
    int k;
    for (k = 0; k < 4; k++) {
        float *v = h->pos + 3 * (4 * h->quads + k);
        v[0] = (float)(c * q[3 * k] - s * q[3 * k + 2]);
        v[1] = q[3 * k + 1];
        v[2] = (float)(s * q[3 * k] + c * q[3 * k + 2]);
    }
    for (k = 0; k < 6; k++) h->idx[6 * h->quads + k] = (uint32_t)(4 * h->quads) + (uint32_t)"\0\1\2\0\2\3"[k];
    h->quads++;
}

/* An axis box's six faces, inward (in) or outward; with `top` 0 all but its top. */
static inline void held_box(held_scene *h, const float lo[3], const float hi[3], int in, int top, double c, double s)
{
    const float x0 = lo[0], y0 = lo[1], z0 = lo[2], x1 = hi[0], y1 = hi[1], z1 = hi[2];
    const float f[6][12] = {{x0, y0, z0, x1, y0, z0, x1, y0, z1, x0, y0, z1}, {x0, y1, z0, x0, y1, z1, x1, y1, z1, x1, y1, z0},
                            {x0, y0, z0, x0, y1, z0, x1, y1, z0, x1, y0, z0}, {x0, y0, z1, x1, y0, z1, x1, y1, z1, x0, y1, z1},
                            {x0, y0, z0, x0, y0, z1, x0, y1, z1, x0, y1, z0}, {x1, y0, z0, x1, y1, z0, x1, y1, z1, x1, y0, z1}};
    int k, v;
    for (k = 0; k < 6; k++) {
        float q[12];
        if (k == 1 && !top) continue;
        for (v = 0; v < 4; v++) memcpy(q + 3 * v, f[k] + 3 * (in ? (4 - v) % 4 : v), 12); /* the table faces out; inward: reversed */
        held_quad(h, q, c, s);
    }
}

static inline void held_camera(voxgi_camera *cam, double ex, double ey, double ez, double tx, double ty, double tz, double c, double s)
{
    memset(cam, 0, sizeof *cam);
    cam->eye[0] = c * ex - s * ez; cam->eye[1] = ey; cam->eye[2] = s * ex + c * ez;
    cam->target[0] = c * tx - s * tz; cam->target[1] = ty; cam->target[2] = s * tx + c * tz;
    cam->fovy_degrees = 90;
}

static inline void held_scene_make(held_scene *h, int kind, double turn)
{
    const double c = cos(turn * 3.141592653589793 / 180), s = sin(turn * 3.141592653589793 / 180);
    memset(h, 0, sizeof *h);
    h->mat.albedo[0] = h->mat.albedo[1] = h->mat.albedo[2] = 0.7f;
    h->lamp.type = VOXGI_LIGHT_RECT;
    h->lamp.intensity[0] = h->lamp.intensity[1] = h->lamp.intensity[2] = 10;
    if (kind == HELD_ROOMS) {
        const float lo[3] = {-2, 0, -1}, hi[3] = {2, 2, 1}, wall[12] = {0, 0, -1, 0, 0, 1, 0, 2, 1, 0, 2, -1};
        held_box(h, lo, hi, 1, 1, c, s);
        held_quad(h, wall, c, s);
        h->lamp.position[0] = -1.2f; h->lamp.position[1] = 1.9f; h->lamp.position[2] = -0.2f;
        held_camera(&h->dark, 1.8, 1.2, 0.7, 0, 0.6, -0.3, c, s);
        held_camera(&h->lit, -1.8, 1.2, 0.7, 0, 0.6, -0.3, c, s);
    } else {
        const float lo[3] = {-2.1f, 0, -1.7f}, hi[3] = {1.9f, 2.6f, 2.2f}, blo[3] = {0.37f, kind == HELD_RESTING ? 0.001f : 0, -0.61f},
                    bhi[3] = {1.13f, 0.57f, 0.23f};
        held_box(h, lo, hi, 1, 1, c, s);
        held_box(h, blo, bhi, 0, kind == HELD_BOX, c, s);
        h->lamp.position[0] = 0.3f; h->lamp.position[1] = 2.5f; h->lamp.position[2] = -0.5f;
        held_camera(&h->dark, 0.5, 0.45, 0.1, 0.9, 0.1, -0.5, c, s);
        held_camera(&h->lit, -1.5, 1.8, 1.8, 0.5, 0.3, -0.2, c, s);
        if (kind == HELD_RESTING) { /* the top around its hole (x 0.73-0.77, z -0.21 to -0.17): four quads */
            const float y = bhi[1], top[4][12] = {{0.37f, y, -0.61f, 0.37f, y, 0.23f, 0.73f, y, 0.23f, 0.73f, y, -0.61f},
                                                  {0.77f, y, -0.61f, 0.77f, y, 0.23f, 1.13f, y, 0.23f, 1.13f, y, -0.61f},
                                                  {0.73f, y, -0.61f, 0.73f, y, -0.21f, 0.77f, y, -0.21f, 0.77f, y, -0.61f},
                                                  {0.73f, y, -0.17f, 0.73f, y, 0.23f, 0.77f, y, 0.23f, 0.77f, y, -0.17f}};
            int k;
            for (k = 0; k < 4; k++) held_quad(h, top[k], c, s);
            h->lamp.position[0] = 0.5f; h->lamp.position[2] = -0.44f;
            held_camera(&h->dark, 0.75, 0.08, -0.19, 1.13, 0.45, -0.19, c, s);
        }
    }
    { /* the lamp, a 0.5 x 0.5 (rooms: 0.4) square facing down, turned with the rest */
        float e = kind == HELD_ROOMS ? 0.4f : 0.5f, p0 = h->lamp.position[0], p2 = h->lamp.position[2];
        h->lamp.position[0] = (float)(c * p0 - s * p2);
        h->lamp.position[2] = (float)(s * p0 + c * p2);
        h->lamp.edge_u[0] = (float)(c * e); h->lamp.edge_u[2] = (float)(s * e);
        h->lamp.edge_v[0] = (float)(-s * e); h->lamp.edge_v[2] = (float)(c * e);
    }
    h->mesh.positions = h->pos;
    h->mesh.vertex_count = 4 * (size_t)h->quads;
    h->mesh.indices = h->idx;
    h->mesh.index_count = 6 * (size_t)h->quads;
    h->scene.meshes = &h->mesh;
    h->scene.mesh_count = 1;
    h->scene.materials = &h->mat;
    h->scene.material_count = 1;
    h->scene.lights = &h->lamp;
    h->scene.light_count = 1;
}

/* The held-out scene cone traced at res^3 (radiance: its store; bounces as voxgi_render_desc's)
   from the dark space, where the exact image is black, and from the lit one: the dark view's mean
   and largest pixel over the lit view's mean (infinite where a pixel is below 0). 0 on success. */
static inline int held_ratios(voxgi_context *ctx, int kind, double turn, int res, voxgi_vct_radiance radiance, int bounces, double *mean_ratio, double *max_ratio)
{
    enum { W = 24 };
    held_scene h;
    voxgi_render_desc d;
    float img[W * W * 3];
    double mean[2] = {0, 0}, top = 0;
    int v, i, bad = 0;
    held_scene_make(&h, kind, turn);
    for (v = 0; v < 2 && !bad; v++) {
        memset(&d, 0, sizeof d);
        d.method = VOXGI_RENDER_VCT;
        d.camera = v ? h.lit : h.dark;
        d.camera.width = d.camera.height = W;
        d.resolution = res;
        d.vct.radiance = radiance;
        d.bounces = bounces;
        d.samples = 1;
        d.hide_emitters = 1;
        bad = voxgi_render(ctx, &h.scene, &d, img, sizeof img, NULL) != VOXGI_OK;
        for (i = 0; i < W * W && !bad; i++) {
            double px = (img[3 * i] + img[3 * i + 1] + img[3 * i + 2]) / 3;
            mean[v] += px / (W * W);
            if (!v && (px > top || px < 0)) top = px < 0 ? HUGE_VAL : px; /* light below zero is no image: the largest pixel fails */
        }
    }
    *mean_ratio = mean[1] > 0 ? mean[0] / mean[1] : 1;
    *max_ratio = mean[1] > 0 ? top / mean[1] : 1;
    return bad;
}

/* The held-out scene's dark view (24 x 24, emitters hidden) by `method` at res^3 (0: its
   default), bounces as voxgi_render_desc's, `samples` per pixel: its mean radiance. 0 on success. */
static inline int held_dark_mean(voxgi_context *ctx, int kind, double turn, voxgi_render_method method, int res, int bounces, int samples, double *mean)
{
    enum { W = 24 };
    held_scene h;
    voxgi_render_desc d;
    float img[W * W * 3];
    int i, bad;
    held_scene_make(&h, kind, turn);
    memset(&d, 0, sizeof d);
    d.method = method;
    d.camera = h.dark;
    d.camera.width = d.camera.height = W;
    d.resolution = res;
    d.bounces = bounces;
    d.samples = samples;
    d.hide_emitters = 1;
    bad = voxgi_render(ctx, &h.scene, &d, img, sizeof img, NULL) != VOXGI_OK;
    for (*mean = 0, i = 0; i < W * W * 3 && !bad; i++) *mean += img[i] / (W * W * 3);
    return bad;
}

#endif
