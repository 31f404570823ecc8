/* tools/voxgi.c - the voxgi command-line tool.
 *
 *   voxgi voxelize MESH [--res N | --grid OX OY OZ SIZE NX NY NZ] [--method M] [--backend B] [-o OUT.binvox] [--json]
 *   voxgi info [--gl KIND] [--json]
 *   voxgi bench voxelize [MESH ...] [--methods LIST] [--min-res N] [--max-res N] [--runs R] [--csv FILE]
 *   voxgi svo MESH [--res N] [--backend B] [--format F] [--bricks] [--neighbours] [--json]
 *   voxgi render SCENE|MESH [--method reference|vct] [--bounces B] [--spp S] [--camera EX EY EZ TX TY TZ FOVY] [--size W H] -o OUT.png|OUT.pfm
 *   voxgi report vct [--scenes LIST] [--size N] [--res LIST] [--cones LIST] [--apertures LIST] [--steps LIST] [--out DIR]
 *
 * MESH is an OBJ (+MTL), OFF, STL or PLY file, or a built-in shape: builtin:quad,
 * builtin:subdivided-quad, builtin:cube, builtin:sphere. Every command takes --help. */
#include "../voxgi.h"
#include "headless_gl.h"
#include "image_io.h"
#include "mesh_io.h"
#include "shapes.h"
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <errno.h>
#include <sys/stat.h>

/* ------------------------------------------------------------------ meshes */
typedef struct tool_mesh {
    char name[256];
    vxt_mesh m;            /* file meshes */
    vxt_shape shape;       /* built-in shapes */
    voxgi_mesh vm;
    voxgi_scene scene;
    voxgi_material *materials;
} tool_mesh;

static const char *builtin_names = "builtin:quad, builtin:subdivided-quad, builtin:cube, builtin:sphere";

static int builtin_shape(const char *name, vxt_shape *s)
{
    memset(s, 0, sizeof *s);
    if (strcmp(name, "builtin:quad") == 0) vxt_shape_quad(s, 1);
    else if (strcmp(name, "builtin:subdivided-quad") == 0) vxt_shape_quad(s, 77); /* 11,858 triangles, as seed 000's */
    else if (strcmp(name, "builtin:cube") == 0) {
        const float lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
        vxt_shape_alloc(s, 8, 12);
        vxt_shape_put_box(s, 0, 0, lo, hi);
    } else if (strcmp(name, "builtin:sphere") == 0) vxt_shape_sphere(s, 96, 64, 1.0, 0, 0, 0);
    else return 0;
    return 1;
}

/* Loads a file or built-in shape into a voxgi scene; 0 on success, else prints why. */
static int mesh_open(const char *path, tool_mesh *t)
{
    char err[512];
    memset(t, 0, sizeof *t);
    snprintf(t->name, sizeof t->name, "%s", path);
    if (strncmp(path, "builtin:", 8) == 0) {
        if (!builtin_shape(path, &t->shape)) {
            fprintf(stderr, "voxgi: unknown built-in shape '%s' (there are %s)\n", path, builtin_names);
            return 1;
        }
        t->vm.positions = t->shape.pos;
        t->vm.vertex_count = t->shape.vertex_count;
        t->vm.indices = t->shape.idx;
        t->vm.index_count = 3 * t->shape.triangle_count;
    } else {
        size_t i;
        if (vxt_mesh_load(path, &t->m, err, sizeof err) != 0) {
            fprintf(stderr, "voxgi: %s\n", err);
            return 1;
        }
        t->vm.positions = t->m.positions;
        t->vm.vertex_count = t->m.vertex_count;
        t->vm.indices = t->m.indices;
        t->vm.index_count = 3 * t->m.triangle_count;
        t->vm.normals = t->m.normals;
        t->vm.uvs = t->m.uvs;
        t->vm.material_ids = t->m.material_ids;
        t->materials = (voxgi_material *)calloc(t->m.material_count, sizeof *t->materials);
        if (!t->materials) { fprintf(stderr, "voxgi: out of memory\n"); return 1; }
        for (i = 0; i < t->m.material_count; i++) {
            memcpy(t->materials[i].albedo, t->m.materials[i].albedo, sizeof t->materials[i].albedo);
            memcpy(t->materials[i].emission, t->m.materials[i].emission, sizeof t->materials[i].emission);
            t->materials[i].transparency = 1.0f - t->m.materials[i].opacity;
        }
        t->scene.materials = t->materials;
        t->scene.material_count = t->m.material_count;
    }
    t->scene.meshes = &t->vm;
    t->scene.mesh_count = 1;
    return 0;
}

static void mesh_close(tool_mesh *t)
{
    vxt_mesh_free(&t->m);
    vxt_shape_free(&t->shape);
    free(t->materials);
    memset(t, 0, sizeof *t);
}

static size_t mesh_triangles(const tool_mesh *t) { return t->vm.index_count / 3; }

/* ------------------------------------------------------------------ arguments */
static int parse_int(const char *s, int lo, int hi, int *out)
{
    char *end;
    long v = strtol(s, &end, 10);
    if (*s == 0 || *end != 0 || v < lo || v > hi) return 0;
    *out = (int)v;
    return 1;
}
static int parse_double(const char *s, double *out)
{
    char *end;
    double v = strtod(s, &end);
    if (*s == 0 || *end != 0) return 0;
    *out = v;
    return 1;
}
static int parse_backend(const char *s, voxgi_backend *b)
{
    if (strcmp(s, "auto") == 0) *b = VOXGI_BACKEND_AUTO;
    else if (strcmp(s, "cpu") == 0) *b = VOXGI_BACKEND_CPU;
    else if (strcmp(s, "gl") == 0) *b = VOXGI_BACKEND_GL;
    else return 0;
    return 1;
}

static int bad_arg(const char *cmd, const char *what)
{
    fprintf(stderr, "voxgi %s: %s (see 'voxgi %s --help')\n", cmd, what, cmd);
    return 2;
}

/* ------------------------------------------------------------------ contexts */
static void log_to_stderr(voxgi_log_level level, const char *msg, void *user)
{
    (void)user;
    if (level <= VOXGI_LOG_WARNING) fprintf(stderr, "voxgi: %s\n", msg);
}

static int progress_to_stderr(double fraction, const char *stage, void *user)
{
    (void)user;
    fprintf(stderr, "\r%s %3d%%", stage, (int)(fraction * 100 + 0.5));
    if (fraction >= 1) fprintf(stderr, "\n");
    return 0;
}

/* Makes a voxgi context; for GL (or AUTO) it first makes a headless GL context. */
static voxgi_context *make_context(voxgi_backend backend, vxt_gl_kind kind, int threads, int progress, vxt_gl **gl_out,
                                   char *why, size_t why_size)
{
    voxgi_desc d;
    voxgi_context *ctx = NULL;
    vxt_gl *gl = NULL;
    voxgi_result r;
    memset(&d, 0, sizeof d);
    d.backend = backend;
    d.thread_count = threads;
    d.logger.func = log_to_stderr;
    if (progress) d.progress.func = progress_to_stderr;
    if (backend != VOXGI_BACKEND_CPU) {
        gl = vxt_gl_create(kind, why, why_size);
        if (!gl && backend == VOXGI_BACKEND_GL) return NULL;
        d.gl_get_proc_address_user = vxt_gl_get_proc;
        d.gl_user = gl;
    }
    r = voxgi_create(&d, &ctx);
    if (r != VOXGI_OK) {
        snprintf(why, why_size, "%s", voxgi_result_string(r));
        if (gl) vxt_gl_destroy(gl);
        return NULL;
    }
    *gl_out = gl;
    return ctx;
}

