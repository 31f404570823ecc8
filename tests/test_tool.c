/* The voxgi command-line tool, run as a user runs it: help, exact grids, JSON, binvox output,
   backends, and bad files and arguments (clear message, non-zero exit, never a crash).
   VOXGI_TOOL names the binary (default: the voxgi beside this program, which the Makefile builds
   there). Works from any directory: the tests run in their own temporary directory. The reports'
   figures (tools/cli_figures.c: the font, the picture, the plot) are also drawn in process. */
#define _XOPEN_SOURCE 700 /* popen, mkdtemp, realpath */
#include "../voxgi.h"
#include "../tools/pareto.h"
#include "../tools/cli.h"
#include "../tools/shapes.h"
#include "harness.h"
#include "../tools/cli_figures.c" /* the reports' figures, drawn in process (the tool's own code) */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

static char tool_path[4096], tmpdir[256];
static const char *tool(void) { return tool_path; }

/* The tool's absolute path, before the tests leave the starting directory: VOXGI_TOOL, else the
   voxgi next to this program. */
static int find_tool(const char *argv0)
{
    char here[4096];
    const char *given = getenv("VOXGI_TOOL");
    ssize_t n;
    if (given && *given) return realpath(given, tool_path) != NULL;
    n = readlink("/proc/self/exe", here, sizeof here - 1);
    if (n > 0) here[n] = 0;
    else if (!realpath(argv0, here)) return 0;
    if (strrchr(here, '/')) *strrchr(here, '/') = 0;
    return snprintf(tool_path, sizeof tool_path, "%s/voxgi", here) < (int)sizeof tool_path && access(tool_path, X_OK) == 0;
}

/* Runs "voxgi ARGS" and captures stdout+stderr; returns the exit status (-1 if it died). */
static int run(const char *args, char *out, size_t out_size)
{
    char cmd[8192];
    FILE *p;
    size_t n = 0;
    int st;
    snprintf(cmd, sizeof cmd, "%s %s 2>&1", tool(), args);
    p = popen(cmd, "r");
    if (!p) return -1;
    while (n + 1 < out_size) {
        size_t got = fread(out + n, 1, out_size - 1 - n, p);
        if (got == 0) break;
        n += got;
    }
    out[n] = 0;
    st = pclose(p);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static double json_number(const char *json, const char *key)
{
    char pat[64];
    const char *at;
    snprintf(pat, sizeof pat, "\"%s\":", key);
    at = strstr(json, pat);
    return at ? strtod(at + strlen(pat), NULL) : -1;
}

static void write_file(const char *name, const char *text, char *path, size_t path_size)
{
    FILE *f;
    snprintf(path, path_size, "%s/%s", tmpdir, name);
    f = fopen(path, "wb");
    fputs(text, f);
    fclose(f);
}

static void test_help_everywhere(void)
{
    static char out[32768];
    const char *cmds[] = {"--help", "voxelize --help", "info --help", "bench --help", "bench voxelize --help", "bench rays --help", "svo --help", "render --help", "report --help", "report vct --help",
                          "report tsm --help", "report rsm --help", "report sh --help", "report ao --help", "report ssgi --help",
                          "report linespace --help", "plan --help", "report all --help"};
    size_t i;
    for (i = 0; i < sizeof cmds / sizeof cmds[0]; i++) {
        int rc = run(cmds[i], out, sizeof out);
        TH_CHECK(rc == 0 && strstr(out, "usage:"), "'voxgi %s' gave %d: %.200s", cmds[i], rc, out);
    }
    TH_CHECK(run("", out, sizeof out) == 2, "no command should exit 2");
    TH_CHECK(run("frobnicate", out, sizeof out) == 2 && strstr(out, "unknown command"), "unknown command: %s", out);
}

/* The cube [-1,1]^3 on a grid whose planes pass through its faces: exactly the voxels that
   touch the surface, 10^3 - 6^3 = 784 (the closed cube meets index range 1..10 per axis, the
   open interior contains 3..8). */
static void test_voxelize_exact_grid_json_binvox(void)
{
    static char out[8192];
    char args[1024], path[512];
    FILE *f;
    voxgi_grid g;
    size_t need = 0;
    uint32_t *bits;
    int rc;
    snprintf(path, sizeof path, "%s/cube.binvox", tmpdir);
    snprintf(args, sizeof args, "voxelize builtin:cube --grid -1.5 -1.5 -1.5 0.25 12 12 12 --backend cpu --json -o %s", path);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 0, "exit %d: %s", rc, out);
    TH_CHECK(json_number(out, "voxels") == 784, "voxels %g, expected 784: %s", json_number(out, "voxels"), out);
    TH_CHECK(json_number(out, "triangles") == 12, "triangles: %s", out);
    TH_CHECK(json_number(out, "voxel_size") == 0.25 && json_number(out, "ms") >= 0, "voxel_size/ms: %s", out);
    TH_CHECK(strstr(out, "\"backend\":\"cpu\"") && strstr(out, "\"method\":\"conservative\"") &&
             strstr(out, "\"origin\":[-1.5,-1.5,-1.5]") && strstr(out, "\"res\":[12,12,12]"), "fields: %s", out);
    f = fopen(path, "rb");
    TH_CHECK(f != NULL, "no binvox written");
    if (!f) return;
    TH_CHECK(voxgi_binvox_read(f, &g, NULL, 0, &need) == VOXGI_OK, "binvox header unreadable");
    rewind(f);
    bits = (uint32_t *)malloc(need);
    TH_CHECK(voxgi_binvox_read(f, &g, bits, need, NULL) == VOXGI_OK, "binvox unreadable");
    fclose(f);
    {
        uint64_t i, count = 0;
        for (i = 0; i < 12 * 12 * 12; i++) count += (uint64_t)voxgi_bit_get(bits, i);
        TH_CHECK(count == 784 && g.res[0] == 12 && g.origin[1] == -1.5 && g.voxel_size == 0.25, "binvox holds %llu voxels",
                 (unsigned long long)count);
    }
    free(bits);
    /* --grid takes the numbers as given: 0.1 stays the double nearest 0.1 */
    rc = run("voxelize builtin:sphere --grid 0.1 -1.3 -1.7 0.1 30 31 32 --backend cpu --json", out, sizeof out);
    TH_CHECK(rc == 0 && strstr(out, "\"origin\":[0.10000000000000001,-1.3,-1.7]") && json_number(out, "voxel_size") == 0.1,
             "grid not taken as given: %s", out);
}

/* GL and CPU give the same count through the tool (when a GL context can be made). */
static void test_voxelize_backends_agree(void)
{
    static char cpu[8192], gl[8192];
    int rc = run("voxelize builtin:sphere --res 48 --backend cpu --json", cpu, sizeof cpu);
    TH_CHECK(rc == 0, "cpu: %s", cpu);
    rc = run("voxelize builtin:sphere --res 48 --backend gl --json", gl, sizeof gl);
    if (rc != 0 && strstr(gl, "cannot use backend gl")) {
        if (th_gl_required()) TH_CHECK(0, "no GL: %s", gl);
        else th_skip("no GL context: %s", gl);
        return;
    }
    TH_CHECK(rc == 0 && strstr(gl, "\"backend\":\"gl\""), "gl: %s", gl);
    TH_CHECK(json_number(cpu, "voxels") == json_number(gl, "voxels") && json_number(cpu, "voxels") > 0, "cpu %g vs gl %g",
             json_number(cpu, "voxels"), json_number(gl, "voxels"));
}

static void test_bad_files_and_arguments(void)
{
    static char out[8192];
    char path[512], args[1024];
    int rc;
    write_file("trunc.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", path, sizeof path);
    snprintf(args, sizeof args, "voxelize %s --backend cpu", path);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 1 && strstr(out, "trunc.obj") && strstr(out, "line 4"), "bad index: exit %d: %s", rc, out);
    write_file("nan.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", path, sizeof path);
    snprintf(args, sizeof args, "voxelize %s --backend cpu", path);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 1 && strstr(out, "nan.off"), "nan: exit %d: %s", rc, out);
    write_file("short.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", path, sizeof path);
    snprintf(args, sizeof args, "voxelize %s --backend cpu", path);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 1 && strstr(out, "short.stl"), "truncated stl: exit %d: %s", rc, out);
    rc = run("voxelize /nonexistent/mesh.ply --backend cpu", out, sizeof out);
    TH_CHECK(rc == 1 && strstr(out, "/nonexistent/mesh.ply"), "missing file: exit %d: %s", rc, out);
    rc = run("voxelize builtin:cube --res 0", out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "--res"), "--res 0: exit %d: %s", rc, out);
    rc = run("voxelize builtin:cube --grid 0 0 0 -1 4 4 4 --backend cpu", out, sizeof out);
    TH_CHECK(rc == 1 && strstr(out, "voxel size"), "negative voxel size: exit %d: %s", rc, out);
    rc = run("voxelize builtin:nothing", out, sizeof out);
    TH_CHECK(rc == 1 && strstr(out, "builtin:"), "unknown built-in: exit %d: %s", rc, out);
    rc = run("voxelize builtin:cube --backend cpu -o /nonexistent/dir/x.binvox", out, sizeof out);
    TH_CHECK(rc == 1 && strstr(out, "cannot write") && strstr(out, strerror(ENOENT)), "unwritable output: exit %d: %s", rc, out);
    rc = run("render builtin:cube --size 4 4 --spp 1 -o /nonexistent/dir/x.png", out, sizeof out);
    TH_CHECK(rc == 1 && strstr(out, "cannot write /nonexistent/dir/x.png: ") && strstr(out, strerror(ENOENT)), "unwritable image: exit %d: %s", rc, out);
}

/* --method: thin is within conservative; solid of the closed cube is its 8^3 interior centres. */
static void test_voxelize_methods(void)
{
    static char out[8192];
    double cons, thin;
    int rc = run("voxelize builtin:sphere --res 40 --backend cpu --json", out, sizeof out);
    cons = json_number(out, "voxels");
    rc |= run("voxelize builtin:sphere --res 40 --backend cpu --json --method thin", out, sizeof out);
    thin = json_number(out, "voxels");
    TH_CHECK(rc == 0 && strstr(out, "\"method\":\"thin\"") && thin > 0 && thin < cons, "thin %g vs conservative %g: %s", thin, cons, out);
    /* cube [-1,1]^3, voxels of 0.25 from -1.5: centres -1.375 + 0.25 i inside for i = 2..9 */
    rc = run("voxelize builtin:cube --grid -1.5 -1.5 -1.5 0.25 12 12 12 --backend cpu --json --method solid --axis x", out, sizeof out);
    TH_CHECK(rc == 0 && json_number(out, "voxels") == 512 && strstr(out, "\"method\":\"solid\""), "solid cube: %s", out);
    rc = run("voxelize builtin:cube --grid -1.5 -1.5 -1.5 0.25 12 12 12 --backend cpu --json --method solid --solid-mode flood", out, sizeof out);
    TH_CHECK(rc == 0 && json_number(out, "voxels") == 1000, "flood cube (interior and the touching shell, 10^3): %s", out);
    /* the atlas: every point lies within one voxel of the conservative set, so it cannot outnumber it
       by much; it reports its atlas; attributes: at least one triangle per voxel */
    rc = run("voxelize builtin:sphere --res 40 --backend cpu --json --method atlas", out, sizeof out);
    TH_CHECK(rc == 0 && json_number(out, "atlas_points") > 0 && json_number(out, "voxels") > 0.5 * cons &&
             json_number(out, "voxels") <= 1.05 * cons && json_number(out, "atlas_size") >= 64, "atlas: %s", out);
    rc = run("voxelize builtin:sphere --res 40 --backend cpu --json --attributes albedo,normal", out, sizeof out);
    TH_CHECK(rc == 0 && json_number(out, "voxels") == cons && json_number(out, "attribute_pairs") >= cons, "attributes: %s", out);
    TH_CHECK(run("voxelize builtin:cube --attributes colour", out, sizeof out) == 2, "unknown attribute accepted");
    TH_CHECK(run("voxelize builtin:cube --method wobbly", out, sizeof out) == 2, "unknown method accepted");
    TH_CHECK(run("voxelize builtin:cube --method solid --solid-mode guess", out, sizeof out) == 2, "unknown solid mode accepted");
}

/* voxgi svo: as many leaves as the voxelization sets, a root, and at most 8 structure bytes
   per voxel; the per-level node counts end with the leaves; -o saves the octree the JSON
   describes (voxgi_svo_read gives the same leaves, nodes and bytes). */
static void test_svo_command(void)
{
    static char out[8192];
    double cons, leaves;
    int rc = run("voxelize builtin:sphere --res 40 --backend cpu --json", out, sizeof out);
    cons = json_number(out, "voxels");
    rc |= run("svo builtin:sphere --res 40 --backend cpu --json", out, sizeof out);
    leaves = json_number(out, "leaf_voxels");
    TH_CHECK(rc == 0 && leaves == cons && json_number(out, "nodes") > 8 && json_number(out, "structure_bytes") <= 8 * leaves &&
             json_number(out, "bytes") > json_number(out, "structure_bytes") && json_number(out, "depth") == 6 && strstr(out, "\"level_nodes\":[1,"),
             "svo: %s", out);
    rc = run("svo builtin:cube --res 16 --backend cpu", out, sizeof out);
    TH_CHECK(rc == 0 && strstr(out, "Table 5.1") && strstr(out, "Table 5.2"), "svo tables: %s", out);
    TH_CHECK(run("svo builtin:cube --attributes colour", out, sizeof out) == 2, "unknown attribute accepted");
    { /* -o FILE.svo: voxgi_svo_read loads the octree the JSON describes; another extension exits 2 */
        char path[512], args[1200];
        voxgi_context *ctx = NULL;
        voxgi_desc d;
        voxgi_svo *svo = NULL;
        voxgi_svo_info info;
        snprintf(path, sizeof path, "%s/sphere.svo", tmpdir);
        snprintf(args, sizeof args, "svo builtin:sphere --res 40 --backend cpu --bricks --neighbours --format float16 --json -o %s", path);
        rc = run(args, out, sizeof out);
        memset(&d, 0, sizeof d);
        d.backend = VOXGI_BACKEND_CPU;
        voxgi_create(&d, &ctx);
        TH_CHECK(rc == 0 && strstr(out, "\"output\":") && voxgi_svo_read(ctx, path, &svo) == VOXGI_OK, "svo -o: %s / %s", out, voxgi_last_error(ctx));
        voxgi_svo_query(svo, &info);
        TH_CHECK(svo && (double)info.leaf_voxels == json_number(out, "leaf_voxels") && (double)info.nodes == json_number(out, "nodes") &&
                     (double)info.bytes == json_number(out, "bytes") && (double)info.brick_bytes == json_number(out, "brick_bytes") &&
                     info.format == VOXGI_SVO_FLOAT16 && info.neighbour_bytes > 0,
                 "the saved octree is not the one described: %s", out);
        voxgi_svo_destroy(ctx, svo);
        voxgi_destroy(ctx);
        remove(path);
        snprintf(args, sizeof args, "svo builtin:cube --res 8 -o %s/cube.txt", tmpdir);
        TH_CHECK(run(args, out, sizeof out) == 2 && strstr(out, ".svo"), "svo -o cube.txt: %s", out);
    }
}

/* voxgi render: the PFM holds exactly what the library renders with the same settings; the PNG
   is a well-formed 8-bit RGB image of the same size; bad arguments exit 2. */
