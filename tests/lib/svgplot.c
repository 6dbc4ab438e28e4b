/*
 * svgplot.c - see svgplot.h.
 *
 * Layout: a title on top, the plot area with its axes, tick labels and axis
 * labels, and the legend to the right of the plot area.  Coordinates are
 * computed in "axis space" (the value on a linear axis, log10 of it on a
 * log axis) and mapped linearly to pixels; SVG's y grows downwards.
 */
#include "svgplot.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "atomic_file.h"

const char *const svgplot_palette[SVGPLOT_N_COLOURS] = {
    "#0072B2", /* blue */
    "#D55E00", /* vermillion */
    "#009E73", /* bluish green */
    "#CC79A7", /* reddish purple */
    "#E69F00", /* orange */
    "#56B4E9", /* sky blue */
    "#000000", /* black */
    "#F0E442", /* yellow */
};

/* Margins around the plot area, in pixels. */
#define MARGIN_LEFT 80
#define MARGIN_TOP 40
#define MARGIN_BOTTOM 56
#define MARGIN_RIGHT_MIN 20
#define LEGEND_CHAR_WIDTH 7 /* rough width of a 12 px sans-serif character */
#define LEGEND_ROW 18
#define MARKER_SIZE 4.0
#define TICK_LENGTH 6
#define MAX_TICKS 128

/* The plot area in pixels and the axis ranges in axis space. */
struct frame {
    double left, top, width, height;
    double u_lo, u_hi; /* x axis */
    double w_lo, w_hi; /* y axis */
    enum svgplot_scale xs, ys;
    double x_lo, x_hi, y_lo, y_hi; /* the same ranges in data units */
};

static bool
drawable(double v, enum svgplot_scale scale)
{
    return isfinite(v) && (scale == SVGPLOT_LINEAR || v > 0);
}

static double
to_axis(double v, enum svgplot_scale scale)
{
    return scale == SVGPLOT_LOG10 ? log10(v) : v;
}

static double
pixel_x(const struct frame *fr, double u)
{
    return fr->left + (u - fr->u_lo) / (fr->u_hi - fr->u_lo) * fr->width;
}

static double
pixel_y(const struct frame *fr, double w)
{
    return fr->top + (fr->w_hi - w) / (fr->w_hi - fr->w_lo) * fr->height;
}

/* ---- text --------------------------------------------------------------- */

/* Length of the valid UTF-8 sequence at s (1 to 4), or 0 if it is not one
 * (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF). */
static int
utf8_length(const unsigned char *s)
{
    unsigned char c = s[0];
    if (c < 0x80) {
        return 1;
    }
    int len = c >= 0xC2 && c <= 0xDF   ? 2
              : c >= 0xE0 && c <= 0xEF ? 3
              : c >= 0xF0 && c <= 0xF4 ? 4
                                       : 0;
    unsigned char lo = c == 0xE0 ? 0xA0 : c == 0xF0 ? 0x90 : 0x80;
    unsigned char hi = c == 0xED ? 0x9F : c == 0xF4 ? 0x8F : 0xBF;
    for (int i = 1; i < len; i++) {
        unsigned char min = i == 1 ? lo : 0x80;
        unsigned char max = i == 1 ? hi : 0xBF;
        if (s[i] < min || s[i] > max) {
            return 0;
        }
    }
    return len;
}

/* XML's predefined entity for c, or NULL when c stands for itself. */
static const char *
entity(unsigned char c)
{
    switch (c) {
    case '&':
        return "&amp;";
    case '<':
        return "&lt;";
    case '>':
        return "&gt;";
    case '"':
        return "&quot;";
    case '\'':
        return "&apos;";
    default:
        return NULL;
    }
}

/* Escape at most max_chars characters of s; true if s was longer. */
static bool
escape_n(FILE *f, const char *s, size_t max_chars)
{
    const unsigned char *p = (const unsigned char *)(s ? s : "");
    for (size_t n = 0; *p; n++) {
        int len = utf8_length(p);
        if (n == max_chars) {
            return true;
        }
        if (len == 0) {
            fputc('?', f);
            p++;
            continue;
        }
        const char *ref = entity(*p);
        if (ref) {
            fputs(ref, f);
        } else if (*p >= 0x20 || *p == '\t' || *p == '\n') {
            /* XML 1.0 forbids other control characters, even as references. */
            fwrite(p, 1, (size_t)len, f);
        }
        p += len;
    }
    return false;
}