static void close_context(voxgi_context *ctx, vxt_gl *gl)
{
    voxgi_destroy(ctx);
    if (gl) vxt_gl_destroy(gl);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* "albedo,normal,emission,opacity" or "all" -> voxgi_attribute bits; 0 on a bad name. */
static int parse_attributes(const char *arg, unsigned *out)
{
    char list[128], *tok;
    snprintf(list, sizeof list, "%s", arg);
    *out = 0;
    for (tok = strtok(list, ","); tok; tok = strtok(NULL, ",")) {
        if (strcmp(tok, "albedo") == 0) *out |= VOXGI_ATTRIBUTE_ALBEDO;
        else if (strcmp(tok, "normal") == 0) *out |= VOXGI_ATTRIBUTE_NORMAL;
        else if (strcmp(tok, "emission") == 0) *out |= VOXGI_ATTRIBUTE_EMISSION;
        else if (strcmp(tok, "opacity") == 0) *out |= VOXGI_ATTRIBUTE_OPACITY;
        else if (strcmp(tok, "all") == 0) *out |= 15u;
        else return 0;
    }
    return *out != 0;
}

/* ------------------------------------------------------------------ voxelize */
static const char *voxelize_help =
    "usage: voxgi voxelize MESH [options]\n"
    "Voxelizes a mesh. conservative: a voxel is set exactly when its closed box meets a triangle;\n"
    "thin: Schwarz & Seidel's 6-separating subset; solid: the interior (see --solid-mode).\n"
    "MESH: an OBJ (+MTL), OFF, STL or PLY file, or builtin:quad|subdivided-quad|cube|sphere.\n"
    "  --res N                  cubic grid of N^3 voxels fitted around the mesh (default 128)\n"
    "  --per-axis               with --res: each axis only as long as the mesh needs\n"
    "  --pad P                  with --res: P empty voxels around the mesh (default 1)\n"
    "  --grid OX OY OZ S NX NY NZ   exactly this grid: origin, voxel size, resolution\n"
    "  --method NAME            conservative (default), thin (6-separating), solid, slicemap (raster,\n"
    "                           logic-op OR on GL), slicemap-atomic (raster, imageAtomicOr on GL),\n"
    "                           atlas (texture atlas points drawn as GL points), atlas-compute\n"
    "                           (the same points, one compute invocation each), geometry (the\n"
    "                           conservative set by geometry-shader rasterization on GL),\n"
    "                           volume-buffer (Volume Buffer M2: each triangle along its dominant\n"
    "                           axis, fragments clipped to slices), volume-buffer-m1 (triangles sliced)\n"
    "  --blend A,N,E,O          per attribute (albedo, normal, emission, opacity): average (default),\n"
    "                           max or add\n"
    "  --atlas-size N           atlas methods: texels per side (default: from the grid, 2 texels\n"
    "                           per voxel edge, at most 8192)\n"
    "  --atlas-uv auto|mesh     atlas methods: voxgi's own charts (default) or the mesh's uvs\n"
    "  --attributes LIST        conservative, thin, geometry, volume-buffer: blend albedo,normal,emission,opacity (or all)\n"
    "                           per voxel over the triangles that set it\n"
    "  --solid-mode MODE        with --method solid: parity (default, closed meshes), vote, flood\n"
    "  --axis x|y|z             solid parity: the counting axis; slicemap: the slicing axis (default z)\n"
    "  --backend auto|cpu|gl    (default auto: GL when a headless GL 4.5 context works)\n"
    "  --gl auto|egl|osmesa     headless GL context to create (default auto)\n"
    "  --threads T              CPU worker threads (default: one per core)\n"
    "  --runs R                 repeat R times and report the median time (default 1)\n"
    "  -o FILE.binvox           write the voxels\n"
    "  --json                   print one JSON object instead of text\n";

static int cmd_voxelize(int argc, char **argv)
{
    const char *mesh_path = NULL, *out_path = NULL;
    int res = 128, per_axis = 0, json = 0, threads = 0, runs = 1, have_grid = 0, i, rc = 1;
    double pad = 1;
    voxgi_backend backend = VOXGI_BACKEND_AUTO;
    vxt_gl_kind kind = VXT_GL_AUTO;
    voxgi_voxelize_desc vd;
    tool_mesh tm;
    voxgi_context *ctx;
    vxt_gl *gl = NULL;
    voxgi_voxels *vox = NULL;
    voxgi_voxels_info info;
    voxgi_info ci;
    char why[512] = "";
    double *times;
    memset(&vd, 0, sizeof vd);
    for (i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) { fputs(voxelize_help, stdout); return 0; }
        else if (strcmp(a, "--res") == 0 && i + 1 < argc) { if (!parse_int(argv[++i], 1, VOXGI_MAX_RES, &res)) return bad_arg("voxelize", "--res needs 1..65536"); }
        else if (strcmp(a, "--per-axis") == 0) per_axis = 1;
        else if (strcmp(a, "--method") == 0 && i + 1 < argc) {
            const char *mname = argv[++i];
            if (strcmp(mname, "conservative") == 0) vd.method = VOXGI_METHOD_CONSERVATIVE;
            else if (strcmp(mname, "thin") == 0) vd.method = VOXGI_METHOD_THIN;
            else if (strcmp(mname, "solid") == 0) vd.method = VOXGI_METHOD_SOLID;
            else if (strcmp(mname, "slicemap") == 0) vd.method = VOXGI_METHOD_SLICEMAP;
            else if (strcmp(mname, "slicemap-atomic") == 0) { vd.method = VOXGI_METHOD_SLICEMAP; vd.atomic = 1; }
            else if (strcmp(mname, "atlas") == 0) vd.method = VOXGI_METHOD_ATLAS;
            else if (strcmp(mname, "atlas-compute") == 0) vd.method = VOXGI_METHOD_ATLAS_COMPUTE;
            else if (strcmp(mname, "geometry") == 0) vd.method = VOXGI_METHOD_GEOMETRY;
            else if (strcmp(mname, "volume-buffer") == 0) vd.method = VOXGI_METHOD_VOLUME_BUFFER;
            else if (strcmp(mname, "volume-buffer-m1") == 0) { vd.method = VOXGI_METHOD_VOLUME_BUFFER; vd.volume_slicing = 1; }
            else return bad_arg("voxelize", "--method is conservative, thin, solid, slicemap, slicemap-atomic, atlas, atlas-compute, "
                                            "geometry, volume-buffer or volume-buffer-m1");
        } else if (strcmp(a, "--atlas-size") == 0 && i + 1 < argc) {
            if (!parse_int(argv[++i], 1, 16384, &vd.atlas_size)) return bad_arg("voxelize", "--atlas-size needs 1..16384");
        } else if (strcmp(a, "--attributes") == 0 && i + 1 < argc) {
            if (!parse_attributes(argv[++i], &vd.attributes)) return bad_arg("voxelize", "--attributes lists albedo, normal, emission, opacity or all");
        } else if (strcmp(a, "--blend") == 0 && i + 1 < argc) {
            char list[128], *tok;
            int k = 0;
            snprintf(list, sizeof list, "%s", argv[++i]);
            for (tok = strtok(list, ","); tok && k < 4; tok = strtok(NULL, ","), k++) {
                if (strcmp(tok, "average") == 0) vd.blend[k] = VOXGI_BLEND_AVERAGE;
                else if (strcmp(tok, "max") == 0) vd.blend[k] = VOXGI_BLEND_MAX;
                else if (strcmp(tok, "add") == 0) vd.blend[k] = VOXGI_BLEND_ADD;
                else return bad_arg("voxelize", "--blend lists average, max or add for albedo, normal, emission, opacity");
            }
            if (k != 4 || tok) return bad_arg("voxelize", "--blend needs four modes: albedo,normal,emission,opacity");
        } else if (strcmp(a, "--atlas-uv") == 0 && i + 1 < argc) {
            const char *uv = argv[++i];
            if (strcmp(uv, "auto") == 0) vd.atlas_uv = VOXGI_ATLAS_AUTO;
            else if (strcmp(uv, "mesh") == 0) vd.atlas_uv = VOXGI_ATLAS_MESH;
            else return bad_arg("voxelize", "--atlas-uv is auto or mesh");
        } else if (strcmp(a, "--solid-mode") == 0 && i + 1 < argc) {
            const char *mode = argv[++i];
            if (strcmp(mode, "parity") == 0) vd.solid_mode = VOXGI_SOLID_PARITY;
            else if (strcmp(mode, "vote") == 0) vd.solid_mode = VOXGI_SOLID_VOTE;
            else if (strcmp(mode, "flood") == 0) vd.solid_mode = VOXGI_SOLID_FLOOD;
            else return bad_arg("voxelize", "--solid-mode is parity, vote or flood");
        } else if (strcmp(a, "--axis") == 0 && i + 1 < argc) {
            const char *ax = argv[++i];
            if (strlen(ax) != 1 || !strchr("xyz", ax[0])) return bad_arg("voxelize", "--axis is x, y or z");
            vd.axis = (voxgi_axis)(VOXGI_AXIS_X + (ax[0] - 'x'));
        }
        else if (strcmp(a, "--pad") == 0 && i + 1 < argc) { if (!parse_double(argv[++i], &pad) || !(pad >= 0)) return bad_arg("voxelize", "--pad needs a number >= 0"); }
        else if (strcmp(a, "--grid") == 0 && i + 7 < argc) {
            int k;
            for (k = 0; k < 3; k++)
                if (!parse_double(argv[i + 1 + k], &vd.grid.origin[k])) return bad_arg("voxelize", "--grid origin is not a number");
            if (!parse_double(argv[i + 4], &vd.grid.voxel_size)) return bad_arg("voxelize", "--grid voxel size is not a number");
            for (k = 0; k < 3; k++)
                if (!parse_int(argv[i + 5 + k], 1, VOXGI_MAX_RES, &vd.grid.res[k])) return bad_arg("voxelize", "--grid resolution needs 1..65536");
            i += 7;
            have_grid = 1;
        } else if (strcmp(a, "--backend") == 0 && i + 1 < argc) { if (!parse_backend(argv[++i], &backend)) return bad_arg("voxelize", "--backend is auto, cpu or gl"); }
        else if (strcmp(a, "--gl") == 0 && i + 1 < argc) { if (vxt_gl_kind_parse(argv[++i], &kind) != 0) return bad_arg("voxelize", "--gl is auto, egl or osmesa"); }
        else if (strcmp(a, "--threads") == 0 && i + 1 < argc) { if (!parse_int(argv[++i], 1, 256, &threads)) return bad_arg("voxelize", "--threads needs 1..256"); }
        else if (strcmp(a, "--runs") == 0 && i + 1 < argc) { if (!parse_int(argv[++i], 1, 1000, &runs)) return bad_arg("voxelize", "--runs needs 1..1000"); }
        else if (strcmp(a, "-o") == 0 && i + 1 < argc) out_path = argv[++i];
        else if (strcmp(a, "--json") == 0) json = 1;
        else if (a[0] == '-') return bad_arg("voxelize", "unknown option or missing value");
        else if (!mesh_path) mesh_path = a;
        else return bad_arg("voxelize", "more than one mesh given");
    }
    if (!mesh_path) return bad_arg("voxelize", "no mesh given");
    if (mesh_open(mesh_path, &tm)) return 1;
    ctx = make_context(backend, kind, threads, !json && isatty(2), &gl, why, sizeof why);
    if (!ctx) {
        fprintf(stderr, "voxgi voxelize: cannot use backend %s: %s\n", voxgi_backend_name(backend), why);
        mesh_close(&tm);
        return 1;
    }
    if (!have_grid) {
        voxgi_fit_desc fit;
        memset(&fit, 0, sizeof fit);
        fit.res = res;
        fit.per_axis = per_axis;
        fit.padding = pad;
        if (voxgi_fit_grid(ctx, &tm.scene, &fit, &vd.grid) != VOXGI_OK) {
            fprintf(stderr, "voxgi voxelize: %s: %s\n", mesh_path, voxgi_last_error(ctx));
            goto done;
        }
    }
    times = (double *)malloc((size_t)runs * sizeof *times);
    for (i = 0; i < runs; i++) {
        voxgi_result r;
        if (vox) voxgi_voxels_destroy(ctx, vox);
        vox = NULL;
        r = voxgi_voxelize(ctx, &tm.scene, &vd, &vox);
        if (r != VOXGI_OK) {
            fprintf(stderr, "voxgi voxelize: %s: %s: %s\n", mesh_path, voxgi_result_string(r), voxgi_last_error(ctx));
            free(times);
            goto done;
        }
        voxgi_voxels_query(vox, &info);
        times[i] = info.ms;
    }
    qsort(times, (size_t)runs, sizeof *times, cmp_double);
    info.ms = times[runs / 2];
    free(times);
    voxgi_query_info(ctx, &ci);
    if (out_path) {
        size_t need = 0;
        uint32_t *bits;
        FILE *f;
        voxgi_voxels_read(ctx, vox, NULL, 0, &need);
        bits = (uint32_t *)malloc(need);
        f = fopen(out_path, "wb");
        if (!bits || !f || voxgi_voxels_read(ctx, vox, bits, need, NULL) != VOXGI_OK ||
            voxgi_binvox_write(f, &vd.grid, bits) != VOXGI_OK || fclose(f) != 0) {
            fprintf(stderr, "voxgi voxelize: cannot write %s\n", out_path);
            free(bits);
            goto done;
        }
        free(bits);
    }
    if (json)
        printf("{\"mesh\":\"%s\",\"triangles\":%lu,\"voxels\":%llu,\"ms\":%.3f,\"runs\":%d,\"backend\":\"%s\",\"renderer\":\"%s\","
               "\"threads\":%d,\"method\":\"%s\",\"origin\":[%.17g,%.17g,%.17g],\"voxel_size\":%.17g,"
               "\"res\":[%d,%d,%d],\"exact_tests\":%llu,\"exact_triangles\":%llu,\"atlas_size\":%d,\"atlas_points\":%llu,\"attribute_pairs\":%llu%s%s%s}\n",
               mesh_path, (unsigned long)mesh_triangles(&tm), (unsigned long long)info.voxel_count, info.ms, runs,
               voxgi_backend_name(ci.backend), ci.backend == VOXGI_BACKEND_GL ? ci.gl_renderer : "", ci.thread_count,
               voxgi_method_name(vd.method), vd.grid.origin[0], vd.grid.origin[1], vd.grid.origin[2], vd.grid.voxel_size, vd.grid.res[0], vd.grid.res[1],
               vd.grid.res[2], (unsigned long long)info.exact_tests, (unsigned long long)info.exact_triangles, info.atlas_size,
               (unsigned long long)info.atlas_points, (unsigned long long)info.attribute_pairs, out_path ? ",\"output\":\"" : "", out_path ? out_path : "", out_path ? "\"" : "");
    else {
        printf("%s: %lu triangles -> %llu voxels of %dx%dx%d in %.2f ms (%s%s%s)\n", mesh_path,
               (unsigned long)mesh_triangles(&tm), (unsigned long long)info.voxel_count, vd.grid.res[0], vd.grid.res[1],
               vd.grid.res[2], info.ms, voxgi_backend_name(ci.backend), ci.backend == VOXGI_BACKEND_GL ? ", " : "",
               ci.backend == VOXGI_BACKEND_GL ? ci.gl_renderer : "");
        printf("grid: origin %.17g %.17g %.17g, voxel size %.17g\n", vd.grid.origin[0], vd.grid.origin[1], vd.grid.origin[2],
               vd.grid.voxel_size);
        if (info.attributes)
            printf("attributes: %llu (triangle, voxel) pairs averaged, %.2f triangles per voxel\n",
                   (unsigned long long)info.attribute_pairs, info.voxel_count ? (double)info.attribute_pairs / (double)info.voxel_count : 0.0);
        if (info.atlas_size)
            printf("atlas: %dx%d texels, %llu points, %.3g texels per voxel edge\n", info.atlas_size, info.atlas_size,
                   (unsigned long long)info.atlas_points, info.atlas_scale);
        if (out_path) printf("wrote %s\n", out_path);
    }
    rc = 0;
done:
    if (vox) voxgi_voxels_destroy(ctx, vox);
    close_context(ctx, gl);
    mesh_close(&tm);
    return rc;
}

/* ------------------------------------------------------------------ info */
static const char *info_help =
    "usage: voxgi info [--gl auto|egl|osmesa] [--json]\n"
    "Prints the version, the compiled-in capabilities, the CPU threads and, for each way of making\n"
    "a headless GL context, whether a GL 4.5 context works and which renderer it has.\n";

static int cmd_info(int argc, char **argv)
{
    int json = 0, i, k;
    vxt_gl_kind only = VXT_GL_AUTO;
    voxgi_info ci;
    voxgi_context *cpu;
    char why[512];
    vxt_gl *gl = NULL;
    const vxt_gl_kind kinds[2] = {VXT_GL_EGL, VXT_GL_OSMESA};
    for (i = 0; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) { fputs(info_help, stdout); return 0; }
        else if (strcmp(argv[i], "--json") == 0) json = 1;
        else if (strcmp(argv[i], "--gl") == 0 && i + 1 < argc) { if (vxt_gl_kind_parse(argv[++i], &only) != 0) return bad_arg("info", "--gl is auto, egl or osmesa"); }
        else return bad_arg("info", "unknown option");
    }
    cpu = make_context(VOXGI_BACKEND_CPU, VXT_GL_AUTO, 0, 0, &gl, why, sizeof why);
    voxgi_query_info(cpu, &ci);
    if (json) printf("{\"version\":\"%s\",\"capabilities\":\"%s\",\"cpu_threads\":%d,\"gl\":[", VOXGI_VERSION_STRING, ci.capabilities, ci.thread_count);
    else printf("voxgi %s\ncapabilities: %s\ncpu: %d worker threads\n", VOXGI_VERSION_STRING, ci.capabilities, ci.thread_count);
    close_context(cpu, NULL);
    for (k = 0; k < 2; k++) {
        voxgi_context *ctx;
        if (only != VXT_GL_AUTO && only != kinds[k]) continue;
        ctx = make_context(VOXGI_BACKEND_GL, kinds[k], 0, 0, &gl, why, sizeof why);
        if (ctx) voxgi_query_info(ctx, &ci);
        if (json)
            printf("%s{\"context\":\"%s\",\"ok\":%s,\"version\":\"%s\",\"renderer\":\"%s\",\"error\":\"%s\"}", k ? "," : "",
                   k ? "osmesa" : "egl", ctx ? "true" : "false", ctx ? ci.gl_version : "", ctx ? ci.gl_renderer : "", ctx ? "" : why);
        else if (ctx)
            printf("gl (%s): %s, %s%s\n", k ? "osmesa" : "egl", ci.gl_version, ci.gl_renderer,
                   strstr(ci.gl_renderer, "llvmpipe") ? " (software rasteriser: timings are not GPU timings)" : "");
        else printf("gl (%s): not available: %s\n", k ? "osmesa" : "egl", why);
        if (ctx) close_context(ctx, gl);
    }
    if (json) printf("]}\n");
    return 0;
}

