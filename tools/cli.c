/* tools/cli.c - the option parser, messages, contexts and meshes the voxgi commands share. */
#include "cli.h"
#include <ctype.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <errno.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <unistd.h>

const char *const cli_backend_names[] = {"auto", "cpu", "gl", NULL}; /* voxgi_backend order */
const char *const cli_gl_names[] = {"auto", "egl", "osmesa", NULL};  /* vxt_gl_kind order */
const char *const cli_svo_format_names[] = {"float32", "float16", NULL}; /* voxgi_svo_format order */
const char *const cli_attribute_names[] = {"albedo", "normal", "emission", "opacity", "all", NULL};
const int cli_attribute_values[] = {VOXGI_ATTRIBUTE_ALBEDO, VOXGI_ATTRIBUTE_NORMAL, VOXGI_ATTRIBUTE_EMISSION,
                                    VOXGI_ATTRIBUTE_OPACITY, 15};

/* ------------------------------------------------------------------ values */
int cli_parse_int(const char *s, int lo, int hi, int *out)
{
    char *end;
    long v = strtol(s, &end, 10);
    if (*s == 0 || *end != 0 || v < lo || v > hi) return 0;
    *out = (int)v;
    return 1;
}

int cli_parse_double(const char *s, double *out)
{
    char *end;
    double v = strtod(s, &end);
    if (*s == 0 || *end != 0) return 0;
    *out = v;
    return 1;
}

int cli_next_item(const char **list, char *buf, size_t size)
{
    const char *s = *list, *comma;
    size_t n;
    if (!s) return 0;
    comma = strchr(s, ',');
    n = comma ? (size_t)(comma - s) : strlen(s);
    *list = comma ? comma + 1 : NULL;
    if (n == 0 || n >= size) return -1;
    memcpy(buf, s, n);
    buf[n] = 0;
    return 1;
}

int cli_has_extension(const char *path, const char *ext)
{
    size_t n = strlen(path), k = strlen(ext), i;
    if (n <= k) return 0; /* ".png" alone names no file */
    for (i = 0; i < k; i++)
        if (tolower((unsigned char)path[n - k + i]) != tolower((unsigned char)ext[i])) return 0;
    return 1;
}

static int name_index(const cli_option *o, const char *s)
{
    int i;
    for (i = 0; o->names[i]; i++)
        if (strcmp(o->names[i], s) == 0) return i;
    return -1;
}

static int name_value(const cli_option *o, int i) { return o->values ? o->values[i] : i; }

static int in_range(const cli_option *o, double v)
{
    if (o->lo == -HUGE_VAL && o->hi == HUGE_VAL) return 1; /* any number, as strtod reads it */
    return (o->lo_open ? v > o->lo : v >= o->lo) && v <= o->hi;
}

/* What a value of o must be, for "--x needs WHAT, got 'v'". */
static void describe(const cli_option *o, char *out, size_t size)
{
    size_t n = 0;
    int i;
#define PUT(...) (void)(n < size && (n += (size_t)snprintf(out + n, size - n, __VA_ARGS__)))
    switch (o->kind) {
    case CLI_INT:
        if (o->count > 1) PUT("%s in ", o->arg);
        PUT("%ld..%ld", (long)o->lo, (long)o->hi);
        break;
    case CLI_DOUBLE:
    case CLI_NUMBERS:
        if (o->kind == CLI_NUMBERS) PUT("%d to %d comma-separated %s", o->min_items, o->max_items, o->whole ? "whole numbers" : "numbers");
        else if (o->count > 1) PUT("%s, each a number", o->arg);
        else PUT("a number");
        if (o->lo == -HUGE_VAL && o->hi == HUGE_VAL) break;
        if (o->hi == HUGE_VAL) PUT(" %s %g", o->lo_open ? ">" : ">=", o->lo);
        else PUT(" in %c%g, %g]", o->lo_open ? '(' : '[', o->lo, o->hi);
        break;
    case CLI_ENUM:
    case CLI_SET:
    case CLI_ENUMS:
        if (o->kind == CLI_SET) PUT("a comma-separated list of ");
        else if (o->kind == CLI_ENUMS && o->min_items == o->max_items) PUT("%d comma-separated values of ", o->min_items);
        else if (o->kind == CLI_ENUMS) PUT("%d to %d comma-separated values of ", o->min_items, o->max_items);
        else PUT("one of ");
        for (i = 0; o->names[i]; i++) PUT("%s%s", i ? ", " : "", o->names[i]);
        break;
    default:
        PUT("a value");
    }
#undef PUT
}

