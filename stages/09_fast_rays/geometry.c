/*
 * geometry.c - ray-sphere, ray-quad and ray-triangle intersection, the
 * closest hit over the whole scene by testing every primitive, and rays
 * that leave a surface without hitting it again.
 *
 * The intersection routines are defined `inline` while geometry.h declares
 * them without it, which keeps these the one external definition (C11
 * 6.7.4): the keyword only invites the compiler to inline them into the
 * loops over primitives, saving a copy of the ray per primitive tested
 * (callgrind: 9% of stage 07's instructions on the Cornell boxes).
 */
#include "geometry.h"

/*
 * Self-intersection.  A computed hit point is off the true surface by a few
 * rounding errors of the numbers it was computed from, so a ray leaving it
 * may find the same surface again at a tiny t ("shadow acne").  A fixed
 * epsilon (smallpt's 1e-4) fails at other scales: too small far from the
 * origin, larger than the scene itself for tiny scenes.  Instead every hit
 * carries a bound on its error, proportional to the magnitude of the numbers
 * the point was computed from, and spawned rays start that far off the
 * surface along the normal (pbrt 4ed, section 6.8; Wachter and Binder, Ray
 * Tracing Gems ch. 6).  Each reconstruction below (p0 + u e1 + v e2, or
 * centre + r n) takes a handful of operations, each rounding by at most half
 * an ulp of the largest magnitude involved; ERROR_ULPS covers them with a
 * wide margin (docs/stages/02_shadows.md measures it).
 */
#define ERROR_ULPS 64

static real
max_abs(vec3 a)
{
    return vec3_max_comp(vec3_abs(a));
}

static real
error_bound(real magnitude)
{
    return ERROR_ULPS * REAL_EPSILON * magnitude;
}

struct world
world_make(const struct scene *s)
{
    int n_shapes = s->n_spheres + s->n_quads + s->n_triangles;
    return (struct world){.scene = s, .n_prims = n_shapes + s->n_area_lights + s->n_sphere_lights};
}

/*
 * The sphere quadratic t^2 + 2 b' t + c = 0 (unit direction), solved without
 * catastrophic cancellation (Haines et al., "Precision Improvements for
 * Ray/Sphere Intersection", Ray Tracing Gems, ch. 7, 2019):
 *  - the discriminant r^2 - |f - (f.d) d|^2 uses the perpendicular distance
 *    of the centre from the ray, not b'^2 - c, which cancels when the sphere
 *    is small or far away;
 *  - the root of larger magnitude q = -b' - sign(b') sqrt(disc) is computed
 *    directly and the other as c / q, never as a difference of near-equal
 *    numbers (Press et al., Numerical Recipes, 5.6).
 */
inline bool
intersect_sphere(const struct sphere *sphere, ray r, real t_max, real *t)
{
    /* LAB 01: ray-sphere intersection */
    vec3 f = vec3_sub(r.o, sphere->center);
    real b = -vec3_dot(f, r.d);
    vec3 perpendicular = vec3_madd(f, r.d, b);
    real radius2 = sphere->radius * sphere->radius;
    real disc = radius2 - vec3_length2(perpendicular);
    if (disc < 0) {
        return false;
    }
    real c = vec3_length2(f) - radius2;
    real q = b + copysign(sqrt(disc), b);
    real t_near = q != 0 ? c / q : 0;
    real t_far = q;
    if (t_near > t_far) {
        real swap = t_near;
        t_near = t_far;
        t_far = swap;
    }
    real t_hit = t_near > 0 ? t_near : t_far;
    if (!(t_hit > 0 && t_hit < t_max)) {
        return false;
    }
    *t = t_hit;
    return true;
    /* END LAB */
}

/*
 * Moller-Trumbore ("Fast, Minimum Storage Ray/Triangle Intersection", 1997):
 * solve o + t d = p0 + u e1 + v e2 by Cramer's rule.  A parallelogram is the
 * same system with u and v each in [0, 1] instead of u, v >= 0, u + v <= 1.
 * Returns false for rays parallel to the plane (det = 0), and as soon as u
 * leaves [0, 1] or v goes below 0, which rules out both shapes: most rays
 * miss most primitives, and they need not pay for t.
 */
static inline bool
solve_planar(vec3 p0, vec3 e1, vec3 e2, ray r, real *t, real *u, real *v)
{
    /* LAB 01: ray-triangle intersection */
    vec3 pvec = vec3_cross(r.d, e2);
    real det = vec3_dot(e1, pvec);
    if (det == 0) {
        return false;
    }
    real inv_det = 1 / det;
    vec3 tvec = vec3_sub(r.o, p0);
    *u = vec3_dot(tvec, pvec) * inv_det;
    if (!(*u >= 0 && *u <= 1)) {
        return false;
    }
    vec3 qvec = vec3_cross(tvec, e1);
    *v = vec3_dot(r.d, qvec) * inv_det;
    if (!(*v >= 0)) {
        return false;
    }
    *t = vec3_dot(e2, qvec) * inv_det;
    return true;
    /* END LAB */
}

