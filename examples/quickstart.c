/* Voxelizes a tetrahedron on the CPU and prints how many voxels its surface touches. */
#define VOXGI_IMPLEMENTATION               /* in exactly one .c file of your project */
#include "../voxgi.h"                      /* next to your own file: #include "voxgi.h" */

int main(void)
{
    static const float xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    static const uint32_t tri[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    voxgi_mesh mesh = {.positions = xyz, .vertex_count = 4, .indices = tri, .index_count = 12};
    voxgi_scene scene = {.meshes = &mesh, .mesh_count = 1};
    voxgi_desc desc = {.backend = VOXGI_BACKEND_CPU};
    voxgi_fit_desc fit = {.res = 16};      /* 16 voxels along the scene's longest side */
    voxgi_voxelize_desc vd = {.method = VOXGI_METHOD_CONSERVATIVE};
    voxgi_context *ctx;
    voxgi_voxels *vox;
    voxgi_voxels_info info;
    int ok;

    if (voxgi_create(&desc, &ctx) != VOXGI_OK) return 1;
    ok = voxgi_fit_grid(ctx, &scene, &fit, &vd.grid) == VOXGI_OK && voxgi_voxelize(ctx, &scene, &vd, &vox) == VOXGI_OK;
    if (ok) {
        voxgi_voxels_query(vox, &info);
        printf("%llu voxels\n", (unsigned long long)info.voxel_count);
        voxgi_voxels_destroy(ctx, vox);
    } else {
        fprintf(stderr, "voxgi: %s\n", voxgi_last_error(ctx));
    }
    voxgi_destroy(ctx);
    return ok ? 0 : 1;
}
