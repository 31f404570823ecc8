/* fuzz/make_seeds.c - writes the binary seeds of fuzz/corpus/ (the text seeds there are written by
 * hand): binary STL and PLY, glTF with a data-URI buffer and its .glb, PFM, and, made by the library
 * itself, binvox and octree files and their damaged copies; and fuzz_api's inputs, encoded in the
 * order fuzz/fuzz_api.c decodes them. `make fuzz-seeds` builds and runs it; its output is
 * committed, so it runs only when a seed changes. Usage: make_seeds CORPUS_DIR */
#include "../voxgi.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *corpus;

typedef struct bytes { unsigned char data[65536]; size_t size; } bytes;
static bytes B; /* the seed being assembled */

static void put(const void *p, size_t n) { if (B.size + n <= sizeof B.data) { memcpy(B.data + B.size, p, n); } B.size += n; }
static void put_str(const char *s) { put(s, strlen(s)); }
static void put_u8(unsigned v) { unsigned char c = (unsigned char)v; put(&c, 1); }
static void put_le(uint64_t v, int n) { while (n--) { put_u8((unsigned)(v & 0xFF)); v >>= 8; } }
static void put_f32(float f) { uint32_t u; memcpy(&u, &f, 4); put_le(u, 4); }
static void put_f64(double d) { uint64_t u; memcpy(&u, &d, 8); put_le(u, 8); }

static void save(const char *dir, const char *name, const void *data, size_t size)
{
    char path[1024];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s/%s", corpus, dir, name);
    if (!(f = fopen(path, "wb")) || fwrite(data, 1, size, f) != size || fclose(f) != 0) {
        fprintf(stderr, "make_seeds: cannot write %s\n", path);
        exit(1);
    }
}
static void save_b(const char *dir, const char *name) { save(dir, name, B.data, B.size); B.size = 0; }

/* ---- meshes */

static void stl_binary(void)
{
    static const float tri[2][12] = {{0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, -1, 0, 0, 0, 0, 1, 0, 1, 0, 0}};
    int t, k;
    put_str("solid but binary: the size decides");
    while (B.size < 80) put_u8(0);
    put_le(2, 4);
    for (t = 0; t < 2; t++) {
        for (k = 0; k < 12; k++) put_f32(tri[t][k]);
        put_le(0, 2);
    }
    save("stl", "two_binary.stl", B.data, B.size);
    B.size -= 30; /* the last facet cut */
    save_b("stl", "cut_binary.stl");
}

static void ply_binary(void)
{
    int i;
    put_str("ply\nformat binary_little_endian 1.0\ncomment every kind of property\nelement vertex 4\nproperty float x\nproperty double y\n"
            "property short z\nproperty uchar red\nproperty float nx\nproperty float ny\nproperty float nz\nelement face 2\nproperty list uchar uint vertex_indices\n"
            "property int flags\nelement extra 1\nproperty list ushort char values\nend_header\n");
    for (i = 0; i < 4; i++) {
        put_f32((float)(i & 1));
        put_f64((double)(i >> 1));
        put_le((uint64_t)(int64_t)-i, 2);
        put_u8(200);
        put_f32(0);
        put_f32(0);
        put_f32(1);
    }
    put_u8(3); put_le(0, 4); put_le(1, 4); put_le(2, 4); put_le(7, 4);
    put_u8(4); put_le(0, 4); put_le(2, 4); put_le(3, 4); put_le(1, 4); put_le(0, 4);
    put_le(2, 2); put_u8(0xFF); put_u8(1);
    save("ply", "mixed_binary.ply", B.data, B.size);
    B.size -= 7;
    save_b("ply", "cut_binary.ply");
}