/* Stores the values of o from args; -1, or the index of the bad value (*need: what it needs). */
static int store(const cli_option *o, char **args, const char **need)
{
    char item[256];
    const char *list = args[0];
    double got[CLI_MAX_ITEMS];
    int k, r, n = 0;
    unsigned set = 0;
    switch (o->kind) {
    case CLI_FLAG: *(int *)o->dst = 1; return -1;
    case CLI_STRING: *(const char **)o->dst = args[0]; return -1;
    case CLI_CUSTOM: return o->parse(o, args, need);
    case CLI_INT:
        for (k = 0; k < (o->count ? o->count : 1); k++)
            if (!cli_parse_int(args[k], (int)o->lo, (int)o->hi, (int *)o->dst + k)) return k;
        return -1;
    case CLI_DOUBLE:
        for (k = 0; k < (o->count ? o->count : 1); k++)
            if (!cli_parse_double(args[k], (double *)o->dst + k) || !in_range(o, ((double *)o->dst)[k])) return k;
        return -1;
    case CLI_ENUM:
        if ((k = name_index(o, args[0])) < 0) return 0;
        *(int *)o->dst = name_value(o, k);
        return -1;
    case CLI_SET:
    case CLI_ENUMS:
    case CLI_NUMBERS: /* the whole list is checked before anything is stored */
        while ((r = cli_next_item(&list, item, sizeof item)) != 0) {
            if (r < 0 || n == CLI_MAX_ITEMS || (o->kind != CLI_SET && n == o->max_items)) return 0;
            if (o->kind == CLI_NUMBERS) {
                if (!cli_parse_double(item, &got[n]) || !in_range(o, got[n]) || (o->whole && got[n] != floor(got[n]))) return 0;
            } else if ((k = name_index(o, item)) < 0) return 0;
            else got[n] = name_value(o, k);
            n++;
        }
        if (n < (o->kind == CLI_SET ? 1 : o->min_items)) return 0;
        for (k = 0; k < n; k++) {
            if (o->kind == CLI_SET) set |= (unsigned)got[k];
            else if (o->kind == CLI_ENUMS) ((int *)o->dst)[k] = (int)got[k];
            else ((double *)o->dst)[k] = got[k];
        }
        if (o->kind == CLI_SET) *(unsigned *)o->dst = set;
        else *o->items = n;
        return -1;
    }
    return 0;
}

static const cli_option *find_option(const cli_command *cmd, const char *a)
{
    int i;
    for (i = 0; i < cmd->option_count; i++)
        if (strcmp(cmd->options[i].name, a) == 0) return &cmd->options[i];
    return NULL;
}

