/* tests/test_octree.c - part 7: the sparse voxel octree, CPU and GL. Lookups equal the dense
   isotropic volume at every level bit for bit, in both value formats, with neighbour pointers and
   bricks; cone tracing over an octree of the radiance (part 8's march over the octree's mips)
   equals the volume's, and the GL octree's cones equal the CPU's. (Half-float rounding and the
   GPU-built octree against the CPU's, which call private helpers: tests/test_internals.c.) The GL
   tests skip (loudly) only when no GL 4.5 context can be made; VOXGI_TEST_GL=egl|osmesa picks the
   kind, VOXGI_REQUIRE_GL=1 turns a skip into a failure. */
#define _XOPEN_SOURCE 700 /* mkdtemp */
#include "../voxgi.h"
#include "fixtures.h"
#include "svo_checks.h"
#include "cone_points.h"
#include <stdlib.h>

/* ---------------------------------------------------------------- random numbers */
static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static double rnd(void) /* [0,1) */
{
    rng_state ^= rng_state << 13; rng_state ^= rng_state >> 7; rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) * (1.0 / 9007199254740992.0);
}

/* ---------------------------------------------------------------- sparse voxel octree */
/* 500 random points in and around the octree tests' grid (27 x 25 x 30), and lods past the root. */
static void svo_sample_points(float pos[3 * 500], float lods[500])
{
    size_t q;
    for (q = 0; q < 500; q++) {
        pos[3 * q] = (float)(-2 + 31 * rnd()); pos[3 * q + 1] = (float)(-2 + 29 * rnd()); pos[3 * q + 2] = (float)(-2 + 34 * rnd());
        lods[q] = (float)(-0.5 + 6.5 * rnd());
    }
}

/* Octree lookups equal the dense isotropic volume at every level, bit for bit (the same float
   formulas in the same child order); the nodes of level l are exactly the distinct
   coordinates >> (depth - l) of the voxels; child pointers never use 0 for a tile; the
   structure costs at most 8 bytes per voxel. */
