/*
 * recorder_svg_top.c - the top view of --trace-svg's picture (recorder_svg.c):
 * the scene seen from above, x right and z down, scaled into its panel:
 * its bounds, its shapes and lights, and the camera.
 */
#include <math.h>
#include <stdio.h>

#include "recorder_svg.h"

/* Grow b to hold p (a point that is not finite is left out). */
static void
grow_vec(struct bounds *b, vec3 p)
{
    if (vec3_is_finite(p)) {
        b->lo = vec3_min(b->lo, p);
        b->hi = vec3_max(b->hi, p);
    }
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

struct bounds
recorder_svg_scene_bounds(const struct scene *s)
{
    struct bounds b = {vec3_splat(REAL_MAX), vec3_splat(-REAL_MAX)};
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

void
recorder_svg_top_point(const struct top *t, vec3 p, real *x, real *y)
{
    *x = t->x0 + (p.x - t->b.lo.x) * t->scale;
    *y = (p.z - t->b.lo.z) * t->scale;
}

static void
top_polygon(FILE *f, const struct top *t, const vec3 *corners, int n, const char *fill)
{
    fprintf(f, "<polygon fill=\"%s\" stroke=\"#555\" stroke-width=\"0.5\" points=\"", fill);
    for (int i = 0; i < n; i++) {
        real x;
        real y;
        recorder_svg_top_point(t, corners[i], &x, &y);
        fprintf(f, "%.2f,%.2f ", (double)x, (double)y);
    }
    fprintf(f, "\"/>\n");
}

static void
top_circle(FILE *f, const struct top *t, vec3 c, real r, const char *fill)
{
    real x;
    real y;
    recorder_svg_top_point(t, c, &x, &y);
    fprintf(
        f,
        "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"%s\" stroke=\"#555\" "
        "stroke-width=\"0.5\"/>\n",
        (double)x,
        (double)y,
        (double)(r * t->scale),
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

void
recorder_svg_top_shapes(FILE *f, const struct top *t, const struct scene *s)
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
    real x;
    real y;
    for (int i = 0; i < s->n_point_lights; i++) {
        recorder_svg_top_point(t, s->point_lights[i].position, &x, &y);
        fprintf(
            f,
            "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"4\" fill=\"#ffd400\"/>\n",
            (double)x,
            (double)y);
    }
    recorder_svg_top_point(t, s->camera.origin, &x, &y);
    fprintf(
        f,
        "<rect x=\"%.2f\" y=\"%.2f\" width=\"8\" height=\"8\" fill=\"#000\"/>"
        "<text x=\"%.2f\" y=\"%.2f\" font-size=\"11\">camera</text>\n",
        (double)x - 4,
        (double)y - 4,
        (double)x + 6,
        (double)y - 6);
}