/* ------------------------------------------------------------------ bench voxelize */
static const char *bench_help =
    "usage: voxgi bench voxelize [MESH ...] [options]\n"
    "Times voxelization in the shape of Buchacher 2014's Tables 1 and 2 and measures each method\n"
    "against its exact reference. Rows are the simple quad (2 triangles), the subdivided quad, the\n"
    "axis-aligned cube and any meshes given; columns are cubic grids N^3 fitted around each mesh\n"
    "(one voxel of padding), N = 32..512. Time is the median of several runs of a whole\n"
    "voxgi_voxelize call, for the CPU with one thread, the CPU with every core, and GL. GL runs on\n"
    "whatever headless context exists - without a GPU that is Mesa's llvmpipe, a software\n"
    "rasteriser: not GPU timings. Table 3 counts missed / extra voxels against exact conservative\n"
    "voxelization (surface methods) or solid parity, the exact inside test of a closed mesh.\n"
    "Table 4 (solid methods) gives the share of voxel centres, sampled, decided against the\n"
    "generalized winding number, the inside test that also holds for open meshes.\n"
    "  --methods LIST              comma separated: conservative, thin, solid, solid-vote, solid-flood,\n"
    "                              slicemap, slicemap-atomic, atlas, atlas-compute, geometry,\n"
    "                              volume-buffer, volume-buffer-m1\n"
    "                              (default conservative)\n"
    "  --min-res N / --max-res N   range of N, powers of two (default 32..512)\n"
    "  --runs R                    runs per cell, median reported (default 3)\n"
    "  --no-gl                     CPU only\n"
    "  --gl auto|egl|osmesa        headless GL context kind\n"
    "  --csv FILE                  also write every measurement as CSV\n"
    "  --atlas-size N              atlas methods: this atlas for every N (the documents' fixed 512^2),\n"
    "                              instead of one sized from each grid\n";

/* variant: atomic (slicemap, atlas) or volume_slicing (volume buffer); exact_twin: GL must
   equal the CPU (the slicemap may differ at rasterizer ties, Volume Buffer M1 near cuts) */
typedef struct bench_method { const char *name; voxgi_method method; voxgi_solid_mode mode; int variant, exact_twin; } bench_method;
static const bench_method bench_methods[] = {
    {"conservative", VOXGI_METHOD_CONSERVATIVE, VOXGI_SOLID_PARITY, 0, 1},
    {"thin", VOXGI_METHOD_THIN, VOXGI_SOLID_PARITY, 0, 1},
    {"solid", VOXGI_METHOD_SOLID, VOXGI_SOLID_PARITY, 0, 1},
    {"solid-vote", VOXGI_METHOD_SOLID, VOXGI_SOLID_VOTE, 0, 1},
    {"solid-flood", VOXGI_METHOD_SOLID, VOXGI_SOLID_FLOOD, 0, 1},
    {"slicemap", VOXGI_METHOD_SLICEMAP, VOXGI_SOLID_PARITY, 0, 0},
    {"slicemap-atomic", VOXGI_METHOD_SLICEMAP, VOXGI_SOLID_PARITY, 1, 0},
    {"atlas", VOXGI_METHOD_ATLAS, VOXGI_SOLID_PARITY, 0, 1},
    {"atlas-compute", VOXGI_METHOD_ATLAS_COMPUTE, VOXGI_SOLID_PARITY, 0, 1},
    {"geometry", VOXGI_METHOD_GEOMETRY, VOXGI_SOLID_PARITY, 0, 1},
    {"volume-buffer", VOXGI_METHOD_VOLUME_BUFFER, VOXGI_SOLID_PARITY, 2, 1},
    {"volume-buffer-m1", VOXGI_METHOD_VOLUME_BUFFER, VOXGI_SOLID_PARITY, 1, 0}};
#define BENCH_METHOD_COUNT (int)(sizeof bench_methods / sizeof bench_methods[0])

typedef struct bench_cell { double ms[3], wrong; uint64_t voxels[3], missed, extra; int ok[3], sampled; } bench_cell;

/* The generalized winding number of the scene's mesh at p (Jacobson et al. 2013): the sum of
   its triangles' signed solid angles (Van Oosterom & Strackee) over 4 pi. p is inside when its
   magnitude is at least 1/2: the exact inside test of a closed mesh (either orientation), and
   the robust one of an open mesh. */
static double winding_number(const voxgi_mesh *m, const double p[3])
{
    size_t t, nt = m->indices ? m->index_count / 3 : m->vertex_count / 3, stride = m->position_stride ? m->position_stride : 12;
    double sum = 0;
    for (t = 0; t < nt; t++) {
        double a[3][3], l[3], det, dot;
        int c, k;
        for (c = 0; c < 3; c++) {
            size_t vi = m->indices ? m->indices[3 * t + (size_t)c] : 3 * t + (size_t)c;
            const float *v = (const float *)(const void *)((const unsigned char *)m->positions + vi * stride);
            for (k = 0; k < 3; k++) a[c][k] = v[k] - p[k];
            l[c] = sqrt(a[c][0] * a[c][0] + a[c][1] * a[c][1] + a[c][2] * a[c][2]);
        }
        det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
              a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        dot = l[0] * l[1] * l[2] + l[2] * (a[0][0] * a[1][0] + a[0][1] * a[1][1] + a[0][2] * a[1][2]) +
              l[1] * (a[0][0] * a[2][0] + a[0][1] * a[2][1] + a[0][2] * a[2][2]) +
              l[0] * (a[1][0] * a[2][0] + a[1][1] * a[2][1] + a[1][2] * a[2][2]);
        sum += 2 * atan2(det, dot);
    }
    return sum / (4 * 3.14159265358979323846);
}

/* Sampled voxel centres of the n^3 fitted grid (a fixed sequence) and whether each is inside. */
typedef struct bench_inside { uint64_t *voxel; unsigned char *inside; int count; } bench_inside;

static void bench_inside_sample(const tool_mesh *tm, voxgi_context *ctx, int n, bench_inside *bi)
{
    voxgi_fit_desc fit;
    voxgi_grid g;
    size_t nt = mesh_triangles(tm);
    uint64_t state = 0x2545F4914F6CDD1Dull, nvox;
    int i;
    memset(&fit, 0, sizeof fit);
    fit.res = n;
    fit.padding = 1;
    bi->count = 0;
    if (voxgi_fit_grid(ctx, &tm->scene, &fit, &g) != VOXGI_OK) return;
    nvox = voxgi_grid_voxel_count(&g);
    /* about 2e8 solid angles per grid: 20000 centres for small meshes, fewer for big ones */
    bi->count = (int)(nt ? (2e8 / (double)nt < 20000 ? 2e8 / (double)nt : 20000) : 0);
    if (bi->count < 500) bi->count = 500;
    bi->voxel = (uint64_t *)malloc((size_t)bi->count * sizeof *bi->voxel);
    bi->inside = (unsigned char *)malloc((size_t)bi->count);
    for (i = 0; i < bi->count; i++) {
        uint64_t l;
        double p[3];
        state ^= state >> 12; state ^= state << 25; state ^= state >> 27;
        l = (state * 0x2545F4914F6CDD1Dull) % nvox;
        p[0] = g.origin[0] + ((double)(l % (uint64_t)g.res[0]) + 0.5) * g.voxel_size;
        p[1] = g.origin[1] + ((double)(l / (uint64_t)g.res[0] % (uint64_t)g.res[1]) + 0.5) * g.voxel_size;
        p[2] = g.origin[2] + ((double)(l / ((uint64_t)g.res[0] * (uint64_t)g.res[1])) + 0.5) * g.voxel_size;
        bi->voxel[i] = l;
        bi->inside[i] = (unsigned char)(fabs(winding_number(&tm->vm, p)) >= 0.5); /* either orientation */
    }
}

/* Median time of `runs` voxelizations; the last result's bits go to *bits when asked. */
static int g_bench_atlas_size; /* --atlas-size: one atlas for every N (0: each grid's default) */

static int bench_measure(voxgi_context *ctx, const tool_mesh *tm, int n, const bench_method *bm, int runs, double *ms,
                         uint64_t *voxels, uint32_t **bits)
{
    voxgi_voxelize_desc vd;
    voxgi_fit_desc fit;
    double t[32];
    int i;
    memset(&vd, 0, sizeof vd);
    memset(&fit, 0, sizeof fit);
    fit.res = n;
    fit.padding = 1;
    if (voxgi_fit_grid(ctx, &tm->scene, &fit, &vd.grid) != VOXGI_OK) return 0;
    vd.method = bm->method;
    vd.solid_mode = bm->mode;
    if (bm->method == VOXGI_METHOD_VOLUME_BUFFER) vd.volume_slicing = bm->variant;
    else vd.atomic = bm->variant;
    vd.atlas_size = g_bench_atlas_size;
    for (i = 0; i < runs; i++) {
        voxgi_voxels *vox = NULL;
        voxgi_voxels_info info;
        if (voxgi_voxelize(ctx, &tm->scene, &vd, &vox) != VOXGI_OK) {
            fprintf(stderr, "voxgi bench: %s %s at %d: %s\n", tm->name, bm->name, n, voxgi_last_error(ctx));
            return 0;
        }
        voxgi_voxels_query(vox, &info);
        t[i] = info.ms;
        *voxels = info.voxel_count;
        if (bits && i == runs - 1) {
            *bits = (uint32_t *)malloc(info.bytes);
            if (*bits && voxgi_voxels_read(ctx, vox, *bits, info.bytes, NULL) != VOXGI_OK) { free(*bits); *bits = NULL; }
        }
        voxgi_voxels_destroy(ctx, vox);
    }
    qsort(t, (size_t)runs, sizeof t[0], cmp_double);
    *ms = t[runs / 2];
    return 1;
}

static uint64_t popcount32(uint32_t x)
{
    uint64_t c = 0;
    for (; x; x &= x - 1) c++;
    return c;
}

static void print_header(const char *first, int ncols, const int *cols)
{
    int n;
    const char *bar = first;
    printf("| mesh | %s |", first);
    for (n = 0; n < ncols; n++) printf(" %d |", cols[n]);
    printf("\n|---|---|");
    while ((bar = strchr(bar, '|')) != NULL) { printf("---|"); bar++; } /* one more per extra label column */
    for (n = 0; n < ncols; n++) printf("---:|");
    printf("\n");
}

static int cmd_bench(int argc, char **argv)
{
    const char *meshes[64], *csv_path = NULL;
    int nmesh = 0, min_res = 32, max_res = 512, runs = 3, use_gl = 1, i, m, n, v, ncols = 0, cols[16], mismatch = 0;
    int chosen[BENCH_METHOD_COUNT], nchosen = 0;
    vxt_gl_kind kind = VXT_GL_AUTO;
    voxgi_context *ctx[3] = {NULL, NULL, NULL};
    vxt_gl *gl = NULL, *unused = NULL;
    voxgi_info ci;
    char why[512] = "";
    bench_cell *cells;
    FILE *csv = NULL;
    static const char *labels[3] = {"CPU 1T", "CPU nT", "GL"};
    if (argc < 1 || strcmp(argv[0], "voxelize") != 0) {
        if (argc >= 1 && (strcmp(argv[0], "--help") == 0 || strcmp(argv[0], "-h") == 0)) { fputs(bench_help, stdout); return 0; }
        return bad_arg("bench", "the benchmark to run is 'voxelize'");
    }
    meshes[nmesh++] = "builtin:quad";
    meshes[nmesh++] = "builtin:subdivided-quad";
    meshes[nmesh++] = "builtin:cube";
    for (i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) { fputs(bench_help, stdout); return 0; }
        else if (strcmp(a, "--min-res") == 0 && i + 1 < argc) { if (!parse_int(argv[++i], 1, 4096, &min_res)) return bad_arg("bench", "--min-res needs 1..4096"); }
        else if (strcmp(a, "--max-res") == 0 && i + 1 < argc) { if (!parse_int(argv[++i], 1, 4096, &max_res)) return bad_arg("bench", "--max-res needs 1..4096"); }
        else if (strcmp(a, "--runs") == 0 && i + 1 < argc) { if (!parse_int(argv[++i], 1, 31, &runs)) return bad_arg("bench", "--runs needs 1..31"); }
        else if (strcmp(a, "--no-gl") == 0) use_gl = 0;
        else if (strcmp(a, "--gl") == 0 && i + 1 < argc) { if (vxt_gl_kind_parse(argv[++i], &kind) != 0) return bad_arg("bench", "--gl is auto, egl or osmesa"); }
        else if (strcmp(a, "--csv") == 0 && i + 1 < argc) csv_path = argv[++i];
        else if (strcmp(a, "--atlas-size") == 0 && i + 1 < argc) {
            if (!parse_int(argv[++i], 1, 16384, &g_bench_atlas_size)) return bad_arg("bench", "--atlas-size needs 1..16384");
        } else if (strcmp(a, "--methods") == 0 && i + 1 < argc) {
            char list[256], *tok, *save = NULL;
            snprintf(list, sizeof list, "%s", argv[++i]);
            nchosen = 0;
            for (tok = list; tok; tok = save) {
                save = strchr(tok, ',');
                if (save) *save++ = 0;
                for (v = 0; v < BENCH_METHOD_COUNT && strcmp(bench_methods[v].name, tok) != 0; v++) {}
                if (v == BENCH_METHOD_COUNT) return bad_arg("bench", "--methods: unknown method");
                if (nchosen < BENCH_METHOD_COUNT) chosen[nchosen++] = v;
            }
        } else if (a[0] == '-') return bad_arg("bench", "unknown option or missing value");
        else if (nmesh < 64) meshes[nmesh++] = a;
    }
    if (!nchosen) chosen[nchosen++] = 0;
    for (n = min_res; n <= max_res && ncols < 16; n *= 2) cols[ncols++] = n;
    if (!ncols) return bad_arg("bench", "empty resolution range");
    ctx[0] = make_context(VOXGI_BACKEND_CPU, kind, 1, 0, &unused, why, sizeof why);
    ctx[1] = make_context(VOXGI_BACKEND_CPU, kind, 0, 0, &unused, why, sizeof why);
    if (use_gl) {
        ctx[2] = make_context(VOXGI_BACKEND_GL, kind, 0, 0, &gl, why, sizeof why);
        if (!ctx[2]) fprintf(stderr, "voxgi bench: no GL column: %s\n", why);
        else { /* compile the shaders before anything is timed */
            tool_mesh warm;
            double ms;
            uint64_t count;
            if (mesh_open("builtin:cube", &warm) == 0) {
                for (v = 0; v < nchosen; v++) bench_measure(ctx[2], &warm, 8, &bench_methods[chosen[v]], 1, &ms, &count, NULL);
                mesh_close(&warm);
            }
        }
    }
    voxgi_query_info(ctx[1], &ci);
    printf("Voxelization, N^3 grids fitted to each mesh; median of %d runs; CPU nT = %d threads.\n", runs, ci.thread_count);
    if (ctx[2]) {
        voxgi_query_info(ctx[2], &ci);
        printf("GL: %s, %s%s\n", ci.gl_version, ci.gl_renderer,
               strstr(ci.gl_renderer, "llvmpipe") ? " - a software rasteriser on the CPU: not GPU timings" : "");
    }
    if (csv_path && !(csv = fopen(csv_path, "w"))) { fprintf(stderr, "voxgi bench: cannot write %s\n", csv_path); return 1; }
    if (csv) fprintf(csv, "mesh,triangles,n,method,backend,ms,voxels,reference,missed,extra,inside_wrong_percent\n");
    cells = (bench_cell *)calloc((size_t)nmesh * (size_t)ncols * (size_t)nchosen, sizeof *cells);
