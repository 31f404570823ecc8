/* tests/test_core.c - parts 2 and 4: the core and the GL core, CPU and GL. Contexts and the
   result API: bad input (scenes, grids, the memory budget, NULL arguments) refused with a message
   and no partial output; every allocation failure (voxelization, attributes, volumes, octrees,
   atlas, Volume Buffer) reported as VOXGI_ERR_OUT_OF_MEMORY without a leak; progress callbacks
   that cancel; the same voxels for any thread count. On a real headless GL 4.5 context (EGL
   surfaceless or OSMesa, llvmpipe): the loader table (a plain or a user-pointer loader, a missing
   function), the AUTO backend's choice and fallback, GL buffers handed to the caller. (Shader error
   mapping and the software-renderer list, which call private helpers, are tested in
   tests/test_internals.c.) The GL tests skip (loudly) only when no GL 4.5 context can be made;
   VOXGI_TEST_GL=egl|osmesa|none picks the kind (none: no context), VOXGI_REQUIRE_GL=1 turns a skip into a failure. */
#include "../voxgi.h"
#include "fixtures.h"
#include <ctype.h>
#include <stdlib.h>

/* 1, 2 and 7 threads give identical bits. */
static void test_thread_determinism(void)
{
    vxt_shape m;
    voxgi_grid g;
    uint32_t *b[3];
    int i, threads[3] = {1, 2, 7};
    vxt_shape_sphere(&m, 48, 32, 1.0, 0, 0, 0);
    g.origin[0] = g.origin[1] = g.origin[2] = -1.1;
    g.voxel_size = 2.2 / 40;
    g.res[0] = g.res[1] = g.res[2] = 40;
    for (i = 0; i < 3; i++) {
        voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, threads[i]);
        b[i] = voxelize_bits(ctx, m.pos, m.vertex_count, m.idx, m.triangle_count, &g, NULL);
        voxgi_destroy(ctx);
    }
    TH_CHECK(b[0] && b[1] && b[2] && memcmp(b[0], b[1], (40 * 40 * 40 + 31) / 32 * 4) == 0 &&
             memcmp(b[0], b[2], (40 * 40 * 40 + 31) / 32 * 4) == 0, "thread counts disagree");
    for (i = 0; i < 3; i++) free(b[i]);
    vxt_shape_free(&m);
}

/* ---------------------------------------------------------------- bad input */
static voxgi_result try_scene(voxgi_context *ctx, const voxgi_mesh *m, size_t nm, const voxgi_grid *g)
{
    voxgi_scene sc;
    voxgi_voxelize_desc vd;
    voxgi_voxels *vox = (voxgi_voxels *)1;
    voxgi_result r;
    memset(&sc, 0, sizeof sc);
    memset(&vd, 0, sizeof vd);
    sc.meshes = m; sc.mesh_count = nm;
    vd.grid = *g;
    r = voxgi_voxelize(ctx, &sc, &vd, &vox);
    if (r != VOXGI_OK && vox != NULL) return (voxgi_result)-1; /* no partial output */
    if (r == VOXGI_OK) voxgi_voxels_destroy(ctx, vox);
    return r;
}