int cli_parse(const cli_command *cmd, int argc, char **argv)
{
    int i, operands = 0;
    for (i = 0; i < argc; i++) {
        const char *a = argv[i], *need = NULL;
        const cli_option *o;
        int nvalues, bad;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            cli_help(cmd, stdout);
            return CLI_EXIT_OK;
        }
        if (a[0] != '-') {
            if (operands == cmd->max_operands) {
                if (!cmd->operand) return cli_usage(cmd->name, "unexpected argument '%s'", a);
                if (cmd->max_operands == 1) return cli_usage(cmd->name, "more than one %s given ('%s', then '%s')", cmd->operand, cmd->operands[0], a);
                return cli_usage(cmd->name, "too many %s arguments (at most %d)", cmd->operand, cmd->max_operands);
            }
            cmd->operands[operands++] = a;
            continue;
        }
        if (!(o = find_option(cmd, a))) return cli_usage(cmd->name, "unknown option '%s'", a);
        if (o->kind == CLI_FLAG) nvalues = 0;
        else if (o->kind == CLI_ENUM && o->optional) nvalues = i + 1 < argc && name_index(o, argv[i + 1]) >= 0;
        else nvalues = (o->kind == CLI_INT || o->kind == CLI_DOUBLE || o->kind == CLI_CUSTOM) && o->count ? o->count : 1;
        if (o->kind == CLI_ENUM && o->optional && !nvalues) bad = -1;
        else if (argc - 1 - i < nvalues)
            return nvalues == 1 ? cli_usage(cmd->name, "%s needs a value", a) : cli_usage(cmd->name, "%s needs %d values: %s", a, nvalues, o->arg);
        else bad = store(o, argv + i + 1, &need);
        if (bad >= 0) {
            char what[512];
            if (need) snprintf(what, sizeof what, "%s", need);
            else describe(o, what, sizeof what);
            return cli_usage(cmd->name, "%s needs %s, got '%s'", a, what, argv[i + 1 + bad]);
        }
        if (o->given) *o->given = 1;
        i += nvalues;
    }
    if (cmd->operand_count) *cmd->operand_count = operands;
    if (operands < cmd->min_operands) return cli_usage(cmd->name, "no %s given", cmd->operand);
    return CLI_CONTINUE;
}

void cli_help(const cli_command *cmd, FILE *f)
{
    int i, width = cmd->column - 2;
    fputs(cmd->help, f);
    for (i = 0; i < cmd->option_count; i++) {
        const cli_option *o = &cmd->options[i];
        const char *h;
        char left[128];
        int n;
        if (!o->help) continue;
        if (o->synopsis) n = snprintf(left, sizeof left, "%s", o->synopsis);
        else n = snprintf(left, sizeof left, "%s%s%s", o->name, o->arg ? " " : "", o->arg ? o->arg : "");
        fprintf(f, "  %-*s", n + 2 <= width ? width : n + 2, left); /* a long left column: two spaces */
        for (h = o->help; *h; h++) {
            fputc(*h, f);
            if (*h == '\n') fprintf(f, "%*s", cmd->column, "");
        }
        fputc('\n', f);
    }
}

int cli_usage(const char *name, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "voxgi %s: ", name);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, " (see 'voxgi %s --help')\n", name);
    return CLI_EXIT_USAGE;
}

/* ------------------------------------------------------------------ messages */
void cli_session_init(cli_session *s, const char *name)
{
    memset(s, 0, sizeof *s);
    s->name = name;
    s->interactive = isatty(2);
}

void cli_status(cli_session *s, const char *fmt, ...)
{
    char line[256];
    int n;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    n = (int)(strlen(s->prefix) + strlen(line));
    /* blanks over whatever of a longer previous line would show past the new one */
    fprintf(stderr, "\r%s%s%*s", s->prefix, line, s->status_width > n ? s->status_width - n : 0, "");
    s->status_width = n;
}

void cli_status_clear(cli_session *s)
{
    if (s->status_width) fprintf(stderr, "\r%*s\r", s->status_width, "");
    s->status_width = 0;
}

static void vnote(cli_session *s, const char *fmt, va_list ap)
{
    cli_status_clear(s);
    fprintf(stderr, "voxgi %s: ", s->name);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
}

void cli_note(cli_session *s, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vnote(s, fmt, ap);
    va_end(ap);
}

int cli_fail(cli_session *s, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vnote(s, fmt, ap);
    va_end(ap);
    return CLI_EXIT_FAILURE;
}

