/*
 * optics.h - perfect specular reflection and refraction, and the exact
 * Fresnel reflectance of a smooth dielectric boundary.
 *
 * Directions follow one convention: d is the direction a ray travels (it
 * points INTO the surface), n is the unit normal on the side d comes from
 * (dot(d, n) < 0).
 */
#ifndef OPTICS_H
#define OPTICS_H

#include <stdbool.h>

#include "vec3.h"

/* The mirror direction of d about n: d - 2 (d.n) n. */
vec3 reflect(vec3 d, vec3 n);

/* The refracted direction by Snell's law, eta = eta_i / eta_t (the index
 * the ray leaves over the index it enters).  False on total internal
 * reflection. */
bool refract(vec3 d, vec3 n, real eta, vec3 *out);

/* Fraction of unpolarised light reflected at a smooth boundary, for the
 * cosine of the incidence angle cos_i (> 0) and eta = eta_i / eta_t:
 * the mean of the s and p Fresnel reflectances (Born and Wolf, Principles of
 * Optics, 1.5.2); 1 beyond the critical angle (total internal reflection). */
real fresnel_dielectric(real cos_i, real eta);

#endif /* OPTICS_H */
