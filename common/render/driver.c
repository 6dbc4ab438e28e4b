/*
 * driver.c - tiles, threads, passes, progress (see driver.h).
 *
 * Each pass: the main thread and threads-1 workers take 16x16 tiles from an
 * atomic counter and write one estimate per pixel into the pass buffer.
 * When every tile is done, the pass is added to the running sum.  Pixels
 * never share a random stream, and sums are formed in pixel order after the
 * pass, so the result is the same bit for bit with any number of threads.
 */
#include "driver.h"

#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "recorder.h"

#define TILE_SIZE 16

static volatile sig_atomic_t stop_requested;
static const struct render_share *share; /* NULL: the whole image */

struct pass_state {
    const struct render_job *job;
    int pass;
    int tiles_x, n_tiles;
    atomic_int next_tile;
    atomic_int tiles_done;
    vec3 *values; /* this pass's estimate, one per pixel */
    double start, last_draw;
    pthread_mutex_t draw_lock;
};

struct worker {
    struct pass_state *ps;
    struct stats counts;
    pthread_t thread;
};

void
driver_set_share(const struct render_share *s)
{
    share = s;
}

/* Whether this process renders the tile (render_share). */
static bool
tile_is_ours(int tile)
{
    return !share || tile % share->parts == share->part;
}

void
driver_request_stop(void)
{
    stop_requested = 1;
}

bool
driver_stop_requested(void)
{
    return stop_requested != 0;
}

static void
draw_progress(struct pass_state *ps, bool final)
{
    const struct render_job *job = ps->job;
    double now = stats_clock_seconds();
    if (!final && now - ps->last_draw < 0.1) {
        return;
    }
    ps->last_draw = now;
    double done = ps->pass + (double)atomic_load(&ps->tiles_done) / ps->n_tiles;
    double fraction = final ? 1.0 : done / job->passes;
    double elapsed = now - ps->start;
    if (job->time_limit > 0 && elapsed / job->time_limit > fraction) {
        fraction = elapsed / job->time_limit;
    }
    fraction = fraction > 1 ? 1 : fraction;
    int bar = (int)(fraction * 30);
    double eta = fraction > 0 ? elapsed / fraction - elapsed : 0;
    fprintf(
        stderr,
        "\r[%.*s%.*s] %3d%%  %.1f s  ETA %.1f s  pass %d/%d ",
        bar,
        "##############################",
        30 - bar,
        "                              ",
        (int)(fraction * 100),
        elapsed,
        eta,
        ps->pass + (final ? 0 : 1),
        job->passes);
    if (final) {
        fprintf(stderr, "\n");
    }
    fflush(stderr);
}

/* Whether the tile was finished (a stop may cut it short).  The stage's
 * tile function sees the stop after the pixel at hand, not after the tile:
 * a tile of a heavy scene takes many seconds, and a stop must come within
 * one.  A tile cut short is not counted done, so the pass it belongs to is
 * never used (run_pass). */
static bool
render_tile(struct pass_state *ps, int tile, struct stats *st)
{
    const struct render_job *job = ps->job;
    struct tile t = {.pass = ps->pass, .seed = job->seed, .width = job->width};
    t.x0 = (tile % ps->tiles_x) * TILE_SIZE;
    t.y0 = (tile / ps->tiles_x) * TILE_SIZE;
    t.x1 = t.x0 + TILE_SIZE < job->width ? t.x0 + TILE_SIZE : job->width;
    t.y1 = t.y0 + TILE_SIZE < job->height ? t.y0 + TILE_SIZE : job->height;
    t.out = ps->values + (size_t)t.y0 * (size_t)job->width + (size_t)t.x0;
    t.stride = job->width;
    return job->tile(job->ctx, &t, st);
}

