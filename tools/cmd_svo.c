/* tools/cmd_svo.c - voxgi svo: the sparse voxel octree of a mesh, its memory and build time per pass. */
#include "cli.h"
#include <string.h>

static const char *const svo_help =
    "usage: voxgi svo MESH [options]\n"
    "Voxelizes a mesh with its material attributes and builds the sparse voxel octree: prints\n"
    "its nodes per level, bytes per occupied voxel against the dense equivalent, and the time of\n"
    "each pass (the rows of Pracuch 2016, Tables 5.1 and 5.2). --backend picks where the\n"
    "voxelization and the octree build run (GL: flag, allocate and initialise passes per level).\n"
    "-o FILE.svo saves the octree (voxgi_svo_write; the format: docs/volumes-and-octrees.md).\n";

typedef struct svo_args {
    cli_common common;
    const char *mesh, *out;
    int res, neighbours, bricks, format;
    unsigned attributes;
} svo_args;

/* bytes per occupied voxel, a mesh without any voxel counting as one */
static double per_voxel(double bytes, const voxgi_svo_info *info) { return bytes / (double)(info->leaf_voxels ? info->leaf_voxels : 1); }

static void print_tables(const svo_args *a, const cli_mesh *tm, const voxgi_grid *grid, const voxgi_svo_info *info,
                         const voxgi_voxels_info *vinfo, double dense8)
{
    int lev;
    if (a->common.json) {
        printf("{\"mesh\":%s,\"triangles\":%lu,\"res\":[%d,%d,%d],\"depth\":%d,\"leaf_voxels\":%llu,\"nodes\":%llu,\"leaf_slots\":%llu,"
               "\"format\":%s,\"bytes\":%lu,\"structure_bytes\":%lu,\"neighbour_bytes\":%lu,\"brick_bytes\":%lu,\"dense_bytes\":%lu,\"dense_rgba8_bytes\":%.0f,"
               "\"voxelize_ms\":%.3f,\"ms\":%.3f,"
               "\"sort_ms\":%.3f,\"nodes_ms\":%.3f,\"neighbours_ms\":%.3f,\"values_ms\":%.3f,\"level_nodes\":[",
               cli_json(a->mesh), (unsigned long)cli_mesh_triangles(tm), grid->res[0], grid->res[1], grid->res[2], info->depth,
               (unsigned long long)info->leaf_voxels, (unsigned long long)info->nodes, (unsigned long long)info->leaf_slots,
               cli_json(info->format == VOXGI_SVO_FLOAT16 ? "float16" : "float32"), (unsigned long)info->bytes, (unsigned long)info->structure_bytes,
               (unsigned long)info->neighbour_bytes, (unsigned long)info->brick_bytes, (unsigned long)info->dense_bytes, dense8, vinfo->ms, info->ms,
               info->ms_sort, info->ms_nodes, info->ms_neighbours, info->ms_values);
        for (lev = 0; lev <= info->depth; lev++) printf("%s%llu", lev ? "," : "", (unsigned long long)info->level_nodes[lev]);
        printf("]%s%s}\n", a->out ? ",\"output\":" : "", a->out ? cli_json(a->out) : "");
        return;
    }
    printf("%s: %lu triangles, %dx%dx%d voxels, depth %d\n", a->mesh, (unsigned long)cli_mesh_triangles(tm), grid->res[0], grid->res[1],
           grid->res[2], info->depth);
    printf("| level | nodes |\n|---:|---:|\n");
    for (lev = 0; lev <= info->depth; lev++) printf("| %d | %llu |\n", lev, (unsigned long long)info->level_nodes[lev]);
    printf("\nTable 5.1 (memory)\n| structure | bytes | per voxel |\n|---|---:|---:|\n");
    printf("| dense equivalent, %s | %lu | %.1f |\n", info->format == VOXGI_SVO_FLOAT16 ? "RGBA16F (R16F)" : "RGBA32F (R32F)",
           (unsigned long)info->dense_bytes, per_voxel((double)info->dense_bytes, info));
    printf("| dense equivalent, RGBA8 (R8) | %.0f | %.1f |\n", dense8, per_voxel(dense8, info));
    printf("| octree structure (%llu node slots) | %lu | %.2f |\n", (unsigned long long)info->nodes, (unsigned long)info->structure_bytes,
           per_voxel((double)info->structure_bytes, info));
    if (info->neighbour_bytes)
        printf("| neighbour pointers | %lu | %.2f |\n", (unsigned long)info->neighbour_bytes, per_voxel((double)info->neighbour_bytes, info));
    if (info->brick_bytes)
        printf("| bricks (4x4x4 per inner node) | %lu | %.2f |\n", (unsigned long)info->brick_bytes, per_voxel((double)info->brick_bytes, info));
    printf("| octree everything (%llu leaf slots) | %lu | %.1f |\n", (unsigned long long)info->leaf_slots, (unsigned long)info->bytes,
           per_voxel((double)info->bytes, info));
    printf("\ndense RGBA8 / octree: %.1fx less memory\n", dense8 / (double)(info->bytes ? info->bytes : 1));
    printf("\nTable 5.2 (ms; %s)\n| pass | ms |\n|---|---:|\n", voxgi_backend_name(vinfo->backend));
    printf("| voxelization with attributes | %.2f |\n| sort voxels (Morton) | %.2f |\n| nodes and child pointers | %.2f |\n"
           "| neighbour pointers | %.2f |\n| values, mips and bricks | %.2f |\n", vinfo->ms, info->ms_sort, info->ms_nodes, info->ms_neighbours,
           info->ms_values);
}