static void test_bad_input(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 1);
    float p[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    uint32_t idx[6] = {0, 1, 2, 1, 3, 2};
    voxgi_mesh m;
    voxgi_grid g;
    g.origin[0] = g.origin[1] = g.origin[2] = -0.5;
    g.voxel_size = 0.25;
    g.res[0] = g.res[1] = g.res[2] = 8;
    memset(&m, 0, sizeof m);
    m.positions = p; m.vertex_count = 4; m.indices = idx; m.index_count = 6;
    TH_CHECK(try_scene(ctx, &m, 1, &g) == VOXGI_OK, "good scene rejected: %s", voxgi_last_error(ctx));

    p[4] = NAN;
    TH_CHECK(try_scene(ctx, &m, 1, &g) == VOXGI_ERR_INVALID_SCENE, "NaN accepted");
    TH_CHECK(strstr(voxgi_last_error(ctx), "triangle 0") && strstr(voxgi_last_error(ctx), "vertex 1"),
             "NaN message does not name the triangle and vertex: %s", voxgi_last_error(ctx));
    p[4] = INFINITY;
    TH_CHECK(try_scene(ctx, &m, 1, &g) == VOXGI_ERR_INVALID_SCENE, "infinity accepted");
    p[4] = 0;
    idx[4] = 4;
    TH_CHECK(try_scene(ctx, &m, 1, &g) == VOXGI_ERR_INVALID_SCENE, "index out of range accepted");
    TH_CHECK(strstr(voxgi_last_error(ctx), "triangle 1") && strstr(voxgi_last_error(ctx), "out of range"),
             "message: %s", voxgi_last_error(ctx));
    idx[4] = 3;
    m.index_count = 5;
    TH_CHECK(try_scene(ctx, &m, 1, &g) == VOXGI_ERR_INVALID_SCENE, "index_count 5 accepted");
    m.index_count = 6;
    m.vertex_count = (size_t)-1 / 4;
    TH_CHECK(try_scene(ctx, &m, 1, &g) == VOXGI_ERR_TOO_LARGE, "overflowing vertex count accepted");
    m.vertex_count = 4;
    m.position_stride = 8;
    TH_CHECK(try_scene(ctx, &m, 1, &g) == VOXGI_ERR_INVALID_SCENE, "stride 8 accepted");
    m.position_stride = 0;
    m.material = 3;
    TH_CHECK(try_scene(ctx, &m, 1, &g) == VOXGI_ERR_INVALID_SCENE, "material out of range accepted");
    m.material = 0;
    m.index_count = 0;
    TH_CHECK(try_scene(ctx, &m, 1, &g) == VOXGI_ERR_EMPTY_SCENE, "empty mesh accepted");
    TH_CHECK(try_scene(ctx, &m, 0, &g) == VOXGI_ERR_EMPTY_SCENE, "no meshes accepted");
    m.index_count = 6;
    m.positions = NULL;
    TH_CHECK(try_scene(ctx, &m, 1, &g) == VOXGI_ERR_INVALID_SCENE, "NULL positions accepted");
    m.positions = p;
    /* grids */
    g.res[1] = 0;
    TH_CHECK(try_scene(ctx, &m, 1, &g) == VOXGI_ERR_INVALID_GRID, "zero resolution accepted");
    g.res[1] = VOXGI_MAX_RES + 1;
    TH_CHECK(try_scene(ctx, &m, 1, &g) == VOXGI_ERR_INVALID_GRID, "huge resolution accepted");
    g.res[1] = 8;
    g.voxel_size = 0;
    TH_CHECK(try_scene(ctx, &m, 1, &g) == VOXGI_ERR_INVALID_GRID, "zero voxel size accepted");
    g.voxel_size = NAN;
    TH_CHECK(try_scene(ctx, &m, 1, &g) == VOXGI_ERR_INVALID_GRID, "NaN voxel size accepted");
    g.voxel_size = 0.25;
    g.origin[2] = INFINITY;
    TH_CHECK(try_scene(ctx, &m, 1, &g) == VOXGI_ERR_INVALID_GRID, "infinite origin accepted");
    g.origin[2] = -0.5;
    voxgi_destroy(ctx);
    {   /* a grid beyond the memory budget is a clear error, not an allocation failure half-way */
        voxgi_desc d;
        memset(&d, 0, sizeof d);
        d.backend = VOXGI_BACKEND_CPU;
        d.memory_budget = 1 << 20;
        voxgi_create(&d, &ctx);
        g.res[0] = g.res[1] = g.res[2] = 2048;
        TH_CHECK(try_scene(ctx, &m, 1, &g) == VOXGI_ERR_TOO_LARGE, "over-budget grid accepted");
        TH_CHECK(strstr(voxgi_last_error(ctx), "budget") != NULL, "message: %s", voxgi_last_error(ctx));
        voxgi_destroy(ctx);
    }
    TH_CHECK(voxgi_create(NULL, &ctx) == VOXGI_ERR_INVALID_ARGUMENT, "NULL desc accepted");
    TH_CHECK(voxgi_voxelize(NULL, NULL, NULL, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "NULL context accepted");
}

/* Every allocation failure is reported as VOXGI_ERR_OUT_OF_MEMORY, never a crash or a leak. */
typedef struct fail_alloc { int countdown, live; } fail_alloc;
static void *fa_alloc(size_t n, void *u)
{
    fail_alloc *f = (fail_alloc *)u;
    if (f->countdown-- == 0) return NULL;
    f->live++;
    return malloc(n);
}
static void fa_free(void *p, void *u) { ((fail_alloc *)u)->live--; free(p); }

/* A CPU context allocating through fa, whose allocation number `countdown` (from 0) fails. */
static voxgi_result failing_ctx(fail_alloc *fa, int countdown, voxgi_context **ctx)
{
    voxgi_desc d;
    ctx_desc(&d, VOXGI_BACKEND_CPU);
    d.allocator.alloc = fa_alloc; d.allocator.free = fa_free; d.allocator.user = fa;
    fa->countdown = countdown;
    return voxgi_create(&d, ctx);
}

/* The allocation tests' scene: the n triangles at p, on a 14^3 grid of 0.1 from -0.1. */
static void failure_scene(voxgi_scene *sc, voxgi_mesh *m, voxgi_voxelize_desc *vd, const float *p, size_t n)
{
    scene_of_triangles(sc, m, p, 3 * n, NULL, 0);
    memset(vd, 0, sizeof *vd);
    vd->grid.origin[0] = vd->grid.origin[1] = vd->grid.origin[2] = -0.1;
    vd->grid.voxel_size = 0.1;
    vd->grid.res[0] = vd->grid.res[1] = vd->grid.res[2] = 14;
}

static void test_failing_allocator(void)
{
    float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0.5f};
    voxgi_mesh m;
    voxgi_scene sc;
    voxgi_voxelize_desc vd;
    int n, ok_at = -1;
    failure_scene(&sc, &m, &vd, p, 1);
    for (n = 0; n < 20 && ok_at < 0; n++) {
        fail_alloc fa = {0, 0};
        voxgi_context *ctx = NULL;
        voxgi_voxels *vox = NULL;
        voxgi_result r = failing_ctx(&fa, n, &ctx);
        if (r == VOXGI_OK) {
            r = voxgi_voxelize(ctx, &sc, &vd, &vox);
            TH_CHECK(r == VOXGI_OK || r == VOXGI_ERR_OUT_OF_MEMORY, "failure %d gave %s", n, voxgi_result_string(r));
            TH_CHECK((r == VOXGI_OK) == (vox != NULL), "failure %d: result and output disagree", n);
            if (r == VOXGI_OK) ok_at = n;
            voxgi_voxels_destroy(ctx, vox);
            voxgi_destroy(ctx);
        } else TH_CHECK(r == VOXGI_ERR_OUT_OF_MEMORY, "create failure gave %s", voxgi_result_string(r));
        TH_CHECK(fa.live == 0, "failure %d leaked %d blocks", n, fa.live);
    }
    TH_CHECK(ok_at > 0, "never succeeded");
}

