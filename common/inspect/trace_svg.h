/*
 * trace_svg.h - what the two halves of --trace-svg's picture share
 * (trace_svg.c draws the camera's view and the segments, trace_svg_top.c
 * the top view).
 */
#ifndef TRACE_SVG_H
#define TRACE_SVG_H

#include <stdio.h>

#include "scene.h"
#include "vec3.h"

/* An axis-aligned box of the scene. */
struct bounds {
    double lo[3], hi[3];
};

/* The top view's map from scene (x, z) to the panel at x0. */
struct top {
    double x0, scale;
    struct bounds b;
};

/* The trace's points are double[3] (trace_events.h), whatever real is. */
static inline void
trace_svg_to3(vec3 v, double out[3])
{
    out[0] = (double)v.x;
    out[1] = (double)v.y;
    out[2] = (double)v.z;
}

/* The scene's bounds: every shape, light and the camera. */
struct bounds trace_svg_scene_bounds(const struct scene *s);
/* Point p of the scene in the top view's panel. */
void trace_svg_top_point(const struct top *t, const double p[3], double *x, double *y);
/* The scene's shapes, lights and camera in the top view, into f. */
void trace_svg_top_shapes(FILE *f, const struct top *t, const struct scene *s);

#endif
