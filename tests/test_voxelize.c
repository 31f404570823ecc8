/* tests/test_voxelize.c - part 5: voxelization, CPU and GL. Every method against an independent
   brute-force evaluation of its definition (conservative, thin, the Volume Buffer and the slicemap's
   drawn voxels exactly in 128-bit integers; solid against the winding number; the atlas's points),
   the same voxels wherever the scene sits, attributes and their blend modes, OR mipmaps, voxel
   visibility (3D-DDA and the hierarchical traversal against a brute-force slab test); each GL pass
   (compute, geometry shader, raster) bit for bit its CPU twin, right after it. (The exact tests on
   arbitrary floats and double grids, in GMP rationals: tests/test_exact.c.) The GL tests skip
   (loudly) only when no GL 4.5 context can be made; VOXGI_TEST_GL=egl|osmesa picks the kind,
   VOXGI_REQUIRE_GL=1 turns a skip into a failure. */
#include "../voxgi.h"
#include "fixtures.h"
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

/* ---------------------------------------------------------------- conservative and thin on GL
   The GL conservative voxelizer equals the CPU voxelizer bit for bit (compute, and the geometry
   shader's raster pass). */

static voxgi_method g_method; /* what compare() runs */
static voxgi_solid_mode g_solid_mode;
static voxgi_axis g_axis;
static int g_atomic;
static int g_atlas_size;
static voxgi_atlas_uv g_atlas_uv;
static const float *g_uvs;

static uint32_t *run(voxgi_context *ctx, const vxt_shape *m, const voxgi_grid *g, voxgi_voxels_info *info)
{
    voxgi_voxelize_desc vd;
    memset(&vd, 0, sizeof vd);
    vd.grid = *g;
    vd.method = g_method;
    vd.solid_mode = g_solid_mode;
    vd.axis = g_axis;
    vd.atomic = g_atomic;
    vd.atlas_size = g_atlas_size;
    vd.atlas_uv = g_atlas_uv;
    return shape_bits(ctx, m, g_uvs, &vd, info);
}

/* Triangles of m whose normal has a component the double filter may not be able to sign
   (zero, or within 1e-9 of the normal's largest, from the vertices in double) or no normal at
   all: the only ones the GL compute pass is meant to hand whole to the CPU's exact referee. */
static uint64_t undecidable_normals(const vxt_shape *m)
{
    uint64_t count = 0;
    size_t t;
    for (t = 0; t < m->triangle_count; t++) {
        const float *v[3];
        double e1[3], e2[3], n[3], big;
        int a;
        for (a = 0; a < 3; a++) v[a] = m->pos + 3 * (size_t)m->idx[3 * t + a];
        for (a = 0; a < 3; a++) { e1[a] = (double)v[1][a] - v[0][a]; e2[a] = (double)v[2][a] - v[0][a]; }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        big = fmax(fabs(n[0]), fmax(fabs(n[1]), fabs(n[2])));
        count += big == 0 || fabs(n[0]) <= 1e-9 * big || fabs(n[1]) <= 1e-9 * big || fabs(n[2]) <= 1e-9 * big;
    }
    return count;
}

/* GL and CPU bits must be identical, and the GL count must equal the CPU popcount. */
static void compare_method(const vxt_shape *m, const voxgi_grid *g, const char *what)
{
    voxgi_context *cpu = make_ctx(VOXGI_BACKEND_CPU, 0), *gl = make_ctx(VOXGI_BACKEND_GL, 0);
    voxgi_voxels_info ic, ig;
    uint32_t *a, *b;
    size_t bytes = (size_t)((voxgi_grid_voxel_count(g) + 31) / 32 * 4);
    uint64_t handover_bound = undecidable_normals(m) * (g_method == VOXGI_METHOD_SOLID && g_solid_mode == VOXGI_SOLID_VOTE ? 3 : 1);
    TH_CHECK(gl != NULL, "%s: no GL voxgi context", what);
    if (!gl) { voxgi_destroy(cpu); return; }
    a = run(cpu, m, g, &ic);
    b = run(gl, m, g, &ig);
    TH_CHECK(a && b, "%s: a run failed", what);
    if (a && b) {
        size_t w, diff = 0;
        for (w = 0; w < bytes / 4; w++) diff += a[w] != b[w];
        TH_CHECK(diff == 0, "%s: %lu words differ between GL and CPU", what, (unsigned long)diff);
        TH_CHECK(ic.voxel_count == ig.voxel_count, "%s: counts %llu (CPU) vs %llu (GL)", what,
                 (unsigned long long)ic.voxel_count, (unsigned long long)ig.voxel_count);
        TH_CHECK(ic.voxel_count > 0, "%s: nothing voxelized", what);
        /* the GL pass must do the work itself: it hands over only triangles whose normal it cannot
           sign (a vote runs the solid pass along each of the three axes) */
        TH_CHECK(ig.exact_triangles <= handover_bound, "%s: %llu triangles handed to the CPU, at most %llu may be",
                 what, (unsigned long long)ig.exact_triangles, (unsigned long long)handover_bound);
        static const char *modes[3] = {"parity", "vote", "flood"};
        printf("    %s%s%s %s: %llu voxels, GL exact tests %llu, triangles handed to the CPU %llu\n", voxgi_method_name(g_method),
               g_method == VOXGI_METHOD_SOLID ? " " : "", g_method == VOXGI_METHOD_SOLID ? modes[g_solid_mode] : "", what,
               (unsigned long long)ig.voxel_count, (unsigned long long)ig.exact_tests, (unsigned long long)ig.exact_triangles);
    }
    free(a);
    free(b);
    voxgi_destroy(cpu);
    voxgi_destroy(gl);
}