/* Every allocation of the attribute, volume, octree, atlas and Volume Buffer paths may fail: the result
   is VOXGI_ERR_OUT_OF_MEMORY (never a crash or a half result) and nothing leaks. Bad points and
   voxels without attributes are refused. */
static void test_volume_and_attribute_failures(void)
{
    float p[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0.5f, 0.2f, 0.1f, 0.3f, 1.1f, 0.4f, 0.2f, 0.3f, 1.2f, 0.9f};
    voxgi_mesh m;
    voxgi_scene sc;
    voxgi_voxelize_desc vd;
    int n, full_at = -1;
    failure_scene(&sc, &m, &vd, p, 2);
    for (n = 0; n < 200 && full_at < 0; n++) {
        fail_alloc fa = {0, 0};
        voxgi_context *ctx = NULL;
        voxgi_voxels *vox = NULL, *other = NULL;
        voxgi_volume *vol = NULL;
        voxgi_volume_desc vold;
        voxgi_result r, r2 = VOXGI_ERR_OUT_OF_MEMORY, r3 = VOXGI_ERR_OUT_OF_MEMORY, r4 = VOXGI_ERR_OUT_OF_MEMORY;
        if (failing_ctx(&fa, n, &ctx) != VOXGI_OK) continue;
        vd.attributes = 15; vd.method = VOXGI_METHOD_CONSERVATIVE;
        r = voxgi_voxelize(ctx, &sc, &vd, &vox);
        if (r == VOXGI_OK) {
            memset(&vold, 0, sizeof vold);
            vold.filter = VOXGI_MIPS_ANISOTROPIC;
            r2 = voxgi_volume_create(ctx, vox, &vold, &vol);
            TH_CHECK((r2 == VOXGI_OK) == (vol != NULL) && (r2 == VOXGI_OK || r2 == VOXGI_ERR_OUT_OF_MEMORY), "volume: %s", voxgi_result_string(r2));
        }
        if (r2 == VOXGI_OK) {
            voxgi_svo_desc sd;
            voxgi_svo *svo = NULL;
            voxgi_result rs;
            memset(&sd, 0, sizeof sd);
            sd.neighbours = 1;
            rs = voxgi_svo_create(ctx, vox, &sd, &svo);
            TH_CHECK((rs == VOXGI_OK) == (svo != NULL) && (rs == VOXGI_OK || rs == VOXGI_ERR_OUT_OF_MEMORY), "octree: %s", voxgi_result_string(rs));
            voxgi_svo_destroy(ctx, svo);
            if (rs != VOXGI_OK) r2 = rs;
        }
        if (r2 == VOXGI_OK) {
            vd.method = VOXGI_METHOD_ATLAS; vd.attributes = 0;
            r3 = voxgi_voxelize(ctx, &sc, &vd, &other);
            TH_CHECK((r3 == VOXGI_OK) == (other != NULL) && (r3 == VOXGI_OK || r3 == VOXGI_ERR_OUT_OF_MEMORY), "atlas: %s", voxgi_result_string(r3));
            voxgi_voxels_destroy(ctx, other);
            other = NULL;
        }
        if (r3 == VOXGI_OK) {
            vd.method = VOXGI_METHOD_VOLUME_BUFFER; vd.attributes = 15;
            r4 = voxgi_voxelize(ctx, &sc, &vd, &other);
            TH_CHECK((r4 == VOXGI_OK) == (other != NULL) && (r4 == VOXGI_OK || r4 == VOXGI_ERR_OUT_OF_MEMORY), "volume buffer: %s", voxgi_result_string(r4));
            voxgi_voxels_destroy(ctx, other);
        }
        TH_CHECK(r == VOXGI_OK || r == VOXGI_ERR_OUT_OF_MEMORY, "attributes: failure %d gave %s", n, voxgi_result_string(r));
        if (r4 == VOXGI_OK) full_at = n;
        voxgi_volume_destroy(ctx, vol);
        voxgi_voxels_destroy(ctx, vox);
        voxgi_destroy(ctx);
        TH_CHECK(fa.live == 0, "failure %d leaked %d blocks", n, fa.live);
    }
    TH_CHECK(full_at > 0, "never got through");
    {   /* refusals */
        voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 1);
        voxgi_voxels *vox = NULL;
        voxgi_volume *vol = NULL;
        voxgi_volume_desc vold;
        float pos[3] = {1, 1, 1}, lod = 0, nan_pos[3], out[4];
        nan_pos[0] = (float)sqrt(-1.0); nan_pos[1] = nan_pos[2] = 1;
        memset(&vold, 0, sizeof vold);
        vd.method = VOXGI_METHOD_CONSERVATIVE; vd.attributes = 0;
        voxgi_voxelize(ctx, &sc, &vd, &vox);
        TH_CHECK(voxgi_volume_create(ctx, vox, &vold, &vol) == VOXGI_ERR_INVALID_ARGUMENT && !vol, "a volume from voxels without attributes");
        voxgi_voxels_destroy(ctx, vox);
        vd.attributes = VOXGI_ATTRIBUTE_ALBEDO;
        voxgi_voxelize(ctx, &sc, &vd, &vox);
        vold.attributes = VOXGI_ATTRIBUTE_NORMAL;
        TH_CHECK(voxgi_volume_create(ctx, vox, &vold, &vol) == VOXGI_ERR_INVALID_ARGUMENT && !vol, "a volume of an attribute not voxelized");
        vold.attributes = 0; vold.levels = 99;
        TH_CHECK(voxgi_volume_create(ctx, vox, &vold, &vol) == VOXGI_ERR_INVALID_ARGUMENT && !vol, "99 levels accepted");
        vold.levels = 2;
        TH_CHECK(voxgi_volume_create(ctx, vox, &vold, &vol) == VOXGI_OK && vol, "2 levels: %s", voxgi_last_error(ctx));
        TH_CHECK(voxgi_volume_sample(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, 0, 1, nan_pos, &lod, out) == VOXGI_ERR_INVALID_ARGUMENT, "NaN point sampled");
        TH_CHECK(voxgi_volume_sample(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, VOXGI_DIR_NEG_Y, 1, pos, &lod, out) == VOXGI_ERR_INVALID_ARGUMENT,
                 "an isotropic volume sampled in a direction");
        voxgi_volume_destroy(ctx, vol);
        voxgi_voxels_destroy(ctx, vox);
        voxgi_destroy(ctx);
    }
}

