/*
 * benchlib.h - what the BVH benchmarks share: a model loaded through the
 * scene loader and framed by a camera, its camera rays and shadow rays, and
 * a timer that traces a batch of rays on N threads.
 *
 * Timings are wall-clock seconds, the best of several runs: the benchmarks
 * run on shared machines, and the best run is the one least disturbed.
 */
#ifndef BENCHLIB_H
#define BENCHLIB_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "bvh.h"
#include "camera.h"
#include "diag.h"
#include "geometry.h"
#include "stats.h"

#define BENCH_WIDTH 600
#define BENCH_HEIGHT 600
#define BENCH_RUNS 5 /* each timing is the best of this many runs */

/* The vector instructions the build may use (make NATIVE=1: the processor's). */
#if defined __AVX2__
#define BENCH_ISA "AVX2"
#elif defined __AVX__
#define BENCH_ISA "AVX"
#else
#define BENCH_ISA "128-bit vectors (SSE2 on x86-64, NEON on arm64)"
#endif

/* A model and what is traced through it.  It points into itself (world at
 * scene): never copy one. */
struct bench_model {
    char name[64];
    struct scene scene;
    struct world world; /* the numbering, and the BVH built by bench_build */
    struct camera camera; /* frames the model in a BENCH_WIDTH x BENCH_HEIGHT image */
    vec3 light; /* the point light shadow rays go to */
    real offset; /* how far shadow rays start off the surface */
    double seconds_load;
    double seconds_build; /* best of BENCH_RUNS builds */
};

/* Rays, each with its own t_max. */
struct ray_batch {
    ray *rays;
    real *t_max;
    size_t n;
};

/* The models the benchmarks time unless told otherwise, from the project
 * root: the generated 1.08M-triangle Buddha (make models) and the bunny. */
#define BENCH_BIG_MODEL "build/models/happy_res3_subdiv16.glb"
#define BENCH_SMALL_MODEL "scenes/models/bunny.glb"

/* The model at path (a glTF mesh; relative to the working directory) through
 * the scene loader, framed.  False when it cannot be loaded (err says why: a
 * missing file, no glTF support). */
bool bench_load(struct bench_model *m, const char *path, struct diag *err);

/* A closed UV sphere of n_bands x 2 n_bands quads (4 n_bands^2 triangles)
 * made in memory, framed: the stand-in when the assets are absent. */
bool bench_generate_sphere(struct bench_model *m, int n_bands, struct diag *err);

/* Build m's BVH BENCH_RUNS times and keep the last, timing the best. */
bool bench_build(struct bench_model *m, struct diag *err);

void bench_model_free(struct bench_model *m);

/* One ray through the centre of every pixel, t_max = REAL_MAX. */
bool bench_camera_rays(const struct bench_model *m, struct ray_batch *out);

/* For every camera ray that hits a surface lit from the side the camera
 * sees, the shadow ray from the hit (moved off the surface) to the light. */
bool bench_shadow_rays(
    const struct bench_model *m,
    const struct ray_batch *camera,
    struct ray_batch *out);

void ray_batch_free(struct ray_batch *b);

/* Trace one ray; true on a hit.  ctx is what bench_time was given. */
typedef bool (*bench_trace_fn)(const void *ctx, ray r, real t_max, struct stats *st);

struct bench_result {
    double seconds; /* best of the runs */
    size_t rays; /* rays traced per run */
    uint64_t hits;
    struct stats counts; /* of one run */
};

/* Trace every stride-th ray of b (stride 1: all) on `threads` threads, the
 * best of `runs` runs.  False when threads or memory cannot be had. */
bool bench_time(
    const struct ray_batch *b,
    size_t stride,
    int threads,
    int runs,
    bench_trace_fn trace,
    const void *ctx,
    struct bench_result *out);

/* Millions of rays per second. */
double bench_mrays(const struct bench_result *r);

/* The trace functions of our BVH and of the brute-force loop; ctx is a
 * struct bench_model. */
bool bench_bvh_closest(const void *ctx, ray r, real t_max, struct stats *st);
bool bench_bvh_any(const void *ctx, ray r, real t_max, struct stats *st);
bool bench_brute_closest(const void *ctx, ray r, real t_max, struct stats *st);

#endif /* BENCHLIB_H */
