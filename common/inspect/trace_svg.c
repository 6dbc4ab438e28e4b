/*
 * trace_svg.c - a traced pixel's paths as a picture (--trace-svg): on the
 * left the full render, with every segment of the pixel's paths projected
 * through the camera; on the right a top view (x right, z down) of the
 * scene's bounds, its spheres and quads, the camera and the same segments
 * (trace_svg_top.c); below, a legend of the segment colours.  The render is embedded as a PNG
 * data URI, so the file stands alone.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "trace_events.h"
#include "trace_svg.h"

/* The larger side of each panel, in SVG units (pixels). */
#define PANEL 480.0
#define GAP 24.0
#define LEGEND_HEIGHT 56.0
#define LEGEND_WIDTH 720.0

struct segment_style {
    enum trace_segment segment;
    const char *colour;
    const char *label;
    const char *dash; /* stroke-dasharray; NULL: solid */
};

static const struct segment_style styles[] = {
    {SEG_CAMERA, "#ffd400", "camera ray", NULL},
    {SEG_BOUNCE, "#ff7f0e", "reflected, refracted or sampled ray", NULL},
    {SEG_SHADOW_CLEAR, "#2ca02c", "shadow ray, clear", "4 3"},
    {SEG_SHADOW_BLOCKED, "#d62728", "shadow ray, blocked", "4 3"},
    {SEG_MISS, "#1f77b4", "ray leaving the scene", "1 3"},
};

#define N_STYLES ((int)(sizeof styles / sizeof styles[0]))

static const struct segment_style *
style_of(enum trace_segment segment)
{
    for (int i = 0; i < N_STYLES; i++) {
        if (styles[i].segment == segment) {
            return &styles[i];
        }
    }
    return NULL;
}

/* --- the render as a data URI ------------------------------------------ */

/* The image as an 8-bit sRGB PNG, base64, into f. */
static bool
put_png_uri(FILE *f, const struct image *image, struct diag *err)
{
    size_t len;
    unsigned char *png = image_png_bytes(image, &len, err);
    if (!png) {
        return false;
    }
    fprintf(f, "data:image/png;base64,");
    image_write_base64(f, png, len);
    free(png);
    return true;
}

/* --- the camera's projection ------------------------------------------- */

/* The pinhole camera of the stages (camera.c): its basis and the
 * half-extents of the image plane at distance 1. */
struct view {
    double origin[3], forward[3], right[3], up[3];
    double half_width, half_height;
    double width, height; /* image, pixels */
    double scale; /* SVG units per image pixel */
};

static double
dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void
unit3(double a[3])
{
    double len = sqrt(dot3(a, a));
    for (int i = 0; i < 3 && len > 0; i++) {
        a[i] /= len;
    }
}

static void
cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static struct view
view_make(const struct camera_desc *c, int width, int height)
{
    struct view v = {.width = width, .height = height};
    double target[3];
    double up[3];
    trace_svg_to3(c->origin, v.origin);
    trace_svg_to3(c->target, target);
    trace_svg_to3(c->up, up);
    for (int i = 0; i < 3; i++) {
        v.forward[i] = target[i] - v.origin[i];
    }
    unit3(v.forward);
    cross3(v.forward, up, v.right);
    unit3(v.right);
    cross3(v.right, v.forward, v.up);
    v.half_height = tan((double)c->vfov_deg * 3.14159265358979323846 / 360);
    v.half_width = v.half_height * width / height;
    v.scale = PANEL / (width > height ? width : height);
    return v;
}

/* Depth of p along the view direction. */
static double
depth_of(const struct view *v, const double p[3])
{
    double d[3] = {p[0] - v->origin[0], p[1] - v->origin[1], p[2] - v->origin[2]};
    return dot3(d, v->forward);
}

/* The film position of p (in front of the camera), in SVG units. */
static void
project(const struct view *v, const double p[3], double *x, double *y)
{
    double d[3] = {p[0] - v->origin[0], p[1] - v->origin[1], p[2] - v->origin[2]};
    double z = dot3(d, v->forward);
    double film_x = (dot3(d, v->right) / z / v->half_width + 1) / 2 * v->width;
    double film_y = (1 - dot3(d, v->up) / z / v->half_height) / 2 * v->height;
    *x = film_x * v->scale;
    *y = film_y * v->scale;
}

static void
line(FILE *f, double x0, double y0, double x1, double y1, const struct segment_style *s)
{
    fprintf(
        f,
        "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"%s\"%s%s%s/>\n",
        x0,
        y0,
        x1,
        y1,
        s->colour,
        s->dash ? " stroke-dasharray=\"" : "",
        s->dash ? s->dash : "",
        s->dash ? "\"" : "");
}

/* Segment a-b through the camera, the part behind the near plane cut off. */
static void
camera_segment(
    FILE *f,
    const void *map,
    const double a[3],
    const double b[3],
    const struct segment_style *s)
{
    const struct view *v = map;
    const double near = 1e-6;
    double p[3];
    double q[3];
    memcpy(p, a, sizeof p);
    memcpy(q, b, sizeof q);
    double dp = depth_of(v, p);
    double dq = depth_of(v, q);
    if (dp < near && dq < near) {
        return;
    }
    if (dp < near || dq < near) {
        double t = (near - dp) / (dq - dp);
        double *cut = dp < near ? p : q;
        for (int i = 0; i < 3; i++) {
            cut[i] = a[i] + t * (b[i] - a[i]);
        }
    }
    double x0;
    double y0;
    double x1;
    double y1;
    project(v, p, &x0, &y0);
    project(v, q, &x1, &y1);
    /* A far end can project far outside the picture: the clip path hides
     * it, but keep the numbers printable. */
    double lim = 1e6;
    if (fabs(x0) < lim && fabs(y0) < lim && fabs(x1) < lim && fabs(y1) < lim) {
        line(f, x0, y0, x1, y1, s);
    }
}

