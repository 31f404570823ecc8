/* tools/cmd_plan.c - voxgi plan: what a scene needs for a method, what it leaves out and why,
   and the memory of what it keeps (voxgi_plan). */
#include "cli.h"
#include <string.h>

static const char *const plan_help =
    "usage: voxgi plan SCENE|MESH [options]\n"
    "Prints the library's plan for rendering a built-in scene (cornell-box, rsm-walls, leak-box,\n"
    "furnace, leak-room, foliage; seen through its camera) or a mesh file (no camera) with a\n"
    "method: what the scene holds, the grid and cones chosen, and each channel, structure and pass\n"
    "kept or left out with the reason and the memory it costs, before anything is allocated\n"
    "(bytes marked ~ are estimated from the scene's surface). The images follow the same plan.\n";

static const char *const plan_methods[] = {"vct", "tsm", "rsm", "sh", "ao", "ssgi", "linespace", "reference", NULL};
static const char *const plan_kinds[] = {"channel", "structure", "pass"};

static void print_bytes(uint64_t b, int estimated)
{
    if (b >= 1048576) printf(" (%s%.1f MB)", estimated ? "~" : "", (double)b / 1048576.0);
    else if (b >= 1024) printf(" (%s%.1f KB)", estimated ? "~" : "", (double)b / 1024.0);
    else if (b) printf(" (%s%lu bytes)", estimated ? "~" : "", (unsigned long)b);
}

int cmd_plan(int argc, char **argv)
{
    cli_common common;
    cli_session s;
    cli_context c;
    cli_mesh tm;
    voxgi_builtin_scene bs;
    voxgi_plan_request q;
    voxgi_plan_info p;
    const voxgi_scene *scene;
    const char *what = NULL;
    int method = 0, rc, nops = 0, i;
    double budget_mb = 0;
    memset(&common, 0, sizeof common);
    memset(&q, 0, sizeof q);
    memset(&tm, 0, sizeof tm);
    memset(&bs, 0, sizeof bs);
    {
        const cli_option options[] = {
            {.name = "--method", .arg = "vct|tsm|rsm|sh|ao|ssgi|linespace|reference", .kind = CLI_ENUM, .dst = &method, .names = plan_methods,
             .help = "the method to plan for (default vct)"},
            {.name = "--error", .arg = "E", .kind = CLI_DOUBLE, .dst = &q.error, .lo = 0, .hi = 1, .lo_open = 1,
             .help = "vct: the relative RMSE wanted (e.g. 0.08): grid, cones and stride from\nthe cone tracer's measured front"},
            {.name = "--res", .arg = "N", .kind = CLI_INT, .dst = &q.resolution, .lo = 1, .hi = 4096,
             .help = "voxels along the longest side (ao, ssgi: through the voxels)"},
            {.name = "--bounces", .arg = "B", .kind = CLI_INT, .dst = &q.bounces, .lo = -1, .hi = 64, .help = "vct: as render's --bounces"},
            {.name = "--anisotropic", .kind = CLI_FLAG, .dst = &q.filter, .help = "vct: six-direction mips"},
            {.name = "--dynamic", .kind = CLI_FLAG, .dst = &q.dynamic, .help = "the geometry moves every frame (default: a static scene)"},
            {.name = "--budget", .arg = "MB", .kind = CLI_DOUBLE, .dst = &budget_mb, .lo = 0, .hi = 1e9, .lo_open = 1,
             .help = "the memory budget (vct: the octree when the dense volume is over it)"},
            {.name = "--everything", .kind = CLI_FLAG, .dst = &q.everything, .help = "keep every item the method has (what the plan saves)"},
            CLI_OPT_THREADS(&common)};
        const cli_command cmd = {.name = "plan", .help = plan_help, .column = 27, .options = options, .option_count = CLI_COUNT(options),
                                 .operand = "scene or mesh", .operands = &what, .min_operands = 1, .max_operands = 1, .operand_count = &nops};
        if ((rc = cli_parse(&cmd, argc, argv)) != CLI_CONTINUE) return rc;
    }
    q.method = (voxgi_plan_method)method;
    q.memory_budget = (uint64_t)(budget_mb * 1048576.0);
    cli_session_init(&s, "plan");
    if (cli_context_open(&s, &c, VOXGI_BACKEND_CPU, VXT_GL_AUTO, common.threads, 0)) return CLI_EXIT_FAILURE;
    rc = CLI_EXIT_FAILURE;
    if (strchr(what, '.') == NULL && strncmp(what, "builtin:", 8) != 0) {
        if (voxgi_builtin_scene_create(c.vx, what, &bs) != VOXGI_OK) { cli_fail_lib(&s, c.vx, NULL); goto done; }
        scene = &bs.scene;
        q.camera = &bs.camera;
    } else {
        if (cli_mesh_open(&s, what, &tm)) goto done;
        scene = &tm.scene;
    }
    if (voxgi_plan(c.vx, scene, &q, &p) != VOXGI_OK) { cli_fail_lib(&s, c.vx, "planning"); goto done; }
    printf("%s, %s: %lu triangles (%lu emissive, %lu translucent, %lu reflective), surface %.4g\n", what, plan_methods[method], (unsigned long)p.triangles,
           (unsigned long)p.emissive_triangles, (unsigned long)p.translucent_triangles, (unsigned long)p.reflective_triangles, p.surface_area);
    printf("lights: %d point, %d spot, %d directional, %d rect; area lights %d; the camera %s\n", p.point_lights, p.spot_lights, p.directional_lights,
           p.rect_lights, p.area_lights, p.emitters_in_view < 0 ? "unknown (no view)" : p.emitters_in_view ? "sees an emitter" : "sees no emitter");
    if (p.resolution)
        printf("grid: %d voxels along the longest side (%d x %d x %d with a voxel of padding), ~%llu set (%.2f%%)\n", p.resolution, p.grid.res[0],
               p.grid.res[1], p.grid.res[2], (unsigned long long)p.voxels, 100 * p.occupancy);
    if (q.method == VOXGI_PLAN_VCT) {
        printf("cones: %d per gather, stride %d; radiance in %s", p.cones, p.cone_stride,
               p.octree ? "an octree" : q.filter || q.error > 0 ? "a dense volume, anisotropic mips" : "a dense volume, isotropic mips");
        if (q.error > 0) printf("; %.2f%% on the Cornell box against %.2f%% asked%s", 100 * p.expected_error, 100 * q.error, p.error_reachable ? "" : " (not reached: the closest)");
        printf("\n");
    }
    for (i = 0; i < p.item_count; i++) {
        const voxgi_plan_item *it = &p.items[i];
        printf("  %-22s %-9s %s - %s", it->name, plan_kinds[it->kind], it->kept ? "kept" : "left out", it->why);
        if (it->kept) print_bytes(it->bytes, it->estimated);
        printf("\n");
    }
    printf("memory of what is kept: %.1f MB\n", (double)p.bytes / 1048576.0);
    rc = CLI_EXIT_OK;
done:
    voxgi_builtin_scene_destroy(c.vx, &bs);
    if (tm.name[0]) cli_mesh_close(&tm);
    cli_context_close(&s, &c);
    return rc;
}
