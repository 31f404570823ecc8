/* tests/test_reference.c - part 13: the reference renderer (built-in scenes: tests/test_files.c).

   The reference renderer against what is known exactly: a furnace (a closed sphere of albedo rho
   and emission E has radiance E / (1 - rho) everywhere; E (1 + rho + ... + rho^(B+1)) with B
   bounces), an integrating sphere (a glowing cap lights every point of a sphere alike; its
   bounces depend on how the path tracer draws their directions), planes lit by directional,
   point, spot and rectangular lights against the analytic radiance, no ray slipping through a
   closed mesh, error falling as 1/sqrt(samples), the same image for any thread count, and clean
   refusals. */
#include "../voxgi.h"
#include "fixtures.h"

/* A closed UV sphere of radius 1 around the origin facing inwards (front faces inside). */
static void inward_sphere(vxt_shape *m, int slices, int stacks)
{
    size_t t;
    vxt_shape_sphere(m, slices, stacks, 1.0, 0, 0, 0);
    for (t = 0; t < m->triangle_count; t++) {
        uint32_t k = m->idx[3 * t + 1];
        m->idx[3 * t + 1] = m->idx[3 * t + 2];
        m->idx[3 * t + 2] = k;
    }
}

/* The shape as one mesh of one material, lit by the lights. */
static void scene_of(voxgi_scene *sc, voxgi_mesh *mesh, const vxt_shape *m, const voxgi_material *mat, const voxgi_light *lights, size_t nl)
{
    scene_of_shape(sc, mesh, m);
    scene_lighting(sc, mat, 1, lights, nl);
}

static void camera(voxgi_render_desc *d, double ex, double ey, double ez, double tx, double ty, double tz, double fovy, int w, int h)
{
    memset(d, 0, sizeof *d);
    d->method = VOXGI_RENDER_REFERENCE;
    d->camera.eye[0] = ex; d->camera.eye[1] = ey; d->camera.eye[2] = ez;
    d->camera.target[0] = tx; d->camera.target[1] = ty; d->camera.target[2] = tz;
    d->camera.fovy_degrees = fovy;
    d->camera.width = w; d->camera.height = h;
}

static double mean_channel(const float *rgb, size_t pixels, int ch)
{
    double s = 0;
    size_t i;
    for (i = 0; i < pixels; i++) s += rgb[3 * i + (size_t)ch];
    return s / (double)pixels;
}

/* The furnace: inside any closed surface of albedo rho and emission E (the tessellated sphere
   too, so there is no geometric error) the radiance is E (1 + rho + ... + rho^(B+1)) with B
   bounces, E / (1 - rho) unlimited. No case is free of noise (the point on the emitters and the
   bounce's emitter carry power-heuristic weights that vary from sample to sample, and Russian
   roulette ends paths at random), so each channel's image mean must lie within 5 standard errors
   of it: the pixels are independent, their spread over sqrt(pixels) is the standard error, and
   1e-6 of the value covers the float pixels. */
