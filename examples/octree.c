/* examples/octree.c - a sparse voxel octree of a tetrahedron on the CPU: its nodes, its memory
   against the dense grid, and the value at a few points (a leaf where the surface is, nothing
   inside or outside it). Links the implementation object (build/voxgi_impl.o). */
#include "../voxgi.h"

int main(void)
{
    static const float xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    static const uint32_t tri[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    static const voxgi_material red = {.albedo = {0.9f, 0.2f, 0.1f}};
    static const struct { const char *what; float p[3]; } query[] = {
        {"on the slanted face", {0.3f, 0.3f, 0.4f}},   /* x + y + z = 1 */
        {"inside", {0.2f, 0.2f, 0.2f}},                /* more than a voxel from every face */
        {"outside", {0.8f, 0.8f, 0.8f}},
    };
    voxgi_mesh mesh = {0};
    voxgi_scene scene = {0};
    voxgi_desc desc = {0};
    voxgi_fit_desc fit = {0};
    voxgi_voxelize_desc vd = {0};
    voxgi_svo_desc sd = {0};
    voxgi_context *ctx;
    voxgi_voxels *vox = NULL;
    voxgi_svo *svo = NULL;
    voxgi_svo_info info;
    size_t q;
    int ok, level;

    mesh.positions = xyz, mesh.vertex_count = 4, mesh.indices = tri, mesh.index_count = 12;
    scene.meshes = &mesh, scene.mesh_count = 1, scene.materials = &red, scene.material_count = 1;
    desc.backend = VOXGI_BACKEND_CPU;
    if (voxgi_create(&desc, &ctx) != VOXGI_OK) return 1;
    fit.res = 32;                                  /* 32 voxels along the longest side */
    vd.attributes = VOXGI_ATTRIBUTE_ALBEDO;        /* the octree holds what the voxels hold */
    ok = voxgi_fit_grid(ctx, &scene, &fit, &vd.grid) == VOXGI_OK && voxgi_voxelize(ctx, &scene, &vd, &vox) == VOXGI_OK &&
         voxgi_svo_create(ctx, vox, &sd, &svo) == VOXGI_OK;
    if (!ok) {
        fprintf(stderr, "voxgi: %s\n", voxgi_last_error(ctx));
        voxgi_voxels_destroy(ctx, vox);
        voxgi_destroy(ctx);
        return 1;
    }
    voxgi_svo_query(svo, &info);
    printf("octree of depth %d: %llu leaf voxels, %llu node slots, %llu leaf slots\n", info.depth, (unsigned long long)info.leaf_voxels,
           (unsigned long long)info.nodes, (unsigned long long)info.leaf_slots);
    for (level = 0; level <= info.depth; level++) printf("  level %d: %llu nodes\n", level, (unsigned long long)info.level_nodes[level]);
    printf("memory: %zu bytes (dense albedo grid: %zu bytes)\n", info.bytes, info.dense_bytes);

    for (q = 0; q < sizeof query / sizeof query[0]; q++) {
        uint32_t v[3];
        float albedo[4];                           /* rgb and alpha: alpha 1 in a set voxel, 0 where no leaf is */
        int a;
        for (a = 0; a < 3; a++) v[a] = (uint32_t)((query[q].p[a] - vd.grid.origin[a]) / vd.grid.voxel_size);
        if (voxgi_svo_lookup(ctx, svo, VOXGI_ATTRIBUTE_ALBEDO, info.depth, 1, v, albedo) != VOXGI_OK) {
            fprintf(stderr, "voxgi: %s\n", voxgi_last_error(ctx));
            ok = 0;
            break;
        }
        printf("point (%.2f %.2f %.2f) %s: voxel (%u %u %u) %s, albedo %.2f %.2f %.2f alpha %.2f\n", query[q].p[0], query[q].p[1], query[q].p[2],
               query[q].what, v[0], v[1], v[2], albedo[3] > 0 ? "set" : "empty", albedo[0], albedo[1], albedo[2], albedo[3]);
    }
    voxgi_svo_destroy(ctx, svo);
    voxgi_voxels_destroy(ctx, vox);
    voxgi_destroy(ctx);
    return ok ? 0 : 1;
}