/* Every exact surface method with a GL pass: conservative and thin by compute; or, from the
   raster test (rasterizing tests run apart, see tests/run.sh), the conservative set by
   geometry-shader rasterization. */
static int g_geometry;
static void compare(const vxt_shape *m, const voxgi_grid *g, const char *what)
{
    if (g_geometry) {
        g_method = VOXGI_METHOD_GEOMETRY;
        compare_method(m, g, what);
    } else
        for (g_method = VOXGI_METHOD_CONSERVATIVE; g_method <= VOXGI_METHOD_THIN; g_method = (voxgi_method)(g_method + 1))
            compare_method(m, g, what);
    g_method = VOXGI_METHOD_CONSERVATIVE;
}

static void test_gl_equals_cpu_sphere(void)
{
    vxt_shape m;
    voxgi_grid g;
    if (!have_gl()) return;
    vxt_shape_sphere(&m, 40, 28, 1.0, 0.013, -0.021, 0.007);
    cubic(&g, -1.1, 2.2, 32);
    compare(&m, &g, "sphere 32^3");
    cubic(&g, -1.1, 2.2, 100);
    compare(&m, &g, "sphere 100^3");
    g.res[0] = 70; g.res[1] = 45; g.res[2] = 33; /* non-cubic, cut through the scene */
    compare(&m, &g, "sphere 70x45x33");
    vxt_shape_free(&m);
}

/* The grid of vxt_shape_box_and_tilted's ties: half voxels from -1, every integer coordinate on
   a voxel boundary; 51 x 50 x nz. */
static void half_voxel_grid(voxgi_grid *g, int nz)
{
    g->origin[0] = g->origin[1] = g->origin[2] = -1;
    g->voxel_size = 0.5;
    g->res[0] = 51; g->res[1] = 50; g->res[2] = nz;
}

static void test_gl_equals_cpu_ties(void)
{
    vxt_shape m;
    voxgi_grid g;
    if (!have_gl()) return;
    vxt_shape_box_and_tilted(&m); /* lattice coordinates: every face on voxel boundaries */
    g.origin[0] = g.origin[1] = g.origin[2] = -1;
    g.voxel_size = 1.5;
    g.res[0] = 19; g.res[1] = 18; g.res[2] = 17;
    compare(&m, &g, "box on voxel faces");
    half_voxel_grid(&g, 52); /* every integer coordinate on a boundary */
    compare(&m, &g, "box at half voxels");
    g.origin[0] = -1.1; g.origin[1] = -0.9; g.origin[2] = -1.05; /* generic: filter with exact fallbacks */
    g.voxel_size = 0.3;
    g.res[0] = 85; g.res[1] = 80; g.res[2] = 87;
    compare(&m, &g, "box generic grid");
    vxt_shape_free(&m);
}

static void test_gl_equals_cpu_quads_and_huge(void)
{
    vxt_shape m;
    voxgi_grid g;
    if (!have_gl()) return;
    vxt_shape_quad(&m, 1); /* two triangles, each far larger than the small-triangle limit */
    m.pos[2] = 0.3f; m.pos[5] = -0.2f;
    cubic(&g, -1.05, 2.1, 256);
    compare(&m, &g, "tilted simple quad 256^3");
    /* 1024^3: about a million columns per triangle, so each pass-1 lane must keep its share
       small (llvmpipe cuts off invocations that loop too long, losing their voxels) */
    g_method = VOXGI_METHOD_THIN;
    cubic(&g, -1.05, 2.1, 1024);
    compare_method(&m, &g, "tilted simple quad 1024^3");
    g_method = VOXGI_METHOD_CONSERVATIVE;
    vxt_shape_free(&m);
    vxt_shape_quad(&m, 40);
    cubic(&g, -1.05, 2.1, 64);
    compare(&m, &g, "subdivided quad 64^3");
    vxt_shape_free(&m);
    {   /* one triangle much larger than the grid */
        vxt_shape big;
        float p[9] = {-1000, -1000, 2.25f, 3000, -1000, 3.125f, -1000, 3000, 3.875f};
        vxt_shape_alloc(&big, 3, 1);
        memcpy(big.pos, p, sizeof p);
        big.idx[0] = 0; big.idx[1] = 1; big.idx[2] = 2;
        g.origin[0] = -2; g.origin[1] = -3; g.origin[2] = 0;
        g.voxel_size = 0.0625;
        g.res[0] = 300; g.res[1] = 256; g.res[2] = 100;
        compare(&big, &g, "one huge triangle");
        vxt_shape_free(&big);
    }
}

static void test_gl_equals_cpu_degenerate(void)
{
    /* segments, points and collinear triangles go to the exact CPU path whole */
    vxt_shape m;
    voxgi_grid g;
    float p[] = {0.1f, 0.2f, 0.3f, 3.7f, 2.9f, 1.3f, 1.9f, 1.55f, 0.8f, /* collinear */
                 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f,  /* point on voxel corners */
                 0.5f, 3.5f, 0.25f, 3.5f, 0.5f, 3.75f, 0.5f, 3.5f, 0.25f}; /* segment */
    size_t i;
    if (!have_gl()) return;
    vxt_shape_alloc(&m, 9, 3);
    memcpy(m.pos, p, sizeof p);
    for (i = 0; i < 9; i++) m.idx[i] = (uint32_t)i;
    cubic(&g, 0, 4, 16);
    compare(&m, &g, "degenerate triangles");
    vxt_shape_free(&m);
}

