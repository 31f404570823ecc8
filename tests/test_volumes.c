/* tests/test_volumes.c - part 6: volumes and mips, CPU and GL. Dense attribute volumes and their
   isotropic and anisotropic mips against what is known (a constant field stays constant, a lone
   voxel keeps its colour with alpha / 8 or / 4 a level, the near voxel's colour in each direction,
   the base level is the attribute means), sampling (trilinear between centres, clamped at the
   faces, lods between levels); the GL mips and samples equal the CPU's. (The mip filters against
   parents worked out by hand, which call private helpers, and the region labels: in
   tests/test_internals.c.) The GL tests skip (loudly) only when no GL 4.5 context can be made;
   VOXGI_TEST_GL=egl|osmesa|none picks the kind (none: no context), VOXGI_REQUIRE_GL=1 turns a skip into a failure. */
#include "../voxgi.h"
#include "fixtures.h"
#include <stdlib.h>

/* ---------------------------------------------------------------- random numbers */
static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static double rnd(void) /* [0,1) */
{
    rng_state ^= rng_state << 13; rng_state ^= rng_state >> 7; rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) * (1.0 / 9007199254740992.0);
}

/* ---------------------------------------------------------------- attribute volumes and mips */
static float *volume_level(voxgi_context *ctx, const voxgi_volume *vol, voxgi_attribute which, voxgi_direction dir, int level)
{
    size_t need = 0;
    float *out;
    if (voxgi_volume_read(ctx, vol, which, dir, level, NULL, 0, &need) != VOXGI_OK) return NULL;
    out = (float *)malloc(need);
    if (voxgi_volume_read(ctx, vol, which, dir, level, out, need, NULL) != VOXGI_OK) { free(out); return NULL; }
    return out;
}

/* A constant field stays constant (and full parents keep its alpha); a lone voxel keeps its
   colour at every level with alpha / 8 per level (isotropic) or / 4 (anisotropic, in every
   direction); two opaque voxels along x show the near one's colour in each direction; the
   base level of a voxelization's volume is its attribute means. */
