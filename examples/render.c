/* examples/render.c - one image of a mesh by any method through voxgi_render, to PNG.
       render MESH METHOD out.png [SIZE]
   METHOD is reference, vct, tsm, rsm, sh, ssao, vao, ssgi, hybrid or linespace; SIZE the image's
   width and height in pixels (default: the library's). Every other setting is the library's
   default: the desc's zero fields, which voxgi resolves and reports in info.used. Runs on the CPU.
   Links the implementation object (build/voxgi_impl.o: voxgi.h's and voxgi_io.h's). */
#include "../voxgi.h"
#include "../voxgi_io.h"         /* the mesh loaders */
#include "../tools/image_io.h"   /* the voxgi tool's PNG writer, as the library has none yet */

int main(int argc, char **argv)
{
    voxgi_io_mesh m;
    voxgi_light sun = {.type = VOXGI_LIGHT_DIRECTIONAL, .direction = {0.36f, -0.8f, 0.48f}, .intensity = {3, 3, 3}};
    voxgi_scene scene;
    voxgi_desc desc = {0};
    voxgi_render_desc d = {0}, used;
    voxgi_render_info info;
    voxgi_context *ctx;
    float *rgb = NULL;
    char err[512], line[1024];
    int method = argc >= 4 ? voxgi_render_method_find(argv[2]) : -1, size = argc == 5 ? atoi(argv[4]) : 0, ok, i;

    if (argc < 4 || argc > 5 || method < 0 || size < 0) {
        fprintf(stderr, "usage: render MESH METHOD out.png [SIZE]   (METHOD: reference, vct, tsm, rsm, sh, ssao, vao, ssgi, hybrid, linespace)\n");
        return 2;
    }
    if (voxgi_io_load_mesh(argv[1], &m, err, sizeof err) != 0) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    scene = voxgi_io_mesh_scene(&m); /* the mesh and its materials */
    /* A mesh file brings no light, and a scene without one renders black: the example adds a sun
       (irradiance 3, from above, behind the default camera). The ambient occlusion methods (ssao,
       vao) show the occluded share instead, and linespace only an area light's (an emissive
       material's) soft shadows: on a convex mesh without an emitter those images are black. */
    scene.lights = &sun, scene.light_count = 1;
    d.method = (voxgi_render_method)method;
    d.camera.width = d.camera.height = size;   /* 0: the library's size; the zero eye and target: it views the bounds */

    desc.backend = VOXGI_BACKEND_CPU;
    if (voxgi_create(&desc, &ctx) != VOXGI_OK) return 1;
    ok = voxgi_render_resolve(ctx, &scene, &d, &used) == VOXGI_OK &&
         (rgb = (float *)malloc((size_t)used.camera.width * (size_t)used.camera.height * 12)) != NULL &&
         voxgi_render(ctx, &scene, &d, rgb, (size_t)used.camera.width * (size_t)used.camera.height * 12, &info) == VOXGI_OK;
    if (ok) {
        voxgi_render_describe(&info.used, line, sizeof line);
        printf("%s\n", line);
        for (i = 0; i < info.stage_count; i++) printf("  %-10s %8.2f ms\n", info.stages[i].name, info.stages[i].ms);
        printf("  %-10s %8.2f ms\n", "all", info.ms);
        ok = vxt_write_png(argv[3], rgb, info.used.camera.width, info.used.camera.height, 1.0f) == 0;
        if (ok) printf("wrote %s (%d x %d)\n", argv[3], info.used.camera.width, info.used.camera.height);
        else fprintf(stderr, "cannot write %s\n", argv[3]);
    } else {
        fprintf(stderr, "voxgi: %s\n", voxgi_last_error(ctx));
    }
    free(rgb);
    voxgi_destroy(ctx);
    voxgi_io_mesh_free(&m);
    return ok ? 0 : 1;
}
