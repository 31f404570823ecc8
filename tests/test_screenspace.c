/* tests/test_screenspace.c - part 11: the screen-space passes, CPU and GL.

   The screen-space passes against what is known. The sampler: radical inverses by hand, the
   Hammersley set and its rotation. Ambient occlusion (the occluded share of the cosine-weighted
   hemisphere within a radius): on an open plane 0, inside a closed box 1, at a floor beside a
   wall the analytic share (acos c - c sqrt(1 - c^2)) / pi, c = the distance to the wall over the
   radius; for the reference renderer's AO mode (the definition), for the depth buffer's ray
   marching and for the voxels'; the depth buffer's known blind spot (a closed box's walls behind
   the camera) shown; the radius check against a floating occluder; one bounce from a lit wall
   against its analytic irradiance; the edge-aware filter against its definition summed by hand;
   GL equals CPU; bad input refused. */
#include "../voxgi.h"
#include "fixtures.h"

static void test_radical_inverse(void)
{
    static const double base2[8] = {0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875};
    double u[2], rot[2] = {0.75, 0.5};
    int i;
    for (i = 0; i < 8; i++) TH_CHECK(voxgi_radical_inverse(2, (uint64_t)i) == base2[i], "Phi_2(%d) = %g", i, voxgi_radical_inverse(2, (uint64_t)i));
    TH_CHECK(fabs(voxgi_radical_inverse(3, 1) - 1.0 / 3) < 1e-15 && fabs(voxgi_radical_inverse(3, 2) - 2.0 / 3) < 1e-15 &&
                 fabs(voxgi_radical_inverse(3, 3) - 1.0 / 9) < 1e-15 && fabs(voxgi_radical_inverse(3, 5) - 7.0 / 9) < 1e-15,
             "Phi_3");
    TH_CHECK(voxgi_radical_inverse(2, (uint64_t)1 << 40) == ldexp(1, -41), "Phi_2(2^40) = 2^-41");
    voxgi_hammersley(3, 8, NULL, u);
    TH_CHECK(u[0] == 3.0 / 8 && u[1] == 0.75, "point 3 of 8: %g %g", u[0], u[1]);
    voxgi_hammersley(3, 8, rot, u);
    TH_CHECK(u[0] == 0.125 && u[1] == 0.25, "rotated, modulo 1: %g %g", u[0], u[1]);
}

/* A floor [-4, 4]^2 at y = 0 facing up; with `wall`, a wall at x = 1 facing -x, 4 high; with
   `box`, instead the closed box [-1, 1]^3 facing in. */
static void ao_scene(quads *q, voxgi_scene *sc, voxgi_mesh *mesh, int wall, int box)
{
    static const float floor_quad[12] = {-4, 0, -4, -4, 0, 4, 4, 0, 4, 4, 0, -4};
    static const float wall_quad[12] = {1, 0, -4, 1, 4, -4, 1, 4, 4, 1, 0, 4};
    static const float box_quads[6][12] = {{-1, -1, -1, -1, -1, 1, 1, -1, 1, 1, -1, -1}, {-1, 1, -1, 1, 1, -1, 1, 1, 1, -1, 1, 1},
                                           {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1}, {-1, -1, 1, -1, 1, 1, 1, 1, 1, 1, -1, 1},
                                           {-1, -1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1}, {1, -1, -1, 1, -1, 1, 1, 1, 1, 1, 1, -1}};
    int k;
    q->n = 0;
    if (box)
        for (k = 0; k < 6; k++) quad(q, box_quads[k], 0);
    else {
        quad(q, floor_quad, 0);
        if (wall) quad(q, wall_quad, 0);
    }
    scene_of_quads(sc, mesh, q, NULL, 0, NULL, 0);
}

/* The analytic occluded share at a floor point d from an infinite wall, radius R. */
static double corner_share(double d, double R)
{
    double c = d / R;
    return c >= 1 ? 0 : (acos(c) - c * sqrt(1 - c * c)) / PI;
}

