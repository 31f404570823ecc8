/* examples/render.c - one image of a mesh by any method through voxgi_render, to PNG.
       render MESH METHOD out.png [SIZE]
   METHOD is reference, vct, tsm, rsm, sh, ssao, vao, ssgi, hybrid or linespace; SIZE the image's
   width and height in pixels (default: the library's). Every other setting is the library's
   default: the desc's zero fields, which voxgi resolves and reports in info.used. Runs on the CPU.
   Links the implementation object (build/voxgi_impl.o) and tools/mesh_io.c. */
#include "../voxgi.h"
/* The voxgi tool's helpers, as the library has no mesh loader or PNG writer yet (link tools/mesh_io.c): */
#include "../tools/mesh_io.h"
#include "../tools/image_io.h"

int main(int argc, char **argv)
{
    vxt_mesh m = {0};
    voxgi_material *materials;
    voxgi_mesh mesh = {0};
    voxgi_light sun = {.type = VOXGI_LIGHT_DIRECTIONAL, .direction = {0.36f, -0.8f, 0.48f}, .intensity = {3, 3, 3}};
    voxgi_scene scene = {0};
    voxgi_desc desc = {0};
    voxgi_render_desc d = {0}, used;
    voxgi_render_info info;
    voxgi_context *ctx;
    float *rgb = NULL;
    char err[512], line[1024];
    int method = argc >= 4 ? voxgi_render_method_find(argv[2]) : -1, size = argc == 5 ? atoi(argv[4]) : 0, ok, i;
    size_t k;

    if (argc < 4 || argc > 5 || method < 0 || size < 0) {
        fprintf(stderr, "usage: render MESH METHOD out.png [SIZE]   (METHOD: reference, vct, tsm, rsm, sh, ssao, vao, ssgi, hybrid, linespace)\n");
        return 2;
    }
    if (vxt_mesh_load(argv[1], &m, err, sizeof err) != 0) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    materials = (voxgi_material *)calloc(m.material_count, sizeof *materials);
    for (k = 0; materials && k < m.material_count; k++) {
        memcpy(materials[k].albedo, m.materials[k].albedo, sizeof materials[k].albedo);
        memcpy(materials[k].emission, m.materials[k].emission, sizeof materials[k].emission);
        materials[k].transparency = 1.0f - m.materials[k].opacity;
    }
    mesh.positions = m.positions, mesh.vertex_count = m.vertex_count, mesh.normals = m.normals;
    mesh.indices = m.indices, mesh.index_count = 3 * m.triangle_count, mesh.material_ids = m.material_ids;
    scene.meshes = &mesh, scene.mesh_count = 1, scene.materials = materials, scene.material_count = m.material_count;
    /* A mesh file brings no light, and a scene without one renders black: the example adds a sun
       (irradiance 3, from above, behind the default camera). The ambient occlusion methods (ssao,
       vao) show the occluded share instead, and linespace only an area light's (an emissive
       material's) soft shadows: on a convex mesh without an emitter those images are black. */
    scene.lights = &sun, scene.light_count = 1;
    d.method = (voxgi_render_method)method;
    d.camera.width = d.camera.height = size;   /* 0: the library's size; the zero eye and target: it views the bounds */

    desc.backend = VOXGI_BACKEND_CPU;
    if (!materials || voxgi_create(&desc, &ctx) != VOXGI_OK) return 1;
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
    free(materials);
    vxt_mesh_free(&m);
    return ok ? 0 : 1;
}
