/* tools/stiff.h - the stiff and extreme cases: every image method at small settings, and the scenes
 * they are run on (scaled, moved, with more triangles or other materials). Shared by the section
 * of `voxgi report all` that measures them and by tests/test_stiff.c, which holds each case to its
 * expectation (docs/stiff-cases.md). */
#ifndef VXT_STIFF_H
#define VXT_STIFF_H
#include "../voxgi.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { VXT_STIFF_METHODS = 10, VXT_STIFF_IMG = 16 };
static const char *const vxt_stiff_methods[VXT_STIFF_METHODS] = {"reference", "vct", "tsm", "rsm", "sh", "ssgi", "hybrid", "ssao", "vao", "linespace"};

/* Whether method m computes occlusion (its image is not light). */
static inline int vxt_stiff_is_occlusion(int m) { return m == 7 || m == 8; }

/* Method m's 16 x 16 image of sc through cam (small settings, seed 3) into rgb. Where a zero
   field of voxgi_render_desc now means another default than the per-method calls' zero did, the
   old value is set: cone tracing's isotropic volume, 16 cones at every pixel; the screen passes
   at full resolution, unblurred, without hidden light; the line space at the pixel's centre. */
static inline voxgi_result vxt_stiff_image(voxgi_context *ctx, int m, const voxgi_scene *sc, voxgi_camera cam, float *rgb)
{
    static const voxgi_render_method methods[VXT_STIFF_METHODS] = {VOXGI_RENDER_REFERENCE, VOXGI_RENDER_VCT,    VOXGI_RENDER_TSM,  VOXGI_RENDER_RSM,
                                                                   VOXGI_RENDER_SH,        VOXGI_RENDER_SSGI,   VOXGI_RENDER_HYBRID, VOXGI_RENDER_SSAO,
                                                                   VOXGI_RENDER_VAO,       VOXGI_RENDER_LINESPACE};
    const size_t bytes = sizeof(float) * 3 * VXT_STIFF_IMG * VXT_STIFF_IMG;
    voxgi_render_desc d;
    memset(&d, 0, sizeof d);
    cam.width = cam.height = VXT_STIFF_IMG;
    d.method = methods[m >= 0 && m < VXT_STIFF_METHODS ? m : VXT_STIFF_METHODS - 1];
    d.camera = cam;
    d.seed = 3;
    if (m == 0) {
        d.samples = 4; d.bounces = 1;
    } else if (m == 1) {
        d.resolution = 16; d.vct.cones.cones = 4; d.samples = 4;
        d.vct.cone_stride = 1; d.vct.radiance = VOXGI_VCT_ISOTROPIC;
    } else if (m == 2) {
        d.tsm.maps.size = 64;
    } else if (m == 3) {
        d.rsm.maps.size = 32; d.resolution = 16; d.samples = 4;
    } else if (m == 4) {
        d.resolution = 16; d.samples = 4;
    } else if (m == 5 || m == 6) {
        d.resolution = 16; d.screen.rays = 4; d.screen.steps = 4; d.samples = 4;
        d.screen.half_resolution = VOXGI_TOGGLE_OFF; d.screen.blur = -1; d.screen.hidden_light = VOXGI_TOGGLE_OFF;
    } else if (m == 7 || m == 8) {
        d.resolution = 16; d.screen.rays = 4; d.screen.steps = 4;
        d.screen.half_resolution = VOXGI_TOGGLE_OFF; d.screen.blur = -1;
    } else {
        d.linespace.samples = 4; d.linespace.supersample = 1;
    }
    return voxgi_render(ctx, sc, &d, rgb, bytes, NULL);
}

/* The RMS difference of two images over b's mean (0 when equal); n values. */
static inline double vxt_stiff_rel_diff(const float *a, const float *b, size_t n)
{
    double d2 = 0, mean = 0;
    size_t i;
    for (i = 0; i < n; i++) {
        d2 += ((double)a[i] - b[i]) * ((double)a[i] - b[i]);
        mean += b[i] / (double)n;
    }
    return d2 == 0 ? 0 : sqrt(d2 / (double)n) / mean;
}

/* Whether every value is finite; their mean into *mean. */
static inline int vxt_stiff_finite(const float *v, size_t n, double *mean)
{
    size_t i;
    *mean = 0;
    for (i = 0; i < n; i++) {
        if (!isfinite(v[i])) return 0;
        *mean += v[i] / (double)n;
    }
    return 1;
}

/* A scene in float positions p k + offset (the product and sum in double, rounded to float once):
   meshes and lights (positions; area lights' edges by k; point and spot lights' intensity by k^2,
   so that irradiance stays). Free with vxt_stiff_placed_free. */
