/* tools/cmd_bench_rays.c - voxgi bench rays: millions of rays per second of the ray core
 * (voxgi_ray_intersect, voxgi_ray_occluded) on a mesh, for a coherent and an incoherent set. */
#include "cli.h"
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
    "Hits are counted too, so that two builds of the core can be checked against each other.\n";

typedef struct rays_args {
    cli_common common; /* --threads, --json */
    const char *mesh;
    int rays, runs;
} rays_args;

/* A uniform random point on the sphere (c, r): xorshift64* and the z-phi method. */
static void sphere_point(uint64_t *state, const double c[3], double r, float p[3])
{
    double z, phi, s;
    uint64_t x = *state;
    x ^= x >> 12; x ^= x << 25; x ^= x >> 27;
    *state = x;
    z = 2.0 * (double)((x * 0x2545F4914F6CDD1Dull) >> 11) / 9007199254740992.0 - 1.0;
    x ^= x >> 12; x ^= x << 25; x ^= x >> 27;
    *state = x;
    phi = 2 * 3.14159265358979323846 * (double)((x * 0x2545F4914F6CDD1Dull) >> 11) / 9007199254740992.0;
    s = sqrt(1 - z * z);
    p[0] = (float)(c[0] + r * s * cos(phi));
    p[1] = (float)(c[1] + r * s * sin(phi));
    p[2] = (float)(c[2] + r * z);
}

/* The coherent set: the camera's rays, tile by tile (4 x 4 pixels), rows from the top. */
static void camera_rays(const double c[3], double r, voxgi_ray *rays)
{
    enum { W = 512 };
    double dir[3] = {1, 0.5, 2}, len = sqrt(1 + 0.25 + 4), eye[3], f[3], right[3], up[3], th = 0.4 / sqrt(1 - 0.16); /* tan(asin(0.4)) */
    int a, tx, ty, x, y;
    size_t i = 0;
    for (a = 0; a < 3; a++) { eye[a] = c[a] + 2.5 * r * dir[a] / len; f[a] = -dir[a] / len; }
    right[0] = f[1] * 0 - f[2] * 1; right[1] = f[2] * 0 - f[0] * 0; right[2] = f[0] * 1 - f[1] * 0; /* f x (0, 1, 0) */
    len = sqrt(right[0] * right[0] + right[1] * right[1] + right[2] * right[2]);
    for (a = 0; a < 3; a++) right[a] /= len;
    up[0] = right[1] * f[2] - right[2] * f[1]; up[1] = right[2] * f[0] - right[0] * f[2]; up[2] = right[0] * f[1] - right[1] * f[0];
    for (ty = 0; ty < W; ty += 4)
        for (tx = 0; tx < W; tx += 4)
            for (y = ty; y < ty + 4; y++)
                for (x = tx; x < tx + 4; x++, i++) {
                    double sx = (2 * (x + 0.5) / W - 1) * th, sy = (1 - 2 * (y + 0.5) / W) * th;
                    for (a = 0; a < 3; a++) {
                        rays[i].origin[a] = (float)eye[a];
                        rays[i].direction[a] = (float)(f[a] + sx * right[a] + sy * up[a]);
                    }
                    rays[i].tmin = 0;
                    rays[i].tmax = INFINITY;
                }
}