static void test_render_command(void)
{
    static char out[8192];
    char pfm[512], png[512], args[1200];
    voxgi_context *ctx = NULL;
    voxgi_desc d;
    voxgi_builtin_scene bs;
    voxgi_render_desc rd;
    float want[6 * 4 * 3], got[6 * 4 * 3];
    unsigned char head[33];
    FILE *f;
    int rc, w = 0, h = 0;
    snprintf(pfm, sizeof pfm, "%s/f.pfm", tmpdir);
    snprintf(png, sizeof png, "%s/f.png", tmpdir);
    snprintf(args, sizeof args, "render furnace --spp 4 --size 6 4 --bounces -1 --seed 5 --threads 2 --json -o %s", pfm);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 0 && json_number(out, "rays") > 0, "render: %s", out);
    memset(&d, 0, sizeof d);
    d.backend = VOXGI_BACKEND_CPU;
    voxgi_create(&d, &ctx);
    memset(&rd, 0, sizeof rd);
    voxgi_builtin_scene_create(ctx, "furnace", &bs);
    rd.method = VOXGI_RENDER_REFERENCE;
    rd.camera = bs.camera;
    rd.camera.width = 6; rd.camera.height = 4;
    rd.samples = 4; rd.bounces = -1; rd.seed = 5;
    TH_CHECK(voxgi_render(ctx, &bs.scene, &rd, want, sizeof want, NULL) == VOXGI_OK, "library render: %s", voxgi_last_error(ctx));
    f = fopen(pfm, "rb");
    TH_CHECK(f && fscanf(f, "PF %d %d -1.0", &w, &h) == 2 && fgetc(f) == '\n' && w == 6 && h == 4, "PFM header");
    if (f) {
        int y;
        for (y = 3; y >= 0; y--) TH_CHECK(fread(got + 3 * 6 * y, 4, 18, f) == 18, "PFM rows");
        fclose(f);
        TH_CHECK(memcmp(got, want, sizeof want) == 0, "the PFM differs from the library's render");
    }
    snprintf(args, sizeof args, "render cornell-box --spp 1 --size 5 3 -o %s", png);
    TH_CHECK(run(args, out, sizeof out) == 0, "png render: %s", out);
    f = fopen(png, "rb");
    TH_CHECK(f && fread(head, 1, 33, f) == 33 && memcmp(head, "\x89PNG\r\n\x1a\n", 8) == 0 && memcmp(head + 12, "IHDR", 4) == 0 &&
             head[19] == 5 && head[23] == 3 && head[24] == 8 && head[25] == 2, "PNG header");
    if (f) fclose(f);
    TH_CHECK(run("render cornell-box -o x.jpg", out, sizeof out) == 2, "a .jpg output accepted");
    TH_CHECK(run("render no-such-scene -o x.png", out, sizeof out) == 1 && strstr(out, "cornell-box"), "unknown scene: %s", out);
    TH_CHECK(run("render cornell-box --camera 0 1 0 0 0 0 40 -o x.png", out, sizeof out) == 1 && strstr(out, "+-Y"), "camera along Y: %s", out);
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* voxgi render --method tsm writes what voxgi_render (TSM) gives with the same settings, bit for
   bit, and reports its maps; --compare measures it against direct light. */
static void test_tsm_command(void)
{
    static char out[16384];
    char pfm[512], args[1400];
    voxgi_context *ctx = NULL;
    voxgi_desc d;
    voxgi_builtin_scene bs;
    voxgi_render_desc td;
    float want[8 * 8 * 3], got[8 * 8 * 3];
    FILE *f;
    int w = 0, h = 0, y;
    snprintf(pfm, sizeof pfm, "%s/t.pfm", tmpdir);
    snprintf(args, sizeof args, "render foliage --method tsm --size 8 8 --tsm-size 64 --slices 16 --sigma 0.5 --compare 8 --json -o %s", pfm);
    TH_CHECK(run(args, out, sizeof out) == 0 && json_number(out, "maps") == 1 && json_number(out, "slices") == 16 && json_number(out, "rel_rmse") > 0,
             "tsm render: %s", out);
    memset(&d, 0, sizeof d);
    d.backend = VOXGI_BACKEND_CPU;
    voxgi_create(&d, &ctx);
    voxgi_builtin_scene_create(ctx, "foliage", &bs);
    memset(&td, 0, sizeof td);
    td.method = VOXGI_RENDER_TSM;
    td.camera = bs.camera;
    td.camera.width = td.camera.height = 8;
    td.tsm.maps.size = 64;
    td.tsm.maps.slices = 16;
    td.tsm.maps.sigma = 0.5f;
    TH_CHECK(voxgi_render(ctx, &bs.scene, &td, want, sizeof want, NULL) == VOXGI_OK, "library tsm render: %s", voxgi_last_error(ctx));
    f = fopen(pfm, "rb");
    TH_CHECK(f && fscanf(f, "PF %d %d -1.0", &w, &h) == 2 && fgetc(f) == '\n' && w == 8 && h == 8, "PFM header");
    if (f) {
        for (y = 7; y >= 0; y--) TH_CHECK(fread(got + 3 * 8 * y, 4, 24, f) == 24, "PFM rows");
        fclose(f);
        TH_CHECK(memcmp(got, want, sizeof want) == 0, "the PFM differs from the library's render");
    }
    TH_CHECK(run("render foliage --method tsm --sigma 0 -o x.png", out, sizeof out) == 2, "--sigma 0 accepted");
    snprintf(args, sizeof args, "report tsm --size 8 --spp 64 --map-sizes 16 --slices 8,16 --out %s/rt", tmpdir);
    TH_CHECK(run(args, out, sizeof out) == 0 && strstr(out, "tsm.md"), "report tsm: %s", out);
    snprintf(pfm, sizeof pfm, "%s/rt/tsm.csv", tmpdir);
    f = fopen(pfm, "r");
    {
        char line[512];
        int lines = 0, front = 0;
        while (f && fgets(line, sizeof line, f)) {
            lines++;
            front += lines > 1 && line[strlen(line) - 2] == '1';
        }
        if (f) fclose(f);
        TH_CHECK(lines == 3 && front >= 1, "tsm.csv: %d lines, %d on the front", lines, front);
    }
    TH_CHECK(run("report tsm --slices 0 --out x", out, sizeof out) == 2, "--slices 0 accepted");
    { /* --method rsm: the library's image, bit for bit */
        voxgi_builtin_scene ts;
        voxgi_render_desc qd;
        snprintf(pfm, sizeof pfm, "%s/q.pfm", tmpdir);
        snprintf(args, sizeof args, "render rsm-walls --method rsm --size 8 8 --rsm-size 32 --rsm-samples 16 --visibility hierarchical --res 16 --compare 8 --json -o %s", pfm);
        TH_CHECK(run(args, out, sizeof out) == 0 && json_number(out, "maps") == 1 && json_number(out, "rel_rmse") > 0 && strstr(out, "\"visibility\":\"hierarchical\""),
                 "rsm render: %s", out);
        voxgi_builtin_scene_create(ctx, "rsm-walls", &ts);
        memset(&qd, 0, sizeof qd);
        qd.method = VOXGI_RENDER_RSM;
        qd.camera = ts.camera;
        qd.camera.width = qd.camera.height = 8;
        qd.rsm.maps.size = 32;
        qd.rsm.maps.samples = 16;
        qd.rsm.visibility = VOXGI_TRAVERSAL_HIERARCHICAL;
        qd.resolution = 16;
        TH_CHECK(voxgi_render(ctx, &ts.scene, &qd, want, sizeof want, NULL) == VOXGI_OK, "library rsm render: %s", voxgi_last_error(ctx));
        f = fopen(pfm, "rb");
        TH_CHECK(f && fscanf(f, "PF %d %d -1.0", &w, &h) == 2 && fgetc(f) == '\n' && w == 8 && h == 8, "PFM header");
        if (f) {
            for (y = 7; y >= 0; y--) TH_CHECK(fread(got + 3 * 8 * y, 4, 24, f) == 24, "PFM rows");
            fclose(f);
            TH_CHECK(memcmp(got, want, sizeof want) == 0, "the PFM differs from the library's rsm render");
        }
        voxgi_builtin_scene_destroy(ctx, &ts);
    }
    { /* --method vao: the library's image, bit for bit, measured against the reference's AO mode */
        voxgi_builtin_scene ts;
        voxgi_render_desc ad;
        snprintf(pfm, sizeof pfm, "%s/a.pfm", tmpdir);
        snprintf(args, sizeof args, "render cornell-box --method vao --size 8 8 --rays 8 --res 24 --radius 0.1 --compare 16 --json -o %s", pfm);
        TH_CHECK(run(args, out, sizeof out) == 0 && json_number(out, "radius") > 0.099 && json_number(out, "rel_rmse") > 0, "vao render: %s", out);
        snprintf(args, sizeof args, "render cornell-box --method ssao --size 8 8 --steps 4 -o %s/s.png", tmpdir);
        TH_CHECK(run(args, out, sizeof out) == 0 && strstr(out, "depth buffer"), "ssao render: %s", out);
        voxgi_builtin_scene_create(ctx, "cornell-box", &ts);
        memset(&ad, 0, sizeof ad);
        ad.method = VOXGI_RENDER_VAO;
        ad.camera = ts.camera;
        ad.camera.width = ad.camera.height = 8;
        ad.resolution = 24;
        ad.screen.rays = 8;
        ad.screen.radius = 0.1f;
        ad.screen.half_resolution = VOXGI_TOGGLE_OFF;
        ad.screen.blur = 2; /* the command's default */
        TH_CHECK(voxgi_render(ctx, &ts.scene, &ad, want, sizeof want, NULL) == VOXGI_OK, "library ao render: %s", voxgi_last_error(ctx));
        f = fopen(pfm, "rb");
        TH_CHECK(f && fscanf(f, "PF %d %d -1.0", &w, &h) == 2 && fgetc(f) == '\n' && w == 8 && h == 8, "PFM header");
        if (f) {
            for (y = 7; y >= 0; y--) TH_CHECK(fread(got + 3 * 8 * y, 4, 24, f) == 24, "PFM rows");
            fclose(f);
            TH_CHECK(memcmp(got, want, sizeof want) == 0, "the PFM differs from the library's ao render");
        }
        voxgi_builtin_scene_destroy(ctx, &ts);
    }
    { /* --method hybrid: the library's image, bit for bit */
        voxgi_builtin_scene ts;
        voxgi_render_desc gd;
        snprintf(pfm, sizeof pfm, "%s/g.pfm", tmpdir);
        snprintf(args, sizeof args, "render cornell-box --method hybrid --size 8 8 --rays 8 --res 24 --radius 0.3 --spp 2 --half-res on --blur 2 --hidden-light on --json -o %s", pfm);
        TH_CHECK(run(args, out, sizeof out) == 0 && json_number(out, "radius") > 0.299 && strstr(out, "\"method\":\"hybrid\""), "hybrid render: %s", out);
        voxgi_builtin_scene_create(ctx, "cornell-box", &ts);
        memset(&gd, 0, sizeof gd);
        gd.method = VOXGI_RENDER_HYBRID;
        gd.camera = ts.camera;
        gd.camera.width = gd.camera.height = 8;
        gd.resolution = 24;
        gd.screen.rays = 8;
        gd.screen.radius = 0.3f;
        gd.samples = 2;
        gd.screen.half_resolution = VOXGI_TOGGLE_ON;
        gd.screen.blur = 2;
        gd.screen.hidden_light = VOXGI_TOGGLE_ON;
        TH_CHECK(voxgi_render(ctx, &ts.scene, &gd, want, sizeof want, NULL) == VOXGI_OK, "library ssgi render: %s", voxgi_last_error(ctx));
        f = fopen(pfm, "rb");
        TH_CHECK(f && fscanf(f, "PF %d %d -1.0", &w, &h) == 2 && fgetc(f) == '\n' && w == 8 && h == 8, "PFM header");
        if (f) {
            for (y = 7; y >= 0; y--) TH_CHECK(fread(got + 3 * 8 * y, 4, 24, f) == 24, "PFM rows");
            fclose(f);
            TH_CHECK(memcmp(got, want, sizeof want) == 0, "the PFM differs from the library's ssgi render");
        }
        voxgi_builtin_scene_destroy(ctx, &ts);
    }
    { /* --method linespace: the library's image, bit for bit, and the tree's memory */
        voxgi_builtin_scene ts;
        voxgi_render_desc ld;
        snprintf(pfm, sizeof pfm, "%s/l.pfm", tmpdir);
        snprintf(args, sizeof args, "render cornell-box --method linespace --size 8 8 --ls-mode fast --ls-n 3 --ls-depth 2 --samples 5 --supersample 2 --packets on --backend cpu --json -o %s", pfm);
        TH_CHECK(run(args, out, sizeof out) == 0 && json_number(out, "bytes") > 0 && json_number(out, "allocated") >= json_number(out, "bytes") &&
                     json_number(out, "rays") > 0 && strstr(out, "\"mode\":\"fast\""),
                 "linespace render: %s", out);
        voxgi_builtin_scene_create(ctx, "cornell-box", &ts);
        memset(&ld, 0, sizeof ld);
        ld.method = VOXGI_RENDER_LINESPACE;
        ld.camera = ts.camera;
        ld.camera.width = ld.camera.height = 8;
        ld.linespace.mode = VOXGI_LINESPACE_FAST;
        ld.linespace.tree.n = 3;
        ld.linespace.tree.depth = 2;
        ld.linespace.samples = 5;
        ld.linespace.supersample = 2;
        ld.linespace.packets = 1;
        TH_CHECK(voxgi_render(ctx, &ts.scene, &ld, want, sizeof want, NULL) == VOXGI_OK, "library linespace render: %s", voxgi_last_error(ctx));
        f = fopen(pfm, "rb");
        TH_CHECK(f && fscanf(f, "PF %d %d -1.0", &w, &h) == 2 && fgetc(f) == '\n' && w == 8 && h == 8, "PFM header");
        if (f) {
            for (y = 7; y >= 0; y--) TH_CHECK(fread(got + 3 * 8 * y, 4, 24, f) == 24, "PFM rows");
            fclose(f);
            TH_CHECK(memcmp(got, want, sizeof want) == 0, "the PFM differs from the library's linespace render");
        }
        snprintf(args, sizeof args, "render cornell-box --method linespace --size 8 8 --ls-n 16 --ls-depth 5 --ls-budget 1 -o %s", pfm);
        TH_CHECK(run(args, out, sizeof out) == 1 && strstr(out, "budget"), "a tree over its budget: %s", out);
        voxgi_builtin_scene_destroy(ctx, &ts);
    }
    { /* --method sh: the library's image, bit for bit */
        voxgi_builtin_scene ts;
        voxgi_render_desc hd;
        snprintf(pfm, sizeof pfm, "%s/h.pfm", tmpdir);
        snprintf(args, sizeof args, "render cornell-box --method sh --size 8 8 --res 16 --spp 2 --gather-stride 2 --opening 0.7 --json -o %s", pfm);
        TH_CHECK(run(args, out, sizeof out) == 0 && json_number(out, "gathered") > 0 && strstr(out, "\"method\":\"sh\""), "sh render: %s", out);
        voxgi_builtin_scene_create(ctx, "cornell-box", &ts);
        memset(&hd, 0, sizeof hd);
        hd.method = VOXGI_RENDER_SH;
        hd.camera = ts.camera;
        hd.camera.width = hd.camera.height = 8;
        hd.resolution = 16;
        hd.samples = 2;
        hd.sh.gather_stride = 2;
        hd.sh.opening = 0.7f;
        TH_CHECK(voxgi_render(ctx, &ts.scene, &hd, want, sizeof want, NULL) == VOXGI_OK, "library sh render: %s", voxgi_last_error(ctx));
        f = fopen(pfm, "rb");
        TH_CHECK(f && fscanf(f, "PF %d %d -1.0", &w, &h) == 2 && fgetc(f) == '\n' && w == 8 && h == 8, "PFM header");
        if (f) {
            for (y = 7; y >= 0; y--) TH_CHECK(fread(got + 3 * 8 * y, 4, 24, f) == 24, "PFM rows");
            fclose(f);
            TH_CHECK(memcmp(got, want, sizeof want) == 0, "the PFM differs from the library's sh render");
        }
        voxgi_builtin_scene_destroy(ctx, &ts);
    }
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* voxgi render --method vct writes what voxgi_render (VCT) gives with the same settings, bit for
   bit; voxgi report vct writes its table, CSV (a row per configuration, one on the Pareto front
   at least) and SVG. */
static void test_vct_and_report_commands(void)
{
    static char out[16384];
    char pfm[512], args[1400], path[600];
    voxgi_context *ctx = NULL;
    voxgi_desc d;
    voxgi_builtin_scene bs;
    voxgi_render_desc vd;
    float want[8 * 8 * 3], got[8 * 8 * 3];
    FILE *f;
    int w = 0, h = 0, y, rows = 0, front = 0;
    snprintf(pfm, sizeof pfm, "%s/v.pfm", tmpdir);
    snprintf(args, sizeof args, "render cornell-box --method vct --backend cpu --res 16 --cones 6 --size 8 8 --spp 2 --json -o %s", pfm);
    TH_CHECK(run(args, out, sizeof out) == 0 && json_number(out, "voxels") > 0 && strstr(out, "\"backend\":\"cpu\""), "vct render: %s", out);
    memset(&d, 0, sizeof d);
    d.backend = VOXGI_BACKEND_CPU;
    voxgi_create(&d, &ctx);
    voxgi_builtin_scene_create(ctx, "cornell-box", &bs);
    memset(&vd, 0, sizeof vd);
    vd.method = VOXGI_RENDER_VCT;
    vd.camera = bs.camera;
    vd.camera.width = vd.camera.height = 8;
    vd.resolution = 16;
    vd.vct.cones.cones = 6;
    vd.samples = 2;
    vd.vct.radiance = VOXGI_VCT_ANISOTROPIC; /* the tool's defaults, which the library's zeros now are too */
    vd.vct.cone_stride = 6;
    TH_CHECK(voxgi_render(ctx, &bs.scene, &vd, want, sizeof want, NULL) == VOXGI_OK, "library vct render: %s", voxgi_last_error(ctx));
    f = fopen(pfm, "rb");
    TH_CHECK(f && fscanf(f, "PF %d %d -1.0", &w, &h) == 2 && fgetc(f) == '\n' && w == 8 && h == 8, "PFM header");
    if (f) {
        for (y = 7; y >= 0; y--) TH_CHECK(fread(got + 3 * 8 * y, 4, 24, f) == 24, "PFM rows");
        fclose(f);
        TH_CHECK(memcmp(got, want, sizeof want) == 0, "the PFM differs from the library's cone-traced render");
    }
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
    snprintf(args, sizeof args, "report vct --scenes cornell-box --size 8 --spp 64 --res 8,16 --cones 4 --steps 1 --strides 1 --filters isotropic,octree --backend cpu --stage-res 16 --out %s/rep",
             tmpdir);
    TH_CHECK(run(args, out, sizeof out) == 0 && strstr(out, "vct.svg"), "report: %s", out);
    snprintf(path, sizeof path, "%s/rep/vct.csv", tmpdir);
    if ((f = fopen(path, "r")) != NULL) { /* the octree's rows measured (an octree is one-sided, the volume two-sided: test_vct
                                              holds the octree to a one-sided volume bit for bit) */
        char line[1024], err[2][2][32];
        int measured = 0;
        memset(err, 0, sizeof err);
        while (fgets(line, sizeof line, f)) {
            size_t n = strlen(line);
            char *field[20];
            int k = 0;
            if (strncmp(line, "cornell-box,", 12) != 0) continue;
            rows++;
            front += n > 2 && line[n - 2] == '1';
            for (field[k++] = strtok(line, ","); k < 20 && (field[k] = strtok(NULL, ",")) != NULL; k++) {}
            if (k == 20) snprintf(err[strcmp(field[1], "16") == 0][strcmp(field[7], "octree") == 0], 32, "%s", field[16]);
        }
        fclose(f);
        measured = atof(err[0][0]) > 0 && atof(err[0][1]) > 0 && atof(err[1][0]) > 0 && atof(err[1][1]) > 0 && atof(err[0][1]) < 1 && atof(err[1][1]) < 1;
        TH_CHECK(measured, "octree rows' errors %s %s, the isotropic volume's %s %s", err[0][1], err[1][1], err[0][0], err[1][0]);
    }
    TH_CHECK(rows == 4 && front >= 1, "CSV: %d rows, %d on the front", rows, front);
    snprintf(path, sizeof path, "%s/rep/vct.md", tmpdir);
    f = fopen(path, "r");
    memset(out, 0, sizeof out);
    TH_CHECK(f && fread(out, 1, sizeof out - 1, f) > 0 && strstr(out, "| 16 | 4 |") && strstr(out, "vct.svg"), "Markdown table");
    if (f) fclose(f);
    {   /* the stages of the defaults on the CPU and on GL: every stage timed on both (GL where a context can be made) */
        const char *stage[4] = {"| cornell-box | voxelize |", "| cornell-box | inject + mips |", "| cornell-box | cones |", "| cornell-box | total |"};
        int k, gl = strstr(out, "no GL 4.5 context could be made") == NULL;
        if (!gl) printf("    SKIPPED (loudly): no GL 4.5 context for the report's stages; the CPU's alone checked\n");
        for (k = 0; k < 4; k++) {
            const char *at = strstr(out, stage[k]);
            double cpu = 0, glt = 0;
            TH_CHECK(at && sscanf(at + strlen(stage[k]), " %lf | %lf |", &cpu, &glt) >= 1 && cpu > 0 && (!gl || glt > 0),
                     "the stages' row %s: CPU %g, GL %g", stage[k], cpu, glt);
        }
    }
    snprintf(path, sizeof path, "%s/rep/vct.svg", tmpdir);
    memset(out, 0, 8);
    f = fopen(path, "r");
    TH_CHECK(f && fread(out, 1, 4, f) == 4 && memcmp(out, "<svg", 4) == 0, "SVG");
    if (f) fclose(f);
    TH_CHECK(run("report vct --res 0", out, sizeof out) == 2 && run("report vct --filters sideways", out, sizeof out) == 2 &&
             run("report nothing", out, sizeof out) == 2, "bad report arguments accepted");
}

static void test_info_and_bench(void)
{
    static char out[16384];
    int rc = run("info --json", out, sizeof out);
    TH_CHECK(rc == 0 && strstr(out, "\"version\":\"" VOXGI_VERSION_STRING "\"") && strstr(out, "\"gl\":["), "info: %s", out);
    rc = run("bench voxelize --min-res 8 --max-res 16 --runs 1 --no-gl --methods conservative,thin", out, sizeof out);
    TH_CHECK(rc == 0 && strstr(out, "Table 1") && strstr(out, "Table 3") && strstr(out, "builtin:cube"), "bench: %s", out);
    /* the quad [-1,1]^2 fills N-2 columns per axis (one voxel of padding) and lies on the
       grid's middle plane, so it touches two slices: 2 (N-2)^2 = 72 and 392 */
    TH_CHECK(strstr(out, "| builtin:quad | conservative | 72 | 392 |") != NULL, "quad counts: %s", out);
    TH_CHECK(strstr(out, "| builtin:quad | conservative | 0 / 0 | 0 / 0 |") != NULL, "conservative against itself: %s", out);
    /* Table 4: the closed cube's parity interior agrees with the winding number at every sampled
       centre; the open quad's parity fills the half space above it, which vote undoes */
    rc = run("bench voxelize --min-res 16 --max-res 16 --runs 1 --no-gl --methods solid,solid-vote --inside-samples 1000", out, sizeof out);
    TH_CHECK(rc == 0 && strstr(out, "Table 4") && strstr(out, "| builtin:cube | solid | 0.00% (") &&
             strstr(out, "| builtin:quad | solid-vote | 0.00% (") && !strstr(out, "| builtin:quad | solid | 0.00% ("), "bench solid: %s", out);
    /* bench rays: both sets measured; the camera sees the sphere (it fills about a quarter of the view: the
       bounding sphere holds the sphere's box), and about a third of the segments across the bounding
       sphere pass through the sphere of radius r / sqrt(3) */
    rc = run("bench rays builtin:sphere --rays 3000 --runs 1 --threads 2 --json", out, sizeof out);
    TH_CHECK(rc == 0 && json_number(out, "coherent_intersect_mrays") > 0 && json_number(out, "incoherent_occluded_mrays") > 0 &&
                 json_number(out, "coherent_rays") == 262144 && json_number(out, "incoherent_rays") == 3000,
             "bench rays: %s", out);
    TH_CHECK(json_number(out, "coherent_hits") > 0.15 * 262144 && json_number(out, "coherent_hits") < 0.35 * 262144 &&
                 json_number(out, "incoherent_occluded") > 0.2 * 3000 && json_number(out, "incoherent_occluded") < 0.5 * 3000,
             "bench rays counts: %s", out);
    TH_CHECK(run("bench rays", out, sizeof out) == 2 && run("bench rays builtin:sphere --rays 0", out, sizeof out) == 2, "bench rays: bad arguments accepted");
}

static int count_of(const char *hay, const char *needle)
{
    int n = 0;
    for (; (hay = strstr(hay, needle)) != NULL; hay += strlen(needle)) n++;
    return n;
}

/* --compare against a black reference (the leak box: every light outside a closed box) has no
   relative error: the JSON says null, never inf, and gives the RMS difference instead. */
static void test_compare_black_reference(void)
{
    static char out[8192];
    char pfm[512], args[1000];
    int rc;
    snprintf(pfm, sizeof pfm, "%s/leak.pfm", tmpdir);
    snprintf(args, sizeof args, "render leak-box --method vct --backend cpu --res 16 --compare 4 --size 8 8 --spp 2 --json -o %s", pfm);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 0 && strstr(out, "\"rel_rmse\":null,\"rms\":") && !strstr(out, "inf"), "leak box: %s", out);
}

