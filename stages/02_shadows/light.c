/*
 * light.c - direct light from point lights, and from area and sphere lights
 * treated as point lights at their centres, each blocked by anything in between.
 */
#include "light.h"

#include "inspect.h"

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

void
inspect_shadow_ray(const struct world *w, ray shadow, real t_max, bool clear, struct stats *st)
{
    struct hit blocker = {.prim = -1};
    if (!clear && !world_intersect(w, shadow, t_max, &blocker, st)) {
        blocker.prim = -1;
    }
    inspect_shadow(st, shadow, t_max, blocker.prim, blocker.t);
}

bool
visible(const struct world *w, const struct hit *h, vec3 to, struct stats *st)
{
    /* LAB 02: shadow ray */
    real t_max;
    ray shadow = spawn_ray_to(h, to, &t_max);
    st->rays_shadow++;
    bool clear = !world_occluded(w, shadow, t_max, st);
    if (inspecting(st)) {
        inspect_shadow_ray(w, shadow, t_max, clear, st);
    }
    return clear;
    /* END LAB */
}

vec3
direct_irradiance(const struct world *w, const struct hit *h, struct stats *st)
{
    const struct scene *s = w->scene;
    vec3 e = vec3_splat(0);
    for (int i = 0; i < s->n_point_lights; i++) {
        const struct point_light *light = &s->point_lights[i];
        inspect_light(st, RECORDER_POINT_LIGHT, i);
        vec3 irradiance = point_irradiance(h, light->position, light->intensity);
        if (!vec3_is_zero(irradiance) && visible(w, h, light->position, st)) {
            e = vec3_add(e, irradiance);
        }
    }
    for (int i = 0; i < s->n_area_lights; i++) {
        const struct area_light *light = &s->area_lights[i];
        inspect_light(st, RECORDER_AREA_LIGHT, i);
        vec3 center = area_light_center(light);
        vec3 irradiance = point_irradiance(h, center, area_light_intensity(light, h->p));
        if (!vec3_is_zero(irradiance) && visible(w, h, center, st)) {
            e = vec3_add(e, irradiance);
        }
    }
    for (int i = 0; i < s->n_sphere_lights; i++) {
        const struct sphere_light *sphere = &s->sphere_lights[i];
        inspect_light(st, RECORDER_SPHERE_LIGHT, i);
        vec3 irradiance = point_irradiance(h, sphere->center, sphere_light_intensity(sphere));
        if (!vec3_is_zero(irradiance) && visible(w, h, sphere->center, st)) {
            e = vec3_add(e, irradiance);
        }
    }
    return e;
}
