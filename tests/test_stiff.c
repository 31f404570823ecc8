/* Stiff and extreme input, one test per case, each with what is expected (docs/stiff-cases.md
   has the table): a large world through double positions; every method's image under scaling;
   degenerate, needle and sliver triangles; an empty scene; the furnace at albedo 0 to 0.999;
   emission over twelve orders; lights outside a closed box. */
#include "../voxgi.h"
#include "fixtures.h"

/* The built-in scene's meshes as doubles moved by `offset` (world units), in *out (meshes and
   positions malloc'd: free with moved_free), the origin set to `origin`. */
typedef struct moved_scene {
    voxgi_scene scene;
    voxgi_mesh *meshes;
    double **pos;
} moved_scene;

static void moved_free(moved_scene *m)
{
    size_t i;
    for (i = 0; m->pos && i < m->scene.mesh_count; i++) free(m->pos[i]);
    free(m->pos);
    free(m->meshes);
}

static int moved_make(const voxgi_scene *src, double offset, double origin, moved_scene *m)
{
    size_t i, v;
    int a;
    memset(m, 0, sizeof *m);
    m->scene = *src;
    m->meshes = (voxgi_mesh *)calloc(src->mesh_count, sizeof *m->meshes);
    m->pos = (double **)calloc(src->mesh_count, sizeof *m->pos);
    if (!m->meshes || !m->pos) return 0;
    for (i = 0; i < src->mesh_count; i++) {
        const voxgi_mesh *s = &src->meshes[i];
        m->meshes[i] = *s;
        if (!(m->pos[i] = (double *)malloc(3 * s->vertex_count * sizeof(double) + 1))) return 0;
        for (v = 0; v < s->vertex_count; v++) {
            const float *p = (const float *)(const void *)((const char *)s->positions + v * (s->position_stride ? s->position_stride : 12));
            for (a = 0; a < 3; a++) m->pos[i][3 * v + (size_t)a] = (double)p[a] + offset;
        }
        m->meshes[i].positions = NULL;
        m->meshes[i].position_stride = 0;
        m->meshes[i].positions_double = m->pos[i];
    }
    m->scene.meshes = m->meshes;
    for (a = 0; a < 3; a++) m->scene.origin[a] = origin;
    return 1;
}

