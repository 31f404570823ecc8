/* tools/cmd_voxelize.c - voxgi voxelize: a mesh into a voxel grid, as text, JSON and files (binvox, .vox, .npy, .ply, .obj). */
#include "cli.h"
#include <stdlib.h>
#include <string.h>

/* --method NAME: a method and its variant (slicemap-atomic, volume-buffer-m1) */
typedef struct voxelize_method { const char *name; voxgi_method method; int atomic, volume_slicing; } voxelize_method;
static const voxelize_method methods[] = {
    {"conservative", VOXGI_METHOD_CONSERVATIVE, 0, 0},
    {"thin", VOXGI_METHOD_THIN, 0, 0},
    {"solid", VOXGI_METHOD_SOLID, 0, 0},
    {"slicemap", VOXGI_METHOD_SLICEMAP, 0, 0},
    {"slicemap-atomic", VOXGI_METHOD_SLICEMAP, 1, 0},
    {"atlas", VOXGI_METHOD_ATLAS, 0, 0},
    {"atlas-compute", VOXGI_METHOD_ATLAS_COMPUTE, 0, 0},
    {"geometry", VOXGI_METHOD_GEOMETRY, 0, 0},
    {"volume-buffer", VOXGI_METHOD_VOLUME_BUFFER, 0, 0},
    {"volume-buffer-m1", VOXGI_METHOD_VOLUME_BUFFER, 0, 1}};

static const char *const blend_names[] = {"average", "max", "add", NULL};       /* voxgi_blend order */
static const char *const atlas_uv_names[] = {"auto", "mesh", NULL};             /* voxgi_atlas_uv order */
static const char *const solid_mode_names[] = {"parity", "vote", "flood", NULL}; /* voxgi_solid_mode order */
static const char *const axis_names[] = {"x", "y", "z", NULL};
static const int axis_values[] = {VOXGI_AXIS_X, VOXGI_AXIS_Y, VOXGI_AXIS_Z};
/* --npy-attribute: the attributes voxgi_io_write_npy_attribute writes */
static const char *const npy_attribute_names[] = {"albedo", "normal", "emission", "opacity", NULL};
static const int npy_attribute_values[] = {VOXGI_ATTRIBUTE_ALBEDO, VOXGI_ATTRIBUTE_NORMAL, VOXGI_ATTRIBUTE_EMISSION, VOXGI_ATTRIBUTE_OPACITY};

static const char *const voxelize_help =
    "usage: voxgi voxelize MESH [options]\n"
    "Voxelizes a mesh. conservative: a voxel is set exactly when its closed box meets a triangle;\n"
    "thin: Schwarz & Seidel's 6-separating subset; solid: the interior (see --solid-mode).\n"
    "MESH: an OBJ (+MTL), OFF, STL, PLY or glTF (.gltf, .glb) file, or builtin:quad|subdivided-quad|cube|sphere.\n";

/* -o by extension: the voxels as binvox, MagicaVoxel, NumPy occupancy, PLY points, OBJ outer faces */
typedef enum out_format { OUT_BINVOX, OUT_VOX, OUT_NPY, OUT_PLY, OUT_OBJ } out_format;
static const char *const out_extensions[] = {".binvox", ".vox", ".npy", ".ply", ".obj"}; /* out_format order */

typedef struct voxelize_args {
    cli_common common;
    const char *mesh, *out;
    out_format out_format;
    int res, per_axis, runs, method, atlas_size, atlas_uv, solid_mode, axis, have_grid, blend[4], nblend;
    int npy_attribute, have_npy_attribute; /* a voxgi_attribute, written to the .npy instead of the occupancy */
    unsigned attributes;
    double pad;
    voxgi_grid grid;
} voxelize_args;

/* --grid OX OY OZ S NX NY NZ: the origin and voxel size exactly as given, whole resolutions */
static int parse_grid(const cli_option *o, char **args, const char **need)
{
    voxgi_grid *g = (voxgi_grid *)o->dst;
    int k;
    *need = "OX OY OZ S as numbers and NX NY NZ in 1..65536";
    for (k = 0; k < 4; k++)
        if (!cli_parse_double(args[k], k < 3 ? &g->origin[k] : &g->voxel_size)) return k;
    for (k = 0; k < 3; k++)
        if (!cli_parse_int(args[4 + k], 1, VOXGI_MAX_RES, &g->res[k])) return 4 + k;
    return -1;
}

