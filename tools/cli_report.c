/* tools/cli_report.c - what the reports share: the skeleton of the single reports (options, the
 * scene loop, the front, the tables) and the pictures' exposure (the figures themselves are in
 * cli_figures.c). */
#include "report.h"
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

void report_append(char *buf, size_t size, const char *fmt, ...)
{
    size_t n = strlen(buf);
    va_list ap;
    if (n + 1 >= size) return;
    va_start(ap, fmt);
    vsnprintf(buf + n, size - n, fmt, ap);
    va_end(ap);
}

void report_percent(FILE *f, double v, const char *after)
{
    if (isfinite(v)) fprintf(f, "%.2f%%%s", 100 * v, after);
    else fprintf(f, "-%s", after);
}

/* ------------------------------------------------------------------ the pictures' exposure */
static int compare_floats(const void *p, const void *q)
{
    float a = *(const float *)p, b = *(const float *)q;
    return a < b ? -1 : a > b;
}

float report_exposure(const float *ref, const cli_error_mask *m)
{
    size_t n = (size_t)m->width * (size_t)m->height, kept = 0, p;
    float *v = (float *)malloc((n ? n : 1) * sizeof *v), top;
    if (!v) return 1;
    for (p = 0; p < n; p++)
        if (!m->masked[p]) v[kept++] = fmaxf(ref[3 * p], fmaxf(ref[3 * p + 1], ref[3 * p + 2]));
    qsort(v, kept, sizeof *v, compare_floats);
    top = kept ? v[(size_t)(0.95 * (double)(kept - 1))] : 0;
    free(v);
    return top > 0 ? 0.8f / top : 1;
}

/* ------------------------------------------------------------------ rows */
void report_measured(report_run *run, report_item *it)
{
    it->error = cli_masked_error(&run->R[it->ref].mask, run->img, run->R[it->ref].image, NULL, NULL);
    run->emit(run, it, run->img);
}

report_row *report_row_add(report_row **rows, size_t *n, size_t *cap)
{
    if (*n == *cap) {
        size_t more = *cap ? 2 * *cap : 256;
        report_row *r = (report_row *)realloc(*rows, more * sizeof *r);
        if (!r) return NULL;
        *rows = r;
        *cap = more;
    }
    memset(&(*rows)[*n], 0, sizeof **rows);
    return &(*rows)[(*n)++];
}

/* ------------------------------------------------------------------ the single reports */
int report_next(const report_list *const *lists, int n, int *at)
{
    int k;
    for (k = n - 1; k >= 0 && ++at[k] == lists[k]->n; k--) at[k] = 0;
    return k >= 0;
}

const char *const report_yes[] = {"", "yes"};

int report_scene_open(cli_session *s, voxgi_context *ctx, const char *name, const cli_cornell_mesh *cm, voxgi_builtin_scene *bs, const voxgi_scene **scene,
                      voxgi_camera *camera, int w, int h)
{
    memset(bs, 0, sizeof *bs);
    if (cm) {
        *scene = &cm->scene;
        *camera = cm->bs.camera;
    } else {
        if (voxgi_builtin_scene_create(ctx, name, bs) != VOXGI_OK) return cli_fail_lib(s, ctx, name);
        *scene = &bs->scene;
        *camera = bs->camera;
    }
    camera->width = w;
    camera->height = h;
    return 0;
}

/* A configuration the sweep measured: a row of the scene being measured, against its reference. */
static void report_emit(report_run *run, const report_item *it, const float *img)
{
    report *rep = (report *)run->user;
    report_row *r = report_row_add(&rep->rows, &rep->nrows, &rep->cap);
    (void)img;
    if (!r) {
        rep->out_of_memory = 1; /* said after the sweep */
        return;
    }
    r->scene = rep->si;
    r->group = r->scene * REPORT_MAX_REFS + it->ref;
    r->it = *it;
    if (rep->def->row) rep->def->row(rep, r);
    else r->ref_ms = cli_reference_ms(&run->R[it->ref], it->error);
}

/* Scene si: made (a built-in one, or --cornell-mesh's), its camera at the report's size, its
   references, the sweep and what the report measures beyond it. */
