/* tools/cli_figures.c - the reports' figures: the plot of error against time (SVG: minor ticks on
 * the log axes, labels placed so that none overlaps another) and the picture of an image beside
 * its reference with the error's heat map (PNG: each panel labelled and the heat map's colour bar,
 * in a 5 x 7 bitmap font of its own, so that the tool needs no font or library to draw text). */
#include "report.h"
#include "image_io.h"
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------ the font */
/* 5 x 7 glyphs from ' ' to '_': seven rows from the top, the leftmost column in bit 4. Lower case
   is drawn as upper case; a character without a glyph as '?'. */
static const unsigned char font5x7[64][7] = {
    ['!' - 32] = {0x04, 0x04, 0x04, 0x04, 0x04, 0x00, 0x04}, ['%' - 32] = {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03},
    ['(' - 32] = {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}, [')' - 32] = {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08},
    ['*' - 32] = {0x00, 0x04, 0x15, 0x0E, 0x15, 0x04, 0x00}, ['+' - 32] = {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00},
    [',' - 32] = {0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08}, ['-' - 32] = {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00},
    ['.' - 32] = {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}, ['/' - 32] = {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00},
    ['0' - 32] = {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}, ['1' - 32] = {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E},
    ['2' - 32] = {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}, ['3' - 32] = {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E},
    ['4' - 32] = {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}, ['5' - 32] = {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E},
    ['6' - 32] = {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}, ['7' - 32] = {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08},
    ['8' - 32] = {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}, ['9' - 32] = {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C},
    [':' - 32] = {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}, ['<' - 32] = {0x02, 0x04, 0x08, 0x10, 0x08, 0x04, 0x02},
    ['=' - 32] = {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}, ['>' - 32] = {0x08, 0x04, 0x02, 0x01, 0x02, 0x04, 0x08},
    ['?' - 32] = {0x0E, 0x11, 0x01, 0x02, 0x04, 0x00, 0x04}, ['A' - 32] = {0x0E, 0x11, 0x11, 0x11, 0x1F, 0x11, 0x11},
    ['B' - 32] = {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E}, ['C' - 32] = {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E},
    ['D' - 32] = {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C}, ['E' - 32] = {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F},
    ['F' - 32] = {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10}, ['G' - 32] = {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F},
    ['H' - 32] = {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}, ['I' - 32] = {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E},
    ['J' - 32] = {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C}, ['K' - 32] = {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11},
    ['L' - 32] = {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F}, ['M' - 32] = {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11},
    ['N' - 32] = {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}, ['O' - 32] = {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E},
    ['P' - 32] = {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10}, ['Q' - 32] = {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D},
    ['R' - 32] = {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11}, ['S' - 32] = {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E},
    ['T' - 32] = {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}, ['U' - 32] = {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E},
    ['V' - 32] = {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04}, ['W' - 32] = {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A},
    ['X' - 32] = {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11}, ['Y' - 32] = {0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04},
    ['Z' - 32] = {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F}, ['^' - 32] = {0x04, 0x0A, 0x11, 0x00, 0x00, 0x00, 0x00},
    ['_' - 32] = {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F},
};

const unsigned char *report_glyph(char ch)
{
    int c = (unsigned char)ch, k;
    if (c >= 'a' && c <= 'z') c -= 'a' - 'A';
    if (c == ' ') return font5x7[0];
    if (c > ' ' && c < ' ' + 64)
        for (k = 0; k < 7; k++)
            if (font5x7[c - 32][k]) return font5x7[c - 32];
    return font5x7['?' - 32];
}

int report_text_width(const char *text, int scale)
{
    int n = (int)strlen(text);
    return n ? (REPORT_GLYPH_ADVANCE * n - 1) * scale : 0;
}

