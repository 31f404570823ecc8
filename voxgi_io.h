/* voxgi_io.h - v0.1.0 - mesh files into voxgi.h's scenes: OBJ (with MTL), OFF, STL, PLY, glTF. MIT licence at the end.

   An optional second single header beside voxgi.h: the loaders that get a mesh file into a
   voxgi_scene, with its materials. It needs voxgi.h (its public types; the exports also its voxel
   readers) and the C standard library; C99 or C++.

   USAGE
     In exactly one C or C++ file (it may be the one that defines VOXGI_IMPLEMENTATION):
         #define VOXGI_IO_IMPLEMENTATION
         #include "voxgi_io.h"
     Everywhere else just #include "voxgi_io.h".

     voxgi_io_mesh m;
     char err[512];
     if (voxgi_io_load_mesh("bunny.obj", &m, err, sizeof err) != 0) { fprintf(stderr, "%s\n", err); return 1; }
     voxgi_scene scene = voxgi_io_mesh_scene(&m);     // points into m: its mesh and its materials
     scene.lights = &sun; scene.light_count = 1;      // a mesh file brings no light
     ... voxgi_render(ctx, &scene, &desc, rgb, bytes, &info) ...
     voxgi_io_mesh_free(&m);

   FORMATS (chosen by content, then by extension)
     Wavefront OBJ with its MTL files (Kd, Ke, d or Tr), polygons split as fans, negative indices,
     vertices split where their normal or texture coordinate differs; OFF; STL, ASCII and binary;
     PLY, ASCII and binary_little_endian, every scalar type; glTF 2.0, .gltf (external or data-URI
     buffers) and .glb: triangle primitives under the scene's node transforms, base colour and
     emissive factors as materials (part 3 lists what is read and refused). Every loader treats its input as
     hostile: a malformed, truncated or absurd file gives an error naming the file and the line
     (text formats) or byte offset (binary formats), never a crash or a leak. Numbers are parsed
     with strtod, so the program must run in the "C" numeric locale (the default unless it calls
     setlocale). The arrays come from malloc and go back to free (not VOXGI_MALLOC).

   CONTENTS (declarations, then the implementation in the same parts)
     1. config          linkage
     2. mesh files      the loaded mesh, loading it (from a file or memory) and freeing it, its
                        scene; the loaders' shared builder, the text cursor, MTL, OBJ, OFF, STL,
                        PLY, the choice of format
     3. glTF            what is read of glTF 2.0; a JSON tokeniser, buffers, accessors, materials,
                        the node tree, GLB chunks
     4. exports         voxels out to MagicaVoxel .vox, NumPy .npy, a PLY point cloud, an OBJ of outer faces

   VERSION HISTORY
     0.1.0  the voxgi tool's loaders (tools/mesh_io.c) moved here; a loaded mesh gives its
            voxgi_scene with materials (voxgi_io_mesh_scene).
*/
#ifndef VOXGI_IO_H
#define VOXGI_IO_H

#include "voxgi.h"

/* ===================================================================== 1. config */
#define VOXGI_IO_VERSION_STRING "0.1.0"

#ifndef VOXGI_IO_API
#define VOXGI_IO_API VOXGI_API /* voxgi.h's linkage: extern, or static with VOXGI_STATIC */
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ===================================================================== 2. mesh files */

typedef struct voxgi_io_material {
    char name[64];      /* truncated to 63 characters */
    float albedo[3];    /* MTL Kd, default 0.8 0.8 0.8 */
    float emission[3];  /* MTL Ke, default 0 */
    float opacity;      /* MTL d (or 1 - Tr), default 1 */
} voxgi_io_material;

/* One flat, indexed triangle mesh that owns its arrays. */
typedef struct voxgi_io_mesh {
    float    *positions;      /* 3 floats per vertex */
    float    *normals;        /* NULL, or 3 floats per vertex when the file gives normals */
    float    *uvs;            /* NULL, or 2 floats per vertex when the file gives texture coordinates */
    uint32_t *indices;        /* 3 per triangle */
    uint32_t *material_ids;   /* one per triangle, index into materials; always allocated */
    voxgi_io_material *materials;  /* at least one (a default material when the file has none) */
    size_t vertex_count, triangle_count, material_count;
    /* The same as voxgi.h takes them (what voxgi_io_mesh_scene points at): */
    voxgi_mesh mesh;                  /* the arrays above */
    voxgi_material *scene_materials;  /* material_count of them: albedo, emission, transparency = 1 - opacity */
} voxgi_io_mesh;

/* Loads OBJ(+MTL), OFF, STL (ASCII and binary), PLY (ASCII and binary_little_endian) or glTF 2.0
   (.gltf, .glb; part 3), chosen by content and extension. Returns 0 on success. On failure returns
   non-zero, leaves *out empty (all zero, nothing to free), and writes into err a message naming
   the file and the line (text formats) or byte offset (binary formats) and what is wrong. err may
   be NULL. A mesh without any triangle is an error. */
VOXGI_IO_API int voxgi_io_load_mesh(const char *path, voxgi_io_mesh *out, char *err, size_t err_size);
/* The same from a file's bytes in memory (an archive's entry, a download): size bytes at data
   (no NUL needed; data may be NULL when size is 0), loaded as voxgi_io_load_mesh loads a file of
   that content whose path is name: the content picks the format, else name's extension; errors
   name name (NULL: "(memory)"). Nothing is read from files, so what a file refers to is not
   resolved: an OBJ's mtllib lines are skipped (its usemtl names still keep their faces apart, with
   the default material each, as when voxgi_io_load_mesh finds no MTL file), and a .gltf buffer
   whose uri names a file is refused with an error naming the uri (data URIs and a .glb's BIN chunk
   are read as from a file). Returns 0, or non-zero with *out left empty, as voxgi_io_load_mesh. */
VOXGI_IO_API int voxgi_io_load_mesh_memory(const void *data, size_t size, const char *name, voxgi_io_mesh *out, char *err, size_t err_size);
/* Frees what voxgi_io_load_mesh allocated and zeroes *m; safe on an empty or zeroed mesh and NULL. */
VOXGI_IO_API void voxgi_io_mesh_free(voxgi_io_mesh *m);
/* A one-mesh scene of m with its materials and no lights: it points at m->mesh and
   m->scene_materials, so it is valid while m is neither freed nor moved (after copying m, take the
   copy's scene). */
VOXGI_IO_API voxgi_scene voxgi_io_mesh_scene(const voxgi_io_mesh *m);

/* Hash-map slots visited by every load so far (the loader's work, for tests and benchmarks: a
   load visits a few slots per face corner; a search that degrades to a scan visits thousands). */
VOXGI_IO_API unsigned long long voxgi_io_probes(void);

/* ===================================================================== 3. glTF */

/* voxgi_io_load_mesh also reads glTF 2.0: a .gltf (JSON, its buffers in files beside it named by
   relative URIs, or base64 data URIs) or a .glb (a binary container: header, JSON chunk, BIN
   chunk). It takes the triangle primitives (mode 4 or none) of every mesh reached from the default
   scene's nodes (every root node when there is no scene), with the nodes' transforms (matrix, or
   translation * rotation * scale) composed down the tree and applied to positions, and to normals
   by the inverse transpose; a mirroring transform keeps the faces counter-clockwise. Indices of
   any type (uint8, uint16, uint32) or none; POSITION and NORMAL must be float VEC3. Each glTF
   material is the material of the same index: pbrMetallicRoughness.baseColorFactor's rgb is the
   albedo, its alpha the opacity (in BLEND or MASK mode; OPAQUE ignores it), emissiveFactor times
   KHR_materials_emissive_strength the emission. Textures are ignored. An accessor without a
   bufferView is all zeros (at most as many elements as the JSON and its buffers have bytes); a sparse accessor's base (its bufferView, or zeros) has the elements at
   sparse.indices (uint8, uint16 or uint32, strictly increasing, below its count) replaced by
   sparse.values, both tightly packed. Other primitive modes, non-float positions, Draco or meshopt
   compression and other required extensions are refused by name; absolute or ".." buffer URIs are
   refused (and every file URI by voxgi_io_load_mesh_memory); malformed JSON or GLB structure gives
   its byte offset (in a .glb, from the file's start). */

/* ===================================================================== 4. exports */

/* Writers of a voxel grid (voxgi_voxelize's result, on either backend: ctx reads its bits and
   its ALBEDO) to files other programs open. Each returns 0, or non-zero with a message in err
   (may be NULL) naming the file and the reason (the C library's, strerror, for a failed open or
   write; a partly written file may remain). voxels NULL or holding no data is refused; an empty
   grid (no voxel set) is not: it gives a valid file without voxels. Colours are the voxels' mean
   ALBEDO when they hold it (voxgi_voxelize_desc.attributes), else 0.8 grey, encoded to sRGB
   bytes (the .vox palette, the PLY colours) as viewers show bytes. Positions (PLY, OBJ) are in
   world units: voxel (i,j,k) spans origin + voxel_size * [i, i+1] x [j, j+1] x [k, k+1]. */

/* MagicaVoxel .vox, version 150. Axes: MagicaVoxel's z is up and voxgi's y, so voxel (i,j,k)
   becomes (x,y,z) = (i, res[2]-1-k, j) (a rotation, not a mirror: +x stays +x, voxgi's up +y
   becomes +z, +z becomes -y). Palette: a uniform 6 x 7 x 6 cube over sRGB (levels 0, 51, ...,
   255 for red and blue, 0, 42.5, ... for green), 252 colours at indices 1..252 (index = 1 +
   (r * 7 + g) * 6 + b; index 0 is MagicaVoxel's empty), each voxel's colour rounded to its
   nearest level per channel. A grid up to 256 voxels per (MagicaVoxel) axis is one model; a
   larger one is split into models of at most 256^3 (blocks from the minimum corner, x fastest,
   empty ones included) placed by a scene graph: root nTRN 0 -> nGRP 1 -> per model m an nTRN
   2+2m with translation _t -> nSHP 3+2m of model m. MagicaVoxel places a model of size s with
   its voxel v at _t + v - floor(s / 2), so a block whose minimum corner is c gets
   _t = c + floor(s / 2) and the models tile the grid from (0,0,0). */
VOXGI_IO_API int voxgi_io_write_vox(voxgi_context *ctx, const voxgi_voxels *voxels, const char *path, char *err, size_t err_size);

/* NumPy .npy (format 1.0): the occupancy as dtype uint8 (1 set, 0 empty), shape
   (res[0], res[1], res[2]) in C order, so numpy.load(path)[i, j, k] is voxel (i, j, k). */
VOXGI_IO_API int voxgi_io_write_npy(voxgi_context *ctx, const voxgi_voxels *voxels, const char *path, char *err, size_t err_size);
/* The same for one attribute the voxels hold (ALBEDO, NORMAL, EMISSION: dtype little-endian
   float32, shape (res[0], res[1], res[2], 3); OPACITY: shape (res[0], res[1], res[2])), C order,
   the value as voxgi_voxels_read_attribute gives it (linear, not sRGB), 0 at empty voxels. */
VOXGI_IO_API int voxgi_io_write_npy_attribute(voxgi_context *ctx, const voxgi_voxels *voxels, voxgi_attribute which, const char *path,
                                              char *err, size_t err_size);

/* PLY point cloud, binary_little_endian 1.0: one vertex per set voxel at its centre (float x, y,
   z) with its colour (uchar red, green, blue), in the order of the bit grid. */
VOXGI_IO_API int voxgi_io_write_ply_points(voxgi_context *ctx, const voxgi_voxels *voxels, const char *path, char *err, size_t err_size);

/* Wavefront OBJ surface of the voxels: one quad per outer face, a face between a set voxel and an
   empty one (outside the grid counts as empty), counter-clockwise seen from outside; faces between
   two set voxels are left out. Four vertices per quad (not shared: the file stays a stream); with
   an MTL-free per-vertex colour (x y z r g b, as MeshLab and Blender read it) from the voxel's
   albedo in [0,1] sRGB. */
VOXGI_IO_API int voxgi_io_write_obj_faces(voxgi_context *ctx, const voxgi_voxels *voxels, const char *path, char *err, size_t err_size);

#ifdef __cplusplus
}
#endif
#endif /* VOXGI_IO_H */

/* ************************************************************************************************
   IMPLEMENTATION
   ************************************************************************************************ */
#ifdef VOXGI_IO_IMPLEMENTATION
#ifndef VOXGI_IO__IMPLEMENTED
#define VOXGI_IO__IMPLEMENTED

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ===================================================================== 1. config */

#if defined(__GNUC__)
#define VOXGI_IO__PRINTF_LIKE(fmt, first) __attribute__((format(printf, fmt, first)))
#else
#define VOXGI_IO__PRINTF_LIKE(fmt, first)
#endif

/* ===================================================================== 2. mesh files */

/* Each format fills one shared builder (growable arrays of positions, normals, uvs, triangle
   indices, material ids and materials); voxgi_io_load_mesh hands the arrays over only when the
   whole file was read, so a failure never shows a partial mesh. The text formats read through one
   cursor that counts lines, so every error can point at its line; the binary readers name byte
   offsets. */

#define VOXGI_IO__NO_INDEX UINT32_MAX /* an absent vt/vn index; also one past the largest vertex index */

/* ---- growable arrays ---------------------------------------------------------------------- */

typedef struct voxgi_io__vec { void *data; size_t count, cap; } voxgi_io__vec;

/* Appends n (> 0) uninitialised elements and returns the first; NULL on overflow or out of memory. */
static void *voxgi_io__vec_push(voxgi_io__vec *v, size_t n, size_t elem_size)
{
    size_t need;
    if (n > SIZE_MAX / elem_size - v->count) return NULL;
    need = v->count + n;
    if (need > v->cap) {
        size_t cap = v->cap ? v->cap : 8;
        void *grown;
        while (cap < need) cap = cap <= SIZE_MAX / 2 / elem_size ? cap * 2 : need;
        grown = realloc(v->data, cap * elem_size);
        if (!grown) return NULL;
        v->data = grown;
        v->cap = cap;
    }
    v->count = need;
    return (char *)v->data + (need - n) * elem_size;
}

static void voxgi_io__vec_free(voxgi_io__vec *v)
{
    free(v->data);
    memset(v, 0, sizeof *v);
}

/* ---- hash map from keys stored elsewhere to 32-bit ids ---------------------------------------- */

/* A slot holds hash << 32 | (id + 1), 0 when empty. Keeping the hash lets the map grow without
   seeing the keys; lookups compare keys through a callback. Linear probing, at most half full. */
typedef struct voxgi_io__id_map { uint64_t *slots; size_t cap, count; } voxgi_io__id_map;
typedef int (*voxgi_io__same_key_fn)(const void *keys, uint32_t id, const void *key);

static unsigned long long voxgi_io__probes; /* slots visited by voxgi_io__id_map_get_or_add, over the program's loads */
VOXGI_IO_API unsigned long long voxgi_io_probes(void) { return voxgi_io__probes; }

static uint32_t voxgi_io__hash_bytes(const void *data, size_t n)
{
    const unsigned char *b = (const unsigned char *)data;
    uint32_t h = 2166136261u; /* FNV-1a, then a murmur finaliser so the low bits mix well */
    while (n--) h = (h ^ *b++) * 16777619u;
    h ^= h >> 16; h *= 0x85ebca6bu; h ^= h >> 13; h *= 0xc2b2ae35u;
    return h ^ (h >> 16);
}

static int voxgi_io__id_map_grow(voxgi_io__id_map *m)
{
    size_t cap = m->cap ? m->cap * 2 : 64, i, j;
    uint64_t *slots;
    if (cap > SIZE_MAX / sizeof *slots || !(slots = (uint64_t *)calloc(cap, sizeof *slots))) return 0;
    for (i = 0; i < m->cap; i++) {
        if (!m->slots[i]) continue;
        for (j = (size_t)(m->slots[i] >> 32) & (cap - 1); slots[j]; j = (j + 1) & (cap - 1)) {}
        slots[j] = m->slots[i];
    }
    free(m->slots);
    m->slots = slots;
    m->cap = cap;
    return 1;
}

/* Returns the id whose key equals key, or inserts new_id when there is none; NO_INDEX when out of
   memory. new_id must be below NO_INDEX. */
static uint32_t voxgi_io__id_map_get_or_add(voxgi_io__id_map *m, uint32_t hash, const void *key, voxgi_io__same_key_fn same,
                                  const void *keys, uint32_t new_id)
{
    size_t i;
    if ((m->count + 1) * 2 > m->cap && !voxgi_io__id_map_grow(m)) return VOXGI_IO__NO_INDEX;
    for (i = hash & (m->cap - 1); m->slots[i]; i = (i + 1) & (m->cap - 1)) {
        uint32_t id = (uint32_t)m->slots[i] - 1;
        voxgi_io__probes++;
        if ((uint32_t)(m->slots[i] >> 32) == hash && same(keys, id, key)) return id;
    }
    m->slots[i] = (uint64_t)hash << 32 | ((uint64_t)new_id + 1);
    m->count++;
    return new_id;
}

/* ---- loader state and errors -------------------------------------------------------------- */

typedef struct voxgi_io__builder {
    voxgi_io__vec positions, normals, uvs;   /* float */
    voxgi_io__vec indices, material_ids;     /* uint32_t */
    voxgi_io__vec materials;                 /* voxgi_io_material */
    voxgi_io__id_map material_names;
    voxgi_io__vec polygon;                   /* uint32_t scratch: the corners of the face being read */
} voxgi_io__builder;

typedef struct voxgi_io__loader {
    const char *path; /* the file errors name: the mesh, or the MTL file being read */
    int in_memory;    /* voxgi_io_load_mesh_memory: no file the mesh names is read */
    char *err;
    size_t err_size;
    voxgi_io__builder b;
} voxgi_io__loader;

static const char VOXGI_IO__LINE[] = "line", VOXGI_IO__OFFSET[] = "byte offset";

/* Writes "path: <where> <at>: message" (or "path: message" when where is NULL); returns -1 so
   callers can write `return voxgi_io__fail_at(...)`. Loaders stop at their first error, which is the one kept. */
static int voxgi_io__fail_at(voxgi_io__loader *L, const char *where, size_t at, const char *fmt, ...) VOXGI_IO__PRINTF_LIKE(4, 5);
static int voxgi_io__fail_at(voxgi_io__loader *L, const char *where, size_t at, const char *fmt, ...)
{
    va_list ap;
    size_t used;
    if (!L->err || !L->err_size) return -1;
    if (where) snprintf(L->err, L->err_size, "%s: %s %zu: ", L->path, where, at);
    else snprintf(L->err, L->err_size, "%s: ", L->path);
    used = strlen(L->err);
    va_start(ap, fmt);
    vsnprintf(L->err + used, L->err_size - used, fmt, ap);
    va_end(ap);
    return -1;
}

#define VOXGI_IO__PUSH(L, v, type, n) ((type *)voxgi_io__push((L), &(v), (n), sizeof(type)))
static void *voxgi_io__push(voxgi_io__loader *L, voxgi_io__vec *v, size_t n, size_t elem_size)
{
    void *p = voxgi_io__vec_push(v, n, elem_size);
    if (!p) voxgi_io__fail_at(L, NULL, 0, "out of memory");
    return p;
}

static int voxgi_io__add_vertex(voxgi_io__loader *L, const float xyz[3])
{
    float *dst;
    if (L->b.positions.count / 3 >= VOXGI_IO__NO_INDEX) return voxgi_io__fail_at(L, NULL, 0, "too many vertices for 32-bit indices");
    if (!(dst = VOXGI_IO__PUSH(L, L->b.positions, float, 3))) return -1;
    memcpy(dst, xyz, 3 * sizeof *dst);
    return 0;
}

/* Triangulates the polygon in b.polygon (stride uint32_t per corner) as a fan around its first
   corner, appending 3 corners per triangle to dst and one material id. */
static int voxgi_io__add_fan(voxgi_io__loader *L, voxgi_io__vec *dst, size_t stride, uint32_t material)
{
    const uint32_t *corner = (const uint32_t *)L->b.polygon.data;
    size_t n = L->b.polygon.count / stride, i;
    for (i = 1; i + 1 < n; i++) {
        uint32_t *tri = VOXGI_IO__PUSH(L, *dst, uint32_t, 3 * stride), *mat;
        if (!tri || !(mat = VOXGI_IO__PUSH(L, L->b.material_ids, uint32_t, 1))) return -1;
        memcpy(tri, corner, stride * sizeof *tri);
        memcpy(tri + stride, corner + i * stride, 2 * stride * sizeof *tri);
        *mat = material;
    }
    return 0;
}