void
svgplot_escape(FILE *f, const char *s)
{
    escape_n(f, s, SIZE_MAX);
}

/* Characters of a label (UTF-8 sequences count once), for the legend width. */
static size_t
text_length(const char *s)
{
    size_t n = 0;
    for (const unsigned char *p = (const unsigned char *)s; p && *p; p++) {
        n += (*p & 0xC0) != 0x80;
    }
    return n;
}

/* ---- axes and ticks ------------------------------------------------------ */

/* 1, 2 or 5 times a power of ten, giving about five intervals over span. */
static double
nice_step(double span)
{
    double raw = span / 5;
    double mag = pow(10, floor(log10(raw)));
    double f = raw / mag;
    double nice = f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10;
    return nice * mag;
}

/* m * 10^e as the nearest double, through the decimal string: pow() may be
 * one ULP off, strtod is correctly rounded, so a tick is exactly "1e-3". */
static double
decimal(int m, int e)
{
    char buf[32];
    snprintf(buf, sizeof buf, "%de%d", m, e);
    return strtod(buf, NULL);
}

void
svgplot_axis_range(double lo, double hi, enum svgplot_scale scale, double *out_lo, double *out_hi)
{
    if (scale == SVGPLOT_LOG10) {
        /* The slack forgives log10 rounding at an exact decade. */
        int e_lo = (int)floor(log10(lo) + 1e-9);
        int e_hi = (int)ceil(log10(hi) - 1e-9);
        if (e_hi <= e_lo) {
            e_hi = e_lo + 1;
        }
        *out_lo = decimal(1, e_lo);
        *out_hi = decimal(1, e_hi);
        return;
    }
    if (hi <= lo) {
        double pad = lo == 0 ? 1 : 0.1 * fabs(lo);
        lo -= pad;
        hi += pad;
    }
    /* Widening can call for a coarser step (0.13..0.87 widens to 0.1..0.9
     * at step 0.1, whose span asks for 0.2): repeat until the step of the
     * widened range is the step that widened it, so svgplot_ticks puts a
     * tick on both ends.  The step only grows, so this ends quickly. */
    double step = nice_step(hi - lo);
    for (int i = 0; i < 8; i++) {
        *out_lo = floor(lo / step + 1e-9) * step;
        *out_hi = ceil(hi / step - 1e-9) * step;
        double next = nice_step(*out_hi - *out_lo);
        if (next <= step * (1 + 1e-9)) {
            break;
        }
        step = next;
    }
}

static size_t
linear_ticks(double lo, double hi, struct svgplot_tick *out, size_t cap)
{
    double step = nice_step(hi - lo);
    double k_lo = ceil(lo / step - 1e-9);
    double k_hi = floor(hi / step + 1e-9);
    size_t n = 0;
    for (double k = k_lo; k <= k_hi && n < MAX_TICKS * 4; k++) {
        double v = k * step;
        if (n < cap) {
            out[n] = (struct svgplot_tick){fabs(v) < 1e-9 * step ? 0 : v, true};
        }
        n++;
    }
    return n;
}

static size_t
log_ticks(double lo, double hi, struct svgplot_tick *out, size_t cap)
{
    int e_lo = (int)ceil(log10(lo) - 1e-9);
    int e_hi = (int)floor(log10(hi) + 1e-9);
    int decades = e_hi - e_lo;
    int every = decades <= 10 ? 1 : (decades + 7) / 8;
    bool minor = every == 1 && decades <= 8;
    size_t n = 0;
    for (int e = e_lo; e <= e_hi; e++) {
        if (e % every == 0) {
            if (n < cap) {
                out[n] = (struct svgplot_tick){decimal(1, e), true};
            }
            n++;
        }
        for (int m = 2; minor && e < e_hi && m <= 9; m++) {
            if (n < cap) {
                out[n] = (struct svgplot_tick){decimal(m, e), false};
            }
            n++;
        }
    }
    return n;
}

