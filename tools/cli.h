/* tools/cli.h - what every command of the voxgi tool shares: exit codes, one table-driven
 * option parser (which also writes each command's option help), messages on stderr that never
 * land after a half-written progress line, voxgi contexts with headless GL, and meshes.
 *
 * A command describes its options in a table of cli_option (name, kind of value, where it goes,
 * help) and calls cli_parse; the parser names an unknown option, a missing value and a bad value
 * separately. Every message goes through a cli_session, which the library's log and progress
 * callbacks also write to: no state lives in globals. */
#ifndef VXT_CLI_H
#define VXT_CLI_H
#include "../voxgi.h"
#include "headless_gl.h"
#include "../voxgi_io.h"
#include "shapes.h"
#include <errno.h>
#include <math.h>
#include <stdio.h>

#if defined(__GNUC__) || defined(__clang__)
#define CLI_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define CLI_PRINTF(f, a)
#endif

/* The exit status of every command, as 'voxgi --help' documents it. */
enum { CLI_EXIT_OK = 0, CLI_EXIT_FAILURE = 1, CLI_EXIT_USAGE = 2 };
#define CLI_CONTINUE (-1) /* cli_parse: the arguments are good, run the command */
#define CLI_MAX_ITEMS 64  /* the longest list a SET, ENUMS or NUMBERS option takes */

/* ------------------------------------------------------------------ options */
typedef enum cli_kind {
    CLI_FLAG,    /* no value: *(int *)dst = 1 */
    CLI_INT,     /* `count` whole numbers in lo..hi into (int *)dst */
    CLI_DOUBLE,  /* `count` numbers in [lo, hi] ((lo, hi] with lo_open) into (double *)dst; with
                    lo = -HUGE_VAL and hi = HUGE_VAL any number strtod reads */
    CLI_STRING,  /* the value as given into (const char **)dst */
    CLI_ENUM,    /* one of `names` into (int *)dst: values[i], or i without values */
    CLI_SET,     /* comma-separated names: the OR of their values into (unsigned *)dst */
    CLI_ENUMS,   /* min_items..max_items comma-separated names into (int *)dst as ENUM does, the count into *items */
    CLI_NUMBERS, /* min_items..max_items comma-separated numbers in range (whole ones if `whole`) into
                    (double *)dst, the count into *items */
    CLI_CUSTOM   /* `count` values handed to parse() */
} cli_kind;

typedef struct cli_option cli_option;
struct cli_option {
    const char *name;          /* "--res" */
    const char *arg;           /* the value(s) in help and messages: "N", "W H"; NULL for a flag */
    cli_kind kind;
    void *dst;
    int count;                 /* INT, DOUBLE, CUSTOM: values after the name (0 means 1) */
    double lo, hi;             /* INT, DOUBLE, NUMBERS: the range */
    int lo_open, whole;        /* DOUBLE, NUMBERS: lo itself excluded; NUMBERS: whole numbers only */
    const char *const *names;  /* ENUM, SET, ENUMS: the words, NULL-terminated */
    const int *values;         /* their values (NULL: the index; SET needs them) */
    int min_items, max_items;  /* ENUMS, NUMBERS */
    int *items;                /* ENUMS, NUMBERS: how many were given */
    int optional;              /* ENUM: the value may be left out (dst keeps its value) */
    int *given;                /* when not NULL, set to 1 when the option appears */
    /* CUSTOM: stores args[0..count); returns -1, or the index of the bad value with *need saying what it needs */
    int (*parse)(const cli_option *o, char **args, const char **need);
    const char *synopsis;      /* help's left column when it is not "name arg" */
    const char *help;          /* its lines after the first are indented to the column; NULL: not listed */
};

typedef struct cli_command {
    const char *name;          /* "render": every message starts "voxgi render: " */
    const char *help;          /* usage line and description, printed before the option lines */
    int column;                /* where the option help text starts */
    const cli_option *options;
    int option_count;
    const char *operand;       /* what the operands are ("mesh"), for messages; NULL: none taken */
    const char **operands;     /* they go here, at most max_operands, at least min_operands */
    int min_operands, max_operands;
    int *operand_count;
} cli_command;

#define CLI_COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

/* Parses argv[0..argc): CLI_CONTINUE when the command should run, else the exit status (0 after
   --help, CLI_EXIT_USAGE after the message naming what is wrong). Options and values are taken in
   order; a value may start with '-' (--bounces -1). */
