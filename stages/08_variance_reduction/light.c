/*
 * light.c - direct light from point lights, blocked by anything in between,
 * and from area lights, estimated with shadow rays to points sampled over
 * their area: soft shadows.
 */
#include "light.h"

#include "inspect.h"
#include "sampler.h"

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
transmittance(const struct world *w, const struct hit *h, vec3 to, struct stats *st)
{
    /* Light through glass reaches a path along its specular bounces (bsdf.c);
     * a shadow ray that passed through glass would count it twice. */
    return vec3_splat(visible(w, h, to, st) ? 1 : 0);
}

/* LAB 03: area light irradiance */
/* One sample of the area light's irradiance at h from its point y:
 * L cos(theta) cos(theta') / r^2 * A (the estimator of E = integral over the
 * light of L cos cos' / r^2 dA, with y drawn with density 1/A), zero when
 * the light faces away or is blocked.  *blocked tells which of the two. */
static vec3
light_sample_irradiance(
    const struct world *w,
    const struct hit *h,
    const struct area_light *light,
    vec3 y,
    struct stats *st,
    bool *blocked)
{
    /* cross(edge1, edge2) is the light's unit normal times its area A
     * (twice A for a triangle), so one product gives cos(theta') A, with
     * no square root per sample. */
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
    vec3 l = vec3_scale(light->radiance, cos_surface * cos_light_area / dist2);
    vec3 e = vec3_mul(through, l);
    inspect_area_sample(st, light, y, e);
    return e;
}

/* For a triangle light, the half of the unit square beyond the diagonal
 * u + v = 1 folded onto the triangle's half (u, v -> 1 - u, 1 - v, a map
 * that keeps area): a uniform (u, v) gives a uniform point of the triangle,
 * and a set of cells covering the square covers the triangle evenly. */
static void
fold_into_triangle(const struct area_light *light, real *u, real *v)
{
    if (light->triangle && *u + *v > 1) {
        *u = 1 - *u;
        *v = 1 - *v;
    }
}

/* One sample of a sphere light's irradiance at h: a direction drawn from
 * (u, v) in [0,1)^2 uniformly over the cone of directions the sphere
 * subtends, and L cos(theta) Omega for it, Omega = 2 pi (1 - cos(theta_max))
 * the cone's solid angle, sin(theta_max) = r / d at distance d from the
 * centre (the estimator of E = integral over the cone of L cos(theta) dw
 * with the direction drawn with density 1 / Omega; Shirley, Wang and
 * Zimmerman, "Monte Carlo Techniques for Direct Lighting Calculations",
 * 1996; pbrt 4ed, 6.2.4).  Every sample lands on the half of the sphere the
 * point sees, unlike points drawn over its whole area.  Zero when h is on or
 * inside the sphere (its light goes outward), when the direction is below
 * the surface's horizon, or when it is blocked: *blocked tells which. */
static vec3
sphere_sample_irradiance(
    const struct world *w,
    const struct hit *h,
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
    vec3 l = vec3_scale(light->radiance, cos_surface * 2 * PI * one_minus_cos_max);
    vec3 e = vec3_mul(through, l);
    inspect_light_sample(st, y, 0, 1 / (2 * PI * one_minus_cos_max), e);
    return e;
}

/* A light the shadow rays sample: an area light or a sphere light (the
 * other NULL). */
struct emitter {
    const struct area_light *area;
    const struct sphere_light *sphere;
};

/* The sum of n samples of the light's irradiance, one in each cell of a
 * k x m grid over [0,1)^2, the light's area or its cone of directions
 * (jittered stratification: each sample is unbiased, so their mean is, and
 * no two crowd together).  *n_blocked counts the samples the light was
 * blocked for. */
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
        if (!sampler_light_numbers(sampling, number, i, n, &u, &v)) {
            u = ((real)(i % k) + rng_uniform(rng)) / (real)k;
            v = ((real)(i / k) + rng_uniform(rng)) / (real)m;
        }
        bool blocked;
        if (light->area) {
            fold_into_triangle(light->area, &u, &v);
            vec3 y = sample_area_light(light->area, u, v);
            sum = vec3_add(sum, light_sample_irradiance(w, h, light->area, y, st, &blocked));
        } else {
            sum = vec3_add(sum, sphere_sample_irradiance(w, h, light->sphere, u, v, st, &blocked));
        }
        *n_blocked += blocked;
    }
    return sum;
}

/* Clip a convex polygon to the half-space above the plane through p with
 * normal n (Sutherland and Hodgman, 1974).  Returns the new vertex count
 * (at most n_in + 1). */
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

/* The irradiance the light gives h when nothing is in the way, in closed
 * form: for a polygon of constant radiance L seen from a point with normal n,
 *     E = L/2 * | sum_i theta_i n . g_i |,
 * theta_i the angle the edge (v_i, v_i+1) subtends and g_i the unit normal
 * of the plane through the point and that edge (Lambert, 1760; Arvo,
 * "Applications of Irradiance Tensors", 1995).  The part of the light below
 * the surface's horizon is clipped away first.  The absolute value makes it
 * hold on either side of the polygon, as a two-sided light needs. */