size_t
svgplot_ticks(double lo, double hi, enum svgplot_scale scale, struct svgplot_tick *out, size_t cap)
{
    if (!(isfinite(lo) && isfinite(hi) && hi > lo) || (scale == SVGPLOT_LOG10 && !(lo > 0))) {
        return 0;
    }
    return scale == SVGPLOT_LOG10 ? log_ticks(lo, hi, out, cap) : linear_ticks(lo, hi, out, cap);
}

/* Data range of every drawable point of every series, per axis. */
static bool
data_range(const struct svgplot *plot, double *x_lo, double *x_hi, double *y_lo, double *y_hi)
{
    bool any = false;
    *x_lo = *y_lo = INFINITY;
    *x_hi = *y_hi = -INFINITY;
    for (size_t i = 0; i < plot->n_series; i++) {
        const struct svgplot_series *s = &plot->series[i];
        for (size_t j = 0; j < s->n; j++) {
            if (drawable(s->x[j], plot->x_scale) && drawable(s->y[j], plot->y_scale)) {
                *x_lo = fmin(*x_lo, s->x[j]);
                *x_hi = fmax(*x_hi, s->x[j]);
                *y_lo = fmin(*y_lo, s->y[j]);
                *y_hi = fmax(*y_hi, s->y[j]);
                any = true;
            }
        }
    }
    return any;
}

/* Width of the legend column: the longest label, within limits. */
static double
legend_width(const struct svgplot *plot)
{
    size_t longest = 0;
    bool any = false;
    for (size_t i = 0; i < plot->n_series; i++) {
        const char *label = plot->series[i].label;
        any = any || label;
        longest = label && text_length(label) > longest ? text_length(label) : longest;
    }
    for (size_t i = 0; i < plot->n_reflines; i++) {
        const char *label = plot->reflines[i].label;
        any = any || label;
        longest = label && text_length(label) > longest ? text_length(label) : longest;
    }
    double w = 50 + LEGEND_CHAR_WIDTH * (double)longest;
    return any ? fmin(w, 320) : MARGIN_RIGHT_MIN;
}

static struct frame
layout(const struct svgplot *plot, double width, double height)
{
    struct frame fr = {.xs = plot->x_scale, .ys = plot->y_scale};
    double x_lo, x_hi, y_lo, y_hi;
    if (!data_range(plot, &x_lo, &x_hi, &y_lo, &y_hi)) {
        x_lo = y_lo = 1;
        x_hi = y_hi = 10;
    }
    svgplot_axis_range(x_lo, x_hi, fr.xs, &fr.x_lo, &fr.x_hi);
    svgplot_axis_range(y_lo, y_hi, fr.ys, &fr.y_lo, &fr.y_hi);
    fr.u_lo = to_axis(fr.x_lo, fr.xs);
    fr.u_hi = to_axis(fr.x_hi, fr.xs);
    fr.w_lo = to_axis(fr.y_lo, fr.ys);
    fr.w_hi = to_axis(fr.y_hi, fr.ys);
    fr.left = MARGIN_LEFT;
    fr.top = MARGIN_TOP;
    fr.width = fmax(width - MARGIN_LEFT - legend_width(plot), 40);
    fr.height = fmax(height - MARGIN_TOP - MARGIN_BOTTOM, 40);
    return fr;
}

/* A tick label: on a log axis 10^e (plain decimals between 0.001 and
 * 10000); on a linear axis as many decimals as the step needs. */
static void
write_tick_label(FILE *f, double v, enum svgplot_scale scale, double step)
{
    if (scale == SVGPLOT_LOG10) {
        int e = (int)lround(log10(v));
        if (e >= -3 && e <= 4) {
            fprintf(f, "%g", v);
        } else {
            fprintf(f, "10<tspan dy=\"-6\" font-size=\"9\">%d</tspan>", e);
        }
        return;
    }
    int decimals = step < 1 ? (int)ceil(-log10(step) - 1e-9) : 0;
    if (fabs(v) >= 1e7 || decimals > 6) {
        fprintf(f, "%g", v);
    } else {
        fprintf(f, "%.*f", decimals, v);
    }
}

/* A line between two points of the SVG. */
static void
write_line(FILE *f, const char *class, double x1, double y1, double x2, double y2)
{
    fprintf(
        f,
        "<line class=\"%s\" x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/>\n",
        class,
        x1,
        y1,
        x2,
        y2);
}

