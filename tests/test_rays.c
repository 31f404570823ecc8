/* tests/test_rays.c - part 3: the scene's ray core, on every SIMD width.

   The ray core (voxgi_ray_scene: a 4-wide BVH, the watertight triangle test) against what is
   known: rays from inside a closed mesh always hit it, also when aimed exactly at its vertices
   and the midpoints of its edges, and also 1e6 away from the origin; rays onto a flat fan of
   triangles hit it at every shared vertex and edge; every closest hit is the brute-force one
   (an independent double-precision test of every triangle); occlusion says what the closest
   hit says; the answers are the same for any thread count; tmin, tmax and bad input behave. */
#include "../voxgi.h"
#include "fixtures.h"

/* A closed sphere of radius r about c from a cube's surface lattice (n x n squares a face, two
   triangles each), each lattice point projected onto the sphere by the same arithmetic wherever
   it appears, so faces that share a point share its floats exactly. */
typedef struct cube_sphere { float *pos; size_t triangles; } cube_sphere;

static void lattice_point(int n, double r, const double c[3], const int q[3], float *out)
{
    double v[3], len;
    int a;
    for (a = 0; a < 3; a++) v[a] = 2.0 * q[a] / n - 1;
    len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (a = 0; a < 3; a++) out[a] = (float)(c[a] + r * v[a] / len);
}

static void cube_sphere_make(cube_sphere *s, int n, double r, const double c[3])
{
    int face, i, j, k;
    size_t t = 0;
    s->triangles = (size_t)12 * n * n;
    s->pos = (float *)malloc(s->triangles * 9 * sizeof(float));
    for (face = 0; face < 6; face++) { /* axis face / 2 at 0 or n; counter-clockwise seen from outside */
        int ax = face / 2, u = (ax + 1) % 3, w = (ax + 2) % 3, side = face & 1;
        for (j = 0; j < n; j++)
            for (i = 0; i < n; i++) {
                int corner[4][3];
                static const int du[4] = {0, 1, 1, 0}, dw[4] = {0, 0, 1, 1}, tris[2][3] = {{0, 1, 2}, {0, 2, 3}};
                for (k = 0; k < 4; k++) {
                    corner[k][ax] = side ? n : 0;
                    corner[k][u] = i + du[k];
                    corner[k][w] = j + dw[k];
                }
                for (k = 0; k < 2; k++) {
                    int m;
                    for (m = 0; m < 3; m++) lattice_point(n, r, c, corner[tris[k][side ? m : 2 - m]], s->pos + 9 * t + 3 * m);
                    t++;
                }
            }
    }
}

/* The brute-force closest hit in double (Moller-Trumbore), its barycentric margin (how far
   inside its triangle, in barycentric units); -1 where nothing is hit. */
static double brute_force(const float *pos, size_t nt, const voxgi_ray *ray, uint32_t *tri, double *margin)
{
    double best = -1;
    size_t t;
    for (t = 0; t < nt; t++) {
        const float *v = pos + 9 * t;
        double e1[3], e2[3], p[3], q[3], s[3], det, u, w, tt;
        int a;
        for (a = 0; a < 3; a++) { e1[a] = (double)v[3 + a] - v[a]; e2[a] = (double)v[6 + a] - v[a]; s[a] = (double)ray->origin[a] - v[a]; }
        p[0] = ray->direction[1] * e2[2] - ray->direction[2] * e2[1];
        p[1] = ray->direction[2] * e2[0] - ray->direction[0] * e2[2];
        p[2] = ray->direction[0] * e2[1] - ray->direction[1] * e2[0];
        det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
        if (det == 0) continue;
        u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) / det;
        q[0] = s[1] * e1[2] - s[2] * e1[1];
        q[1] = s[2] * e1[0] - s[0] * e1[2];
        q[2] = s[0] * e1[1] - s[1] * e1[0];
        w = (ray->direction[0] * q[0] + ray->direction[1] * q[1] + ray->direction[2] * q[2]) / det;
        tt = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
        if (u < 0 || w < 0 || u + w > 1 || !(tt > ray->tmin && tt < ray->tmax)) continue;
        if (best < 0 || tt < best) {
            best = tt;
            *tri = (uint32_t)t;
            *margin = fmin(fmin(u, w), 1 - u - w);
        }
    }
    return best;
}

static void scene_of_soup(voxgi_scene *sc, voxgi_mesh *mesh, const float *pos, size_t nt)
{
    scene_of_triangles(sc, mesh, pos, 3 * nt, NULL, 0);
}

/* Rays from points inside a closed sphere: at every vertex, edge midpoint and random directions. */
static size_t inside_rays(const cube_sphere *s, const double c[3], double r, fx_rng *g, voxgi_ray *rays, size_t max)
{
    size_t n = 0, t;
    int k, a;
    for (t = 0; t < s->triangles && n + 6 <= max; t++)
        for (k = 0; k < 3; k++) { /* at vertex k and at the midpoint of edge k, k + 1, from a random inner point */
            const float *v = s->pos + 9 * t;
            for (a = 0; a < 3; a++) rays[n].origin[a] = (float)(c[a] + fx_rng_range(g, -0.5, 0.5) * r);
            for (a = 0; a < 3; a++) rays[n + 1].origin[a] = rays[n].origin[a];
            for (a = 0; a < 3; a++) {
                rays[n].direction[a] = v[3 * k + a] - rays[n].origin[a];
                rays[n + 1].direction[a] = 0.5f * (v[3 * k + a] + v[3 * ((k + 1) % 3) + a]) - rays[n + 1].origin[a];
            }
            rays[n].tmin = rays[n + 1].tmin = 0;
            rays[n].tmax = rays[n + 1].tmax = INFINITY;
            n += 2;
        }
    while (n < max) {
        for (a = 0; a < 3; a++) { rays[n].origin[a] = (float)(c[a] + fx_rng_range(g, -0.5, 0.5) * r); rays[n].direction[a] = (float)fx_rng_range(g, -1, 1); }
        rays[n].tmin = 0;
        rays[n].tmax = INFINITY;
        n++;
    }
    return n;
}