/* A PFM of w x h pixels into rgb (rows from the top, as the tool's images are); 1 on success. */
static int read_pfm(const char *path, int w, int h, float *rgb)
{
    FILE *f = fopen(path, "rb");
    int fw = 0, fh = 0, y, ok;
    if (!f) return 0;
    ok = fscanf(f, "PF %d %d -1.0", &fw, &fh) == 2 && fgetc(f) == '\n' && fw == w && fh == h;
    for (y = h - 1; ok && y >= 0; y--) ok = fread(rgb + 3 * (size_t)w * (size_t)y, 4, 3 * (size_t)w, f) == 3 * (size_t)w;
    fclose(f);
    return ok;
}

/* The JSON's "mean":[r,g,b]; 1 when found. */
static int json_mean(const char *json, double mean[3])
{
    const char *at = strstr(json, "\"mean\":[");
    char *end;
    int i;
    if (!at) return 0;
    at += 8;
    for (i = 0; i < 3; i++) {
        mean[i] = strtod(at, &end);
        if (end == at) return 0;
        at = end + 1;
    }
    return 1;
}

/* --reference: the error against a PFM rendered before, by --compare's rule. The image itself
   gives 0 exactly; another seed gives the error with the same pixels masked as --compare's; a
   big-endian copy of the reference reads the same; a reference of another size, a truncated one
   and --compare with it are refused. */
static void test_reference_file(void)
{
    static char out[8192];
    char args[1600], ref[512], big[512], cut[512], img[512];
    FILE *f, *g;
    int rc, c;
    long at = 0;
    snprintf(ref, sizeof ref, "%s/ref.pfm", tmpdir);
    snprintf(big, sizeof big, "%s/big.pfm", tmpdir);
    snprintf(cut, sizeof cut, "%s/cut.pfm", tmpdir);
    snprintf(img, sizeof img, "%s/img.pfm", tmpdir);
    snprintf(args, sizeof args, "render cornell-box --size 24 24 --spp 8 -o %s", ref);
    TH_CHECK(run(args, out, sizeof out) == 0, "reference: %s", out);
    snprintf(args, sizeof args, "render cornell-box --size 24 24 --spp 8 --reference %s --json -o %s", ref, img);
    TH_CHECK(run(args, out, sizeof out) == 0 && json_number(out, "rel_rmse") == 0 && json_number(out, "masked_pixels") > 0, "itself: %s", out);
    snprintf(args, sizeof args, "render cornell-box --size 24 24 --spp 8 --seed 2 --reference %s --json -o %s", ref, img);
    TH_CHECK(run(args, out, sizeof out) == 0 && json_number(out, "rel_rmse") > 0.05, "another seed: %s", out);
    {
        double masked = json_number(out, "masked_pixels");
        snprintf(args, sizeof args, "render cornell-box --size 24 24 --spp 8 --compare 4 --json -o %s", img);
        TH_CHECK(run(args, out, sizeof out) == 0 && json_number(out, "masked_pixels") == masked, "--compare masks %g, --reference %g: %s",
                 json_number(out, "masked_pixels"), masked, out);
    }
    f = fopen(ref, "rb"); /* the same image big endian (scale +1), and cut short */
    g = fopen(big, "wb");
    TH_CHECK(f && g, "cannot copy the PFM");
    if (f && g) {
        char head[64];
        int lines = 0, k = 0;
        while (lines < 3 && (c = fgetc(f)) != EOF) { head[k++] = (char)c; lines += c == '\n'; }
        head[k] = 0;
        fputs("PF\n24 24\n1.0\n", g);
        at = ftell(f);
        for (;;) {
            unsigned char b[4];
            if (fread(b, 1, 4, f) != 4) break;
            fputc(b[3], g); fputc(b[2], g); fputc(b[1], g); fputc(b[0], g);
        }
        TH_CHECK(strncmp(head, "PF\n24 24\n-1", 11) == 0, "header %s", head);
    }
    if (f) fclose(f);
    if (g) fclose(g);
    snprintf(args, sizeof args, "render cornell-box --size 24 24 --spp 8 --reference %s --json -o %s", big, img);
    TH_CHECK(run(args, out, sizeof out) == 0 && json_number(out, "rel_rmse") == 0, "big endian: %s", out);
    f = fopen(ref, "rb");
    g = fopen(cut, "wb");
    if (f && g) {
        long k;
        for (k = 0; k < at + 100 && (c = fgetc(f)) != EOF; k++) fputc(c, g);
    }
    if (f) fclose(f);
    if (g) fclose(g);
    snprintf(args, sizeof args, "render cornell-box --size 24 24 --spp 8 --reference %s -o %s", cut, img);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 1 && strstr(out, "fewer pixels"), "truncated: exit %d: %s", rc, out);
    snprintf(args, sizeof args, "render cornell-box --size 16 16 --spp 8 --reference %s -o %s", ref, img);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 1 && strstr(out, "24 x 24, the image 16 x 16"), "another size: exit %d: %s", rc, out);
    snprintf(args, sizeof args, "render cornell-box --size 24 24 --compare 4 --reference %s -o %s", ref, img);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "one or the other"), "both: exit %d: %s", rc, out);
}

/* --compare's error leaves out every pixel within 3 (Chebyshev) of a pixel whose centre sees an
   emitter: masked_pixels is the count of the test's own dilation of the library's G-buffer (the
   Cornell box's light), 0 where the camera sees no emitter (rsm-walls), and rel_rmse is the
   test's own relative RMSE over the kept pixels of the written image and of the reference rendered
   alone with the seed --compare uses (the image's seed + 1000003). Outside the mask neither
   holds any of the emission the camera sees, so the images with it give the same error there. */
static void test_compare_masks_emitters(void)
{
    enum { W = 64, H = 64 };
    static char out[8192];
    static float img[W * H * 3], ref[W * H * 3];
    static uint32_t tri[W * H];
    static unsigned char sees[W * H], masked[W * H];
    char pfm[512], rpfm[512], args[1200];
    voxgi_context *ctx = NULL;
    voxgi_desc d;
    voxgi_builtin_scene bs;
    voxgi_camera cam;
    double sq = 0, sum = 0, sq_all = 0, sum_all = 0, mine, all, theirs;
    int x, y, dx, dy, count = 0, kept = 0, c;
    snprintf(pfm, sizeof pfm, "%s/m.pfm", tmpdir);
    snprintf(rpfm, sizeof rpfm, "%s/mref.pfm", tmpdir);
    snprintf(args, sizeof args, "render cornell-box --method vct --backend cpu --res 16 --cones 6 --size %d %d --spp 2 --compare 8 --json -o %s", W, H, pfm);
    TH_CHECK(run(args, out, sizeof out) == 0, "vct --compare: %s", out);
    theirs = json_number(out, "rel_rmse");
    TH_CHECK(json_number(out, "masked_pixels") > 0, "no pixel masked on the Cornell box: %s", out);
    memset(&d, 0, sizeof d);
    d.backend = VOXGI_BACKEND_CPU;
    voxgi_create(&d, &ctx);
    voxgi_builtin_scene_create(ctx, "cornell-box", &bs);
    cam = bs.camera;
    cam.width = W;
    cam.height = H;
    TH_CHECK(voxgi_gbuffer_render(ctx, &bs.scene, &cam, NULL, NULL, tri) == VOXGI_OK, "G-buffer");
    for (x = 0; x < W * H; x++) { /* the built-in box is one mesh: its triangle ids are the scene's */
        const voxgi_mesh *m = &bs.scene.meshes[0];
        const float *e = tri[x] == UINT32_MAX ? NULL : bs.scene.materials[m->material_ids ? m->material_ids[tri[x]] : m->material].emission;
        sees[x] = e && (e[0] > 0 || e[1] > 0 || e[2] > 0);
    }
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            masked[y * W + x] = 0;
            for (dy = -3; dy <= 3; dy++)
                for (dx = -3; dx <= 3; dx++)
                    if (y + dy >= 0 && y + dy < H && x + dx >= 0 && x + dx < W && sees[(y + dy) * W + x + dx]) masked[y * W + x] = 1;
            count += masked[y * W + x];
        }
    TH_CHECK(count > 0 && count < W * H && json_number(out, "masked_pixels") == count, "masked_pixels %g, the test's own dilation %d: %s",
             json_number(out, "masked_pixels"), count, out);
    snprintf(args, sizeof args, "render cornell-box --size %d %d --spp 8 --seed 1000003 --json -o %s", W, H, rpfm);
    TH_CHECK(run(args, out, sizeof out) == 0, "reference: %s", out);
    TH_CHECK(read_pfm(pfm, W, H, img) && read_pfm(rpfm, W, H, ref), "PFMs");
    for (x = 0; x < W * H; x++)
        for (c = 0; c < 3; c++) {
            double dd = (double)img[3 * x + c] - ref[3 * x + c];
            sq_all += dd * dd;
            sum_all += ref[3 * x + c];
            if (masked[x]) continue;
            sq += dd * dd;
            sum += ref[3 * x + c];
            kept += c == 0;
        }
    mine = sqrt(sq / (3.0 * kept)) / (sum / (3.0 * kept));
    all = sqrt(sq_all / (3.0 * W * H)) / (sum_all / (3.0 * W * H));
    TH_CHECK(fabs(theirs - mine) <= 1e-5 * mine, "rel_rmse %.6g, the test's own over the kept pixels %.6g (over every pixel %.6g)", theirs, mine, all);
    TH_CHECK(fabs(all - mine) > 0.1 * mine, "the mask makes no difference here (%.6g with it, %.6g without): the test proves nothing", mine, all);
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
    snprintf(args, sizeof args, "render rsm-walls --method vct --backend cpu --res 16 --cones 6 --size 32 32 --spp 2 --compare 4 --json -o %s", pfm);
    TH_CHECK(run(args, out, sizeof out) == 0 && strstr(out, "\"masked_pixels\":0,") && json_number(out, "rel_rmse") > 0,
             "rsm-walls: no emitter in view, nothing masked: %s", out);
    /* the report measures by the same rule: its table says how many pixels it left out */
    snprintf(args, sizeof args, "report vct --scenes cornell-box --size %d --spp 64 --res 8 --cones 4 --steps 1 --strides 1 --filters isotropic --backend cpu --no-stages --out %s/rm",
             W, tmpdir);
    TH_CHECK(run(args, out, sizeof out) == 0, "report: %s", out);
    snprintf(args, sizeof args, "%d of %d pixels near an emitter left out", count, W * H);
    TH_CHECK(strstr(out, args) != NULL, "the report's mask is not render's (%s): %s", args, out);
}

