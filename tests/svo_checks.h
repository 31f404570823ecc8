/* Checks of a sparse voxel octree shared by the CPU and GL tests. */
#ifndef VOXGI_TESTS_SVO_CHECKS_H
#define VOXGI_TESTS_SVO_CHECKS_H

/* Neighbour pointers: for every node of levels 1..depth-1, each of the six points at the node
   one step away at the same level (0 where there is none), and back. Returns the wrong
   pointers; *nodes_out: the nodes seen. */
static int svo_wrong_neighbours(voxgi_context *ctx, const voxgi_svo *svo, int depth, int *nodes_out)
{
    int lev, nodes = 0, wrong = 0;
    for (lev = 1; lev < depth; lev++) {
        uint32_t n = 1u << lev, x, y, z, sh = (uint32_t)(depth - lev);
        for (z = 0; z < n; z++)
            for (y = 0; y < n; y++)
                for (x = 0; x < n; x++) {
                    uint32_t c[3], slot = 0, nb[6], back[6];
                    int dir;
                    c[0] = x << sh; c[1] = y << sh; c[2] = z << sh;
                    voxgi_svo_node(ctx, svo, lev, c, &slot);
                    if (!slot) continue;
                    nodes++;
                    voxgi_svo_neighbours(ctx, svo, slot, nb);
                    for (dir = 0; dir < 6; dir++) {
                        uint32_t d[3], want = 0;
                        int64_t v = (int64_t)(dir / 2 == 0 ? x : (dir / 2 == 1 ? y : z)) + ((dir & 1) ? -1 : 1);
                        d[0] = x; d[1] = y; d[2] = z;
                        if (v >= 0 && v < (int64_t)n) {
                            d[dir / 2] = (uint32_t)v;
                            d[0] <<= sh; d[1] <<= sh; d[2] <<= sh;
                            voxgi_svo_node(ctx, svo, lev, d, &want);
                        }
                        wrong += nb[dir] != want;
                        if (nb[dir]) {
                            voxgi_svo_neighbours(ctx, svo, nb[dir], back);
                            wrong += back[dir ^ 1] != slot;
                        }
                    }
                }
    }
    *nodes_out = nodes;
    return wrong;
}

#endif
