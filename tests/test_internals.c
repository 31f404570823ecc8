/* tests/test_internals.c - the tests of voxgi's private helpers (voxgi__*), ordered by the header's
   parts: 3 scene (rays leaving surfaces; Lambert's polygon formula against the lights' own
   samples), 4 GL core (shader error mapping, which GL renderers are software rasterizers), 5
   voxelization (the 3D-DDA of voxel visibility), 6 volumes and mips (the mip filters against
   parents worked out by hand: one parent, one level, a whole chain on the CPU and on GL; the
   region labels of empty space), 7 octree (half-float rounding, the GPU-built octree), 8 cone
   tracing (the diffuse cone set: directions, distribution, weights; each leak defence alone:
   two-sided radiance, the back coverage, the regions; the exact area light of cone-traced
   images), 12 line space (the build, shadow rays, GL against the CPU). Random numbers come from
   fixtures.h's fx_rng, one generator seeded in each test.

   They live here, apart, because those helpers are static inside the implementation: this program
   defines VOXGI_IMPLEMENTATION and compiles the implementation itself, while every other test
   program includes voxgi.h for the declarations only and links the implementation compiled once
   (build/voxgi_impl.o), so it sees nothing but the public API. Keep a test here only while it
   calls a voxgi__ function or reads a private field; its part's public tests are in the part's
   file (tests/test_<part>.c); the shared fixtures are tests/fixtures.h. The GL tests skip
   (loudly) when no GL 4.5 context can be made; VOXGI_TEST_GL and VOXGI_REQUIRE_GL work as in
   every GL test (tests/fixtures.h). */
#define VOXGI_IMPLEMENTATION
#include "../voxgi.h"
#include "fixtures.h"
#include "svo_checks.h"

/* ===================================================================== 3. scene */

/* Rays leaving a surface (voxgi__leave, voxgi__trace skipping the triangle left) find nothing on
   the surface itself: a tilted plane of 2 x 40 x 40 triangles, 1e3 m from the origin (floats
   there are 6e-5 m apart), left from points on it at grazing angles, 2 to 0.01 degrees. Started
   on the plane instead, float rounding puts some origins behind it and they hit its neighbours. */
static void test_rays_leave_surfaces(void)
{
    enum { M = 40 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    static float pos[3 * (M + 1) * (M + 1)];
    static uint32_t idx[6 * M * M];
    const double u[3] = {0.8, 0.6, 0}, v[3] = {-0.36, 0.48, 0.8}, off[3] = {1000.3, -700.1, 400.7};
    double n[3];
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi__tracer tr;
    fx_rng rng;
    int i, j, a, hits = 0, rays = 0;
    n[0] = u[1] * v[2] - u[2] * v[1]; n[1] = u[2] * v[0] - u[0] * v[2]; n[2] = u[0] * v[1] - u[1] * v[0];
    for (j = 0; j <= M; j++)
        for (i = 0; i <= M; i++)
            for (a = 0; a < 3; a++) pos[3 * (j * (M + 1) + i) + a] = (float)(off[a] + (i - M / 2) * 0.25 * u[a] + (j - M / 2) * 0.25 * v[a]);
    for (j = 0; j < M; j++)
        for (i = 0; i < M; i++) {
            uint32_t q = (uint32_t)(j * (M + 1) + i), *t = idx + 6 * (j * M + i);
            t[0] = q; t[1] = q + 1; t[2] = q + M + 2; t[3] = q; t[4] = q + M + 2; t[5] = q + M + 1;
        }
    scene_of_triangles(&sc, &mesh, pos, (M + 1) * (M + 1), idx, 2 * M * M);
    TH_CHECK(voxgi__tracer_build(ctx, &sc, &tr) == VOXGI_OK, "tracer: %s", voxgi_last_error(ctx));
    rng = fx_rng_seeded(5);
    for (i = 0; i < 20000; i++) {
        double o[3], d[3], p[3], ns[3], phi = fx_rng_range(&rng, 0, 6.283185307179586), el = pow(10, fx_rng_range(&rng, -2, log10(2.0))) * 3.141592653589793 / 180;
        double su = fx_rng_range(&rng, -4, 4), sv = fx_rng_range(&rng, -4, 4);
        voxgi__hit h, h2;
        for (a = 0; a < 3; a++) { /* down onto the plane, then away from it along it */
            o[a] = off[a] + su * u[a] + sv * v[a] + n[a];
            d[a] = -n[a];
        }
        if (!voxgi__trace(&tr, o, d, DBL_MAX, UINT32_MAX, 0, &h)) continue;
        for (a = 0; a < 3; a++) {
            ns[a] = h.front ? tr.n[3 * (size_t)h.prim + (size_t)a] : -tr.n[3 * (size_t)h.prim + (size_t)a];
            d[a] = cos(el) * (cos(phi) * u[a] + sin(phi) * v[a]) + sin(el) * ns[a];
        }
        voxgi__leave(&tr, h.p, ns, p);
        rays++;
        hits += voxgi__trace(&tr, p, d, DBL_MAX, h.prim, 1, &h2);
    }
    printf("    %d rays leaving a plane 1e3 m out at 0.01-2 degrees: %d hit it\n", rays, hits);
    TH_CHECK(rays > 19000 && hits == 0, "%d of %d rays leaving the plane hit it", hits, rays);
    voxgi__tracer_free(ctx, &tr);
    voxgi_destroy(ctx);
}

/* Lambert's polygon formula (the cone-traced image's exact unshadowed light from rect lights and
   emitters) against what is known: a huge square overhead gives pi, half of it under the
   horizon pi / 2; a point behind a light or with the light below its horizon gets 0; and at random points and normals, lights cut by the
   horizon included, it equals the mean of voxgi__direct's own light samples without shadow rays
   (65536 stratified points per shading point: within 0.2% of the larger of the two and 0.05). */
static void test_polygon_irradiance(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    double big[4][3] = {{-1e4, 1, -1e4}, {1e4, 1, -1e4}, {1e4, 1, 1e4}, {-1e4, 1, 1e4}}, down[3] = {0, -1, 0}, up[3] = {0, 1, 0}, o[3] = {0, 0, 0};
    double side[3] = {1, 0, 0}, below[3] = {0, 2, 0}, worst = 0;
    voxgi_material mats[2] = {{{0.5f, 0.5f, 0.5f}, {0, 0, 0}, 0}, {{0.5f, 0.5f, 0.5f}, {3, 2, 1}, 0}};
    float emit_q[12] = {-0.3f, 1, -0.2f, 0.2f, 1, -0.2f, 0.2f, 1, 0.4f, -0.3f, 1, 0.4f}; /* faces down: seen from below */
    float floor_q[12] = {-9, -5, -9, -9, -5, 9, 9, -5, 9, 9, -5, -9};
    voxgi_light rect;
    quads q;
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi__tracer tr;
    voxgi__lights Ls;
    int i, k, a;
    fx_rng rng = fx_rng_seeded(3);
    double f = voxgi__polygon_irradiance((const double(*)[3])big, 4, down, o, up);
    printf("    huge square overhead: irradiance %.9f (pi %.9f)\n", f, 3.14159265358979323846);
    TH_CHECK(fabs(f / 3.14159265358979323846 - 1) < 1e-6, "huge square: %.9f", f);
    TH_CHECK(voxgi__polygon_irradiance((const double(*)[3])big, 4, down, below, down) == 0, "a point behind the light is lit");
    TH_CHECK(voxgi__polygon_irradiance((const double(*)[3])big, 4, down, o, down) == 0, "a light below the horizon lights");
    f = voxgi__polygon_irradiance((const double(*)[3])big, 4, down, o, side);
    TH_CHECK(fabs(f / (3.14159265358979323846 / 2) - 1) < 1e-3, "a huge square half under the horizon: %.9f, not pi / 2", f); /* less its far edge */
    q.n = 0;
    quad(&q, emit_q, 1);
    quad(&q, floor_q, 0);
    memset(&rect, 0, sizeof rect);
    rect.type = VOXGI_LIGHT_RECT;
    rect.position[0] = 0.5f; rect.position[1] = 0.2f; rect.position[2] = -0.5f;
    rect.edge_u[2] = 0.6f; rect.edge_v[1] = 0.5f; /* a wall light at x = 0.5 facing -x (edge_u x edge_v) */
    rect.intensity[0] = 1; rect.intensity[1] = 4; rect.intensity[2] = 2;
    scene_of_quads(&sc, &mesh, &q, mats, 2, &rect, 1);
    TH_CHECK(voxgi__tracer_build(ctx, &sc, &tr) == VOXGI_OK && voxgi__lights_build(ctx, &sc, &tr, &Ls) == VOXGI_OK, "lights");
    for (i = 0; i < 40; i++) {
        double p[3], n[3], len = 0, exact[3], mean[6] = {0, 0, 0, 0, 0, 0}, e[3];
        uint64_t rays = 0;
        voxgi__rng g;
        for (a = 0; a < 3; a++) { p[a] = fx_rng_range(&rng, -0.8, 0.8); n[a] = fx_rng_range(&rng, -1, 1); len += n[a] * n[a]; }
        p[1] = fx_rng_range(&rng, -0.5, 0.2);
        len = sqrt(len);
        for (a = 0; a < 3; a++) n[a] /= len;
        voxgi__area_irradiance(&Ls, p, n, UINT32_MAX, exact);
        voxgi__rng_seed(&g, 5, (uint64_t)i, 0);
        for (k = 0; k < 65536; k++) { /* stratified: a 2D Kronecker sequence */
            double area[8] = {0, 0, 0, 0, 0, 0, 0, 0}, xi[2];
            xi[0] = fmod(0.5 + (k + 1) * 0.7548776662466927, 1.0);
            xi[1] = fmod(0.5 + (k + 1) * 0.5698402909980532, 1.0);
            voxgi__direct(&Ls, p, n, UINT32_MAX, &g, 0, xi, &rays, e, area);
            for (a = 0; a < 6; a++) mean[a] += area[a] / 65536;
        }
        for (a = 0; a < 3; a++) worst = fmax(worst, fabs(mean[3 + a] - exact[a]) / fmax(exact[a], 0.05));
    }
    printf("    rect light and emitters at 40 random points: the exact irradiance within %.3f%% of the sampled mean\n", 100 * worst);
    TH_CHECK(worst < 0.002, "polygon irradiance off by %.3g", worst);
    voxgi__lights_free(ctx, &Ls);
    voxgi__tracer_free(ctx, &tr);
    voxgi_destroy(ctx);
}

/* ===================================================================== 4. GL core */

/* A shader that fails to compile gives VOXGI_ERR_GL_SHADER with the log mapped to file:line. */
static void test_gl_shader_error_mapping(void)
{
    voxgi_context *ctx;
    unsigned int prog = 0;
    const char *files[2] = {"good.glsl", "broken.glsl"};
    const char *texts[2] = {"layout(local_size_x = 1) in;\nint one() { return 1; }\n",
                            "void main()\n{\n    undefined_thing = one();\n}\n"};
    if (!have_gl()) return;
    ctx = make_ctx(VOXGI_BACKEND_GL, 0);
    TH_CHECK(voxgi__gl_program(ctx, 0, 2, files, texts, &prog) == VOXGI_ERR_GL_SHADER, "broken shader compiled");
    TH_CHECK(strstr(voxgi_last_error(ctx), "broken.glsl:3") != NULL, "log not mapped to broken.glsl:3: %s", voxgi_last_error(ctx));
    voxgi_destroy(ctx);
}

/* Which GL renderers AUTO turns down for the CPU: the software rasterizers, by name in any case,
   and nothing else (real renderer strings of GPUs, and look-alikes). */
static void test_gl_software_renderers(void)
{
    static const char *const software[] = {"llvmpipe (LLVM 15.0.6, 256 bits)", "LLVMPIPE", "softpipe", "Gallium 0.4 on softpipe",
                                           "Software Rasterizer", "Mesa X11 swrast", "Google SwiftShader", "SwiftShader Device (Subzero)",
                                           "ANGLE (Google, Vulkan 1.3.0 (SwiftShader Device (Subzero) (0x0000C0DE)), SwiftShader driver)",
                                           "D3D12 (Microsoft Basic Render Driver)", "microsoft basic render driver"};
    static const char *const hardware[] = {"", "NVIDIA GeForce RTX 3080/PCIe/SSE2", "AMD Radeon RX 6800 XT (radeonsi, navi21, LLVM 15.0.7, DRM 3.49)",
                                           "Mesa Intel(R) UHD Graphics 620 (KBL GT2)", "Apple M1", "D3D12 (NVIDIA GeForce RTX 3060)",
                                           "virgl (Mesa Intel(R) Xe Graphics)", "llvm pipe", "Soft Rasterizer", "swift shader"};
    size_t k;
    for (k = 0; k < sizeof software / sizeof software[0]; k++)
        TH_CHECK(voxgi__gl_is_software(software[k]), "'%s' not taken for a software rasterizer", software[k]);
    for (k = 0; k < sizeof hardware / sizeof hardware[0]; k++)
        TH_CHECK(!voxgi__gl_is_software(hardware[k]), "'%s' taken for a software rasterizer", hardware[k]);
}

/* ===================================================================== 5. voxelization */

/* 3D-DDA through an empty grid visits exactly the voxels a brute-force slab test finds for the
   segment (those whose box it crosses for more than 1e-9 of its length), in the order it enters
   them; 4000 random segments inside, across and beside a 7 x 5 x 9 grid. */
typedef struct dda_log { int64_t v[64][3]; int n; } dda_log;
static void dda_record(void *user, const int64_t v[3])
{
    dda_log *L = (dda_log *)user;
    if (L->n < 64) memcpy(L->v[L->n], v, sizeof L->v[0]);
    L->n++;
}

static void test_dda_visits_the_slab_voxels(void)
{
    voxgi__occupancy O;
    fx_rng g = fx_rng_seeded(21);
    int trial, bad = 0, visited = 0;
    memset(&O, 0, sizeof O);
    O.levels = 1;
    O.res[0][0] = 7; O.res[0][1] = 5; O.res[0][2] = 9;
    O.bits[0] = (uint32_t *)calloc((7 * 5 * 9 + 31) / 32, 4);
    for (trial = 0; trial < 4000 && !bad; trial++) {
        double o[3], d[3], entry[64];
        int64_t want[64][3];
        int n = 0, a, i, j, k;
        uint64_t steps = 0;
        dda_log L;
        for (a = 0; a < 3; a++) {
            o[a] = fx_rng_range(&g, -2, O.res[0][a] + 2);
            d[a] = fx_rng_range(&g, -2, O.res[0][a] + 2) - o[a];
        }
        if (trial % 5 == 0) d[trial % 3] = 0; /* parallel to an axis */
        for (k = 0; k < 9; k++) /* brute force: each voxel's slab interval */
            for (j = 0; j < 5; j++)
                for (i = 0; i < 7; i++) {
                    double t0 = 0, t1 = 1;
                    int c[3];
                    c[0] = i; c[1] = j; c[2] = k;
                    for (a = 0; a < 3; a++) {
                        if (d[a] == 0) {
                            if (!(o[a] >= c[a] && o[a] <= c[a] + 1)) t1 = -1;
                            continue;
                        }
                        {
                            double ta = (c[a] - o[a]) / d[a], tb = (c[a] + 1 - o[a]) / d[a];
                            if (ta > tb) { double x = ta; ta = tb; tb = x; }
                            if (ta > t0) t0 = ta;
                            if (tb < t1) t1 = tb;
                        }
                    }
                    if (t1 - t0 > 1e-9) { /* in order of entry */
                        int at = n++;
                        while (at > 0 && entry[at - 1] > t0) { entry[at] = entry[at - 1]; memcpy(want[at], want[at - 1], sizeof want[0]); at--; }
                        entry[at] = t0;
                        want[at][0] = i; want[at][1] = j; want[at][2] = k;
                    }
                }
        L.n = 0;
        voxgi__traverse(&O, 0, o, d, &steps, dda_record, &L);
        visited += L.n;
        if (L.n != n) bad = 1;
        for (i = 0; i < n && !bad; i++)
            for (a = 0; a < 3; a++) bad |= L.v[i][a] != want[i][a];
        if (bad) printf("    segment %d: DDA visited %d voxels, the slabs %d\n", trial, L.n, n);
    }
    printf("    %d segments: %d voxels visited, every one the brute force's, in its order\n", trial, visited);
    TH_CHECK(!bad && visited > 10000, "DDA differs from the slab test");
    free(O.bits[0]);
}

/* ===================================================================== 6. volumes and mips */

/* ---------------------------------------------------------------- volume mips, by hand */
/* The mip filters against parents worked out by hand from their definition (voxgi.h, part 6,
   "volumes and mips"; docs/volumes-and-octrees.md): children k = x + 2y + 4z, each (value,
   alpha), empty ones all zero.
   ISOTROPIC: alpha = the mean of the 8 alphas; value = the alpha-weighted mean, sum(v a) / sum(a).
   ANISOTROPIC, per direction of travel (+x -x +y -y +z -z): the 4 pairs of children along the
   axis composited front to back (the near child is the one the travel meets first: low x for
   +x), premultiplied c = v_n a_n + (1 - a_n) v_f a_f, a = a_n + (1 - a_n) a_f; alpha = the mean
   of the 4 pair alphas, value = sum(c) / sum(a) (un-premultiplied).
   RADIANCE is stored premultiplied (v a, a) and filtered alike without the un-premultiplying:
   value = sum(premultiplied values) / 8 (isotropic) or sum(c) / 4 (anisotropic).
   Each case below gives the children and, by hand, per filter (isotropic, +x, -x, +y, -y, +z,
   -z), C = the sum of the premultiplied reds (sum(r a), or sum(c) over the pairs) and A = the
   sum of alphas (sum(a), or sum(a_n + (1 - a_n) a_f)); the parent is then, with m = 8
   (isotropic) or 4: stored plainly (C / A, 1, 0, A / m) (green is 1 and blue 0 in every
   occupied child, so green stays 1, empty children not darkening it), premultiplied
   (C / m, A / m, 0, A / m), alpha alone A / m. */
typedef struct mip_case {
    const char *name;
    float c[8][4];
    double C[7], A[7];
} mip_case;

static const mip_case mip_cases[] = {
    {"mixed: opaque, half-opaque, quarter and three-quarter children, two empty ones",
     {{1, 1, 0, 1}, {0.5f, 1, 0, 0.5f}, {0, 0, 0, 0}, {0.25f, 1, 0, 0.5f}, {0.75f, 1, 0, 0.25f}, {0, 0, 0, 0}, {0, 1, 0, 1}, {1, 1, 0, 0.75f}},
     {/* isotropic: k0 + k1 + k3 + k4 + k6 + k7 (k2, k5 empty) */
      1 * 1 + 0.5 * 0.5 + 0.25 * 0.5 + 0.75 * 0.25 + 0 * 1 + 1 * 0.75,
      /* +x: pairs (near, far) = (k0 k1) (k2 k3) (k4 k5) (k6 k7) */
      (1 * 1 + 0 * 0.5 * 0.5) + (0 + 1 * 0.25 * 0.5) + (0.75 * 0.25 + 0.75 * 0) + (0 * 1 + 0 * 1 * 0.75),
      /* -x: (k1 k0) (k3 k2) (k5 k4) (k7 k6) */
      (0.5 * 0.5 + 0.5 * 1 * 1) + (0.25 * 0.5 + 0.5 * 0) + (0 + 1 * 0.75 * 0.25) + (1 * 0.75 + 0.25 * 0 * 1),
      /* +y: (k0 k2) (k1 k3) (k4 k6) (k5 k7) */
      (1 * 1 + 0 * 0) + (0.5 * 0.5 + 0.5 * 0.25 * 0.5) + (0.75 * 0.25 + 0.75 * 0 * 1) + (0 + 1 * 1 * 0.75),
      /* -y: (k2 k0) (k3 k1) (k6 k4) (k7 k5) */
      (0 + 1 * 1 * 1) + (0.25 * 0.5 + 0.5 * 0.5 * 0.5) + (0 * 1 + 0 * 0.75 * 0.25) + (1 * 0.75 + 0.25 * 0),
      /* +z: (k0 k4) (k1 k5) (k2 k6) (k3 k7) */
      (1 * 1 + 0 * 0.75 * 0.25) + (0.5 * 0.5 + 0.5 * 0) + (0 + 1 * 0 * 1) + (0.25 * 0.5 + 0.5 * 1 * 0.75),
      /* -z: (k4 k0) (k5 k1) (k6 k2) (k7 k3) */
      (0.75 * 0.25 + 0.75 * 1 * 1) + (0 + 1 * 0.5 * 0.5) + (0 * 1 + 0 * 0) + (1 * 0.75 + 0.25 * 0.25 * 0.5)},
     {1 + 0.5 + 0 + 0.5 + 0.25 + 0 + 1 + 0.75,
      (1 + 0 * 0.5) + (0 + 1 * 0.5) + (0.25 + 0.75 * 0) + (1 + 0 * 0.75),
      (0.5 + 0.5 * 1) + (0.5 + 0.5 * 0) + (0 + 1 * 0.25) + (0.75 + 0.25 * 1),
      (1 + 0 * 0) + (0.5 + 0.5 * 0.5) + (0.25 + 0.75 * 1) + (0 + 1 * 0.75),
      (0 + 1 * 1) + (0.5 + 0.5 * 0.5) + (1 + 0 * 0.25) + (0.75 + 0.25 * 0),
      (1 + 0 * 0.25) + (0.5 + 0.5 * 0) + (0 + 1 * 1) + (0.5 + 0.5 * 0.75),
      (0.25 + 0.75 * 1) + (0 + 1 * 0.5) + (1 + 0 * 0) + (0.75 + 0.25 * 0.5)}},
    {"opaque: red k / 8, the near child hides the far one",
     {{0, 1, 0, 1}, {0.125f, 1, 0, 1}, {0.25f, 1, 0, 1}, {0.375f, 1, 0, 1}, {0.5f, 1, 0, 1}, {0.625f, 1, 0, 1}, {0.75f, 1, 0, 1}, {0.875f, 1, 0, 1}},
     {0 + 0.125 + 0.25 + 0.375 + 0.5 + 0.625 + 0.75 + 0.875,
      0 + 0.25 + 0.5 + 0.75,      /* +x: the near reds k0 k2 k4 k6 */
      0.125 + 0.375 + 0.625 + 0.875, /* -x: k1 k3 k5 k7 */
      0 + 0.125 + 0.5 + 0.625,    /* +y: k0 k1 k4 k5 */
      0.25 + 0.375 + 0.75 + 0.875, /* -y: k2 k3 k6 k7 */
      0 + 0.125 + 0.25 + 0.375,   /* +z: k0..k3 */
      0.5 + 0.625 + 0.75 + 0.875}, /* -z: k4..k7 */
     {8, 4, 4, 4, 4, 4, 4}},
    {"half-opaque: red 1 at x = 0, 0 at x = 1, every alpha 0.5",
     {{1, 1, 0, 0.5f}, {0, 1, 0, 0.5f}, {1, 1, 0, 0.5f}, {0, 1, 0, 0.5f}, {1, 1, 0, 0.5f}, {0, 1, 0, 0.5f}, {1, 1, 0, 0.5f}, {0, 1, 0, 0.5f}},
     {4 * (1 * 0.5),
      4 * (1 * 0.5 + 0.5 * 0 * 0.5),                 /* +x: red 1 in front */
      4 * (0 * 0.5 + 0.5 * 1 * 0.5),                 /* -x: red 0 in front, red 1 seen through it */
      2 * (1 * 0.5 + 0.5 * 1 * 0.5) + 2 * 0, 2 * (1 * 0.5 + 0.5 * 1 * 0.5) + 2 * 0, /* y and z: pairs of equal reds */
      2 * (1 * 0.5 + 0.5 * 1 * 0.5) + 2 * 0, 2 * (1 * 0.5 + 0.5 * 1 * 0.5) + 2 * 0},
     {8 * 0.5, 4 * (0.5 + 0.5 * 0.5), 4 * (0.5 + 0.5 * 0.5), 4 * (0.5 + 0.5 * 0.5), 4 * (0.5 + 0.5 * 0.5), 4 * (0.5 + 0.5 * 0.5),
      4 * (0.5 + 0.5 * 0.5)}},
    {"lone: only k5 set (red 0.375, alpha 0.625), it keeps its colour",
     {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0.375f, 1, 0, 0.625f}, {0, 0, 0, 0}, {0, 0, 0, 0}},
     {0.375 * 0.625, 0 + 1 * 0.375 * 0.625, 0.375 * 0.625 + 0.375 * 0, 0.375 * 0.625 + 0.375 * 0, 0.375 * 0.625 + 0.375 * 0,
      0 + 1 * 0.375 * 0.625, 0.375 * 0.625 + 0.375 * 0},
     {0.625, 0.625, 0.625, 0.625, 0.625, 0.625, 0.625}},
    {"empty", {{0}}, {0, 0, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 0, 0}},
};