/* --cornell-mesh: the Cornell box with a mesh for its tall block (its 10 triangles out, the mesh's
   in), rendered by both methods with a mean radiance close to the box's own; a scene other than
   cornell-box is a usage error, a mesh that cannot be read a failure; the report adds the scene. */
static void test_cornell_mesh(void)
{
    static char out[16384];
    char pfm[512], args[1200], path[600];
    double box[3], with[3];
    FILE *f;
    int i, rc, rows = 0;
    snprintf(pfm, sizeof pfm, "%s/cm.pfm", tmpdir);
    snprintf(args, sizeof args, "render cornell-box --size 16 16 --spp 32 --json -o %s", pfm);
    TH_CHECK(run(args, out, sizeof out) == 0 && json_mean(out, box), "box: %s", out);
    snprintf(args, sizeof args, "render cornell-box --cornell-mesh builtin:sphere --size 16 16 --spp 32 --json -o %s", pfm);
    rc = run(args, out, sizeof out);
    /* the box's 32 triangles less the tall block's 10, and the sphere's 96 x 64 x 2 */
    TH_CHECK(rc == 0 && json_number(out, "triangles") == 22 + 96 * 64 * 2 && strstr(out, "\"scene\":\"cornell-box+builtin:sphere\""), "sphere: exit %d: %s", rc, out);
    TH_CHECK(json_mean(out, with), "mean: %s", out);
    for (i = 0; i < 3; i++)
        TH_CHECK(with[i] > 0.8 * box[i] && with[i] < 1.25 * box[i], "channel %d: mean %g with the sphere, %g with the block", i, with[i], box[i]);
    snprintf(args, sizeof args, "render cornell-box --cornell-mesh builtin:sphere --method vct --backend cpu --res 16 --cones 6 --size 16 16 --spp 2 --json -o %s", pfm);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 0 && json_mean(out, with) && json_number(out, "voxels") > 0, "vct: exit %d: %s", rc, out);
    for (i = 0; i < 3; i++) TH_CHECK(with[i] > 0.5 * box[i] && with[i] < 2 * box[i], "vct channel %d: mean %g, the box's %g", i, with[i], box[i]);
    rc = run("render rsm-walls --cornell-mesh builtin:sphere -o x.png", out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "--cornell-mesh") && count_of(out, "\n") == 1, "another scene: exit %d: %s", rc, out);
    rc = run("render builtin:cube --cornell-mesh builtin:sphere -o x.png", out, sizeof out);
    TH_CHECK(rc == 2, "a mesh scene: exit %d: %s", rc, out);
    rc = run("render cornell-box --cornell-mesh /nonexistent/mesh.obj -o x.png", out, sizeof out);
    TH_CHECK(rc == 1 && strstr(out, "/nonexistent/mesh.obj") && count_of(out, "\n") == 1, "missing mesh: exit %d: %s", rc, out);
    snprintf(args, sizeof args, "report vct --scenes rsm-walls --cornell-mesh builtin:nothing --size 8 --spp 64 --res 8 --cones 4 --steps 1 --strides 1 --filters isotropic --backend cpu --no-stages --out %s/rc", tmpdir);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 1 && strstr(out, "builtin:nothing") && !strstr(out, "rsm-walls ("), "report, unknown shape (before any work): exit %d: %s", rc, out);
    snprintf(args, sizeof args, "report vct --scenes rsm-walls --cornell-mesh builtin:sphere --size 8 --spp 64 --res 8 --cones 4 --steps 1 --strides 1 --filters isotropic --backend cpu --no-stages --out %s/rc", tmpdir);
    TH_CHECK(run(args, out, sizeof out) == 0 && strstr(out, "cornell-box+builtin:sphere ("), "report: %s", out);
    snprintf(path, sizeof path, "%s/rc/vct.csv", tmpdir);
    if ((f = fopen(path, "r")) != NULL) {
        char line[1024];
        while (fgets(line, sizeof line, f)) rows += strncmp(line, "cornell-box+builtin:sphere,", 27) == 0;
        fclose(f);
    }
    TH_CHECK(rows == 1, "the report's CSV has %d rows of the Cornell box with the sphere", rows);
}

/* Every command parses its options from one table: an unknown option, a missing value and a bad
   value are each named, in one line, with exit status 2 and a pointer to the command's --help. */
static void test_usage_errors_named(void)
{
    static char out[8192];
    const char *cmds[] = {"voxelize builtin:cube", "info", "bench voxelize", "svo builtin:cube", "render cornell-box -o x.png", "report vct"};
    const char *names[] = {"voxelize", "info", "bench", "svo", "render", "report vct"};
    char args[256], want[128];
    size_t i;
    int rc;
    for (i = 0; i < sizeof cmds / sizeof cmds[0]; i++) {
        snprintf(args, sizeof args, "%s --foo", cmds[i]);
        rc = run(args, out, sizeof out);
        snprintf(want, sizeof want, "voxgi %s: unknown option '--foo' (see 'voxgi %s --help')\n", names[i], names[i]);
        TH_CHECK(rc == 2 && strcmp(out, want) == 0, "'%s': exit %d: %s", args, rc, out);
    }
    rc = run("render cornell-box -o x.png --res", out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "--res needs a value") && count_of(out, "\n") == 1, "missing value: exit %d: %s", rc, out);
    rc = run("render cornell-box --res x -o x.png", out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "--res needs 1..4096, got 'x'") && count_of(out, "\n") == 1, "bad value: exit %d: %s", rc, out);
    rc = run("render cornell-box -o x.png --size 8", out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "--size needs 2 values"), "missing second value: exit %d: %s", rc, out);
    rc = run("voxelize builtin:cube --grid 0 0 0 1 4 4", out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "--grid needs 7 values"), "short --grid: exit %d: %s", rc, out);
    rc = run("svo builtin:cube --threads 0", out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "--threads needs 1..256, got '0'"), "--threads 0: exit %d: %s", rc, out);
    rc = run("voxelize builtin:cube --backend vulkan", out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "--backend needs one of auto, cpu, gl, got 'vulkan'"), "--backend: exit %d: %s", rc, out);
    rc = run("voxelize builtin:cube --blend max,add", out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "--blend needs 4 comma-separated values"), "--blend: exit %d: %s", rc, out);
    rc = run("render cornell-box --bounces -1 --spp 1 --size 2 2 --json -o /nonexistent/dir/x.pfm", out, sizeof out);
    TH_CHECK(rc == 1 && strstr(out, "cannot write"), "a value starting with '-' is a value: exit %d: %s", rc, out);
    rc = run("voxelize", out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "no mesh given"), "no mesh: exit %d: %s", rc, out);
    rc = run("info extra", out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "unexpected argument 'extra'"), "operand to info: exit %d: %s", rc, out);
}

/* -o by its extension, in any case: voxelize writes .binvox, .vox, .npy, .ply and .obj (each
   recognised by its first bytes; voxgi_io.h's exports, tested in test_io_export) and refuses any
   other extension naming these; render PNG and PFM only; a refused name stops the command before
   any work. */
static void test_output_extensions(void)
{
    static const char *const exts[4][2] = {{"VOX", "VOX "}, {"npy", "\x93NUMPY"}, {"Ply", "ply\n"}, {"obj", "# voxgi"}};
    static char out[8192];
    char path[512], args[1024];
    FILE *f;
    int rc, e;
    for (e = 0; e < 4; e++) {
        char head[8] = {0};
        size_t n = strlen(exts[e][1]);
        snprintf(path, sizeof path, "%s/out.%s", tmpdir, exts[e][0]);
        snprintf(args, sizeof args, "voxelize builtin:cube --res 8 --backend cpu -o %s", path);
        rc = run(args, out, sizeof out);
        f = fopen(path, "rb");
        TH_CHECK(rc == 0 && f && fread(head, 1, n, f) == n && !memcmp(head, exts[e][1], n), ".%s: exit %d: %s", exts[e][0], rc, out);
        if (f) fclose(f);
    }
    rc = run("voxelize builtin:nothing -o out.txt", out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "out.txt") && strstr(out, ".binvox, .vox, .npy, .ply or .obj") && !strstr(out, "built-in"), ".txt, before the mesh: exit %d: %s",
             rc, out);
    snprintf(path, sizeof path, "%s/UPPER.BINVOX", tmpdir);
    snprintf(args, sizeof args, "voxelize builtin:cube --res 8 --backend cpu -o %s", path);
    rc = run(args, out, sizeof out);
    f = fopen(path, "rb");
    TH_CHECK(rc == 0 && f != NULL, ".BINVOX: exit %d: %s", rc, out);
    if (f) fclose(f);
    /* the scene is looked up by the library, after the check: a .jpg must be refused first */
    rc = run("render no-such-scene --spp 16777216 -o x.jpg", out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "x.jpg") && strstr(out, ".png or .pfm") && !strstr(out, "no-such-scene"), ".jpg before work: exit %d: %s", rc, out);
    rc = run("render cornell-box -o x.png.txt", out, sizeof out);
    TH_CHECK(rc == 2, "x.png.txt accepted: exit %d: %s", rc, out);
    rc = run("render cornell-box", out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "-o"), "no -o: exit %d: %s", rc, out);
    snprintf(path, sizeof path, "%s/CAPS.PFM", tmpdir);
    snprintf(args, sizeof args, "render cornell-box --spp 1 --size 3 2 -o %s", path);
    rc = run(args, out, sizeof out);
    f = fopen(path, "rb");
    TH_CHECK(rc == 0 && f && fread(out, 1, 3, f) == 3 && memcmp(out, "PF\n", 3) == 0, ".PFM is written as PFM: exit %d", rc);
    if (f) fclose(f);
}

/* A .npy the tool wrote: its header must state dtype `descr` and shape `shape` (as numpy writes it,
   "(12, 12, 12, 3)"), and its data hold `count` elements of `size` bytes; the data from malloc, or NULL. */
static unsigned char *read_npy(const char *path, const char *descr, const char *shape, size_t count, size_t size)
{
    FILE *f = fopen(path, "rb");
    unsigned char head[10], *data = NULL;
    char header[512], want[96];
    size_t hlen = 0;
    int ok = f && fread(head, 1, 10, f) == 10 && !memcmp(head, "\x93NUMPY\x01\x00", 8) && (hlen = (size_t)head[8] | (size_t)head[9] << 8) < sizeof header &&
             fread(header, 1, hlen, f) == hlen;
    TH_CHECK(ok, "%s: no .npy 1.0 header", path);
    if (ok) {
        header[hlen] = 0;
        snprintf(want, sizeof want, "'descr': '%s'", descr);
        TH_CHECK(strstr(header, want) && strstr(header, "'fortran_order': False"), "%s: not %s in C order: %s", path, descr, header);
        snprintf(want, sizeof want, "'shape': %s", shape);
        TH_CHECK(strstr(header, want) != NULL, "%s: not of shape %s: %s", path, shape, header);
        data = (unsigned char *)malloc(count * size + 1);
        TH_CHECK(data && fread(data, 1, count * size + 1, f) == count * size, "%s: not %lu elements of %lu bytes", path, (unsigned long)count,
                 (unsigned long)size);
    }
    if (f) fclose(f);
    return data;
}

static float le_f32(const unsigned char *p)
{
    uint32_t u = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
    float v;
    memcpy(&v, &u, 4);
    return v;
}

/* voxelize -o FILE.npy --npy-attribute: the cube [-1,1]^3 of one material (Kd 0.2 0.4 0.6, d 0.5)
   on the grid whose planes pass through its faces (784 voxels set, as above). The occupancy .npy
   names the set voxels; the albedo .npy ('<f4', (12, 12, 12, 3)) holds Kd at each of them (a mean
   of equal values: within float rounding) and 0 elsewhere, the opacity .npy ('<f4', (12, 12, 12))
   0.5. The option is listed in --help, and refused (exit 2, one line naming it) without a .npy
   output or with an unknown attribute. */
static void test_voxelize_npy_attribute(void)
{
    static char out[8192];
    char mesh[512], path[512], args[1024];
    const char *grid = "--grid -1.5 -1.5 -1.5 0.25 12 12 12 --backend cpu";
    unsigned char *occ, *albedo, *opacity;
    size_t i, set = 0, bad = 0;
    int rc;
    write_file("painted.mtl", "newmtl paint\nKd 0.2 0.4 0.6\nd 0.5\n", path, sizeof path);
    write_file("painted.obj", "mtllib painted.mtl\nv -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\nusemtl paint\n"
                              "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n", mesh, sizeof mesh);
    rc = run("voxelize --help", out, sizeof out);
    TH_CHECK(rc == 0 && strstr(out, "--npy-attribute NAME"), "--npy-attribute not in voxelize --help: %s", out);
    snprintf(args, sizeof args, "voxelize %s %s -o %s/occupancy.npy", mesh, grid, tmpdir);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 0, "occupancy: exit %d: %s", rc, out);
    snprintf(args, sizeof args, "voxelize %s %s -o %s/albedo.npy --npy-attribute albedo", mesh, grid, tmpdir);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 0, "albedo: exit %d: %s", rc, out);
    snprintf(args, sizeof args, "voxelize %s %s --npy-attribute opacity -o %s/opacity.npy", mesh, grid, tmpdir);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 0, "opacity: exit %d: %s", rc, out);
    snprintf(path, sizeof path, "%s/occupancy.npy", tmpdir);
    occ = read_npy(path, "|u1", "(12, 12, 12)", 1728, 1);
    snprintf(path, sizeof path, "%s/albedo.npy", tmpdir);
    albedo = read_npy(path, "<f4", "(12, 12, 12, 3)", 1728 * 3, 4);
    snprintf(path, sizeof path, "%s/opacity.npy", tmpdir);
    opacity = read_npy(path, "<f4", "(12, 12, 12)", 1728, 4);
    for (i = 0; occ && albedo && opacity && i < 1728; i++) {
        static const float kd[3] = {0.2f, 0.4f, 0.6f};
        int c;
        set += occ[i] == 1;
        for (c = 0; c < 3; c++) {
            float v = le_f32(albedo + 4 * (3 * i + (size_t)c));
            bad += occ[i] ? !(fabsf(v - kd[c]) <= 1e-6f) : v != 0;
        }
        bad += occ[i] ? !(fabsf(le_f32(opacity + 4 * i) - 0.5f) <= 1e-6f) : le_f32(opacity + 4 * i) != 0;
    }
    TH_CHECK(set == 784 && bad == 0, "%lu voxels set (784 expected), %lu attribute values differ from the material's", (unsigned long)set, (unsigned long)bad);
    free(occ);
    free(albedo);
    free(opacity);
    snprintf(args, sizeof args, "voxelize %s %s --npy-attribute albedo", mesh, grid);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "--npy-attribute") && strstr(out, "-o FILE.npy") && count_of(out, "\n") == 1, "no output: exit %d: %s", rc, out);
    snprintf(args, sizeof args, "voxelize %s %s --npy-attribute albedo -o %s/albedo.vox", mesh, grid, tmpdir);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "--npy-attribute") && strstr(out, "-o FILE.npy") && count_of(out, "\n") == 1, ".vox output: exit %d: %s", rc, out);
    snprintf(args, sizeof args, "voxelize %s %s --npy-attribute colour -o %s/x.npy", mesh, grid, tmpdir);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "--npy-attribute needs one of albedo, normal, emission, opacity, got 'colour'"), "unknown attribute: exit %d: %s", rc, out);
}

