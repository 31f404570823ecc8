/* tools/ray_sets.h - the two ray sets of `voxgi bench rays`, shared with the Embree anchor
 * (bench/anchor_embree.cpp) so that both cast exactly the same rays. C and C++. */
#ifndef VXT_RAY_SETS_H
#define VXT_RAY_SETS_H
#include <math.h>
#include <stddef.h>
#include <stdint.h>

#define VXT_CAMERA_SIDE 512 /* the coherent set: a 512 x 512 camera */

/* A ray is 8 floats: origin, tmin, direction, tmax (voxgi_ray's layout). */

/* The bounding sphere of n vertices (3 floats each): the box's centre and half its diagonal. */
static inline void vxt_bounding_sphere(const float *pos, size_t n, double centre[3], double *radius)
{
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, r = 0;
    size_t i;
    int k;
    for (i = 0; i < n; i++)
        for (k = 0; k < 3; k++) { lo[k] = fmin(lo[k], pos[3 * i + (size_t)k]); hi[k] = fmax(hi[k], pos[3 * i + (size_t)k]); }
    for (k = 0; k < 3; k++) { centre[k] = 0.5 * (lo[k] + hi[k]); r += 0.25 * (hi[k] - lo[k]) * (hi[k] - lo[k]); }
    *radius = sqrt(r);
}

/* The coherent set: a pinhole camera looking at c from direction (1, 0.5, 2) at 2.5 r, its
   vertical field of view just fitting the sphere (half-angle asin 0.4), rays from the eye
   through the pixel centres, tile by tile (4 x 4 pixels, rows from the top), t in [0, inf). */
static inline void vxt_camera_rays(const double c[3], double r, float *rays)
{
    const int w = VXT_CAMERA_SIDE;
    double dir[3] = {1, 0.5, 2}, len = sqrt(1 + 0.25 + 4), eye[3], f[3], right[3], up[3], th = 0.4 / sqrt(1 - 0.16);
    int a, tx, ty, x, y;
    size_t i = 0;
    for (a = 0; a < 3; a++) { eye[a] = c[a] + 2.5 * r * dir[a] / len; f[a] = -dir[a] / len; }
    right[0] = -f[2]; right[1] = 0; right[2] = f[0]; /* f x (0, 1, 0) */
    len = sqrt(right[0] * right[0] + right[2] * right[2]);
    right[0] /= len; right[2] /= len;
    up[0] = right[1] * f[2] - right[2] * f[1]; up[1] = right[2] * f[0] - right[0] * f[2]; up[2] = right[0] * f[1] - right[1] * f[0];
    for (ty = 0; ty < w; ty += 4)
        for (tx = 0; tx < w; tx += 4)
            for (y = ty; y < ty + 4; y++)
                for (x = tx; x < tx + 4; x++, i++) {
                    double sx = (2 * (x + 0.5) / w - 1) * th, sy = (1 - 2 * (y + 0.5) / w) * th;
                    for (a = 0; a < 3; a++) {
                        rays[8 * i + (size_t)a] = (float)eye[a];
                        rays[8 * i + 4 + (size_t)a] = (float)(f[a] + sx * right[a] + sy * up[a]);
                    }
                    rays[8 * i + 3] = 0;
                    rays[8 * i + 7] = INFINITY;
                }
}

/* A uniform random point on the sphere (c, r): xorshift64* and the z-phi method. */
static inline void vxt_sphere_point(uint64_t *state, const double c[3], double r, float p[3])
{
    double z, phi, s;
    uint64_t x = *state;
    x ^= x >> 12; x ^= x << 25; x ^= x >> 27;
    z = 2.0 * (double)((x * 0x2545F4914F6CDD1Dull) >> 11) / 9007199254740992.0 - 1.0;
    x ^= x >> 12; x ^= x << 25; x ^= x >> 27;
    phi = 2 * 3.14159265358979323846 * (double)((x * 0x2545F4914F6CDD1Dull) >> 11) / 9007199254740992.0;
    *state = x;
    s = sqrt(1 - z * z);
    p[0] = (float)(c[0] + r * s * cos(phi));
    p[1] = (float)(c[1] + r * s * sin(phi));
    p[2] = (float)(c[2] + r * z);
}

/* The incoherent set: n segments between two uniform random points on the sphere, as rays from
   the first with direction to the second and t in [0, 1]. */
static inline void vxt_segment_rays(const double c[3], double r, size_t n, float *rays)
{
    uint64_t state = 0x9E3779B97F4A7C15ull;
    size_t i;
    int k;
    for (i = 0; i < n; i++) {
        float p[3], q[3];
        vxt_sphere_point(&state, c, r, p);
        vxt_sphere_point(&state, c, r, q);
        for (k = 0; k < 3; k++) { rays[8 * i + (size_t)k] = p[k]; rays[8 * i + 4 + (size_t)k] = q[k] - p[k]; }
        rays[8 * i + 3] = 0;
        rays[8 * i + 7] = 1;
    }
}
#endif