static void test_svo_equals_dense(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    material_sphere s;
    voxgi_voxelize_desc xd;
    voxgi_voxels *vox = NULL;
    voxgi_volume *vol = NULL;
    voxgi_volume_desc vd;
    voxgi_svo *svo = NULL;
    voxgi_svo_desc sd;
    voxgi_svo_info info;
    uint32_t *bits;
    size_t need = 0;
    int lev, bad = 0, a;
    material_sphere_make(&s);
    memset(&xd, 0, sizeof xd);
    xd.grid.origin[0] = -1.1; xd.grid.origin[1] = -1.2; xd.grid.origin[2] = -1.05;
    xd.grid.voxel_size = 0.09;
    xd.grid.res[0] = 27; xd.grid.res[1] = 25; xd.grid.res[2] = 30; /* not powers of two */
    xd.attributes = 15;
    voxgi_voxelize(ctx, &s.scene, &xd, &vox);
    memset(&vd, 0, sizeof vd); memset(&sd, 0, sizeof sd);
    sd.neighbours = 1;
    TH_CHECK(vox && voxgi_volume_create(ctx, vox, &vd, &vol) == VOXGI_OK, "volume: %s", voxgi_last_error(ctx));
    TH_CHECK(voxgi_svo_create(ctx, vox, &sd, &svo) == VOXGI_OK, "octree: %s", voxgi_last_error(ctx));
    if (!vol || !svo) return;
    voxgi_svo_query(svo, &info);
    TH_CHECK(info.depth == 5 && info.leaf_voxels > 0 && info.level_nodes[5] == info.leaf_voxels && info.level_nodes[0] == 1, "depth %d", info.depth);
    voxgi_voxels_read(ctx, vox, NULL, 0, &need);
    bits = (uint32_t *)malloc(need);
    voxgi_voxels_read(ctx, vox, bits, need, NULL);
    for (lev = 0; lev <= info.depth; lev++) {
        int k = info.depth - lev, d[3], x, y, z;
        uint64_t distinct = 0, l;
        unsigned char *seen;
        for (a = 0; a < 3; a++) { d[a] = xd.grid.res[a]; for (x = 0; x < k; x++) d[a] = (d[a] + 1) / 2; }
        seen = (unsigned char *)calloc((size_t)d[0] * (size_t)d[1] * (size_t)d[2], 1);
        for (l = 0; l < 27u * 25u * 30u; l++)
            if (voxgi_bit_get(bits, l)) {
                size_t at = (size_t)((l % 27) >> k) + (size_t)d[0] * ((size_t)((l / 27 % 25) >> k) + (size_t)d[1] * (size_t)((l / 675) >> k));
                distinct += !seen[at];
                seen[at] = 1;
            }
        bad += distinct != info.level_nodes[lev];
        for (a = 0; a < 4; a++) {
            voxgi_attribute which = (voxgi_attribute)(1 << a);
            int w = a == 3 ? 1 : 4;
            size_t nd = (size_t)d[0] * (size_t)d[1] * (size_t)d[2], i;
            float *dense = (float *)malloc(nd * (size_t)w * 4), *got = (float *)malloc(nd * (size_t)w * 4);
            uint32_t *coords = (uint32_t *)malloc(nd * 12);
            voxgi_volume_read(ctx, vol, which, 0, k, dense, nd * (size_t)w * 4, NULL);
            for (z = 0, i = 0; z < d[2]; z++)
                for (y = 0; y < d[1]; y++)
                    for (x = 0; x < d[0]; x++, i++) {
                        coords[3 * i] = (uint32_t)x << k; coords[3 * i + 1] = (uint32_t)y << k; coords[3 * i + 2] = (uint32_t)z << k;
                    }
            voxgi_svo_lookup(ctx, svo, which, lev, nd, coords, got);
            bad += memcmp(dense, got, nd * (size_t)w * 4) != 0;
            free(dense); free(got); free(coords);
        }
        free(seen);
    }
    TH_CHECK(bad == 0, "octree and dense volume differ (%d level/attribute pairs)", bad);
    printf("    octree 27x25x30, depth %d: %llu voxels, %llu node slots, %llu leaf slots, structure %.2f bytes per voxel, %lu bytes vs %lu dense\n",
           info.depth, (unsigned long long)info.leaf_voxels, (unsigned long long)info.nodes, (unsigned long long)info.leaf_slots,
           (double)info.structure_bytes / (double)info.leaf_voxels, (unsigned long)info.bytes, (unsigned long)info.dense_bytes);
    TH_CHECK(info.structure_bytes <= 8 * info.leaf_voxels, "structure %lu bytes for %llu voxels", (unsigned long)info.structure_bytes,
             (unsigned long long)info.leaf_voxels);
    {   /* sampling through the octree equals sampling the dense volume, bit for bit */
        float pos[3 * 500], lods[500], a_out[4 * 500], b_out[4 * 500];
        svo_sample_points(pos, lods);
        for (a = 0; a < 4; a++) {
            voxgi_attribute which = (voxgi_attribute)(1 << a);
            int w = a == 3 ? 1 : 4;
            TH_CHECK(voxgi_volume_sample(ctx, vol, which, 0, 500, pos, lods, a_out) == VOXGI_OK &&
                     voxgi_svo_sample(ctx, svo, which, 500, pos, lods, b_out) == VOXGI_OK, "sampling failed");
            TH_CHECK(memcmp(a_out, b_out, 500 * (size_t)w * 4) == 0, "attribute %d: octree and dense samples differ", a);
        }
    }
    {   /* neighbour pointers: at the same level, exactly the node one step away, symmetric */
        int nodes = 0, wrong = svo_wrong_neighbours(ctx, svo, info.depth, &nodes);
        TH_CHECK(nodes > 0 && wrong == 0, "%d wrong neighbour pointers over %d nodes", wrong, nodes);
        TH_CHECK(info.neighbour_bytes == 24 * info.nodes, "neighbour bytes %lu", (unsigned long)info.neighbour_bytes);
    }
    {   /* outside the grid's cube and at empty places: empty */
        uint32_t c[6] = {40, 1, 1, 0, 0, 0};
        float o[8];
        voxgi_svo_lookup(ctx, svo, VOXGI_ATTRIBUTE_ALBEDO, info.depth, 2, c, o);
        TH_CHECK(o[3] == 0 && o[7] == 0, "empty places are not empty");
        TH_CHECK(voxgi_svo_lookup(ctx, svo, VOXGI_ATTRIBUTE_ALBEDO, 9, 1, c, o) == VOXGI_ERR_INVALID_ARGUMENT, "level 9 accepted");
    }
    {   /* bricks: every texel is the dense volume's value at its place one level down (empty
           outside); the texels a brick shares with its +x/+y/+z neighbour's are equal; sampling
           through bricks equals sampling the dense volume bit for bit */
        voxgi_svo *bk = NULL;
        voxgi_svo_info bi;
        int wrong = 0, bricks = 0, shared = 0;
        sd.bricks = 1;
        TH_CHECK(voxgi_svo_create(ctx, vox, &sd, &bk) == VOXGI_OK, "octree with bricks: %s", voxgi_last_error(ctx));
        sd.bricks = 0;
        if (bk) {
            uint64_t inner = 0;
            voxgi_svo_query(bk, &bi);
            for (lev = 0; lev < bi.depth; lev++) inner += bi.level_nodes[lev];
            TH_CHECK(bi.brick_bytes == inner * 64 * (16 * 3 + 4) && bi.bytes == info.bytes + bi.brick_bytes, "brick bytes %lu for %llu inner nodes",
                     (unsigned long)bi.brick_bytes, (unsigned long long)inner);
            for (a = 0; a < 4; a++) {
                voxgi_attribute which = (voxgi_attribute)(1 << a);
                int w = a == 3 ? 1 : 4;
                for (lev = 0; lev < bi.depth; lev++) {
                    int k = bi.depth - lev - 1, d[3], ax;
                    uint32_t n = 1u << lev, sh = (uint32_t)(bi.depth - lev), x, y, z;
                    float *dense, brick[64 * 4], other[64 * 4];
                    for (ax = 0; ax < 3; ax++) { d[ax] = xd.grid.res[ax]; for (x = 0; x < (uint32_t)k; x++) d[ax] = (d[ax] + 1) / 2; }
                    dense = (float *)malloc((size_t)d[0] * (size_t)d[1] * (size_t)d[2] * (size_t)w * 4);
                    voxgi_volume_read(ctx, vol, which, 0, k, dense, (size_t)d[0] * (size_t)d[1] * (size_t)d[2] * (size_t)w * 4, NULL);
                    for (z = 0; z < n; z++)
                        for (y = 0; y < n; y++)
                            for (x = 0; x < n; x++) {
                                uint32_t c[3], slot = 0;
                                int t, ch, dir;
                                c[0] = x << sh; c[1] = y << sh; c[2] = z << sh;
                                if (lev > 0 && (voxgi_svo_node(ctx, bk, lev, c, &slot), !slot)) continue;
                                voxgi_svo_brick(ctx, bk, which, lev, c, brick);
                                bricks++;
                                for (t = 0; t < 64; t++) {
                                    int q[3], inside = 1;
                                    q[0] = 2 * (int)x - 1 + (t & 3); q[1] = 2 * (int)y - 1 + ((t >> 2) & 3); q[2] = 2 * (int)z - 1 + (t >> 4);
                                    for (ax = 0; ax < 3; ax++) inside &= q[ax] >= 0 && q[ax] < d[ax];
                                    for (ch = 0; ch < w; ch++)
                                        wrong += brick[w * t + ch] !=
                                                 (inside ? dense[((size_t)q[0] + (size_t)d[0] * ((size_t)q[1] + (size_t)d[1] * (size_t)q[2])) * (size_t)w + (size_t)ch] : 0.0f);
                                }
                                for (dir = 0; dir < 3; dir++) { /* the shared layers: mine at 2, 3; the neighbour's at 0, 1 */
                                    uint32_t e[3], nslot = 0;
                                    e[0] = x; e[1] = y; e[2] = z;
                                    if (++e[dir] >= n) continue;
                                    e[0] <<= sh; e[1] <<= sh; e[2] <<= sh;
                                    voxgi_svo_node(ctx, bk, lev, e, &nslot);
                                    if (!nslot) continue;
                                    voxgi_svo_brick(ctx, bk, which, lev, e, other);
                                    for (t = 0; t < 64; t++) {
                                        int along = (t >> (2 * dir)) & 3;
                                        if (along >= 2) {
                                            shared++;
                                            wrong += memcmp(brick + w * t, other + w * (t - (2 << (2 * dir))), (size_t)w * 4) != 0;
                                        }
                                    }
                                }
                            }
                    free(dense);
                }
            }
            TH_CHECK(bricks > 0 && shared > 0 && wrong == 0, "%d wrong brick texels over %d bricks (%d shared)", wrong, bricks, shared);
            {
                float pos[3 * 500], lods[500], a_out[4 * 500], b_out[4 * 500];
                svo_sample_points(pos, lods);
                for (a = 0; a < 4; a++) {
                    voxgi_attribute which = (voxgi_attribute)(1 << a);
                    TH_CHECK(voxgi_volume_sample(ctx, vol, which, 0, 500, pos, lods, a_out) == VOXGI_OK &&
                             voxgi_svo_sample(ctx, bk, which, 500, pos, lods, b_out) == VOXGI_OK, "sampling failed");
                    TH_CHECK(memcmp(a_out, b_out, 500 * (size_t)(a == 3 ? 1 : 4) * 4) == 0, "attribute %d: brick and dense samples differ", a);
                }
            }
        }
        voxgi_svo_destroy(ctx, bk);
        {
            uint32_t c[3] = {0, 0, 0};
            float texels[64 * 4];
            TH_CHECK(voxgi_svo_brick(ctx, svo, VOXGI_ATTRIBUTE_ALBEDO, 0, c, texels) == VOXGI_ERR_UNSUPPORTED, "bricks of an octree without them");
        }
    }
    {   /* half-float values: every lookup within (levels above the voxels + 1) x 2^-10 relative of
           the float octree's (a rounding per level: half has 11 significant bits), a quarter of the
           value bytes, the same nodes */
        voxgi_svo *h = NULL;
        voxgi_svo_info hi;
        double worst = 0;
        int over = 0;
        sd.format = VOXGI_SVO_FLOAT16;
        TH_CHECK(voxgi_svo_create(ctx, vox, &sd, &h) == VOXGI_OK, "half octree: %s", voxgi_last_error(ctx));
        sd.format = VOXGI_SVO_FLOAT32;
        if (h) {
            voxgi_svo_query(h, &hi);
            TH_CHECK(hi.nodes == info.nodes && hi.leaf_slots == info.leaf_slots && hi.format == VOXGI_SVO_FLOAT16 &&
                     hi.bytes - hi.structure_bytes - hi.neighbour_bytes == (info.bytes - info.structure_bytes - info.neighbour_bytes) / 2 &&
                     hi.dense_bytes == info.dense_bytes / 2, "half octree sizes: %lu of %lu bytes", (unsigned long)hi.bytes, (unsigned long)info.bytes);
            for (lev = 0; lev <= info.depth; lev++) {
                uint32_t n = 1u << lev, sh = (uint32_t)(info.depth - lev), q = 0, x, y, z;
                uint32_t *coords = (uint32_t *)malloc((size_t)n * n * n * 12);
                float *f32 = (float *)malloc((size_t)n * n * n * 16), *f16 = (float *)malloc((size_t)n * n * n * 16);
                for (z = 0; z < n; z++)
                    for (y = 0; y < n; y++)
                        for (x = 0; x < n; x++, q++) { coords[3 * q] = x << sh; coords[3 * q + 1] = y << sh; coords[3 * q + 2] = z << sh; }
                for (a = 0; a < 4; a++) {
                    voxgi_attribute which = (voxgi_attribute)(1 << a);
                    size_t e, ne = (size_t)q * (a == 3 ? 1u : 4u);
                    voxgi_svo_lookup(ctx, svo, which, lev, q, coords, f32);
                    voxgi_svo_lookup(ctx, h, which, lev, q, coords, f16);
                    for (e = 0; e < ne; e++) {
                        double d = fabs((double)f32[e] - f16[e]), tol = (sh + 1) * ldexp(1, -10) * fmax(1, fabs(f32[e]));
                        over += d > tol || ((a == 3 || e % 4 == 3) && (f32[e] == 0) != (f16[e] == 0)); /* empty stays empty */
                        worst = fmax(worst, d / fmax(1, fabs(f32[e])));
                    }
                }
                free(coords); free(f32); free(f16);
            }
            TH_CHECK(over == 0, "%d half values beyond the bound", over);
            printf("    half-float octree: %lu bytes (float: %lu), worst relative difference %.2e over every level\n", (unsigned long)hi.bytes,
                   (unsigned long)info.bytes, worst);
        }
        voxgi_svo_destroy(ctx, h);
        sd.format = (voxgi_svo_format)7;
        TH_CHECK(voxgi_svo_create(ctx, vox, &sd, &h) == VOXGI_ERR_INVALID_ARGUMENT && !h, "format 7 accepted");
        sd.format = VOXGI_SVO_FLOAT32;
    }
    {   /* a memory budget below the octree's size: refused before anything is built, nothing leaks */
        voxgi_desc d;
        voxgi_context *small = NULL;
        voxgi_svo *none = NULL;
        memset(&d, 0, sizeof d);
        d.backend = VOXGI_BACKEND_CPU;
        d.memory_budget = info.bytes / 2;
        voxgi_create(&d, &small);
        TH_CHECK(voxgi_svo_create(small, vox, &sd, &none) == VOXGI_ERR_TOO_LARGE && !none, "budget %lu: %s", (unsigned long)d.memory_budget,
                 voxgi_last_error(small));
        d.memory_budget = info.bytes;
        voxgi_destroy(small);
        voxgi_create(&d, &small);
        TH_CHECK(voxgi_svo_create(small, vox, &sd, &none) == VOXGI_OK && none, "the exact budget refused: %s", voxgi_last_error(small));
        voxgi_svo_destroy(small, none);
        voxgi_destroy(small);
    }
    free(bits);
    voxgi_svo_destroy(ctx, svo);
    voxgi_volume_destroy(ctx, vol);
    voxgi_voxels_destroy(ctx, vox);
    material_sphere_free(&s);
    voxgi_destroy(ctx);
}

/* Cone tracing over an octree of the radiance: the octree's mips are the isotropic volume's
   (premultiplied, plain means), and the march is the volume's, so a float32 octree gives the
   volume's irradiance, occlusion and single cones bit for bit, with or without bricks, on a grid
   that is not a power of two (24^3 in a 32^3 cube), one-sided and two-sided; a float16 octree
   stays within 1% of the mean irradiance; a cone-traced image through the octree equals the
   volume's bit for bit, also where cones keep to enclosed regions (the leak room, from inside
   its closed box and from the room). Bad radiance inputs are refused. */
