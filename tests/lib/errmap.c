/*
 * errmap.c - see errmap.h.  The legend's text is drawn with a 5x7 pixel
 * font of the few glyphs it needs (defined below).
 */
#include "errmap.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "metrics.h"

/* sRGB colours, 8 bits a channel. */
struct rgb8 {
    uint8_t r, g, b;
};

/* ColorBrewer RdBu, 5 of its 7-class colours: dark blue, light blue,
 * near-white, light red, dark red, at e = -1, -1/2, 0, 1/2, 1 of range. */
static const struct rgb8 diverging[5] = {
    {33, 102, 172},
    {103, 169, 207},
    {247, 247, 247},
    {239, 138, 98},
    {178, 24, 43},
};
static const struct rgb8 nonfinite_colour = {0, 170, 0};
static const struct rgb8 masked_colour = {120, 120, 120};
static const struct rgb8 outline_colour = {0, 0, 0};
static const struct rgb8 paper = {255, 255, 255};
static const struct rgb8 ink = {0, 0, 0};

/* The colour of relative error e on a scale of +-range: piecewise linear
 * between the anchors, in sRGB (the scheme's anchors are sRGB colours
 * spaced for perception). */
static struct rgb8
colour_of(double e, double range)
{
    if (!isfinite(e)) {
        return nonfinite_colour;
    }
    double u = fmin(fmax(e / range, -1.0), 1.0) * 2 + 2; /* [0, 4] */
    int i = u >= 4 ? 3 : (int)u;
    double f = u - i;
    const struct rgb8 *a = &diverging[i], *b = &diverging[i + 1];
    return (struct rgb8){
        (uint8_t)lround(a->r + f * (b->r - a->r)),
        (uint8_t)lround(a->g + f * (b->g - a->g)),
        (uint8_t)lround(a->b + f * (b->b - a->b)),
    };
}

/* Set pixel (x, y) of the output (a linear image, encoded to sRGB when
 * written as PNG) to an sRGB colour; outside the image: nothing. */
static void
put(struct image *out, int x, int y, struct rgb8 c)
{
    if (x < 0 || y < 0 || x >= out->width || y >= out->height) {
        return;
    }
    float *p = image_pixel(out, x, y);
    p[0] = image_linear_from_srgb(c.r / 255.0f);
    p[1] = image_linear_from_srgb(c.g / 255.0f);
    p[2] = image_linear_from_srgb(c.b / 255.0f);
}

static void
fill_rect(struct image *out, int x0, int y0, int w, int h, struct rgb8 c)
{
    for (int y = y0; y < y0 + h; y++) {
        for (int x = x0; x < x0 + w; x++) {
            put(out, x, y, c);
        }
    }
}

/* A rectangle's border, `thick` pixels wide, inside the rectangle. */
static void
outline_rect(struct image *out, int x0, int y0, int w, int h, int thick, struct rgb8 c)
{
    fill_rect(out, x0, y0, w, thick, c);
    fill_rect(out, x0, y0 + h - thick, w, thick, c);
    fill_rect(out, x0, y0, thick, h, c);
    fill_rect(out, x0 + w - thick, y0, thick, h, c);
}

/* ---- the legend's font: 5x7 cells, '#' ink, '.' paper ------------------- */

#define GLYPH_W 5
#define GLYPH_H 7

struct glyph {
    char ch;
    const char *rows; /* GLYPH_H rows of GLYPH_W cells */
};