/*
 * A triangle or parallelogram of zero area (a repeated corner, collinear
 * corners, parallel edges) spans no plane.  Its determinant e1 . (d x e2) is
 * zero only in exact arithmetic: rounded, it is a tiny number of either
 * sign, and a ray along the shape's line would "hit" it at an arbitrary t
 * about one time in thirty (docs/extremes.md).  Such shapes are never hit
 * (docs/scene-format.md): a hit needs edges whose cross product is not
 * exactly zero.  The test comes last, so only rays that pass every other
 * test pay for it.
 */
static bool
spans_plane(vec3 e1, vec3 e2)
{
    return !vec3_is_zero(vec3_cross(e1, e2));
}

inline bool
intersect_quad(const struct quad *quad, ray r, real t_max, real *t, real *u, real *v)
{
    if (!solve_planar(quad->corner, quad->edge1, quad->edge2, r, t, u, v)) {
        return false;
    }
    return *u >= 0 && *u <= 1 && *v >= 0 && *v <= 1 && *t > 0 && *t < t_max
           && spans_plane(quad->edge1, quad->edge2);
}

inline bool
intersect_triangle(vec3 p0, vec3 p1, vec3 p2, ray r, real t_max, real *t, real *u, real *v)
{
    vec3 e1 = vec3_sub(p1, p0);
    vec3 e2 = vec3_sub(p2, p0);
    if (!solve_planar(p0, e1, e2, r, t, u, v)) {
        return false;
    }
    return *u >= 0 && *v >= 0 && *u + *v <= 1 && *t > 0 && *t < t_max && spans_plane(e1, e2);
}

static struct quad
light_quad(const struct area_light *light)
{
    return (struct quad){light->corner, light->edge1, light->edge2, -1, light->loc.line};
}

static struct sphere
light_sphere(const struct sphere_light *light)
{
    return (struct sphere){light->center, light->radius, -1, light->loc.line};
}

inline bool
intersect_prim(const struct scene *s, int prim, ray r, real t_max, struct hit *out)
{
    real t = 0;
    real u = 0;
    real v = 0;
    bool found;
    int n_shapes = s->n_spheres + s->n_quads + s->n_triangles;
    if (prim < s->n_spheres) {
        found = intersect_sphere(&s->spheres[prim], r, t_max, &t);
    } else if (prim < s->n_spheres + s->n_quads) {
        found = intersect_quad(&s->quads[prim - s->n_spheres], r, t_max, &t, &u, &v);
    } else if (prim >= n_shapes + s->n_area_lights) {
        struct sphere sphere = light_sphere(&s->sphere_lights[prim - n_shapes - s->n_area_lights]);
        found = intersect_sphere(&sphere, r, t_max, &t);
    } else if (prim >= n_shapes) {
        /* A triangle light is the half u + v <= 1 of its parallelogram. */
        const struct area_light *light = &s->area_lights[prim - n_shapes];
        struct quad q = light_quad(light);
        found = intersect_quad(&q, r, t_max, &t, &u, &v) && (!light->triangle || u + v <= 1);
    } else {
        const struct triangle *tri = &s->triangles[prim - s->n_spheres - s->n_quads];
        vec3 p0 = s->positions[tri->v[0]];
        vec3 p1 = s->positions[tri->v[1]];
        vec3 p2 = s->positions[tri->v[2]];
        found = intersect_triangle(p0, p1, p2, r, t_max, &t, &u, &v);
    }
    if (found) {
        out->t = t;
        out->u = u;
        out->v = v;
        out->prim = prim;
    }
    return found;
}

/* A unit normal from an unnormalised one; a zero-area primitive (whose
 * cross product vanishes) gets the normal facing the ray, so it never
 * produces NaN. */
static vec3
unit_normal_or(vec3 n, vec3 fallback)
{
    real len2 = vec3_length2(n);
    return len2 > 0 && isfinite(len2) ? vec3_scale(n, 1 / sqrt(len2)) : fallback;
}

static void
finish_sphere(const struct sphere *sphere, ray r, struct hit *h)
{
    vec3 outward = unit_normal_or(vec3_sub(ray_at(r, h->t), sphere->center), vec3_neg(r.d));
    /* Re-project onto the surface: o + t d carries the rounding of t. */
    h->p = vec3_madd(sphere->center, outward, sphere->radius);
    h->error = error_bound(max_abs(sphere->center) + sphere->radius);
    h->ng = outward;
    h->n = outward;
    h->material = sphere->material;
}