int cli_parse(const cli_command *cmd, int argc, char **argv);
void cli_help(const cli_command *cmd, FILE *f);
/* "voxgi NAME: message (see 'voxgi NAME --help')" on stderr; returns CLI_EXIT_USAGE. */
int cli_usage(const char *name, const char *fmt, ...) CLI_PRINTF(2, 3);
int cli_parse_int(const char *s, int lo, int hi, int *out);
int cli_parse_double(const char *s, double *out);
/* The next comma-separated item of *list into buf: 1, or 0 at the end, or -1 for an empty or too long item. */
int cli_next_item(const char **list, char *buf, size_t size);
/* Makes directory path and those above it (mkdir -p); 0, or -1. */
int cli_make_dirs(const char *path);
/* Whether path ends in ext (".png"), in any case. */
int cli_has_extension(const char *path, const char *ext);

/* The options most commands share, each defined once here; a command lists the ones it takes
   with its own help text (what --backend decides differs between commands). */
typedef struct cli_common {
    int backend;  /* voxgi_backend */
    int gl;       /* vxt_gl_kind */
    int threads;  /* 0: one per core */
    int json;
} cli_common;
extern const char *const cli_backend_names[], *const cli_gl_names[], *const cli_svo_format_names[], *const cli_attribute_names[];
extern const int cli_attribute_values[];
#define CLI_OPT_BACKEND(c, text) \
    {.name = "--backend", .arg = "auto|cpu|gl", .kind = CLI_ENUM, .dst = &(c)->backend, .names = cli_backend_names, .help = (text)}
#define CLI_OPT_GL(c, text) \
    {.name = "--gl", .arg = "auto|egl|osmesa", .kind = CLI_ENUM, .dst = &(c)->gl, .names = cli_gl_names, .help = (text)}
#define CLI_OPT_THREADS(c) \
    {.name = "--threads", .arg = "T", .kind = CLI_INT, .dst = &(c)->threads, .lo = 1, .hi = 256, \
     .help = "CPU worker threads (default: one per core)"}
#define CLI_OPT_JSON(c, text) {.name = "--json", .kind = CLI_FLAG, .dst = &(c)->json, .help = (text)}
/* albedo,normal,emission,opacity or all -> voxgi_attribute bits */
#define CLI_OPT_ATTRIBUTES(dst_, text) \
    {.name = "--attributes", .arg = "LIST", .kind = CLI_SET, .dst = (dst_), .names = cli_attribute_names, \
     .values = cli_attribute_values, .help = (text)}

/* ------------------------------------------------------------------ messages */
typedef struct cli_session {
    const char *name;     /* the command: the prefix of every message */
    int interactive;      /* stderr is a terminal: progress lines are worth writing */
    int status_width;     /* characters of the progress line on stderr now; 0: none */
    char error[1024];     /* the last error the library logged, or why a context could not be made */
    char prefix[96];      /* put before every progress line (report all: its stage and fraction); "" by default */
} cli_session;

void cli_session_init(cli_session *s, const char *name);
/* A transient line on stderr (progress), replacing the previous one. */
void cli_status(cli_session *s, const char *fmt, ...) CLI_PRINTF(2, 3);
/* Erases the progress line, if one is shown: before results, errors and the end. */
void cli_status_clear(cli_session *s);
/* "voxgi NAME: message" on stderr. */
void cli_note(cli_session *s, const char *fmt, ...) CLI_PRINTF(2, 3);
/* The same for a failure; returns CLI_EXIT_FAILURE. */
int cli_fail(cli_session *s, const char *fmt, ...) CLI_PRINTF(2, 3);
/* A failed library call on ctx, said once: "voxgi NAME: what: the library's reason" (what may be NULL). */
int cli_fail_lib(cli_session *s, const voxgi_context *ctx, const char *what);
/* Why a file operation failed, for "cannot write PATH: why": strerror(err), or a plain "I/O
   error" when err is 0 (a short write the C library left no errno for). */
const char *cli_io_why(int err);

/* ------------------------------------------------------------------ JSON */
/* s as a JSON string, quotes included, with '"', '\\' and control characters escaped: every text
   the commands put in JSON goes through it (a file may be named `sp "x\y".obj`). The result lives
   in one of 8 rotating buffers: up to 8 in one printf; text over 4000 bytes is cut (still valid). */
