/* tools/cmd_report_stiff.c - voxgi report stiff, and the section of voxgi report all that it is:
 * every image method on the Cornell box made stiff (scaled, moved, with degenerate triangles,
 * emitters over twelve orders), the leak box, an empty scene and the furnace, each case measured
 * against the method's own image of the plain scene or the exact answer, beside what is expected
 * (tests/test_stiff.c holds each expectation; docs/stiff-cases.md explains them). */
#include "report.h"
#include "stiff.h"
#include <stdlib.h>
#include <string.h>

static const char *const stiff_help =
    "usage: voxgi report stiff [options]\n"
    "Every image method (the path tracer, vct, tsm, rsm, sh, ssgi, hybrid, ssao, vao, linespace)\n"
    "at 16 x 16 pixels and small settings on stiff and extreme input, measured against its own image\n"
    "of the plain Cornell box: scaled by 2^20 and 2^-20 (expected: equal), by 1e6 and 1e-6, moved by\n"
    "1e3 and 1e6 in float positions and by 1e6 in double positions with the scene's origin (equal);\n"
    "with a segment and points added (equal where the method sees no voxels), with a needle and a\n"
    "sliver (finite); its light 2^20 times as bright (the image times 2^20); emitters of 1e6 and\n"
    "1e-6 (finite); the leak box (lights outside a closed box: black inside); an empty scene\n"
    "(refused); and the furnace at albedo 0.5 and 0.999 (the path tracer and vct with every\n"
    "bounce). Prints a Markdown table; -o FILE writes it there. The same section is in\n"
    "'voxgi report all'.\n";

enum { STIFF_PX = 3 * VXT_STIFF_IMG * VXT_STIFF_IMG };
typedef char stiff_rows_match[VXT_STIFF_METHODS == REPORT_STIFF_METHODS ? 1 : -1];

/* A method's image of the Cornell box placed by k and offset (float positions). 0, or -1. */
static int placed_image(voxgi_context *ctx, int m, const voxgi_builtin_scene *bs, double k, double offset, float *img)
{
    vxt_stiff_placed p;
    int rc = -1;
    if (vxt_stiff_placed_make(&bs->scene, k, offset, &p) && vxt_stiff_image(ctx, m, &p.scene, vxt_stiff_placed_camera(bs->camera, k, offset), img) == VOXGI_OK)
        rc = 0;
    vxt_stiff_placed_free(&p);
    return rc;
}

/* "equal", or the relative RMS difference. */
static void put_difference(char *cell, size_t size, const float *img, const float *base)
{
    if (!memcmp(img, base, sizeof(float) * STIFF_PX)) snprintf(cell, size, "equal");
    else snprintf(cell, size, "%.2g", vxt_stiff_rel_diff(img, base, STIFF_PX));
}

/* The cell of the box scaled by each of two factors: "equal" when both images are the plain
   one's, else the larger relative RMS difference. 0, or -1. */
static int scaled_cell(voxgi_context *ctx, int m, const voxgi_builtin_scene *box, const double k[2], const float *base, char *cell)
{
    static float img[STIFF_PX];
    double worst = 0;
    int i, same = 1;
    for (i = 0; i < 2; i++) {
        if (placed_image(ctx, m, box, k[i], 0, img)) return -1;
        same &= !memcmp(img, base, sizeof img);
        worst = fmax(worst, vxt_stiff_rel_diff(img, base, STIFF_PX));
    }
    if (same) snprintf(cell, REPORT_STIFF_CELL, "equal");
    else snprintf(cell, REPORT_STIFF_CELL, "%.2g", worst);
    return 0;
}