static int cancel_at_once(double f, const char *stage, void *u) { (void)f; (void)stage; (void)u; return 1; }

static int cancel_octree_values(double fraction, const char *stage, void *user)
{
    (void)fraction;
    ++*(int *)user;
    return strcmp(stage, "octree: values") == 0;
}

static void test_cancel_and_api(void)
{
    vxt_shape m;
    voxgi_desc d;
    voxgi_context *ctx = NULL;
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi_voxelize_desc vd;
    voxgi_voxels *vox = NULL;
    voxgi_voxels_info info;
    uint32_t small[4];
    size_t need = 0;
    vxt_shape_sphere(&m, 64, 48, 1.0, 0, 0, 0);
    ctx_desc(&d, VOXGI_BACKEND_CPU);
    memset(&vd, 0, sizeof vd);
    d.progress.func = cancel_at_once;
    voxgi_create(&d, &ctx);
    scene_of_shape(&sc, &mesh, &m);
    {
        voxgi_fit_desc fit;
        memset(&fit, 0, sizeof fit);
        fit.res = 32;
        fit.padding = 1;
        TH_CHECK(voxgi_fit_grid(ctx, &sc, &fit, &vd.grid) == VOXGI_OK, "fit failed");
        TH_CHECK(vd.grid.res[0] == 32 && vd.grid.res[2] == 32, "cubic fit gave %d %d %d", vd.grid.res[0], vd.grid.res[1], vd.grid.res[2]);
        /* the scene (radius 1) sits inside with a voxel of padding */
        TH_CHECK(vd.grid.origin[0] + vd.grid.voxel_size <= -1.0 && vd.grid.origin[0] + 31 * vd.grid.voxel_size >= 1.0,
                 "fit does not pad: origin %g size %g", vd.grid.origin[0], vd.grid.voxel_size);
    }
    TH_CHECK(voxgi_voxelize(ctx, &sc, &vd, &vox) == VOXGI_ERR_CANCELLED && vox == NULL, "cancel ignored");
    voxgi_destroy(ctx);
    {   /* an octree build reports its stages and stops cleanly when asked to */
        int calls = 0;
        voxgi_svo_desc sd;
        voxgi_svo *svo = NULL;
        d.progress.func = cancel_octree_values;
        d.progress.user = &calls;
        voxgi_create(&d, &ctx);
        vd.attributes = VOXGI_ATTRIBUTE_ALBEDO;
        memset(&sd, 0, sizeof sd);
        TH_CHECK(voxgi_voxelize(ctx, &sc, &vd, &vox) == VOXGI_OK && voxgi_svo_create(ctx, vox, &sd, &svo) == VOXGI_ERR_CANCELLED && !svo &&
                 calls > 2, "octree cancel: %s", voxgi_last_error(ctx));
        voxgi_voxels_destroy(ctx, vox);
        vox = NULL;
        vd.attributes = 0;
        voxgi_destroy(ctx);
        d.progress.user = NULL;
    }
    d.progress.func = NULL;
    voxgi_create(&d, &ctx);
    TH_CHECK(voxgi_voxelize(ctx, &sc, &vd, &vox) == VOXGI_OK, "voxelize failed");
    voxgi_voxels_query(vox, &info);
    TH_CHECK(info.voxel_count > 0 && info.triangle_count == m.triangle_count && info.bytes == (32 * 32 * 32) / 8,
             "info wrong: %llu voxels", (unsigned long long)info.voxel_count);
    TH_CHECK(voxgi_voxels_read(ctx, vox, NULL, 0, &need) == VOXGI_OK && need == info.bytes, "size query wrong");
    TH_CHECK(voxgi_voxels_read(ctx, vox, small, sizeof small, NULL) == VOXGI_ERR_BUFFER_TOO_SMALL, "small buffer accepted");
    {
        unsigned name = 0;
        TH_CHECK(voxgi_voxels_gl_buffer(ctx, vox, &name) == VOXGI_ERR_UNSUPPORTED, "CPU voxels gave a GL buffer");
    }
    voxgi_voxels_destroy(ctx, vox);
    voxgi_destroy(ctx);
    vxt_shape_free(&m);
}

