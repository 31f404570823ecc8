/* CPU conservative voxelization against an independent brute-force evaluation of the definition,
   plus scene validation, grids, binvox and the result API. */
#include "../voxgi.h"
#include "fixtures.h"
#include "svo_checks.h"
#include <stdlib.h>

/* ---------------------------------------------------------------- the oracle
   Inputs are dyadic (every float is), and the tests keep them on a 2^-ORACLE_BITS lattice with
   small magnitudes, so every coordinate times 2^ORACLE_BITS is an integer and the separating
   axis theorem (13 axes, closed sets: touching counts) is evaluated exactly in 128-bit integers.
   Nothing here shares code with the library. */
#define ORACLE_BITS 20
__extension__ typedef __int128 i128;

static int64_t to_fixed(double x)
{
    double y = ldexp(x, ORACLE_BITS);
    if (y != floor(y) || fabs(y) > 9e15) { fprintf(stderr, "oracle input %.17g is off the lattice\n", x); abort(); }
    return (int64_t)y;
}

static void interval3(i128 a, i128 b, i128 c, i128 *lo, i128 *hi)
{
    *lo = a < b ? a : b; if (c < *lo) *lo = c;
    *hi = a > b ? a : b; if (c > *hi) *hi = c;
}

/* does the closed box [bmin, bmax] meet the closed triangle v? (all fixed point) */
static int oracle_overlap(const int64_t v[3][3], const int64_t bmin[3], const int64_t bmax[3])
{
    i128 e[3][3], ax[3], lo, hi, blo, bhi;
    int a, i, j, c;
    for (a = 0; a < 3; a++) {
        interval3(v[0][a], v[1][a], v[2][a], &lo, &hi);
        if (hi < bmin[a] || lo > bmax[a]) return 0;
    }
    for (i = 0; i < 3; i++)
        for (a = 0; a < 3; a++) e[i][a] = (i128)v[(i + 1) % 3][a] - v[i][a];
    /* 13 axes: the normal, then edge x unit axis */
    for (j = -1; j < 9; j++) {
        if (j < 0) {
            ax[0] = e[0][1] * -e[2][2] - e[0][2] * -e[2][1];
            ax[1] = e[0][2] * -e[2][0] - e[0][0] * -e[2][2];
            ax[2] = e[0][0] * -e[2][1] - e[0][1] * -e[2][0];
        } else {
            const i128 *d = e[j / 3];
            int u = j % 3; /* d x unit_u */
            ax[u] = 0;
            ax[(u + 1) % 3] = d[(u + 2) % 3];
            ax[(u + 2) % 3] = -d[(u + 1) % 3];
        }
        if (ax[0] == 0 && ax[1] == 0 && ax[2] == 0) continue;
        interval3(ax[0] * v[0][0] + ax[1] * v[0][1] + ax[2] * v[0][2], ax[0] * v[1][0] + ax[1] * v[1][1] + ax[2] * v[1][2],
                  ax[0] * v[2][0] + ax[1] * v[2][1] + ax[2] * v[2][2], &lo, &hi);
        blo = bhi = 0;
        for (c = 0; c < 8; c++) {
            i128 p = 0;
            for (a = 0; a < 3; a++) p += ax[a] * ((c >> a) & 1 ? bmax[a] : bmin[a]);
            if (c == 0 || p < blo) blo = p;
            if (c == 0 || p > bhi) bhi = p;
        }
        if (hi < blo || lo > bhi) return 0;
    }
    return 1;
}

/* The thin (6-separating) test of Schwarz & Seidel on the same lattice, doubled so the voxel
   centre is an integer: the conservative tests with the box replaced by its inscribed
   octahedron (plane: |n.(c - v0)| <= max|n_i| h) and diamonds (projections). */
static i128 abs128(i128 x) { return x < 0 ? -x : x; }
static i128 max3_128(i128 a, i128 b, i128 c) { i128 m = a > b ? a : b; return m > c ? m : c; }
static int oracle_thin(const int64_t v[3][3], const int64_t bmin[3], const int64_t bmax[3])
{
    i128 e[3][3], n[3], c2[3], w[3][3], h;
    int a, k, p;
    if (!oracle_overlap(v, bmin, bmax)) return 0;
    for (a = 0; a < 3; a++) {
        c2[a] = (i128)bmin[a] + bmax[a]; /* twice the centre */
        for (k = 0; k < 3; k++) w[k][a] = 2 * (i128)v[k][a];
    }
    h = (i128)bmax[0] - bmin[0]; /* the voxel size: twice the half size, as everything is doubled */
    for (k = 0; k < 3; k++)
        for (a = 0; a < 3; a++) e[k][a] = w[(k + 1) % 3][a] - w[k][a];
    n[0] = e[0][1] * -e[2][2] - e[0][2] * -e[2][1];
    n[1] = e[0][2] * -e[2][0] - e[0][0] * -e[2][2];
    n[2] = e[0][0] * -e[2][1] - e[0][1] * -e[2][0];
    if (n[0] || n[1] || n[2]) {
        i128 f = n[0] * (c2[0] - w[0][0]) + n[1] * (c2[1] - w[0][1]) + n[2] * (c2[2] - w[0][2]);
        if (abs128(f) > max3_128(abs128(n[0]), abs128(n[1]), abs128(n[2])) * h) return 0;
    }
    for (p = 0; p < 3; p++) {
        int x = (p + 1) % 3, y = (p + 2) % 3, best = -1;
        i128 sig = n[p] > 0 ? 1 : (n[p] < 0 ? -1 : 0), len = 0;
        for (k = 0; k < 3; k++) {
            i128 mx = -e[k][y], my = e[k][x];
            i128 g = mx * (c2[x] - w[k][x]) + my * (c2[y] - w[k][y]), r = (abs128(mx) > abs128(my) ? abs128(mx) : abs128(my)) * h;
            if (sig != 0 && sig * g + r < 0) return 0; /* oriented edge against the diamond */
            if (abs128(mx) + abs128(my) > len) { len = abs128(mx) + abs128(my); best = k; }
        }
        if (sig == 0 && best >= 0) { /* a segment-shaped projection: its line through the diamond */
            i128 mx = -e[best][y], my = e[best][x];
            i128 g = mx * (c2[x] - w[best][x]) + my * (c2[y] - w[best][y]), r = (abs128(mx) > abs128(my) ? abs128(mx) : abs128(my)) * h;
            if (abs128(g) > r) return 0;
        }
    }
    return 1;
}

/* Brute force over every voxel of the grid. */
static uint32_t *oracle_voxelize_method(const float *pos, const uint32_t *idx, size_t ntri, const voxgi_grid *g, int thin)
{
    uint64_t nvox = voxgi_grid_voxel_count(g);
    uint32_t *bits = (uint32_t *)calloc((size_t)(nvox + 31) / 32, 4);
    int64_t o[3], s = to_fixed(g->voxel_size);
    size_t t;
    int a;
    for (a = 0; a < 3; a++) o[a] = to_fixed(g->origin[a]);
    for (t = 0; t < ntri; t++) {
        int64_t v[3][3];
        int i, j, k, c;
        for (c = 0; c < 3; c++)
            for (a = 0; a < 3; a++) v[c][a] = to_fixed(pos[3 * idx[3 * t + (size_t)c] + (size_t)a]);
        for (k = 0; k < g->res[2]; k++)
            for (j = 0; j < g->res[1]; j++)
                for (i = 0; i < g->res[0]; i++) {
                    int64_t bmin[3], bmax[3];
                    int ijk[3];
                    uint64_t l = (uint64_t)i + (uint64_t)g->res[0] * ((uint64_t)j + (uint64_t)g->res[1] * (uint64_t)k);
                    if (bits[l >> 5] & (1u << (l & 31))) continue;
                    ijk[0] = i; ijk[1] = j; ijk[2] = k;
                    for (a = 0; a < 3; a++) { bmin[a] = o[a] + ijk[a] * s; bmax[a] = bmin[a] + s; }
                    if (thin ? oracle_thin((const int64_t(*)[3])v, bmin, bmax) : oracle_overlap((const int64_t(*)[3])v, bmin, bmax))
                        bits[l >> 5] |= 1u << (l & 31);
                }
    }
    return bits;
}

static uint32_t *oracle_voxelize(const float *pos, const uint32_t *idx, size_t ntri, const voxgi_grid *g)
{
    return oracle_voxelize_method(pos, idx, ntri, g, 0);
}

/* Sets voxel v of the oracle's bits on grid g. */
static void oracle_set(uint32_t *bits, const voxgi_grid *g, const int v[3])
{
    uint64_t l = (uint64_t)v[0] + (uint64_t)g->res[0] * ((uint64_t)v[1] + (uint64_t)g->res[1] * (uint64_t)v[2]);
    bits[l >> 5] |= 1u << (l & 31);
}

/* ---------------------------------------------------------------- helpers */
static uint32_t *voxelize_bits_method(voxgi_context *ctx, const float *pos, size_t nv, const uint32_t *idx, size_t ntri,
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

static uint32_t *voxelize_bits(voxgi_context *ctx, const float *pos, size_t nv, const uint32_t *idx, size_t ntri,
                               const voxgi_grid *g, voxgi_voxels_info *info)
{
    return voxelize_bits_method(ctx, pos, nv, idx, ntri, g, VOXGI_METHOD_CONSERVATIVE, info);
}

/* Compares with the oracle; returns the number of differing voxels (and reports a few). */
static uint64_t compare_bits(const uint32_t *a, const uint32_t *b, const voxgi_grid *g, const char *what)
{
    uint64_t n = voxgi_grid_voxel_count(g), l, diff = 0;
    for (l = 0; l < n; l++) {
        int x = voxgi_bit_get(a, l), y = voxgi_bit_get(b, l);
        if (x != y && ++diff <= 3)
            printf("    %s: voxel (%d,%d,%d) library %d, reference %d\n", what, (int)(l % (uint64_t)g->res[0]),
                   (int)(l / (uint64_t)g->res[0] % (uint64_t)g->res[1]), (int)(l / ((uint64_t)g->res[0] * (uint64_t)g->res[1])), x, y);
    }
    return diff;
}

static double lattice(double x) { return ldexp(floor(ldexp(x, ORACLE_BITS) + 0.5), -ORACLE_BITS); }

static int g_thin; /* check_against_oracle checks the thin method too when set */
static uint64_t check_against_oracle(voxgi_context *ctx, const float *pos, size_t nv, const uint32_t *idx, size_t nt,
                                     const voxgi_grid *g, const char *what)
{
    uint32_t *mine = voxelize_bits_method(ctx, pos, nv, idx, nt, g, g_thin ? VOXGI_METHOD_THIN : VOXGI_METHOD_CONSERVATIVE, NULL);
    uint32_t *ref = oracle_voxelize_method(pos, idx, nt, g, g_thin);
    uint64_t d = mine ? compare_bits(mine, ref, g, what) : (uint64_t)-1;
    free(mine);
    free(ref);
    return d;
}

/* ---------------------------------------------------------------- tests */
static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static double rnd(void) /* [0,1) */
{
    rng_state ^= rng_state << 13; rng_state ^= rng_state >> 7; rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) * (1.0 / 9007199254740992.0);
}

/* Random triangles of every size, one at a time, on a grid with an awkward origin and size. */
static void test_random_triangles_vs_oracle(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 1);
    voxgi_grid g;
    int trial;
    uint64_t bad = 0;
    g.origin[0] = lattice(-3.3); g.origin[1] = lattice(1.7); g.origin[2] = lattice(-0.45);
    g.voxel_size = lattice(0.73);
    g.res[0] = 13; g.res[1] = 9; g.res[2] = 11;
    for (trial = 0; trial < 400 && bad == 0; trial++) {
        float p[9];
        uint32_t idx[3] = {0, 1, 2};
        double size = trial % 4 == 0 ? 12.0 : (trial % 4 == 1 ? 2.0 : (trial % 4 == 2 ? 0.3 : 30.0));
        double cx = -4 + 12 * rnd(), cy = 1 + 8 * rnd(), cz = -1 + 9 * rnd();
        int c;
        for (c = 0; c < 3; c++) {
            p[3 * c + 0] = (float)lattice(cx + size * (rnd() - 0.5));
            p[3 * c + 1] = (float)lattice(cy + size * (rnd() - 0.5));
            p[3 * c + 2] = (float)lattice(cz + size * (rnd() - 0.5));
        }
        if (trial % 7 == 3) { /* needle: third vertex almost on the first edge */
            for (c = 0; c < 3; c++) p[6 + c] = (float)lattice(0.5 * (p[c] + p[3 + c]) + 1e-5 * (rnd() - 0.5));
        }
        bad += check_against_oracle(ctx, p, 3, idx, 1, &g, "random triangle");
    }
    TH_CHECK(bad == 0, "%llu voxels differ from the definition (trial %d)", (unsigned long long)bad, trial);
    voxgi_destroy(ctx);
}

