/* tests/test_octree.c - part 7: the sparse voxel octree, CPU and GL. Lookups equal the dense
   isotropic volume at every level bit for bit, in both value formats, with neighbour pointers and
   bricks; cone tracing over an octree of the radiance (part 8's march over the octree's mips)
   equals the volume's, and the GL octree's cones equal the CPU's. (Half-float rounding and the
   GPU-built octree against the CPU's, which call private helpers: tests/test_internals.c.) The GL
   tests skip (loudly) only when no GL 4.5 context can be made; VOXGI_TEST_GL=egl|osmesa picks the
   kind, VOXGI_REQUIRE_GL=1 turns a skip into a failure. */
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

int main(void)
{
    gl_open();
    TH_RUN(test_svo_equals_dense);
    TH_RUN(test_octree_cones);
    TH_RUN(test_gl_octree_cones_equal_cpu);
    gl_close();
    return th_finish();
}
