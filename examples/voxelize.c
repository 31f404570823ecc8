/* examples/voxelize.c - voxelize a small built-in mesh on the CPU and print what it found. */
#define VOXGI_IMPLEMENTATION
#define VOXGI_NO_GL
#include "../voxgi.h"
#include <stdlib.h>

int main(void)
{
    /* a tetrahedron */
    static const float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    static const uint32_t tri[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    voxgi_desc desc = {0};
    voxgi_mesh mesh = {0};
    voxgi_scene scene = {0};
    voxgi_fit_desc fit = {0};
    voxgi_voxelize_desc vd = {0};
    voxgi_context *ctx;
    voxgi_voxels *vox;
    voxgi_voxels_info info;
    uint32_t *bits;
    size_t bytes;
    int i, j, k;

    desc.backend = VOXGI_BACKEND_CPU;
    if (voxgi_create(&desc, &ctx) != VOXGI_OK) return 1;
    mesh.positions = pos, mesh.vertex_count = 4, mesh.indices = tri, mesh.index_count = 12;
    scene.meshes = &mesh, scene.mesh_count = 1;
    fit.res = 8;                                   /* 8 voxels along the longest axis */
    if (voxgi_fit_grid(ctx, &scene, &fit, &vd.grid) != VOXGI_OK ||
        voxgi_voxelize(ctx, &scene, &vd, &vox) != VOXGI_OK) {
        fprintf(stderr, "voxgi: %s\n", voxgi_last_error(ctx));
        return 1;
    }
    voxgi_voxels_query(vox, &info);
    printf("%llu of %d^3 voxels touch the tetrahedron (%.2f ms)\n", (unsigned long long)info.voxel_count, vd.grid.res[0], info.ms);

    voxgi_voxels_read(ctx, vox, NULL, 0, &bytes);  /* size query, then the bits */
    bits = (uint32_t *)malloc(bytes);
    voxgi_voxels_read(ctx, vox, bits, bytes, NULL);
    for (k = 0; k < vd.grid.res[2]; k += 3) {      /* a few z slices, y up */
        printf("slice z=%d\n", k);
        for (j = vd.grid.res[1] - 1; j >= 0; j--, putchar('\n'))
            for (i = 0; i < vd.grid.res[0]; i++)
                putchar(voxgi_bit_get(bits, (uint64_t)i + (uint64_t)vd.grid.res[0] * ((uint64_t)j + (uint64_t)vd.grid.res[1] * (uint64_t)k)) ? '#' : '.');
    }
    free(bits);
    voxgi_voxels_destroy(ctx, vox);
    voxgi_destroy(ctx);
    return 0;
}