static void test_version_and_exit_codes_documented(void)
{
    static char out[8192];
    int rc = run("--version", out, sizeof out);
    TH_CHECK(rc == 0 && strcmp(out, "voxgi " VOXGI_VERSION_STRING "\n") == 0, "--version: exit %d: %s", rc, out);
    rc = run("--help", out, sizeof out);
    TH_CHECK(rc == 0 && strstr(out, "--version") && strstr(out, "Exit status") && strstr(out, "  0  success") &&
             strstr(out, "  1  failure while running") && strstr(out, "  2  usage error"), "--help: %s", out);
}

/* A failed library call is said once, in one line (the log callback does not repeat it). */
static void test_library_error_once(void)
{
    static char out[8192];
    int rc = run("voxelize builtin:cube --method atlas --atlas-uv mesh --backend cpu", out, sizeof out);
    TH_CHECK(rc == 1 && count_of(out, "has no uvs") == 1 && count_of(out, "\n") == 1 && strncmp(out, "voxgi voxelize: builtin:cube: ", 30) == 0,
             "exit %d: %s", rc, out);
    rc = run("voxelize builtin:cube --grid 0 0 0 -1 4 4 4 --backend cpu", out, sizeof out);
    TH_CHECK(rc == 1 && count_of(out, "voxel size") == 1 && count_of(out, "\n") == 1, "bad grid: exit %d: %s", rc, out);
    rc = run("render no-such-scene -o x.png", out, sizeof out);
    TH_CHECK(rc == 1 && count_of(out, "no-such-scene") == 1 && count_of(out, "\n") == 1, "unknown scene: exit %d: %s", rc, out);
    rc = run("svo builtin:cube --res 8 --backend cpu --attributes albedo --format float16 --json", out, sizeof out);
    TH_CHECK(rc == 0 && count_of(out, "\n") == 1 && out[0] == '{', "svo: nothing but the JSON: %s", out);
}

/* Exit status: 0 success, 1 a failure while running, 2 a usage error; for every command. */
static void test_exit_codes(void)
{
    static char out[16384];
    char args[1024];
    int rc;
    TH_CHECK(run("svo builtin:cube --res 8 --backend cpu", out, sizeof out) == 0, "svo: %s", out);
    /* a combination of options no render can honour is a usage error too, found before any work */
    rc = run("render no-such-scene --method vct --bounces 0 -o x.png", out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "--bounces 1 or more") && !strstr(out, "no-such-scene"), "vct without bounces: exit %d: %s", rc, out);
    rc = run("render cornell-box --method vct --isotropic --anisotropic -o x.png", out, sizeof out);
    TH_CHECK(rc == 2 && strstr(out, "one or the other"), "both mips: exit %d: %s", rc, out);
    TH_CHECK(run("svo /nonexistent/mesh.obj --backend cpu", out, sizeof out) == 1, "svo, missing mesh: %s", out);
    TH_CHECK(run("svo builtin:cube --res 8 --backend cpu --format float64", out, sizeof out) == 2, "svo, bad format: %s", out);
    /* bench opens every mesh before measuring anything */
    rc = run("bench voxelize /nonexistent/mesh.obj --min-res 8 --max-res 8 --runs 1 --no-gl", out, sizeof out);
    TH_CHECK(rc == 1 && strstr(out, "/nonexistent/mesh.obj") && !strstr(out, "Table 1"), "bench, missing mesh: exit %d: %s", rc, out);
    TH_CHECK(run("bench voxelize --min-res 64 --max-res 32", out, sizeof out) == 2, "bench, empty range: %s", out);
    TH_CHECK(run("bench", out, sizeof out) == 2, "bench without a benchmark: %s", out);
    snprintf(args, sizeof args, "report vct --scenes nowhere --size 8 --spp 64 --res 8 --cones 4 --steps 1 --strides 1 --filters isotropic --backend cpu --out %s/r2", tmpdir);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 1 && count_of(out, "no built-in scene") == 1, "report, unknown scene: exit %d: %s", rc, out);
    TH_CHECK(run("report vct --scenes a,b,c,d,e,f,g,h,i", out, sizeof out) == 2, "report, nine scenes: %s", out);
    TH_CHECK(run("report", out, sizeof out) == 2, "report without a report: %s", out);
}

/* The rows of a report's CSV (the header left out) and how many are on the front (the last
   column 1); -1 when it cannot be read. */
static int csv_rows(const char *path, int *front)
{
    char line[1024];
    int lines = 0;
    FILE *f = fopen(path, "r");
    *front = 0;
    if (!f) return -1;
    while (fgets(line, sizeof line, f)) {
        lines++;
        *front += lines > 1 && strlen(line) >= 2 && line[strlen(line) - 2] == '1';
    }
    fclose(f);
    return lines - 1;
}

/* voxgi report rsm and report sh: a row per configuration (visibilities x the parameter lists),
   one on the front at least, the traversals agreeing on every segment inside the grid. */
static void test_bounce_reports(void)
{
    static char out[16384];
    char args[1024], path[512];
    int rows, front;
    snprintf(args, sizeof args, "report rsm --scenes cornell-box --size 12 --spp 64 --map-sizes 32 --samples 8,16 --radii 1 --points 1 --strides 1,2 --visibility dda,hierarchical,none "
                                "--segments 2000 --out %s/rr", tmpdir);
    TH_CHECK(run(args, out, sizeof out) == 0 && strstr(out, "rsm.md") && strstr(out, ", 0 disagree"), "report rsm: %s", out);
    snprintf(path, sizeof path, "%s/rr/rsm.csv", tmpdir);
    rows = csv_rows(path, &front);
    TH_CHECK(rows == 12 && front >= 1, "rsm.csv: %d rows, %d on the front", rows, front);
    snprintf(args, sizeof args, "report sh --scenes rsm-walls --size 12 --spp 64 --res 8,16 --openings 0.5 --strides 2 --visibility none --out %s/rr", tmpdir);
    TH_CHECK(run(args, out, sizeof out) == 0 && strstr(out, "sh.md"), "report sh: %s", out);
    snprintf(path, sizeof path, "%s/rr/sh.csv", tmpdir);
    rows = csv_rows(path, &front);
    TH_CHECK(rows == 2 && front >= 1, "sh.csv: %d rows, %d on the front", rows, front);
    TH_CHECK(run("report rsm --radii 3 --out x", out, sizeof out) == 2 && run("report sh --visibility sideways --out x", out, sizeof out) == 2,
             "bad lists accepted: %s", out);
}

/* voxgi report ao and report ssgi at a tiny size: a row per configuration of the one-parameter
   sweeps (each once), one on the front at least, and their own sections in the Markdown. */
static void test_screen_reports(void)
{
    static char out[16384];
    char args[1024], path[512];
    int rows, front;
    FILE *f;
    /* ao: ssao rays 4 and 16 (the base), steps 8, blur 2 at full and half resolution: 5; point
       sampling (no steps): 4; vao rays 4, 16, res 16, blur 2 full and half: 5 */
    snprintf(args, sizeof args, "report ao --size 8 8 --spp 64 --rays 4 --steps 8 --radii 0.1 --res 16 --blurs 2 --out %s/ra", tmpdir);
    TH_CHECK(run(args, out, sizeof out) == 0 && strstr(out, "ao.md") && strstr(out, "view-independence"), "report ao: %s", out);
    snprintf(path, sizeof path, "%s/ra/ao.csv", tmpdir);
    rows = csv_rows(path, &front);
    TH_CHECK(rows == 14 && front >= 1, "ao.csv: %d rows, %d on the front", rows, front);
    snprintf(path, sizeof path, "%s/ra/ao.md", tmpdir);
    f = fopen(path, "r");
    TH_CHECK(f && fread(out, 1, sizeof out - 1, f) > 0 && strstr(out, "## View-independence"), "ao.md has no view-independence table");
    if (f) fclose(f);
    /* ssgi: ssgi rays 4, 16, steps 8, blur 2 full and half: 5; hybrid and hybrid+light each rays 4,
       16, res 16, blur 2 full and half: 5. Off screen the wall's colour reaches neither screen
       method. */
    snprintf(args, sizeof args, "report ssgi --scenes cornell-box --size 8 8 --spp 64 --rays 4 --steps 8 --radii 1 --res 16 --blurs 2 --out %s/ra", tmpdir);
    TH_CHECK(run(args, out, sizeof out) == 0 && strstr(out, "ssgi.md") && strstr(out, "from the wall's colour SSGI 0.00%, Hybrid-GI 0.00%"),
             "report ssgi: %s", out);
    snprintf(path, sizeof path, "%s/ra/ssgi.csv", tmpdir);
    rows = csv_rows(path, &front);
    TH_CHECK(rows == 15 && front >= 1, "ssgi.csv: %d rows, %d on the front", rows, front);
    snprintf(path, sizeof path, "%s/ra/ssgi.md", tmpdir);
    memset(out, 0, sizeof out);
    f = fopen(path, "r");
    TH_CHECK(f && fread(out, 1, sizeof out - 1, f) > 0 && strstr(out, "## Light the screen cannot see") && strstr(out, "## A wall barely in view"),
             "ssgi.md lacks its sections");
    if (f) fclose(f);
    /* linespace: one tree, 2 sample counts x 2 supersamplings x 2 modes (fast with one exact zone) on the Cornell box; no mesh */
    snprintf(args, sizeof args, "report linespace --size 8 --spp 64 --ns 3 --depths 2 --samples 1,4 --supersample 1,2 --exact-ends 3 --meshes '' --out %s/ra", tmpdir);
    TH_CHECK(run(args, out, sizeof out) == 0 && strstr(out, "linespace.md"), "report linespace: %s", out);
    snprintf(path, sizeof path, "%s/ra/linespace.csv", tmpdir);
    rows = csv_rows(path, &front);
    TH_CHECK(rows == 8, "linespace.csv: %d rows", rows);
    { /* a mesh with two materials on the floor; the leak room, whose reference is black inside its box */
        char mesh[600];
        write_file("two.mtl", "newmtl a\nKd 0.8 0.2 0.2\nnewmtl b\nKd 0.2 0.8 0.2\n", path, sizeof path);
        write_file("two.obj", "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl a\nf 1 3 2\nf 1 2 4\nusemtl b\nf 1 4 3\nf 2 3 4\n", mesh,
                   sizeof mesh);
        snprintf(args, sizeof args, "report linespace --size 8 --spp 16 --ns 3 --depths 2 --samples 1 --supersample 1 --scenes leak-room --meshes %s --out %s/rm",
                 mesh, tmpdir);
        TH_CHECK(run(args, out, sizeof out) == 0 && strstr(out, "linespace.md"), "report linespace, a mesh with two materials: %s", out);
        snprintf(path, sizeof path, "%s/rm/linespace.md", tmpdir);
        memset(out, 0, sizeof out);
        f = fopen(path, "r");
        TH_CHECK(f && fread(out, 1, sizeof out - 1, f) > 0 && strstr(out, "| exact | ") && strstr(out, "| black | black | 0 |") && !strstr(out, "nan") &&
                     strstr(out, "## two.obj on a floor (6 triangles)"),
                 "linespace.md: the black reference or the mesh: %.2000s", out);
        if (f) fclose(f);
    }
    TH_CHECK(run("report ao --rays 0 --out x", out, sizeof out) == 2 && run("report ssgi --blurs 65 --out x", out, sizeof out) == 2 &&
                 run("report ao --size 8 --out x", out, sizeof out) == 2 && run("report ssgi --radii 0 --out x", out, sizeof out) == 2,
             "bad screen report arguments accepted: %s", out);
}

/* voxgi plan: each item on a line with the reason, left out where the scene lacks what it needs. */
/* voxgi render's image at its defaults (no option but the size) is, for every method, the one
   voxgi_render gives a desc with nothing set but the method and the scene's camera: the tool's
   defaults are the library's. */