/* ---------------------------------------------------------------- GL core: loaders and backends */

/* A small sphere (8 x 6 facets, radius 1) as a scene, and a 16^3 grid around it. */
static void small_sphere(vxt_shape *m, voxgi_mesh *mesh, voxgi_scene *sc, voxgi_voxelize_desc *vd)
{
    vxt_shape_sphere(m, 8, 6, 1.0, 0, 0, 0);
    scene_of_shape(sc, mesh, m);
    memset(vd, 0, sizeof *vd);
    cubic(&vd->grid, -1.2, 2.4, 16);
}

/* The GL backend's buffer hand-over and its storage limit (which backend AUTO picks:
   test_gl_auto_backend). */
static void test_gl_interop_and_backends(void)
{
    voxgi_context *ctx;
    voxgi_info info;
    if (!have_gl()) return;
    ctx = make_ctx(VOXGI_BACKEND_GL, 0);
    TH_CHECK(ctx != NULL, "GL refused a GL 4.5 context");
    if (!ctx) return;
    voxgi_query_info(ctx, &info);
    TH_CHECK(info.backend == VOXGI_BACKEND_GL, "GL asked for, %s given", voxgi_backend_name(info.backend));
    TH_CHECK(strstr(info.gl_version, "4.") != NULL, "GL version '%s'", info.gl_version);
    {
        vxt_shape m;
        voxgi_mesh mesh;
        voxgi_scene sc;
        voxgi_voxelize_desc vd;
        voxgi_voxels *vox = NULL;
        unsigned name = 0;
        small_sphere(&m, &mesh, &sc, &vd);
        TH_CHECK(voxgi_voxelize(ctx, &sc, &vd, &vox) == VOXGI_OK, "GL voxelize failed");
        TH_CHECK(voxgi_voxels_gl_buffer(ctx, vox, &name) == VOXGI_OK && name != 0, "no GL buffer name");
        voxgi_voxels_destroy(ctx, vox);
        cubic(&vd.grid, -1.2, 2.4, 2048); /* 1 GiB of bits: beyond this GL's storage block limit */
        TH_CHECK(voxgi_voxelize(ctx, &sc, &vd, &vox) == VOXGI_ERR_TOO_LARGE && vox == NULL, "2048^3 on GL not refused cleanly");
        TH_CHECK(strstr(voxgi_last_error(ctx), "CPU backend") != NULL, "message: %s", voxgi_last_error(ctx));
        vxt_shape_free(&m);
    }
    voxgi_destroy(ctx);
}