/* The ticks of one axis, the horizontal one (x_axis: marks and labels
 * below the frame) or the vertical one (left of it): at a major tick a
 * grid line across the frame and a label, at every tick a mark outward
 * (half as long at a minor one). */
static void
write_ticks(FILE *f, const struct frame *fr, bool x_axis)
{
    enum svgplot_scale scale = x_axis ? fr->xs : fr->ys;
    struct svgplot_tick ticks[MAX_TICKS];
    size_t n = x_axis ? svgplot_ticks(fr->x_lo, fr->x_hi, scale, ticks, MAX_TICKS)
                      : svgplot_ticks(fr->y_lo, fr->y_hi, scale, ticks, MAX_TICKS);
    n = n < MAX_TICKS ? n : MAX_TICKS;
    double step = n > 1 ? ticks[1].value - ticks[0].value : 1;
    double bottom = fr->top + fr->height;
    double right = fr->left + fr->width;
    for (size_t i = 0; i < n; i++) {
        double at = to_axis(ticks[i].value, scale);
        double p = x_axis ? pixel_x(fr, at) : pixel_y(fr, at);
        double len = ticks[i].major ? TICK_LENGTH : TICK_LENGTH / 2.0;
        if (ticks[i].major) {
            if (x_axis) {
                write_line(f, "grid", p, fr->top, p, bottom);
            } else {
                write_line(f, "grid", fr->left, p, right, p);
            }
            fprintf(
                f,
                "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"%s\">",
                x_axis ? p : fr->left - TICK_LENGTH - 4,
                x_axis ? bottom + TICK_LENGTH + 14 : p + 4,
                x_axis ? "middle" : "end");
            write_tick_label(f, ticks[i].value, scale, step);
            fputs("</text>\n", f);
        }
        if (x_axis) {
            write_line(f, "tick", p, bottom, p, bottom + len);
        } else {
            write_line(f, "tick", fr->left - len, p, fr->left, p);
        }
    }
}

/* A text element with escaped content; extra holds further attributes. */
static void
write_text(FILE *f, double x, double y, const char *extra, const char *text)
{
    fprintf(f, "<text x=\"%.2f\" y=\"%.2f\" %s>", x, y, extra);
    svgplot_escape(f, text);
    fputs("</text>\n", f);
}

static void
write_axes(FILE *f, const struct svgplot *plot, const struct frame *fr, double width)
{
    fputs("<g class=\"axes\">\n", f);
    write_ticks(f, fr, true);
    write_ticks(f, fr, false);
    fprintf(
        f,
        "<rect class=\"frame\" x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\"/>\n",
        fr->left,
        fr->top,
        fr->width,
        fr->height);
    if (plot->title) {
        write_text(
            f,
            width / 2,
            MARGIN_TOP / 2.0 + 5,
            "text-anchor=\"middle\" font-size=\"15\"",
            plot->title);
    }
    if (plot->x_label) {
        double y = fr->top + fr->height + MARGIN_BOTTOM - 12;
        write_text(f, fr->left + fr->width / 2, y, "text-anchor=\"middle\"", plot->x_label);
    }
    if (plot->y_label) {
        double x = 18;
        double y = fr->top + fr->height / 2;
        fprintf(
            f,
            "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\""
            " transform=\"rotate(-90 %.2f %.2f)\">",
            x,
            y,
            x,
            y);
        svgplot_escape(f, plot->y_label);
        fputs("</text>\n", f);
    }
    fputs("</g>\n", f);
}

/* ---- series ----------------------------------------------------------- */

static enum svgplot_marker
series_marker(const struct svgplot_series *s, size_t index)
{
    static const enum svgplot_marker cycle[] = {
        SVGPLOT_MARKER_CIRCLE,
        SVGPLOT_MARKER_SQUARE,
        SVGPLOT_MARKER_TRIANGLE,
        SVGPLOT_MARKER_DIAMOND,
        SVGPLOT_MARKER_CROSS,
        SVGPLOT_MARKER_PLUS,
    };

    return s->marker == SVGPLOT_MARKER_AUTO ? cycle[index % 6] : s->marker;
}

static const char *
series_colour(const struct svgplot_series *s, size_t index)
{
    size_t c = s->colour != SVGPLOT_COLOUR_AUTO ? (size_t)s->colour - 1 : index;
    return svgplot_palette[c % SVGPLOT_N_COLOURS];
}