static void test_default_image_is_the_librarys(void)
{
    enum { W = 12, H = 10 };
    static char out[8192];
    static float want[W * H * 3], got[W * H * 3];
    char args[1200], pfm[512];
    voxgi_context *ctx = NULL;
    voxgi_desc cd;
    voxgi_builtin_scene bs;
    int m;
    memset(&cd, 0, sizeof cd);
    cd.backend = VOXGI_BACKEND_CPU;
    cd.thread_count = 2;
    voxgi_create(&cd, &ctx);
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "the Cornell box");
    if (!ctx) return;
    snprintf(pfm, sizeof pfm, "%s/default.pfm", tmpdir);
    for (m = 0; m < VOXGI_RENDER_METHOD_COUNT; m++) {
        voxgi_render_desc rd;
        double lit = 0;
        size_t i;
        memset(&rd, 0, sizeof rd);
        rd.method = (voxgi_render_method)m;
        rd.camera = bs.camera;
        rd.camera.width = W;
        rd.camera.height = H;
        TH_CHECK(voxgi_render(ctx, &bs.scene, &rd, want, sizeof want, NULL) == VOXGI_OK, "%s: %s", voxgi_render_method_name(rd.method), voxgi_last_error(ctx));
        snprintf(args, sizeof args, "render cornell-box --method %s --size %d %d --backend cpu --threads 2 -o %s", voxgi_render_method_name(rd.method), W, H, pfm);
        TH_CHECK(run(args, out, sizeof out) == 0 && read_pfm(pfm, W, H, got), "%s: %s", args, out);
        for (i = 0; i < sizeof want / sizeof want[0]; i++) lit += want[i];
        TH_CHECK(lit > 0 && memcmp(got, want, sizeof want) == 0, "%s: the tool's default image is not the library's zero desc's (library's sum %g)",
                 voxgi_render_method_name(rd.method), lit);
    }
    { /* the names the reports give the cone tracer's defaults are the library's */
        voxgi_render_desc rd, used;
        memset(&rd, 0, sizeof rd);
        rd.method = VOXGI_RENDER_VCT;
        TH_CHECK(voxgi_render_resolve(ctx, &bs.scene, &rd, &used) == VOXGI_OK && used.resolution == CLI_VCT_RES && used.vct.cones.cones == CLI_VCT_CONES &&
                     used.vct.cone_stride == CLI_VCT_STRIDE && used.samples == CLI_VCT_DIRECT_SPP && used.vct.radiance == VOXGI_VCT_ANISOTROPIC,
                 "CLI_VCT_*: %d voxels, %d cones, stride %d, %d rays; the library's: %d, %d, %d, %d", CLI_VCT_RES, CLI_VCT_CONES, CLI_VCT_STRIDE,
                 CLI_VCT_DIRECT_SPP, used.resolution, used.vct.cones.cones, used.vct.cone_stride, used.samples);
    }
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* A JSON value at *p (RFC 8259's grammar, numbers loosely): 1 and *p past it, else 0. The
   tool's JSON is checked with it, and with python3's parser where there is one. */
static int json_value(const char **p)
{
    const char *s = *p;
    while (*s == ' ' || *s == '\n' || *s == '\t' || *s == '\r') s++;
    if (*s == '"') {
        for (s++; *s != '"'; s++) {
            if (!*s || (unsigned char)*s < 0x20) return 0;
            if (*s == '\\') {
                s++;
                if (*s == 'u') {
                    int k;
                    for (k = 1; k <= 4; k++)
                        if (!isxdigit((unsigned char)s[k])) return 0;
                    s += 4;
                } else if (!strchr("\"\\/bfnrt", *s) || !*s) return 0;
            }
        }
        s++;
    } else if (*s == '{' || *s == '[') {
        char close = *s == '{' ? '}' : ']';
        int first = 1;
        for (s++;; first = 0) {
            while (*s == ' ' || *s == '\n') s++;
            if (*s == close && first) break;
            if (close == '}') {
                if (*s != '"' || !json_value(&s)) return 0;
                while (*s == ' ') s++;
                if (*s++ != ':') return 0;
            }
            if (!json_value(&s)) return 0;
            while (*s == ' ' || *s == '\n') s++;
            if (*s == close) break;
            if (*s++ != ',') return 0;
        }
        s++;
    } else if (!strncmp(s, "true", 4) || !strncmp(s, "null", 4)) s += 4;
    else if (!strncmp(s, "false", 5)) s += 5;
    else {
        char *end;
        strtod(s, &end);
        if (end == s || isalpha((unsigned char)*s)) return 0; /* strtod's nan and inf are not JSON */
        s = end;
    }
    *p = s;
    return 1;
}

/* 1 when text is one JSON value and nothing but white space after it. */
static int json_valid(const char *text)
{
    const char *s = text;
    if (!json_value(&s)) return 0;
    while (*s == ' ' || *s == '\n') s++;
    return *s == 0;
}

/* Strings in the JSON are escaped: a mesh named `sp "x\y".obj` (a quote, a backslash and a
   space) gives valid JSON from voxelize, svo and render, whose "mesh" or "scene" and "output" hold
   the names back; the checker itself refuses the unescaped name. Measured: each output parses. */
static void test_json_strings_escaped(void)
{
    static char out[16384];
    static const char *const cmds[] = {"voxelize '%s/sp \"x\\y\".obj' --res 8 --backend cpu --json -o '%s/sp \"x\\y\".binvox'",
                                       "svo '%s/sp \"x\\y\".obj' --res 8 --backend cpu --json",
                                       "render '%s/sp \"x\\y\".obj' --size 4 4 --spp 1 --json -o '%s/sp \"x\\y\".pfm'"};
    char path[512], args[2048], name[600];
    size_t k;
    int python = system("command -v python3 >/dev/null 2>&1") == 0;
    write_file("sp \"x\\y\".obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", path, sizeof path);
    TH_CHECK(!json_valid("{\"mesh\":\"sp \"x\\y\".obj\"}") && json_valid("{\"mesh\":\"sp \\\"x\\\\y\\\".obj\",\"n\":[1,-2.5e3,true,null]}"),
             "the JSON checker takes an unescaped quote or refuses a good object");
    snprintf(name, sizeof name, "\"%s/sp \\\"x\\\\y\\\".obj\"", tmpdir); /* the name as a JSON string */
    for (k = 0; k < sizeof cmds / sizeof cmds[0]; k++) {
        char *nl;
        snprintf(args, sizeof args, cmds[k], tmpdir, tmpdir);
        TH_CHECK(run(args, out, sizeof out) == 0, "%s: %s", args, out);
        nl = strstr(out, k == 2 ? "{\"scene\"" : "{\"mesh\""); /* the JSON object (stderr's notes come first) */
        TH_CHECK(nl && json_valid(nl) && strstr(nl, name), "%s: not valid JSON holding %s: %s", args, name, out);
        if (python && nl) {
            char cmd[3000], file[600];
            FILE *f;
            snprintf(file, sizeof file, "%s/out.json", tmpdir);
            f = fopen(file, "w");
            if (f) {
                fputs(nl, f);
                fclose(f);
            }
            snprintf(cmd, sizeof cmd, "python3 -c 'import json,sys; json.load(open(sys.argv[1]))' %s/out.json", tmpdir);
            TH_CHECK(system(cmd) == 0, "%s: python3's json refuses %s", args, nl);
        }
    }
}

/* World point p through the camera (gluLookAt, up +Y, fovy, w x h) into pixels (x right, y down from
   the top); 0 when p is behind the eye. Written here from the definition, not the library's. */
static int project(const double cam[7], int w, int h, const double p[3], double px[2])
{
    double f[3], r[3], u[3], d[3], lf = 0, lr = 0, z, t = tan(cam[6] * 3.14159265358979 / 360);
    int k;
    for (k = 0; k < 3; k++) {
        f[k] = cam[3 + k] - cam[k];
        d[k] = p[k] - cam[k];
        lf += f[k] * f[k];
    }
    r[0] = -f[2]; r[1] = 0; r[2] = f[0];
    lr = sqrt(r[0] * r[0] + r[2] * r[2]);
    lf = sqrt(lf);
    for (k = 0; k < 3; k++) {
        f[k] /= lf;
        r[k] /= lr;
    }
    u[0] = r[1] * f[2] - r[2] * f[1];
    u[1] = r[2] * f[0] - r[0] * f[2];
    u[2] = r[0] * f[1] - r[1] * f[0];
    z = d[0] * f[0] + d[1] * f[1] + d[2] * f[2];
    if (!(z > 0)) return 0;
    px[0] = 0.5 * w * (1 + (d[0] * r[0] + d[1] * r[1] + d[2] * r[2]) / (z * t * w / h));
    px[1] = 0.5 * h * (1 - (d[0] * u[0] + d[1] * u[1] + d[2] * u[2]) / (z * t));
    return 1;
}

/* The "camera: --camera EX EY EZ TX TY TZ FOVY" line of render's or plan's text; 1 when found. */
static int camera_line(const char *text, double cam[7])
{
    const char *at = strstr(text, "camera: --camera ");
    return at && sscanf(at + 17, "%lf %lf %lf %lf %lf %lf %lf", &cam[0], &cam[1], &cam[2], &cam[3], &cam[4], &cam[5], &cam[6]) == 7;
}

/* A mesh file of the shape, each vertex turned by up (0: as it is; 2: so that +Y becomes +Z). */
static void write_shape_obj(const vxt_shape *m, const char *name, int up, char *path, size_t path_size)
{
    FILE *f;
    size_t i;
    snprintf(path, path_size, "%s/%s", tmpdir, name);
    f = fopen(path, "w");
    if (!f) return;
    for (i = 0; i < m->vertex_count; i++) {
        const float *v = m->pos + 3 * i;
        if (up == 2) fprintf(f, "v %.9g %.9g %.9g\n", v[0], -v[2], v[1]);
        else fprintf(f, "v %.9g %.9g %.9g\n", v[0], v[1], v[2]);
    }
    for (i = 0; i < m->triangle_count; i++) fprintf(f, "f %u %u %u\n", m->idx[3 * i] + 1, m->idx[3 * i + 1] + 1, m->idx[3 * i + 2] + 1);
    fclose(f);
}

/* `voxgi render MESH -o OUT` with no other option, a mesh of no light and no emitter off the origin
   (tools/shapes.h's box and tilted quad, x 1..24, y 1..20, z 2..24): the tool says it added a sun,
   the image is lit (mean radiance > 0), and the camera it prints frames the mesh: its bounding box's
   8 corners, projected here, lie inside the 256 x 256 image (measured: 22..222 across, 44..243
   down; mean radiance 0.0298), the eye in front (+Z), above and to the right of the centre, and no pixel of the image's
   border sees the mesh (the background is black). voxgi plan prints the same camera and a lit
   plan (no "no light and no emitter"). The same mesh written with +Z up and rendered with --up z
   gives the same image, bit for bit. */
static void test_render_own_mesh_framed_and_lit(void)
{
    enum { W = 256, H = 256, S = 24 };
    static char out[16384], planned[16384];
    static float rgb[W * H * 3], small[2][S * S * 3];
    vxt_shape m;
    char path[512], zpath[512], args[2048];
    double cam[7], plan_cam[7], mean = 0, lo[3] = {1e30, 1e30, 1e30}, hi[3] = {-1e30, -1e30, -1e30}, xmin = 1e30, xmax = -1e30, ymin = 1e30, ymax = -1e30;
    size_t i;
    int c, k, border_lit = 0, rc;
    vxt_shape_box_and_tilted(&m);
    write_shape_obj(&m, "own.obj", 0, path, sizeof path);
    write_shape_obj(&m, "own_z.obj", 2, zpath, sizeof zpath);
    for (i = 0; i < m.vertex_count; i++)
        for (k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], m.pos[3 * i + (size_t)k]);
            hi[k] = fmax(hi[k], m.pos[3 * i + (size_t)k]);
        }
    snprintf(args, sizeof args, "render %s -o %s/own.pfm", path, tmpdir);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 0 && strstr(out, "voxgi render: no light or emitter in the scene: added a sun from the camera's upper left") && camera_line(out, cam),
             "%s: exit %d: %s", args, rc, out);
    snprintf(args, sizeof args, "%s/own.pfm", tmpdir);
    if (rc == 0 && read_pfm(args, W, H, rgb)) {
        for (i = 0; i < (size_t)W * H * 3; i++) mean += rgb[i] / (W * H * 3.0);
        for (c = 0; c < W; c++)
            for (k = 0; k < 3; k++) border_lit += rgb[3 * (size_t)c + (size_t)k] != 0 || rgb[3 * ((size_t)(H - 1) * W + (size_t)c) + (size_t)k] != 0 ||
                                                  rgb[3 * ((size_t)c * W) + (size_t)k] != 0 || rgb[3 * ((size_t)c * W + W - 1) + (size_t)k] != 0;
    } else TH_CHECK(0, "no %dx%d image %s", W, H, args);
    for (c = 0; c < 8; c++) {
        double p[3], px[2] = {-1, -1};
        for (k = 0; k < 3; k++) p[k] = (c >> k) & 1 ? hi[k] : lo[k];
        TH_CHECK(project(cam, W, H, p, px), "corner %d behind the eye", c);
        xmin = fmin(xmin, px[0]);
        xmax = fmax(xmax, px[0]);
        ymin = fmin(ymin, px[1]);
        ymax = fmax(ymax, px[1]);
    }
    printf("    mean radiance %.4g, corners %.1f..%.1f across, %.1f..%.1f down, %d border pixels lit\n", mean, xmin, xmax, ymin, ymax, border_lit);
    TH_CHECK(mean > 0 && border_lit == 0, "mean radiance %g, %d border channels lit", mean, border_lit);
    TH_CHECK(xmin >= 0 && ymin >= 0 && xmax <= W && ymax <= H && xmax - xmin > W / 3 && ymax - ymin > H / 3, "the box's corners %g..%g x %g..%g", xmin, xmax, ymin, ymax);
    TH_CHECK(cam[2] > 0.5 * (lo[2] + hi[2]) + 1 && cam[1] > 0.5 * (lo[1] + hi[1]) + 1 && cam[0] > 0.5 * (lo[0] + hi[0]), "not a three-quarter view from above the front: eye %g %g %g",
             cam[0], cam[1], cam[2]);
    snprintf(args, sizeof args, "plan %s --method vct", path);
    TH_CHECK(run(args, planned, sizeof planned) == 0 && camera_line(planned, plan_cam) && !memcmp(plan_cam, cam, sizeof cam) &&
                 !strstr(planned, "no light and no emitter") && strstr(planned, "1 directional"), "%s: %s", args, planned);
    for (k = 0; k < 2; k++) {
        snprintf(args, sizeof args, "render %s%s --size %d %d --spp 2 -o %s/own%d.pfm", k ? zpath : path, k ? " --up z" : "", S, S, tmpdir, k);
        TH_CHECK(run(args, out, sizeof out) == 0, "%s: %s", args, out);
        snprintf(args, sizeof args, "%s/own%d.pfm", tmpdir, k);
        TH_CHECK(read_pfm(args, S, S, small[k]), "no image %s", args);
    }
    TH_CHECK(!memcmp(small[0], small[1], sizeof small[0]), "--up z of the mesh turned to +Z up is not the +Y up mesh's image");
    vxt_shape_free(&m);
}

static void test_plan_command(void)
{
    static char out[16384];
    TH_CHECK(run("plan rsm-walls --method tsm", out, sizeof out) == 0 && strstr(out, "transmittance layers   structure left out - no translucent material") &&
                 strstr(out, "shadow maps            structure kept - "), "an opaque scene under a sun: %s", out);
    TH_CHECK(run("plan foliage --method tsm", out, sizeof out) == 0 && strstr(out, "transmittance layers   structure kept - "), "the foliage: %s", out);
    TH_CHECK(run("plan cornell-box --method linespace", out, sizeof out) == 0 && strstr(out, "line space             structure kept - ") &&
                 strstr(out, "the camera sees an emitter"), "the Cornell box's line space: %s", out);
    TH_CHECK(run("plan cornell-box --method vct --error 0.08", out, sizeof out) == 0 && strstr(out, "grid: 96 voxels") &&
                 strstr(out, "resolution 96, error 0.08, radiance anisotropic volume, cones 24, cone stride 6"),
             "the Cornell box at 8%%: %s", out);
    { /* plan and render report the same settings for the same options (the library resolves them) */
        static const char *const cmds[] = {"cornell-box --method vct --size 8 8", "cornell-box --method vct --res 12 --octree --size 8 8",
                                           "cornell-box --method hybrid --size 8 8", "cornell-box --method linespace --size 8 8 --spp 2"};
        static char planned[16384];
        char args[1024];
        size_t k;
        for (k = 0; k < sizeof cmds / sizeof cmds[0]; k++) {
            char *nl;
            TH_CHECK(run((snprintf(args, sizeof args, "plan %s", cmds[k]), args), planned, sizeof planned) == 0, "plan %s: %s", cmds[k], planned);
            if ((nl = strchr(planned, '\n')) != NULL) *nl = 0; /* its first line: the settings */
            snprintf(args, sizeof args, "render %s -o %s/same.pfm", cmds[k], tmpdir);
            TH_CHECK(run(args, out, sizeof out) == 0 && strlen(planned) > 20 && strstr(out, planned), "plan said '%s', render: %s", planned, out);
        }
    }
    TH_CHECK(run("plan cornell-box --method nothing", out, sizeof out) == 2, "an unknown method: %s", out);
    { /* render follows the plan and says what it left out */
        char args[1024];
        snprintf(args, sizeof args, "render rsm-walls --method linespace --size 8 8 -o %s/plan.pfm", tmpdir);
        TH_CHECK(run(args, out, sizeof out) == 0 && strstr(out, "voxgi render: plan: line space: left out - no area light"), "render: %s", out);
    }
}

/* The Pareto front on a hand-made set whose answer is known: twins are both on it or both off,
   a row as good but slower (or as fast but worse) is off, rows without a finite time or error are
   never on it and hide nothing, and fronts are per group. The fastest row reaching an error is
   on the front. */
static void test_pareto_front(void)
{
    pareto_point p[] = {
        {10, 0.5, 0, -1},        /* 0 on */
        {20, 0.3, 0, -1},        /* 1 on */
        {15, 0.6, 0, -1},        /* 2 off: 0 is faster and closer */
        {20, 0.3, 0, -1},        /* 3 on: 1's twin */
        {5, NAN, 0, -1},         /* 4 off: no error */
        {30, 0.3, 0, -1},        /* 5 off: 1 as close and faster */
        {30, 0.1, 0, -1},        /* 6 on */
        {1, 0.9, 0, -1},         /* 7 on */
        {100, 0.05, 1, -1},      /* 8 on */
        {50, 0.5, 1, -1},        /* 9 on: 0 beats it, in another group */
        {10, 0.5, 0, -1},        /* 10 on: 0's twin */
        {HUGE_VAL, 0.01, 0, -1}, /* 11 off: no time */
        {10, 0.55, 0, -1},       /* 12 off: 0 as fast and closer */
    };
    static const int front[] = {1, 1, 0, 1, 0, 0, 1, 1, 1, 1, 1, 0, 0};
    static const struct { int group; double target; long fastest; } reach[] = {
        {0, 0.35, 1}, {0, 0.5, 0}, {0, 1, 7}, {0, 0.2, 6}, {0, 0.01, -1}, {1, 0.5, 9}, {1, 0.04, -1}};
    const size_t n = sizeof p / sizeof p[0];
    size_t i;
    pareto_mark(p, n);
    for (i = 0; i < n; i++) TH_CHECK(p[i].front == front[i], "point %lu (%g ms, %g, group %d): front %d", (unsigned long)i, p[i].ms, p[i].error, p[i].group, p[i].front);
    for (i = 0; i < sizeof reach / sizeof reach[0]; i++) {
        long got = pareto_fastest(p, n, reach[i].group, reach[i].target);
        TH_CHECK(got == reach[i].fastest && (got < 0 || p[got].front), "group %d, error %g: the fastest is %ld (front %d), not %ld", reach[i].group,
                 reach[i].target, got, got < 0 ? -1 : p[got].front, reach[i].fastest);
    }
}

/* A CSV line's fields (quotes taken off) into f[0..max), in place; their count. */
static int csv_split(char *line, char **f, int max)
{
    int n = 0;
    char *w = line, *r = line;
    line[strcspn(line, "\r\n")] = 0;
    while (n < max) {
        int quoted = *r == '"';
        f[n++] = w;
        if (quoted) r++;
        for (; *r; r++) {
            if (quoted && *r == '"' && r[1] == '"') { *w++ = '"'; r++; continue; }
            if (quoted && *r == '"') { quoted = 0; continue; }
            if (!quoted && *r == ',') break;
            *w++ = *r;
        }
        if (!*r) { *w = 0; break; }
        *w++ = 0;
        r++;
    }
    return n;
}

/* A Markdown table row's cells, trimmed, into c[0..max), in place; their count. */
static int md_cells(char *line, char **c, int max)
{
    int n = 0;
    char *p = line, *bar;
    line[strcspn(line, "\r\n")] = 0;
    if (*p != '|') return 0;
    p++;
    while (n < max && (bar = strchr(p, '|')) != NULL) {
        char *e = bar;
        *bar = 0;
        while (*p == ' ') p++;
        while (e > p && e[-1] == ' ') *--e = 0;
        c[n++] = p;
        p = bar + 1;
    }
    return n;
}

