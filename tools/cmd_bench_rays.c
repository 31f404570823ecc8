/* tools/cmd_bench_rays.c - voxgi bench rays: millions of rays per second of the ray core
 * (voxgi_ray_intersect, voxgi_ray_occluded) on a mesh, for a coherent and an incoherent set. */
#include "cli.h"
#include "ray_sets.h"
#include <stdlib.h>
#include <string.h>

static const char *const rays_help =
    "usage: voxgi bench rays MESH [options]\n"
    "Casts two sets of rays at a mesh with the library's ray core and prints millions of rays per\n"
    "second for each (the median of --runs runs; the BVH's build time apart):\n"
    "  coherent    closest hits of a 512 x 512 pinhole camera looking at the centre of the mesh's\n"
    "              bounding box from direction (1, 0.5, 2) at 2.5 r (r: half the box's diagonal),\n"
    "              its vertical field of view just fitting the bounding sphere, in 4 x 4 pixel tiles;\n"
    "  incoherent  occlusion (any hit) of N segments between two uniform random points on the\n"
    "              bounding sphere.\n"
    "Hits are counted too, so that two builds of the core can be checked against each other.\n"
    "With --linespace N,D the incoherent set is also cast through a line space (n N, depth D) in\n"
    "exact and fast mode: its rates, the segments exact mode and the core disagree on, and the\n"
    "share fast mode blocks wrongly.\n";

typedef struct rays_args {
    cli_common common; /* --threads, --json */
    const char *mesh;
    int rays, runs;
    double linespace[2];          /* n, depth; 0: none */
    int linespace_given;
} rays_args;

static int rays_run(cli_session *s, const rays_args *a)
{
    cli_mesh tm;
    cli_context c;
    voxgi_ray_scene *rs = NULL;
    voxgi_ray *coherent = NULL, *incoherent = NULL;
    voxgi_ray_hit *hits = NULL;
    unsigned char *occluded = NULL, *ls_occluded = NULL;
    voxgi_linespace *L = NULL;
    double centre[3], r, build_ms, ms[4][31], ls_build_ms = 0;
    size_t ls_disagree = 0, ls_wrong = 0;
    size_t i, nc = (size_t)VXT_CAMERA_SIDE * VXT_CAMERA_SIDE, ni = (size_t)a->rays, hit_count = 0, occluded_count = 0;
    int run, rc = CLI_EXIT_FAILURE;
    memset(&c, 0, sizeof c);
    if (cli_mesh_open(s, a->mesh, &tm)) return CLI_EXIT_FAILURE;
    if (cli_context_open(s, &c, VOXGI_BACKEND_CPU, VXT_GL_AUTO, a->common.threads, 0)) goto done;
    vxt_bounding_sphere(tm.vm.positions, tm.vm.vertex_count, centre, &r); /* positions are packed (cli_mesh) */
    coherent = (voxgi_ray *)malloc(nc * sizeof *coherent);
    incoherent = (voxgi_ray *)malloc(ni * sizeof *incoherent);
    hits = (voxgi_ray_hit *)malloc(nc * sizeof *hits);
    occluded = (unsigned char *)malloc(ni);
    if (!coherent || !incoherent || !hits || !occluded) { cli_fail(s, "out of memory for %lu rays", (unsigned long)ni); goto done; }
    vxt_camera_rays(centre, r, (float *)(void *)coherent); /* voxgi_ray is 8 floats */
    vxt_segment_rays(centre, r, ni, (float *)(void *)incoherent);
    build_ms = cli_now_ms();
    if (voxgi_ray_scene_create(c.vx, &tm.scene, &rs) != VOXGI_OK) { cli_fail_lib(s, c.vx, "building the BVH"); goto done; }
    build_ms = cli_now_ms() - build_ms;
    for (run = 0; run < a->runs; run++) {
        double t0 = cli_now_ms();
        if (voxgi_ray_intersect(c.vx, rs, nc, coherent, hits) != VOXGI_OK) { cli_fail_lib(s, c.vx, "coherent rays"); goto done; }
        ms[0][run] = cli_now_ms() - t0;
        t0 = cli_now_ms();
        if (voxgi_ray_occluded(c.vx, rs, ni, incoherent, occluded) != VOXGI_OK) { cli_fail_lib(s, c.vx, "incoherent rays"); goto done; }
        ms[1][run] = cli_now_ms() - t0;
    }
    for (i = 0; i < nc; i++) hit_count += hits[i].triangle != UINT32_MAX;
    for (i = 0; i < ni; i++) occluded_count += occluded[i];
    if (a->linespace_given) { /* the same segments through the line space */
        voxgi_linespace_desc ld;
        int m;
        memset(&ld, 0, sizeof ld);
        ld.n = (int)a->linespace[0];
        ld.depth = (int)a->linespace[1];
        ls_build_ms = cli_now_ms();
        if (!(ls_occluded = (unsigned char *)malloc(ni))) { cli_fail(s, "out of memory for %lu rays", (unsigned long)ni); goto done; }
        if (voxgi_linespace_create(c.vx, &tm.scene, &ld, &L) != VOXGI_OK) { cli_fail_lib(s, c.vx, "building the line space"); goto done; }
        ls_build_ms = cli_now_ms() - ls_build_ms;
        for (m = 0; m < 2; m++)
            for (run = 0; run < a->runs; run++) {
                double t0 = cli_now_ms();
                if (voxgi_linespace_occluded(c.vx, L, (voxgi_linespace_mode)m, ni, incoherent, ls_occluded) != VOXGI_OK) {
                    cli_fail_lib(s, c.vx, "line-space rays");
                    goto done;
                }
                ms[2 + m][run] = cli_now_ms() - t0;
                if (run == 0)
                    for (i = 0; i < ni; i++) {
                        if (m == 0) ls_disagree += ls_occluded[i] != occluded[i];
                        else ls_wrong += ls_occluded[i] && !occluded[i];
                    }
            }
    }
    {
        double mc = cli_median(ms[0], a->runs), mi = cli_median(ms[1], a->runs);
        voxgi_info ci;
        voxgi_query_info(c.vx, &ci);
        if (a->common.json)
            printf("{\"mesh\":%s,\"triangles\":%lu,\"threads\":%d,\"build_ms\":%.3f,\"coherent_rays\":%lu,\"coherent_ms\":%.3f,"
                   "\"coherent_intersect_mrays\":%.3f,\"coherent_hits\":%lu,\"incoherent_rays\":%lu,\"incoherent_ms\":%.3f,"
                   "\"incoherent_occluded_mrays\":%.3f,\"incoherent_occluded\":%lu}\n",
                   cli_json(a->mesh), (unsigned long)cli_mesh_triangles(&tm), ci.thread_count, build_ms, (unsigned long)nc, mc, nc / mc / 1e3,
                   (unsigned long)hit_count, (unsigned long)ni, mi, ni / mi / 1e3, (unsigned long)occluded_count);
        if (a->common.json && L) { /* the same object, with the line space's fields */
            double me = cli_median(ms[2], a->runs), mf = cli_median(ms[3], a->runs);
            printf("{\"mesh\":%s,\"linespace_n\":%d,\"linespace_depth\":%d,\"linespace_build_ms\":%.3f,\"linespace_exact_mrays\":%.3f,"
                   "\"linespace_fast_mrays\":%.3f,\"linespace_exact_disagree\":%lu,\"linespace_fast_wrong\":%lu}\n",
                   cli_json(a->mesh), (int)a->linespace[0], (int)a->linespace[1], ls_build_ms, ni / me / 1e3, ni / mf / 1e3, (unsigned long)ls_disagree,
                   (unsigned long)ls_wrong);
        }
        if (!a->common.json) {
            printf("%s: %lu triangles, BVH built in %.1f ms; %d threads, median of %d runs\n", a->mesh, (unsigned long)cli_mesh_triangles(&tm), build_ms,
                   ci.thread_count, a->runs);
            printf("  coherent   (closest hit, %lu camera rays in 4x4 tiles): %8.2f Mrays/s (%.1f ms, %lu hit)\n", (unsigned long)nc, nc / mc / 1e3, mc,
                   (unsigned long)hit_count);
            printf("  incoherent (any hit, %lu segments across the bounding sphere): %8.2f Mrays/s (%.1f ms, %lu occluded)\n", (unsigned long)ni,
                   ni / mi / 1e3, mi, (unsigned long)occluded_count);
            if (L) {
                double me = cli_median(ms[2], a->runs), mf = cli_median(ms[3], a->runs);
                printf("  line space n %d depth %d (built in %.1f ms), the incoherent set: exact %8.2f Mrays/s (%.3fx the core, %lu segments "
                       "disagree), fast %8.2f Mrays/s (%.3fx, %.2f%% blocked wrongly)\n",
                       (int)a->linespace[0], (int)a->linespace[1], ls_build_ms, ni / me / 1e3, mi / me, (unsigned long)ls_disagree, ni / mf / 1e3, mi / mf,
                       100.0 * ls_wrong / ni);
            }
        }
    }
    rc = CLI_EXIT_OK;
done:
    voxgi_ray_scene_destroy(c.vx, rs);
    voxgi_linespace_destroy(c.vx, L);
    free(ls_occluded);
    free(coherent);
    free(incoherent);
    free(hits);
    free(occluded);
    cli_context_close(s, &c);
    cli_mesh_close(&tm);
    return rc;
}

