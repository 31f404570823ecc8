/* Compile matrix, translation unit 2: a user of the API (with VOXGI_STATIC it carries its own
   copy of the implementation, as a second static copy must link beside the first).

   A part left out (VOXGI_NO_<PART>) takes its implementation only: every declaration stays, and no
   public struct's layout depends on the part macros. So this file names each part's functions
   (unevaluated, so that nothing links against what was left out) and types whatever the macros;
   voxgi_render refuses a left-out part's methods with VOXGI_ERR_UNSUPPORTED and renders the others;
   and `tu_use --layout` prints the public structs' sizes, which tests/run.sh holds to the whole
   build's. */
#ifdef VOXGI_STATIC
#define VOXGI_IMPLEMENTATION
#endif
#include "../../voxgi.h"
#include <stddef.h>
#include <stdio.h>
#include <string.h>

int tu_impl_version(void);

/* Declared whatever the macros: sizeof does not evaluate its operand, so nothing is referenced. */
#define TU_DECLARED(f) ((void)sizeof(&(f)))

static void tu_declared(void)
{
    TU_DECLARED(voxgi_svo_create);               /* 7. octree */
    TU_DECLARED(voxgi_svo_sample);
    TU_DECLARED(voxgi_cone_trace);               /* 8. cone tracing */
    TU_DECLARED(voxgi_specular_half_angle);
    TU_DECLARED(voxgi_inject_light);             /* 9. light injection */
    TU_DECLARED(voxgi_tsm_create);               /* 10. light space */
    TU_DECLARED(voxgi_rsm_create);
    TU_DECLARED(voxgi_sh_create);
    TU_DECLARED(voxgi_ao);                       /* 11. screen space */
    TU_DECLARED(voxgi_ssgi);
    TU_DECLARED(voxgi_screen_filter);
    TU_DECLARED(voxgi_voxels_occluded);          /* 5. voxel visibility: never left out */
    TU_DECLARED(voxgi_linespace_create);         /* 12. line space */
    TU_DECLARED(voxgi_linespace_query);
    TU_DECLARED(voxgi_render);                   /* 14. one image, any method */
    TU_DECLARED(voxgi_render_resolve);
    TU_DECLARED(voxgi_plan);
}

/* The public structs' sizes (and where the render desc's and info's parts lie) on one line. */
#define TU_SIZE(t) printf(" %s %lu", #t, (unsigned long)sizeof(t))
#define TU_OFFSET(t, m) printf(" %s.%s %lu", #t, #m, (unsigned long)offsetof(t, m))
static void tu_layout(void)
{
    printf("layout:");
    TU_SIZE(voxgi_desc);
    TU_SIZE(voxgi_render_desc);
    TU_SIZE(voxgi_render_info);
    TU_SIZE(voxgi_plan_info);
    TU_SIZE(voxgi_svo_desc);
    TU_SIZE(voxgi_svo_info);
    TU_SIZE(voxgi_cone_desc);
    TU_SIZE(voxgi_radiance_source);
    TU_SIZE(voxgi_inject_desc);
    TU_SIZE(voxgi_tsm_desc);
    TU_SIZE(voxgi_tsm_info);
    TU_SIZE(voxgi_rsm_desc);
    TU_SIZE(voxgi_rsm_info);
    TU_SIZE(voxgi_sh_desc);
    TU_SIZE(voxgi_sh_info);
    TU_SIZE(voxgi_ao_desc);
    TU_SIZE(voxgi_ssgi_desc);
    TU_SIZE(voxgi_screen_filter_desc);
    TU_SIZE(voxgi_linespace_desc);
    TU_SIZE(voxgi_linespace_info);
    TU_SIZE(voxgi_linespace_light_desc);
    TU_SIZE(voxgi_linespace_stats);
    TU_OFFSET(voxgi_render_desc, vct);
    TU_OFFSET(voxgi_render_desc, tsm);
    TU_OFFSET(voxgi_render_desc, rsm);
    TU_OFFSET(voxgi_render_desc, sh);
    TU_OFFSET(voxgi_render_desc, screen);
    TU_OFFSET(voxgi_render_desc, linespace);
    TU_OFFSET(voxgi_render_desc, reference);
    TU_OFFSET(voxgi_render_info, tree);
    TU_OFFSET(voxgi_render_info, shadow_rays);
    printf("\n");
}

/* Whether this build left out method m (the parts voxgi.h's CONFIGURATION names). */
static int tu_left_out(int m)
{
    switch (m) {
#ifdef VOXGI_NO_REFERENCE
    case VOXGI_RENDER_REFERENCE: return 1;
#endif
#if defined(VOXGI_NO_CONE_TRACING) || defined(VOXGI_NO_LIGHT_INJECTION)
    case VOXGI_RENDER_VCT: return 1;
#endif
#ifdef VOXGI_NO_LIGHT_SPACE
    case VOXGI_RENDER_TSM: case VOXGI_RENDER_RSM: case VOXGI_RENDER_SH: return 1;
#endif
#ifdef VOXGI_NO_SCREEN_SPACE
    case VOXGI_RENDER_SSAO: case VOXGI_RENDER_VAO: case VOXGI_RENDER_SSGI: case VOXGI_RENDER_HYBRID: return 1;
#endif
#ifdef VOXGI_NO_LINE_SPACE
    case VOXGI_RENDER_LINESPACE: return 1;
#endif
    default: return 0;
    }
}