static void test_furnace(void)
{
    enum { W = 32 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    vxt_shape m;
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi_render_desc d;
    voxgi_material mat = {{0.5f, 0.5f, 0.5f}, {1.0f, 2.0f, 0.5f}, 0};
    float *rgb = (float *)malloc(W * W * 12);
    double rhos[2] = {0.5, 0.9};
    int bounces, ri, ch;
    inward_sphere(&m, 24, 12);
    scene_of(&sc, &mesh, &m, &mat, NULL, 0);
    camera(&d, 0.1, -0.2, 0.05, 0.3, 0.1, 1.0, 90, W, W);
    d.seed = 7;
    for (ri = 0; ri < 2; ri++) {
        for (ch = 0; ch < 3; ch++) mat.albedo[ch] = (float)rhos[ri];
        for (bounces = -1; bounces <= 2; bounces++) {
            voxgi_render_info info;
            double rho = mat.albedo[0], want_factor = 0, worst = 0, worst_se = 0;
            int k;
            if (ri == 1 && bounces >= 0) continue;
            d.bounces = bounces;
            d.direct_only = bounces == 0; /* bounces 0 was the direct light alone */
            d.samples = bounces < 0 ? (ri ? 64 : 16) : 16;
            if (bounces < 0) want_factor = 1 / (1 - rho);
            else for (k = 0; k <= bounces + 1; k++) want_factor += pow(rho, k);
            TH_CHECK(voxgi_render(ctx, &sc, &d, rgb, W * W * 12, &info) == VOXGI_OK, "render: %s", voxgi_last_error(ctx));
            for (ch = 0; ch < 3; ch++) {
                double want = mat.emission[ch] * want_factor, got = mean_channel(rgb, W * W, ch), var = 0, se;
                size_t i;
                for (i = 0; i < W * W; i++) var += (rgb[3 * i + (size_t)ch] - got) * (rgb[3 * i + (size_t)ch] - got) / (W * W - 1);
                se = sqrt(var / (W * W));
                worst = fmax(worst, fabs(got - want) / want);
                worst_se = fmax(worst_se, se / want);
                TH_CHECK(fabs(got - want) <= 5 * se + 1e-6 * want, "furnace rho %g bounces %d channel %d: mean %.7g, want %.7g (standard error %.3g)", rho,
                         bounces, ch, got, want, se);
            }
            printf("    furnace rho %.1f, bounces %2d, %2d spp: mean within %.4f%% of E x %.4f, standard error %.4f%% (%llu rays, BVH %lu nodes)\n", rho,
                   bounces, d.samples, 100 * worst, want_factor, 100 * worst_se, (unsigned long long)info.rays, (unsigned long)info.bvh_nodes);
        }
    }
    {   /* watertight: albedo 0, so a pixel is E exactly unless its ray escaped through a crack */
        float *big = (float *)malloc(64 * 64 * 12);
        size_t i, off = 0;
        for (ch = 0; ch < 3; ch++) mat.albedo[ch] = 0;
        camera(&d, 0.013, 0.021, -0.017, 0.2, 0.7, 0.3, 120, 64, 64);
        d.direct_only = 1; /* the direct light alone (the old bounces 0) */
        d.samples = 16;
        TH_CHECK(voxgi_render(ctx, &sc, &d, big, 64 * 64 * 12, NULL) == VOXGI_OK, "render: %s", voxgi_last_error(ctx));
        for (i = 0; i < 64 * 64; i++) off += fabsf(big[3 * i] - 1.0f) > 1e-6f || fabsf(big[3 * i + 1] - 2.0f) > 1e-6f;
        TH_CHECK(off == 0, "%lu of 4096 pixels saw through the closed sphere", (unsigned long)off);
        free(big);
    }
    free(rgb);
    vxt_shape_free(&m);
    voxgi_destroy(ctx);
}

/* Lambert's formula, written out here: the form factor from a point p (unit normal n) to the
   surface bounded by the closed polygon q[0..nq-1] when all of that surface lies in front of p
   (n.(x - p) >= 0) and faces it: |sum over the edges of the angle each subtends at p times n .
   the unit normal of the plane through p and the edge| / (2 pi). Radiance Le over that surface
   gives p the irradiance pi Le times it. The surface need not be flat: the terms of an edge two
   flat pieces share cancel, so a union of faces is its boundary's polygon. */
static double form_factor(const double (*q)[3], int nq, const double p[3], const double n[3])
{
    double sum = 0;
    int k, a;
    for (k = 0; k < nq; k++) {
        const double *q0 = q[k], *q1 = q[(k + 1) % nq];
        double u[3], v[3], c[3], lu = 0, lv = 0, s;
        for (a = 0; a < 3; a++) { u[a] = q0[a] - p[a]; v[a] = q1[a] - p[a]; lu += u[a] * u[a]; lv += v[a] * v[a]; }
        lu = sqrt(lu); lv = sqrt(lv);
        for (a = 0; a < 3; a++) { u[a] /= lu; v[a] /= lv; }
        c[0] = u[1] * v[2] - u[2] * v[1]; c[1] = u[2] * v[0] - u[0] * v[2]; c[2] = u[0] * v[1] - u[1] * v[0];
        s = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        if (s > 0) sum += atan2(s, u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) * (n[0] * c[0] + n[1] * c[1] + n[2] * c[2]) / s;
    }
    return fabs(sum) / (2 * PI);
}

/* The integrating sphere. Inside a closed sphere of radius R, a point P sees any element dA at Q
   with both cosines |PQ| / 2R, so the form factor cos cos dA / (pi |PQ|^2) is dA / (4 pi R^2) from
   everywhere: a black cap of area A = 4 pi R^2 f glowing with radiance Le gives every point the
   irradiance pi Le f, the walls (albedo rho) the radiance rho Le f after one bounce, and each
   further bounce multiplies that by rho (1 - f) (the walls' share of any point's view). With B
   bounces a wall's radiance is rho Le f (1 + q + ... + q^B), q = rho (1 - f).
   Unlike the furnace, the light reaching a point differs with direction (the cap fills less of
   the view from far away), so the answer depends on how the path tracer draws its bounces: drawn
   uniformly over the hemisphere but weighted as if cosine-distributed, the image is 7% brighter.
   The sphere here is a UV sphere, a convex polyhedron, on which the cap's form factor a(P) varies
   (to first order in the faces' angular size: a face's normal is tilted against the sphere's
   across it). The test evaluates a exactly (form_factor over the cap's boundary) at points all
   over the walls, a in [a_lo, a_hi], and over the part the camera can see, [s_lo, s_hi]; every
   point sees the walls with the form factor 1 - a(P), so the first bounce's wall radiance lies in
   rho Le [a_lo, a_hi], the (k+1)-th in rho [1 - a_hi, 1 - a_lo] times the k-th's range, and a seen
   point's likewise with [s_lo, s_hi] for its own a. The image mean must lie in the sum of those
   ranges widened by 5 standard errors of the mean (the pixels are independent: the spread of
   their values over sqrt(pixels)). */
static void test_integrating_sphere(void)
{
    enum { S = 128, T = 72, JC = 24, W = 32, B = 2 }; /* slices, stacks, the cap's stacks (60 degrees), image side, bounces */
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    vxt_shape m;
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi_render_desc d;
    voxgi_material mats[2] = {{{0.8f, 0.8f, 0.8f}, {0, 0, 0}, 0}, {{0, 0, 0}, {1, 1, 1}, 0}}; /* the walls; the cap */
    uint32_t *ids;
    float *rgb = (float *)malloc(W * W * 12);
    double ring[S][3], r_in = 1, rho = 0.8, Le = 1, f = (1 - cos(PI * JC / T)) / 2, eye = 0.5, tan_half = tan(20 * PI / 180);
    double a_lo = 1, a_hi = 0, s_lo = 1, s_hi = 0, wall_lo, wall_hi, lo, hi, want = 0, mean, var = 0, se, dir[3], ed, t_in, theta_in;
    size_t i, t;
    int k, a, seen;
    inward_sphere(&m, S, T);
    for (i = 0; i < m.vertex_count; i++) { /* the pole to +z (a rotation, exact in float): a camera cannot look along y */
        float y = m.pos[3 * i + 1];
        m.pos[3 * i + 1] = -m.pos[3 * i + 2];
        m.pos[3 * i + 2] = y;
    }
    ids = (uint32_t *)malloc(m.triangle_count * 4);
    for (t = 0; t < m.triangle_count; t++) ids[t] = t / (2 * S) < JC; /* the first JC stacks from the pole glow */
    for (k = 0; k < S; k++)
        for (a = 0; a < 3; a++) ring[k][a] = m.pos[3 * (JC * (S + 1) + k) + a];
    for (t = 0; t < m.triangle_count; t++) { /* the largest ball inside: the nearest face plane */
        const float *v0 = m.pos + 3 * m.idx[3 * t], *v1 = m.pos + 3 * m.idx[3 * t + 1], *v2 = m.pos + 3 * m.idx[3 * t + 2];
        double e1[3], e2[3], n[3], len;
        for (a = 0; a < 3; a++) { e1[a] = (double)v1[a] - v0[a]; e2[a] = (double)v2[a] - v0[a]; }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1]; n[1] = e1[2] * e2[0] - e1[0] * e2[2]; n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (len > 0) r_in = fmin(r_in, fabs(n[0] * v0[0] + n[1] * v0[1] + n[2] * v0[2]) / len);
    }
    /* The camera on the axis looks down it at the pole opposite the cap; its corner rays leave the
       ball of radius r_in (inside the polyhedron) at the least polar angle any ray does, and a ray
       meets the polyhedron beyond that, at a polar angle no less: it sees stacks from `seen` on
       (two stacks' margin for the faces' chords). */
    dir[0] = dir[1] = tan_half;
    dir[2] = -1;
    ed = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + 1);
    for (a = 0; a < 3; a++) dir[a] /= ed;
    ed = eye * dir[2];
    t_in = -ed + sqrt(ed * ed - (eye * eye - r_in * r_in));
    theta_in = acos((eye + t_in * dir[2]) / r_in);
    seen = (int)(theta_in * T / PI) - 2;
    /* a(P) near each wall triangle's corners, edge midpoints and centre, on the triangles of four
       columns of slices: the UV sphere turns each column into any other, and the cap's ring with
       it; its float vertices break that symmetry by < 1e-6 (the four columns' extremes agree to
       4e-7), which the margin of 1e-5 covers */
    for (t = 0; t < m.triangle_count; t++) {
        const float *v[3];
        double e1[3], e2[3], n[3], len, side = 0;
        int s, col = (int)(t % (2 * S)) / 2, stack = (int)(t / (2 * S));
        if (ids[t] || (col != 0 && col != S / 4 + 1 && col != S / 2 + 2 && col != 3 * S / 4 + 3)) continue;
        for (k = 0; k < 3; k++) v[k] = m.pos + 3 * m.idx[3 * t + k];
        for (a = 0; a < 3; a++) { e1[a] = (double)v[1][a] - v[0][a]; e2[a] = (double)v[2][a] - v[0][a]; }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1]; n[1] = e1[2] * e2[0] - e1[0] * e2[2]; n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(len > 0)) continue; /* the poles' degenerate triangles */
        for (a = 0; a < 3; a++) side += n[a] * v[0][a];
        for (a = 0; a < 3; a++) n[a] /= side > 0 ? -len : len; /* towards the centre */
        for (s = 0; s < 7; s++) {
            double b[3], p[3], ff, e = 1e-4;
            for (k = 0; k < 3; k++) b[k] = s == 6 ? 1.0 / 3 : s < 3 ? (k == s ? 1 - 2 * e : e) : (k == s - 3 ? 2 * e : 0.5 - e);
            for (a = 0; a < 3; a++) p[a] = b[0] * v[0][a] + b[1] * v[1][a] + b[2] * v[2][a];
            ff = form_factor((const double(*)[3])ring, S, p, n);
            a_lo = fmin(a_lo, ff);
            a_hi = fmax(a_hi, ff);
            if (stack >= seen) { s_lo = fmin(s_lo, ff); s_hi = fmax(s_hi, ff); }
        }
    }
    a_lo -= 1e-5; s_lo -= 1e-5;
    a_hi += 1e-5; s_hi += 1e-5;
    wall_lo = rho * Le * a_lo; /* the first bounce's radiance on the walls, then each next one's */
    wall_hi = rho * Le * a_hi;
    lo = rho * Le * s_lo;      /* on the walls seen */
    hi = rho * Le * s_hi;
    for (k = 0; k <= B; k++) want += rho * Le * f * pow(rho * (1 - f), k);
    for (k = 1; k <= B; k++) {
        lo += rho * wall_lo * (1 - s_hi);
        hi += rho * wall_hi * (1 - s_lo);
        wall_lo *= rho * (1 - a_hi);
        wall_hi *= rho * (1 - a_lo);
    }
    scene_of_shape(&sc, &mesh, &m);
    mesh.material_ids = ids;
    scene_lighting(&sc, mats, 2, NULL, 0);
    camera(&d, 0, 0, eye, 0, 0, -1, 40, W, W);
    d.samples = 16;
    d.bounces = B;
    d.seed = 5;
    d.hide_emitters = 1;
    TH_CHECK(voxgi_render(ctx, &sc, &d, rgb, W * W * 12, NULL) == VOXGI_OK, "render: %s", voxgi_last_error(ctx));
    mean = mean_channel(rgb, W * W, 0);
    for (i = 0; i < W * W; i++) var += (rgb[3 * i] - mean) * (rgb[3 * i] - mean) / (W * W - 1);
    se = sqrt(var / (W * W));
    printf("    integrating sphere, %d bounces: image mean %.5f (standard error %.5f); sphere %.5f, this polyhedron in [%.5f, %.5f] "
           "(the cap's form factor %.5f..%.5f seen, %.5f..%.5f on all walls, %.5f on a sphere)\n",
           B, mean, se, want, lo, hi, s_lo, s_hi, a_lo, a_hi, f);
    TH_CHECK(mean > lo - 5 * se && mean < hi + 5 * se, "mean %.5f outside [%.5f, %.5f] +- 5 x %.5f", mean, lo, hi, se);
    free(rgb);
    free(ids);
    vxt_shape_free(&m);
    voxgi_destroy(ctx);
}