/* A marker drawn as a path: the points are offsets from the centre in units
 * of MARKER_SIZE; filled polygons are closed, stroked ones are pairs of
 * segments (cross and plus). */
static void
write_shape(FILE *f, const double *pts, int n, bool filled, double x, double y, const char *colour)
{
    fputs("<path d=\"", f);
    for (int i = 0; i < n; i++) {
        char op = filled ? (i == 0 ? 'M' : 'L') : (i % 2 == 0 ? 'M' : 'L');
        fprintf(
            f,
            "%c%.2f %.2f",
            op,
            x + pts[2 * i] * MARKER_SIZE,
            y + pts[2 * i + 1] * MARKER_SIZE);
    }
    if (filled) {
        fprintf(f, "Z\" fill=\"%s\"/>\n", colour);
    } else {
        fprintf(f, "\" fill=\"none\" stroke=\"%s\" stroke-width=\"2\"/>\n", colour);
    }
}

/* One marker centred on (x, y). */
static void
write_marker(FILE *f, enum svgplot_marker m, double x, double y, const char *colour)
{
    static const double square[] = {-1, -1, 1, -1, 1, 1, -1, 1};
    static const double triangle[] = {0, -1.2, 1.1, 0.8, -1.1, 0.8};
    static const double diamond[] = {0, -1.3, 1, 0, 0, 1.3, -1, 0};
    static const double cross[] = {-1, -1, 1, 1, -1, 1, 1, -1};
    static const double plus[] = {-1.2, 0, 1.2, 0, 0, -1.2, 0, 1.2};
    switch (m) {
    case SVGPLOT_MARKER_CIRCLE:
        fprintf(
            f,
            "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"%s\"/>\n",
            x,
            y,
            MARKER_SIZE,
            colour);
        break;
    case SVGPLOT_MARKER_SQUARE:
        write_shape(f, square, 4, true, x, y, colour);
        break;
    case SVGPLOT_MARKER_TRIANGLE:
        write_shape(f, triangle, 3, true, x, y, colour);
        break;
    case SVGPLOT_MARKER_DIAMOND:
        write_shape(f, diamond, 4, true, x, y, colour);
        break;
    case SVGPLOT_MARKER_CROSS:
        write_shape(f, cross, 4, false, x, y, colour);
        break;
    case SVGPLOT_MARKER_PLUS:
        write_shape(f, plus, 4, false, x, y, colour);
        break;
    default:
        break;
    }
}

/* The series' line as polylines broken at points that cannot be drawn. */
static void
write_lines(FILE *f, const struct frame *fr, const struct svgplot_series *s, const char *colour)
{
    bool open = false;
    for (size_t j = 0; j <= s->n; j++) {
        bool ok = j < s->n && drawable(s->x[j], fr->xs) && drawable(s->y[j], fr->ys);
        if (!ok && open) {
            fputs("\"/>\n", f);
            open = false;
        }
        if (!ok) {
            continue;
        }
        if (!open) {
            fprintf(
                f,
                "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"%s\""
                " stroke-linejoin=\"round\" points=\"",
                colour,
                s->highlight ? "3.5" : "1.5");
            open = true;
        }
        double x = pixel_x(fr, to_axis(s->x[j], fr->xs));
        double y = pixel_y(fr, to_axis(s->y[j], fr->ys));
        fprintf(f, "%.2f,%.2f ", x, y);
    }
}

static void
write_series(FILE *f, const struct frame *fr, const struct svgplot_series *s, size_t index)
{
    const char *colour = series_colour(s, index);
    enum svgplot_marker marker = series_marker(s, index);
    fputs("<g class=\"series\">\n", f);
    if (!s->no_line) {
        write_lines(f, fr, s, colour);
    }
    for (size_t j = 0; j < s->n; j++) {
        if (!drawable(s->x[j], fr->xs) || !drawable(s->y[j], fr->ys)) {
            continue;
        }
        double x = pixel_x(fr, to_axis(s->x[j], fr->xs));
        double y = pixel_y(fr, to_axis(s->y[j], fr->ys));
        write_marker(f, marker, x, y, colour);
        if (s->flag && s->flag[j]) {
            fprintf(
                f,
                "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\""
                " fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\"/>\n",
                x,
                y,
                2 * MARKER_SIZE,
                colour);
        }
    }
    fputs("</g>\n", f);
}

