/* tests/test_files.c - part 15: built-in scenes and files. binvox: write then read gives the same
   grid and bits, every truncated file is refused. The built-in scenes: valid, and what the
   reference renderer sees in each (the furnace at radiance 2, the leak box black inside, the
   Cornell box's light at its radiance); an unknown name refused. */
#include "../voxgi.h"
#include "fixtures.h"
#include <stdlib.h>

/* binvox write then read gives the same grid and bits; a truncated file is an error. */
static void test_binvox_roundtrip(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 1);
    vxt_shape m;
    voxgi_grid g, g2;
    uint32_t *bits, *back;
    size_t need = 0, bytes;
    FILE *f = tmpfile();
    long len;
    vxt_shape_sphere(&m, 20, 14, 1.0, 0, 0, 0);
    memset(&g2, 0, sizeof g2);
    g.origin[0] = -1.25; g.origin[1] = -1.5; g.origin[2] = -1.125;
    g.voxel_size = 0.125;
    g.res[0] = 21; g.res[1] = 24; g.res[2] = 19; /* non-cubic: checks the axis order */
    bits = voxelize_bits(ctx, m.pos, m.vertex_count, m.idx, m.triangle_count, &g, NULL);
    bytes = (voxgi_grid_voxel_count(&g) + 31) / 32 * 4;
    TH_CHECK(voxgi_binvox_write(f, &g, bits) == VOXGI_OK, "write failed");
    len = ftell(f);
    rewind(f);
    TH_CHECK(voxgi_binvox_read(f, &g2, NULL, 0, &need) == VOXGI_OK && need == bytes, "header read failed");
    rewind(f);
    back = (uint32_t *)malloc(need);
    TH_CHECK(voxgi_binvox_read(f, &g2, back, need, NULL) == VOXGI_OK, "read failed");
    /* field by field: the struct's padding is not part of the grid (and no read writes it) */
    TH_CHECK(g2.origin[0] == g.origin[0] && g2.origin[1] == g.origin[1] && g2.origin[2] == g.origin[2] &&
             g2.voxel_size == g.voxel_size && g2.res[0] == g.res[0] && g2.res[1] == g.res[1] && g2.res[2] == g.res[2],
             "grid differs after the round trip: origin %g %g %g, size %g, res %d %d %d",
             g2.origin[0], g2.origin[1], g2.origin[2], g2.voxel_size, g2.res[0], g2.res[1], g2.res[2]);
    TH_CHECK(memcmp(bits, back, bytes) == 0, "bits differ after the round trip");
    {   /* truncated: every shorter prefix must fail cleanly */
        char *buf = (char *)malloc((size_t)len);
        long cut;
        int bad = 0;
        rewind(f);
        if (fread(buf, 1, (size_t)len, f) != (size_t)len) bad++;
        for (cut = 0; cut < len; cut += 1 + cut / 8) {
            FILE *t = tmpfile();
            voxgi_grid gt;
            fwrite(buf, 1, (size_t)cut, t);
            rewind(t);
            if (voxgi_binvox_read(t, &gt, back, need, NULL) == VOXGI_OK) bad++;
            fclose(t);
        }
        TH_CHECK(bad == 0, "%d truncated files accepted", bad);
        free(buf);
    }
    fclose(f);
    free(bits);
    free(back);
    vxt_shape_free(&m);
    voxgi_destroy(ctx);
}

static double mean_channel(const float *rgb, size_t pixels, int ch)
{
    double s = 0;
    size_t i;
    for (i = 0; i < pixels; i++) s += rgb[3 * i + (size_t)ch];
    return s / (double)pixels;
}

/* The built-in scenes: valid; the furnace at radiance 2; the leak box black inside exactly; the
   Cornell box's light seen at its radiance, the room lit. */
static void test_builtin_scenes(void)
{
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    const char *names = voxgi_builtin_scene_names();
    voxgi_builtin_scene bs;
    voxgi_render_desc d;
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
        d.method = VOXGI_RENDER_REFERENCE;
        d.bounces = strcmp(name, "cornell-box") == 0 ? 0 : -1;
        d.direct_only = d.bounces == 0; /* the Cornell box: the direct light alone (the old bounces 0) */
        TH_CHECK(voxgi_render(ctx, &bs.scene, &d, rgb, 48 * 48 * 12, NULL) == VOXGI_OK, "%s: %s", name, voxgi_last_error(ctx));
        mean = mean_channel(rgb, 48 * 48, 0);
        for (i = 0; i < 48 * 48; i++) {
            lit += rgb[3 * i] > 0;
            light_pixels += rgb[3 * i] == 17.0f && rgb[3 * i + 1] == 12.0f && rgb[3 * i + 2] == 4.0f;
        }
        printf("    %-12s %lu triangles, mean red radiance %.4f, %lu of 2304 pixels lit\n", name, (unsigned long)(bs.scene.meshes[0].index_count / 3), mean,
               (unsigned long)lit);
        if (strcmp(name, "furnace") == 0) TH_CHECK(fabs(mean - 2) < 0.02, "furnace mean %g", mean);
        else if (strcmp(name, "leak-box") == 0 || strcmp(name, "leak-room") == 0) TH_CHECK(lit == 0, "%s: %lu pixels lit inside the closed box", name, (unsigned long)lit);
        else if (strcmp(name, "cornell-box") == 0) TH_CHECK(light_pixels >= 4 && lit > 1200, "Cornell box: %lu light pixels, %lu lit", (unsigned long)light_pixels, (unsigned long)lit);
        else if (strcmp(name, "foliage") == 0) TH_CHECK(lit > 1400 && lit < 2000, "foliage: %lu lit (the sky above the ground is black)", (unsigned long)lit);
        else TH_CHECK(lit > 1800, "%s: %lu lit", name, (unsigned long)lit);
        voxgi_builtin_scene_destroy(ctx, &bs);
        at = strstr(at, name) + strlen(name);
        n++;
    }
    TH_CHECK(n == 6, "%d built-in scenes", n);
    TH_CHECK(voxgi_builtin_scene_create(ctx, "no-such", &bs) == VOXGI_ERR_INVALID_ARGUMENT, "an unknown name accepted");
    free(rgb);
    voxgi_destroy(ctx);
}

int main(void)
{
    TH_RUN(test_binvox_roundtrip);
    TH_RUN(test_builtin_scenes);
    return th_finish();
}
