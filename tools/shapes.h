/* tools/shapes.h - procedural meshes for the tests, tools and examples (no files needed). */
#ifndef VXT_SHAPES_H
#define VXT_SHAPES_H
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct vxt_shape {
    float *pos;
    uint32_t *idx;
    size_t vertex_count, triangle_count;
} vxt_shape;

static inline void vxt_shape_free(vxt_shape *m)
{
    free(m->pos);
    free(m->idx);
    memset(m, 0, sizeof *m);
}

static inline void vxt_shape_alloc(vxt_shape *m, size_t nv, size_t nt)
{
    m->pos = (float *)malloc(nv * 3 * sizeof(float));
    m->idx = (uint32_t *)malloc(nt * 3 * sizeof(uint32_t));
    m->vertex_count = nv;
    m->triangle_count = nt;
}

/* A closed UV sphere, counter-clockwise seen from outside. */
static inline void vxt_shape_sphere(vxt_shape *m, int slices, int stacks, double radius, double cx, double cy, double cz)
{
    int i, j;
    size_t v = 0, t = 0;
    vxt_shape_alloc(m, (size_t)(slices + 1) * (size_t)(stacks + 1), (size_t)slices * (size_t)stacks * 2);
    for (j = 0; j <= stacks; j++)
        for (i = 0; i <= slices; i++) {
            double th = 3.14159265358979 * j / stacks, ph = 2 * 3.14159265358979 * i / slices;
            m->pos[3 * v + 0] = (float)(cx + radius * sin(th) * cos(ph));
            m->pos[3 * v + 1] = (float)(cy + radius * cos(th));
            m->pos[3 * v + 2] = (float)(cz + radius * sin(th) * sin(ph));
            v++;
        }
    for (j = 0; j < stacks; j++)
        for (i = 0; i < slices; i++) {
            uint32_t a = (uint32_t)(j * (slices + 1) + i), b = a + 1, c = a + (uint32_t)slices + 1, d = c + 1;
            m->idx[3 * t + 0] = a; m->idx[3 * t + 1] = b; m->idx[3 * t + 2] = c; t++;
            m->idx[3 * t + 0] = b; m->idx[3 * t + 1] = d; m->idx[3 * t + 2] = c; t++;
        }
}

/* Axis-aligned box [x0,x1]x[y0,y1]x[z0,z1] as 12 triangles, appended at vertex v / triangle t. */
static inline void vxt_shape_put_box(vxt_shape *m, size_t v, size_t t, const float lo[3], const float hi[3])
{
    static const int faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
    int c, f;
    for (c = 0; c < 8; c++) {
        m->pos[3 * (v + (size_t)c) + 0] = (c & 1) ? hi[0] : lo[0];
        m->pos[3 * (v + (size_t)c) + 1] = (c & 2) ? hi[1] : lo[1];
        m->pos[3 * (v + (size_t)c) + 2] = (c & 4) ? hi[2] : lo[2];
    }
    for (f = 0; f < 6; f++) {
        uint32_t q[4];
        for (c = 0; c < 4; c++) q[c] = (uint32_t)(v + (size_t)faces[f][c]);
        m->idx[3 * t + 0] = q[0]; m->idx[3 * t + 1] = q[1]; m->idx[3 * t + 2] = q[2]; t++;
        m->idx[3 * t + 0] = q[0]; m->idx[3 * t + 1] = q[2]; m->idx[3 * t + 2] = q[3]; t++;
    }
}

/* An axis-aligned box and a tilted quad, integer coordinates in [0, 24]: ties on voxel faces. */
static inline void vxt_shape_box_and_tilted(vxt_shape *m)
{
    const float lo[3] = {2, 3, 4}, hi[3] = {20, 17, 13};
    vxt_shape_alloc(m, 12, 14);
    vxt_shape_put_box(m, 0, 0, lo, hi);
    {
        const float q[12] = {1, 1, 22, 23, 4, 2, 24, 20, 9, 3, 23, 24};
        memcpy(m->pos + 24, q, sizeof q);
        m->idx[36] = 8; m->idx[37] = 9; m->idx[38] = 10;
        m->idx[39] = 8; m->idx[40] = 10; m->idx[41] = 11;
    }
}

/* A square [-1,1]^2 at z = 0 split into 2*n*n triangles (n = 1: seed 000's simple quad). */
static inline void vxt_shape_quad(vxt_shape *m, int n)
{
    int i, j;
    size_t t = 0;
    vxt_shape_alloc(m, (size_t)(n + 1) * (size_t)(n + 1), (size_t)n * (size_t)n * 2);
    for (j = 0; j <= n; j++)
        for (i = 0; i <= n; i++) {
            size_t v = (size_t)j * (size_t)(n + 1) + (size_t)i;
            m->pos[3 * v + 0] = (float)(-1.0 + 2.0 * i / n);
            m->pos[3 * v + 1] = (float)(-1.0 + 2.0 * j / n);
            m->pos[3 * v + 2] = 0.0f;
        }
    for (j = 0; j < n; j++)
        for (i = 0; i < n; i++) {
            uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)n + 1, d = c + 1;
            m->idx[3 * t + 0] = a; m->idx[3 * t + 1] = b; m->idx[3 * t + 2] = d; t++;
            m->idx[3 * t + 0] = a; m->idx[3 * t + 1] = d; m->idx[3 * t + 2] = c; t++;
        }
}
#endif