/* Triangles whose vertices sit on voxel corners, faces and edges; in grid planes; axis-aligned;
   zero-area (segments, points); the whole grid; partly outside. */
static void test_adversarial_vs_oracle(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    voxgi_grid g;
    int trial;
    uint64_t bad = 0;
    g.origin[0] = -2; g.origin[1] = 0.5; g.origin[2] = 1;
    g.voxel_size = 0.5;
    g.res[0] = 12; g.res[1] = 10; g.res[2] = 9;
    for (trial = 0; trial < 600 && bad == 0; trial++) {
        float p[9];
        uint32_t idx[3] = {0, 1, 2};
        int c, a, kind = trial % 10;
        for (c = 0; c < 3; c++)
            for (a = 0; a < 3; a++) {
                /* voxel corners, face centres, quarter points: all exact ties */
                double q = floor(rnd() * 14 * 4) / 4.0 - 1.0;
                if (kind >= 6) q = floor(q); /* only corners */
                p[3 * c + a] = (float)(g.origin[a] + q * g.voxel_size);
            }
        if (kind == 1) p[2] = p[5] = p[8];            /* in a grid-parallel plane */
        if (kind == 2) { p[1] = p[4] = p[7]; p[0] = p[3]; } /* axis-aligned right triangle in a y plane */
        if (kind == 3) for (a = 0; a < 3; a++) p[6 + a] = p[a];            /* segment (two equal vertices) */
        if (kind == 4) for (a = 0; a < 3; a++) p[6 + a] = 0.5f * (p[a] + p[3 + a]); /* collinear */
        if (kind == 5) for (a = 0; a < 3; a++) p[3 + a] = p[6 + a] = p[a]; /* a point */
        if (kind == 7) { p[0] = p[3]; p[1] = p[4]; } /* edge parallel to z */
        bad += check_against_oracle(ctx, p, 3, idx, 1, &g, "adversarial triangle");
    }
    TH_CHECK(bad == 0, "%llu voxels differ from the definition (trial %d)", (unsigned long long)bad, trial);
    {   /* one triangle far larger than the grid, and one spanning it exactly corner to corner */
        float big[9] = {-1000, -1000, 2.25f, 3000, -1000, 3.125f, -1000, 3000, 3.875f};
        float span[9] = {-2, 0.5f, 1, 4, 5.5f, 5.5f, -2, 5.5f, 5.5f};
        uint32_t idx[3] = {0, 1, 2};
        TH_CHECK(check_against_oracle(ctx, big, 3, idx, 1, &g, "huge triangle") == 0, "huge triangle differs");
        TH_CHECK(check_against_oracle(ctx, span, 3, idx, 1, &g, "spanning triangle") == 0, "spanning triangle differs");
    }
    voxgi_destroy(ctx);
}

/* Triangles of more than 4096 columns go through the row-block phase of the worker pool. */
static void test_big_triangles_vs_oracle(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    voxgi_grid g;
    int trial;
    uint64_t bad = 0;
    g.origin[0] = lattice(-1.3); g.origin[1] = lattice(-0.7); g.origin[2] = lattice(-0.2);
    g.voxel_size = lattice(0.1);
    g.res[0] = 76; g.res[1] = 70; g.res[2] = 10;
    for (trial = 0; trial < 6 && bad == 0; trial++) {
        float p[9];
        uint32_t idx[3] = {0, 1, 2};
        int c;
        for (c = 0; c < 3; c++) {
            p[3 * c + 0] = (float)lattice(-2 + 10 * rnd());
            p[3 * c + 1] = (float)lattice(-1.5 + 9 * rnd());
            p[3 * c + 2] = (float)lattice(trial < 3 ? 0.3 + 0.2 * rnd() : 0.5); /* tilted, then flat on a grid plane */
        }
        bad += check_against_oracle(ctx, p, 3, idx, 1, &g, "big triangle");
    }
    TH_CHECK(bad == 0, "%llu voxels differ from the definition (trial %d)", (unsigned long long)bad, trial);
    voxgi_destroy(ctx);
}

/* A closed procedural mesh on a non-cubic grid, all triangles at once, against the oracle. */
static void test_mesh_vs_oracle(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    vxt_shape m;
    voxgi_grid g;
    size_t i;
    vxt_shape_sphere(&m, 12, 9, 2.0, 0.3, -0.2, 0.1);
    for (i = 0; i < 3 * m.vertex_count; i++) m.pos[i] = (float)lattice(m.pos[i]);
    g.origin[0] = lattice(-2.21); g.origin[1] = lattice(-2.52); g.origin[2] = lattice(-2.07);
    g.voxel_size = lattice(0.31);
    g.res[0] = 15; g.res[1] = 17; g.res[2] = 14;
    TH_CHECK(check_against_oracle(ctx, m.pos, m.vertex_count, m.idx, m.triangle_count, &g, "sphere") == 0,
             "sphere differs from the definition");
    vxt_shape_free(&m);
    voxgi_destroy(ctx);
}

/* The same scene moved by 1e7, scaled by 2^-20 and by 2^20 (exactly representable moves, so the
   geometry is the same) gives the same voxels: nothing depends on where the scene sits. */
static void test_offset_and_scale_invariance(void)
{
    static const voxgi_method methods[] = {VOXGI_METHOD_CONSERVATIVE, VOXGI_METHOD_THIN, VOXGI_METHOD_SOLID, VOXGI_METHOD_SLICEMAP,
                                           VOXGI_METHOD_ATLAS, VOXGI_METHOD_VOLUME_BUFFER};
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    vxt_shape m;
    voxgi_grid g0, g;
    uint32_t *ref, *bits;
    size_t i;
    int variant, k;
    float *moved;
    vxt_shape_box_and_tilted(&m); /* integer coordinates in [0, 24] */
    g0.origin[0] = -1; g0.origin[1] = -1; g0.origin[2] = -1;
    g0.voxel_size = 1.5;
    g0.res[0] = 19; g0.res[1] = 18; g0.res[2] = 17;
    moved = (float *)malloc(3 * m.vertex_count * sizeof(float));
    for (k = 0; k < (int)(sizeof methods / sizeof methods[0]); k++) { /* exact moves change no method's voxels */
        ref = voxelize_bits_method(ctx, m.pos, m.vertex_count, m.idx, m.triangle_count, &g0, methods[k], NULL);
        for (variant = 0; variant < 3; variant++) {
            double scale = variant == 0 ? 1.0 : (variant == 1 ? ldexp(1, -20) : ldexp(1, 20));
            double offset = variant == 0 ? 1e7 : 0.0;
            for (i = 0; i < 3 * m.vertex_count; i++) moved[i] = (float)(m.pos[i] * scale + offset);
            g = g0;
            for (i = 0; i < 3; i++) g.origin[i] = g0.origin[i] * scale + offset;
            g.voxel_size = g0.voxel_size * scale;
            bits = voxelize_bits_method(ctx, moved, m.vertex_count, m.idx, m.triangle_count, &g, methods[k], NULL);
            TH_CHECK(ref && bits && compare_bits(bits, ref, &g, "moved scene") == 0, "%s: variant %d (scale %g, offset %g) differs",
                     voxgi_method_name(methods[k]), variant, scale, offset);
            free(bits);
        }
        if (k == 0) { /* and the original against the oracle */
            uint32_t *o = oracle_voxelize(m.pos, m.idx, m.triangle_count, &g0);
            TH_CHECK(compare_bits(ref, o, &g0, "box scene") == 0, "box scene differs from the definition");
            free(o);
        }
        free(ref);
    }
    free(moved);
    vxt_shape_free(&m);
    voxgi_destroy(ctx);
}

/* Literal scale factors 1e-6 and 1e6 round the float vertices, so identical voxels are only
   guaranteed away from ties; a generic sphere on a generic grid has none, and must not change. */
static void test_literal_scales(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    vxt_shape m;
    voxgi_grid g0, g;
    uint32_t *ref, *bits;
    size_t i;
    int variant;
    float *moved;
    vxt_shape_sphere(&m, 37, 23, 1.0, 0.0123, -0.0456, 0.0789);
    g0.origin[0] = -1.1; g0.origin[1] = -1.2; g0.origin[2] = -1.05;
    g0.voxel_size = 0.07;
    g0.res[0] = 33; g0.res[1] = 35; g0.res[2] = 31;
    ref = voxelize_bits(ctx, m.pos, m.vertex_count, m.idx, m.triangle_count, &g0, NULL);
    moved = (float *)malloc(3 * m.vertex_count * sizeof(float));
    for (variant = 0; variant < 2; variant++) {
        double scale = variant ? 1e6 : 1e-6;
        for (i = 0; i < 3 * m.vertex_count; i++) moved[i] = (float)(m.pos[i] * scale);
        g = g0;
        for (i = 0; i < 3; i++) g.origin[i] = g0.origin[i] * scale;
        g.voxel_size = g0.voxel_size * scale;
        bits = voxelize_bits(ctx, moved, m.vertex_count, m.idx, m.triangle_count, &g, NULL);
        TH_CHECK(bits && compare_bits(bits, ref, &g, "scaled sphere") == 0, "scale %g changes the voxels", scale);
        free(bits);
    }
    free(moved);
    free(ref);
    vxt_shape_free(&m);
    voxgi_destroy(ctx);
}

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

/* binvox write then read gives the same grid and bits; a truncated file is an error. */
static void test_binvox_roundtrip(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 1);
    vxt_shape m;
    voxgi_grid g, g2;
    uint32_t *bits, *back;
    size_t need = 0, bytes;
    FILE *f = tmpfile();
    long len;
    vxt_shape_sphere(&m, 20, 14, 1.0, 0, 0, 0);
    memset(&g2, 0, sizeof g2);
    g.origin[0] = -1.25; g.origin[1] = -1.5; g.origin[2] = -1.125;
    g.voxel_size = 0.125;
    g.res[0] = 21; g.res[1] = 24; g.res[2] = 19; /* non-cubic: checks the axis order */
    bits = voxelize_bits(ctx, m.pos, m.vertex_count, m.idx, m.triangle_count, &g, NULL);
    bytes = (voxgi_grid_voxel_count(&g) + 31) / 32 * 4;
    TH_CHECK(voxgi_binvox_write(f, &g, bits) == VOXGI_OK, "write failed");
    len = ftell(f);
    rewind(f);
    TH_CHECK(voxgi_binvox_read(f, &g2, NULL, 0, &need) == VOXGI_OK && need == bytes, "header read failed");
    rewind(f);
    back = (uint32_t *)malloc(need);
    TH_CHECK(voxgi_binvox_read(f, &g2, back, need, NULL) == VOXGI_OK, "read failed");
    /* field by field: the struct's padding is not part of the grid (and no read writes it) */
    TH_CHECK(g2.origin[0] == g.origin[0] && g2.origin[1] == g.origin[1] && g2.origin[2] == g.origin[2] &&
             g2.voxel_size == g.voxel_size && g2.res[0] == g.res[0] && g2.res[1] == g.res[1] && g2.res[2] == g.res[2],
             "grid differs after the round trip: origin %g %g %g, size %g, res %d %d %d",
             g2.origin[0], g2.origin[1], g2.origin[2], g2.voxel_size, g2.res[0], g2.res[1], g2.res[2]);
    TH_CHECK(memcmp(bits, back, bytes) == 0, "bits differ after the round trip");
    {   /* truncated: every shorter prefix must fail cleanly */
        char *buf = (char *)malloc((size_t)len);
        long cut;
        int bad = 0;
        rewind(f);
        if (fread(buf, 1, (size_t)len, f) != (size_t)len) bad++;
        for (cut = 0; cut < len; cut += 1 + cut / 8) {
            FILE *t = tmpfile();
            voxgi_grid gt;
            fwrite(buf, 1, (size_t)cut, t);
            rewind(t);
            if (voxgi_binvox_read(t, &gt, back, need, NULL) == VOXGI_OK) bad++;
            fclose(t);
        }
        TH_CHECK(bad == 0, "%d truncated files accepted", bad);
        free(buf);
    }
    fclose(f);
    free(bits);
    free(back);
    vxt_shape_free(&m);
    voxgi_destroy(ctx);
}

