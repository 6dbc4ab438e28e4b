/*
 * svgplot.h - small line/scatter plots written as standalone SVG 1.1 files,
 * for the speed-versus-accuracy charts (error against seconds, error
 * against samples per pixel), with no plotting library.
 *
 * The caller describes a plot in plain structs and calls svgplot_write():
 *
 *     double spp[] = {1, 4, 16}, err[] = {0.3, 0.08, 0.02};
 *     struct svgplot_series s = {.label = "07_path", .x = spp, .y = err, .n = 3};
 *     struct svgplot_refline ref = {.slope = -1, .x0 = 1, .y0 = 0.3, .label = "1/spp"};
 *     struct svgplot plot = {.title = "relMSE vs spp", .x_label = "spp",
 *                            .y_label = "relMSE", .x_scale = SVGPLOT_LOG10,
 *                            .y_scale = SVGPLOT_LOG10, .series = &s, .n_series = 1,
 *                            .reflines = &ref, .n_reflines = 1};
 *     if (!svgplot_write(&plot, "docs/trade/spp.svg", &err)) ...
 *
 * Fields left zero take defaults: automatic colour and marker (by series
 * index), lines drawn, linear axes, 720 x 480 pixels, no title.
 *
 * Axes: linear axes get "nice" ticks (1, 2 or 5 times a power of ten) and
 * a range widened to whole ticks; log10 axes get a tick at every decade
 * (every few decades over a wide range) and minor ticks at 2..9 times each
 * decade, over a range widened to whole decades.  Points that cannot be
 * drawn (non-finite, or <= 0 on a log axis) are skipped, and a series'
 * line is broken there.  Points are joined in the order given.
 *
 * All text is XML-escaped (and invalid UTF-8 replaced), so labels may hold
 * any bytes.  Files are written through atomic_file: never half-written.
 */
#ifndef SVGPLOT_H
#define SVGPLOT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "diag.h"

enum svgplot_scale {
    SVGPLOT_LINEAR,
    SVGPLOT_LOG10,
};

enum svgplot_marker {
    SVGPLOT_MARKER_AUTO, /* by series index, cycling through the shapes */
    SVGPLOT_MARKER_NONE,
    SVGPLOT_MARKER_CIRCLE,
    SVGPLOT_MARKER_SQUARE,
    SVGPLOT_MARKER_TRIANGLE,
    SVGPLOT_MARKER_DIAMOND,
    SVGPLOT_MARKER_CROSS,
    SVGPLOT_MARKER_PLUS,
};

/* Colours: the Okabe-Ito palette (Okabe & Ito, "Color Universal Design",
 * 2008), distinguishable with every common colour-vision deficiency; yellow
 * comes last because it is faint on white.  AUTO (the zero value) takes
 * the palette in order by series index. */
enum svgplot_colour {
    SVGPLOT_COLOUR_AUTO,
    SVGPLOT_BLUE,
    SVGPLOT_VERMILLION,
    SVGPLOT_GREEN,
    SVGPLOT_PURPLE,
    SVGPLOT_ORANGE,
    SVGPLOT_SKY_BLUE,
    SVGPLOT_BLACK,
    SVGPLOT_YELLOW,
};

#define SVGPLOT_N_COLOURS 8

/* "#rrggbb" of each colour: svgplot_palette[colour - 1]. */
extern const char *const svgplot_palette[SVGPLOT_N_COLOURS];

struct svgplot_series {
    const char *label; /* legend text; NULL: not in the legend */
    const double *x, *y; /* n points */
    size_t n;
    enum svgplot_colour colour;
    enum svgplot_marker marker;
    bool no_line; /* markers only */
    bool highlight; /* thicker line drawn over the others (a Pareto front) */
    const unsigned char *flag; /* NULL or n flags: flagged points get a ring */
};

/* A straight dashed line in axis space: on log-log axes y = y0 (x / x0)^slope,
 * on linear axes y = y0 + slope (x - x0); a mixed pair of axes is straight
 * in its own coordinates the same way.  Drawn across the whole plot, listed
 * in the legend. */
struct svgplot_refline {
    double slope;
    double x0, y0; /* a point it passes through */
    const char *label; /* e.g. "1/spp"; NULL: not in the legend */
};

struct svgplot {
    const char *title, *x_label, *y_label; /* each may be NULL */
    enum svgplot_scale x_scale, y_scale;
    int width, height; /* pixels; 0: 720 x 480 */
    const struct svgplot_series *series;
    size_t n_series;
    const struct svgplot_refline *reflines;
    size_t n_reflines;
};

/* Write the plot to path (through a temporary file renamed into place). */
bool svgplot_write(const struct svgplot *plot, const char *path, struct diag *err);

/* Write the plot to an open stream; fails (diag) on a write error. */
bool svgplot_fprint(const struct svgplot *plot, FILE *f, struct diag *err);

/* Write s to f with XML's five special characters escaped, control
 * characters other than tab/newline dropped and invalid UTF-8 bytes
 * replaced by '?': safe in text and in attribute values. */
void svgplot_escape(FILE *f, const char *s);

/* ---- axes (exposed for tests) --------------------------------------------- */

struct svgplot_tick {
    double value;
    bool major; /* majors carry a label and a grid line */
};

/* The axis range drawn for data in [lo, hi] (lo <= hi; on a log axis
 * lo > 0): widened to whole ticks or whole decades, never empty. */
void
svgplot_axis_range(double lo, double hi, enum svgplot_scale scale, double *out_lo, double *out_hi);

/* The ticks within [lo, hi] in increasing order (a range from
 * svgplot_axis_range has one at both ends); writes at most cap and returns
 * how many there are in all.  Linear majors are k * step, step = 1, 2 or 5
 * times 10^e; log majors are exact powers of ten (the doubles "1e%d"
 * parses to). */
size_t
svgplot_ticks(double lo, double hi, enum svgplot_scale scale, struct svgplot_tick *out, size_t cap);

/* ---- Pareto front ------------------------------------------------------- */

/* Indices of the points (cost[i], error[i]) that no other point beats in
 * both (minimise both: j dominates i when cost_j <= cost_i and
 * error_j <= error_i with one strictly smaller), sorted by increasing cost
 * (so decreasing error).  Of identical points only the first counts; points
 * with a non-finite coordinate never do.  out_idx has room for n.  O(n^2),
 * meant for the few hundred points of a trade-off study. */
size_t svgplot_pareto_front(const double *cost, const double *error, size_t n, size_t *out_idx);

#endif /* SVGPLOT_H */
