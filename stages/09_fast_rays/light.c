/*
 * light.c - direct light from point lights, blocked by anything in between,
 * and from area and sphere lights, sampled with shadow rays: soft shadows.
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
sample_area_light(const struct area_light *light, real u, real v)
{
    /* A triangle is the half u + v <= 1: the other half folds onto it, keeping areas. */
    if (light->triangle && u + v > 1) {
        u = 1 - u;
        v = 1 - v;
    }
    /* LAB 03: point on an area light */
    return vec3_madd(vec3_madd(light->corner, light->edge1, u), light->edge2, v);
    /* END LAB */
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
sphere_sample_irradiance(
    const struct world *w,
    const struct hit *h,
    const struct shadow_sampling *sampling,
    const struct sphere_light *light,
    real u,
    real v,
    struct stats *st,
    bool *blocked)
{
    vec3 axis = vec3_sub(light->center, h->p);
    real dist2 = vec3_length2(axis);
    real radius2 = light->radius * light->radius;
    *blocked = false;
    if (!(dist2 > radius2)) {
        return vec3_splat(0);
    }
    real dist = sqrt(dist2);
    /* 1 - cos(theta_max) as sin^2 / (1 + cos): no cancellation for a small
     * or distant sphere, whose cos(theta_max) is close to 1. */
    real sin2_max = radius2 / dist2;
    real one_minus_cos_max = sin2_max / (1 + sqrt(1 - sin2_max));
    /* cos(theta) uniform in [cos(theta_max), 1] is uniform in solid angle. */
    real a = u * one_minus_cos_max; /* 1 - cos(theta) */
    real cos_theta = 1 - a;
    real sin_theta = safe_sqrt(a * (2 - a));
    real phi = 2 * PI * v;
    struct onb frame = onb_from_normal(vec3_scale(axis, 1 / dist));
    vec3 local = {sin_theta * cos(phi), sin_theta * sin(phi), cos_theta};
    vec3 d = onb_to_world(frame, local);
    real cos_surface = vec3_dot(h->n, d);
    if (!(cos_surface > 0)) {
        return vec3_splat(0);
    }
    /* The nearer point where the direction meets the sphere. */
    real t = dist * cos_theta - safe_sqrt(radius2 - dist2 * sin_theta * sin_theta);
    vec3 y = vec3_madd(h->p, d, t);
    vec3 through = transmittance(w, h, y, st);
    *blocked = through.x < 1 || through.y < 1 || through.z < 1;
    real weight = mis_shadow_weight(sampling, 1 / (2 * PI * one_minus_cos_max), cos_surface);
    vec3 l = vec3_scale(light->radiance, weight * cos_surface * 2 * PI * one_minus_cos_max);
    vec3 e = vec3_mul(through, l);
    inspect_light_sample(st, y, 0, 1 / (2 * PI * one_minus_cos_max), e);
    return e;
}

/* Clip a convex polygon to the half-space above the plane through p with
 * normal n (Sutherland and Hodgman, 1974): at most n_in + 1 vertices. */
static int
clip_above(const vec3 *in, int n_in, vec3 p, vec3 n, vec3 *out)
{
    int n_out = 0;
    for (int i = 0; i < n_in; i++) {
        vec3 a = in[i];
        vec3 b = in[(i + 1) % n_in];
        real da = vec3_dot(n, vec3_sub(a, p));
        real db = vec3_dot(n, vec3_sub(b, p));
        if (da >= 0) {
            out[n_out++] = a;
        }
        if ((da >= 0) != (db >= 0)) {
            out[n_out++] = vec3_lerp(a, b, da / (da - db));
        }
    }
    return n_out;
}

bool
unoccluded_irradiance(const struct hit *h, const struct emitter *light, vec3 *e)
{
    *e = vec3_splat(0);
    const struct sphere_light *sphere = light->sphere;
    if (sphere) {
        vec3 axis = vec3_sub(sphere->center, h->p);
        real dist = vec3_length(axis);
        if (!(dist > sphere->radius)) {
            return true; /* on or inside the sphere */
        }
        *e = point_irradiance(h, sphere->center, sphere_light_intensity(sphere));
        /* Wholly above or below the horizon: |cos(alpha)| >= sin(theta_max). */
        return fabs(vec3_dot(h->n, axis) / dist) >= sphere->radius / dist;
    }
    const struct area_light *area = light->area;
    if (!area->two_sided && vec3_dot(area_light_normal(area), vec3_sub(h->p, area->corner)) <= 0) {
        return true; /* behind the one-sided light */
    }
    vec3 corners[4] = {
        area->corner,
        vec3_add(area->corner, area->edge1),
        vec3_add(vec3_add(area->corner, area->edge1), area->edge2),
        vec3_add(area->corner, area->edge2)};
    int n_corners = 4;
    if (area->triangle) {
        corners[2] = corners[3];
        n_corners = 3;
    }
    vec3 poly[5];
    int n = clip_above(corners, n_corners, h->p, h->n, poly);
    real sum = 0;
    for (int i = 0; i < n; i++) {
        vec3 a = vec3_sub(poly[i], h->p);
        vec3 b = vec3_sub(poly[(i + 1) % n], h->p);
        vec3 g = vec3_cross(a, b);
        real g_len = vec3_length(g);
        if (g_len > 0) {
            sum += atan2(g_len, vec3_dot(a, b)) * vec3_dot(h->n, g) / g_len;
        }
    }
    *e = vec3_scale(area->radiance, fabs(sum) / 2);
    return true;
}