static int voxgi_io__same_name(const void *keys, uint32_t id, const void *key)
{
    return strcmp(((const voxgi_io_material *)keys)[id].name, (const char *)key) == 0;
}

/* Finds the material with this name (its first 63 characters), adding one with default values
   when there is none, so usemtl without a matching MTL entry still keeps its faces apart. */
static int voxgi_io__material_id(voxgi_io__loader *L, const char *name, size_t len, uint32_t *id)
{
    voxgi_io__builder *b = &L->b;
    char key[sizeof ((voxgi_io_material *)NULL)->name];
    uint32_t new_id = (uint32_t)b->materials.count;
    voxgi_io_material *m;
    if (len > sizeof key - 1) len = sizeof key - 1;
    memcpy(key, name, len);
    key[len] = 0;
    if (b->materials.count >= VOXGI_IO__NO_INDEX - 1) return voxgi_io__fail_at(L, NULL, 0, "too many materials");
    *id = voxgi_io__id_map_get_or_add(&b->material_names, voxgi_io__hash_bytes(key, len), key, voxgi_io__same_name, b->materials.data, new_id);
    if (*id == VOXGI_IO__NO_INDEX) return voxgi_io__fail_at(L, NULL, 0, "out of memory");
    if (*id != new_id) return 0;
    if (!(m = VOXGI_IO__PUSH(L, b->materials, voxgi_io_material, 1))) return -1;
    memset(m, 0, sizeof *m);
    memcpy(m->name, key, len + 1);
    m->albedo[0] = m->albedo[1] = m->albedo[2] = 0.8f;
    m->opacity = 1.0f;
    return 0;
}

/* ---- text cursor ------------------------------------------------------------------------ */

typedef struct voxgi_io__text {
    const char *base, *p, *end; /* *end is a NUL read_file appended, so strtod always stops */
    size_t line;                /* 1-based line of p */
    char comment;               /* starts a comment running to the end of the line; 0 for none */
} voxgi_io__text;

static void voxgi_io__text_init(voxgi_io__text *t, const char *data, size_t size, char comment)
{
    t->base = t->p = data;
    t->end = data + size;
    t->line = 1;
    t->comment = comment;
    if (size >= 3 && !memcmp(data, "\xEF\xBB\xBF", 3)) t->p += 3; /* a UTF-8 byte order mark */
}

static int voxgi_io__is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

static int voxgi_io__at_token_end(const voxgi_io__text *t, const char *s)
{
    return s >= t->end || voxgi_io__is_blank(*s) || *s == '\n' || (t->comment && *s == t->comment);
}

/* Skips blanks; returns 1 when another token follows on the current line. */
static int voxgi_io__more(voxgi_io__text *t)
{
    while (t->p < t->end && voxgi_io__is_blank(*t->p)) t->p++;
    return !voxgi_io__at_token_end(t, t->p);
}

static void voxgi_io__next_line(voxgi_io__text *t)
{
    const char *nl = (const char *)memchr(t->p, '\n', (size_t)(t->end - t->p));
    t->p = nl ? nl + 1 : t->end;
    if (nl) t->line++;
}

/* Moves to the next token, across blank and comment lines; 0 at the end of the text. */
static int voxgi_io__skip_to_token(voxgi_io__text *t)
{
    while (!voxgi_io__more(t)) {
        if (t->p >= t->end) return 0;
        voxgi_io__next_line(t);
    }
    return 1;
}

/* The next token on the current line; length 0 when there is none. */
static size_t voxgi_io__next_token(voxgi_io__text *t, const char **s)
{
    size_t n = 0;
    if (voxgi_io__more(t))
        while (!voxgi_io__at_token_end(t, t->p + n)) n++;
    *s = t->p;
    t->p += n;
    return n;
}

static int voxgi_io__token_is(const char *s, size_t n, const char *word)
{
    return strlen(word) == n && memcmp(s, word, n) == 0;
}

/* Statement keywords start with a letter; anything else at the start of a line is garbage. */
static int voxgi_io__is_identifier(const char *s, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        char c = s[i];
        int letter = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
        if (!letter && (i == 0 || !((c >= '0' && c <= '9') || c == '_'))) return 0;
    }
    return n > 0;
}

/* The rest of the line, without surrounding blanks or a comment (names of materials and files). */
static size_t voxgi_io__rest_of_line(voxgi_io__text *t, const char **s)
{
    const char *e;
    voxgi_io__more(t);
    for (*s = e = t->p; e < t->end && *e != '\n' && !(t->comment && *e == t->comment); e++) {}
    t->p = e;
    while (e > *s && voxgi_io__is_blank(e[-1])) e--;
    return (size_t)(e - *s);
}

static int voxgi_io__read_double(voxgi_io__text *t, double *v)
{
    char *e;
    if (!voxgi_io__more(t)) return 0;
    *v = strtod(t->p, &e);
    if (e == t->p || !voxgi_io__at_token_end(t, e)) return 0;
    t->p = e;
    return 1;
}

static int voxgi_io__read_uint(voxgi_io__text *t, uint64_t max, uint64_t *v)
{
    const char *s;
    if (!voxgi_io__more(t)) return 0;
    for (*v = 0, s = t->p; *s >= '0' && *s <= '9'; s++)
        if ((*v = *v * 10 + (uint64_t)(*s - '0')) > max) return 0;
    if (s == t->p || !voxgi_io__at_token_end(t, s)) return 0;
    t->p = s;
    return 1;
}

/* Reads a number that must be finite and fit a float (what names the statement for errors). */
static int voxgi_io__read_float(voxgi_io__loader *L, voxgi_io__text *t, const char *what, float *f)
{
    double v;
    if (!voxgi_io__read_double(t, &v)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "%s: expected a number", what);
    if (!(fabs(v) <= FLT_MAX)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "%s: number is not finite or too large for a float", what);
    *f = (float)v;
    return 0;
}

static int voxgi_io__expect_word(voxgi_io__loader *L, voxgi_io__text *t, const char *word)
{
    const char *s;
    size_t n;
    if (!voxgi_io__skip_to_token(t)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "file ends where '%s' was expected", word);
    n = voxgi_io__next_token(t, &s);
    if (!voxgi_io__token_is(s, n, word)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "expected '%s'", word);
    return 0;
}

/* ---- files ------------------------------------------------------------------------------ */

/* Reads a whole file and appends a NUL. Returns 0 or an errno value; *open_failed tells a file that
   could not be opened at all (a missing MTL is allowed) from one that could not be read. */
static int voxgi_io__read_file(const char *path, char **data, size_t *size, int *open_failed)
{
    enum { VOXGI_IO__CHUNK = 1 << 16 };
    FILE *f = fopen(path, "rb");
    voxgi_io__vec buf;
    int error = 0;
    char *nul = NULL;
    *open_failed = !f;
    if (!f) return errno ? errno : ENOENT;
    memset(&buf, 0, sizeof buf);
    for (;;) {
        char *dst = (char *)voxgi_io__vec_push(&buf, VOXGI_IO__CHUNK, 1);
        size_t got;
        if (!dst) { error = ENOMEM; break; }
        got = fread(dst, 1, VOXGI_IO__CHUNK, f);
        buf.count -= VOXGI_IO__CHUNK - got;
        if (got < VOXGI_IO__CHUNK) {
            if (ferror(f)) error = errno ? errno : EIO;
            break;
        }
    }
    fclose(f);
    if (!error && !(nul = (char *)voxgi_io__vec_push(&buf, 1, 1))) error = ENOMEM;
    if (error) {
        voxgi_io__vec_free(&buf);
        return error;
    }
    *nul = 0;
    *data = (char *)buf.data;
    *size = buf.count - 1;
    return 0;
}

/* ---- MTL -------------------------------------------------------------------------------- */

static int voxgi_io__read_color(voxgi_io__loader *L, voxgi_io__text *t, const char *key, float rgb[3])
{
    if (voxgi_io__read_float(L, t, key, &rgb[0])) return -1;
    if (!voxgi_io__more(t)) { /* "Kd r" means grey r */
        rgb[1] = rgb[2] = rgb[0];
        return 0;
    }
    return voxgi_io__read_float(L, t, key, &rgb[1]) || voxgi_io__read_float(L, t, key, &rgb[2]) ? -1 : 0;
}

static int voxgi_io__mtl_parse(voxgi_io__loader *L, voxgi_io__text *t)
{
    uint32_t current = VOXGI_IO__NO_INDEX;
    for (; t->p < t->end; voxgi_io__next_line(t)) {
        const char *key;
        size_t n = voxgi_io__next_token(t, &key);
        voxgi_io_material *m;
        float value;
        if (!n) continue;
        if (voxgi_io__token_is(key, n, "newmtl")) {
            const char *name;
            size_t len = voxgi_io__rest_of_line(t, &name);
            if (!len) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "newmtl without a name");
            if (voxgi_io__material_id(L, name, len, &current)) return -1;
            continue;
        }
        if (!voxgi_io__is_identifier(key, n)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "not an MTL statement");
        if (!voxgi_io__token_is(key, n, "Kd") && !voxgi_io__token_is(key, n, "Ke") && !voxgi_io__token_is(key, n, "d") && !voxgi_io__token_is(key, n, "Tr"))
            continue; /* Ka, Ks, Ns, illum, map_* ... do not matter here */
        if (current == VOXGI_IO__NO_INDEX) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "'%.*s' before any newmtl", (int)n, key);
        m = (voxgi_io_material *)L->b.materials.data + current;
        if (voxgi_io__token_is(key, n, "Kd")) {
            if (voxgi_io__read_color(L, t, "Kd", m->albedo)) return -1;
        } else if (voxgi_io__token_is(key, n, "Ke")) {
            if (voxgi_io__read_color(L, t, "Ke", m->emission)) return -1;
        } else {
            int is_d = voxgi_io__token_is(key, n, "d");
            if (voxgi_io__more(t) && (size_t)(t->end - t->p) >= 5 && !memcmp(t->p, "-halo", 5) && voxgi_io__at_token_end(t, t->p + 5))
                t->p += 5; /* "d -halo x": the halo variant still gives the opacity */
            if (voxgi_io__read_float(L, t, is_d ? "d" : "Tr", &value)) return -1;
            m->opacity = is_d ? value : 1.0f - value; /* Tr is transparency */
        }
        if (voxgi_io__more(t)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "unexpected text after '%.*s'", (int)n, key);
    }
    return 0;
}

/* Loads an MTL file named relative to the OBJ's folder. Returns 1 when it cannot be opened, which
   is not an error: the OBJ then uses default materials. */
static int voxgi_io__load_mtl(voxgi_io__loader *L, const char *name, size_t len)
{
    const char *obj_path = L->path, *slash = obj_path, *s;
    size_t dir_len;
    char *path, *data;
    size_t size;
    int rc, open_failed;
    voxgi_io__text t;
    for (s = obj_path; *s; s++)
        if (*s == '/' || *s == '\\') slash = s + 1;
    dir_len = (name[0] == '/' || name[0] == '\\' || (len > 1 && name[1] == ':')) ? 0 : (size_t)(slash - obj_path);
    if (!(path = (char *)malloc(dir_len + len + 1))) return voxgi_io__fail_at(L, NULL, 0, "out of memory");
    memcpy(path, obj_path, dir_len);
    memcpy(path + dir_len, name, len);
    path[dir_len + len] = 0;
    L->path = path;
    rc = voxgi_io__read_file(path, &data, &size, &open_failed);
    if (rc) {
        rc = open_failed ? 1 : voxgi_io__fail_at(L, NULL, 0, "cannot read: %s", strerror(rc));
    } else {
        voxgi_io__text_init(&t, data, size, '#');
        rc = voxgi_io__mtl_parse(L, &t);
        free(data);
    }
    L->path = obj_path;
    free(path);
    return rc;
}

/* ---- OBJ -------------------------------------------------------------------------------- */

typedef struct voxgi_io__obj_state {
    voxgi_io__vec positions, texcoords, normals; /* float: v, vt, vn as listed in the file */
    voxgi_io__vec corners;                       /* uint32_t (v, vt, vn) per triangle corner, NO_INDEX when absent */
    uint32_t material;                 /* set by usemtl; NO_INDEX before the first */
    int has_texcoords, has_normals;    /* some face corner uses vt / vn */
} voxgi_io__obj_state;

/* Reads a v, vt or vn statement: `required` numbers, then up to `optional` more (vt's v, v's w or
   vertex colours); all must be finite. Only the first `keep` are stored. */
static int voxgi_io__obj_attribute(voxgi_io__loader *L, voxgi_io__text *t, voxgi_io__vec *dst, int keep, int required, int optional, const char *what)
{
    float *out, extra;
    int i;
    if (dst->count / (size_t)keep >= VOXGI_IO__NO_INDEX) return voxgi_io__fail_at(L, NULL, 0, "too many '%s' statements", what);
    if (!(out = VOXGI_IO__PUSH(L, *dst, float, (size_t)keep))) return -1;
    memset(out, 0, (size_t)keep * sizeof *out);
    for (i = 0; i < required + optional && (i < required || voxgi_io__more(t)); i++)
        if (voxgi_io__read_float(L, t, what, i < keep ? &out[i] : &extra)) return -1;
    if (voxgi_io__more(t)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "%s: too many numbers", what);
    return 0;
}

/* Parses an optionally signed decimal index; 0 when there are no digits or it exceeds 2^32. */
static int voxgi_io__parse_index(const char **s, long long *v)
{
    const char *p = *s;
    int negative = *p == '-';
    if (*p == '-' || *p == '+') p++;
    for (*v = 0; *p >= '0' && *p <= '9'; p++)
        if ((*v = *v * 10 + (*p - '0')) > 4294967296LL) return 0;
    if (p == *s + (negative || **s == '+')) return 0;
    if (negative) *v = -*v;
    *s = p;
    return 1;
}

/* Reads one face corner (v, v/vt, v//vn or v/vt/vn) and resolves 1-based and negative indices. */
static int voxgi_io__obj_corner(voxgi_io__loader *L, voxgi_io__obj_state *o, voxgi_io__text *t, uint32_t out[3])
{
    static const char *const kind[3] = {"vertex", "texture coordinate", "normal"};
    const size_t defined[3] = {o->positions.count / 3, o->texcoords.count / 2, o->normals.count / 3};
    const char *s = t->p;
    long long raw[3] = {0, 0, 0};
    int given[3] = {1, 0, 0}, k;
    if (!voxgi_io__parse_index(&s, &raw[0])) goto malformed;
    if (*s == '/') {
        s++;
        if (*s != '/' && !(given[1] = voxgi_io__parse_index(&s, &raw[1]))) goto malformed;
        if (*s == '/') {
            s++;
            if (!(given[2] = voxgi_io__parse_index(&s, &raw[2]))) goto malformed;
        }
    }
    if (!voxgi_io__at_token_end(t, s)) goto malformed;
    t->p = s;
    for (k = 0; k < 3; k++) {
        long long resolved = raw[k] < 0 ? (long long)defined[k] + raw[k] : raw[k] - 1;
        out[k] = VOXGI_IO__NO_INDEX;
        if (!given[k]) continue;
        if (raw[k] == 0 || resolved < 0 || resolved >= (long long)defined[k])
            return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "%s index %lld is out of range (%zu defined so far)", kind[k], raw[k], defined[k]);
        out[k] = (uint32_t)resolved;
    }
    o->has_texcoords |= out[1] != VOXGI_IO__NO_INDEX;
    o->has_normals |= out[2] != VOXGI_IO__NO_INDEX;
    return 0;
malformed:
    return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "malformed face corner (expected v, v/vt, v//vn or v/vt/vn)");
}

/* The rest of an mtllib line is one file name (exporters write names with spaces) or, when no file
   has that name, a list of names. */
static int voxgi_io__obj_mtllib(voxgi_io__loader *L, const char *names, size_t len)
{
    const char *s = names, *end = names + len, *e;
    int rc;
    if (L->in_memory) return 0;
    if ((rc = voxgi_io__load_mtl(L, names, len)) <= 0) return rc;
    while (s < end) {
        while (s < end && voxgi_io__is_blank(*s)) s++;
        for (e = s; e < end && !voxgi_io__is_blank(*e); e++) {}
        if (e > s && voxgi_io__load_mtl(L, s, (size_t)(e - s)) < 0) return -1;
        s = e;
    }
    return 0;
}

static int voxgi_io__obj_parse(voxgi_io__loader *L, voxgi_io__obj_state *o, voxgi_io__text *t)
{
    for (; t->p < t->end; voxgi_io__next_line(t)) {
        const char *key, *name;
        size_t n = voxgi_io__next_token(t, &key), len;
        if (!n) continue;
        if (voxgi_io__token_is(key, n, "v")) {
            if (voxgi_io__obj_attribute(L, t, &o->positions, 3, 3, 4, "v")) return -1;
        } else if (voxgi_io__token_is(key, n, "vt")) {
            if (voxgi_io__obj_attribute(L, t, &o->texcoords, 2, 1, 2, "vt")) return -1;
        } else if (voxgi_io__token_is(key, n, "vn")) {
            if (voxgi_io__obj_attribute(L, t, &o->normals, 3, 3, 0, "vn")) return -1;
        } else if (voxgi_io__token_is(key, n, "f")) {
            L->b.polygon.count = 0;
            while (voxgi_io__more(t)) {
                uint32_t *corner = VOXGI_IO__PUSH(L, L->b.polygon, uint32_t, 3);
                if (!corner || voxgi_io__obj_corner(L, o, t, corner)) return -1;
            }
            if (L->b.polygon.count < 9) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "face with fewer than 3 vertices");
            if (o->material == VOXGI_IO__NO_INDEX && voxgi_io__material_id(L, "default", 7, &o->material)) return -1;
            if (voxgi_io__add_fan(L, &o->corners, 3, o->material)) return -1;
        } else if (voxgi_io__token_is(key, n, "usemtl") || voxgi_io__token_is(key, n, "mtllib")) {
            if (!(len = voxgi_io__rest_of_line(t, &name))) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "%.*s without a name", (int)n, key);
            if (voxgi_io__token_is(key, n, "usemtl")) {
                if (voxgi_io__material_id(L, name, len, &o->material)) return -1;
            } else if (voxgi_io__obj_mtllib(L, name, len) < 0) {
                return -1;
            }
        } else if (!voxgi_io__is_identifier(key, n)) {
            return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "not an OBJ statement");
        } /* o, g, s, l, p, vp, curves ... carry nothing this loader uses */
    }
    return 0;
}

static int voxgi_io__same_corner(const void *keys, uint32_t id, const void *key)
{
    return memcmp((const uint32_t *)keys + 3 * (size_t)id, key, 3 * sizeof(uint32_t)) == 0;
}

/* Appends the vertex made by one (v, vt, vn) corner; a missing vt or vn reads as zeros. */
static int voxgi_io__obj_emit_vertex(voxgi_io__loader *L, const voxgi_io__obj_state *o, const uint32_t corner[3])
{
    static const float zero[3] = {0, 0, 0};
    const float *texcoords = (const float *)o->texcoords.data, *normals = (const float *)o->normals.data;
    float *dst;
    if (voxgi_io__add_vertex(L, (const float *)o->positions.data + 3 * (size_t)corner[0])) return -1;
    if (o->has_texcoords) {
        if (!(dst = VOXGI_IO__PUSH(L, L->b.uvs, float, 2))) return -1;
        memcpy(dst, corner[1] == VOXGI_IO__NO_INDEX ? zero : texcoords + 2 * (size_t)corner[1], 2 * sizeof *dst);
    }
    if (o->has_normals) {
        if (!(dst = VOXGI_IO__PUSH(L, L->b.normals, float, 3))) return -1;
        memcpy(dst, corner[2] == VOXGI_IO__NO_INDEX ? zero : normals + 3 * (size_t)corner[2], 3 * sizeof *dst);
    }
    return 0;
}

/* Makes the output vertices: the file's own list when no face uses vt or vn, otherwise one vertex
   per distinct (v, vt, vn) triple in order of first use, found through a hash map. */