static void
finish_quad(const struct quad *quad, ray r, struct hit *h)
{
    /* corner + u e1 + v e2 is exact to a few ulps of the quad's size,
     * unlike o + t d, whose error grows with the distance travelled. */
    h->p = vec3_madd(vec3_madd(quad->corner, quad->edge1, h->u), quad->edge2, h->v);
    h->error = error_bound(max_abs(quad->corner) + max_abs(quad->edge1) + max_abs(quad->edge2));
    h->ng = unit_normal_or(vec3_cross(quad->edge1, quad->edge2), vec3_neg(r.d));
    h->n = h->ng;
    h->material = quad->material;
}

static void
finish_triangle(const struct scene *s, const struct triangle *tri, ray r, struct hit *h)
{
    vec3 p0 = s->positions[tri->v[0]];
    vec3 e1 = vec3_sub(s->positions[tri->v[1]], p0);
    vec3 e2 = vec3_sub(s->positions[tri->v[2]], p0);
    h->p = vec3_madd(vec3_madd(p0, e1, h->u), e2, h->v);
    h->error = error_bound(max_abs(p0) + max_abs(e1) + max_abs(e2));
    h->ng = unit_normal_or(vec3_cross(e1, e2), vec3_neg(r.d));
    h->n = h->ng;
    if (tri->smooth) {
        vec3 n = vec3_scale(s->normals[tri->v[0]], 1 - h->u - h->v);
        n = vec3_madd(n, s->normals[tri->v[1]], h->u);
        n = vec3_madd(n, s->normals[tri->v[2]], h->v);
        h->n = unit_normal_or(n, h->ng);
    }
    h->material = tri->material;
}

void
hit_finish(const struct scene *s, ray r, struct hit *h)
{
    int prim = h->prim;
    int n_shapes = s->n_spheres + s->n_quads + s->n_triangles;
    h->light = -1;
    if (prim < s->n_spheres) {
        finish_sphere(&s->spheres[prim], r, h);
    } else if (prim < s->n_spheres + s->n_quads) {
        finish_quad(&s->quads[prim - s->n_spheres], r, h);
    } else if (prim >= n_shapes + s->n_area_lights) {
        struct sphere sphere = light_sphere(&s->sphere_lights[prim - n_shapes - s->n_area_lights]);
        finish_sphere(&sphere, r, h);
        h->light = prim - n_shapes;
    } else if (prim >= n_shapes) {
        struct quad q = light_quad(&s->area_lights[prim - n_shapes]);
        finish_quad(&q, r, h);
        h->light = prim - n_shapes;
    } else {
        finish_triangle(s, &s->triangles[prim - s->n_spheres - s->n_quads], r, h);
    }
    /* Surfaces are two-sided: turn both normals towards the ray's origin,
     * remembering which side was hit (glass needs to know). */
    h->front_face = vec3_dot(r.d, h->ng) < 0;
    if (!h->front_face) {
        h->ng = vec3_neg(h->ng);
    }
    if (vec3_dot(h->n, h->ng) < 0) {
        h->n = vec3_neg(h->n);
    }
}

bool
world_intersect(const struct world *w, ray r, real t_max, struct hit *out, struct stats *st)
{
    if (w->bvh.n_prims > 0) {
        bool hit = bvh_intersect(w, r, t_max, false, out, st);
        if (hit) {
            hit_finish(w->scene, r, out);
        }
        return hit;
    }
    bool found = false;
    for (int prim = 0; prim < w->n_prims; prim++) {
        if (intersect_prim(w->scene, prim, r, t_max, out)) {
            t_max = out->t;
            found = true;
        }
    }
    st->prim_tests += (uint64_t)w->n_prims;
    if (found) {
        hit_finish(w->scene, r, out);
    }
    return found;
}

bool
world_occluded(const struct world *w, ray r, real t_max, struct stats *st)
{
    /* LAB 02: any-hit query */
    struct hit h;
    if (w->bvh.n_prims > 0) {
        return bvh_intersect(w, r, t_max, true, &h, st);
    }
    for (int prim = 0; prim < w->n_prims; prim++) {
        if (intersect_prim(w->scene, prim, r, t_max, &h)) {
            st->prim_tests += (uint64_t)prim + 1;
            return true;
        }
    }
    st->prim_tests += (uint64_t)w->n_prims;
    return false;
    /* END LAB */
}

ray
spawn_ray(const struct hit *h, vec3 d)
{
    /* LAB 02: ray origin off the surface */
    /* Twice the bound: the new origin is clear of the surface even after
     * the offset itself is rounded. */
    real offset = 2 * h->error;
    vec3 n = vec3_dot(d, h->ng) >= 0 ? h->ng : vec3_neg(h->ng);
    return (ray){vec3_madd(h->p, n, offset), d};
    /* END LAB */
}

ray
spawn_ray_to(const struct hit *h, vec3 to, real *t_max)
{
    ray r = spawn_ray(h, vec3_normalize(vec3_sub(to, h->p)));
    vec3 from_origin = vec3_sub(to, r.o);
    r.d = vec3_normalize(from_origin);
    *t_max = vec3_length(from_origin) - 2 * error_bound(max_abs(to));
    return r;
}