/* A 20 x 20 floor at y = 0 facing up, seen from above: each pixel's mean radiance against the
   analytic radiance averaged over the same pixel square (the camera rebuilt by fx_floor_point). */
static double floor_pixel_oracle(const voxgi_render_desc *d, int px, int py, double (*radiance)(const double p[3], const void *), const void *u)
{
    double sum = 0;
    int i, j, n = 8;
    for (j = 0; j < n; j++)
        for (i = 0; i < n; i++) {
            double p[3];
            fx_floor_point(&d->camera, px + (i + 0.5) / n, py + (j + 0.5) / n, p);
            sum += radiance(p, u);
        }
    return sum / (n * n);
}

typedef struct lit { const voxgi_light *light; double albedo; int lambertian; } lit; /* lambertian: a small area light's cos at the light */

static double point_radiance(const double p[3], const void *u)
{
    const lit *l = (const lit *)u;
    double d[3], d2, c;
    int a;
    for (a = 0; a < 3; a++) d[a] = l->light->position[a] - p[a];
    d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    c = d[1] / sqrt(d2);
    return l->albedo / PI * l->light->intensity[0] * c * (l->lambertian ? c : 1) / d2;
}

static void test_lit_floor(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    float pos[12] = {-10, 0, -10, 10, 0, -10, 10, 0, 10, -10, 0, 10};
    uint32_t idx[6] = {0, 2, 1, 0, 3, 2}; /* counter-clockwise seen from above */
    vxt_shape m;
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi_render_desc d;
    voxgi_material mat = {{0.6f, 0.6f, 0.6f}, {0, 0, 0}, 0};
    voxgi_light L;
    float rgb[24 * 16 * 3], rgb2[24 * 16 * 3];
    lit l;
    int x, y, kind;
    m.pos = pos; m.idx = idx; m.vertex_count = 4; m.triangle_count = 2;
    camera(&d, 0.5, 4, -3, 0, 0, 0.5, 50, 24, 16);
    d.samples = 64;
    d.bounces = 2; /* nothing to bounce off: the same as direct light */
    memset(&L, 0, sizeof L);
    {   /* directional: the same radiance everywhere, no noise at all */
        double dir[3] = {0.3, -1, 0.2}, len = sqrt(0.09 + 1 + 0.04), want, worst = 0;
        int i;
        L.type = VOXGI_LIGHT_DIRECTIONAL;
        for (i = 0; i < 3; i++) { L.direction[i] = (float)dir[i]; L.intensity[i] = 2.0f; }
        scene_of(&sc, &mesh, &m, &mat, &L, 1);
        TH_CHECK(voxgi_render(ctx, &sc, &d, rgb, sizeof rgb, NULL) == VOXGI_OK, "render: %s", voxgi_last_error(ctx));
        want = 0.6 / PI * 2.0 * (1 / len);
        for (i = 0; i < 24 * 16 * 3; i++) worst = fmax(worst, fabs(rgb[i] - want) / want);
        TH_CHECK(worst < 1e-6, "directional light: %.3g relative off the analytic radiance", worst);
    }
    for (kind = 0; kind < 3; kind++) { /* point; spot with the floor inside its inner cone; a tiny rect light ~ point */
        double sum_got = 0, sum_want = 0, sq = 0;
        memset(&L, 0, sizeof L);
        L.position[0] = 1; L.position[1] = 2.5f; L.position[2] = 0.5f;
        L.intensity[0] = L.intensity[1] = L.intensity[2] = 5;
        if (kind == 0) L.type = VOXGI_LIGHT_POINT;
        else if (kind == 1) {
            L.type = VOXGI_LIGHT_SPOT;
            L.direction[1] = -1;
            L.spot_inner = 1.5f;
            L.spot_outer = 1.55f;
        } else { /* 1e-3 wide, facing down, radiance x area = the point's intensity */
            L.type = VOXGI_LIGHT_RECT;
            L.position[0] -= 0.0005f; L.position[2] -= 0.0005f;
            L.edge_u[0] = 0.001f; L.edge_v[2] = 0.001f; /* u x v = -y */
            L.intensity[0] = L.intensity[1] = L.intensity[2] = 5e6f;
        }
        scene_of(&sc, &mesh, &m, &mat, &L, 1);
        TH_CHECK(voxgi_render(ctx, &sc, &d, rgb, sizeof rgb, NULL) == VOXGI_OK, "render: %s", voxgi_last_error(ctx));
        {   /* the pixels' only noise is where in the pixel a sample lands: the image mean is tight, each pixel within its noise */
            voxgi_light point = L;
            point.type = VOXGI_LIGHT_POINT;
            point.position[0] = 1; point.position[2] = 0.5f;
            point.intensity[0] = 5;
            l.light = &point;
            l.albedo = 0.6;
            l.lambertian = kind == 2;
            for (y = 0; y < 16; y++)
                for (x = 0; x < 24; x++) {
                    double want = floor_pixel_oracle(&d, x, y, point_radiance, &l), got = rgb[3 * (y * 24 + x)];
                    sum_got += got;
                    sum_want += want;
                    sq += (got / want - 1) * (got / want - 1);
                }
        }
        printf("    %s light on a floor: image mean within %.3f%% of the analytic one, pixels %.2f%% RMS\n",
               kind == 0 ? "point" : (kind == 1 ? "spot" : "rect"), 100 * fabs(sum_got / sum_want - 1), 100 * sqrt(sq / 384));
        TH_CHECK(fabs(sum_got / sum_want - 1) < 0.005 && sqrt(sq / 384) < 0.02, "light kind %d off the analytic radiance", kind);
    }
    {   /* the same image for 1 and 2 threads; another seed gives another */
        voxgi_context *one = make_ctx(VOXGI_BACKEND_CPU, 1);
        TH_CHECK(voxgi_render(one, &sc, &d, rgb2, sizeof rgb2, NULL) == VOXGI_OK && memcmp(rgb, rgb2, sizeof rgb) == 0,
                 "1 and 2 threads differ");
        d.seed = 99;
        TH_CHECK(voxgi_render(one, &sc, &d, rgb2, sizeof rgb2, NULL) == VOXGI_OK && memcmp(rgb, rgb2, sizeof rgb) != 0,
                 "another seed gives the same image");
        voxgi_destroy(one);
    }
    voxgi_destroy(ctx);
}