static char *read_text(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    char *t;
    long n;
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    t = (char *)malloc((size_t)n + 1);
    if (t && fread(t, 1, (size_t)n, f) != (size_t)n) { free(t); t = NULL; }
    if (t) t[n] = 0;
    if (size) *size = (size_t)n;
    fclose(f);
    return t;
}

/* voxgi report stiff on the CPU: a row per image method with a cell per case; where the library
   is exact (scaled by powers of two, moved far through double positions) every cell says equal, an
   empty scene is refused by every method, the leak box is black through the exact rays, and the
   furnace's path tracer is within its noise of 1 / (1 - albedo) (test_stiff holds the library to
   every expectation; this holds the tool to reporting it). */
static void test_report_stiff(void)
{
    static char out[1 << 15];
    static const char *const methods[] = {"reference", "vct", "tsm", "rsm", "sh", "ssgi", "hybrid", "ssao", "vao", "linespace"};
    char args[700], path[600], line[4096], *c[16], *md;
    size_t m;
    int rows = 0, furnace = 0, n;
    FILE *f;
    snprintf(path, sizeof path, "%s/stiff.md", tmpdir);
    snprintf(args, sizeof args, "report stiff --backend cpu --threads 2 -o %s", path);
    TH_CHECK(run(args, out, sizeof out) == 0, "report stiff: %s", out);
    f = fopen(path, "r");
    TH_CHECK(f != NULL, "%s not written", path);
    while (f && fgets(line, sizeof line, f)) {
        n = md_cells(line, c, 16);
        for (m = 0; n == 12 && m < sizeof methods / sizeof methods[0] && strcmp(c[0], methods[m]) != 0; m++) {}
        if (n == 12 && m < sizeof methods / sizeof methods[0]) {
            rows++;
            TH_CHECK(strcmp(c[1], "equal") == 0 && strcmp(c[5], "equal") == 0, "%s: scaled by 2^20 '%s', moved through doubles '%s'", c[0], c[1], c[5]);
            TH_CHECK(strcmp(c[11], "refused: no triangles") == 0, "%s: the empty scene '%s'", c[0], c[11]);
            TH_CHECK(strcmp(c[7], "finite") == 0 && strcmp(c[9], "finite") == 0, "%s: '%s', '%s'", c[0], c[7], c[9]);
            if (m == 0 || m == 9) TH_CHECK(strcmp(c[10], "black") == 0, "%s in the leak box: '%s'", c[0], c[10]);
        }
        if (n == 4 && (atof(c[0]) == 0.5 || atof(c[0]) == 0.999)) {
            furnace++;
            TH_CHECK(fabs(atof(c[2]) / atof(c[1]) - 1) < 0.05, "the furnace at %s: the path tracer %s against %s", c[0], c[2], c[1]);
        }
    }
    if (f) fclose(f);
    TH_CHECK(rows == 10 && furnace == 2, "%d method rows, %d furnace rows", rows, furnace);
    md = read_text(path, NULL);
    TH_CHECK(md && strstr(md, "| *expected* |"), "no expectations in the table");
    free(md);
    TH_CHECK(run("report stiff --help", out, sizeof out) == 0 && strstr(out, "usage: voxgi report stiff"), "help: %s", out);
}

/* ------------------------------------------------------------------ the reports' figures */
/* The font against glyphs drawn here by hand: "F" and "4" (neither symmetric) at scale 2 must
   light exactly these cells and no pixel beside them; every character the figures use has a glyph
   of its own (none blank, none another's, none the '?' of a missing one), lower case as upper. */
static void test_report_font(void)
{
    static const char *const art[7] = {"#####....#.", "#.......##.", "#......#.#.", "####..#..#.", "#.....#####", "#........#.", "#........#."};
    static const char chars[] = "!%()*+,-./0123456789:<=>?ABCDEFGHIJKLMNOPQRSTUVWXYZ^_";
    static const unsigned char ink[3] = {0, 0, 0};
    unsigned char px[3 * 26 * 18];
    report_canvas cv = {px, 26, 18};
    int x, y, wrong = 0, same = 0, blank = 0, i, j;
    memset(px, 255, sizeof px);
    report_text(&cv, 2, 2, 26, "F4", 2, ink);
    for (y = 0; y < 18; y++)
        for (x = 0; x < 26; x++) { /* "F" at columns 2..11, "4" at 14..23 (advance 6 cells), rows 2..15 */
            int gx = (x - 2) / 2, gy = (y - 2) / 2, want = x >= 2 && y >= 2 && y < 16 && gx < 11 && art[gy][gx] == '#';
            wrong += (px[3 * (y * 26 + x)] == 0) != want;
        }
    TH_CHECK(wrong == 0, "\"F4\" at scale 2: %d pixels differ from the hand-drawn glyphs", wrong);
    for (i = 0; chars[i]; i++) {
        const unsigned char *g = report_glyph(chars[i]);
        int lit = 0;
        for (y = 0; y < 7; y++) lit += g[y] != 0;
        blank += lit == 0;
        if (chars[i] != '?' && g == report_glyph('?')) same++;
        for (j = 0; j < i; j++) same += memcmp(g, report_glyph(chars[j]), 7) == 0;
    }
    TH_CHECK(blank == 0 && same == 0, "%d glyphs blank, %d the same as another or as the missing glyph's", blank, same);
    TH_CHECK(report_glyph('q') == report_glyph('Q') && report_glyph('~') == report_glyph('?'), "lower case or a missing glyph");
    TH_CHECK(report_text_width("abc", 2) == 34 && report_text_width("", 1) == 0, "text width %d", report_text_width("abc", 2));
    printf("    \"F4\" drawn as by hand; %d glyphs, all distinct\n", (int)strlen(chars));
}

/* Dark pixels (every channel below 64) in a rectangle of an 8-bit RGB picture of width w. */
static int dark_pixels(const unsigned char *px, int w, int x0, int y0, int x1, int y1)
{
    int x, y, n = 0;
    for (y = y0; y < y1; y++)
        for (x = x0; x < x1; x++) {
            const unsigned char *p = px + 3 * ((size_t)y * (size_t)w + (size_t)x);
            n += p[0] < 64 && p[1] < 64 && p[2] < 64;
        }
    return n;
}

/* The report's picture (report all's SCENE-METHOD.png), made in process from an image whose error
   against a reference of 1 grows along x from 0 to REPORT_HEAT_WHITE of the reference's mean:
   the colour bar runs black to white, each channel never falling along it, and the heat map's
   column x has the bar's colour at x (the bar's scale is the map's, within 1 of 255); each panel's
   label is dark on white, inside its text box, with exactly its glyphs' cells lit; "0" and "50%"
   lie under the bar's ends; the images keep their sRGB; the PNG has the picture's size. At 64 x 40
   (scale 1: a 200 x 70 picture; "vct" 37 dark pixels = its 37 cells, "reference" 152, "error" 88)
   and 200 x 30 (scale 2: 608 x 90, each label 4 x its cells); the heat map within 1 of the bar
   in every channel, the bar's channels never falling. */
static void test_report_picture_labels_and_bar(void)
{
    static const int sizes[2][2] = {{64, 40}, {200, 30}};
    static const char *const titles[3] = {"vct", "reference", "error"};
    int si;
    for (si = 0; si < 2; si++) {
        const int w = sizes[si][0], h = sizes[si][1];
        float *img = (float *)malloc(sizeof(float) * 3 * (size_t)(w * h)), *ref = (float *)malloc(sizeof(float) * 3 * (size_t)(w * h));
        unsigned char *masked = (unsigned char *)calloc((size_t)(w * h), 1), *px;
        cli_error_mask m;
        report_compare_layout l;
        int x, y, c, k, falls = 0, heat_off = 0, bar_rows_differ = 0, label_ok = 1, image_off = 0;
        char path[400], head[24] = {0};
        FILE *f;
        for (y = 0; y < h; y++)
            for (x = 0; x < w; x++)
                for (c = 0; c < 3; c++) {
                    ref[3 * (y * w + x) + c] = 1;
                    img[3 * (y * w + x) + c] = (float)(1 + REPORT_HEAT_WHITE * x / (w - 1));
                }
        m.masked = masked, m.width = w, m.height = h, m.masked_pixels = 0;
        px = report_compare_rgb8(img, ref, &m, 0.5f, titles[0], &l);
        TH_CHECK(px != NULL, "no picture");
        if (!px) return;
        TH_CHECK(l.width == 3 * w + 2 * l.gap && l.height > h + l.panel_y && l.bar_y >= l.panel_y + h && l.bar_text_y >= l.bar_y + l.bar_h, "layout");
        for (x = 0; x < w; x++) {
            const unsigned char *b = px + 3 * ((size_t)l.bar_y * (size_t)l.width + (size_t)(l.bar_x + x));
            const unsigned char *heat = px + 3 * ((size_t)(l.panel_y + h / 2) * (size_t)l.width + (size_t)(l.bar_x + x));
            for (y = 1; y < l.bar_h; y++) bar_rows_differ += memcmp(b, b + 3 * (size_t)y * (size_t)l.width, 3) != 0;
            for (c = 0; c < 3; c++) {
                if (x && b[c] < b[c - 3]) falls++;
                if (abs(heat[c] - b[c]) > 1) heat_off++;
            }
        }
        {
            const unsigned char *b0 = px + 3 * ((size_t)l.bar_y * (size_t)l.width + (size_t)l.bar_x), *b1 = b0 + 3 * (size_t)(w - 1);
            TH_CHECK(b0[0] == 0 && b0[1] == 0 && b0[2] == 0 && b1[0] == 255 && b1[1] == 255 && b1[2] == 255, "%d x %d: the bar runs %d,%d,%d to %d,%d,%d", w, h, b0[0],
                     b0[1], b0[2], b1[0], b1[1], b1[2]);
        }
        TH_CHECK(falls == 0 && bar_rows_differ == 0, "%d x %d: the bar's channels fall %d times; %d bar pixels differ from its top row", w, h, falls, bar_rows_differ);
        TH_CHECK(heat_off == 0, "%d x %d: %d channels of the heat map differ from the bar's colour at the same error", w, h, heat_off);
        for (k = 0; k < 3; k++) { /* each label: its glyphs' cells and nothing else dark in its band */
            const int x0 = k * (w + l.gap), tw = report_text_width(titles[k], l.scale);
            int cells = 0, i, r, in_box, in_band;
            for (i = 0; titles[k][i]; i++)
                for (r = 0; r < 7; r++)
                    for (c = 0; c < 5; c++) cells += (report_glyph(titles[k][i])[r] >> c) & 1;
            in_box = dark_pixels(px, l.width, x0 + l.pad, l.pad, x0 + l.pad + tw, l.pad + 7 * l.scale);
            in_band = dark_pixels(px, l.width, x0, 0, x0 + w, l.panel_y);
            if (in_box != cells * l.scale * l.scale || in_band != in_box || x0 + l.pad + tw > x0 + w) label_ok = 0;
            printf("    %d x %d: label \"%s\": %d dark pixels, its glyphs' %d cells x %d^2\n", w, h, titles[k], in_band, cells, l.scale);
        }
        TH_CHECK(label_ok, "%d x %d: a label's pixels are not its glyphs'", w, h);
        TH_CHECK(dark_pixels(px, l.width, l.bar_x, l.bar_text_y, l.bar_x + 5 * l.scale, l.bar_text_y + 7 * l.scale) > 0 &&
                         dark_pixels(px, l.width, l.bar_x + w - report_text_width("50%", l.scale), l.bar_text_y, l.bar_x + w, l.bar_text_y + 7 * l.scale) > 0,
                 "%d x %d: no \"0\" or \"50%%\" under the bar's ends", w, h);
        for (y = 0; y < h; y++)
            for (x = 0; x < w; x++)
                for (c = 0; c < 3; c++) {
                    const unsigned char *o = px + 3 * ((size_t)(l.panel_y + y) * (size_t)l.width + (size_t)x) + c;
                    image_off += *o != vxt_srgb8(0.5f * img[3 * (y * w + x) + c]) || o[3 * (w + l.gap)] != vxt_srgb8(0.5f * ref[3 * (y * w + x) + c]);
                }
        TH_CHECK(image_off == 0, "%d x %d: %d image bytes are not the images' sRGB at the exposure", w, h, image_off);
        snprintf(path, sizeof path, "%s/picture.png", tmpdir);
        TH_CHECK(report_png_compare(path, img, ref, &m, 0.5f, titles[0]) == 0, "PNG not written");
        f = fopen(path, "rb");
        TH_CHECK(f && fread(head, 1, 24, f) == 24 && memcmp(head + 12, "IHDR", 4) == 0 &&
                         ((unsigned char)head[18] << 8 | (unsigned char)head[19]) == l.width && ((unsigned char)head[22] << 8 | (unsigned char)head[23]) == l.height,
                 "%d x %d: the PNG is not %d x %d", w, h, l.width, l.height);
        if (f) fclose(f);
        remove(path);
        printf("    %d x %d panels: a %d x %d picture, text at scale %d; bar black to white, monotonic, the heat map's colours within 1\n", w, h, l.width, l.height,
               l.scale);
        free(px);
        free(img);
        free(ref);
        free(masked);
    }
}

/* A text element of an SVG: its box by the rule report.h states (0.6 font size a character, 0.8
   above the baseline, 0.2 below), and whether it is a point label. */
typedef struct svg_text { double x0, y0, x1, y1; int point_label; char text[200]; } svg_text;

static double svg_attr(const char *el, const char *end, const char *name, double fallback)
{
    char pat[40];
    const char *at;
    snprintf(pat, sizeof pat, " %s=\"", name);
    at = strstr(el, pat);
    return at && at < end ? strtod(at + strlen(pat), NULL) : fallback;
}

static int double_order(const void *a, const void *b) { return *(const double *)a < *(const double *)b ? -1 : *(const double *)a > *(const double *)b; }

/* The report's plot (report_plot_svg) of crowded points: 3 series over 0.5..3000 ms and errors
   0.2%..40% with an exact point, 14 front points close together each with a long label. The x axis
   spans 0.1..10^4 ms (5 decades) and has 8 minor ticks a decade (40), y 10^-3..1 and the exact
   row, 24 (none between the exact row and 0.1%); each minor tick at log10(m) of its decade's
   width (within 0.2 units); no two texts' boxes overlap; some minor ticks and point labels are
   labelled (else the check is empty). Measured: 40 and 24 minor ticks, 35 texts, none overlapping
   (188 pairs without the collision check), 14 minor ticks and 1 of the 14 point labels placed. */
