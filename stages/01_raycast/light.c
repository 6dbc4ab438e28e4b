/*
 * light.c - direct light from point lights, and from area and sphere lights
 * treated as point lights at their centres.
 */
#include "light.h"

vec3
point_irradiance(const struct hit *h, vec3 from, vec3 intensity)
{
    /* LAB 01: irradiance from a point light */
    vec3 to_light = vec3_sub(from, h->p);
    real dist2 = vec3_length2(to_light);
    real cos_theta = vec3_dot(h->n, to_light);
    if (!(cos_theta > 0 && dist2 > 0)) {
        return vec3_splat(0);
    }
    /* cos(theta) = n.l / |l|, so I cos / r^2 = I (n.l) / |l|^3. */
    return vec3_scale(intensity, cos_theta / (dist2 * sqrt(dist2)));
    /* END LAB */
}

vec3
area_light_intensity(const struct area_light *light, vec3 p)
{
    vec3 center = area_light_center(light);
    vec3 to_p = vec3_sub(p, center);
    real dist = vec3_length(to_p);
    real cos_light = dist > 0 ? area_light_cos(light, area_light_normal(light), to_p) / dist : 0;
    if (!(cos_light > 0)) {
        return vec3_splat(0);
    }
    return vec3_scale(light->radiance, area_light_area(light) * cos_light);
}

vec3
direct_irradiance(const struct scene *s, const struct hit *h)
{
    vec3 e = vec3_splat(0);
    for (int i = 0; i < s->n_point_lights; i++) {
        const struct point_light *light = &s->point_lights[i];
        e = vec3_add(e, point_irradiance(h, light->position, light->intensity));
    }
    for (int i = 0; i < s->n_area_lights; i++) {
        const struct area_light *light = &s->area_lights[i];
        vec3 center = area_light_center(light);
        e = vec3_add(e, point_irradiance(h, center, area_light_intensity(light, h->p)));
    }
    for (int i = 0; i < s->n_sphere_lights; i++) {
        const struct sphere_light *sphere = &s->sphere_lights[i];
        e = vec3_add(e, point_irradiance(h, sphere->center, sphere_light_intensity(sphere)));
    }
    return e;
}
