/* tests/test_stiff.c - stiff and extreme input across the parts, CPU and GL.

   Stiff and extreme input, one test per case, each with what is expected (docs/stiff-cases.md
   has the table; the scenes and the methods' small settings are tools/stiff.h's, which `voxgi
   report stiff` measures too): a large world through double positions; every method's image
   under scaling and moved in float; degenerate, needle and sliver triangles; an empty scene; the
   furnace at albedo 0 to 0.999; emission over twelve orders; lights outside a closed box;
   resolutions 1 to 2048; a million triangles. */
#include "../voxgi.h"
#include "fixtures.h"
#include "../tools/stiff.h"

static void test_large_world(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene bs;
    vxt_stiff_far far;
    voxgi_voxelize_desc vd;
    voxgi_fit_desc fit;
    voxgi_voxels_info i0, i1;
    voxgi_render_desc rd;
    uint32_t *b0 = NULL, *b1 = NULL;
    static float img0[3 * 16 * 16], img1[3 * 16 * 16];
    float ceiling = -1, light = -1;
    size_t v;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "cornell-box");
    TH_CHECK(vxt_stiff_far_make(&bs.scene, 1e6, 1e6, &far), "out of memory");
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
    rd.method = VOXGI_RENDER_REFERENCE;
    rd.camera = bs.camera;
    rd.camera.width = rd.camera.height = 16;
    rd.samples = 4;
    rd.bounces = 1;
    rd.seed = 5;
    TH_CHECK(voxgi_render(ctx, &bs.scene, &rd, img0, sizeof img0, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    TH_CHECK(voxgi_render(ctx, &far.scene, &rd, img1, sizeof img1, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
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
    vxt_stiff_far_free(&far);
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

enum { IMG = VXT_STIFF_IMG, METHODS = VXT_STIFF_METHODS };
#define method_names vxt_stiff_methods

/* Method m's 16 x 16 image of sc through cam (vxt_stiff_image) into rgb: 1 on success. */
static int image_of(voxgi_context *ctx, int m, const voxgi_scene *sc, voxgi_camera cam, float *rgb)
{
    voxgi_result r = vxt_stiff_image(ctx, m, sc, cam, rgb);
    if (r != VOXGI_OK) printf("    %s: %s\n", method_names[m], voxgi_last_error(ctx));
    return r == VOXGI_OK;
}

/* Every method's image of the Cornell box (its light an emissive quad: radiance, the same at any
   scale) scaled by powers of two (2^20, 2^-20: every float product exact) equals the unscaled
   image bit for bit: nothing in voxgi holds an absolute length. Scaled by 1e6, 1e-6 and 1e3 the
   geometry rounds differently, and the images agree to rounding (relative RMS difference under
   2e-3; measured at most 3e-4, but 1.7e-3 for the SH volume's bounce at 1e-6 with some of its
   sampling seeds, 5e-4 without its voxel visibility: a wall's rounding decides which voxels
   beside a voxel boundary the exact voxelization sets). */
static void test_scale_invariance(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene bs;
    static const double scales[5] = {1048576.0, 1.0 / 1048576.0, 1e6, 1e-6, 1e3};
    static float base[3 * IMG * IMG], img[3 * IMG * IMG];
    int m, k;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "cornell-box");
    for (m = 0; m < METHODS; m++) {
        if (!image_of(ctx, m, &bs.scene, bs.camera, base)) { TH_CHECK(0, "%s at scale 1", method_names[m]); continue; }
        for (k = 0; k < 5; k++) {
            vxt_stiff_placed sc;
            voxgi_camera cam = bs.camera;
            double diff2 = 0, mean = 0, rel;
            size_t i;
            cam = vxt_stiff_placed_camera(cam, scales[k], 0);
            TH_CHECK(vxt_stiff_placed_make(&bs.scene, scales[k], 0, &sc), "out of memory");
            TH_CHECK(image_of(ctx, m, &sc.scene, cam, img), "%s at scale %g", method_names[m], scales[k]);
            for (i = 0; i < 3 * IMG * IMG; i++) {
                diff2 += ((double)img[i] - base[i]) * ((double)img[i] - base[i]);
                mean += base[i] / (3.0 * IMG * IMG);
            }
            rel = sqrt(diff2 / (3.0 * IMG * IMG)) / mean;
            if (k < 2) TH_CHECK(!memcmp(img, base, sizeof img), "%s scaled by %g: not the same image (relative RMS difference %.3g)", method_names[m], scales[k], rel);
            else TH_CHECK(rel < 2e-3, "%s scaled by %g: relative RMS difference %.3g", method_names[m], scales[k], rel);
            if (k == 2) printf("    %-9s 1e6: relative RMS difference %.2g\n", method_names[m], rel);
            vxt_stiff_placed_free(&sc);
        }
    }
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* Every method's image of the Cornell box moved by 1e3 in float positions (the camera and the
   lights with it): the vertices round by up to 3e-5 there (half of float's step of 2^-14), and
   the images agree with the box's at the origin up to what that moves (relative RMS difference):
   the rays' and maps' methods under 2e-3; the line space under 2e-2 (a pixel whose centre ray
   grazes an edge, and the light 0.1 mm under the ceiling moving by a third of that); the voxel
   methods under 3e-2 (the box's walls lie on voxel faces, one voxel inside the fitted grid, and
   a closed voxel on either side holds them: rounded, each wall falls on one side, so whole
   layers of voxels change: 340 of 1129 at 16^3). At 1e6 the light's gap closes before voxgi sees
   it (float's step is 0.0625 there): the images are finite and printed, not bounded; the way
   out is test_large_world's. The screen-space methods on GL (which compute in float) are held to
   the same bounds: they work relative to the eye (in world coordinates SSAO was 70% off at 1e3). */
static void test_moved_float(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene bs;
    static const double offsets[2] = {1e3, 1e6};
    static const double bound[METHODS] = {2e-3, 3e-2, 2e-3, 3e-2, 3e-2, 2e-3, 3e-2, 2e-3, 3e-2, 2e-2};
    static float base[3 * IMG * IMG], img[3 * IMG * IMG];
    int m, k;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "cornell-box");
    for (m = 0; m < METHODS; m++) {
        double rel[2] = {0, 0}, mean;
        if (!image_of(ctx, m, &bs.scene, bs.camera, base)) { TH_CHECK(0, "%s at the origin", method_names[m]); continue; }
        for (k = 0; k < 2; k++) {
            vxt_stiff_placed sc;
            TH_CHECK(vxt_stiff_placed_make(&bs.scene, 1, offsets[k], &sc), "out of memory");
            TH_CHECK(image_of(ctx, m, &sc.scene, vxt_stiff_placed_camera(bs.camera, 1, offsets[k]), img) && vxt_stiff_finite(img, 3 * IMG * IMG, &mean),
                     "%s moved by %g: not finite", method_names[m], offsets[k]);
            rel[k] = vxt_stiff_rel_diff(img, base, 3 * IMG * IMG);
            vxt_stiff_placed_free(&sc);
        }
        printf("    %-9s moved by 1e3: relative RMS difference %.2g; by 1e6 (float's limit): %.2g\n", method_names[m], rel[0], rel[1]);
        TH_CHECK(rel[0] < bound[m], "%s moved by 1e3: relative RMS difference %.3g", method_names[m], rel[0]);
    }
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
    if (have_gl()) { /* the screen-space methods on GL: ssgi, hybrid, ssao, vao */
        voxgi_context *gl = make_ctx(VOXGI_BACKEND_GL, 0);
        TH_CHECK(gl && voxgi_builtin_scene_create(gl, "cornell-box", &bs) == VOXGI_OK, "cornell-box on GL");
        for (m = 5; gl && m <= 8; m++) {
            vxt_stiff_placed sc;
            double rel;
            TH_CHECK(image_of(gl, m, &bs.scene, bs.camera, base) && vxt_stiff_placed_make(&bs.scene, 1, 1e3, &sc) &&
                         image_of(gl, m, &sc.scene, vxt_stiff_placed_camera(bs.camera, 1, 1e3), img), "%s on GL", method_names[m]);
            rel = vxt_stiff_rel_diff(img, base, 3 * IMG * IMG);
            vxt_stiff_placed_free(&sc);
            printf("    %-9s on GL, moved by 1e3: relative RMS difference %.2g\n", method_names[m], rel);
            TH_CHECK(rel < bound[m], "%s on GL moved by 1e3: relative RMS difference %.3g", method_names[m], rel);
        }
        if (gl) voxgi_builtin_scene_destroy(gl, &bs);
        voxgi_destroy(gl);
    }
}

/* Needle, sliver, segment and point triangles in the Cornell box: every method gives an image of
   finite values. The segment and the points have no area: the methods that see the scene through
   rays or rasterized maps give the box's image bit for bit; the voxel methods set the voxels a
   segment or a point touches, as the exact definition says, and may differ a little. */
static void test_degenerate_triangles(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene bs;
    vxt_stiff_scene S;
    static float base[3 * IMG * IMG], img[3 * IMG * IMG];
    static const int exact[METHODS] = {1, 0, 1, 0, 0, 1, 0, 1, 1, 1}; /* no voxels in the image */
    int m, k;
    double mean = 0;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "cornell-box");
    for (m = 0; m < METHODS; m++) {
        TH_CHECK(image_of(ctx, m, &bs.scene, bs.camera, base), "%s", method_names[m]);
        for (k = 0; k < 2; k++) {
            TH_CHECK(vxt_stiff_add(&S, &bs.scene, vxt_stiff_degenerate, k ? 5 : 3, 0), "the scene is too big for a vxt_stiff_scene");
            TH_CHECK(image_of(ctx, m, &S.scene, bs.camera, img) && vxt_stiff_finite(img, 3 * IMG * IMG, &mean), "%s with %s: not finite", method_names[m],
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
   bounce (32^3) within 1% at 0.5 and 15% at 0.999 (measured 946: the cones lose about 0.06% of
   the light a bounce, which a thousand bounces compound; without the bounces' geometric tail,
   64 bounces gave 58). No value is NaN or infinite. */
static void test_furnace_albedo(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene fu;
    static const float albedo[3] = {0, 0.5f, 0.999f};
    int k;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "furnace", &fu) == VOXGI_OK, "furnace");
    for (k = 0; k < 3; k++) {
        double mean = 0, exact = 1.0 / (1.0 - (double)albedo[k]);
        TH_CHECK(vxt_stiff_furnace(ctx, &fu, albedo[k], 0, &mean) == VOXGI_OK && isfinite(mean), "reference: %s", voxgi_last_error(ctx));
        printf("    albedo %.3f: path tracer %.4g, exact %.4g\n", albedo[k], mean, exact);
        TH_CHECK(fabs(mean / exact - 1) < (k == 2 ? 0.05 : k ? 0.03 : 1e-6), "path tracer at albedo %g: %g against %g", albedo[k], mean, exact);
        if (!k) continue;
        TH_CHECK(vxt_stiff_furnace(ctx, &fu, albedo[k], 1, &mean) == VOXGI_OK && isfinite(mean), "vct: %s", voxgi_last_error(ctx));
        printf("    albedo %.3f: cone tracing %.4g\n", albedo[k], mean);
        TH_CHECK(fabs(mean / exact - 1) < (k == 2 ? 0.15 : 0.01), "cone tracing at albedo %g: %g against %g", albedo[k], mean, exact);
        if (k == 2 && have_gl()) { /* GL's cones keep the same regions (the shell's outer voxels unseen from inside) */
            voxgi_context *gl = make_ctx(VOXGI_BACKEND_GL, 0);
            double on_gl = 0;
            TH_CHECK(vxt_stiff_furnace(gl, &fu, albedo[k], 1, &on_gl) == VOXGI_OK && fabs(on_gl / mean - 1) < 0.03, "GL: %g, the CPU %g (%s)", on_gl, mean,
                     voxgi_last_error(gl));
            printf("    albedo %.3f: cone tracing on GL %.4g\n", albedo[k], on_gl);
            voxgi_destroy(gl);
        }
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
    vxt_stiff_scene S;
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
        TH_CHECK(vxt_stiff_add(&S, &bs.scene, NULL, 0, 0), "the scene is too big for a vxt_stiff_scene");
        for (mi = 0; mi < S.scene.material_count; mi++)
            for (c = 0; c < 3; c++) S.mats[mi].emission[c] *= 1048576.0f;
        TH_CHECK(image_of(ctx, m, &S.scene, bs.camera, img), "%s", method_names[m]);
        for (i = 0; i < 3 * IMG * IMG; i++) off += (ao ? (double)img[i] : img[i] / 1048576.0) != base[i];
        TH_CHECK(off == 0, "%s: %lu values not %s", method_names[m], (unsigned long)off, ao ? "unchanged" : "2^20 times as bright");
        TH_CHECK(vxt_stiff_add(&S, &bs.scene, dim, 1, (uint32_t)bs.scene.material_count), "the scene is too big for a vxt_stiff_scene"); /* a small dim emitter on the floor */
        for (mi = 0; mi < S.scene.material_count; mi++)
            for (c = 0; c < 3; c++) S.mats[mi].emission[c] = S.mats[mi].emission[c] > 0 ? 1e6f : 0.0f;
        memset(&S.mats[S.scene.material_count], 0, sizeof S.mats[0]);
        for (c = 0; c < 3; c++) S.mats[S.scene.material_count].emission[c] = 1e-6f;
        S.scene.material_count++;
        TH_CHECK(image_of(ctx, m, &S.scene, bs.camera, img) && vxt_stiff_finite(img, 3 * IMG * IMG, &mean), "%s with 1e6 and 1e-6 emitters: not finite", method_names[m]);
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
        TH_CHECK(image_of(ctx, m, &lb.scene, lb.camera, img) && vxt_stiff_finite(img, 3 * IMG * IMG, &mean), "%s", method_names[m]);
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
    const int slices = FX_REDUCED ? 316 : 1000, stacks = slices / 2;
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
    TH_RUN(test_moved_float);
    TH_RUN(test_degenerate_triangles);
    TH_RUN(test_empty_scene);
    TH_RUN(test_furnace_albedo);
    TH_RUN(test_emitter_range);
    TH_RUN(test_light_outside_closed_box);
    gl_close();
    return th_finish();
}