#define CELL(m, n, v) cells[((size_t)(m) * (size_t)ncols + (size_t)(n)) * (size_t)nchosen + (size_t)(v)]
    for (m = 0; m < nmesh; m++) {
        tool_mesh tm;
        if (mesh_open(meshes[m], &tm)) continue;
        for (n = 0; n < ncols; n++) {
            uint32_t *ref[2] = {NULL, NULL}; /* exact references: conservative, solid parity */
            bench_inside inside = {NULL, NULL, -1};
            double ms;
            uint64_t count;
            for (v = 0; v < nchosen; v++) {
                bench_cell *c = &CELL(m, n, v);
                const bench_method *bm = &bench_methods[chosen[v]];
                int b, r = bm->method == VOXGI_METHOD_SOLID;
                uint32_t *bits = NULL;
                if (!ref[r]) bench_measure(ctx[1], &tm, cols[n], &bench_methods[r ? 2 : 0], 1, &ms, &count, &ref[r]);
                for (b = 0; b < 3; b++)
                    if (ctx[b]) c->ok[b] = bench_measure(ctx[b], &tm, cols[n], bm, runs, &c->ms[b], &c->voxels[b], b == 1 ? &bits : NULL);
                if (bits && ref[r]) {
                    uint64_t w, words = ((uint64_t)cols[n] * (uint64_t)cols[n] * (uint64_t)cols[n] + 31) / 32;
                    for (w = 0; w < words; w++) {
                        c->missed += popcount32(ref[r][w] & ~bits[w]);
                        c->extra += popcount32(bits[w] & ~ref[r][w]);
                    }
                }
                if (bits && r) { /* solid: against the winding-number inside test at sampled centres */
                    int k, wrong = 0;
                    if (inside.count < 0) bench_inside_sample(&tm, ctx[1], cols[n], &inside);
                    for (k = 0; k < inside.count; k++)
                        wrong += ((bits[inside.voxel[k] >> 5] >> (inside.voxel[k] & 31)) & 1u) != inside.inside[k];
                    c->sampled = inside.count;
                    c->wrong = inside.count ? 100.0 * wrong / inside.count : 0;
                }
                free(bits);
                for (b = 1; b < 3; b++)
                    if (bm->exact_twin && c->ok[0] && c->ok[b] && c->voxels[b] != c->voxels[0]) mismatch++;
                if (csv)
                    for (b = 0; b < 3; b++)
                        if (c->ok[b])
                            fprintf(csv, "%s,%lu,%d,%s,%s,%.4f,%llu,%s,%llu,%llu,%.3f\n", meshes[m], (unsigned long)mesh_triangles(&tm), cols[n],
                                    bm->name, b == 0 ? "cpu1" : (b == 1 ? "cpu" : "gl"), c->ms[b], (unsigned long long)c->voxels[b],
                                    r ? "solid" : "conservative", (unsigned long long)c->missed, (unsigned long long)c->extra,
                                    r ? c->wrong : 0.0);
                if (isatty(2)) fprintf(stderr, "\r%s %s %d^3 done   ", meshes[m], bm->name, cols[n]);
            }
            free(ref[0]);
            free(ref[1]);
            free(inside.voxel);
            free(inside.inside);
        }
        if (isatty(2)) fprintf(stderr, "\r%70s\r", "");
        printf("%s: %lu triangles\n", meshes[m], (unsigned long)mesh_triangles(&tm));
        mesh_close(&tm);
    }
    printf("\nTable 1: time in ms (median)\n");
    print_header("method | backend", ncols, cols);
    for (m = 0; m < nmesh; m++)
        for (v = 0; v < nchosen; v++) {
            int b;
            for (b = 0; b < 3; b++) {
                if (!ctx[b]) continue;
                printf("| %s | %s | %s |", meshes[m], bench_methods[chosen[v]].name, labels[b]);
                for (n = 0; n < ncols; n++) {
                    bench_cell *c = &CELL(m, n, v);
                    if (c->ok[b]) printf(" %.2f |", c->ms[b]);
                    else printf(" - |");
                }
                printf("\n");
            }
        }
    printf("\nTable 2: set voxels (identical for every backend)\n");
    print_header("method", ncols, cols);
    printf("| total | |");
    for (n = 0; n < ncols; n++) printf(" %llu |", (unsigned long long)cols[n] * (unsigned long long)cols[n] * (unsigned long long)cols[n]);
    printf("\n");
    for (m = 0; m < nmesh; m++)
        for (v = 0; v < nchosen; v++) {
            printf("| %s | %s |", meshes[m], bench_methods[chosen[v]].name);
            for (n = 0; n < ncols; n++) {
                bench_cell *c = &CELL(m, n, v);
                if (c->ok[0]) printf(" %llu |", (unsigned long long)c->voxels[0]);
                else printf(" - |");
            }
            printf("\n");
        }
    printf("\nTable 3: missed / extra voxels against the exact reference (conservative; solid parity for solid methods)\n");
    print_header("method", ncols, cols);
    for (m = 0; m < nmesh; m++)
        for (v = 0; v < nchosen; v++) {
            printf("| %s | %s |", meshes[m], bench_methods[chosen[v]].name);
            for (n = 0; n < ncols; n++) {
                bench_cell *c = &CELL(m, n, v);
                if (c->ok[1]) printf(" %llu / %llu |", (unsigned long long)c->missed, (unsigned long long)c->extra);
                else printf(" - |");
            }
            printf("\n");
        }
    for (v = 0; v < nchosen && bench_methods[chosen[v]].method != VOXGI_METHOD_SOLID; v++) {}
    if (v < nchosen) {
        printf("\nTable 4: solid methods against the exact inside test (generalized winding number >= 1/2 at\n"
               "voxel centres): %% of sampled centres decided wrongly (samples per cell in brackets)\n");
        print_header("method", ncols, cols);
        for (m = 0; m < nmesh; m++)
            for (v = 0; v < nchosen; v++) {
                if (bench_methods[chosen[v]].method != VOXGI_METHOD_SOLID) continue;
                printf("| %s | %s |", meshes[m], bench_methods[chosen[v]].name);
                for (n = 0; n < ncols; n++) {
                    bench_cell *c = &CELL(m, n, v);
                    if (c->ok[1]) printf(" %.2f%% (%d) |", c->wrong, c->sampled);
                    else printf(" - |");
                }
                printf("\n");
            }
    }
#undef CELL
    if (mismatch) printf("\nWARNING: %d cells where a backend's voxel count differs from the CPU's\n", mismatch);
    free(cells);
    if (csv) fclose(csv);
    close_context(ctx[0], NULL);
    close_context(ctx[1], NULL);
    if (ctx[2]) close_context(ctx[2], gl);
    return mismatch ? 1 : 0;
}

/* ------------------------------------------------------------------ svo */
static const char *svo_help =
    "usage: voxgi svo MESH [options]\n"
    "Voxelizes a mesh with its material attributes and builds the sparse voxel octree: prints\n"
    "its nodes per level, bytes per occupied voxel against the dense equivalent, and the time of\n"
    "each pass (the rows of Pracuch 2016, Tables 5.1 and 5.2). --backend picks where the\n"
    "voxelization and the octree build run (GL: flag, allocate and initialise passes per level).\n"
    "  --res N                  cubic grid of N^3 voxels fitted around the mesh (default 128)\n"
    "  --attributes LIST        albedo,normal,emission,opacity or all (default all)\n"
    "  --backend auto|cpu|gl    where it runs (default auto)\n"
    "  --gl auto|egl|osmesa     headless GL context to create (default auto)\n"
    "  --threads T              CPU worker threads (default: one per core)\n"
    "  --neighbours             also build the six neighbour pointers of every node\n"
    "  --bricks                 also a 4x4x4 brick per inner node (seamless trilinear sampling)\n"
    "  --format float32|float16 how values are stored (default float32)\n"
    "  --json                   one JSON object: leaf_voxels, nodes, bytes, structure_bytes, ms, ...\n";