vec3
transmittance(const struct world *w, const struct hit *h, vec3 to, struct stats *st)
{
    /* Light through glass reaches a path along its specular bounces (bsdf.c);
     * a shadow ray that passed through glass would count it twice. */
    return vec3_splat(visible(w, h, to, st) ? 1 : 0);
}

/* LAB 03: area light irradiance */
/* One sample of the area light's irradiance at h from its point y (density 1/A):
 * L cos(theta) cos(theta') / r^2 * A, zero if it faces away or is blocked (*blocked). */
static vec3
light_sample_irradiance(
    const struct world *w,
    const struct hit *h,
    const struct shadow_sampling *sampling,
    const struct area_light *light,
    vec3 y,
    struct stats *st,
    bool *blocked)
{
    /* |edge1 x edge2| is A (twice A for a triangle): one product gives
     * cos(theta') A, with no square root per sample. */
    vec3 normal_area = vec3_cross(light->edge1, light->edge2);
    if (light->triangle) {
        normal_area = vec3_scale(normal_area, (real)0.5);
    }
    vec3 to_light = vec3_sub(y, h->p);
    real dist2 = vec3_length2(to_light);
    real dist = sqrt(dist2);
    real cos_surface = vec3_dot(h->n, to_light) / dist;
    real cos_light_area = area_light_cos(light, normal_area, vec3_neg(to_light)) / dist;
    *blocked = false;
    if (!(cos_surface > 0 && cos_light_area > 0)) {
        inspect_area_sample(st, light, y, vec3_splat(0));
        return vec3_splat(0);
    }
    vec3 through = transmittance(w, h, y, st);
    *blocked = through.x < 1 || through.y < 1 || through.z < 1;
    /* y's density per steradian once its light is picked: r^2 / (A cos(theta'));
     * MIS weighs it with the pick's probability (direct_irradiance divides by it). */
    real pdf = dist2 / cos_light_area;
    int number = (int)(light - w->scene->area_lights);
    real pick = (real)light_pick_probability(w->scene, sampling->picker, number);
    real weight = mis_shadow_weight(sampling, pick * pdf, cos_surface);
    vec3 l = vec3_scale(light->radiance, cos_surface * weight / pdf);
    vec3 e = vec3_mul(through, l);
    inspect_area_sample(st, light, y, e);
    return e;
}

/* The sum of n samples of the light, one jittered in each cell of a k x m grid
 * (stratified: each still unbiased, none crowding); *n_blocked counts the blocked. */
static vec3
sum_light_samples(
    const struct world *w,
    const struct hit *h,
    const struct shadow_sampling *sampling,
    const struct emitter *light,
    int n,
    struct rng *rng,
    struct stats *st,
    int *n_blocked)
{
    int k = strata_columns(n);
    int m = n / k;
    vec3 sum = vec3_splat(0);
    const struct scene *s = w->scene;
    int number = light->area ? (int)(light->area - s->area_lights)
                             : s->n_area_lights + (int)(light->sphere - s->sphere_lights);
    for (int i = 0; i < n; i++) {
        real u;
        real v;
        if (sampling->id.kind == SAMPLER_SOBOL && sampling->adaptive[0] == 0) {
            struct sample_id shot = sampling->id; /* the n rays: consecutive points */
            shot.index = shot.index * (uint32_t)n + (uint32_t)i;
            sampler_2d(shot, sampling->depth, DRAW_LIGHT + number, rng, &u, &v);
        } else {
            u = ((real)(i % k) + rng_uniform(rng)) / (real)k;
            v = ((real)(i / k) + rng_uniform(rng)) / (real)m;
        }
        bool blocked;
        vec3 e;
        if (light->area) {
            vec3 y = sample_area_light(light->area, u, v);
            e = light_sample_irradiance(w, h, sampling, light->area, y, st, &blocked);
        } else {
            e = sphere_sample_irradiance(w, h, sampling, light->sphere, u, v, st, &blocked);
        }
        sum = vec3_add(sum, e);
        *n_blocked += blocked;
    }
    return sum;
}