/* The glTF's binary buffer: a triangle's positions and normals (float VEC3) and uint16 indices. */
static size_t gltf_bin(unsigned char *out)
{
    static const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, nrm[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    static const unsigned char idx[8] = {0, 0, 1, 0, 2, 0, 0, 0};
    memcpy(out, pos, 36);
    memcpy(out + 36, nrm, 36);
    memcpy(out + 72, idx, 8);
    return 80;
}

static const char gltf_body[] =
    "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_materials_emissive_strength\"],\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
    "\"nodes\":[{\"children\":[1],\"translation\":[1,2,3],\"rotation\":[0,0.7071068,0,0.7071068],\"scale\":[2,2,-2]},"
    "{\"mesh\":0,\"matrix\":[1,0,0,0,0,1,0,0,0,0,1,0,0.5,0,0,1]}],"
    "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1},\"indices\":2,\"material\":0,\"mode\":4},"
    "{\"attributes\":{\"POSITION\":0}}]}],"
    "\"materials\":[{\"name\":\"lamp\",\"alphaMode\":\"BLEND\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.8,0.2,0.1,0.5]},"
    "\"emissiveFactor\":[1,0.5,0],\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":4}}}],"
    "\"bufferViews\":[{\"buffer\":0,\"byteLength\":72,\"byteStride\":12},{\"buffer\":0,\"byteOffset\":72,\"byteLength\":6}],"
    "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]},"
    "{\"bufferView\":0,\"byteOffset\":36,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
    "{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}],"
    "\"buffers\":[{\"byteLength\":80";

static void gltf(void)
{
    static const char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    unsigned char bin[80];
    size_t n = gltf_bin(bin), i, json_len;
    put_str(gltf_body);
    put_str(",\"uri\":\"data:application/octet-stream;base64,");
    for (i = 0; i < n; i += 3) { /* 80 bytes: the last group has two, one '=' of padding */
        uint32_t v = (uint32_t)bin[i] << 16 | (uint32_t)(i + 1 < n ? bin[i + 1] : 0) << 8 | (i + 2 < n ? bin[i + 2] : 0);
        put_u8((unsigned char)alphabet[v >> 18 & 63]);
        put_u8((unsigned char)alphabet[v >> 12 & 63]);
        put_u8(i + 1 < n ? (unsigned char)alphabet[v >> 6 & 63] : '=');
        put_u8(i + 2 < n ? (unsigned char)alphabet[v & 63] : '=');
    }
    put_str("\"}]}");
    save_b("gltf", "triangle_data_uri.gltf");
    /* the .glb: the same JSON with the buffer in the BIN chunk */
    put_str("glTF");
    put_le(2, 4);
    put_le(0, 4); /* the length, set below */
    json_len = strlen(gltf_body) + 3;
    put_le((json_len + 3) / 4 * 4, 4);
    put_str("JSON");
    put_str(gltf_body);
    put_str("}]}");
    while (B.size % 4) put_u8(' ');
    put_le(n, 4);
    put_str("BIN");
    put_u8(0);
    put(bin, n);
    B.data[8] = (unsigned char)(B.size & 0xFF);
    B.data[9] = (unsigned char)(B.size >> 8);
    save("glb", "triangle.glb", B.data, B.size);
    B.size -= n / 2; /* the BIN chunk cut */
    save_b("glb", "cut.glb");
}

/* ---- PFM */

static void pfm(void)
{
    int i;
    put_str("PF\n2 2\n-1.0\n");
    for (i = 0; i < 12; i++) put_f32((float)i / 4);
    save_b("pfm", "2x2_little.pfm");
    put_str("PF\n1 1\n1\n");
    for (i = 0; i < 3; i++) { uint32_t u; float f = 0.5f * (float)i; memcpy(&u, &f, 4); put_le((uint64_t)(u >> 24 | (u >> 8 & 0xFF00u) | (u << 8 & 0xFF0000u) | u << 24), 4); }
    save_b("pfm", "1x1_big.pfm");
    put_str("PF\n3 2\n-1\n");
    put_f32(1);
    save_b("pfm", "short.pfm");
    put_str("Pf\n1 1\n-1\n");
    put_f32(1);
    save_b("pfm", "grey.pfm");
}