static const struct glyph font[] = {
    {'0',
     ".###."
     "#...#"
     "#..##"
     "#.#.#"
     "##..#"
     "#...#"
     ".###."},
    {'1',
     "..#.."
     ".##.."
     "..#.."
     "..#.."
     "..#.."
     "..#.."
     ".###."},
    {'2',
     ".###."
     "#...#"
     "....#"
     "...#."
     "..#.."
     ".#..."
     "#####"},
    {'3',
     "#####"
     "...#."
     "..#.."
     "...#."
     "....#"
     "#...#"
     ".###."},
    {'4',
     "...#."
     "..##."
     ".#.#."
     "#..#."
     "#####"
     "...#."
     "...#."},
    {'5',
     "#####"
     "#...."
     "####."
     "....#"
     "....#"
     "#...#"
     ".###."},
    {'6',
     "..##."
     ".#..."
     "#...."
     "####."
     "#...#"
     "#...#"
     ".###."},
    {'7',
     "#####"
     "....#"
     "...#."
     "..#.."
     ".#..."
     ".#..."
     ".#..."},
    {'8',
     ".###."
     "#...#"
     "#...#"
     ".###."
     "#...#"
     "#...#"
     ".###."},
    {'9',
     ".###."
     "#...#"
     "#...#"
     ".####"
     "....#"
     "...#."
     ".##.."},
    {'+',
     "....."
     "..#.."
     "..#.."
     "#####"
     "..#.."
     "..#.."
     "....."},
    {'-',
     "....."
     "....."
     "....."
     "#####"
     "....."
     "....."
     "....."},
    {'%',
     "##..."
     "##..#"
     "...#."
     "..#.."
     ".#..."
     "#..##"
     "...##"},
    {'.',
     "....."
     "....."
     "....."
     "....."
     "....."
     ".##.."
     ".##.."},
    {'A',
     ".###."
     "#...#"
     "#...#"
     "#####"
     "#...#"
     "#...#"
     "#...#"},
    {'B',
     "####."
     "#...#"
     "#...#"
     "####."
     "#...#"
     "#...#"
     "####."},
    {'C',
     ".###."
     "#...#"
     "#...."
     "#...."
     "#...."
     "#...#"
     ".###."},
    {'D',
     "####."
     "#...#"
     "#...#"
     "#...#"
     "#...#"
     "#...#"
     "####."},
    {'E',
     "#####"
     "#...."
     "#...."
     "####."
     "#...."
     "#...."
     "#####"},
    {'F',
     "#####"
     "#...."
     "#...."
     "####."
     "#...."
     "#...."
     "#...."},
    {'G',
     ".###."
     "#...#"
     "#...."
     "#.###"
     "#...#"
     "#...#"
     ".####"},
    {'H',
     "#...#"
     "#...#"
     "#...#"
     "#####"
     "#...#"
     "#...#"
     "#...#"},
    {'I',
     ".###."
     "..#.."
     "..#.."
     "..#.."
     "..#.."
     "..#.."
     ".###."},
    {'K',
     "#...#"
     "#..#."
     "#.#.."
     "##..."
     "#.#.."
     "#..#."
     "#...#"},
    {'L',
     "#...."
     "#...."
     "#...."
     "#...."
     "#...."
     "#...."
     "#####"},
    {'M',
     "#...#"
     "##.##"
     "#.#.#"
     "#.#.#"
     "#...#"
     "#...#"
     "#...#"},
    {'N',
     "#...#"
     "##..#"
     "#.#.#"
     "#..##"
     "#...#"
     "#...#"
     "#...#"},
    {'O',
     ".###."
     "#...#"
     "#...#"
     "#...#"
     "#...#"
     "#...#"
     ".###."},
    {'P',
     "####."
     "#...#"
     "#...#"
     "####."
     "#...."
     "#...."
     "#...."},
    {'R',
     "####."
     "#...#"
     "#...#"
     "####."
     "#.#.."
     "#..#."
     "#...#"},
    {'S',
     ".####"
     "#...."
     "#...."
     ".###."
     "....#"
     "....#"
     "####."},
    {'T',
     "#####"
     "..#.."
     "..#.."
     "..#.."
     "..#.."
     "..#.."
     "..#.."},
};

static const char *
glyph_rows(char ch)
{
    for (size_t i = 0; i < sizeof font / sizeof font[0]; i++) {
        if (font[i].ch == ch) {
            return font[i].rows;
        }
    }
    return NULL; /* a space, or a character the legend never uses */
}

/* Advance of one character at magnification f: the cell and a gap. */
static int
text_width(const char *s, int f)
{
    return (int)strlen(s) * (GLYPH_W + 1) * f;
}

static void
draw_text(struct image *out, int x, int y, const char *s, int f)
{
    for (; *s; s++, x += (GLYPH_W + 1) * f) {
        const char *rows = glyph_rows(*s);
        for (int gy = 0; rows && gy < GLYPH_H; gy++) {
            for (int gx = 0; gx < GLYPH_W; gx++) {
                if (rows[gy * GLYPH_W + gx] == '#') {
                    fill_rect(out, x + gx * f, y + gy * f, f, f, ink);
                }
            }
        }
    }
}

/* ---- the map ----------------------------------------------------------------- */

double
errmap_pixel_error(const struct image *render, const struct image *ref, int x, int y)
{
    const float *p = image_pixel(render, x, y);
    const float *q = image_pixel(ref, x, y);
    double lx = metrics_luminance(p);
    double lr = metrics_luminance(q);
    if (!isfinite(lx) || !isfinite(lr)) {
        return NAN;
    }
    return (lx - lr) / sqrt(lr * lr + METRICS_RELMSE_EPS);
}

static int
compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double
errmap_auto_range(const struct image *render, const struct image *ref)
{
    size_t n = (size_t)render->width * (size_t)render->height, m = 0;
    double *e = malloc((n ? n : 1) * sizeof *e);
    double p99 = 0;
    if (e) {
        for (int y = 0; y < render->height; y++) {
            for (int x = 0; x < render->width; x++) {
                double v = errmap_pixel_error(render, ref, x, y);
                if (isfinite(v)) {
                    e[m++] = fabs(v);
                }
            }
        }
        qsort(e, m, sizeof *e, compare_doubles);
        p99 = m ? e[(size_t)(0.99 * (double)(m - 1))] : 0;
        free(e);
    }
    static const double steps[3] = {1, 2, 5};
    for (double decade = 1e-3; decade < 10; decade *= 10) {
        for (int i = 0; i < 3; i++) {
            if (steps[i] * decade >= p99) {
                return steps[i] * decade;
            }
        }
    }
    return 10;
}