/* Every method once at 4 x 4 (a grid of 8 where it has one), and VCT from an octree: a left-out
   part's methods refused (VOXGI_ERR_UNSUPPORTED) by voxgi_render and voxgi_plan, the rest rendered
   and planned. 0 when all are as expected. */
static int tu_render(voxgi_context *ctx, const voxgi_scene *scene)
{
    float rgb[4 * 4 * 3];
    voxgi_plan_info plan;
    int m, bad = 0;
    for (m = 0; m <= VOXGI_RENDER_METHOD_COUNT; m++) { /* the last: VCT from an octree */
        voxgi_render_desc d;
        voxgi_result want, r;
        memset(&d, 0, sizeof d);
        d.method = (voxgi_render_method)(m < VOXGI_RENDER_METHOD_COUNT ? m : VOXGI_RENDER_VCT);
        d.camera.width = d.camera.height = 4;
        d.samples = 1;
        if (d.method == VOXGI_RENDER_VCT || d.method == VOXGI_RENDER_RSM || d.method == VOXGI_RENDER_SH || d.method == VOXGI_RENDER_VAO ||
            d.method == VOXGI_RENDER_HYBRID)
            d.resolution = 8;
        want = tu_left_out((int)d.method) ? VOXGI_ERR_UNSUPPORTED : VOXGI_OK;
        if (m == VOXGI_RENDER_METHOD_COUNT) {
            d.vct.radiance = VOXGI_VCT_OCTREE;
#ifdef VOXGI_NO_OCTREE
            want = VOXGI_ERR_UNSUPPORTED;
#endif
        }
        r = voxgi_render(ctx, scene, &d, rgb, sizeof rgb, NULL);
        if (r != want) {
            fprintf(stderr, "voxgi_render %s%s: %s (%s), expected %s\n", voxgi_render_method_name(d.method), m == VOXGI_RENDER_METHOD_COUNT ? " (octree)" : "",
                    voxgi_result_string(r), voxgi_last_error(ctx), voxgi_result_string(want));
            bad = 1;
        }
        r = voxgi_plan(ctx, scene, &d, 0, &plan);
        if (r != want) {
            fprintf(stderr, "voxgi_plan %s%s: %s (%s), expected %s\n", voxgi_render_method_name(d.method), m == VOXGI_RENDER_METHOD_COUNT ? " (octree)" : "",
                    voxgi_result_string(r), voxgi_last_error(ctx), voxgi_result_string(want));
            bad = 1;
        }
    }
    return bad;
}

int main(int argc, char **argv)
{
    static const float pos[9] = {0.1f, 0.1f, 0.1f, 0.9f, 0.2f, 0.3f, 0.2f, 0.8f, 0.6f};
    voxgi_desc desc;
    voxgi_context *ctx = NULL;
    voxgi_mesh mesh;
    voxgi_scene scene;
    voxgi_light lights[2];
    voxgi_voxelize_desc vd;
    voxgi_voxels *vox = NULL;
    voxgi_voxels_info info;
    int bad;
    tu_declared();
    if (argc > 1 && !strcmp(argv[1], "--layout")) {
        tu_layout();
        return 0;
    }
    memset(&desc, 0, sizeof desc);
    memset(&mesh, 0, sizeof mesh);
    memset(&scene, 0, sizeof scene);
    memset(lights, 0, sizeof lights);
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
    /* a sun for the maps, a rect light for the line space */
    lights[0].type = VOXGI_LIGHT_DIRECTIONAL;
    lights[0].direction[2] = 1;
    lights[0].intensity[0] = lights[0].intensity[1] = lights[0].intensity[2] = 1;
    lights[1].type = VOXGI_LIGHT_RECT;
    lights[1].position[0] = 0.4f; lights[1].position[1] = 0.4f; lights[1].position[2] = -1;
    lights[1].edge_u[0] = 0.2f; lights[1].edge_v[1] = 0.2f; /* edge_u x edge_v = +Z: toward the triangle */
    lights[1].intensity[0] = lights[1].intensity[1] = lights[1].intensity[2] = 1;
    scene.lights = lights;
    scene.light_count = 2;
    bad = tu_render(ctx, &scene);
    voxgi_destroy(ctx);
    if (bad) return 4;
    return (info.voxel_count > 0 && tu_impl_version() == VOXGI_VERSION) ? 0 : 3;
}
