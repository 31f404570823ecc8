/* tools/report.h - what the reports share: the one skeleton of the single reports (voxgi report
 * vct|tsm|rsm|sh|ao|ssgi|linespace: their options, the scene loop with the references, the Pareto
 * front, the Markdown, CSV and SVG), the sweeps that report all runs too (each in its report's
 * file), the plot of error against time (SVG) and the picture of an image beside its reference
 * with the error's heat map and its colour bar (PNG). */
#ifndef VXT_REPORT_H
#define VXT_REPORT_H
#include "cli.h"
#include "pareto.h"

/* ------------------------------------------------------------------ the plot (cli_figures.c) */
typedef struct report_plot_point {
    double ms, error;     /* error <= 0 (exact) sits on a row of its own below the lowest decade */
    int series;           /* its colour and legend entry */
    int front;            /* drawn filled and joined to the next front point of its front */
    const char *label;    /* written beside a front point (NULL: none) */
} report_plot_point;

/* A dashed line through (ms[i], error[i]): a path tracer's error against its time. */
typedef struct report_plot_curve {
    const double *ms, *error;
    int count, series;
} report_plot_curve;

typedef struct report_plot {
    const char *y_title, *x_title;
    const char *const *legend;   /* per series */
    int series_count;
    const report_plot_point *points;
    size_t count;
    int front_per_series;        /* 1: each series' front joined in its colour; 0: one front across
                                    the series, joined in black */
    const report_plot_curve *curves;
    int curve_count;
} report_plot;

/* Error against time, log scales, the front joined, the curves dashed and clipped to the points'
   range of errors. Each decade a tick (class "major-x"/"major-y") and a label; 2..9 times each
   decade a light tick ("minor-x"/"minor-y"; on y none between the exact row and the lowest
   decade), labelled where the label's box overlaps none placed before it (3 units apart); a front
   point's label (class "point-label") at the first of six places beside the point whose box lies
   in the plot and clears every label and point placed before it, else left out. A text's box is
   report_text_box's. */
void report_plot_svg(FILE *f, const report_plot *p);

/* The box a text is taken to fill: REPORT_CHAR_WIDTH x font size per character (sans-serif's
   average, a little wide), from 0.8 font size above its baseline to 0.2 below; anchor -1 start,
   0 middle, 1 end. */
#define REPORT_CHAR_WIDTH 0.6
typedef struct report_box { double x0, y0, x1, y1; } report_box;
report_box report_text_box(double x, double y, const char *text, double font_size, int anchor);
/* 1 when the boxes share area (touching edges do not). */
int report_boxes_overlap(const report_box *a, const report_box *b);

/* ------------------------------------------------------------------ pictures (cli_report.c, cli_figures.c) */
/* The exposure that puts the 95th percentile of the reference's brightest channel, over the pixels
   the mask keeps, at 0.8 (1 for a black reference). */
float report_exposure(const float *ref, const cli_error_mask *m);
/* The error heat map's white: a pixel's RMS difference over its channels at this share of the
   reference's mean (over the pixels the mask keeps). The scale is fixed, so that pictures compare. */
#define REPORT_HEAT_WHITE 0.5
/* The heat map's colour (8-bit sRGB) at t = error / REPORT_HEAT_WHITE: black at 0 through red and
   yellow to white at 1 and above, in thirds. */
void report_heat_rgb8(double t, unsigned char o[3]);

/* An 8-bit RGB canvas (rows from the top) and text on it in a 5 x 7 bitmap font: each glyph 5 x 7
   cells of scale x scale pixels, REPORT_GLYPH_ADVANCE cells apart; lower case drawn as upper
   case, characters without a glyph as '?'. */
typedef struct report_canvas { unsigned char *rgb; int w, h; } report_canvas;
#define REPORT_GLYPH_ADVANCE 6
/* ch's seven rows from the top, the leftmost column in bit 4. */
const unsigned char *report_glyph(char ch);
/* The width of text in pixels (no space after its last glyph). */
int report_text_width(const char *text, int scale);
/* text with its top left at (x, y) in colour, clipped to the canvas and to columns before x_end. */
void report_text(const report_canvas *c, int x, int y, int x_end, const char *text, int scale, const unsigned char colour[3]);