/* The plain loader hook (no user pointer), shaped like eglGetProcAddress and glfwGetProcAddress. */
static voxgi_gl_proc plain_loader(const char *name) { return vxt_gl_get_proc(name, g_gl); }

static void test_gl_plain_loader(void)
{
    voxgi_desc d;
    voxgi_context *ctx = NULL;
    voxgi_info info;
    if (!have_gl()) return;
    memset(&d, 0, sizeof d);
    d.backend = VOXGI_BACKEND_GL;
    d.gl_get_proc_address = plain_loader;
    TH_CHECK(voxgi_create(&d, &ctx) == VOXGI_OK, "plain loader rejected");
    voxgi_query_info(ctx, &info);
    TH_CHECK(info.backend == VOXGI_BACKEND_GL && info.gl_renderer[0], "plain loader: backend %s", voxgi_backend_name(info.backend));
    voxgi_destroy(ctx);
}
static char g_log[1024];
static void keep_log(voxgi_log_level l, const char *msg, void *u) { (void)l; (void)u; snprintf(g_log, sizeof g_log, "%s", msg); }

/* A loader whose glGetString names g_fake_renderer as GL_RENDERER (0x1F01): AUTO's choice
   on a renderer this machine does not have. */
static const char *g_fake_renderer;
static vxt_gl__get_string_fn g_real_get_string;
static const unsigned char *fake_get_string(unsigned name)
{
    return name == 0x1F01 ? (const unsigned char *)g_fake_renderer : g_real_get_string(name);
}
static voxgi_gl_proc loader_fake_renderer(const char *name, void *user)
{
    if (strcmp(name, "glGetString") == 0) return (voxgi_gl_proc)fake_get_string;
    return vxt_gl_get_proc(name, user);
}