typedef struct vxt_stiff_placed {
    voxgi_scene scene;
    voxgi_mesh *meshes;
    float **pos;
    voxgi_light *lights;
} vxt_stiff_placed;

static inline void vxt_stiff_placed_free(vxt_stiff_placed *m)
{
    size_t i;
    for (i = 0; m->pos && i < m->scene.mesh_count; i++) free(m->pos[i]);
    free(m->pos);
    free(m->meshes);
    free(m->lights);
    memset(m, 0, sizeof *m);
}

static inline int vxt_stiff_placed_make(const voxgi_scene *src, double k, double offset, vxt_stiff_placed *m)
{
    size_t i, v;
    int a;
    memset(m, 0, sizeof *m);
    m->scene = *src;
    m->meshes = (voxgi_mesh *)calloc(src->mesh_count + 1, sizeof *m->meshes);
    m->pos = (float **)calloc(src->mesh_count + 1, sizeof *m->pos);
    m->lights = (voxgi_light *)calloc(src->light_count + 1, sizeof *m->lights);
    if (!m->meshes || !m->pos || !m->lights) return 0;
    for (i = 0; i < src->mesh_count; i++) {
        const voxgi_mesh *s = &src->meshes[i];
        m->meshes[i] = *s;
        if (!(m->pos[i] = (float *)malloc(12 * s->vertex_count + 1))) return 0;
        for (v = 0; v < s->vertex_count; v++) {
            const float *p = (const float *)(const void *)((const char *)s->positions + v * (s->position_stride ? s->position_stride : 12));
            for (a = 0; a < 3; a++) m->pos[i][3 * v + (size_t)a] = (float)(p[a] * k + offset);
        }
        m->meshes[i].positions = m->pos[i];
        m->meshes[i].position_stride = 0;
    }
    for (i = 0; i < src->light_count; i++) {
        voxgi_light L = src->lights[i];
        for (a = 0; a < 3; a++) {
            L.position[a] = (float)(L.position[a] * k + offset);
            L.edge_u[a] = (float)(L.edge_u[a] * k);
            L.edge_v[a] = (float)(L.edge_v[a] * k);
            if (L.type == VOXGI_LIGHT_POINT || L.type == VOXGI_LIGHT_SPOT) L.intensity[a] = (float)(L.intensity[a] * k * k);
        }
        m->lights[i] = L;
    }
    m->scene.meshes = m->meshes;
    m->scene.lights = m->lights;
    return 1;
}

/* The camera that sees the placed scene as cam saw the original. */
static inline voxgi_camera vxt_stiff_placed_camera(voxgi_camera cam, double k, double offset)
{
    int a;
    for (a = 0; a < 3; a++) {
        cam.eye[a] = cam.eye[a] * k + offset;
        cam.target[a] = cam.target[a] * k + offset;
    }
    return cam;
}

/* A scene's meshes as doubles moved by `offset`, the scene's origin at `origin` (the large-world
   path: voxgi takes position - origin in double). Free with vxt_stiff_far_free. */
typedef struct vxt_stiff_far {
    voxgi_scene scene;
    voxgi_mesh *meshes;
    double **pos;
} vxt_stiff_far;

static inline void vxt_stiff_far_free(vxt_stiff_far *m)
{
    size_t i;
    for (i = 0; m->pos && i < m->scene.mesh_count; i++) free(m->pos[i]);
    free(m->pos);
    free(m->meshes);
    memset(m, 0, sizeof *m);
}

static inline int vxt_stiff_far_make(const voxgi_scene *src, double offset, double origin, vxt_stiff_far *m)
{
    size_t i, v;
    int a;
    memset(m, 0, sizeof *m);
    m->scene = *src;
    m->meshes = (voxgi_mesh *)calloc(src->mesh_count + 1, sizeof *m->meshes);
    m->pos = (double **)calloc(src->mesh_count + 1, sizeof *m->pos);
    if (!m->meshes || !m->pos) return 0;
    for (i = 0; i < src->mesh_count; i++) {
        const voxgi_mesh *s = &src->meshes[i];
        m->meshes[i] = *s;
        if (!(m->pos[i] = (double *)malloc(3 * s->vertex_count * sizeof(double) + 1))) return 0;
        for (v = 0; v < s->vertex_count; v++) {
            const float *p = (const float *)(const void *)((const char *)s->positions + v * (s->position_stride ? s->position_stride : 12));
            for (a = 0; a < 3; a++) m->pos[i][3 * v + (size_t)a] = (double)p[a] + offset;
        }
        m->meshes[i].positions = NULL;
        m->meshes[i].position_stride = 0;
        m->meshes[i].positions_double = m->pos[i];
    }
    m->scene.meshes = m->meshes;
    for (a = 0; a < 3; a++) m->scene.origin[a] = origin;
    return 1;
}