/* The thin method on every oracle scene above, and thin within conservative. */
static void test_thin_vs_oracle(void)
{
    int before = th_.cur_failed;
    g_thin = 1;
    test_random_triangles_vs_oracle();
    test_adversarial_vs_oracle();
    test_big_triangles_vs_oracle();
    test_mesh_vs_oracle();
    g_thin = 0;
    TH_CHECK(th_.cur_failed == before, "thin differs from its definition");
    {
        voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
        vxt_shape m;
        voxgi_grid g;
        uint32_t *cons, *thin;
        uint64_t l, n, nc = 0, nt = 0, outside = 0;
        vxt_shape_sphere(&m, 60, 40, 1.0, 0.01, 0.02, 0.03);
        g.origin[0] = g.origin[1] = g.origin[2] = -1.1;
        g.voxel_size = 2.2 / 64;
        g.res[0] = g.res[1] = g.res[2] = 64;
        n = voxgi_grid_voxel_count(&g);
        cons = voxelize_bits_method(ctx, m.pos, m.vertex_count, m.idx, m.triangle_count, &g, VOXGI_METHOD_CONSERVATIVE, NULL);
        thin = voxelize_bits_method(ctx, m.pos, m.vertex_count, m.idx, m.triangle_count, &g, VOXGI_METHOD_THIN, NULL);
        for (l = 0; l < n; l++) {
            nc += (uint64_t)voxgi_bit_get(cons, l);
            nt += (uint64_t)voxgi_bit_get(thin, l);
            outside += (uint64_t)(voxgi_bit_get(thin, l) && !voxgi_bit_get(cons, l));
        }
        TH_CHECK(outside == 0, "%llu thin voxels outside the conservative set", (unsigned long long)outside);
        TH_CHECK(nt > 0 && nt < nc, "thin %llu vs conservative %llu voxels", (unsigned long long)nt, (unsigned long long)nc);
        printf("    sphere 64^3: conservative %llu, thin %llu voxels\n", (unsigned long long)nc, (unsigned long long)nt);
        free(cons);
        free(thin);
        vxt_shape_free(&m);
        voxgi_destroy(ctx);
    }
}

/* ---------------------------------------------------------------- solid */
/* Generalized winding number of a closed mesh at p (solid angles, Van Oosterom & Strackee). */
static double winding_number(const vxt_shape *m, const double p[3])
{
    double w = 0;
    size_t t;
    for (t = 0; t < m->triangle_count; t++) {
        double a[3], b[3], c[3], la, lb, lc, det, den;
        int k;
        for (k = 0; k < 3; k++) {
            a[k] = m->pos[3 * m->idx[3 * t] + (size_t)k] - p[k];
            b[k] = m->pos[3 * m->idx[3 * t + 1] + (size_t)k] - p[k];
            c[k] = m->pos[3 * m->idx[3 * t + 2] + (size_t)k] - p[k];
        }
        la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
        lc = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
        den = la * lb * lc + (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) * lc + (a[0] * c[0] + a[1] * c[1] + a[2] * c[2]) * lb +
              (b[0] * c[0] + b[1] * c[1] + b[2] * c[2]) * la;
        w += 2 * atan2(det, den);
    }
    return w / (4 * 3.14159265358979323846);
}

static uint32_t *solid_bits(voxgi_context *ctx, const vxt_shape *m, const voxgi_grid *g, voxgi_solid_mode mode, voxgi_axis axis)
{
    voxgi_voxelize_desc vd;
    memset(&vd, 0, sizeof vd);
    vd.grid = *g;
    vd.method = VOXGI_METHOD_SOLID;
    vd.solid_mode = mode;
    vd.axis = axis;
    return shape_bits(ctx, m, NULL, &vd, NULL);
}

/* Parity along each axis and the vote equal the inside test (winding number) at every voxel
   centre of a closed sphere and of a shell of two nested spheres (every 7th centre in the reduced builds). */
static void test_solid_closed_vs_inside_test(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    vxt_shape outer, inner, shell;
    voxgi_grid g;
    int scene;
    vxt_shape_sphere(&outer, 40, 26, 1.0, 0.013, -0.021, 0.007);
    vxt_shape_sphere(&inner, 24, 16, 0.55, 0.1, 0.05, -0.08);
    vxt_shape_alloc(&shell, outer.vertex_count + inner.vertex_count, outer.triangle_count + inner.triangle_count);
    memcpy(shell.pos, outer.pos, outer.vertex_count * 12);
    memcpy(shell.pos + 3 * outer.vertex_count, inner.pos, inner.vertex_count * 12);
    memcpy(shell.idx, outer.idx, outer.triangle_count * 12);
    {
        size_t i;
        for (i = 0; i < 3 * inner.triangle_count; i++) shell.idx[3 * outer.triangle_count + i] = inner.idx[i] + (uint32_t)outer.vertex_count;
    }
    g.origin[0] = -1.13; g.origin[1] = -1.07; g.origin[2] = -1.2;
    g.voxel_size = 0.071;
    g.res[0] = 33; g.res[1] = 31; g.res[2] = 35;
    for (scene = 0; scene < 2; scene++) {
        const vxt_shape *m = scene ? &shell : &outer;
        uint32_t *b[4];
        int v;
        uint64_t l, n = voxgi_grid_voxel_count(&g), bad[4] = {0, 0, 0, 0}, set = 0;
        b[0] = solid_bits(ctx, m, &g, VOXGI_SOLID_PARITY, VOXGI_AXIS_DEFAULT);
        b[1] = solid_bits(ctx, m, &g, VOXGI_SOLID_PARITY, VOXGI_AXIS_X);
        b[2] = solid_bits(ctx, m, &g, VOXGI_SOLID_PARITY, VOXGI_AXIS_Y);
        b[3] = solid_bits(ctx, m, &g, VOXGI_SOLID_VOTE, VOXGI_AXIS_DEFAULT);
        for (l = 0; l < n; l += FX_REDUCED ? 7 : 1) { /* every centre; every 7th in the reduced builds */
            double p[3], w;
            int inside;
            p[0] = g.origin[0] + ((double)(l % 33) + 0.5) * g.voxel_size;
            p[1] = g.origin[1] + ((double)(l / 33 % 31) + 0.5) * g.voxel_size;
            p[2] = g.origin[2] + ((double)(l / (33 * 31)) + 0.5) * g.voxel_size;
            w = winding_number(m, p);
            inside = ((long)floor(fabs(w) + 0.5)) % 2;
            set += (uint64_t)inside;
            for (v = 0; v < 4; v++) bad[v] += (uint64_t)(voxgi_bit_get(b[v], l) != inside);
        }
        for (v = 0; v < 4; v++) {
            TH_CHECK(bad[v] == 0, "%s: variant %d differs from the inside test at %llu of %llu centres", scene ? "shell" : "sphere", v,
                     (unsigned long long)bad[v], (unsigned long long)set);
            free(b[v]);
        }
        TH_CHECK(set > (FX_REDUCED ? 1000 / 7 : 1000), "too few inside voxels: %llu", (unsigned long long)set);
    }
    vxt_shape_free(&outer);
    vxt_shape_free(&inner);
    vxt_shape_free(&shell);
    voxgi_destroy(ctx);
}

/* A box with lattice coordinates (faces on voxel faces, centres never on faces): parity is
   exactly the voxels whose centres lie inside, along every axis. */
static void test_solid_box_exact(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 1);
    vxt_shape m;
    voxgi_grid g;
    const float lo[3] = {2, 3, 4}, hi[3] = {20, 17, 13};
    int axis;
    vxt_shape_alloc(&m, 8, 12);
    vxt_shape_put_box(&m, 0, 0, lo, hi);
    g.origin[0] = g.origin[1] = g.origin[2] = -1;
    g.voxel_size = 1.5;
    g.res[0] = 19; g.res[1] = 18; g.res[2] = 17;
    for (axis = VOXGI_AXIS_X; axis <= VOXGI_AXIS_Z; axis++) {
        uint32_t *b = solid_bits(ctx, &m, &g, VOXGI_SOLID_PARITY, (voxgi_axis)axis);
        uint64_t bad = 0;
        int i, j, k;
        for (k = 0; k < 17; k++)
            for (j = 0; j < 18; j++)
                for (i = 0; i < 19; i++) {
                    double c[3];
                    int a, in = 1;
                    c[0] = -1 + 1.5 * (i + 0.5); c[1] = -1 + 1.5 * (j + 0.5); c[2] = -1 + 1.5 * (k + 0.5);
                    for (a = 0; a < 3; a++) in &= c[a] > lo[a] && c[a] < hi[a];
                    bad += (uint64_t)(voxgi_bit_get(b, (uint64_t)(i + 19 * (j + 18 * k))) != in);
                }
        TH_CHECK(bad == 0, "axis %d: %llu voxels wrong", axis, (unsigned long long)bad);
        free(b);
    }
    vxt_shape_free(&m);
    voxgi_destroy(ctx);
}

/* Solid parity at ties: boxes whose faces lie on planes of voxel centres, whose edges run through
   columns' centres, and whose faces' diagonals (each face is two triangles) cross centres. Any
   consistent tie rule puts a centre on a face on exactly one side of it, so whatever the rule,
   each axis's parity holds exactly as many voxels as the box has volume in voxels, every centre
   strictly inside and none strictly outside, and the three axes agree (the rule belongs to the
   point, not to the counting direction). */
static void test_solid_ties(void)
{
    static const float boxes[3][2][3] = {{{2, 2, 2}, {7, 6, 5}}, {{2, 2, 2}, {6, 6, 6}}, {{1, 3, 2}, {9, 5, 8}}};
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    voxgi_grid g;
    int box;
    g.origin[0] = g.origin[1] = g.origin[2] = -0.5; /* centres on the integers */
    g.voxel_size = 1;
    g.res[0] = g.res[1] = g.res[2] = 11;
    for (box = 0; box < 3; box++) {
        const float *lo = boxes[box][0], *hi = boxes[box][1];
        uint64_t volume = (uint64_t)((hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2])), count[3] = {0, 0, 0}, wrong = 0, differ = 0, v;
        uint32_t *b[3];
        vxt_shape m;
        int axis;
        vxt_shape_alloc(&m, 8, 12);
        vxt_shape_put_box(&m, 0, 0, lo, hi);
        for (axis = 0; axis < 3; axis++) b[axis] = solid_bits(ctx, &m, &g, VOXGI_SOLID_PARITY, (voxgi_axis)(VOXGI_AXIS_X + axis));
        for (v = 0; v < 11 * 11 * 11; v++) {
            int c[3], a, inside = 1, outside = 0;
            c[0] = (int)(v % 11); c[1] = (int)(v / 11 % 11); c[2] = (int)(v / 121);
            for (a = 0; a < 3; a++) {
                inside &= c[a] > lo[a] && c[a] < hi[a];
                outside |= c[a] < lo[a] || c[a] > hi[a];
            }
            for (axis = 0; axis < 3; axis++) {
                int set = b[axis] && voxgi_bit_get(b[axis], v);
                count[axis] += (uint64_t)set;
                wrong += (uint64_t)((inside && !set) || (outside && set));
                differ += (uint64_t)(axis && b[0] && b[axis] && set != voxgi_bit_get(b[0], v));
            }
        }
        TH_CHECK(count[0] == volume && count[1] == volume && count[2] == volume && wrong == 0 && differ == 0,
                 "box %d: %llu / %llu / %llu voxels along x / y / z (volume %llu), %llu on the wrong side of a face, %llu where the axes disagree", box,
                 (unsigned long long)count[0], (unsigned long long)count[1], (unsigned long long)count[2], (unsigned long long)volume,
                 (unsigned long long)wrong, (unsigned long long)differ);
        for (axis = 0; axis < 3; axis++) free(b[axis]);
        vxt_shape_free(&m);
    }
    voxgi_destroy(ctx);
}

/* Open meshes: a box without its bottom face is filled by the vote (x and y still see it
   closed); a box whose bottom face leaves a gap thinner than a voxel is filled by the flood. */