/* Method m's row: each case's cell. 0, or CLI_EXIT_FAILURE with the library's error said. */
static int stiff_row(cli_session *s, voxgi_context *ctx, int m, const voxgi_builtin_scene *box, const voxgi_builtin_scene *leak, report_stiff *out)
{
    static float base[STIFF_PX], img[STIFF_PX];
    char(*cell)[REPORT_STIFF_CELL] = out->cells[m];
    const double scale_exact[2] = {1048576.0, 1.0 / 1048576.0}, scale_round[2] = {1e6, 1e-6};
    vxt_stiff_scene S;
    vxt_stiff_far far;
    voxgi_scene empty;
    double mean;
    size_t i, mi, off = 0;
    int k, c;
    if (vxt_stiff_image(ctx, m, &box->scene, box->camera, base) != VOXGI_OK || scaled_cell(ctx, m, box, scale_exact, base, cell[REPORT_STIFF_SCALE_EXACT]) ||
        scaled_cell(ctx, m, box, scale_round, base, cell[REPORT_STIFF_SCALE_ROUND]))
        return cli_fail_lib(s, ctx, vxt_stiff_methods[m]);
    for (k = 0; k < 2; k++) {
        if (placed_image(ctx, m, box, 1, k ? 1e6 : 1e3, img)) return cli_fail_lib(s, ctx, vxt_stiff_methods[m]);
        put_difference(cell[k ? REPORT_STIFF_MOVED_FLOAT_FAR : REPORT_STIFF_MOVED_FLOAT], REPORT_STIFF_CELL, img, base);
    }
    if (!vxt_stiff_far_make(&box->scene, 1e6, 1e6, &far)) return cli_fail(s, "out of memory");
    k = vxt_stiff_image(ctx, m, &far.scene, box->camera, img) == VOXGI_OK;
    vxt_stiff_far_free(&far);
    if (!k) return cli_fail_lib(s, ctx, vxt_stiff_methods[m]);
    put_difference(cell[REPORT_STIFF_MOVED_DOUBLE], REPORT_STIFF_CELL, img, base);
    /* degenerate triangles: a segment and points (no area); then a needle and a sliver */
    if (!vxt_stiff_add(&S, &box->scene, vxt_stiff_degenerate, 3, 0) || vxt_stiff_image(ctx, m, &S.scene, box->camera, img) != VOXGI_OK)
        return cli_fail_lib(s, ctx, vxt_stiff_methods[m]);
    put_difference(cell[REPORT_STIFF_DEGENERATE], REPORT_STIFF_CELL, img, base);
    if (!vxt_stiff_add(&S, &box->scene, vxt_stiff_degenerate, 5, 0) || vxt_stiff_image(ctx, m, &S.scene, box->camera, img) != VOXGI_OK)
        return cli_fail_lib(s, ctx, vxt_stiff_methods[m]);
    snprintf(cell[REPORT_STIFF_NEEDLES], REPORT_STIFF_CELL, "%s", vxt_stiff_finite(img, STIFF_PX, &mean) ? "finite" : "NOT FINITE");
    /* the light 2^20 times as bright */
    vxt_stiff_add(&S, &box->scene, NULL, 0, 0);
    for (mi = 0; mi < S.scene.material_count; mi++)
        for (c = 0; c < 3; c++) S.mats[mi].emission[c] *= 1048576.0f;
    if (vxt_stiff_image(ctx, m, &S.scene, box->camera, img) != VOXGI_OK) return cli_fail_lib(s, ctx, vxt_stiff_methods[m]);
    for (i = 0; i < STIFF_PX; i++) off += (vxt_stiff_is_occlusion(m) ? (double)img[i] : img[i] / 1048576.0) != base[i];
    if (off == 0) snprintf(cell[REPORT_STIFF_BRIGHT], REPORT_STIFF_CELL, vxt_stiff_is_occlusion(m) ? "unchanged" : "equal x 2^20");
    else snprintf(cell[REPORT_STIFF_BRIGHT], REPORT_STIFF_CELL, "%lu values off", (unsigned long)off);
    { /* emitters of 1e6 and 1e-6 */
        static const float dim[9] = {0.3f, 0.05f, 0.3f, 0.35f, 0.05f, 0.3f, 0.3f, 0.05f, 0.35f};
        vxt_stiff_add(&S, &box->scene, dim, 1, (uint32_t)box->scene.material_count);
        for (mi = 0; mi < S.scene.material_count; mi++)
            for (c = 0; c < 3; c++) S.mats[mi].emission[c] = S.mats[mi].emission[c] > 0 ? 1e6f : 0.0f;
        memset(&S.mats[S.scene.material_count], 0, sizeof S.mats[0]);
        for (c = 0; c < 3; c++) S.mats[S.scene.material_count].emission[c] = 1e-6f;
        S.scene.material_count++;
        if (vxt_stiff_image(ctx, m, &S.scene, box->camera, img) != VOXGI_OK) return cli_fail_lib(s, ctx, vxt_stiff_methods[m]);
        snprintf(cell[REPORT_STIFF_RANGE], REPORT_STIFF_CELL, "%s", vxt_stiff_finite(img, STIFF_PX, &mean) ? "finite" : "NOT FINITE");
    }
    if (vxt_stiff_image(ctx, m, &leak->scene, leak->camera, img) != VOXGI_OK) return cli_fail_lib(s, ctx, vxt_stiff_methods[m]);
    if (!vxt_stiff_finite(img, STIFF_PX, &mean)) snprintf(cell[REPORT_STIFF_LEAK], REPORT_STIFF_CELL, "NOT FINITE");
    else if (vxt_stiff_is_occlusion(m)) snprintf(cell[REPORT_STIFF_LEAK], REPORT_STIFF_CELL, "(occlusion %.2g)", mean);
    else if (mean == 0) snprintf(cell[REPORT_STIFF_LEAK], REPORT_STIFF_CELL, "black");
    else snprintf(cell[REPORT_STIFF_LEAK], REPORT_STIFF_CELL, "mean %.2g", mean);
    memset(&empty, 0, sizeof empty);
    if (vxt_stiff_image(ctx, m, &empty, box->camera, img) == VOXGI_OK) snprintf(cell[REPORT_STIFF_EMPTY], REPORT_STIFF_CELL, "RENDERED");
    else snprintf(cell[REPORT_STIFF_EMPTY], REPORT_STIFF_CELL, "refused%s", strstr(voxgi_last_error(ctx), "no triangles") ? ": no triangles" : "");
    return 0;
}

