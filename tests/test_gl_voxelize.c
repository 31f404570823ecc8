/* The GL conservative voxelizer equals the CPU voxelizer bit for bit, on a real headless GL 4.5
   context (EGL surfaceless or OSMesa, llvmpipe). Also: the loader table and backend choice
   (shader error reporting and the GPU-built octree, which call private helpers, are tested in
   tests/test_internals.c). Skips (loudly) only when no GL 4.5 context can be made;
   VOXGI_TEST_GL=egl|osmesa picks the kind, VOXGI_REQUIRE_GL=1 turns a skip into a failure. */
#include "../voxgi.h"
#include "fixtures.h"
#include "cone_points.h"
#include <ctype.h>

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

/* How far GL cones may be from the CPU's, relative to the mean irradiance (occlusion: absolute).
   Both march in float32 (2^-24 per operation; GLSL's exp2 and log2 within 3 ulp), at most a few
   hundred samples of some ten operations each on these grids: S * 30 * 2^-24 < 1e-4 for S < 300.
   That holds where the texture filter computes in float, as llvmpipe's does; a GPU may quantise
   its filter weights to 8 bits, which moves each lerp by up to 2^-9 of its two values' difference:
   there 2^-8 of the mean. */
static double cone_tolerance(void)
{
    return g_gl && strstr(vxt_gl_renderer(g_gl), "llvmpipe") ? 1e-4 : 1.0 / 256;
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

/* The grid of vxt_shape_box_and_tilted's ties: half voxels from -1, every integer coordinate on
   a voxel boundary; 51 x 50 x nz. */
static void half_voxel_grid(voxgi_grid *g, int nz)
{
    g->origin[0] = g->origin[1] = g->origin[2] = -1;
    g->voxel_size = 0.5;
    g->res[0] = 51; g->res[1] = 50; g->res[2] = nz;
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

/* Attribute volumes and their mips: GL (3D textures, compute mips) equals the CPU's arrays
   within float rounding (1e-6 relative) at every level, isotropic and in all six directions. */
static void test_gl_volume_mips_equal_cpu(void)
{
    static const voxgi_attribute kinds[4] = {VOXGI_ATTRIBUTE_ALBEDO, VOXGI_ATTRIBUTE_NORMAL, VOXGI_ATTRIBUTE_EMISSION, VOXGI_ATTRIBUTE_OPACITY};
    voxgi_context *cpu, *gl;
    material_sphere s;
    voxgi_voxelize_desc xd;
    voxgi_voxels *vox[2] = {NULL, NULL};
    int filter, b;
    double worst = 0;
    if (!have_gl()) return;
    cpu = make_ctx(VOXGI_BACKEND_CPU, 0);
    gl = make_ctx(VOXGI_BACKEND_GL, 0);
    material_sphere_make(&s);
    memset(&xd, 0, sizeof xd);
    cubic(&xd.grid, -1.1, 2.2, 27); /* odd: incomplete parents at the far faces */
    xd.attributes = 15;
    for (b = 0; b < 2; b++) voxgi_voxelize(b ? gl : cpu, &s.scene, &xd, &vox[b]);
    TH_CHECK(vox[0] && vox[1], "voxelization failed");
    for (filter = 0; filter < 2 && vox[0] && vox[1]; filter++) {
        voxgi_volume_desc vd;
        voxgi_volume *vol[2] = {NULL, NULL};
        voxgi_volume_info info;
        int k, d, a;
        unsigned int tex = 0;
        memset(&vd, 0, sizeof vd);
        vd.filter = (voxgi_mip_filter)filter;
        for (b = 0; b < 2; b++)
            if (voxgi_volume_create(b ? gl : cpu, vox[b], &vd, &vol[b]) != VOXGI_OK) printf("    %s\n", voxgi_last_error(b ? gl : cpu));
        TH_CHECK(vol[0] && vol[1], "volume creation failed");
        if (!vol[0] || !vol[1]) continue;
        voxgi_volume_query(vol[1], &info);
        TH_CHECK(voxgi_volume_gl_texture(gl, vol[1], VOXGI_ATTRIBUTE_ALBEDO, 0, &tex) == VOXGI_OK && tex != 0, "no GL texture");
        for (a = 0; a < 4; a++)
            for (d = 0; d < (filter ? 6 : 1); d++)
                for (k = 0; k < info.levels; k++) {
                    size_t na = 0, nb = 0, i;
                    float *x, *y;
                    voxgi_volume_read(cpu, vol[0], kinds[a], (voxgi_direction)d, k, NULL, 0, &na);
                    voxgi_volume_read(gl, vol[1], kinds[a], (voxgi_direction)d, k, NULL, 0, &nb);
                    x = (float *)malloc(na); y = (float *)malloc(nb);
                    voxgi_volume_read(cpu, vol[0], kinds[a], (voxgi_direction)d, k, x, na, NULL);
                    voxgi_volume_read(gl, vol[1], kinds[a], (voxgi_direction)d, k, y, nb, NULL);
                    TH_CHECK(na == nb, "level sizes differ");
                    for (i = 0; na == nb && i < na / 4; i++) {
                        double e = fabs((double)x[i] - y[i]) / (fabs(x[i]) > 1 ? fabs(x[i]) : 1);
                        if (e > worst) worst = e;
                    }
                    free(x); free(y);
                }
        printf("    volume %s: %d levels, %lu bytes, GL within %.3g of the CPU\n", filter ? "anisotropic" : "isotropic", info.levels,
               (unsigned long)info.bytes, worst);
        for (b = 0; b < 2; b++) voxgi_volume_destroy(b ? gl : cpu, vol[b]);
    }
    TH_CHECK(worst <= 1e-6, "GL mips differ from the CPU's by %g", worst);
    for (b = 0; b < 2; b++) voxgi_voxels_destroy(b ? gl : cpu, vox[b]);
    material_sphere_free(&s);
    voxgi_destroy(cpu);
    voxgi_destroy(gl);
}

/* The GLSL sampler (hardware trilinear between levels on the padded textures) against the
   CPU's, on a non-power-of-two volume with structure, at random points inside and around the
   grid and random lods: equal within the rasterizer's filter precision. */
static void test_gl_volume_sampling_equals_cpu(void)
{
    voxgi_context *cpu, *gl;
    voxgi_grid g;
    voxgi_volume_desc vd;
    voxgi_volume *vol[2] = {NULL, NULL};
    const float *base[4];
    float *albedo, *opacity, pos[3 * 1000], lods[1000], out[2][4 * 1000];
    size_t i, n;
    int b, f;
    double worst = 0;
    fx_rng rng = fx_rng_seeded(3);
    if (!have_gl()) return;
    cpu = make_ctx(VOXGI_BACKEND_CPU, 0);
    gl = make_ctx(VOXGI_BACKEND_GL, 0);
    g.origin[0] = g.origin[1] = g.origin[2] = 0; g.voxel_size = 1;
    g.res[0] = 21; g.res[1] = 13; g.res[2] = 10;
    n = (size_t)voxgi_grid_voxel_count(&g);
    albedo = (float *)malloc(n * 16);
    opacity = (float *)malloc(n * 4);
    for (i = 0; i < n; i++) {
        int x = (int)(i % 21), y = (int)(i / 21 % 13), z = (int)(i / 273);
        int set = (x * 7 + y * 3 + z * 5) % 4 != 0;
        albedo[4 * i] = set ? (float)x / 21 : 0; albedo[4 * i + 1] = set ? (float)y / 13 : 0;
        albedo[4 * i + 2] = set ? (float)z / 10 : 0; albedo[4 * i + 3] = set ? 0.25f + 0.75f * (float)((x + y) % 3) / 2 : 0;
        opacity[i] = albedo[4 * i + 3];
    }
    base[0] = albedo; base[1] = base[2] = NULL; base[3] = opacity;
    for (i = 0; i < 1000; i++) {
        pos[3 * i] = (float)fx_rng_range(&rng, -2, 23);
        pos[3 * i + 1] = (float)fx_rng_range(&rng, -2, 15);
        pos[3 * i + 2] = (float)fx_rng_range(&rng, -2, 12);
        lods[i] = (float)fx_rng_range(&rng, -0.5, 5.5);
    }
    for (f = 0; f < 2; f++) {
        memset(&vd, 0, sizeof vd);
        vd.filter = (voxgi_mip_filter)f;
        for (b = 0; b < 2; b++) {
            voxgi_volume_create_dense(b ? gl : cpu, &g, &vd, base, &vol[b]);
            TH_CHECK(vol[b] && voxgi_volume_sample(b ? gl : cpu, vol[b], VOXGI_ATTRIBUTE_ALBEDO, (voxgi_direction)(f ? 3 : 0), 1000, pos, lods,
                                                   out[b]) == VOXGI_OK, "sampling failed: %s", voxgi_last_error(b ? gl : cpu));
        }
        for (i = 0; i < 4000; i++) {
            double e = fabs((double)out[0][i] - out[1][i]);
            if (e > worst) worst = e;
        }
        for (b = 0; b < 2; b++) voxgi_volume_destroy(b ? gl : cpu, vol[b]);
    }
    printf("    GL sampling within %.3g of the CPU's (values in [0,1])\n", worst);
    TH_CHECK(worst <= 1e-3, "GL sampling differs from the CPU's by %g", worst);
    free(albedo); free(opacity);
    voxgi_destroy(cpu);
    voxgi_destroy(gl);
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

/* A loader that lacks one entry point: GL fails naming it, AUTO falls back to the CPU. */
static voxgi_gl_proc loader_without_indirect(const char *name, void *user)
{
    if (strcmp(name, "glDispatchComputeIndirect") == 0) return NULL;
    return vxt_gl_get_proc(name, user);
}
static char g_log[1024];
static void keep_log(voxgi_log_level l, const char *msg, void *u) { (void)l; (void)u; snprintf(g_log, sizeof g_log, "%s", msg); }

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

/* A scene voxelized (albedo, normal) on a fitted grid of res voxels with `padding` empty ones
   around it and lit (voxgi_inject_light with id); 1 when it all worked, else the error is printed. */
static int lit_voxels_padded(voxgi_context *ctx, const voxgi_scene *sc, int res, int padding, const voxgi_inject_desc *id, voxgi_voxels **vx,
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

static int lit_voxels(voxgi_context *ctx, const voxgi_scene *sc, int res, const voxgi_inject_desc *id, voxgi_voxels **vx, voxgi_volume **vol)
{
    return lit_voxels_padded(ctx, sc, res, 1, id, vx, vol);
}

/* Light injection on GL (distance maps, a gather per voxel) against the CPU's exact shadow rays
   on the same voxels: where a voxel is lit or dark alike, both are the same analytic irradiance
   (within float rounding); they differ only within a map texel or two of a shadow's edge, and
   for area lights and emitters by their sampling (fixed stratified points on GL, random per
   voxel on the CPU). Checked: the share of voxels that agree to 1e-4, and the total power. */
static void test_gl_raster_injection_matches_cpu(void)
{
    static const char *const scenes[2] = {"rsm-walls", "cornell-box"};
    voxgi_context *ctx[2];
    int sc, b;
    if (!have_gl()) return;
    ctx[0] = make_ctx(VOXGI_BACKEND_CPU, 0);
    ctx[1] = make_ctx(VOXGI_BACKEND_GL, 0);
    for (sc = 0; sc < 2; sc++) {
        voxgi_builtin_scene bs;
        float *rad[2] = {NULL, NULL};
        size_t need = 0, i, n, agree = 0, set = 0, far = 0;
        double power[2] = {0, 0};
        voxgi_builtin_scene_create(ctx[0], scenes[sc], &bs);
        for (b = 0; b < 2; b++) {
            voxgi_inject_desc id;
            voxgi_voxels *vx;
            voxgi_volume *vol;
            memset(&id, 0, sizeof id);
            id.samples = 64;
            TH_CHECK(lit_voxels(ctx[b], &bs.scene, 48, &id, &vx, &vol) &&
                     voxgi_volume_read(ctx[b], vol, VOXGI_ATTRIBUTE_RADIANCE, VOXGI_DIR_POS_X, 0, NULL, 0, &need) == VOXGI_OK,
                     "%s: %s", b ? "GL" : "CPU", voxgi_last_error(ctx[b]));
            rad[b] = (float *)malloc(need ? need : 4);
            TH_CHECK(voxgi_volume_read(ctx[b], vol, VOXGI_ATTRIBUTE_RADIANCE, VOXGI_DIR_POS_X, 0, rad[b], need, NULL) == VOXGI_OK, "read");
            voxgi_volume_destroy(ctx[b], vol);
            voxgi_voxels_destroy(ctx[b], vx);
        }
        n = need / 16;
        for (i = 0; i < n; i++) {
            double d = 0, m = 0;
            int c;
            if (rad[0][4 * i + 3] == 0) continue;
            set++;
            for (c = 0; c < 3; c++) {
                d = fmax(d, fabs((double)rad[0][4 * i + c] - rad[1][4 * i + c]));
                m = fmax(m, fabs(rad[0][4 * i + c]));
                power[0] += rad[0][4 * i + c];
                power[1] += rad[1][4 * i + c];
            }
            agree += d <= 1e-4 * fmax(m, 1e-3);
            far += d > 0.5 * fmax(m, 1e-3);
        }
        printf("    %s 48^3: %lu of %lu voxels lit alike (to 1e-4), %lu differ by more than half, total radiance GL / CPU %.4f\n", scenes[sc],
               (unsigned long)agree, (unsigned long)set, (unsigned long)far, power[1] / power[0]);
        TH_CHECK(set > 1000 && fabs(power[1] / power[0] - 1) < (sc ? 0.03 : 0.01), "%s: power ratio %.4f", scenes[sc], power[1] / power[0]);
        if (sc == 0) /* measured: 98.6% alike; 1.4% differ by more than half, along the shadows' edges (a texel of about 0.7 voxels) */
            TH_CHECK(agree > 0.95 * set && far < 0.03 * set, "two spheres: %lu of %lu voxels agree, %lu far off", (unsigned long)agree, (unsigned long)set,
                     (unsigned long)far);
        free(rad[0]);
        free(rad[1]);
        voxgi_builtin_scene_destroy(ctx[0], &bs);
    }
    voxgi_destroy(ctx[0]);
    voxgi_destroy(ctx[1]);
}

/* The leak room on GL (distance maps, the GL mips and cones), as on the CPU (test_vct): inside
   its closed box at most 0.1% of the room view's mean and no pixel above 1%, at 32^3 and 128^3
   (at 32^3 in the reduced builds, FX_REDUCED: the same paths). */
static void test_gl_raster_leak_room(void)
{
    voxgi_context *ctx;
    int res;
    if (!have_gl()) return;
    ctx = make_ctx(VOXGI_BACKEND_GL, 0);
    for (res = 32; res <= (FX_REDUCED ? 32 : 128); res *= 4) {
        double m = 1, x = 1;
        TH_CHECK(leak_room_ratios(ctx, res, VOXGI_MIPS_ANISOTROPIC, 0, 0, &m, &x) == 0, "render: %s", voxgi_last_error(ctx));
        printf("    GL leak room %3d^3: inside mean %.4f%%, largest %.3f%% of the room view's mean\n", res, 100 * m, 100 * x);
        TH_CHECK(m <= 0.001 && x <= 0.01, "%d^3: mean %.4f%%, largest %.3f%%", res, 100 * m, 100 * x);
    }
    voxgi_destroy(ctx);
}

/* The held-out closed spaces on GL, as on the CPU (test_vct): the rooms split by a zero-thickness
   wall at 32^3 and 95^3, full GI at 32^3, from an octree; the box on the floor with full GI. */
static void test_gl_raster_held_out_closed_spaces(void)
{
    static const struct { int kind; int res; voxgi_vct_radiance radiance; int bounces; } cases[] = {
        {HELD_ROOMS, 32, VOXGI_VCT_ANISOTROPIC, 1}, {HELD_ROOMS, 95, VOXGI_VCT_ANISOTROPIC, 1}, {HELD_ROOMS, 32, VOXGI_VCT_ANISOTROPIC, -1},
        {HELD_ROOMS, 32, VOXGI_VCT_OCTREE, 1},      {HELD_BOX, 32, VOXGI_VCT_ANISOTROPIC, -1}};
    voxgi_context *ctx;
    size_t k;
    if (!have_gl()) return;
    ctx = make_ctx(VOXGI_BACKEND_GL, 0);
    for (k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        double m = 1, x = 1;
        if (FX_REDUCED && cases[k].res > 32) continue;
        TH_CHECK(held_ratios(ctx, cases[k].kind, 0, cases[k].res, cases[k].radiance, cases[k].bounces, &m, &x) == 0, "render: %s", voxgi_last_error(ctx));
        printf("    GL %s %3d^3%s%s: dark mean %.4f%%, largest %.3f%% of the lit view's mean\n", cases[k].kind == HELD_ROOMS ? "rooms" : "box", cases[k].res,
               cases[k].radiance == VOXGI_VCT_OCTREE ? ", octree" : "", cases[k].bounces < 0 ? ", full GI" : "", 100 * m, 100 * x);
        TH_CHECK(m <= 0.001 && x <= 0.01, "case %lu: mean %.4f%%, largest %.3f%%", (unsigned long)k, 100 * m, 100 * x);
    }
    voxgi_destroy(ctx);
}

/* The leak box on GL (distance maps, the GL mips and cones), as on the CPU (test_vct): inside at
   most 0.1% of the lit ground's radiance and no pixel above 1%, sun with a point light and with
   a rectangular light, at 32^3 and 128^3 (32^3 alone in the reduced builds), and from an octree. */
static void test_gl_raster_leak_box(void)
{
    voxgi_context *ctx;
    int res, area;
    if (!have_gl()) return;
    ctx = make_ctx(VOXGI_BACKEND_GL, 0);
    for (area = 0; area < 2; area++)
        for (res = 32; res <= (FX_REDUCED ? 32 : 128); res *= 4) {
            double m = 1, x = 1;
            TH_CHECK(leak_box_ratios(ctx, res, VOXGI_MIPS_ANISOTROPIC, 0, area, &m, &x) == 0, "render: %s", voxgi_last_error(ctx));
            printf("    GL leak box %3d^3 (sun and %s light): inside mean %.4f%%, largest %.3f%% of the lit ground's\n", res,
                   area ? "rectangular" : "point", 100 * m, 100 * x);
            TH_CHECK(m <= 0.001 && x <= 0.01, "%d^3: mean %.4f%%, largest %.3f%%", res, 100 * m, 100 * x);
        }
    {
        double m = 1, x = 1;
        TH_CHECK(leak_box_ratios(ctx, 64, VOXGI_MIPS_ISOTROPIC, 1, 0, &m, &x) == 0, "render: %s", voxgi_last_error(ctx));
        printf("    GL leak box  64^3 (sun and point light), octree: inside mean %.4f%%, largest %.3f%% of the lit ground's\n", 100 * m, 100 * x);
        TH_CHECK(m <= 0.001 && x <= 0.01, "octree: mean %.4f%%, largest %.3f%%", 100 * m, 100 * x);
    }
    voxgi_destroy(ctx);
}

/* The leak box with a lamp inside its closed box as well (lights: 3, the scene's two and the lamp). */
static voxgi_result leak_box_with_lamp(voxgi_context *ctx, voxgi_builtin_scene *box, voxgi_light lights[3])
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

/* The caller's G-buffer as GL textures (voxgi_cone_trace_gl): positions and normals in RGBA32F
   textures, the result in the caller's RGBA32F texture equals voxgi_cone_trace on the same
   points (the positions go to grid units in float on the GPU instead of double: within 1e-4);
   a pixel without a normal is written 0; with an albedo texture and an RGBA16F target the
   result is albedo / pi x irradiance within half precision. */
typedef void (*vx_create_textures)(unsigned int, int, unsigned int *);
typedef void (*vx_texture_storage_2d)(unsigned int, int, unsigned int, int, int);
typedef void (*vx_texture_sub_image_2d)(unsigned int, int, int, int, int, int, unsigned int, unsigned int, const void *);
typedef void (*vx_get_texture_image)(unsigned int, int, unsigned int, unsigned int, int, void *);
typedef void (*vx_delete_textures)(int, const unsigned int *);

static void test_gl_raster_gbuffer_textures(void)
{
    enum { W = 20, H = 15, N = W * H };
    voxgi_context *ctx;
    voxgi_builtin_scene bs;
    voxgi_inject_desc id;
    voxgi_cone_desc cd;
    voxgi_voxels *vx = NULL;
    voxgi_volume *vol = NULL;
    voxgi_gl_gbuffer gb;
    vx_create_textures create;
    vx_texture_storage_2d storage;
    vx_texture_sub_image_2d sub;
    vx_get_texture_image get;
    vx_delete_textures del;
    static float pos[3 * N], nrm[3 * N], irr[3 * N], occ[N], tex_in[3][4 * N], out[4 * N];
    unsigned int tex[5];
    double worst = 0, worst_occ = 0, worst_albedo = 0, mean = 0;
    int i, a;
    fx_rng rng = fx_rng_seeded(11);
    if (!have_gl()) return;
    create = (vx_create_textures)vxt_gl_get_proc("glCreateTextures", g_gl);
    storage = (vx_texture_storage_2d)vxt_gl_get_proc("glTextureStorage2D", g_gl);
    sub = (vx_texture_sub_image_2d)vxt_gl_get_proc("glTextureSubImage2D", g_gl);
    get = (vx_get_texture_image)vxt_gl_get_proc("glGetTextureImage", g_gl);
    del = (vx_delete_textures)vxt_gl_get_proc("glDeleteTextures", g_gl);
    TH_CHECK(create && storage && sub && get && del, "GL texture functions");
    if (!create || !storage || !sub || !get || !del) return;
    ctx = make_ctx(VOXGI_BACKEND_GL, 0);
    voxgi_builtin_scene_create(ctx, "cornell-box", &bs);
    memset(&id, 0, sizeof id);
    memset(&cd, 0, sizeof cd);
    TH_CHECK(lit_voxels(ctx, &bs.scene, 32, &id, &vx, &vol), "lit voxels");
    for (i = 0; i < N; i++)
        for (a = 0; a < 3; a++) {
            pos[3 * i + a] = (float)fx_rng_range(&rng, 0.03, 0.53);
            nrm[3 * i + a] = i == 0 ? 0.0f : (float)fx_rng_range(&rng, -1, 1);
            tex_in[0][4 * i + a] = pos[3 * i + a];
            tex_in[1][4 * i + a] = nrm[3 * i + a];
            tex_in[2][4 * i + a] = (float)(0.2 + 0.7 * a / 2.0);
            tex_in[0][4 * i + 3] = tex_in[1][4 * i + 3] = tex_in[2][4 * i + 3] = 1;
        }
    TH_CHECK(voxgi_cone_trace(ctx, VOLUME_SOURCE(vol), &cd, N, pos, nrm, irr, occ) == VOXGI_OK, "arrays: %s", voxgi_last_error(ctx));
    create(0x0DE1, 5, tex); /* GL_TEXTURE_2D */
    for (i = 0; i < 5; i++) storage(tex[i], 1, i == 4 ? 0x881A : 0x8814, W, H); /* RGBA16F for the last, RGBA32F */
    for (i = 0; i < 3; i++) sub(tex[i], 0, 0, 0, W, H, 0x1908, 0x1406, tex_in[i]); /* GL_RGBA, GL_FLOAT */
    memset(&gb, 0, sizeof gb);
    gb.position_texture = tex[0];
    gb.normal_texture = tex[1];
    gb.width = W;
    gb.height = H;
    gb.irradiance_texture = tex[3];
    TH_CHECK(voxgi_cone_trace_gl(ctx, VOLUME_SOURCE(vol), &cd, &gb) == VOXGI_OK, "textures: %s", voxgi_last_error(ctx));
    get(tex[3], 0, 0x1908, 0x1406, (int)sizeof out, out);
    for (i = 0; i < 3 * N; i++) mean += irr[i] / (3.0 * N);
    for (i = 0; i < N; i++) {
        for (a = 0; a < 3; a++) worst = fmax(worst, fabs(out[4 * i + a] - (i ? irr[3 * i + a] : 0)));
        worst_occ = fmax(worst_occ, fabs(out[4 * i + 3] - (i ? occ[i] : 0)));
    }
    gb.albedo_texture = tex[2];
    gb.irradiance_texture = tex[4];
    gb.irradiance_rgba16f = 1;
    TH_CHECK(voxgi_cone_trace_gl(ctx, VOLUME_SOURCE(vol), &cd, &gb) == VOXGI_OK, "albedo, half: %s", voxgi_last_error(ctx));
    get(tex[4], 0, 0x1908, 0x1406, (int)sizeof out, out);
    for (i = 0; i < N; i++)
        for (a = 0; a < 3; a++)
            worst_albedo = fmax(worst_albedo, fabs(out[4 * i + a] - (i ? tex_in[2][4 * i + a] / 3.14159265358979323846 * irr[3 * i + a] : 0)) / fmax(mean, 1e-3));
    printf("    G-buffer textures: irradiance within %.3g (mean %.3g), occlusion within %.3g; with albedo into RGBA16F within %.3g (relative)\n", worst, mean,
           worst_occ, worst_albedo);
    TH_CHECK(mean > 0.05 && worst <= 1e-4 * mean && worst_occ <= 1e-4 && worst_albedo <= 2e-3, "G-buffer textures differ");
    TH_CHECK(out[0] == 0 && out[1] == 0 && out[2] == 0 && out[3] == 0, "the pixel without a normal was written");
    { /* the same over an octree of the radiance */
        voxgi_svo_desc sd;
        voxgi_svo *svo = NULL;
        double worst_svo = 0;
        memset(&sd, 0, sizeof sd);
        sd.attributes = VOXGI_ATTRIBUTE_RADIANCE;
        sd.radiance = vol;
        TH_CHECK(voxgi_svo_create(ctx, vx, &sd, &svo) == VOXGI_OK && voxgi_cone_trace(ctx, OCTREE_SOURCE(svo), &cd, N, pos, nrm, irr, occ) == VOXGI_OK,
                 "octree arrays: %s", voxgi_last_error(ctx));
        gb.albedo_texture = 0;
        gb.irradiance_texture = tex[3];
        gb.irradiance_rgba16f = 0;
        TH_CHECK(voxgi_cone_trace_gl(ctx, OCTREE_SOURCE(svo), &cd, &gb) == VOXGI_OK, "octree textures: %s", voxgi_last_error(ctx));
        get(tex[3], 0, 0x1908, 0x1406, (int)sizeof out, out);
        for (i = 0; i < N; i++) {
            for (a = 0; a < 3; a++) worst_svo = fmax(worst_svo, fabs(out[4 * i + a] - (i ? irr[3 * i + a] : 0)) / fmax(mean, 1e-3));
            worst_svo = fmax(worst_svo, fabs(out[4 * i + 3] - (i ? occ[i] : 0)));
        }
        printf("    G-buffer textures over the octree: within %.3g of its array path\n", worst_svo);
        TH_CHECK(worst_svo <= 1e-4, "octree G-buffer textures differ by %g", worst_svo);
        voxgi_svo_destroy(ctx, svo);
    }
    gb.width = 0;
    TH_CHECK(voxgi_cone_trace_gl(ctx, VOLUME_SOURCE(vol), &cd, &gb) == VOXGI_ERR_INVALID_ARGUMENT, "an empty G-buffer accepted");
    del(5, tex);
    voxgi_volume_destroy(ctx, vol);
    voxgi_voxels_destroy(ctx, vx);
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* voxgi's own G-buffer rasterized on GL against the CPU's ray cast (the Cornell box, 64 x 48,
   the view's aspect stretched): the same triangle at all but 1 in 500 pixels (a shared edge or a
   silhouette may go to the neighbour; a projective depth test loses the lamp 0.1 mm below the
   ceiling at 17 pixels), there the same normal and the position within float interpolation; no
   surface where the CPU finds none. */
static void test_gl_raster_gbuffer(void)
{
    enum { W = 64, H = 48 };
    voxgi_context *ctx[2];
    voxgi_builtin_scene bs;
    voxgi_camera cam;
    static float pos[2][3 * W * H], nrm[2][3 * W * H];
    static uint32_t tri[2][W * H];
    int b, i, a, same = 0, hits = 0;
    double worst_p = 0, worst_n = 0;
    if (!have_gl()) return;
    ctx[0] = make_ctx(VOXGI_BACKEND_CPU, 0);
    ctx[1] = make_ctx(VOXGI_BACKEND_GL, 0);
    voxgi_builtin_scene_create(ctx[0], "cornell-box", &bs);
    cam = bs.camera;
    cam.width = W;
    cam.height = H;
    for (b = 0; b < 2; b++)
        TH_CHECK(voxgi_gbuffer_render(ctx[b], &bs.scene, &cam, pos[b], nrm[b], tri[b]) == VOXGI_OK, "%s: %s", b ? "GL" : "CPU", voxgi_last_error(ctx[b]));
    for (i = 0; i < W * H; i++) {
        hits += tri[0][i] != UINT32_MAX;
        if (tri[0][i] != tri[1][i]) continue;
        same++;
        for (a = 0; a < 3; a++) {
            worst_p = fmax(worst_p, fabs(pos[0][3 * i + a] - pos[1][3 * i + a]));
            worst_n = fmax(worst_n, fabs(nrm[0][3 * i + a] - nrm[1][3 * i + a]));
        }
    }
    printf("    G-buffer: %d of %d pixels on the same triangle (%d surfaces), positions within %.3g m, normals within %.3g\n", same, W * H, hits, worst_p,
           worst_n);
    TH_CHECK(hits > W * H / 2 && same >= W * H - W * H / 500 && worst_p < 1e-4 && worst_n < 1e-6, "G-buffers differ");
    voxgi_builtin_scene_destroy(ctx[0], &bs);
    voxgi_destroy(ctx[0]);
    voxgi_destroy(ctx[1]);
}

/* Cone tracing on GL (a compute pass, hardware filtering of premultiplied radiance) against the
   CPU's march over the same voxels: the Cornell box voxelized and lit on each backend (the
   voxels equal, the light injected through the same exact shadow rays, the mips equal to float
   rounding), then the same
   points traced, and the whole cone-traced image rendered on both; isotropic and anisotropic. */
static void test_gl_raster_cone_tracing_equals_cpu(void)
{
    enum { N = 300, W = 20 };
    voxgi_context *ctx[2];
    voxgi_builtin_scene bs;
    float pos[3 * N], nrm[3 * N], irr[2][3 * N], occ[2][N], *img[2], each[2][4 * N];
    voxgi_cone single[N];
    double worst_irr = 0, worst_occ = 0, worst_img = 0, mean_irr = 0, mean_img = 0, worst_each = 0;
    int b, f, i, a;
    if (!have_gl()) return;
    ctx[0] = make_ctx(VOXGI_BACKEND_CPU, 0);
    ctx[1] = make_ctx(VOXGI_BACKEND_GL, 0);
    TH_CHECK(voxgi_builtin_scene_create(ctx[0], "cornell-box", &bs) == VOXGI_OK, "scene");
    fx_rng rng = fx_rng_seeded(12);
    cornell_cone_points(5, N, pos, nrm, single);
    for (i = 0; i < N; i++) { /* half of the single cones leave a surface; some have a reach */
        for (a = 0; a < 3; a++) single[i].normal[a] = i % 2 ? nrm[3 * ((i + 1) % N) + a] : 0;
        single[i].max_distance = i % 3 ? (float)fx_rng_range(&rng, 0, 0.6) : 0;
    }
    img[0] = (float *)malloc(W * W * 12);
    img[1] = (float *)malloc(W * W * 12);
    for (f = 0; f < 2; f++) {
        for (b = 0; b < 2; b++) {
            voxgi_inject_desc id;
            voxgi_cone_desc cd;
            voxgi_render_desc vd;
            voxgi_voxels *vx;
            voxgi_volume *vol;
            memset(&id, 0, sizeof id);
            memset(&cd, 0, sizeof cd);
            vct_view(&vd, &bs, W);
            id.volume.filter = (voxgi_mip_filter)f;
            id.samples = 4;
            id.shadow_rays = 1; /* the same radiance on both */
            TH_CHECK(lit_voxels(ctx[b], &bs.scene, 32, &id, &vx, &vol) &&
                     voxgi_cone_trace(ctx[b], VOLUME_SOURCE(vol), &cd, N, pos, nrm, irr[b], occ[b]) == VOXGI_OK &&
                     voxgi_cone_trace_each(ctx[b], VOLUME_SOURCE(vol), &cd, N, single, each[b]) == VOXGI_OK, "%s: %s", b ? "GL" : "CPU", voxgi_last_error(ctx[b]));
            voxgi_volume_destroy(ctx[b], vol);
            voxgi_voxels_destroy(ctx[b], vx);
            vd.resolution = 32;
            vd.samples = 2;
            vd.vct.radiance = vct_radiance((voxgi_mip_filter)f, 0);
            vd.vct.shadow_rays = 1;
            TH_CHECK(voxgi_render(ctx[b], &bs.scene, &vd, img[b], W * W * 12, NULL) == VOXGI_OK, "render: %s", voxgi_last_error(ctx[b]));
        }
        for (i = 0; i < 3 * N; i++) { worst_irr = fmax(worst_irr, fabs(irr[0][i] - irr[1][i])); mean_irr += irr[0][i] / (6.0 * N); }
        for (i = 0; i < N; i++) worst_occ = fmax(worst_occ, fabs(occ[0][i] - occ[1][i]));
        for (i = 0; i < 4 * N; i++) worst_each = fmax(worst_each, fabs(each[0][i] - each[1][i]) / (i % 4 == 3 ? 1 : fmax(mean_irr, 1e-3)));
        for (i = 0; i < 3 * W * W; i++) { worst_img = fmax(worst_img, fabs(img[0][i] - img[1][i])); mean_img += img[0][i] / (6.0 * W * W); }
    }
    printf("    GL cone tracing vs CPU: irradiance within %.3g (mean %.3g), occlusion within %.3g, single cones within %.3g (relative), image within %.3g "
           "(mean %.3g)\n", worst_irr, mean_irr, worst_occ, worst_each, worst_img, mean_img);
    TH_CHECK(worst_each <= cone_tolerance(), "single cones differ by %g", worst_each);
    TH_CHECK(mean_irr > 0.05 && worst_irr <= cone_tolerance() * mean_irr, "irradiance differs by %g (mean %g)", worst_irr, mean_irr);
    TH_CHECK(worst_occ <= cone_tolerance(), "occlusion differs by %g", worst_occ);
    TH_CHECK(worst_img <= cone_tolerance() * mean_img, "image differs by %g (mean %g)", worst_img, mean_img);
    {   /* three bounces among the voxels, gathered on each backend from the same direct light: each
           bounce's gather differs as the cones do, and so the image by at most three times that */
        double worst_b = 0, mean_b = 0;
        voxgi_render_desc vd;
        for (b = 0; b < 2; b++) {
            vct_view(&vd, &bs, W);
            vd.resolution = 32;
            vd.samples = 2;
            vd.vct.shadow_rays = 1;
            vd.bounces = 3;
            TH_CHECK(voxgi_render(ctx[b], &bs.scene, &vd, img[b], W * W * 12, NULL) == VOXGI_OK, "bounces: %s", voxgi_last_error(ctx[b]));
        }
        for (i = 0; i < 3 * W * W; i++) { worst_b = fmax(worst_b, fabs(img[0][i] - img[1][i])); mean_b += img[0][i] / (3.0 * W * W); }
        printf("    3 bounces, GL vs CPU: image within %.3g (mean %.3g)\n", worst_b, mean_b);
        TH_CHECK(mean_b > mean_img && worst_b <= 3 * cone_tolerance() * mean_b, "3 bounces: image differs by %g (mean %g)", worst_b, mean_b);
    }
    {   /* cones from an enclosed region (the regions' rule: the cones stop where they leave it, stay
           at levels that do not reach beyond it and leave out the voxels lit from outside only):
           the leak box with a lamp inside as well, seen from inside, one and three bounces */
        voxgi_builtin_scene box;
        voxgi_light lights[3];
        double worst_r = 0, mean_r = 0;
        int bounces;
        TH_CHECK(leak_box_with_lamp(ctx[0], &box, lights) == VOXGI_OK, "leak-box");
        for (bounces = 1; bounces <= 3; bounces += 2) {
            voxgi_render_desc vd;
            double worst = 0, mean = 0;
            for (b = 0; b < 2; b++) {
                vct_view(&vd, &box, W);
                vd.resolution = 32;
                vd.samples = 2;
                vd.vct.shadow_rays = 1;
                vd.bounces = bounces;
                vd.hide_emitters = 1;
                TH_CHECK(voxgi_render(ctx[b], &box.scene, &vd, img[b], W * W * 12, NULL) == VOXGI_OK, "enclosed: %s", voxgi_last_error(ctx[b]));
            }
            for (i = 0; i < 3 * W * W; i++) { worst = fmax(worst, fabs(img[0][i] - img[1][i])); mean += img[0][i] / (3.0 * W * W); }
            TH_CHECK(mean > 0.01 && worst <= bounces * cone_tolerance() * mean, "enclosed, %d bounce(s): image differs by %g (mean %g)", bounces, worst, mean);
            worst_r = fmax(worst_r, worst / mean);
            mean_r += mean / 2;
        }
        printf("    cones from an enclosed region, 1 and 3 bounces, GL vs CPU: image within %.3g of its mean (%.3g)\n", worst_r, mean_r);
        voxgi_builtin_scene_destroy(ctx[0], &box);
    }
    free(img[0]);
    free(img[1]);
    voxgi_builtin_scene_destroy(ctx[0], &bs);
    voxgi_destroy(ctx[0]);
    voxgi_destroy(ctx[1]);
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
    TH_RUN(test_gl_equals_cpu_sphere);
    TH_RUN(test_gl_equals_cpu_ties);
    TH_RUN(test_gl_equals_cpu_quads_and_huge);
    TH_RUN(test_gl_equals_cpu_degenerate);
    TH_RUN(test_gl_equals_cpu_solid);
    TH_RUN(test_gl_reduce_equals_cpu);
    TH_RUN(test_gl_raster_slicemap_equals_cpu);
    TH_RUN(test_gl_raster_atlas_equals_cpu);
    TH_RUN(test_gl_raster_geometry_equals_cpu);
    TH_RUN(test_gl_volume_mips_equal_cpu);
    TH_RUN(test_gl_volume_sampling_equals_cpu);
    TH_RUN(test_gl_raster_injection_matches_cpu);
    TH_RUN(test_gl_raster_cone_tracing_equals_cpu);
    TH_RUN(test_gl_octree_cones_equal_cpu);
    TH_RUN(test_gl_raster_gbuffer_textures);
    TH_RUN(test_gl_raster_gbuffer);
    TH_RUN(test_gl_raster_leak_box);
    TH_RUN(test_gl_raster_leak_room);
    TH_RUN(test_gl_raster_held_out_closed_spaces);
    TH_RUN(test_gl_raster_volume_buffer);
    TH_RUN(test_gl_raster_attributes_equal_cpu);
    TH_RUN(test_gl_interop_and_backends);
    TH_RUN(test_gl_plain_loader);
    TH_RUN(test_gl_auto_backend);
    TH_RUN(test_gl_missing_function_and_fallback);
    gl_close();
    return th_finish();
}