/* The reference's AO at the centre pixel of a needle-thin view (0.01 degrees) and the point it sees. */
static double reference_ao(voxgi_context *ctx, const voxgi_scene *sc, const voxgi_camera *view, double R, int samples, float p[3])
{
    voxgi_render_desc d;
    voxgi_camera c = *view;
    float rgb[3], n[3];
    uint32_t tri;
    c.width = c.height = 1;
    c.fovy_degrees = 0.01;
    memset(&d, 0, sizeof d);
    d.method = VOXGI_RENDER_REFERENCE;
    d.camera = c;
    d.samples = samples;
    d.reference.ao_radius = (float)R;
    d.seed = 5;
    TH_CHECK(voxgi_render(ctx, sc, &d, rgb, sizeof rgb, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    TH_CHECK(voxgi_gbuffer_render(ctx, sc, &c, p, n, &tri) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    TH_CHECK(rgb[0] == rgb[1] && rgb[1] == rgb[2], "grey");
    return rgb[0];
}

/* voxgi_ao at every pixel of view's G-buffer (W x W) into ao; the centre pixel's value. */
static double pass_ao(voxgi_context *ctx, const voxgi_scene *sc, const voxgi_camera *view, voxgi_ao_method method, double R, int rays, float *ao, int W)
{
    voxgi_ao_desc d;
    voxgi_camera c = *view;
    voxgi_voxels *vox = NULL;
    float *pos = (float *)malloc((size_t)W * W * 12), *nrm = (float *)malloc((size_t)W * W * 12);
    double centre;
    c.width = c.height = W;
    memset(&d, 0, sizeof d);
    d.camera = c;
    TH_CHECK(pos && nrm && voxgi_gbuffer_render(ctx, sc, &c, pos, nrm, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    d.positions = pos;
    d.normals = nrm;
    d.method = method;
    d.rays = rays;
    d.steps = 32;
    d.radius = (float)R;
    d.traversal = VOXGI_TRAVERSAL_HIERARCHICAL;
    if (method == VOXGI_AO_VOXELS) {
        voxgi_voxelize_desc vd;
        voxgi_fit_desc fit;
        memset(&vd, 0, sizeof vd);
        memset(&fit, 0, sizeof fit);
        fit.res = 128;
        TH_CHECK(voxgi_fit_grid(ctx, sc, &fit, &vd.grid) == VOXGI_OK && voxgi_voxelize(ctx, sc, &vd, &vox) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        d.voxels = vox;
    }
    TH_CHECK(voxgi_ao(ctx, &d, ao, (size_t)W * W * 4) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    centre = ao[(W / 2) * W + W / 2];
    voxgi_voxels_destroy(ctx, vox);
    free(pos);
    free(nrm);
    return centre;
}

static voxgi_camera look(double ex, double ey, double ez, double tx, double ty, double tz)
{
    voxgi_camera c;
    memset(&c, 0, sizeof c);
    c.eye[0] = ex; c.eye[1] = ey; c.eye[2] = ez;
    c.target[0] = tx; c.target[1] = ty; c.target[2] = tz;
    c.fovy_degrees = 40;
    c.width = c.height = 32;
    return c;
}

/* An open plane occludes nothing: 0 for the definition and the depth buffer exactly, for the
   voxels but for rays so flat that they end in the floor's own voxels. */
static void test_ao_open_plane(void)
{
    enum { W = 32 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    quads q;
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_camera view = look(-2, 2, 2.5, 0, 0, 0);
    static float ao[W * W];
    float p[3];
    double ref, worst[2] = {0, 0};
    int m, i;
    ao_scene(&q, &sc, &mesh, 0, 0);
    ref = reference_ao(ctx, &sc, &view, 1, 4096, p);
    TH_CHECK(ref == 0, "the reference on an open plane: %g", ref);
    for (m = 0; m < 2; m++) {
        pass_ao(ctx, &sc, &view, (voxgi_ao_method)m, 1, 64, ao, W);
        for (i = 0; i < W * W; i++) worst[m] = fmax(worst[m], ao[i]);
    }
    printf("    open plane: reference %g, depth buffer at most %g, voxels at most %g\n", ref, worst[0], worst[1]);
    TH_CHECK(worst[0] == 0, "the depth buffer occludes an open plane: %g", worst[0]);
    TH_CHECK(worst[1] <= 0.05, "the voxels occlude an open plane: %g", worst[1]);
    voxgi_destroy(ctx);
}

/* A floor point 0.4 from a wall, radius 1: the analytic share 0.2528 for the definition (4096
   samples: within 0.025), the depth buffer and the voxels (256 rays: within 0.04). */
static void test_ao_corner(void)
{
    enum { W = 64 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    quads q;
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_camera view = look(-2.5, 2, 1.5, 0.6, 0, 0);
    static float ao[W * W];
    float p[3];
    double ref, want, screen, voxels;
    ao_scene(&q, &sc, &mesh, 1, 0);
    ref = reference_ao(ctx, &sc, &view, 1, 4096, p);
    want = corner_share(1 - p[0], 1);
    screen = pass_ao(ctx, &sc, &view, VOXGI_AO_SCREEN, 1, 256, ao, W);
    voxels = pass_ao(ctx, &sc, &view, VOXGI_AO_VOXELS, 1, 256, ao, W);
    printf("    floor point %.3f from the wall: analytic %.4f, reference %.4f, depth buffer %.4f, voxels %.4f\n", 1 - p[0], want, ref, screen, voxels);
    TH_CHECK(fabs(p[1]) < 1e-5 && fabs(1 - p[0] - 0.4) < 0.01, "the centre pixel sees the floor 0.4 from the wall: %g %g %g", p[0], p[1], p[2]);
    TH_CHECK(fabs(ref - want) < 0.025, "the reference");
    TH_CHECK(fabs(screen - want) < 0.04, "the depth buffer");
    TH_CHECK(fabs(voxels - want) < 0.04, "the voxels");
    voxgi_destroy(ctx);
}

/* Inside a closed box with a radius beyond its walls every ray is blocked: 1 for the definition
   and the voxels at every pixel; the depth buffer misses the walls it cannot see (behind the
   camera, off the screen) and measures less. */
static void test_ao_closed_box(void)
{
    enum { W = 32 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    quads q;
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_camera view = look(0.1, 0.2, 0.6, 0.3, -0.2, -1);
    static float ao[W * W];
    float p[3];
    double ref, low[2] = {1, 1}, mean = 0;
    int m, i;
    ao_scene(&q, &sc, &mesh, 0, 1);
    ref = reference_ao(ctx, &sc, &view, 10, 1024, p);
    for (m = 0; m < 2; m++) {
        pass_ao(ctx, &sc, &view, (voxgi_ao_method)m, 10, 32, ao, W);
        for (i = 0; i < W * W; i++) {
            low[m] = fmin(low[m], ao[i]);
            if (m == 0) mean += ao[i] / (W * W);
        }
    }
    printf("    closed box: reference %g, voxels at least %g; depth buffer at least %.3f, mean %.3f\n", ref, low[1], low[0], mean);
    TH_CHECK(ref == 1, "the reference in a closed box: %g", ref);
    TH_CHECK(low[1] == 1, "the voxels in a closed box: %g", low[1]);
    TH_CHECK(mean < 0.95, "the depth buffer sees walls it cannot: mean %g", mean);
    voxgi_destroy(ctx);
}

/* One bounce from the screen: the corner's wall sends radiance 1 (its pixels' radiance), the
   floor none; at a floor point d from the wall with radius 1 the irradiance is the wall's
   cosine-weighted share within reach, acos c - c sqrt(1 - c^2) (c = d), by the depth buffer
   (SSGI: within 0.03) and through the voxels (Hybrid-GI: between that and the share of a wall up
   to 1.5 voxels nearer, where its conservative voxels reach), the camera seeing that part of the
   wall. */
static void test_ssgi_corner(void)
{
    enum { W = 64 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    quads q;
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_camera c = look(-2.5, 2, 1.5, 0.6, 0, 0);
    static float pos[3 * W * W], nrm[3 * W * W], L[3 * W * W], irr[3 * W * W];
    voxgi_voxelize_desc vd;
    voxgi_fit_desc fit;
    voxgi_voxels *vox = NULL;
    double want, d0;
    size_t centre = (size_t)(W / 2) * W + W / 2;
    int m, i;
    ao_scene(&q, &sc, &mesh, 1, 0);
    memset(&vd, 0, sizeof vd);
    memset(&fit, 0, sizeof fit);
    fit.res = 128;
    TH_CHECK(voxgi_fit_grid(ctx, &sc, &fit, &vd.grid) == VOXGI_OK && voxgi_voxelize(ctx, &sc, &vd, &vox) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    c.width = c.height = W;
    TH_CHECK(voxgi_gbuffer_render(ctx, &sc, &c, pos, nrm, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (i = 0; i < W * W; i++) L[3 * i] = L[3 * i + 1] = L[3 * i + 2] = nrm[3 * i] < -0.5f ? 1.0f : 0.0f; /* the wall's pixels */
    d0 = 1 - pos[3 * centre];
    want = acos(d0) - d0 * sqrt(1 - d0 * d0);
    TH_CHECK(fabs(pos[3 * centre + 1]) < 1e-5 && d0 > 0.3 && d0 < 0.5, "the centre pixel sees the floor near the wall");
    for (m = 0; m < 2; m++) {
        voxgi_ssgi_desc d;
        memset(&d, 0, sizeof d);
        d.camera = c;
        d.positions = pos;
        d.normals = nrm;
        d.radiance = L;
        d.method = (voxgi_ao_method)m;
        d.voxels = vox;
        d.traversal = VOXGI_TRAVERSAL_HIERARCHICAL;
        d.rays = 256;
        d.steps = 64;
        d.radius = 1;
        TH_CHECK(voxgi_ssgi(ctx, &d, irr, sizeof irr) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        printf("    floor point %.3f from the wall, %s: irradiance %.4f (analytic %.4f)\n", d0, m ? "voxels" : "depth buffer", irr[3 * centre], want);
        if (m == 0) TH_CHECK(fabs(irr[3 * centre] - want) < 0.03, "the wall's light");
        else { /* the wall's conservative voxels reach up to 1.5 voxels nearer: between the two answers */
            double nearer = d0 - 1.5 * vd.grid.voxel_size, most = acos(nearer) - nearer * sqrt(1 - nearer * nearer);
            TH_CHECK(irr[3 * centre] > want - 0.02 && irr[3 * centre] < most + 0.02, "the wall's light: %g not in [%g, %g]", irr[3 * centre], want, most);
        }
    }
    voxgi_voxels_destroy(ctx, vox);
    voxgi_destroy(ctx);
}

/* The radius check: a small quad floating 1.2 above the floor, far beyond the radius 0.3, hides
   part of the floor from the camera; floor points seen beside it stay open (their rays' steps
   that project onto the quad lie behind it, but the quad is not within reach), as the
   definition says. */
static void test_ssao_radius_check(void)
{
    enum { W = 64 };
    static const float floater[12] = {-0.3f, 1.2f, -0.3f, -0.3f, 1.2f, 0.3f, 0.3f, 1.2f, 0.3f, 0.3f, 1.2f, -0.3f};
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    quads q;
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_camera c = look(-2, 3, 2.5, 0, 0, 0);
    static float pos[3 * W * W], nrm[3 * W * W], ao[W * W];
    voxgi_ao_desc d;
    double worst = 0;
    int i, floor_pixels = 0;
    ao_scene(&q, &sc, &mesh, 0, 0);
    quad(&q, floater, 0);
    scene_of_quads(&sc, &mesh, &q, NULL, 0, NULL, 0);
    c.width = c.height = W;
    TH_CHECK(voxgi_gbuffer_render(ctx, &sc, &c, pos, nrm, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    memset(&d, 0, sizeof d);
    d.camera = c;
    d.positions = pos;
    d.normals = nrm;
    d.rays = 64;
    d.steps = 32;
    d.radius = 0.3f;
    TH_CHECK(voxgi_ao(ctx, &d, ao, sizeof ao) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (i = 0; i < W * W; i++)
        if (nrm[3 * i + 1] > 0.5f && fabs(pos[3 * i + 1]) < 1e-4) {
            floor_pixels++;
            worst = fmax(worst, ao[i]);
        }
    printf("    %d floor pixels around a quad 1.2 above, radius 0.3: occlusion at most %g\n", floor_pixels, worst);
    TH_CHECK(floor_pixels > W * W / 4 && worst == 0, "false occlusion from beyond the radius");
    voxgi_destroy(ctx);
}

/* The screen's rays on GL (in float) against the CPU's (in double), from the same G-buffer and
   random numbers: occlusion, SSGI and Hybrid-GI at every pixel of the corner within 1e-4 (or a
   ray's share, where a step or a voxel crossing parts ways: at most 1% of the pixels). */
static void test_screen_gl_equals_cpu(void)
{
    enum { W = 48 };
    voxgi_context *ctx[2];
    quads q;
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_camera c = look(-2.5, 2, 1.5, 0.6, 0, 0);
    static float pos[3 * W * W], nrm[3 * W * W], L[3 * W * W], out[2][3 * W * W];
    voxgi_voxels *vox[2] = {NULL, NULL};
    int b, m, gather, i;
    if (!have_gl()) return;
    ctx[0] = make_ctx(VOXGI_BACKEND_CPU, 0);
    ctx[1] = make_ctx(VOXGI_BACKEND_GL, 0);
    ao_scene(&q, &sc, &mesh, 1, 0);
    c.width = c.height = W;
    TH_CHECK(voxgi_gbuffer_render(ctx[0], &sc, &c, pos, nrm, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx[0]));
    for (i = 0; i < W * W; i++) L[3 * i] = L[3 * i + 1] = L[3 * i + 2] = nrm[3 * i] < -0.5f ? 1.0f : 0.0f;
    for (b = 0; b < 2; b++) {
        voxgi_voxelize_desc vd;
        voxgi_fit_desc fit;
        memset(&vd, 0, sizeof vd);
        memset(&fit, 0, sizeof fit);
        fit.res = 64;
        TH_CHECK(voxgi_fit_grid(ctx[b], &sc, &fit, &vd.grid) == VOXGI_OK && voxgi_voxelize(ctx[b], &sc, &vd, &vox[b]) == VOXGI_OK, "%s", voxgi_last_error(ctx[b]));
    }
    for (gather = 0; gather < 2; gather++)
        for (m = 0; m < 2; m++) {
            size_t off = 0, n = gather ? 3 * W * W : W * W;
            for (b = 0; b < 2; b++) {
                voxgi_result r;
                if (gather) {
                    voxgi_ssgi_desc d;
                    memset(&d, 0, sizeof d);
                    d.camera = c;
                    d.positions = pos;
                    d.normals = nrm;
                    d.radiance = L;
                    d.method = (voxgi_ao_method)m;
                    d.voxels = vox[b];
                    d.traversal = VOXGI_TRAVERSAL_HIERARCHICAL;
                    d.rays = 32;
                    d.radius = 1;
                    r = voxgi_ssgi(ctx[b], &d, out[b], sizeof out[b]);
                } else {
                    voxgi_ao_desc d;
                    memset(&d, 0, sizeof d);
                    d.camera = c;
                    d.positions = pos;
                    d.normals = nrm;
                    d.method = (voxgi_ao_method)m;
                    d.voxels = vox[b];
                    d.traversal = VOXGI_TRAVERSAL_HIERARCHICAL;
                    d.rays = 32;
                    d.radius = 1;
                    r = voxgi_ao(ctx[b], &d, out[b], sizeof out[b]);
                }
                TH_CHECK(r == VOXGI_OK, "%s", voxgi_last_error(ctx[b]));
            }
            for (i = 0; i < (int)n; i++) off += fabs((double)out[0][i] - out[1][i]) > 1e-4;
            printf("    %s, %s: %lu of %lu values differ by more than 1e-4\n", gather ? "one bounce" : "occlusion", m ? "voxels" : "depth buffer", (unsigned long)off,
                   (unsigned long)n);
            TH_CHECK(off <= n / 100, "GL and CPU part ways");
        }
    { /* point sampling */
        size_t off = 0;
        for (b = 0; b < 2; b++) {
            voxgi_ao_desc d;
            memset(&d, 0, sizeof d);
            d.camera = c;
            d.positions = pos;
            d.normals = nrm;
            d.rays = 32;
            d.radius = 1;
            d.point_sampling = 1;
            TH_CHECK(voxgi_ao(ctx[b], &d, out[b], sizeof out[b]) == VOXGI_OK, "%s", voxgi_last_error(ctx[b]));
        }
        for (i = 0; i < W * W; i++) off += fabs((double)out[0][i] - out[1][i]) > 1e-4;
        printf("    occlusion, points: %lu of %d values differ by more than 1e-4\n", (unsigned long)off, W * W);
        TH_CHECK(off <= W * W / 100, "GL and CPU part ways");
    }
    voxgi_voxels_destroy(ctx[0], vox[0]);
    voxgi_voxels_destroy(ctx[1], vox[1]);
    voxgi_destroy(ctx[0]);
    voxgi_destroy(ctx[1]);
}

/* View-independence: a floor point 0.2 beside a unit cube, radius 0.5, seen by two cameras: one
   sees the cube's face beside the point, the other, from above the cube's far side, sees the
   point but not that face (it turns away). The voxels' occlusion there is the same from both
   (within 0.05: the rays' rotation is drawn per pixel); the depth buffer's drops by more, as the
   face it cannot see occludes nothing. */
static void test_vao_view_independence(void)
{
    enum { W = 64 };
    static const float floor_quad[12] = {-4, 0, -4, -4, 0, 4, 4, 0, 4, 4, 0, -4};
    static const float cube[5][12] = {{-0.5f, 1, -0.5f, -0.5f, 1, 0.5f, 0.5f, 1, 0.5f, 0.5f, 1, -0.5f},
                                      {-0.5f, 0, 0.5f, 0.5f, 0, 0.5f, 0.5f, 1, 0.5f, -0.5f, 1, 0.5f},
                                      {-0.5f, 0, -0.5f, -0.5f, 1, -0.5f, 0.5f, 1, -0.5f, 0.5f, 0, -0.5f},
                                      {0.5f, 0, -0.5f, 0.5f, 1, -0.5f, 0.5f, 1, 0.5f, 0.5f, 0, 0.5f},
                                      {-0.5f, 0, -0.5f, -0.5f, 0, 0.5f, -0.5f, 1, 0.5f, -0.5f, 1, -0.5f}};
    static const double pt[3] = {0.7, 0, 0.1};
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    quads q;
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_camera views[2];
    static float pos[3 * W * W], nrm[3 * W * W], ao[2][W * W];
    double at_point[2][2];
    voxgi_voxels *vox = NULL;
    voxgi_voxelize_desc vd;
    voxgi_fit_desc fit;
    int v, k, m, i;
    views[0] = look(3, 2, 0.5, 0.6, 0.2, 0);
    views[1] = look(0.3, 4, 2, 0.7, 0, 0.1); /* from above the cube's far side: the face beside the point turns away */
    q.n = 0;
    quad(&q, floor_quad, 0);
    for (k = 0; k < 5; k++) quad(&q, cube[k], 0);
    scene_of_quads(&sc, &mesh, &q, NULL, 0, NULL, 0);
    memset(&vd, 0, sizeof vd);
    memset(&fit, 0, sizeof fit);
    fit.res = 256;
    TH_CHECK(voxgi_fit_grid(ctx, &sc, &fit, &vd.grid) == VOXGI_OK && voxgi_voxelize(ctx, &sc, &vd, &vox) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (v = 0; v < 2; v++) {
        voxgi_camera c = views[v];
        double best = 1e30;
        int at = -1;
        c.width = c.height = W;
        TH_CHECK(voxgi_gbuffer_render(ctx, &sc, &c, pos, nrm, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        for (i = 0; i < W * W; i++) { /* the pixel seeing the point */
            double dx = pos[3 * i] - pt[0], dy = pos[3 * i + 1] - pt[1], dz = pos[3 * i + 2] - pt[2], dd = dx * dx + dy * dy + dz * dz;
            if (nrm[3 * i + 1] > 0.5f && dd < best) { best = dd; at = i; }
        }
        TH_CHECK(at >= 0 && best < 0.05 * 0.05, "view %d sees the point (%g away)", v, sqrt(best));
        if (at < 0) continue;
        for (k = 0; k < 3; k++) { /* that pixel's surface exactly at the point, so that both views measure the same point */
            pos[3 * at + k] = (float)pt[k];
            nrm[3 * at + k] = k == 1 ? 1.0f : 0.0f;
        }
        for (m = 0; m < 2; m++) {
            voxgi_ao_desc d;
            memset(&d, 0, sizeof d);
            d.camera = c;
            d.positions = pos;
            d.normals = nrm;
            d.method = (voxgi_ao_method)m;
            d.voxels = vox;
            d.traversal = VOXGI_TRAVERSAL_HIERARCHICAL;
            d.rays = 256;
            d.steps = 32;
            d.radius = 0.5f;
            TH_CHECK(voxgi_ao(ctx, &d, ao[m], sizeof ao[m]) == VOXGI_OK, "%s", voxgi_last_error(ctx));
            at_point[v][m] = ao[m][at];
        }
    }
    printf("    the point's occlusion from two views: depth buffer %.3f and %.3f, voxels %.3f and %.3f\n", at_point[0][0], at_point[1][0], at_point[0][1],
           at_point[1][1]);
    TH_CHECK(fabs(at_point[0][1] - at_point[1][1]) <= 0.05, "the voxels' occlusion depends on the view");
    TH_CHECK(fabs(at_point[0][0] - at_point[1][0]) > fabs(at_point[0][1] - at_point[1][1]) + 0.05, "the depth buffer does not depend on the view here");
    voxgi_voxels_destroy(ctx, vox);
    voxgi_destroy(ctx);
}

/* Point sampling counts a ray blocked at d as (1 - d / radius) (one point at a uniform distance
   along it): at the floor-wall corner (radius 1) the share with that falloff, by quadrature over
   the wall's directions, within 0.03 (256 points); 0 on the open plane. */
static void test_ssao_point_sampling(void)
{
    enum { W = 64 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    quads q;
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_camera c = look(-2.5, 2, 1.5, 0.6, 0, 0);
    static float pos[3 * W * W], nrm[3 * W * W], ao[W * W];
    voxgi_ao_desc d;
    size_t centre = (size_t)(W / 2) * W + W / 2;
    double dist, want = 0;
    int i, j, n = 2000;
    ao_scene(&q, &sc, &mesh, 1, 0);
    c.width = c.height = W;
    TH_CHECK(voxgi_gbuffer_render(ctx, &sc, &c, pos, nrm, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    dist = 1 - pos[3 * centre];
    for (i = 0; i < n; i++) /* the projected disk (cosine weight): x = the direction's component toward the wall */
        for (j = 0; j < n; j++) {
            double x = -1 + 2 * (i + 0.5) / n, y = -1 + 2 * (j + 0.5) / n;
            if (x * x + y * y < 1 && x > dist) want += (1 - dist / x) * (4.0 / ((double)n * n)) / PI;
        }
    memset(&d, 0, sizeof d);
    d.camera = c;
    d.positions = pos;
    d.normals = nrm;
    d.rays = 256;
    d.radius = 1;
    d.point_sampling = 1;
    TH_CHECK(voxgi_ao(ctx, &d, ao, sizeof ao) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    printf("    point sampling at the corner (%.3f from the wall): %.4f, with the falloff's share %.4f\n", dist, ao[centre], want);
    TH_CHECK(fabs(ao[centre] - want) < 0.03, "the points");
    d.method = VOXGI_AO_VOXELS;
    TH_CHECK(voxgi_ao(ctx, &d, ao, sizeof ao) == VOXGI_ERR_INVALID_ARGUMENT, "point sampling through voxels");
    voxgi_destroy(ctx);
}

/* A step down: a top at y = 0.5 for x > 0, a floor at y = 0 for x in [-3, 0], a wall at x = -3,
   seen from above the top, so that the top's edge lies on the floor in the image; its G-buffer
   (W x W) and each pixel's surface (0 floor, 1 top, 2 wall, -1 none), and one pixel (odd across
   and down) turned to face +z, as a thing less than a pixel wide would (3). */
enum { FILTER_W = 48 };
static void step_gbuffer(voxgi_context *ctx, voxgi_camera *c, float *pos, float *nrm, int *surface)
{
    static const float quads_xyz[3][12] = {{-3, 0, -4, -3, 0, 4, 0, 0, 4, 0, 0, -4},
                                           {0, 0.5f, -4, 0, 0.5f, 4, 4, 0.5f, 4, 4, 0.5f, -4},
                                           {-3, 0, -4, -3, 3, -4, -3, 3, 4, -3, 0, 4}};
    quads q;
    voxgi_scene sc;
    voxgi_mesh mesh;
    int k, i;
    q.n = 0;
    for (k = 0; k < 3; k++) quad(&q, quads_xyz[k], 0);
    scene_of_quads(&sc, &mesh, &q, NULL, 0, NULL, 0);
    *c = look(2.5, 2, 0.3, -1, 0.3, 0);
    c->width = c->height = FILTER_W;
    TH_CHECK(voxgi_gbuffer_render(ctx, &sc, c, pos, nrm, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (i = 0; i < FILTER_W * FILTER_W; i++)
        surface[i] = nrm[3 * i] == 0 && nrm[3 * i + 1] == 0 && nrm[3 * i + 2] == 0 ? -1 : nrm[3 * i + 1] < 0.5f ? 2 : pos[3 * i + 1] > 0.25f ? 1 : 0;
    i = (FILTER_W / 2 + 1) * FILTER_W + FILTER_W / 2 + 1;
    TH_CHECK(surface[i] >= 0, "the odd pixel shows a surface");
    nrm[3 * i] = nrm[3 * i + 1] = 0;
    nrm[3 * i + 2] = 1;
    surface[i] = 3;
}

/* The edge-aware filter: values constant on each surface of the step (0, 1, 0.5, 0.25) stay
   exactly so under a wide blur and half-resolution upsampling (nothing leaks across the step in
   depth or the edge), but where a pixel is flagged as having no sample on its surface: at half
   resolution the odd pixel alone; noise on them loses most of its variance and none of its mean. */
static void test_screen_filter(void)
{
    enum { W = FILTER_W, N = FILTER_W * FILTER_W };
    static const float level[4] = {0, 1, 0.5f, 0.25f};
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_screen_filter_desc fd;
    voxgi_camera c;
    static float pos[3 * N], nrm[3 * N], in[N], noisy[N], out[N];
    static int surface[N];
    static unsigned char flag[N];
    int half, i, k, count[4] = {0, 0, 0, 0};
    unsigned rnd = 12345;
    double var[2] = {0, 0}, mean[2][4] = {{0, 0, 0, 0}, {0, 0, 0, 0}};
    step_gbuffer(ctx, &c, pos, nrm, surface);
    for (i = 0; i < N; i++) if (surface[i] >= 0) count[surface[i]]++;
    TH_CHECK(count[0] > N / 10 && count[1] > N / 10 && count[2] > N / 10, "the view shows all three surfaces: %d %d %d", count[0], count[1], count[2]);
    memset(&fd, 0, sizeof fd);
    fd.camera = c;
    fd.positions = pos;
    fd.normals = nrm;
    fd.channels = 1;
    for (half = 0; half < 2; half++) {
        int unsupported = 0, off = 0, iw = (W + 1) / 2;
        for (i = 0; i < N; i++) { /* full resolution, or the pixels (2X, 2Y) */
            int x = i % W, y = i / W;
            if (!half) in[i] = surface[i] >= 0 ? level[surface[i]] : 0;
            else if (x % 2 == 0 && y % 2 == 0) in[(y / 2) * iw + x / 2] = surface[i] >= 0 ? level[surface[i]] : 0;
        }
        fd.half_resolution = half;
        fd.radius = half ? 2 : 6;
        TH_CHECK(voxgi_screen_filter(ctx, &fd, in, out, sizeof out, flag) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        for (i = 0; i < N; i++) {
            if (flag[i]) unsupported++;
            else if (surface[i] >= 0 ? fabs(out[i] - level[surface[i]]) > 1e-5 : out[i] != 0) off++;
            if (flag[i] && (surface[i] < 0 || out[i] != 0)) off++;
        }
        printf("    %s, radius %d: %d pixels off their surface's value, %d without a sample on their surface\n", half ? "half resolution" : "full resolution",
               fd.radius, off, unsupported);
        TH_CHECK(off == 0, "values leak across the step or the edge");
        TH_CHECK(unsupported == half && (!half || flag[(W / 2 + 1) * W + W / 2 + 1]), "the pixels without support are not the odd one alone");
    }
    /* noise +-0.5 on each level: blurred, its variance drops at least eightfold, the means stay */
    for (i = 0; i < N; i++) {
        rnd = rnd * 1664525u + 1013904223u;
        noisy[i] = surface[i] >= 0 ? level[surface[i]] + (float)((rnd >> 8) / 16777216.0 - 0.5) : 0;
    }
    fd.half_resolution = 0;
    fd.radius = 4;
    TH_CHECK(voxgi_screen_filter(ctx, &fd, noisy, out, sizeof out, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (i = 0; i < N; i++)
        if (surface[i] >= 0)
            for (k = 0; k < 2; k++) {
                double v = k ? out[i] : noisy[i];
                var[k] += (v - level[surface[i]]) * (v - level[surface[i]]);
                mean[k][surface[i]] += v / count[surface[i]];
            }
    printf("    noise: variance %.4f -> %.4f; means %.3f %.3f %.3f -> %.3f %.3f %.3f\n", var[0] / N, var[1] / N, mean[0][0], mean[0][1], mean[0][2], mean[1][0],
           mean[1][1], mean[1][2]);
    TH_CHECK(var[1] < var[0] / 8, "the blur keeps the noise");
    for (k = 0; k < 3; k++) TH_CHECK(fabs(mean[1][k] - mean[0][k]) < 0.02, "surface %d's mean moved", k);
    voxgi_destroy(ctx);
}

/* The filter's definition (voxgi_screen_filter's comment) summed in double, on G-buffers made by
   hand whose rows are all alike (a column's pixels share one position and normal), so that the
   column pass averages equal values and the filter is its row pass at every row: pixel x takes
   the mean of the values at the source columns fx within the radius (fx = 2X at half
   resolution), weighted exp(-d^2 / (2 sigma^2)) max(0, n.n_s)^8 exp(-(((p_s - p).n) / t)^2),
   d = fx - x, sigma = max(radius, 1) / 2, t = 2 x 2 tan(fovy / 2) / height x |p - eye| (the eye
   at the origin); a support (the weights' sum) below 1e-3 gives 0 and the flag. */
enum { DEF_W = 21, DEF_H = 15 }; /* odd: the half-resolution image's last column is the full image's last */

static double filter_by_definition(const float *pos, const float *nrm, const double *column_value, int x, int scale, int radius, double pixel_width,
                                   double *support)
{
    const float *p = pos + 3 * x, *n = nrm + 3 * x;
    double sigma = (radius > 1 ? radius : 1) / 2.0, t = 2 * pixel_width * sqrt((double)p[0] * p[0] + (double)p[1] * p[1] + (double)p[2] * p[2]);
    double sum = 0, acc = 0;
    int fx, a;
    *support = 0;
    if (n[0] == 0 && n[1] == 0 && n[2] == 0) return 0;
    for (fx = 0; fx < DEF_W; fx += scale) {
        const float *ps = pos + 3 * fx, *ns = nrm + 3 * fx;
        double dn = 0, dp = 0, wt;
        int d = fx - x;
        if (abs(d) > radius || (ns[0] == 0 && ns[1] == 0 && ns[2] == 0)) continue;
        for (a = 0; a < 3; a++) {
            dn += (double)n[a] * ns[a];
            dp += ((double)ps[a] - p[a]) * n[a];
        }
        if (!(dn > 0)) continue;
        wt = exp(-d * d / (2 * sigma * sigma)) * pow(dn, 8) * exp(-(dp / t) * (dp / t));
        sum += wt;
        acc += wt * column_value[fx / scale];
    }
    *support = sum;
    return sum >= 1e-3 ? acc / sum : 0;
}

/* The filter against its definition summed by hand, at full and half resolution and radii 1, 3
   and 6, with random values per column: every pixel within 1e-5 and the same pixels flagged,
   across a crease (from column 10 the normals 0.9 off the plane's in cosine: 0.9^8 = 0.43 of the
   weight), across a step in depth of 1 t at the step (e^-1) and one of 4 t (e^-16), beside a
   column without a surface and an odd one facing aside (no sample on its surface at half
   resolution: flagged). The far side of the 4 t step, valued 1 against the near side's 0,
   reaches the near side by at most the definition's bound e^2 (2 radius + 1) e^-(step / t)^2
   (t the near side's widest: 1.7e-5 at radius 6; measured 1.1e-7); a constant stays so within
   1e-6. A ramp on one plane, upsampled from half resolution with radius 3 (and at full resolution
   with radius 4), is reproduced within 1e-5 wherever the window lies inside the image: there the
   weights are symmetric. Measured: the definition within 4.9e-8, the ramp within 3.1e-8. */
static void test_screen_filter_definition(void)
{
    enum { N = DEF_W * DEF_H, EDGE = 10, HOLE = 16, ASIDE = 19 }; /* ASIDE: an odd column facing +x, unsupported at half resolution */
    static const int radii[3] = {1, 3, 6};
    static float pos[3 * N], nrm[3 * N], in[N], out[N];
    static unsigned char flag[N];
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_screen_filter_desc fd;
    fx_rng g = fx_rng_seeded(2026);
    double pixel_width = 2 * tan(PI / 6) / DEF_H, worst = 0, worst_constant = 0, worst_ramp = 0, worst_leak = 0, leak_bound = 0, column_value[DEF_W];
    int kind, half, ri, valued, x, y, flags_off = 0, flagged = 0;
    memset(&fd, 0, sizeof fd);
    fd.camera.target[2] = -1; /* the eye at the origin, looking down -z, as the definition's t takes it */
    fd.camera.fovy_degrees = 60;
    fd.camera.width = DEF_W;
    fd.camera.height = DEF_H;
    fd.positions = pos;
    fd.normals = nrm;
    fd.channels = 1;
    for (kind = 0; kind < 3; kind++) { /* 0: the crease; 1, 2: a step in depth of 1 t and 4 t at the step */
        double t_near = 2 * pixel_width * sqrt(0.05 * EDGE * 0.05 * EDGE + 9), step = kind == 0 ? 0 : kind == 1 ? 2 * pixel_width * 3 : 8 * pixel_width * 3;
        for (y = 0; y < DEF_H; y++)
            for (x = 0; x < DEF_W; x++) {
                float *p = pos + 3 * (y * DEF_W + x), *n = nrm + 3 * (y * DEF_W + x);
                p[0] = (float)(0.05 * (x - EDGE));
                p[1] = 0;
                p[2] = (float)(x >= EDGE ? -3 - step : -3);
                n[0] = x == ASIDE;
                n[1] = kind == 0 && x >= EDGE && x != HOLE && x != ASIDE ? (float)sqrt(1 - 0.81) : 0;
                n[2] = x == HOLE || x == ASIDE ? 0 : kind == 0 && x >= EDGE ? 0.9f : 1;
            }
        for (half = 0; half < 2; half++)
            for (ri = 0; ri < 3; ri++)
                for (valued = 0; valued < 3; valued++) { /* random per column, a constant, 0 near the step and 1 beyond */
                    int scale = half ? 2 : 1, iw = (DEF_W + scale - 1) / scale, ih = (DEF_H + scale - 1) / scale, X, Y;
                    for (X = 0; X < iw; X++) column_value[X] = valued == 0 ? fx_rng_unit(&g) : valued == 1 ? 0.37 : X * scale >= EDGE;
                    for (Y = 0; Y < ih; Y++)
                        for (X = 0; X < iw; X++) in[Y * iw + X] = (float)column_value[X];
                    fd.half_resolution = half;
                    fd.radius = radii[ri];
                    TH_CHECK(voxgi_screen_filter(ctx, &fd, in, out, sizeof out, flag) == VOXGI_OK, "%s", voxgi_last_error(ctx));
                    for (y = 0; y < DEF_H; y++)
                        for (x = 0; x < DEF_W; x++) {
                            size_t i = (size_t)(y * DEF_W + x);
                            double support, want = filter_by_definition(pos, nrm, column_value, x, scale, radii[ri], pixel_width, &support);
                            worst = fmax(worst, fabs(out[i] - want));
                            flags_off += flag[i] != (support < 1e-3 && x != HOLE);
                            flagged += flag[i];
                            if (valued == 1 && !flag[i] && x != HOLE) worst_constant = fmax(worst_constant, fabs(out[i] - 0.37));
                            if (valued == 2 && kind == 2 && x < EDGE) {
                                double bound = exp(2.0) * (2 * radii[ri] + 1) * exp(-(step / t_near) * (step / t_near));
                                worst_leak = fmax(worst_leak, out[i]);
                                leak_bound = fmax(leak_bound, bound);
                                TH_CHECK(out[i] <= bound, "the step of 4 t leaks %g (bound %g) at pixel %d, radius %d%s", out[i], bound, x, radii[ri],
                                         half ? ", half resolution" : "");
                            }
                        }
                }
    }
    printf("    crease and steps: the filter within %.1e of its definition, %d flags differ (%d flagged); a constant within %.1e; across the 4 t step "
           "%.1e (bound %.1e)\n", worst, flags_off, flagged, worst_constant, worst_leak, leak_bound);
    TH_CHECK(worst < 1e-5 && flags_off == 0, "the filter leaves its definition");
    TH_CHECK(worst_constant < 1e-6, "a constant does not stay constant");
    for (y = 0; y < DEF_H; y++) /* one plane facing the eye: the ramp */
        for (x = 0; x < DEF_W; x++) {
            float *p = pos + 3 * (y * DEF_W + x), *n = nrm + 3 * (y * DEF_W + x);
            p[0] = (float)(0.05 * (x - EDGE));
            p[1] = (float)(0.05 * (y - DEF_H / 2));
            p[2] = -3;
            n[0] = n[1] = 0;
            n[2] = 1;
        }
    for (half = 0; half < 2; half++) {
        int scale = half ? 2 : 1, iw = (DEF_W + scale - 1) / scale, ih = (DEF_H + scale - 1) / scale, X, Y, inside = 0;
        for (Y = 0; Y < ih; Y++)
            for (X = 0; X < iw; X++) in[Y * iw + X] = (float)(0.1 + 0.01 * (X * scale) + 0.02 * (Y * scale));
        fd.half_resolution = half;
        fd.radius = half ? 3 : 4;
        TH_CHECK(voxgi_screen_filter(ctx, &fd, in, out, sizeof out, flag) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        for (y = fd.radius; y + fd.radius <= (ih - 1) * scale; y++)
            for (x = fd.radius; x + fd.radius <= (iw - 1) * scale; x++, inside++)
                worst_ramp = fmax(worst_ramp, fabs(out[y * DEF_W + x] - (0.1 + 0.01 * x + 0.02 * y)));
        printf("    ramp, %s resolution, radius %d: %d pixels with the window inside, within %.1e\n", half ? "half" : "full", fd.radius, inside, worst_ramp);
        TH_CHECK(inside > 60 && worst_ramp < 1e-5, "the ramp is not reproduced");
    }
    voxgi_destroy(ctx);
}

/* The filter on GL (in float) against the CPU: every value within 1e-5, the same pixels flagged. */
static void test_screen_filter_gl(void)
{
    enum { W = FILTER_W, N = FILTER_W * FILTER_W };
    voxgi_context *ctx[2];
    voxgi_screen_filter_desc fd;
    voxgi_camera c;
    static float pos[3 * N], nrm[3 * N], in[3 * N], out[2][3 * N];
    static int surface[N];
    static unsigned char flag[2][N];
    int b, half, i;
    unsigned rnd = 777;
    if (!have_gl()) return;
    ctx[0] = make_ctx(VOXGI_BACKEND_CPU, 0);
    ctx[1] = make_ctx(VOXGI_BACKEND_GL, 0);
    step_gbuffer(ctx[0], &c, pos, nrm, surface);
    for (i = 0; i < 3 * N; i++) {
        rnd = rnd * 1664525u + 1013904223u;
        in[i] = (float)((rnd >> 8) / 16777216.0);
    }
    memset(&fd, 0, sizeof fd);
    fd.camera = c;
    fd.positions = pos;
    fd.normals = nrm;
    fd.channels = 3;
    for (half = 0; half < 2; half++) {
        size_t off = 0, flags_off = 0;
        fd.half_resolution = half;
        fd.radius = half ? 3 : 5;
        for (b = 0; b < 2; b++)
            TH_CHECK(voxgi_screen_filter(ctx[b], &fd, in, out[b], sizeof out[b], flag[b]) == VOXGI_OK, "%s", voxgi_last_error(ctx[b]));
        for (i = 0; i < 3 * N; i++) off += fabs((double)out[0][i] - out[1][i]) > 1e-5;
        for (i = 0; i < N; i++) flags_off += flag[0][i] != flag[1][i];
        printf("    %s: %lu of %d values differ by more than 1e-5, %lu flags\n", half ? "half resolution" : "full resolution", (unsigned long)off, 3 * N,
               (unsigned long)flags_off);
        TH_CHECK(off == 0 && flags_off == 0, "GL and CPU part ways");
    }
    voxgi_destroy(ctx[0]);
    voxgi_destroy(ctx[1]);
}

/* Half resolution in the images: the rays run at about a quarter of the pixels, and on their own
   at the pixels the filter finds no sample for (a pole about a pixel wide beside the wall): no
   pixel that full resolution finds occluded reads open; refused settings. */
static void test_screen_images_half(void)
{
    enum { W = 32 };
    static const float pole[12] = {0.5f, 0, 0, 0.56f, 0, 0, 0.56f, 1.5f, 0, 0.5f, 1.5f, 0};
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    quads q;
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_render_desc d;
    voxgi_render_info info[2];
    static float rgb[2][3 * W * W];
    int half, i;
    size_t quarter = 0, lost = 0;
    double diff = 0;
    ao_scene(&q, &sc, &mesh, 1, 0);
    quad(&q, pole, 0);
    scene_of_quads(&sc, &mesh, &q, NULL, 0, NULL, 0);
    memset(&d, 0, sizeof d);
    d.method = VOXGI_RENDER_SSAO;
    d.camera = look(-2.5, 2, 1.5, 0.6, 0, 0);
    d.screen.radius = 1;
    d.screen.rays = 64;
    d.screen.blur = -1; /* the old blur 0: none */
    for (half = 0; half < 2; half++) {
        d.screen.half_resolution = half ? VOXGI_TOGGLE_ON : VOXGI_TOGGLE_OFF;
        TH_CHECK(voxgi_render(ctx, &sc, &d, rgb[half], sizeof rgb[half], &info[half]) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    }
    for (i = 0; i < W * W; i++) {
        quarter += i % W % 2 == 0 && i / W % 2 == 0;
        diff += fabs((double)rgb[0][3 * i] - rgb[1][3 * i]) / (W * W);
        lost += rgb[0][3 * i] > 0.1f && rgb[1][3 * i] == 0;
    }
    printf("    rays at %lu pixels, at half resolution %lu (%lu on their own); %lu occluded pixels read open; mean difference %.4f\n",
           (unsigned long)info[0].gathered, (unsigned long)info[1].gathered, (unsigned long)(info[1].gathered - quarter), (unsigned long)lost, diff);
    TH_CHECK(info[0].gathered == W * W && info[1].gathered > quarter && info[1].gathered < quarter + W, "rays at %lu and %lu pixels",
             (unsigned long)info[0].gathered, (unsigned long)info[1].gathered);
    TH_CHECK(lost == 0, "pixels without a sample on their surface left open");
    TH_CHECK(diff < 0.05, "half resolution is another image");
    d.screen.blur = 65;
    TH_CHECK(voxgi_render(ctx, &sc, &d, rgb[0], sizeof rgb[0], NULL) == VOXGI_ERR_INVALID_ARGUMENT, "blur 65");
    d.screen.blur = -2;
    TH_CHECK(voxgi_render(ctx, &sc, &d, rgb[0], sizeof rgb[0], NULL) == VOXGI_ERR_INVALID_ARGUMENT, "blur -2");
    d.screen.blur = -1;
    d.screen.half_resolution = (voxgi_toggle)(VOXGI_TOGGLE_OFF + 1); /* past the toggle's values (the old half_resolution 2) */
    TH_CHECK(voxgi_render(ctx, &sc, &d, rgb[0], sizeof rgb[0], NULL) == VOXGI_ERR_INVALID_ARGUMENT, "half_resolution %d", (int)d.screen.half_resolution);
    voxgi_destroy(ctx);
}

/* A floor [-1, 1]^2 and a wall at x = 1, 2 high, white (albedo 0.8), under a sun that lights
   both (irradiance 3 across its beam). */
static void sun_corner(quads *q, voxgi_scene *sc, voxgi_mesh *mesh, voxgi_light *sun, voxgi_material *white)
{
    static const float floor_quad[12] = {-1, 0, -1, -1, 0, 1, 1, 0, 1, 1, 0, -1};
    static const float wall_quad[12] = {1, 0, -1, 1, 2, -1, 1, 2, 1, 1, 0, 1};
    memset(sun, 0, sizeof *sun);
    sun->type = VOXGI_LIGHT_DIRECTIONAL;
    sun->direction[0] = 1;
    sun->direction[1] = -1;
    sun->direction[2] = 0.2f;
    sun->intensity[0] = sun->intensity[1] = sun->intensity[2] = 3;
    memset(white, 0, sizeof *white);
    white->albedo[0] = white->albedo[1] = white->albedo[2] = 0.8f;
    q->n = 0;
    quad(q, floor_quad, 0);
    quad(q, wall_quad, 0);
    scene_of_quads(sc, mesh, q, white, 1, sun, 1);
}

/* The reference's screen_light_only (the most one bounce from the screen can find): a floor and a
   wall meeting at a corner, under the sun. Seen whole, every bounce's surface is on the screen:
   the image is the full one bounce's, bit for bit (the same paths). Seen from above the floor
   alone, the wall out of the image, the bounce (from the wall: the floor cannot see itself) is
   gone: the image is the direct light's, bit for bit, and the full bounce's is brighter. */
static void test_reference_screen_light_only(void)
{
    enum { W = 16 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_light sun;
    voxgi_material white;
    voxgi_render_desc d;
    quads q;
    voxgi_scene sc;
    voxgi_mesh mesh;
    static float img[3][3 * W * W];
    int view, k, i;
    sun_corner(&q, &sc, &mesh, &sun, &white);
    for (view = 0; view < 2; view++) {
        double sum[3] = {0, 0, 0};
        size_t same01 = 0, same02 = 0;
        memset(&d, 0, sizeof d);
        d.method = VOXGI_RENDER_REFERENCE;
        d.camera = view ? look(-0.5, 1.5, 0, -0.5, 0, 0.001) : look(-4, 3, 0, 0, 0.7, 0);
        d.camera.width = d.camera.height = W;
        d.samples = 16;
        d.seed = 3;
        for (k = 0; k < 3; k++) { /* full one bounce, screen light only, direct light */
            d.bounces = 1;
            d.direct_only = k == 2; /* the old bounces 0 */
            d.reference.screen_light_only = k == 1;
            TH_CHECK(voxgi_render(ctx, &sc, &d, img[k], sizeof img[k], NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        }
        for (i = 0; i < 3 * W * W; i++) {
            for (k = 0; k < 3; k++) sum[k] += img[k][i];
            same01 += img[0][i] == img[1][i];
            same02 += img[1][i] == img[2][i];
        }
        printf("    %s: light full bounce %.2f, screen light only %.2f, direct %.2f; as the full bounce %lu, as the direct light %lu of %d values\n",
               view ? "the floor alone" : "all in view", sum[0], sum[1], sum[2], (unsigned long)same01, (unsigned long)same02, 3 * W * W);
        if (!view) TH_CHECK(same01 == 3 * W * W && sum[0] > sum[2] * 1.05, "everything is on the screen: the full bounce");
        else TH_CHECK(same02 == 3 * W * W && sum[0] > sum[1] * 1.05, "the wall is off the screen: no bounce");
    }
    d.bounces = 2;
    d.direct_only = 0;
    d.reference.screen_light_only = 1;
    TH_CHECK(voxgi_render(ctx, &sc, &d, img[0], sizeof img[0], NULL) == VOXGI_ERR_INVALID_ARGUMENT, "screen light only with bounces 2");
    d.bounces = 1;
    d.direct_only = 1;
    TH_CHECK(voxgi_render(ctx, &sc, &d, img[0], sizeof img[0], NULL) == VOXGI_ERR_INVALID_ARGUMENT, "screen light only with direct light only");
    voxgi_destroy(ctx);
}

/* Hybrid-GI's hidden light (the extension), on the floor and wall under the sun. Seen from above
   the floor alone, the wall off the screen: without hidden light there is no bounce; with it, the
   wall's voxels send their injected light, and the bounce comes within 15% of the reference's
   (mean over the image; the voxels' light taken at their centres). Seen whole, the screen has
   the wall's light and the hidden light adds little (within 10%: hits the plane test calls
   hidden). Hidden light needs the voxels' grid and VOXELS. */
static void test_hybrid_hidden_light(void)
{
    enum { W = 24 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_light sun;
    voxgi_material white;
    voxgi_render_desc rd, gd;
    quads q;
    voxgi_scene sc;
    voxgi_mesh mesh;
    static float img[4][3 * W * W];
    int view, k, i;
    sun_corner(&q, &sc, &mesh, &sun, &white);
    for (view = 0; view < 2; view++) {
        double sum[4] = {0, 0, 0, 0}, bounce_ref, bounce_hidden, bounce_screen;
        memset(&rd, 0, sizeof rd);
        rd.method = VOXGI_RENDER_REFERENCE;
        rd.camera = view ? look(-4, 3, 0, 0, 0.7, 0) : look(-0.5, 1.5, 0, -0.5, 0, 0.001);
        rd.camera.width = rd.camera.height = W;
        rd.samples = 256;
        rd.seed = 3;
        for (k = 0; k < 2; k++) { /* the reference's one bounce, its direct light */
            rd.bounces = 1;
            rd.direct_only = k; /* the old bounces 0 */
            TH_CHECK(voxgi_render(ctx, &sc, &rd, img[k], sizeof img[k], NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        }
        memset(&gd, 0, sizeof gd);
        gd.method = VOXGI_RENDER_HYBRID;
        gd.camera = rd.camera;
        gd.resolution = 64;
        gd.screen.rays = 64;
        gd.screen.radius = 3;
        gd.seed = 3;
        gd.screen.half_resolution = VOXGI_TOGGLE_OFF; /* the old zeros: every pixel, no blur */
        gd.screen.blur = -1;
        for (k = 2; k < 4; k++) { /* Hybrid-GI with hidden light, without */
            gd.screen.hidden_light = k == 2 ? VOXGI_TOGGLE_ON : VOXGI_TOGGLE_OFF;
            TH_CHECK(voxgi_render(ctx, &sc, &gd, img[k], sizeof img[k], NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        }
        for (k = 0; k < 4; k++)
            for (i = 0; i < 3 * W * W; i++) sum[k] += img[k][i] / (3 * W * W);
        bounce_ref = sum[0] - sum[1];
        if (!view) { /* nothing on the screen sends light: without hidden light the image is the direct light */
            bounce_hidden = sum[2] - sum[3];
            printf("    the floor alone: mean bounce: reference %.4f, Hybrid-GI with hidden light %.4f\n", bounce_ref, bounce_hidden);
            TH_CHECK(bounce_ref > 0.05 * sum[1], "the wall sends a bounce worth measuring");
            TH_CHECK(fabs(bounce_hidden - bounce_ref) < 0.15 * bounce_ref, "the hidden light is not the wall's");
        } else {
            bounce_hidden = sum[2] - sum[1];
            bounce_screen = sum[3] - sum[1];
            printf("    all in view: mean bounce: reference %.4f, Hybrid-GI %.4f, with hidden light %.4f\n", bounce_ref, bounce_screen, bounce_hidden);
            TH_CHECK(fabs(bounce_hidden - bounce_screen) < 0.1 * bounce_screen, "hidden light where the screen has it");
        }
    }
    { /* the API's checks */
        voxgi_voxelize_desc vd;
        voxgi_fit_desc fit;
        voxgi_inject_desc id;
        voxgi_ssgi_desc d;
        voxgi_voxels *vox[2] = {NULL, NULL};
        voxgi_volume *vol = NULL;
        static float pos[3 * W * W], nrm[3 * W * W], out[3 * W * W];
        memset(&vd, 0, sizeof vd);
        memset(&fit, 0, sizeof fit);
        memset(&id, 0, sizeof id);
        vd.attributes = VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_NORMAL;
        for (k = 0; k < 2; k++) {
            fit.res = 8 << k;
            TH_CHECK(voxgi_fit_grid(ctx, &sc, &fit, &vd.grid) == VOXGI_OK && voxgi_voxelize(ctx, &sc, &vd, &vox[k]) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        }
        TH_CHECK(voxgi_inject_light(ctx, &sc, vox[1], &id, &vol) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        TH_CHECK(voxgi_gbuffer_render(ctx, &sc, &rd.camera, pos, nrm, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        memset(&d, 0, sizeof d);
        d.camera = rd.camera;
        d.positions = pos;
        d.normals = nrm;
        d.radiance = pos;
        d.method = VOXGI_AO_VOXELS;
        d.voxels = vox[1];
        d.radius = 1;
        d.hidden_radiance = vol;
        TH_CHECK(voxgi_ssgi(ctx, &d, out, sizeof out) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        d.voxels = vox[0];
        TH_CHECK(voxgi_ssgi(ctx, &d, out, sizeof out) == VOXGI_ERR_INVALID_ARGUMENT, "hidden light on another grid");
        d.method = VOXGI_AO_SCREEN;
        TH_CHECK(voxgi_ssgi(ctx, &d, out, sizeof out) == VOXGI_ERR_INVALID_ARGUMENT, "hidden light through the depth buffer");
        voxgi_volume_destroy(ctx, vol);
        voxgi_voxels_destroy(ctx, vox[0]);
        voxgi_voxels_destroy(ctx, vox[1]);
    }
    voxgi_destroy(ctx);
}

/* The images' memory (info.bytes): nothing for the depth buffer's passes; for the voxels' AO and
   Hybrid-GI the voxels' bits and their OR mipmaps, every level (halving to one cell a side);
   Hybrid-GI's hidden light adds its volume. */
static void test_image_memory(void)
{
    enum { W = 16 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_light sun;
    voxgi_material white;
    quads q;
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_render_desc ad, gd;
    voxgi_render_info ai[2], gi[3];
    voxgi_voxelize_desc vd;
    voxgi_fit_desc fit;
    voxgi_voxels *vox = NULL;
    voxgi_voxels_info vi;
    static float img[3 * W * W];
    size_t expect = 0;
    int r[3], a, k;
    sun_corner(&q, &sc, &mesh, &sun, &white);
    memset(&vd, 0, sizeof vd);
    memset(&fit, 0, sizeof fit);
    fit.res = 20;
    TH_CHECK(voxgi_fit_grid(ctx, &sc, &fit, &vd.grid) == VOXGI_OK && voxgi_voxelize(ctx, &sc, &vd, &vox) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    voxgi_voxels_query(vox, &vi);
    voxgi_voxels_destroy(ctx, vox);
    expect = 2 * vi.bytes; /* the voxels, and their copy as the occupancy's first level */
    for (a = 0; a < 3; a++) r[a] = vd.grid.res[a];
    while (r[0] > 1 || r[1] > 1 || r[2] > 1) {
        for (a = 0; a < 3; a++) r[a] = (r[a] + 1) / 2;
        expect += ((size_t)r[0] * (size_t)r[1] * (size_t)r[2] + 31) / 32 * 4;
    }
    memset(&ad, 0, sizeof ad);
    ad.camera = look(-4, 3, 0, 0, 0.7, 0);
    ad.camera.width = ad.camera.height = W;
    ad.screen.rays = 4;
    ad.resolution = 20;
    ad.screen.half_resolution = VOXGI_TOGGLE_OFF; /* the old zeros: every pixel, no blur */
    ad.screen.blur = -1;
    memset(&gd, 0, sizeof gd);
    gd.camera = ad.camera;
    gd.screen.rays = 4;
    gd.samples = 1;
    gd.resolution = 20;
    gd.screen.half_resolution = VOXGI_TOGGLE_OFF;
    gd.screen.blur = -1;
    for (k = 0; k < 3; k++) {
        ad.method = k ? VOXGI_RENDER_VAO : VOXGI_RENDER_SSAO;
        gd.method = k ? VOXGI_RENDER_HYBRID : VOXGI_RENDER_SSGI;
        gd.screen.hidden_light = k == 2 ? VOXGI_TOGGLE_ON : VOXGI_TOGGLE_OFF;
        TH_CHECK((k == 2 || voxgi_render(ctx, &sc, &ad, img, sizeof img, &ai[k]) == VOXGI_OK) &&
                     voxgi_render(ctx, &sc, &gd, img, sizeof img, &gi[k]) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    }
    printf("    %d x %d x %d voxels: AO %lu bytes, Hybrid-GI %lu, with the hidden light %lu; expected %lu\n", vd.grid.res[0], vd.grid.res[1], vd.grid.res[2],
           (unsigned long)ai[1].bytes, (unsigned long)gi[1].bytes, (unsigned long)gi[2].bytes, (unsigned long)expect);
    TH_CHECK(ai[0].bytes == 0 && gi[0].bytes == 0, "the depth buffer's passes built %lu and %lu bytes", (unsigned long)ai[0].bytes, (unsigned long)gi[0].bytes);
    TH_CHECK(ai[1].bytes == expect && gi[1].bytes == expect, "the voxels' passes: %lu and %lu bytes", (unsigned long)ai[1].bytes, (unsigned long)gi[1].bytes);
    TH_CHECK(gi[2].bytes > expect, "the hidden light's volume left out");
    voxgi_destroy(ctx);
}

/* Hidden light on GL against the CPU: the same voxels' light on both (injected with the CPU's
   shadow rays), the floor's bounce from the wall off the screen at every pixel within 1e-4. */
static void test_hidden_light_gl(void)
{
    enum { W = 24 };
    voxgi_context *ctx[2];
    voxgi_light sun;
    voxgi_material white;
    quads q;
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_camera c = look(-0.5, 1.5, 0, -0.5, 0, 0.001);
    static float pos[3 * W * W], nrm[3 * W * W], L[3 * W * W], out[2][3 * W * W];
    voxgi_voxels *vox[2] = {NULL, NULL};
    voxgi_volume *vol[2] = {NULL, NULL};
    size_t off = 0;
    double sum = 0;
    int b, i;
    if (!have_gl()) return;
    ctx[0] = make_ctx(VOXGI_BACKEND_CPU, 0);
    ctx[1] = make_ctx(VOXGI_BACKEND_GL, 0);
    sun_corner(&q, &sc, &mesh, &sun, &white);
    c.width = c.height = W;
    TH_CHECK(voxgi_gbuffer_render(ctx[0], &sc, &c, pos, nrm, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx[0]));
    for (b = 0; b < 2; b++) {
        voxgi_voxelize_desc vd;
        voxgi_fit_desc fit;
        voxgi_inject_desc id;
        voxgi_ssgi_desc d;
        memset(&vd, 0, sizeof vd);
        memset(&fit, 0, sizeof fit);
        memset(&id, 0, sizeof id);
        fit.res = 32;
        vd.attributes = VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_NORMAL;
        id.volume.levels = 1;
        id.samples = 4;
        id.shadow_rays = 1;
        TH_CHECK(voxgi_fit_grid(ctx[b], &sc, &fit, &vd.grid) == VOXGI_OK && voxgi_voxelize(ctx[b], &sc, &vd, &vox[b]) == VOXGI_OK &&
                     voxgi_inject_light(ctx[b], &sc, vox[b], &id, &vol[b]) == VOXGI_OK,
                 "%s", voxgi_last_error(ctx[b]));
        memset(&d, 0, sizeof d);
        d.camera = c;
        d.positions = pos;
        d.normals = nrm;
        d.radiance = L; /* nothing on the screen sends light: the bounce is the hidden light alone */
        d.method = VOXGI_AO_VOXELS;
        d.voxels = vox[b];
        d.traversal = VOXGI_TRAVERSAL_HIERARCHICAL;
        d.rays = 32;
        d.radius = 3;
        d.hidden_radiance = vol[b];
        TH_CHECK(voxgi_ssgi(ctx[b], &d, out[b], sizeof out[b]) == VOXGI_OK, "%s", voxgi_last_error(ctx[b]));
    }
    for (i = 0; i < 3 * W * W; i++) {
        off += fabs((double)out[0][i] - out[1][i]) > 1e-4;
        sum += out[0][i] / (3 * W * W);
    }
    printf("    the hidden light's bounce (mean irradiance %.4f): %lu of %d values differ by more than 1e-4\n", sum, (unsigned long)off, 3 * W * W);
    TH_CHECK(sum > 0.05 && off == 0, "GL and CPU part ways");
    for (b = 0; b < 2; b++) {
        voxgi_volume_destroy(ctx[b], vol[b]);
        voxgi_voxels_destroy(ctx[b], vox[b]);
        voxgi_destroy(ctx[b]);
    }
}

static void test_ao_input(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_ao_desc d;
    float pos[3] = {0, 0, 0}, nrm[3] = {0, 1, 0}, ao[1], bad[3] = {0, NAN, 0};
    voxgi_render_desc rd;
    quads q;
    voxgi_scene sc;
    voxgi_mesh mesh;
    float rgb[3];
    memset(&d, 0, sizeof d);
    d.camera = look(0, 1, 1, 0, 0, 0);
    d.camera.width = d.camera.height = 1;
    d.positions = pos;
    d.normals = nrm;
    TH_CHECK(voxgi_ao(ctx, &d, ao, sizeof ao) == VOXGI_ERR_INVALID_ARGUMENT, "radius 0");
    d.radius = 1;
    TH_CHECK(voxgi_ao(ctx, &d, ao, 0) == VOXGI_ERR_BUFFER_TOO_SMALL, "no room");
    d.method = VOXGI_AO_VOXELS;
    TH_CHECK(voxgi_ao(ctx, &d, ao, sizeof ao) == VOXGI_ERR_INVALID_ARGUMENT, "VOXELS without voxels");
    d.method = VOXGI_AO_SCREEN;
    d.rays = -1;
    TH_CHECK(voxgi_ao(ctx, &d, ao, sizeof ao) == VOXGI_ERR_INVALID_ARGUMENT, "rays -1");
    d.rays = 0;
    d.normals = bad;
    TH_CHECK(voxgi_ao(ctx, &d, ao, sizeof ao) == VOXGI_ERR_INVALID_ARGUMENT, "a NaN normal");
    d.normals = nrm;
    TH_CHECK(voxgi_ao(ctx, &d, ao, sizeof ao) == VOXGI_OK && ao[0] == 0, "one pixel alone: %s", voxgi_last_error(ctx));
    ao_scene(&q, &sc, &mesh, 0, 0);
    memset(&rd, 0, sizeof rd);
    rd.method = VOXGI_RENDER_REFERENCE;
    rd.camera = d.camera;
    rd.samples = 16; /* the old samples 0 */
    rd.reference.ao_radius = -1;
    TH_CHECK(voxgi_render(ctx, &sc, &rd, rgb, sizeof rgb, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "ao_radius -1");
    { /* the filter */
        voxgi_screen_filter_desc fd;
        float v[4] = {0.5f, 0.5f, 0.5f, 0.5f}, o[4];
        memset(&fd, 0, sizeof fd);
        fd.camera = d.camera;
        fd.positions = pos;
        fd.normals = nrm;
        fd.channels = 1;
        TH_CHECK(voxgi_screen_filter(ctx, &fd, v, o, sizeof o, NULL) == VOXGI_OK && o[0] == 0.5f, "one pixel: %s", voxgi_last_error(ctx));
        fd.channels = 5;
        TH_CHECK(voxgi_screen_filter(ctx, &fd, v, o, sizeof o, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "5 channels");
        fd.channels = 1;
        fd.radius = 65;
        TH_CHECK(voxgi_screen_filter(ctx, &fd, v, o, sizeof o, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "radius 65");
        fd.radius = 0;
        TH_CHECK(voxgi_screen_filter(ctx, &fd, v, o, 0, NULL) == VOXGI_ERR_BUFFER_TOO_SMALL, "no room");
        fd.normals = bad;
        TH_CHECK(voxgi_screen_filter(ctx, &fd, v, o, sizeof o, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "a NaN normal");
        TH_CHECK(voxgi_screen_filter(ctx, NULL, v, o, sizeof o, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "no desc");
    }
    voxgi_destroy(ctx);
}

int main(void)
{
    gl_open();
    TH_RUN(test_radical_inverse);
    TH_RUN(test_ao_open_plane);
    TH_RUN(test_ao_corner);
    TH_RUN(test_ao_closed_box);
    TH_RUN(test_ssao_radius_check);
    TH_RUN(test_ssao_point_sampling);
    TH_RUN(test_vao_view_independence);
    TH_RUN(test_ssgi_corner);
    TH_RUN(test_reference_screen_light_only);
    TH_RUN(test_hybrid_hidden_light);
    TH_RUN(test_hidden_light_gl);
    TH_RUN(test_image_memory);
    TH_RUN(test_screen_gl_equals_cpu);
    TH_RUN(test_screen_filter);
    TH_RUN(test_screen_filter_definition);
    TH_RUN(test_screen_filter_gl);
    TH_RUN(test_screen_images_half);
    TH_RUN(test_ao_input);
    gl_close();
    return th_finish();
}
