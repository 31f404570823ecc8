/* The reference renderer against what is known exactly: a furnace (a closed sphere of albedo rho
   and emission E has radiance E / (1 - rho) everywhere; E (1 + rho + ... + rho^(B+1)) with B
   bounces), planes lit by directional, point, spot and rectangular lights against the analytic
   radiance, no ray slipping through a closed mesh, error falling as 1/sqrt(samples), the same
   image for any thread count, and clean refusals. */
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

static void camera(voxgi_reference_desc *d, double ex, double ey, double ez, double tx, double ty, double tz, double fovy, int w, int h)
{
    memset(d, 0, sizeof *d);
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

static void test_furnace(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    vxt_shape m;
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi_reference_desc d;
    voxgi_material mat = {{0.5f, 0.5f, 0.5f}, {1.0f, 2.0f, 0.5f}, 0};
    float *rgb = (float *)malloc(16 * 16 * 12);
    double rhos[2] = {0.5, 0.9};
    int bounces, ri, ch;
    inward_sphere(&m, 24, 12);
    scene_of(&sc, &mesh, &m, &mat, NULL, 0);
    camera(&d, 0.1, -0.2, 0.05, 0.3, 0.1, 1.0, 90, 16, 16);
    d.seed = 7;
    for (ri = 0; ri < 2; ri++) {
        for (ch = 0; ch < 3; ch++) mat.albedo[ch] = (float)rhos[ri];
        for (bounces = -1; bounces <= 2; bounces++) {
            voxgi_reference_info info;
            double rho = mat.albedo[0], want_factor = 0, worst = 0;
            int k;
            if (ri == 1 && bounces >= 0) continue;
            d.bounces = bounces;
            d.samples = bounces < 0 ? (ri ? 256 : 64) : 16;
            if (bounces < 0) want_factor = 1 / (1 - rho);
            else for (k = 0; k <= bounces + 1; k++) want_factor += pow(rho, k);
            TH_CHECK(voxgi_reference_render(ctx, &sc, &d, rgb, 16 * 16 * 12, &info) == VOXGI_OK, "render: %s", voxgi_last_error(ctx));
            for (ch = 0; ch < 3; ch++) {
                double want = mat.emission[ch] * want_factor, got = mean_channel(rgb, 256, ch);
                worst = fmax(worst, fabs(got - want) / want);
            }
            printf("    furnace rho %.1f, bounces %2d, %3d spp: mean within %.2f%% of E x %.4f (%llu rays, BVH %lu nodes)\n", rho, bounces,
                   d.samples, 100 * worst, want_factor, (unsigned long long)info.rays, (unsigned long)info.bvh_nodes);
            TH_CHECK(worst < (ri ? 0.03 : 0.015), "furnace rho %g bounces %d: %.2f%% off", rho, bounces, 100 * worst);
        }
    }
    {   /* watertight: albedo 0, so a pixel is E exactly unless its ray escaped through a crack */
        float *big = (float *)malloc(64 * 64 * 12);
        size_t i, off = 0;
        for (ch = 0; ch < 3; ch++) mat.albedo[ch] = 0;
        camera(&d, 0.013, 0.021, -0.017, 0.2, 0.7, 0.3, 120, 64, 64);
        d.bounces = 0;
        d.samples = 16;
        TH_CHECK(voxgi_reference_render(ctx, &sc, &d, big, 64 * 64 * 12, NULL) == VOXGI_OK, "render: %s", voxgi_last_error(ctx));
        for (i = 0; i < 64 * 64; i++) off += fabsf(big[3 * i] - 1.0f) > 1e-6f || fabsf(big[3 * i + 1] - 2.0f) > 1e-6f;
        TH_CHECK(off == 0, "%lu of 4096 pixels saw through the closed sphere", (unsigned long)off);
        free(big);
    }
    free(rgb);
    vxt_shape_free(&m);
    voxgi_destroy(ctx);
}

/* A 20 x 20 floor at y = 0 facing up, seen from above: each pixel's mean radiance against the
   analytic radiance averaged over the same pixel square (the camera rebuilt here). */
static double floor_pixel_oracle(const voxgi_reference_desc *d, int px, int py, double (*radiance)(const double p[3], const void *), const void *u)
{
    const voxgi_camera *c = &d->camera;
    double f[3], r[3], up[3], len, th = tan(c->fovy_degrees * PI / 360), sum = 0;
    int a, i, j, n = 8;
    for (a = 0; a < 3; a++) f[a] = c->target[a] - c->eye[a];
    len = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (a = 0; a < 3; a++) f[a] /= len;
    r[0] = -f[2]; r[1] = 0; r[2] = f[0];
    len = sqrt(r[0] * r[0] + r[2] * r[2]);
    r[0] /= len; r[2] /= len;
    up[0] = r[1] * f[2] - r[2] * f[1]; up[1] = r[2] * f[0] - r[0] * f[2]; up[2] = r[0] * f[1] - r[1] * f[0];
    for (j = 0; j < n; j++)
        for (i = 0; i < n; i++) {
            double sx = (2 * (px + (i + 0.5) / n) / c->width - 1) * th * c->width / c->height, sy = (1 - 2 * (py + (j + 0.5) / n) / c->height) * th;
            double dir[3], t, p[3];
            for (a = 0; a < 3; a++) dir[a] = f[a] + sx * r[a] + sy * up[a];
            t = -c->eye[1] / dir[1];
            for (a = 0; a < 3; a++) p[a] = c->eye[a] + t * dir[a];
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
    voxgi_reference_desc d;
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
        TH_CHECK(voxgi_reference_render(ctx, &sc, &d, rgb, sizeof rgb, NULL) == VOXGI_OK, "render: %s", voxgi_last_error(ctx));
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
        TH_CHECK(voxgi_reference_render(ctx, &sc, &d, rgb, sizeof rgb, NULL) == VOXGI_OK, "render: %s", voxgi_last_error(ctx));
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
        TH_CHECK(voxgi_reference_render(one, &sc, &d, rgb2, sizeof rgb2, NULL) == VOXGI_OK && memcmp(rgb, rgb2, sizeof rgb) == 0,
                 "1 and 2 threads differ");
        d.seed = 99;
        TH_CHECK(voxgi_reference_render(one, &sc, &d, rgb2, sizeof rgb2, NULL) == VOXGI_OK && memcmp(rgb, rgb2, sizeof rgb) != 0,
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
    voxgi_reference_desc d;
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
        voxgi_reference_render(ctx, &sc, &d, rgb, 24 * 24 * 12, NULL);
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
    voxgi_reference_desc d;
    voxgi_material mat = {{0.5f, 0.5f, 0.5f}, {1, 1, 1}, 0};
    voxgi_light bad;
    m.pos = pos; m.idx = NULL; m.vertex_count = 3; m.triangle_count = 1;
    scene_of(&sc, &mesh, &m, &mat, NULL, 0);
    mesh.indices = NULL; mesh.index_count = 0;
    camera(&d, 0, 5, 0, 0, 0, 0, 60, 4, 4); /* straight down: no up vector */
    TH_CHECK(voxgi_reference_render(ctx, &sc, &d, rgb, sizeof rgb, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "looking along -Y accepted");
    camera(&d, 0, 5, -1, 0, 0, 0, 180, 4, 4);
    TH_CHECK(voxgi_reference_render(ctx, &sc, &d, rgb, sizeof rgb, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "fovy 180 accepted");
    camera(&d, 0, 5, -1, 0, 0, 0, 60, 4, 4);
    TH_CHECK(voxgi_reference_render(ctx, &sc, &d, rgb, sizeof rgb - 1, NULL) == VOXGI_ERR_BUFFER_TOO_SMALL, "short buffer accepted");
    memset(&bad, 0, sizeof bad);
    bad.type = VOXGI_LIGHT_RECT; /* no edges */
    sc.lights = &bad; sc.light_count = 1;
    TH_CHECK(voxgi_reference_render(ctx, &sc, &d, rgb, sizeof rgb, NULL) == VOXGI_ERR_INVALID_SCENE, "degenerate rect light accepted");
    bad.type = VOXGI_LIGHT_POINT;
    bad.intensity[1] = -1;
    TH_CHECK(voxgi_reference_render(ctx, &sc, &d, rgb, sizeof rgb, NULL) == VOXGI_ERR_INVALID_SCENE, "negative intensity accepted");
    sc.lights = NULL; sc.light_count = 0;
    voxgi_destroy(ctx);
    ctx_desc(&dd, VOXGI_BACKEND_CPU);
    dd.progress.func = cancel_reference;
    voxgi_create(&dd, &ctx);
    d.samples = 64;
    TH_CHECK(voxgi_reference_render(ctx, &sc, &d, rgb, sizeof rgb, NULL) == VOXGI_ERR_CANCELLED, "cancel ignored: %s", voxgi_last_error(ctx));
    voxgi_destroy(ctx);
}

/* The built-in scenes: valid; the furnace at radiance 2; the leak box black inside exactly; the
   Cornell box's light seen at its radiance, the room lit. */
static void test_builtin_scenes(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    const char *names = voxgi_builtin_scene_names();
    voxgi_builtin_scene bs;
    voxgi_reference_desc d;
    float *rgb = (float *)malloc(48 * 48 * 12);
    char name[32];
    const char *at = names;
    int n = 0;
    while (sscanf(at, "%31s", name) == 1) {
        size_t i, lit = 0, light_pixels = 0;
        double mean;
        TH_CHECK(voxgi_builtin_scene_create(ctx, name, &bs) == VOXGI_OK && voxgi_validate_scene(ctx, &bs.scene) == VOXGI_OK, "%s: %s", name,
                 voxgi_last_error(ctx));
        memset(&d, 0, sizeof d);
        d.camera = bs.camera;
        d.camera.width = d.camera.height = 48;
        d.samples = 8;
        d.bounces = strcmp(name, "cornell-box") == 0 ? 0 : -1;
        TH_CHECK(voxgi_reference_render(ctx, &bs.scene, &d, rgb, 48 * 48 * 12, NULL) == VOXGI_OK, "%s: %s", name, voxgi_last_error(ctx));
        mean = mean_channel(rgb, 48 * 48, 0);
        for (i = 0; i < 48 * 48; i++) {
            lit += rgb[3 * i] > 0;
            light_pixels += rgb[3 * i] == 17.0f && rgb[3 * i + 1] == 12.0f && rgb[3 * i + 2] == 4.0f;
        }
        printf("    %-12s %lu triangles, mean red radiance %.4f, %lu of 2304 pixels lit\n", name, (unsigned long)(bs.scene.meshes[0].index_count / 3), mean,
               (unsigned long)lit);
        if (strcmp(name, "furnace") == 0) TH_CHECK(fabs(mean - 2) < 0.02, "furnace mean %g", mean);
        else if (strcmp(name, "leak-box") == 0) TH_CHECK(lit == 0, "%lu pixels lit inside the closed box", (unsigned long)lit);
        else if (strcmp(name, "cornell-box") == 0) TH_CHECK(light_pixels >= 4 && lit > 1200, "Cornell box: %lu light pixels, %lu lit", (unsigned long)light_pixels, (unsigned long)lit);
        else TH_CHECK(lit > 1800, "%s: %lu lit", name, (unsigned long)lit);
        voxgi_builtin_scene_destroy(ctx, &bs);
        at = strstr(at, name) + strlen(name);
        n++;
    }
    TH_CHECK(n == 4, "%d built-in scenes", n);
    TH_CHECK(voxgi_builtin_scene_create(ctx, "no-such", &bs) == VOXGI_ERR_INVALID_ARGUMENT, "an unknown name accepted");
    free(rgb);
    voxgi_destroy(ctx);
}

int main(void)
{
    TH_RUN(test_builtin_scenes);
    TH_RUN(test_furnace);
    TH_RUN(test_lit_floor);
    TH_RUN(test_convergence);
    TH_RUN(test_refusals_and_cancel);
    return th_finish();
}