/* ---- files the library writes: binvox and octrees */

static void check(voxgi_result r, const char *what)
{
    if (r != VOXGI_OK) {
        fprintf(stderr, "make_seeds: %s: %s\n", what, voxgi_result_string(r));
        exit(1);
    }
}

static voxgi_voxels *voxelize(voxgi_context *ctx, const voxgi_scene *scene, int res, unsigned attributes)
{
    voxgi_voxelize_desc d;
    voxgi_fit_desc fit;
    voxgi_voxels *v;
    memset(&d, 0, sizeof d);
    memset(&fit, 0, sizeof fit);
    fit.res = res;
    check(voxgi_fit_grid(ctx, scene, &fit, &d.grid), "fit");
    d.attributes = attributes;
    check(voxgi_voxelize(ctx, scene, &d, &v), "voxelize");
    return v;
}

static void binvox(voxgi_context *ctx, voxgi_voxels *vox)
{
    voxgi_voxels_info info;
    size_t needed;
    uint32_t bits[64];
    FILE *f = tmpfile();
    voxgi_voxels_query(vox, &info);
    check(voxgi_voxels_read(ctx, vox, bits, sizeof bits, &needed), "read bits");
    if (!f) exit(1);
    check(voxgi_binvox_write(f, &info.grid, bits), "binvox");
    rewind(f);
    B.size = fread(B.data, 1, sizeof B.data, f);
    fclose(f);
    save("binvox", "sphere_4.binvox", B.data, B.size);
    B.size -= 3;
    save_b("binvox", "cut.binvox");
    put_str("#binvox 1\ndim 2 1 2\ntranslate 0.5 -1 2\nscale 2\ndata\n\x00\x01\x01\x03");
    save_b("binvox", "runs.binvox");
}

static void svo(voxgi_context *ctx, voxgi_voxels *vox, const voxgi_volume *radiance, unsigned attributes, int extras, voxgi_svo_format format,
                const char *name, int damage)
{
    voxgi_svo_desc d;
    voxgi_svo *s;
    memset(&d, 0, sizeof d);
    d.attributes = attributes;
    d.neighbours = d.bricks = extras;
    d.format = format;
    d.radiance = radiance;
    check(voxgi_svo_create(ctx, vox, &d, &s), "svo");
    check(voxgi_svo_write_memory(ctx, s, B.data, sizeof B.data, &B.size), "svo write");
    voxgi_svo_destroy(ctx, s);
    save("svo", name, B.data, B.size);
    if (damage) { /* a child pointer out of range, just after the header */
        char damaged[64];
        B.data[232 + 3] = 0x7F;
        snprintf(damaged, sizeof damaged, "bad_pointer_%s", name);
        save("svo", damaged, B.data, B.size);
    }
    B.size = 0;
}

/* The leak box's resolution from which its empty space has enclosed regions (the smallest such
   octree file, about 13 KB). */
#define REGIONS_RES 12