static int cmd_svo(int argc, char **argv)
{
    const char *mesh_path = NULL;
    int res = 128, json = 0, threads = 0, i, rc = 1, lev;
    double dense8 = 0;
    voxgi_backend backend = VOXGI_BACKEND_AUTO;
    vxt_gl_kind kind = VXT_GL_AUTO;
    voxgi_voxelize_desc vd;
    voxgi_svo_desc sd;
    voxgi_fit_desc fit;
    tool_mesh tm;
    voxgi_context *ctx;
    vxt_gl *gl = NULL;
    voxgi_voxels *vox = NULL;
    voxgi_voxels_info vinfo;
    voxgi_svo *svo = NULL;
    voxgi_svo_info info;
    char why[512] = "";
    memset(&vd, 0, sizeof vd);
    memset(&sd, 0, sizeof sd);
    vd.attributes = 15;
    for (i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) { fputs(svo_help, stdout); return 0; }
        else if (strcmp(a, "--res") == 0 && i + 1 < argc) { if (!parse_int(argv[++i], 1, VOXGI_MAX_RES, &res)) return bad_arg("svo", "--res needs 1..65536"); }
        else if (strcmp(a, "--attributes") == 0 && i + 1 < argc) {
            if (!parse_attributes(argv[++i], &vd.attributes)) return bad_arg("svo", "--attributes lists albedo, normal, emission, opacity or all");
        } else if (strcmp(a, "--backend") == 0 && i + 1 < argc) { if (!parse_backend(argv[++i], &backend)) return bad_arg("svo", "--backend is auto, cpu or gl"); }
        else if (strcmp(a, "--gl") == 0 && i + 1 < argc) { if (vxt_gl_kind_parse(argv[++i], &kind) != 0) return bad_arg("svo", "--gl is auto, egl or osmesa"); }
        else if (strcmp(a, "--threads") == 0 && i + 1 < argc) { if (!parse_int(argv[++i], 1, 256, &threads)) return bad_arg("svo", "--threads needs 1..256"); }
        else if (strcmp(a, "--json") == 0) json = 1;
        else if (strcmp(a, "--neighbours") == 0) sd.neighbours = 1;
        else if (strcmp(a, "--bricks") == 0) sd.bricks = 1;
        else if (strcmp(a, "--format") == 0 && i + 1 < argc) {
            const char *f = argv[++i];
            if (strcmp(f, "float32") == 0) sd.format = VOXGI_SVO_FLOAT32;
            else if (strcmp(f, "float16") == 0) sd.format = VOXGI_SVO_FLOAT16;
            else return bad_arg("svo", "--format is float32 or float16");
        }
        else if (a[0] == '-') return bad_arg("svo", "unknown option or missing value");
        else if (!mesh_path) mesh_path = a;
        else return bad_arg("svo", "more than one mesh given");
    }
    if (!mesh_path) return bad_arg("svo", "no mesh given");
    if (mesh_open(mesh_path, &tm)) return 1;
    ctx = make_context(backend, kind, threads, !json && isatty(2), &gl, why, sizeof why);
    if (!ctx) {
        fprintf(stderr, "voxgi svo: cannot use backend %s: %s\n", voxgi_backend_name(backend), why);
        mesh_close(&tm);
        return 1;
    }
    memset(&fit, 0, sizeof fit);
    fit.res = res;
    fit.padding = 1;
    if (voxgi_fit_grid(ctx, &tm.scene, &fit, &vd.grid) != VOXGI_OK || voxgi_voxelize(ctx, &tm.scene, &vd, &vox) != VOXGI_OK ||
        voxgi_svo_create(ctx, vox, &sd, &svo) != VOXGI_OK) {
        fprintf(stderr, "voxgi svo: %s: %s\n", mesh_path, voxgi_last_error(ctx));
        goto done;
    }
    voxgi_voxels_query(vox, &vinfo);
    voxgi_svo_query(svo, &info);
    for (lev = 0; lev < 4; lev++) /* the dense RGBA8 (R8) equivalent, the usual yardstick */
        if (info.attributes & (1u << lev)) dense8 += (double)voxgi_grid_voxel_count(&vd.grid) * (lev == 3 ? 1 : 4);
    if (json) {
        printf("{\"mesh\":\"%s\",\"triangles\":%lu,\"res\":[%d,%d,%d],\"depth\":%d,\"leaf_voxels\":%llu,\"nodes\":%llu,\"leaf_slots\":%llu,"
               "\"format\":\"%s\",\"bytes\":%lu,\"structure_bytes\":%lu,\"neighbour_bytes\":%lu,\"brick_bytes\":%lu,\"dense_bytes\":%lu,\"dense_rgba8_bytes\":%.0f,"
               "\"voxelize_ms\":%.3f,\"ms\":%.3f,"
               "\"sort_ms\":%.3f,\"nodes_ms\":%.3f,\"neighbours_ms\":%.3f,\"values_ms\":%.3f,\"level_nodes\":[",
               mesh_path, (unsigned long)mesh_triangles(&tm), vd.grid.res[0], vd.grid.res[1], vd.grid.res[2], info.depth,
               (unsigned long long)info.leaf_voxels, (unsigned long long)info.nodes, (unsigned long long)info.leaf_slots,
               info.format == VOXGI_SVO_FLOAT16 ? "float16" : "float32", (unsigned long)info.bytes, (unsigned long)info.structure_bytes,
               (unsigned long)info.neighbour_bytes, (unsigned long)info.brick_bytes, (unsigned long)info.dense_bytes, dense8, vinfo.ms, info.ms, info.ms_sort, info.ms_nodes, info.ms_neighbours, info.ms_values);
        for (lev = 0; lev <= info.depth; lev++) printf("%s%llu", lev ? "," : "", (unsigned long long)info.level_nodes[lev]);
        printf("]}\n");
    } else {
        printf("%s: %lu triangles, %dx%dx%d voxels, depth %d\n", mesh_path, (unsigned long)mesh_triangles(&tm), vd.grid.res[0],
               vd.grid.res[1], vd.grid.res[2], info.depth);
        printf("| level | nodes |\n|---:|---:|\n");
        for (lev = 0; lev <= info.depth; lev++) printf("| %d | %llu |\n", lev, (unsigned long long)info.level_nodes[lev]);
        printf("\nTable 5.1 (memory)\n| structure | bytes | per voxel |\n|---|---:|---:|\n");
        printf("| dense equivalent, %s | %lu | %.1f |\n", info.format == VOXGI_SVO_FLOAT16 ? "RGBA16F (R16F)" : "RGBA32F (R32F)",
               (unsigned long)info.dense_bytes, (double)info.dense_bytes / (double)(info.leaf_voxels ? info.leaf_voxels : 1));
        printf("| dense equivalent, RGBA8 (R8) | %.0f | %.1f |\n", dense8, dense8 / (double)(info.leaf_voxels ? info.leaf_voxels : 1));
        printf("| octree structure (%llu node slots) | %lu | %.2f |\n", (unsigned long long)info.nodes, (unsigned long)info.structure_bytes,
               (double)info.structure_bytes / (double)(info.leaf_voxels ? info.leaf_voxels : 1));
        if (info.neighbour_bytes)
            printf("| neighbour pointers | %lu | %.2f |\n", (unsigned long)info.neighbour_bytes,
                   (double)info.neighbour_bytes / (double)(info.leaf_voxels ? info.leaf_voxels : 1));
        if (info.brick_bytes)
            printf("| bricks (4x4x4 per inner node) | %lu | %.2f |\n", (unsigned long)info.brick_bytes,
                   (double)info.brick_bytes / (double)(info.leaf_voxels ? info.leaf_voxels : 1));
        printf("| octree everything (%llu leaf slots) | %lu | %.1f |\n", (unsigned long long)info.leaf_slots, (unsigned long)info.bytes,
               (double)info.bytes / (double)(info.leaf_voxels ? info.leaf_voxels : 1));
        printf("\ndense RGBA8 / octree: %.1fx less memory\n", dense8 / (double)(info.bytes ? info.bytes : 1));
        printf("\nTable 5.2 (ms; %s)\n| pass | ms |\n|---|---:|\n", voxgi_backend_name(vinfo.backend));
        printf("| voxelization with attributes | %.2f |\n| sort voxels (Morton) | %.2f |\n| nodes and child pointers | %.2f |\n"
               "| neighbour pointers | %.2f |\n| values, mips and bricks | %.2f |\n", vinfo.ms, info.ms_sort, info.ms_nodes, info.ms_neighbours,
               info.ms_values);
    }
    rc = 0;
done:
    voxgi_svo_destroy(ctx, svo);
    if (vox) voxgi_voxels_destroy(ctx, vox);
    close_context(ctx, gl);
    mesh_close(&tm);
    return rc;
}

/* ------------------------------------------------------------------ render */
static const char *render_help =
    "usage: voxgi render SCENE|MESH [options] -o OUT.png|OUT.pfm\n"
    "Renders a built-in scene (cornell-box, two-spheres, leak-box, furnace) or a mesh file (OBJ+MTL:\n"
    "Kd is the albedo, Ke the emitted radiance) with the reference path tracer on the CPU. A PFM\n"
    "pixel is the mean linear radiance over the pixel's square; a PNG is that times --exposure,\n"
    "clamped and sRGB encoded.\n"
    "  --method reference|vct   the Monte Carlo path tracer (default), or voxel cone tracing: direct\n"
    "                           light through shadow rays plus one bounce gathered by cones from\n"
    "                           the voxels\n"
    "  --backend auto|cpu|gl    vct: where voxelization, mips and cones run (default auto: GL when a\n"
    "                           headless GL 4.5 context works); the reference runs on the CPU\n"
    "  --gl auto|egl|osmesa     which headless GL to try\n"
    "  --res N                  vct: voxels along the scene's longest side (default 128)\n"
    "  --cones N                vct: diffuse cones (default 16)\n"
    "  --step S                 vct: step as a fraction of the cone diameter (default 0.5)\n"
    "  --anisotropic            vct: six-direction mips (default isotropic)\n"
    "  --cone-stride S          vct: cones at every S-th pixel across and down, the pixels between\n"
    "                           interpolated where they share a surface (default 1: every pixel)\n"
    "  --octree [float32|float16]  vct: the cones gather from a sparse voxel octree of the radiance\n"
    "                           (isotropic mips) instead of the volume (default float32)\n"
    "  --bricks                 vct with --octree: sample the octree through its bricks\n"
    "  --inject-samples N       vct: points on each area light and emitter per voxel's light\n"
    "                           (default 4 on the CPU, 16 on GL)\n"
    "  --no-gi                  vct: direct light only\n"
    "  --compare SPP            also render the reference (same bounces) with SPP samples per pixel and\n"
    "                           print the relative RMSE of the lighting (both without the emitters the\n"
    "                           camera sees) and both times; the image written is the one with them\n"
    "  --bounces B              indirect bounces: 0 = direct light only, -1 = unlimited (default 1);\n"
    "                           vct: B >= 1, the light bouncing B - 1 times among the voxels first\n"
    "  --spp S                  samples per pixel (default 64)\n"
    "  --seed N                 random seed (default 1); the same seed gives the same image\n"
    "  --camera EX EY EZ TX TY TZ FOVY  eye, target (up +Y) and vertical field of view in degrees\n"
    "                           (default: the scene's view; for a mesh, a view of its bounds)\n"
    "  --size W H               image size (default 256 256)\n"
    "  --sun DX DY DZ E         add a directional light travelling along D with irradiance E\n"
    "  --exposure X             PNG only: scale before clamping (default 1)\n"
    "  --threads T              CPU worker threads (default: one per core)\n"
    "  --json                   print one JSON object (timings, rays, mean radiance) instead of text\n";