/* The segment an event draws: a miss is drawn as far as the scene is
 * wide. */
static void
event_segment(const struct trace_event *e, double extent, double a[3], double b[3])
{
    memcpy(a, e->from, 3 * sizeof(double));
    memcpy(b, e->to, 3 * sizeof(double));
    if (e->segment == SEG_MISS) {
        for (int i = 0; i < 3; i++) {
            b[i] = e->from[i] + extent * e->to[i];
        }
    }
}

/* The legend: a swatch of each colour and what it stands for, wrapped at
 * `width`. */
/* Segment a-b in the top view. */
static void
top_segment(
    FILE *f,
    const void *map,
    const double a[3],
    const double b[3],
    const struct segment_style *s)
{
    double x0;
    double y0;
    double x1;
    double y1;
    trace_svg_top_point(map, a, &x0, &y0);
    trace_svg_top_point(map, b, &x1, &y1);
    line(f, x0, y0, x1, y1, s);
}

/* Every segment of the trace, drawn through `map` (the camera's view or
 * the top view). */
static void
draw_segments(
    FILE *f,
    const struct trace *t,
    double extent,
    void (
        *draw)(FILE *, const void *, const double *, const double *, const struct segment_style *),
    const void *map)
{
    for (int i = 0; i < t->n_events; i++) {
        const struct trace_event *e = &t->events[i];
        const struct segment_style *style = style_of(e->segment);
        if (style) {
            double a[3];
            double b[3];
            event_segment(e, extent, a, b);
            draw(f, map, a, b, style);
        }
    }
}

static void
legend(FILE *f, double y, double width)
{
    double x = 8;
    for (int i = 0; i < N_STYLES; i++) {
        double w = 40 + 7.0 * (double)strlen(styles[i].label);
        if (x + w > width && x > 8) {
            x = 8;
            y += 20;
        }
        fprintf(
            f,
            "<rect x=\"%.1f\" y=\"%.1f\" width=\"24\" height=\"8\" fill=\"%s\"/>"
            "<text x=\"%.1f\" y=\"%.1f\" font-size=\"12\">%s</text>\n",
            x,
            y - 4,
            styles[i].colour,
            x + 30,
            y + 4,
            styles[i].label);
        x += w;
    }
}

bool
trace_write_svg(FILE *f, const struct trace *t, const struct image *image, struct diag *err)
{
    const struct scene *s = t->scene;
    struct view v = view_make(&s->camera, image->width, image->height);
    double img_w = image->width * v.scale;
    double img_h = image->height * v.scale;
    struct top top = {.x0 = img_w + GAP, .b = trace_svg_scene_bounds(s)};
    double span_x = top.b.hi[0] - top.b.lo[0];
    double span_z = top.b.hi[2] - top.b.lo[2];
    double span = fmax(fmax(span_x, span_z), 1e-30);
    top.scale = PANEL / span;
    double extent = span * 2;
    double width = fmax(top.x0 + span_x * top.scale, LEGEND_WIDTH);
    double height = fmax(img_h, span_z * top.scale) + LEGEND_HEIGHT;
    fprintf(
        f,
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" "
        "width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.2f %.2f\" font-family=\"sans-serif\">\n"
        "<title>pixel (%d, %d) of %s</title>\n"
        "<defs><clipPath id=\"film\"><rect width=\"%.2f\" height=\"%.2f\"/></clipPath>"
        "<clipPath id=\"top\"><rect x=\"%.2f\" width=\"%.2f\" height=\"%.2f\"/></clipPath></defs>\n"
        "<rect width=\"100%%\" height=\"100%%\" fill=\"#fff\"/>\n<image width=\"%.2f\" height=\"%.2f\" "
        "preserveAspectRatio=\"none\" style=\"image-rendering:pixelated\" xlink:href=\"",
        ceil(width),
        ceil(height),
        width,
        height,
        t->px,
        t->py,
        s->path,
        img_w,
        img_h,
        top.x0,
        span_x * top.scale,
        span_z * top.scale,
        img_w,
        img_h);
    if (!put_png_uri(f, image, err)) {
        return false;
    }
    fprintf(f, "\"/>\n<g clip-path=\"url(#film)\" stroke-width=\"1.2\" fill=\"none\">\n");
    draw_segments(f, t, extent, camera_segment, &v);
    fprintf(
        f,
        "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" stroke=\"#f0f\" "
        "stroke-width=\"1.5\"/>\n</g>\n",
        t->px * v.scale - 2,
        t->py * v.scale - 2,
        v.scale + 4,
        v.scale + 4);
    fprintf(f, "<g id=\"top-view\" clip-path=\"url(#top)\">\n");
    trace_svg_top_shapes(f, &top, s);
    fprintf(f, "<g stroke-width=\"1\" fill=\"none\">\n");
    draw_segments(f, t, extent, top_segment, &top);
    fprintf(
        f,
        "</g>\n<text x=\"%.2f\" y=\"14\" font-size=\"12\">top view (x right, z down)</text>\n</g>\n",
        top.x0 + 4);
    legend(f, fmax(img_h, span_z * top.scale) + 20, width);
    fprintf(f, "</svg>\n");
    return true;
}