static void test_octree_cones(void)
{
    enum { N = 200, W = 16 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene bs;
    voxgi_fit_desc fit;
    voxgi_voxelize_desc xd;
    voxgi_inject_desc id;
    voxgi_voxels *vox = NULL;
    voxgi_volume *vol = NULL, *albedo = NULL;
    voxgi_cone_desc cd;
    voxgi_svo_desc sd;
    voxgi_svo *svo = NULL;
    voxgi_render_desc vd;
    voxgi_cone single[N];
    float pos[3 * N], nrm[3 * N], irr[2][3 * N], occ[2][N], each[2][4 * N], *img[2];
    double mean = 0, worst16 = 0;
    int i, k, sides;
    voxgi_builtin_scene_create(ctx, "cornell-box", &bs);
    for (sides = 1; sides <= 2; sides++) {
        memset(&fit, 0, sizeof fit);
        memset(&xd, 0, sizeof xd);
        memset(&id, 0, sizeof id);
        memset(&cd, 0, sizeof cd);
        fit.res = 24;
        fit.padding = 1;
        xd.attributes = VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_NORMAL;
        id.samples = 4;
        id.one_sided = sides == 1;
        TH_CHECK(voxgi_fit_grid(ctx, &bs.scene, &fit, &xd.grid) == VOXGI_OK && voxgi_voxelize(ctx, &bs.scene, &xd, &vox) == VOXGI_OK &&
                 voxgi_inject_light(ctx, &bs.scene, vox, &id, &vol) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        cornell_cone_points(11, N, pos, nrm, single);
        TH_CHECK(voxgi_cone_trace(ctx, VOLUME_SOURCE(vol), &cd, N, pos, nrm, irr[0], occ[0]) == VOXGI_OK && voxgi_cone_trace_each(ctx, VOLUME_SOURCE(vol), &cd, N, single, each[0]) == VOXGI_OK,
                 "volume: %s", voxgi_last_error(ctx));
        for (i = 0, mean = worst16 = 0; i < 3 * N; i++) mean += irr[0][i] / (3.0 * N);
        for (k = 0; k < 3; k++) { /* float32, float32 with bricks, float16 */
            memset(&sd, 0, sizeof sd);
            sd.attributes = VOXGI_ATTRIBUTE_RADIANCE;
            sd.radiance = vol;
            sd.bricks = k == 1;
            sd.format = k == 2 ? VOXGI_SVO_FLOAT16 : VOXGI_SVO_FLOAT32;
            TH_CHECK(voxgi_svo_create(ctx, vox, &sd, &svo) == VOXGI_OK && voxgi_cone_trace(ctx, OCTREE_SOURCE(svo), &cd, N, pos, nrm, irr[1], occ[1]) == VOXGI_OK &&
                     voxgi_cone_trace_each(ctx, OCTREE_SOURCE(svo), &cd, N, single, each[1]) == VOXGI_OK, "octree %d: %s", k, voxgi_last_error(ctx));
            if (k < 2)
                TH_CHECK(!memcmp(irr[0], irr[1], sizeof irr[0]) && !memcmp(occ[0], occ[1], sizeof occ[0]) && !memcmp(each[0], each[1], sizeof each[0]),
                         "%s-sided float32 octree%s: cones differ from the volume's", sides == 1 ? "one" : "two", k ? " with bricks" : "");
            else {
                for (i = 0; i < 3 * N; i++) worst16 = fmax(worst16, fabs(irr[0][i] - irr[1][i]) / mean);
                printf("    %s-sided octree cones: float32 (and with bricks) == the isotropic volume bit for bit; float16 within %.2g of the mean irradiance %.3g\n",
                       sides == 1 ? "one" : "two", worst16, mean);
                TH_CHECK(mean > 0.05 && worst16 < 0.01, "float16 octree off by %.3g of the mean", worst16);
            }
            voxgi_svo_destroy(ctx, svo);
            svo = NULL;
        }
        if (sides == 1) { voxgi_volume_destroy(ctx, vol); voxgi_voxels_destroy(ctx, vox); }
    }
    for (sides = 0; sides < 3; sides++) { /* images through the octree: the Cornell box one-sided; the leak room from its box and from the room */
        voxgi_builtin_scene room;
        TH_CHECK(voxgi_builtin_scene_create(ctx, sides ? "leak-room" : "cornell-box", &room) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        vct_view(&vd, &room, W);
        vd.resolution = sides ? 32 : 24;
        vd.samples = 2;
        vd.vct.one_sided = !sides;
        if (sides == 2) {
            vd.camera.eye[0] = 0.85f; vd.camera.eye[1] = 1.6f; vd.camera.eye[2] = -0.85f;
            vd.camera.target[0] = 0; vd.camera.target[1] = 0.4f; vd.camera.target[2] = 0;
            vd.camera.fovy_degrees = 75;
        }
        for (k = 0; k < 2; k++) {
            img[k] = (float *)malloc(W * W * 12);
            vd.vct.radiance = k ? VOXGI_VCT_OCTREE : VOXGI_VCT_ISOTROPIC; /* the old octree = k (filter isotropic) */
            TH_CHECK(voxgi_render(ctx, &room.scene, &vd, img[k], W * W * 12, NULL) == VOXGI_OK, "render: %s", voxgi_last_error(ctx));
        }
        for (i = 0, mean = 0; i < 3 * W * W; i++) mean += img[0][i];
        TH_CHECK(sides == 1 || mean > 0, "a black image");
        TH_CHECK(!memcmp(img[0], img[1], W * W * 12), "%s: the image through the octree differs from the volume's", sides ? "leak room" : "Cornell box");
        free(img[0]);
        free(img[1]);
        voxgi_builtin_scene_destroy(ctx, &room);
    }
    { /* the leak room in a shell of empty space 4 voxels thick: no surface lights the shell, so its empty
         cubes above level 0 count as no region, in the octree as in the volume's levels */
        enum { M = LEAK_ROOM_POINTS };
        voxgi_builtin_scene room;
        voxgi_voxels *rvox = NULL;
        voxgi_volume *rvol = NULL;
        float rpos[3 * M], rnrm[3 * M], rirr[2][3 * M];
        TH_CHECK(voxgi_builtin_scene_create(ctx, "leak-room", &room) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        leak_room_points(rpos, rnrm);
        fit.res = 32;
        fit.padding = 4;
        id.one_sided = 0;
        memset(&sd, 0, sizeof sd);
        TH_CHECK(voxgi_fit_grid(ctx, &room.scene, &fit, &xd.grid) == VOXGI_OK && voxgi_voxelize(ctx, &room.scene, &xd, &rvox) == VOXGI_OK &&
                 voxgi_inject_light(ctx, &room.scene, rvox, &id, &rvol) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        sd.radiance = rvol;
        TH_CHECK(voxgi_svo_create(ctx, rvox, &sd, &svo) == VOXGI_OK && voxgi_cone_trace(ctx, VOLUME_SOURCE(rvol), &cd, M, rpos, rnrm, rirr[0], NULL) == VOXGI_OK &&
                 voxgi_cone_trace(ctx, OCTREE_SOURCE(svo), &cd, M, rpos, rnrm, rirr[1], NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        for (i = 0, mean = 0; i < 3 * M; i++) mean += rirr[0][i];
        TH_CHECK(mean > 0 && !memcmp(rirr[0], rirr[1], sizeof rirr[0]), "leak room in a dark shell: the octree's cones differ from the volume's");
        voxgi_svo_destroy(ctx, svo);
        svo = NULL;
        voxgi_volume_destroy(ctx, rvol);
        voxgi_voxels_destroy(ctx, rvox);
        voxgi_builtin_scene_destroy(ctx, &room);
    }
    /* refusals: RADIANCE without a volume, a volume without RADIANCE, another grid, an octree without radiance */
    memset(&sd, 0, sizeof sd);
    sd.attributes = VOXGI_ATTRIBUTE_RADIANCE;
    TH_CHECK(voxgi_svo_create(ctx, vox, &sd, &svo) == VOXGI_ERR_INVALID_ARGUMENT && !svo, "RADIANCE without desc.radiance accepted");
    {
        voxgi_volume_desc ad;
        memset(&ad, 0, sizeof ad);
        ad.attributes = VOXGI_ATTRIBUTE_ALBEDO;
        TH_CHECK(voxgi_volume_create(ctx, vox, &ad, &albedo) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    }
    sd.attributes = 0;
    sd.radiance = albedo;
    TH_CHECK(voxgi_svo_create(ctx, vox, &sd, &svo) == VOXGI_ERR_INVALID_ARGUMENT && !svo, "a volume without RADIANCE accepted");
    {
        voxgi_voxels *other = NULL;
        xd.grid.res[0] -= 1;
        TH_CHECK(voxgi_voxelize(ctx, &bs.scene, &xd, &other) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        sd.radiance = vol;
        TH_CHECK(voxgi_svo_create(ctx, other, &sd, &svo) == VOXGI_ERR_INVALID_ARGUMENT && !svo, "radiance on another grid accepted");
        voxgi_voxels_destroy(ctx, other);
    }
    sd.radiance = NULL;
    TH_CHECK(voxgi_svo_create(ctx, vox, &sd, &svo) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    TH_CHECK(voxgi_cone_trace(ctx, OCTREE_SOURCE(svo), &cd, N, pos, nrm, irr[1], NULL) == VOXGI_ERR_INVALID_ARGUMENT, "an octree without radiance traced");
    TH_CHECK(voxgi_cone_trace(ctx, OCTREE_SOURCE(NULL), &cd, N, pos, nrm, irr[1], NULL) == VOXGI_ERR_INVALID_ARGUMENT, "a NULL octree traced");
    { /* a source names exactly one of a volume and an octree */
        voxgi_radiance_source both;
        both.volume = vol;
        both.octree = svo;
        TH_CHECK(voxgi_cone_trace(ctx, &both, &cd, N, pos, nrm, irr[1], NULL) == VOXGI_ERR_INVALID_ARGUMENT, "a source of both traced");
        TH_CHECK(voxgi_cone_trace_each(ctx, &both, &cd, 0, NULL, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "single cones from both");
        TH_CHECK(voxgi_cone_trace(ctx, NULL, &cd, N, pos, nrm, irr[1], NULL) == VOXGI_ERR_INVALID_ARGUMENT, "a NULL source traced");
    }
    voxgi_svo_destroy(ctx, svo);
    voxgi_volume_destroy(ctx, albedo);
    voxgi_volume_destroy(ctx, vol);
    voxgi_voxels_destroy(ctx, vox);
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* The scene's voxels lit on ctx (res voxels, `padding` empty ones around; the CPU's shadow rays on
   either backend, so that both hold the same radiance), their octree as sd asks, and its cones
   (cd) at n points (occ may be NULL) and, with single, along those n cones. 1 on success. */
static int octree_cones(voxgi_context *ctx, const voxgi_scene *sc, int res, int padding, int one_sided, voxgi_svo_desc sd, const voxgi_cone_desc *cd,
                        size_t n, const float *pos, const float *nrm, float *irr, float *occ, const voxgi_cone *single, float *each)
{
    voxgi_inject_desc id;
    voxgi_voxels *vx;
    voxgi_volume *vol;
    voxgi_svo *svo = NULL;
    int ok;
    memset(&id, 0, sizeof id);
    id.samples = 4;
    id.shadow_rays = 1;
    id.one_sided = one_sided;
    if (!lit_voxels_padded(ctx, sc, res, padding, &id, &vx, &vol)) return 0;
    sd.radiance = vol;
    ok = voxgi_svo_create(ctx, vx, &sd, &svo) == VOXGI_OK && voxgi_cone_trace(ctx, OCTREE_SOURCE(svo), cd, n, pos, nrm, irr, occ) == VOXGI_OK &&
         (!single || voxgi_cone_trace_each(ctx, OCTREE_SOURCE(svo), cd, n, single, each) == VOXGI_OK);
    if (!ok) printf("    %s\n", voxgi_last_error(ctx));
    voxgi_svo_destroy(ctx, svo);
    voxgi_volume_destroy(ctx, vol);
    voxgi_voxels_destroy(ctx, vx);
    return ok;
}

/* Cone tracing over an octree of the radiance on GL (the march over the octree's buffers,
   shaders/cone_svo.glsl) against the CPU's over the CPU's octree of the same radiance: float32
   and float16, with and without bricks, diffuse gathers and single cones, one-sided and
   two-sided, and 32 cones at 64^3 (more loop iterations than llvmpipe runs in one invocation,
   were the cones of a point not spread over invocations); an image from inside an enclosed
   region (the leak box with a lamp inside), where the cones keep to the region by the octree's
   labels; and the leak room in a dark shell. */
static void test_gl_octree_cones_equal_cpu(void)
{
    enum { N = 200 };
    voxgi_context *ctx[2];
    voxgi_builtin_scene bs;
    float pos[3 * N], nrm[3 * N], irr[2][3 * N], occ[2][N], each[2][4 * N];
    voxgi_cone single[N];
    double worst_irr = 0, worst_occ = 0, worst_each = 0, mean = 0;
    int b, k, i;
    if (!have_gl()) return;
    ctx[0] = make_ctx(VOXGI_BACKEND_CPU, 0);
    ctx[1] = make_ctx(VOXGI_BACKEND_GL, 0);
    TH_CHECK(voxgi_builtin_scene_create(ctx[0], "cornell-box", &bs) == VOXGI_OK, "scene");
    cornell_cone_points(7, N, pos, nrm, single);
    for (k = 0; k < 7; k++) { /* float32, float32 with bricks, float16; two-sided, then one-sided; then 32 cones at 64^3 */
        for (b = 0; b < 2; b++) {
            voxgi_cone_desc cd;
            voxgi_svo_desc sd;
            memset(&cd, 0, sizeof cd);
            memset(&sd, 0, sizeof sd);
            sd.attributes = VOXGI_ATTRIBUTE_RADIANCE;
            sd.bricks = k % 3 == 1;
            sd.format = k % 3 == 2 ? VOXGI_SVO_FLOAT16 : VOXGI_SVO_FLOAT32;
            cd.cones = k == 6 ? 32 : 0; /* a gather llvmpipe's loop limit used to cut short */
            TH_CHECK(octree_cones(ctx[b], &bs.scene, k == 6 ? 64 : 24, 1, k >= 3 && k < 6, sd, &cd, N, pos, nrm, irr[b], occ[b], single, each[b]),
                     "%s octree", b ? "GL" : "CPU");
        }
        if (!k) for (i = 0; i < 3 * N; i++) mean += irr[0][i] / (3.0 * N);
        for (i = 0; i < 3 * N; i++) worst_irr = fmax(worst_irr, fabs(irr[0][i] - irr[1][i]));
        for (i = 0; i < N; i++) worst_occ = fmax(worst_occ, fabs(occ[0][i] - occ[1][i]));
        for (i = 0; i < 4 * N; i++) worst_each = fmax(worst_each, fabs(each[0][i] - each[1][i]) / (i % 4 == 3 ? 1 : fmax(mean, 1e-3)));
    }
    printf("    GL octree cones vs CPU: irradiance within %.3g (mean %.3g), occlusion within %.3g, single cones within %.3g (relative)\n", worst_irr, mean,
           worst_occ, worst_each);
    /* the octree's samples are filtered in the shader's own float arithmetic, on any GPU */
    TH_CHECK(mean > 0.05 && worst_irr <= 1e-4 * mean, "irradiance differs by %g (mean %g)", worst_irr, mean);
    TH_CHECK(worst_occ <= 1e-4, "occlusion differs by %g", worst_occ);
    TH_CHECK(worst_each <= 1e-4, "single cones differ by %g", worst_each);
    {
        enum { W = 24 };
        voxgi_builtin_scene box;
        voxgi_light lights[3];
        float *img[2];
        double worst = 0, mean_img = 0;
        TH_CHECK(leak_box_with_lamp(ctx[0], &box, lights) == VOXGI_OK, "leak-box");
        for (b = 0; b < 2; b++) {
            voxgi_render_desc vd;
            img[b] = (float *)malloc(W * W * 12);
            vct_view(&vd, &box, W);
            vd.resolution = 32;
            vd.samples = 2;
            vd.vct.shadow_rays = 1;
            vd.hide_emitters = 1;
            vd.vct.radiance = VOXGI_VCT_OCTREE;
            TH_CHECK(voxgi_render(ctx[b], &box.scene, &vd, img[b], W * W * 12, NULL) == VOXGI_OK, "enclosed: %s", voxgi_last_error(ctx[b]));
        }
        for (i = 0; i < 3 * W * W; i++) { worst = fmax(worst, fabs(img[0][i] - img[1][i])); mean_img += img[0][i] / (3.0 * W * W); }
        printf("    GL octree cones from an enclosed region vs CPU: image within %.3g of its mean (%.3g)\n", worst / mean_img, mean_img);
        TH_CHECK(mean_img > 0.01 && worst <= 1e-4 * mean_img, "enclosed: image differs by %g (mean %g)", worst, mean_img);
        free(img[0]);
        free(img[1]);
        voxgi_builtin_scene_destroy(ctx[0], &box);
    }
    { /* the leak room in a dark shell of empty space 4 voxels thick (its coarse empty cubes count as no region) */
        voxgi_builtin_scene room;
        float rpos[3 * LEAK_ROOM_POINTS], rnrm[3 * LEAK_ROOM_POINTS], rirr[2][3 * LEAK_ROOM_POINTS];
        double worst = 0, mean_room = 0;
        TH_CHECK(voxgi_builtin_scene_create(ctx[0], "leak-room", &room) == VOXGI_OK, "leak-room");
        leak_room_points(rpos, rnrm);
        for (b = 0; b < 2; b++) {
            voxgi_cone_desc cd;
            voxgi_svo_desc sd;
            memset(&cd, 0, sizeof cd);
            memset(&sd, 0, sizeof sd);
            TH_CHECK(octree_cones(ctx[b], &room.scene, 32, 4, 0, sd, &cd, LEAK_ROOM_POINTS, rpos, rnrm, rirr[b], NULL, NULL, NULL), "%s octree",
                     b ? "GL" : "CPU");
        }
        for (i = 0; i < 3 * LEAK_ROOM_POINTS; i++) mean_room += rirr[0][i] / (3.0 * LEAK_ROOM_POINTS);
        for (i = 0; i < 3 * LEAK_ROOM_POINTS; i++) worst = fmax(worst, fabs(rirr[0][i] - rirr[1][i]));
        printf("    GL octree cones in the leak room's dark shell vs CPU: irradiance within %.3g of the mean (%.3g)\n", worst / mean_room, mean_room);
        TH_CHECK(mean_room > 0.01 && worst <= 1e-4 * mean_room, "dark shell: irradiance differs by %g (mean %g)", worst, mean_room);
        voxgi_builtin_scene_destroy(ctx[0], &room);
    }
    voxgi_builtin_scene_destroy(ctx[0], &bs);
    voxgi_destroy(ctx[0]);
    voxgi_destroy(ctx[1]);
}

/* ---------------------------------------------------------------- octree files */
static uint64_t le_at(const unsigned char *p, size_t at, int width) /* the test's own little-endian reader */
{
    uint64_t v = 0;
    int b;
    for (b = width - 1; b >= 0; b--) v = v << 8 | p[at + (size_t)b];
    return v;
}

static void le_put(unsigned char *p, size_t at, int width, uint64_t v)
{
    int b;
    for (b = 0; b < width; b++) p[at + (size_t)b] = (unsigned char)(v >> (8 * b));
}

/* The octree's file in a fresh malloc'd buffer of exactly its size (*size); NULL on failure. */
static unsigned char *svo_bytes(voxgi_context *ctx, const voxgi_svo *svo, size_t *size)
{
    unsigned char *d;
    *size = 0;
    if (voxgi_svo_write_memory(ctx, svo, NULL, 0, size) != VOXGI_OK || !(d = (unsigned char *)malloc(*size))) return NULL;
    if (voxgi_svo_write_memory(ctx, svo, d, *size, size) != VOXGI_OK) { free(d); return NULL; }
    return d;
}

/* Whether b (a CPU octree) answers every query as a does: its info (all but the build times and the backend), lookups of every
   voxel of the grid at every level and attribute, the node slots of every cell of every level,
   the neighbours of every slot, every brick, and 500 samples; bit for bit. Counts the queries. */
static int svo_same(voxgi_context *ctx, const voxgi_svo *a, const voxgi_svo *b, const char *what, long *queries)
{
    voxgi_svo_info ia, ib;
    const voxgi_svo *s[2];
    uint32_t *coords, x, y, z;
    float *out[2], pos[3 * 500], lods[500];
    size_t nvox, i;
    int lev, at, k, same = 1;
    voxgi_svo_query(a, &ia);
    voxgi_svo_query(b, &ib);
    s[0] = a; s[1] = b;
    if (memcmp(ia.grid.origin, ib.grid.origin, sizeof ia.grid.origin) || ia.grid.voxel_size != ib.grid.voxel_size ||
        memcmp(ia.grid.res, ib.grid.res, sizeof ia.grid.res) || ia.attributes != ib.attributes || ia.format != ib.format ||
        ia.depth != ib.depth || ia.leaf_voxels != ib.leaf_voxels || ia.nodes != ib.nodes || ia.leaf_slots != ib.leaf_slots ||
        memcmp(ia.level_nodes, ib.level_nodes, sizeof ia.level_nodes) || ia.structure_bytes != ib.structure_bytes ||
        ia.neighbour_bytes != ib.neighbour_bytes || ia.brick_bytes != ib.brick_bytes || ia.bytes != ib.bytes || ia.dense_bytes != ib.dense_bytes) {
        printf("    %s: the info differs (nodes %llu/%llu, bytes %lu/%lu, bricks %lu/%lu)\n", what, (unsigned long long)ia.nodes, (unsigned long long)ib.nodes,
               (unsigned long)ia.bytes, (unsigned long)ib.bytes, (unsigned long)ia.brick_bytes, (unsigned long)ib.brick_bytes);
        return 0;
    }
    nvox = (size_t)voxgi_grid_voxel_count(&ia.grid);
    coords = (uint32_t *)malloc(nvox * 12);
    out[0] = (float *)malloc(nvox * 16);
    out[1] = (float *)malloc(nvox * 16);
    for (i = 0, z = 0; z < (uint32_t)ia.grid.res[2]; z++)
        for (y = 0; y < (uint32_t)ia.grid.res[1]; y++)
            for (x = 0; x < (uint32_t)ia.grid.res[0]; x++, i++) { coords[3 * i] = x; coords[3 * i + 1] = y; coords[3 * i + 2] = z; }
    svo_sample_points(pos, lods);
    for (at = 0; at < 7 && same; at++) {
        voxgi_attribute which = (voxgi_attribute)(1 << at);
        if (!(ia.attributes & (unsigned)which)) continue;
        for (lev = 0; lev <= ia.depth && same; lev++) { /* lookups of every voxel */
            for (k = 0; k < 2; k++)
                if (voxgi_svo_lookup(ctx, s[k], which, lev, nvox, coords, out[k]) != VOXGI_OK) same = 0;
            same = same && !memcmp(out[0], out[1], nvox * (which == VOXGI_ATTRIBUTE_OPACITY ? 4 : 16));
            *queries += (long)nvox;
            if (!same) printf("    %s: lookups of attribute 0x%x at level %d differ\n", what, (unsigned)which, lev);
        }
        for (lev = 0; lev < ia.depth && ia.brick_bytes && same; lev++) { /* every brick */
            uint32_t sh = (uint32_t)(ia.depth - lev), c[3];
            for (z = 0; z < (uint32_t)ia.grid.res[2] && same; z += 1u << sh)
                for (y = 0; y < (uint32_t)ia.grid.res[1]; y += 1u << sh)
                    for (x = 0; x < (uint32_t)ia.grid.res[0]; x += 1u << sh) {
                        c[0] = x; c[1] = y; c[2] = z;
                        for (k = 0; k < 2; k++)
                            if (voxgi_svo_brick(ctx, s[k], which, lev, c, out[k]) != VOXGI_OK) same = 0;
                        if (memcmp(out[0], out[1], 64 * (which == VOXGI_ATTRIBUTE_OPACITY ? 4 : 16))) same = 0;
                        (*queries)++;
                    }
            if (!same) printf("    %s: bricks of attribute 0x%x at level %d differ\n", what, (unsigned)which, lev);
        }
        for (k = 0; k < 2 && ia.backend == VOXGI_BACKEND_CPU; k++) /* (GL samples in a shader, which test_internals compares with the CPU's) */
            if (voxgi_svo_sample(ctx, s[k], which, 500, pos, lods, out[k]) != VOXGI_OK) same = 0;
        if (same && memcmp(out[0], out[1], 500 * (which == VOXGI_ATTRIBUTE_OPACITY ? 4 : 16))) { same = 0; printf("    %s: samples differ\n", what); }
        *queries += 500;
    }
    for (lev = 1; lev < ia.depth && same; lev++) { /* the node slot of every cell */
        uint32_t sh = (uint32_t)(ia.depth - lev), c[3], slot[2];
        for (z = 0; z < (uint32_t)ia.grid.res[2]; z += 1u << sh)
            for (y = 0; y < (uint32_t)ia.grid.res[1]; y += 1u << sh)
                for (x = 0; x < (uint32_t)ia.grid.res[0]; x += 1u << sh) {
                    c[0] = x; c[1] = y; c[2] = z;
                    for (k = 0; k < 2; k++)
                        if (voxgi_svo_node(ctx, s[k], lev, c, &slot[k]) != VOXGI_OK) same = 0;
                    if (slot[0] != slot[1]) same = 0;
                    (*queries)++;
                }
        if (!same) printf("    %s: node slots at level %d differ\n", what, lev);
    }
    for (i = 0; i < ia.nodes && ia.neighbour_bytes && same; i++) { /* the neighbours of every slot */
        uint32_t nb[2][6];
        for (k = 0; k < 2; k++)
            if (voxgi_svo_neighbours(ctx, s[k], (uint32_t)i, nb[k]) != VOXGI_OK) same = 0;
        if (memcmp(nb[0], nb[1], sizeof nb[0])) { same = 0; printf("    %s: the neighbours of slot %lu differ\n", what, (unsigned long)i); }
        (*queries)++;
    }
    free(coords);
    free(out[0]);
    free(out[1]);
    return same;
}

/* Whether cones over a and b (diffuse gathers and single cones at n points) agree bit for bit. */
static int svo_same_cones(voxgi_context *ctx, const voxgi_svo *a, const voxgi_svo *b, size_t n, const float *pos, const float *nrm, const voxgi_cone *single)
{
    voxgi_cone_desc cd;
    float *irr[2], *occ[2], *each[2];
    int k, same = 1;
    memset(&cd, 0, sizeof cd);
    for (k = 0; k < 2; k++) {
        const voxgi_svo *s = k ? b : a;
        irr[k] = (float *)malloc(n * 12); occ[k] = (float *)malloc(n * 4); each[k] = (float *)malloc(n * 16);
        if (voxgi_cone_trace(ctx, OCTREE_SOURCE(s), &cd, n, pos, nrm, irr[k], occ[k]) != VOXGI_OK ||
            (single && voxgi_cone_trace_each(ctx, OCTREE_SOURCE(s), &cd, n, single, each[k]) != VOXGI_OK)) {
            printf("    cones: %s\n", voxgi_last_error(ctx));
            same = 0;
        }
    }
    if (same) same = !memcmp(irr[0], irr[1], n * 12) && !memcmp(occ[0], occ[1], n * 4) && (!single || !memcmp(each[0], each[1], n * 16));
    for (k = 0; k < 2; k++) { free(irr[k]); free(occ[k]); free(each[k]); }
    return same;
}

/* Writes svo, reads it back and checks the read one answers as svo does (svo_same) and writes the
   same bytes again. Returns the read octree (NULL on failure); *size: the file's bytes. */
static voxgi_svo *svo_round_trip(voxgi_context *ctx, const voxgi_svo *svo, const char *what, long *queries, size_t *size)
{
    unsigned char *d = svo_bytes(ctx, svo, size), *again;
    voxgi_svo *back = NULL;
    size_t size2 = 0;
    TH_CHECK(d != NULL, "%s: write: %s", what, voxgi_last_error(ctx));
    if (!d) return NULL;
    { /* the header as docs/volumes-and-octrees.md lays it out, read by the test's own reader */
        voxgi_svo_info info;
        double vs;
        uint64_t bits = le_at(d, 40, 8);
        memcpy(&vs, &bits, 8);
        voxgi_svo_query(svo, &info);
        TH_CHECK(!memcmp(d, "VOXGISVO", 8) && le_at(d, 8, 4) == 1 && vs == info.grid.voxel_size && le_at(d, 48, 4) == (uint64_t)info.grid.res[0] &&
                     le_at(d, 56, 4) == (uint64_t)info.grid.res[2] && le_at(d, 60, 4) == (uint64_t)info.depth && le_at(d, 64, 4) == info.attributes &&
                     le_at(d, 68, 4) == (uint64_t)info.format && le_at(d, 80 + 8 * (size_t)info.depth, 8) == info.leaf_voxels &&
                     le_at(d, 12, 4) == (info.neighbour_bytes ? 1u : 0u) + (info.brick_bytes ? 2u : 0u) && le_at(d, 224, 8) == *size &&
                     1 + 8 * le_at(d, 72, 8) == info.nodes,
                 "%s: the header is not as documented", what);
    }
    TH_CHECK(voxgi_svo_read_memory(ctx, d, *size, &back) == VOXGI_OK, "%s: read: %s", what, voxgi_last_error(ctx));
    if (back) {
        voxgi_svo_info bi;
        voxgi_svo_query(back, &bi);
        TH_CHECK(bi.backend == VOXGI_BACKEND_CPU, "%s: read on a CPU context, the octree is on backend %d", what, (int)bi.backend);
        TH_CHECK(svo_same(ctx, svo, back, what, queries), "%s: the read octree answers otherwise", what);
        again = svo_bytes(ctx, back, &size2);
        TH_CHECK(again && size2 == *size && !memcmp(again, d, *size), "%s: the read octree writes other bytes", what);
        free(again);
    }
    free(d);
    return back;
}

/* Octree files round-trip: the material sphere's octree (albedo, normal, emission, opacity on
   27 x 25 x 30) in float32 and float16, plain and with neighbours and bricks, and radiance octrees
   (the lit Cornell box one-sided with bricks and neighbours, two-sided in float16; the leak room
   two-sided in a dark shell, whose octree holds region labels): the read octree's info, lookups
   of every voxel at every level, node slots, neighbours, bricks and samples equal the written
   one's bit for bit, its cones too, and it writes the same bytes again; the file functions on a
   path give the same; a too small buffer is refused. */
static void test_svo_file_round_trip(void)
{
    enum { N = 200, M = LEAK_ROOM_POINTS };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    material_sphere s;
    voxgi_voxelize_desc xd;
    voxgi_voxels *vox = NULL;
    voxgi_svo_desc sd;
    voxgi_svo *svo = NULL, *back = NULL;
    voxgi_cone single[N];
    float pos[3 * N], nrm[3 * N], rpos[3 * M], rnrm[3 * M];
    long queries = 0;
    size_t size = 0;
    int k;
    char dir[512], path[600], what[80];
    const char *base = getenv("TMPDIR");
    material_sphere_make(&s);
    memset(&xd, 0, sizeof xd);
    xd.grid.origin[0] = -1.1; xd.grid.origin[1] = -1.2; xd.grid.origin[2] = -1.05;
    xd.grid.voxel_size = 0.09;
    xd.grid.res[0] = 27; xd.grid.res[1] = 25; xd.grid.res[2] = 30;
    xd.attributes = 15;
    TH_CHECK(voxgi_voxelize(ctx, &s.scene, &xd, &vox) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (k = 0; k < 4 && vox; k++) {
        memset(&sd, 0, sizeof sd);
        sd.format = k & 1 ? VOXGI_SVO_FLOAT16 : VOXGI_SVO_FLOAT32;
        sd.neighbours = sd.bricks = k >> 1;
        snprintf(what, sizeof what, "sphere %s%s", k & 1 ? "float16" : "float32", k >> 1 ? " with neighbours and bricks" : "");
        TH_CHECK(voxgi_svo_create(ctx, vox, &sd, &svo) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        back = svo_round_trip(ctx, svo, what, &queries, &size);
        printf("    %s: %lu bytes\n", what, (unsigned long)size);
        voxgi_svo_destroy(ctx, back);
        back = NULL;
        if (k == 3) { /* the path functions, and a buffer one byte short */
            unsigned char *small = (unsigned char *)malloc(size);
            size_t need = 0;
            TH_CHECK(voxgi_svo_write_memory(ctx, svo, small, size - 1, &need) == VOXGI_ERR_BUFFER_TOO_SMALL && need == size, "a short buffer: %lu", (unsigned long)need);
            free(small);
            snprintf(dir, sizeof dir, "%s/voxgi_svo_XXXXXX", base && *base ? base : "/tmp");
            TH_CHECK(mkdtemp(dir) != NULL, "cannot create a temporary directory");
            snprintf(path, sizeof path, "%s/sphere.svo", dir);
            TH_CHECK(voxgi_svo_write(ctx, svo, path) == VOXGI_OK && voxgi_svo_read(ctx, path, &back) == VOXGI_OK, "path: %s", voxgi_last_error(ctx));
            TH_CHECK(back && svo_same(ctx, svo, back, "sphere through a file", &queries), "the octree read from a file answers otherwise");
            voxgi_svo_destroy(ctx, back);
            back = NULL;
            TH_CHECK(voxgi_svo_read(ctx, dir, &back) != VOXGI_OK && !back, "a directory read as an octree");
            remove(path);
            snprintf(path, sizeof path, "%s/missing.svo", dir);
            TH_CHECK(voxgi_svo_read(ctx, path, &back) == VOXGI_ERR_IO && strstr(voxgi_last_error(ctx), "missing.svo"), "a missing file: %s", voxgi_last_error(ctx));
            remove(dir);
        }
        voxgi_svo_destroy(ctx, svo);
        svo = NULL;
    }
    voxgi_voxels_destroy(ctx, vox);
    vox = NULL;
    material_sphere_free(&s);
    { /* radiance octrees: their cones from the read octree equal the written one's */
        voxgi_builtin_scene bs;
        voxgi_inject_desc id;
        voxgi_volume *vol = NULL;
        int sides;
        cornell_cone_points(11, N, pos, nrm, single);
        leak_room_points(rpos, rnrm);
        for (sides = 1; sides <= 3; sides++) { /* 3: the leak room in a dark shell, with regions */
            memset(&id, 0, sizeof id);
            id.samples = 4;
            id.one_sided = sides == 1;
            TH_CHECK(voxgi_builtin_scene_create(ctx, sides < 3 ? "cornell-box" : "leak-room", &bs) == VOXGI_OK, "%s", voxgi_last_error(ctx));
            if (!lit_voxels_padded(ctx, &bs.scene, sides < 3 ? 16 : 32, sides < 3 ? 1 : 4, &id, &vox, &vol)) { TH_CHECK(0, "lighting failed"); break; }
            memset(&sd, 0, sizeof sd);
            sd.radiance = vol;
            sd.bricks = sd.neighbours = sides != 2;
            sd.format = sides == 2 ? VOXGI_SVO_FLOAT16 : VOXGI_SVO_FLOAT32;
            snprintf(what, sizeof what, "%s %s-sided radiance", sides < 3 ? "Cornell box" : "leak room", sides == 1 ? "one" : "two");
            TH_CHECK(voxgi_svo_create(ctx, vox, &sd, &svo) == VOXGI_OK, "%s", voxgi_last_error(ctx));
            back = svo_round_trip(ctx, svo, what, &queries, &size);
            if (size > 224) { /* the regions count, read by the test's own reader at the documented offset */
                unsigned char *d = svo_bytes(ctx, svo, &size);
                printf("    %s: %lu bytes, %llu regions\n", what, (unsigned long)size, d ? (unsigned long long)le_at(d, 216, 8) : 0ull);
                TH_CHECK(d && (sides < 3 || le_at(d, 216, 8) > 2), "%s: no regions in the file", what);
                free(d);
            }
            TH_CHECK(back && (sides < 3 ? svo_same_cones(ctx, svo, back, N, pos, nrm, single) : svo_same_cones(ctx, svo, back, M, rpos, rnrm, NULL)),
                     "%s: the read octree's cones differ", what);
            voxgi_svo_destroy(ctx, back);
            voxgi_svo_destroy(ctx, svo);
            back = svo = NULL;
            voxgi_volume_destroy(ctx, vol);
            voxgi_voxels_destroy(ctx, vox);
            voxgi_builtin_scene_destroy(ctx, &bs);
            vox = NULL;
        }
    }
    printf("    %ld queries equal between written and read octrees\n", queries);
    voxgi_destroy(ctx);
}

/* Loads data (size bytes, copied into a buffer of exactly that size, so that ASan sees any read
   past it): VOXGI_OK with a usable octree, or a refusal with its message; never more. */
static voxgi_result svo_load_exact(voxgi_context *ctx, const unsigned char *data, size_t size, voxgi_svo **out)
{
    unsigned char *copy = (unsigned char *)malloc(size ? size : 1);
    voxgi_result r;
    memcpy(copy, data, size);
    r = voxgi_svo_read_memory(ctx, copy, size, out);
    free(copy);
    return r;
}

/* Whether a refusal is FORMAT and its message names `needle` (a byte offset or the reason). */
static int refused_with(voxgi_context *ctx, voxgi_result r, const voxgi_svo *svo, const char *needle)
{
    if (r == VOXGI_ERR_FORMAT && !svo && strstr(voxgi_last_error(ctx), needle)) return 1;
    printf("    expected a refusal naming \"%s\", got %s: %s\n", needle, voxgi_result_string(r), voxgi_last_error(ctx));
    return 0;
}

/* Hostile octree files: the leak room's two-sided radiance octree at 16^3 (neighbours, bricks,
   region labels; every section of the format) truncated at every 97th byte offset is refused as
   truncated; single bytes flipped at 300 random offsets (and at every header byte) are refused or
   load into an octree whose lookups of every voxel and cones run (ASan: no read outside the
   arrays); and crafted files each give their reason with the byte offset: wrong magic, unknown
   version, a trailing byte, a count that disagrees with the size, a child pointer out of range
   or used twice, a neighbour slot out of range, a region label out of range, huge counts (refused
   before any allocation). A GL context refuses to read (when GL is there). */
static void test_svo_file_refusals(void)
{
    enum { M = LEAK_ROOM_POINTS };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    voxgi_builtin_scene bs;
    voxgi_inject_desc id;
    voxgi_voxels *vox = NULL;
    voxgi_volume *vol = NULL;
    voxgi_svo_desc sd;
    voxgi_svo *svo = NULL, *got = NULL;
    voxgi_svo_info info;
    voxgi_cone_desc cd;
    unsigned char *d = NULL, *bad;
    float rpos[3 * M], rnrm[3 * M], irr[3 * M];
    uint32_t *coords;
    float *vals;
    size_t size = 0, off, nvox, i, truncations = 0, refused = 0, loaded = 0, wrong = 0, values_at;
    uint64_t nodes, leaf_slots, regions, neighbours_at, regions_at;
    int flip;
    memset(&id, 0, sizeof id);
    memset(&sd, 0, sizeof sd);
    memset(&cd, 0, sizeof cd);
    id.samples = 2;
    TH_CHECK(voxgi_builtin_scene_create(ctx, "leak-room", &bs) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    TH_CHECK(lit_voxels_padded(ctx, &bs.scene, 16, 3, &id, &vox, &vol), "lighting failed");
    sd.radiance = vol;
    sd.neighbours = sd.bricks = 1;
    sd.attributes = VOXGI_ATTRIBUTE_RADIANCE | VOXGI_ATTRIBUTE_RADIANCE_BACK | VOXGI_ATTRIBUTE_RADIANCE_SIDE;
    TH_CHECK(vol && voxgi_svo_create(ctx, vox, &sd, &svo) == VOXGI_OK && (d = svo_bytes(ctx, svo, &size)) != NULL, "%s", voxgi_last_error(ctx));
    if (!d) goto done;
    voxgi_svo_query(svo, &info);
    nodes = info.nodes;
    leaf_slots = info.leaf_slots;
    regions = le_at(d, 216, 8);
    neighbours_at = 232 + 4 * nodes;
    regions_at = size - 4 * (nodes + leaf_slots + 6 * regions);
    values_at = (size_t)(neighbours_at + 24 * nodes);
    TH_CHECK(regions > 2 && le_at(d, 224, 8) == size && le_at(d, 232, 4) != 0, "the file's header: %llu regions, %llu bytes claimed of %lu",
             (unsigned long long)regions, (unsigned long long)le_at(d, 224, 8), (unsigned long)size);
    nvox = (size_t)voxgi_grid_voxel_count(&info.grid);
    coords = (uint32_t *)malloc(nvox * 12);
    vals = (float *)malloc(nvox * 16);
    for (i = 0; i < nvox; i++) {
        coords[3 * i] = (uint32_t)(i % (size_t)info.grid.res[0]);
        coords[3 * i + 1] = (uint32_t)(i / (size_t)info.grid.res[0] % (size_t)info.grid.res[1]);
        coords[3 * i + 2] = (uint32_t)(i / ((size_t)info.grid.res[0] * (size_t)info.grid.res[1]));
    }
    leak_room_points(rpos, rnrm);
    for (off = 0; off < size; off += 97, truncations++) {
        voxgi_result r = svo_load_exact(ctx, d, off, &got);
        if (!refused_with(ctx, r, got, "truncated")) { TH_CHECK(0, "a file truncated at byte %lu of %lu", (unsigned long)off, (unsigned long)size); break; }
    }
    bad = (unsigned char *)malloc(size);
    for (flip = 0; flip < 300 + 232; flip++) { /* every header byte, then 300 random ones */
        voxgi_result r;
        off = flip < 232 ? (size_t)flip : (size_t)(rnd() * (double)size);
        memcpy(bad, d, size);
        bad[off] ^= (unsigned char)(flip < 232 ? 0xFF : 1u + (unsigned)(rnd() * 255));
        r = svo_load_exact(ctx, bad, size, &got);
        /* must load: a value; must be refused: a header byte but the grid's doubles and the leaf voxel count */
        if (r == VOXGI_OK ? off < 16 || (off >= 48 && off < 216 && off / 8 != (size_t)(10 + info.depth)) || (off >= 216 && off < 232)
                          : off >= values_at && off < regions_at) {
            wrong++;
            printf("    a flip at byte %lu: %s (%s)\n", (unsigned long)off, voxgi_result_string(r), voxgi_last_error(ctx));
        }
        if (r == VOXGI_OK) { /* values or the grid changed: it must still answer */
            int at;
            loaded++;
            for (at = 4; at < 7; at++)
                TH_CHECK(voxgi_svo_lookup(ctx, got, (voxgi_attribute)(1 << at), info.depth, nvox, coords, vals) == VOXGI_OK, "lookup: %s", voxgi_last_error(ctx));
            voxgi_cone_trace(ctx, OCTREE_SOURCE(got), &cd, M, rpos, rnrm, irr, NULL);
            voxgi_svo_destroy(ctx, got);
            got = NULL;
        } else {
            refused++;
            TH_CHECK(r == VOXGI_ERR_FORMAT && !got && strlen(voxgi_last_error(ctx)) > 10, "a flip at byte %lu: %s", (unsigned long)off, voxgi_result_string(r));
        }
    }
    printf("    %lu bytes (%llu node slots, %llu leaf slots, %llu regions): %lu truncations refused; %d flipped bytes: %lu refused, %lu loaded\n",
           (unsigned long)size, (unsigned long long)nodes, (unsigned long long)leaf_slots, (unsigned long long)regions, (unsigned long)truncations,
           300 + 232, (unsigned long)refused, (unsigned long)loaded);
    TH_CHECK(!wrong && refused > 200 && loaded > 200, "flips: %lu refused, %lu loaded, %lu of them wrongly", (unsigned long)refused, (unsigned long)loaded, (unsigned long)wrong);
    /* crafted files */
    memcpy(bad, d, size); bad[3] = 'x';
    TH_CHECK(refused_with(ctx, svo_load_exact(ctx, bad, size, &got), got, "byte 0:"), "wrong magic");
    memcpy(bad, d, size); le_put(bad, 8, 4, 2);
    TH_CHECK(refused_with(ctx, svo_load_exact(ctx, bad, size, &got), got, "byte 8: octree file version 2"), "version 2");
    {
        unsigned char *longer = (unsigned char *)malloc(size + 1);
        memcpy(longer, d, size); longer[size] = 0;
        TH_CHECK(refused_with(ctx, svo_load_exact(ctx, longer, size + 1, &got), got, "its counts make"), "a trailing byte");
        free(longer);
    }
    memcpy(bad, d, size); le_put(bad, 80 + 8 * (size_t)info.depth, 8, le_at(d, 80 + 8 * (size_t)info.depth, 8) + 1); /* one leaf voxel more: the same size */
    TH_CHECK(voxgi_svo_read_memory(ctx, bad, size, &got) == VOXGI_OK, "the leaf voxel count is no size: %s", voxgi_last_error(ctx));
    voxgi_svo_destroy(ctx, got);
    got = NULL;
    memcpy(bad, d, size); le_put(bad, 80 + 8 * (size_t)(info.depth - 1), 8, le_at(d, 80 + 8 * (size_t)(info.depth - 1), 8) + 1); /* a leaf tile more */
    TH_CHECK(refused_with(ctx, svo_load_exact(ctx, bad, size, &got), got, "byte 224:"), "a leaf tile more than the file holds");
    memcpy(bad, d, size); le_put(bad, 232, 4, 0xFFFFFFFFu); /* the root's child pointer */
    TH_CHECK(refused_with(ctx, svo_load_exact(ctx, bad, size, &got), got, "byte 232: child pointer 4294967295"), "a child pointer out of range");
    memcpy(bad, d, size); /* two level-1 nodes pointing to the same tile: the first with a child and the next */
    {
        size_t first = 232 + 4 * (1 + 8 * (size_t)(le_at(d, 232, 4) - 1));
        for (i = 0; i < 7 && !le_at(d, first + 4 * i, 4); i++) continue;
        le_put(bad, first + 4 * ((i + 1) % 8), 4, le_at(d, first + 4 * i, 4));
    }
    TH_CHECK(refused_with(ctx, svo_load_exact(ctx, bad, size, &got), got, "used twice"), "a tile used twice");
    memcpy(bad, d, size); le_put(bad, (size_t)neighbours_at + 8, 4, nodes);
    TH_CHECK(refused_with(ctx, svo_load_exact(ctx, bad, size, &got), got, "neighbour slot"), "a neighbour slot out of range");
    memcpy(bad, d, size); le_put(bad, (size_t)regions_at + 4, 4, regions);
    TH_CHECK(refused_with(ctx, svo_load_exact(ctx, bad, size, &got), got, "region label"), "a region label out of range");
    memcpy(bad, d, size); le_put(bad, 80 + 8, 8, 8); le_put(bad, 80 + 16, 8, 64); le_put(bad, 80 + 24, 8, 512); /* huge counts, the claimed size to match */
    le_put(bad, 72, 8, 1 + 8 + 64 + (info.depth > 4 ? 512 : 0));
    TH_CHECK(voxgi_svo_read_memory(ctx, bad, size, &got) == VOXGI_ERR_FORMAT && !got, "counts that do not fit the size: %s", voxgi_last_error(ctx));
    memcpy(bad, d, size); le_put(bad, 72, 8, 0xFFFFFFFFFFull);
    TH_CHECK(refused_with(ctx, svo_load_exact(ctx, bad, size, &got), got, "byte 72:"), "inner tiles that disagree with the levels");
    TH_CHECK(refused_with(ctx, voxgi_svo_read_memory(ctx, NULL, 0, &got), got, "truncated at byte 0"), "an empty file");
    if (have_gl()) { /* on GL the same checks refuse before any buffer is made */
        voxgi_context *gl = make_ctx(VOXGI_BACKEND_GL, 0);
        memcpy(bad, d, size); le_put(bad, (size_t)regions_at + 4, 4, regions);
        TH_CHECK(gl && refused_with(gl, voxgi_svo_read_memory(gl, bad, size, &got), got, "region label"), "GL: a region label out of range");
        TH_CHECK(gl && refused_with(gl, voxgi_svo_read_memory(gl, d, size - 1, &got), got, "truncated"), "GL: a truncated file");
        voxgi_destroy(gl);
    }
    free(bad);
    free(coords);
    free(vals);
done:
    free(d);
    voxgi_svo_destroy(ctx, svo);
    voxgi_volume_destroy(ctx, vol);
    voxgi_voxels_destroy(ctx, vox);
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* A GL octree's file (its buffers read back) read on a CPU context answers every query as the GL
   octree does (svo_same: lookups, node slots, neighbours and bricks, bit for bit): the
   material sphere's in float16 with neighbours and bricks, and the lit leak room's two-sided
   radiance with its region labels; the file of the read octree is the GL one's, byte for byte.
   The same file read on GL makes a GL octree that answers every query and traces every cone
   (points' cones and single cones) as the GL octree did, bit for bit, and
   writes the same bytes; a CPU octree's file read on GL writes the CPU one's bytes. */
static void test_gl_svo_file_read_on_cpu(void)
{
    voxgi_context *gl, *cpu;
    material_sphere s;
    voxgi_builtin_scene bs;
    voxgi_inject_desc id;
    voxgi_voxelize_desc xd;
    voxgi_voxels *vox = NULL;
    voxgi_volume *vol = NULL;
    voxgi_svo_desc sd;
    voxgi_svo *svo = NULL, *back = NULL;
    unsigned char *d = NULL, *again = NULL;
    size_t size = 0, size2 = 0;
    long queries = 0;
    int k;
    if (!have_gl()) return;
    gl = make_ctx(VOXGI_BACKEND_GL, 0);
    cpu = make_ctx(VOXGI_BACKEND_CPU, 2);
    material_sphere_make(&s);
    TH_CHECK(voxgi_builtin_scene_create(gl, "leak-room", &bs) == VOXGI_OK, "%s", voxgi_last_error(gl));
    for (k = 0; k < 2; k++) {
        memset(&sd, 0, sizeof sd);
        memset(&xd, 0, sizeof xd);
        memset(&id, 0, sizeof id);
        if (k == 0) {
            xd.grid.origin[0] = -1.1; xd.grid.origin[1] = -1.2; xd.grid.origin[2] = -1.05;
            xd.grid.voxel_size = 0.09;
            xd.grid.res[0] = 27; xd.grid.res[1] = 25; xd.grid.res[2] = 30;
            xd.attributes = 15;
            TH_CHECK(voxgi_voxelize(gl, &s.scene, &xd, &vox) == VOXGI_OK, "%s", voxgi_last_error(gl));
            sd.format = VOXGI_SVO_FLOAT16;
            sd.neighbours = sd.bricks = 1;
        } else {
            id.samples = 2;
            id.shadow_rays = 1;
            TH_CHECK(lit_voxels_padded(gl, &bs.scene, 16, 3, &id, &vox, &vol), "lighting failed");
            sd.radiance = vol;
            sd.bricks = 1;
        }
        TH_CHECK(vox && voxgi_svo_create(gl, vox, &sd, &svo) == VOXGI_OK && (d = svo_bytes(gl, svo, &size)) != NULL, "%s", voxgi_last_error(gl));
        TH_CHECK(d && voxgi_svo_read_memory(cpu, d, size, &back) == VOXGI_OK, "read: %s", voxgi_last_error(cpu));
        TH_CHECK(back && svo_same(gl, svo, back, k ? "GL leak room radiance" : "GL sphere", &queries), "the read octree answers otherwise than the GL one");
        TH_CHECK(back && (again = svo_bytes(cpu, back, &size2)) && size2 == size && !memcmp(again, d, size), "the read octree writes other bytes");
        free(again);
        again = NULL;
        voxgi_svo_destroy(cpu, back);
        back = NULL;
        { /* read on GL */
            voxgi_svo_info bi;
            TH_CHECK(d && voxgi_svo_read_memory(gl, d, size, &back) == VOXGI_OK, "read on GL: %s", voxgi_last_error(gl));
            voxgi_svo_query(back, &bi);
            TH_CHECK(back && bi.backend == VOXGI_BACKEND_GL, "read on GL, the octree is on backend %d", (int)bi.backend);
            TH_CHECK(back && svo_same(gl, svo, back, k ? "GL leak room radiance read on GL" : "GL sphere read on GL", &queries), "the octree read on GL answers otherwise");
            TH_CHECK(back && (again = svo_bytes(gl, back, &size2)) && size2 == size && !memcmp(again, d, size), "the octree read on GL writes other bytes");
            if (back && k == 1) {
                enum { N = 64 };
                float pos[3 * N], nrm[3 * N];
                voxgi_cone single[N];
                int i;
                for (i = 0; i < N; i++) { /* points on the room's floor and walls, normals into the room */
                    int axis = i % 3;
                    float u = (float)((i * 37) % 64) / 64.0f, v = (float)((i * 11) % 64) / 64.0f;
                    pos[3 * i] = axis == 0 ? -0.98f : -0.9f + 1.8f * u; /* the room: x and z -1..1, y 0..2 */
                    pos[3 * i + 1] = axis == 1 ? 0.02f : 0.1f + 1.8f * (axis == 0 ? u : v);
                    pos[3 * i + 2] = axis == 2 ? -0.98f : -0.9f + 1.8f * v;
                    nrm[3 * i] = axis == 0; nrm[3 * i + 1] = axis == 1; nrm[3 * i + 2] = axis == 2;
                    memset(&single[i], 0, sizeof single[i]);
                    memcpy(single[i].origin, pos + 3 * i, sizeof single[i].origin);
                    memcpy(single[i].direction, nrm + 3 * i, sizeof single[i].direction);
                    single[i].half_angle = 0.3f;
                }
                TH_CHECK(svo_same_cones(gl, svo, back, N, pos, nrm, single), "the octree read on GL traces other cones");
            }
            free(again);
            again = NULL;
            voxgi_svo_destroy(gl, back);
            back = NULL;
        }
        printf("    %s: %lu bytes%s\n", k ? "GL leak room radiance" : "GL sphere", (unsigned long)size, k && d ? (le_at(d, 216, 8) > 2 ? ", with regions" : ", no regions") : "");
        free(d); free(again);
        d = again = NULL;
        voxgi_svo_destroy(cpu, back);
        voxgi_svo_destroy(gl, svo);
        back = svo = NULL;
        voxgi_volume_destroy(gl, vol);
        voxgi_voxels_destroy(gl, vox);
        vol = NULL; vox = NULL;
    }
    printf("    %ld queries equal\n", queries);
    voxgi_builtin_scene_destroy(gl, &bs);
    material_sphere_free(&s);
    voxgi_destroy(cpu);
    voxgi_destroy(gl);
}

int main(void)
{
    gl_open();
    TH_RUN(test_svo_equals_dense);
    TH_RUN(test_octree_cones);
    TH_RUN(test_svo_file_round_trip);
    TH_RUN(test_svo_file_refusals);
    TH_RUN(test_gl_octree_cones_equal_cpu);
    TH_RUN(test_gl_svo_file_read_on_cpu);
    gl_close();
    return th_finish();
}
