/* tools/mesh_io.h - triangle mesh loaders shared by the voxgi command-line tools and tests.
 *
 * Reads Wavefront OBJ (with MTL materials), OFF, STL (ASCII and binary) and PLY (ASCII and
 * binary_little_endian) into one flat, indexed triangle mesh. Every loader treats its input as
 * hostile: a malformed, truncated or absurd file gives an error message, never a crash or a leak.
 * Numbers are parsed with strtod, so the program must run in the "C" numeric locale (the default
 * unless it calls setlocale). */
#ifndef VXT_MESH_IO_H
#define VXT_MESH_IO_H
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct vxt_material {
    char name[64];      /* truncated to 63 characters */
    float albedo[3];    /* MTL Kd, default 0.8 0.8 0.8 */
    float emission[3];  /* MTL Ke, default 0 */
    float opacity;      /* MTL d (or 1 - Tr), default 1 */
} vxt_material;

typedef struct vxt_mesh {
    float    *positions;      /* 3 floats per vertex */
    float    *normals;        /* NULL, or 3 floats per vertex when the file gives normals */
    float    *uvs;            /* NULL, or 2 floats per vertex when the file gives texture coordinates */
    uint32_t *indices;        /* 3 per triangle */
    uint32_t *material_ids;   /* one per triangle, index into materials; always allocated */
    vxt_material *materials;  /* at least one (a default material when the file has none) */
    size_t vertex_count, triangle_count, material_count;
} vxt_mesh;

/* Loads OBJ(+MTL), OFF, STL (ASCII and binary) or PLY (ASCII and binary_little_endian), chosen by
   content and extension. Returns 0 on success. On failure returns non-zero, leaves *out empty (all
   zero, nothing to free), and writes into err a message naming the file and the line (text formats)
   or byte offset (binary formats) and what is wrong. err may be NULL. A mesh without any triangle
   is an error. */
int  vxt_mesh_load(const char *path, vxt_mesh *out, char *err, size_t err_size);
/* Frees what vxt_mesh_load allocated and zeroes *m; safe on an empty or zeroed mesh. */
void vxt_mesh_free(vxt_mesh *m);

/* Hash-map slots visited by every load so far (the loader's work, for tests and benchmarks: a
   load visits a few slots per face corner; a search that degrades to a scan visits thousands). */
unsigned long long vxt_mesh_io_probes(void);

#ifdef __cplusplus
}
#endif
#endif
