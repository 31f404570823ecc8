/* tests/test_lightspace.c - part 10: the light-space passes, CPU and GL.

   The light-space passes against their definitions. Transmittance shadow maps: a stack of
   horizontal translucent quads over an opaque ground under a sun or a spot light straight above,
   where every answer is known: no translucent layer lets all light through (sigma 0), sigma = 1
   casts a binary shadow, k layers pass (1 - sigma)^k, a point's own slice never counts, two
   materials multiply, an opaque quad casts a full shadow; the normal offset keeps an open floor
   lit and a plate's shadow dark, at normal and grazing incidence; maps and lookups on GL give
   the very same answers; images equal the reference's direct light; bad input is refused. (Voxel
   visibility, part 5, which the reflective shadow maps use: tests/test_voxelize.c.) Reflective
   shadow maps: the flux they hold (a sun's map, a spot light's, an area's hemisphere maps), the
   gather against equation 5 by hand, a texel's weight as a point source's, a uniform plane's
   light against its view factor, the divider of rsm-walls stopping the red wall's light, the
   gather stride's interpolation. The SH volume: its projection and evaluation against the closed
   forms, lights adding, the Cornell box's ceiling lit by its bounce. */
#include "../voxgi.h"
#include "fixtures.h"

/* Quad at height y over [-r, r]^2 in x and z, two triangles facing up, appended to pos / mats. */
static size_t put_quad(float *pos, uint32_t *mats, size_t t, double y, double r, uint32_t material)
{
    static const double corner[6][2] = {{-1, -1}, {-1, 1}, {1, 1}, {-1, -1}, {1, 1}, {1, -1}};
    int k;
    for (k = 0; k < 6; k++) {
        pos[9 * t + 3 * (size_t)k + 0] = (float)(r * corner[k][0]);
        pos[9 * t + 3 * (size_t)k + 1] = (float)y;
        pos[9 * t + 3 * (size_t)k + 2] = (float)(r * corner[k][1]);
    }
    mats[t] = mats[t + 1] = material;
    return t + 2;
}

/* The stack: ground (opaque, material 0) at y = 0 over [-4, 4]^2; translucent quads (material 1)
   at y = 1, 2, 3 over [-1, 1]^2; a quad of material 2 at y = 2.5 over [-1, 1]^2 when `second`; an
   opaque quad (material 0) at y = 1.5 over [2, 3] x [-1, 1] when `blocker`. The sun shines
   straight down. */
typedef struct stack_scene {
    float pos[9 * 12];
    uint32_t mats[12];
    voxgi_material materials[3];
    voxgi_light sun;
    voxgi_mesh mesh;
    voxgi_scene scene;
} stack_scene;

static void stack_make(stack_scene *S, float transparency1, float transparency2, int second, int blocker)
{
    size_t t = 0;
    int y;
    memset(S, 0, sizeof *S);
    t = put_quad(S->pos, S->mats, t, 0, 4, 0);
    for (y = 1; y <= 3; y++) t = put_quad(S->pos, S->mats, t, y, 1, 1);
    if (second) t = put_quad(S->pos, S->mats, t, 2.5, 1, 2);
    if (blocker) {
        size_t k;
        t = put_quad(S->pos, S->mats, t, 1.5, 0.5, 0);
        for (k = 9 * (t - 2); k < 9 * t; k += 3) S->pos[k] += 2.5f; /* over [2, 3] x [-0.5, 0.5] */
    }
    S->materials[0].albedo[0] = S->materials[0].albedo[1] = S->materials[0].albedo[2] = 0.5f;
    S->materials[1] = S->materials[0];
    S->materials[1].transparency = transparency1;
    S->materials[2] = S->materials[0];
    S->materials[2].transparency = transparency2;
    S->sun.type = VOXGI_LIGHT_DIRECTIONAL;
    S->sun.direction[1] = -1;
    S->sun.intensity[0] = S->sun.intensity[1] = S->sun.intensity[2] = 1;
    S->mesh.positions = S->pos;
    S->mesh.vertex_count = 3 * t;
    S->mesh.material_ids = S->mats;
    S->scene.meshes = &S->mesh;
    S->scene.mesh_count = 1;
    S->scene.materials = S->materials;
    S->scene.material_count = 3;
    S->scene.lights = &S->sun;
    S->scene.light_count = 1;
}

