/* tests/test_faults.c - every allocation failing in turn, and cancellation at every progress report.
 *
 * voxgi allocates through voxgi_desc.allocator alone. Each scenario below (a chain of public calls
 * on the CPU, from the built-in scene to results read back, everything it made destroyed again)
 * runs once to count its allocations and progress reports and to record a hash of its results.
 * Then, for every k:
 *   - the k-th allocation returns NULL: the scenario must end with VOXGI_ERR_OUT_OF_MEMORY and a
 *     message, or succeed with the same results (an allocation a call can do without); and when
 *     all is destroyed, every byte allocated must have been freed (the allocator counts them: a
 *     leak fails in every build, not only under the leak checker);
 *   - the k-th progress report asks to stop: VOXGI_ERR_CANCELLED with a message, and nothing
 *     left allocated;
 *   - a call that fails makes nothing: its result pointer stays NULL.
 * One worker thread (thread_count 1), so that the order of allocations is the same in every run.
 * Then a few of the chains again on a GL context. */
#include "fixtures.h"

/* ---------------------------------------------------------------- the counting allocator */

typedef struct faults {
    unsigned long allocs, fail_at;   /* fail the fail_at-th allocation (1-based; 0: none) */
    long live;                       /* allocations not freed yet */
    unsigned long progress, cancel_at;
    int failed;                      /* the planted failure happened */
} faults;

static void *fault_alloc(size_t size, void *user)
{
    faults *f = (faults *)user;
    size_t *p;
    if (++f->allocs == f->fail_at) { f->failed = 1; return NULL; }
    if (!(p = (size_t *)malloc(size + 16))) return NULL;
    f->live++;
    return p + 2; /* 16 bytes in: keeps malloc's alignment */
}

static void fault_free(void *ptr, void *user)
{
    faults *f = (faults *)user;
    if (!ptr) return;
    f->live--;
    free((size_t *)ptr - 2);
}

static int fault_progress(double fraction, const char *stage, void *user)
{
    faults *f = (faults *)user;
    (void)fraction, (void)stage;
    return ++f->progress == f->cancel_at;
}

/* ---------------------------------------------------------------- the scenarios */

