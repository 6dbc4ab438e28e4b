/*
 * render.h - what this stage computes: the radiance arriving at the camera
 * through each pixel.
 */
#ifndef RENDER_H
#define RENDER_H

#include "camera.h"
#include "geometry.h"
#include "light.h"
#include "rng.h"
#include "scene.h"
#include "stats.h"
#include "vec3.h"

/* The scene features this stage models (see feature_table.h). */
#define RENDER_FEATURES \
    (FEATURE_BIT(FEAT_POINT_LIGHT) | FEATURE_BIT(FEAT_MESH) | FEATURE_BIT(FEAT_AREA_LIGHT) \
     | FEATURE_BIT(FEAT_MIRROR) | FEATURE_BIT(FEAT_GLASS) | FEATURE_BIT(FEAT_BLEND) \
     | FEATURE_BIT(FEAT_CHECKER) | FEATURE_BIT(FEAT_ENVIRONMENT) | FEATURE_BIT(FEAT_SPHERE_LIGHT))

/* Scenes of at most this many primitives are traced without a BVH
 * (--brute-force-max; main.c says why). */
#define BRUTE_FORCE_MAX_PRIMS 16

/* Russian roulette starts once a path has this many rays (camera ray = 1),
 * unless --rr-depth says otherwise. */
#define RR_MIN_DEPTH 3

/* Russian roulette lets a path survive with probability max(beta) / this
 * (at most RR_MAX_SURVIVAL), unless --rr-threshold says otherwise: the
 * survivors carry this throughput (russian_roulette() in render.c).
 * Measured (docs/stages/07_pathtrace.md, "Where Russian roulette starts,
 * and what a survivor carries"): 0.3 to 0.5 render the Cornell boxes 1.1
 * to 1.3 times as efficiently as 1 (pbrt's and Mitsuba's rule, which makes
 * each rare long path a bright sample) from its best start; where roulette
 * starts matters far less then. */
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
    AA_SOBOL, /* Owen-scrambled Sobol points (lowdisc.h): stratified at every scale */
};

/* Where the random numbers of a path come from (ORDER: the --sampler
 * choices): its lobe, direction and Russian-roulette numbers at every
 * bounce. */
enum sampler_kind {
    SAMPLER_INDEPENDENT, /* the pixel's random stream */
    SAMPLER_SOBOL, /* Owen-scrambled Sobol points, one sequence per bounce and use */
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
    struct light_picker lights; /* the emitting triangles, picked by power */
    int max_depth; /* longest chain of rays, the camera ray included */
    int spp; /* camera samples per pixel, over all passes */
    int spp_pass; /* of which each pass takes this many */
    uint64_t seed; /* --seed: also orders each pixel's samples */
    int aa; /* enum aa_pattern */
    real aa_threshold;
    bool nee; /* next-event estimation: shadow rays to area lights */
    bool mis; /* ... combined with the paths that hit them (multiple importance sampling) */
    bool rr; /* Russian roulette */
    int rr_depth; /* ... from this many rays on */
    real rr_threshold; /* ... survival max(beta) / rr_threshold (at most RR_MAX_SURVIVAL) */
    int sampler; /* enum sampler_kind */
    real time_limit; /* seconds; 0: none */
};

/* Which sample of which pixel a path is: the pixel's scramble key (from
 * the seed and the pixel) and the sample's index among the pixel's spp.
 * The Sobol sampler draws point `index` of sequences scrambled by key,
 * from the index's bits reversed (lowdisc.h), reversed once per sample. */
struct sample_id {
    uint64_t key;
    uint32_t index;
    uint32_t index_reversed;
};

/* A path being traced: its throughput beta (the product of the sampling
 * weights so far), whether its last bounce was specular, its length, and
 * which sample it is.  With MIS, where its last bounce was diffuse: the
 * density pdf_bsdf (per steradian) of that bounce's direction and the
 * point `from` it left, which weigh a light the bounce finds (0: none). */
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

/* The driver's pixel function (driver.h): the mean radiance of the pass's
 * spp_pass camera rays through the pixel's square, placed as the aa pattern
 * says for all spp of the passes together (a box filter: SCENES.md's pixel
 * value). */
vec3 render_pixel(const void *ctx, int px, int py, int pass, struct rng *rng, struct stats *st);

#endif /* RENDER_H */