/* No ray from inside a closed mesh escapes it, at its vertices and edges too: near the origin,
   1e6 away (the core works relative to the scene's centre), 1e-6 and 1e6 in size; with 1 and 2
   threads alike. */
static void test_watertight_sphere(void)
{
    enum { N = 12, M = 12 * N * N * 6 + 20000 };
    static voxgi_ray rays[M];
    static voxgi_ray_hit hits[2][M];
    static unsigned char occ[M];
    const double offsets[4] = {0, 1e6, 0, 0}, sizes[4] = {1, 8, 1e-6, 1e6};
    const char *const names[4] = {"at the origin", "1e6 from the origin", "of radius 1e-6", "of radius 1e6"};
    int o;
    for (o = 0; o < 4; o++) {
        double r = sizes[o], c[3] = {0.25 * r + offsets[o], -0.5 * r + offsets[o], 0.125 * r - offsets[o]};
        cube_sphere s;
        voxgi_scene sc;
        voxgi_mesh mesh;
        voxgi_ray_scene *rs[2] = {NULL, NULL};
        fx_rng g = fx_rng_seeded(7);
        size_t n, i, missed = 0, occ_missed = 0;
        int th;
        cube_sphere_make(&s, N, r, c);
        scene_of_soup(&sc, &mesh, s.pos, s.triangles);
        n = inside_rays(&s, c, r, &g, rays, M);
        for (th = 0; th < 2; th++) {
            voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, th + 1);
            TH_CHECK(voxgi_ray_scene_create(ctx, &sc, &rs[th]) == VOXGI_OK && voxgi_ray_intersect(ctx, rs[th], n, rays, hits[th]) == VOXGI_OK &&
                         voxgi_ray_occluded(ctx, rs[th], n, rays, occ) == VOXGI_OK,
                     "%s", voxgi_last_error(ctx));
            voxgi_ray_scene_destroy(ctx, rs[th]);
            voxgi_destroy(ctx);
        }
        for (i = 0; i < n; i++) {
            missed += hits[0][i].triangle == UINT32_MAX;
            occ_missed += !occ[i];
        }
        printf("    closed sphere %s: %lu rays from inside (%lu aimed at vertices and edge midpoints), %lu missed, %lu not occluded\n",
               names[o], (unsigned long)n, (unsigned long)(12 * N * N * 6), (unsigned long)missed,
               (unsigned long)occ_missed);
        TH_CHECK(!missed && !occ_missed, "%lu rays escaped the closed sphere (%lu by occlusion)", (unsigned long)missed, (unsigned long)occ_missed);
        TH_CHECK(!memcmp(hits[0], hits[1], n * sizeof hits[0][0]), "1 and 2 threads answer differently");
        free(s.pos);
    }
}

/* A flat fan (the subdivided square, shared vertices): rays straight down onto every vertex and
   edge midpoint hit it, and so does any ray whose foot lies inside the square; the hit is at z = 0. */