static int cmd_render(int argc, char **argv)
{
    const char *what = NULL, *out_path = NULL;
    int json = 0, threads = 0, i, rc = 1, have_camera = 0, w = 256, h = 256, have_sun = 0, vct = 0, compare = 0, spp_given = 0;
    voxgi_backend backend = VOXGI_BACKEND_AUTO;
    vxt_gl_kind kind = VXT_GL_AUTO;
    voxgi_info ci;
    voxgi_vct_desc vd;
    voxgi_vct_info vinfo;
    double rmse = -1, ref_ms = 0;
    double cam[7], sun[4], exposure = 1;
    voxgi_reference_desc d;
    voxgi_reference_info info;
    voxgi_builtin_scene bs;
    tool_mesh tm;
    const voxgi_scene *scene = NULL;
    voxgi_scene with_sun;
    voxgi_light *lights = NULL;
    voxgi_context *ctx;
    vxt_gl *gl = NULL;
    float *rgb = NULL;
    char why[512] = "";
    memset(&d, 0, sizeof d);
    memset(&vd, 0, sizeof vd);
    memset(&vinfo, 0, sizeof vinfo);
    memset(&bs, 0, sizeof bs);
    memset(&tm, 0, sizeof tm);
    d.bounces = 1;
    d.samples = 64;
    d.seed = 1;
    for (i = 0; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) { fputs(render_help, stdout); return 0; }
        else if (strcmp(a, "--method") == 0 && i + 1 < argc) {
            const char *m = argv[++i];
            if (strcmp(m, "reference") == 0) vct = 0;
            else if (strcmp(m, "vct") == 0) vct = 1;
            else return bad_arg("render", "--method is reference or vct");
        } else if (strcmp(a, "--res") == 0 && i + 1 < argc) { if (!parse_int(argv[++i], 1, 4096, &vd.resolution)) return bad_arg("render", "--res needs 1..4096"); }
        else if (strcmp(a, "--cones") == 0 && i + 1 < argc) { if (!parse_int(argv[++i], 1, 1024, &vd.cones.cones)) return bad_arg("render", "--cones needs 1..1024"); }
        else if (strcmp(a, "--step") == 0 && i + 1 < argc) {
            double st;
            if (!parse_double(argv[++i], &st) || !(st > 0 && st <= 4)) return bad_arg("render", "--step needs (0, 4]");
            vd.cones.step = (float)st;
        } else if (strcmp(a, "--anisotropic") == 0) vd.filter = VOXGI_MIPS_ANISOTROPIC;
        else if (strcmp(a, "--no-gi") == 0) vd.no_gi = 1;
        else if (strcmp(a, "--inject-samples") == 0 && i + 1 < argc) {
            if (!parse_int(argv[++i], 1, 4096, &vd.inject_samples)) return bad_arg("render", "--inject-samples needs 1..4096");
        }
        else if (strcmp(a, "--compare") == 0 && i + 1 < argc) { if (!parse_int(argv[++i], 1, 1 << 24, &compare)) return bad_arg("render", "--compare needs 1..16777216"); }
        else if (strcmp(a, "--bounces") == 0 && i + 1 < argc) { if (!parse_int(argv[++i], -1, 1000, &d.bounces)) return bad_arg("render", "--bounces needs -1..1000"); }
        else if (strcmp(a, "--spp") == 0 && i + 1 < argc) {
            if (!parse_int(argv[++i], 1, 1 << 24, &d.samples)) return bad_arg("render", "--spp needs 1..16777216");
            spp_given = 1;
        }
        else if (strcmp(a, "--seed") == 0 && i + 1 < argc) { int s; if (!parse_int(argv[++i], 0, 2147483647, &s)) return bad_arg("render", "--seed needs 0..2^31-1"); d.seed = (uint64_t)s; }
        else if (strcmp(a, "--camera") == 0 && i + 7 < argc) {
            int k;
            for (k = 0; k < 7; k++) if (!parse_double(argv[++i], &cam[k])) return bad_arg("render", "--camera needs seven numbers");
            have_camera = 1;
        } else if (strcmp(a, "--size") == 0 && i + 2 < argc) {
            if (!parse_int(argv[i + 1], 1, 16384, &w) || !parse_int(argv[i + 2], 1, 16384, &h)) return bad_arg("render", "--size needs W H in 1..16384");
            i += 2;
        } else if (strcmp(a, "--sun") == 0 && i + 4 < argc) {
            int k;
            for (k = 0; k < 4; k++) if (!parse_double(argv[++i], &sun[k])) return bad_arg("render", "--sun needs DX DY DZ E");
            have_sun = 1;
        } else if (strcmp(a, "--exposure") == 0 && i + 1 < argc) { if (!parse_double(argv[++i], &exposure) || !(exposure >= 0)) return bad_arg("render", "--exposure needs a number >= 0"); }
        else if (strcmp(a, "--threads") == 0 && i + 1 < argc) { if (!parse_int(argv[++i], 1, 256, &threads)) return bad_arg("render", "--threads needs 1..256"); }
        else if (strcmp(a, "--json") == 0) json = 1;
        else if (strcmp(a, "--cone-stride") == 0 && i + 1 < argc) { if (!parse_int(argv[++i], 1, 64, &vd.cone_stride)) return bad_arg("render", "--cone-stride needs 1..64"); }
        else if (strcmp(a, "--octree") == 0) {
            vd.octree = 1;
            if (i + 1 < argc && (strcmp(argv[i + 1], "float32") == 0 || strcmp(argv[i + 1], "float16") == 0))
                vd.octree_format = strcmp(argv[++i], "float16") == 0 ? VOXGI_SVO_FLOAT16 : VOXGI_SVO_FLOAT32;
        } else if (strcmp(a, "--bricks") == 0) vd.octree_bricks = 1;
        else if (strcmp(a, "--backend") == 0 && i + 1 < argc) { if (!parse_backend(argv[++i], &backend)) return bad_arg("render", "--backend is auto, cpu or gl"); }
        else if (strcmp(a, "--gl") == 0 && i + 1 < argc) { if (vxt_gl_kind_parse(argv[++i], &kind) != 0) return bad_arg("render", "--gl is auto, egl or osmesa"); }
        else if (strcmp(a, "-o") == 0 && i + 1 < argc) out_path = argv[++i];
        else if (a[0] == '-') return bad_arg("render", "unknown option or missing value");
        else if (!what) what = a;
        else return bad_arg("render", "more than one scene given");
    }
    if (!what) return bad_arg("render", "no scene or mesh given");
    if (!out_path || (!strstr(out_path, ".png") && !strstr(out_path, ".pfm"))) return bad_arg("render", "-o OUT.png or OUT.pfm is needed");
    ctx = make_context(vct ? backend : VOXGI_BACKEND_CPU, kind, threads, !json && isatty(2), &gl, why, sizeof why);
    if (!ctx) { fprintf(stderr, "voxgi render: %s\n", why); return 1; }
    voxgi_query_info(ctx, &ci);
    if (strchr(what, '.') == NULL && strncmp(what, "builtin:", 8) != 0) { /* a built-in scene */
        if (voxgi_builtin_scene_create(ctx, what, &bs) != VOXGI_OK) { fprintf(stderr, "voxgi render: %s\n", voxgi_last_error(ctx)); goto done; }
        scene = &bs.scene;
        d.camera = bs.camera;
    } else {
        float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
        size_t v;
        double c[3], r = 0;
        int a;
        if (mesh_open(what, &tm)) goto done;
        scene = &tm.scene;
        for (v = 0; v < tm.vm.vertex_count; v++)
            for (a = 0; a < 3; a++) { lo[a] = fminf(lo[a], tm.vm.positions[3 * v + a]); hi[a] = fmaxf(hi[a], tm.vm.positions[3 * v + a]); }
        for (a = 0; a < 3; a++) { c[a] = 0.5 * ((double)lo[a] + hi[a]); r = fmax(r, 0.5 * ((double)hi[a] - lo[a])); }
        d.camera.eye[0] = c[0]; d.camera.eye[1] = c[1] + 0.6 * r; d.camera.eye[2] = c[2] - 3.2 * r;
        memcpy(d.camera.target, c, sizeof c);
        d.camera.fovy_degrees = 40;
    }
    if (have_camera) {
        memcpy(d.camera.eye, cam, 3 * sizeof(double));
        memcpy(d.camera.target, cam + 3, 3 * sizeof(double));
        d.camera.fovy_degrees = cam[6];
    }
    d.camera.width = w;
    d.camera.height = h;
    if (have_sun) { /* the scene's lights and one more */
        with_sun = *scene;
        lights = (voxgi_light *)calloc(scene->light_count + 1, sizeof *lights);
        if (!lights) { fprintf(stderr, "voxgi render: out of memory\n"); goto done; }
        if (scene->light_count) memcpy(lights, scene->lights, scene->light_count * sizeof *lights);
        lights[scene->light_count].type = VOXGI_LIGHT_DIRECTIONAL;
        for (i = 0; i < 3; i++) { lights[scene->light_count].direction[i] = (float)sun[i]; lights[scene->light_count].intensity[i] = (float)sun[3]; }
        with_sun.lights = lights;
        with_sun.light_count = scene->light_count + 1;
        scene = &with_sun;
    }
    rgb = (float *)malloc((size_t)w * (size_t)h * 12);
    if (!rgb) { fprintf(stderr, "voxgi render: out of memory\n"); goto done; }
    memset(&info, 0, sizeof info);
    if (vct) { /* the same view and seed; the direct light takes --spp rays per pixel (default 16) */
        vd.camera = d.camera;
        vd.seed = d.seed;
        vd.samples = spp_given ? d.samples : 16;
        if (d.bounces < 1 && !vd.no_gi) { fprintf(stderr, "voxgi render: vct needs --bounces 1 or more (or --no-gi)\n"); goto done; }
        vd.bounces = d.bounces;
        if (vd.no_gi) d.bounces = 0; /* what it is compared against */
    }
    if (vct ? voxgi_vct_render(ctx, scene, &vd, rgb, (size_t)w * (size_t)h * 12, &vinfo) != VOXGI_OK
            : voxgi_reference_render(ctx, scene, &d, rgb, (size_t)w * (size_t)h * 12, &info) != VOXGI_OK) {
        fprintf(stderr, "voxgi render: %s\n", voxgi_last_error(ctx));
        goto done;
    }
    if (compare) { /* relative RMSE of the lighting: the RMS difference over every pixel and channel / the reference's mean, both
                      rendered without the emitters the camera sees (the same in both but for the noise at their edges,
                      which would swamp the lighting) */
        float *ref = (float *)malloc((size_t)w * (size_t)h * 24), *mine = ref ? ref + (size_t)w * (size_t)h * 3 : NULL;
        voxgi_reference_desc rd = d;
        voxgi_reference_info ri;
        double sq = 0, sum = 0;
        size_t p;
        voxgi_vct_desc vh = vd;
        voxgi_reference_desc dh = d;
        rd.samples = compare;
        rd.seed = d.seed + 1000003; /* independent of the image's own noise */
        rd.hide_emitters = vh.hide_emitters = dh.hide_emitters = 1;
        if (!ref || voxgi_reference_render(ctx, scene, &rd, ref, (size_t)w * (size_t)h * 12, &ri) != VOXGI_OK ||
            (vct ? voxgi_vct_render(ctx, scene, &vh, mine, (size_t)w * (size_t)h * 12, NULL)
                 : voxgi_reference_render(ctx, scene, &dh, mine, (size_t)w * (size_t)h * 12, NULL)) != VOXGI_OK) {
            fprintf(stderr, "voxgi render: the reference: %s\n", ref ? voxgi_last_error(ctx) : "out of memory");
            free(ref);
            goto done;
        }
        for (p = 0; p < (size_t)w * (size_t)h * 3; p++) { sq += ((double)mine[p] - ref[p]) * ((double)mine[p] - ref[p]); sum += ref[p]; }
        rmse = sqrt(sq / ((double)w * h * 3)) / (sum / ((double)w * h * 3));
        ref_ms = ri.ms_bvh + ri.ms_render;
        free(ref);
    }
    if ((strstr(out_path, ".pfm") ? vxt_write_pfm(out_path, rgb, w, h) : vxt_write_png(out_path, rgb, w, h, (float)exposure)) != 0) {
        fprintf(stderr, "voxgi render: cannot write %s\n", out_path);
        goto done;
    }
    {
        double mean[3] = {0, 0, 0};
        size_t p;
        for (p = 0; p < (size_t)w * (size_t)h; p++) for (i = 0; i < 3; i++) mean[i] += rgb[3 * p + (size_t)i];
        for (i = 0; i < 3; i++) mean[i] /= (double)w * h;
        if (vct) {
            if (json)
                printf("{\"scene\":\"%s\",\"method\":\"vct\",\"backend\":\"%s\",\"size\":[%d,%d],\"res\":%d,\"cones\":%d,\"gi\":%d,\"voxels\":%llu,\"voxelize_ms\":%.3f,"
                       "\"inject_ms\":%.3f,\"octree_ms\":%.3f,\"radiance_bytes\":%llu,\"cones_ms\":%.3f,\"direct_ms\":%.3f,\"ms\":%.3f,\"mean\":[%.6g,%.6g,%.6g],\"rel_rmse\":%.6g,"
                       "\"reference_ms\":%.3f,\"output\":\"%s\"}\n",
                       what, voxgi_backend_name(ci.backend), w, h, vd.resolution ? vd.resolution : 128, vd.cones.cones ? vd.cones.cones : 16, !vd.no_gi, (unsigned long long)vinfo.voxels,
                       vinfo.ms_voxelize, vinfo.ms_inject, vinfo.ms_octree, (unsigned long long)vinfo.radiance_bytes, vinfo.ms_cones, vinfo.ms_direct, vinfo.ms, mean[0], mean[1], mean[2], rmse, ref_ms, out_path);
            else {
                printf("%s: %d x %d cone-traced (%s%s%s), %llu voxels: voxelize %.1f ms, inject + mips %.1f ms, ", what, w, h, voxgi_backend_name(ci.backend),
                       ci.backend == VOXGI_BACKEND_GL ? ", " : "", ci.backend == VOXGI_BACKEND_GL ? ci.gl_renderer : "", (unsigned long long)vinfo.voxels,
                       vinfo.ms_voxelize, vinfo.ms_inject);
                if (vd.octree) printf("octree %.1f ms, ", vinfo.ms_octree);
                printf("cones %.1f ms (over %.1f MB of %s), direct light %.1f ms, total %.1f ms; mean radiance %.4g %.4g %.4g -> %s\n", vinfo.ms_cones,
                       vinfo.radiance_bytes / 1e6, vd.octree ? "octree" : "volume", vinfo.ms_direct, vinfo.ms, mean[0], mean[1], mean[2], out_path);
                if (compare)
                    printf("against the reference (%d bounce%s, %d spp, %.1f ms): relative RMSE %.2f%%\n", d.bounces, d.bounces == 1 ? "" : "s",
                           compare, ref_ms, 100 * rmse);
            }
        } else if (json)
            printf("{\"scene\":\"%s\",\"method\":\"reference\",\"size\":[%d,%d],\"spp\":%d,\"bounces\":%d,\"seed\":%llu,\"triangles\":%lu,"
                   "\"bvh_nodes\":%lu,\"rays\":%llu,\"bvh_ms\":%.3f,\"render_ms\":%.3f,\"mean\":[%.6g,%.6g,%.6g],\"output\":\"%s\"}\n",
                   what, w, h, d.samples, d.bounces, (unsigned long long)d.seed, (unsigned long)info.triangles, (unsigned long)info.bvh_nodes,
                   (unsigned long long)info.rays, info.ms_bvh, info.ms_render, mean[0], mean[1], mean[2], out_path);
        else
            printf("%s: %d x %d, %d spp, bounces %d: %lu triangles, BVH %lu nodes in %.1f ms, %llu rays in %.1f ms (%.2f Mrays/s, CPU); "
                   "mean radiance %.4g %.4g %.4g -> %s\n",
                   what, w, h, d.samples, d.bounces, (unsigned long)info.triangles, (unsigned long)info.bvh_nodes, info.ms_bvh,
                   (unsigned long long)info.rays, info.ms_render, info.ms_render > 0 ? (double)info.rays / info.ms_render / 1000 : 0.0, mean[0],
                   mean[1], mean[2], out_path);
    }
    rc = 0;
done:
    free(rgb);
    free(lights);
    voxgi_builtin_scene_destroy(ctx, &bs);
    if (tm.name[0]) mesh_close(&tm);
    close_context(ctx, gl);
    return rc;
}

/* ------------------------------------------------------------------ main */
static const char *main_help =
    "usage: voxgi COMMAND [options]      (voxgi COMMAND --help for each)\n"
    "  voxelize MESH ...   exact conservative voxelization to binvox / JSON\n"
    "  info                version, capabilities, CPU threads and headless GL contexts\n"
    "  bench voxelize ...  timing and voxel-count tables (Buchacher 2014, Tables 1-2)\n"
    "  svo MESH ...        sparse voxel octree: nodes, memory, build time per pass\n"
    "  render SCENE ...    an image of a built-in scene or a mesh (PNG, PFM): the path-traced\n"
    "                      reference or voxel cone tracing\n"
    "  report vct ...      cone tracing's error against run time (Markdown, CSV, SVG)\n";

/* ------------------------------------------------------------------ report vct */
static const char *report_help =
    "usage: voxgi report vct [options]\n"
    "Error against run time of voxel cone tracing. For each built-in scene it renders the one-bounce\n"
    "reference (converged, --spp samples per pixel), then the cone-traced image for every\n"
    "combination of grid resolution, cone count, aperture, step, cone stride and mips, and measures the\n"
    "relative RMSE of the lighting (the RMS difference over pixels and channels / the reference's\n"
    "mean; the emitters the camera sees are left out of both). The reference's own convergence\n"
    "(4, 16 and 64 spp against the converged image; error ~ 1/sqrt(spp)) gives the time it needs\n"
    "to reach each error, and so the cone tracer's speed-up. Writes DIR/vct.md (tables),\n"
    "DIR/vct.csv and DIR/vct.svg (error against time, log scales, the Pareto front marked).\n"
    "Times are wall clock on this machine; GL times on a software rasteriser are not GPU times.\n"
    "  --scenes LIST            built-in scenes, comma-separated (default cornell-box,two-spheres)\n"
    "  --size N                 N x N pixels (default 128)\n"
    "  --spp S                  samples per pixel of the converged reference (default 1024)\n"
    "  --direct-spp S           the cone tracer's direct-light rays per pixel (default 16)\n"
    "  --res LIST               voxels along the longest side (default 32,64,128)\n"
    "  --cones LIST             diffuse cones (default 8,16,32)\n"
    "  --apertures LIST         half-angle as a multiple of each cone count's gap-free default (default 1)\n"
    "  --steps LIST             step as a fraction of the diameter (default 0.5,1)\n"
    "  --filters LIST           isotropic, anisotropic (dense mips) and/or octree (an octree of the\n"
    "                           radiance, isotropic mips) (default isotropic,anisotropic)\n"
    "  --strides LIST           cone strides: cones at every S-th pixel, the rest interpolated (default 1,2)\n"
    "  --backend auto|cpu|gl    where the cone tracer runs (default cpu)\n"
    "  --out DIR                where the files go (default build/report)\n"
    "  --threads T              CPU worker threads (default: one per core)\n";

