/* tools/cmd_bench.c - voxgi bench voxelize: timing, voxel-count and accuracy tables of the voxelizers. */
#include "report.h"
#include <stdlib.h>
#include <string.h>

static const char *const bench_help =
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
    "generalized winding number, the inside test that also holds for open meshes.\n";

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
#define BENCH_METHOD_COUNT CLI_COUNT(bench_methods)
#define BENCH_MAX_MESHES 64 /* the three built-in rows and the meshes given */

typedef struct bench_args {
    cli_common common; /* --gl */
    const char *meshes[BENCH_MAX_MESHES];
    const char *csv_path;
    int nmesh, min_res, max_res, runs, no_gl, atlas_size, inside_samples, chosen[BENCH_METHOD_COUNT], nchosen;
} bench_args;

typedef struct bench_cell { double ms[3], wrong; uint64_t voxels[3], missed, extra; int ok[3], sampled; } bench_cell;

/* What the measurements share. */
typedef struct bench_state {
    cli_session *s;
    int atlas_size; /* --atlas-size: one atlas for every N (0: each grid's default) */
    int inside_samples; /* --inside-samples: centres per grid for Table 4 (0: the budget below) */
    int ncols, cols[16], nchosen;
    bench_cell *cells;
} bench_state;

static bench_cell *cell(const bench_state *b, int m, int n, int v)
{
    return &b->cells[((size_t)m * (size_t)b->ncols + (size_t)n) * (size_t)b->nchosen + (size_t)v];
}

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