/* Irradiance from one light: the mean of its samples.  Adaptive: if the probes
 * agree, 0 (umbra) or the closed form (lit), else more samples (a penumbra),
 * averaged with the probes; biased where a thin shadow slips between probes. */
static vec3
light_irradiance(
    const struct world *w,
    const struct hit *h,
    const struct emitter *light,
    const struct shadow_sampling *sampling,
    struct rng *rng,
    struct stats *st)
{
    int blocked = 0;
    if (sampling->adaptive[0] == 0) {
        vec3 sum = sum_light_samples(w, h, sampling, light, sampling->samples, rng, st, &blocked);
        return vec3_scale(sum, 1 / (real)sampling->samples);
    }
    int probes = sampling->adaptive[0];
    vec3 sum = sum_light_samples(w, h, sampling, light, probes, rng, st, &blocked);
    vec3 exact = vec3_splat(0);
    if (blocked == probes || (blocked == 0 && unoccluded_irradiance(h, light, &exact))) {
        inspect_adaptive(st, probes, blocked, 0);
        return exact;
    }
    st->extra[STAT_PENUMBRA]++;
    int more = sampling->adaptive[1];
    inspect_adaptive(st, probes, blocked, more);
    sum = vec3_add(sum, sum_light_samples(w, h, sampling, light, more, rng, st, &blocked));
    return vec3_scale(sum, 1 / (real)(probes + more));
}

/* END LAB */

/* The emitting triangles as one light (light_picker.h): each of its n shadow
 * rays goes to a triangle of its own, picked (the k-th pick stratified in
 * [k/n, (k+1)/n), or the k-th of n Sobol points), its sample divided by
 * the pick's probability; adaptive sampling takes one pick for all its
 * probes.  MIS counts all n rays (`picked`). */
static vec3
picked_irradiance(
    const struct world *w,
    const struct hit *h,
    const struct shadow_sampling *sampling,
    struct rng *rng,
    struct stats *st)
{
    struct shadow_sampling one = *sampling;
    int n = sampling->adaptive[0] > 0 ? 1 : sampling->samples;
    one.samples = 1;
    one.picked = n;
    int group = DRAW_LIGHT + w->scene->n_area_lights + w->scene->n_sphere_lights;
    vec3 sum = vec3_splat(0);
    for (int k = 0; k < n; k++) {
        real u;
        one.id.index = sampling->id.index * (uint32_t)n + (uint32_t)k;
        if (sampling->id.kind == SAMPLER_SOBOL) {
            sampler_2d(one.id, sampling->depth, group, rng, &u, &u);
        } else {
            u = ((real)k + rng_uniform(rng)) / (real)n;
        }
        int i = light_pick(sampling->picker, u);
        struct emitter light = {.area = &w->scene->area_lights[i]};
        inspect_light(st, RECORDER_AREA_LIGHT, i);
        real p = (real)light_pick_probability(w->scene, sampling->picker, i);
        sum = vec3_add(sum, vec3_scale(light_irradiance(w, h, &light, &one, rng, st), 1 / p));
    }
    return vec3_scale(sum, 1 / (real)n);
}

vec3
direct_irradiance(
    const struct world *w,
    const struct hit *h,
    const struct shadow_sampling *sampling,
    struct rng *rng,
    struct stats *st)
{
    const struct scene *s = w->scene;
    vec3 e = vec3_splat(0);
    for (int i = 0; i < s->n_point_lights; i++) {
        const struct point_light *light = &s->point_lights[i];
        inspect_light(st, RECORDER_POINT_LIGHT, i);
        vec3 irradiance = point_irradiance(h, light->position, light->intensity);
        if (!vec3_is_zero(irradiance)) {
            e = vec3_add(e, vec3_mul(irradiance, transmittance(w, h, light->position, st)));
        }
    }
    /* samples = 0: area lights are left to the paths that hit them. */
    if (sampling->samples == 0) {
        return e;
    }
    const struct light_picker *picker = sampling->picker;
    int n_own = picker ? picker->n_own : s->n_area_lights;
    for (int k = 0; k < n_own; k++) {
        int i = picker ? picker->own[k] : k;
        struct emitter light = {.area = &s->area_lights[i]};
        inspect_light(st, RECORDER_AREA_LIGHT, i);
        e = vec3_add(e, light_irradiance(w, h, &light, sampling, rng, st));
    }
    if (picker && picker->cdf) {
        e = vec3_add(e, picked_irradiance(w, h, sampling, rng, st));
    }
    for (int i = 0; i < s->n_sphere_lights; i++) {
        struct emitter light = {.sphere = &s->sphere_lights[i]};
        inspect_light(st, RECORDER_SPHERE_LIGHT, i);
        e = vec3_add(e, light_irradiance(w, h, &light, sampling, rng, st));
    }
    return e;
}