static void test_solid_open_mesh_robust_modes(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    vxt_shape m;
    voxgi_grid g;
    const float lo[3] = {0.3f, 0.35f, 0.4f}, hi[3] = {2.56f, 2.45f, 2.3f}; /* a centre at x = 2.55 sees the gap */
    int variant;
    g.origin[0] = g.origin[1] = g.origin[2] = -0.5;
    g.voxel_size = 0.1;
    g.res[0] = g.res[1] = g.res[2] = 36;
    for (variant = 0; variant < 2; variant++) {
        uint32_t *b, *parity;
        uint64_t wrong_in = 0, wrong_out = 0, parity_wrong = 0;
        int i, j, k;
        vxt_shape_alloc(&m, 8, 12);
        vxt_shape_put_box(&m, 0, 0, lo, hi);
        if (variant == 0) m.triangle_count = 10; /* drop the last face (z = hi) */
        else { /* the bottom face gets its own vertices, its x = hi edge pulled in by 0.02 */
            size_t v;
            vxt_shape_free(&m);
            vxt_shape_alloc(&m, 12, 12);
            vxt_shape_put_box(&m, 0, 0, lo, hi);
            for (v = 0; v < 36; v += 3)
                if (m.pos[3 * m.idx[v] + 2] == lo[2] && m.pos[3 * m.idx[v + 1] + 2] == lo[2] && m.pos[3 * m.idx[v + 2] + 2] == lo[2]) {
                    int c;
                    for (c = 0; c < 3; c++) {
                        uint32_t vi = m.idx[v + (size_t)c], copy = 8 + (vi & 3); /* corners 0..3 have z = lo */
                        memcpy(m.pos + 3 * copy, m.pos + 3 * vi, 3 * sizeof(float));
                        if (m.pos[3 * vi] == hi[0]) m.pos[3 * copy] = hi[0] - 0.02f;
                        m.idx[v + (size_t)c] = copy;
                    }
                }
        }
        b = solid_bits(ctx, &m, &g, variant == 0 ? VOXGI_SOLID_VOTE : VOXGI_SOLID_FLOOD, VOXGI_AXIS_DEFAULT);
        parity = solid_bits(ctx, &m, &g, VOXGI_SOLID_PARITY, VOXGI_AXIS_DEFAULT);
        for (k = 0; k < 36; k++)
            for (j = 0; j < 36; j++)
                for (i = 0; i < 36; i++) {
                    double c[3];
                    int a, in = 1, out = 0;
                    uint64_t l = (uint64_t)(i + 36 * (j + 36 * k));
                    c[0] = -0.5 + 0.1 * (i + 0.5); c[1] = -0.5 + 0.1 * (j + 0.5); c[2] = -0.5 + 0.1 * (k + 0.5);
                    for (a = 0; a < 3; a++) {
                        in &= c[a] > lo[a] + 0.15 && c[a] < hi[a] - 0.15;  /* deep inside */
                        out |= c[a] < lo[a] - 0.15 || c[a] > hi[a] + 0.15; /* clearly outside */
                    }
                    wrong_in += (uint64_t)(in && !voxgi_bit_get(b, l));
                    wrong_out += (uint64_t)(out && voxgi_bit_get(b, l));
                    parity_wrong += (uint64_t)((in && !voxgi_bit_get(parity, l)) || (out && voxgi_bit_get(parity, l)));
                }
        TH_CHECK(wrong_in == 0 && wrong_out == 0, "%s: %llu interior voxels empty, %llu exterior set", variant ? "flood" : "vote",
                 (unsigned long long)wrong_in, (unsigned long long)wrong_out);
        TH_CHECK(parity_wrong > 0, "%s case: parity alone should fail on this open mesh", variant ? "flood" : "vote");
        free(b);
        free(parity);
        vxt_shape_free(&m);
    }
    voxgi_destroy(ctx);
}

/* OR-reduction: every level of 3D occupancy mips and of the column OR-mipmap equals a direct
   OR over the source blocks, down to one voxel, on a non-power-of-two grid. */
static void test_or_mips(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    vxt_shape m;
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi_voxelize_desc vd;
    voxgi_voxels *base = NULL;
    uint32_t *src;
    int variant;
    size_t need = 0;
    reduce_scene(&m, &sc, &mesh, &vd);
    TH_CHECK(voxgi_voxelize(ctx, &sc, &vd, &base) == VOXGI_OK, "voxelize failed");
    for (variant = 0; variant < 2; variant++) {
        const int f[3] = {2, 2, variant ? 1 : 2};
        const voxgi_voxels *cur = base;
        voxgi_voxels *next = NULL;
        int level = 0;
        voxgi_voxels_info ci, ni;
        voxgi_voxels_query(cur, &ci);
        voxgi_voxels_read(ctx, cur, NULL, 0, &need);
        src = (uint32_t *)malloc(need);
        voxgi_voxels_read(ctx, cur, src, need, NULL);
        while ((ci.grid.res[0] > 1 || ci.grid.res[1] > 1) && level < 10) {
            uint32_t *dst;
            uint64_t i, j, k, bad = 0, count = 0;
            TH_CHECK(voxgi_voxels_reduce(ctx, cur, f, &next) == VOXGI_OK, "reduce failed");
            voxgi_voxels_query(next, &ni);
            TH_CHECK(ni.grid.res[0] == (ci.grid.res[0] + 1) / 2 && ni.grid.res[2] == (ci.grid.res[2] + f[2] - 1) / f[2], "level %d size", level);
            voxgi_voxels_read(ctx, next, NULL, 0, &need);
            dst = (uint32_t *)malloc(need);
            voxgi_voxels_read(ctx, next, dst, need, NULL);
            for (k = 0; k < (uint64_t)ni.grid.res[2]; k++)
                for (j = 0; j < (uint64_t)ni.grid.res[1]; j++)
                    for (i = 0; i < (uint64_t)ni.grid.res[0]; i++) {
                        int want = 0, dx, dy, dz;
                        for (dz = 0; dz < f[2]; dz++)
                            for (dy = 0; dy < 2; dy++)
                                for (dx = 0; dx < 2; dx++) {
                                    uint64_t x = 2 * i + (uint64_t)dx, y = 2 * j + (uint64_t)dy, z = (uint64_t)f[2] * k + (uint64_t)dz;
                                    if (x < (uint64_t)ci.grid.res[0] && y < (uint64_t)ci.grid.res[1] && z < (uint64_t)ci.grid.res[2])
                                        want |= voxgi_bit_get(src, x + (uint64_t)ci.grid.res[0] * (y + (uint64_t)ci.grid.res[1] * z));
                                }
                        count += (uint64_t)want;
                        bad += (uint64_t)(want != voxgi_bit_get(dst, i + (uint64_t)ni.grid.res[0] * (j + (uint64_t)ni.grid.res[1] * k)));
                    }
            TH_CHECK(bad == 0 && count == ni.voxel_count, "factor %d%d%d level %d: %llu wrong, count %llu vs %llu", f[0], f[1], f[2],
                     level + 1, (unsigned long long)bad, (unsigned long long)count, (unsigned long long)ni.voxel_count);
            free(src);
            src = dst;
            if (cur != base) voxgi_voxels_destroy(ctx, (voxgi_voxels *)cur);
            cur = next;
            ci = ni;
            level++;
        }
        TH_CHECK(level >= 5, "only %d levels", level);
        free(src);
        if (cur != base) voxgi_voxels_destroy(ctx, (voxgi_voxels *)cur);
    }
    {
        const int bad_factor[3] = {2, 3, 2};
        voxgi_voxels *o = NULL;
        TH_CHECK(voxgi_voxels_reduce(ctx, base, bad_factor, &o) == VOXGI_ERR_INVALID_ARGUMENT && !o, "factor 3 accepted");
    }
    voxgi_voxels_destroy(ctx, base);
    vxt_shape_free(&m);
    voxgi_destroy(ctx);
}

/* ---------------------------------------------------------------- raster slicemap */
/* A triangle drawn along an axis, as the rasterizer draws it, in 128-bit integers: corners
   rounded half up to 1/256 of a voxel in the other two axes, pixel centres covered under the fill
   rule, the exact plane's depth floored. The raster slicemap draws along its axis, the Volume
   Buffer along each triangle's dominant one (largest |n|, lowest axis on ties: axis -1). Needs a
   power-of-two voxel size, so that the library's voxel coordinates are exact. */
static int64_t floor_div(i128 num, i128 den)
{
    if (den < 0) { num = -num; den = -den; }
    return (int64_t)(num >= 0 ? num / den : -((-num + den - 1) / den));
}

static uint32_t *oracle_drawn_along(const float *pos, const uint32_t *idx, size_t ntri, const voxgi_grid *g, int axis)
{
    uint64_t nvox = voxgi_grid_voxel_count(g);
    uint32_t *bits = (uint32_t *)calloc((size_t)(nvox + 31) / 32, 4);
    int64_t o[3], s = to_fixed(g->voxel_size);
    const i128 one = (i128)1 << ORACLE_BITS; /* a voxel, in units of 2^-ORACLE_BITS voxels */
    size_t t;
    int k;
    for (k = 0; k < 3; k++) o[k] = to_fixed(g->origin[k]);
    for (t = 0; t < ntri; t++) {
        i128 q[3][3], n[3], e[3], f[3], X[3], Y[3], area;
        int c = 0, a, b, i, j, v;
        for (v = 0; v < 3; v++)
            for (k = 0; k < 3; k++) q[v][k] = ((i128)to_fixed(pos[3 * idx[3 * t + (size_t)v] + (size_t)k]) - o[k]) * one / s; /* exact: s is 2^m */
        for (k = 0; k < 3; k++) { e[k] = q[1][k] - q[0][k]; f[k] = q[2][k] - q[0][k]; }
        n[0] = e[1] * f[2] - f[1] * e[2]; n[1] = e[2] * f[0] - f[2] * e[0]; n[2] = e[0] * f[1] - f[0] * e[1];
        for (k = 1; k < 3; k++) if ((n[k] < 0 ? -n[k] : n[k]) > (n[c] < 0 ? -n[c] : n[c])) c = k;
        if (axis >= 0) c = axis;
        if (n[c] == 0) continue;
        a = (c + 1) % 3; b = (c + 2) % 3;
        for (v = 0; v < 3; v++) { /* rounded to 1/256, then in units of 1/512 so centres are integers */
            X[v] = 2 * (i128)floor_div(q[v][a] * 256 + one / 2, one);
            Y[v] = 2 * (i128)floor_div(q[v][b] * 256 + one / 2, one);
        }
        area = (X[1] - X[0]) * (Y[2] - Y[0]) - (Y[1] - Y[0]) * (X[2] - X[0]);
        if (area == 0) continue;
        for (j = 0; j < g->res[b]; j++)
            for (i = 0; i < g->res[a]; i++) {
                i128 px = 512 * (i128)i + 256, py = 512 * (i128)j + 256;
                int covered = 1;
                int64_t z;
                for (v = 0; v < 3 && covered; v++) {
                    int w = (v + 1) % 3;
                    i128 dx = (X[w] - X[v]) * (area > 0 ? 1 : -1), dy = (Y[w] - Y[v]) * (area > 0 ? 1 : -1);
                    i128 x0 = area > 0 ? X[v] : X[w], y0 = area > 0 ? Y[v] : Y[w];
                    i128 ev = dx * (py - y0) - dy * (px - x0);
                    covered = ev > 0 || (ev == 0 && (dy < 0 || (dy == 0 && dx > 0)));
                }
                if (!covered) continue;
                {   /* depth: q0c - (n_a (pa - q0a) + n_b (pb - q0b)) / n_c, centres (i + 1/2) voxels */
                    i128 pa = (2 * (i128)i + 1) * one / 2, pb = (2 * (i128)j + 1) * one / 2;
                    z = floor_div(q[0][c] * n[c] - (n[a] * (pa - q[0][a]) + n[b] * (pb - q[0][b])), n[c] * one);
                }
                if (z >= 0 && z < g->res[c]) {
                    int vv[3];
                    vv[a] = i; vv[b] = j; vv[c] = (int)z;
                    oracle_set(bits, g, vv);
                }
            }
    }
    return bits;
}

static uint32_t *oracle_volume_buffer(const float *pos, const uint32_t *idx, size_t ntri, const voxgi_grid *g)
{
    return oracle_drawn_along(pos, idx, ntri, g, -1);
}

static uint64_t outside_dilated(const uint32_t *a, const uint32_t *b, const voxgi_grid *g);

