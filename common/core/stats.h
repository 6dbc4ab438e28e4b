/*
 * stats.h - what a run did: counters kept per thread while rendering, and
 * the report printed at the end and written by --stats as JSON.
 *
 * Counters are per thread (no atomics in the hot path) and summed when the
 * threads finish.  A stage may name up to STATS_MAX_EXTRA counters of its own
 * (e.g. "penumbra_pixels") and add run-level values (e.g. "bvh_nodes").
 */
#ifndef STATS_H
#define STATS_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "diag.h"

#define STATS_MAX_EXTRA 6
#define REPORT_MAX_VALUES 24

struct recorder;

struct stats {
    struct recorder *recorder; /* the recorder of --pixel --trace (recorder.h); NULL in a render */
    uint64_t rays_camera; /* primary rays */
    uint64_t rays_shadow; /* visibility (any-hit) rays */
    uint64_t rays_secondary; /* reflected, refracted, path-continuation rays */
    uint64_t prim_tests; /* ray-primitive intersection tests */
    uint64_t node_visits; /* BVH nodes visited (0 before stage 05) */
    uint64_t extra[STATS_MAX_EXTRA];
};

static inline void
stats_add(struct stats *into, const struct stats *from)
{
    into->rays_camera += from->rays_camera;
    into->rays_shadow += from->rays_shadow;
    into->rays_secondary += from->rays_secondary;
    into->prim_tests += from->prim_tests;
    into->node_visits += from->node_visits;
    for (int i = 0; i < STATS_MAX_EXTRA; i++) {
        into->extra[i] += from->extra[i];
    }
}

struct report_value {
    char key[48];
    double value;
    bool integer; /* print without a fraction */
};

struct report {
    const char *stage;
    const char *scene;
    int width, height, spp, threads;
    uint64_t seed;
    double seconds_total, seconds_load, seconds_build, seconds_render;
    double seconds_render_cpu; /* processor time of the render, all threads */
    struct stats counts;
    const char *extra_names[STATS_MAX_EXTRA]; /* names of the stage's counters; NULL: unused */
    uint64_t nan_pixels; /* pixels that came out NaN or Inf before the guard */
    uint64_t peak_rss_bytes;
    struct report_value values[REPORT_MAX_VALUES];
    int n_values;
};

/* Add (or replace) a run-level value; integer values print without a
 * fraction.  Silently ignored past REPORT_MAX_VALUES (a programming error
 * caught by the stats tests). */
void stats_report_set(struct report *r, const char *key, double value, bool integer);

/* The short human report: time, rays by kind, rays/s. */
void stats_report_print(FILE *f, const struct report *r);

/* One JSON object with every key of CONTRACT.md plus the stage's own;
 * written through a temporary file renamed into place. */
bool stats_report_write_json(const struct report *r, const char *path, struct diag *err);

/* The same object written to an open stream (standard output, or an atomic
 * file the caller finishes); the caller checks the stream for errors. */
void stats_report_write_json_to(FILE *f, const struct report *r);

/* Seconds on a monotonic clock (an arbitrary origin). */
double stats_clock_seconds(void);

/* Peak resident set size of this process, bytes (0 if unknown). */
uint64_t stats_peak_rss_bytes(void);

#endif /* STATS_H */
