/*
 * driver.h - the parallel tile renderer every stage uses.
 *
 * A stage supplies one function: its loop over the pixels of one tile in one
 * pass (each stage's render_tile, render.c).  The driver cuts the image into
 * 16x16 tiles, lets the threads take tiles from a shared counter, names every
 * pixel's own random stream (tile_pixel_rng: the image does not depend on
 * the thread count), averages the passes, counts NaN/Inf pixels, draws the
 * progress bar and keeps the time.  Stages that sample progressively (07) run many passes; a pass
 * that is interrupted (Ctrl-C, time budget) is dropped whole, so the image always holds an equal
 * number of samples in every pixel.
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

/* The pixels [x0, x1) x [y0, y1) of one pass (0,0 is the top-left pixel),
 * and where their estimates go: tile_put. */
struct tile {
    int x0, y0, x1, y1;
    int pass;
    uint64_t seed; /* the job's */
    int width; /* the image's: a pixel's index y * width + x names its stream */
    vec3 *out; /* the estimate of (x, y) at out[(y - y0) * stride + x - x0] */
    int stride;
};

/* A stage's tile function: each pixel's radiance estimate for the tile's
 * pass, stored with tile_put.  It asks driver_stop_requested() after each
 * pixel and returns false when a stop came (the pass is then dropped whole);
 * true when every pixel is done. */
typedef bool (*tile_fn)(const void *ctx, const struct tile *tile, struct stats *st);

/* Store the estimate of pixel (x, y) of the tile. */
static inline void
tile_put(const struct tile *tile, int x, int y, vec3 estimate)
{
    tile->out[(size_t)(y - tile->y0) * (size_t)tile->stride + (size_t)(x - tile->x0)] = estimate;
}

/* Pixel (x, y)'s own random stream in the tile's pass (rng_for_pixel). */
static inline struct rng
tile_pixel_rng(const struct tile *tile, int x, int y)
{
    uint64_t index = (uint64_t)y * (uint64_t)tile->width + (uint64_t)x;
    return rng_for_pixel(tile->seed, index, (uint64_t)tile->pass);
}

struct render_job {
    int width, height;
    int threads; /* >= 1 */
    int passes; /* passes to run (>= 1); the image is their mean */
    double time_limit; /* seconds; stop starting passes after this (0: none) */
    uint64_t seed;
    bool progress; /* draw a progress bar on stderr */
    tile_fn tile;
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

struct recorder;

/* Render only pixel (px, py), pass after pass, with the random streams it
 * has in driver_render_image, recording its rays into trace (recorder.h); rgb gets
 * its value as driver_render_image stores it, bit for bit.  The time limit is not
 * applied: every pass of the job is rendered, unless a stop is asked for
 * (then result->interrupted, and rgb is the mean of the passes done). */
void driver_render_pixel_traced(
    const struct render_job *job,
    int px,
    int py,
    struct recorder *trace,
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

/* Ask a running driver_render_image to stop after the pixels at hand; safe to
 * call from a signal handler. */
void driver_request_stop(void);

/* Whether a stop was asked for: a tile function asks after each pixel. */
bool driver_stop_requested(void);

#endif /* DRIVER_H */