static vec3
unoccluded_irradiance(const struct hit *h, const struct area_light *light)
{
    real side = vec3_dot(area_light_normal(light), vec3_sub(h->p, light->corner));
    if (!light->two_sided && side <= 0) {
        return vec3_splat(0); /* behind the one-sided light */
    }
    vec3 corners[4] = {
        light->corner,
        vec3_add(light->corner, light->edge1),
        vec3_add(vec3_add(light->corner, light->edge1), light->edge2),
        vec3_add(light->corner, light->edge2)};
    int n_corners = 4;
    if (light->triangle) {
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
            real theta = atan2(g_len, vec3_dot(a, b));
            sum += theta * vec3_dot(h->n, g) / g_len;
        }
    }
    return vec3_scale(light->radiance, fabs(sum) / 2);
}

/* The unoccluded irradiance of the light at h, in closed form, into *e.
 * For a sphere all above the surface's horizon (the angle alpha between
 * the normal and the centre at most 90 degrees - theta_max) it is
 * L pi sin^2(theta_max) cos(alpha): that of a point of intensity L pi r^2
 * at the centre.  False for a sphere the horizon cuts, whose closed form is
 * longer (Snyder, "Area Light Sources for Real-Time Graphics", 1996): the
 * caller samples it instead. */
static bool
unoccluded_closed_form(const struct hit *h, const struct emitter *light, vec3 *e)
{
    if (light->area) {
        *e = unoccluded_irradiance(h, light->area);
        return true;
    }
    const struct sphere_light *sphere = light->sphere;
    vec3 axis = vec3_sub(sphere->center, h->p);
    real dist = vec3_length(axis);
    if (!(dist > sphere->radius)) {
        *e = vec3_splat(0); /* on or inside the sphere */
        return true;
    }
    real cos_alpha = vec3_dot(h->n, axis) / dist;
    real sin_max = sphere->radius / dist;
    *e = point_irradiance(h, sphere->center, sphere_light_intensity(sphere));
    return cos_alpha >= sin_max || cos_alpha <= -sin_max;
}

/* Irradiance from one light.  Adaptive mode (as classic renderers do):
 * a few probe rays; if they agree, the point is taken as fully shadowed (0)
 * or fully lit (the exact unoccluded irradiance: no noise at all, where
 * there is a closed form); otherwise it is in a penumbra and gets more
 * samples, averaged with the probes.  The price is a bias where a thin
 * shadow slips between all the probes. */
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
    if (blocked == probes) {
        inspect_adaptive(st, probes, blocked, 0);
        return vec3_splat(0);
    }
    vec3 exact;
    if (blocked == 0 && unoccluded_closed_form(h, light, &exact)) {
        inspect_adaptive(st, probes, blocked, 0);
        return exact;
    }
    st->extra[STAT_PENUMBRA]++;
    int more = sampling->adaptive[1];
    inspect_adaptive(st, probes, blocked, more);
    sum = vec3_add(sum, sum_light_samples(w, h, sampling, light, more, rng, st, &blocked));
    return vec3_scale(sum, 1 / (real)(probes + more));
}

static vec3
area_light_irradiance(
    const struct world *w,
    const struct hit *h,
    const struct area_light *light,
    const struct shadow_sampling *sampling,
    struct rng *rng,
    struct stats *st)
{
    return light_irradiance(w, h, &(struct emitter){.area = light}, sampling, rng, st);
}

static vec3
sphere_light_irradiance(
    const struct world *w,
    const struct hit *h,
    const struct sphere_light *light,
    const struct shadow_sampling *sampling,
    struct rng *rng,
    struct stats *st)
{
    return light_irradiance(w, h, &(struct emitter){.sphere = light}, sampling, rng, st);
}

/* END LAB */

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
        inspect_light(st, TRACE_POINT_LIGHT, i);
        vec3 irradiance = point_irradiance(h, light->position, light->intensity);
        if (!vec3_is_zero(irradiance)) {
            e = vec3_add(e, vec3_mul(irradiance, transmittance(w, h, light->position, st)));
        }
    }
    /* samples = 0: area lights are left to the paths that hit them. */
    if (sampling->samples == 0) {
        return e;
    }
    for (int i = 0; i < s->n_area_lights; i++) {
        const struct area_light *light = &s->area_lights[i];
        inspect_light(st, TRACE_AREA_LIGHT, i);
        e = vec3_add(e, area_light_irradiance(w, h, light, sampling, rng, st));
    }
    for (int i = 0; i < s->n_sphere_lights; i++) {
        const struct sphere_light *light = &s->sphere_lights[i];
        inspect_light(st, TRACE_SPHERE_LIGHT, i);
        e = vec3_add(e, sphere_light_irradiance(w, h, light, sampling, rng, st));
    }
    return e;
}