static void test_volume_mips(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    voxgi_grid g;
    voxgi_volume_desc vd;
    voxgi_volume *vol = NULL;
    voxgi_volume_info info;
    float *albedo, *opacity;
    const float *base[4];
    size_t n, i;
    int k, dir, bad = 0;
    g.origin[0] = g.origin[1] = g.origin[2] = 0; g.voxel_size = 1;
    g.res[0] = 9; g.res[1] = 6; g.res[2] = 5; /* odd sizes: parents at the far faces lack children */
    n = (size_t)voxgi_grid_voxel_count(&g);
    albedo = (float *)malloc(n * 16);
    opacity = (float *)malloc(n * 4);
    for (i = 0; i < n; i++) { albedo[4 * i] = 0.3f; albedo[4 * i + 1] = 0.6f; albedo[4 * i + 2] = 0.9f; albedo[4 * i + 3] = 0.5f; opacity[i] = 0.5f; }
    base[0] = albedo; base[1] = NULL; base[2] = NULL; base[3] = opacity;
    memset(&vd, 0, sizeof vd);
    TH_CHECK(voxgi_volume_create_dense(ctx, &g, &vd, base, &vol) == VOXGI_OK, "dense volume: %s", voxgi_last_error(ctx));
    voxgi_volume_query(vol, &info);
    TH_CHECK(info.levels == 5, "9x6x5 has 5 levels down to one voxel, got %d", info.levels);
    for (k = 0; k < info.levels; k++) {
        float *lv = volume_level(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, 0, k), *op = volume_level(ctx, vol, VOXGI_ATTRIBUTE_OPACITY, 0, k);
        int d[3], x, y, z, a;
        for (a = 0; a < 3; a++) { d[a] = g.res[a]; for (x = 0; x < k; x++) d[a] = (d[a] + 1) / 2; }
        for (z = 0; z < d[2]; z++)
            for (y = 0; y < d[1]; y++)
                for (x = 0; x < d[0]; x++) {
                    size_t l = (size_t)x + (size_t)d[0] * ((size_t)y + (size_t)d[1] * (size_t)z);
                    int full = ((x + 1) << k) <= g.res[0] && ((y + 1) << k) <= g.res[1] && ((z + 1) << k) <= g.res[2];
                    bad += fabs(lv[4 * l] - 0.3f) > 1e-6 || fabs(lv[4 * l + 1] - 0.6f) > 1e-6 || fabs(lv[4 * l + 2] - 0.9f) > 1e-6;
                    bad += full && (fabs(lv[4 * l + 3] - 0.5f) > 1e-6 || fabs(op[l] - 0.5f) > 1e-6);
                    bad += !full && !(lv[4 * l + 3] < 0.5f && fabs(op[l] - lv[4 * l + 3]) < 1e-6);
                }
        free(lv); free(op);
    }
    TH_CHECK(bad == 0, "constant field: %d values changed through the mips", bad);
    voxgi_volume_destroy(ctx, vol);
    for (dir = -1; dir < 6; dir++) { /* a lone voxel at (5, 3, 2), red, alpha 0.8 */
        memset(albedo, 0, n * 16);
        i = 5 + 9 * (3 + 6 * 2);
        albedo[4 * i] = 1; albedo[4 * i + 3] = 0.8f;
        base[3] = NULL;
        vd.filter = dir < 0 ? VOXGI_MIPS_ISOTROPIC : VOXGI_MIPS_ANISOTROPIC;
        voxgi_volume_create_dense(ctx, &g, &vd, base, &vol);
        for (k = 0; k < 5; k++) {
            float *lv = volume_level(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, (voxgi_direction)(dir < 0 ? 0 : dir), k);
            int d0 = g.res[0], d1 = g.res[1], x;
            size_t l;
            double want = 0.8 / pow(dir < 0 ? 8.0 : 4.0, k);
            for (x = 0; x < k; x++) { d0 = (d0 + 1) / 2; d1 = (d1 + 1) / 2; }
            l = (size_t)(5 >> k) + (size_t)d0 * ((size_t)(3 >> k) + (size_t)d1 * (size_t)(2 >> k));
            bad += !lv || fabs(lv[4 * l] - 1.0f) > 1e-6 || lv[4 * l + 1] != 0 || fabs(lv[4 * l + 3] - want) > 1e-6 * want;
            free(lv);
        }
        voxgi_volume_destroy(ctx, vol);
    }
    TH_CHECK(bad == 0, "a lone voxel lost its colour or alpha in the mips (%d)", bad);
    {   /* red opaque at x = 0, blue opaque at x = 1: +x sees red, -x blue, alpha 1/4 at level 1 */
        float *px, *nx;
        memset(albedo, 0, n * 16);
        albedo[0] = 1; albedo[3] = 1;
        albedo[4 * 1 + 2] = 1; albedo[4 * 1 + 3] = 1;
        vd.filter = VOXGI_MIPS_ANISOTROPIC;
        voxgi_volume_create_dense(ctx, &g, &vd, base, &vol);
        px = volume_level(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, VOXGI_DIR_POS_X, 1);
        nx = volume_level(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, VOXGI_DIR_NEG_X, 1);
        TH_CHECK(px && nx && px[0] == 1 && px[2] == 0 && px[3] == 0.25f && nx[0] == 0 && nx[2] == 1 && nx[3] == 0.25f,
                 "anisotropic front-to-back: +x (%g %g %g %g), -x (%g %g %g %g)", px ? px[0] : -1, px ? px[1] : -1, px ? px[2] : -1,
                 px ? px[3] : -1, nx ? nx[0] : -1, nx ? nx[1] : -1, nx ? nx[2] : -1, nx ? nx[3] : -1);
        free(px); free(nx);
        TH_CHECK(voxgi_volume_read(ctx, vol, VOXGI_ATTRIBUTE_NORMAL, 0, 0, NULL, 0, &i) == VOXGI_ERR_INVALID_ARGUMENT, "absent attribute read");
        TH_CHECK(voxgi_volume_read(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, 0, 9, NULL, 0, &i) == VOXGI_ERR_INVALID_ARGUMENT, "level 9 read");
        voxgi_volume_destroy(ctx, vol);
    }
    {   /* from a voxelization: level 0 holds the attribute means at the set voxels, alpha = opacity */
        vxt_shape m;
        voxgi_mesh mesh;
        voxgi_scene sc;
        voxgi_voxelize_desc xd;
        voxgi_voxels *vox = NULL;
        voxgi_material mat = {{0.25f, 0.5f, 0.75f}, {0, 0, 0}, 0.5f};
        float *lv, *means;
        uint32_t *bits;
        size_t need = 0, slot = 0, l;
        vxt_shape_sphere(&m, 24, 12, 1.0, 0, 0, 0);
        scene_of_shape(&sc, &mesh, &m);
        scene_lighting(&sc, &mat, 1, NULL, 0);
        memset(&xd, 0, sizeof xd);
        xd.grid.origin[0] = xd.grid.origin[1] = xd.grid.origin[2] = -1.2; xd.grid.voxel_size = 0.1;
        xd.grid.res[0] = xd.grid.res[1] = xd.grid.res[2] = 24;
        xd.attributes = VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_OPACITY;
        voxgi_voxelize(ctx, &sc, &xd, &vox);
        memset(&vd, 0, sizeof vd);
        TH_CHECK(voxgi_volume_create(ctx, vox, &vd, &vol) == VOXGI_OK, "volume from voxels: %s", voxgi_last_error(ctx));
        lv = volume_level(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, 0, 0);
        means = attr_read(ctx, vox, VOXGI_ATTRIBUTE_ALBEDO);
        voxgi_voxels_read(ctx, vox, NULL, 0, &need);
        bits = (uint32_t *)malloc(need);
        voxgi_voxels_read(ctx, vox, bits, need, NULL);
        for (l = 0, bad = 0; lv && means && l < 24 * 24 * 24; l++) {
            if (!voxgi_bit_get(bits, l)) { bad += lv[4 * l + 3] != 0; continue; }
            bad += lv[4 * l] != means[3 * slot] || lv[4 * l + 2] != means[3 * slot + 2] || fabs(lv[4 * l + 3] - 0.5f) > 1e-6;
            slot++;
        }
        TH_CHECK(lv && means && bad == 0 && slot > 0, "volume base level differs from the voxels' means (%d)", bad);
        free(lv); free(means); free(bits);
        voxgi_volume_destroy(ctx, vol);
        voxgi_voxels_destroy(ctx, vox);
        vxt_shape_free(&m);
    }
    free(albedo); free(opacity);
    voxgi_destroy(ctx);
}