/* The furnace (a closed sphere of emission 1 seen from inside) at albedo 0.5 and 0.999: the path
   tracer and the cone tracer with every bounce, against 1 / (1 - albedo). 0, or CLI_EXIT_FAILURE. */
static int stiff_furnace(cli_session *s, voxgi_context *ctx, report_stiff *out)
{
    static const float albedo[2] = {0.5f, 0.999f};
    voxgi_builtin_scene fu;
    int k, rc = 0;
    if (voxgi_builtin_scene_create(ctx, "furnace", &fu) != VOXGI_OK) return cli_fail_lib(s, ctx, "furnace");
    for (k = 0; k < 2 && rc == 0; k++) {
        out->furnace_albedo[k] = albedo[k];
        if (vxt_stiff_furnace(ctx, &fu, albedo[k], 0, &out->furnace[k][0]) != VOXGI_OK || vxt_stiff_furnace(ctx, &fu, albedo[k], 1, &out->furnace[k][1]) != VOXGI_OK)
            rc = cli_fail_lib(s, ctx, "the furnace");
    }
    voxgi_builtin_scene_destroy(ctx, &fu);
    return rc;
}

int report_stiff_measure(cli_session *s, voxgi_context *ctx, report_stiff *out)
{
    voxgi_builtin_scene box, leak;
    int m, rc = 0;
    memset(out, 0, sizeof *out);
    if (voxgi_builtin_scene_create(ctx, "cornell-box", &box) != VOXGI_OK) return cli_fail_lib(s, ctx, "cornell-box");
    if (voxgi_builtin_scene_create(ctx, "leak-box", &leak) != VOXGI_OK) {
        voxgi_builtin_scene_destroy(ctx, &box);
        return cli_fail_lib(s, ctx, "leak-box");
    }
    for (m = 0; m < VXT_STIFF_METHODS && rc == 0; m++) {
        cli_status(s, "stiff cases: %s", vxt_stiff_methods[m]);
        rc = stiff_row(s, ctx, m, &box, &leak, out);
    }
    if (rc == 0) {
        cli_status(s, "stiff cases: the furnace");
        rc = stiff_furnace(s, ctx, out);
    }
    voxgi_builtin_scene_destroy(ctx, &leak);
    voxgi_builtin_scene_destroy(ctx, &box);
    out->measured = rc == 0;
    return rc;
}

