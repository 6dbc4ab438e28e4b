/*
 * light.c - direct light from point lights, blocked by anything in between,
 * and from area lights, estimated with shadow rays to points sampled over
 * their area: soft shadows.
 */
#include "light.h"

#include "inspect.h"
#include "lowdisc.h"

#include <stdlib.h>

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
/* One shadow ray's estimate of the irradiance at h from the point y of a
 * light of radiance L, the direction to y (cosine cos_surface to the
 * normal) drawn with density pdf per unit solid angle: L cos(theta) / pdf
 * when y is visible (the estimator of E = integral of L cos(theta) dw),
 * zero when it is blocked (*blocked) or below the horizon.  With MIS on
 * (sampling->bsdf_pdf_cos > 0), weighted by the power heuristic against the
 * path's bounce, which finds the same light with its own density; the
 * bounce's weight (render.c) makes up the rest. */
static vec3
shadow_ray_estimate(
    const struct world *w,
    const struct hit *h,
    const struct shadow_sampling *sampling,
    vec3 radiance,
    vec3 y,
    real cos_surface,
    real pdf,
    struct stats *st,
    bool *blocked)
{
    *blocked = false;
    if (!(cos_surface > 0 && pdf > 0)) {
        return vec3_splat(0);
    }
    vec3 through = transmittance(w, h, y, st);
    *blocked = through.x < 1 || through.y < 1 || through.z < 1;
    real pdf_bsdf = sampling->bsdf_pdf_cos * cos_surface;
    real weight = mis_power_heuristic((real)sampling->samples, pdf, 1, pdf_bsdf);
    inspect_mis(st, pdf, pdf_bsdf, weight);
    return vec3_mul(through, vec3_scale(radiance, cos_surface * weight / pdf));
}

/* One sample of the area light's irradiance at h from its point y, which
 * was drawn with density pdf_solid_angle per unit solid angle or, when that
 * is 0, uniformly over its area after the light was picked with probability
 * pick (1 for a light sampled on its own).  Density per unit area p/A is
 * p r^2 / (A cos(theta')) per unit solid angle (dA = r^2 dw / cos(theta')),
 * so the estimate is L cos(theta) cos(theta') A / (r^2 p): zero when the
 * light faces away. */