const char *cli_json(const char *s);

/* ------------------------------------------------------------------ contexts */
typedef struct cli_context {
    voxgi_context *vx;
    vxt_gl *gl; /* the headless GL context vx uses, or NULL */
} cli_context;

/* Makes a voxgi context logging to s (errors are kept for the command to report, once; warnings
   printed) and, with progress, showing the stages the library reports. For GL (or AUTO) it first
   makes a headless GL context of `kind`. 0 on success; else 1 with the reason in s->error and
   nothing printed. */
int cli_context_try(cli_session *s, cli_context *c, voxgi_backend backend, vxt_gl_kind kind, int threads, int progress);
/* The same, saying "cannot use backend B: why" when it fails. */
int cli_context_open(cli_session *s, cli_context *c, voxgi_backend backend, vxt_gl_kind kind, int threads, int progress);
/* The context the shared options ask for: --backend, --gl, --threads, and progress on a terminal unless --json. */
int cli_context_open_options(cli_session *s, cli_context *c, const cli_common *o);
void cli_context_close(cli_session *s, cli_context *c);

/* ------------------------------------------------------------------ meshes */
typedef struct cli_mesh {
    char name[256];
    voxgi_io_mesh m;       /* file meshes */
    vxt_shape shape;       /* built-in shapes */
    voxgi_mesh vm;
    voxgi_scene scene;
} cli_mesh;

/* Loads a file (OBJ+MTL, OFF, STL, PLY, glTF) or built-in shape into a one-mesh scene; 0 on success,
   else says why and returns 1. */
int cli_mesh_open(cli_session *s, const char *path, cli_mesh *t);
void cli_mesh_close(cli_mesh *t);
size_t cli_mesh_triangles(const cli_mesh *t);
/* What voxelize and svo start with: the mesh (first: a bad file fails fast) and the context the options ask for. */
int cli_open_mesh_and_context(cli_session *s, const char *path, const cli_common *o, cli_mesh *t, cli_context *c);
void cli_close_mesh_and_context(cli_session *s, cli_mesh *t, cli_context *c);

/* ------------------------------------------------------------------ numbers */
/* The median of v[0..n) (sorts v). */
double cli_median(double *v, int n);
/* Wall-clock milliseconds (for differences). */
double cli_now_ms(void);
/* A grid of res^3 voxels (per_axis: only as long as the scene needs) fitted around the scene. */
voxgi_result cli_fit_grid(voxgi_context *ctx, const voxgi_scene *scene, int res, int per_axis, double pad, voxgi_grid *out);

/* ------------------------------------------------------------------ what render --compare and the reports measure (cli_measure.c) */
/* The one rule for an image's error against a reference: the relative RMSE (the RMS difference
   over pixels and channels / the reference's mean over the same) over the pixels farther than
   CLI_EMITTER_MARGIN pixels (Chebyshev distance: outside the 7 x 7 square around) from any pixel
   whose centre sees an emitter, both images rendered without the emission the camera sees
   (hide_emitters = 1). The anti-aliased edges of the emitters would otherwise carry most of the
   squared error. "Sees an emitter": the CPU's G-buffer (voxgi_gbuffer_render, the same camera)
   names a triangle whose material has emission > 0, on any backend. */
#define CLI_EMITTER_MARGIN 3
typedef struct cli_error_mask {
    unsigned char *masked;    /* width x height, rows from the top; 1: left out */
    int width, height;
    size_t masked_pixels;
} cli_error_mask;
/* The material of the scene's triangle `id` (meshes in order, then their triangles: the
   G-buffer's numbering); NULL for the library's default material or an id beyond the scene. */
const voxgi_material *cli_triangle_material(const voxgi_scene *scene, uint32_t id);
/* The mask of scene seen by camera; 0, or says why and returns 1. */
int cli_error_mask_make(cli_session *s, voxgi_context *ctx, const voxgi_scene *scene, const voxgi_camera *camera, cli_error_mask *m);
void cli_error_mask_free(cli_error_mask *m);
/* The relative RMSE of img against ref (3 floats per pixel) over the pixels m keeps; NaN when no
   pixel is kept or the reference is black there. rms and ref_mean (may be NULL): its parts. */
double cli_masked_error(const cli_error_mask *m, const float *img, const float *ref, double *rms, double *ref_mean);

