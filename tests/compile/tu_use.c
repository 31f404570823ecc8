/* Compile matrix, translation unit 2: a user of the API (with VOXGI_STATIC it carries its own
   copy of the implementation, as a second static copy must link beside the first). */
#ifdef VOXGI_STATIC
#define VOXGI_IMPLEMENTATION
#endif
#include "../../voxgi.h"
#include <string.h>

int tu_impl_version(void);

/* A part left out takes its declarations with it: its names are free again (as enumerators they
   would clash with any declaration left behind). */
#ifdef VOXGI_NO_OCTREE
enum { voxgi_svo_create, voxgi_svo_sample };
#endif
#ifdef VOXGI_NO_CONE_TRACING
enum { voxgi_cone_trace, voxgi_radiance_source, voxgi_specular_half_angle };
#endif
#ifdef VOXGI_NO_LIGHT_INJECTION
enum { voxgi_inject_light, voxgi_vct_render };
#endif
#ifdef VOXGI_NO_LIGHT_SPACE
enum { voxgi_tsm_create, voxgi_rsm_render, voxgi_sh_create };
#endif
#ifdef VOXGI_NO_SCREEN_SPACE
enum { voxgi_ao, voxgi_ssgi_render, voxgi_screen_filter };
#endif
#if defined(VOXGI_NO_LIGHT_SPACE) && defined(VOXGI_NO_SCREEN_SPACE)
enum { voxgi_voxels_occluded };
#endif
#ifdef VOXGI_NO_LINE_SPACE
enum { voxgi_linespace_create, voxgi_linespace_render };
#endif
#ifdef VOXGI_NO_REFERENCE
enum { voxgi_reference_render };
#endif

int main(void)
{
    static const float pos[9] = {0.1f, 0.1f, 0.1f, 0.9f, 0.2f, 0.3f, 0.2f, 0.8f, 0.6f};
    voxgi_desc desc;
    voxgi_context *ctx = NULL;
    voxgi_mesh mesh;
    voxgi_scene scene;
    voxgi_voxelize_desc vd;
    voxgi_voxels *vox = NULL;
    voxgi_voxels_info info;
    memset(&desc, 0, sizeof desc);
    memset(&mesh, 0, sizeof mesh);
    memset(&scene, 0, sizeof scene);
    memset(&vd, 0, sizeof vd);
    desc.backend = VOXGI_BACKEND_CPU;
    if (voxgi_create(&desc, &ctx) != VOXGI_OK) return 1;
    mesh.positions = pos;
    mesh.vertex_count = 3;
    scene.meshes = &mesh;
    scene.mesh_count = 1;
    vd.grid.voxel_size = 0.25;
    vd.grid.res[0] = vd.grid.res[1] = vd.grid.res[2] = 4;
    if (voxgi_voxelize(ctx, &scene, &vd, &vox) != VOXGI_OK) return 2;
    voxgi_voxels_query(vox, &info);
    voxgi_voxels_destroy(ctx, vox);
    voxgi_destroy(ctx);
    return (info.voxel_count > 0 && tu_impl_version() == VOXGI_VERSION) ? 0 : 3;
}
