/* tests/test_mesh_io.c - the mesh loaders of voxgi_io.h (OBJ, OFF, STL, PLY, glTF), and the PNG writer of tools/image_io.h.
 *
 * First exact results on small files of every format and variant, then hostile input: every
 * truncated prefix and random corruptions of each valid file, garbage, bad indices, non-finite
 * numbers and absurd counts must fail cleanly (run under ASan/UBSan) with a message naming the file
 * and the line or byte offset. All files live in a fresh temporary directory. */
#define _XOPEN_SOURCE 700 /* mkdtemp */
#include "harness.h"
#include "../voxgi_io.h"
#include "../tools/image_io.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

static char tmp_dir[512];
static char created[256][64];
static int created_count;

/* Paths come from a ring of buffers so a test can hold a few at once. */
static const char *tmp_path(const char *name)
{
    static char ring[4][1024];
    static int next;
    char *path = ring[next++ % 4];
    int n = snprintf(path, sizeof ring[0], "%s/%s", tmp_dir, name);
    if (n < 0 || n >= (int)sizeof ring[0]) {
        printf("temporary path too long: %s/%s\n", tmp_dir, name);
        exit(1);
    }
    return path;
}

static const char *write_file(const char *name, const void *data, size_t size)
{
    const char *path = tmp_path(name);
    FILE *f = fopen(path, "wb");
    int i;
    TH_CHECK(f != NULL, "cannot create %s", path);
    if (!f) return path;
    TH_CHECK(fwrite(data, 1, size, f) == size, "cannot write %s", path);
    fclose(f);
    for (i = 0; i < created_count && strcmp(created[i], name); i++) {}
    if (i == created_count && created_count < 256) snprintf(created[created_count++], sizeof created[0], "%s", name);
    return path;
}

static const char *write_text(const char *name, const char *text) { return write_file(name, text, strlen(text)); }

/* Binary files are assembled little-endian, byte by byte, whatever the host. */
typedef struct bytes { unsigned char data[4096]; size_t size; } bytes;
static void put_uint(bytes *b, uint64_t v, int n) { while (n--) { b->data[b->size++] = (unsigned char)v; v >>= 8; } }
static void put_f32(bytes *b, float f) { uint32_t u; memcpy(&u, &f, 4); put_uint(b, u, 4); }
static void put_f64(bytes *b, double d) { uint64_t u; memcpy(&u, &d, 8); put_uint(b, u, 8); }
static void put_text(bytes *b, const char *s) { memcpy(b->data + b->size, s, strlen(s)); b->size += strlen(s); }

static int near(float a, float b) { return fabsf(a - b) < 1e-6f; }
static int is_empty(const voxgi_io_mesh *m)
{
    return !m->positions && !m->normals && !m->uvs && !m->indices && !m->material_ids && !m->materials &&
           !m->vertex_count && !m->triangle_count && !m->material_count && !m->scene_materials && !m->mesh.positions;
}

/* Every index in range, every array present: what callers may rely on after a successful load. */
static void check_consistent(const voxgi_io_mesh *m, const char *path)
{
    size_t i;
    TH_CHECK(m->positions && m->indices && m->material_ids && m->materials, "%s: missing arrays", path);
    TH_CHECK(m->triangle_count > 0 && m->vertex_count > 0 && m->material_count > 0, "%s: empty mesh", path);
    for (i = 0; i < 3 * m->triangle_count; i++)
        if (m->indices[i] >= m->vertex_count) { TH_CHECK(0, "%s: index %u out of range", path, m->indices[i]); break; }
    for (i = 0; i < m->triangle_count; i++)
        if (m->material_ids[i] >= m->material_count) { TH_CHECK(0, "%s: material id out of range", path); break; }
}

static int load_ok(const char *path, voxgi_io_mesh *m)
{
    char err[512];
    int rc = voxgi_io_load_mesh(path, m, err, sizeof err);
    TH_CHECK(rc == 0, "loading %s failed: %s", path, err);
    if (!rc) check_consistent(m, path);
    return rc == 0;
}

/* The file must fail to load with a message naming it and containing `expect`. */
static void expect_error(const char *name, const void *data, size_t size, const char *expect)
{
    const char *path = write_file(name, data, size);
    char err[512];
    voxgi_io_mesh m;
    int rc = voxgi_io_load_mesh(path, &m, err, sizeof err);
    TH_CHECK(rc != 0, "%s loaded although it should fail with '%s'", name, expect);
    if (!rc) { voxgi_io_mesh_free(&m); return; }
    TH_CHECK(is_empty(&m), "%s: mesh not left empty on failure", name);
    TH_CHECK(strstr(err, path) != NULL, "%s: message does not name the file: %s", name, err);
    TH_CHECK(strstr(err, expect) != NULL, "%s: message lacks '%s': %s", name, expect, err);
}
static void expect_text_error(const char *name, const char *text, const char *expect) { expect_error(name, text, strlen(text), expect); }

/* ---- valid files ---- */

static const char obj_quads[] =
    "# a unit cube of quads, plus a pentagon\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"
    "v 0.5 -0.5 0\nf 1 9 2 3 4\n";

static void test_obj_quads_fan(void)
{
    voxgi_io_mesh m;
    size_t i;
    if (!load_ok(write_text("quads.obj", obj_quads), &m)) return;
    TH_CHECK(m.vertex_count == 9 && m.triangle_count == 15, "%zu vertices, %zu triangles", m.vertex_count, m.triangle_count);
    TH_CHECK(m.indices[0] == 0 && m.indices[1] == 3 && m.indices[2] == 2 && m.indices[3] == 0 && m.indices[4] == 2 && m.indices[5] == 1,
             "first quad not split as a fan");
    TH_CHECK(m.indices[36] == 0 && m.indices[37] == 8 && m.indices[38] == 1 && m.indices[42] == 0 && m.indices[43] == 2 && m.indices[44] == 3,
             "pentagon not split as a fan");
    TH_CHECK(near(m.positions[24], 0.5f) && near(m.positions[25], -0.5f), "vertex 9 is %g %g", m.positions[24], m.positions[25]);
    TH_CHECK(m.normals == NULL && m.uvs == NULL, "normals or uvs without vt/vn");
    TH_CHECK(m.material_count == 1 && !strcmp(m.materials[0].name, "default"), "default material missing");
    TH_CHECK(near(m.materials[0].albedo[1], 0.8f) && near(m.materials[0].opacity, 1) && m.materials[0].emission[2] == 0, "default values wrong");
    for (i = 0; i < m.triangle_count; i++) TH_CHECK(m.material_ids[i] == 0, "material id %u", m.material_ids[i]);
    voxgi_io_mesh_free(&m);
    TH_CHECK(is_empty(&m), "voxgi_io_mesh_free did not zero the mesh");
}

static void test_obj_negative_indices(void)
{
    voxgi_io_mesh m;
    static const uint32_t expect[] = {0, 1, 2, 0, 3, 2};
    if (!load_ok(write_text("negative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0 1.0\nf -3 -2 -1\nv 0 0 1\nv 7 7 7\nf -5 -2 -3\n"), &m)) return;
    TH_CHECK(m.vertex_count == 5 && m.triangle_count == 2, "%zu vertices, %zu triangles", m.vertex_count, m.triangle_count);
    TH_CHECK(!memcmp(m.indices, expect, sizeof expect), "indices %u %u %u %u %u %u", m.indices[0], m.indices[1], m.indices[2], m.indices[3], m.indices[4], m.indices[5]);
    voxgi_io_mesh_free(&m);
}

static const char obj_split[] =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
    "vt 0 0\nvt 1 0\nvt 0 1\n"
    "vn 0 0 1\nvn 0 0 -1\n"
    "f 1/1/1 2/2/1 3/3/1\n"
    "f 2/2/1 4/1/1 3/3/1\n" /* shares two corners with the first face */
    "f 1//2 3//2 2//2\n"
    "f 1/2 2/3 3/1\n";

static void test_obj_split_vertices(void)
{
    /* first use of each (v, vt, vn) triple gives the vertex order */
    static const uint32_t expect_indices[] = {0, 1, 2, 1, 3, 2, 4, 5, 6, 7, 8, 9};
    static const int expect_v[] = {0, 1, 2, 3, 0, 2, 1, 0, 1, 2};
    voxgi_io_mesh m;
    int i;
    if (!load_ok(write_text("split.obj", obj_split), &m)) return;
    TH_CHECK(m.vertex_count == 10 && m.triangle_count == 4, "%zu vertices, %zu triangles", m.vertex_count, m.triangle_count);
    TH_CHECK(m.normals && m.uvs, "normals and uvs expected");
    if (m.vertex_count != 10 || !m.normals || !m.uvs) { voxgi_io_mesh_free(&m); return; }
    TH_CHECK(!memcmp(m.indices, expect_indices, sizeof expect_indices), "indices differ");
    for (i = 0; i < 10; i++)
        TH_CHECK(near(m.positions[3 * i], (float)(expect_v[i] & 1)) && near(m.positions[3 * i + 1], (float)(expect_v[i] >> 1)), "vertex %d position", i);
    TH_CHECK(near(m.uvs[6], 0) && near(m.uvs[7], 0) && near(m.normals[11], 1), "vertex 3 is (4, 1, 1)");
    TH_CHECK(near(m.normals[14], -1) && m.uvs[8] == 0 && m.uvs[9] == 0, "vertex 4 has vn 2 and no vt");
    TH_CHECK(near(m.uvs[14], 1) && near(m.uvs[15], 0) && m.normals[21] == 0 && m.normals[23] == 0, "vertex 7 has vt 2 and no vn");
    voxgi_io_mesh_free(&m);
}

static const char mtl_scene[] =
    "# materials\r\n"
    "newmtl red\r\nKa 0 0 0\r\nKd 1 0 0\r\nKe 0 0 0\r\nd 0.5\r\nillum 2\r\n"
    "\r\n"
    "newmtl lamp  \r\n\tKd 0.25\r\nKe 4 3 2\r\nTr 0.25\r\nmap_Kd textures/lamp.png\r\n";
static const char obj_scene[] =
    "# exported with CRLF and trailing blanks\r\n"
    "mtllib scene.mtl\r\n"
    "o thing\r\n"
    "v 0 0 0 \t\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0  \r\n"
    "g part\r\ns 1\r\ns off\r\n"
    "f 1 2 3   \r\n"
    "usemtl lamp\r\nf 1 3 4 # a comment\r\n"
    "usemtl red\r\nf 2 3 4\r\n"
    "usemtl ghost\r\nf 1 2 4\r\n";

static void test_obj_mtl_materials(void)
{
    static const uint32_t expect_ids[] = {2, 1, 0, 3};
    const voxgi_io_material *red, *lamp;
    voxgi_io_mesh m;
    write_text("scene.mtl", mtl_scene);
    if (!load_ok(write_text("scene.obj", obj_scene), &m)) return;
    TH_CHECK(m.vertex_count == 4 && m.triangle_count == 4, "%zu vertices, %zu triangles", m.vertex_count, m.triangle_count);
    TH_CHECK(m.material_count == 4, "%zu materials, expected red, lamp, default, ghost", m.material_count);
    if (m.material_count != 4) { voxgi_io_mesh_free(&m); return; }
    red = &m.materials[0];
    lamp = &m.materials[1];
    TH_CHECK(!strcmp(red->name, "red") && !strcmp(lamp->name, "lamp") && !strcmp(m.materials[2].name, "default") && !strcmp(m.materials[3].name, "ghost"),
             "names %s %s %s %s", red->name, lamp->name, m.materials[2].name, m.materials[3].name);
    TH_CHECK(!memcmp(m.material_ids, expect_ids, sizeof expect_ids), "material ids %u %u %u %u", m.material_ids[0], m.material_ids[1], m.material_ids[2], m.material_ids[3]);
    TH_CHECK(near(red->albedo[0], 1) && red->albedo[1] == 0 && red->emission[0] == 0 && near(red->opacity, 0.5f), "red values");
    TH_CHECK(near(lamp->albedo[0], 0.25f) && near(lamp->albedo[2], 0.25f), "Kd with one value is grey");
    TH_CHECK(near(lamp->emission[0], 4) && near(lamp->emission[1], 3) && near(lamp->emission[2], 2), "lamp emission");
    TH_CHECK(near(lamp->opacity, 0.75f), "Tr 0.25 gives opacity %g", lamp->opacity);
    TH_CHECK(near(m.materials[3].albedo[0], 0.8f) && near(m.materials[3].opacity, 1), "usemtl of an unknown name gets defaults");
    voxgi_io_mesh_free(&m);
}

static void test_obj_missing_mtl(void)
{
    voxgi_io_mesh m;
    if (!load_ok(write_text("lonely.obj", "mtllib does_not_exist.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\nf 3 2 1\n"), &m)) return;
    TH_CHECK(m.material_count == 2 && !strcmp(m.materials[1].name, "b") && m.material_ids[1] == 1, "usemtl names kept as default materials");
    voxgi_io_mesh_free(&m);
}

static void test_obj_mtl_in_subfolder(void)
{
    char dir[600];
    voxgi_io_mesh m;
    snprintf(dir, sizeof dir, "%s/sub", tmp_dir);
    TH_CHECK(mkdir(dir, 0700) == 0, "cannot create %s", dir);
    write_text("sub/tinted.mtl", "newmtl tint\nKd 0.1 0.2 0.3\n");
    if (!load_ok(write_text("sub/tinted.obj", "mtllib tinted.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl tint\nf 1 2 3\n"), &m)) return;
    TH_CHECK(m.material_count == 1 && near(m.materials[0].albedo[2], 0.3f), "MTL next to the OBJ not found");
    voxgi_io_mesh_free(&m);
}

/* The scene voxgi_io_mesh_scene builds renders with its materials: an OBJ of two coplanar quads
   facing the camera, a lamp (MTL Ke 2 3 5, Kd 0, Tr 0) on the left and a wall (Kd 0.5 0.25 0.125,
   d 1) on the right, lit head-on by a directional light of irradiance 2, rendered by the reference
   path tracer (CPU, 16 x 8, direct light only). A pixel on the lamp must show its emission
   exactly (2 3 5) and one on the wall the Lambertian albedo E / pi (0.318 0.159 0.080): an
   emission or albedo lost or the material ids dropped change them by 100% or more (opacity is not
   seen here: surfaces the camera sees directly shade alike). Measured: both within 1e-6. */
