/*
 * trace.h - replay one pixel (render --pixel X,Y --trace FILE): a recorder
 * of every ray of the pixel's samples and of the decisions the stage made
 * with them, written as an indented text tree, as JSON, or drawn as SVG
 * (docs/inspect.md).
 *
 * The recorder is reached from the per-thread statistics the shading code
 * already carries (stats.h: st->trace).  In a normal render it is NULL and
 * every trace_* call below is one test of that pointer, inlined: the render
 * loop pays nothing measurable.  With --pixel only that pixel is rendered,
 * with the samples and random numbers it gets in the full render
 * (render_pixel_traced in driver.h), so its value is the full render's bit
 * for bit.
 *
 * Events form a tree of four levels: a camera sample (0), the ray of each
 * path vertex, hit or miss (1), what the stage did at that vertex (2: a
 * light, shading, a bounce, Russian roulette), and the shadow rays and light
 * samples of a light (3).
 */
#ifndef TRACE_H
#define TRACE_H

#include <stdbool.h>
#include <stdio.h>

#include "diag.h"
#include "image.h"
#include "scene.h"
#include "stats.h"
#include "vec3.h"

/* The kinds of light a trace names (the scene's three lists). */
enum trace_light_kind {
    TRACE_POINT_LIGHT,
    TRACE_AREA_LIGHT,
    TRACE_SPHERE_LIGHT,
};

/* What the SVG draws an event's ray or segment as (its colour). */
enum trace_segment {
    SEG_NONE,
    SEG_CAMERA, /* camera ray */
    SEG_BOUNCE, /* reflected, refracted or sampled ray */
    SEG_SHADOW_CLEAR, /* shadow ray that reached its light */
    SEG_SHADOW_BLOCKED, /* shadow ray that something blocked */
    SEG_MISS, /* ray that left the scene (drawn a short way) */
};

struct trace;

/* A recorder for pixel (px, py) of a scene (which names its primitives,
 * materials and lights).  NULL when memory runs out. */
struct trace *trace_new(const struct scene *scene, int px, int py);
void trace_free(struct trace *t);

/* The driver's calls: a pass begins, and ends with the pixel's estimate for
 * it; the pixel's value (the mean of the passes, as stored in the image). */
void trace_pass_begin(struct trace *t, int pass);
void trace_pass_end(struct trace *t, vec3 estimate);
void trace_set_value(struct trace *t, const float rgb[3]);

/* The written forms: text (an indented tree, numbers rounded), JSON (every
 * number as printed by %.17g), and SVG (the paths over `image`, the full
 * render, projected through the camera, and in a top view).  Write to an
 * open stream; the caller checks it for errors. */
void trace_write_text(FILE *f, const struct trace *t);
void trace_write_json(FILE *f, const struct trace *t);
bool trace_write_svg(FILE *f, const struct trace *t, const struct image *image, struct diag *err);

/* --- the stage's calls (the recorder's side, trace.c) ------------------- */
void trace_log_sample(struct trace *t, int index, real film_x, real film_y, ray r);
void trace_log_sample_done(struct trace *t, vec3 radiance);
void trace_log_hit(
    struct trace *t,
    int depth,
    ray r,
    real dist,
    vec3 p,
    int prim,
    int material,
    vec3 ng,
    vec3 n,
    bool front_face);
void trace_log_miss(struct trace *t, int depth, ray r, vec3 radiance);
void trace_log_light(struct trace *t, enum trace_light_kind kind, int index);
void trace_log_shadow(struct trace *t, ray r, real t_max, int blocker, real blocker_dist);
void trace_log_light_sample(
    struct trace *t,
    vec3 y,
    real pdf_area,
    real pdf_solid_angle,
    vec3 irradiance);
void trace_log_adaptive(struct trace *t, int probes, int blocked, int more);
void trace_log_shade(struct trace *t, vec3 albedo, vec3 irradiance, vec3 ambient, vec3 radiance);
void trace_log_specular(struct trace *t, int depth, const char *event, real fresnel, vec3 weight);
void trace_log_bounce(
    struct trace *t,
    const char *lobe,
    vec3 d,
    real pdf,
    vec3 beta_before,
    vec3 beta_after);
void trace_log_nee(struct trace *t, vec3 radiance);
void trace_log_mis(struct trace *t, real pdf_light, real pdf_bsdf, real weight);
void trace_log_emission(struct trace *t, vec3 radiance, bool after_specular);
void trace_log_roulette(struct trace *t, real q, real u, bool survived);
void trace_log_end(struct trace *t, const char *why);

/* --- what the stage's code calls: each does nothing unless tracing ------ */

/* Whether this pixel is being traced (for work done only for the trace,
 * such as finding what blocked a shadow ray). */
static inline bool
tracing(const struct stats *st)
{
    return st->trace != NULL;
}

/* A camera sample: its film position (pixel px + the sub-pixel offset) and
 * its ray; then the radiance it brought back. */
static inline void
trace_sample(struct stats *st, int index, real film_x, real film_y, ray r)
{
    if (st->trace) {
        trace_log_sample(st->trace, index, film_x, film_y, r);
    }
}

static inline void
trace_sample_done(struct stats *st, vec3 radiance)
{
    if (st->trace) {
        trace_log_sample_done(st->trace, radiance);
    }
}

/* Ray r, the depth-th of its path (the camera ray is 1), hit primitive
 * prim (numbered spheres, quads, triangles, area lights, sphere lights) at
 * distance dist, at point p: its material (-1: none), its geometric and
 * shading normals (facing r's origin), and the side it hit. */
static inline void
trace_hit(
    struct stats *st,
    int depth,
    ray r,
    real dist,
    vec3 p,
    int prim,
    int material,
    vec3 ng,
    vec3 n,
    bool front_face)
{
    if (st->trace) {
        trace_log_hit(st->trace, depth, r, dist, p, prim, material, ng, n, front_face);
    }
}