static int voxgi_io__obj_build(voxgi_io__loader *L, voxgi_io__obj_state *o)
{
    const uint32_t *corners = (const uint32_t *)o->corners.data;
    size_t i, n = o->corners.count / 3;
    uint32_t *indices, *first_use;
    voxgi_io__vec firsts;
    voxgi_io__id_map map;
    int rc = 0;
    if (!n) return 0;
    if (!(indices = VOXGI_IO__PUSH(L, L->b.indices, uint32_t, n))) return -1;
    if (!o->has_texcoords && !o->has_normals) {
        L->b.positions = o->positions;
        memset(&o->positions, 0, sizeof o->positions);
        for (i = 0; i < n; i++) indices[i] = corners[3 * i];
        return 0;
    }
    memset(&firsts, 0, sizeof firsts);
    memset(&map, 0, sizeof map);
    for (i = 0; i < n && !rc; i++) {
        const uint32_t *key = corners + 3 * i;
        uint32_t fresh = (uint32_t)(L->b.positions.count / 3); /* add_vertex keeps this below NO_INDEX */
        uint32_t id = voxgi_io__id_map_get_or_add(&map, voxgi_io__hash_bytes(key, 3 * sizeof *key), key, voxgi_io__same_corner, firsts.data, fresh);
        if (id == VOXGI_IO__NO_INDEX) rc = voxgi_io__fail_at(L, NULL, 0, "out of memory");
        else if (id == fresh) {
            /* the map compares against the first corner that made each vertex */
            if (!(first_use = VOXGI_IO__PUSH(L, firsts, uint32_t, 3)) || voxgi_io__obj_emit_vertex(L, o, key)) rc = -1;
            else memcpy(first_use, key, 3 * sizeof *key);
        }
        indices[i] = id;
    }
    voxgi_io__vec_free(&firsts);
    free(map.slots);
    return rc;
}

static int voxgi_io__load_obj(voxgi_io__loader *L, voxgi_io__text *t)
{
    voxgi_io__obj_state o;
    int rc;
    memset(&o, 0, sizeof o);
    o.material = VOXGI_IO__NO_INDEX;
    t->comment = '#';
    rc = voxgi_io__obj_parse(L, &o, t);
    if (!rc) rc = voxgi_io__obj_build(L, &o);
    voxgi_io__vec_free(&o.positions);
    voxgi_io__vec_free(&o.texcoords);
    voxgi_io__vec_free(&o.normals);
    voxgi_io__vec_free(&o.corners);
    return rc;
}

/* ---- OFF -------------------------------------------------------------------------------- */

/* Reads the rest of an OFF face line: the vertex count, then that many indices. */
static int voxgi_io__off_face(voxgi_io__loader *L, voxgi_io__text *t, uint64_t vertex_count)
{
    uint64_t n, k, index;
    uint32_t *dst;
    if (!voxgi_io__read_uint(t, VOXGI_IO__NO_INDEX, &n)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "expected the face's vertex count");
    if (n < 3) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "face with %llu vertices", (unsigned long long)n);
    L->b.polygon.count = 0;
    for (k = 0; k < n; k++) {
        if (!voxgi_io__read_uint(t, VOXGI_IO__NO_INDEX, &index)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "expected %llu vertex indices", (unsigned long long)n);
        if (index >= vertex_count)
            return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "vertex index %llu is out of range (%llu vertices)",
                           (unsigned long long)index, (unsigned long long)vertex_count);
        if (!(dst = VOXGI_IO__PUSH(L, L->b.polygon, uint32_t, 1))) return -1;
        *dst = (uint32_t)index;
    }
    return voxgi_io__add_fan(L, &L->b.indices, 1, 0);
}

static int voxgi_io__load_off(voxgi_io__loader *L, voxgi_io__text *t)
{
    uint64_t vertex_count, face_count, i;
    const char *s = NULL;
    size_t n;
    float xyz[3];
    t->comment = '#';
    n = voxgi_io__skip_to_token(t) ? voxgi_io__next_token(t, &s) : 0;
    if (!voxgi_io__token_is(s, n, "OFF")) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "missing OFF header");
    /* the counts may share the header line or follow on the next one */
    if (!voxgi_io__skip_to_token(t) || !voxgi_io__read_uint(t, VOXGI_IO__NO_INDEX, &vertex_count) || !voxgi_io__read_uint(t, VOXGI_IO__NO_INDEX, &face_count))
        return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "expected vertex and face counts below 2^32");
    for (i = 0; i < vertex_count + face_count; i++) {
        voxgi_io__next_line(t); /* colours and other trailing values on a line are ignored */
        if (!voxgi_io__skip_to_token(t))
            return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "file ends after %llu of %llu %s", (unsigned long long)(i < vertex_count ? i : i - vertex_count),
                           (unsigned long long)(i < vertex_count ? vertex_count : face_count), i < vertex_count ? "vertices" : "faces");
        if (i < vertex_count) {
            if (voxgi_io__read_float(L, t, "vertex", &xyz[0]) || voxgi_io__read_float(L, t, "vertex", &xyz[1]) ||
                voxgi_io__read_float(L, t, "vertex", &xyz[2]) || voxgi_io__add_vertex(L, xyz)) return -1;
        } else if (voxgi_io__off_face(L, t, vertex_count)) return -1;
    }
    return 0;
}

/* ---- STL -------------------------------------------------------------------------------- */

static int voxgi_io__load_stl_ascii(voxgi_io__loader *L, voxgi_io__text *t)
{
    const char *s;
    size_t n;
    double normal;
    float xyz[3];
    int k;
    if (voxgi_io__expect_word(L, t, "solid")) return -1;
    for (voxgi_io__next_line(t);;) { /* the solid's name is skipped */
        if (!voxgi_io__skip_to_token(t)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "file ends before 'endsolid'");
        n = voxgi_io__next_token(t, &s);
        if (voxgi_io__token_is(s, n, "endsolid")) { /* another solid may follow */
            voxgi_io__next_line(t);
            if (!voxgi_io__skip_to_token(t)) return 0;
            if (voxgi_io__expect_word(L, t, "solid")) return -1;
            voxgi_io__next_line(t);
            continue;
        }
        if (!voxgi_io__token_is(s, n, "facet")) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "expected 'facet' or 'endsolid'");
        if (voxgi_io__expect_word(L, t, "normal")) return -1;
        for (k = 0; k < 3; k++)
            if (!voxgi_io__read_double(t, &normal)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "facet normal: expected 3 numbers");
        if (voxgi_io__expect_word(L, t, "outer") || voxgi_io__expect_word(L, t, "loop")) return -1;
        L->b.polygon.count = 0;
        for (;;) {
            uint32_t *corner;
            if (!voxgi_io__skip_to_token(t)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "file ends before 'endloop'");
            n = voxgi_io__next_token(t, &s);
            if (voxgi_io__token_is(s, n, "endloop")) break;
            if (!voxgi_io__token_is(s, n, "vertex")) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "expected 'vertex' or 'endloop'");
            for (k = 0; k < 3; k++)
                if (voxgi_io__read_float(L, t, "vertex", &xyz[k])) return -1;
            if (!(corner = VOXGI_IO__PUSH(L, L->b.polygon, uint32_t, 1))) return -1;
            *corner = (uint32_t)(L->b.positions.count / 3);
            if (voxgi_io__add_vertex(L, xyz)) return -1;
        }
        if (L->b.polygon.count < 3) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "facet with fewer than 3 vertices");
        if (voxgi_io__add_fan(L, &L->b.indices, 1, 0) || voxgi_io__expect_word(L, t, "endfacet")) return -1;
    }
}

static uint32_t voxgi_io__le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* 80-byte header, uint32 triangle count, then 50 bytes per triangle: normal, 3 vertices, attribute. */
static int voxgi_io__load_stl_binary(voxgi_io__loader *L, const unsigned char *data, size_t size)
{
    uint32_t count, i, *tri, *mat;
    int k;
    if (size < 84) return voxgi_io__fail_at(L, VOXGI_IO__OFFSET, size, "file ends inside the 84-byte binary STL header");
    count = voxgi_io__le32(data + 80);
    if ((size - 84) / 50 != count || (size - 84) % 50)
        return voxgi_io__fail_at(L, VOXGI_IO__OFFSET, 80, "header declares %lu triangles (%llu bytes) but the file has %zu bytes",
                       (unsigned long)count, 84 + 50ULL * count, size);
    for (i = 0; i < count; i++) {
        const unsigned char *record = data + 84 + 50 * (size_t)i;
        uint32_t first = (uint32_t)(L->b.positions.count / 3);
        float xyz[3];
        for (k = 0; k < 9; k++) {
            uint32_t bits = voxgi_io__le32(record + 12 + 4 * k);
            memcpy(&xyz[k % 3], &bits, sizeof bits);
            if (!(fabsf(xyz[k % 3]) <= FLT_MAX))
                return voxgi_io__fail_at(L, VOXGI_IO__OFFSET, (size_t)(record + 12 + 4 * k - data), "vertex coordinate is not finite");
            if (k % 3 == 2 && voxgi_io__add_vertex(L, xyz)) return -1;
        }
        if (!(tri = VOXGI_IO__PUSH(L, L->b.indices, uint32_t, 3)) || !(mat = VOXGI_IO__PUSH(L, L->b.material_ids, uint32_t, 1))) return -1;
        tri[0] = first; tri[1] = first + 1; tri[2] = first + 2;
        *mat = 0;
    }
    return 0;
}

/* ---- PLY -------------------------------------------------------------------------------- */

enum { VOXGI_IO__PLY_INT8, VOXGI_IO__PLY_UINT8, VOXGI_IO__PLY_INT16, VOXGI_IO__PLY_UINT16, VOXGI_IO__PLY_INT32, VOXGI_IO__PLY_UINT32, VOXGI_IO__PLY_FLOAT32, VOXGI_IO__PLY_FLOAT64, VOXGI_IO__PLY_TYPE_COUNT };
static const struct voxgi_io__ply_type_info { const char *name, *alias; unsigned size; double lo, hi; } voxgi_io__ply_types[VOXGI_IO__PLY_TYPE_COUNT] = {
    {"char", "int8", 1, -128.0, 127.0}, {"uchar", "uint8", 1, 0.0, 255.0},
    {"short", "int16", 2, -32768.0, 32767.0}, {"ushort", "uint16", 2, 0.0, 65535.0},
    {"int", "int32", 4, -2147483648.0, 2147483647.0}, {"uint", "uint32", 4, 0.0, 4294967295.0},
    {"float", "float32", 4, 0.0, 0.0}, {"double", "float64", 8, 0.0, 0.0}};
#define VOXGI_IO__PLY_IS_INTEGER(type) ((type) < VOXGI_IO__PLY_FLOAT32)

/* What a property means to the mesh; everything with ROLE_NONE is read and dropped. */
enum { VOXGI_IO__ROLE_NONE, VOXGI_IO__ROLE_X, VOXGI_IO__ROLE_Y, VOXGI_IO__ROLE_Z, VOXGI_IO__ROLE_NX, VOXGI_IO__ROLE_NY, VOXGI_IO__ROLE_NZ, VOXGI_IO__ROLE_U, VOXGI_IO__ROLE_V, VOXGI_IO__ROLE_INDICES, VOXGI_IO__ROLE_COUNT };
#define VOXGI_IO__ROLE_BIT(role) (1u << (role))
#define VOXGI_IO__PLY_MAX_ELEMENTS 16
#define VOXGI_IO__PLY_MAX_PROPERTIES 32

typedef struct voxgi_io__ply_property { int type, count_type, role; } voxgi_io__ply_property; /* count_type < 0: a scalar */
typedef struct voxgi_io__ply_element {
    const char *name;
    size_t name_len;
    uint32_t count;
    int property_count;
    voxgi_io__ply_property properties[VOXGI_IO__PLY_MAX_PROPERTIES];
} voxgi_io__ply_element;
typedef struct voxgi_io__ply_file {
    int binary, element_count;
    voxgi_io__ply_element elements[VOXGI_IO__PLY_MAX_ELEMENTS];
} voxgi_io__ply_file;

static int voxgi_io__ply_type(const char *s, size_t n)
{
    int i;
    for (i = 0; i < VOXGI_IO__PLY_TYPE_COUNT; i++)
        if (voxgi_io__token_is(s, n, voxgi_io__ply_types[i].name) || voxgi_io__token_is(s, n, voxgi_io__ply_types[i].alias)) return i;
    return -1;
}

static int voxgi_io__ply_role(const voxgi_io__ply_element *e, const char *s, size_t n, int is_list)
{
    static const char *const names[] = {"x", "y", "z", "nx", "ny", "nz", "u", "v", "s", "t",
                                        "texture_u", "texture_v", "texture_s", "texture_t"};
    static const int roles[] = {VOXGI_IO__ROLE_X, VOXGI_IO__ROLE_Y, VOXGI_IO__ROLE_Z, VOXGI_IO__ROLE_NX, VOXGI_IO__ROLE_NY, VOXGI_IO__ROLE_NZ, VOXGI_IO__ROLE_U, VOXGI_IO__ROLE_V,
                                VOXGI_IO__ROLE_U, VOXGI_IO__ROLE_V, VOXGI_IO__ROLE_U, VOXGI_IO__ROLE_V, VOXGI_IO__ROLE_U, VOXGI_IO__ROLE_V};
    size_t i;
    if (voxgi_io__token_is(e->name, e->name_len, "vertex") && !is_list)
        for (i = 0; i < sizeof names / sizeof names[0]; i++)
            if (voxgi_io__token_is(s, n, names[i])) return roles[i];
    if (voxgi_io__token_is(e->name, e->name_len, "face") && is_list && (voxgi_io__token_is(s, n, "vertex_indices") || voxgi_io__token_is(s, n, "vertex_index")))
        return VOXGI_IO__ROLE_INDICES;
    return VOXGI_IO__ROLE_NONE;
}

static int voxgi_io__ply_property_line(voxgi_io__loader *L, voxgi_io__text *t, voxgi_io__ply_element *e)
{
    voxgi_io__ply_property *p;
    const char *s;
    size_t n;
    int is_list;
    if (!e) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "property before any element");
    if (e->property_count == VOXGI_IO__PLY_MAX_PROPERTIES) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "more than %d properties", VOXGI_IO__PLY_MAX_PROPERTIES);
    p = &e->properties[e->property_count++];
    n = voxgi_io__next_token(t, &s);
    is_list = voxgi_io__token_is(s, n, "list");
    p->count_type = -1;
    if (is_list) {
        n = voxgi_io__next_token(t, &s);
        if ((p->count_type = voxgi_io__ply_type(s, n)) < 0 || !VOXGI_IO__PLY_IS_INTEGER(p->count_type))
            return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "list length type must be an integer type");
        n = voxgi_io__next_token(t, &s);
    }
    if ((p->type = voxgi_io__ply_type(s, n)) < 0) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "unknown property type '%.*s'", (int)(n < 32 ? n : 32), s);
    if (!(n = voxgi_io__next_token(t, &s))) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "property without a name");
    p->role = voxgi_io__ply_role(e, s, n, is_list);
    if (p->role == VOXGI_IO__ROLE_INDICES && !VOXGI_IO__PLY_IS_INTEGER(p->type)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "vertex indices must have an integer type");
    return 0;
}

static int voxgi_io__ply_header(voxgi_io__loader *L, voxgi_io__text *t, voxgi_io__ply_file *f)
{
    int have_format = 0;
    const char *s;
    size_t n;
    memset(f, 0, sizeof *f);
    n = voxgi_io__next_token(t, &s);
    if (!voxgi_io__token_is(s, n, "ply") || voxgi_io__more(t)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, 1, "missing 'ply' magic line");
    for (;;) {
        voxgi_io__ply_element *e = f->element_count ? &f->elements[f->element_count - 1] : NULL;
        uint64_t count;
        voxgi_io__next_line(t);
        if (t->p >= t->end) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "header ends without end_header");
        if (!(n = voxgi_io__next_token(t, &s)) || voxgi_io__token_is(s, n, "comment") || voxgi_io__token_is(s, n, "obj_info")) continue;
        if (voxgi_io__token_is(s, n, "end_header")) break;
        if (voxgi_io__token_is(s, n, "format")) {
            n = voxgi_io__next_token(t, &s);
            if (voxgi_io__token_is(s, n, "binary_big_endian")) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "binary_big_endian PLY is not supported");
            if (!voxgi_io__token_is(s, n, "ascii") && !voxgi_io__token_is(s, n, "binary_little_endian")) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "unknown PLY format");
            f->binary = voxgi_io__token_is(s, n, "binary_little_endian");
            if (!voxgi_io__next_token(t, &s)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "format without a version");
            have_format = 1;
        } else if (voxgi_io__token_is(s, n, "element")) {
            if (f->element_count == VOXGI_IO__PLY_MAX_ELEMENTS) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "more than %d elements", VOXGI_IO__PLY_MAX_ELEMENTS);
            e = &f->elements[f->element_count++];
            if (!(e->name_len = voxgi_io__next_token(t, &e->name))) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "element without a name");
            if (!voxgi_io__read_uint(t, UINT32_MAX, &count)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "element count must be an integer below 2^32");
            e->count = (uint32_t)count;
        } else if (voxgi_io__token_is(s, n, "property")) {
            if (voxgi_io__ply_property_line(L, t, e)) return -1;
        } else {
            return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "unknown PLY header line");
        }
        if (voxgi_io__more(t)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "unexpected text at the end of the header line");
    }
    if (!have_format) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "header has no format line");
    return 0;
}

/* Reads one value; *at receives where it was (a line, or a byte offset in binary files). */
static int voxgi_io__ply_value(voxgi_io__loader *L, voxgi_io__text *t, int binary, int type, double *v, size_t *at)
{
    if (binary) {
        const unsigned char *p = (const unsigned char *)t->p;
        unsigned size = voxgi_io__ply_types[type].size, i;
        uint64_t bits = 0;
        *at = (size_t)(t->p - t->base);
        if ((size_t)(t->end - t->p) < size) return voxgi_io__fail_at(L, VOXGI_IO__OFFSET, *at, "file ends inside a %s value", voxgi_io__ply_types[type].name);
        for (i = size; i-- > 0;) bits = bits << 8 | p[i];
        t->p += size;
        if (type == VOXGI_IO__PLY_FLOAT32) {
            uint32_t bits32 = (uint32_t)bits;
            float f;
            memcpy(&f, &bits32, sizeof f);
            *v = f;
        } else if (type == VOXGI_IO__PLY_FLOAT64) {
            memcpy(v, &bits, sizeof *v);
        } else { /* sign-extend by hand: converting to a narrower signed type is implementation-defined */
            *v = (double)bits;
            if (type % 2 == 0 && bits >> (8 * size - 1)) *v -= ldexp(1.0, (int)(8 * size));
        }
        return 0;
    }
    if (!voxgi_io__skip_to_token(t)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "file ends before all elements were read");
    *at = t->line;
    if (!voxgi_io__read_double(t, v)) return voxgi_io__fail_at(L, VOXGI_IO__LINE, *at, "expected a number");
    if (VOXGI_IO__PLY_IS_INTEGER(type) && !(*v == floor(*v) && *v >= voxgi_io__ply_types[type].lo && *v <= voxgi_io__ply_types[type].hi))
        return voxgi_io__fail_at(L, VOXGI_IO__LINE, *at, "%g is not a valid %s", *v, voxgi_io__ply_types[type].name);
    return 0;
}

/* Reads a list property whose length was just read: vertex indices become a triangle fan, any other
   list is skipped. */
static int voxgi_io__ply_list(voxgi_io__loader *L, voxgi_io__text *t, int binary, const voxgi_io__ply_property *p, double length, size_t at, uint32_t vertex_count)
{
    const char *where = binary ? VOXGI_IO__OFFSET : VOXGI_IO__LINE;
    size_t n, k;
    double v;
    uint32_t *dst;
    if (length < 0) return voxgi_io__fail_at(L, where, at, "negative list length");
    n = (size_t)length; /* an integer below 2^32: ply_value checked it against its type */
    if (binary && n > (size_t)(t->end - t->p) / voxgi_io__ply_types[p->type].size)
        return voxgi_io__fail_at(L, where, at, "list of %zu values runs past the end of the file", n);
    if (p->role != VOXGI_IO__ROLE_INDICES) {
        if (binary) t->p += n * voxgi_io__ply_types[p->type].size;
        for (k = 0; !binary && k < n; k++)
            if (voxgi_io__ply_value(L, t, binary, p->type, &v, &at)) return -1;
        return 0;
    }
    if (n < 3) return voxgi_io__fail_at(L, where, at, "face with %zu vertices", n);
    L->b.polygon.count = 0;
    for (k = 0; k < n; k++) {
        if (voxgi_io__ply_value(L, t, binary, p->type, &v, &at)) return -1;
        if (v < 0 || v >= vertex_count)
            return voxgi_io__fail_at(L, where, at, "vertex index %.0f is out of range (%lu vertices)", v, (unsigned long)vertex_count);
        if (!(dst = VOXGI_IO__PUSH(L, L->b.polygon, uint32_t, 1))) return -1;
        *dst = (uint32_t)v;
    }
    return voxgi_io__add_fan(L, &L->b.indices, 1, 0);
}

