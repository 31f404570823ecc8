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
    TH_RUN(test_closest_hits_are_brute_force);
    TH_RUN(test_camera_rays);
    TH_RUN(test_build_on_workers);
    TH_RUN(test_ray_input);
    return th_finish();
}
