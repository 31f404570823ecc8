/* fuzz/fuzz_svo.c - libFuzzer harness: octree files, voxgi_svo_read_memory on a CPU context. A
 * refusal is VOXGI_ERR_FORMAT (or TOO_LARGE past the context's memory budget); an octree it
 * accepts must answer what it holds (every lookup level, node slots, neighbours, bricks, samples,
 * cones where it holds RADIANCE) and write the same bytes again (docs/volumes-and-octrees.md). */
#include "fuzz.h"

/* Voxel coordinates at level depth: the first voxel, the cube's middle, the last voxel of the
   grid, and one past the cube. */
static void probe_coords(const voxgi_svo_info *info, uint32_t coords[12])
{
    int a;
    for (a = 0; a < 3; a++) {
        coords[a] = 0;
        coords[3 + a] = 1u << (info->depth - 1);
        coords[6 + a] = (uint32_t)info->grid.res[a] - 1;
        coords[9 + a] = 1u << info->depth;
    }
}

static void query(voxgi_context *ctx, const voxgi_svo *svo, const voxgi_svo_info *info)
{
    static const float unit_normals[6] = {0, 1, 0, 0, 0, -1};
    uint32_t coords[12], slot, neighbours[6];
    float out[4 * 64], positions[9], lods[3], world[6], irradiance[6], occlusion[2];
    int level, a, k;
    voxgi_radiance_source source;
    voxgi_cone_desc cones;
    probe_coords(info, coords);
    for (a = 0; a < 3; a++) {
        positions[a] = 0.5f;
        positions[3 + a] = (float)info->grid.res[a] / 2;
        positions[6 + a] = (float)info->grid.res[a] + 1;
    }
    lods[0] = 0;
    lods[1] = 1.5f;
    lods[2] = (float)info->depth;
    for (a = 0; a < 7; a++) {
        voxgi_attribute which = (voxgi_attribute)(1u << a);
        if (!(info->attributes & (unsigned)which)) continue;
        for (level = 0; level <= info->depth; level++) FUZZ_CHECK(voxgi_svo_lookup(ctx, svo, which, level, 4, coords, out) == VOXGI_OK);
        FUZZ_CHECK(voxgi_svo_sample(ctx, svo, which, 3, positions, lods, out) == VOXGI_OK);
        for (level = 0; info->brick_bytes && level < info->depth; level++)
            for (k = 0; k < 4; k++) FUZZ_CHECK(voxgi_svo_brick(ctx, svo, which, level, coords + 3 * k, out) == VOXGI_OK);
    }
    for (level = 0; level < info->depth; level++)
        for (k = 0; k < 4; k++) {
            FUZZ_CHECK(voxgi_svo_node(ctx, svo, level, coords + 3 * k, &slot) == VOXGI_OK);
            if (info->neighbour_bytes) FUZZ_CHECK(voxgi_svo_neighbours(ctx, svo, slot, neighbours) == VOXGI_OK);
        }
    if (!(info->attributes & VOXGI_ATTRIBUTE_RADIANCE)) return;
    for (a = 0; a < 3; a++) { /* two surface points in world units: the grid's middle and a corner */
        world[a] = (float)(info->grid.origin[a] + info->grid.voxel_size * info->grid.res[a] / 2);
        world[3 + a] = (float)info->grid.origin[a];
    }
    memset(&source, 0, sizeof source);
    source.octree = svo;
    memset(&cones, 0, sizeof cones);
    cones.cones = 4;
    if (isfinite(world[0]) && isfinite(world[1]) && isfinite(world[2]) && isfinite(world[3]) && isfinite(world[4]) && isfinite(world[5]))
        FUZZ_CHECK(voxgi_cone_trace(ctx, &source, &cones, 2, world, unit_normals, irradiance, occlusion) == VOXGI_OK);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    voxgi_context *ctx = fuzz_context();
    voxgi_svo *svo = NULL;
    voxgi_svo_info info;
    voxgi_result r = voxgi_svo_read_memory(ctx, data, size, &svo);
    size_t written = 0;
    unsigned char *copy;
    if (r != VOXGI_OK) {
        FUZZ_CHECK(!svo && (r == VOXGI_ERR_FORMAT || r == VOXGI_ERR_TOO_LARGE));
        return 0;
    }
    voxgi_svo_query(svo, &info);
    query(ctx, svo, &info);
    FUZZ_CHECK(voxgi_svo_write_memory(ctx, svo, NULL, 0, &written) == VOXGI_OK && written == size);
    FUZZ_CHECK((copy = (unsigned char *)malloc(size)) != NULL);
    FUZZ_CHECK(voxgi_svo_write_memory(ctx, svo, copy, size, &written) == VOXGI_OK && memcmp(copy, data, size) == 0);
    free(copy);
    voxgi_svo_destroy(ctx, svo);
    return 0;
}