/* Reads every record of an element; vertex_roles is non-zero for the vertex element and says which
   optional attributes (normals, uvs) are complete. */
static int voxgi_io__ply_element_data(voxgi_io__loader *L, voxgi_io__text *t, const voxgi_io__ply_file *f, const voxgi_io__ply_element *e, uint32_t vertex_count, unsigned vertex_roles)
{
    const char *where = f->binary ? VOXGI_IO__OFFSET : VOXGI_IO__LINE;
    size_t min_record = 0, left = (size_t)(t->end - t->p) + !f->binary; /* the last ASCII value needs no separator */
    double value[VOXGI_IO__ROLE_COUNT], v;
    uint32_t r;
    int i;
    for (i = 0; i < e->property_count; i++) {
        const voxgi_io__ply_property *p = &e->properties[i];
        min_record += f->binary ? voxgi_io__ply_types[p->count_type < 0 ? p->type : p->count_type].size : 2;
    }
    /* reject absurd counts before reading (or allocating for) any record */
    if (e->count > left / min_record)
        return voxgi_io__fail_at(L, where, f->binary ? (size_t)(t->p - t->base) : t->line, "element '%.*s' declares %lu records, more than the %zu bytes left can hold",
                       (int)e->name_len, e->name, (unsigned long)e->count, left);
    for (r = 0; r < e->count; r++) {
        memset(value, 0, sizeof value);
        for (i = 0; i < e->property_count; i++) {
            const voxgi_io__ply_property *p = &e->properties[i];
            size_t at;
            if (voxgi_io__ply_value(L, t, f->binary, p->count_type < 0 ? p->type : p->count_type, &v, &at)) return -1;
            if (p->count_type >= 0) {
                if (voxgi_io__ply_list(L, t, f->binary, p, v, at, vertex_count)) return -1;
            } else if (p->role != VOXGI_IO__ROLE_NONE) {
                if (!(fabs(v) <= FLT_MAX)) return voxgi_io__fail_at(L, where, at, "vertex value is not finite or too large for a float");
                value[p->role] = v;
            }
        }
        if (vertex_roles) {
            float xyz[3], *dst;
            for (i = 0; i < 3; i++) xyz[i] = (float)value[VOXGI_IO__ROLE_X + i];
            if (voxgi_io__add_vertex(L, xyz)) return -1;
            if (vertex_roles & VOXGI_IO__ROLE_BIT(VOXGI_IO__ROLE_NX)) {
                if (!(dst = VOXGI_IO__PUSH(L, L->b.normals, float, 3))) return -1;
                for (i = 0; i < 3; i++) dst[i] = (float)value[VOXGI_IO__ROLE_NX + i];
            }
            if (vertex_roles & VOXGI_IO__ROLE_BIT(VOXGI_IO__ROLE_U)) {
                if (!(dst = VOXGI_IO__PUSH(L, L->b.uvs, float, 2))) return -1;
                dst[0] = (float)value[VOXGI_IO__ROLE_U];
                dst[1] = (float)value[VOXGI_IO__ROLE_V];
            }
        }
    }
    return 0;
}

static int voxgi_io__load_ply(voxgi_io__loader *L, voxgi_io__text *t)
{
    const unsigned xyz = VOXGI_IO__ROLE_BIT(VOXGI_IO__ROLE_X) | VOXGI_IO__ROLE_BIT(VOXGI_IO__ROLE_Y) | VOXGI_IO__ROLE_BIT(VOXGI_IO__ROLE_Z);
    const unsigned normals = VOXGI_IO__ROLE_BIT(VOXGI_IO__ROLE_NX) | VOXGI_IO__ROLE_BIT(VOXGI_IO__ROLE_NY) | VOXGI_IO__ROLE_BIT(VOXGI_IO__ROLE_NZ), uvs = VOXGI_IO__ROLE_BIT(VOXGI_IO__ROLE_U) | VOXGI_IO__ROLE_BIT(VOXGI_IO__ROLE_V);
    voxgi_io__ply_file f;
    unsigned roles = 0, has_indices = 0;
    int i, k, vertex_element = -1;
    if (voxgi_io__ply_header(L, t, &f)) return -1;
    for (i = 0; i < f.element_count; i++) {
        const voxgi_io__ply_element *e = &f.elements[i];
        if (vertex_element < 0 && voxgi_io__token_is(e->name, e->name_len, "vertex")) {
            vertex_element = i;
            for (k = 0; k < e->property_count; k++) roles |= VOXGI_IO__ROLE_BIT(e->properties[k].role);
        }
        for (k = 0; k < e->property_count; k++) has_indices |= e->properties[k].role == VOXGI_IO__ROLE_INDICES;
    }
    if (vertex_element < 0 || (roles & xyz) != xyz)
        return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "header has no vertex element with x, y and z");
    if (!has_indices) return voxgi_io__fail_at(L, VOXGI_IO__LINE, t->line, "header has no face element with vertex_indices");
    roles = xyz | ((roles & normals) == normals ? normals : 0) | ((roles & uvs) == uvs ? uvs : 0);
    voxgi_io__next_line(t);
    for (i = 0; i < f.element_count; i++) {
        const voxgi_io__ply_element *e = &f.elements[i];
        if (!e->property_count) continue; /* records without properties take no bytes */
        if (voxgi_io__ply_element_data(L, t, &f, e, f.elements[vertex_element].count, i == vertex_element ? roles : 0)) return -1;
    }
    return 0;
}

/* ---- format choice and the public entry points ----------------------------------------------- */

static int voxgi_io__starts_with_word(const char *data, const char *word)
{
    size_t n = strlen(word);
    while (voxgi_io__is_blank(*data) || *data == '\n') data++;
    return strncmp(data, word, n) == 0 && (data[n] == 0 || voxgi_io__is_blank(data[n]) || data[n] == '\n');
}

static int voxgi_io__has_extension(const char *path, const char *ext)
{
    const char *dot = strrchr(path, '.');
    size_t i;
    if (!dot || strchr(dot, '/') || strchr(dot, '\\')) return 0;
    for (i = 0; ext[i]; i++) {
        char c = dot[1 + i];
        if ((c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c) != ext[i]) return 0;
    }
    return dot[1 + i] == 0;
}

static int voxgi_io__is_gltf(const char *path, const char *data, size_t size);        /* part 3 */
static int voxgi_io__load_gltf(voxgi_io__loader *L, const char *path, const char *data, size_t size);

static int voxgi_io__load_any(voxgi_io__loader *L, const char *path, const char *data, size_t size)
{
    voxgi_io__text t;
    /* a binary STL's size follows from its triangle count, even when its header starts with "solid";
       ASCII STL never holds NUL bytes while binary data almost always does */
    int stl_binary_size = size >= 84 && (size - 84) % 50 == 0 && (size - 84) / 50 == voxgi_io__le32((const unsigned char *)data + 80);
    int stl_ascii = voxgi_io__starts_with_word(data, "solid") && !memchr(data, 0, size);
    int ply = (size >= 4 && !memcmp(data, "ply\n", 4)) || (size >= 5 && !memcmp(data, "ply\r\n", 5));
    voxgi_io__text_init(&t, data, size, 0);
    /* content first; the extension only decides for files without a signature (OBJ has none) */
    if (stl_binary_size) return voxgi_io__load_stl_binary(L, (const unsigned char *)data, size);
    if (voxgi_io__is_gltf(path, data, size)) return voxgi_io__load_gltf(L, path, data, size);
    if (ply) return voxgi_io__load_ply(L, &t);
    if (stl_ascii) return voxgi_io__load_stl_ascii(L, &t);
    if (voxgi_io__starts_with_word(data, "OFF") || voxgi_io__has_extension(path, "off")) return voxgi_io__load_off(L, &t);
    if (voxgi_io__has_extension(path, "stl")) return voxgi_io__load_stl_binary(L, (const unsigned char *)data, size);
    if (voxgi_io__has_extension(path, "ply")) return voxgi_io__load_ply(L, &t);
    if (voxgi_io__has_extension(path, "obj")) return voxgi_io__load_obj(L, &t);
    return voxgi_io__fail_at(L, NULL, 0, "unrecognised mesh format (expected OBJ, OFF, STL, PLY, glTF or GLB)");
}

/* The mesh's arrays as voxgi.h takes them: the voxgi_mesh over them, and its materials as
   voxgi_material (whose transparency is 1 - opacity, so that zero is opaque). 0, or -1 out of memory. */
static int voxgi_io__make_scene_view(voxgi_io_mesh *m)
{
    size_t i;
    m->scene_materials = (voxgi_material *)calloc(m->material_count, sizeof *m->scene_materials);
    if (!m->scene_materials) return -1;
    for (i = 0; i < m->material_count; i++) {
        memcpy(m->scene_materials[i].albedo, m->materials[i].albedo, sizeof m->scene_materials[i].albedo);
        memcpy(m->scene_materials[i].emission, m->materials[i].emission, sizeof m->scene_materials[i].emission);
        m->scene_materials[i].transparency = 1.0f - m->materials[i].opacity;
    }
    memset(&m->mesh, 0, sizeof m->mesh);
    m->mesh.positions = m->positions;
    m->mesh.vertex_count = m->vertex_count;
    m->mesh.indices = m->indices;
    m->mesh.index_count = 3 * m->triangle_count;
    m->mesh.normals = m->normals;
    m->mesh.uvs = m->uvs;
    m->mesh.material_ids = m->material_ids;
    return 0;
}

/* Loads the mesh from data (size bytes and a NUL after them, which the text cursor's strtod stops
   at) into *out, which is zeroed first; L names the input. The core of both public loaders. */
static int voxgi_io__load(voxgi_io__loader *L, const char *data, size_t size, voxgi_io_mesh *out)
{
    uint32_t unused_id;
    int rc = voxgi_io__load_any(L, L->path, data, size);
    if (!rc && !L->b.indices.count) rc = voxgi_io__fail_at(L, NULL, 0, "contains no triangles");
    if (!rc && !L->b.materials.count) rc = voxgi_io__material_id(L, "default", 7, &unused_id);
    if (rc) {
        voxgi_io__vec_free(&L->b.positions); voxgi_io__vec_free(&L->b.normals); voxgi_io__vec_free(&L->b.uvs);
        voxgi_io__vec_free(&L->b.indices); voxgi_io__vec_free(&L->b.material_ids); voxgi_io__vec_free(&L->b.materials);
        free(L->b.material_names.slots);
        voxgi_io__vec_free(&L->b.polygon);
        return -1;
    }
    out->positions = (float *)L->b.positions.data;
    out->normals = (float *)L->b.normals.data;
    out->uvs = (float *)L->b.uvs.data;
    out->indices = (uint32_t *)L->b.indices.data;
    out->material_ids = (uint32_t *)L->b.material_ids.data;
    out->materials = (voxgi_io_material *)L->b.materials.data;
    out->vertex_count = L->b.positions.count / 3;
    out->triangle_count = L->b.indices.count / 3;
    out->material_count = L->b.materials.count;
    free(L->b.material_names.slots);
    voxgi_io__vec_free(&L->b.polygon);
    if (voxgi_io__make_scene_view(out) != 0) {
        voxgi_io_mesh_free(out);
        return voxgi_io__fail_at(L, NULL, 0, "out of memory");
    }
    return 0;
}

static void voxgi_io__loader_init(voxgi_io__loader *L, const char *path, char *err, size_t err_size)
{
    memset(L, 0, sizeof *L);
    L->path = path;
    L->err = err;
    L->err_size = err_size;
    if (err && err_size) err[0] = 0;
}

VOXGI_IO_API int voxgi_io_load_mesh(const char *path, voxgi_io_mesh *out, char *err, size_t err_size)
{
    voxgi_io__loader L;
    char *data;
    size_t size;
    int rc, open_failed;
    voxgi_io__loader_init(&L, path ? path : "(null)", err, err_size);
    if (!out || !path) return voxgi_io__fail_at(&L, NULL, 0, "no mesh or no path given");
    memset(out, 0, sizeof *out);
    if ((rc = voxgi_io__read_file(path, &data, &size, &open_failed)) != 0)
        return voxgi_io__fail_at(&L, NULL, 0, "cannot %s: %s", open_failed ? "open" : "read", strerror(rc));
    rc = voxgi_io__load(&L, data, size, out);
    free(data);
    return rc;
}

VOXGI_IO_API int voxgi_io_load_mesh_memory(const void *data, size_t size, const char *name, voxgi_io_mesh *out, char *err, size_t err_size)
{
    voxgi_io__loader L;
    char *copy;
    int rc;
    voxgi_io__loader_init(&L, name ? name : "(memory)", err, err_size);
    L.in_memory = 1;
    if (!out || (!data && size)) return voxgi_io__fail_at(&L, NULL, 0, "no mesh or no data given");
    memset(out, 0, sizeof *out);
    if (size == SIZE_MAX || !(copy = (char *)malloc(size + 1))) return voxgi_io__fail_at(&L, NULL, 0, "out of memory");
    if (size) memcpy(copy, data, size);
    copy[size] = 0;
    rc = voxgi_io__load(&L, copy, size, out);
    free(copy);
    return rc;
}

VOXGI_IO_API void voxgi_io_mesh_free(voxgi_io_mesh *m)
{
    if (!m) return;
    free(m->positions);
    free(m->normals);
    free(m->uvs);
    free(m->indices);
    free(m->material_ids);
    free(m->materials);
    free(m->scene_materials);
    memset(m, 0, sizeof *m);
}

VOXGI_IO_API voxgi_scene voxgi_io_mesh_scene(const voxgi_io_mesh *m)
{
    voxgi_scene scene;
    memset(&scene, 0, sizeof scene);
    if (!m || !m->triangle_count) return scene; /* an empty mesh: an empty scene, which voxgi refuses */
    scene.meshes = &m->mesh;
    scene.mesh_count = 1;
    scene.materials = m->scene_materials;
    scene.material_count = m->material_count;
    return scene;
}

/* ===================================================================== 3. glTF */

/* glTF 2.0: the JSON is tokenised once into a flat array (no recursion: an explicit stack whose
   depth is limited), then read by index. Buffers are the GLB's BIN chunk, data URIs (base64) or
   files beside the .gltf. The node tree is walked with an explicit stack; every triangle primitive
   of every mesh it reaches is appended with its node's world transform applied. Every error names
   a byte offset: of the JSON value at fault (in a .glb, counted from the file's start) or of the
   GLB structure. */

#define VOXGI_IO__JSON_MAX_DEPTH 64
#define VOXGI_IO__NONE ((size_t)-1)

enum { VOXGI_IO__J_OBJECT, VOXGI_IO__J_ARRAY, VOXGI_IO__J_STRING, VOXGI_IO__J_NUMBER, VOXGI_IO__J_LITERAL };

typedef struct voxgi_io__jtok {
    int type;
    size_t start, end; /* the value's bytes in the JSON text; a string's without its quotes */
    size_t count;      /* an object's members (key-value pairs) or an array's elements */
    size_t next;       /* the token after this value and everything inside it */
} voxgi_io__jtok;

typedef struct voxgi_io__gltf_buffer { const unsigned char *data; size_t size; char *owned; } voxgi_io__gltf_buffer;

/* A top-level array of the glTF JSON (accessors, nodes, ...): the token of each element. */
typedef struct voxgi_io__jlist { size_t *item, count; } voxgi_io__jlist;

typedef struct voxgi_io__gltf {
    voxgi_io__loader *L;
    const char *path;
    const char *json;
    size_t json_size, json_base; /* json[0] is at byte json_base of the file */
    voxgi_io__jtok *tok;
    size_t tok_count;
    const unsigned char *bin;    /* a .glb's BIN chunk, or NULL */
    size_t bin_size;
    voxgi_io__gltf_buffer *buffers;
    unsigned char **dense;       /* per accessor: its sparse elements, tightly packed, once made */
    voxgi_io__jlist buffer_list, views, accessors, meshes, nodes, materials, scenes;
    uint32_t default_material;   /* NO_INDEX until a primitive without a material needs it */
} voxgi_io__gltf;

typedef struct voxgi_io__accessor {
    const unsigned char *data;
    size_t count, stride;
    uint32_t component; /* componentType: 5121 uint8, 5123 uint16, 5125 uint32, 5126 float, ... */
    int components;     /* 1 SCALAR, 3 VEC3, ... */
} voxgi_io__accessor;

/* Fails at the byte offset of token tok (NONE: no offset). */
static int voxgi_io__gltf_fail(voxgi_io__gltf *G, size_t tok, const char *fmt, ...) VOXGI_IO__PRINTF_LIKE(3, 4);
static int voxgi_io__gltf_fail(voxgi_io__gltf *G, size_t tok, const char *fmt, ...)
{
    char msg[384];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (tok == VOXGI_IO__NONE) return voxgi_io__fail_at(G->L, NULL, 0, "%s", msg);
    return voxgi_io__fail_at(G->L, VOXGI_IO__OFFSET, G->json_base + G->tok[tok].start - (G->tok[tok].type == VOXGI_IO__J_STRING), "%s", msg);
}

/* ---- JSON ------------------------------------------------------------------------------- */

static int voxgi_io__json_error(voxgi_io__gltf *G, size_t at, const char *what)
{
    return voxgi_io__fail_at(G->L, VOXGI_IO__OFFSET, G->json_base + at, "malformed JSON: %s", what);
}

static int voxgi_io__is_digit(char c) { return c >= '0' && c <= '9'; }
static int voxgi_io__hex_value(char c)
{
    return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
}

/* Scans the string starting at the quote s[*i]; *i ends one past the closing quote. */
static int voxgi_io__json_scan_string(voxgi_io__gltf *G, size_t *i)
{
    const char *s = G->json;
    size_t n = G->json_size, j = *i + 1;
    for (;; j++) {
        if (j >= n) return voxgi_io__json_error(G, *i, "unterminated string");
        if (s[j] == '"') break;
        if ((unsigned char)s[j] < 0x20) return voxgi_io__json_error(G, j, "control character in a string");
        if (s[j] == '\\') {
            if (++j >= n) return voxgi_io__json_error(G, *i, "unterminated string");
            if (s[j] == 'u') {
                int k;
                for (k = 1; k <= 4; k++)
                    if (j + k >= n || voxgi_io__hex_value(s[j + k]) < 0) return voxgi_io__json_error(G, j, "bad \\u escape");
                j += 4;
            } else if (!strchr("\"\\/bfnrt", s[j]) || !s[j]) return voxgi_io__json_error(G, j - 1, "bad escape");
        }
    }
    *i = j + 1;
    return 0;
}

static int voxgi_io__json_scan_number(voxgi_io__gltf *G, size_t *i)
{
    const char *s = G->json;
    size_t n = G->json_size, j = *i;
    if (j < n && s[j] == '-') j++;
    if (j < n && s[j] == '0') j++;
    else if (j < n && voxgi_io__is_digit(s[j])) while (j < n && voxgi_io__is_digit(s[j])) j++;
    else return voxgi_io__json_error(G, *i, "malformed number");
    if (j < n && s[j] == '.') {
        if (++j >= n || !voxgi_io__is_digit(s[j])) return voxgi_io__json_error(G, *i, "malformed number");
        while (j < n && voxgi_io__is_digit(s[j])) j++;
    }
    if (j < n && (s[j] == 'e' || s[j] == 'E')) {
        if (++j < n && (s[j] == '+' || s[j] == '-')) j++;
        if (j >= n || !voxgi_io__is_digit(s[j])) return voxgi_io__json_error(G, *i, "malformed number");
        while (j < n && voxgi_io__is_digit(s[j])) j++;
    }
    *i = j;
    return 0;
}