static int voxelize_run(cli_session *s, const voxelize_args *a)
{
    voxgi_voxelize_desc vd;
    cli_mesh tm;
    cli_context c;
    voxgi_voxels *vox = NULL;
    voxgi_voxels_info info;
    voxgi_info ci;
    double *times;
    int i, rc = CLI_EXIT_FAILURE;
    memset(&vd, 0, sizeof vd);
    vd.method = methods[a->method].method;
    vd.atomic = methods[a->method].atomic;
    vd.volume_slicing = methods[a->method].volume_slicing;
    vd.atlas_size = a->atlas_size;
    vd.atlas_uv = (voxgi_atlas_uv)a->atlas_uv;
    vd.attributes = a->attributes;
    if (a->have_npy_attribute) vd.attributes |= (unsigned)a->npy_attribute;
    /* coloured outputs take the albedo where the method blends attributes */
    if ((a->out_format == OUT_VOX || a->out_format == OUT_PLY || a->out_format == OUT_OBJ) &&
        (vd.method == VOXGI_METHOD_CONSERVATIVE || vd.method == VOXGI_METHOD_THIN || vd.method == VOXGI_METHOD_GEOMETRY ||
         vd.method == VOXGI_METHOD_VOLUME_BUFFER))
        vd.attributes |= VOXGI_ATTRIBUTE_ALBEDO;
    vd.solid_mode = (voxgi_solid_mode)a->solid_mode;
    vd.axis = (voxgi_axis)a->axis;
    for (i = 0; i < 4; i++) vd.blend[i] = (voxgi_blend)a->blend[i];
    if (a->have_grid) vd.grid = a->grid;
    if (cli_open_mesh_and_context(s, a->mesh, &a->common, &tm, &c)) return CLI_EXIT_FAILURE;
    if (!a->have_grid && cli_fit_grid(c.vx, &tm.scene, a->res, a->per_axis, a->pad, &vd.grid) != VOXGI_OK) {
        cli_fail_lib(s, c.vx, a->mesh);
        goto done;
    }
    if (!(times = (double *)malloc((size_t)a->runs * sizeof *times))) {
        cli_fail(s, "out of memory");
        goto done;
    }
    for (i = 0; i < a->runs; i++) {
        if (vox) voxgi_voxels_destroy(c.vx, vox);
        vox = NULL;
        if (voxgi_voxelize(c.vx, &tm.scene, &vd, &vox) != VOXGI_OK) {
            cli_fail_lib(s, c.vx, a->mesh);
            free(times);
            goto done;
        }
        voxgi_voxels_query(vox, &info);
        times[i] = info.ms;
    }
    info.ms = cli_median(times, a->runs);
    free(times);
    voxgi_query_info(c.vx, &ci);
    if (a->out && a->out_format != OUT_BINVOX) {
        char err[1024];
        int r = a->out_format == OUT_VOX   ? voxgi_io_write_vox(c.vx, vox, a->out, err, sizeof err)
                : a->out_format == OUT_NPY && a->have_npy_attribute
                    ? voxgi_io_write_npy_attribute(c.vx, vox, (voxgi_attribute)a->npy_attribute, a->out, err, sizeof err)
                : a->out_format == OUT_NPY ? voxgi_io_write_npy(c.vx, vox, a->out, err, sizeof err)
                : a->out_format == OUT_PLY ? voxgi_io_write_ply_points(c.vx, vox, a->out, err, sizeof err)
                                           : voxgi_io_write_obj_faces(c.vx, vox, a->out, err, sizeof err);
        if (r != 0) {
            cli_fail(s, "%s", err);
            goto done;
        }
    } else if (a->out) {
        size_t need = 0;
        uint32_t *bits;
        FILE *f;
        voxgi_voxels_read(c.vx, vox, NULL, 0, &need);
        bits = (uint32_t *)malloc(need);
        errno = 0; /* a short write may leave none */
        f = fopen(a->out, "wb");
        if (!bits || !f || voxgi_voxels_read(c.vx, vox, bits, need, NULL) != VOXGI_OK || voxgi_binvox_write(f, &vd.grid, bits) != VOXGI_OK) {
            int err = errno;
            if (f) fclose(f);
            free(bits);
            cli_fail(s, "cannot write %s: %s", a->out, cli_io_why(err));
            goto done;
        }
        free(bits);
        if (fclose(f) != 0) {
            cli_fail(s, "cannot write %s: %s", a->out, cli_io_why(errno));
            goto done;
        }
    }
    cli_status_clear(s);
    if (a->common.json)
        printf("{\"mesh\":%s,\"triangles\":%lu,\"voxels\":%llu,\"ms\":%.3f,\"runs\":%d,\"backend\":%s,\"renderer\":%s,"
               "\"threads\":%d,\"method\":%s,\"origin\":[%.17g,%.17g,%.17g],\"voxel_size\":%.17g,"
               "\"res\":[%d,%d,%d],\"exact_tests\":%llu,\"exact_triangles\":%llu,\"atlas_size\":%d,\"atlas_points\":%llu,\"attribute_pairs\":%llu%s%s}\n",
               cli_json(a->mesh), (unsigned long)cli_mesh_triangles(&tm), (unsigned long long)info.voxel_count, info.ms, a->runs,
               cli_json(voxgi_backend_name(ci.backend)), cli_json(ci.backend == VOXGI_BACKEND_GL ? ci.gl_renderer : ""), ci.thread_count,
               cli_json(voxgi_method_name(vd.method)), vd.grid.origin[0], vd.grid.origin[1], vd.grid.origin[2], vd.grid.voxel_size, vd.grid.res[0], vd.grid.res[1],
               vd.grid.res[2], (unsigned long long)info.exact_tests, (unsigned long long)info.exact_triangles, info.atlas_size,
               (unsigned long long)info.atlas_points, (unsigned long long)info.attribute_pairs, a->out ? ",\"output\":" : "", a->out ? cli_json(a->out) : "");
    else {
        printf("%s: %lu triangles -> %llu voxels of %dx%dx%d in %.2f ms (%s%s%s)\n", a->mesh, (unsigned long)cli_mesh_triangles(&tm),
               (unsigned long long)info.voxel_count, vd.grid.res[0], vd.grid.res[1], vd.grid.res[2], info.ms, voxgi_backend_name(ci.backend),
               ci.backend == VOXGI_BACKEND_GL ? ", " : "", ci.backend == VOXGI_BACKEND_GL ? ci.gl_renderer : "");
        printf("grid: origin %.17g %.17g %.17g, voxel size %.17g\n", vd.grid.origin[0], vd.grid.origin[1], vd.grid.origin[2], vd.grid.voxel_size);
        if (info.attributes)
            printf("attributes: %llu (triangle, voxel) pairs averaged, %.2f triangles per voxel\n", (unsigned long long)info.attribute_pairs,
                   info.voxel_count ? (double)info.attribute_pairs / (double)info.voxel_count : 0.0);
        if (info.atlas_size)
            printf("atlas: %dx%d texels, %llu points, %.3g texels per voxel edge\n", info.atlas_size, info.atlas_size,
                   (unsigned long long)info.atlas_points, info.atlas_scale);
        if (a->out) printf("wrote %s\n", a->out);
    }
    rc = CLI_EXIT_OK;
done:
    if (vox) voxgi_voxels_destroy(c.vx, vox);
    cli_close_mesh_and_context(s, &tm, &c);
    return rc;
}

