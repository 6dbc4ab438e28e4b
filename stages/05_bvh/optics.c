/* optics.c - reflection, refraction and the dielectric Fresnel equations. */
#include "optics.h"

/* LAB 04: mirror reflection, Snell refraction with total internal reflection, and
 * the exact dielectric Fresnel reflectance (docs/stages/04_reflect_refract.md#lab)
 * stub: vec3
 * reflect(vec3 d, vec3 n)
 * {
 *     (void)n;
 *     return d;
 * }
 *
 * bool
 * refract(vec3 d, vec3 n, real eta, vec3 *out)
 * {
 *     (void)d;
 *     (void)n;
 *     (void)eta;
 *     (void)out;
 *     return false;
 * }
 *
 * real
 * fresnel_dielectric(real cos_i, real eta)
 * {
 *     (void)cos_i;
 *     (void)eta;
 *     return 1;
 * } */
vec3
reflect(vec3 d, vec3 n)
{
    return vec3_madd(d, n, -2 * vec3_dot(d, n));
}

/* sin^2 of the transmitted angle, from Snell: sin_t = eta sin_i. */
static real
sin2_transmitted(real cos_i, real eta)
{
    return eta * eta * fmax((real)0, 1 - cos_i * cos_i);
}

bool
refract(vec3 d, vec3 n, real eta, vec3 *out)
{
    real cos_i = -vec3_dot(d, n);
    real sin2_t = sin2_transmitted(cos_i, eta);
    if (sin2_t >= 1) {
        return false;
    }
    real cos_t = sqrt(1 - sin2_t);
    /* t = eta d + (eta cos_i - cos_t) n (pbrt 4ed, 9.3.2), renormalised
     * against rounding. */
    vec3 t = vec3_madd(vec3_scale(d, eta), n, eta * cos_i - cos_t);
    *out = vec3_normalize(t);
    return true;
}

real
fresnel_dielectric(real cos_i, real eta)
{
    real sin2_t = sin2_transmitted(cos_i, eta);
    if (sin2_t >= 1) {
        return 1;
    }
    real cos_t = sqrt(1 - sin2_t);
    /* With eta = eta_i / eta_t, dividing the textbook forms by eta_t:
     * r_s = (eta_i cos_i - eta_t cos_t) / (eta_i cos_i + eta_t cos_t)
     * r_p = (eta_t cos_i - eta_i cos_t) / (eta_t cos_i + eta_i cos_t) */
    real r_s = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    real r_p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return (r_s * r_s + r_p * r_p) / 2;
}
/* END LAB */
