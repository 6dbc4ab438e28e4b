/*
 * light.h - light arriving directly from the scene's lights.
 */
#ifndef LIGHT_H
#define LIGHT_H

#include "geometry.h"
#include "scene.h"
#include "stats.h"
#include "vec3.h"

/* Irradiance (W/m^2 per channel) that a point source of intensity I at
 * `from` delivers to the surface at h: I cos(theta) / r^2, zero when the
 * light is behind the surface.  Occlusion is the caller's business. */
vec3 point_irradiance(const struct hit *h, vec3 from, vec3 intensity);

/* Intensity (W/sr) towards p of an area light approximated as a point at its
 * centre: L * A * cos(angle between its normal and p), zero behind it.
 * Exact in the limit of a light far away compared with its size. */
vec3 area_light_intensity(const struct area_light *light, vec3 p);

/* For --pixel --trace (inspect.h), called only when inspecting: record the
 * shadow ray and, when it is not clear, the nearest surface in its way
 * (found by a second, closest-hit query). */
void
inspect_shadow_ray(const struct world *w, ray shadow, real t_max, bool clear, struct stats *st);

/* Whether the segment from the surface at h to the point `to` is clear:
 * one shadow ray, an any-hit query. */
bool visible(const struct world *w, const struct hit *h, vec3 to, struct stats *st);

/* Irradiance at h from every light of the scene that h can see. */
vec3 direct_irradiance(const struct world *w, const struct hit *h, struct stats *st);

#endif /* LIGHT_H */
