/* tools/cli_report.c - what the reports share: the plot of error against time (SVG) and the
 * picture of an image beside its reference with the error's heat map (PNG). */
#include "report.h"
#include "image_io.h"
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

/* ------------------------------------------------------------------ the plot */
static const char *const plot_colours[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b",
                                           "#e377c2", "#17becf", "#bcbd22", "#7f7f7f", "#393b79", "#637939"};
#define PLOT_COLOUR(series) plot_colours[(series) % CLI_COUNT(plot_colours)]

void report_plot_svg(FILE *f, const report_plot *p)
{
    const double W = 740, H = 480, L = 70, R = 40, T = 20, B = 50, legend_line = 15;
    const double height = H + legend_line * p->series_count + 10;
    double tmin = HUGE_VAL, tmax = 0, emin = HUGE_VAL, emax = 0;
    int zero = 0, k, c;
    size_t i, j;
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
    for (k = (int)floor(log10(tmin) + 0.5); k <= (int)floor(log10(tmax) + 0.5); k++)
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.0f\" x2=\"%.1f\" y2=\"%.0f\" stroke=\"#ddd\"/><text x=\"%.1f\" y=\"%.0f\" text-anchor=\"middle\">%g ms</text>\n",
                RX(pow(10, k)), T, RX(pow(10, k)), H - B, RX(pow(10, k)), H - B + 15, pow(10, k));
    for (k = (int)floor(log10(emin) + 0.5); k <= (int)floor(log10(emax) + 0.5); k++) {
        fprintf(f, "<line x1=\"%.0f\" y1=\"%.1f\" x2=\"%.0f\" y2=\"%.1f\" stroke=\"#ddd\"/><text x=\"%.0f\" y=\"%.1f\" text-anchor=\"end\">", L,
                RY(pow(10, k)), W - R, RY(pow(10, k)), L - 5, RY(pow(10, k)) + 4);
        if (zero && k == (int)floor(log10(emin) + 0.5)) fprintf(f, "0 (exact)</text>\n");
        else fprintf(f, "%g%%</text>\n", 100 * pow(10, k));
    }
    fprintf(f, "<text x=\"%.0f\" y=\"%.0f\" text-anchor=\"middle\">%s</text>\n", (L + W - R) / 2, H - 12, p->x_title);
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
        if (q->label)
            fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" fill=\"%s\" font-size=\"9\">%s</text>\n", RX(q->ms) + 4, RY(q->error) - 4, PLOT_COLOUR(q->series), q->label);
    }
    for (i = 0; i < p->count; i++) {
        const report_plot_point *q = &p->points[i];
        if (!(q->ms > 0) || !isfinite(q->ms) || !(q->error >= 0) || !isfinite(q->error)) continue;
        fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%d\" fill=\"%s\" fill-opacity=\"%s\" stroke=\"%s\"/>\n", RX(q->ms), RY(q->error), q->front ? 4 : 3,
                q->front ? PLOT_COLOUR(q->series) : "white", q->front ? "1" : "0", PLOT_COLOUR(q->series));
    }
    for (c = 0; c < p->series_count; c++)
        fprintf(f, "<circle cx=\"%.0f\" cy=\"%.0f\" r=\"4\" fill=\"%s\"/><text x=\"%.0f\" y=\"%.0f\">%s</text>\n", L + 5, H + 5 + legend_line * c,
                PLOT_COLOUR(c), L + 15, H + 9 + legend_line * c, p->legend[c]);
    fprintf(f, "</svg>\n");
#undef RX
#undef RY
}

/* ------------------------------------------------------------------ pictures */
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

/* An sRGB-encoded value as the linear one vxt_write_png encodes back to it. */
static float srgb_to_linear(double c) { return (float)(c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4)); }

int report_png_compare(const char *path, const float *img, const float *ref, const cli_error_mask *m, float exposure)
{
    const int w = m->width, h = m->height, gap = 4, cw = 3 * w + 2 * gap;
    float *out = (float *)malloc((size_t)cw * (size_t)h * 12);
    double mean = 0;
    size_t kept = 0, p;
    int x, y, c, rc;
    if (!out) return -1;
    for (p = 0; p < (size_t)w * (size_t)h; p++)
        if (!m->masked[p]) {
            mean += ((double)ref[3 * p] + ref[3 * p + 1] + ref[3 * p + 2]) / 3;
            kept++;
        }
    mean = kept ? mean / (double)kept : 0;
    for (y = 0; y < h; y++)
        for (x = 0; x < cw; x++) {
            float *o = out + 3 * ((size_t)y * (size_t)cw + (size_t)x);
            int panel = x / (w + gap), px = x % (w + gap);
            size_t at = (size_t)y * (size_t)w + (size_t)px;
            if (px >= w) { /* the gap */
                o[0] = o[1] = o[2] = 1;
                continue;
            }
            if (panel < 2) {
                for (c = 0; c < 3; c++) o[c] = exposure * (panel ? ref : img)[3 * at + (size_t)c];
                continue;
            }
            if (m->masked[at]) {
                o[0] = o[1] = o[2] = srgb_to_linear(0.5);
                continue;
            }
            {
                double d2 = 0, t;
                for (c = 0; c < 3; c++) d2 += ((double)img[3 * at + (size_t)c] - ref[3 * at + (size_t)c]) * ((double)img[3 * at + (size_t)c] - ref[3 * at + (size_t)c]);
                t = mean > 0 ? sqrt(d2 / 3) / mean / REPORT_HEAT_WHITE : (d2 > 0);
                t = t < 1 ? t : 1; /* black, red, yellow, white in thirds */
                o[0] = srgb_to_linear(fmin(1, 3 * t));
                o[1] = srgb_to_linear(fmin(1, fmax(0, 3 * t - 1)));
                o[2] = srgb_to_linear(fmax(0, 3 * t - 2));
            }
        }
    rc = vxt_write_png(path, out, cw, h, 1);
    free(out);
    return rc;
}