static int report_scene_run(report *rep, int si)
{
    const report_def *d = rep->def;
    voxgi_context *ctx = rep->c.vx;
    report_scene *sc = &rep->scenes[si];
    voxgi_builtin_scene bs;
    cli_reference R[REPORT_MAX_REFS];
    report_run run;
    int k, rc;
    memset(R, 0, sizeof R);
    memset(&run, 0, sizeof run);
    rep->si = si;
    if (report_scene_open(&rep->s, ctx, sc->name, si == rep->nscenes - 1 && rep->cm.name[0] ? &rep->cm : NULL, &bs, &run.scene, &run.camera, rep->o->size[0],
                          rep->o->size[1]))
        return CLI_EXIT_FAILURE;
    run.s = &rep->s;
    run.ctx = run.cpu = ctx;
    run.scene_name = sc->name;
    run.R = R;
    run.args = rep->own;
    run.img = rep->img;
    run.emit = report_emit;
    run.user = rep;
    rep->nrefs = 1;
    rc = d->references ? d->references(rep, &run, R) : cli_reference_make(&rep->s, ctx, run.scene, &run.camera, rep->o->spp, d->bounces, 0, R);
    if (rc == 0) {
        sc->masked = R[0].mask.masked_pixels;
        for (k = 0; k < rep->nrefs; k++) {
            sc->c[k] = R[k].c;
            sc->ms_per_spp[k] = R[k].ms_per_spp;
        }
        rc = d->sweep(&run);
        if (rc == REPORT_NOT_APPLICABLE) rc = cli_fail(&rep->s, "%s: %s", d->name, run.why); /* asked for by name: a failure */
        if (rc == 0 && rep->out_of_memory) rc = cli_fail(&rep->s, "out of memory");
    }
    if (rc == 0 && d->scene_done) rc = d->scene_done(rep, &run);
    for (k = 0; k < REPORT_MAX_REFS; k++) cli_reference_free(&R[k]);
    voxgi_builtin_scene_destroy(ctx, &bs);
    return rc;
}

/* Row r's cell of column c in the Markdown or the CSV (buf: room for its number); NULL: a blank
   Markdown cell. */
static const char *report_cell(const report *rep, const report_row *r, const report_column *c, int csv, char *buf, size_t size)
{
    const char *const *names = csv ? c->csv_names : c->names, *none = csv ? c->csv_none : c->md_none;
    double v;
    switch (c->at) {
    case REPORT_AT_SCENE: return rep->scenes[r->scene].name;
    case REPORT_AT_MS: v = r->it.ms; break;
    case REPORT_AT_BYTES: v = r->it.bytes; break;
    case REPORT_AT_ERROR: v = r->it.error; break;
    case REPORT_AT_REF_MS: v = r->ref_ms; break;
    case REPORT_AT_SPEEDUP: v = r->ref_ms / r->it.ms; break;
    case REPORT_AT_FRONT: v = r->front; break;
    case REPORT_AT_NONE: v = NAN; break;
    default: v = r->it.v[c->at];
    }
    if (names) return names[(int)v];
    if (!isfinite(v) && none) return none[0] || csv ? none : NULL;
    if (!csv && c->md_unit) v = c->md_unit == '%' ? 100 * v : v / 1e6;
    snprintf(buf, size, csv ? c->csv_fmt : c->md_fmt, v);
    return buf;
}

/* The Markdown's table of scene si and its rows in the CSV. */
static void report_table(const report *rep, int si, FILE *md, FILE *csv)
{
    const report_def *d = rep->def;
    char buf[64];
    size_t i;
    int k, first;
    fputc('|', md);
    for (k = 0; k < d->ncolumns; k++)
        if (d->columns[k].md) fprintf(md, " %s |", d->columns[k].md);
    fputs("\n|", md);
    for (k = 0; k < d->ncolumns; k++)
        if (d->columns[k].md) fprintf(md, "%s|", d->columns[k].align);
    fputc('\n', md);
    for (i = 0; i < rep->nrows; i++) {
        const report_row *r = &rep->rows[i];
        if (r->scene != si) continue;
        if (r->it.note[0]) { /* not measured: a line of its own */
            fprintf(md, "%s\n", r->it.note);
            continue;
        }
        fputc('|', md);
        for (k = 0; k < d->ncolumns; k++)
            if (d->columns[k].md) {
                const char *cell = report_cell(rep, r, &d->columns[k], 0, buf, sizeof buf);
                fprintf(md, cell ? " %s |" : " |", cell ? cell : "");
            }
        fputc('\n', md);
        for (k = 0, first = 1; k < d->ncolumns; k++)
            if (d->columns[k].csv) {
                fprintf(csv, "%s%s", first ? "" : ",", report_cell(rep, r, &d->columns[k], 1, buf, sizeof buf));
                first = 0;
            }
        fputc('\n', csv);
    }
}

/* DIR/NAME.md and DIR/NAME.csv (and DIR/NAME.svg): 0, or says why and returns 1. */
static int report_write(report *rep)
{
    const report_def *d = rep->def;
    char path[3][1100];
    FILE *f[3] = {NULL, NULL, NULL};
    int i, k, rc = 0;
    for (i = 0; i < (d->svg ? 3 : 2); i++) {
        snprintf(path[i], sizeof path[i], "%s/%s.%s", rep->o->out_dir, d->name, i == 0 ? "md" : i == 1 ? "csv" : "svg");
        if (!(f[i] = fopen(path[i], "w"))) {
            rc = cli_fail(&rep->s, "cannot write %s: %s", path[i], cli_io_why(errno));
            break;
        }
    }
    if (rc == 0) {
        if (d->md_head) d->md_head(f[0], rep);
        for (k = 0, i = 0; k < d->ncolumns; k++)
            if (d->columns[k].csv) fprintf(f[1], "%s%s", i++ ? "," : "", d->columns[k].csv);
        fputc('\n', f[1]);
        for (i = 0; i < rep->nscenes; i++) {
            if (d->md_scene) d->md_scene(f[0], rep, i, 0);
            report_table(rep, i, f[0], f[1]);
            if (d->md_scene) d->md_scene(f[0], rep, i, 1);
        }
        rc = d->md_end ? d->md_end(rep, f[0], f[1]) : 0;
        if (f[2]) d->svg(f[2], rep);
    }
    for (i = 0; i < 3; i++)
        if (f[i] && (ferror(f[i]) | fclose(f[i])) && rc == 0) rc = cli_fail(&rep->s, "cannot write %s: %s", path[i], cli_io_why(errno));
    return rc;
}