/* Filter f (0 isotropic, 1 + d for direction d) of one case: the parent by hand (4 floats, or 1
   for alpha alone: w), stored plainly or premultiplied. */
static void mip_expected(const double C, const double A, int f, int w, int premultiplied, double out[4])
{
    double m = f ? 4 : 8;
    if (w == 1) { out[0] = A / m; return; }
    out[0] = premultiplied ? C / m : (A > 0 ? C / A : 0);
    out[1] = premultiplied ? A / m : (A > 0 ? 1 : 0);
    out[2] = 0;
    out[3] = A / m;
}

/* The case's children as the volume stores them: plainly, premultiplied (v a, a), or alpha alone. */
static void mip_stored(const mip_case *mc, int w, int premultiplied, float c[8][4])
{
    int k, ch;
    for (k = 0; k < 8; k++)
        for (ch = 0; ch < 4; ch++)
            c[k][ch] = w == 1 ? (ch == 3 ? mc->c[k][3] : 0) : (premultiplied && ch < 3 ? mc->c[k][ch] * mc->c[k][3] : mc->c[k][ch]);
}

static const char *mip_filter_name(int f) { return f ? "+x\0-x\0+y\0-y\0+z\0-z" + 3 * (f - 1) : "isotropic"; }
static const char *mip_storage_name(int mode) { return mode == 0 ? "plain" : (mode == 1 ? "premultiplied" : "alpha alone"); }

/* 1 when got is not want (to float rounding; NaN is never near). */
static int mip_off(double got, double want) { return !(fabs(got - want) <= 1e-6 * fmax(1, fabs(want))); }

/* voxgi__mip_combine, each case, each filter, stored plainly, premultiplied and alpha alone. */
static void test_mip_combine_by_hand(void)
{
    int i, f, mode, ch, bad = 0, checked = 0;
    for (i = 0; i < (int)(sizeof mip_cases / sizeof mip_cases[0]); i++)
        for (mode = 0; mode < 3; mode++) { /* 0 plain, 1 premultiplied, 2 alpha alone */
            int w = mode == 2 ? 1 : 4, pre = mode == 1;
            for (f = 0; f < 7; f++) {
                float c[8][4], dst[4] = {-7, -7, -7, -7};
                double want[4];
                mip_stored(&mip_cases[i], w, pre, c);
                mip_expected(mip_cases[i].C[f], mip_cases[i].A[f], f, w, pre, want);
                voxgi__mip_combine(c, w, f - 1, pre, dst);
                for (ch = 0; ch < w; ch++, checked++)
                    if (mip_off(dst[ch], want[ch])) {
                        bad++;
                        TH_CHECK(0, "%s, %s, %s: channel %d is %.9g, by hand %.9g", mip_cases[i].name, mip_filter_name(f), mip_storage_name(mode), ch,
                                 dst[ch], want[ch]);
                    }
            }
        }
    printf("    %d parent values of %d cases x 7 filters x 3 storages as worked out by hand, %d wrong\n", checked,
           (int)(sizeof mip_cases / sizeof mip_cases[0]), bad);
}

/* voxgi__mip_voxel (with voxgi__mip_load): a parent from a level stored x fastest, its children
   beyond the level's edge empty. A 3 x 2 x 2 level, its x = 0..1 half the mixed case above,
   x = 2 an opaque red-1 voxel at (2,0,0) and a half-opaque red-0.5 one at (2,1,1): parent (0,0,0)
   is the mixed case's in every filter (one direction at a time, and the six at once, dir -2);
   parent (1,0,0) has children k0 (opaque) and k6 (half) and nothing else (x = 3 is beyond the
   edge), so in every filter C = 1 * 1 + 0.5 * 0.5 (each a pair's near child, or far behind an
   empty one) and A = 1 + 0.5; an edge clamped instead of empty would double both. */
static void test_mip_voxel_by_hand(void)
{
    static const int sd[3] = {3, 2, 2};
    float lvl[12 * 4], alpha[12], six[6][4], *dst6[6];
    int mode, f, k, ch, q, p[3] = {0, 0, 0}, bad = 0;
    memset(lvl, 0, sizeof lvl);
    for (k = 0; k < 8; k++) {
        int at = (k & 1) + 3 * (((k >> 1) & 1) + 2 * (k >> 2));
        memcpy(lvl + 4 * at, mip_cases[0].c[k], 4 * sizeof(float));
    }
    lvl[4 * 2 + 0] = 1; lvl[4 * 2 + 1] = 1; lvl[4 * 2 + 3] = 1;                     /* (2,0,0) */
    lvl[4 * 11 + 0] = 0.5f; lvl[4 * 11 + 1] = 1; lvl[4 * 11 + 3] = 0.5f;            /* (2,1,1) */
    for (k = 0; k < 12; k++) alpha[k] = lvl[4 * k + 3];
    for (k = 0; k < 6; k++) dst6[k] = six[k];
    for (mode = 0; mode < 3; mode++) { /* plain, premultiplied, alpha alone */
        int w = mode == 2 ? 1 : 4, pre = mode == 1;
        float src[12 * 4];
        for (k = 0; k < 12 * 4; k++) src[k] = mode == 2 ? (k < 12 ? alpha[k] : 0) : (pre && k % 4 != 3 ? lvl[k] * lvl[k - k % 4 + 3] : lvl[k]);
        for (f = 0; f < 7; f++) {
            float got[2][4] = {{-7, -7, -7, -7}, {-7, -7, -7, -7}};
            double want[2][4];
            p[0] = 0;
            voxgi__mip_voxel(src, sd, got[0], NULL, w, f - 1, pre, p);
            p[0] = 1;
            voxgi__mip_voxel(src, sd, got[1], NULL, w, f - 1, pre, p);
            mip_expected(mip_cases[0].C[f], mip_cases[0].A[f], f, w, pre, want[0]);
            mip_expected(1 * 1 + 0.5 * 0.5, 1 + 0.5, f, w, pre, want[1]);
            for (q = 0; q < 2; q++)
                for (ch = 0; ch < w; ch++)
                    if (mip_off(got[q][ch], want[q][ch])) {
                        bad++;
                        TH_CHECK(0, "parent (%d,0,0), %s, %s: channel %d is %.9g, by hand %.9g", q, mip_filter_name(f), mip_storage_name(mode), ch,
                                 got[q][ch], want[q][ch]);
                    }
        }
        for (q = 0; q < 2; q++) { /* all six directions at once */
            p[0] = q;
            for (k = 0; k < 6; k++) for (ch = 0; ch < 4; ch++) six[k][ch] = -7;
            voxgi__mip_voxel(src, sd, NULL, dst6, w, -2, pre, p);
            for (k = 0; k < 6; k++) {
                double want[4];
                if (q == 0) mip_expected(mip_cases[0].C[1 + k], mip_cases[0].A[1 + k], 1 + k, w, pre, want);
                else mip_expected(1 * 1 + 0.5 * 0.5, 1 + 0.5, 1 + k, w, pre, want);
                for (ch = 0; ch < w; ch++)
                    if (mip_off(six[k][ch], want[ch])) {
                        bad++;
                        TH_CHECK(0, "six at once, parent (%d,0,0), %s, %s: channel %d is %.9g, by hand %.9g", q, mip_filter_name(1 + k),
                                 mip_storage_name(mode), ch, six[k][ch], want[ch]);
                    }
            }
        }
    }
    printf("    parents (0,0,0) and (1,0,0) of a 3 x 2 x 2 level in 7 filters x 3 storages (and the six directions at once): %d wrong\n", bad);
}

/* A RADIANCE volume of a grid from its level 0 (premultiplied RGBA, x fastest), built as
   voxgi_inject_light builds its own: by the volume's level and mip builders. */
static voxgi_volume *radiance_volume(voxgi_context *ctx, const voxgi_grid *g, voxgi_mip_filter filter, const float *rgba)
{
    voxgi_volume_desc vd;
    const float *slots[VOXGI__VOLUME_SLOTS] = {NULL, NULL, NULL, NULL, NULL};
    voxgi_volume *vol = NULL;
    memset(&vd, 0, sizeof vd);
    vd.filter = filter;
    slots[VOXGI__RADIANCE_SLOT] = rgba;
    if (voxgi__volume_new(ctx, g, &vd, VOXGI_ATTRIBUTE_RADIANCE, &vol) != VOXGI_OK) return NULL;
    if (voxgi__volume_build(ctx, vol, slots) != VOXGI_OK) { voxgi_volume_destroy(ctx, vol); return NULL; }
    return vol;
}

/* A 4^3 volume's whole mip chain (4, 2, 1 voxels per axis) against the hand-worked parents:
   level 0 empty but for two blocks of 2x2x2 children, the opaque case's (becoming level-1 voxel
   (0,0,1)) and the mixed case's (level-1 voxel (1,0,1)); every other level-1 voxel empty. Level
   2 is the parent of those two level-1 voxels (children k4 and k5), each filtered in its own
   direction from its own direction's level 1. By hand, from the two cases' level-1 parents
   (opaque: C = 3.5, 1.5, 2, 1.25, 2.25, 0.75, 2.75 over A = 8, 4, ...; mixed: C = 2.3125,
   1.3125, 1.8125, 2.25, 2, 1.75, 1.96875 over A = 4, 2.75, 2.75, 3.5, 3.5, 3.375, 3.375; a
   parent's premultiplied red is C / m, its alpha A / m): */
static const double mip_level2_C[7] = {
    3.5 / 8 + 2.3125 / 8,                        /* isotropic: k4 + k5, premultiplied reds */
    1.5 / 4 + (1 - 1) * (1.3125 / 4),            /* +x: k4 (opaque) in front of k5 */
    1.8125 / 4 + (1 - 2.75 / 4) * (2.0 / 4),     /* -x: k5 in front of k4 */
    1.25 / 4 + 2.25 / 4,                         /* +y: k4, k5 each in front of an empty child */
    2.25 / 4 + 2.0 / 4,                          /* -y: each behind an empty one */
    0.75 / 4 + 1.75 / 4,                         /* +z: behind empty ones */
    2.75 / 4 + 1.96875 / 4};                     /* -z: in front of empty ones */
static const double mip_level2_A[7] = {1 + 4.0 / 8, 1 + (1 - 1) * (2.75 / 4), 2.75 / 4 + (1 - 2.75 / 4) * 1, 1 + 3.5 / 4, 1 + 3.5 / 4,
                                       1 + 3.375 / 4, 1 + 3.375 / 4};

/* The 4^3 chain on ctx, through voxgi_volume_create_dense (ALBEDO stored plainly, OPACITY alpha
   alone) and a RADIANCE volume (premultiplied), read back with voxgi_volume_read: the number of
   values that differ from the hand-worked ones (each printed), -1 when a volume could not be made. */