static void *
work(void *arg)
{
    struct worker *w = arg;
    struct pass_state *ps = w->ps;
    /* Count on this thread's stack: counters of neighbouring workers share
     * cache lines, and updating them per ray would make the threads fight
     * over those lines (false sharing). */
    struct stats counts = {0};
    while (!stop_requested) {
        int tile = atomic_fetch_add(&ps->next_tile, 1);
        if (tile >= ps->n_tiles) {
            break;
        }
        if (tile_is_ours(tile) && !render_tile(ps, tile, &counts)) {
            break;
        }
        atomic_fetch_add(&ps->tiles_done, 1);
        if (ps->job->progress && pthread_mutex_trylock(&ps->draw_lock) == 0) {
            draw_progress(ps, false);
            pthread_mutex_unlock(&ps->draw_lock);
        }
    }
    stats_add(&w->counts, &counts);
    return NULL;
}

/* Run one pass on all threads; false if it was interrupted or threads could
 * not be started (then *thread_error is set). */
static bool
run_pass(struct pass_state *ps, struct worker *workers, int n_threads, bool *thread_error)
{
    atomic_store(&ps->next_tile, 0);
    atomic_store(&ps->tiles_done, 0);
    int started = 1;
    for (int i = 1; i < n_threads; i++, started++) {
        workers[i].ps = ps;
        if (pthread_create(&workers[i].thread, NULL, work, &workers[i]) != 0) {
            *thread_error = true;
            break;
        }
    }
    workers[0].ps = ps;
    work(&workers[0]);
    for (int i = 1; i < started; i++) {
        pthread_join(workers[i].thread, NULL);
    }
    return !*thread_error && atomic_load(&ps->tiles_done) == ps->n_tiles;
}

/* Add one pass's estimate of a pixel to its sum; a non-finite estimate
 * flags the pixel (counted once in nan_pixels) and contributes 0 (the
 * guard). */
static void
accumulate(vec3 v, vec3 *sum, unsigned char *bad)
{
    if (!vec3_is_finite(v)) {
        *bad = 1;
        v = vec3_splat(0);
    }
    *sum = vec3_add(*sum, v);
}

static void
accumulate_pass(const vec3 *values, size_t n, vec3 *sum, unsigned char *bad)
{
    for (size_t i = 0; i < n; i++) {
        accumulate(values[i], &sum[i], &bad[i]);
    }
}

/* The pixel as the image stores it: the mean of its passes, in float. */
static void
store_mean(vec3 sum, int passes, float *rgb)
{
    real scale = passes > 0 ? 1 / (real)passes : 0;
    vec3 mean = vec3_scale(sum, scale);
    rgb[0] = (float)mean.x;
    rgb[1] = (float)mean.y;
    rgb[2] = (float)mean.z;
}

static void
write_mean(const vec3 *sum, int passes, struct image *out)
{
    size_t n = (size_t)out->width * (size_t)out->height;
    for (size_t i = 0; i < n; i++) {
        store_mean(sum[i], passes, &out->rgb[3 * i]);
    }
}

static uint64_t
count_flagged(const unsigned char *bad, size_t n)
{
    uint64_t count = 0;
    for (size_t i = 0; i < n; i++) {
        count += bad[i];
    }
    return count;
}

/* The share's image of this job, rendered already (render_share): copied,
 * as if its passes had just been run. */
static bool
copy_rendered(const struct render_job *job, struct image *out, struct render_result *result)
{
    const struct image *done = share->rendered;
    if (done->width != job->width || done->height != job->height) {
        return false;
    }
    size_t floats = 3 * (size_t)job->width * (size_t)job->height;
    memcpy(out->rgb, done->rgb, floats * sizeof *out->rgb);
    result->passes_done = job->passes;
    return true;
}

uint64_t
driver_job_bytes(const struct render_job *job)
{
    uint64_t per_pixel = 3 * sizeof(float) + 2 * sizeof(vec3) + sizeof(unsigned char);
    uint64_t pixels = (uint64_t)job->width * (uint64_t)job->height;
    return pixels * per_pixel + (uint64_t)job->threads * sizeof(struct worker);
}