/* Tokenises G->json; the root must be an object. */
static int voxgi_io__json_parse(voxgi_io__gltf *G)
{
    enum { VALUE, KEY, COLON, AFTER } state = VALUE;
    const char *s = G->json;
    size_t n = G->json_size, i = 0, stack[VOXGI_IO__JSON_MAX_DEPTH];
    int depth = 0, may_close = 0;
    voxgi_io__vec toks;
    memset(&toks, 0, sizeof toks);
#define VOXGI_IO__TOKS ((voxgi_io__jtok *)toks.data)
#define VOXGI_IO__JFAIL(at, what) do { voxgi_io__vec_free(&toks); return voxgi_io__json_error(G, (at), (what)); } while (0)
    for (;;) {
        char c;
        voxgi_io__jtok *t;
        while (i < n && (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r')) i++;
        if (i >= n) {
            if (state == AFTER && depth == 0) break;
            VOXGI_IO__JFAIL(n, "the text ends inside a value");
        }
        c = s[i];
        if (state == COLON) {
            if (c != ':') VOXGI_IO__JFAIL(i, "expected ':'");
            state = VALUE; may_close = 0; i++;
            continue;
        }
        if (state == AFTER) {
            int in_object = depth && VOXGI_IO__TOKS[stack[depth - 1]].type == VOXGI_IO__J_OBJECT;
            if (!depth) VOXGI_IO__JFAIL(i, "text after the end of the JSON value");
            if (c == ',') { state = in_object ? KEY : VALUE; may_close = 0; i++; continue; }
            if (c != (in_object ? '}' : ']')) VOXGI_IO__JFAIL(i, in_object ? "expected ',' or '}'" : "expected ',' or ']'");
        }
        if ((state == AFTER || (may_close && state == (c == '}' ? KEY : VALUE))) && (c == '}' || c == ']')) {
            t = &VOXGI_IO__TOKS[stack[--depth]];
            if ((c == '}') != (t->type == VOXGI_IO__J_OBJECT)) VOXGI_IO__JFAIL(i, "mismatched bracket");
            t->end = i + 1;
            t->next = toks.count;
            state = AFTER; i++;
            continue;
        }
        if (state == KEY && c != '"') VOXGI_IO__JFAIL(i, "expected a string key");
        if (!(t = (voxgi_io__jtok *)voxgi_io__vec_push(&toks, 1, sizeof *t))) {
            voxgi_io__vec_free(&toks);
            return voxgi_io__fail_at(G->L, NULL, 0, "out of memory");
        }
        memset(t, 0, sizeof *t);
        t->start = i;
        t->next = toks.count;
        if (depth && (state == KEY || VOXGI_IO__TOKS[stack[depth - 1]].type == VOXGI_IO__J_ARRAY)) VOXGI_IO__TOKS[stack[depth - 1]].count++;
        if (c == '{' || c == '[') {
            if (depth == VOXGI_IO__JSON_MAX_DEPTH) VOXGI_IO__JFAIL(i, "nested deeper than 64 levels");
            t->type = c == '{' ? VOXGI_IO__J_OBJECT : VOXGI_IO__J_ARRAY;
            stack[depth++] = toks.count - 1;
            state = c == '{' ? KEY : VALUE; may_close = 1; i++;
            continue;
        }
        if (c == '"') {
            t->type = VOXGI_IO__J_STRING;
            t->start = i + 1;
            if (voxgi_io__json_scan_string(G, &i)) { voxgi_io__vec_free(&toks); return -1; }
            VOXGI_IO__TOKS[toks.count - 1].end = i - 1;
            state = state == KEY ? COLON : AFTER;
            continue;
        }
        if (state == KEY) VOXGI_IO__JFAIL(i, "expected a string key");
        if (c == '-' || voxgi_io__is_digit(c)) {
            t->type = VOXGI_IO__J_NUMBER;
            if (voxgi_io__json_scan_number(G, &i)) { voxgi_io__vec_free(&toks); return -1; }
        } else {
            static const char *const words[3] = {"true", "false", "null"};
            int w;
            for (w = 0; w < 3; w++)
                if (n - i >= strlen(words[w]) && !memcmp(s + i, words[w], strlen(words[w]))) break;
            if (w == 3) VOXGI_IO__JFAIL(i, "expected a value");
            t->type = VOXGI_IO__J_LITERAL;
            i += strlen(words[w]);
        }
        VOXGI_IO__TOKS[toks.count - 1].end = i;
        state = AFTER;
    }
#undef VOXGI_IO__JFAIL
    G->tok = VOXGI_IO__TOKS;
    G->tok_count = toks.count;
#undef VOXGI_IO__TOKS
    if (G->tok[0].type != VOXGI_IO__J_OBJECT) return voxgi_io__json_error(G, G->tok[0].start, "the top level is not an object");
    return 0;
}

static int voxgi_io__json_is(const voxgi_io__gltf *G, size_t t, const char *word)
{
    size_t n = strlen(word);
    return t != VOXGI_IO__NONE && G->tok[t].type == VOXGI_IO__J_STRING && G->tok[t].end - G->tok[t].start == n &&
           !memcmp(G->json + G->tok[t].start, word, n);
}

/* The value of obj's member key; NONE when obj is not an object or has no such member. */
static size_t voxgi_io__json_get(const voxgi_io__gltf *G, size_t obj, const char *key)
{
    size_t i, k;
    if (obj == VOXGI_IO__NONE || G->tok[obj].type != VOXGI_IO__J_OBJECT) return VOXGI_IO__NONE;
    for (i = obj + 1, k = 0; k < G->tok[obj].count; k++, i = G->tok[i + 1].next)
        if (voxgi_io__json_is(G, i, key)) return i + 1;
    return VOXGI_IO__NONE;
}

/* The elements of the array at t (NONE: an empty list); an error when t is not an array. */
static int voxgi_io__json_list(voxgi_io__gltf *G, size_t t, const char *what, voxgi_io__jlist *list)
{
    size_t i, k;
    list->item = NULL;
    list->count = 0;
    if (t == VOXGI_IO__NONE) return 0;
    if (G->tok[t].type != VOXGI_IO__J_ARRAY) return voxgi_io__gltf_fail(G, t, "%s is not an array", what);
    if (!(list->item = (size_t *)malloc((G->tok[t].count ? G->tok[t].count : 1) * sizeof *list->item)))
        return voxgi_io__gltf_fail(G, VOXGI_IO__NONE, "out of memory");
    for (i = t + 1, k = 0; k < G->tok[t].count; k++, i = G->tok[i].next) list->item[k] = i;
    list->count = G->tok[t].count;
    return 0;
}

static int voxgi_io__json_number(voxgi_io__gltf *G, size_t t, const char *what, double *v)
{
    if (G->tok[t].type != VOXGI_IO__J_NUMBER) return voxgi_io__gltf_fail(G, t, "%s is not a number", what);
    *v = strtod(G->json + G->tok[t].start, NULL); /* the scan checked the grammar, so strtod stops where it did */
    if (!(fabs(*v) <= FLT_MAX)) return voxgi_io__gltf_fail(G, t, "%s is too large for a float", what);
    return 0;
}

/* obj.key as an integer in [0, max]; def when absent (NONE: it is required). */
static int voxgi_io__json_uint(voxgi_io__gltf *G, size_t obj, const char *key, size_t def, size_t max, const char *what, size_t *v)
{
    size_t t = voxgi_io__json_get(G, obj, key);
    double d = 0;
    if (t == VOXGI_IO__NONE) {
        if (def == VOXGI_IO__NONE) return voxgi_io__gltf_fail(G, obj, "%s has no %s", what, key);
        *v = def;
        return 0;
    }
    if (G->tok[t].type != VOXGI_IO__J_NUMBER) return voxgi_io__gltf_fail(G, t, "%s.%s is not a number", what, key);
    d = strtod(G->json + G->tok[t].start, NULL);
    if (!(d >= 0 && d <= (double)max && d == floor(d))) return voxgi_io__gltf_fail(G, t, "%s.%s is not an integer in 0..%zu", what, key, max);
    *v = (size_t)d;
    return 0;
}

/* obj.key as n numbers (an array of exactly n); out keeps its defaults when absent. */
static int voxgi_io__json_numbers(voxgi_io__gltf *G, size_t obj, const char *key, size_t n, const char *what, double *out)
{
    size_t t = voxgi_io__json_get(G, obj, key), i, k;
    if (t == VOXGI_IO__NONE) return 0;
    if (G->tok[t].type != VOXGI_IO__J_ARRAY || G->tok[t].count != n) return voxgi_io__gltf_fail(G, t, "%s.%s is not an array of %zu numbers", what, key, n);
    for (i = t + 1, k = 0; k < n; k++, i = G->tok[i].next)
        if (voxgi_io__json_number(G, i, what, &out[k])) return -1;
    return 0;
}

/* The string at t with its escapes decoded, NUL-terminated, from malloc; NULL after an error. */
static char *voxgi_io__json_string(voxgi_io__gltf *G, size_t t, const char *what)
{
    const char *s = G->json + G->tok[t].start, *e = G->json + G->tok[t].end;
    char *out, *o;
    if (G->tok[t].type != VOXGI_IO__J_STRING) { voxgi_io__gltf_fail(G, t, "%s is not a string", what); return NULL; }
    if (!(o = out = (char *)malloc((size_t)(e - s) + 1))) { voxgi_io__gltf_fail(G, VOXGI_IO__NONE, "out of memory"); return NULL; }
    while (s < e) {
        if (*s != '\\') { *o++ = *s++; continue; }
        switch (s[1]) {
        case 'b': *o++ = '\b'; break;
        case 'f': *o++ = '\f'; break;
        case 'n': *o++ = '\n'; break;
        case 'r': *o++ = '\r'; break;
        case 't': *o++ = '\t'; break;
        case 'u': {
            unsigned u = (unsigned)(voxgi_io__hex_value(s[2]) << 12 | voxgi_io__hex_value(s[3]) << 8 | voxgi_io__hex_value(s[4]) << 4 | voxgi_io__hex_value(s[5]));
            if (u < 0x80) *o++ = (char)u; /* UTF-8, at most 3 bytes: no longer than the 6-byte escape */
            else if (u < 0x800) { *o++ = (char)(0xC0 | u >> 6); *o++ = (char)(0x80 | (u & 63)); }
            else { *o++ = (char)(0xE0 | u >> 12); *o++ = (char)(0x80 | (u >> 6 & 63)); *o++ = (char)(0x80 | (u & 63)); }
            s += 4;
            break;
        }
        default: *o++ = s[1];
        }
        s += 2;
    }
    *o = 0;
    return out;
}

/* ---- buffers ---------------------------------------------------------------------------- */

static int voxgi_io__base64_value(char c)
{
    return c >= 'A' && c <= 'Z' ? c - 'A' : c >= 'a' && c <= 'z' ? c - 'a' + 26 : c >= '0' && c <= '9' ? c - '0' + 52 : c == '+' ? 62 : c == '/' ? 63 : -1;
}

/* Decodes base64 text in place; returns the byte count, or NONE with *bad at the first bad character. */
static size_t voxgi_io__base64_decode(char *text, size_t *bad)
{
    size_t n = strlen(text), i, out = 0;
    uint32_t acc = 0;
    int bits = 0;
    while (n && text[n - 1] == '=' && n + 2 > strlen(text)) n--; /* up to two '=' of padding */
    for (i = 0; i < n; i++) {
        int v = voxgi_io__base64_value(text[i]);
        if (v < 0) { *bad = i; return VOXGI_IO__NONE; }
        acc = acc << 6 | (uint32_t)v;
        if ((bits += 6) >= 8) { bits -= 8; text[out++] = (char)(acc >> bits & 0xFF); }
    }
    return out;
}

/* A uri to read beside the glTF file: relative, without "..", percent-decoded in place. */
static int voxgi_io__gltf_file_uri(voxgi_io__gltf *G, size_t t, size_t index, char *uri)
{
    const char *p;
    char *o;
    if (uri[0] == '/' || uri[0] == '\\' || strchr(uri, ':'))
        return voxgi_io__gltf_fail(G, t, "buffers[%zu].uri '%s' is absolute or has a scheme; only file names relative to the glTF file are read", index, uri);
    for (p = uri; *p; p++)
        if (p[0] == '.' && p[1] == '.' && (p == uri || p[-1] == '/' || p[-1] == '\\') && (!p[2] || p[2] == '/' || p[2] == '\\'))
            return voxgi_io__gltf_fail(G, t, "buffers[%zu].uri '%s' climbs out of the glTF file's folder ('..')", index, uri);
    for (p = o = uri; *p; p++) {
        if (*p == '%' && voxgi_io__hex_value(p[1]) >= 0 && voxgi_io__hex_value(p[2]) >= 0) {
            *o++ = (char)(voxgi_io__hex_value(p[1]) << 4 | voxgi_io__hex_value(p[2]));
            p += 2;
        } else *o++ = *p;
    }
    *o = 0;
    if (!uri[0] || strlen(uri) != (size_t)(o - uri)) return voxgi_io__gltf_fail(G, t, "buffers[%zu].uri is empty or holds a NUL", index);
    return 0;
}

static int voxgi_io__gltf_load_buffers(voxgi_io__gltf *G)
{
    size_t i;
    if (G->buffer_list.count && !(G->buffers = (voxgi_io__gltf_buffer *)calloc(G->buffer_list.count, sizeof *G->buffers)))
        return voxgi_io__gltf_fail(G, VOXGI_IO__NONE, "out of memory");
    for (i = 0; i < G->buffer_list.count; i++) {
        voxgi_io__gltf_buffer *b = &G->buffers[i];
        size_t buf = G->buffer_list.item[i], uri_tok = voxgi_io__json_get(G, buf, "uri"), length, got;
        char what[48], *uri;
        snprintf(what, sizeof what, "buffers[%zu]", i);
        if (voxgi_io__json_uint(G, buf, "byteLength", VOXGI_IO__NONE, SIZE_MAX / 2, what, &length)) return -1;
        if (uri_tok == VOXGI_IO__NONE) {
            if (i != 0 || !G->bin) return voxgi_io__gltf_fail(G, buf, "%s has no uri (only a .glb's first buffer may have none)", what);
            b->data = G->bin;
            got = G->bin_size;
        } else {
            if (!(uri = voxgi_io__json_string(G, uri_tok, "uri"))) return -1;
            b->owned = uri;
            if (!strncmp(uri, "data:", 5)) {
                char *comma = strchr(uri, ','), *payload;
                size_t bad = 0;
                if (!comma || comma - uri < 12 || memcmp(comma - 7, ";base64", 7))
                    return voxgi_io__gltf_fail(G, uri_tok, "%s: a data URI must be base64 (data:...;base64,...)", what);
                payload = comma + 1;
                if ((got = voxgi_io__base64_decode(payload, &bad)) == VOXGI_IO__NONE)
                    return voxgi_io__fail_at(G->L, VOXGI_IO__OFFSET, G->json_base + G->tok[uri_tok].start + (size_t)(payload - uri) + bad,
                                             "%s: bad base64 character", what);
                b->data = (const unsigned char *)payload;
            } else {
                const char *slash = strrchr(G->path, '/'), *back = strrchr(G->path, '\\');
                size_t dir_len;
                char *file;
                int rc;
                int open_failed;
                if (back && (!slash || back > slash)) slash = back;
                dir_len = slash ? (size_t)(slash - G->path) + 1 : 0;
                if (voxgi_io__gltf_file_uri(G, uri_tok, i, uri)) return -1;
                if (G->L->in_memory)
                    return voxgi_io__gltf_fail(G, uri_tok, "%s: uri '%s' names a file, which a mesh loaded from memory cannot read "
                                                           "(embed the buffer as a data URI, or as a .glb's BIN chunk)", what, uri);
                if (!(file = (char *)malloc(dir_len + strlen(uri) + 1))) return voxgi_io__gltf_fail(G, VOXGI_IO__NONE, "out of memory");
                memcpy(file, G->path, dir_len);
                strcpy(file + dir_len, uri);
                b->owned = NULL;
                rc = voxgi_io__read_file(file, &b->owned, &got, &open_failed);
                free(file);
                if (rc) {
                    voxgi_io__gltf_fail(G, uri_tok, "%s: cannot %s '%s': %s", what, open_failed ? "open" : "read", uri, strerror(rc));
                    free(uri);
                    return -1;
                }
                free(uri);
                b->data = (const unsigned char *)b->owned;
            }
        }
        if (got < length) return voxgi_io__gltf_fail(G, buf, "%s: byteLength is %zu but its data holds %zu bytes", what, length, got);
        b->size = length;
    }
    return 0;
}

/* ---- accessors -------------------------------------------------------------------------- */

/* A bufferView's bytes, checked to lie inside its buffer. */
typedef struct voxgi_io__gltf_view {
    const unsigned char *data;
    size_t length, stride; /* stride: byteStride, or the element size given when it has none */
    size_t tok;            /* the bufferView's JSON object */
    char what[48];         /* "bufferViews[i]" */
} voxgi_io__gltf_view;

/* Resolves obj.bufferView (what names obj in errors) for elements of elem bytes. */
static int voxgi_io__gltf_buffer_view(voxgi_io__gltf *G, size_t obj, const char *what, size_t elem, voxgi_io__gltf_view *v)
{
    size_t view_index, buffer_index, view_offset;
    const voxgi_io__gltf_buffer *buffer;
    if (voxgi_io__json_uint(G, obj, "bufferView", VOXGI_IO__NONE, SIZE_MAX / 2, what, &view_index)) return -1;
    if (view_index >= G->views.count) return voxgi_io__gltf_fail(G, obj, "%s refers to bufferViews[%zu], which does not exist", what, view_index);
    v->tok = G->views.item[view_index];
    snprintf(v->what, sizeof v->what, "bufferViews[%zu]", view_index);
    if (voxgi_io__json_uint(G, v->tok, "buffer", VOXGI_IO__NONE, SIZE_MAX / 2, v->what, &buffer_index) ||
        voxgi_io__json_uint(G, v->tok, "byteOffset", 0, SIZE_MAX / 2, v->what, &view_offset) ||
        voxgi_io__json_uint(G, v->tok, "byteLength", VOXGI_IO__NONE, SIZE_MAX / 2, v->what, &v->length) ||
        voxgi_io__json_uint(G, v->tok, "byteStride", elem, 252, v->what, &v->stride))
        return -1;
    if (buffer_index >= G->buffer_list.count) return voxgi_io__gltf_fail(G, v->tok, "%s refers to buffers[%zu], which does not exist", v->what, buffer_index);
    buffer = &G->buffers[buffer_index];
    if (view_offset > buffer->size || v->length > buffer->size - view_offset)
        return voxgi_io__gltf_fail(G, v->tok, "%s: bytes %zu..%zu lie outside buffers[%zu] (%zu bytes)", v->what, view_offset, view_offset + v->length, buffer_index, buffer->size);
    if (v->stride < elem) return voxgi_io__gltf_fail(G, v->tok, "%s: byteStride %zu is smaller than an element of %s (%zu bytes)", v->what, v->stride, what, elem);
    v->data = buffer->data + view_offset;
    return 0;
}

static uint32_t voxgi_io__gltf_index_at(const voxgi_io__accessor *a, size_t i)
{
    const unsigned char *p = a->data + i * a->stride;
    return a->component == 5121 ? p[0] : a->component == 5123 ? (uint32_t)(p[0] | p[1] << 8) : voxgi_io__le32(p);
}

static float voxgi_io__gltf_float_at(const voxgi_io__accessor *a, size_t i, int k)
{
    uint32_t bits = voxgi_io__le32(a->data + i * a->stride + 4 * (size_t)k);
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

/* One part of a sparse accessor (sparse.indices or sparse.values at tok): count packed elements of
   elem bytes from its byteOffset in its bufferView, which the specification forbids a byteStride. */
static int voxgi_io__gltf_sparse_part(voxgi_io__gltf *G, size_t tok, const char *what, size_t count, size_t elem, const unsigned char **data)
{
    voxgi_io__gltf_view v;
    size_t offset = 0;
    if (voxgi_io__json_uint(G, tok, "byteOffset", 0, SIZE_MAX / 2, what, &offset) || voxgi_io__gltf_buffer_view(G, tok, what, elem, &v)) return -1;
    if (voxgi_io__json_get(G, v.tok, "byteStride") != VOXGI_IO__NONE)
        return voxgi_io__gltf_fail(G, v.tok, "%s: %s has a byteStride, which sparse data must not have", what, v.what);
    if (offset > v.length || count > (v.length - offset) / elem)
        return voxgi_io__gltf_fail(G, tok, "%s: %zu elements of %zu bytes from byte %zu overrun %s (%zu bytes)", what, count, elem, offset, v.what, v.length);
    *data = v.data + offset;
    return 0;
}

/* Applies accessors[index].sparse (the token sparse) to a, whose elements are elem bytes: they are
   copied, tightly packed, into an array the load owns (made once per accessor), and the elements at
   sparse.indices (strictly increasing, below a's count) replaced by sparse.values. */
static int voxgi_io__gltf_sparse(voxgi_io__gltf *G, size_t index, size_t sparse, size_t elem, voxgi_io__accessor *a)
{
    size_t indices_tok = voxgi_io__json_get(G, sparse, "indices"), values_tok = voxgi_io__json_get(G, sparse, "values");
    size_t count, component, i;
    voxgi_io__accessor at;
    const unsigned char *values;
    unsigned char *dense;
    char what[64], indices_what[64], values_what[64];
    if (G->dense && G->dense[index]) {
        a->data = G->dense[index];
        a->stride = elem;
        return 0;
    }
    snprintf(what, sizeof what, "accessors[%zu].sparse", index);
    snprintf(indices_what, sizeof indices_what, "accessors[%zu].sparse.indices", index);
    snprintf(values_what, sizeof values_what, "accessors[%zu].sparse.values", index);
    if (voxgi_io__json_uint(G, sparse, "count", VOXGI_IO__NONE, SIZE_MAX / 2, what, &count)) return -1;
    if (!count || count > a->count)
        return voxgi_io__gltf_fail(G, voxgi_io__json_get(G, sparse, "count"), "%s.count %zu is not in 1..%zu (the accessor's count)", what, count, a->count);
    if (indices_tok == VOXGI_IO__NONE || values_tok == VOXGI_IO__NONE)
        return voxgi_io__gltf_fail(G, sparse, "%s has no %s", what, indices_tok == VOXGI_IO__NONE ? "indices" : "values");
    if (voxgi_io__json_uint(G, indices_tok, "componentType", VOXGI_IO__NONE, 1u << 16, indices_what, &component)) return -1;
    memset(&at, 0, sizeof at);
    at.component = (uint32_t)component;
    at.stride = component == 5121 ? 1 : component == 5123 ? 2 : component == 5125 ? 4 : 0;
    if (!at.stride) return voxgi_io__gltf_fail(G, indices_tok, "%s: componentType %zu is not 5121, 5123 or 5125", indices_what, component);
    if (voxgi_io__gltf_sparse_part(G, indices_tok, indices_what, count, at.stride, &at.data) ||
        voxgi_io__gltf_sparse_part(G, values_tok, values_what, count, elem, &values))
        return -1;
    if (a->count > SIZE_MAX / elem) return voxgi_io__gltf_fail(G, sparse, "%s: %zu elements of %zu bytes do not fit in memory", what, a->count, elem);
    if (!G->dense && !(G->dense = (unsigned char **)calloc(G->accessors.count, sizeof *G->dense)))
        return voxgi_io__gltf_fail(G, VOXGI_IO__NONE, "out of memory");
    if (!(dense = G->dense[index] = (unsigned char *)malloc(a->count * elem))) return voxgi_io__gltf_fail(G, VOXGI_IO__NONE, "out of memory");
    for (i = 0; i < a->count; i++) memcpy(dense + i * elem, a->data + i * a->stride, elem);
    for (i = 0; i < count; i++) {
        uint32_t k = voxgi_io__gltf_index_at(&at, i), before = i ? voxgi_io__gltf_index_at(&at, i - 1) : 0;
        if (k >= a->count)
            return voxgi_io__gltf_fail(G, indices_tok, "%s: index %u (element %zu) is not below the accessor's count %zu", indices_what, k, i, a->count);
        if (i && k <= before)
            return voxgi_io__gltf_fail(G, indices_tok, "%s: index %u (element %zu) does not follow %u: sparse indices must increase", indices_what, k, i, before);
        memcpy(dense + (size_t)k * elem, values + i * elem, elem);
    }
    a->data = dense;
    a->stride = elem;
    return 0;
}

/* Resolves accessors[index] (what it is for names it in errors) to a checked view of its elements:
   in its bufferView, or all zeros without one, with its sparse substitutions applied. */
static int voxgi_io__gltf_accessor(voxgi_io__gltf *G, size_t ref_tok, size_t index, const char *role, voxgi_io__accessor *a)
{
    static const char *const types[7] = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
    static const int type_components[7] = {1, 2, 3, 4, 4, 9, 16};
    static const unsigned char zeros[64] = {0}; /* an element of the largest type, MAT4 of 4-byte components */
    size_t acc, component_type, offset, elem, size, k, sparse;
    char what[48];
    if (index >= G->accessors.count) return voxgi_io__gltf_fail(G, ref_tok, "%s refers to accessors[%zu], which does not exist", role, index);
    acc = G->accessors.item[index];
    snprintf(what, sizeof what, "accessors[%zu]", index);
    if (voxgi_io__json_uint(G, acc, "componentType", VOXGI_IO__NONE, 1u << 16, what, &component_type) ||
        voxgi_io__json_uint(G, acc, "count", VOXGI_IO__NONE, SIZE_MAX / 2, what, &a->count) ||
        voxgi_io__json_uint(G, acc, "byteOffset", 0, SIZE_MAX / 2, what, &offset))
        return -1;
    a->component = (uint32_t)component_type;
    size = component_type == 5120 || component_type == 5121 ? 1 : component_type == 5122 || component_type == 5123 ? 2 : component_type == 5125 || component_type == 5126 ? 4 : 0;
    if (!size) return voxgi_io__gltf_fail(G, acc, "%s: unknown componentType %zu", what, component_type);
    for (k = 0; k < 7 && !voxgi_io__json_is(G, voxgi_io__json_get(G, acc, "type"), types[k]); k++) {}
    if (k == 7) return voxgi_io__gltf_fail(G, acc, "%s has no valid type (SCALAR, VEC2, VEC3, ...)", what);
    a->components = type_components[k];
    elem = size * (size_t)a->components;
    if (!a->count) return voxgi_io__gltf_fail(G, acc, "%s has no elements", what);
    if (voxgi_io__json_get(G, acc, "bufferView") != VOXGI_IO__NONE) {
        voxgi_io__gltf_view v;
        if (voxgi_io__gltf_buffer_view(G, acc, what, elem, &v)) return -1;
        if (offset > v.length || elem > v.length - offset || a->count - 1 > (v.length - offset - elem) / v.stride)
            return voxgi_io__gltf_fail(G, acc, "%s: %zu elements of %zu bytes, %zu apart from byte %zu, overrun %s (%zu bytes)", what, a->count, elem, v.stride, offset, v.what, v.length);
        a->data = v.data + offset;
        a->stride = v.stride;
    } else {
        /* all zeros: one zero element, read in place of every element; no more of them than the glTF
           has bytes, so that a few bytes cannot make the mesh gigabytes */
        size_t bytes = G->json_size;
        for (k = 0; k < G->buffer_list.count; k++) bytes += G->buffers[k].size;
        if (a->count > bytes)
            return voxgi_io__gltf_fail(G, acc, "%s has no bufferView and %zu elements (all zeros), more than the glTF's %zu bytes", what, a->count, bytes);
        a->data = zeros;
        a->stride = 0;
    }
    sparse = voxgi_io__json_get(G, acc, "sparse");
    return sparse == VOXGI_IO__NONE ? 0 : voxgi_io__gltf_sparse(G, index, sparse, elem, a);
}

/* ---- meshes, materials, nodes -------------------------------------------------------------- */

/* Column-major 4x4 matrices, as glTF stores them: m[4 * column + row]. */
static void voxgi_io__mat4_mul(const double *a, const double *b, double *out)
{
    int r, c, k;
    for (c = 0; c < 4; c++)
        for (r = 0; r < 4; r++) {
            double s = 0;
            for (k = 0; k < 4; k++) s += a[4 * k + r] * b[4 * c + k];
            out[4 * c + r] = s;
        }
}

/* A node's local matrix: its matrix, or translation * rotation * scale. */
static int voxgi_io__gltf_local_matrix(voxgi_io__gltf *G, size_t node, const char *what, double *m)
{
    double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1}, len, x, y, z, w;
    int k;
    static const double identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    memcpy(m, identity, sizeof identity);
    if (voxgi_io__json_get(G, node, "matrix") != VOXGI_IO__NONE) return voxgi_io__json_numbers(G, node, "matrix", 16, what, m);
    if (voxgi_io__json_numbers(G, node, "translation", 3, what, t) || voxgi_io__json_numbers(G, node, "rotation", 4, what, q) ||
        voxgi_io__json_numbers(G, node, "scale", 3, what, s))
        return -1;
    len = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(len > 0)) return voxgi_io__gltf_fail(G, voxgi_io__json_get(G, node, "rotation"), "%s.rotation is not a unit quaternion", what);
    x = q[0] / len; y = q[1] / len; z = q[2] / len; w = q[3] / len;
    m[0] = 1 - 2 * (y * y + z * z); m[4] = 2 * (x * y - z * w);     m[8] = 2 * (x * z + y * w);
    m[1] = 2 * (x * y + z * w);     m[5] = 1 - 2 * (x * x + z * z); m[9] = 2 * (y * z - x * w);
    m[2] = 2 * (x * z - y * w);     m[6] = 2 * (y * z + x * w);     m[10] = 1 - 2 * (x * x + y * y);
    for (k = 0; k < 3; k++) {
        m[4 * k + 0] *= s[k]; m[4 * k + 1] *= s[k]; m[4 * k + 2] *= s[k];
        m[12 + k] = t[k];
    }
    return 0;
}

/* Every glTF material becomes the builder's material of the same index. */
static int voxgi_io__gltf_materials(voxgi_io__gltf *G)
{
    size_t i;
    for (i = 0; i < G->materials.count; i++) {
        size_t mat = G->materials.item[i], pbr = voxgi_io__json_get(G, mat, "pbrMetallicRoughness"), name = voxgi_io__json_get(G, mat, "name");
        size_t mode = voxgi_io__json_get(G, mat, "alphaMode");
        size_t strength_ext = voxgi_io__json_get(G, voxgi_io__json_get(G, mat, "extensions"), "KHR_materials_emissive_strength");
        size_t strength_tok = voxgi_io__json_get(G, strength_ext, "emissiveStrength");
        double base[4] = {1, 1, 1, 1}, emissive[3] = {0, 0, 0}, strength = 1;
        char what[48];
        voxgi_io_material *m;
        int k;
        snprintf(what, sizeof what, "materials[%zu]", i);
        if (voxgi_io__json_numbers(G, pbr, "baseColorFactor", 4, what, base) || voxgi_io__json_numbers(G, mat, "emissiveFactor", 3, what, emissive) ||
            (strength_tok != VOXGI_IO__NONE && voxgi_io__json_number(G, strength_tok, "emissiveStrength", &strength)))
            return -1;
        if (!(m = VOXGI_IO__PUSH(G->L, G->L->b.materials, voxgi_io_material, 1))) return -1;
        memset(m, 0, sizeof *m);
        if (name != VOXGI_IO__NONE && G->tok[name].type == VOXGI_IO__J_STRING) {
            size_t len = G->tok[name].end - G->tok[name].start;
            memcpy(m->name, G->json + G->tok[name].start, len < sizeof m->name - 1 ? len : sizeof m->name - 1);
        } else snprintf(m->name, sizeof m->name, "material%zu", i);
        for (k = 0; k < 3; k++) {
            m->albedo[k] = (float)base[k];
            m->emission[k] = (float)(emissive[k] * strength);
        }
        /* alpha counts only in BLEND and MASK modes: OPAQUE (the default) ignores it */
        m->opacity = mode == VOXGI_IO__NONE || voxgi_io__json_is(G, mode, "OPAQUE") ? 1.0f : (float)base[3];
    }
    return 0;
}

/* Appends every triangle primitive of meshes[index] with the world matrix m applied. */
static int voxgi_io__gltf_mesh(voxgi_io__gltf *G, size_t node, size_t index, const double *m)
{
    voxgi_io__builder *b = &G->L->b;
    voxgi_io__jlist prims;
    size_t p, mesh, i;
    double normal_m[9], det;
    int rc = 0;
    if (index >= G->meshes.count) return voxgi_io__gltf_fail(G, node, "a node refers to meshes[%zu], which does not exist", index);
    mesh = G->meshes.item[index];
    /* normals go by the inverse transpose, the transpose of this adjugate (rows of cofactors) over
       the determinant; only the determinant's sign matters as normals are normalised */
    normal_m[0] = m[5] * m[10] - m[6] * m[9]; normal_m[1] = m[6] * m[8] - m[4] * m[10]; normal_m[2] = m[4] * m[9] - m[5] * m[8];
    normal_m[3] = m[9] * m[2] - m[10] * m[1]; normal_m[4] = m[10] * m[0] - m[8] * m[2]; normal_m[5] = m[8] * m[1] - m[9] * m[0];
    normal_m[6] = m[1] * m[6] - m[2] * m[5];  normal_m[7] = m[2] * m[4] - m[0] * m[6]; normal_m[8] = m[0] * m[5] - m[1] * m[4];
    det = m[0] * normal_m[0] + m[1] * normal_m[1] + m[2] * normal_m[2];
    if (voxgi_io__json_list(G, voxgi_io__json_get(G, mesh, "primitives"), "a mesh's primitives", &prims)) return -1;
    for (p = 0; p < prims.count && !rc; p++) {
        size_t prim = prims.item[p], attrs = voxgi_io__json_get(G, prim, "attributes"), mode, material, pos_index, normal_index, index_index = 0;
        size_t base = b->positions.count / 3, triangles, has_indices = voxgi_io__json_get(G, prim, "indices") != VOXGI_IO__NONE;
        voxgi_io__accessor pos, nrm, idx;
        char what[64];
        uint32_t material_id;
        memset(&idx, 0, sizeof idx);
        snprintf(what, sizeof what, "meshes[%zu].primitives[%zu]", index, p);
        if ((rc = voxgi_io__json_uint(G, prim, "mode", 4, 6, what, &mode)) != 0) break;
        if (mode != 4) {
            static const char *const names[7] = {"points", "lines", "line loop", "line strip", "triangles", "triangle strip", "triangle fan"};
            rc = voxgi_io__gltf_fail(G, voxgi_io__json_get(G, prim, "mode"), "%s: primitive mode %zu (%s) is not supported, only triangles (4)", what, mode, names[mode]);
            break;
        }
        if ((rc = voxgi_io__json_uint(G, attrs, "POSITION", VOXGI_IO__NONE, SIZE_MAX / 2, what, &pos_index)) != 0 ||
            (rc = voxgi_io__gltf_accessor(G, prim, pos_index, "POSITION", &pos)) != 0)
            break;
        if (pos.component != 5126 || pos.components != 3) {
            rc = voxgi_io__gltf_fail(G, attrs, "%s: POSITION of componentType %u with %d components is not supported, only float VEC3", what, pos.component, pos.components);
            break;
        }
        if (pos.count >= VOXGI_IO__NO_INDEX - base) { rc = voxgi_io__gltf_fail(G, prim, "too many vertices for 32-bit indices"); break; }
        nrm.data = NULL;
        if (voxgi_io__json_get(G, attrs, "NORMAL") != VOXGI_IO__NONE) {
            if ((rc = voxgi_io__json_uint(G, attrs, "NORMAL", 0, SIZE_MAX / 2, what, &normal_index)) != 0 ||
                (rc = voxgi_io__gltf_accessor(G, prim, normal_index, "NORMAL", &nrm)) != 0)
                break;
            if (nrm.component != 5126 || nrm.components != 3 || nrm.count != pos.count) {
                rc = voxgi_io__gltf_fail(G, attrs, "%s: NORMAL must be float VEC3 with one per position", what);
                break;
            }
        }
        if (voxgi_io__json_get(G, prim, "material") == VOXGI_IO__NONE) {
            if (G->default_material == VOXGI_IO__NO_INDEX) {
                voxgi_io_material *dm = VOXGI_IO__PUSH(G->L, b->materials, voxgi_io_material, 1);
                if (!dm) { rc = -1; break; }
                memset(dm, 0, sizeof *dm);
                strcpy(dm->name, "default");
                dm->albedo[0] = dm->albedo[1] = dm->albedo[2] = 1.0f; /* glTF's default base colour */
                dm->opacity = 1.0f;
                G->default_material = (uint32_t)(b->materials.count - 1);
            }
            material_id = G->default_material;
        } else {
            if ((rc = voxgi_io__json_uint(G, prim, "material", 0, G->materials.count ? G->materials.count - 1 : 0, what, &material)) != 0) break;
            if (material >= G->materials.count) { rc = voxgi_io__gltf_fail(G, prim, "%s refers to a material that does not exist", what); break; }
            material_id = (uint32_t)material;
        }
        if (has_indices) {
            if ((rc = voxgi_io__json_uint(G, prim, "indices", 0, SIZE_MAX / 2, what, &index_index)) != 0 ||
                (rc = voxgi_io__gltf_accessor(G, prim, index_index, "indices", &idx)) != 0)
                break;
            if (idx.components != 1 || (idx.component != 5121 && idx.component != 5123 && idx.component != 5125)) {
                rc = voxgi_io__gltf_fail(G, prim, "%s: indices must be SCALAR of componentType 5121, 5123 or 5125, not %u", what, idx.component);
                break;
            }
        } else idx.count = pos.count;
        if (idx.count % 3) { rc = voxgi_io__gltf_fail(G, prim, "%s: %zu corners do not make whole triangles", what, idx.count); break; }
        triangles = idx.count / 3;
        for (i = 0; i < pos.count; i++) {
            double v[3];
            float out[3];
            int k;
            for (k = 0; k < 3; k++) v[k] = voxgi_io__gltf_float_at(&pos, i, k);
            for (k = 0; k < 3; k++) {
                double w = m[k] * v[0] + m[4 + k] * v[1] + m[8 + k] * v[2] + m[12 + k];
                if (!(fabs(w) <= FLT_MAX)) { rc = voxgi_io__gltf_fail(G, attrs, "%s: POSITION %zu is not finite", what, i); break; }
                out[k] = (float)w;
            }
            if (rc || (rc = voxgi_io__add_vertex(G->L, out)) != 0) break;
        }
        if (rc) break;
        if (nrm.data || b->normals.count) {
            /* normals for every vertex once any primitive has them; zeros where one has none */
            size_t have = b->normals.count / 3;
            float *dst = VOXGI_IO__PUSH(G->L, b->normals, float, 3 * (base + pos.count - have));
            if (!dst) { rc = -1; break; }
            memset(dst, 0, 3 * (base + pos.count - have) * sizeof *dst);
            for (i = 0; nrm.data && i < pos.count; i++) {
                double v[3], w[3], len;
                int k;
                for (k = 0; k < 3; k++) v[k] = voxgi_io__gltf_float_at(&nrm, i, k);
                for (k = 0; k < 3; k++) w[k] = (normal_m[k] * v[0] + normal_m[3 + k] * v[1] + normal_m[6 + k] * v[2]) * (det < 0 ? -1 : 1);
                len = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
                for (k = 0; k < 3 && len > 0 && len <= FLT_MAX; k++) dst[3 * (base - have + i) + (size_t)k] = (float)(w[k] / len);
            }
        }
        for (i = 0; i < triangles; i++) {
            uint32_t *tri = VOXGI_IO__PUSH(G->L, b->indices, uint32_t, 3), *mat;
            int k;
            if (!tri || !(mat = VOXGI_IO__PUSH(G->L, b->material_ids, uint32_t, 1))) { rc = -1; break; }
            *mat = material_id;
            for (k = 0; k < 3; k++) {
                uint32_t v = has_indices ? voxgi_io__gltf_index_at(&idx, 3 * i + (size_t)k) : (uint32_t)(3 * i + (size_t)k);
                if (v >= pos.count) {
                    rc = voxgi_io__gltf_fail(G, voxgi_io__json_get(G, prim, "indices"), "%s: index %u (element %zu of accessors[%zu]) is out of range: the primitive has %zu vertices",
                                             what, v, 3 * i + (size_t)k, index_index, pos.count);
                    break;
                }
                tri[k] = (uint32_t)base + v;
            }
            if (rc) break;
            /* a mirroring transform turns the winding over; glTF keeps faces counter-clockwise */
            if (det < 0) { uint32_t swap = tri[1]; tri[1] = tri[2]; tri[2] = swap; }
        }
    }
    free(prims.item);
    return rc;
}

/* Walks the default scene's node trees (or every root node when there is no scene) depth first. */
static int voxgi_io__gltf_nodes(voxgi_io__gltf *G)
{
    typedef struct { size_t node; double parent[16]; } entry;
    static const double identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    voxgi_io__vec stack;
    unsigned char *seen = (unsigned char *)calloc(G->nodes.count + 1, 1);
    size_t *roots = (size_t *)malloc((G->nodes.count + 1) * sizeof *roots), root_count = 0, scene, k, i;
    int rc = 0;
    memset(&stack, 0, sizeof stack);
    if (!seen || !roots) rc = voxgi_io__gltf_fail(G, VOXGI_IO__NONE, "out of memory");
    else rc = voxgi_io__json_uint(G, 0, "scene", 0, G->scenes.count ? G->scenes.count - 1 : 0, "the glTF", &scene);
    if (!rc && G->scenes.count) {
        size_t list = voxgi_io__json_get(G, G->scenes.item[scene], "nodes"), c;
        if (list != VOXGI_IO__NONE && G->tok[list].type != VOXGI_IO__J_ARRAY) rc = voxgi_io__gltf_fail(G, list, "scenes[%zu].nodes is not an array", scene);
        for (c = list + 1, k = 0; !rc && list != VOXGI_IO__NONE && k < G->tok[list].count; k++, c = G->tok[c].next) {
            double d = 0;
            if ((rc = voxgi_io__json_number(G, c, "a scene's node", &d)) != 0) break;
            if (!(d >= 0 && d < (double)G->nodes.count && d == floor(d))) rc = voxgi_io__gltf_fail(G, c, "a scene refers to a node that does not exist");
            else if (root_count == G->nodes.count) rc = voxgi_io__gltf_fail(G, c, "a scene lists a node twice");
            else roots[root_count++] = (size_t)d;
        }
    } else if (!rc) {
        /* no scene: every node that is nobody's child is a root */
        for (i = 0; i < G->nodes.count; i++) {
            size_t children = voxgi_io__json_get(G, G->nodes.item[i], "children"), c;
            if (children == VOXGI_IO__NONE || G->tok[children].type != VOXGI_IO__J_ARRAY) continue;
            for (c = children + 1, k = 0; k < G->tok[children].count; k++, c = G->tok[c].next) {
                double d = 0;
                if (G->tok[c].type == VOXGI_IO__J_NUMBER && (d = strtod(G->json + G->tok[c].start, NULL)) >= 0 && d < (double)G->nodes.count)
                    seen[(size_t)d] = 1;
            }
        }
        for (i = 0; i < G->nodes.count; i++)
            if (!seen[i]) roots[root_count++] = i;
        memset(seen, 0, G->nodes.count + 1);
    }
    /* roots go on the stack last first, so the first root's triangles come first */
    for (k = root_count; !rc && k-- > 0;) {
        entry *e = (entry *)voxgi_io__vec_push(&stack, 1, sizeof *e);
        if (!e) { rc = voxgi_io__gltf_fail(G, VOXGI_IO__NONE, "out of memory"); break; }
        memcpy(e->parent, identity, sizeof identity);
        e->node = roots[k];
    }
    while (!rc && stack.count) {
        entry e = ((entry *)stack.data)[--stack.count];
        size_t node = G->nodes.item[e.node], children, mesh, c;
        double local[16], world[16];
        char what[48];
        snprintf(what, sizeof what, "nodes[%zu]", e.node);
        if (seen[e.node]) { rc = voxgi_io__gltf_fail(G, node, "%s is reached twice: the node hierarchy has a cycle or a shared child", what); break; }
        seen[e.node] = 1;
        if ((rc = voxgi_io__gltf_local_matrix(G, node, what, local)) != 0) break;
        voxgi_io__mat4_mul(e.parent, local, world);
        if (voxgi_io__json_get(G, node, "mesh") != VOXGI_IO__NONE &&
            ((rc = voxgi_io__json_uint(G, node, "mesh", 0, SIZE_MAX / 2, what, &mesh)) != 0 || (rc = voxgi_io__gltf_mesh(G, node, mesh, world)) != 0))
            break;
        children = voxgi_io__json_get(G, node, "children");
        if (children == VOXGI_IO__NONE) continue;
        if (G->tok[children].type != VOXGI_IO__J_ARRAY) { rc = voxgi_io__gltf_fail(G, children, "%s.children is not an array", what); break; }
        {
            size_t count = G->tok[children].count;
            entry *pushed = (entry *)voxgi_io__vec_push(&stack, count ? count : 1, sizeof *pushed);
            if (!pushed) { rc = voxgi_io__gltf_fail(G, VOXGI_IO__NONE, "out of memory"); break; }
            if (!count) stack.count--;
            for (c = children + 1, k = 0; k < count; k++, c = G->tok[c].next) {
                double d = 0;
                if ((rc = voxgi_io__json_number(G, c, "a child", &d)) != 0) break;
                if (!(d >= 0 && d < (double)G->nodes.count && d == floor(d))) { rc = voxgi_io__gltf_fail(G, c, "%s has a child that does not exist", what); break; }
                pushed[count - 1 - k].node = (size_t)d; /* reversed: the first child comes off the stack first */
                memcpy(pushed[count - 1 - k].parent, world, sizeof world);
            }
        }
    }
    free(seen);
    free(roots);
    voxgi_io__vec_free(&stack);
    return rc;
}

/* ---- the file ------------------------------------------------------------------------------- */

/* The JSON (and BIN) chunks of a .glb: a 12-byte header (magic, version 2, length), then chunks of
   a 4-byte length, a 4-byte type and their bytes, the JSON chunk first. */
static int voxgi_io__glb_chunks(voxgi_io__gltf *G, const unsigned char *d, size_t size)
{
    size_t at = 12, length;
    if (size < 12) return voxgi_io__fail_at(G->L, VOXGI_IO__OFFSET, size, "truncated glb: the 12-byte header ends early");
    if (voxgi_io__le32(d + 4) != 2) return voxgi_io__fail_at(G->L, VOXGI_IO__OFFSET, 4, "glb version %u is not supported, only 2", (unsigned)voxgi_io__le32(d + 4));
    length = voxgi_io__le32(d + 8);
    if (length > size) return voxgi_io__fail_at(G->L, VOXGI_IO__OFFSET, size, "truncated glb: its header gives %zu bytes, the file has %zu", length, size);
    while (at < length) {
        size_t chunk, type;
        if (length - at < 8) return voxgi_io__fail_at(G->L, VOXGI_IO__OFFSET, at, "truncated glb: a chunk header runs past the end");
        chunk = voxgi_io__le32(d + at);
        type = voxgi_io__le32(d + at + 4);
        if (chunk > length - at - 8) return voxgi_io__fail_at(G->L, VOXGI_IO__OFFSET, at, "truncated glb: a chunk of %zu bytes runs past the end (%zu)", chunk, length);
        if (at == 12 && type != 0x4E4F534Au) return voxgi_io__fail_at(G->L, VOXGI_IO__OFFSET, at, "the first glb chunk is not JSON");
        if (at == 12) { G->json = (const char *)d + at + 8; G->json_size = chunk; G->json_base = at + 8; }
        else if (type == 0x004E4942u && !G->bin) { G->bin = d + at + 8; G->bin_size = chunk; }
        at += 8 + chunk;
    }
    if (!G->json) return voxgi_io__fail_at(G->L, VOXGI_IO__OFFSET, at, "the glb has no JSON chunk");
    return 0;
}

static int voxgi_io__gltf_check_header(voxgi_io__gltf *G)
{
    size_t version = voxgi_io__json_get(G, voxgi_io__json_get(G, 0, "asset"), "version"), req = voxgi_io__json_get(G, 0, "extensionsRequired"), i, k;
    if (version == VOXGI_IO__NONE || G->tok[version].type != VOXGI_IO__J_STRING)
        return voxgi_io__gltf_fail(G, 0, "no asset.version: not a glTF file");
    if (G->tok[version].end - G->tok[version].start < 2 || memcmp(G->json + G->tok[version].start, "2.", 2))
        return voxgi_io__gltf_fail(G, version, "glTF version %.*s is not supported, only 2.x", (int)(G->tok[version].end - G->tok[version].start) & 63,
                                  G->json + G->tok[version].start);
    if (req == VOXGI_IO__NONE) return 0;
    if (G->tok[req].type != VOXGI_IO__J_ARRAY) return voxgi_io__gltf_fail(G, req, "extensionsRequired is not an array");
    for (i = req + 1, k = 0; k < G->tok[req].count; k++, i = G->tok[i].next) {
        int len = (int)(G->tok[i].end - G->tok[i].start) & 127;
        if (voxgi_io__json_is(G, i, "KHR_materials_emissive_strength")) continue;
        if (voxgi_io__json_is(G, i, "KHR_draco_mesh_compression")) return voxgi_io__gltf_fail(G, i, "Draco compression (KHR_draco_mesh_compression) is not supported");
        if (voxgi_io__json_is(G, i, "EXT_meshopt_compression") || voxgi_io__json_is(G, i, "KHR_meshopt_compression"))
            return voxgi_io__gltf_fail(G, i, "meshopt compression (%.*s) is not supported", len, G->json + G->tok[i].start);
        return voxgi_io__gltf_fail(G, i, "the file requires extension %.*s, which is not supported", len, G->json + G->tok[i].start);
    }
    return 0;
}

static int voxgi_io__is_gltf(const char *path, const char *data, size_t size)
{
    while (size && (*data == ' ' || *data == '\t' || *data == '\n' || *data == '\r')) data++, size--;
    return (size >= 4 && !memcmp(data, "glTF", 4)) || (size && *data == '{') || voxgi_io__has_extension(path, "gltf") || voxgi_io__has_extension(path, "glb");
}

static int voxgi_io__load_gltf(voxgi_io__loader *L, const char *path, const char *data, size_t size)
{
    voxgi_io__gltf G;
    size_t i;
    int rc;
    memset(&G, 0, sizeof G);
    G.L = L;
    G.path = path;
    G.default_material = VOXGI_IO__NO_INDEX;
    if (size >= 4 && !memcmp(data, "glTF", 4)) rc = voxgi_io__glb_chunks(&G, (const unsigned char *)data, size);
    else { G.json = data; G.json_size = size; rc = 0; }
    rc = rc || voxgi_io__json_parse(&G) || voxgi_io__gltf_check_header(&G) ||
         voxgi_io__json_list(&G, voxgi_io__json_get(&G, 0, "buffers"), "buffers", &G.buffer_list) ||
         voxgi_io__json_list(&G, voxgi_io__json_get(&G, 0, "bufferViews"), "bufferViews", &G.views) ||
         voxgi_io__json_list(&G, voxgi_io__json_get(&G, 0, "accessors"), "accessors", &G.accessors) ||
         voxgi_io__json_list(&G, voxgi_io__json_get(&G, 0, "meshes"), "meshes", &G.meshes) ||
         voxgi_io__json_list(&G, voxgi_io__json_get(&G, 0, "nodes"), "nodes", &G.nodes) ||
         voxgi_io__json_list(&G, voxgi_io__json_get(&G, 0, "materials"), "materials", &G.materials) ||
         voxgi_io__json_list(&G, voxgi_io__json_get(&G, 0, "scenes"), "scenes", &G.scenes) ||
         voxgi_io__gltf_load_buffers(&G) || voxgi_io__gltf_materials(&G) || voxgi_io__gltf_nodes(&G);
    for (i = 0; G.buffers && i < G.buffer_list.count; i++) free(G.buffers[i].owned);
    free(G.buffers);
    for (i = 0; G.dense && i < G.accessors.count; i++) free(G.dense[i]);
    free(G.dense);
    free(G.buffer_list.item); free(G.views.item); free(G.accessors.item); free(G.meshes.item);
    free(G.nodes.item); free(G.materials.item); free(G.scenes.item);
    free(G.tok);
    return rc ? -1 : 0;
}

/* ===================================================================== 4. exports */

/* Every writer reads the grid into memory once (its bits; its attribute; per 32-bit word the set
   voxels before it, which turns a voxel's linear index into its row of the attribute, stored in
   the order of the bit grid), then streams the file through stdio. The first failed call's errno
   is the reason reported. */

typedef struct voxgi_io__export {
    const char *path;
    char *err;
    size_t err_size;
    voxgi_voxels_info info;
    uint64_t voxels;  /* res[0] * res[1] * res[2] */
    uint64_t set;     /* set voxels (counted in the bits) */
    uint32_t *bits;
    uint64_t *rank;   /* set voxels before each word */
    float *attr;      /* width floats per set voxel, or NULL */
    int width;
    FILE *f;
    int failed, why;  /* a write failed, and its errno (0: unknown) */
} voxgi_io__export;

static int voxgi_io__export_fail(voxgi_io__export *x, const char *fmt, ...) VOXGI_IO__PRINTF_LIKE(2, 3);
static int voxgi_io__export_fail(voxgi_io__export *x, const char *fmt, ...)
{
    va_list ap;
    size_t used;
    if (!x->err || !x->err_size) return -1;
    snprintf(x->err, x->err_size, "%s: ", x->path);
    used = strlen(x->err);
    va_start(ap, fmt);
    vsnprintf(x->err + used, x->err_size - used, fmt, ap);
    va_end(ap);
    return -1;
}

static unsigned voxgi_io__x_popcount(uint32_t w)
{
    unsigned n = 0;
    for (; w; w &= w - 1u) n++;
    return n;
}

static int voxgi_io__x_is_set(const voxgi_io__export *x, uint64_t idx) { return (int)((x->bits[idx >> 5] >> (idx & 31u)) & 1u); }

/* The row of set voxel idx in the attribute arrays: the set voxels before it. */
static uint64_t voxgi_io__x_row(const voxgi_io__export *x, uint64_t idx)
{
    return x->rank[idx >> 5] + voxgi_io__x_popcount(x->bits[idx >> 5] & ((1u << (idx & 31u)) - 1u));
}

static uint64_t voxgi_io__x_index(const voxgi_io__export *x, uint64_t i, uint64_t j, uint64_t k)
{
    return i + (uint64_t)x->info.grid.res[0] * (j + (uint64_t)x->info.grid.res[1] * k);
}

/* Reads the grid and, when which is not 0, that attribute (required: refused without it; else
   ALBEDO when held, for colours), then creates path. */
static int voxgi_io__export_begin(voxgi_io__export *x, voxgi_context *ctx, const voxgi_voxels *voxels, voxgi_attribute which, int required,
                                  const char *path, char *err, size_t err_size)
{
    size_t need = 0, words, w;
    const voxgi_grid *g;
    memset(x, 0, sizeof *x);
    x->path = path ? path : "(no path)";
    x->err = err;
    x->err_size = err_size;
    if (err && err_size) err[0] = '\0';
    if (!path) return voxgi_io__export_fail(x, "the path is NULL");
    if (!ctx) return voxgi_io__export_fail(x, "the voxgi context is NULL");
    if (!voxels) return voxgi_io__export_fail(x, "the voxels are NULL");
    voxgi_voxels_query(voxels, &x->info);
    g = &x->info.grid;
    if (g->res[0] < 1 || g->res[1] < 1 || g->res[2] < 1) return voxgi_io__export_fail(x, "the voxels' grid has no voxel");
    x->voxels = (uint64_t)g->res[0] * (uint64_t)g->res[1] * (uint64_t)g->res[2];
    words = (size_t)((x->voxels + 31u) / 32u);
    if (voxgi_voxels_read(ctx, voxels, NULL, 0, &need) != VOXGI_OK) return voxgi_io__export_fail(x, "%s", voxgi_last_error(ctx));
    if (need < words * 4u) return voxgi_io__export_fail(x, "the bit grid holds %lu bytes, not the %lu of its grid", (unsigned long)need, (unsigned long)(words * 4u));
    x->bits = (uint32_t *)malloc(need);
    x->rank = (uint64_t *)malloc((words + 1u) * sizeof *x->rank);
    if (!x->bits || !x->rank) return voxgi_io__export_fail(x, "out of memory for the bit grid (%lu bytes)", (unsigned long)need);
    if (voxgi_voxels_read(ctx, voxels, x->bits, need, NULL) != VOXGI_OK) return voxgi_io__export_fail(x, "%s", voxgi_last_error(ctx));
    if (x->voxels & 31u) x->bits[words - 1u] &= (1u << (x->voxels & 31u)) - 1u; /* no bit past the grid */
    for (w = 0; w < words; w++) x->rank[w + 1u] = (x->rank[w] = x->set) + voxgi_io__x_popcount(x->bits[w]), x->set = x->rank[w + 1u];
    if (which && (x->info.attributes & (unsigned)which)) {
        x->width = which == VOXGI_ATTRIBUTE_OPACITY ? 1 : 3;
        if (x->set != x->info.voxel_count) return voxgi_io__export_fail(x, "the bit grid holds %llu voxels, its attributes %llu", (unsigned long long)x->set, (unsigned long long)x->info.voxel_count);
        need = 0;
        if (voxgi_voxels_read_attribute(ctx, voxels, which, NULL, 0, &need) != VOXGI_OK) return voxgi_io__export_fail(x, "%s", voxgi_last_error(ctx));
        if (!(x->attr = (float *)malloc(need ? need : 1u))) return voxgi_io__export_fail(x, "out of memory for the attribute (%lu bytes)", (unsigned long)need);
        if (voxgi_voxels_read_attribute(ctx, voxels, which, x->attr, need, NULL) != VOXGI_OK) return voxgi_io__export_fail(x, "%s", voxgi_last_error(ctx));
    } else if (required)
        return voxgi_io__export_fail(x, "the voxels hold no attribute %d (held: 0x%x; ask for it in voxgi_voxelize_desc.attributes)", (int)which, x->info.attributes);
    errno = 0;
    if (!(x->f = fopen(path, "wb"))) return voxgi_io__export_fail(x, "cannot open for writing: %s", errno ? strerror(errno) : "unknown reason");
    return 0;
}

static void voxgi_io__x_put(voxgi_io__export *x, const void *data, size_t n)
{
    if (x->failed || !n) return;
    errno = 0;
    if (fwrite(data, 1, n, x->f) != n) x->failed = 1, x->why = errno;
}

static void voxgi_io__x_print(voxgi_io__export *x, const char *fmt, ...) VOXGI_IO__PRINTF_LIKE(2, 3);
static void voxgi_io__x_print(voxgi_io__export *x, const char *fmt, ...)
{
    va_list ap;
    if (x->failed) return;
    errno = 0;
    va_start(ap, fmt);
    if (vfprintf(x->f, fmt, ap) < 0) x->failed = 1, x->why = errno;
    va_end(ap);
}

/* Closes the file (a failed write or close becomes the error when rc is 0) and frees the grid. */
static int voxgi_io__export_end(voxgi_io__export *x, int rc)
{
    if (x->f) {
        errno = 0;
        if (fclose(x->f) != 0 && !x->failed) x->failed = 1, x->why = errno;
        x->f = NULL;
        if (rc == 0 && x->failed) rc = voxgi_io__export_fail(x, "cannot write: %s", x->why ? strerror(x->why) : "I/O error");
    }
    free(x->bits);
    free(x->rank);
    free(x->attr);
    x->bits = NULL, x->rank = NULL, x->attr = NULL;
    return rc;
}

static unsigned char *voxgi_io__x_le32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)v, p[1] = (unsigned char)(v >> 8), p[2] = (unsigned char)(v >> 16), p[3] = (unsigned char)(v >> 24);
    return p + 4;
}