void report_stiff_markdown(FILE *f, const report_stiff *r, const voxgi_info *ci)
{
    static const char *const heads[REPORT_STIFF_CASES] = {
        "scaled by 2^20, 2^-20", "scaled by 1e6, 1e-6", "moved by 1e3 (float)", "moved by 1e6 (float)", "moved by 1e6 (double, origin)",
        "a segment and points", "a needle and a sliver", "light x 2^20", "emitters 1e6 and 1e-6", "lights outside a closed box", "no triangles"};
    static const char *const expected[REPORT_STIFF_CASES] = {
        "equal", "rounding: < 1e-3", "rounding: < 2e-3; voxels < 3e-2, linespace < 2e-2", "float's limit: the light's gap closes", "equal",
        "equal, or the voxels it touches", "finite", "equal x 2^20", "finite", "black (tsm: its seams; sh: its coarse cells)", "refused"};
    int m, k;
    fprintf(f, "Every image method at %d x %d pixels and small settings (`voxgi report stiff`; on %s%s%s%s), each case against the method's own image of "
               "the plain Cornell box (cells: `equal` bit for bit, else the relative RMS difference) or the exact answer. The expectations are "
               "tests (tests/test_stiff.c); docs/stiff-cases.md says why each holds.\n\n| method |",
            VXT_STIFF_IMG, VXT_STIFF_IMG, voxgi_backend_name(ci->backend), ci->backend == VOXGI_BACKEND_GL ? " (" : "",
            ci->backend == VOXGI_BACKEND_GL ? ci->gl_renderer : "", ci->backend == VOXGI_BACKEND_GL ? ")" : "");
    for (k = 0; k < REPORT_STIFF_CASES; k++) fprintf(f, " %s |", heads[k]);
    fprintf(f, "\n|---|");
    for (k = 0; k < REPORT_STIFF_CASES; k++) fprintf(f, "---|");
    fprintf(f, "\n| *expected* |");
    for (k = 0; k < REPORT_STIFF_CASES; k++) fprintf(f, " *%s* |", expected[k]);
    for (m = 0; m < VXT_STIFF_METHODS; m++) {
        fprintf(f, "\n| %s |", vxt_stiff_methods[m]);
        for (k = 0; k < REPORT_STIFF_CASES; k++) fprintf(f, " %s |", r->cells[m][k]);
    }
    fprintf(f, "\n\nThe furnace (a closed sphere of emission 1 seen from inside; every bounce; expected 1 / (1 - albedo)):\n\n| albedo | exact | path "
               "tracer (4 spp) | cone tracing (32^3) |\n|---:|---:|---:|---:|\n");
    for (k = 0; k < 2; k++)
        fprintf(f, "| %g | %.4g | %.4g | %.4g |\n", r->furnace_albedo[k], 1 / (1 - r->furnace_albedo[k]), r->furnace[k][0], r->furnace[k][1]);
}

int cmd_report_stiff(int argc, char **argv)
{
    cli_common common;
    cli_session s;
    cli_context c;
    report_stiff *r;
    voxgi_info ci;
    const char *out = NULL;
    FILE *f = stdout;
    int rc;
    memset(&common, 0, sizeof common);
    {
        const cli_option options[] = {
            {.name = "-o", .arg = "FILE", .kind = CLI_STRING, .dst = &out, .help = "write the table there (default: standard output)"},
            CLI_OPT_BACKEND(&common, "where the methods run (default auto: GL when a context can be made)"),
            CLI_OPT_GL(&common, "the headless GL context"), CLI_OPT_THREADS(&common)};
        const cli_command cmd = {.name = "report stiff", .help = stiff_help, .column = 27, .options = options, .option_count = CLI_COUNT(options)};
        if ((rc = cli_parse(&cmd, argc, argv)) != CLI_CONTINUE) return rc;
    }
    cli_session_init(&s, "report stiff");
    if (!(r = (report_stiff *)calloc(1, sizeof *r))) return cli_fail(&s, "out of memory");
    if (cli_context_open_options(&s, &c, &common)) {
        free(r);
        return CLI_EXIT_FAILURE;
    }
    voxgi_query_info(c.vx, &ci);
    rc = CLI_EXIT_FAILURE;
    if (report_stiff_measure(&s, c.vx, r) == 0 && (!out || (f = fopen(out, "w")) != NULL)) {
        cli_status_clear(&s);
        report_stiff_markdown(f, r, &ci);
        rc = CLI_EXIT_OK;
        if (out && (ferror(f) | fclose(f))) rc = cli_fail(&s, "cannot write %s: %s", out, cli_io_why(errno));
    } else if (out && !f)
        cli_fail(&s, "cannot write %s: %s", out, cli_io_why(errno));
    cli_context_close(&s, &c);
    free(r);
    return rc;
}
