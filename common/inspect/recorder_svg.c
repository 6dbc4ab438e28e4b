/*
 * recorder_svg.c - a traced pixel's paths as a picture (--trace-svg): on the
 * left the full render, with every segment of the pixel's paths projected
 * through the camera; on the right a top view (x right, z down) of the
 * scene's bounds, its spheres and quads, the camera and the same segments
 * (recorder_svg_top.c); below, a legend of the segment colours.  The render is embedded as a PNG
 * data URI, so the file stands alone.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "recorder_events.h"
#include "recorder_svg.h"

/* The larger side of each panel, in SVG units (pixels). */
#define PANEL 480.0
#define GAP 24.0
#define LEGEND_HEIGHT 56.0
#define LEGEND_WIDTH 720.0

struct segment_style {
    enum recorder_segment segment;
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
style_of(enum recorder_segment segment)
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

/* The stage's own camera, inverted: the rays it casts through a few film
 * positions fix its eye (the point all their lines pass through) and where
 * each film position lies on the image plane at distance 1 along the
 * centre ray; a point of the scene projects to the film position whose ray
 * passes through it. */
struct view {
    const struct recorder_camera *camera;
    vec3 origin, forward; /* the eye, and the centre ray's unit direction */
    vec3 film0, dx, dy; /* film (0, 0) on the plane, and one pixel's step in x and y */
    real g_xx, g_xy, g_yy, det; /* the Gram matrix of dx, dy, and its determinant */
    real scale; /* SVG units per image pixel */
};

/* Where the camera's ray through film (fx, fy) meets the image plane,
 * relative to the eye; its origin into *o when o is not NULL. */
static vec3
plane_point(const struct view *v, real fx, real fy, vec3 *o)
{
    ray r = v->camera->camera_ray(v->camera->ctx, fx, fy);
    if (o) {
        *o = r.o;
    }
    return vec3_scale(r.d, 1 / vec3_dot(r.d, v->forward));
}

static struct view
view_make(const struct recorder_camera *camera, int width, int height)
{
    struct view v = {.camera = camera};
    ray centre = camera->camera_ray(camera->ctx, (real)width / 2, (real)height / 2);
    v.forward = centre.d;
    /* Camera rays may start on a near plane (scene-format.md's `near`):
     * the ray through film (0, 0) starts at eye + near p0 and the centre
     * ray at eye + near forward, so near is the step between their origins
     * measured along p0 - forward. */
    vec3 o0;
    v.film0 = plane_point(&v, 0, 0, &o0);
    vec3 spread = vec3_sub(v.film0, v.forward);
    real near = vec3_dot(vec3_sub(o0, centre.o), spread) / vec3_length2(spread);
    v.origin = vec3_madd(centre.o, v.forward, -near);
    v.dx = vec3_scale(vec3_sub(plane_point(&v, (real)width, 0, NULL), v.film0), 1 / (real)width);
    v.dy = vec3_scale(vec3_sub(plane_point(&v, 0, (real)height, NULL), v.film0), 1 / (real)height);
    v.g_xx = vec3_dot(v.dx, v.dx);
    v.g_xy = vec3_dot(v.dx, v.dy);
    v.g_yy = vec3_dot(v.dy, v.dy);
    v.det = v.g_xx * v.g_yy - v.g_xy * v.g_xy;
    v.scale = (real)PANEL / (real)(width > height ? width : height);
    return v;
}

/* Depth of p along the view direction. */
static real
depth_of(const struct view *v, vec3 p)
{
    return vec3_dot(vec3_sub(p, v->origin), v->forward);
}

/* The film position of p (in front of the camera), in SVG units: p's
 * point on the image plane, written as film0 + fx dx + fy dy (the normal
 * equations of the two steps). */
static void
project(const void *map, vec3 p, real *x, real *y)
{
    const struct view *v = map;
    vec3 d = vec3_sub(p, v->origin);
    vec3 q = vec3_sub(vec3_scale(d, 1 / vec3_dot(d, v->forward)), v->film0);
    real qx = vec3_dot(q, v->dx);
    real qy = vec3_dot(q, v->dy);
    real film_x = (v->g_yy * qx - v->g_xy * qy) / v->det;
    real film_y = (v->g_xx * qy - v->g_xy * qx) / v->det;
    *x = film_x * v->scale;
    *y = film_y * v->scale;
}

static void
line(FILE *f, real x0, real y0, real x1, real y1, const struct segment_style *s)
{
    fprintf(
        f,
        "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"%s\"%s%s%s/>\n",
        (double)x0,
        (double)y0,
        (double)x1,
        (double)y1,
        s->colour,
        s->dash ? " stroke-dasharray=\"" : "",
        s->dash ? s->dash : "",
        s->dash ? "\"" : "");
}

/* Panel position of p through `map`: the camera's view or the top view. */
typedef void (*panel_map)(const void *map, vec3 p, real *x, real *y);

/* Segment a-b through `to_panel`. */
static void
panel_line(
    FILE *f,
    panel_map to_panel,
    const void *map,
    vec3 a,
    vec3 b,
    const struct segment_style *s)
{
    real x0;
    real y0;
    real x1;
    real y1;
    to_panel(map, a, &x0, &y0);
    to_panel(map, b, &x1, &y1);
    /* A far end can project far outside the picture: the clip path hides
     * it, but keep the numbers printable. */
    real lim = (real)1e6;
    if (fabs(x0) < lim && fabs(y0) < lim && fabs(x1) < lim && fabs(y1) < lim) {
        line(f, x0, y0, x1, y1, s);
    }
}

/* Segment a-b through the camera, the part behind the near plane cut off. */
static void
camera_segment(FILE *f, const void *map, vec3 a, vec3 b, const struct segment_style *s)
{
    const struct view *v = map;
    /* The cut's depth grows with the eye's distance from the origin: a
     * point at depth d has its coordinates rounded by about
     * 1e-16 |origin|, so its projection is good to 1e-16 |origin| / d. */
    const real near = (real)1e-6 * (1 + vec3_max_comp(vec3_abs(v->origin)));
    real da = depth_of(v, a);
    real db = depth_of(v, b);
    if (da < near && db < near) {
        return;
    }
    if (da < near || db < near) {
        vec3 cut = vec3_lerp(a, b, (near - da) / (db - da));
        a = da < near ? cut : a;
        b = db < near ? cut : b;
    }
    panel_line(f, project, v, a, b, s);
}

/* A point of the trace (double, recorder_events.h, whatever real is). */
static vec3
event_point(const double p[3])
{
    return vec3_make((real)p[0], (real)p[1], (real)p[2]);
}

/* The segment an event draws: a miss is drawn as far as the scene is
 * wide. */
static void
event_segment(const struct recorder_event *e, real extent, vec3 *a, vec3 *b)
{
    *a = event_point(e->from);
    *b = event_point(e->to);
    if (e->segment == SEG_MISS) {
        *b = vec3_madd(*a, *b, extent);
    }
}

static void
top_point(const void *map, vec3 p, real *x, real *y)
{
    recorder_svg_top_point(map, p, x, y);
}

/* Segment a-b in the top view. */
static void
top_segment(FILE *f, const void *map, vec3 a, vec3 b, const struct segment_style *s)
{
    panel_line(f, top_point, map, a, b, s);
}

/* Every segment of the trace, drawn through `map` (the camera's view or
 * the top view). */
static void
draw_segments(
    FILE *f,
    const struct recorder *t,
    real extent,
    void (*draw)(FILE *, const void *, vec3, vec3, const struct segment_style *),
    const void *map)
{
    for (int i = 0; i < t->n_events; i++) {
        const struct recorder_event *e = &t->events[i];
        const struct segment_style *style = style_of(e->segment);
        if (style) {
            vec3 a;
            vec3 b;
            event_segment(e, extent, &a, &b);
            draw(f, map, a, b, style);
        }
    }
}

/* The legend: a swatch of each colour and what it stands for, wrapped at
 * `width`. */
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
recorder_write_svg(
    FILE *f,
    const struct recorder *t,
    const struct image *image,
    const struct recorder_camera *camera,
    struct diag *err)
{
    const struct scene *s = t->scene;
    struct view v = view_make(camera, image->width, image->height);
    double img_w = image->width * (double)v.scale;
    double img_h = image->height * (double)v.scale;
    struct top top = {.x0 = (real)(img_w + GAP), .b = recorder_svg_scene_bounds(s)};
    double span_x = (double)(top.b.hi.x - top.b.lo.x);
    double span_z = (double)(top.b.hi.z - top.b.lo.z);
    double span = fmax(fmax(span_x, span_z), 1e-30);
    top.scale = (real)(PANEL / span);
    real extent = (real)(span * 2);
    double width = fmax(img_w + GAP + span_x * (double)top.scale, LEGEND_WIDTH);
    double height = fmax(img_h, span_z * (double)top.scale) + LEGEND_HEIGHT;
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
    recorder_svg_top_shapes(f, &top, s);
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