/* The front of each scene on stdout, and what the report adds. */
static void report_print(const report *rep)
{
    const report_def *d = rep->def;
    size_t i;
    int si;
    for (si = 0; si < rep->nscenes && d->print_row; si++) {
        if (d->print_scene) d->print_scene(rep, si, 0);
        for (i = 0; i < rep->nrows; i++)
            if (rep->rows[i].scene == si && rep->rows[i].front) d->print_row(rep, &rep->rows[i]);
        if (d->print_scene) d->print_scene(rep, si, 1);
    }
    if (d->print_end) d->print_end(rep);
    printf("wrote %s/%s.md, %s/%s.csv", rep->o->out_dir, d->name, rep->o->out_dir, d->name);
    if (d->svg) printf(", %s/%s.svg", rep->o->out_dir, d->name);
    printf("\n");
}

/* After the options: the rest of the report. */
static int report_make(report *rep)
{
    const report_def *d = rep->def;
    const size_t pixels = (size_t)rep->o->size[0] * (size_t)rep->o->size[1];
    int si;
    if (cli_context_open_options(&rep->s, &rep->c, &rep->o->common)) return CLI_EXIT_FAILURE;
    voxgi_query_info(rep->c.vx, &rep->ci);
    if (d->open && d->open(rep)) return CLI_EXIT_FAILURE;
    if (rep->o->cornell_mesh) { /* first: a bad mesh fails before any rendering */
        if (cli_cornell_mesh_open(&rep->s, rep->c.vx, rep->o->cornell_mesh, &rep->cm)) return CLI_EXIT_FAILURE;
        snprintf(rep->scenes[rep->nscenes++].name, sizeof rep->scenes[0].name, "%s", rep->cm.name);
    }
    if (!(rep->img = (float *)malloc(pixels * 12))) return cli_fail(&rep->s, "out of memory");
    if (cli_make_dirs(rep->o->out_dir) != 0) return cli_fail(&rep->s, "cannot make %s", rep->o->out_dir);
    for (si = 0; si < rep->nscenes; si++)
        if (report_scene_run(rep, si)) return CLI_EXIT_FAILURE;
    if (d->done && d->done(rep)) return CLI_EXIT_FAILURE;
    PARETO_MARK(rep->rows, rep->nrows, report_row, it.ms, it.error, group, front); /* per scene and reference */
    if (report_write(rep)) return CLI_EXIT_FAILURE;
    cli_status_clear(&rep->s);
    report_print(rep);
    return CLI_EXIT_OK;
}

int report_main(const report_def *d, report_opts *o, void *own, const cli_option *options, int count, int argc, char **argv)
{
    char name[64];
    const char *list;
    report rep;
    int r, rc;
    snprintf(name, sizeof name, "report %s", d->name);
    {
        const cli_command cmd = {.name = name, .help = d->help, .column = 27, .options = options, .option_count = count};
        if ((rc = cli_parse(&cmd, argc, argv)) != CLI_CONTINUE) return rc;
    }
    if (!o->size[1]) o->size[1] = o->size[0];
    memset(&rep, 0, sizeof rep);
    rep.def = d;
    rep.o = o;
    rep.own = own;
    for (list = o->scene_list; (!d->scenes_optional || *o->scene_list) && (r = cli_next_item(&list, rep.scenes[rep.nscenes].name, 64)) != 0; rep.nscenes++)
        if (r < 0 || rep.nscenes == REPORT_MAX_SCENES - 1)
            return cli_usage(name, "--scenes needs 1 to %d comma-separated built-in scenes, got '%s'", REPORT_MAX_SCENES - 1, o->scene_list);
    cli_session_init(&rep.s, "report");
    rc = report_make(&rep);
    if (d->close) d->close(&rep);
    if (rep.cm.name[0]) cli_cornell_mesh_close(rep.c.vx, &rep.cm);
    if (rep.c.vx) cli_context_close(&rep.s, &rep.c);
    free(rep.img);
    free(rep.rows);
    return rc;
}

void report_md_scene(FILE *f, const report *rep, int si, int end)
{
    const report_scene *sc = &rep->scenes[si];
    if (!end)
        fprintf(f, "\n## %s\n\nReference: its error is %.2f%% / sqrt(spp), %.2f ms per sample per pixel; %lu pixels near an emitter left out.\n\n",
                sc->name, 100 * sc->c[0], sc->ms_per_spp[0], (unsigned long)sc->masked);
}