static void test_large_world(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene bs;
    moved_scene far;
    voxgi_voxelize_desc vd;
    voxgi_fit_desc fit;
    voxgi_voxels_info i0, i1;
    voxgi_reference_desc rd;
    uint32_t *b0 = NULL, *b1 = NULL;
    static float img0[3 * 16 * 16], img1[3 * 16 * 16];
    float ceiling = -1, light = -1;
    size_t v;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "cornell-box");
    TH_CHECK(moved_make(&bs.scene, 1e6, 1e6, &far), "out of memory");
    /* the gap in float32 at 1e6: the light's and the ceiling's heights (the largest y of the scene
       and the light's, 0.1 mm apart) round to the same float */
    for (v = 0; v < bs.scene.meshes[0].vertex_count; v++) ceiling = fmaxf(ceiling, bs.scene.meshes[0].positions[3 * v + 1]);
    light = ceiling - 1e-4f;
    TH_CHECK((float)(1e6 + ceiling) == (float)(1e6 + (double)light) && (float)ceiling != light,
             "float32 keeps the gap at 1e6 (%.9g against %.9g): the case is moot", (double)(float)(1e6 + ceiling), (double)(float)(1e6 + (double)light));
    memset(&vd, 0, sizeof vd);
    memset(&fit, 0, sizeof fit);
    fit.res = 48;
    TH_CHECK(voxgi_fit_grid(ctx, &bs.scene, &fit, &vd.grid) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    b0 = voxelized_bits(ctx, &bs.scene, &vd, &i0);
    TH_CHECK(voxgi_fit_grid(ctx, &far.scene, &fit, &vd.grid) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    b1 = voxelized_bits(ctx, &far.scene, &vd, &i1);
    TH_CHECK(b0 && b1 && i0.voxel_count == i1.voxel_count && i0.bytes == i1.bytes && !memcmp(b0, b1, i0.bytes), "voxels at 1e6: %lu against %lu",
             (unsigned long)i1.voxel_count, (unsigned long)i0.voxel_count);
    memset(&rd, 0, sizeof rd);
    rd.camera = bs.camera;
    rd.camera.width = rd.camera.height = 16;
    rd.samples = 4;
    rd.bounces = 1;
    rd.seed = 5;
    TH_CHECK(voxgi_reference_render(ctx, &bs.scene, &rd, img0, sizeof img0, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    TH_CHECK(voxgi_reference_render(ctx, &far.scene, &rd, img1, sizeof img1, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    TH_CHECK(!memcmp(img0, img1, sizeof img0), "the image at 1e6 differs from the image at the origin");
    { /* bad input: both kinds of positions, a stride shorter than three doubles, an origin that leaves floats behind */
        voxgi_mesh keep = far.meshes[0];
        far.meshes[0].positions = bs.scene.meshes[0].positions;
        TH_CHECK(voxgi_validate_scene(ctx, &far.scene) == VOXGI_ERR_INVALID_SCENE, "both positions accepted");
        far.meshes[0] = keep;
        far.meshes[0].position_stride = 12;
        TH_CHECK(voxgi_validate_scene(ctx, &far.scene) == VOXGI_ERR_INVALID_SCENE, "a 12-byte stride of doubles accepted");
        far.meshes[0] = keep;
        far.scene.origin[1] = -1e300;
        TH_CHECK(voxgi_validate_scene(ctx, &far.scene) == VOXGI_ERR_INVALID_SCENE, "a vertex beyond float in the frame accepted");
        far.scene.origin[1] = NAN;
        TH_CHECK(voxgi_validate_scene(ctx, &far.scene) == VOXGI_ERR_INVALID_SCENE, "a NaN origin accepted");
        printf("    the last error: %s\n", voxgi_last_error(ctx));
    }
    free(b0);
    free(b1);
    moved_free(&far);
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* The scene scaled by k about the origin (meshes, lights: positions and edges; point and spot
   lights' intensity by k^2, so that irradiance stays): free with scaled_free. */
typedef struct scaled_scene {
    voxgi_scene scene;
    voxgi_mesh *meshes;
    float **pos;
    voxgi_light *lights;
} scaled_scene;

static void scaled_free(scaled_scene *m)
{
    size_t i;
    for (i = 0; m->pos && i < m->scene.mesh_count; i++) free(m->pos[i]);
    free(m->pos);
    free(m->meshes);
    free(m->lights);
}

static int scaled_make(const voxgi_scene *src, double k, scaled_scene *m)
{
    size_t i, v;
    int a;
    memset(m, 0, sizeof *m);
    m->scene = *src;
    m->meshes = (voxgi_mesh *)calloc(src->mesh_count + 1, sizeof *m->meshes);
    m->pos = (float **)calloc(src->mesh_count + 1, sizeof *m->pos);
    m->lights = (voxgi_light *)calloc(src->light_count + 1, sizeof *m->lights);
    if (!m->meshes || !m->pos || !m->lights) return 0;
    for (i = 0; i < src->mesh_count; i++) {
        const voxgi_mesh *s = &src->meshes[i];
        m->meshes[i] = *s;
        if (!(m->pos[i] = (float *)malloc(12 * s->vertex_count + 1))) return 0;
        for (v = 0; v < s->vertex_count; v++) {
            const float *p = (const float *)(const void *)((const char *)s->positions + v * (s->position_stride ? s->position_stride : 12));
            for (a = 0; a < 3; a++) m->pos[i][3 * v + (size_t)a] = (float)(p[a] * k);
        }
        m->meshes[i].positions = m->pos[i];
        m->meshes[i].position_stride = 0;
    }
    for (i = 0; i < src->light_count; i++) {
        voxgi_light L = src->lights[i];
        for (a = 0; a < 3; a++) {
            L.position[a] = (float)(L.position[a] * k);
            L.edge_u[a] = (float)(L.edge_u[a] * k);
            L.edge_v[a] = (float)(L.edge_v[a] * k);
            if (L.type == VOXGI_LIGHT_POINT || L.type == VOXGI_LIGHT_SPOT) L.intensity[a] = (float)(L.intensity[a] * k * k);
        }
        m->lights[i] = L;
    }
    m->scene.meshes = m->meshes;
    m->scene.lights = m->lights;
    return 1;
}

enum { IMG = 16, METHODS = 10 };
static const char *const method_names[METHODS] = {"reference", "vct", "tsm", "rsm", "sh", "ssgi", "hybrid", "ssao", "vao", "linespace"};

/* Method m's 16 x 16 image of sc through cam (small settings, seed 3) into rgb: 1 on success. */
static int image_of(voxgi_context *ctx, int m, const voxgi_scene *sc, voxgi_camera cam, float *rgb)
{
    size_t bytes = sizeof(float) * 3 * IMG * IMG;
    voxgi_result r = VOXGI_ERR_INVALID_ARGUMENT;
    cam.width = cam.height = IMG;
    if (m == 0) {
        voxgi_reference_desc d;
        memset(&d, 0, sizeof d);
        d.camera = cam; d.samples = 4; d.bounces = 1; d.seed = 3;
        r = voxgi_reference_render(ctx, sc, &d, rgb, bytes, NULL);
    } else if (m == 1) {
        voxgi_vct_desc d;
        memset(&d, 0, sizeof d);
        d.camera = cam; d.resolution = 16; d.cones.cones = 4; d.samples = 4; d.seed = 3;
        r = voxgi_vct_render(ctx, sc, &d, rgb, bytes, NULL);
    } else if (m == 2) {
        voxgi_tsm_image_desc d;
        memset(&d, 0, sizeof d);
        d.camera = cam; d.tsm.size = 64; d.seed = 3;
        r = voxgi_tsm_render(ctx, sc, &d, rgb, bytes, NULL);
    } else if (m == 3) {
        voxgi_rsm_image_desc d;
        memset(&d, 0, sizeof d);
        d.camera = cam; d.rsm.size = 32; d.resolution = 16; d.samples = 4; d.seed = 3;
        r = voxgi_rsm_render(ctx, sc, &d, rgb, bytes, NULL);
    } else if (m == 4) {
        voxgi_sh_image_desc d;
        memset(&d, 0, sizeof d);
        d.camera = cam; d.resolution = 16; d.samples = 4; d.seed = 3;
        r = voxgi_sh_render(ctx, sc, &d, rgb, bytes, NULL);
    } else if (m == 5 || m == 6) {
        voxgi_ssgi_image_desc d;
        memset(&d, 0, sizeof d);
        d.camera = cam; d.method = m == 6 ? VOXGI_AO_VOXELS : VOXGI_AO_SCREEN; d.resolution = 16; d.rays = 4; d.steps = 4; d.samples = 4; d.seed = 3;
        r = voxgi_ssgi_render(ctx, sc, &d, rgb, bytes, NULL);
    } else if (m == 7 || m == 8) {
        voxgi_ao_image_desc d;
        memset(&d, 0, sizeof d);
        d.camera = cam; d.method = m == 8 ? VOXGI_AO_VOXELS : VOXGI_AO_SCREEN; d.resolution = 16; d.rays = 4; d.steps = 4; d.seed = 3;
        r = voxgi_ao_render(ctx, sc, &d, rgb, bytes, NULL);
    } else {
        voxgi_linespace_image_desc d;
        memset(&d, 0, sizeof d);
        d.camera = cam; d.samples = 4; d.seed = 3;
        r = voxgi_linespace_render(ctx, sc, &d, rgb, bytes, NULL, NULL);
    }
    if (r != VOXGI_OK) printf("    %s: %s\n", method_names[m], voxgi_last_error(ctx));
    return r == VOXGI_OK;
}

/* Every method's image of the Cornell box (its light an emissive quad: radiance, the same at any
   scale) scaled by powers of two (2^20, 2^-20: every float product exact) equals the unscaled
   image bit for bit: nothing in voxgi holds an absolute length. Scaled by 1e6, 1e-6 and 1e3 the
   geometry rounds differently, and the images agree to rounding (relative RMS difference under
   1e-3; measured at most 3e-4). */
static void test_scale_invariance(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene bs;
    static const double scales[5] = {1048576.0, 1.0 / 1048576.0, 1e6, 1e-6, 1e3};
    static float base[3 * IMG * IMG], img[3 * IMG * IMG];
    int m, k, a;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "cornell-box");
    for (m = 0; m < METHODS; m++) {
        if (!image_of(ctx, m, &bs.scene, bs.camera, base)) { TH_CHECK(0, "%s at scale 1", method_names[m]); continue; }
        for (k = 0; k < 5; k++) {
            scaled_scene sc;
            voxgi_camera cam = bs.camera;
            double diff2 = 0, mean = 0, rel;
            size_t i;
            for (a = 0; a < 3; a++) { cam.eye[a] *= scales[k]; cam.target[a] *= scales[k]; }
            TH_CHECK(scaled_make(&bs.scene, scales[k], &sc), "out of memory");
            TH_CHECK(image_of(ctx, m, &sc.scene, cam, img), "%s at scale %g", method_names[m], scales[k]);
            for (i = 0; i < 3 * IMG * IMG; i++) {
                diff2 += ((double)img[i] - base[i]) * ((double)img[i] - base[i]);
                mean += base[i] / (3.0 * IMG * IMG);
            }
            rel = sqrt(diff2 / (3.0 * IMG * IMG)) / mean;
            if (k < 2) TH_CHECK(!memcmp(img, base, sizeof img), "%s scaled by %g: not the same image (relative RMS difference %.3g)", method_names[m], scales[k], rel);
            else TH_CHECK(rel < 1e-3, "%s scaled by %g: relative RMS difference %.3g", method_names[m], scales[k], rel);
            if (k == 2) printf("    %-9s 1e6: relative RMS difference %.2g\n", method_names[m], rel);
            scaled_free(&sc);
        }
    }
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* Whether every value is finite; their mean into *mean. */
static int all_finite(const float *v, size_t n, double *mean)
{
    size_t i;
    *mean = 0;
    for (i = 0; i < n; i++) {
        if (!isfinite(v[i])) return 0;
        *mean += v[i] / (double)n;
    }
    return 1;
}

/* A built-in scene with up to 16 more triangles (a mesh of their own, all of material `mat`) and
   its materials copied into S->mats (up to 32), for a test to change. */
typedef struct stiff_scene {
    voxgi_scene scene;
    voxgi_mesh meshes[8];
    voxgi_material mats[32];
    float extra[9 * 16];
    uint32_t extra_mat[16];
} stiff_scene;

static void stiff_add(stiff_scene *S, const voxgi_scene *base, const float *tris, int count, uint32_t mat)
{
    int i;
    TH_CHECK(base->mesh_count < 8 && base->material_count < 32 && count <= 16, "the scene is too big for a stiff_scene");
    S->scene = *base;
    memcpy(S->meshes, base->meshes, base->mesh_count * sizeof *S->meshes);
    memcpy(S->mats, base->materials, base->material_count * sizeof *S->mats);
    if (count) memcpy(S->extra, tris, 9 * (size_t)count * sizeof(float));
    memset(&S->meshes[base->mesh_count], 0, sizeof S->meshes[0]);
    S->meshes[base->mesh_count].positions = S->extra;
    S->meshes[base->mesh_count].vertex_count = 3 * (size_t)count;
    for (i = 0; i < count; i++) S->extra_mat[i] = mat;
    S->meshes[base->mesh_count].material_ids = S->extra_mat;
    S->scene.meshes = S->meshes;
    S->scene.mesh_count = base->mesh_count + (count > 0);
    S->scene.materials = S->mats;
    S->scene.material_count = base->material_count;
}

/* Needle, sliver, segment and point triangles in the Cornell box: every method gives an image of
   finite values. The segment and the points have no area: the methods that see the scene through
   rays or rasterized maps give the box's image bit for bit; the voxel methods set the voxels a
   segment or a point touches, as the exact definition says, and may differ a little. */
static void test_degenerate_triangles(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene bs;
    stiff_scene S;
    static float base[3 * IMG * IMG], img[3 * IMG * IMG];
    static const float tris[9 * 5] = {
        0.2f, 0.3f, 0.3f, 0.3f, 0.3f, 0.3f, 0.25f, 0.3f, 0.3f,                 /* a segment */
        0.3f, 0.3f, 0.3f, 0.3f, 0.3f, 0.3f, 0.3f, 0.3f, 0.3f,                  /* a point */
        0.1f, 0.1f, 0.1f, 0.1f, 0.1f, 0.1f, 0.1f, 0.1f, 0.1f,                  /* another */
        0.1f, 0.1f, 0.2f, 0.4f, 0.1f, 0.2f, 0.25f, 0.1f + 1e-7f, 0.2f,          /* a needle: 0.3 long, 1e-7 wide */
        0.1f, 0.2f, 0.3f, 0.2f, 0.2f + 1e-9f, 0.3f, 0.3f, 0.2f, 0.3f};         /* a sliver: three points all but on a line */
    static const int exact[METHODS] = {1, 0, 1, 0, 0, 1, 0, 1, 1, 1}; /* no voxels in the image */
    int m, k;
    double mean = 0;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "cornell-box");
    for (m = 0; m < METHODS; m++) {
        TH_CHECK(image_of(ctx, m, &bs.scene, bs.camera, base), "%s", method_names[m]);
        for (k = 0; k < 2; k++) {
            stiff_add(&S, &bs.scene, tris, k ? 5 : 3, 0);
            TH_CHECK(image_of(ctx, m, &S.scene, bs.camera, img) && all_finite(img, 3 * IMG * IMG, &mean), "%s with %s: not finite", method_names[m],
                     k ? "needles and slivers" : "a segment and points");
            if (!k && exact[m]) TH_CHECK(!memcmp(img, base, sizeof img), "%s: a segment and points changed the image", method_names[m]);
        }
    }
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* A scene without triangles: every method refuses it (VOXGI_ERR_INVALID_SCENE, "no triangles"):
   the scene's bounds size every grid, map and line space. */
static void test_empty_scene(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene bs;
    voxgi_scene empty;
    static float img[3 * IMG * IMG];
    int m;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "cornell-box");
    memset(&empty, 0, sizeof empty);
    for (m = 0; m < METHODS; m++) {
        voxgi_result r;
        TH_CHECK(!image_of(ctx, m, &empty, bs.camera, img), "%s rendered an empty scene", method_names[m]);
        r = voxgi_validate_scene(ctx, &empty);
        TH_CHECK(strstr(voxgi_last_error(ctx), "no triangles") != NULL, "%s: %s (%s)", method_names[m], voxgi_last_error(ctx), voxgi_result_string(r));
    }
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* The furnace (a closed sphere of emission 1 seen from inside) at albedo 0, 0.5 and 0.999: the
   radiance is 1 / (1 - albedo) everywhere. The path tracer (all bounces, 4 samples per pixel):
   exactly 1 at 0, within its noise at 0.5 (3%; measured 1.5%) and 0.999 (5%: 1000, measured
   1006); cone tracing with every
   bounce (32^3) within 1% at 0.5 and 15% at 0.999 (measured 920: the cones lose about 0.1% of
   the light a bounce, which a thousand bounces compound; without the bounces' geometric tail,
   64 bounces gave 58). No value is NaN or infinite. */
static void test_furnace_albedo(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene fu;
    stiff_scene S;
    static float img[3 * IMG * IMG];
    static const float albedo[3] = {0, 0.5f, 0.999f};
    int k;
    size_t mi;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "furnace", &fu) == VOXGI_OK, "furnace");
    for (k = 0; k < 3; k++) {
        voxgi_reference_desc rd;
        voxgi_vct_desc vd;
        double mean = 0, exact = 1.0 / (1.0 - (double)albedo[k]);
        stiff_add(&S, &fu.scene, NULL, 0, 0);
        for (mi = 0; mi < S.scene.material_count; mi++) S.mats[mi].albedo[0] = S.mats[mi].albedo[1] = S.mats[mi].albedo[2] = albedo[k];
        memset(&rd, 0, sizeof rd);
        rd.camera = fu.camera;
        rd.camera.width = rd.camera.height = IMG;
        rd.samples = 4;
        rd.bounces = -1;
        rd.seed = 1;
        TH_CHECK(voxgi_reference_render(ctx, &S.scene, &rd, img, sizeof img, NULL) == VOXGI_OK && all_finite(img, 3 * IMG * IMG, &mean), "reference: %s",
                 voxgi_last_error(ctx));
        printf("    albedo %.3f: path tracer %.4g, exact %.4g\n", albedo[k], mean, exact);
        TH_CHECK(fabs(mean / exact - 1) < (k == 2 ? 0.05 : k ? 0.03 : 1e-6), "path tracer at albedo %g: %g against %g", albedo[k], mean, exact);
        if (!k) continue;
        vct_view(&vd, &fu, IMG);
        vd.resolution = 32;
        vd.samples = 4;
        vd.bounces = -1;
        TH_CHECK(voxgi_vct_render(ctx, &S.scene, &vd, img, sizeof img, NULL) == VOXGI_OK && all_finite(img, 3 * IMG * IMG, &mean), "vct: %s", voxgi_last_error(ctx));
        printf("    albedo %.3f: cone tracing %.4g\n", albedo[k], mean);
        TH_CHECK(fabs(mean / exact - 1) < (k == 2 ? 0.15 : 0.01), "cone tracing at albedo %g: %g against %g", albedo[k], mean, exact);
    }
    voxgi_builtin_scene_destroy(ctx, &fu);
    voxgi_destroy(ctx);
}

/* Emission over twelve orders: the Cornell box's light 2^20 times as bright gives every light
   method's image times 2^20 bit for bit (light is linear and every sampling decision depends on
   ratios only), occlusion unchanged; beside it an emitter of 1e-6 keeps every value finite. */
static void test_emitter_range(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene bs;
    stiff_scene S;
    static float base[3 * IMG * IMG], img[3 * IMG * IMG];
    static const float dim[9] = {0.3f, 0.05f, 0.3f, 0.35f, 0.05f, 0.3f, 0.3f, 0.05f, 0.35f};
    size_t mi, i;
    int m, c;
    double mean = 0;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "cornell-box");
    for (m = 0; m < METHODS; m++) {
        int ao = m == 7 || m == 8;
        size_t off = 0;
        TH_CHECK(image_of(ctx, m, &bs.scene, bs.camera, base), "%s", method_names[m]);
        stiff_add(&S, &bs.scene, NULL, 0, 0);
        for (mi = 0; mi < S.scene.material_count; mi++)
            for (c = 0; c < 3; c++) S.mats[mi].emission[c] *= 1048576.0f;
        TH_CHECK(image_of(ctx, m, &S.scene, bs.camera, img), "%s", method_names[m]);
        for (i = 0; i < 3 * IMG * IMG; i++) off += (ao ? (double)img[i] : img[i] / 1048576.0) != base[i];
        TH_CHECK(off == 0, "%s: %lu values not %s", method_names[m], (unsigned long)off, ao ? "unchanged" : "2^20 times as bright");
        stiff_add(&S, &bs.scene, dim, 1, (uint32_t)bs.scene.material_count); /* a small dim emitter on the floor */
        for (mi = 0; mi < S.scene.material_count; mi++)
            for (c = 0; c < 3; c++) S.mats[mi].emission[c] = S.mats[mi].emission[c] > 0 ? 1e6f : 0.0f;
        memset(&S.mats[S.scene.material_count], 0, sizeof S.mats[0]);
        for (c = 0; c < 3; c++) S.mats[S.scene.material_count].emission[c] = 1e-6f;
        S.scene.material_count++;
        TH_CHECK(image_of(ctx, m, &S.scene, bs.camera, img) && all_finite(img, 3 * IMG * IMG, &mean), "%s with 1e6 and 1e-6 emitters: not finite", method_names[m]);
    }
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* Every light outside a closed box with the camera inside (leak-box): the exact image is black.
   Methods whose visibility is exact rays or voxels that close the box are black too; the
   transmittance shadow map lets light in along the box's inner seams (an opaque depth within half
   a texel of a point passes it: mean 0.03 at 64^2 texels, 0.003 at 512^2) and the SH volume
   through its coarse cells (0.027); occlusion is not light. */
static void test_light_outside_closed_box(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene lb;
    static float img[3 * IMG * IMG];
    static const double bound[METHODS] = {0, 0, 0.05, 0, 0.05, 0, 0, -1, -1, 0}; /* -1: occlusion */
    int m;
    double mean = 0;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "leak-box", &lb) == VOXGI_OK, "leak-box");
    for (m = 0; m < METHODS; m++) {
        TH_CHECK(image_of(ctx, m, &lb.scene, lb.camera, img) && all_finite(img, 3 * IMG * IMG, &mean), "%s", method_names[m]);
        printf("    %-9s mean %.3g inside the box\n", method_names[m], mean);
        if (bound[m] >= 0) TH_CHECK(mean <= bound[m], "%s: light inside the closed box: mean %g", method_names[m], mean);
    }
    voxgi_builtin_scene_destroy(ctx, &lb);
    voxgi_destroy(ctx);
}

/* Grids of 1, 2, 3 and 5 voxels a side, and one 2048 long: the conservative voxels on a grid equal
   the OR of each 2 x 2 x 2 block of the voxels on the grid of half the voxel size (the closed
   children cover the closed parent, so a triangle meets the parent exactly when it meets a
   child), on the CPU and on GL. */
static void test_resolutions(void)
{
    static const int res[5][3] = {{1, 1, 1}, {2, 2, 2}, {3, 3, 3}, {5, 5, 5}, {2048, 4, 4}};
    voxgi_builtin_scene bs;
    int b, k, a;
    for (b = 0; b < 2; b++) {
        voxgi_context *ctx;
        if (b && !have_gl()) break;
        ctx = make_ctx(b ? VOXGI_BACKEND_GL : VOXGI_BACKEND_CPU, 0);
        TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "cornell-box");
        for (k = 0; k < 5; k++) {
            voxgi_fit_desc fit;
            voxgi_voxelize_desc coarse, fine;
            voxgi_voxels *vf = NULL, *vr = NULL;
            voxgi_voxels_info ic, ir;
            uint32_t *bc, *br = NULL;
            size_t need = 0;
            const int factor[3] = {2, 2, 2};
            memset(&fit, 0, sizeof fit);
            memset(&coarse, 0, sizeof coarse);
            fit.res = res[k][0];
            TH_CHECK(voxgi_fit_grid(ctx, &bs.scene, &fit, &coarse.grid) == VOXGI_OK, "%s", voxgi_last_error(ctx));
            for (a = 0; a < 3; a++) coarse.grid.res[a] = res[k][a];
            fine = coarse;
            fine.grid.voxel_size = coarse.grid.voxel_size / 2;
            for (a = 0; a < 3; a++) fine.grid.res[a] = 2 * res[k][a];
            bc = voxelized_bits(ctx, &bs.scene, &coarse, &ic);
            TH_CHECK(voxgi_voxelize(ctx, &bs.scene, &fine, &vf) == VOXGI_OK && voxgi_voxels_reduce(ctx, vf, factor, &vr) == VOXGI_OK, "%s", voxgi_last_error(ctx));
            if (vr) {
                voxgi_voxels_query(vr, &ir);
                voxgi_voxels_read(ctx, vr, NULL, 0, &need);
                br = (uint32_t *)malloc(need);
                if (br && voxgi_voxels_read(ctx, vr, br, need, NULL) != VOXGI_OK) { free(br); br = NULL; }
            }
            TH_CHECK(bc && br && ic.bytes == need && !memcmp(bc, br, need), "%s, %d x %d x %d: %lu voxels, the finer grid's OR %lu", b ? "GL" : "CPU", res[k][0],
                     res[k][1], res[k][2], (unsigned long)ic.voxel_count, (unsigned long)(vr ? ir.voxel_count : 0));
            if (k == 0) TH_CHECK(ic.voxel_count == 1, "one voxel around the scene: %lu set", (unsigned long)ic.voxel_count);
            free(bc);
            free(br);
            voxgi_voxels_destroy(ctx, vf);
            voxgi_voxels_destroy(ctx, vr);
        }
        voxgi_builtin_scene_destroy(ctx, &bs);
        voxgi_destroy(ctx);
    }
}

/* A million triangles (a UV sphere of 1000 x 500, radius 1; a tenth of that under the
   sanitizers): the exact voxelization at 128^3 is the same on GL as on the CPU, and every set voxel
   lies within a voxel's diagonal of the sphere; the ray core's rays from the centre meet the
   surface between the inscribed polygon's radius and 1. The voxelizers' times are printed, not
   asserted. */
static void test_million_triangles(void)
{
    voxgi_context *cpu = make_ctx(VOXGI_BACKEND_CPU, 0), *gl = NULL;
    vxt_shape m;
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_voxelize_desc vd;
    voxgi_voxels_info ic, ig;
    voxgi_ray_scene *rs = NULL;
    uint32_t *bc, *bg = NULL;
    const int slices = FX_UNDER_ASAN ? 316 : 1000, stacks = slices / 2;
    const double inner = cos(3.14159265358979 / stacks); /* the facets' nearest points are at least this far from the centre */
    size_t i, far = 0;
    int x, y, z, n = 128;
    vxt_shape_sphere(&m, slices, stacks, 1.0, 0, 0, 0);
    scene_of_shape(&sc, &mesh, &m);
    printf("    %lu triangles\n", (unsigned long)m.triangle_count);
    memset(&vd, 0, sizeof vd);
    vd.grid.origin[0] = vd.grid.origin[1] = vd.grid.origin[2] = -1.0625;
    vd.grid.voxel_size = 2.125 / n;
    vd.grid.res[0] = vd.grid.res[1] = vd.grid.res[2] = n;
    bc = voxelized_bits(cpu, &sc, &vd, &ic);
    printf("    CPU voxelization: %lu voxels in %.0f ms\n", (unsigned long)ic.voxel_count, ic.ms);
    TH_CHECK(bc != NULL, "CPU voxelization failed");
    for (i = 0; bc && i < (size_t)n * n * n; i++) {
        double c[3], r;
        if (!(bc[i >> 5] >> (i & 31) & 1)) continue;
        x = (int)(i % (size_t)n); y = (int)(i / (size_t)n % (size_t)n); z = (int)(i / ((size_t)n * n));
        c[0] = vd.grid.origin[0] + (x + 0.5) * vd.grid.voxel_size;
        c[1] = vd.grid.origin[1] + (y + 0.5) * vd.grid.voxel_size;
        c[2] = vd.grid.origin[2] + (z + 0.5) * vd.grid.voxel_size;
        r = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        far += r > 1 + 0.87 * vd.grid.voxel_size || r < inner - 0.87 * vd.grid.voxel_size;
    }
    TH_CHECK(far == 0, "%lu set voxels are farther than their half-diagonal from the sphere", (unsigned long)far);
    if (have_gl() && (gl = make_ctx(VOXGI_BACKEND_GL, 0)) != NULL) {
        bg = voxelized_bits(gl, &sc, &vd, &ig);
        printf("    GL voxelization (a software rasteriser's time, not a GPU's): %.0f ms\n", ig.ms);
        TH_CHECK(bc && bg && ic.bytes == ig.bytes && !memcmp(bc, bg, ic.bytes), "GL and CPU differ: %lu against %lu voxels", (unsigned long)ig.voxel_count,
                 (unsigned long)ic.voxel_count);
    }
    TH_CHECK(voxgi_ray_scene_create(cpu, &sc, &rs) == VOXGI_OK, "%s", voxgi_last_error(cpu));
    if (rs) {
        enum { R = 4096 };
        static voxgi_ray rays[R];
        static voxgi_ray_hit hits[R];
        fx_rng g = fx_rng_seeded(7);
        int bad = 0;
        for (i = 0; i < R; i++) {
            double d[3], len = 0;
            int a;
            for (a = 0; a < 3; a++) { d[a] = fx_rng_range(&g, -1, 1); len += d[a] * d[a]; }
            len = sqrt(len);
            memset(&rays[i], 0, sizeof rays[i]);
            for (a = 0; a < 3; a++) rays[i].direction[a] = (float)(d[a] / len);
            rays[i].tmax = 10;
        }
        TH_CHECK(voxgi_ray_intersect(cpu, rs, R, rays, hits) == VOXGI_OK, "%s", voxgi_last_error(cpu));
        for (i = 0; i < R; i++) bad += hits[i].triangle == UINT32_MAX || !(hits[i].t >= inner * 0.999999 && hits[i].t <= 1.000001);
        TH_CHECK(bad == 0, "%d rays from the centre missed the sphere or met it off its facets", bad);
    }
    voxgi_ray_scene_destroy(cpu, rs);
    free(bc);
    free(bg);
    vxt_shape_free(&m);
    voxgi_destroy(gl);
    voxgi_destroy(cpu);
}

int main(void)
{
    gl_open();
    TH_RUN(test_million_triangles);
    TH_RUN(test_resolutions);
    TH_RUN(test_large_world);
    TH_RUN(test_scale_invariance);
    TH_RUN(test_degenerate_triangles);
    TH_RUN(test_empty_scene);
    TH_RUN(test_furnace_albedo);
    TH_RUN(test_emitter_range);
    TH_RUN(test_light_outside_closed_box);
    gl_close();
    return th_finish();
}