/* 1 when s contains what, ignoring ASCII case. */
static int contains_nocase(const char *s, const char *what)
{
    size_t i, j;
    for (i = 0; s[i]; i++) {
        for (j = 0; what[j] && tolower((unsigned char)s[i + j]) == tolower((unsigned char)what[j]); j++) {}
        if (!what[j]) return 1;
    }
    return 0;
}

/* AUTO takes GL unless its renderer is a software rasterizer on the CPU's own cores (llvmpipe
   here), where the CPU backend is faster: then it picks the CPU and its log says why. GL asked
   for is GL all the same, and says it is software. */
static void test_gl_auto_backend(void)
{
    const char *renderer;
    voxgi_desc d;
    voxgi_context *ctx = NULL;
    voxgi_info info;
    int software;
    if (!have_gl()) return;
    renderer = vxt_gl_renderer(g_gl);
    software = contains_nocase(renderer, "llvmpipe") || contains_nocase(renderer, "softpipe") || contains_nocase(renderer, "swiftshader") ||
               contains_nocase(renderer, "software rasterizer") || contains_nocase(renderer, "basic render driver");
    ctx_desc(&d, VOXGI_BACKEND_GL);
    d.logger.func = keep_log;
    TH_CHECK(voxgi_create(&d, &ctx) == VOXGI_OK, "GL refused %s", renderer);
    voxgi_query_info(ctx, &info);
    TH_CHECK(info.backend == VOXGI_BACKEND_GL && strcmp(info.gl_renderer, renderer) == 0 && info.gl_software == software,
             "GL: backend %s, renderer '%s', software %d", voxgi_backend_name(info.backend), info.gl_renderer, info.gl_software);
    TH_CHECK(strstr(g_log, "backend gl: GL") && (!software || strstr(g_log, "software rasterizer")), "GL log: %s", g_log);
    voxgi_destroy(ctx);

    d.backend = VOXGI_BACKEND_AUTO;
    TH_CHECK(voxgi_create(&d, &ctx) == VOXGI_OK, "AUTO failed");
    voxgi_query_info(ctx, &info);
    TH_CHECK(info.backend == (software ? VOXGI_BACKEND_CPU : VOXGI_BACKEND_GL), "AUTO on %s picked %s", renderer, voxgi_backend_name(info.backend));
    TH_CHECK(strcmp(info.gl_renderer, renderer) == 0 && strstr(info.gl_version, "4.") && info.gl_software == software,
             "AUTO: renderer '%s', version '%s', software %d", info.gl_renderer, info.gl_version, info.gl_software);
    if (software)
        TH_CHECK(strstr(g_log, "backend auto: CPU") && strstr(g_log, renderer) && strstr(g_log, "software rasterizer") && strstr(g_log, "VOXGI_BACKEND_GL"),
                 "AUTO's log does not say why: %s", g_log);
    else TH_CHECK(strstr(g_log, "backend auto: GL"), "AUTO's log: %s", g_log);
    if (info.backend == VOXGI_BACKEND_CPU) { /* and the CPU it picked works, with the GL context still current */
        vxt_shape m;
        voxgi_mesh mesh;
        voxgi_scene sc;
        voxgi_voxelize_desc vd;
        voxgi_voxels *vox = NULL;
        unsigned name = 0;
        small_sphere(&m, &mesh, &sc, &vd);
        TH_CHECK(voxgi_voxelize(ctx, &sc, &vd, &vox) == VOXGI_OK, "AUTO (CPU) voxelize: %s", voxgi_last_error(ctx));
        TH_CHECK(voxgi_voxels_gl_buffer(ctx, vox, &name) != VOXGI_OK, "CPU voxels gave a GL buffer");
        voxgi_voxels_destroy(ctx, vox);
        vxt_shape_free(&m);
    }
    voxgi_destroy(ctx);

    /* renderers this machine may not have, through a loader that renames its own */
    {
        static const struct { const char *renderer; int software; } cases[] = {
            {"SwiftShader Device (Subzero)", 1}, {"D3D12 (Microsoft Basic Render Driver)", 1}, {"A Test GPU (hardware)", 0}};
        size_t k;
        g_real_get_string = (vxt_gl__get_string_fn)vxt_gl_get_proc("glGetString", g_gl);
        for (k = 0; k < sizeof cases / sizeof cases[0]; k++) {
            ctx_desc(&d, VOXGI_BACKEND_AUTO);
            d.gl_get_proc_address_user = loader_fake_renderer;
            d.logger.func = keep_log;
            g_fake_renderer = cases[k].renderer;
            TH_CHECK(voxgi_create(&d, &ctx) == VOXGI_OK, "AUTO on '%s' failed", cases[k].renderer);
            voxgi_query_info(ctx, &info);
            TH_CHECK(info.backend == (cases[k].software ? VOXGI_BACKEND_CPU : VOXGI_BACKEND_GL) && info.gl_software == cases[k].software &&
                         strcmp(info.gl_renderer, cases[k].renderer) == 0 && strstr(g_log, cases[k].renderer),
                     "AUTO on '%s': backend %s, software %d, log %s", cases[k].renderer, voxgi_backend_name(info.backend), info.gl_software, g_log);
            voxgi_destroy(ctx);
        }
    }
}

