/* tests/test_headless_gl.c - the headless GL helper gives a real OpenGL 4.5 context that
 * runs compute shaders with doubles and atomics, on EGL and on OSMesa; and embed_shaders
 * writes the same header whatever the argument order or the paths.
 *
 *     cc -std=c99 tests/test_headless_gl.c -o test_headless_gl -ldl -lm
 *
 * tools/deps.sh installs what the GL tests need; a kind that cannot start is skipped, or fails
 * when VOXGI_REQUIRE_GL=1 (CI, which installs both kinds). */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include "harness.h"
#include "../tools/headless_gl.h"
#define EMBED_SHADERS_NO_MAIN
#include "../tools/embed_shaders.c"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>

/* The GL entry points the test uses, resolved per context through vxt_gl_get_proc. */
#define TGL_FUNCS(X)                                                                          \
    X(const unsigned char *, GetString, (unsigned name))                                      \
    X(unsigned, GetError, (void))                                                             \
    X(unsigned, CreateShader, (unsigned type))                                                \
    X(void, ShaderSource, (unsigned shader, int count, const char *const *src, const int *len)) \
    X(void, CompileShader, (unsigned shader))                                                 \
    X(void, GetShaderiv, (unsigned shader, unsigned pname, int *value))                       \
    X(void, GetShaderInfoLog, (unsigned shader, int size, int *length, char *log))            \
    X(unsigned, CreateProgram, (void))                                                        \
    X(void, AttachShader, (unsigned program, unsigned shader))                                \
    X(void, LinkProgram, (unsigned program))                                                  \
    X(void, GetProgramiv, (unsigned program, unsigned pname, int *value))                     \
    X(void, GetProgramInfoLog, (unsigned program, int size, int *length, char *log))          \
    X(void, UseProgram, (unsigned program))                                                   \
    X(void, DeleteShader, (unsigned shader))                                                  \
    X(void, DeleteProgram, (unsigned program))                                                \
    X(void, CreateBuffers, (int n, unsigned *buffers))                                        \
    X(void, NamedBufferStorage, (unsigned buffer, ptrdiff_t size, const void *data, unsigned flags)) \
    X(void, BindBufferBase, (unsigned target, unsigned index, unsigned buffer))               \
    X(void, DispatchCompute, (unsigned x, unsigned y, unsigned z))                            \
    X(void, MemoryBarrier, (unsigned barriers))                                               \
    X(void, GetNamedBufferSubData, (unsigned buffer, ptrdiff_t offset, ptrdiff_t size, void *data)) \
    X(void, DeleteBuffers, (int n, const unsigned *buffers))

#define TGL_TYPEDEF(ret, name, params) typedef ret (*tgl_##name##_fn) params;
TGL_FUNCS(TGL_TYPEDEF)
#define TGL_FIELD(ret, name, params) tgl_##name##_fn name;
static struct { TGL_FUNCS(TGL_FIELD) } tgl;

enum {
    TGL_RENDERER = 0x1F01,
    TGL_VERSION = 0x1F02,
    TGL_SHADING_LANGUAGE_VERSION = 0x8B8C,
    TGL_COMPILE_STATUS = 0x8B81,
    TGL_LINK_STATUS = 0x8B82,
    TGL_SHADER_STORAGE_BUFFER = 0x90D2,
    TGL_COMPUTE_SHADER = 0x91B9,
    TGL_BUFFER_UPDATE_BARRIER_BIT = 0x0200
};