static int mip_chain_wrong(voxgi_context *ctx, const char *label)
{
    float albedo[64 * 4], opacity[64], radiance[64 * 4];
    const float *base[4];
    voxgi_grid g;
    int filter, bad = 0, k, ch, b, v;
    memset(albedo, 0, sizeof albedo); memset(opacity, 0, sizeof opacity); memset(radiance, 0, sizeof radiance);
    cubic(&g, 0, 1, 4);
    for (b = 0; b < 2; b++) /* block b (level-1 voxel (b,0,1)) holds case 1 - b: opaque, then mixed */
        for (k = 0; k < 8; k++) {
            int at = 2 * b + (k & 1) + 4 * (((k >> 1) & 1) + 4 * (2 + (k >> 2)));
            const float *c = mip_cases[1 - b].c[k];
            for (ch = 0; ch < 4; ch++) {
                albedo[4 * at + ch] = c[ch];
                radiance[4 * at + ch] = ch < 3 ? c[ch] * c[3] : c[3];
            }
            opacity[at] = c[3];
        }
    base[0] = albedo; base[1] = base[2] = NULL; base[3] = opacity;
    for (filter = 0; filter < 2; filter++) {
        voxgi_volume_desc vd;
        voxgi_volume *vol[2] = {NULL, NULL}; /* albedo and opacity; radiance */
        voxgi_volume_info info;
        int dirs = filter ? 6 : 1, d, lev;
        memset(&vd, 0, sizeof vd);
        vd.filter = (voxgi_mip_filter)filter;
        if (voxgi_volume_create_dense(ctx, &g, &vd, base, &vol[0]) != VOXGI_OK || !(vol[1] = radiance_volume(ctx, &g, vd.filter, radiance))) {
            printf("    %s: %s\n", label, voxgi_last_error(ctx));
            voxgi_volume_destroy(ctx, vol[0]);
            return -1;
        }
        voxgi_volume_query(vol[0], &info);
        if (info.levels != 3) { printf("    %s: %d levels, not 3\n", label, info.levels); bad++; }
        for (d = 0; d < dirs; d++)
            for (lev = 0; lev < 3 && lev < info.levels; lev++)
                for (v = 0; v < 3; v++) { /* 0 albedo (plain), 1 radiance (premultiplied), 2 opacity (alpha alone) */
                    int w = v == 2 ? 1 : 4, n = 4 >> lev, f = filter ? 1 + d : 0, i;
                    float got[64 * 4];
                    voxgi_attribute which = v == 0 ? VOXGI_ATTRIBUTE_ALBEDO : (v == 1 ? VOXGI_ATTRIBUTE_RADIANCE : VOXGI_ATTRIBUTE_OPACITY);
                    if (voxgi_volume_read(ctx, vol[v == 1], which, (voxgi_direction)d, lev, got, sizeof got, NULL) != VOXGI_OK) {
                        printf("    %s: %s\n", label, voxgi_last_error(ctx));
                        bad++;
                        continue;
                    }
                    for (i = 0; i < n * n * n; i++) {
                        double want[4] = {0, 0, 0, 0};
                        const float *in = v == 0 ? albedo : (v == 1 ? radiance : opacity);
                        if (lev == 0) for (ch = 0; ch < w; ch++) want[ch] = in[w * i + ch]; /* the same in every direction */
                        else if (lev == 1 && (i == 0 + 2 * (0 + 2 * 1) || i == 1 + 2 * (0 + 2 * 1))) {
                            const mip_case *mc = &mip_cases[i == 4 ? 1 : 0];
                            mip_expected(mc->C[f], mc->A[f], f, w, v == 1, want);
                        } else if (lev == 2) mip_expected(mip_level2_C[f], mip_level2_A[f], f, w, v == 1, want);
                        for (ch = 0; ch < w; ch++)
                            if (mip_off(got[w * i + ch], want[ch])) {
                                bad++;
                                TH_CHECK(0, "%s, %s volume, %s, level %d voxel %d channel %d: %.9g, by hand %.9g", label, mip_storage_name(v),
                                         mip_filter_name(f), lev, i, ch, got[w * i + ch], want[ch]);
                            }
                    }
                }
        voxgi_volume_destroy(ctx, vol[0]);
        voxgi_volume_destroy(ctx, vol[1]);
    }
    return bad;
}

static void test_volume_mips_by_hand(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    int bad = mip_chain_wrong(ctx, "CPU");
    printf("    a 4^3 chain, isotropic and anisotropic, albedo, radiance and opacity, every level: %d values wrong\n", bad);
    TH_CHECK(bad == 0, "%d volume values differ from the hand-worked ones", bad);
    voxgi_destroy(ctx);
}

/* The GL volumes' compute pass (shaders/volume_mip.glsl) against the same hand-worked 4^3 chain
   as the CPU's (test_volume_mips_by_hand). */
static void test_gl_volume_mips_by_hand(void)
{
    voxgi_context *ctx;
    int bad;
    if (!have_gl()) return;
    ctx = make_ctx(VOXGI_BACKEND_GL, 0);
    bad = mip_chain_wrong(ctx, "GL");
    printf("    GL: a 4^3 chain, isotropic and anisotropic, albedo, radiance and opacity, every level: %d values wrong\n", bad);
    TH_CHECK(bad == 0, "%d GL volume values differ from the hand-worked ones", bad);
    voxgi_destroy(ctx);
}


/* ---------------------------------------------------------------- regions and rays leaving surfaces */
/* The region labels of a volume's empty space (voxgi__volume_regions) against a flood fill:
   random 13 x 11 x 9 grids, 45% of the voxels filled; two empty voxels share a label exactly when
   6-connected through empty voxels, a region touching the grid's faces is OPEN, the others
   enclosed; no labels at all where nothing is enclosed. */
static void test_region_labels_flood_fill(void)
{
    enum { X = 13, Y = 11, Z = 9, N = X * Y * Z };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    static float rad[4 * N], back[4 * N], side[4 * N];
    static int comp[N], open_comp[N], stack[N];
    static uint32_t label_of[N];
    fx_rng rng;
    int trial, bad = 0, enclosed_seen = 0;
    rng = fx_rng_seeded(77);
    for (trial = 0; trial < 40; trial++) {
        voxgi_grid g;
        voxgi_volume_desc vd;
        voxgi_volume *vol = NULL;
        const float *base[VOXGI__VOLUME_SLOTS] = {NULL, NULL, NULL, NULL, NULL, NULL, NULL};
        int i, c, ncomp = 0, enclosed = 0;
        memset(&g, 0, sizeof g);
        g.res[0] = X; g.res[1] = Y; g.res[2] = Z;
        g.voxel_size = 1;
        memset(&vd, 0, sizeof vd);
        memset(back, 0, sizeof back);
        memset(side, 0, sizeof side);
        for (i = 0; i < N; i++) { rad[4 * i + 3] = fx_rng_range(&rng, 0, 1) < 0.45 ? 1.0f : 0.0f; comp[i] = -1; }
        for (i = 0; i < N; i++) { /* the oracle: flood fill */
            int sp = 0;
            if (rad[4 * i + 3] > 0 || comp[i] >= 0) continue;
            open_comp[ncomp] = 0;
            comp[i] = ncomp;
            stack[sp++] = i;
            while (sp) {
                int v = stack[--sp], x = v % X, y = v / X % Y, z = v / (X * Y), q;
                if (x == 0 || y == 0 || z == 0 || x == X - 1 || y == Y - 1 || z == Z - 1) open_comp[ncomp] = 1;
                for (q = 0; q < 6; q++) {
                    int nx = x + (q == 0) - (q == 1), ny = y + (q == 2) - (q == 3), nz = z + (q == 4) - (q == 5), w;
                    if (nx < 0 || ny < 0 || nz < 0 || nx >= X || ny >= Y || nz >= Z) continue;
                    w = nx + X * (ny + Y * nz);
                    if (rad[4 * w + 3] > 0 || comp[w] >= 0) continue;
                    comp[w] = ncomp;
                    stack[sp++] = w;
                }
            }
            enclosed += !open_comp[ncomp];
            ncomp++;
        }
        base[VOXGI__RADIANCE_SLOT] = rad;
        base[VOXGI__BACK_SLOT] = back;
        base[VOXGI__SIDE_SLOT] = side;
        TH_CHECK(voxgi__volume_new(ctx, &g, &vd, VOXGI__RADIANCE_FAMILY, &vol) == VOXGI_OK && voxgi__volume_regions(ctx, vol, base) == VOXGI_OK,
                 "regions: %s", voxgi_last_error(ctx));
        if (!vol) continue;
        enclosed_seen += enclosed;
        if (!enclosed) bad += vol->regions != NULL;
        else if (!vol->regions) bad++;
        else {
            for (c = 0; c < ncomp; c++) label_of[c] = 0;
            for (i = 0; i < N && bad < 5; i++) {
                uint32_t l = vol->regions[i];
                if (comp[i] < 0) continue;
                if (!l || (l == VOXGI__REGION_OPEN) != open_comp[comp[i]] || (label_of[comp[i]] && label_of[comp[i]] != l)) {
                    TH_CHECK(0, "trial %d: voxel %d of region %d (%s) labelled %u", trial, i, comp[i], open_comp[comp[i]] ? "open" : "enclosed", l);
                    bad++;
                }
                label_of[comp[i]] = l;
            }
            for (c = 0; c < ncomp; c++) { /* distinct enclosed regions, distinct labels */
                int d;
                for (d = c + 1; d < ncomp; d++)
                    if (!open_comp[c] && label_of[c] && label_of[c] == label_of[d]) bad++;
            }
        }
        voxgi_volume_destroy(ctx, vol);
    }
    printf("    40 random grids, %d enclosed regions: %d labels wrong\n", enclosed_seen, bad);
    TH_CHECK(bad == 0 && enclosed_seen > 40, "%d region labels wrong (%d enclosed regions)", bad, enclosed_seen);
    voxgi_destroy(ctx);
}

/* Two rooms in a res[0] x res[1] x res[2] shell of voxels whose faces face in, split by a wall on
   the boundary x = 6 filling voxels 5 and 6 (room A x 1-4, B x 7 on): whether voxel c is a
   surface's, and then its side plane (n . p = plane, n facing A at the wall, in elsewhere). */
static int two_rooms_surface(const int res[3], const int c[3], int n[3], float *plane)
{
    int a;
    n[0] = n[1] = n[2] = 0;
    if (c[0] == 5 || c[0] == 6) {
        n[0] = -1;
        *plane = -6;
        return 1;
    }
    for (a = 0; a < 3; a++)
        if (!n[0] && !n[1] && !n[2] && (c[a] == 0 || c[a] == res[a] - 1)) n[a] = c[a] == 0 ? 1 : -1;
    if (!n[0] && !n[1] && !n[2]) return 0;
    a = n[0] ? 0 : n[1] ? 1 : 2;
    *plane = (float)(n[a] * (c[a] == 0 ? 1 : c[a]));
    return 1;
}

/* The two rooms' volume (two_rooms_surface; 12 x 6 x 6 voxels of 1, RADIANCE, BACK and SIDE, its
   levels and regions): lit from A (the front of every voxel of x 1-6), or from B (the wall's back,
   facing B, and the front of B's far wall). NULL where it cannot be made. */
static voxgi_volume *two_rooms_volume(voxgi_context *ctx, int from_b)
{
    enum { X = 12, Y = 6, Z = 6, N = X * Y * Z };
    static float rad[4 * N], back[4 * N], side[4 * N];
    const float *base[VOXGI__VOLUME_SLOTS] = {NULL, NULL, NULL, NULL, NULL, NULL, NULL};
    voxgi_grid g;
    voxgi_volume_desc vd;
    voxgi_volume *vol = NULL;
    int x, y, z, a;
    memset(&g, 0, sizeof g);
    g.res[0] = X; g.res[1] = Y; g.res[2] = Z;
    g.voxel_size = 1;
    memset(&vd, 0, sizeof vd);
    memset(rad, 0, sizeof rad);
    memset(back, 0, sizeof back);
    memset(side, 0, sizeof side);
    for (z = 0; z < Z; z++)
        for (y = 0; y < Y; y++)
            for (x = 0; x < X; x++) {
                int i = x + X * (y + Y * z), c[3], n[3];
                float plane, *lit = NULL;
                c[0] = x; c[1] = y; c[2] = z;
                if (!two_rooms_surface(g.res, c, n, &plane)) continue;
                rad[4 * i + 3] = back[4 * i + 3] = 1;
                for (a = 0; a < 3; a++) side[4 * i + a] = (float)n[a];
                side[4 * i + 3] = plane;
                if (!from_b && x >= 1 && x <= 6) lit = rad + 4 * i;
                if (from_b && (x == 5 || x == 6)) lit = back + 4 * i;
                if (from_b && x == X - 1) lit = rad + 4 * i;
                if (lit) lit[0] = lit[1] = lit[2] = 1;
            }
    base[VOXGI__RADIANCE_SLOT] = rad;
    base[VOXGI__BACK_SLOT] = back;
    base[VOXGI__SIDE_SLOT] = side;
    if (voxgi__volume_new(ctx, &g, &vd, VOXGI__RADIANCE_FAMILY, &vol) != VOXGI_OK) return NULL;
    if (voxgi__volume_build(ctx, vol, base) != VOXGI_OK) { voxgi_volume_destroy(ctx, vol); return NULL; }
    return vol;
}

/* The surfaces' labels (voxgi__volume_regions), built by hand: a closed box of 12 x 6 x 6 voxels,
   its shell one voxel thick facing in, split by a wall of no thickness on the boundary x = 6,
   which fills the columns x = 5 and 6, its lit side facing -x into room A (x 1-4); room B (x 7-10)
   has no light. Each voxel's side plane is its surfaces' (the wall's: x = 6), its front lit where
   it faces A. The wall's voxel beside A holds BORDER | A; the one beside B, whose light goes into
   A across its twin, BORDER | A | UNSEEN (seen from no region at level 0); B's shell, dark, no
   label; A's shell BORDER | A. Level 1: a voxel holding the wall's unseen layer and B's space is
   MIXED (the wall counts as A, not as no region), one of B's space and dark shell B (a dark region
   closes the mips too). With every voxel's light turned off, no surface is labelled at all. */
static void test_region_labels_of_surfaces(void)
{
    enum { X = 12, Y = 6, Z = 6, N = X * Y * Z };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    static float rad[4 * N], back[4 * N], side[4 * N];
    int x, y, z, a, lit, bad = 0;
    for (lit = 1; lit >= 0; lit--) {
        voxgi_grid g;
        voxgi_volume_desc vd;
        voxgi_volume *vol = NULL;
        const float *base[VOXGI__VOLUME_SLOTS] = {NULL, NULL, NULL, NULL, NULL, NULL, NULL};
        uint32_t ra = 0, rb = 0;
        memset(&g, 0, sizeof g);
        g.res[0] = X; g.res[1] = Y; g.res[2] = Z;
        g.voxel_size = 1;
        memset(&vd, 0, sizeof vd);
        memset(rad, 0, sizeof rad);
        memset(back, 0, sizeof back);
        memset(side, 0, sizeof side);
        for (z = 0; z < Z; z++)
            for (y = 0; y < Y; y++)
                for (x = 0; x < X; x++) {
                    int i = x + X * (y + Y * z), c[3], n[3];
                    float plane;
                    c[0] = x; c[1] = y; c[2] = z;
                    if (!two_rooms_surface(g.res, c, n, &plane)) continue;
                    rad[4 * i + 3] = back[4 * i + 3] = side[4 * i + 3] = 1;
                    for (a = 0; a < 3; a++) side[4 * i + a] = (float)n[a];
                    side[4 * i + 3] = plane;
                    if (lit && (x == 5 || x == 6 || (x >= 1 && x <= 4))) rad[4 * i] = rad[4 * i + 1] = rad[4 * i + 2] = 1;
                }
        base[VOXGI__RADIANCE_SLOT] = rad;
        base[VOXGI__BACK_SLOT] = back;
        base[VOXGI__SIDE_SLOT] = side;
        TH_CHECK(voxgi__volume_new(ctx, &g, &vd, VOXGI__RADIANCE_FAMILY, &vol) == VOXGI_OK && voxgi__volume_regions(ctx, vol, base) == VOXGI_OK &&
                     vol->regions, "regions: %s", voxgi_last_error(ctx));
        if (!vol || !vol->regions) { voxgi_volume_destroy(ctx, vol); continue; }
        ra = vol->regions[2 + X * (2 + Y * 2)];
        rb = vol->regions[8 + X * (2 + Y * 2)];
        TH_CHECK(ra > VOXGI__REGION_OPEN && rb > VOXGI__REGION_OPEN && ra != rb && !(ra & VOXGI__REGION_BORDER), "rooms labelled %x and %x", ra, rb);
        for (z = 1; z < Z - 1; z++)
            for (y = 1; y < Y - 1; y++) {
                uint32_t beside_a = vol->regions[5 + X * (y + Y * z)], beside_b = vol->regions[6 + X * (y + Y * z)];
                uint32_t floor_a = vol->regions[3 + X * (Y * z)], floor_b = vol->regions[9 + X * (Y * z)];
                if (lit) bad += beside_a != (VOXGI__REGION_BORDER | ra) || beside_b != (VOXGI__REGION_BORDER | VOXGI__REGION_UNSEEN | ra) ||
                                floor_a != (VOXGI__REGION_BORDER | ra) || floor_b != 0;
                else bad += beside_a || beside_b || floor_a || floor_b;
            }
        if (lit) { /* level 1 (6 x 3 x 3): x = 3 holds x 6-7 (the unseen layer and B), x = 4 holds x 8-9 (B's space, y 2-3) */
            const uint32_t *l1 = vol->regions + vol->first[1];
            int dx = vol->dims[1][0], dy = vol->dims[1][1];
            TH_CHECK(l1[3 + dx * (1 + dy * 1)] == VOXGI__REGION_MIXED && l1[4 + dx * (1 + dy * 1)] == rb, "level 1: %x beside the wall, %x in B (B %x)",
                     l1[3 + dx * (1 + dy * 1)], l1[4 + dx * (1 + dy * 1)], rb);
        }
        voxgi_volume_destroy(ctx, vol);
    }
    printf("    two rooms split by a wall on a voxel boundary: %d surface labels wrong\n", bad);
    TH_CHECK(bad == 0, "%d surface labels wrong", bad);
    voxgi_destroy(ctx);
}