/* Linear [0,1] to the sRGB curve, clamped (NaN to 0). */
static float voxgi_io__x_srgb(float c)
{
    if (!(c > 0.0f)) return 0.0f;
    if (c >= 1.0f) return 1.0f;
    return c <= 0.0031308f ? 12.92f * c : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
}

/* Voxel idx's colour in sRGB [0,1]: its albedo, else 0.8 grey. */
static void voxgi_io__x_colour(const voxgi_io__export *x, uint64_t idx, float srgb[3])
{
    int c;
    for (c = 0; c < 3; c++) srgb[c] = voxgi_io__x_srgb(x->attr ? x->attr[3u * voxgi_io__x_row(x, idx) + (uint64_t)c] : 0.8f);
}

static unsigned char voxgi_io__x_byte(float unit) { return (unsigned char)floorf(unit * 255.0f + 0.5f); }

/* ---- MagicaVoxel .vox ---------------------------------------------------------------------- */

#define VOXGI_IO__X_VOX_BLOCK 256

/* The uniform 6 x 7 x 6 palette: the index (1..252) of an sRGB colour, and the colour of an index. */
static unsigned char voxgi_io__x_vox_index(const float srgb[3])
{
    int r = (int)floorf(srgb[0] * 5.0f + 0.5f), g = (int)floorf(srgb[1] * 6.0f + 0.5f), b = (int)floorf(srgb[2] * 5.0f + 0.5f);
    return (unsigned char)(1 + (r * 7 + g) * 6 + b);
}

