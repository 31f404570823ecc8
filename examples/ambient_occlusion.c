/* examples/ambient_occlusion.c - screen-space ambient occlusion (voxgi_ao) on the caller's own
   G-buffer: a floor (y = 0) meeting a wall (z = 0), ray cast analytically per pixel, no mesh at
   all. Prints the mean occlusion near the corner, where the wall hides up to half the floor's
   sky, and on the open floor and wall, farther than the rays' reach from the corner: nothing
   hides anything there, so 0. Links the implementation object (build/voxgi_impl.o). */
#include "../voxgi.h"
#include <math.h>

enum { W = 64, H = 64 };

int main(void)
{
    static float pos[3 * W * H], nrm[3 * W * H], ao[W * H];
    voxgi_camera cam = {.eye = {0, 0.5, 2}, .target = {0, 0.5, 0}, .fovy_degrees = 60, .width = W, .height = H}; /* along -z, 0.5 m up */
    voxgi_ao_desc ad = {0};
    voxgi_desc desc = {0};
    voxgi_context *ctx;
    double tan_half = tan(cam.fovy_degrees * 3.14159265358979323846 / 360), sum[3] = {0, 0, 0};
    int x, y, n[3] = {0, 0, 0}, region;

    /* The G-buffer: per pixel the first surface the ray through its centre meets (gluLookAt, rows
       from the top, as voxgi's camera): its position and its normal facing the camera. */
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            double dx = (2 * (x + 0.5) / W - 1) * tan_half * W / H, dy = (1 - 2 * (y + 0.5) / H) * tan_half; /* direction (dx, dy, -1) */
            float *p = pos + 3 * (y * W + x), *nm = nrm + 3 * (y * W + x);
            if (0.5 + 2 * dy >= 0) { /* the wall, 2 m ahead */
                p[0] = (float)(2 * dx), p[1] = (float)(0.5 + 2 * dy), p[2] = 0;
                nm[2] = 1;
            } else { /* the floor, at t = 0.5 / -dy */
                p[0] = (float)(0.5 / -dy * dx), p[1] = 0, p[2] = (float)(2 - 0.5 / -dy);
                nm[1] = 1;
            }
        }

    desc.backend = VOXGI_BACKEND_CPU;
    if (voxgi_create(&desc, &ctx) != VOXGI_OK) return 1;
    ad.camera = cam;
    ad.positions = pos, ad.normals = nrm;
    ad.method = VOXGI_AO_SCREEN;               /* ray marching through the G-buffer's depth */
    ad.radius = 0.25f;                         /* the rays' reach, world units */
    ad.rays = 64;                              /* per pixel (default 16) */
    if (voxgi_ao(ctx, &ad, ao, sizeof ao) != VOXGI_OK) {
        fprintf(stderr, "voxgi: %s\n", voxgi_last_error(ctx));
        voxgi_destroy(ctx);
        return 1;
    }
    for (x = 0; x < W * H; x++) { /* 0: within 0.05 of the corner; 1: open floor; 2: open wall (beyond 2 x radius) */
        const float *p = pos + 3 * x;
        region = p[1] < 0.05f && p[2] < 0.05f ? 0 : p[2] > 0.5f ? 1 : p[1] > 0.5f ? 2 : -1;
        if (region >= 0) sum[region] += ao[x], n[region]++;
    }
    printf("occlusion at the corner: %.3f (%d pixels)\n", sum[0] / (n[0] ? n[0] : 1), n[0]);
    printf("occlusion on the open floor: %.3f (%d pixels)\n", sum[1] / (n[1] ? n[1] : 1), n[1]);
    printf("occlusion on the open wall: %.3f (%d pixels)\n", sum[2] / (n[2] ? n[2] : 1), n[2]);
    voxgi_destroy(ctx);
    return 0;
}