/* Where a side's normal finds no empty voxel (voxgi__region_lit_ahead): the one lit region with an
   empty voxel within two voxels in front of the side. A 7^3 grid split by a surface's column at
   x = 3 (regions 2 left, 3 right): the side facing -x finds 2 when 2 is lit, nothing when only 3
   is (3 lies behind it); a side along the column (+y) has both in front, so two lit regions make it
   MIXED; the surfaces' own voxels (BORDER) never count. */
static void test_region_lit_ahead(void)
{
    enum { S = 7 };
    static uint32_t lab[S * S * S];
    const int dm[3] = {S, S, S}, c[3] = {3, 3, 3};
    const double left[3] = {-1, 0, 0}, right[3] = {1, 0, 0}, up[3] = {0, 1, 0};
    unsigned char lit[4] = {0, 0, 0, 0};
    int x, y, z, bad = 0;
    for (z = 0; z < S; z++)
        for (y = 0; y < S; y++)
            for (x = 0; x < S; x++)
                lab[x + S * (y + S * z)] = x < 3 ? 2u : x > 3 ? 3u : (y == 5 ? VOXGI__REGION_BORDER | 3u : 0u);
    lit[2] = 1;
    bad += voxgi__region_lit_ahead(dm, lab, lit, c, left) != 2;
    bad += voxgi__region_lit_ahead(dm, lab, lit, c, right) != 0;
    bad += voxgi__region_lit_ahead(dm, lab, lit, c, up) != 2;
    lit[2] = 0;
    lit[3] = 1;
    bad += voxgi__region_lit_ahead(dm, lab, lit, c, left) != 0;
    bad += voxgi__region_lit_ahead(dm, lab, lit, c, right) != 3;
    lit[2] = 1;
    bad += voxgi__region_lit_ahead(dm, lab, lit, c, up) != VOXGI__REGION_MIXED;
    bad += voxgi__region_lit_ahead(dm, lab, lit, c, left) != 2;
    printf("    a surface's column between two regions: %d of 7 sides wrong\n", bad);
    TH_CHECK(bad == 0, "%d of 7 sides find the wrong lit region", bad);
}

/* ===================================================================== 7. octree */

/* ---------------------------------------------------------------- formats */
/* Every finite half survives float and back; every midpoint between neighbours rounds to the
   even one, and a float just above or below it to the nearer; beyond the range: infinity. */
static void test_half_rounding(void)
{
    uint32_t h;
    int bad = 0;
    for (h = 0; h < 0x10000u; h++) {
        uint16_t hh = (uint16_t)h, up = (uint16_t)(h + 1);
        double v, next, mid;
        float f;
        if ((h & 0x7C00u) == 0x7C00u) continue; /* infinities and NaNs */
        v = voxgi__float_from_half(hh);
        bad += voxgi__half_from_float((float)v) != hh;
        if ((h & 0x7FFFu) == 0x7BFFu) { /* the largest finite: beyond its midpoint to 65536 is infinity */
            double away = v < 0 ? -1 : 1;
            bad += voxgi__half_from_float((float)(v + 15.99 * away)) != hh || voxgi__half_from_float((float)(v + 16 * away)) != ((hh & 0x8000u) | 0x7C00u);
            continue;
        }
        next = voxgi__float_from_half(up);
        mid = (v + next) / 2; /* exact in float: halves have 11 significant bits */
        f = (float)mid;
        bad += voxgi__half_from_float(f) != ((h & 1u) ? up : hh);
        bad += voxgi__half_from_float(nextafterf(f, (float)next)) != up || voxgi__half_from_float(nextafterf(f, (float)v)) != hh;
    }
    TH_CHECK(bad == 0, "%d half conversions wrong", bad);
    TH_CHECK(voxgi__half_from_float(1e-9f) == 0 && voxgi__half_from_float(-1e-9f) == 0x8000u && voxgi__half_from_float(1e30f) == 0x7C00u,
             "tiny and huge values");
}

/* ---------------------------------------------------------------- GL */
/* The GPU-built octree against the CPU's, through lookups (allocation order differs, so the
   slots do, the values at every place do not): the same nodes per level, point lookups at every
   level bit for bit, samples within float rounding, neighbour pointers right, in both value
   formats; grids 27^3 (odd: incomplete parents), 2 (depth 1) and an empty one. */
static void test_gl_svo_equals_cpu(void)
{
    voxgi_context *cpu, *gl;
    material_sphere s;
    int res_i, b;
    double worst_sample = 0;
    fx_rng rng = fx_rng_seeded(11); /* the sample points of every grid and format, in turn */
    if (!have_gl()) return;
    cpu = make_ctx(VOXGI_BACKEND_CPU, 0);
    gl = make_ctx(VOXGI_BACKEND_GL, 0);
    material_sphere_make(&s);
    for (res_i = 0; res_i < 3; res_i++) {
        voxgi_voxelize_desc xd;
        voxgi_voxels *vox[2] = {NULL, NULL};
        int fmt;
        memset(&xd, 0, sizeof xd);
        if (res_i == 2) cubic(&xd.grid, 5, 1, 4); /* far from the sphere: no voxels */
        else cubic(&xd.grid, -1.1, 2.2, res_i == 0 ? 27 : 2);
        xd.attributes = 15;
        for (b = 0; b < 2; b++) voxgi_voxelize(b ? gl : cpu, &s.scene, &xd, &vox[b]);
        TH_CHECK(vox[0] && vox[1], "voxelization failed");
        for (fmt = 0; fmt < 2 && vox[0] && vox[1]; fmt++) {
            voxgi_svo_desc sd;
            voxgi_svo *svo[2] = {NULL, NULL};
            voxgi_svo_info info[2];
            int lev, a, diff = 0, nodes = 0, wrong;
            memset(&sd, 0, sizeof sd);
            sd.neighbours = 1;
            sd.format = (voxgi_svo_format)fmt;
            sd.bricks = fmt; /* half floats with bricks, floats without */
            for (b = 0; b < 2; b++) {
                if (voxgi_svo_create(b ? gl : cpu, vox[b], &sd, &svo[b]) != VOXGI_OK) printf("    %s\n", voxgi_last_error(b ? gl : cpu));
                voxgi_svo_query(svo[b], &info[b]);
            }
            TH_CHECK(svo[0] && svo[1] && info[1].backend == VOXGI_BACKEND_GL, "octree creation failed");
            if (!svo[0] || !svo[1]) continue;
            TH_CHECK(info[0].nodes == info[1].nodes && info[0].leaf_slots == info[1].leaf_slots && info[0].bytes == info[1].bytes &&
                     info[0].depth == info[1].depth && info[0].leaf_voxels == info[1].leaf_voxels &&
                     memcmp(info[0].level_nodes, info[1].level_nodes, sizeof info[0].level_nodes) == 0,
                     "res %d: GL octree %llu nodes, %llu leaf slots; CPU %llu, %llu", xd.grid.res[0], (unsigned long long)info[1].nodes,
                     (unsigned long long)info[1].leaf_slots, (unsigned long long)info[0].nodes, (unsigned long long)info[0].leaf_slots);
            for (lev = 0; lev <= info[0].depth; lev++) { /* every node place at every level, and a place outside the cube */
                uint32_t n = 1u << lev, sh = (uint32_t)(info[0].depth - lev), q = 0, x, y, z;
                uint32_t *coords = (uint32_t *)malloc(((size_t)n * n * n + 1) * 12);
                float *got[2];
                got[0] = (float *)malloc(((size_t)n * n * n + 1) * 16);
                got[1] = (float *)malloc(((size_t)n * n * n + 1) * 16);
                for (z = 0; z < n; z++)
                    for (y = 0; y < n; y++)
                        for (x = 0; x < n; x++, q++) { coords[3 * q] = x << sh; coords[3 * q + 1] = y << sh; coords[3 * q + 2] = z << sh; }
                coords[3 * q] = 1u << info[0].depth; coords[3 * q + 1] = coords[3 * q + 2] = 0; q++;
                for (a = 0; a < 4; a++) {
                    voxgi_attribute which = (voxgi_attribute)(1 << a);
                    for (b = 0; b < 2; b++)
                        TH_CHECK(voxgi_svo_lookup(b ? gl : cpu, svo[b], which, lev, q, coords, got[b]) == VOXGI_OK, "lookup: %s",
                                 voxgi_last_error(b ? gl : cpu));
                    diff += memcmp(got[0], got[1], (size_t)q * (a == 3 ? 4u : 16u)) != 0;
                }
                free(coords); free(got[0]); free(got[1]);
            }
            TH_CHECK(diff == 0, "res %d format %d: GL and CPU lookups differ at %d level/attribute pairs", xd.grid.res[0], fmt, diff);
            for (lev = 0; lev < info[0].depth && sd.bricks; lev++) { /* every brick, texel for texel */
                uint32_t n = 1u << lev, sh = (uint32_t)(info[0].depth - lev), x, y, z;
                for (z = 0; z < n; z++)
                    for (y = 0; y < n; y++)
                        for (x = 0; x < n; x++) {
                            uint32_t c[3];
                            float br[2][64 * 4];
                            c[0] = x << sh; c[1] = y << sh; c[2] = z << sh;
                            for (a = 0; a < 4; a++) {
                                for (b = 0; b < 2; b++) voxgi_svo_brick(b ? gl : cpu, svo[b], (voxgi_attribute)(1 << a), lev, c, br[b]);
                                diff += memcmp(br[0], br[1], (size_t)(a == 3 ? 64 * 4 : 64 * 16)) != 0;
                            }
                        }
            }
            TH_CHECK(diff == 0 && info[1].brick_bytes == info[0].brick_bytes, "res %d: %d GL bricks differ from the CPU's", xd.grid.res[0], diff);
            {   /* samples: float weights on GL, double on the CPU */
                float pos[3 * 400], lods[400], out[2][4 * 400];
                int i;
                for (i = 0; i < 400; i++) {
                    pos[3 * i] = (float)fx_rng_range(&rng, -2, 29);
                    pos[3 * i + 1] = (float)fx_rng_range(&rng, -2, 29);
                    pos[3 * i + 2] = (float)fx_rng_range(&rng, -2, 29);
                    lods[i] = (float)fx_rng_range(&rng, -0.5, 6);
                }
                for (a = 0; a < 4; a++) {
                    for (b = 0; b < 2; b++)
                        TH_CHECK(voxgi_svo_sample(b ? gl : cpu, svo[b], (voxgi_attribute)(1 << a), 400, pos, lods, out[b]) == VOXGI_OK,
                                 "sampling: %s", voxgi_last_error(b ? gl : cpu));
                    for (i = 0; i < 400 * (a == 3 ? 1 : 4); i++) {
                        double e = fabs((double)out[0][i] - out[1][i]) / fmax(1, fabs(out[0][i]));
                        if (e > worst_sample) worst_sample = e;
                    }
                }
            }
            wrong = svo_wrong_neighbours(gl, svo[1], info[1].depth, &nodes);
            for (lev = 1; lev < info[1].depth; lev++) nodes -= (int)info[1].level_nodes[lev];
            TH_CHECK(wrong == 0 && nodes == 0, "%d wrong GL neighbour pointers, %d nodes unaccounted for", wrong, nodes);
            if (res_i == 0 && fmt == 0) { /* a memory budget below the octree: a clean refusal; the exact size: built */
                voxgi_desc d;
                voxgi_context *small = NULL;
                voxgi_svo *none = NULL;
                ctx_desc(&d, VOXGI_BACKEND_GL);
                d.memory_budget = info[1].bytes - 1;
                voxgi_create(&d, &small);
                TH_CHECK(small && voxgi_svo_create(small, vox[1], &sd, &none) == VOXGI_ERR_TOO_LARGE && !none, "budget %lu: %s",
                         (unsigned long)d.memory_budget, small ? voxgi_last_error(small) : "no context");
                voxgi_destroy(small);
                d.memory_budget = info[1].bytes;
                voxgi_create(&d, &small);
                TH_CHECK(small && voxgi_svo_create(small, vox[1], &sd, &none) == VOXGI_OK && none, "the exact budget refused");
                voxgi_svo_destroy(small, none);
                voxgi_destroy(small);
            }
            for (b = 0; b < 2; b++) voxgi_svo_destroy(b ? gl : cpu, svo[b]);
        }
        for (b = 0; b < 2; b++) voxgi_voxels_destroy(b ? gl : cpu, vox[b]);
    }
    {   /* footprint -> lod: the GLSL function and the C one agree (log2 within an ulp), 0 below a voxel */
        static const float d[8] = {0.0f, 0.25f, 1.0f, 1.5f, 2.0f, 8.0f, 1000.0f, 65536.0f};
        float pts[8 * 4], lod[8 * 4];
        voxgi_svo_desc sd;
        voxgi_svo *one = NULL;
        voxgi_voxels *v = NULL;
        voxgi_voxelize_desc xd;
        int i, bad = 0;
        memset(&xd, 0, sizeof xd); memset(&sd, 0, sizeof sd); memset(pts, 0, sizeof pts);
        cubic(&xd.grid, -1.1, 2.2, 4);
        xd.attributes = VOXGI_ATTRIBUTE_ALBEDO;
        voxgi_voxelize(gl, &s.scene, &xd, &v);
        if (v) voxgi_svo_create(gl, v, &sd, &one);
        for (i = 0; i < 8; i++) pts[4 * i + 3] = d[i];
        TH_CHECK(one && voxgi__svo_points_gl(gl, one, 0, 2, 8, pts, lod) == VOXGI_OK, "footprints on GL");
        for (i = 0; i < 8 && one; i++) bad += fabsf(lod[4 * i] - voxgi_lod_from_footprint(d[i])) > 1e-6f * fmaxf(1, lod[4 * i]);
        TH_CHECK(bad == 0 && voxgi_lod_from_footprint(8) == 3 && voxgi_lod_from_footprint(0.5f) == 0 && voxgi_lod_from_footprint(1) == 0,
                 "footprint lods: %d differ", bad);
        voxgi_svo_destroy(gl, one);
        voxgi_voxels_destroy(gl, v);
    }
    printf("    GL octree samples within %.3g (relative) of the CPU's\n", worst_sample);
    TH_CHECK(worst_sample <= 1e-6, "GL octree samples differ from the CPU's by %g", worst_sample);
    material_sphere_free(&s);
    voxgi_destroy(cpu);
    voxgi_destroy(gl);
}

/* ===================================================================== 8. cone tracing */

/* ---------------------------------------------------------------- cone tracing and light */
/* qsort's order of doubles. */
static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The diffuse cone set: n directions (voxgi__cone_direction, in the frame whose z is the normal)
   that split the cosine-weighted hemisphere into n equal shares, each cone weighted pi / n in the
   irradiance, with the default half-angle acos(1 - 1/n). What that promises, tested as such:
   - unit directions in the upper hemisphere;
   - cosine-distributed: projected onto the disc (x, y) a cosine-distributed direction is uniform
     over the unit disc (Malley), so r^2 = sin^2(theta) is uniform on [0, 1]: the largest gap
     between the share of the set with r^2 <= t and t (Kolmogorov-Smirnov) is at most 1 / (2n),
     the least n points can have (one per equal share); and over the disc, every polar box of an
     8 x 8 grid of equal-area cells (r^2 and the azimuth in eighths) holds its area's share of the
     points within 4 / n (low discrepancy; a random set is off by about 1 / sqrt(n));
   - the set's mean of f, (1/n) sum f(d_k), is a quadrature of the cosine-weighted mean
     (1/pi) int f cos(theta) dw; by hand, with dw = sin(theta) dtheta dphi and s = sin(theta):
     f = 1: 1; cos(theta): 2 int cos^2 sin = 2/3; cos^2: 2 int cos^3 sin = 1/2; x^2 = s^2 cos^2(phi):
     (1/pi) pi int s^3 ds = 1/4, y^2 the same; x, y, xy: 0 (odd in phi); x^2 y^2: (1/pi) (pi/4)
     int s^5 ds = 1/24. Each within 1 / n of it from n = 8 on, so converging as n grows;
   - the weights sum to 1: under a uniform opaque radiance L every cone sees L, and
     voxgi_cone_trace gives pi L and occlusion 1 for any n, isotropic or anisotropic;
   - the default half-angle gives each cone 1/n of the hemisphere's solid angle: n 2 pi (1 - cos) = 2 pi. */
