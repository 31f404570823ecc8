/* Renders your own mesh file (OBJ+MTL, OFF, STL, PLY, glTF) lit by a sun and writes a PPM image. */
#define VOXGI_IMPLEMENTATION               /* in exactly one .c file of your project */
#define VOXGI_IO_IMPLEMENTATION            /* likewise: voxgi_io.h's loaders */
#include "../voxgi_io.h"                   /* includes voxgi.h; next to your file: "voxgi_io.h" */

int main(int argc, char **argv)
{
    static float rgb[128 * 128 * 3];
    voxgi_light sun = {.type = VOXGI_LIGHT_DIRECTIONAL, .direction = {0.36f, -0.8f, 0.48f}, .intensity = {3, 3, 3}};
    voxgi_desc desc = {.backend = VOXGI_BACKEND_CPU};
    voxgi_render_desc d = {.method = VOXGI_RENDER_VCT, .camera = {.width = 128, .height = 128}}; /* zero eye: views the bounds */
    voxgi_io_mesh m;
    voxgi_scene scene;
    voxgi_context *ctx;
    char err[512];
    FILE *f;
    int i, ok;

    if (argc != 3) return fprintf(stderr, "usage: own_mesh MESH out.ppm\n"), 2;
    if (voxgi_io_load_mesh(argv[1], &m, err, sizeof err) != 0) return fprintf(stderr, "%s\n", err), 1;
    scene = voxgi_io_mesh_scene(&m);       /* the mesh and its materials */
    scene.lights = &sun, scene.light_count = 1; /* a mesh file brings no light */
    if (voxgi_create(&desc, &ctx) != VOXGI_OK) return 1;
    ok = voxgi_render(ctx, &scene, &d, rgb, sizeof rgb, NULL) == VOXGI_OK;
    if (!ok) fprintf(stderr, "voxgi: %s\n", voxgi_last_error(ctx));
    if (ok && (ok = (f = fopen(argv[2], "wb")) != NULL)) { /* binary PPM, radiance 1 as white */
        fprintf(f, "P6\n128 128\n255\n");
        for (i = 0; i < 128 * 128 * 3; i++) fputc(rgb[i] >= 1 ? 255 : rgb[i] > 0 ? (int)(255 * rgb[i] + 0.5f) : 0, f);
        ok = fclose(f) == 0;
    }
    voxgi_destroy(ctx);
    voxgi_io_mesh_free(&m);
    return ok ? 0 : 1;
}