int cmd_voxelize(int argc, char **argv)
{
    voxelize_args a;
    cli_session s;
    const char *method_names[CLI_COUNT(methods) + 1];
    int i, rc;
    memset(&a, 0, sizeof a);
    a.res = 128;
    a.pad = 1;
    a.runs = 1;
    for (i = 0; i < CLI_COUNT(methods); i++) method_names[i] = methods[i].name;
    method_names[i] = NULL;
    {
        const cli_option options[] = {
            {.name = "--res", .arg = "N", .kind = CLI_INT, .dst = &a.res, .lo = 1, .hi = VOXGI_MAX_RES,
             .help = "cubic grid of N^3 voxels fitted around the mesh (default 128)"},
            {.name = "--per-axis", .kind = CLI_FLAG, .dst = &a.per_axis, .help = "with --res: each axis only as long as the mesh needs"},
            {.name = "--pad", .arg = "P", .kind = CLI_DOUBLE, .dst = &a.pad, .lo = 0, .hi = HUGE_VAL,
             .help = "with --res: P empty voxels around the mesh (default 1)"},
            {.name = "--grid", .arg = "OX OY OZ S NX NY NZ", .kind = CLI_CUSTOM, .count = 7, .dst = &a.grid, .parse = parse_grid,
             .given = &a.have_grid, .help = "exactly this grid: origin, voxel size, resolution"},
            {.name = "--method", .arg = "NAME", .kind = CLI_ENUM, .dst = &a.method, .names = method_names,
             .help = "conservative (default), thin (6-separating), solid, slicemap (raster,\n"
                     "logic-op OR on GL), slicemap-atomic (raster, imageAtomicOr on GL),\n"
                     "atlas (texture atlas points drawn as GL points), atlas-compute\n"
                     "(the same points, one compute invocation each), geometry (the\n"
                     "conservative set by geometry-shader rasterization on GL),\n"
                     "volume-buffer (Volume Buffer M2: each triangle along its dominant\n"
                     "axis, fragments clipped to slices), volume-buffer-m1 (triangles sliced)"},
            {.name = "--blend", .arg = "A,N,E,O", .kind = CLI_ENUMS, .dst = a.blend, .names = blend_names, .min_items = 4,
             .max_items = 4, .items = &a.nblend,
             .help = "per attribute (albedo, normal, emission, opacity): average (default),\nmax or add"},
            {.name = "--atlas-size", .arg = "N", .kind = CLI_INT, .dst = &a.atlas_size, .lo = 1, .hi = 16384,
             .help = "atlas methods: texels per side (default: from the grid, 2 texels\nper voxel edge, at most 8192)"},
            {.name = "--atlas-uv", .arg = "auto|mesh", .kind = CLI_ENUM, .dst = &a.atlas_uv, .names = atlas_uv_names,
             .help = "atlas methods: voxgi's own charts (default) or the mesh's uvs"},
            CLI_OPT_ATTRIBUTES(&a.attributes, "conservative, thin, geometry, volume-buffer: blend albedo,normal,emission,opacity (or all)\n"
                                              "per voxel over the triangles that set it"),
            {.name = "--solid-mode", .arg = "MODE", .kind = CLI_ENUM, .dst = &a.solid_mode, .names = solid_mode_names,
             .help = "with --method solid: parity (default, closed meshes), vote, flood"},
            {.name = "--axis", .arg = "x|y|z", .kind = CLI_ENUM, .dst = &a.axis, .names = axis_names, .values = axis_values,
             .help = "solid parity: the counting axis; slicemap: the slicing axis (default z)"},
            CLI_OPT_BACKEND(&a.common, "(default auto: GL when a headless GL 4.5 context works)"),
            CLI_OPT_GL(&a.common, "headless GL context to create (default auto)"),
            CLI_OPT_THREADS(&a.common),
            {.name = "--runs", .arg = "R", .kind = CLI_INT, .dst = &a.runs, .lo = 1, .hi = 1000,
             .help = "repeat R times and report the median time (default 1)"},
            {.name = "-o", .arg = "FILE", .kind = CLI_STRING, .dst = &a.out,
             .help = "write the voxels, by extension: .binvox, .vox (MagicaVoxel), .npy\n"
                     "(uint8 occupancy [x,y,z]), .ply (coloured voxel centres), .obj\n"
                     "(outer faces); colours from the albedo (conservative, thin,\n"
                     "geometry, volume-buffer), else grey"},
            {.name = "--npy-attribute", .arg = "NAME", .kind = CLI_ENUM, .dst = &a.npy_attribute, .names = npy_attribute_names,
             .values = npy_attribute_values, .given = &a.have_npy_attribute,
             .help = "with -o FILE.npy: this attribute (albedo, normal, emission or\n"
                     "opacity; voxelized with it) instead of the occupancy, float32\n"
                     "[x,y,z,3] ([x,y,z] for opacity), linear, 0 where empty"},
            CLI_OPT_JSON(&a.common, "print one JSON object instead of text")};
        const cli_command cmd = {.name = "voxelize", .help = voxelize_help, .column = 27, .options = options, .option_count = CLI_COUNT(options),
                                 .operand = "mesh", .operands = &a.mesh, .min_operands = 1, .max_operands = 1};
        if ((rc = cli_parse(&cmd, argc, argv)) != CLI_CONTINUE) return rc;
    }
    if (a.out) {
        for (i = 0; i < CLI_COUNT(out_extensions) && !cli_has_extension(a.out, out_extensions[i]); i++) {}
        if (i == CLI_COUNT(out_extensions))
            return cli_usage("voxelize", "-o %s: voxelize writes .binvox, .vox, .npy, .ply or .obj files", a.out);
        a.out_format = (out_format)i;
    }
    if (a.have_npy_attribute && (!a.out || a.out_format != OUT_NPY))
        return cli_usage("voxelize", "--npy-attribute writes an attribute into a .npy file: it needs -o FILE.npy");
    cli_session_init(&s, "voxelize");
    return voxelize_run(&s, &a);
}
