/* tests/test_linespace.c - part 12: the line space, CPU and GL.

   The line space's soft shadows against what is known exactly: a plane under an area light with
   nothing between sees all of it, in both modes, packets or not; under a box occluder each point
   sees the light minus the box's shadow on it (the convex hull of the box's corners projected from
   the point onto the light's plane, clipped to the light: the analytic penumbra), fast mode never
   lighter than exact; the sample weights: a half-shuttered light's shadowed irradiance against
   Lambert's formula for its visible part; the Cornell box's direct light against the reference
   renderer's on 4 x 4 block means away from the emitter; bad input refused. (Exact mode against brute-force ray
   casting, the line space's bits against sampled segments, packets against single rays: in
   tests/test_internals.c, which sees the private walk.) */
#include "../voxgi.h"
#include "fixtures.h"

/* A 2 x 2 floor at y = 0 facing up, and (box) a closed box [-0.15, 0.15] x [0.5, 0.55] x
   [-0.1, 0.2] above it: triangles into pos, their count. */
static int floor_and_box(float *pos, int box)
{
    static const float lo[3] = {-0.15f, 0.5f, -0.1f}, hi[3] = {0.15f, 0.55f, 0.2f};
    static const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    static const float fl[6][3] = {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {-1, 0, -1}, {1, 0, 1}, {1, 0, -1}};
    int t = 2, q, k;
    memcpy(pos, fl, sizeof fl);
    for (q = 0; box && q < 6; q++)
        for (k = 0; k < 6; k++) {
            int c = faces[q][(int)"\0\1\2\0\2\3"[k]], a;
            for (a = 0; a < 3; a++) pos[9 * t + 3 * (k % 3) + a] = (c >> a & 1) ? hi[a] : lo[a];
            if (k == 2 || k == 5) t++;
        }
    return t;
}

/* The light of these tests: 0.4 x 0.4 at y = 1, shining down. */
static void light_desc(voxgi_linespace_light_desc *d, voxgi_linespace_mode mode, int samples, int packets)
{
    memset(d, 0, sizeof *d);
    d->mode = mode;
    d->samples = samples;
    d->packets = packets;
    d->corner[0] = -0.2; d->corner[1] = 1; d->corner[2] = -0.2;
    d->edge_u[0] = 0.4;
    d->edge_v[2] = 0.4;
    d->seed = 3;
}

/* Points on the floor: a grid over [-r, r]^2 (n x n), normals up. */
static void floor_points(float *p, float *nrm, int n, double r)
{
    int i, j;
    for (j = 0; j < n; j++)
        for (i = 0; i < n; i++) {
            float *q = p + 3 * (j * n + i), *m = nrm + 3 * (j * n + i);
            q[0] = (float)(-r + 2 * r * (i + 0.5) / n); q[1] = 0; q[2] = (float)(-r + 2 * r * (j + 0.5) / n);
            m[0] = 0; m[1] = 1; m[2] = 0;
        }
}

/* With nothing between but triangles without area (a point, a segment: they can never be hit),
   every point of the floor sees the whole light: exact and fast, rays alone and in packets, 1 and
   7 and 16 samples. */