static void voxgi_io__x_vox_palette_colour(int index, unsigned char rgba[4])
{
    int e = index - 1, r = e / 42, g = e / 6 % 7, b = e % 6;
    rgba[0] = (unsigned char)((r * 255 + 2) / 5);
    rgba[1] = (unsigned char)((g * 255 + 3) / 6);
    rgba[2] = (unsigned char)((b * 255 + 2) / 5);
    rgba[3] = 255;
}

static unsigned char *voxgi_io__x_chunk(unsigned char *p, const char *id, uint32_t content, uint32_t children)
{
    memcpy(p, id, 4);
    return voxgi_io__x_le32(voxgi_io__x_le32(p + 4, content), children);
}

static unsigned char *voxgi_io__x_vox_string(unsigned char *p, const char *s)
{
    size_t n = strlen(s);
    p = voxgi_io__x_le32(p, (uint32_t)n);
    memcpy(p, s, n);
    return p + n;
}

/* MagicaVoxel coordinates of voxel (i,j,k) and back: x = i, y = res[2]-1-k, z = j. */
static void voxgi_io__x_vox_size(const voxgi_io__export *x, int m[3])
{
    m[0] = x->info.grid.res[0], m[1] = x->info.grid.res[2], m[2] = x->info.grid.res[1];
}