/* Fills tgl from the current context; the name of the first missing function, or NULL. */
static const char *tgl_load(vxt_gl *gl)
{
#define TGL_LOAD(ret, name, params)                                         \
    tgl.name = (tgl_##name##_fn)vxt_gl_get_proc("gl" #name, gl);            \
    if (!tgl.name) return "gl" #name;
    TGL_FUNCS(TGL_LOAD)
#undef TGL_LOAD
    return NULL;
}

enum { INVOCATIONS = 256, BIT_WORDS = INVOCATIONS / 32 + 1 };

/* Every invocation sets its own bit in bits[0..7] and, contending with all the others, bit
 * i % 32 of bits[8]; the 1e-12 in values[] would vanish if doubles were floats. */
static const char *const compute_src =
    "#version 450\n"
    "layout(local_size_x = 64) in;\n"
    "layout(std430, binding = 0) buffer Bits { uint bits[]; };\n"
    "layout(std430, binding = 1) buffer Values { double values[]; };\n"
    "void main() {\n"
    "    uint i = gl_GlobalInvocationID.x;\n"
    "    double third = (double(i) + 1.0lf) / 3.0lf;\n"
    "    values[i] = fma(third, 3.0lf, 1.0e-12lf);\n"
    "    atomicOr(bits[i / 32u], 1u << (i % 32u));\n"
    "    atomicOr(bits[bits.length() - 1], 1u << (i % 32u));\n"
    "}\n";

static void run_compute(void)
{
    static unsigned bits[BIT_WORDS];
    static double values[INVOCATIONS];
    char log[2048] = "";
    int ok = 0, i;
    unsigned shader, program, buffers[2];

    shader = tgl.CreateShader(TGL_COMPUTE_SHADER);
    tgl.ShaderSource(shader, 1, &compute_src, NULL);
    tgl.CompileShader(shader);
    tgl.GetShaderiv(shader, TGL_COMPILE_STATUS, &ok);
    tgl.GetShaderInfoLog(shader, (int)sizeof log, NULL, log);
    TH_CHECK(ok, "compute shader with doubles and atomicOr does not compile: %s", log);
    program = tgl.CreateProgram();
    tgl.AttachShader(program, shader);
    tgl.LinkProgram(program);
    tgl.GetProgramiv(program, TGL_LINK_STATUS, &ok);
    tgl.GetProgramInfoLog(program, (int)sizeof log, NULL, log);
    TH_CHECK(ok, "compute program does not link: %s", log);

    memset(bits, 0, sizeof bits);
    memset(values, 0, sizeof values);
    tgl.CreateBuffers(2, buffers);
    tgl.NamedBufferStorage(buffers[0], (ptrdiff_t)sizeof bits, bits, 0);
    tgl.NamedBufferStorage(buffers[1], (ptrdiff_t)sizeof values, values, 0);
    tgl.BindBufferBase(TGL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
    tgl.BindBufferBase(TGL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
    tgl.UseProgram(program);
    tgl.DispatchCompute(INVOCATIONS / 64, 1, 1);
    tgl.MemoryBarrier(TGL_BUFFER_UPDATE_BARRIER_BIT);
    tgl.GetNamedBufferSubData(buffers[0], 0, (ptrdiff_t)sizeof bits, bits);
    tgl.GetNamedBufferSubData(buffers[1], 0, (ptrdiff_t)sizeof values, values);

    for (i = 0; i < BIT_WORDS; i++)
        TH_CHECK(bits[i] == 0xffffffffu, "bits[%d] = 0x%08x, want 0xffffffff", i, bits[i]);
    for (i = 0; i < INVOCATIONS; i++) {
        double want = i + 1 + 1e-12;
        TH_CHECK(fabs(values[i] - want) < 1e-13, "values[%d] = %.17g, want %.17g", i, values[i], want);
    }
    TH_CHECK(tgl.GetError() == 0, "GL error 0x%x", tgl.GetError());

    tgl.UseProgram(0);
    tgl.DeleteBuffers(2, buffers);
    tgl.DeleteProgram(program);
    tgl.DeleteShader(shader);
}

static void check_kind(vxt_gl_kind kind, const char *name)
{
    char err[1024];
    const char *missing, *version;
    int major = 0, minor = 0;
    vxt_gl *gl = vxt_gl_create(kind, err, sizeof err);

    if (!gl) {
        if (th_gl_required()) TH_CHECK(0, "no %s context, and VOXGI_REQUIRE_GL is set: %s", name, err);
        else th_skip("NO %s CONTEXT, nothing ran: %s", name, err);
        return;
    }
    TH_CHECK(strcmp(vxt_gl_kind_name(gl), name) == 0, "kind name %s, want %s", vxt_gl_kind_name(gl), name);
    missing = tgl_load(gl);
    TH_CHECK(!missing, "%s does not resolve", missing);
    if (!missing) {
        version = (const char *)tgl.GetString(TGL_VERSION);
        printf("    %s: OpenGL %s, GLSL %s, %s\n", name, version,
               (const char *)tgl.GetString(TGL_SHADING_LANGUAGE_VERSION), vxt_gl_renderer(gl));
        TH_CHECK(sscanf(version, "%d.%d", &major, &minor) == 2 && (major > 4 || (major == 4 && minor >= 5)),
                 "GL_VERSION %s, want 4.5 or higher", version);
        TH_CHECK(strcmp(vxt_gl_renderer(gl), (const char *)tgl.GetString(TGL_RENDERER)) == 0,
                 "vxt_gl_renderer says %s", vxt_gl_renderer(gl));
        run_compute();
    }
    vxt_gl_destroy(gl);
}

static void test_egl_compute(void) { check_kind(VXT_GL_EGL, "egl"); }
static void test_osmesa_compute(void) { check_kind(VXT_GL_OSMESA, "osmesa"); }

static void test_auto_picks_a_kind(void)
{
    char err[1024];
    vxt_gl *gl = vxt_gl_create(VXT_GL_AUTO, err, sizeof err);
    if (!gl) {
        if (th_gl_required()) TH_CHECK(0, "no GL context at all, and VOXGI_REQUIRE_GL is set: %s", err);
        else th_skip("NO GL CONTEXT AT ALL: %s", err);
        return;
    }
    TH_CHECK(strcmp(vxt_gl_kind_name(gl), "egl") == 0 || strcmp(vxt_gl_kind_name(gl), "osmesa") == 0,
             "kind name %s", vxt_gl_kind_name(gl));
    vxt_gl_destroy(gl);
}

static void test_kind_parse(void)
{
    vxt_gl_kind kind = VXT_GL_AUTO;
    TH_CHECK(vxt_gl_kind_parse("osmesa", &kind) == 0 && kind == VXT_GL_OSMESA, "osmesa");
    TH_CHECK(vxt_gl_kind_parse("egl", &kind) == 0 && kind == VXT_GL_EGL, "egl");
    TH_CHECK(vxt_gl_kind_parse("auto", &kind) == 0 && kind == VXT_GL_AUTO, "auto");
    TH_CHECK(vxt_gl_kind_parse("EGL", &kind) == -1 && kind == VXT_GL_AUTO, "EGL is not a kind");
    TH_CHECK(vxt_gl_kind_parse("", &kind) == -1, "empty is not a kind");
}

/* embed_shaders, on files in a fresh temporary directory. */
static char tmp_dir[256];

static const char *tmp_path(const char *name)
{
    static char paths[8][512];
    static int next;
    char *p = paths[next++ % 8];
    snprintf(p, sizeof paths[0], "%s/%s", tmp_dir, name);
    return p;
}

static void write_file(const char *name, const char *text)
{
    FILE *f = fopen(tmp_path(name), "wb");
    int ok = f && fputs(text, f) >= 0;
    if (f && fclose(f) != 0) ok = 0;
    TH_CHECK(ok, "cannot write %s", tmp_path(name));
}

static es_file read_file(const char *name)
{
    char err[512];
    es_file f;
    memset(&f, 0, sizeof f);
    TH_CHECK(es_read(tmp_path(name), &f, err, sizeof err) == 0, "%s", err);
    return f;
}

static const char *const shader_names[] = {"b.glsl", "a.glsl", "my-weird name.v2.glsl"};

static void test_embed_shaders(void)
{
    static const char banner[] = "// GENERATED from shaders/*.glsl by tools/embed_shaders.c";
    char err[512], *forward[3], *backward[3], *raw_text;
    es_file one, two, three;
    const char *text, *weird;
    int i;

    snprintf(tmp_dir, sizeof tmp_dir, "%s/voxgi-embed-XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(tmp_dir)) {
        TH_CHECK(0, "mkdtemp %s failed", tmp_dir);
        return;
    }
    write_file("a.glsl", "#version 450\nvoid main() {}\n");
    write_file("b.glsl", "// b \"quoted\" \\\n");
    write_file("my-weird name.v2.glsl", "");
    /* Same base names through different paths, in opposite orders. */
    for (i = 0; i < 3; i++) {
        forward[i] = (char *)malloc(600);
        backward[2 - i] = (char *)malloc(600);
        snprintf(forward[i], 600, "%s/%s", tmp_dir, shader_names[i]);
        snprintf(backward[2 - i], 600, "%s/./%s", tmp_dir, shader_names[i]);
    }
    TH_CHECK(embed_shaders(tmp_path("one.h"), 3, forward, err, sizeof err) == 0, "%s", err);
    TH_CHECK(embed_shaders(tmp_path("two.h"), 3, backward, err, sizeof err) == 0, "%s", err);
    one = read_file("one.h");
    two = read_file("two.h");
    TH_CHECK(one.data && two.data && one.size == two.size && memcmp(one.data, two.data, one.size) == 0,
             "the two runs differ");

    /* es_read does not NUL-terminate; make it a string. */
    raw_text = (char *)calloc(1, one.size + 1);
    if (one.data && raw_text) memcpy(raw_text, one.data, one.size);
    text = raw_text ? raw_text : "";
    TH_CHECK(strncmp(text, banner, sizeof banner - 1) == 0, "banner: %.80s", text);
    TH_CHECK(!strstr(text, tmp_dir), "the output names the input directory");
    weird = strstr(text, "static const unsigned char voxgi__glsl_my_weird_name_v2[] = {");
    TH_CHECK(weird != NULL, "no sanitised array for the weird name");
    TH_CHECK(strstr(text, "{\"my-weird name.v2.glsl\", voxgi__glsl_my_weird_name_v2, 0UL},") != NULL,
             "table row of the weird name");
    TH_CHECK(strstr(text, "voxgi__glsl_a[]") && strstr(text, "voxgi__glsl_b[]")
                 && strstr(text, "voxgi__glsl_a[]") < strstr(text, "voxgi__glsl_b[]")
                 && weird && strstr(text, "voxgi__glsl_b[]") < weird,
             "arrays not sorted by file name");
    TH_CHECK(strstr(text, "{\"a.glsl\", voxgi__glsl_a, 28UL},") != NULL, "size of a.glsl");
    TH_CHECK(strstr(text, "#define VOXGI__GLSL_FILE_COUNT ((int)(sizeof voxgi__glsl_files / sizeof voxgi__glsl_files[0]))\n") != NULL,
             "file count");
    TH_CHECK(!strstr(text, "VOXGI_NO_"), "a guard without an \"embedded unless\" line");

    /* A missing input fails with a message and leaves the previous output alone. */
    forward[1][strlen(forward[1]) - 1] = 'x';
    err[0] = '\0';
    TH_CHECK(embed_shaders(tmp_path("one.h"), 3, forward, err, sizeof err) == -1,
             "a missing input succeeded");
    TH_CHECK(strstr(err, "a.glsx") != NULL, "message does not name the missing file: %s", err);
    three = read_file("one.h");
    TH_CHECK(three.data && three.size == one.size && memcmp(three.data, one.data, one.size) == 0,
             "a failed run changed the output");

    for (i = 0; i < 3; i++) {
        free(forward[i]);
        free(backward[i]);
        remove(tmp_path(shader_names[i]));
    }
    free(raw_text);
    free(one.data);
    free(two.data);
    free(three.data);
    remove(tmp_path("one.h"));
    remove(tmp_path("two.h"));
    TH_CHECK(remove(tmp_dir) == 0, "%s is not empty: a temporary file was left behind", tmp_dir);
}

/* "embedded unless" lines: each file's array and table row kept by the matching #if; a malformed
   line or two of them fail with the file's name. */
static void test_embed_shaders_guards(void)
{
    static const char *const names[] = {"one.glsl", "either.glsl", "both.glsl", "plain.glsl"};
    static const char *const bad[] = {"// embedded unless OCTREE\n", "// embedded unless VOXGI_NO_A or\n",
                                      "// embedded unless VOXGI_NO_A or VOXGI_NO_B and VOXGI_NO_C\n", "// embedded unless VOXGI_NO_A  or VOXGI_NO_B\n",
                                      "// embedded unless VOXGI_NO_A\n// embedded unless VOXGI_NO_B\n"};
    char err[512], *paths[4], *text;
    es_file out;
    int i;
    snprintf(tmp_dir, sizeof tmp_dir, "%s/voxgi-embed-XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(tmp_dir)) {
        TH_CHECK(0, "mkdtemp %s failed", tmp_dir);
        return;
    }
    write_file("one.glsl", "// a part's file\n// embedded unless VOXGI_NO_OCTREE\r\nvoid f() {}\n");
    write_file("either.glsl", "// embedded unless VOXGI_NO_CONE_TRACING or VOXGI_NO_OCTREE");
    write_file("both.glsl", "// embedded unless VOXGI_NO_LIGHT_SPACE and VOXGI_NO_SCREEN_SPACE and VOXGI_NO_X2\n");
    write_file("plain.glsl", "// embedded unlessVOXGI_NO_OCTREE\n  // embedded unless VOXGI_NO_OCTREE\n");
    for (i = 0; i < 4; i++) {
        paths[i] = (char *)malloc(600);
        snprintf(paths[i], 600, "%s/%s", tmp_dir, names[i]);
    }
    TH_CHECK(embed_shaders(tmp_path("out.h"), 4, paths, err, sizeof err) == 0, "%s", err);
    out = read_file("out.h");
    text = (char *)calloc(1, out.size + 1);
    if (text && out.data) memcpy(text, out.data, out.size);
    if (text) {
        TH_CHECK(strstr(text, "\n#ifndef VOXGI_NO_OCTREE\nstatic const unsigned char voxgi__glsl_one[] = {") != NULL, "one macro: %.300s", text);
        TH_CHECK(strstr(text, "\n#if !defined(VOXGI_NO_CONE_TRACING) && !defined(VOXGI_NO_OCTREE)\nstatic const unsigned char voxgi__glsl_either[]") != NULL,
                 "or");
        TH_CHECK(strstr(text, "\n#if !defined(VOXGI_NO_LIGHT_SPACE) || !defined(VOXGI_NO_SCREEN_SPACE) || !defined(VOXGI_NO_X2)\n"
                              "static const unsigned char voxgi__glsl_both[]") != NULL,
                 "and");
        TH_CHECK(strstr(text, "0x00\n};\n#endif\n") != NULL, "an array's #endif");
        TH_CHECK(strstr(text, "#ifndef VOXGI_NO_OCTREE\n    {\"one.glsl\", voxgi__glsl_one, 65UL},\n#endif\n") != NULL, "a table row's guard");
        TH_CHECK(strstr(text, "\nstatic const unsigned char voxgi__glsl_plain[]") != NULL &&
                     strstr(text, "};\n    {\"plain.glsl\"") == NULL && strstr(text, "#endif\n    {\"plain.glsl\"") != NULL,
                 "a file without the line is kept whole");
    }
    free(text);
    free(out.data);
    for (i = 0; i < (int)(sizeof bad / sizeof bad[0]); i++) {
        write_file("one.glsl", bad[i]);
        err[0] = '\0';
        TH_CHECK(embed_shaders(tmp_path("bad.h"), 4, paths, err, sizeof err) == -1, "accepted %s", bad[i]);
        TH_CHECK(strstr(err, "one.glsl") != NULL, "the message does not name the file: %s", err);
    }
    for (i = 0; i < 4; i++) {
        remove(paths[i]);
        free(paths[i]);
    }
    remove(tmp_path("out.h"));
    TH_CHECK(remove(tmp_dir) == 0, "%s is not empty: a temporary file was left behind", tmp_dir);
}

int main(void)
{
    TH_RUN(test_kind_parse);
    TH_RUN(test_egl_compute);
    TH_RUN(test_osmesa_compute);
    TH_RUN(test_auto_picks_a_kind);
    TH_RUN(test_embed_shaders);
    TH_RUN(test_embed_shaders_guards);
    return th_finish();
}