/* Where the picture's parts lie, for panels of w x h: a white band of labels (text at (pad, pad)
   in each panel, the panels at x = k (w + gap) from panel_y down); under the heat map its colour
   bar (w x bar_h at (bar_x, bar_y): 0 at its left end, REPORT_HEAT_WHITE at its right) with "0"
   and "50%" under its ends at bar_text_y, and left of it what the bar measures. Text at scale 2
   from w = 192 up, else 1. */
typedef struct report_compare_layout { int width, height, scale, pad, gap, panel_y, bar_x, bar_y, bar_h, bar_text_y; } report_compare_layout;
report_compare_layout report_compare_layout_of(int w, int h);
/* The picture, 8-bit RGB (free() it; NULL without memory), its layout in *out: img (labelled
   label, "method" when NULL), ref ("reference") and the heat map of their difference ("error"),
   the images at exposure, the pixels the mask leaves out mid grey in the heat map. */
unsigned char *report_compare_rgb8(const float *img, const float *ref, const cli_error_mask *m, float exposure, const char *label, report_compare_layout *out);
/* The picture as a PNG at path. 0, or -1. */
int report_png_compare(const char *path, const float *img, const float *ref, const cli_error_mask *m, float exposure, const char *label);

/* 100 v as "12.34%", or "-" when v is not finite; then after. */
void report_percent(FILE *f, double v, const char *after);
/* Appends printf-formatted text to the string in buf (cut at size). */
void report_append(char *buf, size_t size, const char *fmt, ...) CLI_PRINTF(3, 4);

/* ------------------------------------------------------------------ stiff cases (cmd_report_stiff.c) */
/* The cases, one column each, for every image method of tools/stiff.h (a row each). */
enum {
    REPORT_STIFF_SCALE_EXACT, REPORT_STIFF_SCALE_ROUND, REPORT_STIFF_MOVED_FLOAT, REPORT_STIFF_MOVED_FLOAT_FAR, REPORT_STIFF_MOVED_DOUBLE,
    REPORT_STIFF_DEGENERATE, REPORT_STIFF_NEEDLES, REPORT_STIFF_BRIGHT, REPORT_STIFF_RANGE, REPORT_STIFF_LEAK, REPORT_STIFF_EMPTY, REPORT_STIFF_CASES
};
#define REPORT_STIFF_METHODS 10
#define REPORT_STIFF_CELL 48
typedef struct report_stiff {
    char cells[REPORT_STIFF_METHODS][REPORT_STIFF_CASES][REPORT_STIFF_CELL]; /* what each case gave ("equal", a difference, "black", ...) */
    double furnace_albedo[2], furnace[2][2];                                /* per albedo: the path tracer's mean, the cone tracer's */
    int measured;
} report_stiff;
/* Every case on ctx, with progress on s: 0, or CLI_EXIT_FAILURE with the library's error said. */
int report_stiff_measure(cli_session *s, voxgi_context *ctx, report_stiff *out);
/* The tables, in Markdown (ci: the context's, for where the methods ran). */
void report_stiff_markdown(FILE *f, const report_stiff *r, const voxgi_info *ci);

/* ------------------------------------------------------------------ the sweeps (report all and the single reports) */
/* What a row measures, and against what (report all). */
enum { REPORT_BOUNCE, REPORT_DIRECT, REPORT_AO, REPORT_VOXELS, REPORT_QUANTITIES };
#define REPORT_AO_RADIUS 0.1 /* report all's ambient occlusion: within this share of the scene's longest side */
#define REPORT_VALUES 20     /* a row's own values (report_item.v) */