/* RMS error of the furnace image (one bounce: E (1 + rho + rho^2)) as samples grow 4x: it halves. */
static void test_convergence(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    vxt_shape m;
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi_render_desc d;
    voxgi_material mat = {{0.5f, 0.5f, 0.5f}, {1, 1, 1}, 0};
    float *rgb = (float *)malloc(24 * 24 * 12);
    double err[3];
    int k;
    inward_sphere(&m, 16, 8);
    scene_of(&sc, &mesh, &m, &mat, NULL, 0);
    camera(&d, 0, 0, 0, 0.2, 0.3, 1, 90, 24, 24);
    d.bounces = 1;
    for (k = 0; k < 3; k++) {
        double s = 0;
        size_t i;
        d.samples = 4 << (2 * k);
        voxgi_render(ctx, &sc, &d, rgb, 24 * 24 * 12, NULL);
        for (i = 0; i < 24 * 24; i++) s += (rgb[3 * i] - 1.75) * (rgb[3 * i] - 1.75);
        err[k] = sqrt(s / (24 * 24));
    }
    printf("    RMS error at 4 / 16 / 64 spp: %.4f %.4f %.4f (ratios %.2f %.2f; 1/sqrt(spp) gives 2)\n", err[0], err[1], err[2], err[0] / err[1],
           err[1] / err[2]);
    TH_CHECK(err[0] / err[1] > 1.6 && err[0] / err[1] < 2.5 && err[1] / err[2] > 1.6 && err[1] / err[2] < 2.5, "error does not fall as 1/sqrt(spp)");
    free(rgb);
    vxt_shape_free(&m);
    voxgi_destroy(ctx);
}