void report_text(const report_canvas *c, int x, int y, int x_end, const char *text, int scale, const unsigned char colour[3])
{
    int gx, gy, sx, sy;
    for (; *text; text++, x += REPORT_GLYPH_ADVANCE * scale) {
        const unsigned char *g = report_glyph(*text);
        for (gy = 0; gy < 7; gy++)
            for (gx = 0; gx < 5; gx++)
                if ((g[gy] >> (4 - gx)) & 1)
                    for (sy = 0; sy < scale; sy++)
                        for (sx = 0; sx < scale; sx++) {
                            int px = x + gx * scale + sx, py = y + gy * scale + sy;
                            if (px >= 0 && px < c->w && px < x_end && py >= 0 && py < c->h) memcpy(c->rgb + 3 * ((size_t)py * (size_t)c->w + (size_t)px), colour, 3);
                        }
    }
}

/* ------------------------------------------------------------------ the picture */
void report_heat_rgb8(double t, unsigned char o[3])
{
    t = t > 0 ? (t < 1 ? t : 1) : 0; /* black, red, yellow, white in thirds */
    o[0] = (unsigned char)(255 * fmin(1, 3 * t) + 0.5);
    o[1] = (unsigned char)(255 * fmin(1, fmax(0, 3 * t - 1)) + 0.5);
    o[2] = (unsigned char)(255 * fmax(0, 3 * t - 2) + 0.5);
}

report_compare_layout report_compare_layout_of(int w, int h)
{
    report_compare_layout l;
    l.scale = w >= 192 ? 2 : 1;
    l.pad = 2 * l.scale;
    l.gap = 4;
    l.width = 3 * w + 2 * l.gap;
    l.panel_y = 7 * l.scale + 2 * l.pad;
    l.bar_x = 2 * (w + l.gap);
    l.bar_y = l.panel_y + h + l.pad;
    l.bar_h = 6 * l.scale;
    l.bar_text_y = l.bar_y + l.bar_h + l.pad;
    l.height = l.bar_text_y + 7 * l.scale + l.pad;
    return l;
}

unsigned char *report_compare_rgb8(const float *img, const float *ref, const cli_error_mask *m, float exposure, const char *label, report_compare_layout *out)
{
    static const unsigned char black[3] = {0, 0, 0};
    const int w = m->width, h = m->height;
    const report_compare_layout l = report_compare_layout_of(w, h);
    const report_canvas cv = {(unsigned char *)malloc((size_t)3 * (size_t)l.width * (size_t)l.height + 1), l.width, l.height};
    const char *titles[3];
    char top[16];
    double mean = 0;
    size_t kept = 0, p;
    int x, y, c, k;
    if (!cv.rgb) return NULL;
    memset(cv.rgb, 255, (size_t)3 * (size_t)l.width * (size_t)l.height); /* white: the bands and the gaps */
    for (p = 0; p < (size_t)w * (size_t)h; p++)
        if (!m->masked[p]) {
            mean += ((double)ref[3 * p] + ref[3 * p + 1] + ref[3 * p + 2]) / 3;
            kept++;
        }
    mean = kept ? mean / (double)kept : 0;
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            size_t at = (size_t)y * (size_t)w + (size_t)x;
            unsigned char *o = cv.rgb + 3 * ((size_t)(l.panel_y + y) * (size_t)l.width + (size_t)x);
            double d2 = 0, t;
            for (c = 0; c < 3; c++) {
                o[c] = vxt_srgb8(exposure * img[3 * at + (size_t)c]);
                o[3 * (w + l.gap) + c] = vxt_srgb8(exposure * ref[3 * at + (size_t)c]);
            }
            o += 6 * (w + l.gap);
            if (m->masked[at]) {
                o[0] = o[1] = o[2] = 128; /* mid grey */
                continue;
            }
            for (c = 0; c < 3; c++) d2 += ((double)img[3 * at + (size_t)c] - ref[3 * at + (size_t)c]) * ((double)img[3 * at + (size_t)c] - ref[3 * at + (size_t)c]);
            t = mean > 0 ? sqrt(d2 / 3) / mean / REPORT_HEAT_WHITE : (d2 > 0);
            report_heat_rgb8(t, o);
        }
    for (x = 0; x < w; x++) { /* the colour bar under the heat map: 0 at its left end, REPORT_HEAT_WHITE at its right */
        unsigned char col[3];
        report_heat_rgb8(w > 1 ? (double)x / (w - 1) : 1, col);
        for (y = 0; y < l.bar_h; y++) memcpy(cv.rgb + 3 * ((size_t)(l.bar_y + y) * (size_t)l.width + (size_t)(l.bar_x + x)), col, 3);
    }
    snprintf(top, sizeof top, "%g%%", 100 * REPORT_HEAT_WHITE);
    report_text(&cv, l.bar_x, l.bar_text_y, l.bar_x + w, "0", l.scale, black);
    report_text(&cv, l.bar_x + w - report_text_width(top, l.scale), l.bar_text_y, l.bar_x + w, top, l.scale, black);
    report_text(&cv, l.pad, l.bar_y, l.bar_x - l.gap, "error: RMS / ref. mean", l.scale, black);
    titles[0] = label && *label ? label : "method";
    titles[1] = "reference";
    titles[2] = "error";
    for (k = 0; k < 3; k++) report_text(&cv, k * (w + l.gap) + l.pad, l.pad, k * (w + l.gap) + w, titles[k], l.scale, black);
    if (out) *out = l;
    return cv.rgb;
}