static vec3
area_sample_irradiance(
    const struct world *w,
    const struct hit *h,
    const struct shadow_sampling *sampling,
    const struct area_light *light,
    vec3 y,
    real pdf_solid_angle,
    real pick,
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
    real cos_light_area = area_light_cos(light, normal_area, vec3_neg(to_light)) / dist;
    *blocked = false;
    if (!(cos_light_area > 0)) {
        inspect_picked_sample(
            st,
            light,
            pick,
            y,
            pdf_solid_angle,
            pdf_solid_angle == 0,
            vec3_splat(0));
        return vec3_splat(0);
    }
    real pdf = pdf_solid_angle > 0 ? pdf_solid_angle : pick * dist2 / cos_light_area;
    real cos_surface = vec3_dot(h->n, to_light) / dist;
    vec3 e = shadow_ray_estimate(w, h, sampling, light->radiance, y, cos_surface, pdf, st, blocked);
    inspect_picked_sample(st, light, pick, y, pdf, pdf_solid_angle == 0, e);
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

/* Rectangle lights by solid angle (Urena, Fajardo and King, "An
 * Area-Preserving Parametrization for Spherical Rectangles", 2013).  A
 * point uniform over a light's area is seen from x with density
 * r^2 / (A cos(theta')) per unit solid angle: where the light is close and
 * large (the floor under a big ceiling panel, a corner next to it), that
 * density varies a lot over it, and so does the estimate.  Drawing the
 * direction uniformly in the solid angle Omega the rectangle subtends
 * leaves only L cos(theta) Omega to vary.
 *
 * The paper's construction: in a frame with x at the origin, the edges
 * along the axes and the rectangle [x0, x1] x [y0, y1] in the plane
 * z = z0 < 0, the planes through x and each edge have unit normals n0
 * (edge y = y0), n1 (x = x1), n2 (y = y1), n3 (x = x0), the spherical
 * rectangle's interior angles are g_i = acos(-n_i . n_(i+1)), and its area
 * is Omega = g0 + g1 + g2 + g3 - 2 pi (Girard's theorem).  A vertical line
 * x = xu cuts off the part [x0, xu] of the rectangle; its solid angle is a
 * function of xu that the paper inverts in closed form: given u, the xu
 * whose part has solid angle u Omega.  Along that line, y = d h / sqrt(1 -
 * h^2) (d the distance of the line from x) for h uniform between its values
 * at y0 and y1 is uniform in solid angle.  Both steps preserve area, so the
 * point's density is 1 / Omega, and a stratified (u, v) gives stratified
 * directions. */

/* A solid angle this small is computed with too large a relative error
 * (it is the angle of a product of four unit complex numbers, near 1 for a
 * small light, to an absolute error of a few REAL_EPSILON: a relative one
 * of about 2 pi REAL_EPSILON / Omega): such a light, small or far, is
 * sampled by area instead, where
 * 1 / Omega would be less accurate than the area density it would replace.
 * 2^16 REAL_EPSILON keeps that error below 1e-4 (a float build falls back
 * under 8e-3 sr, a double one under 1.5e-11 sr). */
#define RECT_SOLID_ANGLE_MIN (65536 * REAL_EPSILON)

/* Edges whose cosine exceeds this make a parallelogram, not a rectangle:
 * sampled by area. */
#define RECT_MAX_EDGE_COS ((real)1e-4)

/* A rectangle light seen from a point: the frame and numbers of the
 * paper's construction. */
struct spherical_rect {
    vec3 origin; /* the point x */
    vec3 ex, ey, ez; /* the frame: along edge1, along edge2, towards the light's plane */
    real x0, x1, y0, y1, z0; /* the rectangle in that frame, z0 < 0 */
    real b0, b1; /* the z components of n0 and n2 */
    real cos_k, sin_k; /* of the paper's k = 2 pi - g2 - g3 */
    real solid_angle; /* Omega, steradians */
};

static real
clamp_real(real x, real lo, real hi)
{
    return fmin(fmax(x, lo), hi);
}

/* An angle as a unit complex number (cos, sin): adding angles multiplies
 * them, which needs no trigonometric function. */
struct turn {
    real c, s;
};

static struct turn
turn_add(struct turn a, struct turn b)
{
    return (struct turn){a.c * b.c - a.s * b.s, a.s * b.c + a.c * b.s};
}

/* The interior angle between the planes of unit normals a and b, in
 * [0, pi]: cosine -a.b, sine |a x b| (no cancellation for angles near 0
 * or pi, where 1 - cos^2 would lose the sine's digits). */
static struct turn
corner_angle(vec3 a, vec3 b)
{
    return (struct turn){-vec3_dot(a, b), vec3_length(vec3_cross(a, b))};
}

/* The spherical rectangle of the light seen from x.  False when the light
 * is no rectangle, x lies in its plane, or its solid angle is under
 * RECT_SOLID_ANGLE_MIN (or not finite).
 *
 * The paper takes the four angles g_i with inverse cosines; here they stay
 * (cos, sin) pairs, added by complex multiplication, and one atan2 gives
 * Omega = g0 + g1 + g2 + g3 - 2 pi, the angle of their product.  That
 * angle is known modulo 2 pi: Omega in (0, 2 pi) is the atan2 result, or
 * that plus 2 pi when it is negative.  Only a light of solid angle within
 * rounding of 0 or 2 pi is ambiguous; a rectangle subtends at most
 * A / z0^2 (every point is at least |z0| away), which tells a tiny one from
 * a huge one. */
static bool
spherical_rect_make(const struct area_light *light, vec3 x, struct spherical_rect *sr)
{
    real len1 = vec3_length(light->edge1);
    real len2 = vec3_length(light->edge2);
    if (light->triangle || !(len1 > 0 && len2 > 0)) {
        return false;
    }
    sr->origin = x;
    sr->ex = vec3_scale(light->edge1, 1 / len1);
    sr->ey = vec3_scale(light->edge2, 1 / len2);
    if (!(fabs(vec3_dot(sr->ex, sr->ey)) <= RECT_MAX_EDGE_COS)) {
        return false;
    }
    sr->ez = vec3_cross(sr->ex, sr->ey);
    vec3 d = vec3_sub(light->corner, x);
    sr->z0 = vec3_dot(d, sr->ez);
    if (sr->z0 > 0) {
        sr->ez = vec3_neg(sr->ez);
        sr->z0 = -sr->z0;
    }
    if (!(sr->z0 < 0)) {
        return false; /* in the plane: the light subtends no solid angle */
    }
    sr->x0 = vec3_dot(d, sr->ex);
    sr->y0 = vec3_dot(d, sr->ey);
    sr->x1 = sr->x0 + len1;
    sr->y1 = sr->y0 + len2;
    /* The normals, cross products of consecutive corners (x0, y0, z0),
     * (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), in closed form. */
    real z0 = sr->z0;
    vec3 n0 = vec3_normalize((vec3){0, z0, -sr->y0});
    vec3 n1 = vec3_normalize((vec3){-z0, 0, sr->x1});
    vec3 n2 = vec3_normalize((vec3){0, -z0, sr->y1});
    vec3 n3 = vec3_normalize((vec3){z0, 0, -sr->x0});
    struct turn g01 = turn_add(corner_angle(n0, n1), corner_angle(n1, n2));
    struct turn g23 = turn_add(corner_angle(n2, n3), corner_angle(n3, n0));
    struct turn sum = turn_add(g01, g23);
    sr->b0 = n0.z;
    sr->b1 = n2.z;
    sr->cos_k = g23.c; /* cos(2 pi - a) = cos(a), sin(2 pi - a) = -sin(a) */
    sr->sin_k = -g23.s;
    real omega = atan2(sum.s, sum.c);
    if (omega < 0) {
        omega += 2 * PI;
    }
    if (omega > PI && len1 * len2 < PI * z0 * z0) {
        return false; /* a tiny Omega rounded below 0: too small anyway */
    }
    sr->solid_angle = omega;
    return sr->solid_angle >= RECT_SOLID_ANGLE_MIN && sr->solid_angle <= 2 * PI;
}

/* The point of the spherical rectangle at (u, v) in [0,1)^2 (the paper's
 * two inversions, written with its names).  Clamped into the rectangle,
 * which absorbs the round-off of the inversions (and a division by zero
 * at u = 0 or 1, where sin(au) can vanish). */
static vec3
spherical_rect_point(const struct spherical_rect *sr, real u, real v)
{
    /* xu: the line whose part [x0, xu] has the solid angle u Omega.  The
     * paper's angle au = u Omega + k, by its cosine and sine. */
    struct turn au = turn_add(
        (struct turn){cos(u * sr->solid_angle), sin(u * sr->solid_angle)},
        (struct turn){sr->cos_k, sr->sin_k});
    real fu = (au.c * sr->b0 - sr->b1) / au.s;
    real cu = copysign((real)1, fu) / sqrt(fu * fu + sr->b0 * sr->b0);
    cu = clamp_real(cu, -1, 1);
    real xu = -cu * sr->z0 / safe_sqrt(1 - cu * cu);
    xu = clamp_real(xu, sr->x0, sr->x1);
    /* yv: h = y / sqrt(d^2 + y^2), the sine of the elevation seen from the
     * origin in the plane of the line, is uniform in solid angle along it. */
    real d2 = xu * xu + sr->z0 * sr->z0;
    real h0 = sr->y0 / sqrt(d2 + sr->y0 * sr->y0);
    real h1 = sr->y1 / sqrt(d2 + sr->y1 * sr->y1);
    real hv = h0 + v * (h1 - h0);
    real yv = hv * sqrt(d2) / safe_sqrt(1 - hv * hv);
    yv = clamp_real(yv, sr->y0, sr->y1);
    vec3 local = vec3_madd(vec3_scale(sr->ex, xu), sr->ey, yv);
    return vec3_add(sr->origin, vec3_madd(local, sr->ez, sr->z0));
}

bool
sample_rect_solid_angle(const struct area_light *light, vec3 x, real u, real v, vec3 *y, real *pdf)
{
    struct spherical_rect sr;
    if (!spherical_rect_make(light, x, &sr)) {
        return false;
    }
    *y = spherical_rect_point(&sr, u, v);
    *pdf = 1 / sr.solid_angle;
    return true;
}

/* The auto mode's rule (RECT_BY_SIZE): a rectangle looks large from x when
 * its squared diagonal exceeds RECT_LARGE times the squared distance to its
 * centre (about 50 degrees across at RECT_LARGE = 1).  Then r^2 /
 * cos(theta') varies much over it and area sampling is noisy; a smaller one
 * is sampled well enough by area, which costs a fraction of the solid-angle
 * construction (its atan2, sine, cosine and square roots).  Measured: at 0.25
 * the Cornell box's light is sampled by solid angle from half the box, for
 * 1.5% less noise at 20% more time; at 1, only near the light. */
#define RECT_LARGE ((real)1)

/* Whether the shadow rays from x to the rectangle light go by its solid
 * angle (true) or its area: --light-sampling, a function of x and the
 * light only, so that light_pdf() makes the same choice. */
static bool
rect_by_solid_angle(const struct shadow_sampling *sampling, const struct area_light *light, vec3 x)
{
    if (sampling->rect != RECT_BY_SIZE) {
        return sampling->rect == RECT_BY_SOLID_ANGLE;
    }
    vec3 to_center = vec3_sub(area_light_center(light), x);
    if (!light->two_sided && vec3_dot(vec3_cross(light->edge1, light->edge2), to_center) >= 0) {
        return false; /* x is behind it: it gets no light whichever way it is sampled */
    }
    real diagonal2 = vec3_length2(vec3_add(light->edge1, light->edge2));
    return diagonal2 > RECT_LARGE * vec3_length2(to_center);
}

/* A sphere light seen from x: 1 - cos(theta_max) of the cone it subtends,
 * sin(theta_max) = r / d at distance d from the centre, into
 * *one_minus_cos_max; false when x is on or inside it (its light goes
 * outward).  Written as sin^2 / (1 + cos): no cancellation for a small or
 * distant sphere, whose cos(theta_max) is close to 1. */
static bool
sphere_cone(const struct sphere_light *light, vec3 x, real *one_minus_cos_max)
{
    real dist2 = vec3_length2(vec3_sub(light->center, x));
    real radius2 = light->radius * light->radius;
    if (!(dist2 > radius2)) {
        return false;
    }
    real sin2_max = radius2 / dist2;
    *one_minus_cos_max = sin2_max / (1 + sqrt(1 - sin2_max));
    return true;
}

/* One sample of a sphere light's irradiance at h: a direction drawn from
 * (u, v) in [0,1)^2 uniformly over the cone of directions the sphere
 * subtends, density 1 / Omega, Omega = 2 pi (1 - cos(theta_max)) the
 * cone's solid angle, and L cos(theta) Omega for it (the estimator of
 * E = integral over the cone of L cos(theta) dw; Shirley, Wang and
 * Zimmerman, "Monte Carlo Techniques for Direct Lighting Calculations",
 * 1996; pbrt 4ed, 6.2.4).  Every sample lands on the half of the sphere the
 * point sees, unlike points drawn over its whole area.  Zero when h is on or
 * inside the sphere, when the direction is below the surface's horizon, or
 * when it is blocked: *blocked tells which. */
static vec3
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
    real one_minus_cos_max;
    *blocked = false;
    if (!sphere_cone(light, h->p, &one_minus_cos_max)) {
        return vec3_splat(0);
    }
    vec3 axis = vec3_sub(light->center, h->p);
    real dist2 = vec3_length2(axis);
    real dist = sqrt(dist2);
    /* cos(theta) uniform in [cos(theta_max), 1] is uniform in solid angle. */
    real a = u * one_minus_cos_max; /* 1 - cos(theta) */
    real cos_theta = 1 - a;
    real sin_theta = safe_sqrt(a * (2 - a));
    real phi = 2 * PI * v;
    struct onb frame = onb_from_normal(vec3_scale(axis, 1 / dist));
    vec3 local = {sin_theta * cos(phi), sin_theta * sin(phi), cos_theta};
    vec3 d = onb_to_world(frame, local);
    /* The nearer point where the direction meets the sphere. */
    real radius2 = light->radius * light->radius;
    real t = dist * cos_theta - safe_sqrt(radius2 - dist2 * sin_theta * sin_theta);
    vec3 y = vec3_madd(h->p, d, t);
    real pdf = 1 / (2 * PI * one_minus_cos_max);
    vec3 e = shadow_ray_estimate(
        w,
        h,
        sampling,
        light->radiance,
        y,
        vec3_dot(h->n, d),
        pdf,
        st,
        blocked);
    inspect_light_sample(st, y, 0, pdf, e);
    return e;
}