static void test_plane_fully_lit(void)
{
    static const float degenerate[18] = {0.05f, 0.5f, 0.05f, 0.05f, 0.5f, 0.05f, 0.05f, 0.5f, 0.05f, -0.1f, 0.6f, -0.1f, 0, 0.6f, 0, 0.1f, 0.6f, 0.1f};
    static float pos[9 * 4], p[3 * 400], nrm[3 * 400], vis[400], w[400];
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_linespace *L = NULL;
    voxgi_linespace_desc td;
    int m, pk, s, i, dark = 0, runs = 0;
    static const int samples[3] = {1, 7, 16};
    memcpy(pos + 9 * floor_and_box(pos, 0), degenerate, sizeof degenerate);
    scene_of_triangles(&sc, &mesh, pos, 12, NULL, 0);
    memset(&td, 0, sizeof td);
    td.n = 4;
    td.depth = 2;
    TH_CHECK(voxgi_linespace_create(ctx, &sc, &td, &L) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    floor_points(p, nrm, 20, 0.999);
    for (m = 0; L && m < 2; m++)
        for (pk = 0; pk < 2; pk++)
            for (s = 0; s < 3; s++) {
                voxgi_linespace_light_desc d;
                light_desc(&d, (voxgi_linespace_mode)m, samples[s], pk);
                TH_CHECK(voxgi_linespace_light(ctx, L, &d, 400, p, nrm, vis, w, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
                for (i = 0; i < 400; i++) dark += vis[i] != 1.0f || w[i] != 1.0f;
                runs++;
            }
    printf("    %d runs of 400 floor points: %d not fully lit\n", runs, dark);
    TH_CHECK(runs == 12 && dark == 0, "a floor with nothing over it is shadowed");
    voxgi_linespace_destroy(ctx, L);
    voxgi_destroy(ctx);
}

/* The area of the convex polygon q (n points, 2D) clipped to [lo, hi]^2. */
static double clipped_area(const double q[][2], int n, double lo, double hi)
{
    double a[32][2], b[32][2], area = 0;
    int m = n, e, i, k;
    memcpy(a, q, (size_t)n * sizeof *a);
    for (e = 0; e < 4; e++) { /* x >= lo, x <= hi, z >= lo, z <= hi */
        int ax = e / 2, nb = 0;
        double bound = (e % 2) ? hi : lo, sign = (e % 2) ? -1 : 1;
        for (i = 0; i < m; i++) {
            const double *p0 = a[i], *p1 = a[(i + 1) % m];
            double d0 = sign * (p0[ax] - bound), d1 = sign * (p1[ax] - bound);
            if (d0 >= 0) { b[nb][0] = p0[0]; b[nb][1] = p0[1]; nb++; }
            if ((d0 >= 0) != (d1 >= 0)) {
                double t = d0 / (d0 - d1);
                for (k = 0; k < 2; k++) b[nb][k] = p0[k] + t * (p1[k] - p0[k]);
                nb++;
            }
        }
        memcpy(a, b, (size_t)nb * sizeof *a);
        m = nb;
    }
    for (i = 0; i < m; i++) area += a[i][0] * a[(i + 1) % m][1] - a[(i + 1) % m][0] * a[i][1];
    return fabs(area) / 2;
}

/* The share of the light point p sees past the box: 1 - the area of the box's shadow on the
   light's plane (the hull of its 8 corners projected from p) within the light / the light's. */
static double analytic_visible(const float p[3])
{
    static const double lo[3] = {-0.15, 0.5, -0.1}, hi[3] = {0.15, 0.55, 0.2};
    double pts[8][2], hull[16][2];
    int c, i, n = 0;
    for (c = 0; c < 8; c++) {
        double x = (c & 1) ? hi[0] : lo[0], y = (c & 2) ? hi[1] : lo[1], z = (c & 4) ? hi[2] : lo[2], s = (1 - p[1]) / (y - p[1]);
        pts[c][0] = p[0] + (x - p[0]) * s;
        pts[c][1] = p[2] + (z - p[2]) * s;
    }
    for (c = 1; c < 8; c++) /* sorted by x, then z (insertion) */
        for (i = c; i > 0 && (pts[i][0] < pts[i - 1][0] || (pts[i][0] == pts[i - 1][0] && pts[i][1] < pts[i - 1][1])); i--) {
            double t0 = pts[i][0], t1 = pts[i][1];
            pts[i][0] = pts[i - 1][0]; pts[i][1] = pts[i - 1][1];
            pts[i - 1][0] = t0; pts[i - 1][1] = t1;
        }
    for (c = 0; c < 8; c++) { /* the monotone chain: lower hull, then upper */
        while (n >= 2 && (hull[n - 1][0] - hull[n - 2][0]) * (pts[c][1] - hull[n - 2][1]) - (hull[n - 1][1] - hull[n - 2][1]) * (pts[c][0] - hull[n - 2][0]) <= 0) n--;
        hull[n][0] = pts[c][0]; hull[n][1] = pts[c][1]; n++;
    }
    for (c = 6, i = n + 1; c >= 0; c--) {
        while (n >= i && (hull[n - 1][0] - hull[n - 2][0]) * (pts[c][1] - hull[n - 2][1]) - (hull[n - 1][1] - hull[n - 2][1]) * (pts[c][0] - hull[n - 2][0]) <= 0) n--;
        hull[n][0] = pts[c][0]; hull[n][1] = pts[c][1]; n++;
    }
    return 1 - clipped_area((const double(*)[2])hull, n - 1, -0.2, 0.2) / 0.16;
}

/* A box over the floor: each point's visible share against the analytic one (64 samples, 8 x 8
   jittered: mean error under 0.02, none over 0.15; 256: no bias, the error down by more than
   0.6, stratification's 4^-0.75), the penumbra present (shares strictly
   between 0 and 1), fast mode never lighter than exact, and packets the same as rays alone. */
static void test_box_penumbra(void)
{
    enum { G = 48, P = G * G };
    static float pos[9 * 14], p[3 * P], nrm[3 * P], ex[P], fa[P], pk[P], ex256[P];
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_linespace *L = NULL;
    voxgi_linespace_desc td;
    voxgi_linespace_light_desc d;
    double err = 0, err256 = 0, bias256 = 0, worst = 0, fast_err = 0;
    int i, penumbra = 0, lighter = 0, packets_differ = 0;
    scene_of_triangles(&sc, &mesh, pos, 3 * (size_t)floor_and_box(pos, 1), NULL, 0);
    memset(&td, 0, sizeof td);
    td.n = 4;
    td.depth = 3;
    TH_CHECK(voxgi_linespace_create(ctx, &sc, &td, &L) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    if (!L) { voxgi_destroy(ctx); return; }
    floor_points(p, nrm, G, 0.6);
    light_desc(&d, VOXGI_LINESPACE_EXACT, 64, 0);
    TH_CHECK(voxgi_linespace_light(ctx, L, &d, P, p, nrm, ex, NULL, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    d.packets = 1;
    TH_CHECK(voxgi_linespace_light(ctx, L, &d, P, p, nrm, pk, NULL, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    d.samples = 256;
    d.packets = 0;
    TH_CHECK(voxgi_linespace_light(ctx, L, &d, P, p, nrm, ex256, NULL, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    light_desc(&d, VOXGI_LINESPACE_FAST, 64, 0);
    TH_CHECK(voxgi_linespace_light(ctx, L, &d, P, p, nrm, fa, NULL, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (i = 0; i < P; i++) {
        double a = analytic_visible(p + 3 * i), e = fabs(ex[i] - a);
        err += e;
        err256 += fabs(ex256[i] - a);
        bias256 += ex256[i] - a;
        fast_err += fabs(fa[i] - a);
        worst = e > worst ? e : worst;
        penumbra += a > 0.01 && a < 0.99;
        lighter += fa[i] > ex[i];
        packets_differ += pk[i] != ex[i];
    }
    err /= P;
    err256 /= P;
    bias256 /= P;
    fast_err /= P;
    printf("    %d floor points, %d in the penumbra: exact, 64 samples: mean error %.4f (worst %.3f), 256 samples %.4f (mean %+.5f); "
           "fast, 64: %.4f, %d lighter than exact; packets: %d differ\n",
           P, penumbra, err, worst, err256, bias256, fast_err, lighter, packets_differ);
    TH_CHECK(penumbra > P / 10, "no penumbra to test");
    TH_CHECK(err < 0.02 && worst < 0.15 && fabs(bias256) < 0.002, "exact mode's shadow is not the box's");
    TH_CHECK(err256 < 0.6 * err, "more samples do not converge");
    TH_CHECK(lighter == 0, "fast mode is lighter than exact");
    TH_CHECK(packets_differ == 0, "packets see otherwise than rays alone");
    voxgi_linespace_destroy(ctx, L);
    voxgi_destroy(ctx);
}

/* The irradiance at p (normal up) from the rectangle [x0, x1] x [-0.2, 0.2] at y = 1 facing down,
   per unit radiance: Lambert's polygon formula, 1/2 sum over the edges of the angle they subtend
   times the cosine of their plane's normal to n. */
static double rect_irradiance(const double p[3], double x0, double x1)
{
    const double c[4][2] = {{x0, -0.2}, {x1, -0.2}, {x1, 0.2}, {x0, 0.2}};
    double v[4][3], sum = 0;
    int k, a;
    for (k = 0; k < 4; k++) {
        double len;
        v[k][0] = c[k][0] - p[0];
        v[k][1] = 1 - p[1];
        v[k][2] = c[k][1] - p[2];
        len = sqrt(v[k][0] * v[k][0] + v[k][1] * v[k][1] + v[k][2] * v[k][2]);
        for (a = 0; a < 3; a++) v[k][a] /= len;
    }
    for (k = 0; k < 4; k++) {
        const double *s = v[k], *e = v[(k + 1) % 4];
        double g[3] = {s[1] * e[2] - s[2] * e[1], s[2] * e[0] - s[0] * e[2], s[0] * e[1] - s[1] * e[0]};
        double gl = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
        sum += acos(fmax(-1.0, fmin(1.0, s[0] * e[0] + s[1] * e[1] + s[2] * e[2]))) * g[1] / gl;
    }
    return fabs(sum) / 2;
}

/* The area light's sample weights (cos_p cos_l / r^2) on the CPU. Unoccluded, the weighted share
   is 1 whatever the weights, so half the light is hidden: an opaque shutter at y = 0.98 over x in
   [-0.6, 0] hides the part of the light (0.4 x 0.4 at y = 1) left of x' = -0.02 p_x / (d - 0.02)
   seen from a point at distance d below it, and the shadowed irradiance is exactly that of
   [x', 0.2] x [-0.2, 0.2] (Lambert's polygon formula). 32 points at distances 0.1, 0.2, 0.4 and
   0.8, 0.2 and 0.5 either side of the light's centre in x, at z = 0 and 0.3, normals up: the
   weighted share x the whole light's irradiance (what the images multiply) against it, per the
   whole light's irradiance, 4096 samples (64 x 64 jittered) each: within 0.005, five times the noise of the column of 64
   cells the edge crosses (sqrt(64 / 4) / 4096 = 0.001); measured 0.0014 (seed 3), at most
   0.0025 over seeds 1 to 12. Unweighted shares (visible) are off by 0.34, and weights of the
   wrong power of the distance (cos_p cos_l, or / r^4) by 0.13 and 0.09. */
static void test_area_light_weights(void)
{
    enum { P = 32 };
    static const float shutter[18] = {-0.6f, 0.98f, -0.6f, 0, 0.98f, -0.6f, 0, 0.98f, 0.6f, -0.6f, 0.98f, -0.6f, 0, 0.98f, 0.6f, -0.6f, 0.98f, 0.6f};
    static const double dist[4] = {0.1, 0.2, 0.4, 0.8}, across[4] = {-0.5, -0.2, 0.2, 0.5};
    static float pos[9 * 4], p[3 * P], nrm[3 * P], vis[P], w[P];
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_linespace *L = NULL;
    voxgi_linespace_desc td;
    voxgi_linespace_light_desc d;
    double worst = 0, worst_unweighted = 0;
    int i;
    memcpy(pos + 9 * floor_and_box(pos, 0), shutter, sizeof shutter);
    scene_of_triangles(&sc, &mesh, pos, 12, NULL, 0);
    memset(&td, 0, sizeof td);
    td.n = 4;
    td.depth = 2;
    TH_CHECK(voxgi_linespace_create(ctx, &sc, &td, &L) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    if (!L) { voxgi_destroy(ctx); return; }
    for (i = 0; i < P; i++) {
        p[3 * i] = (float)across[i % 4];
        p[3 * i + 1] = (float)(1 - dist[i / 4 % 4]);
        p[3 * i + 2] = i < 16 ? 0.0f : 0.3f;
        nrm[3 * i] = nrm[3 * i + 2] = 0;
        nrm[3 * i + 1] = 1;
    }
    light_desc(&d, VOXGI_LINESPACE_EXACT, 4096, 0);
    TH_CHECK(voxgi_linespace_light(ctx, L, &d, P, p, nrm, vis, w, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (i = 0; i < P; i++) {
        double x[3] = {p[3 * i], p[3 * i + 1], p[3 * i + 2]}, edge = -0.02 * x[0] / (1 - x[1] - 0.02);
        double full = rect_irradiance(x, -0.2, 0.2), want = rect_irradiance(x, edge, 0.2);
        worst = fmax(worst, fabs(w[i] * full - want) / full);
        worst_unweighted = fmax(worst_unweighted, fabs(vis[i] * full - want) / full);
    }
    printf("    %d points 0.1 to 0.8 under the half-shuttered light: shadowed irradiance within %.4f of Lambert's (of the whole light's); "
           "unweighted shares %.4f\n", P, worst, worst_unweighted);
    TH_CHECK(worst < 0.005, "the sample weights are not the irradiance's");
    TH_CHECK(worst_unweighted > 0.1, "the points do not tell weighted from unweighted shares");
    voxgi_linespace_destroy(ctx, L);
    voxgi_destroy(ctx);
}

/* The Cornell box's direct light (32 x 32, 4 x 4 points per pixel, 4 samples each: 64 rays per
   pixel) against the reference's (1024 spp) on 4 x 4 block means, the blocks within 3 pixels of
   one whose centre sees the light left out: exact within 3% (the bound); fast mode,
   whose shafts are a child's face wide (n 8, depth 2: 1/64 of the box), coarser, within 25%
   (measured 16%; docs/line-space.md) and never lighter; with 24 leaves' edges exact at the rays'
   ends within 6% (the bound for fast mode); the visible shares in [0, 1]. */
static void test_cornell_direct_light(void)
{
    enum { W = 32, P = W * W };
    static float ref[3 * P], img[3][3 * P], vis[P];
    static uint32_t tri[P];
    static unsigned char seen[P], masked[P];
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    voxgi_builtin_scene bs;
    voxgi_render_desc rd, d;
    double err[3], mean[3] = {0, 0, 0};
    int m, i, x, y, out_of_range = 0;
    TH_CHECK(voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    bs.camera.width = bs.camera.height = W;
    memset(&rd, 0, sizeof rd);
    rd.method = VOXGI_RENDER_REFERENCE;
    rd.camera = bs.camera;
    rd.samples = 1024;
    rd.direct_only = 1; /* the direct light alone (the old bounces 0) */
    rd.seed = 5;
    rd.hide_emitters = 1;
    TH_CHECK(voxgi_render(ctx, &bs.scene, &rd, ref, sizeof ref, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    TH_CHECK(voxgi_gbuffer_render(ctx, &bs.scene, &bs.camera, NULL, NULL, tri) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (i = 0; i < P; i++) seen[i] = tri[i] != UINT32_MAX && bs.scene.materials[bs.scene.meshes[0].material_ids ? bs.scene.meshes[0].material_ids[tri[i]] : 0].emission[0] > 0;
    for (i = 0; i < P; i++) /* within 3 pixels of the light */
        for (y = -3; y <= 3; y++)
            for (x = -3; x <= 3; x++) {
                int px = i % W + x, py = i / W + y;
                if (px >= 0 && py >= 0 && px < W && py < W && seen[py * W + px]) masked[i] = 1;
            }
    for (m = 0; m < 3; m++) { /* exact; fast; fast with the triangles deciding within 24 leaves of the ends */
        double num = 0, den = 0;
        int bx, by, c;
        memset(&d, 0, sizeof d);
        d.method = VOXGI_RENDER_LINESPACE;
        d.camera = bs.camera;
        d.linespace.mode = m ? VOXGI_LINESPACE_FAST : VOXGI_LINESPACE_EXACT;
        d.linespace.exact_ends = m == 2 ? 24 : 0;
        d.linespace.samples = 4;
        d.linespace.supersample = 4;
        d.seed = 1;
        d.hide_emitters = 1;
        d.linespace.tree.n = 8;
        d.linespace.tree.depth = 2;
        d.linespace.visible = vis;
        TH_CHECK(voxgi_render(ctx, &bs.scene, &d, img[m], sizeof img[m], NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        for (i = 0; i < P; i++) out_of_range += !(vis[i] >= 0 && vis[i] <= 1);
        for (by = 0; by < W; by += 4)
            for (bx = 0; bx < W; bx += 4) {
                double a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
                int skip = 0;
                for (y = by; y < by + 4; y++)
                    for (x = bx; x < bx + 4; x++) {
                        skip |= masked[y * W + x];
                        for (c = 0; c < 3; c++) { a[c] += img[m][3 * (y * W + x) + c]; b[c] += ref[3 * (y * W + x) + c]; }
                    }
                if (skip) continue;
                for (c = 0; c < 3; c++) { num += (a[c] - b[c]) * (a[c] - b[c]); den += b[c] * b[c]; mean[m] += a[c]; }
            }
        err[m] = sqrt(num / den);
    }
    printf("    4 x 4 block means against the reference: exact %.2f%%, fast %.2f%%, fast with 24 leaves exact at the ends %.2f%% (means %.4g, %.4g "
           "against exact's %.4g); %d visible shares out of [0, 1]\n",
           100 * err[0], 100 * err[1], 100 * err[2], mean[1], mean[2], mean[0], out_of_range);
    TH_CHECK(err[0] < 0.03, "exact mode's soft shadows are not the reference's direct light");
    TH_CHECK(err[1] > err[0] && err[1] < 0.25 && mean[1] <= mean[0], "fast mode is no coarser than exact, far off, or lighter");
    TH_CHECK(err[2] < 0.06 && err[2] < err[1] && mean[2] <= mean[0], "fast mode with a wide exact zone is not within 6%, or lighter");
    TH_CHECK(out_of_range == 0, "a visible share out of [0, 1]");
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* Bad input: a clear error, nothing done. */
static void test_linespace_input(void)
{
    static float pos[9 * 2], p[3] = {0, 0, 0}, nrm[3] = {0, 1, 0}, nan_p[3] = {0, 0, 0}, v;
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 1);
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_linespace *L = NULL;
    voxgi_linespace_desc td;
    voxgi_linespace_light_desc d;
    voxgi_render_desc id;
    float rgb[3];
    static float rgb4[3 * 16];
    scene_of_triangles(&sc, &mesh, pos, 3 * (size_t)floor_and_box(pos, 0), NULL, 0);
    memset(&td, 0, sizeof td);
    td.n = 4;
    td.depth = 2;
    TH_CHECK(voxgi_linespace_create(ctx, &sc, &td, &L) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    light_desc(&d, VOXGI_LINESPACE_EXACT, 5000, 0);
    TH_CHECK(voxgi_linespace_light(ctx, L, &d, 1, p, nrm, &v, NULL, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "5000 samples accepted");
    light_desc(&d, VOXGI_LINESPACE_EXACT, 4, 0);
    d.edge_v[0] = 0.4; d.edge_v[2] = 0;
    TH_CHECK(voxgi_linespace_light(ctx, L, &d, 1, p, nrm, &v, NULL, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "a light without area accepted");
    light_desc(&d, (voxgi_linespace_mode)7, 4, 0);
    TH_CHECK(voxgi_linespace_light(ctx, L, &d, 1, p, nrm, &v, NULL, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "mode 7 accepted");
    light_desc(&d, VOXGI_LINESPACE_EXACT, 4, 0);
    nan_p[1] = NAN;
    TH_CHECK(voxgi_linespace_light(ctx, L, &d, 1, nan_p, nrm, &v, NULL, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "a NaN point accepted");
    memset(&id, 0, sizeof id);
    id.method = VOXGI_RENDER_LINESPACE;
    id.linespace.samples = 16;    /* the old defaults: 16 shadow rays, */
    id.linespace.supersample = 1; /* the pixel's centre */
    id.camera.eye[2] = -3; id.camera.eye[1] = 1; id.camera.fovy_degrees = 40; id.camera.width = id.camera.height = 1;
    { /* no area light: the plan leaves the line space out, and the image holds only the (absent) emission */
        voxgi_render_info ii;
        float vis = -1;
        rgb[0] = rgb[1] = rgb[2] = -1;
        id.linespace.visible = &vis;
        TH_CHECK(voxgi_render(ctx, &sc, &id, rgb, sizeof rgb, &ii) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        id.linespace.visible = NULL;
        TH_CHECK(rgb[0] == 0 && rgb[1] == 0 && rgb[2] == 0 && vis == 0, "without an area light: %g %g %g, visible %g", rgb[0], rgb[1], rgb[2], vis);
        TH_CHECK(ii.lights == 0 && ii.tree.bytes == 0 && ii.shadow_rays.rays == 0, "without an area light: %d lights, a %lu-byte tree, %lu rays", ii.lights,
                 (unsigned long)ii.tree.bytes, (unsigned long)ii.shadow_rays.rays);
    }
    voxgi_linespace_destroy(ctx, L);
    { /* an emissive quad over the floor with a degenerate emissive triangle on its edge: one light; the furnace's
         thousands of emissive triangles: refused */
        static float lit[9 * 5];
        static const float quadl[27] = {-0.2f, 1, -0.2f, 0.2f, 1, 0.2f, 0.2f, 1, -0.2f,  /* the quad's first half, */
                                        -0.2f, 1, -0.2f, 0.2f, 1, 0.2f, 0.2f, 1, 0.2f,   /* a degenerate one on its diagonal, */
                                        -0.2f, 1, -0.2f, -0.2f, 1, 0.2f, 0.2f, 1, 0.2f}; /* the quad's second half */
        static uint32_t ids[5] = {0, 0, 1, 1, 1};
        static const voxgi_material mats[2] = {{{0.5f, 0.5f, 0.5f}, {0, 0, 0}, 0}, {{0.5f, 0.5f, 0.5f}, {5, 5, 5}, 0}};
        voxgi_render_info info;
        voxgi_builtin_scene bs;
        memcpy(lit, pos, sizeof pos);
        memcpy(lit + 18, quadl, sizeof quadl);
        scene_of_triangles(&sc, &mesh, lit, 15, NULL, 0);
        mesh.material_ids = ids;
        sc.materials = mats;
        sc.material_count = 2;
        memset(&id, 0, sizeof id);
        id.method = VOXGI_RENDER_LINESPACE;
        id.linespace.samples = 16;    /* the old defaults */
        id.linespace.supersample = 1;
        id.camera.eye[1] = 3; id.camera.eye[2] = -3; id.camera.fovy_degrees = 40; id.camera.width = id.camera.height = 4;
        id.linespace.tree.n = 4;
        id.linespace.tree.depth = 2;
        TH_CHECK(voxgi_render(ctx, &sc, &id, rgb4, sizeof rgb4, &info) == VOXGI_OK && info.lights == 1, "%s (lights %d)",
                 voxgi_last_error(ctx), info.lights);
        { /* the image's tree outside voxgi_linespace_create's ranges: refused before the plan sizes it (with n^4 in int) */
            static const int bad[5][2] = {{1, 2}, {17, 2}, {2147483647, 2}, {4, 9}, {4, -1}};
            voxgi_render_desc used, bd = id;
            int k;
            for (k = 0; k < 5; k++) {
                bd.linespace.tree.n = bad[k][0];
                bd.linespace.tree.depth = bad[k][1];
                TH_CHECK(voxgi_render_resolve(ctx, &sc, &bd, &used) == VOXGI_ERR_INVALID_ARGUMENT && strstr(voxgi_last_error(ctx), "tree n"),
                         "tree n %d, depth %d: %s", bad[k][0], bad[k][1], voxgi_last_error(ctx));
            }
        }
        TH_CHECK(voxgi_builtin_scene_create(ctx, "furnace", &bs) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        bs.camera.width = bs.camera.height = 4;
        id.camera = bs.camera;
        TH_CHECK(voxgi_render(ctx, &bs.scene, &id, rgb4, sizeof rgb4, NULL) == VOXGI_ERR_UNSUPPORTED, "the furnace's emitters accepted");
        voxgi_builtin_scene_destroy(ctx, &bs);
    }
    td.depth = 7;
    td.n = 10;
    TH_CHECK(voxgi_linespace_create(ctx, &sc, &td, &L) == VOXGI_ERR_INVALID_ARGUMENT && L == NULL, "10^7 leaves a side accepted");
    td.depth = -1;
    td.n = 4;
    TH_CHECK(voxgi_linespace_create(ctx, &sc, &td, &L) == VOXGI_ERR_INVALID_ARGUMENT && L == NULL, "depth -1 accepted");
    { /* depth 0: the scene's, 2 under 256 triangles, else 3 */
        static float tris[9 * 256];
        int t, k;
        for (t = 0; t < 256; t++) /* a row of small triangles */
            for (k = 0; k < 9; k++) tris[9 * t + k] = (k % 3 == 0 ? 0.01f * (float)t : 0) + (k == 3 || k == 7 ? 0.005f : 0);
        for (t = 255; t <= 256; t++) {
            voxgi_linespace_info info;
            scene_of_triangles(&sc, &mesh, tris, 3 * (size_t)t, NULL, 0);
            td.depth = 0;
            L = NULL;
            TH_CHECK(voxgi_linespace_create(ctx, &sc, &td, &L) == VOXGI_OK, "%s", voxgi_last_error(ctx));
            voxgi_linespace_query(L, &info);
            TH_CHECK(info.depth == (t < 256 ? 2 : 3) && info.triangles == (size_t)t, "%d triangles: depth %d (%lu triangles)", t, info.depth,
                     (unsigned long)info.triangles);
            voxgi_linespace_destroy(ctx, L);
        }
    }
    voxgi_destroy(ctx);
}

int main(void)
{
    gl_open();
    TH_RUN(test_plane_fully_lit);
    TH_RUN(test_box_penumbra);
    TH_RUN(test_area_light_weights);
    TH_RUN(test_cornell_direct_light);
    TH_RUN(test_linespace_input);
    gl_close();
    return th_finish();
}
