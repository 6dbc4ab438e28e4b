/*
 * trace_svg.c - a traced pixel's paths as a picture (--trace-svg): on the
 * left the full render, with every segment of the pixel's paths projected
 * through the camera; on the right a top view (x right, z down) of the
 * scene's bounds, its spheres and quads, the camera and the same segments;
 * below, a legend of the segment colours.  The render is embedded as a PNG
 * data URI, so the file stands alone.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "trace_events.h"

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
    write_base64(f, png, len);
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

static void
to3(vec3 v, double out[3])
{
    out[0] = (double)v.x;
    out[1] = (double)v.y;
    out[2] = (double)v.z;
}

static struct view
view_make(const struct camera_desc *c, int width, int height)
{
    struct view v = {.width = width, .height = height};
    double target[3];
    double up[3];
    to3(c->origin, v.origin);
    to3(c->target, target);
    to3(c->up, up);
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

/* --- the top view ------------------------------------------------------- */

struct bounds {
    double lo[3], hi[3];
};

static void
grow(struct bounds *b, const double p[3])
{
    for (int i = 0; i < 3; i++) {
        if (isfinite(p[i])) {
            b->lo[i] = fmin(b->lo[i], p[i]);
            b->hi[i] = fmax(b->hi[i], p[i]);
        }
    }
}

static void
grow_vec(struct bounds *b, vec3 v)
{
    double p[3];
    to3(v, p);
    grow(b, p);
}

static void
grow_parallelogram(struct bounds *b, vec3 corner, vec3 e1, vec3 e2)
{
    grow_vec(b, corner);
    grow_vec(b, vec3_add(corner, e1));
    grow_vec(b, vec3_add(corner, e2));
    grow_vec(b, vec3_add(vec3_add(corner, e1), e2));
}

static void
grow_sphere(struct bounds *b, vec3 c, real r)
{
    grow_vec(b, vec3_sub(c, vec3_splat(r)));
    grow_vec(b, vec3_add(c, vec3_splat(r)));
}

/* The scene's bounds: every shape, light and the camera. */
static struct bounds
scene_bounds(const struct scene *s)
{
    struct bounds b = {{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
    grow_vec(&b, s->camera.origin);
    for (int i = 0; i < s->n_spheres; i++) {
        grow_sphere(&b, s->spheres[i].center, s->spheres[i].radius);
    }
    for (int i = 0; i < s->n_quads; i++) {
        grow_parallelogram(&b, s->quads[i].corner, s->quads[i].edge1, s->quads[i].edge2);
    }
    for (int i = 0; i < s->n_vertices; i++) {
        grow_vec(&b, s->positions[i]);
    }
    for (int i = 0; i < s->n_area_lights; i++) {
        const struct area_light *l = &s->area_lights[i];
        grow_parallelogram(&b, l->corner, l->edge1, l->edge2);
    }
    for (int i = 0; i < s->n_sphere_lights; i++) {
        grow_sphere(&b, s->sphere_lights[i].center, s->sphere_lights[i].radius);
    }
    for (int i = 0; i < s->n_point_lights; i++) {
        grow_vec(&b, s->point_lights[i].position);
    }
    return b;
}

/* The top view's map from scene (x, z) to the panel at x0. */
struct top {
    double x0, scale;
    struct bounds b;
};

static void
top_point(const struct top *t, const double p[3], double *x, double *y)
{
    *x = t->x0 + (p[0] - t->b.lo[0]) * t->scale;
    *y = (p[2] - t->b.lo[2]) * t->scale;
}

static void
top_polygon(FILE *f, const struct top *t, const vec3 *corners, int n, const char *fill)
{
    fprintf(f, "<polygon fill=\"%s\" stroke=\"#555\" stroke-width=\"0.5\" points=\"", fill);
    for (int i = 0; i < n; i++) {
        double p[3];
        double x;
        double y;
        to3(corners[i], p);
        top_point(t, p, &x, &y);
        fprintf(f, "%.2f,%.2f ", x, y);
    }
    fprintf(f, "\"/>\n");
}

static void
top_circle(FILE *f, const struct top *t, vec3 c, real r, const char *fill)
{
    double p[3];
    double x;
    double y;
    to3(c, p);
    top_point(t, p, &x, &y);
    fprintf(
        f,
        "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"%s\" stroke=\"#555\" "
        "stroke-width=\"0.5\"/>\n",
        x,
        y,
        (double)r * t->scale,
        fill);
}

/* Triangles are drawn in the top view only for small meshes. */
#define TOP_MAX_TRIANGLES 4096

/* corner + s edge1 + t edge2 over s, t in [0, 1] (n = 4), or the triangle
 * corner, corner + edge1, corner + edge2 (n = 3). */
static void
top_parallelogram(
    FILE *f,
    const struct top *t,
    vec3 corner,
    vec3 e1,
    vec3 e2,
    int n,
    const char *fill)
{
    vec3 c[4] =
        {corner, vec3_add(corner, e1), vec3_add(vec3_add(corner, e1), e2), vec3_add(corner, e2)};
    if (n == 3) {
        c[2] = c[3];
    }
    top_polygon(f, t, c, n, fill);
}

static void
top_shapes(FILE *f, const struct top *t, const struct scene *s)
{
    for (int i = 0; i < s->n_quads; i++) {
        const struct quad *q = &s->quads[i];
        top_parallelogram(f, t, q->corner, q->edge1, q->edge2, 4, "rgba(128,128,128,0.15)");
    }
    for (int i = 0; s->n_triangles <= TOP_MAX_TRIANGLES && i < s->n_triangles; i++) {
        const struct triangle *tri = &s->triangles[i];
        vec3 c[3] = {s->positions[tri->v[0]], s->positions[tri->v[1]], s->positions[tri->v[2]]};
        top_polygon(f, t, c, 3, "rgba(128,128,128,0.10)");
    }
    for (int i = 0; i < s->n_spheres; i++) {
        top_circle(f, t, s->spheres[i].center, s->spheres[i].radius, "rgba(128,128,128,0.25)");
    }
    for (int i = 0; i < s->n_area_lights; i++) {
        const struct area_light *l = &s->area_lights[i];
        int n = l->triangle ? 3 : 4;
        top_parallelogram(f, t, l->corner, l->edge1, l->edge2, n, "rgba(255,220,0,0.6)");
    }
    for (int i = 0; i < s->n_sphere_lights; i++) {
        top_circle(
            f,
            t,
            s->sphere_lights[i].center,
            s->sphere_lights[i].radius,
            "rgba(255,220,0,0.6)");
    }
    for (int i = 0; i < s->n_point_lights; i++) {
        double p[3];
        double x;
        double y;
        to3(s->point_lights[i].position, p);
        top_point(t, p, &x, &y);
        fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"4\" fill=\"#ffd400\"/>\n", x, y);
    }
    double cam[3];
    double x;
    double y;
    to3(s->camera.origin, cam);
    top_point(t, cam, &x, &y);
    fprintf(
        f,
        "<rect x=\"%.2f\" y=\"%.2f\" width=\"8\" height=\"8\" fill=\"#000\"/>"
        "<text x=\"%.2f\" y=\"%.2f\" font-size=\"11\">camera</text>\n",
        x - 4,
        y - 4,
        x + 6,
        y - 6);
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
    top_point(map, a, &x0, &y0);
    top_point(map, b, &x1, &y1);
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
    struct top top = {.x0 = img_w + GAP, .b = scene_bounds(s)};
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
    top_shapes(f, &top, s);
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
