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
#include "light.h"
#include "rng.h"
#include "scene.h"
#include "stats.h"
#include "vec3.h"

/* The scene features this stage models (see ../course.h). */
#define RENDER_FEATURES \
    (FEATURE_BIT(FEAT_POINT_LIGHT) | FEATURE_BIT(FEAT_AMBIENT) | FEATURE_BIT(FEAT_MESH) \
     | FEATURE_BIT(FEAT_AREA_LIGHT) | FEATURE_BIT(FEAT_MIRROR) | FEATURE_BIT(FEAT_GLASS) \
     | FEATURE_BIT(FEAT_BLEND) | FEATURE_BIT(FEAT_CHECKER) | FEATURE_BIT(FEAT_SPHERE_LIGHT))

struct renderer {
    const struct scene *scene;
    struct world world;
    struct camera camera;
    struct shadow_sampling shadow;
    int max_depth; /* longest chain of rays, the camera ray included */
};

/* The Lambertian albedo this stage shades material m with at h (render.c). */
vec3 diffuse_albedo(const struct material *m, const struct hit *h);

/* Radiance leaving the surface at h (where r hit it) towards r's origin;
 * r is the depth-th ray of its chain. */
vec3 shade(
    const struct renderer *renderer,
    ray r,
    const struct hit *h,
    int depth,
    struct rng *rng,
    struct stats *st);

/* Radiance arriving at r.o from direction -r.d; r is the depth-th ray of
 * its chain (the camera ray is 1); chains end at max_depth rays. */
vec3 trace(const struct renderer *renderer, ray r, int depth, struct rng *rng, struct stats *st);

/* The radiance through pixel (px, py), (0, 0) top-left: one ray through its centre. */
vec3
render_pixel(const struct renderer *renderer, int px, int py, struct rng *rng, struct stats *st);

/* What the render passes (--aov) ask of this stage, its own rays (passes.c). */
struct aov_source render_passes_source(const struct renderer *renderer);

/* The driver's tile function (driver.h): each pixel's radiance for the tile's
 * pass; false when a stop cut the tile short. */
bool render_tile(const void *ctx, const struct tile *tile, struct stats *st);

#endif /* RENDER_H */