static int svo_run(cli_session *s, const svo_args *a)
{
    voxgi_voxelize_desc vd;
    voxgi_svo_desc sd;
    cli_mesh tm;
    cli_context c;
    voxgi_voxels *vox = NULL;
    voxgi_voxels_info vinfo;
    voxgi_svo *svo = NULL;
    voxgi_svo_info info;
    double dense8 = 0;
    int lev, rc = CLI_EXIT_FAILURE;
    memset(&vd, 0, sizeof vd);
    memset(&sd, 0, sizeof sd);
    vd.attributes = a->attributes;
    sd.neighbours = a->neighbours;
    sd.bricks = a->bricks;
    sd.format = (voxgi_svo_format)a->format;
    if (cli_open_mesh_and_context(s, a->mesh, &a->common, &tm, &c)) return CLI_EXIT_FAILURE;
    if (cli_fit_grid(c.vx, &tm.scene, a->res, 0, 1, &vd.grid) != VOXGI_OK || voxgi_voxelize(c.vx, &tm.scene, &vd, &vox) != VOXGI_OK ||
        voxgi_svo_create(c.vx, vox, &sd, &svo) != VOXGI_OK) {
        cli_fail_lib(s, c.vx, a->mesh);
        goto done;
    }
    voxgi_voxels_query(vox, &vinfo);
    voxgi_svo_query(svo, &info);
    for (lev = 0; lev < 4; lev++) /* the dense RGBA8 (R8) equivalent, the usual yardstick */
        if (info.attributes & (1u << lev)) dense8 += (double)voxgi_grid_voxel_count(&vd.grid) * (lev == 3 ? 1 : 4);
    if (a->out && voxgi_svo_write(c.vx, svo, a->out) != VOXGI_OK) {
        cli_fail(s, "%s", voxgi_last_error(c.vx)); /* names the file and the reason */
        goto done;
    }
    cli_status_clear(s);
    print_tables(a, &tm, &vd.grid, &info, &vinfo, dense8);
    if (a->out && !a->common.json) printf("\nwrote %s\n", a->out);
    rc = CLI_EXIT_OK;
done:
    voxgi_svo_destroy(c.vx, svo);
    if (vox) voxgi_voxels_destroy(c.vx, vox);
    cli_close_mesh_and_context(s, &tm, &c);
    return rc;
}

int cmd_svo(int argc, char **argv)
{
    svo_args a;
    cli_session s;
    int rc;
    memset(&a, 0, sizeof a);
    a.res = 128;
    a.attributes = 15;
    {
        const cli_option options[] = {
            {.name = "--res", .arg = "N", .kind = CLI_INT, .dst = &a.res, .lo = 1, .hi = VOXGI_MAX_RES,
             .help = "cubic grid of N^3 voxels fitted around the mesh (default 128)"},
            CLI_OPT_ATTRIBUTES(&a.attributes, "albedo,normal,emission,opacity or all (default all)"),
            CLI_OPT_BACKEND(&a.common, "where it runs (default auto)"),
            CLI_OPT_GL(&a.common, "headless GL context to create (default auto)"),
            CLI_OPT_THREADS(&a.common),
            {.name = "--neighbours", .kind = CLI_FLAG, .dst = &a.neighbours, .help = "also build the six neighbour pointers of every node"},
            {.name = "--bricks", .kind = CLI_FLAG, .dst = &a.bricks, .help = "also a 4x4x4 brick per inner node (seamless trilinear sampling)"},
            {.name = "--format", .arg = "float32|float16", .kind = CLI_ENUM, .dst = &a.format, .names = cli_svo_format_names,
             .help = "how values are stored (default float32)"},
            {.name = "-o", .arg = "FILE.svo", .kind = CLI_STRING, .dst = &a.out,
             .help = "save the octree there (voxgi_svo_read loads it)"},
            CLI_OPT_JSON(&a.common, "one JSON object: leaf_voxels, nodes, bytes, structure_bytes, ms, ...")};
        const cli_command cmd = {.name = "svo", .help = svo_help, .column = 27, .options = options, .option_count = CLI_COUNT(options),
                                 .operand = "mesh", .operands = &a.mesh, .min_operands = 1, .max_operands = 1};
        if ((rc = cli_parse(&cmd, argc, argv)) != CLI_CONTINUE) return rc;
    }
    if (a.out && !cli_has_extension(a.out, ".svo")) return cli_usage("svo", "-o %s: svo writes .svo files", a.out);
    cli_session_init(&s, "svo");
    return svo_run(&s, &a);
}
