/* optics.c - reflection, refraction and the dielectric Fresnel equations. */
#include "optics.h"

/* LAB 04: reflection, refraction, Fresnel */
vec3
reflect(vec3 d, vec3 n)
{
    return vec3_madd(d, n, -2 * vec3_dot(d, n));
}

/*
 * cos^2 of the transmitted angle, from Snell (sin_t = eta sin_i):
 * 1 - eta^2 (1 - cos_i^2), summed as (1 - eta^2) + eta^2 cos_i^2.  The two
 * are equal in exact arithmetic, but the first rounds 1 - cos_i^2 to 1
 * within 1e-8 rad of grazing (1e-4 in float), so that index 1 - no boundary
 * at all - reflected everything there; the second is exact for eta = 1
 * (cos_t = cos_i).  Zero or less: total internal reflection.
 */
static real
cos2_transmitted(real cos_i, real eta)
{
    return (1 - eta * eta) + eta * eta * cos_i * cos_i;
}

bool
refract(vec3 d, vec3 n, real eta, vec3 *out)
{
    real cos_i = -vec3_dot(d, n);
    real cos2_t = cos2_transmitted(cos_i, eta);
    if (cos2_t <= 0) {
        return false;
    }
    real cos_t = sqrt(cos2_t);
    /* t = eta d + (eta cos_i - cos_t) n (pbrt 4ed, 9.3.2), renormalised
     * against rounding. */
    vec3 t = vec3_madd(vec3_scale(d, eta), n, eta * cos_i - cos_t);
    *out = vec3_normalize(t);
    return true;
}

real
fresnel_dielectric(real cos_i, real eta)
{
    real cos2_t = cos2_transmitted(cos_i, eta);
    if (cos2_t <= 0) {
        return 1;
    }
    real cos_t = sqrt(cos2_t);
    /* With eta = eta_i / eta_t, dividing the textbook forms by eta_t:
     * r_s = (eta_i cos_i - eta_t cos_t) / (eta_i cos_i + eta_t cos_t)
     * r_p = (eta_t cos_i - eta_i cos_t) / (eta_t cos_i + eta_i cos_t) */
    real r_s = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    real r_p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return (r_s * r_s + r_p * r_p) / 2;
}

/* END LAB */