/* One measured configuration. */
typedef struct report_item {
    const char *method;   /* its series: "vct", "rsm", "ssao", "linespace-fast", "thin", ... */
    char settings[160];   /* what was set: "64^3, 16 cones, step 0.5, stride 6, anisotropic" */
    char passes[200];     /* the time of each pass, ms: "voxelize 4.9, inject + mips 44.2, ..." */
    double ms;            /* the whole image (voxel sets: the voxelization) */
    double bytes;         /* what the method built from the scene (maps, voxels, volumes, trees) */
    double error;         /* relative RMSE by the tools' rule against the run's reference; voxel
                             sets: (missed + extra) / the exact set's voxels */
    char detail[96];      /* voxel sets: "missed M, extra E of N" */
    int ref;              /* the reference it is measured against: report_run.R[ref] */
    double v[REPORT_VALUES]; /* the columns of its own report's tables (report_column.at) */
    char note[320];       /* not measured (the line space's refused trees): its own report's Markdown row */
} report_item;

/* One method's sweep on one scene. */
typedef struct report_run {
    cli_session *s;
    voxgi_context *ctx;          /* where the passes run */
    voxgi_context *cpu;          /* a CPU context (the voxel sets' exact reference) */
    const voxgi_scene *scene;
    const char *scene_name;
    voxgi_camera camera;         /* the scene's view at the report's size */
    const cli_reference *R;      /* the references of the method's quantity (NULL for voxel sets) */
    const void *args;            /* the settings to sweep: the method's report struct */
    int quick;                   /* --quick: the few settings */
    float *img;                  /* scratch: one image */
    /* each configuration measured, with its image (NULL for voxel sets) */
    void (*emit)(struct report_run *run, const report_item *item, const float *img);
    void *user;
    char why[256];               /* REPORT_NOT_APPLICABLE: why */
} report_run;
#define REPORT_NOT_APPLICABLE 3  /* what a sweep returns for a scene it does not apply to */

/* report all's settings of each method's sweep, each in its report's file: 0, CLI_EXIT_FAILURE
   (said why), or REPORT_NOT_APPLICABLE. */
int report_vct_all(report_run *run);                    /* REPORT_BOUNCE */
int report_rsm_all(report_run *run);                    /* REPORT_BOUNCE */
int report_sh_all(report_run *run);                     /* REPORT_BOUNCE */
int report_ssgi_all(report_run *run);                   /* REPORT_BOUNCE: ssgi, hybrid, hybrid+light */
int report_tsm_all(report_run *run);                    /* REPORT_DIRECT */
int report_linespace_all(report_run *run);              /* REPORT_DIRECT: linespace-exact, linespace-fast */
int report_ao_all(report_run *run);                     /* REPORT_AO: ssao, ssao-points, vao */
int report_voxels_all(report_run *run);                 /* REPORT_VOXELS: the surface voxelizers */

/* it, the image in run->img, measured against its reference (run->R[it->ref]) and handed on. */
void report_measured(report_run *run, report_item *it);

/* A measured row of a report. */
typedef struct report_row {
    int scene, quantity;  /* quantity: report all's */
    int group, front;     /* its front's (scene, and reference or quantity); 1: on it */
    double ref_ms;        /* the path tracer's time for an image at its error (HUGE_VAL: beyond its reference; NAN: voxel sets) */
    report_item it;
} report_row;
/* A new zeroed row at the end of *rows (grown as needed), or NULL when out of memory. */
report_row *report_row_add(report_row **rows, size_t *n, size_t *cap);

/* ------------------------------------------------------------------ the single reports (cli_report.c) */
#define REPORT_MAX_LIST 16   /* numbers of a LIST option */
#define REPORT_MAX_SCENES 9  /* --scenes' 8 and --cornell-mesh's */
#define REPORT_MAX_REFS 17   /* references of a scene (ao: one per radius, the base's and --radii's) */