static void test_slicemap_vs_oracle_and_relations(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    vxt_shape m;
    voxgi_grid g;
    int A, trial;
    uint64_t bad = 0, outside = 0;
    /* random triangles on a grid of power-of-two voxels (lattice inputs) along every axis */
    g.origin[0] = lattice(-3.3); g.origin[1] = lattice(1.7); g.origin[2] = lattice(-0.45);
    g.voxel_size = 0.5;
    g.res[0] = 23; g.res[1] = 19; g.res[2] = 21;
    for (trial = 0; trial < 150 && bad == 0 && outside == 0; trial++) {
        float p[9];
        uint32_t idx[3] = {0, 1, 2};
        int c;
        for (c = 0; c < 9; c++) p[c] = (float)lattice((c % 3 == 0 ? -4 : (c % 3 == 1 ? 1 : -1)) + 11 * rnd());
        for (A = 0; A < 3; A++) {
            voxgi_voxelize_desc vd;
            uint32_t *mine, *ref, *cons;
            uint64_t n = voxgi_grid_voxel_count(&g);
            voxgi_mesh mesh;
            voxgi_scene sc;
            voxgi_voxels *vox = NULL;
            memset(&vd, 0, sizeof vd);
            scene_of_triangles(&sc, &mesh, p, 3, idx, 1);
            vd.grid = g; vd.method = VOXGI_METHOD_SLICEMAP; vd.axis = (voxgi_axis)(A + 1);
            voxgi_voxelize(ctx, &sc, &vd, &vox);
            mine = (uint32_t *)malloc((size_t)(n + 31) / 32 * 4);
            voxgi_voxels_read(ctx, vox, mine, (size_t)(n + 31) / 32 * 4, NULL);
            voxgi_voxels_destroy(ctx, vox);
            ref = oracle_drawn_along(p, idx, 1, &g, A);
            cons = oracle_voxelize(p, idx, 1, &g);
            bad += compare_bits(mine, ref, &g, "slicemap");
            outside += outside_dilated(mine, cons, &g);
            free(mine); free(ref); free(cons);
        }
    }
    TH_CHECK(bad == 0 && outside == 0, "slicemap: %llu voxels differ from the definition (trial %d), %llu beyond one voxel of conservative",
             (unsigned long long)bad, trial, (unsigned long long)outside);
    {   /* the axis-aligned cube at 32: the faces parallel to the axis vanish, only the two caps
           remain: 2 * 30^2 voxels, against 5048 conservative ones */
        voxgi_voxelize_desc vd;
        voxgi_mesh mesh;
        voxgi_scene sc;
        voxgi_voxels *vox = NULL;
        voxgi_voxels_info info;
        voxgi_fit_desc fit;
        const float lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
        uint64_t counts[2];
        int method;
        vxt_shape_alloc(&m, 8, 12);
        vxt_shape_put_box(&m, 0, 0, lo, hi);
        memset(&vd, 0, sizeof vd); memset(&fit, 0, sizeof fit);
        scene_of_shape(&sc, &mesh, &m);
        fit.res = 32; fit.padding = 1;
        voxgi_fit_grid(ctx, &sc, &fit, &vd.grid);
        for (method = 0; method < 2; method++) {
            vd.method = method ? VOXGI_METHOD_SLICEMAP : VOXGI_METHOD_CONSERVATIVE;
            voxgi_voxelize(ctx, &sc, &vd, &vox);
            voxgi_voxels_query(vox, &info);
            counts[method] = info.voxel_count;
            voxgi_voxels_destroy(ctx, vox);
        }
        TH_CHECK(counts[1] == 2 * 30 * 30 && counts[0] > 2 * counts[1], "cube at 32: slicemap %llu, conservative %llu",
                 (unsigned long long)counts[1], (unsigned long long)counts[0]);
        printf("    cube 32^3: conservative %llu, slicemap %llu voxels\n", (unsigned long long)counts[0], (unsigned long long)counts[1]);
        vxt_shape_free(&m);
    }
    voxgi_destroy(ctx);
}

/* ---------------------------------------------------------------- texture atlas */
static uint32_t *atlas_bits(voxgi_context *ctx, const voxgi_scene *sc, const voxgi_grid *g, voxgi_method method, int size,
                            voxgi_atlas_uv uv, voxgi_voxels_info *info)
{
    voxgi_voxelize_desc vd;
    memset(&vd, 0, sizeof vd);
    vd.grid = *g;
    vd.method = method;
    vd.atlas_size = size;
    vd.atlas_uv = uv;
    return voxelized_bits(ctx, sc, &vd, info);
}

/* Voxels set in a but in no 26-neighbourhood (or itself) of a voxel of b. */
static uint64_t outside_dilated(const uint32_t *a, const uint32_t *b, const voxgi_grid *g)
{
    uint64_t n = voxgi_grid_voxel_count(g), l, out = 0;
    for (l = 0; l < n; l++) {
        int x = (int)(l % (uint64_t)g->res[0]), y = (int)(l / (uint64_t)g->res[0] % (uint64_t)g->res[1]);
        int z = (int)(l / ((uint64_t)g->res[0] * (uint64_t)g->res[1])), dx, dy, dz, near = 0;
        if (!voxgi_bit_get(a, l)) continue;
        for (dz = -1; dz <= 1 && !near; dz++)
            for (dy = -1; dy <= 1 && !near; dy++)
                for (dx = -1; dx <= 1 && !near; dx++) {
                    int X = x + dx, Y = y + dy, Z = z + dz;
                    if (X < 0 || Y < 0 || Z < 0 || X >= g->res[0] || Y >= g->res[1] || Z >= g->res[2]) continue;
                    near = voxgi_bit_get(b, (uint64_t)X + (uint64_t)g->res[0] * ((uint64_t)Y + (uint64_t)g->res[1] * (uint64_t)Z));
                }
        out += (uint64_t)!near;
    }
    return out;
}

/* The mesh's own uvs: texel ownership (highest covering triangle) and each point's voxel
   evaluated exactly in 128-bit integers: uv * size on the 1/256 lattice, voxel size 1, lattice
   vertices, so the point is a rational number. (The library rounds the point in double; a point
   within an ulp of a voxel face could round across it, which random inputs do not produce.) */
static void test_atlas_mesh_uvs_vs_oracle(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    enum { NT = 40, SIZE = 97 };
    float pos[NT * 9], uv[NT * 6];
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi_grid g;
    voxgi_voxels_info info;
    uint32_t *mine, *ref;
    int64_t *owner = (int64_t *)malloc(sizeof(int64_t) * SIZE * SIZE);
    uint64_t points = 0, l, n;
    int t, c, i, j;
    for (c = 0; c < NT * 9; c++) pos[c] = (float)lattice(0.5 + 14 * rnd());
    for (c = 0; c < NT * 6; c++) uv[c] = (float)lattice(rnd() * 1.2 - 0.1); /* some outside [0,1]: clamped */
    scene_of_triangles(&sc, &mesh, pos, NT * 3, NULL, 0);
    mesh.uvs = uv;
    g.origin[0] = 0; g.origin[1] = 0; g.origin[2] = 0; g.voxel_size = 1;
    g.res[0] = 15; g.res[1] = 16; g.res[2] = 14;
    n = voxgi_grid_voxel_count(&g);
    mine = atlas_bits(ctx, &sc, &g, VOXGI_METHOD_ATLAS, SIZE, VOXGI_ATLAS_MESH, &info);
    ref = (uint32_t *)calloc((size_t)(n + 31) / 32, 4);
    for (i = 0; i < SIZE * SIZE; i++) owner[i] = -1;
    for (t = 0; t < NT; t++) { /* integer coverage, texel units * 512 so centres are integers */
        int64_t x[3], y[3];
        int64_t area;
        for (c = 0; c < 3; c++) {
            double u = uv[6 * t + 2 * c], v = uv[6 * t + 2 * c + 1];
            u = u < 0 ? 0 : (u > 1 ? 1 : u);
            v = v < 0 ? 0 : (v > 1 ? 1 : v);
            x[c] = 2 * (int64_t)floor(u * SIZE * 256 + 0.5);
            y[c] = 2 * (int64_t)floor(v * SIZE * 256 + 0.5);
        }
        area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
        if (area == 0) continue;
        for (j = 0; j < SIZE; j++)
            for (i = 0; i < SIZE; i++) {
                int64_t px = 512 * (int64_t)i + 256, py = 512 * (int64_t)j + 256;
                int covered = 1;
                for (c = 0; c < 3 && covered; c++) {
                    int64_t dx = (x[(c + 1) % 3] - x[c]) * (area > 0 ? 1 : -1), dy = (y[(c + 1) % 3] - y[c]) * (area > 0 ? 1 : -1);
                    int64_t x0 = area > 0 ? x[c] : x[(c + 1) % 3], y0 = area > 0 ? y[c] : y[(c + 1) % 3];
                    int64_t e = dx * (py - y0) - dy * (px - x0);
                    covered = e > 0 || (e == 0 && (dy < 0 || (dy == 0 && dx > 0)));
                }
                if (covered) owner[j * SIZE + i] = t;
            }
    }
    for (j = 0; j < SIZE; j++)
        for (i = 0; i < SIZE; i++) {
            int64_t x[3], y[3], den, n1, n2, px, py;
            int a, inside = 1;
            int64_t vox[3];
            t = (int)owner[j * SIZE + i];
            if (t < 0) continue;
            points++;
            for (c = 0; c < 3; c++) {
                double u = uv[6 * t + 2 * c], v = uv[6 * t + 2 * c + 1];
                x[c] = (int64_t)floor((u < 0 ? 0 : (u > 1 ? 1 : u)) * SIZE * 256 + 0.5);
                y[c] = (int64_t)floor((v < 0 ? 0 : (v > 1 ? 1 : v)) * SIZE * 256 + 0.5);
            }
            px = 256 * (int64_t)i + 128 - x[0]; py = 256 * (int64_t)j + 128 - y[0];
            den = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
            n1 = px * (y[2] - y[0]) - py * (x[2] - x[0]);
            n2 = (x[1] - x[0]) * py - (y[1] - y[0]) * px;
            for (a = 0; a < 3 && inside; a++) { /* P * den * 2^B = q0 den + n1 (q1 - q0) + n2 (q2 - q0), exact */
                i128 q0 = to_fixed(pos[9 * t + a]), q1 = to_fixed(pos[9 * t + 3 + a]), q2 = to_fixed(pos[9 * t + 6 + a]);
                i128 num = q0 * den + (i128)n1 * (q1 - q0) + (i128)n2 * (q2 - q0), d = (i128)den * ((i128)1 << ORACLE_BITS), f;
                if (d < 0) { num = -num; d = -d; }
                f = num >= 0 ? num / d : -((-num + d - 1) / d);
                vox[a] = (int64_t)f;
                inside = f >= 0 && f < g.res[a];
            }
            if (inside) {
                l = (uint64_t)vox[0] + (uint64_t)g.res[0] * ((uint64_t)vox[1] + (uint64_t)g.res[1] * (uint64_t)vox[2]);
                ref[l >> 5] |= 1u << (l & 31);
            }
        }
    TH_CHECK(mine != NULL && info.atlas_points == points, "atlas points %llu, oracle %llu", (unsigned long long)info.atlas_points,
             (unsigned long long)points);
    TH_CHECK(mine && compare_bits(mine, ref, &g, "atlas (mesh uvs)") == 0, "atlas voxels differ from the exact points");
    free(mine); free(ref); free(owner);
    /* a mesh without uvs is refused when its uvs are asked for */
    mesh.uvs = NULL;
    {
        voxgi_voxelize_desc vd;
        voxgi_voxels *vox = NULL;
        memset(&vd, 0, sizeof vd);
        vd.grid = g; vd.method = VOXGI_METHOD_ATLAS; vd.atlas_uv = VOXGI_ATLAS_MESH;
        TH_CHECK(voxgi_voxelize(ctx, &sc, &vd, &vox) == VOXGI_ERR_INVALID_SCENE && !vox, "missing uvs accepted");
        vd.atlas_uv = VOXGI_ATLAS_AUTO; vd.atlas_size = 16385;
        TH_CHECK(voxgi_voxelize(ctx, &sc, &vd, &vox) == VOXGI_ERR_INVALID_ARGUMENT && !vox, "atlas_size 16385 accepted");
        vd.atlas_size = 8; /* 40 charts of at least 3x3 texels do not fit into 8x8 */
        TH_CHECK(voxgi_voxelize(ctx, &sc, &vd, &vox) == VOXGI_ERR_TOO_LARGE && !vox, "a too small atlas accepted: %s", voxgi_last_error(ctx));
    }
    voxgi_destroy(ctx);
}

/* voxgi's own charts: within one voxel of the conservative set; every triangle has a point (a
   scatter of triangles much smaller than a texel); coverage rises with the atlas size; the
   raster (B) and compute (D) methods give one set; any thread count gives the same bits. */