const char *cli_io_why(int err) { return err ? strerror(err) : "I/O error"; }

const char *cli_json(const char *s)
{
    static char ring[8][4096 + 8];
    static int next;
    char *out = ring[next++ & 7];
    size_t n = 0;
    out[n++] = '"';
    for (; s && *s && n < 4090; s++) { /* room for one escape (6 bytes) and the closing quote */
        unsigned char ch = (unsigned char)*s;
        if (ch == '"' || ch == '\\') {
            out[n++] = '\\';
            out[n++] = (char)ch;
        } else if (ch < 0x20 || ch == 0x7f) n += (size_t)sprintf(out + n, "\\u%04x", (unsigned)ch);
        else out[n++] = (char)ch;
    }
    out[n++] = '"';
    out[n] = 0;
    return out;
}

int cli_fail_lib(cli_session *s, const voxgi_context *ctx, const char *what)
{
    /* the context's own record of the failure, else what the logger kept (a failed voxgi_create has no context) */
    const char *why = ctx && voxgi_last_error(ctx)[0] ? voxgi_last_error(ctx) : (s->error[0] ? s->error : "failed");
    return what ? cli_fail(s, "%s: %s", what, why) : cli_fail(s, "%s", why);
}

/* ------------------------------------------------------------------ contexts */
static void log_to_session(voxgi_log_level level, const char *msg, void *user)
{
    cli_session *s = (cli_session *)user;
    /* errors are kept, not printed: the command that sees the failed call says it once, in context */
    if (level == VOXGI_LOG_ERROR) snprintf(s->error, sizeof s->error, "%s", msg);
    else if (level == VOXGI_LOG_WARNING) cli_note(s, "warning: %s", msg);
    else if (level == VOXGI_LOG_INFO && strncmp(msg, "plan: ", 6) == 0) cli_note(s, "%s", msg); /* what the image leaves out, and why */
}

/* Any stage the library names, at any fraction; the line stays until replaced or cleared. */
static int progress_to_session(double fraction, const char *stage, void *user)
{
    cli_session *s = (cli_session *)user;
    double f = fraction > 0 ? (fraction < 1 ? fraction : 1) : 0;
    cli_status(s, "%s %3d%%", stage && stage[0] ? stage : "working", (int)(f * 100 + 0.5));
    return 0;
}

int cli_context_try(cli_session *s, cli_context *c, voxgi_backend backend, vxt_gl_kind kind, int threads, int progress)
{
    voxgi_desc d;
    voxgi_result r;
    memset(c, 0, sizeof *c);
    memset(&d, 0, sizeof d);
    s->error[0] = 0;
    d.backend = backend;
    d.thread_count = threads;
    d.logger.func = log_to_session;
    d.logger.user = s;
    if (progress) {
        d.progress.func = progress_to_session;
        d.progress.user = s;
    }
    if (backend != VOXGI_BACKEND_CPU) {
        char why[512]; /* the size headless_gl.h's own messages have */
        c->gl = vxt_gl_create(kind, why, sizeof why);
        if (!c->gl) snprintf(s->error, sizeof s->error, "%s", why);
        if (!c->gl && backend == VOXGI_BACKEND_GL) return 1;
        d.gl_get_proc_address_user = vxt_gl_get_proc;
        d.gl_user = c->gl;
    }
    r = voxgi_create(&d, &c->vx);
    if (r != VOXGI_OK) {
        if (!s->error[0]) snprintf(s->error, sizeof s->error, "%s", voxgi_result_string(r));
        if (c->gl) vxt_gl_destroy(c->gl);
        memset(c, 0, sizeof *c);
        return 1;
    }
    s->error[0] = 0; /* AUTO may have logged why it fell back to the CPU: not an error */
    return 0;
}