int cmd_bench_rays(int argc, char **argv)
{
    rays_args a;
    cli_session s;
    int rc, given = 0;
    memset(&a, 0, sizeof a);
    a.rays = 1000000;
    a.runs = 3;
    {
        const cli_option options[] = {
            {.name = "--rays", .arg = "N", .kind = CLI_INT, .dst = &a.rays, .lo = 1, .hi = 100000000, .help = "incoherent segments (default 1000000)"},
            {.name = "--runs", .arg = "R", .kind = CLI_INT, .dst = &a.runs, .lo = 1, .hi = 31, .help = "runs of each set, median reported (default 3)"},
            {.name = "--linespace", .arg = "N,D", .kind = CLI_NUMBERS, .dst = a.linespace, .items = &a.linespace_given, .min_items = 2, .max_items = 2,
             .lo = 1, .hi = 16, .whole = 1,
             .help = "also cast the incoherent set through a line space of n N, depth D, exact and fast"},
            CLI_OPT_THREADS(&a.common),
            CLI_OPT_JSON(&a.common, "one JSON object: coherent_intersect_mrays, incoherent_occluded_mrays, ...")};
        const cli_command cmd = {.name = "bench rays", .help = rays_help, .column = 26, .options = options, .option_count = CLI_COUNT(options),
                                 .operand = "mesh", .operands = &a.mesh, .min_operands = 1, .max_operands = 1, .operand_count = &given};
        if ((rc = cli_parse(&cmd, argc, argv)) != CLI_CONTINUE) return rc;
    }
    cli_session_init(&s, "bench rays");
    return rays_run(&s, &a);
}
