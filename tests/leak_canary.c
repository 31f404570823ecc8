/* tests/leak_canary.c - a program that leaks on purpose, to prove the leak checks of the test
 * run still catch voxgi's own leaks. tests/run.sh runs it under AddressSanitizer with the same
 * leak settings as every test (the GL driver's libraries kept loaded, suppressions by driver
 * library) and passes only when LeakSanitizer reports the voxels below, allocated by
 * voxgi_voxelize and never destroyed. It voxelizes on GL when a context can be made (then the
 * driver ran in this process, as in the GL tests) and on the CPU otherwise. */
#include "../voxgi.h"
#include "../tools/headless_gl.h"

int main(void)
{
    static const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    char err[512];
    vxt_gl *gl = vxt_gl_create(VXT_GL_AUTO, err, sizeof err);
    voxgi_desc desc = {0};
    voxgi_context *ctx;
    voxgi_mesh mesh = {0};
    voxgi_scene scene = {0};
    voxgi_voxelize_desc vd = {0};
    voxgi_fit_desc fit = {0};
    voxgi_voxels *leaked = NULL;

    desc.backend = gl ? VOXGI_BACKEND_GL : VOXGI_BACKEND_CPU;
    desc.gl_get_proc_address_user = vxt_gl_get_proc;
    desc.gl_user = gl;
    if (voxgi_create(&desc, &ctx) != VOXGI_OK) return 1;
    mesh.positions = xyz;
    mesh.vertex_count = 3;
    scene.meshes = &mesh;
    scene.mesh_count = 1;
    fit.res = 8;
    if (voxgi_fit_grid(ctx, &scene, &fit, &vd.grid) != VOXGI_OK
        || voxgi_voxelize(ctx, &scene, &vd, &leaked) != VOXGI_OK) return 1;
    printf("leak_canary: voxelized on %s, leaking the voxels\n", gl ? "GL" : "the CPU");
    leaked = NULL; /* the only reference gone: a leak, not memory still reachable at exit */
    voxgi_destroy(ctx);
    vxt_gl_destroy(gl);
    return 0;
}