static int cancel_reference(double fraction, const char *stage, void *user)
{
    (void)user;
    return fraction > 0.2 && strcmp(stage, "reference render") == 0;
}

static void test_refusals_and_cancel(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 1);
    voxgi_desc dd;
    float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, rgb[4 * 4 * 3];
    vxt_shape m;
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi_render_desc d;
    voxgi_material mat = {{0.5f, 0.5f, 0.5f}, {1, 1, 1}, 0};
    voxgi_light bad;
    m.pos = pos; m.idx = NULL; m.vertex_count = 3; m.triangle_count = 1;
    scene_of(&sc, &mesh, &m, &mat, NULL, 0);
    mesh.indices = NULL; mesh.index_count = 0;
    camera(&d, 0, 5, 0, 0, 0, 0, 60, 4, 4); /* straight down: no up vector */
    d.samples = 16;
    TH_CHECK(voxgi_render(ctx, &sc, &d, rgb, sizeof rgb, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "looking along -Y accepted");
    camera(&d, 0, 5, -1, 0, 0, 0, 180, 4, 4);
    d.samples = 16;
    TH_CHECK(voxgi_render(ctx, &sc, &d, rgb, sizeof rgb, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "fovy 180 accepted");
    camera(&d, 0, 5, -1, 0, 0, 0, 60, 4, 4);
    d.samples = 16; /* the old default */
    TH_CHECK(voxgi_render(ctx, &sc, &d, rgb, sizeof rgb - 1, NULL) == VOXGI_ERR_BUFFER_TOO_SMALL, "short buffer accepted");
    memset(&bad, 0, sizeof bad);
    bad.type = VOXGI_LIGHT_RECT; /* no edges */
    sc.lights = &bad; sc.light_count = 1;
    TH_CHECK(voxgi_render(ctx, &sc, &d, rgb, sizeof rgb, NULL) == VOXGI_ERR_INVALID_SCENE, "degenerate rect light accepted");
    bad.type = VOXGI_LIGHT_POINT;
    bad.intensity[1] = -1;
    TH_CHECK(voxgi_render(ctx, &sc, &d, rgb, sizeof rgb, NULL) == VOXGI_ERR_INVALID_SCENE, "negative intensity accepted");
    sc.lights = NULL; sc.light_count = 0;
    voxgi_destroy(ctx);
    ctx_desc(&dd, VOXGI_BACKEND_CPU);
    dd.progress.func = cancel_reference;
    voxgi_create(&dd, &ctx);
    d.samples = 64;
    TH_CHECK(voxgi_render(ctx, &sc, &d, rgb, sizeof rgb, NULL) == VOXGI_ERR_CANCELLED, "cancel ignored: %s", voxgi_last_error(ctx));
    voxgi_destroy(ctx);
}

int main(void)
{
    TH_RUN(test_furnace);
    TH_RUN(test_integrating_sphere);
    TH_RUN(test_lit_floor);
    TH_RUN(test_convergence);
    TH_RUN(test_refusals_and_cancel);
    return th_finish();
}