static void test_watertight_fan(void)
{
    enum { N = 16 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    vxt_shape m;
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_ray_scene *rs = NULL;
    voxgi_ray *rays;
    voxgi_ray_hit *hits;
    size_t n = 0, i, missed = 0, t;
    double worst_t = 0;
    vxt_shape_quad(&m, N);
    scene_of_shape(&sc, &mesh, &m);
    rays = (voxgi_ray *)malloc(m.triangle_count * 6 * sizeof *rays);
    hits = (voxgi_ray_hit *)malloc(m.triangle_count * 6 * sizeof *hits);
    for (t = 0; t < m.triangle_count; t++) {
        int k;
        for (k = 0; k < 3; k++) {
            const float *a = m.pos + 3 * m.idx[3 * t + (size_t)k], *b = m.pos + 3 * m.idx[3 * t + (size_t)(k + 1) % 3];
            float p[2][3] = {{a[0], a[1], 1}, {0.5f * (a[0] + b[0]), 0.5f * (a[1] + b[1]), 1}};
            int e;
            for (e = 0; e < 2; e++) {
                if (fabsf(p[e][0]) == 1 || fabsf(p[e][1]) == 1) continue; /* the square's border: a ray may graze past it */
                memcpy(rays[n].origin, p[e], sizeof p[e]);
                rays[n].direction[0] = rays[n].direction[1] = 0;
                rays[n].direction[2] = -1;
                rays[n].tmin = 0;
                rays[n].tmax = INFINITY;
                n++;
            }
        }
    }
    TH_CHECK(voxgi_ray_scene_create(ctx, &sc, &rs) == VOXGI_OK && voxgi_ray_intersect(ctx, rs, n, rays, hits) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (i = 0; i < n; i++) {
        missed += hits[i].triangle == UINT32_MAX;
        if (hits[i].triangle != UINT32_MAX) worst_t = fmax(worst_t, fabs(hits[i].t - 1.0));
    }
    printf("    fan of %lu triangles: %lu rays onto shared vertices and edges, %lu missed, t within %.2g of 1\n", (unsigned long)m.triangle_count,
           (unsigned long)n, (unsigned long)missed, worst_t);
    TH_CHECK(n > 1000 && !missed && worst_t <= 1e-6, "%lu of %lu rays slipped through the fan (t off by %g)", (unsigned long)missed, (unsigned long)n, worst_t);
    voxgi_ray_scene_destroy(ctx, rs);
    free(rays);
    free(hits);
    vxt_shape_free(&m);
    voxgi_destroy(ctx);
}

/* Exact orientation of q against the line a -> b, coordinates in units of 2^-22 (|x| <= 2^23:
   the products fit 64 bits): +1 left, -1 right, 0 on it. */
static int orient_exact(const int64_t a[2], const int64_t b[2], const int64_t q[2])
{
    int64_t c = (b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0]);
    return (c > 0) - (c < 0);
}

/* Whether the edge function of a -> b at q, as the core's float test computes it (the products
   of the exact float differences rounded, then subtracted), is 0 where the exact one is not.
   Rounding is monotonic, so without a fused multiply-add that difference never takes the wrong
   sign, only 0: those zeros are what the rounding band must send to the double test. */
static int float_edge_lost(const int64_t a[2], const int64_t b[2], const int64_t q[2])
{
    const float s = 1.0f / 4194304.0f; /* 2^-22 */
    float ax = (float)(a[0] - q[0]) * s, ay = (float)(a[1] - q[1]) * s, bx = (float)(b[0] - q[0]) * s, by = (float)(b[1] - q[1]) * s;
    float p = ax * by, r = ay * bx;
    return p - r == 0 && orient_exact(a, b, q) != 0;
}

/* The rounding band of the watertight test, on the CPU: a fan of 24 long triangles (spokes ~0.9
   long) whose vertices and ray origins lie on a 2^-22 grid, so vertical rays meet them in exact
   float differences and the exact answer is an integer orientation test. Rays at the grid points
   nearest the lines of every spoke and rim edge (off them) and at and beside every vertex, the
   triangles shuffled and each starting at another vertex: every ray hits a triangle that holds
   its point exactly, never slips through, and misses where none does. Near a spoke the float
   edge function often rounds to 0 (taken as it is, both triangles would claim the ray, and the
   lower numbered one win): the band must send those to the double test. A band narrowed but not
   below 0 still does, so on the CPU it is the same test (see float_edge_lost).
   The fan lies at the origin on a grid of 2^-22 (radius ~2^22 steps), or 1e6 from it on the
   floats' own grid there, 2^-4 (radius ~2^18 steps: a fan 100 times smaller than its distance);
   relative to the scene's centre both are exact in float, so the integer oracle holds for both.
   Measured: 11745 rays each, 8395 rounding to 0 at the origin and 2415 1e6 away; 0 wrong, 0
   slipped, 0 outside. */
static void rounding_band_fan(const char *where, double offset, int radius_bits, int step_bits)
{
    enum { K = 24, ON_SPOKE = 400, ON_RIM = 80, R = K * (ON_SPOKE + ON_RIM) + 9 * (K + 1) };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    int64_t v[K + 1][2], q[2];
    float pos[3 * (K + 1)];
    uint32_t idx[3 * K];
    int slot[K]; /* fan triangle k is the scene's triangle slot[k] */
    static voxgi_ray rays[R];
    static voxgi_ray_hit hits[R];
    static int64_t at[R][2];
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_ray_scene *rs = NULL;
    fx_rng g = fx_rng_seeded(31);
    size_t n = 0, i, lost = 0, wrong_tri = 0, slipped = 0, phantom = 0, inside = 0;
    int k, j, a;
    const double radius = ldexp(1, radius_bits), step = ldexp(1, step_bits); /* grid steps to the rim; world units per step */
    v[K][0] = llround(fx_rng_range(&g, -0.05, 0.05) * radius); /* the hub */
    v[K][1] = llround(fx_rng_range(&g, -0.05, 0.05) * radius);
    for (k = 0; k < K; k++) {
        double th = 2 * 3.14159265358979 * (k + fx_rng_range(&g, -0.3, 0.3)) / K, r = fx_rng_range(&g, 0.85, 0.95);
        v[k][0] = llround(r * cos(th) * radius);
        v[k][1] = llround(r * sin(th) * radius);
    }
    for (k = 0; k <= K; k++) { /* exact floats: offset and steps on the grid */
        pos[3 * k] = (float)(offset + (double)v[k][0] * step);
        pos[3 * k + 1] = (float)(-offset + (double)v[k][1] * step);
        pos[3 * k + 2] = (float)offset;
        TH_CHECK((double)pos[3 * k] == offset + (double)v[k][0] * step && (double)pos[3 * k + 1] == -offset + (double)v[k][1] * step, "vertex %d is not on the grid", k);
    }
    for (k = 0; k < K; k++) slot[k] = k;
    for (k = K - 1; k > 0; k--) { /* the triangles in shuffled order, so that a tie of two is decided either way */
        j = (int)(fx_rng_u64(&g) % (uint64_t)(k + 1));
        a = slot[k]; slot[k] = slot[j]; slot[j] = a;
    }
    for (k = 0; k < K; k++) { /* counter-clockwise: hub, rim k, rim k + 1, starting at vertex k % 3, so a spoke is each of the three edges */
        const uint32_t tri[3] = {K, (uint32_t)k, (uint32_t)((k + 1) % K)};
        for (a = 0; a < 3; a++) idx[3 * slot[k] + a] = tri[(a + k) % 3];
    }
    scene_of_triangles(&sc, &mesh, pos, K + 1, idx, K);
    for (k = 0; k < K; k++) {
        const int64_t *edges[2][2] = {{v[K], v[k]}, {v[k], v[(k + 1) % K]}}; /* a spoke, a rim edge */
        for (j = 0; j < ON_SPOKE + ON_RIM; j++) {
            const int64_t *e0 = edges[j >= ON_SPOKE][0], *e1 = edges[j >= ON_SPOKE][1];
            int64_t best = INT64_MAX;
            int m;
            for (m = 0; m < 256; m++) { /* of 256 grid points by the edge, the nearest to its line */
                double s = fx_rng_range(&g, 0.02, 0.98);
                int64_t p[2], c;
                p[0] = llround((double)e0[0] + s * (double)(e1[0] - e0[0]));
                p[1] = llround((double)e0[1] + s * (double)(e1[1] - e0[1]));
                c = (e1[0] - e0[0]) * (p[1] - e0[1]) - (e1[1] - e0[1]) * (p[0] - e0[0]);
                if (c < 0) c = -c;
                if (c && c < best) { best = c; memcpy(q, p, sizeof p); } /* off the line: one side is right */
            }
            lost += float_edge_lost(e0, e1, q);
            memcpy(at[n++], q, sizeof q);
        }
    }
    for (k = 0; k <= K; k++) /* at each vertex and one grid step beside it */
        for (j = 0; j < 9; j++) {
            at[n][0] = v[k][0] + j % 3 - 1;
            at[n][1] = v[k][1] + j / 3 - 1;
            n++;
        }
    for (i = 0; i < n; i++) {
        rays[i].origin[0] = (float)(offset + (double)at[i][0] * step);
        rays[i].origin[1] = (float)(-offset + (double)at[i][1] * step);
        rays[i].origin[2] = (float)(offset + 64 * step);
        rays[i].direction[0] = rays[i].direction[1] = 0;
        rays[i].direction[2] = -1;
        rays[i].tmin = 0;
        rays[i].tmax = INFINITY;
    }
    TH_CHECK(voxgi_ray_scene_create(ctx, &sc, &rs) == VOXGI_OK && voxgi_ray_intersect(ctx, rs, n, rays, hits) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (i = 0; i < n; i++) {
        int holds = 0, named = 0, rim = 0; /* some triangle holds the point; the one hit does; it lies on the fan's rim */
        for (k = 0; k < K; k++) {
            const int64_t *h = v[K], *b = v[k], *c = v[(k + 1) % K];
            int o0 = orient_exact(h, b, at[i]), o1 = orient_exact(b, c, at[i]), o2 = orient_exact(c, h, at[i]);
            int in = o0 >= 0 && o1 >= 0 && o2 >= 0;
            holds |= in;
            rim |= in && o1 == 0;
            if (in && hits[i].triangle == (uint32_t)slot[k]) named = 1;
        }
        inside += holds;
        if (hits[i].triangle == UINT32_MAX) slipped += holds && !rim; /* exactly on the rim a ray may graze past (see test_watertight_fan) */
        else if (!holds) phantom++;
        else if (!named) wrong_tri++;
    }
    printf("    fan of %d triangles %s: %lu vertical rays (%lu inside), %lu whose edge function rounds to 0 in float; %lu on "
           "a triangle that does not hold their point, %lu slipped through, %lu hit outside\n",
           K, where, (unsigned long)n, (unsigned long)inside, (unsigned long)lost, (unsigned long)wrong_tri, (unsigned long)slipped, (unsigned long)phantom);
    TH_CHECK(lost > n / 20 && inside > n / 2 && inside < n, "the rays do not test the band");
    TH_CHECK(!wrong_tri && !slipped && !phantom, "the triangle test takes a float edge function within rounding of 0 as it is (%lu wrong, %lu slipped, %lu outside)",
             (unsigned long)wrong_tri, (unsigned long)slipped, (unsigned long)phantom);
    voxgi_ray_scene_destroy(ctx, rs);
    voxgi_destroy(ctx);
}

static void test_watertight_rounding_band(void)
{
    rounding_band_fan("at the origin, on a 2^-22 grid", 0, 22, -22);
    rounding_band_fan("1e6 from the origin, on a 2^-4 grid", 1e6, 18, -4);
}

/* Random rays through a soup of random triangles and a sphere: the closest hit is the brute
   force's (the same triangle where its hit lies 1e-4 inside it, else the same t), occlusion is
   a hit's existence; tmin and tmax cut as asked. */
static void test_closest_hits_are_brute_force(void)
{
    enum { T = 400, R = 4000 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    cube_sphere s;
    double c[3] = {0, 0, 0};
    float *pos;
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_ray_scene *rs = NULL;
    static voxgi_ray rays[R];
    static voxgi_ray_hit hits[R];
    static unsigned char occ[R];
    fx_rng g = fx_rng_seeded(11);
    size_t nt, i, wrong_tri = 0, wrong_t = 0, wrong_occ = 0, hit = 0;
    int a;
    cube_sphere_make(&s, 6, 0.7, c);
    nt = s.triangles + T;
    pos = (float *)malloc(nt * 9 * sizeof(float));
    memcpy(pos, s.pos, s.triangles * 9 * sizeof(float));
    for (i = 9 * s.triangles; i < 9 * nt; i++) pos[i] = (float)fx_rng_range(&g, -2, 2); /* big random triangles too */
    for (i = s.triangles; i < nt; i++)
        if (i % 2) /* and small ones */
            for (a = 3; a < 9; a++) pos[9 * i + (size_t)a] = pos[9 * i + (size_t)(a % 3)] + (float)fx_rng_range(&g, -0.2, 0.2);
    scene_of_soup(&sc, &mesh, pos, nt);
    for (i = 0; i < R; i++) {
        for (a = 0; a < 3; a++) { rays[i].origin[a] = (float)fx_rng_range(&g, -3, 3); rays[i].direction[a] = (float)fx_rng_range(&g, -1, 1); }
        rays[i].tmin = i % 3 == 1 ? (float)fx_rng_range(&g, 0, 2) : 0;
        rays[i].tmax = i % 3 == 2 ? (float)fx_rng_range(&g, 0, 4) : INFINITY;
        if (i % 7 == 0) rays[i].direction[i % 3] = 0; /* axis-parallel in one coordinate */
    }
    TH_CHECK(voxgi_ray_scene_create(ctx, &sc, &rs) == VOXGI_OK && voxgi_ray_intersect(ctx, rs, R, rays, hits) == VOXGI_OK &&
                 voxgi_ray_occluded(ctx, rs, R, rays, occ) == VOXGI_OK,
             "%s", voxgi_last_error(ctx));
    for (i = 0; i < R; i++) {
        uint32_t bt = UINT32_MAX;
        double margin = 0, bf = brute_force(pos, nt, &rays[i], &bt, &margin);
        if (bf >= 0) hit++;
        if ((bf >= 0) != (hits[i].triangle != UINT32_MAX)) {
            if (margin > 1e-4 || bf < 0) wrong_tri++; /* a hit near an edge may fall to either side in float */
        } else if (bf >= 0) {
            if (hits[i].triangle != bt && margin > 1e-4) wrong_tri++;
            if (fabs(hits[i].t - bf) > 1e-5 * fmax(1.0, bf)) wrong_t++;
        }
        wrong_occ += occ[i] != (hits[i].triangle != UINT32_MAX);
    }
    printf("    %lu random rays, %lu triangles: %lu hit; %lu on another triangle than brute force's, %lu at another t, occlusion off for %lu\n",
           (unsigned long)R, (unsigned long)nt, (unsigned long)hit, (unsigned long)wrong_tri, (unsigned long)wrong_t, (unsigned long)wrong_occ);
    TH_CHECK(hit > R / 4 && !wrong_tri && !wrong_t && !wrong_occ, "the core disagrees with brute force");
    voxgi_ray_scene_destroy(ctx, rs);
    free(pos);
    free(s.pos);
    voxgi_destroy(ctx);
}

/* Camera rays in 4 x 4 tiles, as voxgi bench rays casts them, at a sphere whose every triangle
   is there twice: a batch (packets of 16) gives each ray's answer cast alone (the same t and
   triangle, also where two triangles meet at that t), the lower of two equal triangles, and brute
   force's. */
static void test_camera_rays(void)
{
    enum { W = 64, R = W * W };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    cube_sphere s;
    double c[3] = {0, 0, 0};
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_ray_scene *rs = NULL;
    static voxgi_ray rays[R];
    static voxgi_ray_hit hits[R], one[R];
    const double eye[3] = {2.5, 1.9, 3.1};
    size_t i, hit = 0, differ = 0, wrong = 0, upper = 0;
    float *twice;
    int x, y, a;
    cube_sphere_make(&s, 16, 1, c);
    twice = (float *)malloc(2 * s.triangles * 9 * sizeof(float));
    memcpy(twice, s.pos, s.triangles * 9 * sizeof(float));
    memcpy(twice + s.triangles * 9, s.pos, s.triangles * 9 * sizeof(float));
    scene_of_soup(&sc, &mesh, twice, 2 * s.triangles);
    for (i = 0, y = 0; y < W; y += 4) /* tile by tile */
        for (x = 0; x < W; x += 4) {
            int tx, ty;
            for (ty = y; ty < y + 4; ty++)
                for (tx = x; tx < x + 4; tx++, i++) {
                    double d[3] = {-eye[0], -eye[1], -eye[2]};
                    d[0] += 3.0 * (tx - W / 2.0) / W;
                    d[1] += 3.0 * (ty - W / 2.0) / W;
                    for (a = 0; a < 3; a++) { rays[i].origin[a] = (float)eye[a]; rays[i].direction[a] = (float)d[a]; }
                    rays[i].tmin = 0;
                    rays[i].tmax = INFINITY;
                }
        }
    TH_CHECK(voxgi_ray_scene_create(ctx, &sc, &rs) == VOXGI_OK && voxgi_ray_intersect(ctx, rs, R, rays, hits) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (i = 0; i < R; i++) { /* one at a time */
        TH_CHECK(voxgi_ray_intersect(ctx, rs, 1, &rays[i], &one[i]) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        hit += hits[i].triangle != UINT32_MAX;
        if (memcmp(&hits[i], &one[i], sizeof one[i])) differ++;
        if (hits[i].triangle != UINT32_MAX) {
            uint32_t bt = UINT32_MAX;
            upper += hits[i].triangle >= s.triangles;
            double margin = 0, bf = brute_force(s.pos, s.triangles, &rays[i], &bt, &margin);
            if (bf < 0 || fabs(hits[i].t - bf) > 1e-5 * bf || (hits[i].triangle != bt && margin > 1e-4)) wrong++;
        }
    }
    printf("    %d camera rays in 4x4 tiles at a sphere of %lu triangles, each twice: %lu hit, %lu differ from the same rays one at a time, %lu from brute "
           "force, %lu on a second copy\n",
           R, (unsigned long)s.triangles, (unsigned long)hit, (unsigned long)differ, (unsigned long)wrong, (unsigned long)upper);
    TH_CHECK(hit > R / 4 && hit < R && !differ && !wrong && !upper, "camera rays differ from single rays or from brute force");
    voxgi_ray_scene_destroy(ctx, rs);
    free(twice);
    free(s.pos);
    voxgi_destroy(ctx);
}

/* The triangles of a scene's meshes (float positions, indexed or not) as a soup, 9 floats each. */
static float *scene_soup_of(const voxgi_scene *sc, size_t *nt)
{
    size_t m, t, n = 0, total = 0;
    float *soup;
    for (m = 0; m < sc->mesh_count; m++) total += sc->meshes[m].indices ? sc->meshes[m].index_count / 3 : sc->meshes[m].vertex_count / 3;
    soup = (float *)malloc(total * 9 * sizeof(float));
    for (m = 0; m < sc->mesh_count; m++) {
        const voxgi_mesh *me = &sc->meshes[m];
        size_t stride = me->position_stride ? me->position_stride : 3 * sizeof(float), count = me->indices ? me->index_count : me->vertex_count;
        for (t = 0; t < count; t++) {
            size_t v = me->indices ? me->indices[t] : t;
            memcpy(soup + 3 * n++, (const char *)me->positions + v * stride, 3 * sizeof(float));
        }
    }
    *nt = total;
    return soup;
}

/* Whether the 16 rays from first share the signs of their directions (so the core casts them as
   one packet). */
static int same_signs(const voxgi_ray *rays)
{
    int k, a;
    for (k = 1; k < 16; k++)
        for (a = 0; a < 3; a++)
            if ((rays[k].direction[a] < 0) != (rays[0].direction[a] < 0)) return 0;
    return 1;
}

/* Packets whose rays end at different tmax, in the Cornell box: camera rays in 4 x 4 tiles, each
   ray's tmax drawn around its own first hit t0 (t0 (1 - 1e-3), t0 (1 + 1e-3), infinite, or
   uniform in (0, 2 t0)), and shadow segments in tiles of 16 from a patch of a wall, block or
   floor to samples of the lamp (tmin 1e-4; tmax 1e-4 short of the lamp, 1e-3 past it, infinite,
   or uniform along the way). The batch (packets of 16 where the signs agree: closest hits only,
   occlusion casts every ray alone) gives every ray exactly the hit it gets cast alone (triangle,
   t, u, v); occlusion is that hit's existence; a camera ray hits nothing before t0 and its t0
   hit after it. Measured: 4096 camera rays (3844 hit unbounded, 2424 within their tmax), 4096
   shadow segments (2821 hit), 384 of 512 packets share their signs; 0 differ. */
static void test_packets_of_varied_tmax(void)
{
    enum { W = 64, CAM = W * W, SHADOW = 4096, R = CAM + SHADOW };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene bs;
    voxgi_ray_scene *rs = NULL;
    static voxgi_ray rays[R];
    static voxgi_ray_hit batch[R], alone[R], open[R];
    static unsigned char occ[R];
    static const float light[2][3] = {{0.213f, 0.5487f, 0.227f}, {0.343f, 0.5487f, 0.332f}}; /* the lamp's quad: x, z range at y */
    fx_rng g = fx_rng_seeded(23);
    double f[3], right[3], up[3], len, tan_half;
    size_t nt, i, differ = 0, occ_wrong = 0, cut_wrong = 0, open_hit = 0, cut_hit = 0, segment_hit = 0, packets = 0;
    float *soup;
    int x, y, a, k;
    TH_CHECK(voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK && voxgi_ray_scene_create(ctx, &bs.scene, &rs) == VOXGI_OK, "%s",
             voxgi_last_error(ctx));
    soup = scene_soup_of(&bs.scene, &nt);
    for (a = 0, len = 0; a < 3; a++) { f[a] = bs.camera.target[a] - bs.camera.eye[a]; len += f[a] * f[a]; }
    for (a = 0; a < 3; a++) f[a] /= sqrt(len);
    right[0] = -f[2]; right[1] = 0; right[2] = f[0]; /* f x (0, 1, 0) */
    len = sqrt(right[0] * right[0] + right[2] * right[2]);
    right[0] /= len; right[2] /= len;
    for (a = 0; a < 3; a++) up[a] = right[(a + 1) % 3] * f[(a + 2) % 3] - right[(a + 2) % 3] * f[(a + 1) % 3];
    tan_half = tan(bs.camera.fovy_degrees * 3.14159265358979 / 360);
    for (i = 0, y = 0; y < W; y += 4) /* camera rays tile by tile */
        for (x = 0; x < W; x += 4) {
            int tx, ty;
            for (ty = y; ty < y + 4; ty++)
                for (tx = x; tx < x + 4; tx++, i++) {
                    double sx = (2.0 * (tx + 0.5) / W - 1) * tan_half, sy = (1 - 2.0 * (ty + 0.5) / W) * tan_half;
                    for (a = 0; a < 3; a++) {
                        rays[i].origin[a] = (float)bs.camera.eye[a];
                        rays[i].direction[a] = (float)(f[a] + sx * right[a] + sy * up[a]);
                    }
                    rays[i].tmin = 0;
                    rays[i].tmax = INFINITY;
                }
        }
    for (i = 0; i < CAM; i++) { /* each one's first hit, alone and unbounded */
        TH_CHECK(voxgi_ray_intersect(ctx, rs, 1, &rays[i], &open[i]) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        open_hit += open[i].triangle != UINT32_MAX;
    }
    for (i = 0; i < CAM; i++) {
        double t0 = open[i].triangle != UINT32_MAX ? open[i].t : 1.0;
        int kind = (int)(fx_rng_u64(&g) % 4);
        rays[i].tmax = kind == 0 ? INFINITY : (float)(kind == 1 ? t0 * (1 - 1e-3) : kind == 2 ? t0 * (1 + 1e-3) : fx_rng_range(&g, 0, 2 * t0));
    }
    for (; i < R; i += 16) { /* shadow segments: 16 points of one patch to 16 samples of the lamp */
        uint32_t t;
        const float *v;
        double u0, v0;
        do t = (uint32_t)(fx_rng_u64(&g) % nt);
        while (t == 10 || t == 11); /* the lamp's own two */
        v = soup + 9 * t;
        u0 = fx_rng_range(&g, 0, 0.8);
        v0 = fx_rng_range(&g, 0, 0.8 - u0);
        for (k = 0; k < 16; k++) {
            voxgi_ray *r = &rays[i + (size_t)k];
            double bu = u0 + fx_rng_range(&g, 0, 0.1), bv = v0 + fx_rng_range(&g, 0, 0.1), p[3], d[3], dist = 0;
            int kind = (int)(fx_rng_u64(&g) % 4);
            for (a = 0; a < 3; a++) p[a] = v[a] + bu * (v[3 + a] - v[a]) + bv * (v[6 + a] - v[a]);
            d[0] = fx_rng_range(&g, light[0][0], light[1][0]) - p[0];
            d[1] = light[0][1] - p[1];
            d[2] = fx_rng_range(&g, light[0][2], light[1][2]) - p[2];
            for (a = 0; a < 3; a++) dist += d[a] * d[a];
            dist = sqrt(dist);
            for (a = 0; a < 3; a++) { r->origin[a] = (float)p[a]; r->direction[a] = (float)(d[a] / dist); }
            r->tmin = 1e-4f;
            r->tmax = kind == 2 ? INFINITY : (float)(kind == 0 ? dist * (1 - 1e-4) : kind == 1 ? dist * (1 + 1e-3) : dist * fx_rng_range(&g, 0.05, 1));
        }
    }
    TH_CHECK(voxgi_ray_intersect(ctx, rs, R, rays, batch) == VOXGI_OK && voxgi_ray_occluded(ctx, rs, R, rays, occ) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (i = 0; i < R; i++) {
        int hit;
        TH_CHECK(voxgi_ray_intersect(ctx, rs, 1, &rays[i], &alone[i]) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        hit = alone[i].triangle != UINT32_MAX;
        differ += memcmp(&batch[i], &alone[i], sizeof alone[i]) != 0;
        occ_wrong += occ[i] != hit;
        if (i < CAM) {
            double t0 = open[i].t;
            cut_hit += hit;
            if (open[i].triangle == UINT32_MAX || rays[i].tmax < t0 * (1 - 1e-6)) cut_wrong += hit; /* nothing before the first hit */
            else if (rays[i].tmax > t0 * (1 + 1e-6)) cut_wrong += memcmp(&alone[i], &open[i], sizeof open[i]) != 0;
        } else
            segment_hit += hit;
        if (i % 16 == 0) packets += same_signs(&rays[i]);
    }
    printf("    Cornell box: %d camera rays (%lu hit unbounded, %lu within their tmax, %lu not as t0 says), %d shadow segments (%lu hit); %lu "
           "of %d packets share their signs; %lu rays differ from the same ray alone, occlusion off for %lu\n",
           CAM, (unsigned long)open_hit, (unsigned long)cut_hit, (unsigned long)cut_wrong, SHADOW, (unsigned long)segment_hit, (unsigned long)packets, R / 16,
           (unsigned long)differ, (unsigned long)occ_wrong);
    TH_CHECK(open_hit > CAM / 2 && open_hit < CAM && cut_hit > CAM / 4 && cut_hit < open_hit && segment_hit > SHADOW / 8 && segment_hit < SHADOW && packets > R / 32,
             "the rays do not cover hits and misses, or too few packets");
    TH_CHECK(!differ && !occ_wrong && !cut_wrong, "packets of varied tmax differ from single rays (%lu), from occlusion (%lu) or from t0 (%lu)",
             (unsigned long)differ, (unsigned long)occ_wrong, (unsigned long)cut_wrong);
    voxgi_ray_scene_destroy(ctx, rs);
    voxgi_builtin_scene_destroy(ctx, &bs);
    free(soup);
    voxgi_destroy(ctx);
}

/* A scene big enough that its BVH's subtrees are built on the workers (10800 triangles): the
   same tree, so the same answers, with 1, 2 and 3 threads. */
static void test_build_on_workers(void)
{
    enum { R = 20000 };
    cube_sphere s;
    double c[3] = {0.5, 0.25, -0.125};
    voxgi_scene sc;
    voxgi_mesh mesh;
    static voxgi_ray rays[R];
    static voxgi_ray_hit hits[3][R];
    fx_rng g = fx_rng_seeded(5);
    size_t n, hit = 0, i;
    int th;
    cube_sphere_make(&s, 30, 1, c);
    scene_of_soup(&sc, &mesh, s.pos, s.triangles);
    n = inside_rays(&s, c, 1, &g, rays, R);
    for (i = 0; i < n; i += 3) rays[i].origin[0] += 3; /* some from outside, to miss or hit the far side */
    for (th = 0; th < 3; th++) {
        voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, th + 1);
        voxgi_ray_scene *rs = NULL;
        TH_CHECK(voxgi_ray_scene_create(ctx, &sc, &rs) == VOXGI_OK && voxgi_ray_intersect(ctx, rs, n, rays, hits[th]) == VOXGI_OK, "%s",
                 voxgi_last_error(ctx));
        voxgi_ray_scene_destroy(ctx, rs);
        voxgi_destroy(ctx);
    }
    for (i = 0; i < n; i++) hit += hits[0][i].triangle != UINT32_MAX;
    printf("    %lu triangles, %lu rays (%lu hit): 1, 2 and 3 threads %s\n", (unsigned long)s.triangles, (unsigned long)n, (unsigned long)hit,
           !memcmp(hits[0], hits[1], n * sizeof hits[0][0]) && !memcmp(hits[0], hits[2], n * sizeof hits[0][0]) ? "agree" : "differ");
    TH_CHECK(hit > n / 2 && hit < n, "%lu of %lu hit", (unsigned long)hit, (unsigned long)n);
    TH_CHECK(!memcmp(hits[0], hits[1], n * sizeof hits[0][0]) && !memcmp(hits[0], hits[2], n * sizeof hits[0][0]), "thread counts answer differently");
    free(s.pos);
}

/* Bad input: NULLs, a scene without triangles and non-finite rays are refused; a zero direction
   hits nothing; a hit is at (tmin, tmax) exclusive and reports the barycentrics of its point. */
static void test_ray_input(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    voxgi_scene sc, empty;
    voxgi_mesh mesh;
    voxgi_ray_scene *rs = NULL, *none = (voxgi_ray_scene *)&sc;
    voxgi_ray ray = {{0.25f, 0.5f, 1}, 0, {0, 0, -1}, INFINITY};
    voxgi_ray_hit hit;
    unsigned char occ = 9;
    scene_of_soup(&sc, &mesh, tri, 1);
    memset(&empty, 0, sizeof empty);
    TH_CHECK(voxgi_ray_scene_create(ctx, &sc, &rs) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    TH_CHECK(voxgi_ray_scene_create(ctx, &empty, &none) == VOXGI_ERR_EMPTY_SCENE && !none, "a scene without triangles accepted");
    TH_CHECK(voxgi_ray_intersect(ctx, rs, 1, &ray, &hit) == VOXGI_OK && hit.triangle == 0 && hit.t == 1 && hit.u == 0.25f && hit.v == 0.5f,
             "hit %u at t %g (u %g, v %g)", hit.triangle, hit.t, hit.u, hit.v);
    ray.tmax = 1;
    TH_CHECK(voxgi_ray_intersect(ctx, rs, 1, &ray, &hit) == VOXGI_OK && hit.triangle == UINT32_MAX, "a hit at tmax counted");
    ray.tmax = INFINITY;
    ray.tmin = 1;
    TH_CHECK(voxgi_ray_occluded(ctx, rs, 1, &ray, &occ) == VOXGI_OK && occ == 0, "a hit at tmin counted");
    ray.tmin = 0;
    ray.direction[2] = 0;
    TH_CHECK(voxgi_ray_intersect(ctx, rs, 1, &ray, &hit) == VOXGI_OK && hit.triangle == UINT32_MAX, "a zero direction hit");
    ray.direction[2] = -1;
    ray.origin[0] = NAN;
    TH_CHECK(voxgi_ray_intersect(ctx, rs, 1, &ray, &hit) == VOXGI_ERR_INVALID_ARGUMENT, "a NaN origin accepted");
    ray.origin[0] = 0.25f;
    TH_CHECK(voxgi_ray_intersect(ctx, rs, 1, &ray, NULL) == VOXGI_ERR_INVALID_ARGUMENT && voxgi_ray_occluded(ctx, NULL, 1, &ray, &occ) == VOXGI_ERR_INVALID_ARGUMENT &&
                 voxgi_ray_scene_create(ctx, NULL, &rs) == VOXGI_ERR_INVALID_ARGUMENT,
             "NULLs accepted");
    TH_CHECK(voxgi_ray_intersect(ctx, rs, 0, NULL, NULL) == VOXGI_OK, "no rays refused");
    voxgi_ray_scene_destroy(ctx, rs);
    voxgi_destroy(ctx);
}

int main(void)
{
    TH_RUN(test_watertight_sphere);
    TH_RUN(test_watertight_fan);
    TH_RUN(test_watertight_rounding_band);
    TH_RUN(test_closest_hits_are_brute_force);
    TH_RUN(test_camera_rays);
    TH_RUN(test_packets_of_varied_tmax);
    TH_RUN(test_build_on_workers);
    TH_RUN(test_ray_input);
    return th_finish();
}