/* Ray r, the depth-th of its path, left the scene, and brings back the
 * background's radiance (times the path's throughput, in 07). */
static inline void
trace_miss(struct stats *st, int depth, ray r, vec3 radiance)
{
    if (st->trace) {
        trace_log_miss(st->trace, depth, r, radiance);
    }
}

/* The estimate of one light's direct light begins (its shadow rays and
 * samples follow). */
static inline void
trace_light(struct stats *st, enum trace_light_kind kind, int index)
{
    if (st->trace) {
        trace_log_light(st->trace, kind, index);
    }
}

/* A shadow ray r that may travel t_max: clear (blocker -1) or blocked by
 * primitive `blocker` at blocker_dist. */
static inline void
trace_shadow(struct stats *st, ray r, real t_max, int blocker, real blocker_dist)
{
    if (st->trace) {
        trace_log_shadow(st->trace, r, t_max, blocker, blocker_dist);
    }
}

/* One sample y of the light: its densities per unit area and per unit
 * solid angle (0: not drawn that way) and the irradiance this sample
 * estimates (after its shadow rays). */
static inline void
trace_light_sample(struct stats *st, vec3 y, real pdf_area, real pdf_solid_angle, vec3 irradiance)
{
    if (st->trace) {
        trace_log_light_sample(st->trace, y, pdf_area, pdf_solid_angle, irradiance);
    }
}

/* The same for a point y drawn uniformly over an area light (density
 * 1 / its area). */
static inline void
trace_area_sample(struct stats *st, const struct area_light *light, vec3 y, vec3 irradiance)
{
    if (st->trace) {
        trace_log_light_sample(st->trace, y, 1 / area_light_area(light), 0, irradiance);
    }
}

/* A point y of an area light picked with probability `pick` among others
 * (1: sampled on its own), drawn with density pdf_solid_angle per
 * steradian: by solid angle, or uniformly over the light's area (then its
 * density per unit area, pick / area, is recorded too). */
static inline void
trace_picked_sample(
    struct stats *st,
    const struct area_light *light,
    real pick,
    vec3 y,
    real pdf_solid_angle,
    bool by_area,
    vec3 irradiance)
{
    if (st->trace) {
        real pdf_area = by_area ? pick / area_light_area(light) : 0;
        trace_log_light_sample(st->trace, y, pdf_area, pdf_solid_angle, irradiance);
    }
}

/* Adaptive shadow sampling decided: of `probes` probe rays `blocked` were
 * blocked, and `more` samples follow (a penumbra). */
static inline void
trace_adaptive(struct stats *st, int probes, int blocked, int more)
{
    if (st->trace) {
        trace_log_adaptive(st->trace, probes, blocked, more);
    }
}

/* Lambertian shading: albedo, irradiance from the lights, ambient term,
 * and the radiance it gives. */
static inline void
trace_shade(struct stats *st, vec3 albedo, vec3 irradiance, vec3 ambient, vec3 radiance)
{
    if (st->trace) {
        trace_log_shade(st->trace, albedo, irradiance, ambient, radiance);
    }
}

/* A specular decision ("mirror", "reflect", "refract", "total internal
 * reflection") at a hit of this depth, with its Fresnel term and the
 * weight of the ray it spawns. */
static inline void
trace_specular(struct stats *st, int depth, const char *event, real fresnel, vec3 weight)
{
    if (st->trace) {
        trace_log_specular(st->trace, depth, event, fresnel, weight);
    }
}

/* A sampled bounce: the lobe, the direction, its pdf (0: a delta lobe)
 * and the path's throughput before and after. */
static inline void
trace_bounce(
    struct stats *st,
    const char *lobe,
    vec3 d,
    real pdf,
    vec3 beta_before,
    vec3 beta_after)
{
    if (st->trace) {
        trace_log_bounce(st->trace, lobe, d, pdf, beta_before, beta_after);
    }
}

/* Next-event estimation added `radiance` to the path (the throughput and
 * the multiple-importance weights folded in). */
static inline void
trace_nee(struct stats *st, vec3 radiance)
{
    if (st->trace) {
        trace_log_nee(st->trace, radiance);
    }
}

/* Multiple importance sampling of a shadow ray against the bounce: the
 * densities per steradian with which the light sample and the BSDF would
 * draw its direction, and the weight given to the shadow ray; or, after
 * an emission found by a diffuse bounce, the bounce's weight (recorded
 * where pdf_bsdf > 0: elsewhere the weight is 1). */
static inline void
trace_mis(struct stats *st, real pdf_light, real pdf_bsdf, real weight)
{
    if (st->trace) {
        trace_log_mis(st->trace, pdf_light, pdf_bsdf, weight);
    }
}

/* The ray hit an emitter and adds this radiance (in 07, 0 where next-event
 * estimation already counted the light: after a diffuse bounce); whether
 * the ray was a camera ray or a specular bounce. */
static inline void
trace_emission(struct stats *st, vec3 radiance, bool after_specular)
{
    if (st->trace) {
        trace_log_emission(st->trace, radiance, after_specular);
    }
}

/* Russian roulette: survival probability q (1: not yet applied at this
 * depth), the uniform number u drawn; the path survives when u < q. */
static inline void
trace_roulette(struct stats *st, real q, real u, bool survived)
{
    if (st->trace) {
        trace_log_roulette(st->trace, q, u, survived);
    }
}

/* The path ends here, and why. */
static inline void
trace_end(struct stats *st, const char *why)
{
    if (st->trace) {
        trace_log_end(st->trace, why);
    }
}

#endif /* TRACE_H */
