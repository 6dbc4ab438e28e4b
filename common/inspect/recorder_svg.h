/*
 * recorder_svg.h - what the two halves of --trace-svg's picture share
 * (recorder_svg.c draws the camera's view and the segments, recorder_svg_top.c
 * the top view).
 */
#ifndef RECORDER_SVG_H
#define RECORDER_SVG_H

#include <stdio.h>

#include "scene.h"
#include "vec3.h"

/* An axis-aligned box of the scene. */
struct bounds {
    vec3 lo, hi;
};

/* The top view's map from scene (x, z) to the panel at x0. */
struct top {
    real x0, scale;
    struct bounds b;
};

/* The scene's bounds: every shape, light and the camera. */
struct bounds recorder_svg_scene_bounds(const struct scene *s);
/* Point p of the scene in the top view's panel. */
void recorder_svg_top_point(const struct top *t, vec3 p, real *x, real *y);
/* The scene's shapes, lights and camera in the top view, into f. */
void recorder_svg_top_shapes(FILE *f, const struct top *t, const struct scene *s);

#endif