VOXGI_IO_API int voxgi_io_write_vox(voxgi_context *ctx, const voxgi_voxels *voxels, const char *path, char *err, size_t err_size)
{
    voxgi_io__export x;
    int m[3], blocks[3], models, model, c;
    uint64_t *counts = NULL, i, j, k, children;
    unsigned char *scene = NULL, *p, head[64], entry[4 * 256];
    size_t scene_size;
    if (voxgi_io__export_begin(&x, ctx, voxels, VOXGI_ATTRIBUTE_ALBEDO, 0, path, err, err_size)) return voxgi_io__export_end(&x, -1);
    voxgi_io__x_vox_size(&x, m);
    for (c = 0; c < 3; c++) blocks[c] = (m[c] + VOXGI_IO__X_VOX_BLOCK - 1) / VOXGI_IO__X_VOX_BLOCK;
    models = blocks[0] * blocks[1] * blocks[2];
    counts = (uint64_t *)calloc((size_t)models, sizeof *counts);
    /* the scene graph: 40 (root nTRN) + 24 (LAYR) + 24 + 4 per model (nGRP) + at most 86 (nTRN) + 32 (nSHP) per model */
    scene = (unsigned char *)malloc(88u + 130u * (size_t)models);
    if (!counts || !scene) {
        free(counts);
        free(scene);
        return voxgi_io__export_end(&x, voxgi_io__export_fail(&x, "out of memory for %d models", models));
    }
    for (k = 0; k < (uint64_t)x.info.grid.res[2]; k++)
        for (j = 0; j < (uint64_t)x.info.grid.res[1]; j++)
            for (i = 0; i < (uint64_t)x.info.grid.res[0]; i++)
                if (voxgi_io__x_is_set(&x, voxgi_io__x_index(&x, i, j, k))) {
                    uint64_t y = (uint64_t)m[1] - 1u - k;
                    counts[i / VOXGI_IO__X_VOX_BLOCK + (uint64_t)blocks[0] * (y / VOXGI_IO__X_VOX_BLOCK + (uint64_t)blocks[1] * (j / VOXGI_IO__X_VOX_BLOCK))]++;
                }
    /* root transform 0 -> group 1 -> (transform 2+2m -> shape 3+2m of model m) per model, all on layer 0 */
    p = scene;
    p = voxgi_io__x_chunk(p, "nTRN", 28, 0);
    p = voxgi_io__x_le32(p, 0), p = voxgi_io__x_le32(p, 0), p = voxgi_io__x_le32(p, 1), p = voxgi_io__x_le32(p, UINT32_MAX);
    p = voxgi_io__x_le32(p, UINT32_MAX), p = voxgi_io__x_le32(p, 1), p = voxgi_io__x_le32(p, 0);
    p = voxgi_io__x_chunk(p, "nGRP", 12u + 4u * (uint32_t)models, 0);
    p = voxgi_io__x_le32(p, 1), p = voxgi_io__x_le32(p, 0), p = voxgi_io__x_le32(p, (uint32_t)models);
    for (model = 0; model < models; model++) p = voxgi_io__x_le32(p, 2u + 2u * (uint32_t)model);
    for (model = 0; model < models; model++) {
        int block[3] = {model % blocks[0], model / blocks[0] % blocks[1], model / (blocks[0] * blocks[1])}, t[3];
        char translation[48];
        for (c = 0; c < 3; c++) {
            int lo = block[c] * VOXGI_IO__X_VOX_BLOCK, size = m[c] - lo < VOXGI_IO__X_VOX_BLOCK ? m[c] - lo : VOXGI_IO__X_VOX_BLOCK;
            t[c] = lo + size / 2;
        }
        snprintf(translation, sizeof translation, "%d %d %d", t[0], t[1], t[2]);
        p = voxgi_io__x_chunk(p, "nTRN", 38u + (uint32_t)strlen(translation), 0);
        p = voxgi_io__x_le32(p, 2u + 2u * (uint32_t)model), p = voxgi_io__x_le32(p, 0), p = voxgi_io__x_le32(p, 3u + 2u * (uint32_t)model);
        p = voxgi_io__x_le32(p, UINT32_MAX), p = voxgi_io__x_le32(p, 0), p = voxgi_io__x_le32(p, 1), p = voxgi_io__x_le32(p, 1);
        p = voxgi_io__x_vox_string(p, "_t"), p = voxgi_io__x_vox_string(p, translation);
        p = voxgi_io__x_chunk(p, "nSHP", 20, 0);
        p = voxgi_io__x_le32(p, 3u + 2u * (uint32_t)model), p = voxgi_io__x_le32(p, 0), p = voxgi_io__x_le32(p, 1);
        p = voxgi_io__x_le32(p, (uint32_t)model), p = voxgi_io__x_le32(p, 0);
    }
    p = voxgi_io__x_chunk(p, "LAYR", 12, 0);
    p = voxgi_io__x_le32(p, 0), p = voxgi_io__x_le32(p, 0), p = voxgi_io__x_le32(p, UINT32_MAX);
    scene_size = (size_t)(p - scene);
    children = scene_size + 12u + 1024u;
    for (model = 0; model < models; model++) children += 24u + 16u + 4u * counts[model];
    if (children > UINT32_MAX) {
        free(counts);
        free(scene);
        return voxgi_io__export_end(&x, voxgi_io__export_fail(&x, "%llu bytes of voxels exceed the .vox format's 4 GiB", (unsigned long long)children));
    }
    memcpy(head, "VOX ", 4);
    voxgi_io__x_chunk(voxgi_io__x_le32(head + 4, 150), "MAIN", 0, (uint32_t)children);
    voxgi_io__x_put(&x, head, 20);
    for (model = 0; model < models; model++) {
        int block[3] = {model % blocks[0], model / blocks[0] % blocks[1], model / (blocks[0] * blocks[1])}, lo[3], size[3];
        uint64_t xx, yy, zz;
        for (c = 0; c < 3; c++) {
            lo[c] = block[c] * VOXGI_IO__X_VOX_BLOCK;
            size[c] = m[c] - lo[c] < VOXGI_IO__X_VOX_BLOCK ? m[c] - lo[c] : VOXGI_IO__X_VOX_BLOCK;
        }
        p = voxgi_io__x_chunk(head, "SIZE", 12, 0);
        p = voxgi_io__x_le32(p, (uint32_t)size[0]), p = voxgi_io__x_le32(p, (uint32_t)size[1]), p = voxgi_io__x_le32(p, (uint32_t)size[2]);
        p = voxgi_io__x_chunk(p, "XYZI", 4u + 4u * (uint32_t)counts[model], 0);
        p = voxgi_io__x_le32(p, (uint32_t)counts[model]);
        voxgi_io__x_put(&x, head, (size_t)(p - head));
        for (zz = 0; zz < (uint64_t)size[2]; zz++)
            for (yy = 0; yy < (uint64_t)size[1]; yy++)
                for (xx = 0; xx < (uint64_t)size[0]; xx++) {
                    uint64_t idx = voxgi_io__x_index(&x, (uint64_t)lo[0] + xx, (uint64_t)lo[2] + zz, (uint64_t)m[1] - 1u - ((uint64_t)lo[1] + yy));
                    if (voxgi_io__x_is_set(&x, idx)) {
                        float srgb[3];
                        unsigned char v[4];
                        voxgi_io__x_colour(&x, idx, srgb);
                        v[0] = (unsigned char)xx, v[1] = (unsigned char)yy, v[2] = (unsigned char)zz, v[3] = voxgi_io__x_vox_index(srgb);
                        voxgi_io__x_put(&x, v, 4);
                    }
                }
    }
    voxgi_io__x_put(&x, scene, scene_size);
    voxgi_io__x_put(&x, voxgi_io__x_chunk(head, "RGBA", 1024, 0) - 12, 12);
    /* entry e is the colour of index e + 1; the last 4 (indices 253..255, and 256 = 0) are unused, black */
    for (c = 0; c < 256; c++) {
        if (c < 252) voxgi_io__x_vox_palette_colour(c + 1, entry + 4 * c);
        else entry[4 * c] = entry[4 * c + 1] = entry[4 * c + 2] = 0, entry[4 * c + 3] = 255;
    }
    voxgi_io__x_put(&x, entry, sizeof entry);
    free(counts);
    free(scene);
    return voxgi_io__export_end(&x, 0);
}

/* ---- NumPy .npy -------------------------------------------------------------------------- */

/* The format 1.0 header: magic, version, header length, then the dict padded with spaces and a
   newline to a multiple of 64 bytes (what numpy writes; 1.0 asks for 16). */
static void voxgi_io__x_npy_header(voxgi_io__export *x, const char *descr, int width)
{
    char dict[256];
    unsigned char head[10];
    const int *r = x->info.grid.res;
    int n;
    if (width > 1) n = snprintf(dict, sizeof dict, "{'descr': '%s', 'fortran_order': False, 'shape': (%d, %d, %d, %d), }", descr, r[0], r[1], r[2], width);
    else n = snprintf(dict, sizeof dict, "{'descr': '%s', 'fortran_order': False, 'shape': (%d, %d, %d), }", descr, r[0], r[1], r[2]);
    while ((10 + n + 1) % 64) dict[n++] = ' ';
    dict[n++] = '\n';
    memcpy(head, "\x93NUMPY\x01\x00", 8);
    head[8] = (unsigned char)n, head[9] = (unsigned char)(n >> 8);
    voxgi_io__x_put(x, head, 10);
    voxgi_io__x_put(x, dict, (size_t)n);
}

/* C order: k (the last index) fastest, one row of k per (i, j). */
static int voxgi_io__x_npy_write(voxgi_io__export *x, int width)
{
    const int *r = x->info.grid.res;
    size_t row_bytes = (size_t)r[2] * (size_t)(x->attr ? 4 * width : 1);
    unsigned char *row = (unsigned char *)malloc(row_bytes), *p;
    uint64_t i, j, k;
    int c;
    if (!row) return voxgi_io__export_fail(x, "out of memory for a row of %lu bytes", (unsigned long)row_bytes);
    voxgi_io__x_npy_header(x, x->attr ? "<f4" : "|u1", x->attr ? width : 1);
    for (i = 0; i < (uint64_t)r[0]; i++)
        for (j = 0; j < (uint64_t)r[1]; j++) {
            for (p = row, k = 0; k < (uint64_t)r[2]; k++) {
                uint64_t idx = voxgi_io__x_index(x, i, j, k);
                int set = voxgi_io__x_is_set(x, idx);
                if (!x->attr) *p++ = (unsigned char)set;
                else
                    for (c = 0; c < width; c++) {
                        float v = set ? x->attr[(uint64_t)width * voxgi_io__x_row(x, idx) + (uint64_t)c] : 0.0f;
                        uint32_t u;
                        memcpy(&u, &v, 4);
                        p = voxgi_io__x_le32(p, u);
                    }
            }
            voxgi_io__x_put(x, row, row_bytes);
        }
    free(row);
    return 0;
}

VOXGI_IO_API int voxgi_io_write_npy(voxgi_context *ctx, const voxgi_voxels *voxels, const char *path, char *err, size_t err_size)
{
    voxgi_io__export x;
    if (voxgi_io__export_begin(&x, ctx, voxels, (voxgi_attribute)0, 0, path, err, err_size)) return voxgi_io__export_end(&x, -1);
    return voxgi_io__export_end(&x, voxgi_io__x_npy_write(&x, 1));
}

VOXGI_IO_API int voxgi_io_write_npy_attribute(voxgi_context *ctx, const voxgi_voxels *voxels, voxgi_attribute which, const char *path,
                                              char *err, size_t err_size)
{
    voxgi_io__export x;
    if (which != VOXGI_ATTRIBUTE_ALBEDO && which != VOXGI_ATTRIBUTE_NORMAL && which != VOXGI_ATTRIBUTE_EMISSION && which != VOXGI_ATTRIBUTE_OPACITY) {
        memset(&x, 0, sizeof x);
        x.path = path ? path : "(no path)", x.err = err, x.err_size = err_size;
        return voxgi_io__export_fail(&x, "attribute %d is not one of ALBEDO, NORMAL, EMISSION, OPACITY", (int)which);
    }
    if (voxgi_io__export_begin(&x, ctx, voxels, which, 1, path, err, err_size)) return voxgi_io__export_end(&x, -1);
    return voxgi_io__export_end(&x, voxgi_io__x_npy_write(&x, x.width));
}

/* ---- PLY points and OBJ faces ------------------------------------------------------------ */

VOXGI_IO_API int voxgi_io_write_ply_points(voxgi_context *ctx, const voxgi_voxels *voxels, const char *path, char *err, size_t err_size)
{
    voxgi_io__export x;
    const voxgi_grid *g;
    uint64_t i, j, k;
    if (voxgi_io__export_begin(&x, ctx, voxels, VOXGI_ATTRIBUTE_ALBEDO, 0, path, err, err_size)) return voxgi_io__export_end(&x, -1);
    g = &x.info.grid;
    voxgi_io__x_print(&x, "ply\nformat binary_little_endian 1.0\ncomment voxgi voxel centres: grid %dx%dx%d, voxel size %.17g\n"
                        "element vertex %llu\nproperty float x\nproperty float y\nproperty float z\n"
                        "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n",
                    g->res[0], g->res[1], g->res[2], g->voxel_size, (unsigned long long)x.set);
    for (k = 0; k < (uint64_t)g->res[2]; k++)
        for (j = 0; j < (uint64_t)g->res[1]; j++)
            for (i = 0; i < (uint64_t)g->res[0]; i++) {
                uint64_t idx = voxgi_io__x_index(&x, i, j, k), ijk[3];
                unsigned char v[15], *p = v;
                float srgb[3];
                int c;
                if (!voxgi_io__x_is_set(&x, idx)) continue;
                ijk[0] = i, ijk[1] = j, ijk[2] = k;
                for (c = 0; c < 3; c++) {
                    float centre = (float)(g->origin[c] + g->voxel_size * ((double)ijk[c] + 0.5));
                    uint32_t u;
                    memcpy(&u, &centre, 4);
                    p = voxgi_io__x_le32(p, u);
                }
                voxgi_io__x_colour(&x, idx, srgb);
                for (c = 0; c < 3; c++) *p++ = voxgi_io__x_byte(srgb[c]);
                voxgi_io__x_put(&x, v, sizeof v);
            }
    return voxgi_io__export_end(&x, 0);
}

VOXGI_IO_API int voxgi_io_write_obj_faces(voxgi_context *ctx, const voxgi_voxels *voxels, const char *path, char *err, size_t err_size)
{
    voxgi_io__export x;
    const voxgi_grid *g;
    int64_t ijk[3];
    unsigned long long faces = 0;
    if (voxgi_io__export_begin(&x, ctx, voxels, VOXGI_ATTRIBUTE_ALBEDO, 0, path, err, err_size)) return voxgi_io__export_end(&x, -1);
    g = &x.info.grid;
    voxgi_io__x_print(&x, "# voxgi: the outer faces of %llu voxels (grid %dx%dx%d, voxel size %.17g); v x y z r g b\n",
                    (unsigned long long)x.set, g->res[0], g->res[1], g->res[2], g->voxel_size);
    for (ijk[2] = 0; ijk[2] < g->res[2]; ijk[2]++)
        for (ijk[1] = 0; ijk[1] < g->res[1]; ijk[1]++)
            for (ijk[0] = 0; ijk[0] < g->res[0]; ijk[0]++) {
                uint64_t idx = voxgi_io__x_index(&x, (uint64_t)ijk[0], (uint64_t)ijk[1], (uint64_t)ijk[2]);
                float srgb[3];
                int axis, side;
                if (!voxgi_io__x_is_set(&x, idx)) continue;
                voxgi_io__x_colour(&x, idx, srgb);
                for (axis = 0; axis < 3; axis++)
                    for (side = 0; side < 2; side++) {
                        int64_t n[3], corner[3];
                        int u = (axis + 1) % 3, v = (axis + 2) % 3, q;
                        n[0] = ijk[0], n[1] = ijk[1], n[2] = ijk[2];
                        n[axis] += side ? 1 : -1;
                        if (n[axis] >= 0 && n[axis] < g->res[axis] && voxgi_io__x_is_set(&x, voxgi_io__x_index(&x, (uint64_t)n[0], (uint64_t)n[1], (uint64_t)n[2])))
                            continue; /* a face between two set voxels is inside */
                        /* corners base, +u, +u+v, +v turn around +axis (e_u x e_v = e_axis); reversed on the low side */
                        for (q = 0; q < 4; q++) {
                            int du = q == 1 || q == 2, dv = q >= 2, c;
                            if (!side) c = du, du = dv, dv = c;
                            corner[0] = ijk[0], corner[1] = ijk[1], corner[2] = ijk[2];
                            corner[axis] += side;
                            corner[u] += du, corner[v] += dv;
                            voxgi_io__x_print(&x, "v %.9g %.9g %.9g %.4f %.4f %.4f\n", g->origin[0] + g->voxel_size * (double)corner[0],
                                            g->origin[1] + g->voxel_size * (double)corner[1], g->origin[2] + g->voxel_size * (double)corner[2],
                                            (double)srgb[0], (double)srgb[1], (double)srgb[2]);
                        }
                        voxgi_io__x_print(&x, "f %llu %llu %llu %llu\n", 4 * faces + 1, 4 * faces + 2, 4 * faces + 3, 4 * faces + 4);
                        faces++;
                    }
            }
    return voxgi_io__export_end(&x, 0);
}

#endif /* VOXGI_IO__IMPLEMENTED */
#endif /* VOXGI_IO_IMPLEMENTATION */
/*
MIT License

Copyright (c) 2026 the voxgi authors

Permission is hereby granted, free of charge, to any person obtaining a copy of this software and
associated documentation files (the "Software"), to deal in the Software without restriction,
including without limitation the rights to use, copy, modify, merge, publish, distribute,
sublicense, and/or sell copies of the Software, and to permit persons to whom the Software is
furnished to do so, subject to the following conditions:

The above copyright notice and this permission notice shall be included in all copies or
substantial portions of the Software.

THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR IMPLIED, INCLUDING BUT
NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY, FITNESS FOR A PARTICULAR PURPOSE AND
NONINFRINGEMENT. IN NO EVENT SHALL THE AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM,
DAMAGES OR OTHER LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM, OUT
OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE SOFTWARE.
*/