/* A light the shadow rays sample: an area light or a sphere light (the
 * other NULL), and its number (area lights, then sphere lights, then the
 * emitting triangles as one: the Sobol sequences' seeds). */
struct emitter {
    const struct area_light *area;
    const struct sphere_light *sphere;
    int number;
};

/* The seed of the Sobol sequences of light `number` at this vertex: in
 * the family of the vertex's seed, past the counters render.c gives the
 * other uses (depth << 8 | use). */
static uint64_t
light_seed(const struct shadow_sampling *sampling, int number)
{
    return lowdisc_family_seed(sampling->lowdisc_seed, ((uint64_t)number + 1) << 32);
}

/* The uniform numbers (u, v) of shadow ray i of n to a light: with the
 * Sobol sampler, point lowdisc_index * n + i of the light's own sequence
 * (the n rays of a vertex are consecutive points of a (0,2)-sequence,
 * stratified together when n is a power of two, and the pixel's samples
 * stratify each ray's numbers across the pixel); otherwise a random point
 * of cell i of a k x m grid (k m = n). */
static void
light_sample_numbers(
    const struct shadow_sampling *sampling,
    int light,
    int i,
    int n,
    struct rng *rng,
    real *u,
    real *v)
{
    if (sampling->lowdisc) {
        lowdisc_point2(
            sampling->lowdisc_index * (uint32_t)n + (uint32_t)i,
            light_seed(sampling, light),
            u,
            v);
        return;
    }
    int k = strata_columns(n);
    int m = n / k;
    *u = ((real)(i % k) + rng_uniform(rng)) / (real)k;
    *v = ((real)(i / k) + rng_uniform(rng)) / (real)m;
}