static uint64_t hash_bytes(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = (const unsigned char *)data;
    size_t i;
    for (i = 0; i < n; i++) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

typedef voxgi_result (*scenario_fn)(voxgi_context *ctx, int variant, uint64_t *hash);

/* Calls that failed but left their result set (a failure must make nothing). */
static int partial_results;
#define MADE_NOTHING(call, out) ((r = (call)) == VOXGI_OK || ((out) ? (partial_results++, 0) : 0))

/* The Cornell box voxelized at 16^3 with every attribute; its bits and albedo read back. */
static voxgi_result sc_voxelize(voxgi_context *ctx, int variant, uint64_t *hash)
{
    voxgi_builtin_scene bs;
    voxgi_voxelize_desc vd;
    voxgi_fit_desc fit = {16, 0, 1};
    voxgi_voxels *vox = NULL;
    voxgi_voxels_info info;
    uint32_t bits[4096];
    float *albedo = NULL;
    voxgi_result r;
    size_t need = 0;
    memset(&bs, 0, sizeof bs);
    memset(&vd, 0, sizeof vd);
    vd.method = (voxgi_method)variant;
    vd.attributes = variant == VOXGI_METHOD_CONSERVATIVE ? 15 : 0;
    if ((r = voxgi_builtin_scene_create(ctx, "cornell-box", &bs)) != VOXGI_OK || (r = voxgi_fit_grid(ctx, &bs.scene, &fit, &vd.grid)) != VOXGI_OK ||
        !MADE_NOTHING(voxgi_voxelize(ctx, &bs.scene, &vd, &vox), vox) || (r = voxgi_voxels_read(ctx, vox, bits, sizeof bits, &need)) != VOXGI_OK)
        goto done;
    *hash = hash_bytes(*hash, bits, need);
    voxgi_voxels_query(vox, &info);
    if (info.attributes & VOXGI_ATTRIBUTE_ALBEDO) {
        if (!(albedo = (float *)malloc(info.voxel_count * 12 + 12))) { r = VOXGI_ERR_OUT_OF_MEMORY; goto done; }
        if ((r = voxgi_voxels_read_attribute(ctx, vox, VOXGI_ATTRIBUTE_ALBEDO, albedo, info.voxel_count * 12 + 12, NULL)) != VOXGI_OK) goto done;
        *hash = hash_bytes(*hash, albedo, info.voxel_count * 12);
    }
done:
    free(albedo);
    voxgi_voxels_destroy(ctx, vox);
    voxgi_builtin_scene_destroy(ctx, &bs);
    return r;
}

/* The leak room's light injected (two-sided, one bounce more: variant 0; one-sided: 1), its
   volume's mips, an octree of it with neighbours and bricks written and read back, and cones
   traced over the volume and over the read octree. */
static voxgi_result sc_light(voxgi_context *ctx, int variant, uint64_t *hash)
{
    voxgi_builtin_scene bs;
    voxgi_voxelize_desc vd;
    voxgi_fit_desc fit = {16, 0, 1};
    voxgi_inject_desc id;
    voxgi_svo_desc sd;
    voxgi_cone_desc cd;
    voxgi_voxels *vox = NULL;
    voxgi_volume *vol = NULL;
    voxgi_svo *svo = NULL, *back = NULL;
    voxgi_radiance_source src;
    unsigned char *file = NULL;
    size_t size = 0;
    float pos[3 * 8], nrm[3 * 8], irr[3 * 8], occ[8];
    voxgi_result r;
    int i;
    memset(&bs, 0, sizeof bs);
    memset(&vd, 0, sizeof vd);
    memset(&id, 0, sizeof id);
    memset(&sd, 0, sizeof sd);
    memset(&cd, 0, sizeof cd);
    vd.attributes = 15;
    id.samples = 2;
    id.bounces = variant ? 1 : 2;
    id.one_sided = variant;
    sd.neighbours = sd.bricks = 1;
    for (i = 0; i < 8; i++) {
        pos[3 * i] = -0.9f + 0.2f * (float)i, pos[3 * i + 1] = 0.02f, pos[3 * i + 2] = 0.5f;
        nrm[3 * i] = 0, nrm[3 * i + 1] = 1, nrm[3 * i + 2] = 0;
    }
    if ((r = voxgi_builtin_scene_create(ctx, "leak-room", &bs)) != VOXGI_OK || (r = voxgi_fit_grid(ctx, &bs.scene, &fit, &vd.grid)) != VOXGI_OK ||
        !MADE_NOTHING(voxgi_voxelize(ctx, &bs.scene, &vd, &vox), vox) || !MADE_NOTHING(voxgi_inject_light(ctx, &bs.scene, vox, &id, &vol), vol))
        goto done;
    memset(&src, 0, sizeof src);
    src.volume = vol;
    if ((r = voxgi_cone_trace(ctx, &src, &cd, 8, pos, nrm, irr, occ)) != VOXGI_OK) goto done;
    *hash = hash_bytes(hash_bytes(*hash, irr, sizeof irr), occ, sizeof occ);
    sd.radiance = vol;
    if (!MADE_NOTHING(voxgi_svo_create(ctx, vox, &sd, &svo), svo) || (r = voxgi_svo_write_memory(ctx, svo, NULL, 0, &size)) != VOXGI_OK) goto done;
    if (!(file = (unsigned char *)malloc(size))) { r = VOXGI_ERR_OUT_OF_MEMORY; goto done; }
    if ((r = voxgi_svo_write_memory(ctx, svo, file, size, &size)) != VOXGI_OK || !MADE_NOTHING(voxgi_svo_read_memory(ctx, file, size, &back), back)) goto done;
    *hash = hash_bytes(*hash, file, size);
    src.volume = NULL;
    src.octree = back;
    if ((r = voxgi_cone_trace(ctx, &src, &cd, 8, pos, nrm, irr, occ)) != VOXGI_OK) goto done;
    *hash = hash_bytes(hash_bytes(*hash, irr, sizeof irr), occ, sizeof occ);
done:
    free(file);
    voxgi_svo_destroy(ctx, back);
    voxgi_svo_destroy(ctx, svo);
    voxgi_volume_destroy(ctx, vol);
    voxgi_voxels_destroy(ctx, vox);
    voxgi_builtin_scene_destroy(ctx, &bs);
    return r;
}

/* voxgi_render of a built-in scene by one method (variant), 8 x 8 pixels, small settings. */
static voxgi_result sc_render(voxgi_context *ctx, int variant, uint64_t *hash)
{
    static const char *const scene_of[VOXGI_RENDER_LINESPACE + 1] = {"cornell-box", "cornell-box", "rsm-walls", "rsm-walls", "rsm-walls",
                                                                     "cornell-box", "cornell-box", "rsm-walls", "rsm-walls", "cornell-box"};
    voxgi_builtin_scene bs;
    voxgi_render_desc rd;
    float rgb[8 * 8 * 3];
    voxgi_result r;
    memset(&bs, 0, sizeof bs);
    if ((r = voxgi_builtin_scene_create(ctx, scene_of[variant], &bs)) != VOXGI_OK) goto done;
    memset(&rd, 0, sizeof rd);
    rd.method = (voxgi_render_method)variant;
    rd.camera = bs.camera;
    rd.camera.width = rd.camera.height = 8;
    rd.samples = 1;
    rd.resolution = 16;
    if ((r = voxgi_render(ctx, &bs.scene, &rd, rgb, sizeof rgb, NULL)) == VOXGI_OK) *hash = hash_bytes(*hash, rgb, sizeof rgb);
done:
    voxgi_builtin_scene_destroy(ctx, &bs);
    return r;
}

/* Rays against the Cornell box: the ray scene (its BVH) made, 64 rays intersected and tested. */
static voxgi_result sc_rays(voxgi_context *ctx, int variant, uint64_t *hash)
{
    voxgi_builtin_scene bs;
    voxgi_ray_scene *rs = NULL;
    voxgi_ray rays[64];
    voxgi_ray_hit hits[64];
    unsigned char occluded[64];
    voxgi_result r;
    int i;
    (void)variant;
    memset(&bs, 0, sizeof bs);
    memset(rays, 0, sizeof rays);
    for (i = 0; i < 64; i++) {
        rays[i].origin[0] = 0.278f, rays[i].origin[1] = 0.27f, rays[i].origin[2] = 0.28f;
        rays[i].direction[0] = (float)cos(0.1 * i), rays[i].direction[1] = (float)sin(0.37 * i), rays[i].direction[2] = (float)sin(0.1 * i);
        rays[i].tmax = 10;
    }
    if ((r = voxgi_builtin_scene_create(ctx, "cornell-box", &bs)) != VOXGI_OK || !MADE_NOTHING(voxgi_ray_scene_create(ctx, &bs.scene, &rs), rs) ||
        (r = voxgi_ray_intersect(ctx, rs, 64, rays, hits)) != VOXGI_OK || (r = voxgi_ray_occluded(ctx, rs, 64, rays, occluded)) != VOXGI_OK)
        goto done;
    for (i = 0; i < 64; i++) *hash = hash_bytes(hash_bytes(*hash, &hits[i].t, sizeof hits[i].t), &hits[i].triangle, sizeof hits[i].triangle);
    *hash = hash_bytes(*hash, occluded, sizeof occluded);
done:
    voxgi_ray_scene_destroy(ctx, rs);
    voxgi_builtin_scene_destroy(ctx, &bs);
    return r;
}

/* ---------------------------------------------------------------- the sweeps */

static voxgi_backend sweep_backend = VOXGI_BACKEND_CPU;

static voxgi_context *fault_ctx(faults *f)
{
    voxgi_desc d;
    voxgi_context *ctx = NULL;
    ctx_desc(&d, sweep_backend);
    d.thread_count = 1;
    d.allocator.alloc = fault_alloc;
    d.allocator.free = fault_free;
    d.allocator.user = f;
    d.progress.func = fault_progress;
    d.progress.user = f;
    return voxgi_create(&d, &ctx) == VOXGI_OK ? ctx : NULL;
}

/* Runs the scenario with the k-th allocation failing (fail_at) or the k-th report cancelling
   (cancel_at); 1 when it ended as it must, else 0 with the reason printed. */
static int trial(scenario_fn fn, int variant, const char *name, unsigned long fail_at, unsigned long cancel_at, uint64_t expected_hash)
{
    faults f;
    voxgi_context *ctx;
    voxgi_result r;
    uint64_t hash = 1469598103934665603ull;
    unsigned long before;
    char message[256] = "";
    int ok = 1;
    memset(&f, 0, sizeof f);
    if (!(ctx = fault_ctx(&f))) { printf("    %s: no context\n", name); return 0; }
    before = f.allocs;
    f.fail_at = fail_at ? before + fail_at : 0;
    f.cancel_at = cancel_at;
    partial_results = 0;
    r = fn(ctx, variant, &hash);
    snprintf(message, sizeof message, "%s", voxgi_last_error(ctx));
    if (partial_results) printf("    %s: a call failed (%s) but made its result\n", name, voxgi_result_string(r)), ok = 0;
    voxgi_destroy(ctx);
    if (f.live != 0) printf("    %s: %ld allocations not freed after %s %lu\n", name, f.live, fail_at ? "failing allocation" : "cancelling at report", fail_at ? fail_at : cancel_at), ok = 0;
    if (r == VOXGI_OK && cancel_at) printf("    %s: cancelled at report %lu, it still succeeded\n", name, cancel_at), ok = 0;
    if (r == VOXGI_OK && hash != expected_hash)
        printf("    %s: succeeded with other results after %s %lu\n", name, fail_at ? "failing allocation" : "cancelling at report", fail_at ? fail_at : cancel_at), ok = 0;
    if (r != VOXGI_OK && r != (fail_at ? VOXGI_ERR_OUT_OF_MEMORY : VOXGI_ERR_CANCELLED))
        printf("    %s: %s %lu gave %s: %s\n", name, fail_at ? "failing allocation" : "cancelling at report", fail_at ? fail_at : cancel_at, voxgi_result_string(r), message), ok = 0;
    if (r != VOXGI_OK && !message[0]) printf("    %s: %s without a message\n", name, voxgi_result_string(r)), ok = 0;
    return ok;
}

typedef struct scenario { const char *name; scenario_fn fn; int variant; } scenario;

static void sweep(const scenario *s, long *total_allocs, long *total_reports)
{
    faults f;
    voxgi_context *ctx;
    uint64_t hash = 1469598103934665603ull;
    unsigned long n, k, reports, before, bad = 0;
    voxgi_result r;
    memset(&f, 0, sizeof f);
    ctx = fault_ctx(&f);
    TH_CHECK(ctx != NULL, "no context");
    if (!ctx) return;
    before = f.allocs;
    r = s->fn(ctx, s->variant, &hash);
    n = f.allocs - before;
    reports = f.progress;
    TH_CHECK(r == VOXGI_OK, "%s: %s", s->name, voxgi_last_error(ctx));
    voxgi_destroy(ctx);
    TH_CHECK(f.live == 0, "%s: %ld allocations not freed", s->name, f.live);
    if (r != VOXGI_OK) return;
    for (k = 1; k <= n && bad < 5; k++) bad += !trial(s->fn, s->variant, s->name, k, 0, hash);
    for (k = 1; k <= reports && bad < 5; k++) bad += !trial(s->fn, s->variant, s->name, 0, k, hash);
    TH_CHECK(bad == 0, "%s: %lu of %lu allocation failures and %lu cancellations ended badly", s->name, bad, n, reports);
    printf("    %-22s %5lu allocations failed in turn, %4lu cancellations: %s\n", s->name, n, reports, bad ? "FAILED" : "each clean");
    *total_allocs += (long)n;
    *total_reports += (long)reports;
}

/* voxgi_create itself: its one allocation failing gives OUT_OF_MEMORY and no context. */
static void test_create_out_of_memory(void)
{
    faults f;
    voxgi_desc d;
    voxgi_context *ctx = NULL;
    voxgi_result r;
    memset(&f, 0, sizeof f);
    memset(&d, 0, sizeof d);
    d.backend = VOXGI_BACKEND_CPU;
    d.allocator.alloc = fault_alloc;
    d.allocator.free = fault_free;
    d.allocator.user = &f;
    f.fail_at = 1;
    r = voxgi_create(&d, &ctx);
    TH_CHECK(r == VOXGI_ERR_OUT_OF_MEMORY && !ctx && f.live == 0, "voxgi_create with its allocation failing: %s, context %p", voxgi_result_string(r), (void *)ctx);
    voxgi_destroy(ctx);
}

static void test_every_allocation_fails_in_turn(void)
{
    static const scenario scenarios[] = {
        {"voxelize conservative", sc_voxelize, VOXGI_METHOD_CONSERVATIVE}, {"voxelize solid", sc_voxelize, VOXGI_METHOD_SOLID},
        {"light, octree, cones", sc_light, 0}, {"one-sided light", sc_light, 1}, {"rays", sc_rays, 0},
        {"render reference", sc_render, VOXGI_RENDER_REFERENCE}, {"render vct", sc_render, VOXGI_RENDER_VCT},
        {"render tsm", sc_render, VOXGI_RENDER_TSM}, {"render rsm", sc_render, VOXGI_RENDER_RSM}, {"render sh", sc_render, VOXGI_RENDER_SH},
        {"render ssao", sc_render, VOXGI_RENDER_SSAO}, {"render vao", sc_render, VOXGI_RENDER_VAO}, {"render ssgi", sc_render, VOXGI_RENDER_SSGI},
        {"render hybrid", sc_render, VOXGI_RENDER_HYBRID}, {"render linespace", sc_render, VOXGI_RENDER_LINESPACE}};
    long allocs = 0, reports = 0;
    size_t i;
    for (i = 0; i < sizeof scenarios / sizeof scenarios[0]; i++) sweep(&scenarios[i], &allocs, &reports);
    printf("    in all: %ld allocations failed one at a time, %ld cancellations\n", allocs, reports);
}

/* The same on a GL context: the GL passes' CPU-side allocations (read-backs, uploads, the exact
   voxelizer's referee) fail in turn too. */
static void test_every_allocation_fails_in_turn_gl(void)
{
    static const scenario scenarios[] = {
        {"GL voxelize", sc_voxelize, VOXGI_METHOD_CONSERVATIVE}, {"GL render vct", sc_render, VOXGI_RENDER_VCT},
        {"GL render linespace", sc_render, VOXGI_RENDER_LINESPACE}};
    long allocs = 0, reports = 0;
    size_t i;
    if (!have_gl()) return;
    sweep_backend = VOXGI_BACKEND_GL;
    for (i = 0; i < sizeof scenarios / sizeof scenarios[0]; i++) sweep(&scenarios[i], &allocs, &reports);
    sweep_backend = VOXGI_BACKEND_CPU;
    printf("    in all: %ld allocations failed one at a time, %ld cancellations\n", allocs, reports);
}

int main(void)
{
    gl_open();
    TH_RUN(test_create_out_of_memory);
    TH_RUN(test_every_allocation_fails_in_turn);
    TH_RUN(test_every_allocation_fails_in_turn_gl);
    gl_close();
    return th_finish();
}
