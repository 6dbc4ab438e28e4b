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
#include "sampler.h"
#include "scene.h"
#include "stats.h"
#include "vec3.h"

/* The scene features this stage models (see ../course.h). */
#define RENDER_FEATURES \
    (FEATURE_BIT(FEAT_POINT_LIGHT) | FEATURE_BIT(FEAT_MESH) | FEATURE_BIT(FEAT_AREA_LIGHT) \
     | FEATURE_BIT(FEAT_MIRROR) | FEATURE_BIT(FEAT_GLASS) | FEATURE_BIT(FEAT_BLEND) \
     | FEATURE_BIT(FEAT_CHECKER) | FEATURE_BIT(FEAT_ENVIRONMENT) | FEATURE_BIT(FEAT_SPHERE_LIGHT))

/* No BVH for scenes of at most this many primitives (--brute-force-max). */
#define BRUTE_FORCE_MAX_PRIMS 16

/* Russian roulette starts once a path has this many rays (camera ray = 1),
 * unless --rr-depth says otherwise. */
#define RR_MIN_DEPTH 3

/* The throughput roulette's survivors carry (--rr-threshold). */
#define RR_THRESHOLD 0.4

/* Russian roulette's survival probability is at most this: a path whose
 * throughput is 1 or more (white diffuse, mirror, glass) still ends with
 * probability 5% at each bounce, so even in a closed white room a path has
 * on average at most 1 / 0.05 = 20 more rays; the price is a little variance
 * on bright paths.  pbrt (3rd edition, PathIntegrator) uses the same cap. */
#define RR_MAX_SURVIVAL 0.95

/* Where a pixel's camera samples go (ORDER: the --aa choices). */
enum aa_pattern {
    AA_GRID, /* a regular k x k grid (spp = k^2) */
    AA_JITTER, /* one random sample in each cell of that grid */
    AA_ADAPTIVE, /* a few jittered samples; all spp only where they disagree */
};

/* Probe samples of adaptive sampling.  A pixel costs this many samples where
 * the probes agree (most of an image) and spp where they do not: four, about
 * one per quarter of the pixel, cost a smooth pixel 1/16 of --spp 64.  A
 * feature all the probes miss is never refined
 * (docs/stages/06_supersample.md); more probes find thinner features, but
 * every pixel pays for them. */
#define AA_PROBES 4

/* The extra statistics counter: pixels adaptive sampling refined. */
#define STAT_AA_REFINED 1

struct renderer {
    const struct scene *scene;
    struct world world;
    struct camera camera;
    struct shadow_sampling shadow;
    int max_depth; /* longest chain of rays, the camera ray included */
    int spp; /* camera samples per pixel in one pass */
    int aa; /* enum aa_pattern */
    real aa_threshold;
    bool nee; /* next-event estimation: shadow rays to area lights */
    bool rr; /* Russian roulette */
    int rr_depth; /* ... from this many rays on */
    real rr_threshold; /* ... survival max(beta) / rr_threshold (at most RR_MAX_SURVIVAL) */
    int sampler; /* enum sampler_kind */
    int brute_force_max; /* no BVH for scenes of at most this many primitives */
    bool pick_lights; /* the emitting triangles picked by power, not by area (picker.c) */
    real time_limit; /* seconds; 0: none */
};

/* The Lambertian albedo this stage shades material m with at h (render.c). */
vec3 diffuse_albedo(const struct material *m, const struct hit *h);

/* A path being traced: its throughput beta (the product of the sampling
 * weights so far), whether its last bounce was specular, and its length;
 * its sample, and for MIS its last diffuse bounce's density and origin. */
struct path {
    vec3 beta;
    bool specular;
    int depth;
    struct sample_id id;
    real pdf_bsdf;
    vec3 from;
};

/* One vertex of a path, where *r hit h: returns the light it adds to the
 * path (emission, and direct light by shadow rays), and continues the path:
 * *r becomes the next ray and path->beta its throughput (0 when it ends). */
vec3 shade(
    const struct renderer *renderer,
    ray *r,
    const struct hit *h,
    struct path *path,
    struct rng *rng,
    struct stats *st);

/* MIS (mis.c): the light at h, weighed against the shadow rays of the vertex the bounce left. */
vec3 mis_emitted(const struct renderer *renderer, const struct hit *h, const struct path *path);

/* Radiance arriving at r.o from direction -r.d, estimated by one random
 * path; r is the depth-th ray of its chain (the camera ray is 1), and none
 * beyond max_depth is traced. */
vec3 trace(
    const struct renderer *renderer,
    ray r,
    int depth,
    struct sample_id id,
    struct rng *rng,
    struct stats *st);

/* The radiance through pixel (px, py), (0, 0) top-left: the mean of spp camera
 * rays through the pixel's square, placed as the aa pattern says (a box
 * filter: SCENES.md's pixel value). */
vec3
render_pixel(const struct renderer *renderer, int px, int py, struct rng *rng, struct stats *st);

/* What the render passes (--aov) ask of this stage, its own rays (passes.c). */
struct aov_source render_passes_source(const struct renderer *renderer);

/* The driver's tile function (driver.h): each pixel's radiance for the tile's
 * pass; false when a stop cut the tile short. */
bool render_tile(const void *ctx, const struct tile *tile, struct stats *st);

#endif /* RENDER_H */