/* The sum of n samples of the light's irradiance, their numbers in [0,1)^2
 * stratified (light_sample_numbers()) and mapped to the light's area, its
 * solid angle or its cone of directions (each sample is unbiased, so their
 * mean is, and no two crowd together).  *n_blocked counts the samples the
 * light was blocked for. */
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
    vec3 sum = vec3_splat(0);
    for (int i = 0; i < n; i++) {
        real u;
        real v;
        light_sample_numbers(sampling, light->number, i, n, rng, &u, &v);
        bool blocked;
        vec3 e;
        if (light->area) {
            vec3 y;
            real pdf = 0;
            if (!rect_by_solid_angle(sampling, light->area, h->p)
                || !sample_rect_solid_angle(light->area, h->p, u, v, &y, &pdf)) {
                fold_into_triangle(light->area, &u, &v);
                y = sample_area_light(light->area, u, v);
            }
            e = area_sample_irradiance(w, h, sampling, light->area, y, pdf, 1, st, &blocked);
        } else {
            e = sphere_sample_irradiance(w, h, sampling, light->sphere, u, v, st, &blocked);
        }
        sum = vec3_add(sum, e);
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
    int number = (int)(light - w->scene->area_lights);
    return light_irradiance(
        w,
        h,
        &(struct emitter){.area = light, .number = number},
        sampling,
        rng,
        st);
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
    const struct scene *s = w->scene;
    int number = s->n_area_lights + (int)(light - s->sphere_lights);
    return light_irradiance(
        w,
        h,
        &(struct emitter){.sphere = light, .number = number},
        sampling,
        rng,
        st);
}

