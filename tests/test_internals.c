/* tests/test_internals.c - the tests of voxgi's private helpers (voxgi__*): half-float rounding,
   the cone set's directions, Lambert's polygon formula against the lights' own samples, the exact
   area light of cone-traced images, GL octree footprints and shader error mapping.

   They live here, apart, because those helpers are static inside the implementation: this program
   defines VOXGI_IMPLEMENTATION and compiles the implementation itself, while every other test
   program includes voxgi.h for the declarations only and links the implementation compiled once
   (build/voxgi_impl.o), so it sees nothing but the public API. Keep a test here only while it
   calls a voxgi__ function; the shared fixtures are tests/fixtures.h. The GL tests skip (loudly)
   when no GL 4.5 context can be made; VOXGI_TEST_GL and VOXGI_REQUIRE_GL work as in
   tests/test_gl_voxelize.c. */
#define VOXGI_IMPLEMENTATION
#include "../voxgi.h"
#include "fixtures.h"
#include "svo_checks.h"

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

/* ---------------------------------------------------------------- cone tracing and light */
/* The cone set's directions: unit, in the upper hemisphere, their cosine-weighted shares equal
   (the projected radii split the disc evenly), and the half-angles cover the hemisphere's solid
   angle exactly. */
static void test_cone_set(void)
{
    int n, k, bad = 0;
    for (n = 1; n <= 64; n *= 2) {
        double half = acos(1 - 1.0 / n), covered = n * 2 * PI * (1 - cos(half));
        for (k = 0; k < n; k++) {
            double d[3];
            voxgi__cone_direction(k, n, d);
            bad += fabs(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - 1) > 1e-12 || d[2] <= 0;
        }
        bad += fabs(covered - 2 * PI) > 1e-9;
    }
    TH_CHECK(bad == 0, "%d bad cone directions or coverages", bad);
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
    srand(3);
    for (i = 0; i < 40; i++) {
        double p[3], n[3], len = 0, exact[3], mean[6] = {0, 0, 0, 0, 0, 0}, e[3];
        uint64_t rays = 0;
        voxgi__rng g;
        for (a = 0; a < 3; a++) { p[a] = 1.6 * rand() / RAND_MAX - 0.8; n[a] = 2.0 * rand() / RAND_MAX - 1; len += n[a] * n[a]; }
        p[1] = 0.7 * rand() / RAND_MAX - 0.5;
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
    voxgi_vct_desc vd;
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
    memset(&vd, 0, sizeof vd);
    vd.camera.eye[0] = 0.01; vd.camera.eye[1] = 3; vd.camera.eye[2] = 0.3;
    vd.camera.fovy_degrees = 30;
    vd.camera.width = vd.camera.height = W;
    vd.no_gi = 1;
    for (k = 0; k < 2; k++) {
        vd.sampled_direct = k;
        TH_CHECK(voxgi_vct_render(ctx, &sc, &vd, img[k], sizeof img[k], NULL) == VOXGI_OK, "render: %s", voxgi_last_error(ctx));
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
                    pos[3 * i] = (float)(-2 + 31 * ((double)rand() / RAND_MAX));
                    pos[3 * i + 1] = (float)(-2 + 31 * ((double)rand() / RAND_MAX));
                    pos[3 * i + 2] = (float)(-2 + 31 * ((double)rand() / RAND_MAX));
                    lods[i] = (float)(-0.5 + 6.5 * ((double)rand() / RAND_MAX));
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

int main(void)
{
    gl_open();
    TH_RUN(test_half_rounding);
    TH_RUN(test_polygon_irradiance);
    TH_RUN(test_exact_area_light_image);
    TH_RUN(test_cone_set);
    TH_RUN(test_gl_svo_equals_cpu);
    TH_RUN(test_gl_shader_error_mapping);
    gl_close();
    return th_finish();
}