/* The light at (x, y, z) without a normal, on a map of 64 texels and 32 slices. */
static double light_at(voxgi_context *ctx, const voxgi_tsm *tsm, double x, double y, double z)
{
    float p[3], out = -1;
    p[0] = (float)x; p[1] = (float)y; p[2] = (float)z;
    TH_CHECK(voxgi_tsm_transmittance(ctx, tsm, 1, p, NULL, &out) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    return out;
}

static voxgi_tsm *make_tsm(voxgi_context *ctx, const voxgi_scene *sc, float sigma)
{
    voxgi_tsm_desc d;
    voxgi_tsm *tsm = NULL;
    memset(&d, 0, sizeof d);
    d.size = 64;
    d.slices = 32;
    d.sigma = sigma;
    TH_CHECK(voxgi_tsm_create(ctx, sc, &d, &tsm) == VOXGI_OK && tsm, "tsm: %s", voxgi_last_error(ctx));
    return tsm;
}

/* Depth runs from y = 3 (slice 0) to y = 0 (slice 31): the quads at 3, 2, 1 fill slices 0, 10 and
   21 (3 / 32 each), so a point at y = 0.5 lies under all three, one at 1.5 under two, one on the
   quad at 2 (its own slice 10) under one; beside the quads (x = 3) nothing is above. */
static void test_tsm_layers(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    stack_scene S;
    voxgi_tsm *tsm;
    voxgi_tsm_info info;
    const double s = 0.3, pass = 1 - s;
    double got[5];
    stack_make(&S, (float)pass, 0.5f, 0, 0);
    tsm = make_tsm(ctx, &S.scene, 0);
    if (tsm) {
        got[0] = light_at(ctx, tsm, 0.1, 0.5, 0.2);
        got[1] = light_at(ctx, tsm, 0.1, 1.5, 0.2);
        got[2] = light_at(ctx, tsm, 0.1, 2.0, 0.2);
        got[3] = light_at(ctx, tsm, 0.1, 3.5, 0.2);
        got[4] = light_at(ctx, tsm, 3.0, 0.5, 0.2);
        voxgi_tsm_query(tsm, &info);
        printf("    sigma 0.3: under 3, 2 and 1 (its own slice) layers %.6f %.6f %.6f, above %.6f, beside %.6f; %d material, %llu voxels\n", got[0],
               got[1], got[2], got[3], got[4], info.materials, (unsigned long long)info.voxels);
        TH_CHECK(fabs(got[0] - pass * pass * pass) < 1e-6 && fabs(got[1] - pass * pass) < 1e-6 && fabs(got[2] - pass) < 1e-6, "k layers pass (1 - sigma)^k");
        TH_CHECK(got[3] == 1 && got[4] == 1, "nothing above: all the light");
        TH_CHECK(info.materials == 1 && info.voxels > 0, "one translucent material");
        voxgi_tsm_destroy(ctx, tsm);
    }
    tsm = make_tsm(ctx, &S.scene, 1); /* sigma = 1: a binary shadow */
    if (tsm) {
        got[0] = light_at(ctx, tsm, 0.1, 0.5, 0.2);
        got[1] = light_at(ctx, tsm, 0.1, 3.01, 0.2); /* on the top quad: its own slice */
        got[2] = light_at(ctx, tsm, 3.0, 0.5, 0.2);
        TH_CHECK(got[0] == 0 && got[1] == 1 && got[2] == 1, "sigma 1: %g under, %g on the top quad, %g beside", got[0], got[1], got[2]);
        voxgi_tsm_destroy(ctx, tsm);
    }
    stack_make(&S, 1.0f, 0.5f, 0, 0); /* transparency 1, sigma 0: no layer at all */
    tsm = make_tsm(ctx, &S.scene, 0);
    if (tsm) {
        got[0] = light_at(ctx, tsm, 0.1, 0.5, 0.2);
        voxgi_tsm_query(tsm, &info);
        TH_CHECK(got[0] == 1 && info.materials == 0, "sigma 0: %g, %d materials", got[0], info.materials);
        voxgi_tsm_destroy(ctx, tsm);
    }
    voxgi_destroy(ctx);
}

/* The same stack under a spot light 5 above the ground pointing down (outer angle 0.6): its map
   is perspective, slices uniform in 1 / depth from the top quad (depth 2) to the ground (5), so
   the quads at 3, 2, 1 fill slices 0, 17 and 26, and the same layers are counted; points off the
   cone's axis, and one above the top quad (before the near plane: nothing in the way). Built on
   GL, the same answers. */
static void test_tsm_spot_layers(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    stack_scene S;
    voxgi_tsm *tsm;
    const double pass = 0.7;
    double got[5];
    stack_make(&S, (float)pass, 0.5f, 0, 0);
    S.sun.type = VOXGI_LIGHT_SPOT;
    S.sun.position[1] = 5;
    S.sun.spot_inner = 0.5f;
    S.sun.spot_outer = 0.6f;
    tsm = make_tsm(ctx, &S.scene, 0);
    if (tsm) {
        got[0] = light_at(ctx, tsm, 0.3, 0.5, -0.4);
        got[1] = light_at(ctx, tsm, -0.5, 1.5, 0.2);
        got[2] = light_at(ctx, tsm, 0.1, 2.0, 0.6);
        got[3] = light_at(ctx, tsm, 0.1, 3.5, 0.2);
        got[4] = light_at(ctx, tsm, 2.5, 0.1, 0.0); /* outside the quads' shadow cone */
        printf("    spot light, sigma 0.3: under 3, 2 and 1 (its own slice) layers %.6f %.6f %.6f, above %.6f, beside %.6f\n", got[0], got[1], got[2], got[3],
               got[4]);
        TH_CHECK(fabs(got[0] - pass * pass * pass) < 1e-6 && fabs(got[1] - pass * pass) < 1e-6 && fabs(got[2] - pass) < 1e-6, "spot: k layers");
        TH_CHECK(got[3] == 1 && got[4] == 1, "spot: nothing in the way");
        voxgi_tsm_destroy(ctx, tsm);
    }
    if (have_gl()) {
        voxgi_context *gl = make_ctx(VOXGI_BACKEND_GL, 0);
        voxgi_tsm *a = make_tsm(ctx, &S.scene, 0), *b = make_tsm(gl, &S.scene, 0);
        fx_rng g = fx_rng_seeded(8);
        size_t i, differ = 0, shaded = 0;
        float p[3], ta, tb;
        for (i = 0; a && b && i < 2000; i++) {
            p[0] = (float)fx_rng_range(&g, -1.5, 1.5);
            p[1] = (float)fx_rng_range(&g, 0, 3.2);
            p[2] = (float)fx_rng_range(&g, -1.5, 1.5);
            voxgi_tsm_transmittance(ctx, a, 1, p, NULL, &ta);
            voxgi_tsm_transmittance(gl, b, 1, p, NULL, &tb);
            differ += ta != tb;
            shaded += ta < 1;
        }
        printf("    spot light: 2000 points, %lu in some shadow, %lu differ between the CPU's and GL's maps\n", (unsigned long)shaded, (unsigned long)differ);
        TH_CHECK(a && b && differ == 0 && shaded > 200, "spot: GL's maps differ");
        voxgi_tsm_destroy(ctx, a);
        voxgi_tsm_destroy(gl, b);
        voxgi_destroy(gl);
    }
    voxgi_destroy(ctx);
}

/* Two translucent materials multiply their layers; an opaque quad casts a full shadow (the
   shadow map, checked before the slicemaps), and a point on the lit ground with its normal is
   not shadowed by the ground itself (the normal offset). */
static void test_tsm_materials_and_opaque(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    stack_scene S;
    voxgi_tsm *tsm;
    voxgi_tsm_info info;
    double got[3], want = 0.7 * 0.7 * 0.4 * 0.7;
    stack_make(&S, 0.7f, 0.4f, 1, 1);
    tsm = make_tsm(ctx, &S.scene, 0);
    if (tsm) {
        float p[3] = {3.5f, 0.0f, 0.0f}, n[3] = {0, 1, 0}, out = -1;
        got[0] = light_at(ctx, tsm, 0.1, 0.5, 0.2);
        got[1] = light_at(ctx, tsm, 2.5, 0.5, 0.0);
        TH_CHECK(voxgi_tsm_transmittance(ctx, tsm, 1, p, n, &out) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        got[2] = out;
        voxgi_tsm_query(tsm, &info);
        printf("    two materials: %.6f (want %.6f); under the opaque quad %g; the open ground %g\n", got[0], want, got[1], got[2]);
        TH_CHECK(info.materials == 2 && fabs(got[0] - want) < 1e-6, "two materials multiply");
        TH_CHECK(got[1] == 0 && got[2] == 1, "an opaque quad shadows fully, the open ground is lit");
        voxgi_tsm_destroy(ctx, tsm);
    }
    voxgi_destroy(ctx);
}

/* Whether the segment from p to the light (a sun: along -direction) crosses y = 0.5 inside
   [-0.9, 0.9]^2, a tenth inside the plate of test_tsm_normal_offset (2 texels and more). */
static int crosses_plate(const voxgi_light *L, const double p[3])
{
    double to[3], t, x, z;
    int a;
    for (a = 0; a < 3; a++) to[a] = L->type == VOXGI_LIGHT_SPOT ? L->position[a] - p[a] : -L->direction[a];
    if (!(to[1] > 0)) return 0;
    t = (0.5 - p[1]) / to[1];
    if (L->type == VOXGI_LIGHT_SPOT && t > 1) return 0;
    x = p[0] + t * to[0];
    z = p[2] + t * to[2];
    return t > 0 && fabs(x) <= 0.9 && fabs(z) <= 0.9;
}

/* The normal offset on the CPU (maps of 256 texels): an opaque floor at y = 0 over [-4, 4]^2
   and an opaque plate at y = 0.5 over [-1, 1]^2, under a sun and a spot light each at normal
   incidence (straight above) and grazing (the sun 80 degrees from the floor's normal; the spot
   low at (-5, 1, 0), 56 to 75 degrees on the open floor). 50 points of the open floor (x in
   [-3.5, -1.5], where no segment to the light meets the plate) read 1 with the normal up and
   down (the offset goes to the side the light comes from), and 25 points 0.15 under the plate
   (x in [0.4, 0.9]: each segment to the light crosses the plate two texels and more inside it)
   read 0 either way: measured so for all 4 lights. An offset away from the light, or along the
   normal whatever its side, puts a floor point under its own floor: it reads 0. */
static void test_tsm_normal_offset(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    float pos[9 * 4];
    uint32_t mats[4];
    voxgi_material mat;
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi_light lights[4];
    voxgi_tsm_desc d;
    const double graze = 80 * PI / 180;
    int l, i, side;
    memset(&mat, 0, sizeof mat);
    mat.albedo[0] = mat.albedo[1] = mat.albedo[2] = 0.5f;
    put_quad(pos, mats, put_quad(pos, mats, 0, 0, 4, 0), 0.5, 1, 0);
    memset(&mesh, 0, sizeof mesh);
    mesh.positions = pos;
    mesh.vertex_count = 12;
    memset(&sc, 0, sizeof sc);
    sc.meshes = &mesh;
    sc.mesh_count = 1;
    sc.materials = &mat;
    sc.material_count = 1;
    memset(lights, 0, sizeof lights);
    for (l = 0; l < 4; l++) lights[l].intensity[0] = lights[l].intensity[1] = lights[l].intensity[2] = 1;
    lights[0].type = lights[1].type = VOXGI_LIGHT_DIRECTIONAL;
    lights[0].direction[1] = -1;
    lights[1].direction[0] = (float)sin(graze);
    lights[1].direction[1] = (float)-cos(graze);
    lights[2].type = lights[3].type = VOXGI_LIGHT_SPOT;
    lights[2].position[1] = 5;
    lights[2].direction[1] = -1;
    lights[3].position[0] = -5;
    lights[3].position[1] = 1;
    lights[3].direction[0] = 5;
    lights[3].direction[1] = -1;
    lights[2].spot_inner = lights[3].spot_inner = 0.7f;
    lights[2].spot_outer = lights[3].spot_outer = 0.8f;
    sc.lights = lights;
    sc.light_count = 4;
    memset(&d, 0, sizeof d);
    d.size = 256;
    d.slices = 32;
    for (l = 0; l < 4; l++) {
        voxgi_tsm *tsm = NULL;
        int dark = 0, leaked = 0, fixture = 0;
        d.light = (size_t)l;
        TH_CHECK(voxgi_tsm_create(ctx, &sc, &d, &tsm) == VOXGI_OK && tsm, "%s", voxgi_last_error(ctx));
        if (!tsm) continue;
        for (side = -1; side <= 1; side += 2)
            for (i = 0; i < 75; i++) {
                int under = i >= 50, a;
                double p[3];
                float fp[3], n[3] = {0, 0, 0}, out = -1;
                p[0] = under ? 0.4 + 0.125 * (i % 5) : -3.5 + 0.5 * (i % 5);
                p[1] = under ? 0.35 : 0;
                p[2] = under ? -0.5 + 0.25 * ((i - 50) / 5) : -1 + 0.2 * (i / 5);
                n[1] = (float)side;
                for (a = 0; a < 3; a++) fp[a] = (float)p[a];
                fixture += crosses_plate(&lights[l], p) != under;
                TH_CHECK(voxgi_tsm_transmittance(ctx, tsm, 1, fp, n, &out) == VOXGI_OK, "%s", voxgi_last_error(ctx));
                if (under) leaked += out != 0;
                else dark += out != 1;
            }
        printf("    %s, %s incidence: %d of 100 open floor points (normal up, down) not fully lit, %d of 50 under the plate not dark\n",
               l < 2 ? "sun" : "spot light", l % 2 ? "grazing" : "normal", dark, leaked);
        TH_CHECK(fixture == 0, "%d points on the wrong side of the plate's shadow", fixture);
        TH_CHECK(dark == 0, "the open floor shadows itself");
        TH_CHECK(leaked == 0, "light through the plate");
        voxgi_tsm_destroy(ctx, tsm);
    }
    voxgi_destroy(ctx);
}

/* On GL (maps built by GL's raster slicemap, lookups by shaders/tsm_lookup.glsl) the answers are
   the CPU's bit for bit, at 2000 random points in and beside the stack, without and with normals
   (random unit vectors). */
static void test_tsm_gl_equals_cpu(void)
{
    enum { N = 2000 };
    voxgi_context *cpu, *gl;
    stack_scene S;
    voxgi_tsm *a, *b;
    static float pts[3 * N], nrm[3 * N], ta[N], tb[N];
    fx_rng g = fx_rng_seeded(3);
    size_t i, differ = 0, shaded = 0, differ_n = 0;
    if (!have_gl()) return;
    cpu = make_ctx(VOXGI_BACKEND_CPU, 0);
    gl = make_ctx(VOXGI_BACKEND_GL, 0);
    stack_make(&S, 0.7f, 0.4f, 1, 1);
    for (i = 0; i < 3 * N; i++) pts[i] = (float)(i % 3 == 0 ? fx_rng_range(&g, -1.2, 3.2) : i % 3 == 1 ? fx_rng_range(&g, 0, 3.2) : fx_rng_range(&g, -1.2, 1.2));
    for (i = 0; i < N; i++) {
        double v[3], len;
        int k;
        do {
            for (k = 0; k < 3; k++) v[k] = fx_rng_range(&g, -1, 1);
            len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        } while (len > 1 || len < 0.1);
        for (k = 0; k < 3; k++) nrm[3 * i + (size_t)k] = (float)(v[k] / len);
    }
    a = make_tsm(cpu, &S.scene, 0);
    b = make_tsm(gl, &S.scene, 0);
    if (a && b) {
        TH_CHECK(voxgi_tsm_transmittance(cpu, a, N, pts, NULL, ta) == VOXGI_OK && voxgi_tsm_transmittance(gl, b, N, pts, NULL, tb) == VOXGI_OK, "lookups");
        for (i = 0; i < N; i++) {
            differ += ta[i] != tb[i];
            shaded += ta[i] < 1;
        }
        TH_CHECK(voxgi_tsm_transmittance(cpu, a, N, pts, nrm, ta) == VOXGI_OK && voxgi_tsm_transmittance(gl, b, N, pts, nrm, tb) == VOXGI_OK, "lookups");
        for (i = 0; i < N; i++) differ_n += ta[i] != tb[i];
        printf("    %d points: %lu in some shadow, %lu differ between the CPU and GL (%lu with normals)\n", N, (unsigned long)shaded, (unsigned long)differ,
               (unsigned long)differ_n);
        TH_CHECK(differ == 0 && differ_n == 0 && shaded > N / 10, "GL differs");
    }
    voxgi_tsm_destroy(cpu, a);
    voxgi_tsm_destroy(gl, b);
    voxgi_destroy(cpu);
    voxgi_destroy(gl);
}

/* The reference renderer's shadow rays pass translucent surfaces the same way, without slices:
   the ground straight under the stack (three layers of transparency 0.7, the sun of irradiance 1
   straight above) has radiance 0.5 / pi x 0.7^3 in every pixel, direct light only; with a second
   material of transparency 0.4 between them, x 0.4 more. */
static void test_reference_sees_through_leaves(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    stack_scene S;
    voxgi_render_desc d;
    float rgb[3 * 9 * 9];
    double worst[2] = {0, 0};
    int second, i;
    for (second = 0; second < 2; second++) {
        double want = 0.5 / 3.14159265358979 * 0.343 * (second ? 0.4 : 1);
        stack_make(&S, 0.7f, 0.4f, second, 0);
        memset(&d, 0, sizeof d);
        d.method = VOXGI_RENDER_REFERENCE;
        d.camera.eye[1] = 0.9; d.camera.eye[2] = -3; /* under the lowest quad, looking at the ground's centre */
        d.camera.fovy_degrees = 4;
        d.camera.width = d.camera.height = 9;
        d.samples = 4;
        d.seed = 1;
        d.direct_only = 1; /* the old bounces 0: direct light only */
        TH_CHECK(voxgi_render(ctx, &S.scene, &d, rgb, sizeof rgb, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        for (i = 0; i < 3 * 81; i++) worst[second] = fmax(worst[second], fabs(rgb[i] - want) / want);
    }
    printf("    the ground under three leaves: relative error %.2e; with a fourth of another material %.2e\n", worst[0], worst[1]);
    TH_CHECK(worst[0] < 1e-5 && worst[1] < 1e-5, "the reference's shadow rays through translucent surfaces");
    voxgi_destroy(ctx);
}

/* The TSM image (voxgi_render) of the ground under the stack equals the reference's direct light,
   for the sun (to 1e-5) and for a spot light (its cone's falloff and the inverse square included; to 1%:
   the two sample other points of each pixel, where the spot's light varies): where every layer
   has a slice of its own the maps count them all. */
static void test_tsm_image_equals_reference(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    stack_scene S;
    voxgi_render_desc d, td;
    voxgi_render_info ti;
    float ref[3 * 9 * 9], img[3 * 9 * 9];
    double worst[2] = {0, 0};
    int spot, i;
    for (spot = 0; spot < 2; spot++) {
        stack_make(&S, 0.7f, 0.4f, 0, 0);
        if (spot) {
            S.sun.type = VOXGI_LIGHT_SPOT;
            S.sun.position[1] = 5;
            S.sun.spot_inner = 0.05f;
            S.sun.spot_outer = 0.6f;
            S.sun.intensity[0] = S.sun.intensity[1] = S.sun.intensity[2] = 20;
        }
        memset(&d, 0, sizeof d);
        d.method = VOXGI_RENDER_REFERENCE;
        d.camera.eye[1] = 0.9; d.camera.eye[2] = -3;
        d.camera.fovy_degrees = 4;
        d.camera.width = d.camera.height = 9;
        d.samples = 4;
        d.seed = 1;
        d.direct_only = 1; /* the old bounces 0: direct light only */
        memset(&td, 0, sizeof td);
        td.method = VOXGI_RENDER_TSM;
        td.camera = d.camera;
        td.tsm.maps.size = 128;
        td.seed = 1;
        TH_CHECK(voxgi_render(ctx, &S.scene, &d, ref, sizeof ref, NULL) == VOXGI_OK && voxgi_render(ctx, &S.scene, &td, img, sizeof img, &ti) == VOXGI_OK,
                 "%s", voxgi_last_error(ctx));
        TH_CHECK(ti.maps == 1, "%d maps", ti.maps);
        for (i = 0; i < 3 * 81; i++) worst[spot] = fmax(worst[spot], fabs(img[i] - ref[i]) / ref[i]);
    }
    printf("    the ground under the stack: maps against the reference's rays within %.2e (sun), %.2e (spot light)\n", worst[0], worst[1]);
    TH_CHECK(worst[0] < 1e-5 && worst[1] < 1e-2, "the image differs from the reference's direct light");
    voxgi_destroy(ctx);
}

/* Bad input: a light that is not directional, a light index past the end, absurd sizes, a NaN
   point, NULLs. */
static void test_tsm_input(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    stack_scene S;
    voxgi_tsm_desc d;
    voxgi_tsm *tsm = NULL;
    float p[3] = {0, NAN, 0}, out;
    stack_make(&S, 0.7f, 0.4f, 0, 0);
    memset(&d, 0, sizeof d);
    S.sun.type = VOXGI_LIGHT_POINT;
    TH_CHECK(voxgi_tsm_create(ctx, &S.scene, &d, &tsm) == VOXGI_ERR_UNSUPPORTED && !tsm, "a point light");
    S.sun.type = VOXGI_LIGHT_DIRECTIONAL;
    d.light = 1;
    TH_CHECK(voxgi_tsm_create(ctx, &S.scene, &d, &tsm) == VOXGI_ERR_INVALID_ARGUMENT && !tsm, "light 1 of 1");
    d.light = 0;
    d.size = -3;
    TH_CHECK(voxgi_tsm_create(ctx, &S.scene, &d, &tsm) == VOXGI_ERR_INVALID_ARGUMENT && !tsm, "size -3");
    d.size = 16;
    d.sigma = 2;
    TH_CHECK(voxgi_tsm_create(ctx, &S.scene, &d, &tsm) == VOXGI_ERR_INVALID_ARGUMENT && !tsm, "sigma 2");
    d.sigma = 0;
    TH_CHECK(voxgi_tsm_create(ctx, &S.scene, &d, &tsm) == VOXGI_OK && tsm, "%s", voxgi_last_error(ctx));
    TH_CHECK(voxgi_tsm_transmittance(ctx, tsm, 1, p, NULL, &out) == VOXGI_ERR_INVALID_ARGUMENT, "a NaN point");
    TH_CHECK(voxgi_tsm_transmittance(ctx, NULL, 1, p, NULL, &out) == VOXGI_ERR_INVALID_ARGUMENT, "no map");
    TH_CHECK(voxgi_tsm_create(ctx, NULL, &d, &tsm) == VOXGI_ERR_INVALID_ARGUMENT, "no scene");
    voxgi_tsm_destroy(ctx, tsm);
    voxgi_destroy(ctx);
}

/* Reflective shadow maps on rsm-walls (the seed's scene: two white spheres, a red and a blue
   wall, a grey divider, the sun): the pattern's weights sum to 1 within its disc; the gather at
   points equals this test's own double evaluation of the seed's equation 5 (with the Lambertian
   1 / pi) over the pattern's texels; texels lie on surfaces and face the light; and the divider,
   through the voxels, stops the red wall's light reaching the floor right of it (by DDA and by
   the hierarchy alike), where without visibility it bleeds through. */
static void test_rsm_walls(void)
{
    enum { S = 64, K = 100 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene bs;
    voxgi_rsm_desc d;
    voxgi_rsm *rsm = NULL;
    voxgi_voxelize_desc vd;
    voxgi_fit_desc fit;
    voxgi_voxels *vox = NULL;
    static float pos[3 * S * S], nrm[3 * S * S], flux[3 * S * S];
    float off[2 * K], w[K], pts[6] = {0.3f, 0.001f, 0.4f, -0.4f, 0.001f, 0.6f}, nr[6] = {0, 1, 0, 0, 1, 0}, e[6], e_dda[6], e_hier[6];
    double sum = 0, worst_off = 0, worst = 0, radius = 0.3 * S;
    int k, i, a, lit = 0;
    TH_CHECK(voxgi_builtin_scene_create(ctx, "rsm-walls", &bs) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    memset(&d, 0, sizeof d);
    d.size = S;
    d.samples = K;
    d.radius = 0.3f;
    d.seed = 4;
    TH_CHECK(voxgi_rsm_create(ctx, &bs.scene, &d, &rsm) == VOXGI_OK && rsm, "%s", voxgi_last_error(ctx));
    if (rsm) {
        TH_CHECK(voxgi_rsm_pattern(ctx, rsm, off, w) == VOXGI_OK && voxgi_rsm_texels(ctx, rsm, pos, nrm, flux) == VOXGI_OK, "read");
        for (k = 0; k < K; k++) {
            sum += w[k];
            worst_off = fmax(worst_off, sqrt((double)off[2 * k] * off[2 * k] + (double)off[2 * k + 1] * off[2 * k + 1]));
        }
        for (i = 0; i < S * S; i++) {
            double facing = 0;
            lit += flux[3 * i] > 0;
            for (a = 0; a < 3; a++) facing += nrm[3 * i + a] * (a == 0 ? 0.35 : a == 1 ? -0.8 : 0.5);
            if (flux[3 * i] > 0) TH_CHECK(facing < 0 && pos[3 * i + 1] > -1e-3 && pos[3 * i + 1] < 2.01, "texel %d: facing %g, height %g", i, facing, pos[3 * i + 1]);
        }
        printf("    %d x %d texels, %d lit; %d samples: weights sum to %.7f, the farthest %.2f texels out (radius %.2f)\n", S, S, lit, K, sum, worst_off, radius);
        TH_CHECK(fabs(sum - 1) < 1e-5 && worst_off <= radius && lit > S * S / 4, "the pattern or the texels");
        TH_CHECK(voxgi_rsm_irradiance(ctx, rsm, NULL, VOXGI_TRAVERSAL_DDA, 2, pts, nr, e) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        for (i = S / 4; i < S * S; i += 37) { /* by hand at lit texels' own points (whose texel is their own): equation 5 / pi in double */
            int ti = i % S, tj = i / S;
            float x[3], n[3], got[3];
            double want[3] = {0, 0, 0};
            if (!(flux[3 * i] > 0)) continue;
            for (a = 0; a < 3; a++) { x[a] = pos[3 * i + a]; n[a] = nrm[3 * i + a]; }
            TH_CHECK(voxgi_rsm_irradiance(ctx, rsm, NULL, VOXGI_TRAVERSAL_DDA, 1, x, n, got) == VOXGI_OK, "%s", voxgi_last_error(ctx));
            for (k = 0; k < K; k++) {
                double ss = ti + 0.5 + off[2 * k], tt = tj + 0.5 + off[2 * k + 1], dd[3], dist2 = 0, cp = 0, cx = 0;
                int q;
                if (!(ss >= 0 && ss < S && tt >= 0 && tt < S)) continue;
                q = (int)tt * S + (int)ss;
                for (a = 0; a < 3; a++) {
                    dd[a] = (double)x[a] - pos[3 * q + a];
                    dist2 += dd[a] * dd[a];
                    cp += nrm[3 * q + a] * dd[a];
                    cx -= n[a] * dd[a];
                }
                if (cp <= 0 || cx <= 0) continue;
                for (a = 0; a < 3; a++) want[a] += 3.14159265358979 * radius * radius * w[k] * flux[3 * q + a] * cp * cx / (3.14159265358979 * dist2 * dist2);
            }
            for (a = 0; a < 3; a++) worst = fmax(worst, fabs(got[a] - want[a]) / fmax(want[a], 1e-3));
        }
        printf("    the gather at lit texels' points against equation 5 by hand: within %.2e\n", worst);
        TH_CHECK(worst < 1e-4, "the gather differs from equation 5");
        memset(&fit, 0, sizeof fit);
        fit.res = 64;
        memset(&vd, 0, sizeof vd);
        TH_CHECK(voxgi_fit_grid(ctx, &bs.scene, &fit, &vd.grid) == VOXGI_OK && voxgi_voxelize(ctx, &bs.scene, &vd, &vox) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        TH_CHECK(voxgi_rsm_irradiance(ctx, rsm, vox, VOXGI_TRAVERSAL_DDA, 2, pts, nr, e_dda) == VOXGI_OK &&
                     voxgi_rsm_irradiance(ctx, rsm, vox, VOXGI_TRAVERSAL_HIERARCHICAL, 2, pts, nr, e_hier) == VOXGI_OK,
                 "%s", voxgi_last_error(ctx));
        /* red's excess over green: the red wall's share (the grey floor and white spheres send all three alike) */
        printf("    red bleeding on the floor right of the divider: %.4f without visibility, %.4f with DDA, %.4f hierarchical; left of it: %.4f, %.4f\n",
               e[0] - e[1], e_dda[0] - e_dda[1], e_hier[0] - e_hier[1], e[3] - e[4], e_dda[3] - e_dda[4]);
        TH_CHECK(e_dda[0] == e_hier[0] && e_dda[1] == e_hier[1] && e_dda[2] == e_hier[2], "DDA and hierarchical gathers differ");
        TH_CHECK(e[0] - e[1] > 0.01 && e_dda[0] - e_dda[1] < 0.05 * (e[0] - e[1]), "the red wall's light bleeds through the divider");
        TH_CHECK(e_dda[3] - e_dda[4] > 0.3 * (e[3] - e[4]), "the red wall's light is lost on its own side");
    }
    voxgi_voxels_destroy(ctx, vox);
    voxgi_rsm_destroy(ctx, rsm);
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* A floor [-4, 4]^2 at y = 0 facing up (two triangles) of albedo (0.5, 0.4, 0.3) under a sun. */
typedef struct floor_scene {
    float pos[18];
    uint32_t mats[2];
    voxgi_material material;
    voxgi_light sun;
    voxgi_mesh mesh;
    voxgi_scene scene;
} floor_scene;

static void floor_make(floor_scene *F, double dx, double dy, double dz)
{
    memset(F, 0, sizeof *F);
    put_quad(F->pos, F->mats, 0, 0, 4, 0);
    F->material.albedo[0] = 0.5f;
    F->material.albedo[1] = 0.4f;
    F->material.albedo[2] = 0.3f;
    F->sun.type = VOXGI_LIGHT_DIRECTIONAL;
    F->sun.direction[0] = (float)dx;
    F->sun.direction[1] = (float)dy;
    F->sun.direction[2] = (float)dz;
    F->sun.intensity[0] = F->sun.intensity[1] = F->sun.intensity[2] = 1;
    F->mesh.positions = F->pos;
    F->mesh.vertex_count = 6;
    F->mesh.material_ids = F->mats;
    F->scene.meshes = &F->mesh;
    F->scene.mesh_count = 1;
    F->scene.materials = &F->material;
    F->scene.material_count = 1;
    F->scene.lights = &F->sun;
    F->scene.light_count = 1;
}

/* One texel's weight in the gather by its definition (equation 5 with the Lambertian 1 / pi):
   with the sample disc half a texel across (radius 0.25 texels), every sample of a point on the
   ray through a texel's centre falls in that texel, so whatever the pattern (its weights sum to
   1) the gather sees the share pi r^2 of the texel's flux Phi as a Lambertian point source:
   pi r^2 Phi cos_p cos_x / (pi d^2), cos_p at the texel's normal, cos_x at the point's. A sun
   36.9 degrees off the vertical over the floor (cos_p = 0.8 all up the ray), three texels, points
   0.75, 1.5 and 3 up the ray (the texels 0.26 wide), their normals facing the texel, 60 degrees
   off it (cos_x = 0.5) and 100 degrees off (nothing): every value within 1e-6 relative
   (measured 5.1e-8). A distance's power short or a cosine dropped is off by 25% and more. */
static void test_rsm_point_source(void)
{
    enum { S = 32 };
    static const int texel[3][2] = {{16, 16}, {8, 21}, {23, 10}};
    static const double up_the_ray[3] = {0.75, 1.5, 3}, off_degrees[3] = {0, 60, 100};
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    static floor_scene F;
    voxgi_rsm_desc d;
    voxgi_rsm *rsm = NULL;
    static float pos[3 * S * S], nrm[3 * S * S], flux[3 * S * S];
    const double w[3] = {0.6, -0.8, 0}, side[3] = {0, 0, 1}; /* the light's direction, and one across it */
    double worst = 0, largest = 0;
    int ti, di, ni, a, zeros = 0;
    floor_make(&F, w[0], w[1], w[2]);
    memset(&d, 0, sizeof d);
    d.size = S;
    d.samples = 64;
    d.radius = 0.25f / S; /* of the map's width: 0.25 texels */
    d.seed = 9;
    TH_CHECK(voxgi_rsm_create(ctx, &F.scene, &d, &rsm) == VOXGI_OK && voxgi_rsm_texels(ctx, rsm, pos, nrm, flux) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (ti = 0; rsm && ti < 3; ti++) {
        int at = 3 * (texel[ti][1] * S + texel[ti][0]);
        TH_CHECK(flux[at] > 0 && flux[at + 1] > 0 && flux[at + 2] > 0, "texel %d %d is not lit", texel[ti][0], texel[ti][1]);
        for (di = 0; di < 3; di++)
            for (ni = 0; ni < 3; ni++) {
                float x[3], n[3], got[3];
                double dd[3], dist2 = 0, cos_p = 0, cos_x = 0, c = cos(off_degrees[ni] * PI / 180), s = sin(off_degrees[ni] * PI / 180);
                for (a = 0; a < 3; a++) {
                    x[a] = (float)(pos[at + a] - up_the_ray[di] * w[a]);
                    n[a] = (float)(c * w[a] + s * side[a]);
                }
                TH_CHECK(voxgi_rsm_irradiance(ctx, rsm, NULL, VOXGI_TRAVERSAL_DDA, 1, x, n, got) == VOXGI_OK, "%s", voxgi_last_error(ctx));
                for (a = 0; a < 3; a++) dd[a] = (double)x[a] - pos[at + a];
                for (a = 0; a < 3; a++) dist2 += dd[a] * dd[a];
                for (a = 0; a < 3; a++) {
                    cos_p += nrm[at + a] * dd[a] / sqrt(dist2);
                    cos_x -= n[a] * dd[a] / sqrt(dist2);
                }
                for (a = 0; a < 3; a++) {
                    double want = cos_x > 0 ? PI * 0.25 * 0.25 * flux[at + a] * cos_p * cos_x / (PI * dist2) : 0;
                    if (want == 0) {
                        zeros++;
                        TH_CHECK(got[a] == 0, "light from behind the point: %g", got[a]);
                    } else
                        worst = fmax(worst, fabs(got[a] - want) / want);
                    largest = fmax(largest, want);
                }
                TH_CHECK(ni == 2 || fabs(cos_p - 0.8) < 1e-5, "cos_p %g", cos_p);
            }
    }
    printf("    a texel seen as a point source (cos_p 0.8; cos_x 1, 0.5, below 0; d 0.75 to 3): within %.1e relative (the largest %.3g), %d values 0\n",
           worst, largest, zeros);
    TH_CHECK(worst < 1e-6 && zeros == 27, "the gather's weight of a texel leaves the point source's");
    voxgi_rsm_destroy(ctx, rsm);
    voxgi_destroy(ctx);
}

/* The whole gather (pattern, weights, texels) over a uniform plane against the closed form: the
   floor under a sun of irradiance 1 straight above sends radiosity B = albedo; a point h above
   its centre facing down gathers the disc of radius R (0.3 of the map's width) around it, whose
   view factor gives B R^2 / (R^2 + h^2). With 65536 samples, at h = R / 2, R and 2 R: within 1.5%
   (measured +0.64%, +0.29%, +0.10%; over eight other seeds the error at R / 2 spread 0.25% rms,
   0.51% at most). The seed's weights xi1^2, which over-count the rim, lose 14% at h = R. */
static void test_rsm_uniform_plane(void)
{
    enum { S = 64 };
    static const double height[3] = {0.5, 1, 2};
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    static floor_scene F;
    voxgi_rsm_desc d;
    voxgi_rsm *rsm = NULL;
    static float pos[3 * S * S];
    double texel, R, worst = 0;
    int hi, a;
    floor_make(&F, 0, -1, 0);
    memset(&d, 0, sizeof d);
    d.size = S;
    d.samples = 65536;
    d.radius = 0.3f;
    d.seed = 11;
    TH_CHECK(voxgi_rsm_create(ctx, &F.scene, &d, &rsm) == VOXGI_OK && voxgi_rsm_texels(ctx, rsm, pos, NULL, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    texel = fabs((double)pos[3 * (S / 2 * S + S / 2 + 1)] - pos[3 * (S / 2 * S + S / 2)]) + fabs((double)pos[3 * (S / 2 * S + S / 2 + 1) + 2] - pos[3 * (S / 2 * S + S / 2) + 2]);
    R = 0.3 * S * texel;
    for (hi = 0; rsm && hi < 3; hi++) {
        float x[3] = {0, 0, 0}, n[3] = {0, -1, 0}, got[3];
        x[1] = (float)(height[hi] * R);
        TH_CHECK(voxgi_rsm_irradiance(ctx, rsm, NULL, VOXGI_TRAVERSAL_DDA, 1, x, n, got) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        for (a = 0; a < 3; a++) {
            double want = F.material.albedo[a] * R * R / (R * R + (double)x[1] * x[1]);
            worst = fmax(worst, fabs(got[a] - want) / want);
        }
    }
    printf("    a uniform floor seen from h = R / 2, R, 2 R over its centre (R = %.3f, texels %.4f wide): within %.2e of B R^2 / (R^2 + h^2)\n", R, texel, worst);
    TH_CHECK(worst < 0.015, "the gather over a uniform plane");
    voxgi_rsm_destroy(ctx, rsm);
    voxgi_destroy(ctx);
}

/* The flux of a reflective shadow map under a sun straight above the stack (ground 8 x 8 m and
   quads, all of albedo 0.5; irradiance 1) sums to 0.5 x 1 x 64, the power the scene reflects,
   within the map's border texels (a spot light's map: test_rsm_spot_flux). */
static void test_rsm_flux(void)
{
    enum { S = 63 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    stack_scene St;
    voxgi_rsm_desc d;
    voxgi_rsm *rsm = NULL;
    static float flux[3 * S * S];
    double total = 0;
    int i;
    stack_make(&St, 0.7f, 0.4f, 0, 0);
    memset(&d, 0, sizeof d);
    d.size = S;
    TH_CHECK(voxgi_rsm_create(ctx, &St.scene, &d, &rsm) == VOXGI_OK && voxgi_rsm_texels(ctx, rsm, NULL, NULL, flux) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (i = 0; i < S * S; i++) total += flux[3 * i];
    printf("    under the sun: reflected flux %.4f (the scene reflects 32)\n", total);
    TH_CHECK(fabs(total - 32) < 0.02 * 32, "the flux");
    voxgi_rsm_destroy(ctx, rsm);
    voxgi_destroy(ctx);
}

/* A closed box [-2, 2]^3 of albedo 0.5 (12 triangles, material 0) and, when `emitter`, a 0.5 m
   square at y = -1.9 facing up of emission 2 (material 1): a hemisphere map from any point on it
   meets the box in every texel. */
typedef struct box_scene {
    float pos[9 * 14];
    uint32_t mats[14];
    voxgi_material materials[2];
    voxgi_mesh mesh;
    voxgi_scene scene;
} box_scene;

static void box_make(box_scene *B, int emitter)
{
    static const int face[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    static const double corner[6][2] = {{-1, -1}, {-1, 1}, {1, 1}, {-1, -1}, {1, 1}, {1, -1}};
    size_t t = 0;
    int f, k, side;
    memset(B, 0, sizeof *B);
    for (f = 0; f < 3; f++)
        for (side = -1; side <= 1; side += 2) { /* the face at coordinate face[f][0] = 2 side */
            for (k = 0; k < 6; k++) {
                float *p = B->pos + 9 * t + 3 * (size_t)k;
                p[face[2 * f][0]] = (float)(2 * side);
                p[face[2 * f][1]] = (float)(2 * corner[k][0]);
                p[face[2 * f][2]] = (float)(2 * corner[k][1]);
            }
            t += 2;
        }
    if (emitter) t = put_quad(B->pos, B->mats, t, -1.9, 0.25, 1);
    B->materials[0].albedo[0] = B->materials[0].albedo[1] = B->materials[0].albedo[2] = 0.5f;
    B->materials[1] = B->materials[0];
    B->materials[1].emission[0] = B->materials[1].emission[1] = B->materials[1].emission[2] = 2;
    B->mesh.positions = B->pos;
    B->mesh.vertex_count = 3 * t;
    B->mesh.material_ids = B->mats;
    B->scene.meshes = &B->mesh;
    B->scene.mesh_count = 1;
    B->scene.materials = B->materials;
    B->scene.material_count = 2;
}

/* An area's points each map their hemisphere (the concentric map: every texel the same cosine-
   weighted solid angle), so the flux the box reflects is its albedo times all the area sends,
   pi L A: for the emitters and for a rectangular light of the same size and radiance. */
static void test_rsm_area_flux(void)
{
    enum { S = 63, POINTS = 4 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    static box_scene B;
    voxgi_light rect;
    voxgi_rsm_desc d;
    voxgi_rsm_info ri;
    static float flux[3 * S * S * POINTS];
    int pass;
    for (pass = 0; pass < 2; pass++) {
        voxgi_rsm *rsm = NULL;
        double total = 0, expect = 0.5 * PI * 2 * 0.25;
        int i;
        box_make(&B, pass == 0);
        memset(&d, 0, sizeof d);
        d.size = S;
        d.points = POINTS;
        if (pass == 0) d.emitters = 1;
        else {
            memset(&rect, 0, sizeof rect);
            rect.type = VOXGI_LIGHT_RECT;
            rect.position[0] = -0.25f; rect.position[1] = -1.9f; rect.position[2] = -0.25f;
            rect.edge_u[2] = 0.5f;
            rect.edge_v[0] = 0.5f; /* edge_u x edge_v faces up */
            rect.intensity[0] = rect.intensity[1] = rect.intensity[2] = 2;
            B.scene.lights = &rect;
            B.scene.light_count = 1;
        }
        TH_CHECK(voxgi_rsm_create(ctx, &B.scene, &d, &rsm) == VOXGI_OK && voxgi_rsm_texels(ctx, rsm, NULL, NULL, flux) == VOXGI_OK, "%s",
                 voxgi_last_error(ctx));
        voxgi_rsm_query(rsm, &ri);
        TH_CHECK(ri.maps == POINTS && ri.size == S, "maps %d, size %d", ri.maps, ri.size);
        for (i = 0; i < S * S * POINTS; i++) total += flux[3 * i];
        printf("    %s: reflected flux %.6f (albedo x pi L A = %.6f)\n", pass ? "rectangular light" : "emitters", total, expect);
        TH_CHECK(fabs(total - expect) < 1e-4 * expect, "the flux");
        voxgi_rsm_destroy(ctx, rsm);
    }
    d.emitters = 1; /* no emitters in the box now */
    B.scene.light_count = 0;
    TH_CHECK(voxgi_rsm_create(ctx, &B.scene, &d, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "out NULL");
    {
        voxgi_rsm *rsm = NULL;
        TH_CHECK(voxgi_rsm_create(ctx, &B.scene, &d, &rsm) == VOXGI_ERR_INVALID_ARGUMENT && !rsm, "a scene without emitters is refused");
    }
    voxgi_destroy(ctx);
}

/* A spot light at the centre of the closed box (albedo 0.5), pointing down, inner 0.3 and outer
   1.0 rad: every ray of its cone meets the box (floor and walls), so the map's flux is albedo I
   times the falloff's integral over the sphere, 2 pi (1 - (cos inner + cos outer) / 2) (the
   smoothstep in cos averages 1/2 across the band). The texels are the midpoint rule of that
   integral over the map's square (h = 2 tan(outer) / size across), and the smoothstep has no
   kink at either edge, so the error is O(h^2): held within h^2 / 24, the midpoint rule's term
   for a second derivative of 1 (1.0e-4 at 64 texels, 2.5e-5 at 128; measured 6.6e-7 and
   -2.5e-8). A texel's solid angle with one power of the distance too few gains the cone's mean
   1 / cos: +18% here. */
static void test_rsm_spot_flux(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    static box_scene B;
    static float flux[3 * 128 * 128];
    voxgi_light spot;
    voxgi_rsm_desc d;
    const double inner = 0.3, outer = 1.0, I = 3;
    double expect = 0.5 * I * 2 * PI * (1 - (cos(inner) + cos(outer)) / 2), err;
    int pass;
    box_make(&B, 0);
    memset(&spot, 0, sizeof spot);
    spot.type = VOXGI_LIGHT_SPOT;
    spot.direction[1] = -1;
    spot.intensity[0] = spot.intensity[1] = spot.intensity[2] = (float)I;
    spot.spot_inner = (float)inner;
    spot.spot_outer = (float)outer;
    B.scene.lights = &spot;
    B.scene.light_count = 1;
    for (pass = 0; pass < 2; pass++) {
        voxgi_rsm *rsm = NULL;
        int S = 64 << pass, i, lit = 0;
        double total = 0, h = 2 * tan(outer) / S;
        memset(&d, 0, sizeof d);
        d.size = S;
        TH_CHECK(voxgi_rsm_create(ctx, &B.scene, &d, &rsm) == VOXGI_OK && voxgi_rsm_texels(ctx, rsm, NULL, NULL, flux) == VOXGI_OK, "%s",
                 voxgi_last_error(ctx));
        for (i = 0; i < S * S; i++) {
            total += flux[3 * i];
            lit += flux[3 * i] > 0;
        }
        err = (total - expect) / expect;
        printf("    spot light, %d texels across (%d lit): reflected flux %.6f (albedo I x the falloff's solid angle = %.6f): %+.2e, bound h^2 / 24 = %.1e\n", S,
               lit, total, expect, err, h * h / 24);
        TH_CHECK(fabs(err) < h * h / 24, "the spot light's flux");
        TH_CHECK(lit > S * S / 2, "the cone's texels lit: %d", lit);
        voxgi_rsm_destroy(ctx, rsm);
    }
    voxgi_destroy(ctx);
}

/* Gathering at every fourth pixel and interpolating the rest changes the Cornell box's bounce by
   little while far fewer pixels gather. */
static void test_rsm_gather_stride(void)
{
    enum { W = 48 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene bs;
    voxgi_render_desc d;
    voxgi_render_info full, strided;
    static float a[3 * W * W], b[3 * W * W];
    double diff = 0, sum = 0;
    int i;
    TH_CHECK(voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    memset(&d, 0, sizeof d);
    d.method = VOXGI_RENDER_RSM;
    d.camera = bs.camera;
    d.camera.width = d.camera.height = W;
    d.rsm.maps.size = 64;
    d.rsm.visibility = VOXGI_TRAVERSAL_NONE;
    d.samples = 1;
    d.hide_emitters = 1;
    d.rsm.gather_stride = 1;
    TH_CHECK(voxgi_render(ctx, &bs.scene, &d, a, sizeof a, &full) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    d.rsm.gather_stride = 4;
    TH_CHECK(voxgi_render(ctx, &bs.scene, &d, b, sizeof b, &strided) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (i = 0; i < 3 * W * W; i++) { diff += fabs((double)a[i] - b[i]); sum += a[i]; }
    printf("    %lu of %lu pixels gather at stride 4 (%lu at 1); mean change %.3f%%\n", (unsigned long)strided.gathered, (unsigned long)(W * W),
           (unsigned long)full.gathered, 100 * diff / sum);
    TH_CHECK(full.gathered > 0.9 * W * W && strided.gathered < 0.6 * full.gathered, "gathers %lu and %lu", (unsigned long)full.gathered,
             (unsigned long)strided.gathered);
    TH_CHECK(diff < 0.04 * sum && diff > 0, "the interpolated image moved by %.3f%%", 100 * diff / sum);
    TH_CHECK(full.bytes > (size_t)full.maps * 64 * 64 * 36 && strided.bytes == full.bytes, "the maps' memory: %lu and %lu bytes for %d maps",
             (unsigned long)full.bytes, (unsigned long)strided.bytes, full.maps); /* each texel a position, a normal and a flux, no voxels */
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* The SH volume: a 1 m square of albedo 0.5 facing up under suns of irradiance E. Every cell sums
   the projection of albedo E A / pi max(0, n.w); the top cell holds albedo E A (Y00 pi, Y1 2 pi / 3 n)
   / pi exactly; far above, the estimator sees one point: albedo E A / pi (pi Y00^2 + 2 pi / 3
   Y1^2) / D^2 = 0.75 albedo E A / (pi D^2); two suns' volumes add cell by cell. */
static void test_sh_volume(void)
{
    const double Y0 = 0.28209479177387814, Y1 = 0.48860251190291992;
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    float pos[9 * 2];
    uint32_t mats[2];
    voxgi_material mat;
    voxgi_light suns[2];
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi_grid grid;
    voxgi_fit_desc fit;
    voxgi_sh_desc sd;
    voxgi_sh *sh[3] = {NULL, NULL, NULL};
    voxgi_sh_info si;
    float top[3][16], point[3] = {0, 100, 0}, down[3] = {0, -1, 0}, e[3];
    static float cells[3][16 * 8 * 8 * 8];
    int res[3], k, i;
    double E = 2 * 0.6, expect;
    memset(&mat, 0, sizeof mat);
    mat.albedo[0] = mat.albedo[1] = mat.albedo[2] = 0.5f;
    put_quad(pos, mats, 0, 0, 0.5, 0);
    memset(&mesh, 0, sizeof mesh);
    mesh.positions = pos;
    mesh.vertex_count = 6;
    memset(&sc, 0, sizeof sc);
    sc.meshes = &mesh;
    sc.mesh_count = 1;
    sc.materials = &mat;
    sc.material_count = 1;
    memset(suns, 0, sizeof suns);
    suns[0].type = suns[1].type = VOXGI_LIGHT_DIRECTIONAL;
    suns[0].direction[0] = 0.8f; suns[0].direction[1] = -0.6f; /* cos 0.6 */
    suns[0].intensity[0] = suns[0].intensity[1] = suns[0].intensity[2] = 2;
    suns[1].direction[1] = -1;
    suns[1].intensity[0] = 1; suns[1].intensity[1] = 0.5f; suns[1].intensity[2] = 0.25f;
    memset(&fit, 0, sizeof fit);
    fit.res = 8;
    memset(&sd, 0, sizeof sd);
    TH_CHECK(voxgi_fit_grid(ctx, &sc, &fit, &grid) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (k = 0; k < 3; k++) { /* sun 0, sun 1, both */
        sc.lights = suns + (k == 1);
        sc.light_count = k == 2 ? 2 : 1;
        TH_CHECK(voxgi_sh_create(ctx, &sc, &grid, &sd, &sh[k]) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        voxgi_sh_query(sh[k], &si);
        TH_CHECK(voxgi_sh_read(ctx, sh[k], si.levels - 1, top[k], sizeof top[k], res) == VOXGI_OK && res[0] == 1 && res[1] == 1 && res[2] == 1, "top");
        TH_CHECK(voxgi_sh_read(ctx, sh[k], 0, cells[k], sizeof cells[k], res) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    }
    printf("    top cell, red: %.6f %.6f %.6f %.6f (expected %.6f %.6f 0 0)\n", top[0][0], top[0][1], top[0][2], top[0][3], 0.5 * E * Y0,
           0.5 * E / PI * 2 * PI / 3 * Y1);
    for (i = 0; i < 3; i++) {
        TH_CHECK(fabs(top[0][4 * i] - 0.5 * E * Y0) < 1e-3 * 0.5 * E * Y0, "Y00");
        TH_CHECK(fabs(top[0][4 * i + 1] - 0.5 * E / PI * 2 * PI / 3 * Y1) < 1e-3 * 0.5 * E * Y1, "Y1-1 (y)");
        TH_CHECK(fabs(top[0][4 * i + 2]) < 1e-6 && fabs(top[0][4 * i + 3]) < 1e-6, "Y10, Y11");
    }
    TH_CHECK(voxgi_sh_irradiance(ctx, sh[0], NULL, VOXGI_TRAVERSAL_DDA, 0, 1, point, down, e) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    expect = 0.75 * 0.5 * E / (PI * 100.0 * 100.0);
    printf("    irradiance 100 m above: %.9g (expected %.9g)\n", e[0], expect);
    TH_CHECK(fabs(e[0] - expect) < 1e-3 * expect && fabs(e[1] - e[0]) < 1e-6 * expect, "the far irradiance");
    for (i = 0; i < 16 * 8 * 8 * 8; i++) { /* coefficients add; the centroids' weights too */
        double sum = (double)cells[0][i] + cells[1][i];
        TH_CHECK(fabs(cells[2][i] - sum) <= 1e-6 * (fabs(sum) + 1e-3), "cell value %d: %g, not %g + %g", i, cells[2][i], cells[0][i], cells[1][i]);
    }
    TH_CHECK(voxgi_sh_irradiance(ctx, sh[0], NULL, VOXGI_TRAVERSAL_DDA, -1, 1, point, down, e) == VOXGI_ERR_INVALID_ARGUMENT, "opening -1");
    TH_CHECK(voxgi_sh_read(ctx, sh[0], 99, NULL, 0, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "level 99");
    for (k = 0; k < 3; k++) voxgi_sh_destroy(ctx, sh[k]);
    voxgi_destroy(ctx);
}

/* An SH image of the Cornell box: the bounce lights the ceiling, which direct light leaves black,
   to the reference's one bounce within the method's known loss (a coarse bound). */
static void test_sh_image(void)
{
    enum { W = 32 };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene bs;
    voxgi_render_desc d, rd;
    voxgi_render_info info;
    static float img[3 * W * W], ref[3 * W * W];
    double a = 0, b = 0;
    int x, y;
    TH_CHECK(voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    memset(&d, 0, sizeof d);
    d.method = VOXGI_RENDER_SH;
    d.camera = bs.camera;
    d.camera.width = d.camera.height = W;
    d.samples = 4;
    d.hide_emitters = 1;
    TH_CHECK(voxgi_render(ctx, &bs.scene, &d, img, sizeof img, &info) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    memset(&rd, 0, sizeof rd);
    rd.method = VOXGI_RENDER_REFERENCE;
    rd.camera = d.camera;
    rd.samples = 256;
    rd.bounces = 1;
    rd.hide_emitters = 1;
    TH_CHECK(voxgi_render(ctx, &bs.scene, &rd, ref, sizeof ref, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    for (y = 0; y < 3; y++) /* the ceiling's rows, away from the light */
        for (x = 2; x < 8; x++) { a += img[3 * (y * W + x) + 1]; b += ref[3 * (y * W + x) + 1]; }
    printf("    ceiling (green): SH %.4f, reference %.4f; %lu bytes\n", a, b, (unsigned long)info.bytes);
    TH_CHECK(info.bytes > (size_t)64 * 60 * 60 * 60, "the SH volume's memory: %lu bytes", (unsigned long)info.bytes); /* 64 bytes a cell of a grid 64 across */
    TH_CHECK(a > 0.4 * b && a < 1.2 * b, "the ceiling's bounce"); /* measured 0.67: L1 sends 0.75 of the light along a normal */
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* Bad input to the reflective shadow maps and the SH volume: refused with the right result and
   nothing made; degenerate input (no lights, one voxel, a point far outside) answered. */
static void test_bounce_input(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    stack_scene S;
    voxgi_rsm_desc d;
    voxgi_rsm *rsm = NULL;
    voxgi_sh_desc sd;
    voxgi_sh *sh = NULL;
    voxgi_sh_info si;
    voxgi_grid grid, small;
    voxgi_fit_desc fit;
    voxgi_voxels *vox = NULL;
    voxgi_voxelize_desc vd;
    voxgi_render_desc hd, qd;
    float p[3] = {0, NAN, 0}, q[3] = {0, 0.5f, 0}, far[3] = {1e30f, 0, 0}, up[3] = {0, 1, 0}, e[3], img[3 * 4 * 4];
    stack_make(&S, 0.7f, 0.4f, 0, 0);
    memset(&d, 0, sizeof d);
    d.size = 16;
    S.sun.type = VOXGI_LIGHT_POINT;
    TH_CHECK(voxgi_rsm_create(ctx, &S.scene, &d, &rsm) == VOXGI_ERR_UNSUPPORTED && !rsm, "a point light");
    S.sun.type = VOXGI_LIGHT_DIRECTIONAL;
    d.points = -1;
    TH_CHECK(voxgi_rsm_create(ctx, &S.scene, &d, &rsm) == VOXGI_ERR_INVALID_ARGUMENT && !rsm, "points -1");
    d.points = 0;
    d.radius = 2.5f;
    TH_CHECK(voxgi_rsm_create(ctx, &S.scene, &d, &rsm) == VOXGI_ERR_INVALID_ARGUMENT && !rsm, "radius 2.5");
    d.radius = NAN;
    TH_CHECK(voxgi_rsm_create(ctx, &S.scene, &d, &rsm) == VOXGI_ERR_INVALID_ARGUMENT && !rsm, "radius NaN");
    d.radius = 0;
    d.emitters = 1;
    TH_CHECK(voxgi_rsm_create(ctx, &S.scene, &d, &rsm) == VOXGI_ERR_INVALID_ARGUMENT && !rsm, "no emitters");
    d.emitters = 0;
    TH_CHECK(voxgi_rsm_create(ctx, &S.scene, &d, &rsm) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    TH_CHECK(voxgi_rsm_irradiance(ctx, rsm, NULL, VOXGI_TRAVERSAL_DDA, 1, p, up, e) == VOXGI_ERR_INVALID_ARGUMENT, "a NaN point");
    TH_CHECK(voxgi_rsm_irradiance(ctx, rsm, NULL, VOXGI_TRAVERSAL_DDA, 1, far, up, e) == VOXGI_OK && e[0] == 0, "a point far outside: %g", e[0]);
    voxgi_rsm_destroy(ctx, rsm);

    memset(&sd, 0, sizeof sd);
    memset(&fit, 0, sizeof fit);
    fit.res = 16;
    TH_CHECK(voxgi_fit_grid(ctx, &S.scene, &fit, &grid) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    small = grid;
    small.voxel_size = -1;
    TH_CHECK(voxgi_sh_create(ctx, &S.scene, &small, &sd, &sh) == VOXGI_ERR_INVALID_GRID && !sh, "a negative voxel size");
    small = grid;
    small.res[0] = small.res[1] = small.res[2] = 1000000;
    TH_CHECK(voxgi_sh_create(ctx, &S.scene, &small, &sd, &sh) != VOXGI_OK && !sh, "a grid of 10^18 voxels");
    sd.samples = -2;
    TH_CHECK(voxgi_sh_create(ctx, &S.scene, &grid, &sd, &sh) == VOXGI_ERR_INVALID_ARGUMENT && !sh, "samples -2");
    sd.samples = 0;
    small = grid; /* one voxel holding everything */
    small.res[0] = small.res[1] = small.res[2] = 1;
    small.voxel_size = 16 * grid.voxel_size;
    TH_CHECK(voxgi_sh_create(ctx, &S.scene, &small, &sd, &sh) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    voxgi_sh_query(sh, &si);
    TH_CHECK(si.levels == 1 && si.voxels == 1, "one voxel: %d levels, %lu voxels", si.levels, (unsigned long)si.voxels);
    voxgi_sh_destroy(ctx, sh);
    sh = NULL;
    S.scene.light_count = 0; /* no light: a volume of zeros, no bounce */
    TH_CHECK(voxgi_sh_create(ctx, &S.scene, &grid, &sd, &sh) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    TH_CHECK(voxgi_sh_irradiance(ctx, sh, NULL, VOXGI_TRAVERSAL_DDA, 0, 1, q, up, e) == VOXGI_OK && e[0] == 0 && e[1] == 0 && e[2] == 0, "no light");
    TH_CHECK(voxgi_sh_irradiance(ctx, sh, NULL, VOXGI_TRAVERSAL_DDA, 0, 1, p, up, e) == VOXGI_ERR_INVALID_ARGUMENT, "a NaN point");
    TH_CHECK(voxgi_sh_irradiance(ctx, sh, NULL, (voxgi_traversal)7, 0, 1, q, up, e) == VOXGI_ERR_INVALID_ARGUMENT, "traversal 7");
    memset(&vd, 0, sizeof vd);
    vd.grid = grid;
    vd.grid.res[0]++;
    TH_CHECK(voxgi_voxelize(ctx, &S.scene, &vd, &vox) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    TH_CHECK(voxgi_sh_irradiance(ctx, sh, vox, VOXGI_TRAVERSAL_DDA, 0, 1, q, up, e) == VOXGI_ERR_INVALID_ARGUMENT, "voxels on another grid");
    voxgi_voxels_destroy(ctx, vox);
    voxgi_sh_destroy(ctx, sh);
    S.scene.light_count = 1;

    memset(&hd, 0, sizeof hd);
    hd.method = VOXGI_RENDER_SH;
    hd.camera.eye[1] = 5;
    hd.camera.fovy_degrees = 40;
    hd.camera.eye[2] = 0.1;
    hd.camera.width = hd.camera.height = 4;
    hd.sh.opening = 9;
    TH_CHECK(voxgi_render(ctx, &S.scene, &hd, img, sizeof img, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "opening 9");
    hd.sh.opening = 0;
    TH_CHECK(voxgi_render(ctx, &S.scene, &hd, img, sizeof img - 4, NULL) == VOXGI_ERR_BUFFER_TOO_SMALL, "a short buffer");
    memset(&qd, 0, sizeof qd);
    qd.method = VOXGI_RENDER_RSM;
    qd.camera = hd.camera;
    qd.rsm.gather_stride = 65;
    TH_CHECK(voxgi_render(ctx, &S.scene, &qd, img, sizeof img, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "stride 65");
    qd.rsm.gather_stride = 0;
    qd.rsm.visibility = (voxgi_traversal)5;
    TH_CHECK(voxgi_render(ctx, &S.scene, &qd, img, sizeof img, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "visibility 5");
    voxgi_destroy(ctx);
}

/* The gathers on GL (in float) against the CPU's (in double) at the Cornell box's surfaces, with
   and without voxels: every point within 1e-4 of the CPU's (relative to the larger of its value
   and the mean), but for a few where a segment grazes a voxel's corner and the traversals in
   float and double part ways (at most 0.5%), and the sums within 1e-5. */
static void test_bounce_gl_equals_cpu(void)
{
    enum { W = 32, N = W * W };
    voxgi_context *ctx[2];
    voxgi_builtin_scene bs;
    voxgi_camera cam;
    static float pos[3 * N], nrm[3 * N], irr[2][3 * N];
    uint32_t tri[N];
    int method, vis, b;
    if (!have_gl()) return;
    ctx[0] = make_ctx(VOXGI_BACKEND_CPU, 0);
    ctx[1] = make_ctx(VOXGI_BACKEND_GL, 0);
    TH_CHECK(voxgi_builtin_scene_create(ctx[0], "cornell-box", &bs) == VOXGI_OK, "%s", voxgi_last_error(ctx[0]));
    cam = bs.camera;
    cam.width = cam.height = W;
    TH_CHECK(voxgi_gbuffer_render(ctx[0], &bs.scene, &cam, pos, nrm, tri) == VOXGI_OK, "%s", voxgi_last_error(ctx[0]));
    for (method = 0; method < 2; method++)
        for (vis = 0; vis < 3; vis++) { /* hierarchical, DDA, none */
            double sum[2] = {0, 0}, mean;
            size_t i, off = 0, n = 0;
            for (b = 0; b < 2; b++) {
                voxgi_voxelize_desc vd;
                voxgi_fit_desc fit;
                voxgi_voxels *vox = NULL;
                memset(&vd, 0, sizeof vd);
                memset(&fit, 0, sizeof fit);
                fit.res = 24;
                TH_CHECK(voxgi_fit_grid(ctx[b], &bs.scene, &fit, &vd.grid) == VOXGI_OK && voxgi_voxelize(ctx[b], &bs.scene, &vd, &vox) == VOXGI_OK, "%s",
                         voxgi_last_error(ctx[b]));
                if (method == 0) {
                    voxgi_rsm_desc d;
                    voxgi_rsm *rsm = NULL;
                    memset(&d, 0, sizeof d);
                    d.emitters = 1;
                    d.size = 64;
                    d.samples = 64;
                    TH_CHECK(voxgi_rsm_create(ctx[b], &bs.scene, &d, &rsm) == VOXGI_OK &&
                                 voxgi_rsm_irradiance(ctx[b], rsm, vis == 2 ? NULL : vox, vis ? VOXGI_TRAVERSAL_DDA : VOXGI_TRAVERSAL_HIERARCHICAL, N, pos, nrm,
                                                      irr[b]) == VOXGI_OK,
                             "rsm: %s", voxgi_last_error(ctx[b]));
                    voxgi_rsm_destroy(ctx[b], rsm);
                } else {
                    voxgi_sh_desc d;
                    voxgi_sh *sh = NULL;
                    memset(&d, 0, sizeof d);
                    TH_CHECK(voxgi_sh_create(ctx[b], &bs.scene, &vd.grid, &d, &sh) == VOXGI_OK &&
                                 voxgi_sh_irradiance(ctx[b], sh, vis == 2 ? NULL : vox, vis ? VOXGI_TRAVERSAL_DDA : VOXGI_TRAVERSAL_HIERARCHICAL, 0, N, pos, nrm,
                                                     irr[b]) == VOXGI_OK,
                             "sh: %s", voxgi_last_error(ctx[b]));
                    voxgi_sh_destroy(ctx[b], sh);
                }
                voxgi_voxels_destroy(ctx[b], vox);
            }
            for (i = 0; i < N; i++) {
                if (tri[i] == UINT32_MAX) continue;
                n++;
                sum[0] += irr[0][3 * i + 1];
                sum[1] += irr[1][3 * i + 1];
            }
            mean = n ? sum[0] / (double)n : 0;
            for (i = 0; i < N; i++)
                if (tri[i] != UINT32_MAX && fabs((double)irr[0][3 * i + 1] - irr[1][3 * i + 1]) > 1e-4 * fmax(fabs((double)irr[0][3 * i + 1]), mean)) off++;
            printf("    %s, %s: %lu of %lu points off by more than 1e-4; sums %.6f and %.6f\n", method ? "sh" : "rsm", vis == 0 ? "hierarchical" : vis == 1 ? "dda" : "no visibility",
                   (unsigned long)off, (unsigned long)n, sum[0], sum[1]);
            TH_CHECK(n > N / 2 && sum[0] > 0, "points seen");
            TH_CHECK(off <= n / 200, "%lu points differ", (unsigned long)off);
            TH_CHECK(fabs(sum[0] - sum[1]) <= 1e-5 * sum[0], "the sums differ");
        }
    voxgi_builtin_scene_destroy(ctx[0], &bs);
    voxgi_destroy(ctx[0]);
    voxgi_destroy(ctx[1]);
}

int main(void)
{
    gl_open();
    TH_RUN(test_tsm_layers);
    TH_RUN(test_tsm_spot_layers);
    TH_RUN(test_tsm_materials_and_opaque);
    TH_RUN(test_tsm_normal_offset);
    TH_RUN(test_tsm_gl_equals_cpu);
    TH_RUN(test_reference_sees_through_leaves);
    TH_RUN(test_tsm_image_equals_reference);
    TH_RUN(test_tsm_input);
    TH_RUN(test_rsm_walls);
    TH_RUN(test_rsm_point_source);
    TH_RUN(test_rsm_uniform_plane);
    TH_RUN(test_rsm_flux);
    TH_RUN(test_rsm_area_flux);
    TH_RUN(test_rsm_spot_flux);
    TH_RUN(test_rsm_gather_stride);
    TH_RUN(test_sh_volume);
    TH_RUN(test_sh_image);
    TH_RUN(test_bounce_input);
    TH_RUN(test_bounce_gl_equals_cpu);
    gl_close();
    return th_finish();
}
