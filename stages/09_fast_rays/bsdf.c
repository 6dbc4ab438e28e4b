/*
 * bsdf.c - sampling the materials' scattering for path tracing: cosine-
 * weighted diffuse bounces, mirror reflection, and glass that reflects or
 * refracts with the Fresnel probability.
 */
#include "bsdf.h"

#include "optics.h"

/* LAB 07: BSDF sampling */
vec3
sample_cosine_hemisphere(real u, real v)
{
    real r = sqrt(u);
    real phi = 2 * PI * v;
    return (vec3){r * cos(phi), r * sin(phi), safe_sqrt(1 - u)};
}

static real
channel_mean(vec3 c)
{
    return (c.x + c.y + c.z) / 3;
}

/* Glass: reflect with probability F (when u < F), refract otherwise.  Choosing each with
 * the probability of its Fresnel weight makes the weight exactly 1 (no
 * absorption), and total internal reflection is F = 1. */
static bool
sample_glass(const struct material *m, const struct hit *h, vec3 d, real u, struct bsdf_sample *out)
{
    vec3 n = vec3_dot(d, h->n) < 0 ? h->n : h->ng;
    real eta = h->front_face ? 1 / m->ior : m->ior;
    real f = fresnel_dielectric(-vec3_dot(d, n), eta);
    out->weight = vec3_splat(1);
    out->specular = true;
    if (u < f || !refract(d, n, eta, &out->d)) {
        out->d = reflect(d, n);
        out->lobe = f < 1 ? "glass reflection" : "total internal reflection";
        out->pdf = f;
        return vec3_dot(out->d, h->ng) > 0;
    }
    out->lobe = "glass refraction";
    out->pdf = 1 - f;
    return vec3_dot(out->d, h->ng) < 0;
}

bool
sample_bsdf(
    const struct material *m,
    vec3 albedo,
    const struct hit *h,
    vec3 d,
    const real u[3],
    struct bsdf_sample *out)
{
    if (m->kind == MAT_GLASS) {
        return sample_glass(m, h, d, u[0], out);
    }
    bool has_mirror = m->kind == MAT_MIRROR || m->kind == MAT_BLEND;
    vec3 mirror = has_mirror ? m->reflectance : vec3_splat(0);
    real p_mirror = channel_mean(mirror);
    real p_total = p_mirror + channel_mean(albedo);
    if (!(p_total > 0)) {
        return false;
    }
    /* One lobe, chosen in proportion to its mean reflectance; dividing by
     * that probability keeps the estimate unbiased. */
    if (u[0] * p_total < p_mirror) {
        out->d = reflect(d, h->n);
        out->weight = vec3_scale(mirror, p_total / p_mirror);
        out->specular = true;
        out->lobe = "mirror";
        out->pdf = p_mirror / p_total;
    } else {
        /* f cos / pdf = (albedo / pi) cos / (cos / pi) = albedo. */
        vec3 local = sample_cosine_hemisphere(u[1], u[2]);
        out->d = onb_to_world(onb_from_normal(h->n), local);
        out->weight = vec3_scale(albedo, p_total / (p_total - p_mirror));
        out->specular = false;
        out->lobe = "diffuse";
        out->pdf = (p_total - p_mirror) / p_total * local.z * INV_PI;
    }
    return vec3_dot(out->d, h->ng) > 0;
}

/* END LAB */