/* The scale's end as a percentage: "5%", "0.2%", "1000%". */
static void
format_percent(char *buf, size_t cap, const char *sign, double range)
{
    snprintf(buf, cap, "%s%.4g%%", sign, range * 100); /* 4 digits: 1000, not 1e+03 */
}

/* The legend below the map, from row y0 of out, magnification f. */
static void
draw_legend(struct image *out, int y0, double range, bool masked, bool nonfinite, int f)
{
    int margin = 6 * f, line = (GLYPH_H + 2) * f, bar_h = 10 * f;
    int x0 = margin, x1 = out->width - margin;
    int y = y0 + margin;
    draw_text(out, x0, y, "DARKER", f);
    draw_text(out, x1 - text_width("BRIGHTER", f) + f, y, "BRIGHTER", f);
    y += line;
    for (int x = x0; x < x1; x++) {
        double e = range * (2.0 * (x - x0) / (double)(x1 - x0 - 1) - 1);
        fill_rect(out, x, y, 1, bar_h, colour_of(e, range));
    }
    y += bar_h + 2 * f;
    char lo[32], hi[32];
    format_percent(lo, sizeof lo, "-", range);
    format_percent(hi, sizeof hi, "+", range);
    draw_text(out, x0, y, lo, f);
    draw_text(out, (x0 + x1) / 2 - text_width("0", f) / 2, y, "0", f);
    draw_text(out, x1 - text_width(hi, f) + f, y, hi, f);
    y += line + 4 * f;
    outline_rect(out, x0, y, GLYPH_H * f, GLYPH_H * f, f, outline_colour);
    int x = x0 + (GLYPH_H + 3) * f;
    draw_text(out, x, y, "FAILING BLOCK", f);
    x += text_width("FAILING BLOCK ", f) + 3 * f;
    if (nonfinite) {
        fill_rect(out, x, y, GLYPH_H * f, GLYPH_H * f, nonfinite_colour);
        draw_text(out, x + (GLYPH_H + 3) * f, y, "NAN OR INF", f);
        x += (GLYPH_H + 3) * f + text_width("NAN OR INF ", f) + 3 * f;
    }
    if (masked) {
        fill_rect(out, x, y, GLYPH_H * f, GLYPH_H * f, masked_colour);
        draw_text(out, x + (GLYPH_H + 3) * f, y, "NOT COMPARED", f);
    }
}

/* Rows the legend takes at magnification f (draw_legend's layout). */
static int
legend_height(int f)
{
    int margin = 6 * f, line = (GLYPH_H + 2) * f;
    return margin + line + 10 * f + 2 * f + line + 4 * f + GLYPH_H * f + margin;
}

bool
errmap_draw(
    const struct image *render,
    const struct image *ref,
    double range,
    const unsigned char *mask,
    const struct errmap_box *boxes,
    int n_boxes,
    struct image *out,
    struct diag *err)
{
    *out = (struct image){0};
    if (render->width != ref->width || render->height != ref->height || !(range > 0)) {
        diag_set(err, NULL, 0, 0, "error map: mismatched sizes or a bad range");
        return false;
    }
    int s = (ERRMAP_MIN_WIDTH + render->width - 1) / render->width;
    s = s < 1 ? 1 : s > 16 ? 16 : s;
    int width = render->width * s;
    /* The legend needs about 50 characters across; bigger text on big maps. */
    int f = width >= 4 * ERRMAP_MIN_WIDTH ? 3 : width >= 2 * ERRMAP_MIN_WIDTH ? 2 : 1;
    if (width < 50 * (GLYPH_W + 1) * f) {
        width = 50 * (GLYPH_W + 1) * f;
    }
    int map_h = render->height * s;
    if (!image_alloc(out, width, map_h + legend_height(f), err)) {
        return false;
    }
    fill_rect(out, 0, 0, out->width, out->height, paper);
    bool nonfinite = false;
    for (int y = 0; y < render->height; y++) {
        for (int x = 0; x < render->width; x++) {
            bool compared = !mask || mask[(size_t)y * (size_t)render->width + (size_t)x];
            double e = errmap_pixel_error(render, ref, x, y);
            nonfinite = nonfinite || (compared && !isfinite(e));
            fill_rect(out, x * s, y * s, s, s, compared ? colour_of(e, range) : masked_colour);
        }
    }
    int thick = s >= 4 ? 2 : 1;
    for (int i = 0; i < n_boxes; i++) {
        const struct errmap_box *b = &boxes[i];
        outline_rect(out, b->x0 * s, b->y0 * s, b->w * s, b->h * s, thick, outline_colour);
    }
    draw_legend(out, map_h, range, mask != NULL, nonfinite, f);
    return true;
}
