/*
 * render.h - what this stage computes: the radiance arriving at the camera
 * through each pixel.
 */
#ifndef RENDER_H
#define RENDER_H

#include "camera.h"
#include "geometry.h"
#include "rng.h"
#include "scene.h"
#include "stats.h"
#include "vec3.h"

/* The scene features this stage models (see feature_table.h). */
#define RENDER_FEATURES \
    (FEATURE_BIT(FEAT_POINT_LIGHT) | FEATURE_BIT(FEAT_AMBIENT) | FEATURE_BIT(FEAT_MESH))

struct renderer {
    const struct scene *scene;
    struct world world;
    struct camera camera;
};

/* Radiance leaving the surface at h towards the ray's origin. */
vec3 shade(const struct renderer *renderer, const struct hit *h, struct stats *st);

/* Radiance arriving at r.o from direction -r.d. */
vec3 trace(const struct renderer *renderer, ray r, struct stats *st);

/* The driver's pixel function (driver.h): one ray through the pixel centre. */
vec3 render_pixel(const void *ctx, int px, int py, struct rng *rng, struct stats *st);

#endif /* RENDER_H */