/* END LAB */

/* The light's power per unit of pi: A lum(L), doubled for a two-sided one. */
static real
light_power(const struct area_light *light)
{
    vec3 l = light->radiance;
    real lum = (real)0.2126 * l.x + (real)0.7152 * l.y + (real)0.0722 * l.z;
    return area_light_area(light) * lum * (light->two_sided ? 2 : 1);
}

bool
light_picker_build(struct light_picker *lp, const struct scene *s, struct diag *err)
{
    *lp = (struct light_picker){0};
    size_t n = (size_t)s->n_area_lights;
    lp->light = malloc((n + 1) * sizeof *lp->light);
    lp->cdf = malloc((n + 1) * sizeof *lp->cdf);
    lp->prob = calloc(n + 1, sizeof *lp->prob);
    if (!lp->light || !lp->cdf || !lp->prob) {
        light_picker_free(lp);
        diag_set(err, NULL, 0, 0, "out of memory for %zu lights", n);
        return false;
    }
    real total = 0;
    for (int i = 0; i < s->n_area_lights; i++) {
        real power = light_power(&s->area_lights[i]);
        if (s->area_lights[i].triangle && power > 0) {
            total += power;
            lp->light[lp->n] = i;
            lp->cdf[lp->n++] = total;
        }
    }
    for (int k = 0; k < lp->n; k++) {
        lp->cdf[k] /= total;
        lp->prob[lp->light[k]] = lp->cdf[k] - (k > 0 ? lp->cdf[k - 1] : 0);
    }
    if (lp->n > 0) {
        /* The last bin ends at 1 exactly, so every u0 < 1 finds one; the
         * probabilities stay the cdf's steps, which is what picking uses. */
        lp->cdf[lp->n - 1] = 1;
        int last = lp->light[lp->n - 1];
        lp->prob[last] = 1 - (lp->n > 1 ? lp->cdf[lp->n - 2] : 0);
    }
    return true;
}

