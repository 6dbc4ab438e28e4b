/*
 * light.h - light arriving directly from the scene's lights.
 */
#ifndef LIGHT_H
#define LIGHT_H

#include "geometry.h"
#include "rng.h"
#include "scene.h"
#include "stats.h"
#include "vec3.h"

/* Irradiance (W/m^2 per channel) that a point source of intensity I at
 * `from` delivers to the surface at h: I cos(theta) / r^2, zero when the
 * light is behind the surface.  Occlusion is the caller's business. */
vec3 point_irradiance(const struct hit *h, vec3 from, vec3 intensity);

/* How area lights are sampled: `samples` shadow rays per light, or, when
 * adaptive[0] > 0, adaptive[0] probe rays and adaptive[1] more only where
 * the probes disagree (a penumbra).  lowdisc...: the Sobol sampler's
 * (sampler.c). */
struct shadow_sampling {
    int samples;
    int adaptive[2];
    bool lowdisc;
    uint64_t lowdisc_seed;
    uint32_t lowdisc_index;
};

/* The extra statistics counter: shading points that took the penumbra path. */
#define STAT_PENUMBRA 0

/* The point of the light at (u, v) in [0,1)^2: uniform over its area. */
vec3 sample_area_light(const struct area_light *light, real u, real v);

/* For --pixel --trace (inspect.h), called only when inspecting: record the
 * shadow ray and, when it is not clear, the nearest surface in its way
 * (found by a second, closest-hit query). */
void inspect_shadow_ray(const struct world *w, ray shadow, real t_max, bool clear, struct stats *st);

/* Whether the segment from the surface at h to the point `to` is clear:
 * one shadow ray, an any-hit query. */
bool visible(const struct world *w, const struct hit *h, vec3 to, struct stats *st);

/* The fraction of light from `to` that reaches h: 1 or 0, glass included
 * (light through glass arrives along the path's own specular bounces). */
vec3 transmittance(const struct world *w, const struct hit *h, vec3 to, struct stats *st);

/* Irradiance at h from every light of the scene that h can see; area
 * lights are sampled with shadow rays as `sampling` says. */
vec3 direct_irradiance(
    const struct world *w,
    const struct hit *h,
    const struct shadow_sampling *sampling,
    struct rng *rng,
    struct stats *st);

#endif /* LIGHT_H */