static int rays_run(cli_session *s, const rays_args *a)
{
    enum { W = 512 };
    cli_mesh tm;
    cli_context c;
    voxgi_ray_scene *rs = NULL;
    voxgi_ray *coherent = NULL, *incoherent = NULL;
    voxgi_ray_hit *hits = NULL;
    unsigned char *occluded = NULL;
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, centre[3], r = 0, build_ms, ms[2][31];
    size_t i, nc = (size_t)W * W, ni = (size_t)a->rays, hit_count = 0, occluded_count = 0;
    uint64_t state = 0x9E3779B97F4A7C15ull;
    int k, run, rc = CLI_EXIT_FAILURE;
    memset(&c, 0, sizeof c);
    if (cli_mesh_open(s, a->mesh, &tm)) return CLI_EXIT_FAILURE;
    if (cli_context_open(s, &c, VOXGI_BACKEND_CPU, VXT_GL_AUTO, a->common.threads, 0)) goto done;
    for (i = 0; i < tm.vm.vertex_count; i++) {
        const float *p = (const float *)(const void *)((const unsigned char *)tm.vm.positions + i * (tm.vm.position_stride ? tm.vm.position_stride : 12));
        for (k = 0; k < 3; k++) { lo[k] = fmin(lo[k], p[k]); hi[k] = fmax(hi[k], p[k]); }
    }
    for (k = 0; k < 3; k++) { centre[k] = 0.5 * (lo[k] + hi[k]); r += 0.25 * (hi[k] - lo[k]) * (hi[k] - lo[k]); }
    r = sqrt(r);
    coherent = (voxgi_ray *)malloc(nc * sizeof *coherent);
    incoherent = (voxgi_ray *)malloc(ni * sizeof *incoherent);
    hits = (voxgi_ray_hit *)malloc(nc * sizeof *hits);
    occluded = (unsigned char *)malloc(ni);
    if (!coherent || !incoherent || !hits || !occluded) { cli_fail(s, "out of memory for %lu rays", (unsigned long)ni); goto done; }
    camera_rays(centre, r, coherent);
    for (i = 0; i < ni; i++) {
        float p[3], q[3];
        sphere_point(&state, centre, r, p);
        sphere_point(&state, centre, r, q);
        for (k = 0; k < 3; k++) { incoherent[i].origin[k] = p[k]; incoherent[i].direction[k] = q[k] - p[k]; }
        incoherent[i].tmin = 0;
        incoherent[i].tmax = 1;
    }
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
    {
        double mc = cli_median(ms[0], a->runs), mi = cli_median(ms[1], a->runs);
        voxgi_info ci;
        voxgi_query_info(c.vx, &ci);
        if (a->common.json)
            printf("{\"mesh\":\"%s\",\"triangles\":%lu,\"threads\":%d,\"build_ms\":%.3f,\"coherent_rays\":%lu,\"coherent_ms\":%.3f,"
                   "\"coherent_intersect_mrays\":%.3f,\"coherent_hits\":%lu,\"incoherent_rays\":%lu,\"incoherent_ms\":%.3f,"
                   "\"incoherent_occluded_mrays\":%.3f,\"incoherent_occluded\":%lu}\n",
                   a->mesh, (unsigned long)cli_mesh_triangles(&tm), ci.thread_count, build_ms, (unsigned long)nc, mc, nc / mc / 1e3,
                   (unsigned long)hit_count, (unsigned long)ni, mi, ni / mi / 1e3, (unsigned long)occluded_count);
        else {
            printf("%s: %lu triangles, BVH built in %.1f ms; %d threads, median of %d runs\n", a->mesh, (unsigned long)cli_mesh_triangles(&tm), build_ms,
                   ci.thread_count, a->runs);
            printf("  coherent   (closest hit, %lu camera rays in 4x4 tiles): %8.2f Mrays/s (%.1f ms, %lu hit)\n", (unsigned long)nc, nc / mc / 1e3, mc,
                   (unsigned long)hit_count);
            printf("  incoherent (any hit, %lu segments across the bounding sphere): %8.2f Mrays/s (%.1f ms, %lu occluded)\n", (unsigned long)ni,
                   ni / mi / 1e3, mi, (unsigned long)occluded_count);
        }
    }
    rc = CLI_EXIT_OK;
done:
    voxgi_ray_scene_destroy(c.vx, rs);
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
            CLI_OPT_THREADS(&a.common),
            CLI_OPT_JSON(&a.common, "one JSON object: coherent_intersect_mrays, incoherent_occluded_mrays, ...")};
        const cli_command cmd = {.name = "bench rays", .help = rays_help, .column = 26, .options = options, .option_count = CLI_COUNT(options),
                                 .operand = "mesh", .operands = &a.mesh, .min_operands = 1, .max_operands = 1, .operand_count = &given};
        if ((rc = cli_parse(&cmd, argc, argv)) != CLI_CONTINUE) return rc;
    }
    cli_session_init(&s, "bench rays");
    return rays_run(&s, &a);
}