static const char *const mips_names[3] = {"isotropic", "anisotropic", "octree"}, *const mips_short[3] = {"iso", "aniso", "octree"},
                         *const mips_mark[3] = {"", "a", "o"};

typedef struct report_row {
    const char *scene;
    int res, cones, mips, stride; /* mips: 0 isotropic, 1 anisotropic, 2 octree */
    double aperture, half_angle_deg, step;
    voxgi_vct_info info;
    double rmse, ref_ms, pareto;
} report_row;

/* Splits a comma-separated list in place into at most max items; the count, or 0 when empty,
   too long or with an empty item. */
static int split_list(char *s, char **items, int max)
{
    int n = 0;
    for (;;) {
        char *comma = strchr(s, ',');
        if (n == max || *s == 0 || *s == ',') return 0;
        items[n++] = s;
        if (!comma) return n;
        *comma = 0;
        s = comma + 1;
    }
}

/* Comma-separated positive numbers into out[0..max); the count, or 0 on a bad list. */
static int parse_list(const char *s, double *out, int max)
{
    char buf[256], *items[16];
    int n, i;
    if (strlen(s) >= sizeof buf || max > 16) return 0;
    strcpy(buf, s);
    n = split_list(buf, items, max);
    for (i = 0; i < n; i++)
        if (!parse_double(items[i], &out[i]) || !(out[i] > 0)) return 0;
    return n;
}

/* Makes a directory and its parents (like mkdir -p); 0 on success. */
static int make_dirs(const char *path)
{
    char buf[1024];
    size_t i, n = strlen(path);
    if (n == 0 || n >= sizeof buf) return -1;
    strcpy(buf, path);
    for (i = 1; i <= n; i++)
        if (buf[i] == '/' || buf[i] == 0) {
            char c = buf[i];
            buf[i] = 0;
            if (mkdir(buf, 0777) != 0 && errno != EEXIST) return -1;
            buf[i] = c;
        }
    return 0;
}

/* RMS difference over every value / mean of the reference. */
static double rel_rmse(const float *a, const float *ref, size_t n)
{
    double sq = 0, sum = 0;
    size_t i;
    for (i = 0; i < n; i++) { sq += ((double)a[i] - ref[i]) * ((double)a[i] - ref[i]); sum += ref[i]; }
    return sum > 0 ? sqrt(sq / (double)n) / (sum / (double)n) : 0;
}

static void report_svg(FILE *f, const report_row *rows, int n, const char *const *scenes, int scene_count, const double *ref_c,
                       const double *ref_floor, const double *ref_ms_per_spp, const double *ref_bvh_ms)
{
    static const char *colours[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd"};
    double tmin = 1e300, tmax = 0, emin = 1e300, emax = 0;
    const double W = 720, H = 480, L = 70, R = 20, T = 30, B = 50;
    int i, s, k;
#define RX(t) (L + (log10(t) - log10(tmin)) / (log10(tmax) - log10(tmin)) * (W - L - R))
#define RY(e) (H - B - (log10(e) - log10(emin)) / (log10(emax) - log10(emin)) * (H - T - B))
    for (i = 0; i < n; i++) {
        tmin = fmin(tmin, rows[i].info.ms); tmax = fmax(tmax, fmax(rows[i].info.ms, rows[i].ref_ms));
        emin = fmin(emin, rows[i].rmse); emax = fmax(emax, rows[i].rmse);
    }
    tmin = pow(10, floor(log10(tmin))); tmax = pow(10, ceil(log10(tmax)));
    emin = pow(10, floor(log10(emin))); emax = pow(10, ceil(log10(emax)));
    if (emax <= emin) emax = emin * 10;
    if (tmax <= tmin) tmax = tmin * 10;
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" font-family=\"sans-serif\" font-size=\"11\">\n", W, H);
    fprintf(f, "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n");
    for (k = (int)log10(tmin); k <= (int)log10(tmax); k++)
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.0f\" x2=\"%.1f\" y2=\"%.0f\" stroke=\"#ddd\"/><text x=\"%.1f\" y=\"%.0f\" text-anchor=\"middle\">%g ms</text>\n",
                RX(pow(10, k)), T, RX(pow(10, k)), H - B, RX(pow(10, k)), H - B + 15, pow(10, k));
    for (k = (int)floor(log10(emin) + 0.5); k <= (int)floor(log10(emax) + 0.5); k++)
        fprintf(f, "<line x1=\"%.0f\" y1=\"%.1f\" x2=\"%.0f\" y2=\"%.1f\" stroke=\"#ddd\"/><text x=\"%.0f\" y=\"%.1f\" text-anchor=\"end\">%g%%</text>\n", L,
                RY(pow(10, k)), W - R, RY(pow(10, k)), L - 5, RY(pow(10, k)) + 4, 100 * pow(10, k));
    fprintf(f, "<text x=\"%.0f\" y=\"%.0f\" text-anchor=\"middle\">time per image (wall clock)</text>\n", (L + W - R) / 2, H - 12);
    fprintf(f, "<text x=\"15\" y=\"%.0f\" transform=\"rotate(-90 15 %.0f)\" text-anchor=\"middle\">relative RMSE against the one-bounce reference</text>\n",
            (T + H - B) / 2, (T + H - B) / 2);
    for (s = 0; s < scene_count; s++) {
        const char *c = colours[s % 4];
        double prev_t = 0, prev_e = 0;
        int first = 1;
        for (k = 0; k <= 40; k++) { /* the path tracer at spp k: its error c / sqrt(k) measured against the reference (with its floor), at time bvh + k x per-spp */
            double spp = pow(2, k / 2.0), t = ref_bvh_ms[s] + spp * ref_ms_per_spp[s], e = sqrt(ref_c[s] * ref_c[s] / spp + ref_floor[s] * ref_floor[s]);
            if (t < tmin || t > tmax || e < emin || e > emax) continue;
            if (!first) fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-dasharray=\"4 3\"/>\n", RX(prev_t), RY(prev_e), RX(t), RY(e), c);
            prev_t = t; prev_e = e; first = 0;
        }
        first = 1;
        for (i = 0; i < n; i++) { /* the Pareto front, in time order (rows are not sorted: find them) */
            if (strcmp(rows[i].scene, scenes[s]) != 0 || !rows[i].pareto) continue;
            fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" fill=\"%s\" font-size=\"9\">%d/%d%s</text>\n", RX(rows[i].info.ms) + 4, RY(rows[i].rmse) - 4, c, rows[i].res,
                    rows[i].cones, mips_mark[rows[i].mips]);
        }
        for (i = 0; i < n; i++) {
            int j, best = -1;
            if (strcmp(rows[i].scene, scenes[s]) != 0 || !rows[i].pareto) continue;
            for (j = 0; j < n; j++) /* the next front point in time */
                if (strcmp(rows[j].scene, scenes[s]) == 0 && rows[j].pareto && rows[j].info.ms > rows[i].info.ms &&
                    (best < 0 || rows[j].info.ms < rows[best].info.ms))
                    best = j;
            if (best >= 0)
                fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"2\"/>\n", RX(rows[i].info.ms), RY(rows[i].rmse),
                        RX(rows[best].info.ms), RY(rows[best].rmse), c);
        }
        for (i = 0; i < n; i++)
            if (strcmp(rows[i].scene, scenes[s]) == 0)
                fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%d\" fill=\"%s\" fill-opacity=\"%s\" stroke=\"%s\"/>\n", RX(rows[i].info.ms), RY(rows[i].rmse),
                        rows[i].pareto ? 4 : 3, rows[i].pareto ? c : "white", rows[i].pareto ? "1" : "0", c);
        fprintf(f, "<circle cx=\"%.0f\" cy=\"%.0f\" r=\"4\" fill=\"%s\"/><text x=\"%.0f\" y=\"%.0f\">%s: cone tracing (filled: Pareto front, "
                   "label res/cones, a = anisotropic, o = octree); dashed: the reference</text>\n", L + 15, T + 12 + 15.0 * s, c, L + 25, T + 16 + 15.0 * s, scenes[s]);
    }
    fprintf(f, "</svg>\n");
#undef RX
#undef RY
}

