/*
 * render.h - what this stage computes: the radiance arriving at the camera
 * through each pixel.
 */
#ifndef RENDER_H
#define RENDER_H

#include "aov.h"
#include "camera.h"
#include "driver.h"
#include "geometry.h"
#include "rng.h"
#include "scene.h"
#include "stats.h"
#include "vec3.h"

/* The scene features this stage models (see ../course.h). */
#define RENDER_FEATURES \
    (FEATURE_BIT(FEAT_POINT_LIGHT) | FEATURE_BIT(FEAT_AMBIENT) | FEATURE_BIT(FEAT_MESH))

struct renderer {
    const struct scene *scene;
    struct world world;
    struct camera camera;
};

/* The Lambertian albedo this stage shades material m with (render.c). */
vec3 diffuse_albedo(const struct material *m);

/* Radiance leaving the surface at h towards the ray's origin. */
vec3 shade(const struct renderer *renderer, const struct hit *h, struct stats *st);

/* Radiance arriving at r.o from direction -r.d. */
vec3 trace(const struct renderer *renderer, ray r, struct stats *st);

/* The radiance through pixel (px, py), (0, 0) top-left: one ray through its centre. */
vec3 render_pixel(const struct renderer *renderer, int px, int py, struct stats *st);

/* What the render passes (--aov) ask of this stage, its own rays (passes.c). */
struct aov_source render_passes_source(const struct renderer *renderer);

/* The driver's tile function (driver.h): each pixel's radiance for the tile's
 * pass; false when a stop cut the tile short. */
bool render_tile(const void *ctx, const struct tile *tile, struct stats *st);

#endif /* RENDER_H */