typedef struct report_list {
    double v[REPORT_MAX_LIST];
    int n;
} report_list;
/* A LIST option: 1 to REPORT_MAX_LIST comma-separated numbers in [lo, hi] ((lo, hi] when open), whole ones when whole. */
#define REPORT_LIST(opt, list, lo_, open_, hi_, whole_, text) \
    {.name = opt, .arg = "LIST", .kind = CLI_NUMBERS, .dst = (list).v, .items = &(list).n, .min_items = 1, .max_items = REPORT_MAX_LIST, \
     .lo = lo_, .lo_open = open_, .hi = hi_, .whole = whole_, .help = text}
/* A report_list of the numbers given: REPORT_L(8, 16, 32) */
#define REPORT_L(...) {{__VA_ARGS__}, (int)(sizeof((double[]){__VA_ARGS__}) / sizeof(double))}

/* The next combination of the lists' values, the last list varying fastest: at[k] indexes lists[k]
   (all 0 for the first). 1, or 0 after the last. */
int report_next(const report_list *const *lists, int n, int *at);

/* What every single report takes; each report's struct starts with it. */
typedef struct report_opts {
    cli_common common;  /* --backend, --threads */
    const char *out_dir, *scene_list, *cornell_mesh;
    int size[2], spp;   /* size[1] 0: size[0] (--size N) */
} report_opts;
/* The defaults: the CPU, build/report, these scenes, size x size pixels, references of spp. */
#define REPORT_OPTS(scenes, size_, spp_) \
    {.common = {.backend = VOXGI_BACKEND_CPU}, .out_dir = "build/report", .scene_list = scenes, .size = {size_}, .spp = spp_}
#define REPORT_OPT_SCENES(o, text) {.name = "--scenes", .arg = "LIST", .kind = CLI_STRING, .dst = &(o)->scene_list, .help = text}
#define REPORT_OPT_SIZE(o, lo_, text) {.name = "--size", .arg = "N", .kind = CLI_INT, .dst = (o)->size, .lo = lo_, .hi = 4096, .help = text}
#define REPORT_OPT_SPP(o, lo_, text) {.name = "--spp", .arg = "S", .kind = CLI_INT, .dst = &(o)->spp, .lo = lo_, .hi = 1 << 20, .help = text}
#define REPORT_OPT_OUT(o) {.name = "--out", .arg = "DIR", .kind = CLI_STRING, .dst = &(o)->out_dir, .help = "where the files go (default build/report)"}

/* A column of a report's tables. Its heads (NULL: not in that file; a column may sit at another
   place in each file as two columns, one in each), the value it shows, and how: names[value]
   (csv_names in the CSV), else for a value that is not finite md_none / csv_none where given
   (md_none "": the cell left blank), else printf of the value (in the Markdown times 100 for
   md_unit '%', over 1e6 for 'M'). A Markdown cell is " text |" after the row's "|". */
typedef struct report_column {
    const char *md, *align, *csv;
    int at;                    /* report_item.v[at], or one of REPORT_AT_* */
    const char *md_fmt, *csv_fmt;
    const char *const *names, *const *csv_names;
    char md_unit;
    const char *md_none, *csv_none;
} report_column;
enum { REPORT_AT_SCENE = REPORT_VALUES, REPORT_AT_MS, REPORT_AT_BYTES, REPORT_AT_ERROR, REPORT_AT_REF_MS, REPORT_AT_SPEEDUP, REPORT_AT_FRONT,
       REPORT_AT_NONE /* always not finite: the none texts */ };
extern const char *const report_yes[]; /* "", "yes" */
#define REPORT_COL(md_, csv_, at_, md_fmt_, csv_fmt_) {.md = md_, .align = "---:", .csv = csv_, .at = at_, .md_fmt = md_fmt_, .csv_fmt = csv_fmt_}
#define REPORT_COL_INT(md_, csv_, at_) REPORT_COL(md_, csv_, at_, "%.0f", "%.0f")
#define REPORT_COL_SCENE {.csv = "scene", .at = REPORT_AT_SCENE}
#define REPORT_COL_ERROR(md_none_) \
    {.md = "rel. RMSE", .align = "---:", .csv = "rel_rmse", .at = REPORT_AT_ERROR, .md_fmt = "%.2f%%", .csv_fmt = "%.6g", .md_unit = '%', .md_none = md_none_}
