/*
 * inspect.h - what a stage's code calls to record, for --pixel --trace
 * (docs/inspect.md), the rays it traces and the decisions it makes: the
 * path inspector's calls, named inspect_* so that they read apart from the
 * lesson's own trace() and shade().  Each does nothing unless this pixel
 * is being inspected (st->recorder, the recorder of recorder.h, is not NULL).
 *
 * inspect_hit reads the stage's own struct hit (geometry.h: t, p, prim,
 * material, ng, n, front_face): include this header after it.
 */
#ifndef INSPECT_H
#define INSPECT_H

#include "recorder.h"

/* Whether this pixel is being traced (for work done only for the trace,
 * such as finding what blocked a shadow ray). */
static inline bool
inspecting(const struct stats *st)
{
    return st->recorder != NULL;
}

/* A camera sample: its film position (pixel px + the sub-pixel offset) and
 * its ray; then the radiance it brought back. */
static inline void
inspect_sample(struct stats *st, int index, real film_x, real film_y, ray r)
{
    if (st->recorder) {
        recorder_log_sample(st->recorder, index, film_x, film_y, r);
    }
}

static inline void
inspect_sample_done(struct stats *st, vec3 radiance)
{
    if (st->recorder) {
        recorder_log_sample_done(st->recorder, radiance);
    }
}

/* Ray r, the depth-th of its path (the camera ray is 1), found hit h: its
 * primitive (numbered spheres, quads, triangles, area lights, sphere
 * lights), distance, point, material (-1: none), geometric and shading
 * normals (facing r's origin) and the side it hit. */
static inline void
inspect_hit(struct stats *st, int depth, ray r, const struct hit *h)
{
    if (st->recorder) {
        recorder_log_hit(
            st->recorder, depth, r, h->t, h->p, h->prim, h->material, h->ng, h->n, h->front_face);
    }
}

/* Ray r, the depth-th of its path, left the scene, and brings back the
 * background's radiance (times the path's throughput, in 07). */
static inline void
inspect_miss(struct stats *st, int depth, ray r, vec3 radiance)
{
    if (st->recorder) {
        recorder_log_miss(st->recorder, depth, r, radiance);
    }
}

/* The estimate of one light's direct light begins (its shadow rays and
 * samples follow). */
static inline void
inspect_light(struct stats *st, enum recorder_light_kind kind, int index)
{
    if (st->recorder) {
        recorder_log_light(st->recorder, kind, index);
    }
}

/* A shadow ray r that may travel t_max: clear (blocker -1) or blocked by
 * primitive `blocker` at blocker_dist. */
static inline void
inspect_shadow(struct stats *st, ray r, real t_max, int blocker, real blocker_dist)
{
    if (st->recorder) {
        recorder_log_shadow(st->recorder, r, t_max, blocker, blocker_dist);
    }
}

/* One sample y of the light: its densities per unit area and per unit
 * solid angle (0: not drawn that way) and the irradiance this sample
 * estimates (after its shadow rays). */
static inline void
inspect_light_sample(struct stats *st, vec3 y, real pdf_area, real pdf_solid_angle, vec3 irradiance)
{
    if (st->recorder) {
        recorder_log_light_sample(st->recorder, y, pdf_area, pdf_solid_angle, irradiance);
    }
}

/* The same for a point y drawn uniformly over an area light (density
 * 1 / its area). */
static inline void
inspect_area_sample(struct stats *st, const struct area_light *light, vec3 y, vec3 irradiance)
{
    if (st->recorder) {
        recorder_log_light_sample(st->recorder, y, 1 / area_light_area(light), 0, irradiance);
    }
}

/* Adaptive shadow sampling decided: of `probes` probe rays `blocked` were
 * blocked, and `more` samples follow (a penumbra). */
static inline void
inspect_adaptive(struct stats *st, int probes, int blocked, int more)
{
    if (st->recorder) {
        recorder_log_adaptive(st->recorder, probes, blocked, more);
    }
}

/* Lambertian shading: albedo, irradiance from the lights, ambient term,
 * and the radiance it gives. */
static inline void
inspect_shade(struct stats *st, vec3 albedo, vec3 irradiance, vec3 ambient, vec3 radiance)
{
    if (st->recorder) {
        recorder_log_shade(st->recorder, albedo, irradiance, ambient, radiance);
    }
}

/* A specular decision ("mirror", "reflect", "refract", "total internal
 * reflection") at a hit of this depth, with its Fresnel term and the
 * weight of the ray it spawns. */
static inline void
inspect_specular(struct stats *st, int depth, const char *event, real fresnel, vec3 weight)
{
    if (st->recorder) {
        recorder_log_specular(st->recorder, depth, event, fresnel, weight);
    }
}

/* A sampled bounce: the lobe, the direction, its pdf (0: a delta lobe)
 * and the path's throughput before and after. */
static inline void
inspect_bounce(
    struct stats *st,
    const char *lobe,
    vec3 d,
    real pdf,
    vec3 beta_before,
    vec3 beta_after)
{
    if (st->recorder) {
        recorder_log_bounce(st->recorder, lobe, d, pdf, beta_before, beta_after);
    }
}

/* Next-event estimation added `radiance` to the path (the throughput and
 * the multiple-importance weights folded in). */
static inline void
inspect_nee(struct stats *st, vec3 radiance)
{
    if (st->recorder) {
        recorder_log_nee(st->recorder, radiance);
    }
}

/* The ray hit an emitter and adds this radiance (in 07, 0 where next-event
 * estimation already counted the light: after a diffuse bounce); whether
 * the ray was a camera ray or a specular bounce. */
static inline void
inspect_emission(struct stats *st, vec3 radiance, bool after_specular)
{
    if (st->recorder) {
        recorder_log_emission(st->recorder, radiance, after_specular);
    }
}

/* Russian roulette: survival probability q (1: not yet applied at this
 * depth), the uniform number u drawn; the path survives when u < q. */
static inline void
inspect_roulette(struct stats *st, real q, real u, bool survived)
{
    if (st->recorder) {
        recorder_log_roulette(st->recorder, q, u, survived);
    }
}

/* The path ends here, and why. */
static inline void
inspect_end(struct stats *st, const char *why)
{
    if (st->recorder) {
        recorder_log_end(st->recorder, why);
    }
}

#endif /* INSPECT_H */