/* A converged reference of a scene's view for the reports: the path tracer's image with `spp`
   samples per pixel and `bounces` (without the emission the camera sees), or with ao_radius > 0
   its ambient occlusion within that radius (voxgi_render_desc.reference.ao_radius), the error mask, and
   how the path tracer converges there: c from a 16-spp image, so that k samples measure
   c sqrt(1/k + 1/spp) against it. 0, or says why and returns 1. */
typedef struct cli_reference {
    float *image;
    cli_error_mask mask;
    double c, ms_per_spp;
    int spp;
} cli_reference;
int cli_reference_make(cli_session *s, voxgi_context *ctx, const voxgi_scene *scene, const voxgi_camera *camera, int spp, int bounces,
                       double ao_radius, cli_reference *R);
void cli_reference_free(cli_reference *R);
/* The path tracer's time for an image that measures error e against R, a sample per pixel at
   least (HUGE_VAL: beyond R). */
double cli_reference_ms(const cli_reference *R, double e);
/* The red light of img beyond R's: the sum over the pixels R's mask keeps of
   max(0, (r - g) - (r - g) of the reference), over the reference's sum of all channels / 3
   (colour bleeding through walls); NaN for a black reference. */
double cli_red_excess(const cli_reference *R, const float *img);

/* The longest side of the box around the scene's triangles (1 when they have no extent), as the
   library takes it for the screen passes' default radii. */
double cli_scene_longest_side(const voxgi_scene *scene);
/* The default cone tracing (voxgi render --method vct: the library's zero desc, the middle of
   report vct's Pareto front) at camera's view, without the emission the camera sees, seed 1.
   CLI_VCT_* name its settings for the reports' text and sweeps: 96 voxels along the longest side,
   anisotropic mips, 24 cones at every 6th pixel, 24 direct-light rays per pixel (test_tool holds
   them to what voxgi_render_resolve gives). */
#define CLI_VCT_RES 96
#define CLI_VCT_CONES 24
#define CLI_VCT_STRIDE 6
#define CLI_VCT_DIRECT_SPP 24
void cli_vct_defaults(voxgi_render_desc *vd, const voxgi_camera *camera);

/* The built-in Cornell box with a mesh in place of its tall block: the box's triangles but the
   block's (found by geometry: the triangles that do not emit and lie inside the room, the highest
   of them), and the mesh (file or built-in shape, +Y up as it comes) scaled uniformly and moved
   so that its bounding box fits inside the block's (width, depth and height) and stands on the
   floor at the centre of the block's footprint, in the block's material. Its view is the box's. */
typedef struct cli_cornell_mesh {
    voxgi_scene scene;        /* two meshes: the box without the block, the mesh */
    voxgi_builtin_scene bs;
    cli_mesh mesh;
    char name[288];           /* "cornell-box+NAME", NAME the file's name without directory and extension */
    double scale, block_lo[3], block_hi[3];
    uint32_t material;        /* the block's */
    voxgi_mesh meshes[2];
    float *positions;
    uint32_t *box_indices, *box_materials;
} cli_cornell_mesh;
/* 0, or says why and returns 1. */
int cli_cornell_mesh_open(cli_session *s, voxgi_context *ctx, const char *mesh, cli_cornell_mesh *c);
void cli_cornell_mesh_close(voxgi_context *ctx, cli_cornell_mesh *c);

/* ------------------------------------------------------------------ commands, one file each */
int cmd_voxelize(int argc, char **argv);
int cmd_info(int argc, char **argv);
int cmd_plan(int argc, char **argv);
int cmd_bench(int argc, char **argv);  /* argv[0] is "voxelize" or "rays" */
int cmd_bench_rays(int argc, char **argv);
int cmd_svo(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_report(int argc, char **argv); /* argv[0] names the report: its table is in cmd_report.c */
int cmd_report_tsm(int argc, char **argv);
int cmd_report_rsm(int argc, char **argv); /* rsm and sh: cmd_report_bounce.c */
int cmd_report_sh(int argc, char **argv);
int cmd_report_ao(int argc, char **argv); /* ao and ssgi: cmd_report_screen.c */
int cmd_report_ssgi(int argc, char **argv);
int cmd_report_linespace(int argc, char **argv);
int cmd_report_all(int argc, char **argv);
int cmd_report_stiff(int argc, char **argv);
#endif