#define REPORT_COL_REF \
    {.md = "reference at the same error", .align = "---:", .csv = "reference_ms", .at = REPORT_AT_REF_MS, .md_fmt = "%.0f ms", .csv_fmt = "%.6g", \
     .md_none = "beyond its reference", .csv_none = "-1"}
#define REPORT_COL_FRONT {.md = "Pareto", .align = ":-:", .csv = "pareto", .at = REPORT_AT_FRONT, .csv_fmt = "%.0f", .names = report_yes}

typedef struct report report;
/* A single report: its name, its columns, its sweep (report all's), and what it adds to the
   skeleton (each optional), in the order they run. */
typedef struct report_def {
    const char *name, *help;   /* "tsm": 'voxgi report tsm', DIR/tsm.md, DIR/tsm.csv */
    int bounces;               /* the path tracer's reference (no references hook): 0 the direct light, 1 one bounce */
    int scenes_optional;       /* --scenes '' (none) is taken */
    const report_column *columns;
    int ncolumns;
    int (*sweep)(report_run *run);
    int (*open)(report *rep);                                       /* after the context */
    int (*references)(report *rep, report_run *run, cli_reference *R); /* into R[0..rep->nrefs) */
    void (*row)(report *rep, report_row *r);                        /* a row's error and ref_ms (else cli_reference_ms) */
    int (*scene_done)(report *rep, report_run *run);                /* after the sweep */
    int (*done)(report *rep);                                       /* after every scene */
    void (*close)(report *rep);
    void (*md_head)(FILE *f, const report *rep);
    void (*md_scene)(FILE *f, const report *rep, int si, int end);  /* before its table, after it (end) */
    int (*md_end)(report *rep, FILE *md, FILE *csv);
    void (*svg)(FILE *f, const report *rep);                        /* DIR/NAME.svg (NULL: none) */
    void (*print_scene)(const report *rep, int si, int end);        /* stdout: around the scene's front */
    void (*print_row)(const report *rep, const report_row *r);      /* a row of the front */
    void (*print_end)(const report *rep);
} report_def;

typedef struct report_scene {
    char name[288];
    size_t masked;                                          /* pixels left out near an emitter */
    double c[REPORT_MAX_REFS], ms_per_spp[REPORT_MAX_REFS]; /* each reference's convergence */
} report_scene;

struct report {
    const report_def *def;
    report_opts *o;
    void *own;                  /* the report's struct: its options and what it measures beyond the rows */
    cli_session s;
    cli_context c;
    voxgi_info ci;              /* the context's */
    report_scene scenes[REPORT_MAX_SCENES];
    int nscenes, si, nrefs;     /* si: the scene being measured; nrefs: its references */
    cli_cornell_mesh cm;        /* --cornell-mesh's, the last scene */
    float *img;                 /* scratch: one image */
    report_row *rows;
    size_t nrows, cap;
    int out_of_memory;          /* a row could not be kept */
};

/* voxgi report NAME with options (those of o and of own): the scenes, each one's references, the
   sweep and the hooks, the front, DIR/NAME.md, .csv (and .svg), the front on stdout. The exit status. */
int report_main(const report_def *def, report_opts *o, void *own, const cli_option *options, int count, int argc, char **argv);
/* The scene of a report: cm's when given, else the built-in one named (made into bs, for the caller
   to destroy); its camera at w x h. 0, or says why and returns 1. */
int report_scene_open(cli_session *s, voxgi_context *ctx, const char *name, const cli_cornell_mesh *cm, voxgi_builtin_scene *bs, const voxgi_scene **scene,
                      voxgi_camera *camera, int w, int h);
/* A md_scene: "## NAME" and its reference's convergence. */
void report_md_scene(FILE *f, const report *rep, int si, int end);
#endif