int report_png_compare(const char *path, const float *img, const float *ref, const cli_error_mask *m, float exposure, const char *label)
{
    report_compare_layout l;
    unsigned char *px = report_compare_rgb8(img, ref, m, exposure, label, &l);
    int rc = px ? vxt_write_png8(path, px, l.width, l.height) : -1;
    free(px);
    return rc;
}

/* ------------------------------------------------------------------ the plot */
static const char *const plot_colours[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b",
                                           "#e377c2", "#17becf", "#bcbd22", "#7f7f7f", "#393b79", "#637939"};
#define PLOT_COLOUR(series) plot_colours[(series) % CLI_COUNT(plot_colours)]

report_box report_text_box(double x, double y, const char *text, double font_size, int anchor)
{
    double w = REPORT_CHAR_WIDTH * font_size * (double)strlen(text);
    report_box b;
    b.x0 = anchor < 0 ? x : anchor == 0 ? x - w / 2 : x - w;
    b.x1 = b.x0 + w;
    b.y0 = y - 0.8 * font_size;
    b.y1 = y + 0.2 * font_size;
    return b;
}

int report_boxes_overlap(const report_box *a, const report_box *b)
{
    return a->x0 < b->x1 && b->x0 < a->x1 && a->y0 < b->y1 && b->y0 < a->y1;
}

/* The labels placed so far, which a new one may not overlap. */
typedef struct plot_labels {
    report_box *box;
    size_t n, cap;
} plot_labels;

static int plot_free_at(const plot_labels *pl, const report_box *b, double margin)
{
    report_box grown = {b->x0 - margin, b->y0 - margin, b->x1 + margin, b->y1 + margin};
    size_t i;
    for (i = 0; i < pl->n; i++)
        if (report_boxes_overlap(&grown, &pl->box[i])) return 0;
    return 1;
}

static void plot_take(plot_labels *pl, report_box b)
{
    if (pl->n == pl->cap) {
        size_t cap = pl->cap ? 2 * pl->cap : 64;
        report_box *nb = (report_box *)realloc(pl->box, cap * sizeof *nb);
        if (!nb) return;
        pl->box = nb;
        pl->cap = cap;
    }
    pl->box[pl->n++] = b;
}

static const char *const plot_anchor_names[3] = {"start", "middle", "end"};

/* A text at (x, y) when its box is free (always when forced): 1 when written. */
static int plot_text(FILE *f, plot_labels *pl, double x, double y, const char *text, double font_size, int anchor, const char *attrs, int forced)
{
    report_box b = report_text_box(x, y, text, font_size, anchor);
    if (!forced && !plot_free_at(pl, &b, 3)) return 0;
    plot_take(pl, b);
    fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"%s\" font-size=\"%g\"%s>%s</text>\n", x, y, plot_anchor_names[anchor + 1], font_size, attrs, text);
    return 1;
}

