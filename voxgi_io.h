/* voxgi_io.h - v0.1.0 - mesh files into voxgi.h's scenes: OBJ (with MTL), OFF, STL, PLY. MIT licence at the end.

   An optional second single header beside voxgi.h: the loaders that get a mesh file into a
   voxgi_scene, with its materials. It needs voxgi.h (its public types only) and the C standard
   library; C99 or C++.

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
     PLY, ASCII and binary_little_endian, every scalar type. Every loader treats its input as
     hostile: a malformed, truncated or absurd file gives an error naming the file and the line
     (text formats) or byte offset (binary formats), never a crash or a leak. Numbers are parsed
     with strtod, so the program must run in the "C" numeric locale (the default unless it calls
     setlocale). The arrays come from malloc and go back to free (not VOXGI_MALLOC).

   CONTENTS (declarations, then the implementation in the same parts)
     1. config          linkage
     2. mesh files      the loaded mesh, loading and freeing it, its scene; the loaders' shared
                        builder, the text cursor, MTL, OBJ, OFF, STL, PLY, the choice of format

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

/* Loads OBJ(+MTL), OFF, STL (ASCII and binary) or PLY (ASCII and binary_little_endian), chosen by
   content and extension. Returns 0 on success. On failure returns non-zero, leaves *out empty (all
   zero, nothing to free), and writes into err a message naming the file and the line (text formats)
   or byte offset (binary formats) and what is wrong. err may be NULL. A mesh without any triangle
   is an error. */
VOXGI_IO_API int voxgi_io_load_mesh(const char *path, voxgi_io_mesh *out, char *err, size_t err_size);
/* Frees what voxgi_io_load_mesh allocated and zeroes *m; safe on an empty or zeroed mesh and NULL. */
VOXGI_IO_API void voxgi_io_mesh_free(voxgi_io_mesh *m);
/* A one-mesh scene of m with its materials and no lights: it points at m->mesh and
   m->scene_materials, so it is valid while m is neither freed nor moved (after copying m, take the
   copy's scene). */
VOXGI_IO_API voxgi_scene voxgi_io_mesh_scene(const voxgi_io_mesh *m);

/* Hash-map slots visited by every load so far (the loader's work, for tests and benchmarks: a
   load visits a few slots per face corner; a search that degrades to a scan visits thousands). */
VOXGI_IO_API unsigned long long voxgi_io_probes(void);

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
    int rc = voxgi_io__load_mtl(L, names, len);
    if (rc <= 0) return rc;
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
    if (ply) return voxgi_io__load_ply(L, &t);
    if (stl_ascii) return voxgi_io__load_stl_ascii(L, &t);
    if (voxgi_io__starts_with_word(data, "OFF") || voxgi_io__has_extension(path, "off")) return voxgi_io__load_off(L, &t);
    if (voxgi_io__has_extension(path, "stl")) return voxgi_io__load_stl_binary(L, (const unsigned char *)data, size);
    if (voxgi_io__has_extension(path, "ply")) return voxgi_io__load_ply(L, &t);
    if (voxgi_io__has_extension(path, "obj")) return voxgi_io__load_obj(L, &t);
    return voxgi_io__fail_at(L, NULL, 0, "unrecognised mesh format (expected OBJ, OFF, STL or PLY)");
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

VOXGI_IO_API int voxgi_io_load_mesh(const char *path, voxgi_io_mesh *out, char *err, size_t err_size)
{
    voxgi_io__loader L;
    char *data;
    size_t size;
    int rc, open_failed;
    uint32_t unused_id;
    memset(&L, 0, sizeof L);
    L.path = path ? path : "(null)";
    L.err = err;
    L.err_size = err_size;
    if (err && err_size) err[0] = 0;
    if (!out || !path) return voxgi_io__fail_at(&L, NULL, 0, "no mesh or no path given");
    memset(out, 0, sizeof *out);
    if ((rc = voxgi_io__read_file(path, &data, &size, &open_failed)) != 0)
        return voxgi_io__fail_at(&L, NULL, 0, "cannot %s: %s", open_failed ? "open" : "read", strerror(rc));
    rc = voxgi_io__load_any(&L, path, data, size);
    free(data);
    if (!rc && !L.b.indices.count) rc = voxgi_io__fail_at(&L, NULL, 0, "contains no triangles");
    if (!rc && !L.b.materials.count) rc = voxgi_io__material_id(&L, "default", 7, &unused_id);
    if (rc) {
        voxgi_io__vec_free(&L.b.positions); voxgi_io__vec_free(&L.b.normals); voxgi_io__vec_free(&L.b.uvs);
        voxgi_io__vec_free(&L.b.indices); voxgi_io__vec_free(&L.b.material_ids); voxgi_io__vec_free(&L.b.materials);
        free(L.b.material_names.slots);
        voxgi_io__vec_free(&L.b.polygon);
        return -1;
    }
    out->positions = (float *)L.b.positions.data;
    out->normals = (float *)L.b.normals.data;
    out->uvs = (float *)L.b.uvs.data;
    out->indices = (uint32_t *)L.b.indices.data;
    out->material_ids = (uint32_t *)L.b.material_ids.data;
    out->materials = (voxgi_io_material *)L.b.materials.data;
    out->vertex_count = L.b.positions.count / 3;
    out->triangle_count = L.b.indices.count / 3;
    out->material_count = L.b.materials.count;
    free(L.b.material_names.slots);
    voxgi_io__vec_free(&L.b.polygon);
    if (voxgi_io__make_scene_view(out) != 0) {
        voxgi_io_mesh_free(out);
        return voxgi_io__fail_at(&L, NULL, 0, "out of memory");
    }
    return 0;
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
