/* Points to trace cones from, shared by the CPU and GL cone tests. */
#ifndef VOXGI_TESTS_CONE_POINTS_H
#define VOXGI_TESTS_CONE_POINTS_H
#include "fixtures.h"

/* n points inside the Cornell box (0.03..0.53 m on each axis) with any normal, drawn from fx_rng seed;
   single[i] (if not NULL): a cone from the same point along the same direction, half-angle in
   0.03..0.63, the rest zero. */
static void cornell_cone_points(unsigned seed, int n, float *pos, float *nrm, voxgi_cone *single)
{
    int i, a;
    fx_rng g = fx_rng_seeded(seed);
    for (i = 0; i < n; i++) {
        double len = 0;
        for (a = 0; a < 3; a++) {
            pos[3 * i + a] = (float)fx_rng_range(&g, 0.03, 0.53);
            nrm[3 * i + a] = (float)fx_rng_range(&g, -1, 1);
            len += nrm[3 * i + a] * nrm[3 * i + a];
        }
        if (len < 1e-4) nrm[3 * i + 1] = 1;
        if (!single) continue;
        memset(&single[i], 0, sizeof single[i]);
        for (a = 0; a < 3; a++) { single[i].origin[a] = pos[3 * i + a]; single[i].direction[a] = nrm[3 * i + a]; }
        single[i].half_angle = (float)fx_rng_range(&g, 0.03, 0.63);
    }
}
#endif