void report_plot_svg(FILE *f, const report_plot *p)
{
    const double W = 740, H = 480, L = 70, R = 40, T = 20, B = 50, legend_line = 15;
    const double height = H + legend_line * p->series_count + 10;
    double tmin = HUGE_VAL, tmax = 0, emin = HUGE_VAL, emax = 0;
    int zero = 0, k, c, m, pass;
    size_t i, j;
    plot_labels pl = {NULL, 0, 0};
    char text[64];
    for (i = 0; i < p->count; i++) { /* the range: the points' errors, and the times of the points and of the curves within those errors */
        const report_plot_point *q = &p->points[i];
        if (!(q->ms > 0) || !isfinite(q->ms) || !(q->error >= 0) || !isfinite(q->error)) continue;
        tmin = fmin(tmin, q->ms);
        tmax = fmax(tmax, q->ms);
        if (q->error > 0) {
            emin = fmin(emin, q->error);
            emax = fmax(emax, q->error);
        } else zero = 1;
    }
    if (!(tmax > 0)) tmin = 1, tmax = 10;
    if (!(emax > 0)) emin = emax = 0.01;
    for (c = 0; c < p->curve_count; c++)
        for (k = 0; k < p->curves[c].count; k++)
            if (p->curves[c].error[k] >= emin && p->curves[c].error[k] <= emax && p->curves[c].ms[k] > 0) tmax = fmax(tmax, p->curves[c].ms[k]);
    tmin = pow(10, floor(log10(tmin)));
    tmax = pow(10, ceil(log10(tmax)));
    emin = pow(10, floor(log10(emin)));
    emax = pow(10, ceil(log10(emax)));
    if (emax <= emin) emax = emin * 10;
    if (tmax <= tmin) tmax = tmin * 10;
    if (zero) emin /= 10; /* the exact points' row, below the lowest decade */
#define RX(t) (L + (log10(t) - log10(tmin)) / (log10(tmax) - log10(tmin)) * (W - L - R))
#define RY(e) (H - B - (log10((e) > emin ? (e) : emin) - log10(emin)) / (log10(emax) - log10(emin)) * (H - T - B))
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" font-family=\"sans-serif\" font-size=\"11\">\n", W, height);
    fprintf(f, "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n");
    /* the axes' ticks: the decades first (each labelled), then 2..9 times each decade (a light
       line, labelled where its label overlaps none placed before it) */
    for (pass = 0; pass < 2; pass++) {
        int kt0 = (int)floor(log10(tmin) + 0.5), kt1 = (int)floor(log10(tmax) + 0.5), ke0 = (int)floor(log10(emin) + 0.5), ke1 = (int)floor(log10(emax) + 0.5);
        for (k = kt0; k <= kt1 - pass; k++)
            for (m = pass ? 2 : 1; m <= (pass ? 9 : 1); m++) {
                double v = m * pow(10, k), x = RX(v);
                fprintf(f, "<line class=\"%s-x\" x1=\"%.1f\" y1=\"%.0f\" x2=\"%.1f\" y2=\"%.0f\" stroke=\"%s\"/>\n", pass ? "minor" : "major", x, T, x, H - B,
                        pass ? "#f0f0f0" : "#ddd");
                snprintf(text, sizeof text, "%g ms", v);
                plot_text(f, &pl, x, H - B + 15, text, 11, 0, "", !pass);
            }
        for (k = ke0 + (pass && zero); k <= ke1 - pass; k++) /* y: no minor ticks between the exact row and the lowest decade */
            for (m = pass ? 2 : 1; m <= (pass ? 9 : 1); m++) {
                double v = m * pow(10, k), y = RY(v);
                fprintf(f, "<line class=\"%s-y\" x1=\"%.0f\" y1=\"%.1f\" x2=\"%.0f\" y2=\"%.1f\" stroke=\"%s\"/>\n", pass ? "minor" : "major", L, y, W - R, y,
                        pass ? "#f0f0f0" : "#ddd");
                if (!pass && zero && k == ke0) snprintf(text, sizeof text, "0 (exact)");
                else snprintf(text, sizeof text, "%g%%", 100 * v);
                plot_text(f, &pl, L - 5, y + 4, text, 11, 1, "", !pass);
            }
    }
    plot_text(f, &pl, (L + W - R) / 2, H - 12, p->x_title, 11, 0, "", 1);
    fprintf(f, "<text x=\"15\" y=\"%.0f\" transform=\"rotate(-90 15 %.0f)\" text-anchor=\"middle\">%s</text>\n", (T + H - B) / 2, (T + H - B) / 2, p->y_title);
    for (c = 0; c < p->curve_count; c++) { /* dashed, the parts within the range */
        const report_plot_curve *cv = &p->curves[c];
        int prev = -1;
        for (k = 0; k < cv->count; k++) {
            if (cv->ms[k] < tmin || cv->ms[k] > tmax || cv->error[k] < emin || cv->error[k] > emax) {
                prev = -1;
                continue;
            }
            if (prev >= 0)
                fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-dasharray=\"4 3\"/>\n", RX(cv->ms[prev]),
                        RY(cv->error[prev]), RX(cv->ms[k]), RY(cv->error[k]), PLOT_COLOUR(cv->series));
            prev = k;
        }
    }
    for (i = 0; i < p->count; i++) { /* each front point joined to the next one of its front in time */
        const report_plot_point *q = &p->points[i];
        long next = -1;
        if (!q->front) continue;
        for (j = 0; j < p->count; j++) {
            const report_plot_point *o = &p->points[j];
            if (o->front && (!p->front_per_series || o->series == q->series) && o->ms > q->ms && (next < 0 || o->ms < p->points[next].ms)) next = (long)j;
        }
        if (next >= 0)
            fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"2\"/>\n", RX(q->ms), RY(q->error),
                    RX(p->points[next].ms), RY(p->points[next].error), p->front_per_series ? PLOT_COLOUR(q->series) : "#000");
    }
    for (i = 0; i < p->count; i++) { /* the points' own places, which no label may cover */
        const report_plot_point *q = &p->points[i];
        report_box b;
        if (!(q->ms > 0) || !isfinite(q->ms) || !(q->error >= 0) || !isfinite(q->error)) continue;
        b.x0 = RX(q->ms) - 4, b.x1 = RX(q->ms) + 4, b.y0 = RY(q->error) - 4, b.y1 = RY(q->error) + 4;
        plot_take(&pl, b);
    }
    for (i = 0; i < p->count; i++) { /* a front point's label at the first of six places beside it that is free and in the plot, else left out */
        static const double dx[6] = {8, 8, -8, -8, 0, 0}, dy[6] = {-4, 10, -4, 10, -9, 16}; /* clear of the point itself */
        static const int anchor[6] = {-1, -1, 1, 1, 0, 0};
        const report_plot_point *q = &p->points[i];
        char attrs[64];
        if (!q->front || !q->label || !(q->ms > 0) || !isfinite(q->ms) || !(q->error >= 0) || !isfinite(q->error)) continue;
        snprintf(attrs, sizeof attrs, " class=\"point-label\" fill=\"%s\"", PLOT_COLOUR(q->series));
        for (k = 0; k < 6; k++) {
            double x = RX(q->ms) + dx[k], y = RY(q->error) + dy[k];
            report_box b = report_text_box(x, y, q->label, 9, anchor[k]);
            if (b.x0 < L || b.x1 > W - R || b.y0 < T || b.y1 > H - B) continue;
            if (plot_text(f, &pl, x, y, q->label, 9, anchor[k], attrs, 0)) break;
        }
    }
    for (i = 0; i < p->count; i++) {
        const report_plot_point *q = &p->points[i];
        if (!(q->ms > 0) || !isfinite(q->ms) || !(q->error >= 0) || !isfinite(q->error)) continue;
        fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%d\" fill=\"%s\" fill-opacity=\"%s\" stroke=\"%s\"/>\n", RX(q->ms), RY(q->error), q->front ? 4 : 3,
                q->front ? PLOT_COLOUR(q->series) : "white", q->front ? "1" : "0", PLOT_COLOUR(q->series));
    }
    for (c = 0; c < p->series_count; c++) {
        fprintf(f, "<circle cx=\"%.0f\" cy=\"%.0f\" r=\"4\" fill=\"%s\"/>\n", L + 5, H + 5 + legend_line * c, PLOT_COLOUR(c));
        plot_text(f, &pl, L + 15, H + 9 + legend_line * c, p->legend[c], 11, -1, "", 1);
    }
    fprintf(f, "</svg>\n");
    free(pl.box);
#undef RX
#undef RY
}