static void library_files(void)
{
    voxgi_desc desc;
    voxgi_context *ctx;
    voxgi_builtin_scene box;
    voxgi_voxels *vox;
    voxgi_volume *radiance;
    voxgi_inject_desc inject;
    memset(&desc, 0, sizeof desc);
    desc.backend = VOXGI_BACKEND_CPU;
    desc.thread_count = 1;
    check(voxgi_create(&desc, &ctx), "context");
    check(voxgi_builtin_scene_create(ctx, "furnace", &box), "furnace");
    vox = voxelize(ctx, &box.scene, 4, 0);
    binvox(ctx, vox);
    voxgi_voxels_destroy(ctx, vox);
    voxgi_builtin_scene_destroy(ctx, &box);
    /* a closed box lit from outside: a two-sided radiance whose empty space has regions */
    check(voxgi_builtin_scene_create(ctx, "leak-box", &box), "leak-box");
    vox = voxelize(ctx, &box.scene, 4, VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_NORMAL | VOXGI_ATTRIBUTE_OPACITY);
    svo(ctx, vox, NULL, VOXGI_ATTRIBUTE_ALBEDO, 0, VOXGI_SVO_FLOAT32, "albedo.svo", 1);
    svo(ctx, vox, NULL, 0, 1, VOXGI_SVO_FLOAT16, "all_half_bricks.svo", 0);
    memset(&inject, 0, sizeof inject);
    inject.samples = 1;
    inject.one_sided = 1;
    check(voxgi_inject_light(ctx, &box.scene, vox, &inject, &radiance), "inject");
    svo(ctx, vox, radiance, VOXGI_ATTRIBUTE_RADIANCE | VOXGI_ATTRIBUTE_OPACITY, 1, VOXGI_SVO_FLOAT32, "radiance_bricks.svo", 0);
    voxgi_volume_destroy(ctx, radiance);
    voxgi_voxels_destroy(ctx, vox);
    vox = voxelize(ctx, &box.scene, REGIONS_RES, VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_NORMAL);
    inject.one_sided = 0;
    check(voxgi_inject_light(ctx, &box.scene, vox, &inject, &radiance), "inject");
    svo(ctx, vox, radiance, VOXGI_ATTRIBUTE_RADIANCE, 0, VOXGI_SVO_FLOAT16, "radiance_two_sided.svo", 1);
    voxgi_volume_destroy(ctx, radiance);
    voxgi_voxels_destroy(ctx, vox);
    voxgi_builtin_scene_destroy(ctx, &box);
    voxgi_destroy(ctx);
}

/* ---- fuzz_api's inputs: each byte is what one of fuzz_api.c's readers takes, in its order */

static void f(float v) { put_u8((unsigned)(64 + (int)(v * 16))); } /* fuzz_float of a multiple of 1/16 in [-4, 4) */
static void unit(float v) { put_u8((unsigned)(v * 199 + 0.5f)); } /* unit_or_odd in [0, 1] */

static void api_scene(void)
{
    static const float vertices[7][3] = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}, {-0.25f, 1, -0.25f}, {0, 1, 0.25f}, {0.25f, 1, -0.25f}};
    static const unsigned indices[9] = {0, 2, 1, 0, 3, 2, 4, 6, 5};
    int i, c;
    put_u8(2);                                  /* two materials */
    for (c = 0; c < 3; c++) { unit(0.8f); put_u8(1); } /* grey, no emission */
    put_u8(1);                                  /* opaque */
    for (c = 0; c < 3; c++) { unit(0.5f); put_u8(0); unit(1); } /* the lamp */
    put_u8(1);
    put_u8(0);                                  /* one mesh */
    put_u8(1);                                  /* float positions */
    put_u8(7);                                  /* 7 vertices */
    put_u8(0);                                  /* tight */
    for (i = 0; i < 7; i++) for (c = 0; c < 3; c++) f(vertices[i][c]);
    put_u8(1); put_u8(1);                       /* no normals, no uvs */
    put_u8(1); put_u8(9);                       /* 9 indices */
    for (i = 0; i < 9; i++) put_u8(indices[i]);
    put_u8(0); put_u8(0); put_u8(0); put_u8(1); /* material ids 0 0 1 */
    put_u8(1); put_u8(0);                       /* mesh material 0 */
    put_u8(1);                                  /* one light */
    put_u8(2);                                  /* directional */
    for (c = 0; c < 3; c++) { f(0); f(c == 1 ? -1.0f : 0.5f); unit(0.5f); f(0); f(0); }
    unit(0); unit(0);
    put_u8(1);                                  /* origin 0 */
    put_u8(7);                                  /* voxelize, rays and an image */
}