void
light_picker_free(struct light_picker *lp)
{
    free(lp->light);
    free(lp->cdf);
    free(lp->prob);
    *lp = (struct light_picker){0};
}

int
light_picker_sample(
    const struct light_picker *lp,
    const struct scene *s,
    real u0,
    real u,
    real v,
    vec3 *y,
    real *pdf_area)
{
    if (lp->n == 0) {
        return -1;
    }
    /* The first bin whose upper end exceeds u0 (binary search). */
    int lo = 0;
    int hi = lp->n - 1;
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (lp->cdf[mid] > u0) {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    int i = lp->light[lo];
    const struct area_light *light = &s->area_lights[i];
    fold_into_triangle(light, &u, &v);
    *y = sample_area_light(light, u, v);
    *pdf_area = lp->prob[i] / area_light_area(light);
    return i;
}

real
light_picker_pdf_solid_angle(
    const struct light_picker *lp,
    const struct scene *s,
    int i,
    vec3 x,
    vec3 y)
{
    const struct area_light *light = &s->area_lights[i];
    vec3 d = vec3_sub(y, x);
    real dist2 = vec3_length2(d);
    real cos_light = fabs(vec3_dot(area_light_normal(light), d)) / sqrt(dist2);
    if (!(cos_light > 0) || lp->prob[i] == 0) {
        return 0;
    }
    return lp->prob[i] / area_light_area(light) * dist2 / cos_light;
}

real
mis_power_heuristic(real n_f, real pdf_f, real n_g, real pdf_g)
{
    real f = n_f * pdf_f;
    real g = n_g * pdf_g;
    if (!(f > 0)) {
        return 0;
    }
    /* f^2 / (f^2 + g^2), written as 1 / (1 + (g/f)^2) so that neither
     * square overflows. */
    real ratio = g / f;
    return 1 / (1 + ratio * ratio);
}

real
light_pdf(
    const struct scene *s,
    const struct shadow_sampling *sampling,
    const struct light_picker *picker,
    int light,
    vec3 x,
    vec3 y)
{
    if (light >= s->n_area_lights) {
        real one_minus_cos_max;
        const struct sphere_light *sphere = &s->sphere_lights[light - s->n_area_lights];
        return sphere_cone(sphere, x, &one_minus_cos_max) ? 1 / (2 * PI * one_minus_cos_max) : 0;
    }
    const struct area_light *area = &s->area_lights[light];
    if (area->triangle) {
        return light_picker_pdf_solid_angle(picker, s, light, x, y);
    }
    struct spherical_rect sr;
    if (rect_by_solid_angle(sampling, area, x) && spherical_rect_make(area, x, &sr)) {
        return 1 / sr.solid_angle;
    }
    /* By area: 1 / A per unit area, r^2 / (A cos(theta')) per steradian. */
    vec3 d = vec3_sub(y, x);
    real dist2 = vec3_length2(d);
    real cos_light = area_light_cos(area, area_light_normal(area), vec3_neg(d)) / sqrt(dist2);
    if (!(cos_light > 0)) {
        return 0;
    }
    return dist2 / (area_light_area(area) * cos_light);
}

/* Irradiance from the emitting triangles, sampled as one light (Shirley,
 * Wang and Zimmerman, "Monte Carlo Techniques for Direct Lighting
 * Calculations", 1996): each of n samples is a point y drawn by the picker
 * with density p_i / A_i, and L cos(theta) cos(theta') / r^2 divided by that
 * density, i.e. the rectangle's estimate L cos cos' A / r^2 divided by p_i. */
static vec3
triangle_lights_irradiance(
    const struct world *w,
    const struct hit *h,
    const struct shadow_sampling *sampling,
    const struct light_picker *picker,
    int n,
    struct rng *rng,
    struct stats *st)
{
    vec3 sum = vec3_splat(0);
    int number = w->scene->n_area_lights + w->scene->n_sphere_lights;
    for (int k = 0; k < n; k++) {
        real u0;
        real u;
        real v;
        if (sampling->lowdisc) {
            /* The pick from a 1D sequence of its own, the point on the
             * triangle from the 2D one of the picker. */
            uint32_t index = sampling->lowdisc_index * (uint32_t)n + (uint32_t)k;
            u0 = lowdisc_point1(index, light_seed(sampling, number + 1));
            lowdisc_point2(index, light_seed(sampling, number), &u, &v);
        } else {
            u0 = rng_uniform(rng);
            u = rng_uniform(rng);
            v = rng_uniform(rng);
        }
        vec3 y;
        real pdf_area;
        int i = light_picker_sample(picker, w->scene, u0, u, v, &y, &pdf_area);
        const struct area_light *light = &w->scene->area_lights[i];
        inspect_light(st, TRACE_AREA_LIGHT, i);
        bool blocked;
        vec3 e = area_sample_irradiance(w, h, sampling, light, y, 0, picker->prob[i], st, &blocked);
        sum = vec3_add(sum, e);
    }
    return vec3_scale(sum, 1 / (real)n);
}

vec3
direct_irradiance(
    const struct world *w,
    const struct hit *h,
    const struct shadow_sampling *sampling,
    const struct light_picker *picker,
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
        if (!light->triangle) {
            inspect_light(st, TRACE_AREA_LIGHT, i);
            e = vec3_add(e, area_light_irradiance(w, h, light, sampling, rng, st));
        }
    }
    for (int i = 0; i < s->n_sphere_lights; i++) {
        const struct sphere_light *sphere = &s->sphere_lights[i];
        inspect_light(st, TRACE_SPHERE_LIGHT, i);
        e = vec3_add(e, sphere_light_irradiance(w, h, sphere, sampling, rng, st));
    }
    if (picker->n > 0) {
        e = vec3_add(
            e,
            triangle_lights_irradiance(w, h, sampling, picker, sampling->samples, rng, st));
    }
    return e;
}