static void test_obj_mtl_scene_renders(void)
{
    static const char mtl[] = "newmtl lamp\nKd 0 0 0\nKe 2 3 5\nTr 0\nnewmtl wall\nKd 0.5 0.25 0.125\nd 1\n";
    static const char obj[] = "mtllib render.mtl\n"
                              "v -2 -1 0\nv -0.1 -1 0\nv -0.1 1 0\nv -2 1 0\nv 0.1 -1 0\nv 2 -1 0\nv 2 1 0\nv 0.1 1 0\n"
                              "usemtl lamp\nf 1 2 3 4\nusemtl wall\nf 5 6 7 8\n";
    const double pi = 3.14159265358979323846, irradiance = 2;
    const float lamp[3] = {2, 3, 5}, albedo[3] = {0.5f, 0.25f, 0.125f};
    voxgi_light sun;
    voxgi_io_mesh m;
    voxgi_scene scene;
    voxgi_desc desc;
    voxgi_render_desc d;
    voxgi_context *ctx = NULL;
    float rgb[16 * 8 * 3];
    int c;
    write_text("render.mtl", mtl);
    if (!load_ok(write_text("render.obj", obj), &m)) return;
    scene = voxgi_io_mesh_scene(&m);
    TH_CHECK(scene.mesh_count == 1 && scene.meshes == &m.mesh && scene.material_count == 2, "the scene: %zu meshes, %zu materials", scene.mesh_count,
             scene.material_count);
    memset(&sun, 0, sizeof sun);
    sun.type = VOXGI_LIGHT_DIRECTIONAL;
    sun.direction[2] = -1; /* travelling along -z: onto the quads' fronts, which face the eye */
    sun.intensity[0] = sun.intensity[1] = sun.intensity[2] = (float)irradiance;
    scene.lights = &sun;
    scene.light_count = 1;
    memset(&desc, 0, sizeof desc);
    desc.backend = VOXGI_BACKEND_CPU;
    memset(&d, 0, sizeof d);
    d.method = VOXGI_RENDER_REFERENCE;
    d.camera.eye[2] = 4;                 /* looking down -z at the origin: x from -2.9 to 2.9 in view, y from -1.46 to 1.46 */
    d.camera.fovy_degrees = 40;
    d.camera.width = 16, d.camera.height = 8;
    d.samples = 4;
    d.direct_only = 1;
    TH_CHECK(voxgi_create(&desc, &ctx) == VOXGI_OK, "no CPU context");
    if (ctx && voxgi_render(ctx, &scene, &d, rgb, sizeof rgb, NULL) == VOXGI_OK) {
        const float *on_lamp = rgb + 3 * (4 * 16 + 3), *on_wall = rgb + 3 * (4 * 16 + 12); /* x = -1.6 and 1.6, y = -0.2 */
        printf("    lamp %g %g %g (emission 2 3 5), wall %g %g %g (albedo E / pi %g %g %g)\n", on_lamp[0], on_lamp[1], on_lamp[2], on_wall[0],
               on_wall[1], on_wall[2], albedo[0] * irradiance / pi, albedo[1] * irradiance / pi, albedo[2] * irradiance / pi);
        for (c = 0; c < 3; c++) {
            TH_CHECK(fabs(on_lamp[c] - lamp[c]) < 1e-3 * lamp[c], "channel %d: the lamp shows %g, its emission is %g", c, on_lamp[c], lamp[c]);
            TH_CHECK(fabs(on_wall[c] - albedo[c] * irradiance / pi) < 1e-3 * albedo[c] * irradiance / pi, "channel %d: the wall shows %g, not %g", c,
                     on_wall[c], albedo[c] * irradiance / pi);
        }
    } else TH_CHECK(0, "voxgi_render: %s", voxgi_last_error(ctx));
    voxgi_destroy(ctx);
    voxgi_io_mesh_free(&m);
}

/* MTL opacity reaches the shadows: a wall (Kd 0.5) at z = 0 facing the camera, lit by a sun
   travelling down and back along (0, -1, -1) / sqrt 2, and above the view at z = 2 two strips the
   camera does not see, an opaque one (d 1) over x 0.1..1 and a translucent one (d 0.25, so
   transparency 0.75) over x 1..2, both over y 1.5..2.5: the sun's rays through them land on the
   wall at y -0.5..0.5, which pixel rows 3 and 4 lie in whole. Rendered by the direct light (cone tracing's shadow rays, which pass
   translucent surfaces with their transparency; CPU, 16 x 8): a lit wall pixel shows
   albedo E cos 45 / pi, one under the opaque strip 0, one under the translucent strip 0.75 of
   the lit one. d read as transparency (or Tr as opacity) swaps them. */
static void test_mtl_opacity_shadows(void)
{
    static const char mtl[] = "newmtl wall\nKd 0.5 0.5 0.5\nnewmtl blind\nKd 0.5 0.5 0.5\nd 1\nnewmtl veil\nKd 0.5 0.5 0.5\nd 0.25\n";
    static const char obj[] = "mtllib shadows.mtl\n"
                              "v -3 -2 0\nv 3 -2 0\nv 3 2 0\nv -3 2 0\n"
                              "v 0.1 1.5 2\nv 1 1.5 2\nv 1 2.5 2\nv 0.1 2.5 2\n"
                              "v 1 1.5 2\nv 2 1.5 2\nv 2 2.5 2\nv 1 2.5 2\n"
                              "usemtl wall\nf 1 2 3 4\nusemtl blind\nf 5 6 7 8\nusemtl veil\nf 9 10 11 12\n";
    const double pi = 3.14159265358979323846, irradiance = 2, lit = 0.5 * irradiance * sqrt(0.5) / pi;
    voxgi_light sun;
    voxgi_io_mesh m;
    voxgi_scene scene;
    voxgi_desc desc;
    voxgi_render_desc d;
    voxgi_context *ctx = NULL;
    float rgb[16 * 8 * 3];
    write_text("shadows.mtl", mtl);
    if (!load_ok(write_text("shadows.obj", obj), &m)) return;
    scene = voxgi_io_mesh_scene(&m);
    memset(&sun, 0, sizeof sun);
    sun.type = VOXGI_LIGHT_DIRECTIONAL;
    sun.direction[1] = sun.direction[2] = (float)-sqrt(0.5);
    sun.intensity[0] = sun.intensity[1] = sun.intensity[2] = (float)irradiance;
    scene.lights = &sun;
    scene.light_count = 1;
    memset(&desc, 0, sizeof desc);
    desc.backend = VOXGI_BACKEND_CPU;
    memset(&d, 0, sizeof d);
    d.method = VOXGI_RENDER_VCT;
    d.direct_only = 1;
    d.camera.eye[2] = 4; /* looking down -z: pixel column c at x = (2 (c + 0.5) / 16 - 1) 2.91, row r at y = (1 - 2 (r + 0.5) / 8) 1.46 */
    d.camera.fovy_degrees = 40;
    d.camera.width = 16, d.camera.height = 8;
    TH_CHECK(voxgi_create(&desc, &ctx) == VOXGI_OK, "no CPU context");
    if (ctx && voxgi_render(ctx, &scene, &d, rgb, sizeof rgb, NULL) == VOXGI_OK) {
        const float *sunlit = rgb + 3 * (0 * 16 + 9), *under_blind = rgb + 3 * (4 * 16 + 9), *under_veil = rgb + 3 * (4 * 16 + 12); /* x 0.55, 0.55, 1.64 */
        printf("    wall: lit %g (E cos 45 albedo / pi %g), under the opaque strip %g, under the translucent one %g (0.75 of lit: %g)\n", sunlit[1], lit,
               under_blind[1], under_veil[1], 0.75 * lit);
        TH_CHECK(fabs(sunlit[1] - lit) < 1e-3 * lit, "the lit wall shows %g, not %g", sunlit[1], lit);
        TH_CHECK(under_blind[1] == 0, "under the opaque strip (d 1): %g, not 0", under_blind[1]);
        TH_CHECK(fabs(under_veil[1] - 0.75 * lit) < 1e-3 * lit, "under the translucent strip (d 0.25): %g, not %g", under_veil[1], 0.75 * lit);
    } else TH_CHECK(0, "voxgi_render: %s", voxgi_last_error(ctx));
    voxgi_destroy(ctx);
    voxgi_io_mesh_free(&m);
}

