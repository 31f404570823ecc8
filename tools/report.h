/* tools/report.h - what the reports share: the plot of error against time (SVG), the picture of an
 * image beside its reference with the error's heat map (PNG), and the interface through which
 * voxgi report all runs each method's sweep (each report's file keeps its sweep and the settings
 * report all gives it). */
#ifndef VXT_REPORT_H
#define VXT_REPORT_H
#include "cli.h"
#include "pareto.h"

/* ------------------------------------------------------------------ the plot (cli_report.c) */
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
   range of errors. */
void report_plot_svg(FILE *f, const report_plot *p);

/* ------------------------------------------------------------------ pictures (cli_report.c) */
/* The exposure that puts the 95th percentile of the reference's brightest channel, over the pixels
   the mask keeps, at 0.8 (1 for a black reference). */
float report_exposure(const float *ref, const cli_error_mask *m);
/* The error heat map's white: a pixel's RMS difference over its channels at this share of the
   reference's mean (over the pixels the mask keeps). */
#define REPORT_HEAT_WHITE 0.5
/* PNG at path: img, ref and the heat map of their difference side by side (4 white pixels between),
   the images at exposure; the heat map black (no difference) through red and yellow to white
   (REPORT_HEAT_WHITE and above), pixels the mask leaves out mid grey. 0, or -1. */
int report_png_compare(const char *path, const float *img, const float *ref, const cli_error_mask *m, float exposure);

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

/* ------------------------------------------------------------------ report all */
/* What a row measures, and against what. */
enum { REPORT_BOUNCE, REPORT_DIRECT, REPORT_AO, REPORT_VOXELS, REPORT_QUANTITIES };
#define REPORT_AO_RADIUS 0.1 /* report all's ambient occlusion: within this share of the scene's longest side */

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
} report_item;

/* One method's sweep on one scene. */
typedef struct report_run {
    cli_session *s;
    voxgi_context *ctx;          /* where the passes run */
    voxgi_context *cpu;          /* a CPU context (the voxel sets' exact reference) */
    const voxgi_scene *scene;
    const char *scene_name;
    voxgi_camera camera;         /* the scene's view at the report's size */
    const cli_reference *R;      /* the reference of the method's quantity (NULL for voxel sets) */
    int quick;                   /* --quick: the few settings */
    float *img;                  /* scratch: one image */
    /* each configuration measured, with its image (NULL for voxel sets) */
    void (*emit)(struct report_run *run, const report_item *item, const float *img);
    void *user;
    char why[256];               /* REPORT_NOT_APPLICABLE: why */
} report_run;
#define REPORT_NOT_APPLICABLE 3  /* what a sweep returns for a scene it does not apply to */

/* The sweeps, each in its report's file: 0, CLI_EXIT_FAILURE (said why), or REPORT_NOT_APPLICABLE. */
int report_vct_all(report_run *run);                    /* REPORT_BOUNCE */
int report_rsm_all(report_run *run);                    /* REPORT_BOUNCE */
int report_sh_all(report_run *run);                     /* REPORT_BOUNCE */
int report_ssgi_all(report_run *run);                   /* REPORT_BOUNCE: ssgi, hybrid, hybrid+light */
int report_tsm_all(report_run *run);                    /* REPORT_DIRECT */
int report_linespace_all(report_run *run);              /* REPORT_DIRECT: linespace-exact, linespace-fast */
int report_ao_all(report_run *run);                     /* REPORT_AO: ssao, ssao-points, vao */
int report_voxels_all(report_run *run);                 /* REPORT_VOXELS: the surface voxelizers */
#endif