static int cmd_report(int argc, char **argv)
{
    const char *out_dir = "build/report", *scene_list = "cornell-box,two-spheres";
    double res_l[16] = {32, 64, 128}, cone_l[16] = {8, 16, 32}, ap_l[16] = {1}, step_l[16] = {0.5, 1}, stride_l[16] = {1, 2};
    int nres = 3, ncone = 3, nap = 1, nstep = 2, nstride = 2, ist, filters = 3, size = 128, spp = 1024, direct_spp = 16, threads = 0, i, rc = 1, nrows = 0, s;
    voxgi_backend backend = VOXGI_BACKEND_CPU;
    char why[512] = "", path[1024], scenes_buf[256], *scenes[8];
    int scene_count = 0;
    double ref_c[8], ref_ms_per_spp[8], ref_bvh_ms[8], ref_floor[8];
    report_row *rows = NULL;
    voxgi_context *ctx = NULL;
    voxgi_info ci;
    vxt_gl *gl = NULL;
    float *ref = NULL, *img = NULL;
    FILE *md = NULL, *csv = NULL, *svg = NULL;
    if (argc < 1 || strcmp(argv[0], "vct") != 0) {
        if (argc >= 1 && (strcmp(argv[0], "--help") == 0 || strcmp(argv[0], "-h") == 0)) { fputs(report_help, stdout); return 0; }
        return bad_arg("report", "the report to make is 'vct'");
    }
    for (i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) { fputs(report_help, stdout); return 0; }
        else if (strcmp(a, "--scenes") == 0 && i + 1 < argc) scene_list = argv[++i];
        else if (strcmp(a, "--size") == 0 && i + 1 < argc) { if (!parse_int(argv[++i], 1, 4096, &size)) return bad_arg("report", "--size needs 1..4096"); }
        else if (strcmp(a, "--spp") == 0 && i + 1 < argc) { if (!parse_int(argv[++i], 64, 1 << 20, &spp)) return bad_arg("report", "--spp needs 64..1048576"); }
        else if (strcmp(a, "--direct-spp") == 0 && i + 1 < argc) { if (!parse_int(argv[++i], 1, 65536, &direct_spp)) return bad_arg("report", "--direct-spp needs 1..65536"); }
        else if (strcmp(a, "--res") == 0 && i + 1 < argc) { if (!(nres = parse_list(argv[++i], res_l, 16))) return bad_arg("report", "--res needs a list of numbers"); }
        else if (strcmp(a, "--cones") == 0 && i + 1 < argc) { if (!(ncone = parse_list(argv[++i], cone_l, 16))) return bad_arg("report", "--cones needs a list of numbers"); }
        else if (strcmp(a, "--apertures") == 0 && i + 1 < argc) { if (!(nap = parse_list(argv[++i], ap_l, 16))) return bad_arg("report", "--apertures needs a list of numbers"); }
        else if (strcmp(a, "--steps") == 0 && i + 1 < argc) { if (!(nstep = parse_list(argv[++i], step_l, 16))) return bad_arg("report", "--steps needs a list of numbers"); }
        else if (strcmp(a, "--strides") == 0 && i + 1 < argc) { if (!(nstride = parse_list(argv[++i], stride_l, 16))) return bad_arg("report", "--strides needs a list of numbers"); }
        else if (strcmp(a, "--filters") == 0 && i + 1 < argc) {
            char buf[64], *items[3];
            int k, n = strlen(argv[++i]) < sizeof buf ? split_list(strcpy(buf, argv[i]), items, 3) : 0;
            for (filters = 0, k = 0; k < n; k++)
                filters |= strcmp(items[k], "isotropic") == 0 ? 1 : (strcmp(items[k], "anisotropic") == 0 ? 2 : (strcmp(items[k], "octree") == 0 ? 4 : 8));
            if (!n || filters > 7) return bad_arg("report", "--filters is a list of isotropic, anisotropic, octree");
        }
        else if (strcmp(a, "--backend") == 0 && i + 1 < argc) { if (!parse_backend(argv[++i], &backend)) return bad_arg("report", "--backend is auto, cpu or gl"); }
        else if (strcmp(a, "--out") == 0 && i + 1 < argc) out_dir = argv[++i];
        else if (strcmp(a, "--threads") == 0 && i + 1 < argc) { if (!parse_int(argv[++i], 1, 256, &threads)) return bad_arg("report", "--threads needs 1..256"); }
        else return bad_arg("report", "unknown option or missing value");
    }
    if (strlen(scene_list) >= sizeof scenes_buf) return bad_arg("report", "--scenes is too long");
    strcpy(scenes_buf, scene_list);
    if (!(scene_count = split_list(scenes_buf, scenes, 8))) return bad_arg("report", "--scenes needs a list of at most 8 built-in scenes");
    for (i = 0; i < nres; i++) if (res_l[i] > 4096) return bad_arg("report", "--res values are at most 4096");
    for (i = 0; i < ncone; i++) if (cone_l[i] > 1024) return bad_arg("report", "--cones values are at most 1024");
    for (i = 0; i < nstep; i++) if (step_l[i] > 4) return bad_arg("report", "--steps values are at most 4");
    for (i = 0; i < nstride; i++) if (stride_l[i] > 64 || stride_l[i] != floor(stride_l[i])) return bad_arg("report", "--strides are whole numbers up to 64");
    ctx = make_context(backend, VXT_GL_AUTO, threads, isatty(2), &gl, why, sizeof why);
    if (!ctx) { fprintf(stderr, "voxgi report: %s\n", why); return 1; }
    voxgi_query_info(ctx, &ci);
    rows = (report_row *)calloc((size_t)scene_count * (size_t)(nres * ncone * nap * nstep * nstride * 3), sizeof *rows);
    ref = (float *)malloc((size_t)size * (size_t)size * 12);
    img = (float *)malloc((size_t)size * (size_t)size * 12);
    if (!rows || !ref || !img) { fprintf(stderr, "voxgi report: out of memory\n"); goto done; }
    if (make_dirs(out_dir) != 0) { fprintf(stderr, "voxgi report: cannot make %s\n", out_dir); goto done; }
    for (s = 0; s < scene_count; s++) {
        voxgi_builtin_scene bs;
        voxgi_reference_desc rd;
        voxgi_reference_info ri;
        size_t nv = (size_t)size * (size_t)size * 3;
        int ir, ic, ia, is, f, k, first_row = nrows;
        double c2 = 0;
        if (voxgi_builtin_scene_create(ctx, scenes[s], &bs) != VOXGI_OK) { fprintf(stderr, "voxgi report: %s\n", voxgi_last_error(ctx)); goto done; }
        memset(&rd, 0, sizeof rd);
        rd.camera = bs.camera;
        rd.camera.width = rd.camera.height = size;
        rd.bounces = 1;
        rd.hide_emitters = 1;
        rd.samples = spp;
        rd.seed = 1000;
        fprintf(stderr, "voxgi report: %s: the reference, %d spp\n", scenes[s], spp);
        if (voxgi_reference_render(ctx, &bs.scene, &rd, ref, nv * 4, &ri) != VOXGI_OK) {
            fprintf(stderr, "voxgi report: %s\n", voxgi_last_error(ctx));
            voxgi_builtin_scene_destroy(ctx, &bs);
            goto done;
        }
        for (k = 4; k <= 64; k *= 4) { /* the reference's convergence: a difference of two independent estimates has variance c^2 (1/k + 1/spp) */
            rd.samples = k;
            rd.seed = 7 + (uint64_t)k;
            if (voxgi_reference_render(ctx, &bs.scene, &rd, img, nv * 4, &ri) != VOXGI_OK) { fprintf(stderr, "voxgi report: %s\n", voxgi_last_error(ctx)); goto done; }
            c2 += rel_rmse(img, ref, nv) * rel_rmse(img, ref, nv) / (1.0 / k + 1.0 / spp) / 3;
        }
        ref_c[s] = sqrt(c2);
        ref_ms_per_spp[s] = ri.ms_render / 64;
        ref_bvh_ms[s] = ri.ms_bvh;
        ref_floor[s] = ref_c[s] / sqrt((double)spp);
        for (f = 0; f < 3; f++)
            for (ir = 0; ir < nres; ir++)
                for (ic = 0; ic < ncone; ic++)
                    for (ia = 0; ia < nap; ia++)
                        for (is = 0; is < nstep; is++)
                        for (ist = 0; ist < nstride; ist++) {
                            voxgi_vct_desc vd;
                            report_row *row = &rows[nrows];
                            double need;
                            if (!(filters & (1 << f))) continue;
                            memset(&vd, 0, sizeof vd);
                            vd.camera = rd.camera;
                            vd.resolution = (int)res_l[ir];
                            vd.filter = f == 1 ? VOXGI_MIPS_ANISOTROPIC : VOXGI_MIPS_ISOTROPIC;
                            vd.octree = f == 2;
                            vd.cones.cones = (int)cone_l[ic];
                            vd.cones.half_angle = (float)(ap_l[ia] * acos(1 - 1.0 / vd.cones.cones));
                            vd.cones.step = (float)step_l[is];
                            vd.samples = direct_spp;
                            vd.seed = 1;
                            vd.hide_emitters = 1;
                            vd.cone_stride = (int)stride_l[ist];
                            if (!(vd.cones.half_angle < 1.5f)) continue;
                            fprintf(stderr, "voxgi report: %s: %d^3, %d cones x %.2f, step %.2f, stride %d, %s\n", scenes[s], vd.resolution, vd.cones.cones, ap_l[ia],
                                    step_l[is], vd.cone_stride, mips_names[f]);
                            if (voxgi_vct_render(ctx, &bs.scene, &vd, img, nv * 4, &row->info) != VOXGI_OK) {
                                fprintf(stderr, "voxgi report: %s\n", voxgi_last_error(ctx));
                                voxgi_builtin_scene_destroy(ctx, &bs);
                                goto done;
                            }
                            row->scene = scenes[s];
                            row->res = vd.resolution;
                            row->cones = vd.cones.cones;
                            row->mips = f;
                            row->aperture = ap_l[ia];
                            row->half_angle_deg = vd.cones.half_angle * 180 / 3.14159265358979323846;
                            row->step = step_l[is];
                            row->stride = vd.cone_stride;
                            row->rmse = rel_rmse(img, ref, nv);
                            { /* the path tracer's spp k whose image measures the same error against the same reference:
                                 c^2 (1/k + 1/spp) = rmse^2 (the reference's own noise is in both) */
                                double inv = row->rmse * row->rmse / (ref_c[s] * ref_c[s]) - 1.0 / spp;
                                need = inv > 1.0 / (1024.0 * spp) ? 1 / inv : 1024.0 * spp;
                            }
                            row->ref_ms = ref_bvh_ms[s] + ref_ms_per_spp[s] * (need > 1.0 ? need : 1.0);
                            nrows++;
                        }
        for (i = first_row; i < nrows; i++) { /* on the front: nothing both faster and closer */
            int j;
            rows[i].pareto = 1;
            for (j = first_row; j < nrows; j++)
                if (j != i && rows[j].info.ms <= rows[i].info.ms && rows[j].rmse <= rows[i].rmse &&
                    (rows[j].info.ms < rows[i].info.ms || rows[j].rmse < rows[i].rmse))
                    rows[i].pareto = 0;
        }
        voxgi_builtin_scene_destroy(ctx, &bs);
    }
    snprintf(path, sizeof path, "%s/vct.csv", out_dir);
    if (!(csv = fopen(path, "w"))) { fprintf(stderr, "voxgi report: cannot write %s\n", path); goto done; }
    fprintf(csv, "scene,res,cones,aperture,half_angle_deg,step,stride,filter,voxels,radiance_bytes,voxelize_ms,inject_ms,octree_ms,cones_ms,direct_ms,ms,rel_rmse,"
                 "reference_ms_same_error,speedup,pareto\n");
    for (i = 0; i < nrows; i++)
        fprintf(csv, "%s,%d,%d,%g,%.2f,%g,%d,%s,%llu,%llu,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.5f,%.1f,%.2f,%d\n", rows[i].scene, rows[i].res, rows[i].cones, rows[i].aperture,
                rows[i].half_angle_deg, rows[i].step, rows[i].stride, mips_names[rows[i].mips], (unsigned long long)rows[i].info.voxels,
                (unsigned long long)rows[i].info.radiance_bytes, rows[i].info.ms_voxelize, rows[i].info.ms_inject, rows[i].info.ms_octree, rows[i].info.ms_cones, rows[i].info.ms_direct, rows[i].info.ms, rows[i].rmse,
                rows[i].ref_ms, rows[i].ref_ms / rows[i].info.ms, (int)rows[i].pareto);
    snprintf(path, sizeof path, "%s/vct.md", out_dir);
    if (!(md = fopen(path, "w"))) { fprintf(stderr, "voxgi report: cannot write %s\n", path); goto done; }
    fprintf(md, "# Voxel cone tracing: error against run time\n\n%d x %d pixels; cone tracer on %s%s%s, %d direct-light rays per pixel; the "
                "reference is the one-bounce path tracer (CPU). Error: relative RMSE of the lighting against the converged reference, "
                "emitters seen by the camera left out. *Reference at the same error*: the time the path tracer needs for an image that "
                "measures that error against the same reference (from its measured convergence, the reference's own noise in both). Wall clock on this machine%s.\n\n",
            size, size, voxgi_backend_name(ci.backend), ci.backend == VOXGI_BACKEND_GL ? ", " : "", ci.backend == VOXGI_BACKEND_GL ? ci.gl_renderer : "",
            direct_spp, ci.backend == VOXGI_BACKEND_GL && strstr(ci.gl_renderer, "llvmpipe") ? " (GL on llvmpipe, a software rasteriser: not GPU timings)" : "");
    for (s = 0; s < scene_count; s++) {
        fprintf(md, "## %s\n\nReference: %d spp; its error is %.2f%% / sqrt(spp) (%.3f%% at %d spp: the floor of every error below), %.2f ms per "
                    "sample per pixel.\n\n| res | cones | half-angle | step | stride | mips | voxels | radiance MB | voxelize ms | inject ms | octree ms | cones ms | "
                    "direct ms | total ms | rel. RMSE | reference at the same error | speed-up | Pareto |\n"
                    "|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|:-:|\n",
                scenes[s], spp, 100 * ref_c[s], 100 * ref_floor[s], spp, ref_ms_per_spp[s]);
        for (i = 0; i < nrows; i++)
            if (rows[i].scene == scenes[s])
                fprintf(md, "| %d | %d | %.1f° | %g | %d | %s | %llu | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.2f%% | %.0f ms | %.1fx | %s |\n",
                        rows[i].res, rows[i].cones, rows[i].half_angle_deg, rows[i].step, rows[i].stride, mips_short[rows[i].mips],
                        (unsigned long long)rows[i].info.voxels, rows[i].info.radiance_bytes / 1e6, rows[i].info.ms_voxelize, rows[i].info.ms_inject,
                        rows[i].info.ms_octree, rows[i].info.ms_cones, rows[i].info.ms_direct, rows[i].info.ms, 100 * rows[i].rmse,
                        rows[i].ref_ms, rows[i].ref_ms / rows[i].info.ms, rows[i].pareto ? "yes" : "");
        fprintf(md, "\n");
    }
    fprintf(md, "![error against time](vct.svg)\n");
    snprintf(path, sizeof path, "%s/vct.svg", out_dir);
    if (!(svg = fopen(path, "w"))) { fprintf(stderr, "voxgi report: cannot write %s\n", path); goto done; }
    report_svg(svg, rows, nrows, (const char *const *)scenes, scene_count, ref_c, ref_floor, ref_ms_per_spp, ref_bvh_ms);
    for (s = 0; s < scene_count; s++) { /* the front on stdout */
        printf("%s (reference error %.2f%% / sqrt(spp), %.2f ms per spp; floor %.3f%%)\n", scenes[s], 100 * ref_c[s], ref_ms_per_spp[s], 100 * ref_floor[s]);
        for (i = 0; i < nrows; i++)
            if (rows[i].scene == scenes[s] && rows[i].pareto)
                printf("  %4d^3 %3d cones %5.1f deg step %-4g stride %d %-5s %9.1f ms  %6.2f%%  reference %9.0f ms  %6.1fx\n", rows[i].res, rows[i].cones,
                       rows[i].half_angle_deg, rows[i].step, rows[i].stride, mips_short[rows[i].mips], rows[i].info.ms, 100 * rows[i].rmse, rows[i].ref_ms, rows[i].ref_ms / rows[i].info.ms);
    }
    printf("wrote %s/vct.md, %s/vct.csv, %s/vct.svg\n", out_dir, out_dir, out_dir);
    rc = 0;
done:
    if (md) fclose(md);
    if (csv) fclose(csv);
    if (svg) fclose(svg);
    free(rows);
    free(ref);
    free(img);
    if (ctx) close_context(ctx, gl);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "help") == 0) {
        fputs(main_help, argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    if (strcmp(argv[1], "--version") == 0) { printf("voxgi %s\n", VOXGI_VERSION_STRING); return 0; }
    if (strcmp(argv[1], "voxelize") == 0) return cmd_voxelize(argc - 2, argv + 2);
    if (strcmp(argv[1], "info") == 0) return cmd_info(argc - 2, argv + 2);
    if (strcmp(argv[1], "bench") == 0) return cmd_bench(argc - 2, argv + 2);
    if (strcmp(argv[1], "svo") == 0) return cmd_svo(argc - 2, argv + 2);
    if (strcmp(argv[1], "render") == 0) return cmd_render(argc - 2, argv + 2);
    if (strcmp(argv[1], "report") == 0) return cmd_report(argc - 2, argv + 2);
    fprintf(stderr, "voxgi: unknown command '%s'\n%s", argv[1], main_help);
    return 2;
}
