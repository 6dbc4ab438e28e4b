/*
 * light.h - light arriving directly from the scene's lights.
 */
#ifndef LIGHT_H
#define LIGHT_H

#include "geometry.h"
#include "light_picker.h"
#include "rng.h"
#include "sampler.h"
#include "scene.h"
#include "stats.h"
#include "vec3.h"

/* Irradiance (W/m^2 per channel) that a point source of intensity I at
 * `from` delivers to the surface at h: I cos(theta) / r^2, zero when the
 * light is behind the surface.  Occlusion is the caller's business. */
vec3 point_irradiance(const struct hit *h, vec3 from, vec3 intensity);

/* How area lights are sampled: `samples` shadow rays per light, or, when
 * adaptive[0] > 0, adaptive[0] probe rays and adaptive[1] more only where
 * the probes disagree (a penumbra); the emitting triangles picked by picker
 * (light_picker.h; NULL: every area light on its own);
 * the numbers of sample id at the depth-th vertex (sampler.h), MIS (mis.c). */
struct shadow_sampling {
    int samples;
    int adaptive[2];
    const struct light_picker *picker;
    struct sample_id id;
    int depth;
    bool mis;
    int picked; /* > 0: a ray of `picked` to picked triangles (MIS weighs by them) */
};

/* The extra statistics counter: shading points that took the penumbra path. */
#define STAT_PENUMBRA 0

/* The point of the light at (u, v) in [0,1)^2: uniform over its area. */
vec3 sample_area_light(const struct area_light *light, real u, real v);

/* A light the shadow rays sample: an area light or a sphere light (the other NULL). */
struct emitter {
    const struct area_light *area;
    const struct sphere_light *sphere;
};

/* One sample of a sphere light's irradiance at h: a direction drawn from
 * (u, v) uniformly over the cone the sphere subtends, and L cos(theta) Omega
 * for it, Omega = 2 pi (1 - cos(theta_max)), sin(theta_max) = r / d (Shirley,
 * Wang and Zimmerman 1996; pbrt 4ed, 6.2.4); *blocked: was its ray? */
vec3 sphere_sample_irradiance(
    const struct world *w,
    const struct hit *h,
    const struct shadow_sampling *sampling,
    const struct sphere_light *light,
    real u,
    real v,
    struct stats *st,
    bool *blocked);

/* The light's irradiance at h with nothing in the way, in closed form, into *e.
 * A polygon of radiance L clipped to h's horizon: E = L/2 |sum_i theta_i n . g_i|,
 * theta_i the angle its edge (v_i, v_i+1) subtends at h, g_i the unit normal of
 * the plane through h and that edge (Lambert 1760; Arvo 1995, "Applications of
 * Irradiance Tensors").  A sphere: pi L sin^2(theta_max) cos(alpha), that of a
 * point of intensity pi L r^2 at its centre; false where the horizon cuts it. */
bool unoccluded_irradiance(const struct hit *h, const struct emitter *light, vec3 *e);

/* For --pixel --trace (inspect.h), called only when inspecting: record the
 * shadow ray and, when it is not clear, the nearest surface in its way
 * (found by a second, closest-hit query). */
void
inspect_shadow_ray(const struct world *w, ray shadow, real t_max, bool clear, struct stats *st);

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

/* mis.c: the weight of a shadow ray drawn with density pdf_light per
 * steradian at cos_surface to the normal (1 without MIS). */
real mis_shadow_weight(const struct shadow_sampling *sampling, real pdf_light, real cos_surface);

/* picker.c: a triangle light's share of the picks, its power (stage 07's is its area). */
double light_weight_power(const struct area_light *light);

#endif /* LIGHT_H */