bool
driver_render_image(
    const struct render_job *job,
    struct image *out,
    struct render_result *result,
    struct diag *err)
{
    *result = (struct render_result){0};
    if (!image_alloc(out, job->width, job->height, err)) {
        return false;
    }
    if (share && share->rendered && copy_rendered(job, out, result)) {
        return true;
    }
    size_t n = (size_t)job->width * (size_t)job->height;
    struct pass_state ps = {.job = job};
    ps.tiles_x = (job->width + TILE_SIZE - 1) / TILE_SIZE;
    ps.n_tiles = ps.tiles_x * ((job->height + TILE_SIZE - 1) / TILE_SIZE);
    /* Zeroed: the tiles of other shares (render_share) are never written. */
    ps.values = calloc(n, sizeof *ps.values);
    vec3 *sum = calloc(n, sizeof *sum);
    unsigned char *bad = calloc(n, 1);
    struct worker *workers = calloc((size_t)job->threads, sizeof *workers);
    bool ok = ps.values && sum && bad && workers;
    if (!ok) {
        diag_set(err, NULL, 0, 0, "out of memory for a %dx%d image", job->width, job->height);
    }
    pthread_mutex_init(&ps.draw_lock, NULL);
    ps.start = stats_clock_seconds();
    clock_t cpu_start = clock();
    bool thread_error = false;
    for (ps.pass = 0; ok && ps.pass < job->passes && !stop_requested; ps.pass++) {
        bool over_time = job->time_limit > 0 && stats_clock_seconds() - ps.start >= job->time_limit;
        if (over_time && ps.pass > 0) {
            break;
        }
        if (!run_pass(&ps, workers, job->threads, &thread_error)) {
            break;
        }
        accumulate_pass(ps.values, n, sum, bad);
        result->passes_done++;
        if (share && share->on_pass) {
            write_mean(sum, result->passes_done, out);
            share->on_pass(share->ctx, out, result->passes_done);
        }
    }
    if (thread_error) {
        diag_set(err, NULL, 0, 0, "cannot start %d threads", job->threads);
        ok = false;
    }
    if (ok) {
        if (job->progress) {
            draw_progress(&ps, true);
        }
        write_mean(sum, result->passes_done, out);
        result->nan_pixels = count_flagged(bad, n);
        result->interrupted = stop_requested != 0;
        result->seconds = stats_clock_seconds() - ps.start;
        result->cpu_seconds = (double)(clock() - cpu_start) / CLOCKS_PER_SEC;
        for (int i = 0; i < job->threads; i++) {
            stats_add(&result->counts, &workers[i].counts);
        }
    } else {
        image_free(out);
    }
    pthread_mutex_destroy(&ps.draw_lock);
    free(ps.values);
    free(sum);
    free(bad);
    free(workers);
    return ok;
}

void
driver_render_pixel_traced(
    const struct render_job *job,
    int px,
    int py,
    struct recorder *trace,
    float rgb[3],
    struct render_result *result)
{
    *result = (struct render_result){0};
    double start = stats_clock_seconds();
    clock_t cpu_start = clock();
    vec3 sum = vec3_splat(0);
    unsigned char bad = 0;
    struct stats st = {.recorder = trace};
    for (int pass = 0; pass < job->passes; pass++) {
        recorder_pass_begin(trace, pass);
        vec3 v = vec3_splat(0);
        struct tile one = {px, py, px + 1, py + 1, pass, job->seed, job->width, &v, 1};
        bool finished = job->tile(job->ctx, &one, &st);
        recorder_pass_end(trace, v);
        if (!finished) {
            result->interrupted = true; /* a stop: the passes done so far */
            break;
        }
        accumulate(v, &sum, &bad);
        result->passes_done++;
    }
    store_mean(sum, result->passes_done, rgb);
    recorder_set_value(trace, rgb);
    st.recorder = NULL;
    result->counts = st;
    result->nan_pixels = bad;
    result->seconds = stats_clock_seconds() - start;
    result->cpu_seconds = (double)(clock() - cpu_start) / CLOCKS_PER_SEC;
}