int cli_context_open(cli_session *s, cli_context *c, voxgi_backend backend, vxt_gl_kind kind, int threads, int progress)
{
    if (cli_context_try(s, c, backend, kind, threads, progress) == 0) return 0;
    return cli_fail(s, "cannot use backend %s: %s", voxgi_backend_name(backend), s->error);
}

int cli_context_open_options(cli_session *s, cli_context *c, const cli_common *o)
{
    return cli_context_open(s, c, (voxgi_backend)o->backend, (vxt_gl_kind)o->gl, o->threads, !o->json && s->interactive);
}

void cli_context_close(cli_session *s, cli_context *c)
{
    cli_status_clear(s);
    voxgi_destroy(c->vx);
    if (c->gl) vxt_gl_destroy(c->gl);
    memset(c, 0, sizeof *c);
}

/* ------------------------------------------------------------------ meshes */
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

int cli_mesh_open(cli_session *s, const char *path, cli_mesh *t)
{
    char err[512];
    memset(t, 0, sizeof *t);
    snprintf(t->name, sizeof t->name, "%s", path);
    if (strncmp(path, "builtin:", 8) == 0) {
        if (!builtin_shape(path, &t->shape))
            return cli_fail(s, "unknown built-in shape '%s' (there are builtin:quad, builtin:subdivided-quad, builtin:cube, builtin:sphere)", path);
        t->vm.positions = t->shape.pos;
        t->vm.vertex_count = t->shape.vertex_count;
        t->vm.indices = t->shape.idx;
        t->vm.index_count = 3 * t->shape.triangle_count;
    } else {
        if (voxgi_io_load_mesh(path, &t->m, err, sizeof err) != 0) return cli_fail(s, "%s", err);
        t->scene = voxgi_io_mesh_scene(&t->m); /* with the file's materials */
        t->vm = t->m.mesh;
    }
    t->scene.meshes = &t->vm;
    t->scene.mesh_count = 1;
    return 0;
}

void cli_mesh_close(cli_mesh *t)
{
    voxgi_io_mesh_free(&t->m);
    vxt_shape_free(&t->shape);
    memset(t, 0, sizeof *t);
}

size_t cli_mesh_triangles(const cli_mesh *t) { return t->vm.index_count / 3; }

int cli_open_mesh_and_context(cli_session *s, const char *path, const cli_common *o, cli_mesh *t, cli_context *c)
{
    if (cli_mesh_open(s, path, t)) return CLI_EXIT_FAILURE;
    if (cli_context_open_options(s, c, o) == 0) return 0;
    cli_mesh_close(t);
    return CLI_EXIT_FAILURE;
}

void cli_close_mesh_and_context(cli_session *s, cli_mesh *t, cli_context *c)
{
    cli_context_close(s, c);
    cli_mesh_close(t);
}

/* ------------------------------------------------------------------ numbers */
static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double cli_now_ms(void)
{
    struct timeval tv;
    gettimeofday(&tv, NULL);
    return (double)tv.tv_sec * 1e3 + (double)tv.tv_usec * 1e-3;
}

double cli_median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return v[n / 2];
}

voxgi_result cli_fit_grid(voxgi_context *ctx, const voxgi_scene *scene, int res, int per_axis, double pad, voxgi_grid *out)
{
    voxgi_fit_desc fit;
    memset(&fit, 0, sizeof fit);
    fit.res = res;
    fit.per_axis = per_axis;
    fit.padding = pad;
    return voxgi_fit_grid(ctx, scene, &fit, out);
}

int cli_make_dirs(const char *path)
{
    char buf[1024];
    size_t i, n = strlen(path);
    if (n == 0 || n >= sizeof buf) return -1;
    memcpy(buf, path, n + 1);
    for (i = 1; i <= n; i++)
        if (buf[i] == '/' || buf[i] == 0) {
            char c = buf[i];
            buf[i] = 0;
            if (mkdir(buf, 0777) != 0 && errno != EEXIST) return -1;
            buf[i] = c;
        }
    return 0;
}