/* A malformed MTL line fails the OBJ, and the message names the MTL file and its line. */
static void test_mtl_errors(void)
{
    static const struct { const char *mtl; int line; } cases[] = {
        {"newmtl a\nKd 1 1 1\nKd 1 zero 0\n", 3}, {"Kd 1 1 1\n", 1}, {"newmtl a\nd 0.5 0.5\n", 2}, {"newmtl a\r\nKe nan 0 0\r\n", 2}};
    char obj[1024], err[512], expect[600];
    voxgi_io_mesh m;
    size_t i;
    snprintf(obj, sizeof obj, "%s", write_text("bad_mtl.obj", "mtllib bad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        snprintf(expect, sizeof expect, "%s: line %d: ", write_text("bad.mtl", cases[i].mtl), cases[i].line);
        TH_CHECK(voxgi_io_load_mesh(obj, &m, err, sizeof err) != 0 && is_empty(&m), "case %zu loaded", i);
        TH_CHECK(strstr(err, expect) == err, "case %zu: expected '%s...', got '%s'", i, expect, err);
    }
}

static const char off_pyramid[] =
    "OFF\n# a square pyramid\n5 2 0\n\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 1\n"
    "4 0 1 2 3\n3 0 1 4  255 0 0\n";

static void test_off(void)
{
    static const uint32_t expect[] = {0, 1, 2, 0, 2, 3, 0, 1, 4};
    voxgi_io_mesh m;
    if (!load_ok(write_text("pyramid.off", off_pyramid), &m)) return;
    TH_CHECK(m.vertex_count == 5 && m.triangle_count == 3, "%zu vertices, %zu triangles", m.vertex_count, m.triangle_count);
    TH_CHECK(!memcmp(m.indices, expect, sizeof expect), "indices differ");
    TH_CHECK(near(m.positions[12], 0.5f) && near(m.positions[14], 1), "apex position");
    voxgi_io_mesh_free(&m);
    /* the counts may follow OFF on its line, and the content decides over the extension */
    if (!load_ok(write_text("inline_counts.txt", "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), &m)) return;
    TH_CHECK(m.triangle_count == 1, "%zu triangles", m.triangle_count);
    voxgi_io_mesh_free(&m);
}

static const char stl_ascii[] =
    "solid two triangles\n"
    "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 1 1 0\n    endloop\n  endfacet\n"
    "  facet normal 0 0 -1\n    outer loop\n      vertex 0 0 0\n      vertex 1 1 0\n      vertex 0 1 -2.5e-1\n    endloop\n  endfacet\n"
    "endsolid two triangles\n";

static void test_stl_ascii(void)
{
    voxgi_io_mesh m;
    if (!load_ok(write_text("two.stl", stl_ascii), &m)) return;
    TH_CHECK(m.vertex_count == 6 && m.triangle_count == 2, "%zu vertices, %zu triangles", m.vertex_count, m.triangle_count);
    TH_CHECK(m.indices[3] == 3 && m.indices[5] == 5 && near(m.positions[17], -0.25f), "second facet");
    voxgi_io_mesh_free(&m);
}

static bytes stl_binary(const char *header, float last_z)
{
    bytes b;
    int t, k;
    memset(&b, 0, sizeof b);
    memcpy(b.data, header, strlen(header)); /* the rest of the 80 bytes stays zero */
    b.size = 80;
    put_uint(&b, 2, 4);
    for (t = 0; t < 2; t++) {
        put_f32(&b, 0); put_f32(&b, 0); put_f32(&b, 1);
        for (k = 0; k < 9; k++) put_f32(&b, k == 8 && t == 1 ? last_z : (float)(k / 3 + t));
        put_uint(&b, 0, 2);
    }
    return b;
}

static void test_stl_binary(void)
{
    bytes plain = stl_binary("binary STL", 7.5f), solid = stl_binary("solid looks like ASCII but is binary", 7.5f);
    voxgi_io_mesh m;
    TH_CHECK(plain.size == 84 + 2 * 50, "test file has %zu bytes", plain.size);
    if (load_ok(write_file("binary.stl", plain.data, plain.size), &m)) {
        TH_CHECK(m.vertex_count == 6 && m.triangle_count == 2, "%zu vertices, %zu triangles", m.vertex_count, m.triangle_count);
        TH_CHECK(near(m.positions[3], 1) && near(m.positions[9], 1) && near(m.positions[17], 7.5f), "coordinates");
        voxgi_io_mesh_free(&m);
    }
    if (load_ok(write_file("solid_header.stl", solid.data, solid.size), &m)) {
        TH_CHECK(m.triangle_count == 2 && near(m.positions[17], 7.5f), "binary STL with a 'solid' header");
        voxgi_io_mesh_free(&m);
    }
    if (load_ok(write_file("solid_header.bin", solid.data, solid.size), &m)) voxgi_io_mesh_free(&m); /* size alone tells */
}

static const char ply_ascii[] =
    "ply\nformat ascii 1.0\ncomment made by hand\n"
    "element vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty float s\nproperty float t\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 -3 0 0.5\n4 0 1 2 3\n";

static void test_ply_ascii(void)
{
    static const uint32_t expect[] = {0, 1, 2, 0, 2, 3};
    voxgi_io_mesh m;
    if (!load_ok(write_text("quad.ply", ply_ascii), &m)) return;
    TH_CHECK(m.vertex_count == 4 && m.triangle_count == 2, "%zu vertices, %zu triangles", m.vertex_count, m.triangle_count);
    TH_CHECK(!memcmp(m.indices, expect, sizeof expect), "indices differ");
    TH_CHECK(m.uvs && !m.normals, "s,t give uvs; no normals");
    if (m.uvs) TH_CHECK(near(m.uvs[7], 0.5f) && near(m.positions[11], -3), "vertex 3");
    voxgi_io_mesh_free(&m);
}

/* Doubles, normals, uvs, an unused scalar and list on the vertices, an extra element before the
   faces, and faces with a flag, a uint-counted index list and another list. */
static bytes ply_binary(void)
{
    static const double xyz[4][3] = {{0, 0, 0}, {0.5, 0, 0}, {0.5, -2.25, 0}, {0, -2.25, 1e10}};
    bytes b;
    int i, k;
    memset(&b, 0, sizeof b);
    put_text(&b, "ply\r\nformat binary_little_endian 1.0\r\ncomment extra properties and an extra element\r\n"
                 "element vertex 4\r\nproperty double x\r\nproperty double y\r\nproperty double z\r\nproperty uchar red\r\n"
                 "property float nx\r\nproperty float ny\r\nproperty float nz\r\nproperty list uchar float extra\r\n"
                 "property float u\r\nproperty float v\r\n"
                 "element edge 2\r\nproperty int vertex1\r\nproperty int vertex2\r\n"
                 "element face 2\r\nproperty uchar flags\r\nproperty list uint int vertex_index\r\nproperty list int short other\r\n"
                 "end_header\r\n");
    for (i = 0; i < 4; i++) {
        put_f64(&b, xyz[i][0]); put_f64(&b, xyz[i][1]); put_f64(&b, xyz[i][2]);
        put_uint(&b, 200, 1);
        put_f32(&b, 0); put_f32(&b, (float)i); put_f32(&b, 1);
        put_uint(&b, (uint64_t)i, 1);
        for (k = 0; k < i; k++) put_f32(&b, -1);
        put_f32(&b, 0.25f * (float)i); put_f32(&b, 1);
    }
    put_uint(&b, (uint64_t)-1, 4); put_uint(&b, 3, 4);
    put_uint(&b, 1, 4); put_uint(&b, 2, 4);
    put_uint(&b, 7, 1); put_uint(&b, 3, 4); put_uint(&b, 0, 4); put_uint(&b, 1, 4); put_uint(&b, 2, 4);
    put_uint(&b, 1, 4); put_uint(&b, (uint64_t)-5, 2);
    put_uint(&b, 7, 1); put_uint(&b, 4, 4); put_uint(&b, 3, 4); put_uint(&b, 2, 4); put_uint(&b, 1, 4); put_uint(&b, 0, 4);
    put_uint(&b, 0, 4);
    return b;
}

static void test_ply_binary(void)
{
    static const uint32_t expect[] = {0, 1, 2, 3, 2, 1, 3, 1, 0};
    bytes b = ply_binary();
    voxgi_io_mesh m;
    if (!load_ok(write_file("extras.ply", b.data, b.size), &m)) return;
    TH_CHECK(m.vertex_count == 4 && m.triangle_count == 3, "%zu vertices, %zu triangles", m.vertex_count, m.triangle_count);
    TH_CHECK(!memcmp(m.indices, expect, sizeof expect), "indices %u %u %u / %u %u %u", m.indices[0], m.indices[1], m.indices[2], m.indices[3], m.indices[4], m.indices[5]);
    TH_CHECK(near(m.positions[3], 0.5f) && near(m.positions[7], -2.25f) && m.positions[11] == 1e10f, "positions");
    TH_CHECK(m.normals && m.uvs, "normals and uvs expected");
    if (m.normals && m.uvs) TH_CHECK(near(m.normals[10], 3) && near(m.uvs[6], 0.75f) && near(m.uvs[7], 1), "vertex 3 attributes");
    voxgi_io_mesh_free(&m);
}

/* ---- every PLY scalar type ---- */

/* The test's own table of the PLY scalar types (names, aliases, sizes; ranges follow from them). */
static const struct ply_kind { const char *name, *alias; int size, is_signed, is_float; } ply_kinds[8] = {
    {"char", "int8", 1, 1, 0}, {"uchar", "uint8", 1, 0, 0}, {"short", "int16", 2, 1, 0}, {"ushort", "uint16", 2, 0, 0},
    {"int", "int32", 4, 1, 0}, {"uint", "uint32", 4, 0, 0}, {"float", "float32", 4, 1, 1}, {"double", "float64", 8, 1, 1}};
enum { KIND_CHAR, KIND_UCHAR, KIND_SHORT, KIND_USHORT, KIND_INT, KIND_UINT, KIND_FLOAT, KIND_DOUBLE };
static double kind_lo(int k) { return ply_kinds[k].is_signed ? -ldexp(1, 8 * ply_kinds[k].size - 1) : 0; }
static double kind_hi(int k) { return ldexp(1, 8 * ply_kinds[k].size - ply_kinds[k].is_signed) - 1; }
static const char *kind_spelling(int k, int alias) { return alias ? ply_kinds[k].alias : ply_kinds[k].name; }

/* A growing file image: binary values little-endian two's complement / IEEE, ASCII as %.17g (exact). */
typedef struct growing { unsigned char *data; size_t size, cap; } growing;
static void grow_put(growing *g, const void *p, size_t n)
{
    if (g->size + n > g->cap) {
        size_t cap = 2 * (g->size + n) + 4096;
        unsigned char *d = (unsigned char *)realloc(g->data, cap);
        if (!d) { printf("out of memory\n"); exit(1); }
        g->data = d;
        g->cap = cap;
    }
    memcpy(g->data + g->size, p, n);
    g->size += n;
}
static void grow_printf(growing *g, const char *fmt, ...)
{
    char line[512];
    va_list ap;
    int n;
    va_start(ap, fmt);
    n = vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    grow_put(g, line, (size_t)n);
}
static void grow_value(growing *g, int binary, int kind, double v)
{
    unsigned char b[8];
    uint64_t bits;
    int i;
    if (!binary) { grow_printf(g, " %.17g", v); return; }
    if (kind == KIND_FLOAT) {
        float f = (float)v;
        uint32_t u;
        memcpy(&u, &f, 4);
        bits = u;
    } else if (kind == KIND_DOUBLE) {
        memcpy(&bits, &v, 8);
    } else {
        bits = (uint64_t)(int64_t)v; /* two's complement, wrapped to the type's size below */
    }
    for (i = 0; i < ply_kinds[kind].size; i++) b[i] = (unsigned char)(bits >> (8 * i));
    grow_put(g, b, (size_t)ply_kinds[kind].size);
}
static void grow_header(growing *g, int binary) { g->size = 0; grow_printf(g, "ply\nformat %s 1.0\n", binary ? "binary_little_endian" : "ascii"); }

/* Eight values of each type: its extremes, the values around half an unsigned type's range, and for
   the floating types the largest float, a denormal, values float rounds and one it flushes to -0. */
static double kind_value(int k, int i)
{
    double lo = kind_lo(k), hi = kind_hi(k), half = ldexp(1, 8 * ply_kinds[k].size - 1);
    const double floats[8] = {-FLT_MAX, FLT_MAX, -ldexp(1, -149), -1.5, (double)0.1f, -2147483648.0, 4294967296.0, -16777216.0};
    const double doubles[8] = {-FLT_MAX, -0.1, -1e-300, 4294967295.0, -2147483649.0, 1e10 + 0.5, ldexp(1.5, 127), -65535.75};
    if (k == KIND_FLOAT) return floats[i];
    if (k == KIND_DOUBLE) return doubles[i];
    if (ply_kinds[k].is_signed) {
        const double v[8] = {lo, lo + 1, -1, 0, 1, hi - 1, hi, lo / 2};
        return v[i];
    } else {
        const double v[8] = {0, 1, half - 1, half, half + 1, hi - 1, hi, 1.5 * half};
        return v[i];
    }
}

/* Vertex coordinates of every PLY scalar type (name and alias), ASCII and binary_little_endian
   (the loader refuses binary_big_endian: test_other_failures): file k has x, y, z of types k, k+1,
   k+2 (mod 8) with unused scalars of the five other types between and after them, so each type is
   read as x, y, z and skipped, in every spelling and format. The 8 vertices take each type's 8
   values (signed: its negative extreme, -1 and its maximum; unsigned: 2^(n-1) - 1, 2^(n-1),
   2^(n-1) + 1 and 2^n - 1; floats: -FLT_MAX, a denormal, values float rounds) in every axis; each
   loaded coordinate must be bit for bit the C conversion (float)value: 32 files x 24 coordinates. */
static void test_ply_coordinate_types(void)
{
    static const uint32_t expect_indices[12] = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7};
    growing g = {NULL, 0, 0};
    int k, alias, binary, bad = 0;
    for (k = 0; k < 8; k++)
        for (alias = 0; alias < 2; alias++)
            for (binary = 0; binary < 2; binary++) {
                /* property order: x, pad, y, pad, z, pad, pad, pad; the kind of each */
                const int kinds[8] = {k, (k + 3) % 8, (k + 1) % 8, (k + 4) % 8, (k + 2) % 8, (k + 5) % 8, (k + 6) % 8, (k + 7) % 8};
                const int axis_of[8] = {0, -1, 1, -1, 2, -1, -1, -1};
                float expect[24];
                char name[64];
                voxgi_io_mesh m;
                int v, p;
                grow_header(&g, binary);
                grow_printf(&g, "element vertex 8\n");
                for (p = 0; p < 8; p++)
                    if (axis_of[p] < 0) grow_printf(&g, "property %s pad%d\n", kind_spelling(kinds[p], alias), p);
                    else grow_printf(&g, "property %s %c\n", kind_spelling(kinds[p], alias), "xyz"[axis_of[p]]);
                grow_printf(&g, "element face 2\nproperty list uchar uint vertex_indices\nend_header\n");
                for (v = 0; v < 8; v++) {
                    for (p = 0; p < 8; p++) {
                        /* slot 3v + axis: by the Chinese remainder theorem every (value, axis) pair occurs */
                        double value = kind_value(kinds[p], axis_of[p] < 0 ? (v + p) % 8 : (3 * v + axis_of[p]) % 8);
                        grow_value(&g, binary, kinds[p], value);
                        if (axis_of[p] >= 0) expect[3 * v + axis_of[p]] = (float)value;
                    }
                    if (!binary) grow_printf(&g, "\n");
                }
                for (v = 0; v < 2; v++) {
                    grow_value(&g, binary, KIND_UCHAR, 4);
                    for (p = 0; p < 4; p++) grow_value(&g, binary, KIND_UINT, 4 * v + p);
                    if (!binary) grow_printf(&g, "\n");
                }
                snprintf(name, sizeof name, "types_%s_%s.ply", kind_spelling(k, alias), binary ? "binary" : "ascii");
                if (!load_ok(write_file("types.ply", g.data, g.size), &m)) { TH_CHECK(0, "%s did not load", name); bad++; continue; }
                TH_CHECK(m.vertex_count == 8 && m.triangle_count == 4 && !memcmp(m.indices, expect_indices, sizeof expect_indices), "%s: %zu vertices, %zu triangles",
                         name, m.vertex_count, m.triangle_count);
                for (v = 0; v < 24 && m.vertex_count == 8; v++)
                    if (memcmp(&m.positions[v], &expect[v], sizeof expect[v])) {
                        TH_CHECK(0, "%s: vertex %d %c (%s) is %.9g, not %.9g", name, v / 3, "xyz"[v % 3], kind_spelling(kinds[2 * (v % 3)], alias),
                                 (double)m.positions[v], (double)expect[v]);
                        bad++;
                        break;
                    }
                voxgi_io_mesh_free(&m);
            }
    printf("    32 files (8 types x 2 spellings x ASCII/binary): %d with a wrong coordinate\n", bad);
    free(g.data);
}

/* A vertex element of n vertices (uchar x = v mod 256, y = v / 256, z = 7) and the face header. */
static void grow_vertices(growing *g, int binary, uint32_t n, int count_kind, int index_kind, int alias, int faces)
{
    uint32_t v;
    grow_printf(g, "element vertex %lu\nproperty uchar x\nproperty uint8 y\nproperty uchar z\nelement face %d\nproperty list %s %s vertex_indices\nend_header\n",
                (unsigned long)n, faces, kind_spelling(count_kind, alias), kind_spelling(index_kind, !alias));
    for (v = 0; v < n; v++) {
        grow_value(g, binary, KIND_UCHAR, v & 255);
        grow_value(g, binary, KIND_UCHAR, v >> 8);
        grow_value(g, binary, KIND_UCHAR, 7);
        if (!binary) grow_printf(g, "\n");
    }
}

/* Face lists with every integer index type under every integer count type, ASCII and binary (72
   files): 256 vertices for 8-bit indices, else 65536, a triangle of the largest valid indices
   (uchar 255 254 128, char 127 126 64, 16- and 32-bit 65535 65534 32768) and a polygon whose length
   is at or above half the count type's unsigned range (uchar 200, ushort 40000; char 127, short 300,
   int 70000, uint 5), its indices spread over the valid range; the fan of each must come back
   index for index. Refused, binary and ASCII: a signed index type's negative extreme where its
   unsigned reading (128, 32768) would be a valid vertex, a signed count type's negative extreme
   followed by as many valid indices as its unsigned reading would take, and in ASCII each integer
   type's maximum + 1 and minimum - 1. */
static void test_ply_index_types(void)
{
    static const uint32_t big_counts[6] = {127, 200, 300, 40000, 70000, 5};
    growing g = {NULL, 0, 0};
    uint32_t *expect = (uint32_t *)malloc(3 * 70000 * sizeof *expect), *face = (uint32_t *)malloc(70000 * sizeof *face);
    int ik, ck, binary, loaded = 0;
    char name[64];
    if (!expect || !face) { TH_CHECK(0, "out of memory"); free(expect); free(face); return; }
    for (ik = 0; ik <= KIND_UINT; ik++)
        for (ck = 0; ck <= KIND_UINT; ck++)
            for (binary = 0; binary < 2; binary++) {
                uint32_t n = ply_kinds[ik].size == 1 ? 256 : 65536, top = (uint32_t)(kind_hi(ik) < n - 1 ? kind_hi(ik) : n - 1), count = big_counts[ck], k;
                size_t triangles = 1 + (count - 2), t;
                voxgi_io_mesh m;
                grow_header(&g, binary);
                grow_vertices(&g, binary, n, ck, ik, (ik + ck + binary) % 2, 2);
                face[0] = top; face[1] = top - 1; face[2] = (top + 1) / 2;
                grow_value(&g, binary, ck, 3);
                for (k = 0; k < 3; k++) grow_value(&g, binary, ik, face[k]), expect[k] = face[k];
                if (!binary) grow_printf(&g, "\n");
                grow_value(&g, binary, ck, count);
                for (k = 0; k < count; k++) grow_value(&g, binary, ik, face[k] = (uint32_t)(((uint64_t)k * 7919 + 3) % ((uint64_t)top + 1)));
                if (!binary) grow_printf(&g, "\n");
                for (k = 1; k + 1 < count; k++) { expect[3 * k] = face[0]; expect[3 * k + 1] = face[k]; expect[3 * k + 2] = face[k + 1]; }
                snprintf(name, sizeof name, "indices_%s_%s_%s.ply", ply_kinds[ck].name, ply_kinds[ik].name, binary ? "binary" : "ascii");
                if (!load_ok(write_file("indices.ply", g.data, g.size), &m)) { TH_CHECK(0, "%s did not load", name); continue; }
                TH_CHECK(m.vertex_count == n && m.triangle_count == triangles, "%s: %zu vertices, %zu triangles (expected %lu, %zu)", name, m.vertex_count,
                         m.triangle_count, (unsigned long)n, triangles);
                if (m.triangle_count == triangles) {
                    for (t = 0; t < 3 * triangles && m.indices[t] == expect[t]; t++) {}
                    TH_CHECK(t == 3 * triangles, "%s: index %zu is %u, not %u", name, t, m.indices[t], expect[t]);
                    loaded += t == 3 * triangles;
                }
                if (m.vertex_count == n) /* a vertex near the end: its low byte, high byte, 7 */
                    TH_CHECK(m.positions[3 * (n - 56)] == (float)((n - 56) & 255) && m.positions[3 * (n - 56) + 1] == (float)((n - 56) >> 8) &&
                             m.positions[3 * (n - 56) + 2] == 7, "%s: vertex %lu", name, (unsigned long)(n - 56));
                voxgi_io_mesh_free(&m);
            }
    printf("    72 files (6 count x 6 index types x ASCII/binary): %d with every index right\n", loaded);
    for (binary = 0; binary < 2; binary++) {
        for (ik = KIND_CHAR; ik <= KIND_INT; ik += 2) { /* the signed index types' negative extreme */
            grow_header(&g, binary);
            grow_vertices(&g, binary, ply_kinds[ik].size == 1 ? 256 : 65536, KIND_UCHAR, ik, binary, 1);
            grow_value(&g, binary, KIND_UCHAR, 3);
            grow_value(&g, binary, ik, 0);
            grow_value(&g, binary, ik, 1);
            grow_value(&g, binary, ik, kind_lo(ik));
            snprintf(name, sizeof name, "negative_index_%s_%s.ply", ply_kinds[ik].name, binary ? "binary" : "ascii");
            expect_error(name, g.data, g.size, "out of range");
        }
        for (ck = KIND_CHAR; ck <= KIND_INT; ck += 2) { /* the signed count types' negative extreme */
            uint32_t k, follow = ck == KIND_INT ? 3 : (uint32_t)-kind_lo(ck);
            grow_header(&g, binary);
            grow_vertices(&g, binary, 3, ck, KIND_UCHAR, binary, 1);
            grow_value(&g, binary, ck, kind_lo(ck));
            for (k = 0; k < follow; k++) grow_value(&g, binary, KIND_UCHAR, k % 3);
            snprintf(name, sizeof name, "negative_count_%s_%s.ply", ply_kinds[ck].name, binary ? "binary" : "ascii");
            expect_error(name, g.data, g.size, "negative list length");
        }
    }
    for (ik = 0; ik <= KIND_UINT; ik++) { /* ASCII values just outside each integer type */
        int side;
        for (side = 0; side < 2; side++) {
            char expect_text[64];
            double v = side ? kind_hi(ik) + 1 : kind_lo(ik) - 1;
            grow_header(&g, 0);
            grow_printf(&g, "element vertex 3\nproperty %s x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                        "end_header\n0 0 0\n1 0 0\n%.17g 1 0\n3 0 1 2\n", kind_spelling(ik, side), v);
            snprintf(name, sizeof name, "outside_%s.ply", ply_kinds[ik].name);
            snprintf(expect_text, sizeof expect_text, "is not a valid %s", ply_kinds[ik].name);
            expect_error(name, g.data, g.size, expect_text);
        }
    }
    free(expect);
    free(face);
    free(g.data);
}

/* ---- hostile input ---- */

typedef struct sample { const char *name; const void *data; size_t size; } sample;

static int valid_samples(sample *s, bytes *stl, bytes *ply)
{
    *stl = stl_binary("solid", 2);
    *ply = ply_binary();
    write_text("scene.mtl", mtl_scene);
    s[0].name = "scene.obj"; s[0].data = obj_scene; s[0].size = strlen(obj_scene);
    s[1].name = "split.obj"; s[1].data = obj_split; s[1].size = strlen(obj_split);
    s[2].name = "pyramid.off"; s[2].data = off_pyramid; s[2].size = strlen(off_pyramid);
    s[3].name = "two.stl"; s[3].data = stl_ascii; s[3].size = strlen(stl_ascii);
    s[4].name = "binary.stl"; s[4].data = stl->data; s[4].size = stl->size;
    s[5].name = "quad.ply"; s[5].data = ply_ascii; s[5].size = strlen(ply_ascii);
    s[6].name = "extras.ply"; s[6].data = ply->data; s[6].size = ply->size;
    return 7;
}

/* Loads a file that may be valid or not: either way the result must be clean. */
static int load_any(const char *path)
{
    char err[256];
    voxgi_io_mesh m;
    int rc = voxgi_io_load_mesh(path, &m, err, sizeof err);
    if (rc) {
        TH_CHECK(is_empty(&m), "%s: mesh not left empty on failure", path);
        TH_CHECK(strstr(err, path) == err, "%s: message does not start with the file: %s", path, err);
        return 0;
    }
    check_consistent(&m, path);
    voxgi_io_mesh_free(&m);
    return 1;
}

static void test_truncated_prefixes(void)
{
    sample s[8];
    bytes stl, ply;
    int n = valid_samples(s, &stl, &ply), i;
    size_t len;
    for (i = 0; i < n; i++) {
        for (len = 0; len < s[i].size; len++) load_any(write_file(s[i].name, s[i].data, len));
        TH_CHECK(load_any(write_file(s[i].name, s[i].data, len)), "%s: the whole file did not load", s[i].name);
    }
}

static uint32_t rng_state = 12345;
static uint32_t rng(void) { rng_state = rng_state * 1664525u + 1013904223u; return rng_state >> 8; }

static void test_corrupted_and_garbage(void)
{
    static const char *const names[] = {"garbage.obj", "garbage.off", "garbage.stl", "garbage.ply", "garbage.dat"};
    static const char alphabet[] = "vtnf/ -0123456789.e#\n\rnaOFFsolidply";
    unsigned char data[4096];
    sample s[8];
    bytes stl, ply;
    int n = valid_samples(s, &stl, &ply), i, k, round;
    for (round = 0; round < 300; round++) { /* valid files with a few bytes changed */
        const sample *v = &s[round % n];
        memcpy(data, v->data, v->size);
        for (k = 0; k < 1 + (int)(rng() % 4); k++) data[rng() % v->size] = (unsigned char)rng();
        load_any(write_file(v->name, data, v->size));
    }
    for (round = 0; round < 200; round++) { /* random bytes, and random text from the formats' own characters */
        size_t size = rng() % 300;
        for (i = 0; i < (int)size; i++) data[i] = round % 2 ? (unsigned char)rng() : (unsigned char)alphabet[rng() % (sizeof alphabet - 1)];
        load_any(write_file(names[round % 5], data, size));
    }
    expect_text_error("binary_junk.obj", "\x01\x02\x03 garbage\n", "line 1");
    expect_text_error("late_junk.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n\xff\xfe\n", "line 5");
    expect_text_error("hello.dat", "hello world\n", "unrecognised");
    expect_text_error("empty.obj", "", "no triangles");
    expect_text_error("points.obj", "v 0 0 0\nv 1 0 0\n", "no triangles");
}

static void test_bad_indices(void)
{
    bytes b;
    static const char ply_head[] = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                   "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    int i;
    expect_text_error("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "line 4");
    expect_text_error("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "out of range");
    expect_text_error("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "line 4");
    expect_text_error("before.obj", "v 0 0 0\nv 1 0 0\nf -3 1 2\nv 0 1 0\n", "line 3");
    expect_text_error("forward.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n", "line 3");
    expect_text_error("vt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", "texture coordinate index 2");
    expect_text_error("vn.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//-2\n", "normal index -2");
    expect_text_error("overflow.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n", "line 4");
    expect_text_error("slashes.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/ 2 3\n", "line 4");
    expect_text_error("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", "fewer than 3");
    expect_text_error("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "line 6");
    expect_text_error("negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "line 6");
    expect_text_error("range.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                   "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "line 13");
    memset(&b, 0, sizeof b);
    put_text(&b, ply_head);
    for (i = 0; i < 9; i++) put_f32(&b, (float)(i % 4 == 0));
    put_uint(&b, 3, 1); put_uint(&b, 0, 4); put_uint(&b, (uint64_t)-1, 4); put_uint(&b, 2, 4);
    {
        char where[64];
        snprintf(where, sizeof where, "byte offset %zu", b.size - 8);
        expect_error("range_binary.ply", b.data, b.size, where);
    }
}

static void test_non_finite_numbers(void)
{
    bytes stl = stl_binary("nan", NAN), b;
    char where[64];
    int i;
    expect_text_error("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "line 2");
    expect_text_error("inf.obj", "v 0 0 0\nv 0 -inf 0\n", "line 2");
    expect_text_error("huge.obj", "v 0 0 1e39\n", "line 1");
    expect_text_error("word.obj", "v 0 0 0\nv 1 2 abc\n", "line 2");
    expect_text_error("short.obj", "v 0 0 0\nv 1 2\n", "line 2");
    expect_text_error("glued.obj", "v 0 0 0\nv 1 2 3x\n", "line 2");
    expect_text_error("nan.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "line 4");
    expect_text_error("nan.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 NaN\n", "line 5");
    expect_text_error("nan_ascii.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n", "line 11");
    expect_error("nan.stl", stl.data, stl.size, "byte offset 178"); /* the last vertex's z: 84 + 50 + 12 + 32 */
    memset(&b, 0, sizeof b);
    put_text(&b, "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty double y\nproperty float z\n"
                 "element face 0\nproperty list uchar int vertex_indices\nend_header\n");
    snprintf(where, sizeof where, "byte offset %zu", b.size + 16 + 4);
    for (i = 0; i < 3; i++) { put_f32(&b, 0); put_f64(&b, i == 1 ? NAN : 0.0); put_f32(&b, 0); }
    expect_error("nan_binary.ply", b.data, b.size, where);
}

static void test_absurd_counts(void)
{
    bytes b;
    static const char head[] = "ply\nformat binary_little_endian 1.0\nelement vertex 100000000\nproperty float x\nproperty float y\nproperty float z\n"
                               "element face 1\nproperty list uint int vertex_indices\nend_header\n";
    char where[64];
    expect_text_error("huge.ply", "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\n"
                                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n", "declares 4000000000 records");
    expect_text_error("overflow.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999\n", "line 3");
    expect_text_error("huge.off", "OFF\n1000000000 1000000000 0\n0 0 0\n1 0 0\n", "line 5");
    expect_text_error("huge_face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n", "line 6");
    expect_text_error("toolong.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n99999999999 0 1 2\n", "line 6");
    memset(&b, 0, sizeof b);
    put_text(&b, head);
    snprintf(where, sizeof where, "byte offset %zu", b.size);
    put_f32(&b, 0); put_f32(&b, 0); put_f32(&b, 0);
    expect_error("huge_binary.ply", b.data, b.size, where);
    /* one vertex element record, then a face whose uint list length claims 4 billion indices */
    memset(&b, 0, sizeof b);
    put_text(&b, "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                 "element face 1\nproperty list uint int vertex_indices\nend_header\n");
    put_f32(&b, 0); put_f32(&b, 0); put_f32(&b, 0);
    snprintf(where, sizeof where, "byte offset %zu", b.size);
    put_uint(&b, 4000000000u, 4); put_uint(&b, 0, 4);
    expect_error("huge_list.ply", b.data, b.size, where);
    expect_text_error("negative_list.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                           "element face 1\nproperty list char int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n", "line 13");
    memset(&b, 0, sizeof b);
    put_text(&b, "solid but binary");
    b.size = 80;
    put_uint(&b, 1000000, 4);
    memset(b.data + b.size, 0, 50);
    b.size += 50;
    expect_error("huge_count.stl", b.data, b.size, "byte offset 80");
    expect_error("tiny.stl", "abc", 3, "byte offset 3");
}

static void test_other_failures(void)
{
    char err[512], small[12];
    voxgi_io_mesh m;
    const char *missing = tmp_path("does_not_exist.obj");
    TH_CHECK(voxgi_io_load_mesh(missing, &m, err, sizeof err) != 0 && strstr(err, missing) && strstr(err, "cannot open"), "missing file: %s", err);
    TH_CHECK(is_empty(&m), "mesh not left empty");
    TH_CHECK(voxgi_io_load_mesh(tmp_dir, &m, err, sizeof err) != 0 && strstr(err, "cannot read"), "directory: %s", err);
    expect_text_error("big_endian.ply", "ply\nformat binary_big_endian 1.0\nend_header\n", "line 2");
    expect_text_error("no_faces.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n",
                      "no face element");
    expect_text_error("no_end.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n", "endsolid");
    TH_CHECK(voxgi_io_load_mesh(write_text("bad.obj", "f 1 2 3\n"), &m, NULL, 0) != 0, "no error buffer");
    TH_CHECK(voxgi_io_load_mesh(write_text("bad.obj", "f 1 2 3\n"), &m, small, sizeof small) != 0 && strlen(small) == sizeof small - 1,
             "a small error buffer is filled and terminated");
    voxgi_io_mesh_free(NULL);
}

/* A 100k-triangle OBJ with v/vt/vn must load in linear time, measured as work rather than time:
   the corners' hash map may visit a few slots per corner on average (linear probing at most half
   full expects 2.5 for a new key, 1.5 for a known one), where a degraded hash or a scan visits
   thousands. */
static void test_large_obj(void)
{
    enum { N = 224 };
    const char *path = tmp_path("large.obj");
    FILE *f = fopen(path, "wb");
    voxgi_io_mesh m;
    unsigned long long before;
    double per_corner;
    int x, y;
    TH_CHECK(f != NULL, "cannot create %s", path);
    if (!f) return;
    if (created_count < 128) snprintf(created[created_count++], sizeof created[0], "large.obj");
    for (y = 0; y < N; y++)
        for (x = 0; x < N; x++) fprintf(f, "v %d %d %f\nvt %f %f\n", x, y, 0.001 * x * y, x / (double)N, y / (double)N);
    fprintf(f, "vn 0 0 1\n");
    for (y = 0; y + 1 < N; y++)
        for (x = 0; x + 1 < N; x++) {
            int a = y * N + x + 1, b = a + 1, c = a + N, d = c + 1;
            fprintf(f, "f %d/%d/1 %d/%d/1 %d/%d/1\nf %d/%d/1 %d/%d/1 %d/%d/1\n", a, a, b, b, d, d, a, a, d, d, c, c);
        }
    fclose(f);
    before = voxgi_io_probes();
    if (!load_ok(path, &m)) return;
    per_corner = (double)(voxgi_io_probes() - before) / (3.0 * (double)m.triangle_count);
    TH_CHECK(m.vertex_count == N * N && m.triangle_count == 2 * (N - 1) * (N - 1), "%zu vertices, %zu triangles", m.vertex_count, m.triangle_count);
    printf("    %zu corners: %.2f hash-map slots visited per corner\n", 3 * m.triangle_count, per_corner);
    TH_CHECK(per_corner < 4, "%.1f hash-map slots visited per corner: the corner map degraded", per_corner);
    voxgi_io_mesh_free(&m);
}

/* ---------------------------------------------------------------- glTF */

/* The test's own glTF writer: a JSON body (everything but asset and buffers) and one binary
   buffer, stored as a base64 data URI, an external .bin beside the .gltf, or a .glb. */
enum { GLTF_DATA_URI, GLTF_EXTERNAL, GLTF_GLB };
static const char *const gltf_container_names[3] = {"data URI", "external .bin", "glb"};

static void grow_f32(growing *g, float f) { unsigned char b[4]; uint32_t u; int k; memcpy(&u, &f, 4); for (k = 0; k < 4; k++) b[k] = (unsigned char)(u >> 8 * k); grow_put(g, b, 4); }
static void grow_uint(growing *g, uint32_t v, int n) { unsigned char b[4]; int k; for (k = 0; k < n; k++) b[k] = (unsigned char)(v >> 8 * k); grow_put(g, b, (size_t)n); }
static void grow_str(growing *g, const char *s) { grow_put(g, s, strlen(s)); }

static char *base64(const unsigned char *d, size_t n)
{
    static const char abc[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    char *out = (char *)malloc(4 * (n / 3 + 1) + 1), *o = out;
    size_t i;
    if (!out) { printf("out of memory\n"); exit(1); }
    for (i = 0; i < n; i += 3) {
        uint32_t v = (uint32_t)d[i] << 16 | (i + 1 < n ? (uint32_t)d[i + 1] << 8 : 0) | (i + 2 < n ? d[i + 2] : 0);
        *o++ = abc[v >> 18]; *o++ = abc[v >> 12 & 63];
        *o++ = i + 1 < n ? abc[v >> 6 & 63] : '=';
        *o++ = i + 2 < n ? abc[v & 63] : '=';
    }
    *o = 0;
    return out;
}

/* The whole JSON text (NUL-terminated in a growing), its buffer named by uri (NULL: a data URI;
   "": none, the glb's BIN chunk). */
static growing gltf_json(const char *body, const growing *bin, const char *uri)
{
    growing j = {0, 0, 0};
    grow_str(&j, "{\"asset\":{\"version\":\"2.0\"},");
    grow_str(&j, body); /* may be longer than grow_printf's line */
    grow_printf(&j, ",\"buffers\":[{\"byteLength\":%lu", (unsigned long)bin->size);
    if (!uri) {
        char *b = base64(bin->data, bin->size);
        grow_str(&j, ",\"uri\":\"data:application/octet-stream;base64,");
        grow_str(&j, b);
        grow_str(&j, "\"");
        free(b);
    } else if (*uri) grow_printf(&j, ",\"uri\":\"%s\"", uri);
    grow_str(&j, "}]}");
    grow_put(&j, "", 1);
    j.size--;
    return j;
}

static growing glb_image(const growing *json, const growing *bin)
{
    growing g = {0, 0, 0};
    size_t json_len = (json->size + 3) & ~(size_t)3, bin_len = (bin->size + 3) & ~(size_t)3;
    grow_str(&g, "glTF");
    grow_uint(&g, 2, 4);
    grow_uint(&g, (uint32_t)(12 + 8 + json_len + 8 + bin_len), 4);
    grow_uint(&g, (uint32_t)json_len, 4);
    grow_str(&g, "JSON");
    grow_put(&g, json->data, json->size);
    while (g.size % 4) grow_str(&g, " ");
    grow_uint(&g, (uint32_t)bin_len, 4);
    grow_put(&g, "BIN", 4);
    grow_put(&g, bin->data, bin->size);
    while (g.size % 4) grow_put(&g, "", 1);
    return g;
}

/* Writes name.gltf (with name.bin when external) or name.glb and returns its path. */
static const char *write_gltf(const char *name, const char *body, const growing *bin, int container)
{
    char file[64], bin_name[64];
    growing j, glb;
    const char *path;
    snprintf(bin_name, sizeof bin_name, "%s.bin", name);
    snprintf(file, sizeof file, "%s.%s", name, container == GLTF_GLB ? "glb" : "gltf");
    j = gltf_json(body, bin, container == GLTF_DATA_URI ? NULL : container == GLTF_EXTERNAL ? bin_name : "");
    if (container == GLTF_GLB) {
        glb = glb_image(&j, bin);
        path = write_file(file, glb.data, glb.size);
        free(glb.data);
    } else {
        if (container == GLTF_EXTERNAL) write_file(bin_name, bin->data, bin->size);
        path = write_file(file, j.data, j.size);
    }
    free(j.data);
    return path;
}

/* The test's vertices: distinct, exact in float, and each preceded by a 4-byte pad that must be
   skipped (accessor byteOffset 4, byteStride 16). */
static void gltf_vertex(size_t i, float v[3]) { v[0] = 0.5f * (float)i; v[1] = (float)(i % 17) - 8.0f; v[2] = 1.0f / (float)(1 + i); }
static void grow_padded_vertices(growing *bin, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        float v[3];
        gltf_vertex(i, v);
        grow_f32(bin, -999.0f);
        grow_f32(bin, v[0]); grow_f32(bin, v[1]); grow_f32(bin, v[2]);
    }
}
static uint32_t gltf_corner(size_t t, int k, size_t n) { return (uint32_t)(k == 0 ? t : k == 1 ? n - 1 - t : (t * 37 + 5) % n); }

/* Each index type (uint8 with 200 vertices, uint16 and uint32 with 300, so indices above 255
   exist) and no indices, each in each container (data URI, external .bin, .glb): 12 loads. The
   positions come through an accessor with byteOffset 4 and byteStride 16; every position and
   every index must arrive exactly as the test wrote it (float equality; no transform). */
static void test_gltf_index_types(void)
{
    static const unsigned types[4] = {5121, 5123, 5125, 0};
    int ti, c;
    for (ti = 0; ti < 4; ti++)
        for (c = 0; c < 3; c++) {
            size_t n = types[ti] == 5121 ? 200 : 300, tris = 100, i, index_size = types[ti] == 5121 ? 1 : types[ti] == 5123 ? 2 : 4;
            size_t vertex_count = types[ti] ? n : 3 * tris, bad = 0;
            growing bin = {0, 0, 0};
            char body[1024], name[32];
            voxgi_io_mesh m;
            grow_padded_vertices(&bin, vertex_count);
            if (types[ti]) {
                for (i = 0; i < 3 * tris; i++) grow_uint(&bin, gltf_corner(i / 3, (int)(i % 3), n), (int)index_size);
                while (bin.size % 4) grow_put(&bin, "", 1);
                snprintf(body, sizeof body,
                         "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
                         "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":4}]}],"
                         "\"bufferViews\":[{\"buffer\":0,\"byteLength\":%lu,\"byteStride\":16},{\"buffer\":0,\"byteOffset\":%lu,\"byteLength\":%lu}],"
                         "\"accessors\":[{\"bufferView\":0,\"byteOffset\":4,\"componentType\":5126,\"count\":%lu,\"type\":\"VEC3\"},"
                         "{\"bufferView\":1,\"componentType\":%u,\"count\":%lu,\"type\":\"SCALAR\"}]",
                         (unsigned long)(16 * vertex_count), (unsigned long)(16 * vertex_count), (unsigned long)(bin.size - 16 * vertex_count),
                         (unsigned long)vertex_count, types[ti], (unsigned long)(3 * tris));
            } else
                snprintf(body, sizeof body,
                         "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
                         "\"bufferViews\":[{\"buffer\":0,\"byteLength\":%lu,\"byteStride\":16}],"
                         "\"accessors\":[{\"bufferView\":0,\"byteOffset\":4,\"componentType\":5126,\"count\":%lu,\"type\":\"VEC3\"}]",
                         (unsigned long)bin.size, (unsigned long)vertex_count);
            snprintf(name, sizeof name, "index%u_%d", types[ti], c);
            if (!load_ok(write_gltf(name, body, &bin, c), &m)) { free(bin.data); continue; }
            TH_CHECK(m.vertex_count == vertex_count && m.triangle_count == tris && m.material_count == 1, "%s (%s): %zu vertices, %zu triangles, %zu materials",
                     name, gltf_container_names[c], m.vertex_count, m.triangle_count, m.material_count);
            for (i = 0; m.vertex_count == vertex_count && i < vertex_count; i++) {
                float v[3];
                gltf_vertex(i, v);
                bad += m.positions[3 * i] != v[0] || m.positions[3 * i + 1] != v[1] || m.positions[3 * i + 2] != v[2];
            }
            for (i = 0; m.triangle_count == tris && i < 3 * tris; i++)
                bad += m.indices[i] != (types[ti] ? gltf_corner(i / 3, (int)(i % 3), n) : (uint32_t)i);
            TH_CHECK(bad == 0, "%s (%s): %zu positions or indices differ from those written", name, gltf_container_names[c], bad);
            voxgi_io_mesh_free(&m);
            free(bin.data);
        }
}

/* Rotates v by the unit quaternion q (x, y, z, w): v + 2 w (q x v) + 2 q x (q x v), a route
   independent of the loader's rotation matrix. */
static void quat_rotate(const double q[4], const double v[3], double out[3])
{
    double c1[3], c2[3];
    int k;
    c1[0] = q[1] * v[2] - q[2] * v[1]; c1[1] = q[2] * v[0] - q[0] * v[2]; c1[2] = q[0] * v[1] - q[1] * v[0];
    c2[0] = q[1] * c1[2] - q[2] * c1[1]; c2[1] = q[2] * c1[0] - q[0] * c1[2]; c2[2] = q[0] * c1[1] - q[1] * c1[0];
    for (k = 0; k < 3; k++) out[k] = v[k] + 2 * q[3] * c1[k] + 2 * c2[k];
}

/* A scene of three nodes over one mesh (two triangles, no indices, a normal per vertex): node 0 has
   translation (1, -2, 3), rotation 0.7 rad about (1, 2, 2)/3 and scale (2, 0.5, 1.5); its child
   node 1 has a matrix (90 degrees about z, x scaled by 3, then moved by (0.5, 0, -1)); node 2 is
   another root, mirrored in x and moved by (100, 0, 0), outside the scene. The test transforms the vertices itself
   in double precision (scale, quaternion rotation, translation; the child's matrix first):
   positions within 1e-5 relative, normals (the inverse transpose: rotation of n / scale, the
   child's x component over 3 before its turn) within 1e-5. With the scene, node 2 is not loaded (4
   triangles); without any scene every root is (6), node 2's mirrored triangles with their last two
   corners swapped so that they still face the way their normals do. */
static void test_gltf_node_transforms(void)
{
    static const float tri[6][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.25f, -0.5f, 2}, {-1, 3, 0.5f}, {2, 2, -2}};
    const double half = 0.35, t0[3] = {1, -2, 3}, s0[3] = {2, 0.5, 1.5}, nrm[3] = {0.48, 0.6, 0.64};
    double q[4] = {sin(half) / 3, 2 * sin(half) / 3, 2 * sin(half) / 3, cos(half)};
    growing bin = {0, 0, 0};
    char body[2048];
    int with_scene;
    size_t i;
    for (i = 0; i < 6; i++) { grow_f32(&bin, tri[i][0]); grow_f32(&bin, tri[i][1]); grow_f32(&bin, tri[i][2]); }
    for (i = 0; i < 6; i++) { grow_f32(&bin, (float)nrm[0]); grow_f32(&bin, (float)nrm[1]); grow_f32(&bin, (float)nrm[2]); }
    for (with_scene = 1; with_scene >= 0; with_scene--) {
        voxgi_io_mesh m;
        double worst_p = 0, worst_n = 0;
        size_t expect_tris = with_scene ? 4 : 6;
        snprintf(body, sizeof body,
                 "%s\"nodes\":[{\"mesh\":0,\"children\":[1],\"translation\":[1,-2,3],\"rotation\":[%.17g,%.17g,%.17g,%.17g],\"scale\":[2,0.5,1.5]},"
                 "{\"mesh\":0,\"matrix\":[0,3,0,0, -1,0,0,0, 0,0,1,0, 0.5,0,-1,1]},{\"mesh\":0,\"translation\":[100,0,0],\"scale\":[-1,1,1]}],"
                 "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1}}]}],"
                 "\"bufferViews\":[{\"buffer\":0,\"byteLength\":72},{\"buffer\":0,\"byteOffset\":72,\"byteLength\":72}],"
                 "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":6,\"type\":\"VEC3\"},{\"bufferView\":1,\"componentType\":5126,\"count\":6,\"type\":\"VEC3\"}]",
                 with_scene ? "\"scene\":0,\"scenes\":[{\"nodes\":[0]}]," : "", q[0], q[1], q[2], q[3]);
        if (!load_ok(write_gltf(with_scene ? "nodes_scene" : "nodes_roots", body, &bin, GLTF_DATA_URI), &m)) continue;
        TH_CHECK(m.triangle_count == expect_tris && m.vertex_count == 3 * expect_tris && m.normals, "%s scene: %zu triangles, %zu vertices, normals %s",
                 with_scene ? "with a" : "without", m.triangle_count, m.vertex_count, m.normals ? "present" : "missing");
        for (i = 0; m.vertex_count == 3 * expect_tris && m.normals && i < m.vertex_count; i++) {
            double p[3] = {tri[i % 6][0], tri[i % 6][1], tri[i % 6][2]}, n[3] = {nrm[0], nrm[1], nrm[2]}, scaled[3], e[3], en[3], len;
            int k;
            if (i >= 12) { p[0] = 100 - p[0]; n[0] = -n[0]; } /* node 2: a mirror in x, then a move */
            else {
                if (i >= 6) { /* node 1's matrix: x' = -y + 0.5, y' = 3x, z' = z - 1; its normals: (-n.y, n.x / 3, n.z) */
                    double x = p[0], nx = n[0];
                    p[0] = -p[1] + 0.5; p[1] = 3 * x; p[2] = p[2] - 1;
                    n[0] = -n[1]; n[1] = nx / 3;
                }
                for (k = 0; k < 3; k++) scaled[k] = p[k] * s0[k];
                quat_rotate(q, scaled, e);
                for (k = 0; k < 3; k++) p[k] = e[k] + t0[k];
                for (k = 0; k < 3; k++) scaled[k] = n[k] / s0[k];
                quat_rotate(q, scaled, n);
            }
            len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (k = 0; k < 3; k++) en[k] = n[k] / len;
            for (k = 0; k < 3; k++) {
                double dp = fabs(m.positions[3 * i + (size_t)k] - p[k]) / (1 + fabs(p[k])), dn = fabs(m.normals[3 * i + (size_t)k] - en[k]);
                if (dp > worst_p) worst_p = dp;
                if (dn > worst_n) worst_n = dn;
            }
        }
        if (!with_scene && m.triangle_count == 6)
            TH_CHECK(m.indices[12] == 12 && m.indices[13] == 14 && m.indices[14] == 13 && m.indices[15] == 15 && m.indices[16] == 17 && m.indices[17] == 16,
                     "the mirrored node's triangles keep their winding: %u %u %u", m.indices[12], m.indices[13], m.indices[14]);
        printf("    %s scene: worst position error %.2g (relative), worst normal error %.2g\n", with_scene ? "with a" : "without", worst_p, worst_n);
        TH_CHECK(worst_p < 1e-5 && worst_n < 1e-5, "%s scene: positions off by %g, normals by %g", with_scene ? "with a" : "without", worst_p, worst_n);
        voxgi_io_mesh_free(&m);
    }
    free(bin.data);
}

/* Three primitives over one triangle: the first takes material 1 (base colour (0.9, 0.1, 0.3),
   alpha 0.3 ignored as OPAQUE is the default), the second material 0 (base colour (0.2, 0.4, 0.6)
   with alpha 0.5 in BLEND mode, emissive (1, 0.5, 0.25) times KHR_materials_emissive_strength 4),
   the third none (glTF's default: white, opaque). Each must arrive on its triangle, and the scene's
   materials carry the same albedo, emission (4, 2, 1) and transparency (0.5, 0, 0). */
static void test_gltf_materials(void)
{
    growing bin = {0, 0, 0};
    voxgi_io_mesh m;
    const voxgi_io_material *a, *b, *d;
    grow_f32(&bin, 0); grow_f32(&bin, 0); grow_f32(&bin, 0);
    grow_f32(&bin, 1); grow_f32(&bin, 0); grow_f32(&bin, 0);
    grow_f32(&bin, 0); grow_f32(&bin, 1); grow_f32(&bin, 0);
    if (!load_ok(write_gltf("materials",
                            "\"extensionsUsed\":[\"KHR_materials_emissive_strength\"],\"extensionsRequired\":[\"KHR_materials_emissive_strength\"],"
                            "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"material\":1},"
                            "{\"attributes\":{\"POSITION\":0},\"material\":0},{\"attributes\":{\"POSITION\":0}}]}],"
                            "\"materials\":[{\"name\":\"glow\",\"alphaMode\":\"BLEND\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.2,0.4,0.6,0.5]},"
                            "\"emissiveFactor\":[1,0.5,0.25],\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":4}}},"
                            "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.9,0.1,0.3,0.3],\"metallicFactor\":0}}],"
                            "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}]",
                            &bin, GLTF_GLB), &m)) { free(bin.data); return; }
    free(bin.data);
    TH_CHECK(m.triangle_count == 3 && m.material_count == 3, "%zu triangles, %zu materials", m.triangle_count, m.material_count);
    if (m.triangle_count != 3 || m.material_count != 3) { voxgi_io_mesh_free(&m); return; }
    TH_CHECK(m.material_ids[0] == 1 && m.material_ids[1] == 0 && m.material_ids[2] == 2, "material ids %u %u %u", m.material_ids[0], m.material_ids[1], m.material_ids[2]);
    a = &m.materials[0]; b = &m.materials[1]; d = &m.materials[2];
    TH_CHECK(!strcmp(a->name, "glow") && near(a->albedo[0], 0.2f) && near(a->albedo[1], 0.4f) && near(a->albedo[2], 0.6f) && near(a->opacity, 0.5f),
             "glow: %s albedo %g %g %g opacity %g", a->name, a->albedo[0], a->albedo[1], a->albedo[2], a->opacity);
    TH_CHECK(near(a->emission[0], 4) && near(a->emission[1], 2) && near(a->emission[2], 1), "glow: emission %g %g %g", a->emission[0], a->emission[1], a->emission[2]);
    TH_CHECK(near(b->albedo[0], 0.9f) && near(b->albedo[1], 0.1f) && near(b->albedo[2], 0.3f) && b->opacity == 1 && b->emission[0] == 0,
             "material 1: albedo %g %g %g opacity %g emission %g", b->albedo[0], b->albedo[1], b->albedo[2], b->opacity, b->emission[0]);
    TH_CHECK(d->albedo[0] == 1 && d->albedo[1] == 1 && d->albedo[2] == 1 && d->opacity == 1 && d->emission[1] == 0, "default: albedo %g opacity %g", d->albedo[0], d->opacity);
    TH_CHECK(near(m.scene_materials[0].emission[0], 4) && near(m.scene_materials[0].albedo[2], 0.6f) && near(m.scene_materials[0].transparency, 0.5f) &&
             m.scene_materials[1].transparency == 0, "scene materials: emission %g albedo %g transparency %g %g", m.scene_materials[0].emission[0],
             m.scene_materials[0].albedo[2], m.scene_materials[0].transparency, m.scene_materials[1].transparency);
    voxgi_io_mesh_free(&m);
}

/* A one-triangle mesh (indices uint16 0 1 2) for the failure tests, as a complete JSON text. */
static const char gltf_small_body[] =
    "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
    "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":36,\"byteLength\":6}],"
    "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}]";
static growing gltf_small_bin(uint32_t last_index)
{
    growing bin = {0, 0, 0};
    grow_f32(&bin, 0); grow_f32(&bin, 0); grow_f32(&bin, 0);
    grow_f32(&bin, 1); grow_f32(&bin, 0); grow_f32(&bin, 0);
    grow_f32(&bin, 0); grow_f32(&bin, 1); grow_f32(&bin, 0);
    grow_uint(&bin, 0, 2); grow_uint(&bin, 1, 2); grow_uint(&bin, last_index, 2);
    grow_uint(&bin, 0, 2);
    return bin;
}

/* The glTF text with `from` replaced by `to` (its first occurrence) must fail with `expect` in the message. */
static void expect_text_edit_error(const char *name, const growing *text, const char *from, const char *to, const char *expect)
{
    growing edited = {0, 0, 0};
    const char *at = strstr((const char *)text->data, from);
    TH_CHECK(at != NULL, "%s: '%s' not in the file", name, from);
    if (at) {
        grow_put(&edited, text->data, (size_t)(at - (const char *)text->data));
        grow_str(&edited, to);
        grow_str(&edited, at + strlen(from));
        expect_error(name, edited.data, edited.size, expect);
    }
    free(edited.data);
}

/* The small file with `from` replaced by `to` (once) must fail with `expect` in the message. */
static void expect_gltf_edit_error(const char *name, const char *from, const char *to, const char *expect)
{
    growing bin = gltf_small_bin(2), j = gltf_json(gltf_small_body, &bin, NULL);
    expect_text_edit_error(name, &j, from, to, expect);
    free(j.data);
    free(bin.data);
}

/* Buffer URIs: a percent-encoded name beside the file loads; "..", an absolute path, a scheme and
   a missing file are refused by name; a bad base64 character is refused at its byte offset. */
static void test_gltf_buffer_uris(void)
{
    growing bin = gltf_small_bin(2), j = gltf_json(gltf_small_body, &bin, "my%20data.bin");
    voxgi_io_mesh m;
    char expect[64];
    size_t at;
    write_file("my data.bin", bin.data, bin.size);
    if (load_ok(write_file("encoded.gltf", j.data, j.size), &m)) {
        TH_CHECK(m.triangle_count == 1 && m.positions[3] == 1 && m.positions[7] == 1, "%zu triangles", m.triangle_count);
        voxgi_io_mesh_free(&m);
    }
    free(j.data);
    free(bin.data);
    expect_gltf_edit_error("parent.gltf", "data:application/octet-stream;base64,", "../x.bin?", "'..'");
    expect_gltf_edit_error("absolute.gltf", "data:application/octet-stream;base64,", "/x.bin?", "absolute");
    expect_gltf_edit_error("scheme.gltf", "data:application/octet-stream;base64,", "http://example.com/x?", "absolute or has a scheme");
    expect_gltf_edit_error("missing.gltf", "data:application/octet-stream;base64,", "missing", "cannot open");
    bin = gltf_small_bin(2);
    j = gltf_json(gltf_small_body, &bin, NULL);
    at = (size_t)(strstr((const char *)j.data, "base64,") - (const char *)j.data) + 7 + 5;
    j.data[at] = '!';
    snprintf(expect, sizeof expect, "byte offset %lu: buffers[0]: bad base64", (unsigned long)at);
    expect_error("bad_base64.gltf", j.data, j.size, expect);
    free(j.data);
    free(bin.data);
}

/* Hostile and unsupported glTF: every prefix of a valid .glb fails with a byte offset (a cut
   header or chunk: "truncated glb" at the file's size); bad JSON at the offset of the defect; an
   index out of range; a sparse accessor without indices; each unsupported feature by name; nesting
   100000 deep; a node cycle; and 3000 random corruptions of the .glb and .gltf load or fail
   cleanly (under ASan). */
static void test_gltf_bad_files(void)
{
    growing bin = gltf_small_bin(2), j = gltf_json(gltf_small_body, &bin, ""), glb = glb_image(&j, &bin), deep = {0, 0, 0};
    growing text = gltf_json(gltf_small_body, &bin, NULL);
    voxgi_io_mesh m;
    char expect[96], err[512];
    size_t n, i, at;
    int k;
    if (load_ok(write_file("small.glb", glb.data, glb.size), &m)) voxgi_io_mesh_free(&m);
    for (n = 0; n < glb.size; n++) {
        snprintf(expect, sizeof expect, n >= 12 ? "byte offset %lu: truncated glb" : "byte offset", (unsigned long)n);
        expect_error("cut.glb", glb.data, n, expect);
    }
    for (i = 0; i < 3000; i++) {
        growing *src = i % 2 ? &glb : &text;
        unsigned char *copy = (unsigned char *)malloc(src->size);
        memcpy(copy, src->data, src->size);
        for (k = 0; k < 1 + (int)(rng() % 4); k++) copy[rng() % src->size] = (unsigned char)rng();
        write_file(i % 2 ? "fuzz.glb" : "fuzz.gltf", copy, src->size);
        if (voxgi_io_load_mesh(tmp_path(i % 2 ? "fuzz.glb" : "fuzz.gltf"), &m, err, sizeof err) == 0) { check_consistent(&m, "fuzz"); voxgi_io_mesh_free(&m); }
        else TH_CHECK(is_empty(&m) && strstr(err, "fuzz"), "a failed load: %s", err);
        free(copy);
    }
    at = (size_t)(strstr((const char *)text.data, ",\"meshes\"") - (const char *)text.data);
    text.data[at] = ';';
    snprintf(expect, sizeof expect, "byte offset %lu: malformed JSON: expected ',' or '}'", (unsigned long)at);
    expect_error("bad_json.gltf", text.data, text.size, expect);
    expect_text_error("cut_json.gltf", "{\"asset\":{\"version\":\"2.0\"", "byte offset 25: malformed JSON");
    expect_text_error("not_gltf.gltf", "{\"asset\":{}}", "no asset.version");
    expect_text_error("version3.gltf", "{\"asset\":{\"version\":\"3.0\"}}", "byte offset 20: glTF version 3.0 is not supported");
    for (n = 0; n < 100000; n++) grow_str(&deep, "[");
    expect_error("deep.gltf", deep.data, deep.size, "byte offset 64: malformed JSON: nested deeper than 64 levels");
    expect_gltf_edit_error("lines.gltf", "\"indices\":1", "\"indices\":1,\"mode\":1", "primitive mode 1 (lines) is not supported");
    expect_gltf_edit_error("strip.gltf", "\"indices\":1", "\"indices\":1,\"mode\":5", "primitive mode 5 (triangle strip) is not supported");
    expect_gltf_edit_error("sparse.gltf", "\"type\":\"VEC3\"", "\"type\":\"VEC3\",\"sparse\":{\"count\":1}", "accessors[0].sparse has no indices");
    expect_gltf_edit_error("draco.gltf", "\"nodes\"", "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],\"nodes\"", "Draco compression");
    expect_gltf_edit_error("meshopt.gltf", "\"nodes\"", "\"extensionsRequired\":[\"EXT_meshopt_compression\"],\"nodes\"", "meshopt compression");
    expect_gltf_edit_error("required.gltf", "\"nodes\"", "\"extensionsRequired\":[\"KHR_texture_basisu\"],\"nodes\"", "requires extension KHR_texture_basisu");
    expect_gltf_edit_error("int_positions.gltf", "\"componentType\":5126", "\"componentType\":5122", "only float VEC3");
    expect_gltf_edit_error("overrun.gltf", "\"count\":3,\"type\":\"VEC3\"", "\"count\":4,\"type\":\"VEC3\"", "overrun bufferViews[0]");
    expect_gltf_edit_error("no_buffer.gltf", "\"byteOffset\":36,\"byteLength\":6", "\"byteOffset\":36,\"byteLength\":60", "lie outside buffers[0]");
    expect_gltf_edit_error("cycle.gltf", "\"nodes\":[{\"mesh\":0}]", "\"nodes\":[{\"mesh\":0,\"children\":[1]},{\"children\":[0]}],\"scenes\":[{\"nodes\":[0]}]", "reached twice");
    expect_gltf_edit_error("bad_child.gltf", "\"nodes\":[{\"mesh\":0}]", "\"nodes\":[{\"mesh\":0,\"children\":[7]}]", "child that does not exist");
    bin.data[40] = 3; /* the last index, 2, becomes 3 of 3 vertices */
    free(text.data);
    text = gltf_json(gltf_small_body, &bin, NULL);
    expect_error("out_of_range.gltf", text.data, text.size, "index 3 (element 2 of accessors[1]) is out of range: the primitive has 3 vertices");
    glb.data[4] = 3;
    expect_error("version.glb", glb.data, glb.size, "byte offset 4: glb version 3");
    glb.data[4] = 2;
    glb.data[12] = 0xF0; /* the JSON chunk's length runs past the end */
    expect_error("chunk.glb", glb.data, glb.size, "byte offset 12: truncated glb: a chunk");
    free(deep.data);
    free(text.data);
    free(glb.data);
    free(j.data);
    free(bin.data);
}

/* ---- sparse accessors and accessors without a bufferView ---- */

/* The sparse tests' replacement values: exact in float and unlike any gltf_vertex. */
static void sparse_value(size_t j, float v[3]) { v[0] = 100.0f + (float)j; v[1] = -50.0f - (float)j; v[2] = 0.25f * (float)(j + 1); }

/* A glTF text (data URI) of one primitive without indices whose POSITION accessor (count vertices)
   is sparse. Its base: the padded gltf_vertex data (byteOffset 4, byteStride 16), or no
   bufferView without has_base. Its n sparse indices at[], of componentType index_type, lie behind
   4 junk bytes (sparse.indices.byteOffset 4) and the values sparse_value(0..n-1) behind 12
   (sparse.values.byteOffset 12), each in its own bufferView, the values' values_cut bytes short;
   sparse.count is sparse_count. */
static growing sparse_positions_gltf(int has_base, size_t count, unsigned index_type, const uint32_t *at, size_t n, size_t sparse_count, size_t values_cut)
{
    growing bin = {0, 0, 0}, text;
    size_t index_size = index_type == 5121 ? 1 : index_type == 5123 ? 2 : 4, indices_at, values_at, i;
    char body[1024];
    grow_padded_vertices(&bin, count);
    indices_at = bin.size;
    grow_uint(&bin, 0xEEEEEEEEu, 4);
    for (i = 0; i < n; i++) grow_uint(&bin, at[i], (int)index_size);
    while (bin.size % 4) grow_put(&bin, "", 1);
    values_at = bin.size;
    for (i = 0; i < 3; i++) grow_f32(&bin, -777.0f);
    for (i = 0; i < n; i++) {
        float v[3];
        sparse_value(i, v);
        grow_f32(&bin, v[0]); grow_f32(&bin, v[1]); grow_f32(&bin, v[2]);
    }
    snprintf(body, sizeof body,
             "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteLength\":%lu,\"byteStride\":16},{\"buffer\":0,\"byteOffset\":%lu,\"byteLength\":%lu},"
             "{\"buffer\":0,\"byteOffset\":%lu,\"byteLength\":%lu}],"
             "\"accessors\":[{%s\"componentType\":5126,\"count\":%lu,\"type\":\"VEC3\",\"sparse\":{\"count\":%lu,"
             "\"indices\":{\"bufferView\":1,\"byteOffset\":4,\"componentType\":%u},\"values\":{\"bufferView\":2,\"byteOffset\":12}}}]",
             (unsigned long)(16 * count), (unsigned long)indices_at, (unsigned long)(4 + n * index_size), (unsigned long)values_at,
             (unsigned long)(12 + 12 * n - values_cut), has_base ? "\"bufferView\":0,\"byteOffset\":4," : "", (unsigned long)count,
             (unsigned long)sparse_count, index_type);
    text = gltf_json(body, &bin, NULL);
    free(bin.data);
    return text;
}

/* Loads sparse_positions_gltf's file: position i must be sparse_value(j) where at[j] == i, else
   its base (gltf_vertex(i), or zero without has_base), exactly; the triangles 0 1 2, 3 4 5, ... */
static void check_sparse_positions(const char *name, int has_base, size_t count, unsigned index_type, const uint32_t *at, size_t n)
{
    growing text = sparse_positions_gltf(has_base, count, index_type, at, n, n, 0);
    voxgi_io_mesh m;
    size_t i, j, bad = 0;
    int ok = load_ok(write_file(name, text.data, text.size), &m);
    free(text.data);
    if (!ok) return;
    TH_CHECK(m.vertex_count == count && m.triangle_count == count / 3, "%s: %zu vertices, %zu triangles", name, m.vertex_count, m.triangle_count);
    for (i = 0; m.vertex_count == count && m.triangle_count == count / 3 && i < count; i++) {
        float v[3] = {0, 0, 0};
        if (has_base) gltf_vertex(i, v);
        for (j = 0; j < n; j++)
            if (at[j] == i) sparse_value(j, v);
        bad += m.positions[3 * i] != v[0] || m.positions[3 * i + 1] != v[1] || m.positions[3 * i + 2] != v[2] || m.indices[i] != i;
    }
    TH_CHECK(bad == 0, "%s: %zu vertices differ from those written", name, bad);
    voxgi_io_mesh_free(&m);
}

/* Sparse POSITION accessors: a triangle given wholly by the sparse values over no bufferView (zeros
   beneath); six zero vertices of which three are replaced; and six vertices in a strided
   bufferView with one replaced (uint8 sparse indices), two (uint16) and three (uint32). */
static void test_gltf_sparse_positions(void)
{
    static const uint32_t all3[3] = {0, 1, 2}, three[3] = {1, 2, 4}, one[1] = {4}, two[2] = {0, 5};
    check_sparse_positions("sparse_triangle.gltf", 0, 3, 5121, all3, 3);
    check_sparse_positions("sparse_on_zeros.gltf", 0, 6, 5125, three, 3);
    check_sparse_positions("sparse_uint8.gltf", 1, 6, 5121, one, 1);
    check_sparse_positions("sparse_uint16.gltf", 1, 6, 5123, two, 2);
    check_sparse_positions("sparse_uint32.gltf", 1, 6, 5125, three, 3);
}

/* Sparse index accessors: two primitives over six packed vertices; the first's indices, uint16
   0 1 2 3 4 5 in a bufferView, have elements 1 and 5 replaced by 5 and 1 (uint8 sparse indices,
   uint16 values); the second's, uint32 without a bufferView (zeros), have elements 1 2 4 5
   replaced by 1 2 4 5 (uint8 sparse indices, uint32 values). The mesh's indices: 0 5 2 3 4 1,
   then the second primitive's vertices (6..11) by 0 1 2 0 4 5. */
static void test_gltf_sparse_indices(void)
{
    static const uint32_t expect[12] = {0, 5, 2, 3, 4, 1, 6, 7, 8, 6, 10, 11};
    growing bin = {0, 0, 0};
    voxgi_io_mesh m;
    size_t i, bad = 0;
    for (i = 0; i < 6; i++) {
        float v[3];
        gltf_vertex(i, v);
        grow_f32(&bin, v[0]); grow_f32(&bin, v[1]); grow_f32(&bin, v[2]);
    }
    for (i = 0; i < 6; i++) grow_uint(&bin, (uint32_t)i, 2);                        /* 72: dense indices */
    grow_uint(&bin, 1, 1); grow_uint(&bin, 5, 1); grow_uint(&bin, 0, 2);            /* 84: sparse indices, 2 bytes */
    grow_uint(&bin, 5, 2); grow_uint(&bin, 1, 2);                                   /* 88: their values */
    grow_uint(&bin, 1, 1); grow_uint(&bin, 2, 1); grow_uint(&bin, 4, 1); grow_uint(&bin, 5, 1); /* 92 */
    grow_uint(&bin, 1, 4); grow_uint(&bin, 2, 4); grow_uint(&bin, 4, 4); grow_uint(&bin, 5, 4); /* 96 */
    if (!load_ok(write_gltf("sparse_indices", "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1},"
                            "{\"attributes\":{\"POSITION\":0},\"indices\":2}]}],"
                            "\"bufferViews\":[{\"buffer\":0,\"byteLength\":72},{\"buffer\":0,\"byteOffset\":72,\"byteLength\":12},"
                            "{\"buffer\":0,\"byteOffset\":84,\"byteLength\":2},{\"buffer\":0,\"byteOffset\":88,\"byteLength\":4},"
                            "{\"buffer\":0,\"byteOffset\":92,\"byteLength\":4},{\"buffer\":0,\"byteOffset\":96,\"byteLength\":16}],"
                            "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":6,\"type\":\"VEC3\"},"
                            "{\"bufferView\":1,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\",\"sparse\":{\"count\":2,"
                            "\"indices\":{\"bufferView\":2,\"componentType\":5121},\"values\":{\"bufferView\":3}}},"
                            "{\"componentType\":5125,\"count\":6,\"type\":\"SCALAR\",\"sparse\":{\"count\":4,"
                            "\"indices\":{\"bufferView\":4,\"componentType\":5121},\"values\":{\"bufferView\":5}}}]",
                            &bin, GLTF_GLB), &m)) { free(bin.data); return; }
    free(bin.data);
    TH_CHECK(m.vertex_count == 12 && m.triangle_count == 4, "%zu vertices, %zu triangles", m.vertex_count, m.triangle_count);
    for (i = 0; m.triangle_count == 4 && i < 12; i++) bad += m.indices[i] != expect[i];
    TH_CHECK(bad == 0, "%zu indices differ: %u %u %u %u %u %u, %u %u %u %u %u %u", bad, m.indices[0], m.indices[1], m.indices[2], m.indices[3],
             m.indices[4], m.indices[5], m.indices[6], m.indices[7], m.indices[8], m.indices[9], m.indices[10], m.indices[11]);
    voxgi_io_mesh_free(&m);
}

/* A POSITION accessor without a bufferView and without sparse: six vertices, all (0, 0, 0). The
   loader keeps degenerate triangles as they are (a point is what voxgi voxelizes of it), so it
   gives 6 vertices at the origin and 2 triangles 0 1 2, 3 4 5; its count, componentType and type
   are still checked, and a count of zeros beyond the file's bytes (3e9) is refused. */
static void test_gltf_zero_accessor(void)
{
    static const char body[] = "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
                               "\"accessors\":[{\"componentType\":5126,\"count\":6,\"type\":\"VEC3\"}]";
    growing bin = {0, 0, 0}, text;
    voxgi_io_mesh m;
    size_t i, bad = 0;
    grow_uint(&bin, 0, 4);
    text = gltf_json(body, &bin, NULL);
    if (load_ok(write_file("zeros.gltf", text.data, text.size), &m)) {
        TH_CHECK(m.vertex_count == 6 && m.triangle_count == 2, "%zu vertices, %zu triangles", m.vertex_count, m.triangle_count);
        for (i = 0; m.vertex_count == 6 && m.triangle_count == 2 && i < 6; i++)
            bad += m.positions[3 * i] != 0 || m.positions[3 * i + 1] != 0 || m.positions[3 * i + 2] != 0 || m.indices[i] != i;
        TH_CHECK(bad == 0, "%zu vertices are not at the origin or out of order", bad);
        voxgi_io_mesh_free(&m);
    }
    expect_text_edit_error("zeros_int.gltf", &text, "\"componentType\":5126", "\"componentType\":5123", "only float VEC3");
    expect_text_edit_error("zeros_vec2.gltf", &text, "\"VEC3\"", "\"VEC2\"", "only float VEC3");
    expect_text_edit_error("zeros_empty.gltf", &text, "\"count\":6", "\"count\":0", "accessors[0] has no elements");
    expect_text_edit_error("zeros_huge.gltf", &text, "\"count\":6", "\"count\":3000000000", "accessors[0] has no bufferView and 3000000000 elements");
    free(text.data);
    free(bin.data);
}

/* Sparse accessors the specification forbids, each refused naming the accessor's sparse part:
   indices that decrease (at the byte offset of sparse.indices) or repeat, an index equal to the
   count, values or indices overrunning their bufferView, sparse.count 0 or above the count, an
   index type that is not an unsigned integer, a byteStride on a sparse bufferView; and 1000 random
   corruptions of a sparse file load or fail cleanly (under ASan). */
static void test_gltf_sparse_refused(void)
{
    static const uint32_t down[2] = {2, 1}, same[2] = {3, 3}, at_count[2] = {1, 6}, fine[2] = {1, 4};
    growing text = sparse_positions_gltf(1, 6, 5123, down, 2, 2, 0);
    voxgi_io_mesh m;
    char expect[160], err[512];
    size_t i;
    int k;
    snprintf(expect, sizeof expect, "byte offset %lu: accessors[0].sparse.indices: index 1 (element 1) does not follow 2: sparse indices must increase",
             (unsigned long)(strstr((const char *)text.data, "\"indices\":{") - (const char *)text.data + 10));
    expect_error("sparse_down.gltf", text.data, text.size, expect);
    free(text.data);
    text = sparse_positions_gltf(1, 6, 5123, same, 2, 2, 0);
    expect_error("sparse_same.gltf", text.data, text.size, "accessors[0].sparse.indices: index 3 (element 1) does not follow 3");
    free(text.data);
    text = sparse_positions_gltf(1, 6, 5123, at_count, 2, 2, 0);
    expect_error("sparse_at_count.gltf", text.data, text.size, "accessors[0].sparse.indices: index 6 (element 1) is not below the accessor's count 6");
    free(text.data);
    text = sparse_positions_gltf(1, 6, 5123, fine, 2, 2, 1);
    expect_error("sparse_short_values.gltf", text.data, text.size, "accessors[0].sparse.values: 2 elements of 12 bytes from byte 12 overrun bufferViews[2] (35 bytes)");
    free(text.data);
    text = sparse_positions_gltf(1, 6, 5123, fine, 2, 3, 0);
    expect_error("sparse_short_indices.gltf", text.data, text.size, "accessors[0].sparse.indices: 3 elements of 2 bytes from byte 4 overrun bufferViews[1] (8 bytes)");
    free(text.data);
    text = sparse_positions_gltf(1, 6, 5123, fine, 2, 0, 0);
    expect_error("sparse_count0.gltf", text.data, text.size, "accessors[0].sparse.count 0 is not in 1..6 (the accessor's count)");
    free(text.data);
    text = sparse_positions_gltf(0, 6, 5123, fine, 2, 7, 0);
    expect_error("sparse_count7.gltf", text.data, text.size, "accessors[0].sparse.count 7 is not in 1..6 (the accessor's count)");
    free(text.data);
    text = sparse_positions_gltf(1, 6, 5126, fine, 2, 2, 0);
    expect_error("sparse_float_indices.gltf", text.data, text.size, "accessors[0].sparse.indices: componentType 5126 is not 5121, 5123 or 5125");
    free(text.data);
    text = sparse_positions_gltf(1, 6, 5123, fine, 2, 2, 0);
    expect_text_edit_error("sparse_stride.gltf", &text, "}],\"accessors\"", ",\"byteStride\":12}],\"accessors\"",
                           "accessors[0].sparse.values: bufferViews[2] has a byteStride, which sparse data must not have");
    for (i = 0; i < 1000; i++) {
        unsigned char *copy = (unsigned char *)malloc(text.size);
        memcpy(copy, text.data, text.size);
        for (k = 0; k < 1 + (int)(rng() % 4); k++) copy[rng() % text.size] = (unsigned char)rng();
        write_file("sparse_fuzz.gltf", copy, text.size);
        if (voxgi_io_load_mesh(tmp_path("sparse_fuzz.gltf"), &m, err, sizeof err) == 0) { check_consistent(&m, "sparse_fuzz"); voxgi_io_mesh_free(&m); }
        else TH_CHECK(is_empty(&m) && strstr(err, "sparse_fuzz"), "a failed load: %s", err);
        free(copy);
    }
    free(text.data);
}

/* ---------------------------------------------------------------- from memory */

static int same_floats(const float *a, const float *b, size_t n) { return (!a && !b) || (a && b && !memcmp(a, b, n * sizeof *a)); }

/* The mesh loaded from memory is the one the same bytes give from a file: every array equal, and
   each triangle's material the same by name, with the same values when the file's own materials
   came along (with_values), else the defaults. */
static void expect_same_mesh(const char *name, const voxgi_io_mesh *file, const voxgi_io_mesh *mem, int with_values)
{
    size_t t;
    TH_CHECK(file->vertex_count == mem->vertex_count && file->triangle_count == mem->triangle_count,
             "%s: %zu vertices and %zu triangles from the file, %zu and %zu from memory", name, file->vertex_count, file->triangle_count,
             mem->vertex_count, mem->triangle_count);
    if (file->vertex_count != mem->vertex_count || file->triangle_count != mem->triangle_count) return;
    TH_CHECK(same_floats(file->positions, mem->positions, 3 * file->vertex_count), "%s: positions differ", name);
    TH_CHECK(same_floats(file->normals, mem->normals, 3 * file->vertex_count), "%s: normals differ", name);
    TH_CHECK(same_floats(file->uvs, mem->uvs, 2 * file->vertex_count), "%s: uvs differ", name);
    TH_CHECK(!memcmp(file->indices, mem->indices, 3 * file->triangle_count * sizeof *file->indices), "%s: indices differ", name);
    for (t = 0; t < file->triangle_count; t++) {
        const voxgi_io_material *a = &file->materials[file->material_ids[t]], *b = &mem->materials[mem->material_ids[t]];
        TH_CHECK(!strcmp(a->name, b->name), "%s: triangle %zu's material is '%s' from the file, '%s' from memory", name, t, a->name, b->name);
        if (with_values)
            TH_CHECK(!memcmp(a->albedo, b->albedo, sizeof a->albedo) && !memcmp(a->emission, b->emission, sizeof a->emission) && a->opacity == b->opacity,
                     "%s: triangle %zu's material values differ", name, t);
        else
            TH_CHECK(b->albedo[0] == 0.8f && b->albedo[1] == 0.8f && b->albedo[2] == 0.8f && b->emission[0] == 0 && b->emission[1] == 0 &&
                     b->emission[2] == 0 && b->opacity == 1, "%s: triangle %zu's material '%s' is not the default", name, t, b->name);
    }
    TH_CHECK(file->material_count == mem->material_count, "%s: %zu materials from the file, %zu from memory", name, file->material_count, mem->material_count);
}

/* voxgi_io_load_mesh_memory on the bytes of each format's files (OBJ with and without an MTL,
   OFF, STL ASCII and binary, PLY ASCII and binary, glTF with a data URI, GLB) gives what
   voxgi_io_load_mesh gives of the same bytes as a file of that name, the OBJ's mtllib aside (its
   materials stay the defaults, by name, though the MTL file lies beside the name); a .gltf whose
   buffer is a file beside it is refused from memory with the uri named, though the file loads; the bytes are copied (the caller's need no NUL
   after them); errors name the name given, "(memory)" without one (then only content picks the
   format: OBJ, which has no signature, needs its extension). */
static void test_load_from_memory(void)
{
    static const char off_bad[] = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n";
    sample s[10];
    bytes stl, ply;
    growing bin = gltf_small_bin(2), uri_json = gltf_json(gltf_small_body, &bin, NULL), glb_json = gltf_json(gltf_small_body, &bin, ""),
            glb = glb_image(&glb_json, &bin), ext_json = gltf_json(gltf_small_body, &bin, "small.bin");
    int n = valid_samples(s, &stl, &ply), i;
    voxgi_io_mesh file, mem;
    char err[512];
    unsigned char *exact;
    const char *ext_path;
    s[n].name = "uri.gltf"; s[n].data = uri_json.data; s[n].size = uri_json.size; n++;
    s[n].name = "small.glb"; s[n].data = glb.data; s[n].size = glb.size; n++;
    s[n].name = "quads.obj"; s[n].data = obj_quads; s[n].size = strlen(obj_quads); n++;
    for (i = 0; i < n; i++) {
        const char *path = write_file(s[i].name, s[i].data, s[i].size);
        if (!load_ok(path, &file)) continue;
        /* an exact copy, so that ASan sees any read past the bytes given; named by the file's path,
           beside which the OBJ's MTL file lies: it must not be read all the same */
        exact = (unsigned char *)malloc(s[i].size);
        memcpy(exact, s[i].data, s[i].size);
        TH_CHECK(voxgi_io_load_mesh_memory(exact, s[i].size, path, &mem, err, sizeof err) == 0, "%s from memory: %s", s[i].name, err);
        free(exact);
        if (!err[0]) {
            check_consistent(&mem, s[i].name);
            expect_same_mesh(s[i].name, &file, &mem, strcmp(s[i].name, "scene.obj") != 0);
            voxgi_io_mesh_free(&mem);
        }
        voxgi_io_mesh_free(&file);
    }
    write_file("small.bin", bin.data, bin.size);
    ext_path = write_file("external.gltf", ext_json.data, ext_json.size);
    if (load_ok(ext_path, &file)) voxgi_io_mesh_free(&file);
    TH_CHECK(voxgi_io_load_mesh_memory(ext_json.data, ext_json.size, ext_path, &mem, err, sizeof err) != 0 && is_empty(&mem) &&
             !strncmp(err, ext_path, strlen(ext_path)) && strstr(err, ": byte offset ") && strstr(err, "'small.bin'") && strstr(err, "from memory"),
             "an external buffer from memory: %s", err);
    TH_CHECK(voxgi_io_load_mesh_memory("hello world\n", 12, "archive/entry.dat", &mem, err, sizeof err) != 0 && is_empty(&mem) &&
             !strcmp(err, "archive/entry.dat: unrecognised mesh format (expected OBJ, OFF, STL, PLY, glTF or GLB)"), "a name in errors: %s", err);
    TH_CHECK(voxgi_io_load_mesh_memory(off_bad, strlen(off_bad), NULL, &mem, err, sizeof err) != 0 &&
             !strncmp(err, "(memory): line 6: ", 18), "no name (the content picks OFF): %s", err);
    TH_CHECK(voxgi_io_load_mesh_memory(NULL, 0, "empty.obj", &mem, err, sizeof err) != 0 && !strcmp(err, "empty.obj: contains no triangles"),
             "no bytes: %s", err);
    TH_CHECK(voxgi_io_load_mesh_memory(NULL, 1, "x.obj", &mem, err, sizeof err) != 0 && is_empty(&mem) && strstr(err, "no data"), "NULL data: %s", err);
    free(uri_json.data);
    free(glb_json.data);
    free(glb.data);
    free(ext_json.data);
    free(bin.data);
}

/* ---------------------------------------------------------------- PNG */
/* An inflater written from RFC 1951 for the test alone (stored and fixed-code blocks: what the
   writer makes; a dynamic block fails), so that the writer's deflate is held to the format, not to
   itself. */
typedef struct inflater { const unsigned char *p; size_t n, at; uint32_t bit; int bad; } inflater;
static unsigned bits_get(inflater *z, int n)
{
    unsigned v = 0;
    int i;
    for (i = 0; i < n; i++, z->bit++) {
        if (z->bit / 8 >= z->n) { z->bad = 1; return 0; }
        v |= (unsigned)((z->p[z->bit / 8] >> (z->bit % 8)) & 1u) << i;
    }
    return v;
}
typedef struct huff { unsigned short count[16], symbol[320]; } huff;
static void huff_build(huff *h, const unsigned char *len, int n)
{
    unsigned short offs[16];
    int i;
    memset(h, 0, sizeof *h);
    for (i = 0; i < n; i++) h->count[len[i]]++;
    h->count[0] = 0;
    offs[1] = 0;
    for (i = 1; i < 15; i++) offs[i + 1] = (unsigned short)(offs[i] + h->count[i]);
    for (i = 0; i < n; i++)
        if (len[i]) h->symbol[offs[len[i]]++] = (unsigned short)i;
}
static int huff_decode(inflater *z, const huff *h)
{
    int code = 0, first = 0, index = 0, len;
    for (len = 1; len < 16; len++) {
        code |= (int)bits_get(z, 1);
        if (code - first < h->count[len]) return h->symbol[index + code - first];
        index += h->count[len];
        first = (first + h->count[len]) << 1;
        code <<= 1;
    }
    z->bad = 1;
    return 0;
}
/* The zlib stream's data into out (cap bytes): its length, or (size_t)-1. Checks the Adler-32. */
static size_t inflate_zlib(const unsigned char *p, size_t n, unsigned char *out, size_t cap)
{
    static const unsigned short lbase[29] = {3, 4, 5, 6, 7, 8, 9, 10, 11, 13, 15, 17, 19, 23, 27, 31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
    static const unsigned short lext[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
    static const unsigned short dbase[30] = {1, 2, 3, 4, 5, 7, 9, 13, 17, 25, 33, 49, 65, 97, 129, 193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
    static const unsigned short dext[30] = {0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
    inflater z = {NULL, 0, 0, 16, 0};
    size_t o = 0, i;
    uint32_t s1 = 1, s2 = 0, want;
    int last = 0;
    if (n < 6 || (p[0] & 15) != 8 || ((unsigned)p[0] << 8 | p[1]) % 31 != 0) return (size_t)-1;
    z.p = p;
    z.n = n - 4;
    while (!last && !z.bad) {
        unsigned type;
        huff lit, dist;
        last = (int)bits_get(&z, 1);
        type = bits_get(&z, 2);
        if (type == 0) {
            size_t at = (z.bit + 7) / 8, len;
            if (at + 4 > z.n) return (size_t)-1;
            len = (size_t)p[at] | (size_t)p[at + 1] << 8;
            if ((len ^ ((size_t)p[at + 2] | (size_t)p[at + 3] << 8)) != 0xFFFF || at + 4 + len > z.n || o + len > cap) return (size_t)-1;
            memcpy(out + o, p + at + 4, len);
            o += len;
            z.bit = (uint32_t)(8 * (at + 4 + len));
            continue;
        }
        if (type != 1) return (size_t)-1;
        {
            unsigned char lens[320];
            int k;
            for (k = 0; k < 288; k++) lens[k] = (unsigned char)(k < 144 ? 8 : k < 256 ? 9 : k < 280 ? 7 : 8);
            for (k = 0; k < 30; k++) lens[288 + k] = 5;
            huff_build(&lit, lens, 288);
            huff_build(&dist, lens + 288, 30);
        }
        for (;;) {
            int sym = huff_decode(&z, &lit);
            if (z.bad) return (size_t)-1;
            if (sym < 256) {
                if (o >= cap) return (size_t)-1;
                out[o++] = (unsigned char)sym;
            } else if (sym == 256) break;
            else {
                size_t len, d;
                int ds;
                if (sym > 285) return (size_t)-1;
                len = lbase[sym - 257] + bits_get(&z, lext[sym - 257]);
                ds = huff_decode(&z, &dist);
                if (ds > 29 || z.bad) return (size_t)-1;
                d = dbase[ds] + bits_get(&z, dext[ds]);
                if (d > o || o + len > cap) return (size_t)-1;
                for (i = 0; i < len; i++, o++) out[o] = out[o - d];
            }
        }
    }
    if (z.bad) return (size_t)-1;
    for (i = 0; i < o; i++) { s1 = (s1 + out[i]) % 65521u; s2 = (s2 + s1) % 65521u; }
    want = (uint32_t)p[n - 4] << 24 | (uint32_t)p[n - 3] << 16 | (uint32_t)p[n - 2] << 8 | p[n - 1];
    return want == (s2 << 16 | s1) ? o : (size_t)-1;
}

static uint32_t be32(const unsigned char *p) { return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3]; }

/* PNGs of images that compress well and badly (smooth gradients, flat areas, a repeated pattern,
   noise; sizes down to 1 x 1 and wider than the LZ77 window) read back through the inflater above
   and PNG's unfiltering to exactly the sRGB bytes written; every chunk's CRC holds; the smooth
   image takes under half of its raw bytes. */
static void test_png_round_trip(void)
{
    static const int sizes[5][2] = {{1, 1}, {7, 3}, {64, 48}, {300, 40}, {12000, 2}};
    int k;
    for (k = 0; k < 5; k++) {
        int w = sizes[k][0], h = sizes[k][1], x, y, c, filters[5] = {0, 0, 0, 0, 0};
        size_t n = (size_t)3 * (size_t)w * (size_t)h, size = 0, at = 8, zn = 0, got, row = (size_t)3 * (size_t)w + 1;
        float *img = (float *)malloc(n * sizeof(float));
        unsigned char *file = NULL, *zdata = NULL, *raw = (unsigned char *)malloc(row * (size_t)h + 1), *px = (unsigned char *)malloc(n);
        const char *path = tmp_path("image.png");
        uint32_t seed = 7;
        FILE *f;
        for (y = 0; y < h; y++)
            for (x = 0; x < w; x++)
                for (c = 0; c < 3; c++) {
                    size_t i = ((size_t)y * (size_t)w + (size_t)x) * 3 + (size_t)c;
                    seed = seed * 1664525u + 1013904223u;
                    img[i] = x < w / 3 ? (float)x / (float)w + 0.1f * (float)c                     /* a gradient */
                             : x < w / 2 ? 0.25f                                                  /* flat */
                             : x < 2 * w / 3 ? (float)((x / 4 + y / 4 + c) % 3) * 0.4f            /* a pattern */
                             : (float)(seed >> 8) / 16777216.0f * 1.2f - 0.1f;                   /* noise, clamped */
                }
        TH_CHECK(vxt_write_png(path, img, w, h, 1.0f) == 0, "%d x %d: not written", w, h);
        if ((f = fopen(path, "rb")) != NULL) {
            fseek(f, 0, SEEK_END);
            size = (size_t)ftell(f);
            fseek(f, 0, SEEK_SET);
            file = (unsigned char *)malloc(size + 1);
            if (file && fread(file, 1, size, f) != size) size = 0;
            fclose(f);
        }
        remove(path);
        TH_CHECK(file && size > 8 && memcmp(file, "\x89PNG\r\n\x1a\n", 8) == 0, "%d x %d: no PNG signature", w, h);
        zdata = (unsigned char *)malloc(size + 1);
        while (file && zdata && at + 12 <= size) { /* chunks: CRC, IHDR, the IDATs gathered */
            uint32_t len = be32(file + at);
            if (at + 12 + len > size) break;
            TH_CHECK(vxt_crc32(0, file + at + 4, 4 + (size_t)len) == be32(file + at + 8 + len), "%d x %d: a chunk's CRC", w, h);
            if (!memcmp(file + at + 4, "IHDR", 4))
                TH_CHECK(len == 13 && be32(file + at + 8) == (uint32_t)w && be32(file + at + 12) == (uint32_t)h && file[at + 16] == 8 && file[at + 17] == 2,
                         "%d x %d: IHDR", w, h);
            if (!memcmp(file + at + 4, "IDAT", 4)) { memcpy(zdata + zn, file + at + 8, len); zn += len; }
            at += 12 + len;
        }
        got = zdata && raw ? inflate_zlib(zdata, zn, raw, row * (size_t)h) : (size_t)-1;
        TH_CHECK(got == row * (size_t)h, "%d x %d: the zlib stream does not inflate to its %lu bytes", w, h, (unsigned long)(row * (size_t)h));
        if (got == row * (size_t)h && px) {
            size_t bad = 0, i;
            for (y = 0; y < h; y++) { /* unfilter */
                unsigned char *cur = raw + row * (size_t)y + 1, *up = y ? raw + row * (size_t)(y - 1) + 1 : NULL;
                int ft = raw[row * (size_t)y];
                TH_CHECK(ft <= 4, "row %d: filter %d", y, ft);
                if (ft <= 4) filters[ft]++;
                for (i = 0; i < row - 1; i++) {
                    int a = i >= 3 ? cur[i - 3] : 0, b = up ? up[i] : 0, cc = i >= 3 && up ? up[i - 3] : 0, pred;
                    int p = a + b - cc, pa = abs(p - a), pb = abs(p - b), pc = abs(p - cc);
                    pred = ft == 0 ? 0 : ft == 1 ? a : ft == 2 ? b : ft == 3 ? (a + b) / 2 : pa <= pb && pa <= pc ? a : pb <= pc ? b : cc;
                    cur[i] = (unsigned char)(cur[i] + pred);
                    px[(size_t)y * (row - 1) + i] = cur[i];
                }
            }
            for (i = 0; i < n; i++) bad += px[i] != vxt_srgb8(img[i]);
            TH_CHECK(bad == 0, "%d x %d: %lu bytes differ from the sRGB of the image", w, h, (unsigned long)bad);
        }
        printf("    %d x %d: %lu bytes of pixels in a %lu-byte file; filters none %d, sub %d, up %d, average %d, paeth %d\n", w, h, (unsigned long)n,
               (unsigned long)size, filters[0], filters[1], filters[2], filters[3], filters[4]);
        if (k == 2) TH_CHECK(size < n / 2, "64 x 48: %lu bytes for %lu of pixels", (unsigned long)size, (unsigned long)n);
        free(img);
        free(file);
        free(zdata);
        free(raw);
        free(px);
    }
}

int main(void)
{
    const char *base = getenv("TMPDIR");
    int i;
    snprintf(tmp_dir, sizeof tmp_dir, "%s/voxgi_mesh_io_XXXXXX", base && *base ? base : "/tmp");
    if (!mkdtemp(tmp_dir)) {
        printf("cannot create a temporary directory under %s\n", base && *base ? base : "/tmp");
        return 1;
    }
    TH_RUN(test_obj_quads_fan);
    TH_RUN(test_obj_negative_indices);
    TH_RUN(test_obj_split_vertices);
    TH_RUN(test_obj_mtl_materials);
    TH_RUN(test_obj_missing_mtl);
    TH_RUN(test_obj_mtl_in_subfolder);
    TH_RUN(test_obj_mtl_scene_renders);
    TH_RUN(test_mtl_opacity_shadows);
    TH_RUN(test_mtl_errors);
    TH_RUN(test_off);
    TH_RUN(test_stl_ascii);
    TH_RUN(test_stl_binary);
    TH_RUN(test_ply_ascii);
    TH_RUN(test_ply_binary);
    TH_RUN(test_ply_coordinate_types);
    TH_RUN(test_ply_index_types);
    TH_RUN(test_truncated_prefixes);
    TH_RUN(test_corrupted_and_garbage);
    TH_RUN(test_bad_indices);
    TH_RUN(test_non_finite_numbers);
    TH_RUN(test_absurd_counts);
    TH_RUN(test_other_failures);
    TH_RUN(test_large_obj);
    TH_RUN(test_gltf_index_types);
    TH_RUN(test_gltf_node_transforms);
    TH_RUN(test_gltf_materials);
    TH_RUN(test_gltf_buffer_uris);
    TH_RUN(test_gltf_bad_files);
    TH_RUN(test_gltf_sparse_positions);
    TH_RUN(test_gltf_sparse_indices);
    TH_RUN(test_gltf_zero_accessor);
    TH_RUN(test_gltf_sparse_refused);
    TH_RUN(test_load_from_memory);
    TH_RUN(test_png_round_trip);
    for (i = 0; i < created_count; i++) remove(tmp_path(created[i]));
    rmdir(tmp_path("sub"));
    rmdir(tmp_dir);
    return th_finish();
}