/* Attribute volumes and their mips: GL (3D textures, compute mips) equals the CPU's arrays
   within float rounding (1e-6 relative) at every level, isotropic and in all six directions. */
static void test_gl_volume_mips_equal_cpu(void)
{
    static const voxgi_attribute kinds[4] = {VOXGI_ATTRIBUTE_ALBEDO, VOXGI_ATTRIBUTE_NORMAL, VOXGI_ATTRIBUTE_EMISSION, VOXGI_ATTRIBUTE_OPACITY};
    voxgi_context *cpu, *gl;
    material_sphere s;
    voxgi_voxelize_desc xd;
    voxgi_voxels *vox[2] = {NULL, NULL};
    int filter, b;
    double worst = 0;
    if (!have_gl()) return;
    cpu = make_ctx(VOXGI_BACKEND_CPU, 0);
    gl = make_ctx(VOXGI_BACKEND_GL, 0);
    material_sphere_make(&s);
    memset(&xd, 0, sizeof xd);
    cubic(&xd.grid, -1.1, 2.2, 27); /* odd: incomplete parents at the far faces */
    xd.attributes = 15;
    for (b = 0; b < 2; b++) voxgi_voxelize(b ? gl : cpu, &s.scene, &xd, &vox[b]);
    TH_CHECK(vox[0] && vox[1], "voxelization failed");
    for (filter = 0; filter < 2 && vox[0] && vox[1]; filter++) {
        voxgi_volume_desc vd;
        voxgi_volume *vol[2] = {NULL, NULL};
        voxgi_volume_info info;
        int k, d, a;
        unsigned int tex = 0;
        memset(&vd, 0, sizeof vd);
        vd.filter = (voxgi_mip_filter)filter;
        for (b = 0; b < 2; b++)
            if (voxgi_volume_create(b ? gl : cpu, vox[b], &vd, &vol[b]) != VOXGI_OK) printf("    %s\n", voxgi_last_error(b ? gl : cpu));
        TH_CHECK(vol[0] && vol[1], "volume creation failed");
        if (!vol[0] || !vol[1]) continue;
        voxgi_volume_query(vol[1], &info);
        TH_CHECK(voxgi_volume_gl_texture(gl, vol[1], VOXGI_ATTRIBUTE_ALBEDO, 0, &tex) == VOXGI_OK && tex != 0, "no GL texture");
        for (a = 0; a < 4; a++)
            for (d = 0; d < (filter ? 6 : 1); d++)
                for (k = 0; k < info.levels; k++) {
                    size_t na = 0, nb = 0, i;
                    float *x, *y;
                    voxgi_volume_read(cpu, vol[0], kinds[a], (voxgi_direction)d, k, NULL, 0, &na);
                    voxgi_volume_read(gl, vol[1], kinds[a], (voxgi_direction)d, k, NULL, 0, &nb);
                    x = (float *)malloc(na); y = (float *)malloc(nb);
                    voxgi_volume_read(cpu, vol[0], kinds[a], (voxgi_direction)d, k, x, na, NULL);
                    voxgi_volume_read(gl, vol[1], kinds[a], (voxgi_direction)d, k, y, nb, NULL);
                    TH_CHECK(na == nb, "level sizes differ");
                    for (i = 0; na == nb && i < na / 4; i++) {
                        double e = fabs((double)x[i] - y[i]) / (fabs(x[i]) > 1 ? fabs(x[i]) : 1);
                        if (e > worst) worst = e;
                    }
                    free(x); free(y);
                }
        printf("    volume %s: %d levels, %lu bytes, GL within %.3g of the CPU\n", filter ? "anisotropic" : "isotropic", info.levels,
               (unsigned long)info.bytes, worst);
        for (b = 0; b < 2; b++) voxgi_volume_destroy(b ? gl : cpu, vol[b]);
    }
    TH_CHECK(worst <= 1e-6, "GL mips differ from the CPU's by %g", worst);
    for (b = 0; b < 2; b++) voxgi_voxels_destroy(b ? gl : cpu, vox[b]);
    material_sphere_free(&s);
    voxgi_destroy(cpu);
    voxgi_destroy(gl);
}