static void test_cone_set(void)
{
    static const int ns[] = {1, 2, 3, 5, 8, 16, 64, 256, 1024};
    static const double exact[9] = {1, 2.0 / 3, 0.5, 0.25, 0.25, 0, 0, 0, 1.0 / 24};
    static const char *fname[9] = {"1", "cos", "cos^2", "x^2", "y^2", "x", "y", "xy", "x^2 y^2"};
    static double u[1024];
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    double worst_err[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}, worst_ks = 0, worst_box = 0, worst_irr = 0, worst_cover = 0;
    float rad[64 * 4], pos[3] = {0.625f, 0.625f, 0.25f}, nrm[3] = {0, 0, 1};
    voxgi_grid g;
    int i, k, f, bad = 0, filter;
    for (i = 0; i < (int)(sizeof ns / sizeof ns[0]); i++) {
        int n = ns[i], cell[8][8], a, b, c, e;
        double mean[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
        memset(cell, 0, sizeof cell);
        for (k = 0; k < n; k++) {
            double d[3], x, y, z, phi;
            voxgi__cone_direction(k, n, d);
            x = d[0]; y = d[1]; z = d[2];
            bad += fabs(x * x + y * y + z * z - 1) > 1e-12 || !(z > 0);
            u[k] = x * x + y * y;
            phi = atan2(y, x) / (2 * PI);
            if (phi < 0) phi += 1;
            a = (int)(u[k] * 8); b = (int)(phi * 8);
            cell[a > 7 ? 7 : a][b > 7 ? 7 : b]++;
            mean[0] += 1.0 / n; mean[1] += z / n; mean[2] += z * z / n; mean[3] += x * x / n; mean[4] += y * y / n;
            mean[5] += x / n; mean[6] += y / n; mean[7] += x * y / n; mean[8] += x * x * y * y / n;
        }
        qsort(u, (size_t)n, sizeof u[0], cmp_double);
        for (k = 0; k < n; k++) { /* the empirical distribution of r^2 against the uniform one, both sides of each step */
            double ks = fmax(fabs((k + 1.0) / n - u[k]), fabs((double)k / n - u[k]));
            if (ks > 0.5 / n + 1e-12) bad++;
            worst_ks = fmax(worst_ks, ks * n);
        }
        for (a = 0; a < 8 && n >= 16; a++) /* every box [a, b) x [c, e) of cells */
            for (b = a + 1; b <= 8; b++)
                for (c = 0; c < 8; c++)
                    for (e = c + 1; e <= 8; e++) {
                        int cnt = 0, r, s;
                        double off;
                        for (r = a; r < b; r++) for (s = c; s < e; s++) cnt += cell[r][s];
                        off = fabs((double)cnt / n - (b - a) * (e - c) / 64.0) * n;
                        worst_box = fmax(worst_box, off);
                        bad += off > 4;
                    }
        for (f = 0; f < 9 && n >= 8; f++) {
            double err = fabs(mean[f] - exact[f]);
            worst_err[f] = fmax(worst_err[f], err * n);
            if (err > 1.0 / n) { bad++; printf("    n %d: the mean of %s is %.6f, not %.6f\n", n, fname[f], mean[f], exact[f]); }
        }
    }
    printf("    n up to 1024: r^2 within %.3f / n of uniform, polar boxes within %.2f / n of their share; "
           "means within n x (1 %.2g, cos %.2g, cos^2 %.2g, x^2 %.2g, y^2 %.2g, x %.2g, y %.2g, xy %.2g, x^2y^2 %.2g) / n\n",
           worst_ks, worst_box, worst_err[0], worst_err[1], worst_err[2], worst_err[3], worst_err[4], worst_err[5], worst_err[6], worst_err[7],
           worst_err[8]);
    TH_CHECK(bad == 0, "%d failures of the cone set's directions or distribution", bad);
    /* the weights and the default half-angle, through the library: a 4^3 radiance volume, opaque and
       uniform, L = (0.5, 1, 2); a point whose first samples (1.5 voxels along the normal) fall on a
       voxel centre, (2.5, 2.5, 2.5) in grid units */
    cubic(&g, 0, 1, 4);
    for (k = 0; k < 64; k++) { rad[4 * k] = 0.5f; rad[4 * k + 1] = 1; rad[4 * k + 2] = 2; rad[4 * k + 3] = 1; }
    for (filter = 0; filter < 2; filter++) {
        voxgi_volume *vol = radiance_volume(ctx, &g, (voxgi_mip_filter)filter, rad);
        static const int cones[5] = {1, 2, 7, 0, 64}; /* 0: the default, 16 */
        TH_CHECK(vol != NULL, "radiance volume: %s", voxgi_last_error(ctx));
        for (i = 0; i < 5 && vol; i++) {
            voxgi_cone_desc cd;
            voxgi__cone_job J;
            float irr[3] = {0, 0, 0}, occ = 0;
            int a;
            memset(&cd, 0, sizeof cd);
            cd.cones = cones[i];
            TH_CHECK(voxgi_cone_trace(ctx, VOLUME_SOURCE(vol), &cd, 1, pos, nrm, irr, &occ) == VOXGI_OK && voxgi__cone_job_init(ctx, VOLUME_SOURCE(vol), &cd, &J) == VOXGI_OK,
                     "cone trace: %s", voxgi_last_error(ctx));
            for (a = 0; a < 3; a++) worst_irr = fmax(worst_irr, fabs(irr[a] / (PI * rad[a]) - 1));
            worst_irr = fmax(worst_irr, fabs(occ - 1));
            worst_cover = fmax(worst_cover, fabs(J.cones * 2 * PI * (1 - cos(atan(J.half_tan))) / (2 * PI) - 1));
            TH_CHECK(J.cones == (cones[i] ? cones[i] : 16), "%d cones asked for, %d traced", cones[i], J.cones);
        }
        voxgi_volume_destroy(ctx, vol);
    }
    printf("    under uniform opaque radiance: irradiance / (pi L) and occlusion within %.2g of 1; default half-angles cover the hemisphere within %.2g\n",
           worst_irr, worst_cover);
    TH_CHECK(worst_irr < 1e-6, "the cone weights do not sum to 1: off by %.3g", worst_irr);
    TH_CHECK(worst_cover < 1e-9, "the default half-angles cover the hemisphere's solid angle only to %.3g", worst_cover);
    voxgi_destroy(ctx);
}

/* ---------------------------------------------------------------- the leak defences, one at a time */
/* Two-sided radiance alone (docs/cone-tracing.md, "Light leaking"): a wall of no thickness in the
   open (its empty space all open, so the volume keeps no region labels and the cones keep to no
   region), one side lit by a sun, the other dark. Single cones from 6 voxels off the dark side
   at it, narrow (level 0 at the wall) to wide (level 1 there, the most 6 voxels out allows),
   read exactly 0: each level takes the back, unlit, where the origin lies behind the mipped
   plane; the same cones from the lit side read what one-sided radiance reads there (measured:
   equal, at least 0.223). One-sided radiance, the baseline, leaks: its dark-side cones read the
   lit side's light (measured: at least 1.05 times what the mirrored lit-side cones read). */
static void test_two_sided_radiance_alone(void)
{
    enum { CONES = 8 };
    static const float half_angles[4] = {0.02f, 0.1f, 0.3f, 0.6f};
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    quads q;
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi_material mat = {{0.7f, 0.6f, 0.5f}, {0, 0, 0}, 0};
    voxgi_light sun;
    voxgi_grid g;
    voxgi_voxelize_desc xd;
    voxgi_voxels *vox = NULL;
    voxgi_volume *vol[2] = {NULL, NULL}; /* two-sided, one-sided */
    const float wall[12] = {-0.013f, -1, -1, -0.013f, -1, 1, -0.013f, 1, 1, -0.013f, 1, -1}; /* faces -x, toward the sun */
    const double dir[3] = {1, -0.2, 0.3};
    voxgi_cone cones[2 * CONES];
    float out[2][2 * CONES * 4];
    double dark_two = 0, dark_one = 1e30, lit_off = 0, lit_min = 1e30, blocked = 1;
    int i, s, a;
    q.n = 0;
    quad(&q, wall, 0);
    memset(&sun, 0, sizeof sun);
    sun.type = VOXGI_LIGHT_DIRECTIONAL;
    for (a = 0; a < 3; a++) { sun.direction[a] = (float)dir[a]; sun.intensity[a] = 3.0f; }
    scene_of_quads(&sc, &mesh, &q, &mat, 1, &sun, 1);
    cubic(&g, -1.2, 2.4, 24);
    memset(&xd, 0, sizeof xd);
    xd.grid = g;
    xd.attributes = VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_NORMAL | VOXGI_ATTRIBUTE_EMISSION;
    TH_CHECK(voxgi_voxelize(ctx, &sc, &xd, &vox) == VOXGI_OK, "voxelize: %s", voxgi_last_error(ctx));
    for (s = 0; s < 2 && vox; s++) {
        voxgi_inject_desc id;
        memset(&id, 0, sizeof id);
        id.one_sided = s;
        TH_CHECK(voxgi_inject_light(ctx, &sc, vox, &id, &vol[s]) == VOXGI_OK, "inject: %s", voxgi_last_error(ctx));
    }
    voxgi_voxels_destroy(ctx, vox);
    if (!vol[0] || !vol[1]) goto done;
    TH_CHECK(vol[0]->regions == NULL && vol[0]->region_count <= 2, "the open wall's volume keeps region labels (%lu)", (unsigned long)vol[0]->region_count);
    for (i = 0; i < CONES; i++) { /* i: from the dark side (+x), CONES + i: its mirror on the lit side */
        float tilt_y = 0.15f * (float)((i & 1) ? 1 : -1), tilt_z = 0.1f * (float)(i >> 2);
        voxgi_cone *c = &cones[i], *m = &cones[CONES + i];
        memset(c, 0, sizeof *c);
        c->origin[0] = -0.013f + 0.6f;
        c->origin[1] = 0.05f;
        c->origin[2] = -0.07f;
        c->direction[0] = -1;
        c->direction[1] = tilt_y;
        c->direction[2] = tilt_z;
        c->half_angle = half_angles[(i >> 1) & 3];
        *m = *c;
        m->origin[0] = -0.013f - 0.6f;
        m->direction[0] = 1;
    }
    for (s = 0; s < 2; s++) {
        voxgi_radiance_source src = {NULL, NULL};
        voxgi_cone_desc cd;
        memset(&cd, 0, sizeof cd);
        src.volume = vol[s];
        TH_CHECK(voxgi_cone_trace_each(ctx, &src, &cd, 2 * CONES, cones, out[s]) == VOXGI_OK, "cones: %s", voxgi_last_error(ctx));
    }
    for (i = 0; i < CONES; i++) {
        const float *d2 = out[0] + 4 * i, *d1 = out[1] + 4 * i, *l2 = out[0] + 4 * (CONES + i), *l1 = out[1] + 4 * (CONES + i);
        for (a = 0; a < 3; a++) {
            dark_two = fmax(dark_two, fabs(d2[a]));
            dark_one = fmin(dark_one, d1[a] / l1[a]);
            lit_off = fmax(lit_off, fabs(l2[a] - l1[a]) / l1[a]);
            lit_min = fmin(lit_min, l1[a]);
        }
        blocked = fmin(blocked, d2[3]);
    }
    printf("    a wall lit on one side, %d cones from the dark side: two-sided reads at most %.3g (opacity at least %.3f); "
           "one-sided at least %.3f of the lit side's radiance (at least %.3f); the lit side two-sided within %.2g of one-sided\n",
           CONES, dark_two, blocked, dark_one, lit_min, lit_off);
    TH_CHECK(dark_two == 0, "two-sided: the dark side's cones read %.3g", dark_two);
    TH_CHECK(blocked > 0.9, "the dark side's cones pass the wall (opacity %.3f)", blocked);
    TH_CHECK(lit_min > 0.01 && lit_off < 1e-6, "the lit side: radiance at least %.3g, two-sided %.3g off one-sided", lit_min, lit_off);
    TH_CHECK(dark_one > 0.5, "the baseline: one-sided radiance's dark-side cones read %.3g of the lit side's, not a leak", dark_one);
done:
    voxgi_volume_destroy(ctx, vol[0]);
    voxgi_volume_destroy(ctx, vol[1]);
    voxgi_destroy(ctx);
}

/* The back coverage alone (VOXGI__BACK_COVERAGE: a back side covers twice its alpha), on a volume
   built by hand: a wall two voxels thick (x 15 and 16) across a 32^3 grid, its side plane x = 16
   facing -x, its front lit (colour 1, alpha 1/4), its back dark (alpha 1/8); both halves of the
   grid are open, so no region labels. Each level k's sample at the centre of the voxel holding x
   16, one level exactly, reads (analytic, the isotropic mean of the wall's share of the voxel,
   n_k of 2^k columns: 1, or 2 at level 5) from behind colour 0 and alpha 2 x (1/8) n_k / 2^k,
   from the front colour 1 and alpha (1/4) n_k / 2^k. A cone marched through it from behind then
   gathers the opacity the mirrored cone gathers from the front (the grid and the wall are
   symmetric about x = 16), with colour 0: measured 0.343 both ways (a coverage of 1 gives 0.180
   from behind). */
static void test_back_coverage_alone(void)
{
    enum { R = 32, N = R * R * R };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    static float rad[4 * N], back[4 * N], side[4 * N];
    const float *base[VOXGI__VOLUME_SLOTS] = {NULL, NULL, NULL, NULL, NULL, NULL, NULL};
    voxgi_grid g;
    voxgi_volume_desc vd;
    voxgi_volume *vol = NULL;
    voxgi_cone_desc cd;
    voxgi_radiance_source src = {NULL, NULL};
    voxgi__cone_job J;
    voxgi__cone_axes X;
    voxgi_cone cones[2];
    float got[8];
    double worst = 0;
    int i, k, a;
    memset(&g, 0, sizeof g);
    g.res[0] = g.res[1] = g.res[2] = R;
    g.voxel_size = 1;
    memset(&vd, 0, sizeof vd);
    memset(rad, 0, sizeof rad);
    memset(back, 0, sizeof back);
    memset(side, 0, sizeof side);
    for (i = 0; i < N; i++) {
        if (i % R != 15 && i % R != 16) continue;
        rad[4 * i] = rad[4 * i + 1] = rad[4 * i + 2] = rad[4 * i + 3] = 0.25f; /* premultiplied: colour 1 */
        back[4 * i + 3] = 0.125f;
        side[4 * i] = -1;
        side[4 * i + 3] = -16;
    }
    base[VOXGI__RADIANCE_SLOT] = rad;
    base[VOXGI__BACK_SLOT] = back;
    base[VOXGI__SIDE_SLOT] = side;
    TH_CHECK(voxgi__volume_new(ctx, &g, &vd, VOXGI__RADIANCE_FAMILY, &vol) == VOXGI_OK && voxgi__volume_build(ctx, vol, base) == VOXGI_OK,
             "volume: %s", voxgi_last_error(ctx));
    if (!vol) goto done;
    TH_CHECK(vol->regions == NULL && vol->region_count <= 2, "the open grid keeps region labels (%lu)", (unsigned long)vol->region_count);
    memset(&cd, 0, sizeof cd);
    src.volume = vol;
    TH_CHECK(voxgi__cone_job_init(ctx, &src, &cd, &J) == VOXGI_OK && J.two_sided && !J.regions, "job: %s", voxgi_last_error(ctx));
    for (k = 0; k < vol->info.levels; k++) {
        const double behind[3] = {28, 16, 16}, before[3] = {4, 16, 16}, dx[3] = {-1, 0, 0};
        const int size = 1 << k, lo = (16 >> k) << k, columns = (lo <= 15) + (lo + size > 16);
        const double share = (double)columns / size;
        float p[3];
        for (a = 0; a < 3; a++) p[a] = ((float)(16 >> k) + 0.5f) * (float)size;
        voxgi__cone_axes_of(dx, &X);
        voxgi__cone_sample(&J, &X, p, (float)k, behind, 0, got);
        voxgi__cone_sample(&J, &X, p, (float)k, before, 0, got + 4);
        printf("    level %d: from behind colour %.3g alpha %.6f (2 x 1/8 x %.4f), from the front colour %.3g alpha %.6f (1/4 x %.4f)\n", k, got[0], got[3],
               share, got[4], got[7], share);
        worst = fmax(worst, fabs(got[3] - 2 * 0.125 * share) + fabs(got[7] - 0.25 * share) + fabs(got[0]) + fabs(got[1]) + fabs(got[2]) +
                                fabs(got[4] - 1) + fabs(got[5] - 1) + fabs(got[6] - 1));
    }
    TH_CHECK(worst < 1e-6, "the samples %.3g off the rule's values", worst);
    memset(cones, 0, sizeof cones);
    for (i = 0; i < 2; i++) { /* 0: from behind along -x; 1: its mirror from the front */
        cones[i].origin[0] = i ? 4.0f : 28.0f;
        cones[i].origin[1] = cones[i].origin[2] = 16;
        cones[i].direction[0] = i ? 1.0f : -1.0f;
        cones[i].half_angle = 0.25f;
    }
    TH_CHECK(voxgi_cone_trace_each(ctx, &src, &cd, 2, cones, got) == VOXGI_OK, "cones: %s", voxgi_last_error(ctx));
    printf("    a cone through the wall from behind: colour %.3g, opacity %.6f; from the front: colour %.3g, opacity %.6f\n", got[0], got[3], got[4], got[7]);
    TH_CHECK(got[0] == 0 && got[1] == 0 && got[2] == 0 && got[4] > 0, "colours %.3g from behind, %.3g from the front", got[0], got[4]);
    TH_CHECK(fabs(got[3] - got[7]) < 1e-5 && got[7] > 0.1 && got[7] < 0.9, "opacity %.6f from behind, %.6f from the front", got[3], got[7]);
done:
    voxgi_volume_destroy(ctx, vol);
    voxgi_destroy(ctx);
}

/* The regions of empty space alone: the leak box (a closed box of inward-facing faces on ground
   lit by a sun and a lamp), 64^3, where two-sided radiance and the back coverage are no defence:
   the cones from inside leave through the walls' fronts, and a coarse level's voxel holds a
   wall's share and the lit ground beyond it. Points on the inside of the box's floor, walls and
   ceiling (9 x 9 a face, every 0.1 m) gather exactly 0, as the exact image is black; the same
   volume with its region labels removed (two-sided radiance and the back coverage alone) leaks:
   measured a mean of 4.4% and at most 28% of the lit ground's irradiance. */
static void test_regions_alone(void)
{
    enum { S = 9, PTS = 6 * S * S };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene bs;
    voxgi_inject_desc id;
    voxgi_voxels *vx = NULL;
    voxgi_volume *vol = NULL;
    voxgi_cone_desc cd;
    static float pos[3 * PTS], nrm[3 * PTS], irr[2][3 * PTS];
    double ground, mean[2] = {0, 0}, top[2] = {0, 0};
    size_t saved;
    int f, i, j, a, n = 0, s;
    if (voxgi_builtin_scene_create(ctx, "leak-box", &bs) != VOXGI_OK) {
        TH_CHECK(0, "leak-box: %s", voxgi_last_error(ctx));
        voxgi_destroy(ctx);
        return;
    }
    { /* the ground's irradiance under the sun */
        const float *d = bs.scene.lights[0].direction;
        ground = bs.scene.lights[0].intensity[0] * -d[1] / sqrt((double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2]);
    }
    for (f = 0; f < 6; f++) /* the box [-0.5, 0.5] x [0, 1] x [-0.5, 0.5]: face f on axis f / 2, at its low (f even) or high side, normal inward */
        for (j = 0; j < S; j++)
            for (i = 0; i < S; i++, n++) {
                int ax = f / 2, u = (ax + 1) % 3, v = (ax + 2) % 3;
                double lo[3] = {-0.5, 0, -0.5};
                pos[3 * n + ax] = (float)(lo[ax] + (f & 1));
                pos[3 * n + u] = (float)(lo[u] + 0.1 * (i + 1));
                pos[3 * n + v] = (float)(lo[v] + 0.1 * (j + 1));
                for (a = 0; a < 3; a++) nrm[3 * n + a] = a == ax ? (f & 1 ? -1.0f : 1.0f) : 0.0f;
            }
    memset(&id, 0, sizeof id);
    TH_CHECK(lit_voxels(ctx, &bs.scene, 64, &id, &vx, &vol), "injection failed");
    memset(&cd, 0, sizeof cd);
    TH_CHECK(!vol || (vol->regions && vol->region_count > 2), "the closed box keeps no enclosed region");
    if (vol && vol->regions) {
        for (s = 0; s < 2; s++) { /* 0: with the labels; 1: without (the cones see no enclosed region) */
            saved = vol->region_count;
            if (s) vol->region_count = 0;
            TH_CHECK(voxgi_cone_trace(ctx, VOLUME_SOURCE(vol), &cd, PTS, pos, nrm, irr[s], NULL) == VOXGI_OK, "cones: %s", voxgi_last_error(ctx));
            vol->region_count = saved;
            for (i = 0; i < 3 * PTS; i++) {
                mean[s] += irr[s][i] / ground / (3 * PTS);
                top[s] = fmax(top[s], irr[s][i] / ground);
            }
        }
        printf("    %d points inside the leak box, 64^3: with the regions mean %.3g%%, largest %.3g%% of the lit ground's irradiance; "
               "without (two-sided radiance alone) %.3g%%, largest %.3g%%\n", PTS, 100 * mean[0], 100 * top[0], 100 * mean[1], 100 * top[1]);
        TH_CHECK(top[0] == 0, "with the regions the inside gathers %.3g%% of the ground's light", 100 * top[0]);
        TH_CHECK(top[1] > 1e-3, "the baseline: without the regions the inside gathers at most %.3g%%, not a leak", 100 * top[1]);
    }
    voxgi_volume_destroy(ctx, vol);
    voxgi_voxels_destroy(ctx, vx);
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* Surfaces facing apart store no side plane (voxgi__inject_planes, voxgi__inject_store): a floor
   (facing up) under a plate 1 mm above it (facing down, 1 x 1 of the floor's 2 x 2), both in one
   layer of a 16^3 grid (a ledge 0.3 up keeps a voxel boundary from falling between them), lit by
   a sun from above. Every voxel that holds both has a zero
   RADIANCE_SIDE (a plane of the nearest surface's, mixed by the cones with a wall foot's mean plane,
   let full GI through a resting box's bottom); every voxel of the floor alone keeps the floor's
   plane (its normal up): the rule is not "no plane anywhere". */
static void test_facing_apart_store_no_side(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    const float floor_q[12] = {-1, 0, -1, -1, 0, 1, 1, 0, 1, 1, 0, -1}, plate[12] = {-0.5f, 0.001f, -0.5f, 0.5f, 0.001f, -0.5f, 0.5f, 0.001f, 0.5f, -0.5f, 0.001f, 0.5f},
                ledge[12] = {0.8f, 0.3f, 0.8f, 0.8f, 0.3f, 1, 1, 0.3f, 1, 1, 0.3f, 0.8f}; /* off-centres the grid: no voxel boundary between the two */
    voxgi_material mat;
    voxgi_light sun;
    quads q;
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_fit_desc fit;
    voxgi_voxelize_desc xd;
    voxgi_voxels *vox = NULL;
    voxgi_inject_desc id;
    voxgi_volume *vol = NULL;
    int x, y, z, both = 0, both_bad = 0, alone = 0, alone_bad = 0;
    memset(&mat, 0, sizeof mat);
    mat.albedo[0] = mat.albedo[1] = mat.albedo[2] = 0.5f;
    memset(&sun, 0, sizeof sun);
    sun.type = VOXGI_LIGHT_DIRECTIONAL;
    sun.direction[1] = -1;
    sun.intensity[0] = sun.intensity[1] = sun.intensity[2] = 1;
    q.n = 0;
    quad(&q, floor_q, 0);
    quad(&q, plate, 0);
    quad(&q, ledge, 0);
    scene_of_quads(&sc, &mesh, &q, &mat, 1, &sun, 1);
    memset(&fit, 0, sizeof fit);
    fit.res = 16;
    fit.padding = 1;
    memset(&xd, 0, sizeof xd);
    xd.attributes = VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_NORMAL;
    memset(&id, 0, sizeof id);
    TH_CHECK(voxgi_fit_grid(ctx, &sc, &fit, &xd.grid) == VOXGI_OK && voxgi_voxelize(ctx, &sc, &xd, &vox) == VOXGI_OK &&
                 voxgi_inject_light(ctx, &sc, vox, &id, &vol) == VOXGI_OK && vol->cpu[VOXGI__SIDE_SLOT][0],
             "inject: %s", voxgi_last_error(ctx));
    if (vol && vol->cpu[VOXGI__SIDE_SLOT][0]) {
        const float *side = vol->cpu[VOXGI__SIDE_SLOT][0], *rad = vol->cpu[VOXGI__RADIANCE_SLOT][0];
        const int *dm = vol->dims[0];
        for (z = 0; z < dm[2]; z++)
            for (y = 0; y < dm[1]; y++)
                for (x = 0; x < dm[0]; x++) {
                    size_t i = (size_t)x + (size_t)dm[0] * ((size_t)y + (size_t)dm[1] * (size_t)z);
                    double cx = xd.grid.origin[0] + (x + 0.5) * xd.grid.voxel_size, cz = xd.grid.origin[2] + (z + 0.5) * xd.grid.voxel_size;
                    double h = 0.5 * xd.grid.voxel_size, ylo = xd.grid.origin[1] + y * xd.grid.voxel_size;
                    int under_plate = cx - h > -0.5 && cx + h < 0.5 && cz - h > -0.5 && cz + h < 0.5 && ylo < 0 && ylo + 2 * h > 0.001,
                        off_plate = cx + h < -0.5 || cx - h > 0.5 || cz + h < -0.5 || cz - h > 0.5;
                    if (!(rad[4 * i + 3] > 0)) continue;
                    if (under_plate) {
                        both++;
                        both_bad += side[4 * i] != 0 || side[4 * i + 1] != 0 || side[4 * i + 2] != 0 || side[4 * i + 3] != 0;
                    } else if (off_plate) {
                        alone++;
                        alone_bad += !(side[4 * i + 1] > 0.99f);
                    }
                }
    }
    printf("    floor and plate 1 mm apart: %d voxels hold both (%d with a side plane), %d the floor alone (%d without its plane)\n", both, both_bad, alone,
           alone_bad);
    TH_CHECK(both >= 16 && alone >= 16, "the scene makes %d voxels of both and %d of the floor alone", both, alone);
    TH_CHECK(!both_bad && !alone_bad, "%d voxels of both surfaces store a side plane, %d of the floor alone store none", both_bad, alone_bad);
    voxgi_volume_destroy(ctx, vol);
    voxgi_voxels_destroy(ctx, vox);
    voxgi_destroy(ctx);
}

/* The region search's second pass (voxgi__home_region): where every candidate some plane around
   the point cuts off, the planes of the voxels between the point and a candidate alone decide.
   The two rooms (two_rooms_volume, lit from A); a point inside the wall's voxels (x 5.3) whose
   normal runs up the wall, so the walk along it meets only surfaces; beside it a voxel of the wall's far half
   given an odd mean plane (x = 5.2, facing +x, as an edge's voxel holds) that cuts A's voxels off
   from the point. No segment from the point to A passes that voxel: the point's region is A. */
static void test_home_region_second_pass(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    const double o[3] = {5.3, 2.5, 2.5}, up[3] = {0, 1, 0};
    voxgi_volume *vol = two_rooms_volume(ctx, 0);
    voxgi_cone_desc cd;
    voxgi__cone_job J;
    uint32_t home = 0, ra = 0;
    memset(&cd, 0, sizeof cd);
    memset(&J, 0, sizeof J);
    TH_CHECK(vol && vol->regions && voxgi__cone_job_init(ctx, VOLUME_SOURCE(vol), &cd, &J) == VOXGI_OK && J.regions, "volume: %s", voxgi_last_error(ctx));
    if (vol && vol->regions && J.regions) {
        const int X = vol->dims[0][0], Y = vol->dims[0][1];
        float *odd = vol->cpu[VOXGI__SIDE_SLOT][0] + 4 * (size_t)(6 + X * (2 + Y * 3)); /* voxel (6, 2, 3), beside the point's (5, 2, 2) */
        ra = vol->regions[2 + X * (2 + Y * 2)];
        odd[0] = 1; odd[1] = odd[2] = 0; odd[3] = 5.2f;
        TH_CHECK(voxgi__home_along(&J, o, up, 0) == 0, "the walk up the wall found a region");
        home = voxgi__home_region(&J, o, up);
    }
    printf("    a point in the wall, its walk up the wall meeting only surfaces: region %u (room A %u)\n", home, ra);
    TH_CHECK(ra > VOXGI__REGION_OPEN && home == ra, "region %u, not room A's %u", home, ra);
    voxgi_volume_destroy(ctx, vol);
    voxgi_destroy(ctx);
}

/* The bounces' geometric tail (voxgi__add_bounce_tail): a channel whose last bounce added light
   gets tail x that step; one whose light fell by rounding (the bounces only add light) keeps its
   light, so a dark voxel never goes below zero (at a ratio of 0.999 a bounce the tail is 999). */
static void test_bounce_tail(void)
{
    float rgb[3] = {1e-7f, 0.5f, 0.25f};
    const float step[3] = {-2e-7f, 0.001f, 0};
    voxgi__add_bounce_tail(rgb, step, 999.0f);
    printf("    tail 999 on steps -2e-7, 0.001, 0: %g %g %g\n", rgb[0], rgb[1], rgb[2]);
    TH_CHECK(rgb[0] == 1e-7f && fabsf(rgb[1] - 1.499f) < 1e-5f && rgb[2] == 0.25f, "light %g %g %g, not 1e-7 1.499 0.25", rgb[0], rgb[1], rgb[2]);
}

/* A cone from an enclosed region ends, opaque, where it enters a region not inside its own,
   whatever lies beyond. Two rooms split by a wall on a voxel boundary (two_rooms_volume), the
   wall lit from B alone, so that room A's cones leave both its voxels out of level 0 and pass it;
   B's far wall lit too, its voxels' labels then cleared (a surface whose region is unknown, seen
   from every region). A narrow cone from A along +x: colour 0 and opacity 1; marched on past the
   wall it would reach the far wall's light. */
static void test_cone_ends_leaving_its_region(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_volume *vol = two_rooms_volume(ctx, 1);
    voxgi_cone_desc cd;
    voxgi_cone cone;
    float got[4] = {1, 1, 1, 0};
    int X, Y, Z, y, z;
    TH_CHECK(vol && vol->regions, "volume: %s", voxgi_last_error(ctx));
    if (!vol || !vol->regions) goto done;
    X = vol->dims[0][0]; Y = vol->dims[0][1]; Z = vol->dims[0][2];
    TH_CHECK((vol->regions[5 + X * (3 + Y * 3)] & VOXGI__REGION_BORDER) && VOXGI__REGION_OF(vol->regions[5 + X * (3 + Y * 3)]) == vol->regions[8 + X * (3 + Y * 3)],
             "the wall's voxel is labelled %x, B %x", vol->regions[5 + X * (3 + Y * 3)], vol->regions[8 + X * (3 + Y * 3)]);
    for (z = 0; z < Z; z++)
        for (y = 0; y < Y; y++) vol->regions[X - 1 + X * (y + Y * z)] = 0;
    memset(&cd, 0, sizeof cd);
    memset(&cone, 0, sizeof cone);
    cone.origin[0] = 2.5f;
    cone.origin[1] = cone.origin[2] = 3;
    cone.direction[0] = cone.normal[0] = 1;
    cone.half_angle = 0.1f;
    TH_CHECK(voxgi_cone_trace_each(ctx, VOLUME_SOURCE(vol), &cd, 1, &cone, got) == VOXGI_OK, "cone: %s", voxgi_last_error(ctx));
    printf("    a cone from room A past the wall lit from B: colour %.3g %.3g %.3g, opacity %.3g\n", got[0], got[1], got[2], got[3]);
    TH_CHECK(got[0] == 0 && got[1] == 0 && got[2] == 0 && got[3] == 1, "colour %g %g %g, opacity %g", got[0], got[1], got[2], got[3]);
done:
    voxgi_volume_destroy(ctx, vol);
    voxgi_destroy(ctx);
}

/* A floor under a rect light, seen from above, GI off: nothing shadows the floor, so the shadow
   rays' visible share is 1, and a pixel whose rays all meet the triangle its centre shows stops
   after half of them with albedo / pi x the exact (polygon) irradiance at its centre: within
   1e-5 of it at every pixel away from the floor's diagonal (whose pixels average the exact light
   over their square: within 1%). The sampled estimate (sampled_direct) is noisier by far. */
static void test_exact_area_light_image(void)
{
    enum { W = 24 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_material mat = {{0.5f, 0.5f, 0.5f}, {0, 0, 0}, 0};
    float floor_q[12] = {-2, 0, -2, -2, 0, 2, 2, 0, 2, 2, 0, -2};
    voxgi_light rect;
    quads q;
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi_camera cam;
    voxgi_render_desc vd;
    voxgi__tracer tr;
    voxgi__lights Ls;
    static float img[2][W * W * 3], pos[W * W * 3], nrm[W * W * 3];
    static uint32_t tri[W * W];
    double worst[2] = {0, 0}, worst_edge = 0, mean = 0;
    int i, k, a, inner = 0;
    q.n = 0;
    quad(&q, floor_q, 0);
    memset(&rect, 0, sizeof rect);
    rect.type = VOXGI_LIGHT_RECT;
    rect.position[0] = -0.2f; rect.position[1] = 1; rect.position[2] = -0.2f;
    rect.edge_u[0] = 0.4f; rect.edge_v[2] = 0.4f; /* u x v = -y: faces the floor */
    rect.intensity[0] = rect.intensity[1] = rect.intensity[2] = 5;
    scene_of_quads(&sc, &mesh, &q, &mat, 1, &rect, 1);
    memset(&cam, 0, sizeof cam);
    cam.eye[0] = 0.01; cam.eye[1] = 3; cam.eye[2] = 0.3;
    cam.fovy_degrees = 30;
    cam.width = cam.height = W;
    vct_desc_old(&vd, &cam);
    vd.direct_only = 1;
    for (k = 0; k < 2; k++) {
        vd.vct.sampled_direct = k;
        TH_CHECK(voxgi_render(ctx, &sc, &vd, img[k], sizeof img[k], NULL) == VOXGI_OK, "render: %s", voxgi_last_error(ctx));
    }
    TH_CHECK(voxgi_gbuffer_render(ctx, &sc, &vd.camera, pos, nrm, tri) == VOXGI_OK && voxgi__tracer_build(ctx, &sc, &tr) == VOXGI_OK &&
             voxgi__lights_build(ctx, &sc, &tr, &Ls) == VOXGI_OK, "G-buffer: %s", voxgi_last_error(ctx));
    for (i = 0; i < W * W; i++) {
        double p[3], n[3], e[3];
        for (a = 0; a < 3; a++) { p[a] = pos[3 * i + a]; n[a] = nrm[3 * i + a]; }
        int x = i % W, y = i / W, one = 1;
        voxgi__area_irradiance(&Ls, p, n, UINT32_MAX, e);
        mean += 0.5 / PI * e[0] / (W * W);
        for (k = -1; k <= 1; k++) /* the pixel and its neighbours on one triangle */
            for (a = -1; a <= 1; a++)
                if (x + a >= 0 && x + a < W && y + k >= 0 && y + k < W) one &= tri[(y + k) * W + x + a] == tri[i];
        inner += one;
        if (one) worst[0] = fmax(worst[0], fabs(img[0][3 * i] - 0.5 / PI * e[0]) / (0.5 / PI * e[0]));
        else worst_edge = fmax(worst_edge, fabs(img[0][3 * i] - 0.5 / PI * e[0]) / (0.5 / PI * e[0]));
        worst[1] = fmax(worst[1], fabs(img[1][3 * i] - 0.5 / PI * e[0]) / (0.5 / PI * e[0]));
    }
    printf("    floor under a rect light: exact area light within %.2g of albedo / pi x the polygon irradiance at %d pixels (%.2g on the diagonal), "
           "the sampled estimate within %.2g (mean %.3f)\n", worst[0], inner, worst_edge, worst[1], mean);
    TH_CHECK(mean > 0.05 && inner > W * W / 2 && worst[0] < 1e-5 && worst_edge < 0.01, "exact area light off by %.3g (diagonal %.3g)", worst[0], worst_edge);
    TH_CHECK(worst[1] > 5 * worst[0], "the sampled estimate (%.3g) is not noisier than the exact one (%.3g)", worst[1], worst[0]);
    voxgi__lights_free(ctx, &Ls);
    voxgi__tracer_free(ctx, &tr);
    voxgi_destroy(ctx);
}

/* ===================================================================== 12. line space */

/* ---------------------------------------------------------------- line space */

/* Whether the closed triangle v meets the box [lo, hi], by clipping it against the box's six
   planes (Sutherland-Hodgman): an oracle independent of the separating-axis test. */
static int ls_clip_meets(const double v[9], const double lo[3], const double hi[3])
{
    double poly[2][32][3];
    int np = 3, a, s, k, cur = 0;
    for (k = 0; k < 3; k++)
        for (a = 0; a < 3; a++) poly[0][k][a] = v[3 * k + a];
    for (a = 0; a < 3 && np; a++)
        for (s = 0; s < 2 && np; s++) {
            int m = 0;
            for (k = 0; k < np; k++) {
                const double *p = poly[cur][k], *q = poly[cur][(k + 1) % np];
                double dp = s ? hi[a] - p[a] : p[a] - lo[a], dq = s ? hi[a] - q[a] : q[a] - lo[a];
                if (dp >= 0) memcpy(poly[1 - cur][m++], p, sizeof poly[0][0]);
                if ((dp >= 0) != (dq >= 0)) {
                    double t = dp / (dp - dq);
                    int b;
                    for (b = 0; b < 3; b++) poly[1 - cur][m][b] = p[b] + t * (q[b] - p[b]);
                    m++;
                }
            }
            np = m;
            cur = 1 - cur;
        }
    return np > 0;
}

/* The segment p + t (q - p), t in [0, 1], meets the closed box [lo, hi] (slabs). */
static int ls_segment_meets(const double p[3], const double q[3], const double lo[3], const double hi[3])
{
    double t0 = 0, t1 = 1;
    int a;
    for (a = 0; a < 3; a++) {
        double d = q[a] - p[a];
        if (d == 0) {
            if (p[a] < lo[a] || p[a] > hi[a]) return 0;
        } else {
            double u = (lo[a] - p[a]) / d, w = (hi[a] - p[a]) / d;
            t0 = VOXGI__MAX(t0, VOXGI__MIN(u, w));
            t1 = VOXGI__MIN(t1, VOXGI__MAX(u, w));
        }
    }
    return t0 <= t1;
}

typedef struct ls_check {
    const voxgi_linespace *L;
    const float *pos;
    int ntri;
    unsigned rnd;
    size_t missing, extra, filled_wrong, false_negatives, segments, zero_bits, bits, zero_hits;
} ls_check;

static double ls_unit(unsigned *rnd)
{
    *rnd = *rnd * 1664525u + 1013904223u;
    return (*rnd >> 8) / 16777216.0;
}

static int ls_filled(const voxgi_linespace *L, uint32_t node)
{
    return L->node[2 * (size_t)node] != UINT32_MAX || L->node[2 * (size_t)node + 1] != UINT32_MAX;
}

/* Node `node` at `corner`, of edge `size`: its leaf lists against clipping, its filled flag
   against its children's, its line space against segments between random points of two faces. */
static void ls_visit(ls_check *C, uint32_t node, const double corner[3], double size)
{
    const voxgi_linespace *L = C->L;
    int n = L->info.n, c, k, t;
    double cell = size / n;
    uint32_t child0 = L->node[2 * (size_t)node];
    if (child0 == UINT32_MAX) { /* a leaf, or empty: its list against every triangle clipped to its box */
        double lo[3], hi[3], v[9], grow = 1e-6 * L->info.size;
        const uint32_t *list = NULL;
        uint32_t count = 0;
        if (ls_filled(L, node)) {
            list = L->tris + L->leaf[2 * (size_t)L->node[2 * (size_t)node + 1]];
            count = L->leaf[2 * (size_t)L->node[2 * (size_t)node + 1] + 1];
        }
        for (t = 0; t < C->ntri; t++) {
            double slo[3], shi[3];
            int in = 0, a;
            uint32_t j;
            for (a = 0; a < 9; a++) v[a] = C->pos[9 * t + a];
            for (a = 0; a < 3; a++) {
                lo[a] = corner[a];
                hi[a] = corner[a] + size;
                slo[a] = lo[a] + grow;
                shi[a] = hi[a] - grow;
            }
            for (j = 0; j < count; j++) in |= list[j] == (uint32_t)t;
            if (!in && ls_clip_meets(v, slo, shi)) C->missing++;
            for (a = 0; a < 3; a++) { slo[a] = lo[a] - grow - VOXGI__LS_PAD * L->info.size; shi[a] = hi[a] + grow + VOXGI__LS_PAD * L->info.size; }
            if (in && !ls_clip_meets(v, slo, shi)) C->extra++;
        }
        return;
    }
    { /* filled == some child filled */
        int any = 0;
        for (c = 0; c < n * n * n; c++) any |= ls_filled(L, child0 + (uint32_t)c);
        if (!any) C->filled_wrong++;
    }
    { /* the line space: segments between random points of two different faces (a quarter of them on patch edges) */
        const uint32_t *bits = L->bits + (size_t)L->node[2 * (size_t)node + 1] * L->words_per_space;
        size_t b;
        for (b = 0; b < 15 * (size_t)n * n * n * n; b++) {
            C->bits++;
            C->zero_bits += !((bits[b >> 5] >> (b & 31)) & 1);
        }
        for (k = 0; k < 3000; k++) {
            double p[2][3];
            int f[2], pa[2], e, ok = 1, hit = 0;
            size_t bit;
            f[0] = (int)(ls_unit(&C->rnd) * 6);
            f[1] = (f[0] + 1 + (int)(ls_unit(&C->rnd) * 5)) % 6;
            for (e = 0; e < 2; e++) {
                int ax = f[e] >> 1, u = (ax + 1) % 3, w = (ax + 2) % 3, i, j;
                p[e][ax] = (f[e] & 1) ? n : 0;
                p[e][u] = k % 4 == 0 ? floor(ls_unit(&C->rnd) * (n + 1)) : ls_unit(&C->rnd) * n;
                p[e][w] = ls_unit(&C->rnd) * n;
                i = VOXGI__MIN((int)p[e][u], n - 1);
                j = VOXGI__MIN((int)p[e][w], n - 1);
                pa[e] = i * n + j;
            }
            bit = voxgi__ls_bit(n, f[0], pa[0], f[1], pa[1]);
            for (c = 0; c < n * n * n && ok; c++) {
                double clo[3], chi[3];
                if (!ls_filled(L, child0 + (uint32_t)c)) continue;
                clo[0] = c % n; clo[1] = c / n % n; clo[2] = c / (n * n);
                for (e = 0; e < 3; e++) chi[e] = clo[e] + 1;
                if (ls_segment_meets(p[0], p[1], clo, chi)) hit = 1;
            }
            C->segments++;
            if (hit && !((bits[bit >> 5] >> (bit & 31)) & 1)) C->false_negatives++;
            if (!hit && !((bits[bit >> 5] >> (bit & 31)) & 1)) C->zero_hits++;
        }
    }
    for (c = 0; c < n * n * n; c++) {
        double sub[3];
        if (!ls_filled(L, child0 + (uint32_t)c)) {
            if (C->ntri) { /* an empty child: no triangle meets it (its list would be empty) */
                sub[0] = corner[0] + cell * (c % n); sub[1] = corner[1] + cell * (c / n % n); sub[2] = corner[2] + cell * (c / (n * n));
                ls_visit(C, child0 + (uint32_t)c, sub, cell);
            }
            continue;
        }
        sub[0] = corner[0] + cell * (c % n);
        sub[1] = corner[1] + cell * (c / n % n);
        sub[2] = corner[2] + cell * (c / (n * n));
        ls_visit(C, child0 + (uint32_t)c, sub, cell);
    }
}

/* The line space of 14 triangles (random ones, a needle, one on a cell boundary), n = 4, depth
   2: every triangle in every leaf its clipped polygon meets and in none it misses; every filled
   node has a filled child; no segment between two faces' patches through a filled child finds
   its bit clear, while some bits are clear; the same pools on 1 and 2 threads; the memory as
   the formula says; a budget too small refused, its own or the context's. */
static void test_linespace_build(void)
{
    enum { T = 14 };
    static float pos[9 * T];
    voxgi_context *ctx[2];
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_linespace_desc d;
    voxgi_linespace *L[2] = {NULL, NULL};
    voxgi_linespace_info info;
    ls_check C;
    unsigned rnd = 99;
    int i, b;
    for (i = 0; i < 9 * 12; i++) pos[i] = (float)ls_unit(&rnd);
    { /* a needle, and a triangle in the plane x = 0.5 */
        static const float extra[18] = {0.1f, 0.2f, 0.3f, 0.9f, 0.8f, 0.7f, 0.1f, 0.2f, 0.30001f, 0.5f, 0.1f, 0.1f, 0.5f, 0.9f, 0.1f, 0.5f, 0.1f, 0.9f};
        memcpy(pos + 9 * 12, extra, sizeof extra);
    }
    scene_of_triangles(&sc, &mesh, pos, 3 * T, NULL, 0);
    memset(&d, 0, sizeof d);
    d.n = 4;
    d.depth = 2;
    for (b = 0; b < 2; b++) {
        ctx[b] = make_ctx(VOXGI_BACKEND_CPU, b + 1);
        TH_CHECK(voxgi_linespace_create(ctx[b], &sc, &d, &L[b]) == VOXGI_OK, "%s", voxgi_last_error(ctx[b]));
    }
    if (!L[0] || !L[1]) return;
    voxgi_linespace_query(L[0], &info);
    memset(&C, 0, sizeof C);
    C.L = L[0];
    C.pos = pos;
    C.ntri = T;
    C.rnd = 7;
    ls_visit(&C, 0, info.origin, info.size);
    printf("    %lu nodes, %lu line spaces, %lu leaves, %lu triangle references, %lu bytes; leaves: %lu missing, %lu extra; %lu segments: %lu false "
           "negatives, %lu with a clear bit; %lu of %lu bits clear\n",
           (unsigned long)info.nodes, (unsigned long)info.line_spaces, (unsigned long)info.leaves, (unsigned long)info.triangle_refs, (unsigned long)info.bytes,
           (unsigned long)C.missing, (unsigned long)C.extra, (unsigned long)C.segments, (unsigned long)C.false_negatives, (unsigned long)C.zero_hits,
           (unsigned long)C.zero_bits, (unsigned long)C.bits);
    TH_CHECK(C.missing == 0 && C.extra == 0 && C.filled_wrong == 0, "the tree is not the triangles'");
    TH_CHECK(C.false_negatives == 0, "a shaft through a filled child has its bit clear");
    TH_CHECK(C.zero_bits > 0 && C.zero_hits > 0, "every bit set: the line space skips nothing");
    TH_CHECK(info.line_spaces >= 2 && info.bytes == 8 * info.nodes + 15 * 256 / 8 * info.line_spaces + 4 * info.triangle_refs + 8 * info.leaves + 36 * (size_t)T,
             "the memory is not the formula's");
    TH_CHECK(L[0]->info.nodes == L[1]->info.nodes && L[0]->info.line_spaces == L[1]->info.line_spaces && L[0]->info.triangle_refs == L[1]->info.triangle_refs &&
                 memcmp(L[0]->node, L[1]->node, 8 * info.nodes) == 0 && memcmp(L[0]->bits, L[1]->bits, 4 * L[0]->words_per_space * info.line_spaces) == 0 &&
                 memcmp(L[0]->tris, L[1]->tris, 4 * info.triangle_refs) == 0,
             "1 and 2 threads build different line spaces");
    voxgi_linespace_destroy(ctx[0], L[0]);
    voxgi_linespace_destroy(ctx[1], L[1]);
    d.memory_budget = 4096;
    TH_CHECK(voxgi_linespace_create(ctx[0], &sc, &d, &L[0]) == VOXGI_ERR_TOO_LARGE && L[0] == NULL, "a 4 KiB budget accepted");
    d.memory_budget = 0;
    { /* budget 0: the context's, as every budget */
        voxgi_desc cd;
        voxgi_context *small = NULL;
        ctx_desc(&cd, VOXGI_BACKEND_CPU);
        cd.memory_budget = 4096;
        TH_CHECK(voxgi_create(&cd, &small) == VOXGI_OK && voxgi_linespace_create(small, &sc, &d, &L[0]) == VOXGI_ERR_TOO_LARGE && L[0] == NULL,
                 "the context's 4 KiB budget accepted");
        voxgi_destroy(small);
    }
    d.n = 1;
    TH_CHECK(voxgi_linespace_create(ctx[0], &sc, &d, &L[0]) == VOXGI_ERR_INVALID_ARGUMENT, "n 1 accepted");
    voxgi_destroy(ctx[0]);
    voxgi_destroy(ctx[1]);
}

/* The scene of the line-space ray tests: 12 random triangles in the unit cube, a needle, a
   triangle in the plane x = 0.5 (on cell boundaries for n 2 and 4), and a closed box (0.3..0.7,
   12 triangles sharing edges and vertices). */
static int ls_scene(float *pos, unsigned seed)
{
    static const float box[8][3] = {{0.3f, 0.3f, 0.3f}, {0.7f, 0.3f, 0.3f}, {0.3f, 0.7f, 0.3f}, {0.7f, 0.7f, 0.3f},
                                    {0.3f, 0.3f, 0.7f}, {0.7f, 0.3f, 0.7f}, {0.3f, 0.7f, 0.7f}, {0.7f, 0.7f, 0.7f}};
    static const int quad[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    static const float extra[18] = {0.1f, 0.2f, 0.3f, 0.9f, 0.8f, 0.7f, 0.1f, 0.2f, 0.30001f, 0.5f, 0.1f, 0.1f, 0.5f, 0.9f, 0.1f, 0.5f, 0.1f, 0.9f};
    int i, q, t = 14;
    for (i = 0; i < 9 * 12; i++) pos[i] = (float)ls_unit(&seed);
    memcpy(pos + 9 * 12, extra, sizeof extra);
    for (q = 0; q < 6; q++) {
        static const int tri[6] = {0, 1, 2, 0, 2, 3};
        for (i = 0; i < 6; i++) memcpy(pos + 9 * t + 3 * (i % 3) + (i / 3) * 9, box[quad[q][tri[i]]], 12);
        t += 2;
    }
    return t;
}

/* A random point in [-0.2, 1.2]^3; one in four snapped to the grid of the leaves (n^depth a side). */
static void ls_point(unsigned *rnd, int cells, float p[3])
{
    int a, snap = ls_unit(rnd) < 0.25;
    for (a = 0; a < 3; a++) {
        double x = -0.2 + 1.4 * ls_unit(rnd);
        p[a] = (float)(snap ? floor(x * cells + 0.5) / cells : x);
    }
}

/* Shadow rays through line spaces of 26 triangles (n 4 depth 2, n 3 depth 3, n 5 depth 1):
   random segments (a quarter from the leaves' grid, a tenth along an axis, some on the box's
   edges) in exact mode give the brute-force answer (every triangle, the same watertight test)
   and the ray core's (but for segments ending on a surface, hit or not at tmax), fast mode is never lighter; packets of rays from one point to a light
   give the per-ray answers in both modes. */
static void test_linespace_rays(void)
{
    static float pos[9 * 26];
    static const int shape[3][2] = {{4, 2}, {3, 3}, {5, 1}};
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_ray_scene *rs = NULL;
    enum { R = 20000 };
    static voxgi_ray rays[R];
    static unsigned char ex[R], fa[R], core[R];
    int T = ls_scene(pos, 5), sh;
    scene_of_triangles(&sc, &mesh, pos, 3 * (size_t)T, NULL, 0);
    TH_CHECK(voxgi_ray_scene_create(ctx, &sc, &rs) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (sh = 0; sh < 3; sh++) {
        voxgi_linespace_desc d;
        voxgi_linespace *L = NULL;
        voxgi__ls_counts cnt;
        unsigned rnd = 11 + (unsigned)sh;
        size_t i, ends_on = 0, brute_wrong = 0, core_wrong = 0, lighter = 0, blocked = 0, darker = 0, packet_wrong = 0, packet_rays = 0, axis = 0;
        int cells = 1, k;
        memset(&d, 0, sizeof d);
        d.n = shape[sh][0];
        d.depth = shape[sh][1];
        for (k = 0; k < d.depth; k++) cells *= d.n;
        TH_CHECK(voxgi_linespace_create(ctx, &sc, &d, &L) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        if (!L) continue;
        for (i = 0; i < R; i++) {
            float a[3], b[3];
            int c;
            ls_point(&rnd, cells, a);
            ls_point(&rnd, cells, b);
            if (i % 10 == 0) { /* along an axis */
                int keep = (int)(ls_unit(&rnd) * 3);
                for (c = 0; c < 3; c++) if (c != keep) b[c] = a[c];
                axis++;
            }
            if (i % 50 == 1) { /* along an edge of the box, or through its corner */
                a[0] = 0.3f; a[1] = 0.3f; b[0] = 0.3f; b[1] = (i % 100 == 1) ? 0.3f : 0.9f;
            }
            for (c = 0; c < 3; c++) {
                rays[i].origin[c] = a[c];
                rays[i].direction[c] = b[c] - a[c];
            }
            rays[i].tmin = 0;
            rays[i].tmax = 1;
        }
        TH_CHECK(voxgi_linespace_occluded(ctx, L, VOXGI_LINESPACE_EXACT, R, rays, ex) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        TH_CHECK(voxgi_linespace_occluded(ctx, L, VOXGI_LINESPACE_FAST, R, rays, fa) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        TH_CHECK(voxgi_ray_occluded(ctx, rs, R, rays, core) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        for (i = 0; i < R; i++) {
            voxgi__ls_ray r;
            int t, hit = 0, at_end = 0;
            if (voxgi__ls_ray_set(L, rays[i].origin, rays[i].direction, rays[i].tmin, rays[i].tmax, 3 * L->leaf_edge, &r)) {
                for (t = 0; t < T && !hit; t++) hit = voxgi__ls_tri_hit(L->tv + 9 * t, &r);
                r.t1 = nextafterf(r.t1, 2.0f); /* a surface at tmax itself, which the ray core's boxes may or may not count */
                for (t = 0; t < T && !hit && !at_end; t++) at_end = voxgi__ls_tri_hit(L->tv + 9 * t, &r);
            }
            brute_wrong += ex[i] != hit;
            core_wrong += !at_end && ex[i] != core[i];
            ends_on += at_end;
            lighter += ex[i] && !fa[i];
            darker += fa[i] && !ex[i];
            blocked += ex[i];
        }
        for (k = 0; k < 200; k++) { /* packets: one point, a light's samples */
            voxgi__ls_ray pr[VOXGI__LS_PACKET];
            float o[3], q0[3];
            int m = 1 + (int)(ls_unit(&rnd) * VOXGI__LS_PACKET), j, t;
            ls_point(&rnd, cells, o);
            ls_point(&rnd, cells, q0);
            for (j = 0; j < m; j++) {
                float dd[3];
                int c;
                for (c = 0; c < 3; c++) dd[c] = q0[c] + (float)(0.3 * ls_unit(&rnd)) - o[c];
                if (j == 1) dd[0] = 0; /* one along a face's plane */
                if (!voxgi__ls_ray_set(L, o, dd, 0, 1, 3 * L->leaf_edge, &pr[j])) pr[j] = pr[0];
            }
            for (t = 0; t < 2; t++) {
                uint64_t got;
                memset(&cnt, 0, sizeof cnt);
                got = voxgi__ls_trace_packet(L, pr, m, t, &cnt);
                for (j = 0; j < m; j++) packet_wrong += (int)(got >> j & 1) != voxgi__ls_trace(L, &pr[j], t, &cnt);
                packet_rays += (size_t)m;
            }
        }
        printf("    n %d depth %d: %lu segments (%lu along an axis), %lu blocked, %lu ending on a surface; exact vs brute force %lu wrong, vs the ray core %lu; fast: "
               "%lu lighter, %lu darker; packets: %lu of %lu rays differ from walking alone\n",
               d.n, d.depth, (unsigned long)R, (unsigned long)axis, (unsigned long)blocked, (unsigned long)ends_on, (unsigned long)brute_wrong, (unsigned long)core_wrong,
               (unsigned long)lighter, (unsigned long)darker, (unsigned long)packet_wrong, (unsigned long)packet_rays);
        TH_CHECK(brute_wrong == 0 && core_wrong == 0, "exact mode is not the triangles' answer");
        TH_CHECK(lighter == 0, "fast mode finds light where the triangles block it");
        TH_CHECK((darker > 0 || d.depth == 1) && blocked > R / 10 && blocked < R - R / 10, "the rays test nothing"); /* depth 1: 3 leaves from the ends span most segments */
        TH_CHECK(packet_wrong == 0, "packets answer otherwise than rays walking alone");
        voxgi_linespace_destroy(ctx, L);
    }
    voxgi_ray_scene_destroy(ctx, rs);
    voxgi_destroy(ctx);
}

/* The GL shadow rays (shaders/linespace.glsl) against the CPU's, per point: line spaces of the
   ray tests' scene (n 4 depth 2, n 3 depth 3), points on its triangles (their normals, either
   side) and in and around it (random normals, some zero), a parallelogram light above the scene
   and a triangle light inside it; exact and fast modes, 16, 7 and 40 samples (40: three passes
   of samples on GL; 5000 points: two slices): `visible` the same for every point, `weighted`
   (float sums on GL) within 1e-5, the same rays traced. The line space made on the GL context
   keeps its buffers; the CPU context's is uploaded for the call (7 samples); 40 samples with fast
   mode's exact zone 12 leaves wide. */
static void test_gl_linespace_light_equals_cpu(void)
{
    static float pos[9 * 26];
    static const int shape[2][2] = {{4, 2}, {3, 3}}, samples[3] = {16, 7, 40};
    enum { P = 5000 };
    static float pts[3 * P], nrm[3 * P], vis[2][P], wt[2][P];
    voxgi_context *ctx[2];
    voxgi_scene sc;
    voxgi_mesh mesh;
    unsigned rnd = 23;
    int T = ls_scene(pos, 5), sh, b;
    size_t i;
    if (!have_gl()) return;
    ctx[0] = make_ctx(VOXGI_BACKEND_CPU, 2);
    ctx[1] = make_ctx(VOXGI_BACKEND_GL, 0);
    TH_CHECK(ctx[0] && ctx[1], "contexts");
    if (!ctx[0] || !ctx[1]) return;
    scene_of_triangles(&sc, &mesh, pos, 3 * (size_t)T, NULL, 0);
    for (i = 0; i < P; i++) {
        float *p = pts + 3 * i, *n = nrm + 3 * i;
        int a;
        if (i < 2 * P / 3) { /* on triangle i % T, its normal to one side or the other */
            const float *v = pos + 9 * (i % (size_t)T);
            double u = ls_unit(&rnd), w = ls_unit(&rnd), e1[3], e2[3], c[3], len;
            if (u + w > 1) { u = 1 - u; w = 1 - w; }
            for (a = 0; a < 3; a++) {
                e1[a] = (double)v[3 + a] - v[a];
                e2[a] = (double)v[6 + a] - v[a];
                p[a] = (float)(v[a] + u * e1[a] + w * e2[a]);
            }
            for (a = 0; a < 3; a++) c[a] = e1[(a + 1) % 3] * e2[(a + 2) % 3] - e1[(a + 2) % 3] * e2[(a + 1) % 3];
            len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) * (i % 2 ? -1 : 1);
            for (a = 0; a < 3; a++) n[a] = len != 0 ? (float)(c[a] / len) : 0.0f;
        } else { /* anywhere near, any way */
            double len = 0, d[3];
            ls_point(&rnd, 16, p);
            for (a = 0; a < 3; a++) {
                d[a] = 2 * ls_unit(&rnd) - 1;
                len += d[a] * d[a];
            }
            len = sqrt(len);
            for (a = 0; a < 3; a++) n[a] = i % 97 == 0 ? 0.0f : (float)(d[a] / len);
        }
    }
    for (sh = 0; sh < 2; sh++) {
        voxgi_linespace_desc d;
        voxgi_linespace *L[2] = {NULL, NULL};
        int light, mode, si;
        memset(&d, 0, sizeof d);
        d.n = shape[sh][0];
        d.depth = shape[sh][1];
        for (b = 0; b < 2; b++) TH_CHECK(voxgi_linespace_create(ctx[b], &sc, &d, &L[b]) == VOXGI_OK, "%s", voxgi_last_error(ctx[b]));
        if (!L[0] || !L[1]) continue;
        TH_CHECK(L[1]->gl[0] != 0 && L[0]->gl[0] == 0, "the GL context's line space keeps no buffers, or the CPU's does");
        for (light = 0; light < 2; light++)
            for (mode = 0; mode < 2; mode++) {
                printf("    n %d depth %d, %s light, %s:", d.n, d.depth, light ? "triangle" : "square", mode ? "fast" : "exact");
                for (si = 0; si < 3; si++) {
                    voxgi_linespace_light_desc ld;
                    voxgi_linespace_stats st[2];
                    size_t differ = 0, lit = 0, partly = 0;
                    double worst = 0;
                    memset(&ld, 0, sizeof ld);
                    ld.mode = mode ? VOXGI_LINESPACE_FAST : VOXGI_LINESPACE_EXACT;
                    ld.samples = samples[si];
                    ld.seed = 77u + (uint32_t)sh;
                    ld.exact_ends = si == 2 ? 12 : 0; /* fast mode's exact zone widened */
                    if (light == 0) { /* a square above the scene, shining down */
                        ld.corner[0] = 0.2; ld.corner[1] = 1.3; ld.corner[2] = 0.2;
                        ld.edge_u[0] = 0.6; ld.edge_v[2] = 0.6;
                    } else { /* a triangle inside it, in the plane x = 0.85, shining to -x */
                        ld.corner[0] = 0.85; ld.corner[1] = 0.15; ld.corner[2] = 0.15;
                        ld.edge_u[2] = 0.7; ld.edge_v[1] = 0.7;
                        ld.triangle = 1;
                    }
                    for (b = 0; b < 2; b++)
                        TH_CHECK(voxgi_linespace_light(ctx[b], L[b == 1 && si == 1 ? 0 : b], &ld, P, pts, nrm, vis[b], wt[b], &st[b]) == VOXGI_OK, "%s",
                                 voxgi_last_error(ctx[b]));
                    for (i = 0; i < P; i++) {
                        differ += vis[0][i] != vis[1][i];
                        lit += vis[0][i] > 0;
                        partly += vis[0][i] > 0 && vis[0][i] < 1;
                        worst = fmax(worst, fabs((double)wt[0][i] - wt[1][i]));
                    }
                    printf("%s S %d: %lu of %d points lit (%lu in part), GL: %lu differ, weighted within %.2g, %llu rays", si ? ";" : "", ld.samples,
                           (unsigned long)lit, P, (unsigned long)partly, (unsigned long)differ, worst, (unsigned long long)st[1].rays);
                    TH_CHECK(differ == 0, "%lu points see the light otherwise on GL", (unsigned long)differ);
                    TH_CHECK(worst <= 1e-5, "weighted differs by %g on GL", worst);
                    TH_CHECK(st[0].rays == st[1].rays && st[0].samples == st[1].samples, "GL traced %llu rays, the CPU %llu", (unsigned long long)st[1].rays,
                             (unsigned long long)st[0].rays);
                    TH_CHECK(lit > P / 10 && partly > P / 20, "the light tests nothing: %lu of %d points see it, %lu in part", (unsigned long)lit, P,
                             (unsigned long)partly);
                }
                printf("\n");
            }
        for (b = 0; b < 2; b++) voxgi_linespace_destroy(ctx[b], L[b]);
    }
    voxgi_destroy(ctx[0]);
    voxgi_destroy(ctx[1]);
}

/* voxgi_linespace_occluded on GL against the CPU, ray by ray, in both modes: random segments
   through a line space of 26 triangles (a tenth along an axis, some along the box's edges and
   through its corner, rays with tmax <= tmin and with no direction), 20,000 of them (two slices);
   the GL context's own line space (n 4, depth 2), the CPU context's uploaded for the call, and
   one of n 9, depth 1 (bits twice its nodes) with GL's storage blocks made half its bits' size
   (the bits in two parts, as Mesa's 128 MiB limit splits a large line space); a fifth of it
   (five parts, one more than the walk has) is refused. */
static void test_gl_linespace_occluded_equals_cpu(void)
{
    static float pos[9 * 26];
    enum { R = 20000 };
    static voxgi_ray rays[R];
    static unsigned char occ[2][R];
    voxgi_context *ctx[2];
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_linespace_desc d;
    voxgi_linespace *L[3] = {NULL, NULL, NULL};
    unsigned rnd = 41;
    int T = ls_scene(pos, 5), b, mode, cells = 16, src;
    size_t i;
    if (!have_gl()) return;
    ctx[0] = make_ctx(VOXGI_BACKEND_CPU, 2);
    ctx[1] = make_ctx(VOXGI_BACKEND_GL, 0);
    TH_CHECK(ctx[0] && ctx[1], "contexts");
    if (!ctx[0] || !ctx[1]) return;
    scene_of_triangles(&sc, &mesh, pos, 3 * (size_t)T, NULL, 0);
    for (i = 0; i < R; i++) {
        float a[3], e[3];
        int c;
        ls_point(&rnd, cells, a);
        ls_point(&rnd, cells, e);
        if (i % 10 == 0) { /* along an axis */
            int keep = (int)(ls_unit(&rnd) * 3);
            for (c = 0; c < 3; c++)
                if (c != keep) e[c] = a[c];
        }
        if (i % 50 == 1) { a[0] = 0.3f; a[1] = 0.3f; e[0] = 0.3f; e[1] = (i % 100 == 1) ? 0.3f : 0.9f; } /* the box's edge, its corner */
        for (c = 0; c < 3; c++) {
            rays[i].origin[c] = a[c];
            rays[i].direction[c] = i % 997 == 3 ? 0.0f : e[c] - a[c];
        }
        rays[i].tmin = i % 499 == 7 ? 1.0f : 0.0f;
        rays[i].tmax = 1;
    }
    memset(&d, 0, sizeof d);
    d.n = 4;
    d.depth = 2;
    for (b = 0; b < 2; b++) TH_CHECK(voxgi_linespace_create(ctx[b], &sc, &d, &L[b]) == VOXGI_OK, "%s", voxgi_last_error(ctx[b]));
    d.n = 9;
    d.depth = 1;
    TH_CHECK(voxgi_linespace_create(ctx[0], &sc, &d, &L[2]) == VOXGI_OK, "%s", voxgi_last_error(ctx[0]));
    for (src = 0; src < 3 && L[0] && L[1] && L[2]; src++) /* the GL context's line space, then the CPU context's, then in parts */
        for (mode = 0; mode < 2; mode++) {
            const voxgi_linespace *cpu = L[src == 2 ? 2 : 0], *on_gl = src == 2 ? L[2] : L[src ? 0 : 1];
            int64_t whole = ctx[1]->gl->max_ssbo_bytes;
            uint64_t words = (uint64_t)cpu->words_per_space * cpu->info.line_spaces;
            if (src == 2) ctx[1]->gl->max_ssbo_bytes = (int64_t)(4 * ((words + 1) / 2));
            size_t differ = 0, blocked = 0;
            TH_CHECK(voxgi_linespace_occluded(ctx[0], cpu, (voxgi_linespace_mode)mode, R, rays, occ[0]) == VOXGI_OK, "%s", voxgi_last_error(ctx[0]));
            memset(occ[1], 7, sizeof occ[1]);
            TH_CHECK(voxgi_linespace_occluded(ctx[1], on_gl, (voxgi_linespace_mode)mode, R, rays, occ[1]) == VOXGI_OK, "%s", voxgi_last_error(ctx[1]));
            if (src == 2) {
                unsigned char one;
                TH_CHECK(voxgi__ls_bits_part_words(ctx[1], cpu) < words && 2 * voxgi__ls_bits_part_words(ctx[1], cpu) >= words, "not two parts");
                ctx[1]->gl->max_ssbo_bytes = (int64_t)(4 * ((words + 4) / 5));
                TH_CHECK(voxgi_linespace_occluded(ctx[1], cpu, (voxgi_linespace_mode)mode, 1, rays, &one) == VOXGI_ERR_TOO_LARGE &&
                             strstr(voxgi_last_error(ctx[1]), "bits"), "five parts: %s", voxgi_last_error(ctx[1]));
                ctx[1]->gl->max_ssbo_bytes = whole;
            }
            for (i = 0; i < R; i++) {
                differ += occ[0][i] != occ[1][i];
                blocked += occ[0][i];
            }
            printf("    %s, %s line space: %lu of %d rays blocked on the CPU, %lu differ on GL\n", mode ? "fast" : "exact",
                   src == 2 ? "the CPU context's n 9, its bits in two parts," : src ? "the CPU context's" : "GL's",
                   (unsigned long)blocked, (int)R, (unsigned long)differ);
            TH_CHECK(differ == 0 && blocked > R / 20 && blocked < R - R / 20, "GL's answers are not the CPU's, or the rays test nothing");
        }
    for (b = 0; b < 2; b++) voxgi_linespace_destroy(ctx[b], L[b]);
    voxgi_linespace_destroy(ctx[0], L[2]);
    for (b = 0; b < 2; b++) voxgi_destroy(ctx[b]);
}

int main(void)
{
    gl_open();
    TH_RUN(test_rays_leave_surfaces);
    TH_RUN(test_polygon_irradiance);
    TH_RUN(test_gl_shader_error_mapping);
    TH_RUN(test_gl_software_renderers);
    TH_RUN(test_dda_visits_the_slab_voxels);
    TH_RUN(test_mip_combine_by_hand);
    TH_RUN(test_mip_voxel_by_hand);
    TH_RUN(test_volume_mips_by_hand);
    TH_RUN(test_gl_volume_mips_by_hand);
    TH_RUN(test_region_labels_flood_fill);
    TH_RUN(test_region_labels_of_surfaces);
    TH_RUN(test_region_lit_ahead);
    TH_RUN(test_half_rounding);
    TH_RUN(test_gl_svo_equals_cpu);
    TH_RUN(test_cone_set);
    TH_RUN(test_two_sided_radiance_alone);
    TH_RUN(test_back_coverage_alone);
    TH_RUN(test_regions_alone);
    TH_RUN(test_cone_ends_leaving_its_region);
    TH_RUN(test_bounce_tail);
    TH_RUN(test_home_region_second_pass);
    TH_RUN(test_facing_apart_store_no_side);
    TH_RUN(test_exact_area_light_image);
    TH_RUN(test_linespace_build);
    TH_RUN(test_linespace_rays);
    TH_RUN(test_gl_linespace_light_equals_cpu);
    TH_RUN(test_gl_linespace_occluded_equals_cpu);
    gl_close();
    return th_finish();
}