/* A built-in scene with up to 16 more triangles (a mesh of their own, all of material `mat`) and
   its materials copied into S->mats (up to 32), for a case to change. 0: the scene is too big. */
typedef struct vxt_stiff_scene {
    voxgi_scene scene;
    voxgi_mesh meshes[8];
    voxgi_material mats[32];
    float extra[9 * 16];
    uint32_t extra_mat[16];
} vxt_stiff_scene;

static inline int vxt_stiff_add(vxt_stiff_scene *S, const voxgi_scene *base, const float *tris, int count, uint32_t mat)
{
    int i;
    if (base->mesh_count >= 8 || base->material_count >= 32 || count > 16) return 0;
    S->scene = *base;
    memcpy(S->meshes, base->meshes, base->mesh_count * sizeof *S->meshes);
    memcpy(S->mats, base->materials, base->material_count * sizeof *S->mats);
    if (count) memcpy(S->extra, tris, 9 * (size_t)count * sizeof(float));
    memset(&S->meshes[base->mesh_count], 0, sizeof S->meshes[0]);
    S->meshes[base->mesh_count].positions = S->extra;
    S->meshes[base->mesh_count].vertex_count = 3 * (size_t)count;
    for (i = 0; i < count; i++) S->extra_mat[i] = mat;
    S->meshes[base->mesh_count].material_ids = S->extra_mat;
    S->scene.meshes = S->meshes;
    S->scene.mesh_count = base->mesh_count + (count > 0);
    S->scene.materials = S->mats;
    S->scene.material_count = base->material_count;
    return 1;
}

/* The mean radiance of the furnace `fu` (a closed sphere of emission 1 seen from inside) with
   every material's albedo `albedo`, 16 x 16 through its camera, every bounce: the path tracer's
   (4 samples per pixel, seed 1) or, with vct, the cone tracer's (32^3); NAN where a value is not
   finite. */
static inline voxgi_result vxt_stiff_furnace(voxgi_context *ctx, const voxgi_builtin_scene *fu, float albedo, int vct, double *mean)
{
    const size_t n = 3 * VXT_STIFF_IMG * VXT_STIFF_IMG;
    float *img = (float *)malloc(n * sizeof(float));
    vxt_stiff_scene S;
    voxgi_camera cam = fu->camera;
    voxgi_result r = VOXGI_ERR_OUT_OF_MEMORY;
    size_t mi;
    *mean = NAN;
    cam.width = cam.height = VXT_STIFF_IMG;
    if (img && vxt_stiff_add(&S, &fu->scene, NULL, 0, 0)) {
        for (mi = 0; mi < S.scene.material_count; mi++) S.mats[mi].albedo[0] = S.mats[mi].albedo[1] = S.mats[mi].albedo[2] = albedo;
        voxgi_render_desc d;
        memset(&d, 0, sizeof d);
        d.camera = cam; d.samples = 4; d.bounces = -1;
        if (vct) { /* the old zeros: an isotropic volume, 16 cones at every pixel */
            d.method = VOXGI_RENDER_VCT;
            d.resolution = 32; d.vct.cones.cones = 16; d.vct.cone_stride = 1; d.vct.radiance = VOXGI_VCT_ISOTROPIC;
        } else {
            d.method = VOXGI_RENDER_REFERENCE;
            d.seed = 1;
        }
        r = voxgi_render(ctx, &S.scene, &d, img, n * sizeof(float), NULL);
        if (r == VOXGI_OK && !vxt_stiff_finite(img, n, mean)) *mean = NAN;
    }
    free(img);
    return r;
}

/* Degenerate triangles for the Cornell box (its unit frame): a segment and two points (no area),
   then a needle (0.3 long, 1e-7 wide) and a sliver (1e-9 off a line). */
static const float vxt_stiff_degenerate[9 * 5] = {
    0.2f, 0.3f, 0.3f, 0.3f, 0.3f, 0.3f, 0.25f, 0.3f, 0.3f,        /* a segment */
    0.3f, 0.3f, 0.3f, 0.3f, 0.3f, 0.3f, 0.3f, 0.3f, 0.3f,         /* a point */
    0.1f, 0.1f, 0.1f, 0.1f, 0.1f, 0.1f, 0.1f, 0.1f, 0.1f,         /* another */
    0.1f, 0.1f, 0.2f, 0.4f, 0.1f, 0.2f, 0.25f, 0.1f + 1e-7f, 0.2f, /* a needle */
    0.1f, 0.2f, 0.3f, 0.2f, 0.2f + 1e-9f, 0.3f, 0.3f, 0.2f, 0.3f}; /* a sliver */

#endif