static void test_report_plot_ticks_and_labels(void)
{
    static report_plot_point pts[40];
    static const char *const legend[3] = {"cone tracing", "radiosity maps", "screen space"};
    static svg_text texts[400];
    double minor_x[100], major_x[20];
    size_t n = 0, i, j, nt = 0, nmx = 0, nMx = 0, nmy = 0;
    int overlaps = 0, placed = 0, minor_labels = 0, given = 0, misplaced = 0, expect_x, expect_y;
    char path[400], *svg, *at;
    report_plot plot;
    FILE *f;
    for (i = 0; i < 14; i++, n++) { /* the crowded front */
        pts[n].ms = 10 * pow(1.06, (double)i), pts[n].error = 0.05 / pow(1.04, (double)i), pts[n].series = (int)(i % 3), pts[n].front = 1;
        pts[n].label = "64^3, 16 cones, step 0.5, aniso";
        given++;
    }
    for (i = 0; i < 20; i++, n++) /* the rest, spread out */
        pts[n].ms = 0.5 * pow(6000, (double)i / 19), pts[n].error = 0.002 * pow(200, (double)((i * 7) % 20) / 19), pts[n].series = (int)(i % 3), pts[n].front = 0,
        pts[n].label = NULL;
    pts[n].ms = 5, pts[n].error = 0, pts[n].series = 0, pts[n].front = 0, pts[n].label = NULL, n++; /* exact */
    memset(&plot, 0, sizeof plot);
    plot.y_title = "relative RMSE", plot.x_title = "time per image", plot.legend = legend, plot.series_count = 3, plot.points = pts, plot.count = n;
    snprintf(path, sizeof path, "%s/plot.svg", tmpdir);
    f = fopen(path, "w");
    TH_CHECK(f != NULL, "cannot write %s", path);
    if (!f) return;
    report_plot_svg(f, &plot);
    fclose(f);
    svg = read_text(path, NULL);
    TH_CHECK(svg != NULL, "no SVG");
    if (!svg) return;
    for (at = svg; (at = strstr(at, "<line class=\"")) != NULL; at++) {
        const char *end = strchr(at, '>');
        if (!strncmp(at + 13, "minor-x", 7) && nmx < 100) minor_x[nmx++] = svg_attr(at, end, "x1", 0);
        if (!strncmp(at + 13, "major-x", 7) && nMx < 20) major_x[nMx++] = svg_attr(at, end, "x1", 0);
        if (!strncmp(at + 13, "minor-y", 7)) nmy++;
    }
    for (at = svg; (at = strstr(at, "<text ")) != NULL && nt < 400; at++) {
        const char *end = strchr(at, '>'), *close = end ? strstr(end, "</text>") : NULL;
        double x, y, fs, w;
        svg_text *t = &texts[nt];
        if (!end || !close || (strstr(at, "transform=") && strstr(at, "transform=") < end)) continue; /* the rotated axis title: beside the plot */
        snprintf(t->text, sizeof t->text, "%.*s", (int)(close - end - 1), end + 1);
        x = svg_attr(at, end, "x", 0), y = svg_attr(at, end, "y", 0), fs = svg_attr(at, end, "font-size", 11);
        w = 0.6 * fs * (double)strlen(t->text);
        t->x0 = strstr(at, "\"middle\"") && strstr(at, "\"middle\"") < end ? x - w / 2 : strstr(at, "\"end\"") && strstr(at, "\"end\"") < end ? x - w : x;
        t->x1 = t->x0 + w, t->y0 = y - 0.8 * fs, t->y1 = y + 0.2 * fs;
        t->point_label = strstr(at, "point-label") && strstr(at, "point-label") < end;
        placed += t->point_label;
        minor_labels += !t->point_label && (t->text[0] >= '2' && t->text[0] <= '9');
        nt++;
    }
    for (i = 0; i < nt; i++)
        for (j = 0; j < i; j++)
            if (texts[i].x0 < texts[j].x1 && texts[j].x0 < texts[i].x1 && texts[i].y0 < texts[j].y1 && texts[j].y0 < texts[i].y1) {
                if (overlaps++ < 3) printf("    overlap: \"%s\" and \"%s\"\n", texts[i].text, texts[j].text);
            }
    expect_x = 8 * (int)(ceil(log10(3000.0)) - floor(log10(0.5))), expect_y = 8 * (int)(ceil(log10(0.4)) - floor(log10(0.002)));
    TH_CHECK((int)nmx == expect_x && (int)nmy == expect_y, "minor ticks: x %lu (want %d), y %lu (want %d)", (unsigned long)nmx, expect_x, (unsigned long)nmy, expect_y);
    qsort(minor_x, nmx, sizeof(double), double_order);
    qsort(major_x, nMx, sizeof(double), double_order);
    for (i = 0; i < nmx && i / 8 + 1 < nMx; i++) {
        double want = major_x[i / 8] + log10((double)(i % 8 + 2)) * (major_x[i / 8 + 1] - major_x[i / 8]);
        misplaced += fabs(minor_x[i] - want) > 0.2;
    }
    TH_CHECK(nMx == 6 && misplaced == 0, "%lu decades on x; %d minor ticks away from log10(m) of their decade", (unsigned long)nMx, misplaced);
    TH_CHECK(overlaps == 0, "%d pairs of texts overlap", overlaps);
    TH_CHECK(placed > 0 && placed <= given && minor_labels > 0, "%d of %d point labels placed, %d minor ticks labelled", placed, given, minor_labels);
    printf("    minor ticks x %lu, y %lu; %lu texts, none overlapping; %d of %d point labels placed, %d minor ticks labelled\n", (unsigned long)nmx,
           (unsigned long)nmy, (unsigned long)nt, placed, given, minor_labels);
    free(svg);
    remove(path);
}

/* voxgi report all --quick at 16 x 16: progress on stderr, report.md, the CSV, a plot per scene and
   quantity, pictures; every method of every report in it; the CSV's front the front of its own
   rows per scene and quantity; every row of report.md the CSV's numbers, and the summary's
   fastest row the fastest reaching its error. */
#define ALL_ROWS 512
static void test_report_all(void)
{
    static char out[1 << 16];
    static const char *const files[] = {"report.md", "report.csv", "cornell-box-bounce.svg", "cornell-box-direct.svg", "cornell-box-ao.svg",
                                        "cornell-box-voxels.svg", "rsm-walls-bounce.svg", "rsm-walls-direct.svg", "rsm-walls-ao.svg", "rsm-walls-voxels.svg",
                                        "cornell-box-vct.png", "cornell-box-linespace-fast.png", "rsm-walls-tsm.png", "rsm-walls-vao.png"};
    static const char *const methods[] = {"vct", "rsm", "sh", "ssgi", "hybrid", "hybrid+light", "tsm", "linespace-exact", "linespace-fast", "ssao", "ssao-points",
                                          "vao", "conservative", "thin", "slicemap", "atlas", "atlas-compute", "geometry", "volume-buffer"};
    static const char *const quantity_keys[] = {"bounce", "direct", "ao", "voxels"}, *const quantity_titles[] = {"direct light and one bounce", "direct light",
                                                                                                                "ambient occlusion", "voxel sets"};
    static char csv_lines[ALL_ROWS][1024];
    static char *cf[ALL_ROWS][12];
    static pareto_point pts[ALL_ROWS];
    static int matched[ALL_ROWS];
    char args[1024], path[600], line[4096], scene[300] = "";
    char *md, *at, *c[16];
    size_t i, j, k, nrows = 0, md_rows = 0, summary_rows = 0, update_rows = 0;
    int rc, section = 0; /* 1: the summary, 2: a quantity's table */
    FILE *f;
    snprintf(args, sizeof args, "report all --quick --size 16 --spp 16 --threads 2 -o %s/all", tmpdir);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 0 && strstr(out, "wrote ") && strstr(out, "[1/25   0%] cornell-box: the reference") && strstr(out, "[23/25  88%] rsm-walls: voxelizers") &&
                 strstr(out, "[24/25  92%] rsm-walls: a light-only update") && strstr(out, "[25/25  96%] stiff and extreme input"),
             "report all: exit %d: %.3000s", rc, out);
    for (i = 0; i < sizeof files / sizeof files[0]; i++) {
        char head[8] = {0};
        snprintf(path, sizeof path, "%s/all/%s", tmpdir, files[i]);
        f = fopen(path, "rb");
        TH_CHECK(f && fread(head, 1, 4, f) == 4, "%s not written", files[i]);
        if (f) fclose(f);
        if (strstr(files[i], ".svg")) TH_CHECK(memcmp(head, "<svg", 4) == 0, "%s is no SVG", files[i]);
        if (strstr(files[i], ".png")) TH_CHECK(memcmp(head, "\x89PNG", 4) == 0, "%s is no PNG", files[i]);
    }
    /* the CSV: every method, the front its own rows' */
    snprintf(path, sizeof path, "%s/all/report.csv", tmpdir);
    f = fopen(path, "r");
    TH_CHECK(f && fgets(line, sizeof line, f) && strncmp(line, "scene,quantity,method,settings,backend,ms,passes_ms,bytes,rel_error,detail,reference_ms,pareto", 90) == 0,
             "report.csv's header");
    while (f && nrows < ALL_ROWS && fgets(csv_lines[nrows], sizeof csv_lines[0], f)) {
        int q;
        TH_CHECK(csv_split(csv_lines[nrows], cf[nrows], 12) == 12, "a CSV row without 12 fields");
        for (q = 0; q < 4 && cf[nrows][1] && strcmp(cf[nrows][1], quantity_keys[q]) != 0; q++) {}
        pts[nrows].ms = atof(cf[nrows][5]);
        pts[nrows].error = atof(cf[nrows][8]);
        pts[nrows].group = (strcmp(cf[nrows][0], "cornell-box") == 0 ? 0 : 4) + q;
        nrows++;
    }
    if (f) fclose(f);
    for (i = 0; i < sizeof methods / sizeof methods[0]; i++) {
        int seen = 0;
        for (j = 0; j < nrows; j++) seen += strcmp(cf[j][2], methods[i]) == 0;
        TH_CHECK(seen > 0, "%s has no row in report.csv", methods[i]);
    }
    pareto_mark(pts, nrows);
    for (j = 0; j < nrows; j++)
        TH_CHECK(pts[j].front == atoi(cf[j][11]), "%s %s %s (%s): the CSV's front %s", cf[j][0], cf[j][2], cf[j][3], cf[j][5], cf[j][11]);
    /* report.md: every row the CSV's numbers, the summary the fastest reaching each error */
    snprintf(path, sizeof path, "%s/all/report.md", tmpdir);
    md = read_text(path, NULL);
    TH_CHECK(md != NULL, "report.md cannot be read");
    for (at = md; at && *at;) {
        char *end = strchr(at, '\n');
        size_t len = end ? (size_t)(end - at) : strlen(at);
        int n;
        snprintf(line, sizeof line, "%.*s", (int)(len < sizeof line - 1 ? len : sizeof line - 1), at);
        at = end ? end + 1 : NULL;
        if (strncmp(line, "## ", 3) == 0) {
            section = strstr(line, "The fastest method") ? 1 : strstr(line, "a light-only update") ? 3 : 0;
            snprintf(scene, sizeof scene, "%.299s", line + 3);
        }
        if (strncmp(line, "### ", 4) == 0) section = 2;
        if (section == 3 && (n = md_cells(line, c, 16)) == 5 && strcmp(c[0], "scene") != 0 && strncmp(c[0], "---", 3) != 0) {
            double full = 0, kept = 0, saved = 0, voxelize = 0;
            update_rows++;
            TH_CHECK(sscanf(c[1], "%lf ms", &full) == 1 && sscanf(c[2], "%lf ms", &kept) == 1 && sscanf(c[3], "%lf%%", &saved) == 1 &&
                         sscanf(c[4], "%lf ms", &voxelize) == 1 && full > 0 && kept > 0 && voxelize > 0 && fabs(saved - 100 * (1 - kept / full)) <= 1.5,
                     "the light-only update's row %s", line);
        }
        if ((n = md_cells(line, c, 16)) < 8 || strcmp(c[0], "method") == 0 || strcmp(c[0], "scene") == 0 || strncmp(c[0], "---", 3) == 0) continue;
        if (section == 2) {
            double ms = 0, mb = 0, err = 0;
            for (j = 0; j < nrows && !(strcmp(cf[j][0], scene) == 0 && strcmp(cf[j][2], c[0]) == 0 && strcmp(cf[j][3], c[1]) == 0); j++) {}
            md_rows++;
            TH_CHECK(j < nrows, "report.md's row %s %s %s is not in the CSV", scene, c[0], c[1]);
            if (j == nrows) continue;
            matched[j]++;
            TH_CHECK(sscanf(c[2], "%lf ms", &ms) == 1 && sscanf(c[4], "%lf", &mb) == 1 && sscanf(c[5], "%lf%%", &err) == 1, "report.md's row %s", line);
            TH_CHECK(fabs(ms - atof(cf[j][5])) <= 0.05 + 1e-9 && fabs(mb - atof(cf[j][7]) / 1e6) <= 0.005 * mb + 1e-12 && fabs(err - 100 * atof(cf[j][8])) <= 0.005 + 1e-9 &&
                         (strcmp(c[7], "yes") == 0) == (atoi(cf[j][11]) == 1),
                     "report.md's %s %s %s: %s ms, %s MB, %s, front '%s'; the CSV's %s ms, %s bytes, %s, %s", scene, c[0], c[1], c[2], c[4], c[5], c[7], cf[j][5],
                     cf[j][7], cf[j][8], cf[j][11]);
        } else if (section == 1) { /* scene, quantity, targets ("40%, 20%"), method, settings, time, error, path tracer */
            const char *t = c[2];
            int q;
            for (q = 0; q < 4 && strcmp(c[1], quantity_titles[q]) != 0; q++) {}
            summary_rows++;
            for (; t && *t; t = strchr(t, ',') ? strchr(t, ',') + 2 : NULL) { /* each target: the CSV's fastest reaching it is the row's */
                double target = strncmp(t, "0 (exact)", 9) == 0 ? 0 : atof(t) / 100;
                long best = -1;
                for (j = 0; j < nrows; j++)
                    if (strcmp(cf[j][0], c[0]) == 0 && strcmp(cf[j][1], q < 4 ? quantity_keys[q] : "") == 0 && atof(cf[j][8]) <= target &&
                        (best < 0 || atof(cf[j][5]) < atof(cf[best][5])))
                        best = (long)j;
                TH_CHECK(best < 0 ? strcmp(c[3], "none reaches it") == 0 : strcmp(cf[best][2], c[3]) == 0 && strcmp(cf[best][3], c[4]) == 0 && atoi(cf[best][11]) == 1,
                         "the summary's %s, %s, %s (%g): %s (%s); the CSV's fastest: %s (%s)", c[0], c[1], c[2], target, c[3], c[4], best >= 0 ? cf[best][2] : "none",
                         best >= 0 ? cf[best][3] : "");
            }
        }
    }
    for (k = j = 0; j < nrows; j++) k += matched[j] == 1;
    for (i = j = 0; j < nrows; j++) i += pts[j].front;
    printf("    %lu rows, %lu on the fronts; %lu in report.md; %lu rows in the summary\n", (unsigned long)nrows, (unsigned long)i, (unsigned long)md_rows,
           (unsigned long)summary_rows);
    TH_CHECK(nrows > 50 && md_rows == nrows && k == nrows, "report.md has %lu rows, %lu of the CSV's %lu once", (unsigned long)md_rows, (unsigned long)k,
             (unsigned long)nrows);
    TH_CHECK(summary_rows >= 8, "the summary has %lu rows", (unsigned long)summary_rows);
    TH_CHECK(update_rows == 2, "the light-only update has %lu rows, not one per scene", (unsigned long)update_rows);
    TH_CHECK(md && strstr(md, "\n## Stiff and extreme input\n") && strstr(md, "\n| linespace | equal | "), "report.md has no stiff cases' section");
    for (i = 0; md && i < sizeof methods / sizeof methods[0]; i++) {
        snprintf(line, sizeof line, "\n| %s | ", methods[i]);
        TH_CHECK(strstr(md, line) != NULL, "report.md has no row of %s", methods[i]);
    }
    free(md);
    TH_CHECK(run("report all --size 4 -o x", out, sizeof out) == 2 && run("report all --scenes '' -o x", out, sizeof out) == 2 &&
                 run("report all --backend sideways -o x", out, sizeof out) == 2,
             "bad report all arguments accepted: %s", out);
    snprintf(args, sizeof args, "report all --quick --scenes nowhere -o %s/none", tmpdir);
    rc = run(args, out, sizeof out);
    TH_CHECK(rc == 1 && strstr(out, "nowhere"), "report all, unknown scene: exit %d: %s", rc, out);
}

int main(int argc, char **argv)
{
    (void)argc;
    if (!find_tool(argv[0])) {
        printf("no voxgi tool found (VOXGI_TOOL=%s); build it first\n", getenv("VOXGI_TOOL") ? getenv("VOXGI_TOOL") : "");
        return 1;
    }
    snprintf(tmpdir, sizeof tmpdir, "%s/voxgi_tool_XXXXXX", getenv("TMPDIR") && *getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(tmpdir)) { perror("mkdtemp"); return 1; }
    if (chdir(tmpdir) != 0) { perror("chdir"); return 1; } /* whatever a command writes lands here */
    TH_RUN(test_help_everywhere);
    TH_RUN(test_voxelize_exact_grid_json_binvox);
    TH_RUN(test_voxelize_backends_agree);
    TH_RUN(test_bad_files_and_arguments);
    TH_RUN(test_voxelize_methods);
    TH_RUN(test_info_and_bench);
    TH_RUN(test_svo_command);
    TH_RUN(test_render_command);
    TH_RUN(test_tsm_command);
    TH_RUN(test_bounce_reports);
    TH_RUN(test_screen_reports);
    TH_RUN(test_pareto_front);
    TH_RUN(test_report_font);
    TH_RUN(test_report_picture_labels_and_bar);
    TH_RUN(test_report_plot_ticks_and_labels);
    TH_RUN(test_report_all);
    TH_RUN(test_report_stiff);
    TH_RUN(test_vct_and_report_commands);
    TH_RUN(test_compare_black_reference);
    TH_RUN(test_compare_masks_emitters);
    TH_RUN(test_reference_file);
    TH_RUN(test_cornell_mesh);
    TH_RUN(test_usage_errors_named);
    TH_RUN(test_output_extensions);
    TH_RUN(test_voxelize_npy_attribute);
    TH_RUN(test_version_and_exit_codes_documented);
    TH_RUN(test_library_error_once);
    TH_RUN(test_exit_codes);
    TH_RUN(test_default_image_is_the_librarys);
    TH_RUN(test_plan_command);
    TH_RUN(test_json_strings_escaped);
    TH_RUN(test_render_own_mesh_framed_and_lit);
    {
        char cmd[300];
        snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
        if (system(cmd) != 0) return 1;
    }
    return th_finish();
}