/* Sampling: trilinear between voxel centres and linear between levels reproduce a linear field
   (red = x) at every lod in the interior, whatever the level; beyond the grid the volume is empty. */
static void test_volume_sampling(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 1);
    voxgi_grid g;
    voxgi_volume_desc vd;
    voxgi_volume *vol = NULL;
    float *albedo, pos[3 * 200], lods[200], out[4 * 200];
    const float *base[4];
    size_t i, n;
    double worst = 0;
    g.origin[0] = g.origin[1] = g.origin[2] = 0; g.voxel_size = 1;
    g.res[0] = 32; g.res[1] = 16; g.res[2] = 16;
    n = (size_t)voxgi_grid_voxel_count(&g);
    albedo = (float *)malloc(n * 16);
    for (i = 0; i < n; i++) {
        albedo[4 * i] = (float)(i % 32) + 0.5f;
        albedo[4 * i + 1] = 0.25f; albedo[4 * i + 2] = 0.5f; albedo[4 * i + 3] = 1;
    }
    base[0] = albedo; base[1] = base[2] = base[3] = NULL;
    memset(&vd, 0, sizeof vd);
    voxgi_volume_create_dense(ctx, &g, &vd, base, &vol);
    for (i = 0; i < 200; i++) { /* lod l needs 2^l voxels of margin for its centres to straddle p */
        lods[i] = (float)(3.0 * rnd());
        pos[3 * i] = (float)(8 + 16 * rnd());
        pos[3 * i + 1] = (float)(8 + 0.1 * rnd());
        pos[3 * i + 2] = (float)(8 + 0.1 * rnd());
    }
    TH_CHECK(voxgi_volume_sample(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, 0, 200, pos, lods, out) == VOXGI_OK, "sample: %s", voxgi_last_error(ctx));
    for (i = 0; i < 200; i++) {
        double e = fabs(out[4 * i] - pos[3 * i]) + fabs(out[4 * i + 1] - 0.25) + fabs(out[4 * i + 3] - 1);
        if (e > worst) worst = e;
    }
    TH_CHECK(worst < 1e-4, "a linear field sampled off by %g", worst);
    pos[0] = -3; pos[1] = 5; pos[2] = 5; lods[0] = 0;
    voxgi_volume_sample(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, 0, 1, pos, lods, out);
    TH_CHECK(out[0] == 0 && out[3] == 0, "outside the grid: %g %g", out[0], out[3]);
    pos[0] = 0.5f; /* half way between the border and the first centre column: alpha half */
    voxgi_volume_sample(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, 0, 1, pos, lods, out);
    TH_CHECK(fabs(out[3] - 1) < 1e-6 && out[0] == 0.5f, "on the first centre: %g %g", out[0], out[3]);
    pos[0] = 0; voxgi_volume_sample(ctx, vol, VOXGI_ATTRIBUTE_ALBEDO, 0, 1, pos, lods, out);
    TH_CHECK(fabs(out[3] - 0.5) < 1e-6, "at the grid's face alpha %g, want 0.5", out[3]);
    voxgi_volume_destroy(ctx, vol);
    free(albedo);
    voxgi_destroy(ctx);
}

