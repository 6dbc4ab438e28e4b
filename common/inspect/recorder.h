/*
 * recorder.h - replay one pixel (render --pixel X,Y --trace FILE): a recorder
 * of every ray of the pixel's samples and of the decisions the stage made
 * with them, written as an indented text tree, as JSON, or drawn as SVG
 * (docs/inspect.md).
 *
 * The stage's code records through inspect.h (inspect_hit, inspect_shade,
 * ...), each call one test of the per-thread recorder pointer (stats.h:
 * st->recorder), NULL in a normal render: the render loop pays nothing
 * measurable.  This header is the recorder's side: the driver's calls, the
 * writers, and the recorder_log_* functions inspect.h forwards to.  With
 * --pixel only that pixel is rendered, with the samples and random numbers
 * it gets in the full render (driver_render_pixel_traced in driver.h), so its value
 * is the full render's bit for bit.
 *
 * Events form a tree of four levels: a camera sample (0), the ray of each
 * path vertex, hit or miss (1), what the stage did at that vertex (2: a
 * light, shading, a bounce, Russian roulette), and the shadow rays and light
 * samples of a light (3).
 */
#ifndef RECORDER_H
#define RECORDER_H

#include <stdbool.h>
#include <stdio.h>

#include "diag.h"
#include "image.h"
#include "scene.h"
#include "stats.h"
#include "vec3.h"

/* The kinds of light a trace names (the scene's three lists). */
enum recorder_light_kind {
    RECORDER_POINT_LIGHT,
    RECORDER_AREA_LIGHT,
    RECORDER_SPHERE_LIGHT,
};

/* What the SVG draws an event's ray or segment as (its colour). */
enum recorder_segment {
    SEG_NONE,
    SEG_CAMERA, /* camera ray */
    SEG_BOUNCE, /* reflected, refracted or sampled ray */
    SEG_SHADOW_CLEAR, /* shadow ray that reached its light */
    SEG_SHADOW_BLOCKED, /* shadow ray that something blocked */
    SEG_MISS, /* ray that left the scene (drawn a short way) */
};

struct recorder;

/* A recorder for pixel (px, py) of a scene (which names its primitives,
 * materials and lights).  NULL when memory runs out. */
struct recorder *recorder_new(const struct scene *scene, int px, int py);
void recorder_free(struct recorder *t);

/* The driver's calls: a pass begins, and ends with the pixel's estimate for
 * it; the pixel's value (the mean of the passes, as stored in the image). */
void recorder_pass_begin(struct recorder *t, int pass);
void recorder_pass_end(struct recorder *t, vec3 estimate);
void recorder_set_value(struct recorder *t, const float rgb[3]);

/* The stage's camera, as the SVG draws through it: its camera_ray
 * (camera.h), the ray through a film position in pixels. */
struct recorder_camera {
    const void *ctx;
    ray (*camera_ray)(const void *ctx, real film_x, real film_y);
};

/* The written forms: text (an indented tree, numbers rounded), JSON (every
 * number as printed by %.17g), and SVG (the paths over `image`, the full
 * render, projected through the stage's camera, and in a top view).  Write
 * to an open stream; the caller checks it for errors. */
void recorder_write_text(FILE *f, const struct recorder *t);
void recorder_write_json(FILE *f, const struct recorder *t);
bool recorder_write_svg(
    FILE *f,
    const struct recorder *t,
    const struct image *image,
    const struct recorder_camera *camera,
    struct diag *err);

/* --- what inspect.h forwards to (the recorder's side) -------------------- */
void recorder_log_sample(struct recorder *t, int index, real film_x, real film_y, ray r);
void recorder_log_sample_done(struct recorder *t, vec3 radiance);
void recorder_log_hit(
    struct recorder *t,
    int depth,
    ray r,
    real dist,
    vec3 p,
    int prim,
    int material,
    vec3 ng,
    vec3 n,
    bool front_face);
void recorder_log_miss(struct recorder *t, int depth, ray r, vec3 radiance);
void recorder_log_light(struct recorder *t, enum recorder_light_kind kind, int index);
void recorder_log_shadow(struct recorder *t, ray r, real t_max, int blocker, real blocker_dist);
void recorder_log_light_sample(
    struct recorder *t,
    vec3 y,
    real pdf_area,
    real pdf_solid_angle,
    vec3 irradiance);
void recorder_log_adaptive(struct recorder *t, int probes, int blocked, int more);
void
recorder_log_shade(struct recorder *t, vec3 albedo, vec3 irradiance, vec3 ambient, vec3 radiance);
void
recorder_log_specular(struct recorder *t, int depth, const char *event, real fresnel, vec3 weight);
void recorder_log_bounce(
    struct recorder *t,
    const char *lobe,
    vec3 d,
    real pdf,
    vec3 beta_before,
    vec3 beta_after);
void recorder_log_nee(struct recorder *t, vec3 radiance);
void recorder_log_emission(struct recorder *t, vec3 radiance, bool after_specular);
void recorder_log_roulette(struct recorder *t, real q, real u, bool survived);
void recorder_log_end(struct recorder *t, const char *why);

#endif /* RECORDER_H */