static void test_atlas_auto_relations(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2), *one = make_ctx(VOXGI_BACKEND_CPU, 1);
    vxt_shape m;
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi_grid g;
    voxgi_fit_desc fit;
    voxgi_voxels_info info;
    uint32_t *cons, *b, *d, *c1;
    uint64_t missed[3], n;
    int k, sizes[3] = {160, 320, 1024};
    vxt_shape_sphere(&m, 48, 24, 1.0, 0.1, -0.2, 0.3);
    scene_of_shape(&sc, &mesh, &m);
    memset(&fit, 0, sizeof fit);
    fit.res = 48; fit.padding = 1;
    voxgi_fit_grid(ctx, &sc, &fit, &g);
    n = voxgi_grid_voxel_count(&g);
    cons = voxelize_bits(ctx, m.pos, m.vertex_count, m.idx, m.triangle_count, &g, NULL);
    b = atlas_bits(ctx, &sc, &g, VOXGI_METHOD_ATLAS, 0, VOXGI_ATLAS_AUTO, &info);
    d = atlas_bits(ctx, &sc, &g, VOXGI_METHOD_ATLAS_COMPUTE, 0, VOXGI_ATLAS_AUTO, NULL);
    c1 = atlas_bits(one, &sc, &g, VOXGI_METHOD_ATLAS, 0, VOXGI_ATLAS_AUTO, NULL);
    TH_CHECK(b && d && c1 && memcmp(b, d, (size_t)(n + 31) / 32 * 4) == 0 && memcmp(b, c1, (size_t)(n + 31) / 32 * 4) == 0,
             "atlas and atlas-compute (or 1 and 2 threads) differ");
    TH_CHECK(b && outside_dilated(b, cons, &g) == 0, "atlas voxels beyond one voxel of the conservative set");
    TH_CHECK(info.atlas_scale >= 2.0 && info.atlas_points > 0, "default atlas: %.3g texels per voxel", info.atlas_scale);
    printf("    sphere 48^3: default atlas %dx%d (%.3g texels/voxel), %llu points\n", info.atlas_size, info.atlas_size,
           info.atlas_scale, (unsigned long long)info.atlas_points);
    for (k = 0; k < 3; k++) {
        uint32_t *a = atlas_bits(ctx, &sc, &g, VOXGI_METHOD_ATLAS, sizes[k], VOXGI_ATLAS_AUTO, &info);
        uint64_t l;
        missed[k] = 0;
        TH_CHECK(a != NULL, "atlas %d failed", sizes[k]);
        for (l = 0; a && l < n; l++) missed[k] += (uint64_t)(voxgi_bit_get(cons, l) && !voxgi_bit_get(a, l));
        printf("    atlas %d^2: %llu points, missed %llu of the conservative voxels\n", sizes[k], (unsigned long long)info.atlas_points,
               (unsigned long long)missed[k]);
        free(a);
    }
    TH_CHECK(missed[0] > missed[1] && missed[1] > missed[2], "coverage does not rise with the atlas size");
    {   /* a coarse grid: every chart is at its smallest, and the default atlas still holds them */
        voxgi_grid coarse = g;
        uint32_t *a;
        coarse.voxel_size = g.voxel_size * 16;
        coarse.res[0] = coarse.res[1] = coarse.res[2] = 3;
        a = atlas_bits(ctx, &sc, &coarse, VOXGI_METHOD_ATLAS, 0, VOXGI_ATLAS_AUTO, &info);
        TH_CHECK(a && info.voxel_count > 0 && info.atlas_points >= m.triangle_count, "coarse grid: default atlas failed");
        free(a);
    }
    free(cons); free(b); free(d); free(c1);
    vxt_shape_free(&m);
    {   /* 300 triangles far smaller than a texel, scattered: each sets the voxel of its centroid */
        enum { NT = 300 };
        float p[NT * 9];
        uint32_t *bits;
        uint64_t lost = 0;
        int t, c;
        g.origin[0] = g.origin[1] = g.origin[2] = 0; g.voxel_size = 1; g.res[0] = g.res[1] = g.res[2] = 40;
        for (t = 0; t < NT; t++) {
            double cx = 1 + 38 * rnd(), cy = 1 + 38 * rnd(), cz = 1 + 38 * rnd();
            for (c = 0; c < 3; c++) {
                p[9 * t + 3 * c] = (float)(cx + 1e-3 * rnd());
                p[9 * t + 3 * c + 1] = (float)(cy + 1e-3 * rnd());
                p[9 * t + 3 * c + 2] = (float)(cz + 1e-3 * rnd());
            }
        }
        memset(&mesh, 0, sizeof mesh);
        mesh.positions = p; mesh.vertex_count = NT * 3;
        bits = atlas_bits(ctx, &sc, &g, VOXGI_METHOD_ATLAS, 0, VOXGI_ATLAS_AUTO, &info);
        for (t = 0; bits && t < NT; t++) {
            int v[3], a;
            for (a = 0; a < 3; a++) v[a] = (int)floor((p[9 * t + a] + p[9 * t + 3 + a] + p[9 * t + 6 + a]) / 3);
            lost += (uint64_t)!voxgi_bit_get(bits, (uint64_t)v[0] + 40u * ((uint64_t)v[1] + 40u * (uint64_t)v[2]));
        }
        TH_CHECK(bits && lost == 0 && info.atlas_points >= NT, "%llu tiny triangles lost their point", (unsigned long long)lost);
        free(bits);
    }
    voxgi_destroy(ctx);
    voxgi_destroy(one);
}

/* ---------------------------------------------------------------- attributes */
static voxgi_voxels *attr_run(voxgi_context *ctx, const float *pos, size_t nv, const uint32_t *idx, size_t nt, const uint32_t *mat_ids,
                              const voxgi_material *mats, size_t nm, const voxgi_grid *g, unsigned attributes, voxgi_method method,
                              const voxgi_blend blend[4])
{
    voxgi_mesh m;
    voxgi_scene sc;
    voxgi_voxelize_desc vd;
    voxgi_voxels *vox = NULL;
    scene_of_triangles(&sc, &m, pos, nv, idx, nt);
    m.material_ids = mat_ids;
    scene_lighting(&sc, mats, nm, NULL, 0);
    memset(&vd, 0, sizeof vd);
    vd.grid = *g; vd.attributes = attributes; vd.method = method;
    memcpy(vd.blend, blend, sizeof vd.blend);
    if (voxgi_voxelize(ctx, &sc, &vd, &vox) != VOXGI_OK) printf("    voxelize: %s\n", voxgi_last_error(ctx));
    return vox;
}

static float *attr_read(voxgi_context *ctx, const voxgi_voxels *vox, voxgi_attribute which)
{
    size_t need = 0;
    float *out;
    if (voxgi_voxels_read_attribute(ctx, vox, which, NULL, 0, &need) != VOXGI_OK) return NULL;
    out = (float *)malloc(need ? need : 4);
    if (voxgi_voxels_read_attribute(ctx, vox, which, out, need, NULL) != VOXGI_OK) { free(out); return NULL; }
    return out;
}

/* The Volume Buffer on the CPU equals its integer definition, triangle by triangle and for a
   whole mesh, and stays within one voxel of the conservative set. */
static void test_volume_buffer_vs_oracle(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    voxgi_grid g;
    vxt_shape m;
    uint64_t bad = 0, outside = 0, n;
    int trial;
    g.origin[0] = lattice(-3.3); g.origin[1] = lattice(1.7); g.origin[2] = lattice(-0.45);
    g.voxel_size = 0.5;
    g.res[0] = 23; g.res[1] = 19; g.res[2] = 21;
    n = voxgi_grid_voxel_count(&g);
    for (trial = 0; trial < 200 && bad == 0; trial++) {
        float p[9];
        uint32_t idx[3] = {0, 1, 2}, *mine, *ref, *cons;
        int c;
        for (c = 0; c < 9; c++) p[c] = (float)lattice((c % 3 == 0 ? -4 : (c % 3 == 1 ? 1 : -1)) + 11 * rnd());
        mine = voxelize_bits_method(ctx, p, 3, idx, 1, &g, VOXGI_METHOD_VOLUME_BUFFER, NULL);
        ref = oracle_volume_buffer(p, idx, 1, &g);
        cons = oracle_voxelize(p, idx, 1, &g);
        bad += mine ? compare_bits(mine, ref, &g, "volume buffer") : 1;
        if (mine) outside += outside_dilated(mine, cons, &g);
        free(mine); free(ref); free(cons);
    }
    TH_CHECK(bad == 0 && outside == 0, "volume buffer: %llu voxels differ from the definition (trial %d), %llu beyond one voxel of conservative",
             (unsigned long long)bad, trial, (unsigned long long)outside);
    vxt_shape_sphere(&m, 30, 17, 4.2, 2.5, 6.4, 4.9);
    for (trial = 0; trial < (int)(3 * m.vertex_count); trial++) m.pos[trial] = (float)lattice(m.pos[trial]);
    {
        uint32_t *mine = voxelize_bits_method(ctx, m.pos, m.vertex_count, m.idx, m.triangle_count, &g, VOXGI_METHOD_VOLUME_BUFFER, NULL);
        uint32_t *ref = oracle_volume_buffer(m.pos, m.idx, m.triangle_count, &g);
        uint64_t l, count = 0;
        for (l = 0; mine && l < n; l++) count += (uint64_t)voxgi_bit_get(mine, l);
        TH_CHECK(mine && compare_bits(mine, ref, &g, "volume buffer sphere") == 0 && count > 0, "volume buffer sphere differs");
        free(mine); free(ref);
    }
    vxt_shape_free(&m);
    voxgi_destroy(ctx);
}

/* Each voxel's attributes against the blend (mean, maximum or sum) over the triangles whose
   exact (oracle) set holds it, computed here in double: within half a fixed-point unit plus the
   float rounding of the output. Shuffling the triangles or changing the thread count changes no
   bit. For the conservative set and the Volume Buffer's. */
