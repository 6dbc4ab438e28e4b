/*
 * mis.c - multiple importance sampling (Veach and Guibas 1995; Veach's
 * thesis, 1997, 9.2): a light reaches a diffuse point by n shadow rays
 * (density p_light per steradian) and by the bounce that hits it (p_bsdf,
 * taken as cos / pi whatever the lobe).  Both count it, weighted by the
 * power heuristic (n p)^2 / ((n p_light)^2 + p_bsdf^2): the weights of a
 * direction sum to 1 (unbiased), and the variance stays near the better
 * technique's, the shadow ray for a small light, the bounce for a large one.
 */
#include "render.h"

/* f^2 / (f^2 + g^2) for f > 0, as 1 / (1 + (g/f)^2): neither square overflows. */
static real
power_heuristic(real f, real g)
{
    real ratio = g / f;
    return 1 / (1 + ratio * ratio);
}

/* The density per steradian of the shadow rays from x at the point y of
 * light `light` (as light_emitted() numbers them): uniform in a sphere's
 * cone (light.c), over an area light's area after its pick (picker.c). */
static real
light_pdf(const struct scene *s, const struct shadow_sampling *sampling, int light, vec3 x, vec3 y)
{
    if (light >= s->n_area_lights) {
        const struct sphere_light *sphere = &s->sphere_lights[light - s->n_area_lights];
        real sin2_max = sphere->radius * sphere->radius / vec3_length2(vec3_sub(sphere->center, x));
        return sin2_max < 1 ? (1 + sqrt(1 - sin2_max)) / (2 * PI * sin2_max) : 0;
    }
    const struct area_light *area = &s->area_lights[light];
    real pick = (real)light_pick_probability(s, sampling->picker, light);
    vec3 d = vec3_sub(y, x);
    real dist2 = vec3_length2(d);
    real cos_light = fabs(vec3_dot(area_light_normal(area), d)) / sqrt(dist2);
    return cos_light > 0 ? pick * dist2 / (area_light_area(area) * cos_light) : 0;
}

real
mis_shadow_weight(const struct shadow_sampling *sampling, real pdf_light, real cos_surface)
{
    real n = (real)(sampling->picked > 0 ? sampling->picked : sampling->samples);
    return sampling->mis ? power_heuristic(n * pdf_light, cos_surface * INV_PI) : 1;
}

vec3
mis_emitted(const struct renderer *renderer, const struct hit *h, const struct path *path)
{
    const struct scene *s = renderer->scene;
    real pdf_light = light_pdf(s, &renderer->shadow, h->light, path->from, h->p);
    real weight = power_heuristic(path->pdf_bsdf, (real)renderer->shadow.samples * pdf_light);
    return vec3_scale(light_emitted(s, h->light, h->front_face), weight);
}