/* ---- reference lines --------------------------------------------------- */

/* The reference line across the x range, cut to the y range (in axis
 * space, where it is straight); false when none of it is inside. */
static bool
clip_refline(const struct frame *fr, const struct svgplot_refline *r, double seg[4])
{
    double u0 = to_axis(r->x0, fr->xs);
    double w0 = to_axis(r->y0, fr->ys);
    double ua = fr->u_lo;
    double ub = fr->u_hi;
    if (r->slope != 0) {
        /* u where the line crosses w_lo and w_hi. */
        double c1 = u0 + (fr->w_lo - w0) / r->slope;
        double c2 = u0 + (fr->w_hi - w0) / r->slope;
        ua = fmax(ua, fmin(c1, c2));
        ub = fmin(ub, fmax(c1, c2));
    } else if (w0 < fr->w_lo || w0 > fr->w_hi) {
        return false;
    }
    if (!(ua < ub)) {
        return false;
    }
    seg[0] = ua;
    seg[1] = w0 + r->slope * (ua - u0);
    seg[2] = ub;
    seg[3] = w0 + r->slope * (ub - u0);
    return true;
}

static void
write_reflines(FILE *f, const struct svgplot *plot, const struct frame *fr)
{
    for (size_t i = 0; i < plot->n_reflines; i++) {
        const struct svgplot_refline *r = &plot->reflines[i];
        double seg[4];
        if (!drawable(r->x0, fr->xs) || !drawable(r->y0, fr->ys) || !isfinite(r->slope)
            || !clip_refline(fr, r, seg)) {
            continue;
        }
        write_line(
            f,
            "refline",
            pixel_x(fr, seg[0]),
            pixel_y(fr, seg[1]),
            pixel_x(fr, seg[2]),
            pixel_y(fr, seg[3]));
    }
}

/* ---- legend ------------------------------------------------------------ */

/* One legend row: the series' line and marker, or (s NULL) a dashed
 * reference line; the label cut to max_chars characters. */
static void
write_legend_row(
    FILE *f,
    double x,
    double y,
    const struct svgplot_series *s,
    size_t index,
    const char *label,
    size_t max_chars)
{
    const char *colour = s ? series_colour(s, index) : "";
    if (!s) {
        write_line(f, "refline", x, y, x + 24, y);
    } else if (!s->no_line) {
        fprintf(
            f,
            "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\""
            " stroke=\"%s\" stroke-width=\"%s\"/>\n",
            x,
            y,
            x + 24,
            y,
            colour,
            s->highlight ? "3.5" : "1.5");
    }
    if (s) {
        write_marker(f, series_marker(s, index), x + 12, y, colour);
    }
    fprintf(f, "<text x=\"%.2f\" y=\"%.2f\">", x + 30, y + 4);
    if (escape_n(f, label, max_chars)) {
        fputs("\xe2\x80\xa6", f); /* an ellipsis */
    }
    fputs("</text>\n", f);
}

/* The legend right of the plot: one row per labelled series, then per
 * labelled reference line; rows that do not fit are counted instead. */
static void
write_legend(FILE *f, const struct svgplot *plot, const struct frame *fr)
{
    size_t rows = 0;
    for (size_t i = 0; i < plot->n_series + plot->n_reflines; i++) {
        rows +=
            (i < plot->n_series ? plot->series[i].label : plot->reflines[i - plot->n_series].label)
            != NULL;
    }
    size_t fit = (size_t)fmax(2, floor((fr->height + MARGIN_BOTTOM / 2.0) / LEGEND_ROW));
    size_t shown = rows <= fit ? rows : fit - 1;
    size_t max_chars = (size_t)((legend_width(plot) - 50) / LEGEND_CHAR_WIDTH);
    double x = fr->left + fr->width + 14;
    double y = fr->top + 10;
    fputs("<g class=\"legend\">\n", f);
    for (size_t i = 0, row = 0; i < plot->n_series + plot->n_reflines && row < shown; i++) {
        bool is_series = i < plot->n_series;
        const struct svgplot_series *s = is_series ? &plot->series[i] : NULL;
        const char *label = is_series ? s->label : plot->reflines[i - plot->n_series].label;
        if (label) {
            write_legend_row(f, x, y + LEGEND_ROW * (double)row++, s, i, label, max_chars);
        }
    }
    if (shown < rows) {
        fprintf(
            f,
            "<text x=\"%.2f\" y=\"%.2f\">\xe2\x80\xa6 and %zu more</text>\n",
            x,
            y + LEGEND_ROW * (double)shown + 4,
            rows - shown);
    }
    fputs("</g>\n", f);
}