static void api_voxelize(void)
{
    int i;
    put_u8(1); put_u8(11); put_u8(0); put_u8(1); /* a fitted grid of 12, cubic, no padding */
    put_u8(0); put_u8(0); put_u8(0); put_u8(0); put_u8(0); put_u8(0); /* conservative, default axis, mode, atomic, atlas */
    put_u8(0); put_u8(1); put_u8(3);            /* attributes albedo and normal */
    for (i = 0; i < 5; i++) put_u8(0);          /* blends, volume slicing */
    for (i = 0; i < 12; i++) { put_u8(1); put_u8((unsigned)(40 + 15 * i)); } /* four points inside the grid */
    put_u8(0);                                  /* hierarchical segments */
    put_u8(2); put_u8(2); put_u8(1);            /* reduce 2 2 1 */
    put_u8(1); put_u8(3); put_u8(1); put_u8(0); /* an anisotropic volume of albedo and normal, every level */
    for (i = 0; i < 4; i++) f(0.5f * (float)i); /* lods */
    put_u8(1); put_u8(1); put_u8(0);            /* sample albedo along +x */
    put_u8(1); put_u8(0); put_u8(2); put_u8(0); put_u8(1); put_u8(0); put_u8(0); /* inject: 1 sample, 1 bounce */
    put_u8(1); put_u8(0); put_u8(1); put_u8(1); put_u8(0); put_u8(1); /* an octree of everything with neighbours and bricks, traced */
    put_u8(4); put_u8(1); put_u8(1); put_u8(1); put_u8(1); put_u8(0); /* 4 cones, defaults */
    put_u8(100); put_u8(100); put_u8(100);      /* eye */
    for (i = 0; i < 12; i++) f(i % 3 == 1 ? 1.0f : 0.0f); /* normals +y */
}

static void api_rays(void)
{
    int i, c;
    for (i = 0; i < 2; i++) {
        for (c = 0; c < 3; c++) { f(c == 1 ? 2.0f : 0.125f * (float)i); f(c == 1 ? -1.0f : 0.0f); }
        put_u8(1); put_u8(1);
    }
}

static void api_render(int method)
{
    static const unsigned head[] = {7, 7, 0, 1, 1, 3, 11, 2, 0, 0, 1, 1};
    static const unsigned parts[] = {
        0, 4, 2, 1, 0, 0, 0, 0, 0, 0,            /* vct */
        0, 15, 7, 1,                             /* tsm: light 0, 16 texels, 8 slices */
        15, 8, 1, 0, 1, 0, 2,                    /* rsm */
        1, 0, 1, 2,                              /* sh */
        4, 4, 1, 0, 0, 1, 0, 1,                  /* screen */
        0, 0, 0, 2, 0, 0, 1,                     /* line space: defaults, 2 samples, supersample 1 */
        1, 0,                                    /* reference */
        0, 1, 1, 1};                             /* a visible buffer, no voxels or rays given, the whole image */
    size_t i;
    put_u8((unsigned)method);
    for (i = 0; i < sizeof head / sizeof head[0]; i++) put_u8(head[i]);
    for (i = 0; i < sizeof parts / sizeof parts[0]; i++) put_u8(parts[i]);
}

static void api(void)
{
    int m;
    char name[32];
    for (m = 0; m < VOXGI_RENDER_METHOD_COUNT; m++) {
        api_scene();
        api_voxelize();
        api_rays();
        api_render(m);
        snprintf(name, sizeof name, "lit_scene_%s", voxgi_render_method_name((voxgi_render_method)m));
        save_b("api", name);
    }
    api_scene();
    B.data[B.size - 1] = 4; /* the image alone */
    api_render(VOXGI_RENDER_METHOD_COUNT);
    save_b("api", "unknown_method");
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: make_seeds CORPUS_DIR\n");
        return 2;
    }
    corpus = argv[1];
    stl_binary();
    ply_binary();
    gltf();
    pfm();
    library_files();
    api();
    return 0;
}