static void check_attributes(voxgi_method method, const voxgi_blend blend[4])
{
    enum { NT = 24, NM = 4 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2), *one = make_ctx(VOXGI_BACKEND_CPU, 1);
    float pos[NT * 9], shuffled[NT * 9];
    uint32_t idx[NT * 3], mat_ids[NT], smat[NT], perm[NT];
    voxgi_material mats[NM];
    voxgi_grid g;
    uint32_t *tri_bits[NT];
    voxgi_voxels *vox, *vs, *v1;
    double worst[4] = {0, 0, 0, 0}, emax = 0, erange = 1, esum_max = 0;
    int t, c, k, a;
    uint64_t n, l, slot = 0, bad_order = 0;
    static const voxgi_attribute kinds[4] = {VOXGI_ATTRIBUTE_ALBEDO, VOXGI_ATTRIBUTE_NORMAL, VOXGI_ATTRIBUTE_EMISSION, VOXGI_ATTRIBUTE_OPACITY};
    g.origin[0] = lattice(-0.3); g.origin[1] = lattice(0.2); g.origin[2] = lattice(-0.1);
    g.voxel_size = method == VOXGI_METHOD_VOLUME_BUFFER ? 0.25 : lattice(0.37);
    g.res[0] = 11; g.res[1] = 10; g.res[2] = 12;
    if (method == VOXGI_METHOD_VOLUME_BUFFER) { g.res[0] = 18; g.res[1] = 17; g.res[2] = 19; }
    n = voxgi_grid_voxel_count(&g);
    for (k = 0; k < NM; k++) {
        for (c = 0; c < 3; c++) {
            mats[k].albedo[c] = (float)rnd();
            mats[k].emission[c] = k == 2 ? (float)(100 * rnd()) : 0.0f; /* one bright emitter */
            emax = mats[k].emission[c] > emax ? mats[k].emission[c] : emax;
        }
        mats[k].transparency = (float)rnd();
    }
    while (erange < emax) erange *= 2;
    for (t = 0; t < NT; t++) { /* clustered, so voxels are shared by several triangles */
        double cx = 1 + 2 * rnd(), cy = 1 + 2 * rnd(), cz = 1 + 2 * rnd();
        for (c = 0; c < 3; c++)
            for (a = 0; a < 3; a++) pos[9 * t + 3 * c + a] = (float)lattice((a == 0 ? cx : (a == 1 ? cy : cz)) + 1.6 * (rnd() - 0.5));
        for (c = 0; c < 3; c++) idx[3 * t + c] = (uint32_t)(3 * t + c);
        mat_ids[t] = (uint32_t)(t % NM);
        tri_bits[t] = method == VOXGI_METHOD_VOLUME_BUFFER ? oracle_volume_buffer(pos + 9 * t, idx, 1, &g)
                                                           : oracle_voxelize(pos + 9 * t, idx, 1, &g); /* idx[0..2] = 0,1,2 */
    }
    vox = attr_run(ctx, pos, NT * 3, idx, NT, mat_ids, mats, NM, &g, 15, method, blend);
    v1 = attr_run(one, pos, NT * 3, idx, NT, mat_ids, mats, NM, &g, 15, method, blend);
    for (t = 0; t < NT; t++) perm[t] = (uint32_t)t;
    for (t = NT - 1; t > 0; t--) { int j = (int)(rnd() * (t + 1)); uint32_t x = perm[t]; perm[t] = perm[j]; perm[j] = x; }
    for (t = 0; t < NT; t++) { /* triangle t of the shuffled scene is perm[t], its corners rotated */
        for (c = 0; c < 3; c++) memcpy(shuffled + 9 * t + 3 * c, pos + 9 * perm[t] + 3 * ((c + t) % 3), 3 * sizeof(float));
        smat[t] = mat_ids[perm[t]];
    }
    vs = attr_run(ctx, shuffled, NT * 3, idx, NT, smat, mats, NM, &g, 15, method, blend);
    TH_CHECK(vox && vs && v1, "attribute voxelization failed");
    if (!vox || !vs || !v1) return;
    for (k = 0; k < 4; k++) {
        float *mine = attr_read(ctx, vox, kinds[k]), *other = attr_read(ctx, vs, kinds[k]), *single = attr_read(one, v1, kinds[k]);
        int w = k == 3 ? 1 : 3;
        voxgi_voxels_info info;
        voxgi_voxels_query(vox, &info);
        /* corners rotated cyclically: the Volume Buffer's rounding sees the same triangle, the order alone changed */
        bad_order += (uint64_t)(memcmp(mine, other, info.voxel_count * (size_t)w * 4) != 0);
        bad_order += (uint64_t)(memcmp(mine, single, info.voxel_count * (size_t)w * 4) != 0);
        slot = 0;
        for (l = 0; l < n; l++) {
            double acc[3] = {0, 0, 0};
            int cnt = 0;
            for (t = 0; t < NT; t++) {
                const voxgi_material *m = &mats[mat_ids[t]];
                if (!voxgi_bit_get(tri_bits[t], l)) continue;
                cnt++;
                for (c = 0; c < w; c++) {
                    double x;
                    if (k == 0) x = m->albedo[c];
                    else if (k == 2) x = m->emission[c];
                    else if (k == 3) x = 1.0 - m->transparency;
                    else {
                        const float *p = pos + 9 * t;
                        double e[3], f[3], nn[3], len;
                        for (a = 0; a < 3; a++) { e[a] = (double)p[3 + a] - p[a]; f[a] = (double)p[6 + a] - p[a]; }
                        for (a = 0; a < 3; a++) nn[a] = e[(a + 1) % 3] * f[(a + 2) % 3] - e[(a + 2) % 3] * f[(a + 1) % 3];
                        len = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
                        x = nn[c] / len;
                    }
                    if (blend[k] == VOXGI_BLEND_MAX) acc[c] = cnt == 1 || x > acc[c] ? x : acc[c];
                    else acc[c] += x;
                }
            }
            if (!cnt) continue;
            for (c = 0; c < w; c++) {
                double want = blend[k] == VOXGI_BLEND_AVERAGE ? acc[c] / cnt : acc[c], err = fabs(mine[slot * (uint64_t)w + (uint64_t)c] - want);
                if (err > worst[k]) worst[k] = err;
                if (k == 2 && want > esum_max) esum_max = want;
            }
            slot++;
        }
        TH_CHECK(slot == info.voxel_count, "%llu voxels with triangles, %llu set", (unsigned long long)slot, (unsigned long long)info.voxel_count);
        free(mine); free(other); free(single);
    }
    {   /* half a unit of 2^-24 of the range (times the count for sums), plus float rounding */
        double sum_units = blend[2] == VOXGI_BLEND_ADD ? NT : 1;
        TH_CHECK(worst[0] <= ldexp(1, -25) + ldexp(1, -24), "albedo off by %g", worst[0]);
        TH_CHECK(worst[1] <= ldexp(1, -24) + ldexp(1, -24) + 1e-12, "normal off by %g", worst[1]);
        TH_CHECK(worst[2] <= sum_units * erange * ldexp(1, -25) + esum_max * ldexp(1, -24), "emission off by %g (range %g)", worst[2], erange);
        TH_CHECK(worst[3] <= ldexp(1, -25) + ldexp(1, -24), "opacity off by %g", worst[3]);
        printf("    %s, blend %d%d%d%d: worst errors albedo %.3g, normal %.3g, emission %.3g (max %.4g), opacity %.3g\n",
               voxgi_method_name(method), blend[0], blend[1], blend[2], blend[3], worst[0], worst[1], worst[2], esum_max, worst[3]);
    }
    TH_CHECK(bad_order == 0, "attributes depend on triangle order or thread count (%llu arrays differ)", (unsigned long long)bad_order);
    for (t = 0; t < NT; t++) free(tri_bits[t]);
    voxgi_voxels_destroy(ctx, vox);
    voxgi_voxels_destroy(ctx, vs);
    voxgi_voxels_destroy(one, v1);
    voxgi_destroy(ctx);
    voxgi_destroy(one);
}

/* The faults of 8-bit moving averages (truncation bias, updates below one step lost, the
   counter wrapping at 256) cannot happen: 300 triangles inside one voxel, one of albedo 1 and
   299 of albedo 0, give 1/300; 300 of albedo 0.2 + 1e-6 give exactly that. */