/* The GLSL sampler (hardware trilinear between levels on the padded textures) against the
   CPU's, on a non-power-of-two volume with structure, at random points inside and around the
   grid and random lods: equal within the rasterizer's filter precision. */
static void test_gl_volume_sampling_equals_cpu(void)
{
    voxgi_context *cpu, *gl;
    voxgi_grid g;
    voxgi_volume_desc vd;
    voxgi_volume *vol[2] = {NULL, NULL};
    const float *base[4];
    float *albedo, *opacity, pos[3 * 1000], lods[1000], out[2][4 * 1000];
    size_t i, n;
    int b, f;
    double worst = 0;
    fx_rng rng = fx_rng_seeded(3);
    if (!have_gl()) return;
    cpu = make_ctx(VOXGI_BACKEND_CPU, 0);
    gl = make_ctx(VOXGI_BACKEND_GL, 0);
    g.origin[0] = g.origin[1] = g.origin[2] = 0; g.voxel_size = 1;
    g.res[0] = 21; g.res[1] = 13; g.res[2] = 10;
    n = (size_t)voxgi_grid_voxel_count(&g);
    albedo = (float *)malloc(n * 16);
    opacity = (float *)malloc(n * 4);
    for (i = 0; i < n; i++) {
        int x = (int)(i % 21), y = (int)(i / 21 % 13), z = (int)(i / 273);
        int set = (x * 7 + y * 3 + z * 5) % 4 != 0;
        albedo[4 * i] = set ? (float)x / 21 : 0; albedo[4 * i + 1] = set ? (float)y / 13 : 0;
        albedo[4 * i + 2] = set ? (float)z / 10 : 0; albedo[4 * i + 3] = set ? 0.25f + 0.75f * (float)((x + y) % 3) / 2 : 0;
        opacity[i] = albedo[4 * i + 3];
    }
    base[0] = albedo; base[1] = base[2] = NULL; base[3] = opacity;
    for (i = 0; i < 1000; i++) {
        pos[3 * i] = (float)fx_rng_range(&rng, -2, 23);
        pos[3 * i + 1] = (float)fx_rng_range(&rng, -2, 15);
        pos[3 * i + 2] = (float)fx_rng_range(&rng, -2, 12);
        lods[i] = (float)fx_rng_range(&rng, -0.5, 5.5);
    }
    for (f = 0; f < 2; f++) {
        memset(&vd, 0, sizeof vd);
        vd.filter = (voxgi_mip_filter)f;
        for (b = 0; b < 2; b++) {
            voxgi_volume_create_dense(b ? gl : cpu, &g, &vd, base, &vol[b]);
            TH_CHECK(vol[b] && voxgi_volume_sample(b ? gl : cpu, vol[b], VOXGI_ATTRIBUTE_ALBEDO, (voxgi_direction)(f ? 3 : 0), 1000, pos, lods,
                                                   out[b]) == VOXGI_OK, "sampling failed: %s", voxgi_last_error(b ? gl : cpu));
        }
        for (i = 0; i < 4000; i++) {
            double e = fabs((double)out[0][i] - out[1][i]);
            if (e > worst) worst = e;
        }
        for (b = 0; b < 2; b++) voxgi_volume_destroy(b ? gl : cpu, vol[b]);
    }
    printf("    GL sampling within %.3g of the CPU's (values in [0,1])\n", worst);
    TH_CHECK(worst <= 1e-3, "GL sampling differs from the CPU's by %g", worst);
    free(albedo); free(opacity);
    voxgi_destroy(cpu);
    voxgi_destroy(gl);
}

int main(void)
{
    gl_open();
    TH_RUN(test_volume_mips);
    TH_RUN(test_gl_volume_mips_equal_cpu);
    TH_RUN(test_volume_sampling);
    TH_RUN(test_gl_volume_sampling_equals_cpu);
    gl_close();
    return th_finish();
}
