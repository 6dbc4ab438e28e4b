/*
 * driver.h - the parallel tile renderer every stage uses.
 *
 * A stage supplies one function: the radiance estimate of one pixel for one
 * pass.  The driver cuts the image into 16x16 tiles, lets the threads take
 * tiles from a shared counter, gives every pixel its own random stream
 * (rng_for_pixel: the image does not depend on the thread count), averages
 * the passes, counts NaN/Inf pixels, draws the progress bar and keeps the
 * time.  Stages that sample progressively (07) run many passes; a pass that
 * is interrupted (Ctrl-C, time budget) is dropped whole, so the image always
 * holds an equal number of samples in every pixel.
 */
#ifndef DRIVER_H
#define DRIVER_H

#include <stdbool.h>
#include <stdint.h>

#include "diag.h"
#include "image.h"
#include "rng.h"
#include "stats.h"
#include "vec3.h"

/* Radiance estimate for pixel (px, py) (0,0 top-left) in one pass. */
typedef vec3 (*pixel_fn)(const void *ctx, int px, int py, struct rng *rng, struct stats *st);

struct render_job {
    int width, height;
    int threads; /* >= 1 */
    int passes; /* passes to run (>= 1); the image is their mean */
    double time_limit; /* seconds; stop starting passes after this (0: none) */
    uint64_t seed;
    bool progress; /* draw a progress bar on stderr */
    pixel_fn pixel;
    const void *ctx;
};

struct render_result {
    int passes_done; /* complete passes in the image */
    bool interrupted; /* stopped early by driver_request_stop() */
    uint64_t nan_pixels; /* pixels with a NaN or Inf estimate in any pass */
    struct stats counts; /* summed over threads */
    double seconds; /* wall-clock time */
    double cpu_seconds; /* processor time of all threads (steadier on a busy machine) */
};

/* The bytes driver_render_image allocates for the job, before it allocates them:
 * per pixel the image (3 floats), one pass's estimates and their running
 * sum (a vec3 each) and a NaN flag; per thread its bookkeeping. */
uint64_t driver_job_bytes(const struct render_job *job);

/* Render into out (allocated here).  Returns false only when memory or
 * threads could not be had (err says which). */
bool driver_render_image(
    const struct render_job *job,
    struct image *out,
    struct render_result *result,
    struct diag *err);

struct trace;

/* Render only pixel (px, py), pass after pass, with the random streams it
 * has in driver_render_image, recording its rays into trace (trace.h); rgb gets
 * its value as driver_render_image stores it, bit for bit.  The time limit is not
 * applied: every pass of the job is rendered. */
void driver_render_pixel_traced(
    const struct render_job *job,
    int px,
    int py,
    struct trace *trace,
    float rgb[3],
    struct render_result *result);

/* A share of one image's work, for a renderer split across processes that
 * share no memory (the browser's Web Workers, common/web/): driver_render_image
 * renders only the tiles t with t % parts == part and leaves the others 0,
 * so the images of parts 0 .. parts-1 add up to the whole image, each pixel
 * computed exactly as without a share.  After each pass, on_pass (if set)
 * gets the mean of the passes so far.  `rendered`, when set, is this job's
 * image already rendered by the parts together: driver_render_image returns a copy
 * of it instead of rendering (the pixel inspector's run, which traces one
 * pixel and draws it over the image). */
struct render_share {
    int part, parts;
    void (*on_pass)(void *ctx, const struct image *mean, int passes_done);
    void *ctx;
    const struct image *rendered;
};

/* Set the share of the renders that follow; NULL (the default): the whole
 * image. */
void driver_set_share(const struct render_share *share);

/* Ask a running driver_render_image to stop after the tiles in flight; safe to
 * call from a signal handler. */
void driver_request_stop(void);

#endif /* DRIVER_H */