/* A loader that lacks one entry point: GL fails naming it, AUTO falls back to the CPU. */
static voxgi_gl_proc loader_without_indirect(const char *name, void *user)
{
    if (strcmp(name, "glDispatchComputeIndirect") == 0) return NULL;
    return vxt_gl_get_proc(name, user);
}

static void test_gl_missing_function_and_fallback(void)
{
    voxgi_desc d;
    voxgi_context *ctx = NULL;
    voxgi_info info;
    if (!have_gl()) return;
    memset(&d, 0, sizeof d);
    d.backend = VOXGI_BACKEND_GL;
    d.gl_get_proc_address_user = loader_without_indirect;
    d.gl_user = g_gl;
    d.logger.func = keep_log;
    TH_CHECK(voxgi_create(&d, &ctx) == VOXGI_ERR_GL_MISSING_FUNCTION && ctx == NULL, "missing entry point accepted");
    TH_CHECK(strstr(g_log, "glDispatchComputeIndirect") != NULL, "log does not name the function: %s", g_log);
    d.backend = VOXGI_BACKEND_AUTO;
    TH_CHECK(voxgi_create(&d, &ctx) == VOXGI_OK, "AUTO failed");
    voxgi_query_info(ctx, &info);
    TH_CHECK(info.backend == VOXGI_BACKEND_CPU, "AUTO did not fall back to the CPU");
    TH_CHECK(strstr(g_log, "CPU") && strstr(g_log, "glDispatchComputeIndirect"), "fallback not explained: %s", g_log);
    voxgi_destroy(ctx);
    memset(&d, 0, sizeof d); /* no loader at all */
    TH_CHECK(voxgi_create(&d, &ctx) == VOXGI_OK, "AUTO without loader failed");
    voxgi_query_info(ctx, &info);
    TH_CHECK(info.backend == VOXGI_BACKEND_CPU, "AUTO without loader is not CPU");
    voxgi_destroy(ctx);
}

int main(void)
{
    gl_open();
    TH_RUN(test_thread_determinism);
    TH_RUN(test_bad_input);
    TH_RUN(test_failing_allocator);
    TH_RUN(test_volume_and_attribute_failures);
    TH_RUN(test_cancel_and_api);
    TH_RUN(test_gl_interop_and_backends);
    TH_RUN(test_gl_plain_loader);
    TH_RUN(test_gl_auto_backend);
    TH_RUN(test_gl_missing_function_and_fallback);
    gl_close();
    return th_finish();
}