static void test_attributes_many_small_updates(void)
{
    enum { NT = 300 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    static float pos[NT * 9];
    static uint32_t idx[NT * 3], ids[NT];
    voxgi_material mats[3] = {{{0, 0, 0}, {0, 0, 0}, 0}, {{1, 1, 1}, {0, 0, 0}, 0}, {{0.200001f, 0.200001f, 0.200001f}, {0, 0, 0}, 0}};
    static const voxgi_blend mean[4] = {VOXGI_BLEND_AVERAGE, VOXGI_BLEND_AVERAGE, VOXGI_BLEND_AVERAGE, VOXGI_BLEND_AVERAGE};
    voxgi_grid g;
    int t, c, pass;
    g.origin[0] = g.origin[1] = g.origin[2] = 0; g.voxel_size = 1; g.res[0] = g.res[1] = g.res[2] = 3;
    for (t = 0; t < NT; t++) { /* small triangles strictly inside voxel (1,1,1) */
        for (c = 0; c < 9; c++) pos[9 * t + c] = (float)(1.25 + 0.5 * rnd());
        for (c = 0; c < 3; c++) idx[3 * t + c] = (uint32_t)(3 * t + c);
    }
    for (pass = 0; pass < 2; pass++) {
        voxgi_voxels *vox;
        float *albedo;
        double want = pass == 0 ? 1.0 / NT : (double)0.200001f;
        for (t = 0; t < NT; t++) ids[t] = pass == 0 ? (t == NT / 2 ? 1u : 0u) : 2u;
        vox = attr_run(ctx, pos, NT * 3, idx, NT, ids, mats, 3, &g, VOXGI_ATTRIBUTE_ALBEDO, VOXGI_METHOD_CONSERVATIVE, mean);
        albedo = vox ? attr_read(ctx, vox, VOXGI_ATTRIBUTE_ALBEDO) : NULL;
        TH_CHECK(albedo && fabs(albedo[0] - want) <= ldexp(1, -24), "%d triangles in one voxel: albedo %.9g, want %.9g", NT,
                 albedo ? albedo[0] : -1.0, want);
        free(albedo);
        voxgi_voxels_destroy(ctx, vox);
    }
    voxgi_destroy(ctx);
}

static void test_attributes_vs_oracle_and_order(void)
{
    static const voxgi_blend mean[4] = {VOXGI_BLEND_AVERAGE, VOXGI_BLEND_AVERAGE, VOXGI_BLEND_AVERAGE, VOXGI_BLEND_AVERAGE};
    static const voxgi_blend paper[4] = {VOXGI_BLEND_MAX, VOXGI_BLEND_MAX, VOXGI_BLEND_ADD, VOXGI_BLEND_MAX};
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    check_attributes(VOXGI_METHOD_CONSERVATIVE, mean);
    check_attributes(VOXGI_METHOD_CONSERVATIVE, paper);
    check_attributes(VOXGI_METHOD_VOLUME_BUFFER, mean);
    check_attributes(VOXGI_METHOD_VOLUME_BUFFER, paper);
    {   /* refusals */
        float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, *none;
        voxgi_material mats[2] = {{{0.5f, 0.5f, 0.5f}, {0, 0, 0}, 0}, {{1.5f, 0.5f, 0.5f}, {0, 0, 0}, 0}};
        uint32_t ids[1] = {1};
        voxgi_voxelize_desc vd;
        voxgi_mesh m;
        voxgi_scene sc;
        voxgi_voxels *bad = NULL;
        memset(&vd, 0, sizeof vd);
        scene_of_triangles(&sc, &m, pos, 3, NULL, 0);
        vd.grid.voxel_size = 0.5; vd.grid.res[0] = vd.grid.res[1] = vd.grid.res[2] = 4;
        vd.attributes = VOXGI_ATTRIBUTE_ALBEDO; vd.method = VOXGI_METHOD_SLICEMAP;
        TH_CHECK(voxgi_voxelize(ctx, &sc, &vd, &bad) == VOXGI_ERR_UNSUPPORTED && !bad, "slicemap attributes accepted");
        vd.method = VOXGI_METHOD_CONSERVATIVE; vd.attributes = 16;
        TH_CHECK(voxgi_voxelize(ctx, &sc, &vd, &bad) == VOXGI_ERR_INVALID_ARGUMENT && !bad, "attribute bit 16 accepted");
        vd.attributes = 1; vd.blend[2] = (voxgi_blend)7;
        TH_CHECK(voxgi_voxelize(ctx, &sc, &vd, &bad) == VOXGI_ERR_INVALID_ARGUMENT && !bad, "blend mode 7 accepted");
        vd.blend[2] = VOXGI_BLEND_AVERAGE;
        m.material_ids = ids; sc.materials = mats; sc.material_count = 2;
        TH_CHECK(voxgi_voxelize(ctx, &sc, &vd, &bad) == VOXGI_ERR_INVALID_SCENE && !bad, "albedo 1.5 accepted");
        mats[1].albedo[0] = 0.5f;
        vd.attributes = 0;
        voxgi_voxelize(ctx, &sc, &vd, &bad);
        none = attr_read(ctx, bad, VOXGI_ATTRIBUTE_ALBEDO);
        TH_CHECK(bad && !none, "an attribute read from voxels without attributes");
        voxgi_voxels_destroy(ctx, bad);
    }
    voxgi_destroy(ctx);
}

/* ---------------------------------------------------------------- attribute volumes and mips */
static float *volume_level(voxgi_context *ctx, const voxgi_volume *vol, voxgi_attribute which, voxgi_direction dir, int level)
{
    size_t need = 0;
    float *out;
    if (voxgi_volume_read(ctx, vol, which, dir, level, NULL, 0, &need) != VOXGI_OK) return NULL;
    out = (float *)malloc(need);
    if (voxgi_volume_read(ctx, vol, which, dir, level, out, need, NULL) != VOXGI_OK) { free(out); return NULL; }
    return out;
}

/* A constant field stays constant (and full parents keep its alpha); a lone voxel keeps its
   colour at every level with alpha / 8 per level (isotropic) or / 4 (anisotropic, in every
   direction); two opaque voxels along x show the near one's colour in each direction; the
   base level of a voxelization's volume is its attribute means. */
static void test_volume_mips(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    voxgi_grid g;
    voxgi_volume_desc vd;
    voxgi_volume *vol = NULL;
    voxgi_volume_info info;
    float *albedo, *opacity;
    const float *base[4];
    size_t n, i;
    int k, dir, bad = 0;
    g.origin[0] = g.origin[1] = g.origin[2] = 0; g.voxel_size = 1;
    g.res[0] = 9; g.res[1] = 6; g.res[2] = 5; /* odd sizes: parents at the far faces lack children */
    n = (size_t)voxgi_grid_voxel_count(&g);
    albedo = (float *)malloc(n * 16);
    opacity = (float *)malloc(n * 4);
    for (i = 0; i < n; i++) { albedo[4 * i] = 0.3f; albedo[4 * i + 1] = 0.6f; albedo[4 * i + 2] = 0.9f; albedo[4 * i + 3] = 0.5f; opacity[i] = 0.5f; }
    base[0] = albedo; base[1] = NULL; base[2] = NULL; base[3] = opacity;
    memset(&vd, 0, sizeof vd);
    TH_CHECK(voxgi_volume_create_dense(ctx, &g, &vd, base, &vol) == VOXGI_OK, "dense volume: %s", voxgi_last_error(ctx));
    voxgi_volume_query(vol, &info);
    TH_CHECK(info.levels == 5, "9x6x5 has 5 levels down to one voxel, got %d", info.levels);
    for (k = 0; k < info.levels; k++) {
        float *lv = volume_level(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, 0, k), *op = volume_level(ctx, vol, VOXGI_ATTRIBUTE_OPACITY, 0, k);
        int d[3], x, y, z, a;
        for (a = 0; a < 3; a++) { d[a] = g.res[a]; for (x = 0; x < k; x++) d[a] = (d[a] + 1) / 2; }
        for (z = 0; z < d[2]; z++)
            for (y = 0; y < d[1]; y++)
                for (x = 0; x < d[0]; x++) {
                    size_t l = (size_t)x + (size_t)d[0] * ((size_t)y + (size_t)d[1] * (size_t)z);
                    int full = ((x + 1) << k) <= g.res[0] && ((y + 1) << k) <= g.res[1] && ((z + 1) << k) <= g.res[2];
                    bad += fabs(lv[4 * l] - 0.3f) > 1e-6 || fabs(lv[4 * l + 1] - 0.6f) > 1e-6 || fabs(lv[4 * l + 2] - 0.9f) > 1e-6;
                    bad += full && (fabs(lv[4 * l + 3] - 0.5f) > 1e-6 || fabs(op[l] - 0.5f) > 1e-6);
                    bad += !full && !(lv[4 * l + 3] < 0.5f && fabs(op[l] - lv[4 * l + 3]) < 1e-6);
                }
        free(lv); free(op);
    }
    TH_CHECK(bad == 0, "constant field: %d values changed through the mips", bad);
    voxgi_volume_destroy(ctx, vol);
    for (dir = -1; dir < 6; dir++) { /* a lone voxel at (5, 3, 2), red, alpha 0.8 */
        memset(albedo, 0, n * 16);
        i = 5 + 9 * (3 + 6 * 2);
        albedo[4 * i] = 1; albedo[4 * i + 3] = 0.8f;
        base[3] = NULL;
        vd.filter = dir < 0 ? VOXGI_MIPS_ISOTROPIC : VOXGI_MIPS_ANISOTROPIC;
        voxgi_volume_create_dense(ctx, &g, &vd, base, &vol);
        for (k = 0; k < 5; k++) {
            float *lv = volume_level(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, (voxgi_direction)(dir < 0 ? 0 : dir), k);
            int d0 = g.res[0], d1 = g.res[1], x;
            size_t l;
            double want = 0.8 / pow(dir < 0 ? 8.0 : 4.0, k);
            for (x = 0; x < k; x++) { d0 = (d0 + 1) / 2; d1 = (d1 + 1) / 2; }
            l = (size_t)(5 >> k) + (size_t)d0 * ((size_t)(3 >> k) + (size_t)d1 * (size_t)(2 >> k));
            bad += !lv || fabs(lv[4 * l] - 1.0f) > 1e-6 || lv[4 * l + 1] != 0 || fabs(lv[4 * l + 3] - want) > 1e-6 * want;
            free(lv);
        }
        voxgi_volume_destroy(ctx, vol);
    }
    TH_CHECK(bad == 0, "a lone voxel lost its colour or alpha in the mips (%d)", bad);
    {   /* red opaque at x = 0, blue opaque at x = 1: +x sees red, -x blue, alpha 1/4 at level 1 */
        float *px, *nx;
        memset(albedo, 0, n * 16);
        albedo[0] = 1; albedo[3] = 1;
        albedo[4 * 1 + 2] = 1; albedo[4 * 1 + 3] = 1;
        vd.filter = VOXGI_MIPS_ANISOTROPIC;
        voxgi_volume_create_dense(ctx, &g, &vd, base, &vol);
        px = volume_level(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, VOXGI_DIR_POS_X, 1);
        nx = volume_level(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, VOXGI_DIR_NEG_X, 1);
        TH_CHECK(px && nx && px[0] == 1 && px[2] == 0 && px[3] == 0.25f && nx[0] == 0 && nx[2] == 1 && nx[3] == 0.25f,
                 "anisotropic front-to-back: +x (%g %g %g %g), -x (%g %g %g %g)", px ? px[0] : -1, px ? px[1] : -1, px ? px[2] : -1,
                 px ? px[3] : -1, nx ? nx[0] : -1, nx ? nx[1] : -1, nx ? nx[2] : -1, nx ? nx[3] : -1);
        free(px); free(nx);
        TH_CHECK(voxgi_volume_read(ctx, vol, VOXGI_ATTRIBUTE_NORMAL, 0, 0, NULL, 0, &i) == VOXGI_ERR_INVALID_ARGUMENT, "absent attribute read");
        TH_CHECK(voxgi_volume_read(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, 0, 9, NULL, 0, &i) == VOXGI_ERR_INVALID_ARGUMENT, "level 9 read");
        voxgi_volume_destroy(ctx, vol);
    }
    {   /* from a voxelization: level 0 holds the attribute means at the set voxels, alpha = opacity */
        vxt_shape m;
        voxgi_mesh mesh;
        voxgi_scene sc;
        voxgi_voxelize_desc xd;
        voxgi_voxels *vox = NULL;
        voxgi_material mat = {{0.25f, 0.5f, 0.75f}, {0, 0, 0}, 0.5f};
        float *lv, *means;
        uint32_t *bits;
        size_t need = 0, slot = 0, l;
        vxt_shape_sphere(&m, 24, 12, 1.0, 0, 0, 0);
        scene_of_shape(&sc, &mesh, &m);
        scene_lighting(&sc, &mat, 1, NULL, 0);
        memset(&xd, 0, sizeof xd);
        xd.grid.origin[0] = xd.grid.origin[1] = xd.grid.origin[2] = -1.2; xd.grid.voxel_size = 0.1;
        xd.grid.res[0] = xd.grid.res[1] = xd.grid.res[2] = 24;
        xd.attributes = VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_OPACITY;
        voxgi_voxelize(ctx, &sc, &xd, &vox);
        memset(&vd, 0, sizeof vd);
        TH_CHECK(voxgi_volume_create(ctx, vox, &vd, &vol) == VOXGI_OK, "volume from voxels: %s", voxgi_last_error(ctx));
        lv = volume_level(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, 0, 0);
        means = attr_read(ctx, vox, VOXGI_ATTRIBUTE_ALBEDO);
        voxgi_voxels_read(ctx, vox, NULL, 0, &need);
        bits = (uint32_t *)malloc(need);
        voxgi_voxels_read(ctx, vox, bits, need, NULL);
        for (l = 0, bad = 0; lv && means && l < 24 * 24 * 24; l++) {
            if (!voxgi_bit_get(bits, l)) { bad += lv[4 * l + 3] != 0; continue; }
            bad += lv[4 * l] != means[3 * slot] || lv[4 * l + 2] != means[3 * slot + 2] || fabs(lv[4 * l + 3] - 0.5f) > 1e-6;
            slot++;
        }
        TH_CHECK(lv && means && bad == 0 && slot > 0, "volume base level differs from the voxels' means (%d)", bad);
        free(lv); free(means); free(bits);
        voxgi_volume_destroy(ctx, vol);
        voxgi_voxels_destroy(ctx, vox);
        vxt_shape_free(&m);
    }
    free(albedo); free(opacity);
    voxgi_destroy(ctx);
}

/* Sampling: trilinear between voxel centres and linear between levels reproduce a linear field
   (red = x) at every lod in the interior, whatever the level; beyond the grid the volume is empty. */
static void test_volume_sampling(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 1);
    voxgi_grid g;
    voxgi_volume_desc vd;
    voxgi_volume *vol = NULL;
    float *albedo, pos[3 * 200], lods[200], out[4 * 200];
    const float *base[4];
    size_t i, n;
    double worst = 0;
    g.origin[0] = g.origin[1] = g.origin[2] = 0; g.voxel_size = 1;
    g.res[0] = 32; g.res[1] = 16; g.res[2] = 16;
    n = (size_t)voxgi_grid_voxel_count(&g);
    albedo = (float *)malloc(n * 16);
    for (i = 0; i < n; i++) {
        albedo[4 * i] = (float)(i % 32) + 0.5f;
        albedo[4 * i + 1] = 0.25f; albedo[4 * i + 2] = 0.5f; albedo[4 * i + 3] = 1;
    }
    base[0] = albedo; base[1] = base[2] = base[3] = NULL;
    memset(&vd, 0, sizeof vd);
    voxgi_volume_create_dense(ctx, &g, &vd, base, &vol);
    for (i = 0; i < 200; i++) { /* lod l needs 2^l voxels of margin for its centres to straddle p */
        lods[i] = (float)(3.0 * rnd());
        pos[3 * i] = (float)(8 + 16 * rnd());
        pos[3 * i + 1] = (float)(8 + 0.1 * rnd());
        pos[3 * i + 2] = (float)(8 + 0.1 * rnd());
    }
    TH_CHECK(voxgi_volume_sample(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, 0, 200, pos, lods, out) == VOXGI_OK, "sample: %s", voxgi_last_error(ctx));
    for (i = 0; i < 200; i++) {
        double e = fabs(out[4 * i] - pos[3 * i]) + fabs(out[4 * i + 1] - 0.25) + fabs(out[4 * i + 3] - 1);
        if (e > worst) worst = e;
    }
    TH_CHECK(worst < 1e-4, "a linear field sampled off by %g", worst);
    pos[0] = -3; pos[1] = 5; pos[2] = 5; lods[0] = 0;
    voxgi_volume_sample(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, 0, 1, pos, lods, out);
    TH_CHECK(out[0] == 0 && out[3] == 0, "outside the grid: %g %g", out[0], out[3]);
    pos[0] = 0.5f; /* half way between the border and the first centre column: alpha half */
    voxgi_volume_sample(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, 0, 1, pos, lods, out);
    TH_CHECK(fabs(out[3] - 1) < 1e-6 && out[0] == 0.5f, "on the first centre: %g %g", out[0], out[3]);
    pos[0] = 0; voxgi_volume_sample(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, 0, 1, pos, lods, out);
    TH_CHECK(fabs(out[3] - 0.5) < 1e-6, "at the grid's face alpha %g, want 0.5", out[3]);
    voxgi_volume_destroy(ctx, vol);
    free(albedo);
    voxgi_destroy(ctx);
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

int main(void)
{
    TH_RUN(test_random_triangles_vs_oracle);
    TH_RUN(test_adversarial_vs_oracle);
    TH_RUN(test_big_triangles_vs_oracle);
    TH_RUN(test_mesh_vs_oracle);
    TH_RUN(test_thin_vs_oracle);
    TH_RUN(test_solid_closed_vs_inside_test);
    TH_RUN(test_solid_box_exact);
    TH_RUN(test_solid_ties);
    TH_RUN(test_solid_open_mesh_robust_modes);
    TH_RUN(test_or_mips);
    TH_RUN(test_slicemap_vs_oracle_and_relations);
    TH_RUN(test_atlas_mesh_uvs_vs_oracle);
    TH_RUN(test_atlas_auto_relations);
    TH_RUN(test_volume_buffer_vs_oracle);
    TH_RUN(test_attributes_vs_oracle_and_order);
    TH_RUN(test_attributes_many_small_updates);
    TH_RUN(test_volume_mips);
    TH_RUN(test_volume_sampling);
    TH_RUN(test_volume_and_attribute_failures);
    TH_RUN(test_svo_equals_dense);
    TH_RUN(test_offset_and_scale_invariance);
    TH_RUN(test_literal_scales);
    TH_RUN(test_thread_determinism);
    TH_RUN(test_bad_input);
    TH_RUN(test_failing_allocator);
    TH_RUN(test_cancel_and_api);
    TH_RUN(test_binvox_roundtrip);
    return th_finish();
}