static void bench_inside_sample(const cli_mesh *tm, voxgi_context *ctx, int n, int samples, bench_inside *bi)
{
    voxgi_grid g;
    size_t nt = cli_mesh_triangles(tm);
    uint64_t state = 0x2545F4914F6CDD1Dull, nvox;
    int i;
    bi->count = 0;
    if (cli_fit_grid(ctx, &tm->scene, n, 0, 1, &g) != VOXGI_OK) return;
    nvox = voxgi_grid_voxel_count(&g);
    /* about 2e8 solid angles per grid: 20000 centres for small meshes, fewer for big ones */
    bi->count = (int)(nt ? (2e8 / (double)nt < 20000 ? 2e8 / (double)nt : 20000) : 0);
    if (bi->count < 500) bi->count = 500;
    if (samples) bi->count = samples;
    bi->voxel = (uint64_t *)malloc((size_t)bi->count * sizeof *bi->voxel);
    bi->inside = (unsigned char *)malloc((size_t)bi->count);
    if (!bi->voxel || !bi->inside) {
        bi->count = 0;
        return;
    }
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

/* Median time of `runs` voxelizations of scene (name: for a message) on the n^3 grid fitted around
   it, atlas_size the atlas methods' (0: each grid's default); the last result's bits go to *bits
   when asked, its bytes to *bytes (may be NULL). 1, or says why and returns 0. */
static int bench_measure(cli_session *s, int atlas_size, voxgi_context *ctx, const voxgi_scene *scene, const char *name, int n, const bench_method *bm, int runs,
                         double *ms, uint64_t *voxels, uint32_t **bits, size_t *bytes)
{
    voxgi_voxelize_desc vd;
    double t[32];
    int i;
    memset(&vd, 0, sizeof vd);
    if (cli_fit_grid(ctx, scene, n, 0, 1, &vd.grid) != VOXGI_OK) return 0;
    vd.method = bm->method;
    vd.solid_mode = bm->mode;
    if (bm->method == VOXGI_METHOD_VOLUME_BUFFER) vd.volume_slicing = bm->variant;
    else vd.atomic = bm->variant;
    vd.atlas_size = atlas_size;
    for (i = 0; i < runs; i++) {
        voxgi_voxels *vox = NULL;
        voxgi_voxels_info info;
        if (voxgi_voxelize(ctx, scene, &vd, &vox) != VOXGI_OK) {
            cli_note(s, "%s %s at %d: %s", name, bm->name, n, voxgi_last_error(ctx));
            return 0;
        }
        voxgi_voxels_query(vox, &info);
        t[i] = info.ms;
        *voxels = info.voxel_count;
        if (bytes) *bytes = info.bytes;
        if (bits && i == runs - 1) {
            *bits = (uint32_t *)malloc(info.bytes);
            if (*bits && voxgi_voxels_read(ctx, vox, *bits, info.bytes, NULL) != VOXGI_OK) { free(*bits); *bits = NULL; }
        }
        voxgi_voxels_destroy(ctx, vox);
    }
    *ms = cli_median(t, runs);
    return 1;
}

static uint64_t popcount32(uint32_t x)
{
    uint64_t c = 0;
    for (; x; x &= x - 1) c++;
    return c;
}

/* The voxels of ref that bits misses and those it has beyond ref, over an n^3 grid's bits. */
static void bench_compare(const uint32_t *ref, const uint32_t *bits, int n, uint64_t *missed, uint64_t *extra)
{
    uint64_t w, words = ((uint64_t)n * (uint64_t)n * (uint64_t)n + 31) / 32;
    for (w = 0; w < words; w++) {
        *missed += popcount32(ref[w] & ~bits[w]);
        *extra += popcount32(bits[w] & ~ref[w]);
    }
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

/* Measures every method of one mesh at one N on each context, against the exact references. */
static void bench_mesh_at(bench_state *b, const bench_args *a, cli_context *ctx, const cli_mesh *tm, int m, int n, FILE *csv, int *mismatch)
{
    uint32_t *ref[2] = {NULL, NULL}; /* exact references: conservative, solid parity */
    bench_inside inside = {NULL, NULL, -1};
    double ms;
    uint64_t count;
    int v;
    for (v = 0; v < a->nchosen; v++) {
        bench_cell *c = cell(b, m, n, v);
        const bench_method *bm = &bench_methods[a->chosen[v]];
        int k, r = bm->method == VOXGI_METHOD_SOLID;
        uint32_t *bits = NULL;
        if (!ref[r]) bench_measure(b->s, b->atlas_size, ctx[1].vx, &tm->scene, tm->name, b->cols[n], &bench_methods[r ? 2 : 0], 1, &ms, &count, &ref[r], NULL);
        for (k = 0; k < 3; k++)
            if (ctx[k].vx)
                c->ok[k] = bench_measure(b->s, b->atlas_size, ctx[k].vx, &tm->scene, tm->name, b->cols[n], bm, a->runs, &c->ms[k], &c->voxels[k],
                                         k == 1 ? &bits : NULL, NULL);
        if (bits && ref[r]) bench_compare(ref[r], bits, b->cols[n], &c->missed, &c->extra);
        if (bits && r) { /* solid: against the winding-number inside test at sampled centres */
            int i, wrong = 0;
            if (inside.count < 0) bench_inside_sample(tm, ctx[1].vx, b->cols[n], b->inside_samples, &inside);
            for (i = 0; i < inside.count; i++) wrong += ((bits[inside.voxel[i] >> 5] >> (inside.voxel[i] & 31)) & 1u) != inside.inside[i];
            c->sampled = inside.count;
            c->wrong = inside.count ? 100.0 * wrong / inside.count : 0;
        }
        free(bits);
        for (k = 1; k < 3; k++)
            if (bm->exact_twin && c->ok[0] && c->ok[k] && c->voxels[k] != c->voxels[0]) (*mismatch)++;
        if (csv)
            for (k = 0; k < 3; k++)
                if (c->ok[k])
                    fprintf(csv, "%s,%lu,%d,%s,%s,%.4f,%llu,%s,%llu,%llu,%.3f\n", a->meshes[m], (unsigned long)cli_mesh_triangles(tm), b->cols[n], bm->name,
                            k == 0 ? "cpu1" : (k == 1 ? "cpu" : "gl"), c->ms[k], (unsigned long long)c->voxels[k], r ? "solid" : "conservative",
                            (unsigned long long)c->missed, (unsigned long long)c->extra, r ? c->wrong : 0.0);
        if (b->s->interactive) cli_status(b->s, "%s %s %d^3 done", a->meshes[m], bm->name, b->cols[n]);
    }
    free(ref[0]);
    free(ref[1]);
    free(inside.voxel);
    free(inside.inside);
}

/* Table 1 (time per backend) and the count tables: 2 voxels, 3 missed / extra, 4 inside test. */
static void print_tables(const bench_state *b, const bench_args *a, const cli_context *ctx)
{
    static const char *const labels[3] = {"CPU 1T", "CPU nT", "GL"};
    int m, n, v, k, table, last_table = 3;
    printf("\nTable 1: time in ms (median)\n");
    print_header("method | backend", b->ncols, b->cols);
    for (m = 0; m < a->nmesh; m++)
        for (v = 0; v < a->nchosen; v++)
            for (k = 0; k < 3; k++) {
                if (!ctx[k].vx) continue;
                printf("| %s | %s | %s |", a->meshes[m], bench_methods[a->chosen[v]].name, labels[k]);
                for (n = 0; n < b->ncols; n++) {
                    const bench_cell *c = cell(b, m, n, v);
                    if (c->ok[k]) printf(" %.2f |", c->ms[k]);
                    else printf(" - |");
                }
                printf("\n");
            }
    for (v = 0; v < a->nchosen; v++)
        if (bench_methods[a->chosen[v]].method == VOXGI_METHOD_SOLID) last_table = 4; /* only with a solid method */
    for (table = 2; table <= last_table; table++) {
        if (table == 2) {
            printf("\nTable 2: set voxels (identical for every backend)\n");
            print_header("method", b->ncols, b->cols);
            printf("| total | |");
            for (n = 0; n < b->ncols; n++)
                printf(" %llu |", (unsigned long long)b->cols[n] * (unsigned long long)b->cols[n] * (unsigned long long)b->cols[n]);
            printf("\n");
        } else if (table == 3) {
            printf("\nTable 3: missed / extra voxels against the exact reference (conservative; solid parity for solid methods)\n");
            print_header("method", b->ncols, b->cols);
        } else {
            printf("\nTable 4: solid methods against the exact inside test (generalized winding number >= 1/2 at\n"
                   "voxel centres): %% of sampled centres decided wrongly (samples per cell in brackets)\n");
            print_header("method", b->ncols, b->cols);
        }
        for (m = 0; m < a->nmesh; m++)
            for (v = 0; v < a->nchosen; v++) {
                if (table == 4 && bench_methods[a->chosen[v]].method != VOXGI_METHOD_SOLID) continue;
                printf("| %s | %s |", a->meshes[m], bench_methods[a->chosen[v]].name);
                for (n = 0; n < b->ncols; n++) {
                    const bench_cell *c = cell(b, m, n, v);
                    if (!c->ok[table == 2 ? 0 : 1]) printf(" - |");
                    else if (table == 2) printf(" %llu |", (unsigned long long)c->voxels[0]);
                    else if (table == 3) printf(" %llu / %llu |", (unsigned long long)c->missed, (unsigned long long)c->extra);
                    else printf(" %.2f%% (%d) |", c->wrong, c->sampled);
                }
                printf("\n");
            }
    }
}

static int bench_run(cli_session *s, const bench_args *a)
{
    bench_state b;
    cli_context ctx[3];
    cli_mesh *meshes;
    voxgi_info ci;
    FILE *csv = NULL;
    int m, n, v, mismatch = 0, rc = CLI_EXIT_FAILURE;
    memset(&b, 0, sizeof b);
    memset(ctx, 0, sizeof ctx);
    b.s = s;
    b.atlas_size = a->atlas_size;
    b.inside_samples = a->inside_samples;
    b.nchosen = a->nchosen;
    for (n = a->min_res; n <= a->max_res && b.ncols < 16; n *= 2) b.cols[b.ncols++] = n;
    /* every mesh first: a bad one fails now, not after the others' measurements */
    if (!(meshes = (cli_mesh *)calloc((size_t)a->nmesh, sizeof *meshes))) return cli_fail(s, "out of memory");
    for (m = 0; m < a->nmesh; m++)
        if (cli_mesh_open(s, a->meshes[m], &meshes[m])) goto done;
    if (a->csv_path && !(csv = fopen(a->csv_path, "w"))) {
        cli_fail(s, "cannot write %s: %s", a->csv_path, cli_io_why(errno));
        goto done;
    }
    if (cli_context_open(s, &ctx[0], VOXGI_BACKEND_CPU, (vxt_gl_kind)a->common.gl, 1, 0) || cli_context_open(s, &ctx[1], VOXGI_BACKEND_CPU, (vxt_gl_kind)a->common.gl, 0, 0))
        goto done;
    if (!a->no_gl) {
        if (cli_context_try(s, &ctx[2], VOXGI_BACKEND_GL, (vxt_gl_kind)a->common.gl, 0, 0)) cli_note(s, "no GL column: %s", s->error);
        else { /* compile the shaders before anything is timed */
            cli_mesh warm;
            double ms;
            uint64_t count;
            if (cli_mesh_open(s, "builtin:cube", &warm) == 0) {
                for (v = 0; v < a->nchosen; v++) bench_measure(s, b.atlas_size, ctx[2].vx, &warm.scene, warm.name, 8, &bench_methods[a->chosen[v]], 1, &ms, &count, NULL, NULL);
                cli_mesh_close(&warm);
            }
        }
    }
    voxgi_query_info(ctx[1].vx, &ci);
    printf("Voxelization, N^3 grids fitted to each mesh; median of %d runs; CPU nT = %d threads.\n", a->runs, ci.thread_count);
    if (ctx[2].vx) {
        voxgi_query_info(ctx[2].vx, &ci);
        printf("GL: %s, %s%s\n", ci.gl_version, ci.gl_renderer, ci.gl_software ? " - a software rasteriser on the CPU: not GPU timings" : "");
    }
    if (csv) fprintf(csv, "mesh,triangles,n,method,backend,ms,voxels,reference,missed,extra,inside_wrong_percent\n");
    if (!(b.cells = (bench_cell *)calloc((size_t)a->nmesh * (size_t)b.ncols * (size_t)a->nchosen, sizeof *b.cells))) {
        cli_fail(s, "out of memory");
        goto done;
    }
    for (m = 0; m < a->nmesh; m++) {
        for (n = 0; n < b.ncols; n++) bench_mesh_at(&b, a, ctx, &meshes[m], m, n, csv, &mismatch);
        cli_status_clear(s);
        printf("%s: %lu triangles\n", a->meshes[m], (unsigned long)cli_mesh_triangles(&meshes[m]));
    }
    print_tables(&b, a, ctx);
    if (mismatch) printf("\nWARNING: %d cells where a backend's voxel count differs from the CPU's\n", mismatch);
    rc = mismatch ? CLI_EXIT_FAILURE : CLI_EXIT_OK;
done:
    if (csv && fclose(csv) != 0 && rc == CLI_EXIT_OK) rc = cli_fail(s, "cannot write %s: %s", a->csv_path, cli_io_why(errno));
    free(b.cells);
    for (m = 0; m < 3; m++) cli_context_close(s, &ctx[m]);
    for (m = 0; m < a->nmesh; m++) cli_mesh_close(&meshes[m]);
    free(meshes);
    return rc;
}

/* report all's voxel sets: every surface method (on GL also the variants GL alone has) against
   the exact conservative set, made on the CPU, on one grid (each grid its own exact set: one
   front); the median of 3 runs (quick: 1). */
int report_voxels_all(report_run *run)
{
    static const int res[] = {128}, quick_res[] = {32};
    voxgi_info ci;
    int i, m, rc = 0;
    voxgi_query_info(run->ctx, &ci);
    for (i = 0; i < (run->quick ? CLI_COUNT(quick_res) : CLI_COUNT(res)) && rc == 0; i++) {
        const int n = run->quick ? quick_res[i] : res[i];
        uint32_t *ref = NULL;
        uint64_t exact = 0;
        double ms;
        cli_status(run->s, "%s: the exact voxels, %d^3", run->scene_name, n);
        if (!bench_measure(run->s, 0, run->cpu, run->scene, run->scene_name, n, &bench_methods[0], 1, &ms, &exact, &ref, NULL) || !ref) {
            free(ref);
            return cli_fail(run->s, "%s: the exact voxels at %d^3 could not be made", run->scene_name, n);
        }
        for (m = 0; m < BENCH_METHOD_COUNT && rc == 0; m++) {
            const bench_method *bm = &bench_methods[m];
            report_item it;
            uint32_t *bits = NULL;
            uint64_t voxels = 0, missed = 0, extra = 0;
            size_t bytes = 0;
            if (bm->method == VOXGI_METHOD_SOLID || (bm->variant == 1 && ci.backend != VOXGI_BACKEND_GL)) continue; /* solids; GL's variants */
            cli_status(run->s, "%s: %s, %d^3", run->scene_name, bm->name, n);
            if (!bench_measure(run->s, 0, run->ctx, run->scene, run->scene_name, n, bm, run->quick ? 1 : 3, &ms, &voxels, &bits, &bytes) || !bits) {
                free(bits);
                rc = cli_fail(run->s, "%s: %s at %d^3 failed", run->scene_name, bm->name, n);
                break;
            }
            bench_compare(ref, bits, n, &missed, &extra);
            free(bits);
            memset(&it, 0, sizeof it);
            it.method = bm->name;
            snprintf(it.settings, sizeof it.settings, "%d^3", n);
            snprintf(it.passes, sizeof it.passes, "voxelize %.2f", ms);
            snprintf(it.detail, sizeof it.detail, "missed %llu, extra %llu of %llu", (unsigned long long)missed, (unsigned long long)extra,
                     (unsigned long long)exact);
            it.ms = ms;
            it.bytes = (double)bytes;
            it.error = exact ? (double)(missed + extra) / (double)exact : 0;
            run->emit(run, &it, NULL);
        }
        free(ref);
    }
    return rc;
}

int cmd_bench(int argc, char **argv)
{
    bench_args a;
    cli_session s;
    const char *method_names[BENCH_METHOD_COUNT + 1];
    int i, rc, ngiven = 0;
    memset(&a, 0, sizeof a);
    a.min_res = 32;
    a.max_res = 512;
    a.runs = 3;
    a.nchosen = 1; /* conservative */
    for (i = 0; i < BENCH_METHOD_COUNT; i++) method_names[i] = bench_methods[i].name;
    method_names[i] = NULL;
    a.meshes[a.nmesh++] = "builtin:quad";
    a.meshes[a.nmesh++] = "builtin:subdivided-quad";
    a.meshes[a.nmesh++] = "builtin:cube";
    {
        const cli_option options[] = {
            {.name = "--methods", .arg = "LIST", .kind = CLI_ENUMS, .dst = a.chosen, .names = method_names, .min_items = 1,
             .max_items = BENCH_METHOD_COUNT, .items = &a.nchosen,
             .help = "comma separated: conservative, thin, solid, solid-vote, solid-flood,\n"
                     "slicemap, slicemap-atomic, atlas, atlas-compute, geometry,\n"
                     "volume-buffer, volume-buffer-m1\n"
                     "(default conservative)"},
            {.name = "--min-res", .arg = "N", .kind = CLI_INT, .dst = &a.min_res, .lo = 1, .hi = 4096, .synopsis = "--min-res N / --max-res N",
             .help = "range of N, powers of two (default 32..512)"},
            {.name = "--max-res", .arg = "N", .kind = CLI_INT, .dst = &a.max_res, .lo = 1, .hi = 4096}, /* listed with --min-res */
            {.name = "--runs", .arg = "R", .kind = CLI_INT, .dst = &a.runs, .lo = 1, .hi = 31, .help = "runs per cell, median reported (default 3)"},
            {.name = "--no-gl", .kind = CLI_FLAG, .dst = &a.no_gl, .help = "CPU only"},
            CLI_OPT_GL(&a.common, "headless GL context kind"),
            {.name = "--csv", .arg = "FILE", .kind = CLI_STRING, .dst = &a.csv_path, .help = "also write every measurement as CSV"},
            {.name = "--atlas-size", .arg = "N", .kind = CLI_INT, .dst = &a.atlas_size, .lo = 1, .hi = 16384,
             .help = "atlas methods: this atlas for every N (the documents' fixed 512^2),\ninstead of one sized from each grid"},
            {.name = "--inside-samples", .arg = "S", .kind = CLI_INT, .dst = &a.inside_samples, .lo = 1, .hi = 1000000,
             .help = "solid methods: voxel centres per grid checked against the winding number\n(default: 20000, fewer for big meshes, about 2e8 solid angles per grid)"}};
        const cli_command cmd = {.name = "bench", .help = bench_help, .column = 30, .options = options, .option_count = CLI_COUNT(options),
                                 .operand = "mesh", .operands = a.meshes + a.nmesh, .max_operands = BENCH_MAX_MESHES - 3, .operand_count = &ngiven};
        if (argc >= 1 && (strcmp(argv[0], "--help") == 0 || strcmp(argv[0], "-h") == 0)) {
            cli_help(&cmd, stdout);
            return CLI_EXIT_OK;
        }
        if (argc >= 1 && strcmp(argv[0], "rays") == 0) return cmd_bench_rays(argc - 1, argv + 1);
        if (argc < 1 || strcmp(argv[0], "voxelize") != 0) return cli_usage("bench", "the benchmark to run is 'voxelize' or 'rays'");
        if ((rc = cli_parse(&cmd, argc - 1, argv + 1)) != CLI_CONTINUE) return rc;
    }
    if (a.min_res > a.max_res) return cli_usage("bench", "empty resolution range: --min-res %d is above --max-res %d", a.min_res, a.max_res);
    a.nmesh += ngiven;
    cli_session_init(&s, "bench");
    return bench_run(&s, &a);
}