/* ---- the document ------------------------------------------------------- */

static void
write_header(FILE *f, const struct svgplot *plot, int width, int height)
{
    fputs("<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n", f);
    fputs(
        "<!DOCTYPE svg PUBLIC \"-//W3C//DTD SVG 1.1//EN\"\n"
        "  \"http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd\">\n",
        f);
    fprintf(
        f,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"%d\" height=\"%d\""
        " viewBox=\"0 0 %d %d\" font-family=\"sans-serif\" font-size=\"12\">\n",
        width,
        height,
        width,
        height);
    fputs("<title>", f);
    svgplot_escape(f, plot->title ? plot->title : "plot");
    fputs("</title>\n", f);
    fputs(
        "<style type=\"text/css\"><![CDATA[\n"
        ".grid { stroke: #dddddd; stroke-width: 1; }\n"
        ".tick { stroke: #000000; stroke-width: 1; }\n"
        ".frame { fill: none; stroke: #000000; stroke-width: 1; }\n"
        ".refline { stroke: #555555; stroke-width: 1.5; stroke-dasharray: 6 4; }\n"
        "]]></style>\n",
        f);
    fprintf(
        f,
        "<rect x=\"0\" y=\"0\" width=\"%d\" height=\"%d\" fill=\"#ffffff\"/>\n",
        width,
        height);
}

bool
svgplot_fprint(const struct svgplot *plot, FILE *f, struct diag *err)
{
    int width = plot->width > 0 ? plot->width : 720;
    int height = plot->height > 0 ? plot->height : 480;
    struct frame fr = layout(plot, width, height);
    write_header(f, plot, width, height);
    write_axes(f, plot, &fr, width);
    write_reflines(f, plot, &fr);
    /* Highlighted series (a Pareto front) last, so they are drawn on top. */
    for (int pass = 0; pass < 2; pass++) {
        for (size_t i = 0; i < plot->n_series; i++) {
            if (plot->series[i].highlight == (pass == 1)) {
                write_series(f, &fr, &plot->series[i], i);
            }
        }
    }
    write_legend(f, plot, &fr);
    fputs("</svg>\n", f);
    if (ferror(f)) {
        diag_set(err, NULL, 0, 0, "write error");
        return false;
    }
    return true;
}

bool
svgplot_write(const struct svgplot *plot, const char *path, struct diag *err)
{
    struct atomic_file af;
    if (!atomic_file_open(&af, path, err)) {
        return false;
    }
    if (!svgplot_fprint(plot, af.f, err)) {
        diag_set(err, path, 0, 0, "cannot write: write error");
        atomic_file_abort(&af);
        return false;
    }
    return atomic_file_commit(&af, err);
}

/* ---- Pareto front -------------------------------------------------------- */

/* Does point j knock point i off the front?  Yes when it dominates i, or
 * when it is the same point and comes first. */
static bool
beaten(const double *cost, const double *error, size_t i, size_t j)
{
    if (!isfinite(cost[j]) || !isfinite(error[j]) || j == i) {
        return false;
    }
    bool no_worse = cost[j] <= cost[i] && error[j] <= error[i];
    bool better = cost[j] < cost[i] || error[j] < error[i];
    return no_worse && (better || j < i);
}

size_t
svgplot_pareto_front(const double *cost, const double *error, size_t n, size_t *out_idx)
{
    size_t count = 0;
    for (size_t i = 0; i < n; i++) {
        bool on_front = isfinite(cost[i]) && isfinite(error[i]);
        for (size_t j = 0; j < n && on_front; j++) {
            on_front = !beaten(cost, error, i, j);
        }
        if (!on_front) {
            continue;
        }
        /* Insertion by cost: the front is short. */
        size_t k = count++;
        while (k > 0 && cost[out_idx[k - 1]] > cost[i]) {
            out_idx[k] = out_idx[k - 1];
            k--;
        }
        out_idx[k] = i;
    }
    return count;
}