/* The geometry-shader voxelizer on every shape of the compute tests: bit for bit the CPU's. */
static void test_gl_raster_geometry_equals_cpu(void)
{
    g_geometry = 1;
    test_gl_equals_cpu_sphere();
    test_gl_equals_cpu_ties();
    test_gl_equals_cpu_quads_and_huge();
    test_gl_equals_cpu_degenerate();
    g_geometry = 0;
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

/* Every solid mode (parity along each axis, vote, flood). */
static void compare_solid(const vxt_shape *m, const voxgi_grid *g, const char *what)
{
    g_method = VOXGI_METHOD_SOLID;
    for (g_axis = VOXGI_AXIS_X; g_axis <= VOXGI_AXIS_Z; g_axis = (voxgi_axis)(g_axis + 1)) compare_method(m, g, what);
    g_axis = VOXGI_AXIS_DEFAULT;
    g_solid_mode = VOXGI_SOLID_VOTE;
    compare_method(m, g, what);
    g_solid_mode = VOXGI_SOLID_FLOOD;
    compare_method(m, g, what);
    g_solid_mode = VOXGI_SOLID_PARITY;
    g_method = VOXGI_METHOD_CONSERVATIVE;
}

static void test_gl_equals_cpu_solid(void)
{
    vxt_shape m, big;
    voxgi_grid g;
    if (!have_gl()) return;
    vxt_shape_sphere(&m, 40, 28, 1.0, 0.013, -0.021, 0.007);
    g.origin[0] = -1.13; g.origin[1] = -1.07; g.origin[2] = -1.2;
    g.voxel_size = 0.031;
    g.res[0] = 75; g.res[1] = 70; g.res[2] = 60; /* cut through the sphere: crossings below the grid count */
    compare_solid(&m, &g, "sphere");
    vxt_shape_free(&m);
    vxt_shape_box_and_tilted(&m); /* ties: lattice box, and an open quad */
    half_voxel_grid(&g, 52);
    compare_solid(&m, &g, "box and quad");
    vxt_shape_free(&m);
    {   /* a box far larger than a few triangles' worth of columns: the big-triangle pass */
        const float lo[3] = {-0.9f, -0.8f, -0.7f}, hi[3] = {0.85f, 0.9f, 0.8f};
        vxt_shape_alloc(&big, 8, 12);
        vxt_shape_put_box(&big, 0, 0, lo, hi);
        g.origin[0] = g.origin[1] = g.origin[2] = -1.0;
        g.voxel_size = 2.0 / 96;
        g.res[0] = g.res[1] = g.res[2] = 96;
        compare_solid(&big, &g, "big box");
        vxt_shape_free(&big);
    }
    {   /* ties: faces on planes of centres, edges and face diagonals through columns' centres */
        const float lo[3] = {2, 2, 2}, hi[3] = {6, 6, 6}, lo2[3] = {1, 3, 2}, hi2[3] = {9, 5, 8};
        vxt_shape_alloc(&big, 16, 24);
        vxt_shape_put_box(&big, 0, 0, lo, hi);
        vxt_shape_put_box(&big, 8, 12, lo2, hi2);
        g.origin[0] = g.origin[1] = g.origin[2] = -0.5;
        g.voxel_size = 1;
        g.res[0] = g.res[1] = g.res[2] = 11;
        compare_solid(&big, &g, "boxes on centre planes");
        vxt_shape_free(&big);
    }
}

/* ---------------------------------------------------------------- OR mipmaps */

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

/* GL OR-reduction equals the CPU's level by level (bits and GPU popcount). */
static void test_gl_reduce_equals_cpu(void)
{
    vxt_shape m;
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi_voxelize_desc vd;
    voxgi_context *ctx[2];
    voxgi_voxels *cur[2] = {NULL, NULL};
    int b, level, variant;
    if (!have_gl()) return;
    ctx[0] = make_ctx(VOXGI_BACKEND_CPU, 0);
    ctx[1] = make_ctx(VOXGI_BACKEND_GL, 0);
    reduce_scene(&m, &sc, &mesh, &vd);
    for (variant = 0; variant < 2; variant++) {
        const int f[3] = {2, 2, variant ? 1 : 2};
        for (b = 0; b < 2; b++) TH_CHECK(voxgi_voxelize(ctx[b], &sc, &vd, &cur[b]) == VOXGI_OK, "voxelize");
        for (level = 1; level <= 6; level++) {
            voxgi_voxels *next[2];
            voxgi_voxels_info info[2];
            uint32_t *bits[2];
            size_t need = 0;
            for (b = 0; b < 2; b++) {
                TH_CHECK(voxgi_voxels_reduce(ctx[b], cur[b], f, &next[b]) == VOXGI_OK, "reduce: %s", voxgi_last_error(ctx[b]));
                voxgi_voxels_destroy(ctx[b], cur[b]);
                cur[b] = next[b];
                voxgi_voxels_query(cur[b], &info[b]);
                voxgi_voxels_read(ctx[b], cur[b], NULL, 0, &need);
                bits[b] = (uint32_t *)malloc(need);
                voxgi_voxels_read(ctx[b], cur[b], bits[b], need, NULL);
            }
            TH_CHECK(memcmp(bits[0], bits[1], need) == 0 && info[0].voxel_count == info[1].voxel_count,
                     "factor %d%d%d level %d: GL differs (%llu vs %llu voxels)", f[0], f[1], f[2], level,
                     (unsigned long long)info[0].voxel_count, (unsigned long long)info[1].voxel_count);
            free(bits[0]);
            free(bits[1]);
        }
        for (b = 0; b < 2; b++) voxgi_voxels_destroy(ctx[b], cur[b]);
    }
    vxt_shape_free(&m);
    voxgi_destroy(ctx[0]);
    voxgi_destroy(ctx[1]);
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

/* The raster slicemap on GL (logic op and atomic) equals its CPU twin bit for bit: the corners
   reach the rasterizer on its subpixel grid and the CPU samples the same rounded triangles. Shape
   3 is a bumpy sphere of 19200 small triangles at 128^3, like a scanned mesh: before the corners
   were rounded, CPU and GL split a voxel or two of such meshes (pixel centres within the
   rasterizer's snapping of an edge). Shape 2's vertices sit on the subpixel lattice (edges
   through pixel centres, horizontal and vertical ones included): the fill rules must agree. */
static void test_gl_raster_slicemap_equals_cpu(void)
{
    vxt_shape shapes[4];
    voxgi_grid g;
    int sh, variant, axis;
    size_t v;
    static const float square[] = {1.5f, 1.5f, 1.3f, 5.5f, 1.5f, 1.3f, 5.5f, 5.5f, 1.3f, 1.5f, 5.5f, 1.3f,
                                   2.5f, 2.5f, 2.6f, 6.5f, 2.5f, 2.6f, 4.5f, 6.5f, 2.6f};
    static const uint32_t square_idx[] = {0, 1, 2, 0, 2, 3, 4, 5, 6};
    if (!have_gl()) return;
    vxt_shape_sphere(&shapes[0], 40, 28, 1.0, 0.013, -0.021, 0.007);
    vxt_shape_box_and_tilted(&shapes[1]);
    vxt_shape_alloc(&shapes[2], 7, 3);
    memcpy(shapes[2].pos, square, sizeof square);
    memcpy(shapes[2].idx, square_idx, sizeof square_idx);
    vxt_shape_sphere(&shapes[3], 160, 60, 1.0, 0.0, 0.0, 0.0);
    for (v = 0; v < shapes[3].vertex_count; v++) { /* radius 1 +- 4%, in a pattern no grid lines up with */
        float *p = shapes[3].pos + 3 * v;
        double bump = 1 + 0.04 * sin(17.3 * p[0] + 3.1 * p[1]) * cos(13.7 * p[2] - 5.3 * p[0]) + 0.01 * sin(91.0 * p[1]);
        int k;
        for (k = 0; k < 3; k++) p[k] = (float)(p[k] * bump);
    }
    for (sh = 0; sh < 4; sh++)
        for (axis = VOXGI_AXIS_X; axis <= VOXGI_AXIS_Z; axis++)
            for (variant = 0; variant < 2 && (sh != 2 || axis == VOXGI_AXIS_Z); variant++) { /* the square faces z */
                voxgi_context *cpu = make_ctx(VOXGI_BACKEND_CPU, 0), *gl = make_ctx(VOXGI_BACKEND_GL, 0);
                voxgi_voxels_info ic, ig;
                uint32_t *c, *q;
                uint64_t l, n, diff = 0;
                if (sh == 0) { cubic(&g, -1.1, 2.2, 64); g.res[2] = 300; /* > 256 slices: several MRT layers */ }
                else if (sh == 1) half_voxel_grid(&g, 52);
                else if (sh == 2) cubic(&g, 0, 8, 8);
                else cubic(&g, -1.1, 2.2, 128);
                g_method = VOXGI_METHOD_SLICEMAP;
                g_axis = (voxgi_axis)axis;
                g_atomic = variant;
                c = run(cpu, &shapes[sh], &g, &ic);
                q = run(gl, &shapes[sh], &g, &ig);
                n = voxgi_grid_voxel_count(&g);
                for (l = 0; c && q && l < n; l++) diff += voxgi_bit_get(c, l) != voxgi_bit_get(q, l);
                TH_CHECK(c && q && diff == 0, "shape %d axis %d %s: %llu voxels differ", sh, axis, variant ? "atomic" : "logic op", (unsigned long long)diff);
                TH_CHECK(ic.voxel_count > 0 && ig.voxel_count > 0, "empty slicemap");
                printf("    slicemap shape %d axis %c %s: %llu voxels CPU, %llu GL, %llu differ\n", sh, "xyz"[axis - 1], variant ? "atomic" : "logic-op",
                       (unsigned long long)ic.voxel_count, (unsigned long long)ig.voxel_count, (unsigned long long)diff);
                free(c);
                free(q);
                voxgi_destroy(cpu);
                voxgi_destroy(gl);
            }
    g_method = VOXGI_METHOD_CONSERVATIVE;
    g_axis = VOXGI_AXIS_DEFAULT;
    g_atomic = 0;
    for (sh = 0; sh < 4; sh++) vxt_shape_free(&shapes[sh]);
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

/* Both atlas methods (points drawn, and one compute invocation per point) equal the CPU twin
   bit for bit: the charts' corners are on the rasterizer's subpixel grid, and the points are
   computed in double in the same order. */
static void test_gl_raster_atlas_equals_cpu(void)
{
    vxt_shape shapes[3];
    voxgi_grid g;
    int sh, c;
    float *uv;
    fx_rng rng = fx_rng_seeded(1);
    if (!have_gl()) return;
    vxt_shape_sphere(&shapes[0], 40, 28, 1.0, 0.013, -0.021, 0.007);
    vxt_shape_box_and_tilted(&shapes[1]);
    vxt_shape_alloc(&shapes[2], 90, 30); /* random triangles with random, overlapping uvs */
    uv = (float *)malloc(90 * 2 * sizeof(float));
    for (c = 0; c < 270; c++) shapes[2].pos[c] = (float)fx_rng_range(&rng, -1, 1);
    for (c = 0; c < 90; c++) shapes[2].idx[c] = (uint32_t)c;
    for (c = 0; c < 180; c++) uv[c] = (float)fx_rng_unit(&rng);
    for (sh = 0; sh < 3; sh++) {
        cubic(&g, -1.1, 2.2, sh == 1 ? 40 : 64);
        if (sh == 1) half_voxel_grid(&g, 300);
        for (g_method = VOXGI_METHOD_ATLAS; g_method <= VOXGI_METHOD_ATLAS_COMPUTE; g_method = (voxgi_method)(g_method + 1)) {
            if (sh == 2) { g_uvs = uv; g_atlas_uv = VOXGI_ATLAS_MESH; g_atlas_size = 300; }
            compare_method(&shapes[sh], &g, sh == 0 ? "sphere, default atlas" : (sh == 1 ? "box and tilted box, 300 slices" : "random triangles, mesh uvs"));
            if (sh == 0 && g_method == VOXGI_METHOD_ATLAS) { /* the atomic variant, another axis, a large atlas */
                g_atomic = 1;
                g_axis = VOXGI_AXIS_X;
                compare_method(&shapes[sh], &g, "sphere, atomic, along x");
                g_atomic = 0;
                g_axis = VOXGI_AXIS_DEFAULT;
                g_atlas_size = 4000;
                if (!FX_REDUCED) compare_method(&shapes[sh], &g, "sphere, 4000^2 atlas"); /* see FX_REDUCED */
                g_atlas_size = 0;
            }
            g_uvs = NULL; g_atlas_uv = VOXGI_ATLAS_AUTO; g_atlas_size = 0;
        }
    }
    g_method = VOXGI_METHOD_CONSERVATIVE;
    free(uv);
    for (sh = 0; sh < 3; sh++) vxt_shape_free(&shapes[sh]);
}

/* ---------------------------------------------------------------- Volume Buffer */

static uint32_t *oracle_volume_buffer(const float *pos, const uint32_t *idx, size_t ntri, const voxgi_grid *g)
{
    return oracle_drawn_along(pos, idx, ntri, g, -1);
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

/* Attribute `which` of the CPU's voxels vox[0] and the GL's vox[1]: *a and *c (malloc'd with 4
   bytes to spare: free them), *na and *nb bytes. */
static void read_attribute_twins(voxgi_context *cpu, voxgi_context *gl, voxgi_voxels *const vox[2], voxgi_attribute which, float **a, size_t *na,
                                 float **c, size_t *nb)
{
    *na = *nb = 0;
    voxgi_voxels_read_attribute(cpu, vox[0], which, NULL, 0, na);
    voxgi_voxels_read_attribute(gl, vox[1], which, NULL, 0, nb);
    *a = (float *)malloc(*na + 4);
    *c = (float *)malloc(*nb + 4);
    voxgi_voxels_read_attribute(cpu, vox[0], which, *a, *na, NULL);
    voxgi_voxels_read_attribute(gl, vox[1], which, *c, *nb, NULL);
}

/* The Volume Buffer: M2 sets the CPU twin's voxels bit for bit; M1 (sliced triangles) differs
   only by a slice, next to a CPU voxel of the same column, and rarely; attributes blended in
   float targets match the CPU's integer sums within float rounding (count * 2^-24 relative). */
static void test_gl_raster_volume_buffer(void)
{
    static const voxgi_attribute kinds[4] = {VOXGI_ATTRIBUTE_ALBEDO, VOXGI_ATTRIBUTE_NORMAL, VOXGI_ATTRIBUTE_EMISSION, VOXGI_ATTRIBUTE_OPACITY};
    static const voxgi_blend blends[2][4] = {{VOXGI_BLEND_AVERAGE, VOXGI_BLEND_AVERAGE, VOXGI_BLEND_AVERAGE, VOXGI_BLEND_AVERAGE},
                                             {VOXGI_BLEND_MAX, VOXGI_BLEND_MAX, VOXGI_BLEND_ADD, VOXGI_BLEND_MAX}};
    vxt_shape shapes[3];
    static const float tilted[] = {0.5f, 0.5f, 0.3f, 99.5f, 0.5f, 70.0f, 0.5f, 99.5f, 1.0f, 99.5f, 99.5f, 71.0f};
    static const uint32_t tilted_idx[] = {0, 1, 2, 2, 1, 3};
    voxgi_material mats[3] = {{{0.9f, 0.1f, 0.2f}, {0, 0, 0}, 0}, {{0.3f, 0.7f, 0.5f}, {40, 20, 5}, 0.25f}, {{1, 1, 1}, {0, 0, 0}, 1}};
    int sh, variant;
    if (!have_gl()) return;
    vxt_shape_sphere(&shapes[0], 40, 28, 1.0, 0.013, -0.021, 0.007);
    vxt_shape_box_and_tilted(&shapes[1]);
    vxt_shape_alloc(&shapes[2], 4, 2); /* two big triangles over ~70 slices: the 32-invocation pass */
    memcpy(shapes[2].pos, tilted, sizeof tilted);
    memcpy(shapes[2].idx, tilted_idx, sizeof tilted_idx);
    for (sh = 0; sh < 3; sh++)
        for (variant = 0; variant < 3; variant++) { /* M2 mean, M2 max/add, M1 mean */
            voxgi_context *cpu = make_ctx(VOXGI_BACKEND_CPU, 0), *gl = make_ctx(VOXGI_BACKEND_GL, 0);
            voxgi_voxels *vox[2] = {NULL, NULL};
            uint32_t *ids = material_ids_in_turn(&shapes[sh], 3), *bits[2] = {NULL, NULL};
            voxgi_voxels_info info[2];
            voxgi_grid g;
            size_t need = 0;
            uint64_t l, n, diff = 0, far = 0;
            int b, k;
            double worst = 0;
            if (sh == 0) cubic(&g, -1.1, 2.2, 48);
            else if (sh == 1) half_voxel_grid(&g, 52);
            else cubic(&g, 0, 100, 100);
            n = voxgi_grid_voxel_count(&g);
            for (b = 0; b < 2; b++) {
                voxgi_mesh mesh;
                voxgi_scene sc;
                voxgi_voxelize_desc vd;
                scene_of_materials(&sc, &mesh, &shapes[sh], ids, mats, 3);
                memset(&vd, 0, sizeof vd);
                vd.grid = g; vd.method = VOXGI_METHOD_VOLUME_BUFFER; vd.attributes = 15;
                vd.volume_slicing = variant == 2 ? 1 : 2;
                memcpy(vd.blend, blends[variant == 1], sizeof vd.blend);
                if (voxgi_voxelize(b ? gl : cpu, &sc, &vd, &vox[b]) != VOXGI_OK) { printf("    %s\n", voxgi_last_error(b ? gl : cpu)); continue; }
                voxgi_voxels_query(vox[b], &info[b]);
                voxgi_voxels_read(b ? gl : cpu, vox[b], NULL, 0, &need);
                bits[b] = (uint32_t *)malloc(need);
                voxgi_voxels_read(b ? gl : cpu, vox[b], bits[b], need, NULL);
            }
            TH_CHECK(bits[0] && bits[1], "shape %d variant %d: volume buffer failed", sh, variant);
            if (!bits[0] || !bits[1]) continue;
            for (l = 0; l < n; l++)
                if (voxgi_bit_get(bits[0], l) != voxgi_bit_get(bits[1], l)) {
                    /* M1: the CPU (exact depth) has a voxel one slice away in some axis' column */
                    int x = (int)(l % (uint64_t)g.res[0]), y = (int)(l / (uint64_t)g.res[0] % (uint64_t)g.res[1]);
                    int z = (int)(l / ((uint64_t)g.res[0] * (uint64_t)g.res[1])), d, a, near = 0;
                    diff++;
                    for (a = 0; a < 3 && !near; a++)
                        for (d = -1; d <= 1; d += 2) {
                            int v[3] = {x, y, z};
                            v[a] += d;
                            if (v[a] < 0 || v[a] >= g.res[a]) continue;
                            near |= voxgi_bit_get(bits[voxgi_bit_get(bits[0], l) ? 1 : 0],
                                                  (uint64_t)v[0] + (uint64_t)g.res[0] * ((uint64_t)v[1] + (uint64_t)g.res[1] * (uint64_t)v[2]));
                        }
                    far += (uint64_t)!near;
                }
            if (variant < 2) TH_CHECK(diff == 0, "shape %d: M2 differs from the CPU in %llu voxels", sh, (unsigned long long)diff);
            else TH_CHECK(far == 0 && diff * 100 <= info[0].voxel_count, "shape %d: M1 differs in %llu voxels, %llu not next to a CPU voxel",
                          sh, (unsigned long long)diff, (unsigned long long)far);
            for (k = 0; k < 4 && variant < 2; k++) {
                size_t na, nb, i;
                float *a, *c;
                read_attribute_twins(cpu, gl, vox, kinds[k], &a, &na, &c, &nb);
                TH_CHECK(na == nb && na > 0, "attribute sizes %lu vs %lu", (unsigned long)na, (unsigned long)nb);
                for (i = 0; na == nb && i < na / 4; i++) { /* relative to the larger of 1 and the value */
                    double e = fabs((double)a[i] - c[i]) / (fabs(a[i]) > 1 ? fabs(a[i]) : 1);
                    if (e > worst) worst = e;
                }
                free(a); free(c);
            }
            if (variant < 2) TH_CHECK(worst <= 64 * ldexp(1, -24), "shape %d: GL attributes off by %g", sh, worst);
            printf("    volume buffer %s shape %d%s: %llu voxels CPU, %llu GL, %llu differ", variant == 2 ? "M1" : "M2", sh,
                   variant == 1 ? " (max/add)" : "", (unsigned long long)info[0].voxel_count, (unsigned long long)info[1].voxel_count,
                   (unsigned long long)diff);
            if (variant < 2) printf("; attributes within %.3g (relative)", worst);
            printf("; %llu triangles in the big pass\n", (unsigned long long)info[1].big_triangles);
            if (sh == 2) TH_CHECK(info[1].big_triangles == 2 && info[1].lost_slices == 0, "big pass: %llu triangles, %llu slices lost",
                                  (unsigned long long)info[1].big_triangles, (unsigned long long)info[1].lost_slices);
            voxgi_voxels_destroy(cpu, vox[0]);
            voxgi_voxels_destroy(gl, vox[1]);
            free(bits[0]); free(bits[1]); free(ids);
            voxgi_destroy(cpu);
            voxgi_destroy(gl);
        }
    vxt_shape_free(&shapes[0]);
    vxt_shape_free(&shapes[1]);
    vxt_shape_free(&shapes[2]);
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

/* Attribute averages: GL (sums on the GPU, undecided pairs and flagged triangles on the CPU)
   equals the CPU bit for bit, since both add the same fixed-point integers. */
static void test_gl_raster_attributes_equal_cpu(void)
{
    static const voxgi_attribute kinds[4] = {VOXGI_ATTRIBUTE_ALBEDO, VOXGI_ATTRIBUTE_NORMAL, VOXGI_ATTRIBUTE_EMISSION, VOXGI_ATTRIBUTE_OPACITY};
    vxt_shape shapes[3];
    voxgi_material mats[3] = {{{0.9f, 0.1f, 0.2f}, {0, 0, 0}, 0}, {{0.3f, 0.7f, 0.5f}, {40, 20, 5}, 0.25f}, {{1, 1, 1}, {0, 0, 0}, 1}};
    int sh, method, k0;
    fx_rng rng = fx_rng_seeded(2);
    if (!have_gl()) return;
    vxt_shape_sphere(&shapes[0], 40, 28, 1.0, 0.013, -0.021, 0.007);
    vxt_shape_box_and_tilted(&shapes[1]); /* big triangles: the row-chunk pass */
    vxt_shape_alloc(&shapes[2], 900, 300); /* 300 small triangles inside one voxel: no counter wraps */
    for (k0 = 0; k0 < 2700; k0++) shapes[2].pos[k0] = (float)fx_rng_range(&rng, 1.25, 1.75);
    for (k0 = 0; k0 < 900; k0++) shapes[2].idx[k0] = (uint32_t)k0;
    for (sh = 0; sh < 3; sh++)
        for (method = 0; method < 3; method++) {
            static const voxgi_method methods[3] = {VOXGI_METHOD_CONSERVATIVE, VOXGI_METHOD_THIN, VOXGI_METHOD_GEOMETRY};
            voxgi_context *cpu = make_ctx(VOXGI_BACKEND_CPU, 0), *gl = make_ctx(VOXGI_BACKEND_GL, 0);
            voxgi_voxels *vox[2] = {NULL, NULL};
            uint32_t *ids = material_ids_in_turn(&shapes[sh], 3);
            voxgi_grid g;
            int b, k, same = 1;
            if (sh == 0) cubic(&g, -1.1, 2.2, 48);
            else if (sh == 1) half_voxel_grid(&g, 52);
            else cubic(&g, 0, 3, 3);
            for (b = 0; b < 2; b++) {
                voxgi_mesh mesh;
                voxgi_scene sc;
                voxgi_voxelize_desc vd;
                scene_of_materials(&sc, &mesh, &shapes[sh], ids, mats, 3);
                memset(&vd, 0, sizeof vd);
                vd.grid = g; vd.method = methods[method]; vd.attributes = 15;
                if (voxgi_voxelize(b ? gl : cpu, &sc, &vd, &vox[b]) != VOXGI_OK) printf("    %s\n", voxgi_last_error(b ? gl : cpu));
            }
            TH_CHECK(vox[0] && vox[1], "shape %d: attribute voxelization failed", sh);
            for (k = 0; k < 4 && vox[0] && vox[1]; k++) {
                size_t na, nb;
                float *a, *c;
                read_attribute_twins(cpu, gl, vox, kinds[k], &a, &na, &c, &nb);
                same = same && na == nb && na > 0 && memcmp(a, c, na) == 0;
                free(a); free(c);
            }
            TH_CHECK(same, "shape %d %s: GL attributes differ from the CPU's", sh, voxgi_method_name(methods[method]));
            if (vox[1]) {
                voxgi_voxels_info info;
                voxgi_voxels_query(vox[1], &info);
                printf("    attributes shape %d %s: %llu voxels, %llu (triangle, voxel) pairs averaged, GL == CPU\n", sh,
                       voxgi_method_name(methods[method]), (unsigned long long)info.voxel_count, (unsigned long long)info.attribute_pairs);
            }
            voxgi_voxels_destroy(cpu, vox[0]);
            voxgi_voxels_destroy(gl, vox[1]);
            free(ids);
            voxgi_destroy(cpu);
            voxgi_destroy(gl);
        }
    vxt_shape_free(&shapes[0]);
    vxt_shape_free(&shapes[1]);
    vxt_shape_free(&shapes[2]);
}

/* ---------------------------------------------------------------- voxel visibility */

/* Voxel visibility: on the voxels of 40 random triangles in a 24 x 17 x 30 grid, 20000 random
   segments inside, across and beside it are blocked by 3D-DDA exactly when by the hierarchical
   traversal of the OR mipmaps, and exactly when a brute-force slab test finds an occupied voxel
   whose box they cross; the hierarchy visits fewer cells than DDA voxels. Beyond the grid nothing
   blocks. */
static void test_voxel_visibility(void)
{
    enum { T = 40, N = 20000 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_voxelize_desc vd;
    voxgi_voxels *vox = NULL;
    static float tri[9 * T], from[3 * N], to[3 * N];
    static unsigned char dda[N], hier[N];
    uint32_t *bits;
    size_t bytes;
    uint64_t steps_dda = 0, steps_hier = 0;
    fx_rng g = fx_rng_seeded(17);
    int i, a, wrong = 0, disagree = 0, blocked = 0;
    const int res[3] = {24, 17, 30};
    for (i = 0; i < 9 * T; i++) tri[i] = (float)fx_rng_range(&g, 0.5, res[i % 3] - 0.5);
    for (i = 0; i < T; i++) /* small triangles: a corner and two near it */
        for (a = 3; a < 9; a++) tri[9 * i + a] = tri[9 * i + a % 3] + (float)fx_rng_range(&g, -2.5, 2.5);
    scene_of_triangles(&sc, &mesh, tri, 3 * T, NULL, 0);
    memset(&vd, 0, sizeof vd);
    vd.grid.voxel_size = 1;
    for (a = 0; a < 3; a++) vd.grid.res[a] = res[a];
    TH_CHECK(voxgi_voxelize(ctx, &sc, &vd, &vox) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    voxgi_voxels_read(ctx, vox, NULL, 0, &bytes);
    bits = (uint32_t *)malloc(bytes);
    voxgi_voxels_read(ctx, vox, bits, bytes, NULL);
    for (i = 0; i < 3 * N; i++) {
        from[i] = (float)fx_rng_range(&g, -3, res[i % 3] + 3);
        to[i] = (float)fx_rng_range(&g, -3, res[i % 3] + 3);
    }
    TH_CHECK(voxgi_voxels_occluded(ctx, vox, VOXGI_TRAVERSAL_DDA, N, from, to, dda, &steps_dda) == VOXGI_OK &&
                 voxgi_voxels_occluded(ctx, vox, VOXGI_TRAVERSAL_HIERARCHICAL, N, from, to, hier, &steps_hier) == VOXGI_OK,
             "%s", voxgi_last_error(ctx));
    for (i = 0; i < N; i++) { /* brute force */
        double o[3], d[3];
        int x, y, z, hit = 0;
        for (a = 0; a < 3; a++) { o[a] = from[3 * i + a]; d[a] = (double)to[3 * i + a] - o[a]; }
        for (z = 0; z < res[2] && !hit; z++)
            for (y = 0; y < res[1] && !hit; y++)
                for (x = 0; x < res[0] && !hit; x++) {
                    double t0 = 0, t1 = 1;
                    int c[3];
                    if (!voxgi_bit_get(bits, (uint64_t)x + (uint64_t)res[0] * ((uint64_t)y + (uint64_t)res[1] * (uint64_t)z))) continue;
                    c[0] = x; c[1] = y; c[2] = z;
                    for (a = 0; a < 3; a++) {
                        double ta = (c[a] - o[a]) / d[a], tb = (c[a] + 1 - o[a]) / d[a];
                        if (ta > tb) { double q = ta; ta = tb; tb = q; }
                        if (ta > t0) t0 = ta;
                        if (tb < t1) t1 = tb;
                    }
                    hit = t1 - t0 > 1e-9;
                }
        blocked += hit;
        wrong += dda[i] != hit;
        disagree += dda[i] != hier[i];
    }
    printf("    %d segments (%d blocked): DDA %d off the brute force, hierarchical %d off DDA; %llu voxels by DDA, %llu cells by the hierarchy\n", N,
           blocked, wrong, disagree, (unsigned long long)steps_dda, (unsigned long long)steps_hier);
    TH_CHECK(wrong == 0 && disagree == 0 && blocked > N / 10 && blocked < N - N / 10, "the traversals disagree");
    TH_CHECK(steps_hier < steps_dda, "the hierarchy visits more");
    {   /* beside the grid: nothing blocks, whatever lies at its border */
        float f[3] = {-5, 3, 3}, t[3] = {-1, 10, 20};
        unsigned char b = 1;
        TH_CHECK(voxgi_voxels_occluded(ctx, vox, VOXGI_TRAVERSAL_HIERARCHICAL, 1, f, t, &b, NULL) == VOXGI_OK && b == 0, "outside the grid");
        f[1] = NAN;
        TH_CHECK(voxgi_voxels_occluded(ctx, vox, VOXGI_TRAVERSAL_DDA, 1, f, t, &b, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "a NaN segment");
        f[1] = 3;
        TH_CHECK(voxgi_voxels_occluded(ctx, vox, VOXGI_TRAVERSAL_NONE, 1, f, t, &b, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "no traversal: accepted");
    }
    free(bits);
    voxgi_voxels_destroy(ctx, vox);
    voxgi_destroy(ctx);
}

int main(void)
{
    gl_open();
    TH_RUN(test_random_triangles_vs_oracle);
    TH_RUN(test_adversarial_vs_oracle);
    TH_RUN(test_big_triangles_vs_oracle);
    TH_RUN(test_mesh_vs_oracle);
    TH_RUN(test_thin_vs_oracle);
    TH_RUN(test_gl_equals_cpu_sphere);
    TH_RUN(test_gl_equals_cpu_ties);
    TH_RUN(test_gl_equals_cpu_quads_and_huge);
    TH_RUN(test_gl_equals_cpu_degenerate);
    TH_RUN(test_gl_raster_geometry_equals_cpu);
    TH_RUN(test_solid_closed_vs_inside_test);
    TH_RUN(test_solid_box_exact);
    TH_RUN(test_solid_ties);
    TH_RUN(test_solid_open_mesh_robust_modes);
    TH_RUN(test_gl_equals_cpu_solid);
    TH_RUN(test_or_mips);
    TH_RUN(test_gl_reduce_equals_cpu);
    TH_RUN(test_slicemap_vs_oracle_and_relations);
    TH_RUN(test_gl_raster_slicemap_equals_cpu);
    TH_RUN(test_atlas_mesh_uvs_vs_oracle);
    TH_RUN(test_atlas_auto_relations);
    TH_RUN(test_gl_raster_atlas_equals_cpu);
    TH_RUN(test_volume_buffer_vs_oracle);
    TH_RUN(test_gl_raster_volume_buffer);
    TH_RUN(test_attributes_vs_oracle_and_order);
    TH_RUN(test_attributes_many_small_updates);
    TH_RUN(test_gl_raster_attributes_equal_cpu);
    TH_RUN(test_offset_and_scale_invariance);
    TH_RUN(test_literal_scales);
    TH_RUN(test_voxel_visibility);
    gl_close();
    return th_finish();
}
