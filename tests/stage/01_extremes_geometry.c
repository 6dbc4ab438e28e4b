/*
 * 01_extremes_geometry.c - the extremes battery, white-box part: the
 * stage's intersection routines (geometry.h, the same names from stage 01
 * on) at the edges of floating point, each case judged against
 * tests/extremes/expect.tsv (see tests/extremes/expect.h).
 *
 *  - Watertight triangles (Woop, Benthin and Wald, "Watertight Ray/Triangle
 *    Intersection", JCGT 2(1), 2013; pbrt-v4's Triangle.Watertight test):
 *    closed tessellated spheres (meshgen), rays from random points inside
 *    aimed exactly at every vertex and at the midpoint of every edge, and
 *    in random directions.  A ray leaving a closed surface must meet at
 *    least one of its triangles: the figure is the number of rays that meet
 *    none.  Run with the stage's intersect_triangle (Moller-Trumbore) and
 *    with the watertight algorithm, implemented below from the paper, to
 *    show the difference.
 *  - Quadratic cancellation: a sphere of radius 1e-4 at distance 1e4, and
 *    one of radius 1e4 with the ray origins 1e-3 from its surface.  The t
 *    of intersect_sphere against a reference computed from the same inputs
 *    in long double (64-bit significand: ~2^-11 of double's rounding); the
 *    figure is the largest error in units of REAL_EPSILON (|o - c| + r), the
 *    magnitude of the numbers t is computed from, where the ray meets the
 *    sphere at cos >= 0.5; everywhere, the computed point must lie within
 *    as many units of the sphere.  The stated bound is 8 units.  The
 *    textbook quadratic (b^2 - c) is measured beside it for the lesson.
 *  - Tangent rays: rays whose distance from a sphere's centre is r (1 + s)
 *    for s from -1e-6 to 1e-6 through 0 (exactly tangent as far as the
 *    rounded ray allows): those clearly inside the silhouette must hit,
 *    those clearly outside must miss, and every hit must have a finite
 *    t > 0 and a point within 1e-6 r of the sphere.  "Clearly" is a margin
 *    of 64 ulps of |o - c| relative to r: the resolution the rounded inputs
 *    allow (their own rounding moves the ray by that much).
 *  - Degenerate triangles and quads: zero area (a repeated vertex, three
 *    collinear points with e2 = 2 e1 exactly, one point; a quad with
 *    parallel or zero edges).  docs/scene-format.md promises they are never
 *    hit; rays aimed exactly at points of them count the hits, and every
 *    hit's normals must still be finite and unit (hit_finish falls back to
 *    -d when the cross product vanishes).
 */
#include <stdint.h>
#include <string.h>

#include "check.h"
#include "cull.h"
#include "extremes/expect.h"
#include "geometry.h"
#include "meshgen.h"
#include "rng.h"
#include "scene.h"
#include "stagecheck.h"

#define TAG "geometry"

/* Aimed rays per vertex and per edge, and random rays from inside. */
#define RAYS_PER_FEATURE 4
#define RAYS_FROM_INSIDE 20000

/* Random rays per quadratic case and per degenerate shape. */
#define QUADRATIC_RAYS 20000
#define DEGENERATE_RAYS 20000

/* --- a closed mesh as vec3 triangles ------------------------------------- */

struct tri_mesh {
    size_t n;
    vec3 (*corners)[3];
    struct cull_ball *balls; /* per triangle: the rays pass most by (cull.h) */
    double center[3];
    double radius; /* of the sphere it was tessellated from */
};

static struct tri_mesh
tri_mesh_from(const struct meshgen_mesh *m, const double center[3], double radius)
{
    struct tri_mesh t = {.n = m->n_triangles, .radius = radius};
    memcpy(t.center, center, sizeof t.center);
    t.corners = malloc(t.n * sizeof *t.corners);
    t.balls = malloc(t.n * sizeof *t.balls);
    for (size_t i = 0; t.corners && t.balls && i < t.n; i++) {
        for (int k = 0; k < 3; k++) {
            const double *p = &m->positions[3 * m->indices[3 * i + k]];
            t.corners[i][k] = vec3_make((real)p[0], (real)p[1], (real)p[2]);
        }
        const vec3 *c = t.corners[i];
        t.balls[i] = cull_ball_around(
            vec3_min(vec3_min(c[0], c[1]), c[2]),
            vec3_max(vec3_max(c[0], c[1]), c[2]));
    }
    return t;
}

/* --- the watertight test of Woop, Benthin and Wald ------------------------
 *
 * The ray is made the +z axis of a sheared space: the axis kz where |d| is
 * largest becomes z, the vertices are translated by -o and sheared so that
 * d becomes (0, 0, 1).  The 2D edge functions of the sheared triangle
 * decide the hit; each depends only on the two vertices of its edge, and
 * for the neighbour across that edge it is computed from the same two
 * transformed vertices in the other order, which negates it exactly.  So
 * one of the two triangles always claims a ray through their shared edge:
 * watertight.  An edge function that comes out exactly 0 is recomputed in
 * higher precision (the paper's fallback to double, here long double).
 */
struct wbw_ray {
    int kx, ky, kz;
    real sx, sy, sz;
    vec3 o;
};

static struct wbw_ray
wbw_prepare(ray r)
{
    vec3 a = vec3_abs(r.d);
    struct wbw_ray w = {.o = r.o};
    w.kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    w.kx = (w.kz + 1) % 3;
    w.ky = (w.kx + 1) % 3;
    if (vec3_axis(r.d, w.kz) < 0) { /* keep the winding: swap x and y */
        int swap = w.kx;
        w.kx = w.ky;
        w.ky = swap;
    }
    real dz = vec3_axis(r.d, w.kz);
    w.sx = vec3_axis(r.d, w.kx) / dz;
    w.sy = vec3_axis(r.d, w.ky) / dz;
    w.sz = 1 / dz;
    return w;
}

/* A vertex in the ray's sheared space (z not yet scaled). */
struct wbw_vertex {
    real x, y, z;
};

static struct wbw_vertex
wbw_transform(const struct wbw_ray *w, vec3 p)
{
    vec3 a = vec3_sub(p, w->o);
    real z = vec3_axis(a, w->kz);
    return (struct wbw_vertex){vec3_axis(a, w->kx) - w->sx * z, vec3_axis(a, w->ky) - w->sy * z, z};
}

/* The edge function of (a, b): twice the signed area of (0, a, b). */
static real
wbw_edge(struct wbw_vertex a, struct wbw_vertex b)
{
    real e = a.x * b.y - a.y * b.x;
    if (e == 0) {
        e = (real)((long double)a.x * b.y - (long double)a.y * b.x);
    }
    return e;
}

static bool
wbw_intersect(const struct wbw_ray *w, const vec3 corners[3], real t_max)
{
    struct wbw_vertex a = wbw_transform(w, corners[0]);
    struct wbw_vertex b = wbw_transform(w, corners[1]);
    struct wbw_vertex c = wbw_transform(w, corners[2]);
    real u = wbw_edge(b, c);
    real v = wbw_edge(c, a);
    real e = wbw_edge(a, b);
    if ((u < 0 || v < 0 || e < 0) && (u > 0 || v > 0 || e > 0)) {
        return false;
    }
    real det = u + v + e;
    if (det == 0) {
        return false;
    }
    real t_scaled = w->sz * (u * a.z + v * b.z + e * c.z);
    /* t = t_scaled / det in (0, t_max), without dividing. */
    if (det < 0) {
        t_scaled = -t_scaled;
        det = -det;
    }
    return t_scaled > 0 && t_scaled < t_max * det;
}

/* Whether the ray meets any triangle of the mesh, by the stage's test or by
 * the watertight one. */
static bool
mesh_hit(const struct tri_mesh *m, ray r, bool watertight)
{
    struct wbw_ray w = wbw_prepare(r);
    struct cull_line line = cull_line_make(r.o, r.d);
    for (size_t i = 0; i < m->n; i++) {
        if (!cull_line_meets(&m->balls[i], &line)) {
            continue;
        }
        real t, u, v;
        const vec3 *c = m->corners[i];
        bool hit = watertight ? wbw_intersect(&w, c, REAL_MAX)
                              : intersect_triangle(c[0], c[1], c[2], r, REAL_MAX, &t, &u, &v);
        if (hit) {
            return true;
        }
    }
    return false;
}

/* A random point within half a radius of the mesh's centre: inside it. */
static vec3
inside_point(const struct tri_mesh *m, struct rng *rng)
{
    double d[3];
    stagecheck_random_unit(rng, d);
    double s = 0.5 * m->radius * (double)rng_uniform(rng);
    return vec3_make(
        (real)(m->center[0] + s * d[0]),
        (real)(m->center[1] + s * d[1]),
        (real)(m->center[2] + s * d[2]));
}

/* Rays from inside that meet no triangle, though a ray leaving a closed
 * surface must cross it: aimed exactly at each corner and at the midpoint of
 * each edge (each edge twice, once from each of its triangles, which costs
 * nothing and keeps the code short), and in random directions. */
static int
count_leaks(const struct tri_mesh *m, bool watertight, uint64_t seed, int *aimed, int *random)
{
    struct rng rng = rng_make(seed, 1);
    *aimed = 0;
    *random = 0;
    for (size_t i = 0; i < m->n; i++) {
        for (int k = 0; k < 3; k++) {
            vec3 a = m->corners[i][k];
            vec3 mid = vec3_scale(vec3_add(a, m->corners[i][(k + 1) % 3]), (real)0.5);
            for (int j = 0; j < RAYS_PER_FEATURE; j++) {
                vec3 target = j % 2 ? a : mid;
                vec3 o = inside_point(m, &rng);
                *aimed += !mesh_hit(m, (ray){o, vec3_normalize(vec3_sub(target, o))}, watertight);
            }
        }
    }
    for (int i = 0; i < RAYS_FROM_INSIDE; i++) {
        vec3 o = inside_point(m, &rng);
        *random += !mesh_hit(m, (ray){o, stagecheck_random_vec3(&rng)}, watertight);
    }
    return *aimed + *random;
}

/* pbrt's watertight mesh (a UV sphere with jittered radii, exactly closed
 * seam and poles) and an icosphere far from the origin. */
static void
run_watertight(const char *case_name, bool watertight)
{
    static const double origin[3] = {0, 0, 0};
    static const double far[3] = {1000, -2000, 3000};
    struct meshgen_mesh uv = meshgen_sphere(16, 32, 1, origin, 0.05, 5);
    struct meshgen_mesh ico = meshgen_icosphere(3, 10, far);
    CHECK(uv.n_triangles > 0 && ico.n_triangles > 0);
    CHECK(meshgen_is_closed(&uv) && meshgen_is_closed(&ico));
    struct tri_mesh meshes[2] = {tri_mesh_from(&uv, origin, 1), tri_mesh_from(&ico, far, 10)};
    struct outcome o = {0};
    int aimed[2], inside[2];
    for (int i = 0; i < 2; i++) {
        bool made = meshes[i].corners && meshes[i].balls;
        CHECK(made);
        o.figure +=
            made ? count_leaks(&meshes[i], watertight, 11 + (uint64_t)i, &aimed[i], &inside[i])
                 : 1;
        free(meshes[i].corners);
        free(meshes[i].balls);
    }
    o.passed = o.figure == 0;
    snprintf(
        o.note,
        sizeof o.note,
        "rays from inside through no triangle: UV sphere (%zu triangles) %d aimed at "
        "vertices and edges, %d random; icosphere at 1e3..3e3 (%zu triangles) %d aimed, %d random",
        uv.n_triangles,
        aimed[0],
        inside[0],
        ico.n_triangles,
        aimed[1],
        inside[1]);
    expect_judge(TAG, case_name, REAL_NAME, &o);
    meshgen_free(&uv);
    meshgen_free(&ico);
}

TEST(watertight_moller_trumbore)
{
    run_watertight("watertight_mt", false);
}

TEST(watertight_woop_benthin_wald)
{
    run_watertight("watertight_wbw", true);
}

/* --- the sphere quadratic -------------------------------------------------- */

/* The near root of |o + t d - c| = r with t > 0 (the far one from inside),
 * in long double, by the same stable formulation as the stage (the
 * discriminant from the perpendicular distance, the smaller root as c / q):
 * the point is the precision, not the method.  NaN on a miss. */
static long double
reference_t(vec3 center, real radius, ray r)
{
    long double f[3] = {
        (long double)r.o.x - center.x,
        (long double)r.o.y - center.y,
        (long double)r.o.z - center.z};
    long double d[3] = {r.d.x, r.d.y, r.d.z};
    long double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    long double b = -(f[0] * d[0] + f[1] * d[1] + f[2] * d[2]) / dd;
    long double perp2 = 0;
    long double f2 = 0;
    for (int i = 0; i < 3; i++) {
        long double p = f[i] + b * d[i];
        perp2 += p * p;
        f2 += f[i] * f[i];
    }
    long double rr = (long double)radius * radius;
    long double disc = (rr - perp2) / dd;
    if (disc < 0) {
        return NAN;
    }
    long double c = (f2 - rr) / dd;
    long double q = b + copysignl(sqrtl(disc), b);
    long double t_near = c / q;
    long double t_far = q;
    long double lo = t_near < t_far ? t_near : t_far;
    long double hi = t_near < t_far ? t_far : t_near;
    return lo > 0 ? lo : hi > 0 ? hi : NAN;
}

/* The textbook root -b - sqrt(b^2 - c), in the working precision, for
 * comparison: what the stable form saves. */
static real
textbook_t(vec3 center, real radius, ray r)
{
    vec3 f = vec3_sub(r.o, center);
    real b = vec3_dot(f, r.d);
    real c = vec3_dot(f, f) - radius * radius;
    real disc = b * b - c;
    return disc < 0 ? (real)NAN : -b - sqrt(disc);
}

struct quadratic_case {
    const char *name;
    double radius;
    double distance; /* of the ray origins from the sphere's centre */
};

/* How far the point o + t d lies from the sphere, in long double. */
static long double
off_surface(vec3 center, real radius, ray r, real t)
{
    long double s = 0;
    for (int i = 0; i < 3; i++) {
        long double q = (long double)vec3_axis(r.o, i) + (long double)t * vec3_axis(r.d, i)
                        - vec3_axis(center, i);
        s += q * q;
    }
    return fabsl(sqrtl(s) - radius);
}

/* The worst errors over a set of rays, in ulps of |o - c| + r. */
struct t_errors {
    double forward; /* |t - t_ref|, rays meeting the sphere at cos >= 0.5 */
    double relative; /* the same relative to t_ref */
    double backward; /* distance of o + t d from the sphere, every ray */
    int misses;
};

static void
add_error(struct t_errors *e, vec3 center, real radius, ray r, real t, bool conditioned, double ulp)
{
    long double ref = reference_t(center, radius, r);
    if (isnan(t) || isnan((double)ref)) {
        e->misses++;
        return;
    }
    if (conditioned) {
        e->forward = fmax(e->forward, (double)fabsl((long double)t - ref) / ulp);
        e->relative = fmax(e->relative, (double)(fabsl((long double)t - ref) / ref));
    }
    e->backward = fmax(e->backward, (double)off_surface(center, radius, r, t) / ulp);
}

/* A random direction from the origin into the cone of half-angle 0.99
 * alpha around `axis` (alpha: the sphere's angular radius), so every ray
 * must hit: the angle from the axis is 0.99 alpha sqrt(u), which works for
 * alpha = 1e-8 (a sphere of radius 1e-4 at 1e4) as for alpha near 90
 * degrees (one of radius 1e4 seen from 1e-3 away). */
static vec3
into_cone(vec3 axis, double alpha, struct rng *rng)
{
    struct onb basis = onb_from_normal(axis);
    double theta = 0.99 * alpha * sqrt((double)rng_uniform(rng));
    double phi = 2 * PI * (double)rng_uniform(rng);
    vec3 local =
        vec3_make((real)(sin(theta) * cos(phi)), (real)(sin(theta) * sin(phi)), (real)cos(theta));
    return vec3_normalize(onb_to_world(basis, local));
}

/* Whether ray r meets the sphere at an incidence of cos >= 0.5 (by the
 * reference hit): where t is well conditioned.  Nearer the silhouette a
 * perturbation of the ray by its own rounding moves t by more, whatever
 * the algorithm, so only the distance from the surface is judged there. */
static bool
well_conditioned(vec3 center, real radius, ray r)
{
    long double t = reference_t(center, radius, r);
    long double cos_in = 0;
    for (int i = 0; i < 3; i++) {
        long double n =
            ((long double)vec3_axis(r.o, i) + t * vec3_axis(r.d, i) - vec3_axis(center, i))
            / radius;
        cos_in -= n * vec3_axis(r.d, i);
    }
    return cos_in >= 0.5L;
}

/* Rays from the origin, `distance` from the centre, into the cone of
 * directions that meet the sphere: the errors of the stage's t and of the
 * textbook t. */
static void
run_quadratic(const struct quadratic_case *qc)
{
    double gap = fmin(qc->radius, qc->distance - qc->radius); /* the smallest length */
    if (!stagecheck_representable(gap, qc->distance)) {
        expect_log_skip(TAG, qc->name, REAL_NAME, "below this precision's resolution");
        return;
    }
    vec3 axis = vec3_normalize(vec3_make((real)0.48, (real)-0.6, (real)0.64));
    vec3 center = vec3_scale(axis, (real)qc->distance);
    real radius = (real)qc->radius;
    struct sphere sphere = {.center = center, .radius = radius, .material = 0};
    double ulp = (double)REAL_EPSILON * (qc->distance + qc->radius);
    double alpha = asin(qc->radius / qc->distance);
    struct rng rng = rng_make(21, 1);
    struct t_errors stage = {0};
    struct t_errors textbook = {0};
    int conditioned_rays = 0;
    for (int i = 0; i < QUADRATIC_RAYS; i++) {
        ray r = {vec3_make(0, 0, 0), into_cone(axis, alpha, &rng)};
        bool conditioned = well_conditioned(center, radius, r);
        conditioned_rays += conditioned;
        real t;
        bool hit = intersect_sphere(&sphere, r, REAL_MAX, &t);
        add_error(&stage, center, radius, r, hit ? t : (real)NAN, conditioned, ulp);
        add_error(&textbook, center, radius, r, textbook_t(center, radius, r), conditioned, ulp);
    }
    struct outcome o = {.figure = stage.misses > 0 ? INFINITY : stage.forward};
    /* A handful of roundings of numbers of magnitude |o - c| + r. */
    o.passed = stage.misses == 0 && stage.forward <= 8 && stage.backward <= 8;
    snprintf(
        o.note,
        sizeof o.note,
        "%d rays (%d at cos >= 0.5), worst errors in ulps of |o-c|+r: |t - t_ref| %.3g (%.2g "
        "relative to t), "
        "distance from the sphere %.3g, misses %d; textbook b^2 - c: %.3g (%.2g relative), "
        "%.3g, misses %d",
        QUADRATIC_RAYS,
        conditioned_rays,
        stage.forward,
        stage.relative,
        stage.backward,
        stage.misses,
        textbook.forward,
        textbook.relative,
        textbook.backward,
        textbook.misses);
    expect_judge(TAG, qc->name, REAL_NAME, &o);
}

TEST(quadratic_cancellation)
{
    static const struct quadratic_case cases[] = {
        {"quadratic_tiny_far", 1e-4, 1e4},
        {"quadratic_huge_near", 1e4, 1e4 + 1e-3},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        run_quadratic(&cases[i]);
    }
}

/* --- tangent rays ----------------------------------------------------------- */

/* A ray passing at distance h from the centre, with direction d and the
 * point of closest approach c + h p (p unit, perpendicular to d), starting
 * `back` before it; built in long double and rounded. */
static ray
ray_past(vec3 center, vec3 d, vec3 p, long double h, long double back)
{
    long double o[3];
    for (int i = 0; i < 3; i++) {
        o[i] = (long double)vec3_axis(center, i) + h * vec3_axis(p, i) - back * vec3_axis(d, i);
    }
    return (ray){vec3_make((real)o[0], (real)o[1], (real)o[2]), d};
}

/* The distance of the (rounded) ray from the centre, in long double. */
static long double
ray_distance(vec3 center, ray r)
{
    long double f[3] = {
        (long double)r.o.x - center.x,
        (long double)r.o.y - center.y,
        (long double)r.o.z - center.z};
    long double d[3] = {r.d.x, r.d.y, r.d.z};
    long double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    long double b = (f[0] * d[0] + f[1] * d[1] + f[2] * d[2]) / dd;
    long double s = 0;
    for (int i = 0; i < 3; i++) {
        long double q = f[i] - b * d[i];
        s += q * q;
    }
    return sqrtl(s);
}

/* Wrong answers among rays tangent (or nearly) to a sphere. */
static int
tangent_errors(const struct quadratic_case *qc, int *n_rays, int *n_hits)
{
    static const long double offsets[] = {-1e-6L, -1e-9L, -1e-12L, 0, 1e-12L, 1e-9L, 1e-6L};
    vec3 center = vec3_scale(vec3_normalize(vec3_make(-2, 3, 1)), (real)qc->distance);
    real radius = (real)qc->radius;
    struct sphere sphere = {.center = center, .radius = radius, .material = 0};
    /* The distance at which the rays start, and the resolution it allows. */
    long double back = qc->distance > 2 * qc->radius ? qc->distance : 2 * qc->radius;
    long double margin = 64 * REAL_EPSILON * (back + qc->radius) / qc->radius;
    struct rng rng = rng_make(31, 1);
    int errors = 0;
    for (int i = 0; i < 200; i++) {
        vec3 d = stagecheck_random_vec3(&rng);
        vec3 p = vec3_normalize(vec3_cross(d, stagecheck_random_vec3(&rng)));
        for (size_t k = 0; k < sizeof offsets / sizeof offsets[0]; k++) {
            ray r = ray_past(center, d, p, qc->radius * (1 + offsets[k]), back);
            long double s = ray_distance(center, r) / qc->radius - 1;
            real t;
            bool hit = intersect_sphere(&sphere, r, REAL_MAX, &t);
            (*n_rays)++;
            *n_hits += hit;
            if (hit) {
                vec3 q = ray_at(r, t);
                long double off = fabsl(
                    sqrtl(
                        ((long double)q.x - center.x) * (q.x - center.x)
                        + ((long double)q.y - center.y) * (q.y - center.y)
                        + ((long double)q.z - center.z) * (q.z - center.z))
                    - radius);
                errors += !(isfinite(t) && t > 0) || off > 1e-6L * radius + margin * radius;
            }
            errors += (s < -margin && !hit) || (s > margin && hit);
        }
    }
    return errors;
}

TEST(tangent_rays)
{
    static const struct quadratic_case cases[] = {
        {"tangent_unit", 1, 0},
        {"tangent_tiny_far", 1e-4, 1e4},
        {"tangent_huge", 1e4, 1e4},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        if (!stagecheck_representable(cases[i].radius, cases[i].distance)) {
            expect_log_skip(TAG, cases[i].name, REAL_NAME, "below this precision's resolution");
            continue;
        }
        int n_rays = 0;
        int n_hits = 0;
        struct outcome o = {.figure = tangent_errors(&cases[i], &n_rays, &n_hits)};
        o.passed = o.figure == 0;
        snprintf(
            o.note,
            sizeof o.note,
            "%d rays at r(1 + s), |s| <= 1e-6: %d hits, %g wrong",
            n_rays,
            n_hits,
            o.figure);
        expect_judge(TAG, cases[i].name, REAL_NAME, &o);
    }
}

/* --- degenerate triangles and quads ---------------------------------------- */

/* A scene of one degenerate shape (the rest of the statement after the
 * material), loaded from text. */
static bool
load_shape(const char *statement, struct scene *s)
{
    char text[1024];
    snprintf(
        text,
        sizeof text,
        "camera origin 0 0 10 target 0 0 0 up 0 1 0 fov 40\n"
        "image width 1 height 1\n"
        "material m diffuse albedo 0.5 0.5 0.5\n%s material m\n",
        statement);
    struct diag err;
    if (!scene_load_string(text, strlen(text), "degenerate.scene", s, &err)) {
        diag_print(stdout, &err, "error");
        return false;
    }
    return true;
}

struct degenerate {
    const char *kind;
    const char *statement;
    double a[3], e[3]; /* rays are aimed at a + s e, s in [0, 1] */
};

/* Rays aimed at points of the shape: how many report a hit, and how many
 * of those have a normal that is not finite and unit. */
static void
shoot_degenerate(const struct degenerate *dg, int *hits, int *bad_normals)
{
    struct scene s = {0};
    if (!load_shape(dg->statement, &s)) {
        *hits += DEGENERATE_RAYS;
        return;
    }
    struct world w = world_make(&s);
    struct rng rng = rng_make(41, 1);
    for (int i = 0; i < DEGENERATE_RAYS; i++) {
        real u = rng_uniform(&rng);
        vec3 target = vec3_make(
            (real)(dg->a[0] + u * dg->e[0]),
            (real)(dg->a[1] + u * dg->e[1]),
            (real)(dg->a[2] + u * dg->e[2]));
        vec3 o = vec3_madd(target, stagecheck_random_vec3(&rng), 5);
        ray r = {o, vec3_normalize(vec3_sub(target, o))};
        struct hit h;
        struct stats st = {0};
        if (world_intersect(&w, r, REAL_MAX, &h, &st)) {
            (*hits)++;
            bool unit = fabs(vec3_length(h.ng) - 1) < 1e-3 && fabs(vec3_length(h.n) - 1) < 1e-3;
            *bad_normals += !(vec3_is_finite(h.ng) && vec3_is_finite(h.p) && unit);
        }
    }
    scene_free(&s);
}

TEST(degenerate_shapes_never_hit)
{
    /* Dyadic coordinates: the edges below are exact, and e2 = 2 e1 or
     * e2 = e1 / 2 exactly, so each cross product is exactly zero. */
    static const struct degenerate shapes[] = {
        {"repeated vertex",
         "triangle v0 -0.75 0.25 0.5 v1 0.5 -0.375 -0.25 v2 0.5 -0.375 -0.25",
         {-0.75, 0.25, 0.5},
         {1.25, -0.625, -0.75}},
        {"collinear",
         "triangle v0 -0.75 0.25 0.5 v1 -0.125 -0.0625 0.125 v2 0.5 -0.375 -0.25",
         {-0.75, 0.25, 0.5},
         {1.25, -0.625, -0.75}},
        {"one point",
         "triangle v0 0.5 -0.375 -0.25 v1 0.5 -0.375 -0.25 v2 0.5 -0.375 -0.25",
         {0.5, -0.375, -0.25},
         {0, 0, 0}},
        {"quad, parallel edges",
         "quad corner -0.75 0.25 0.5 edge1 1.25 -0.625 -0.75 edge2 0.625 -0.3125 -0.375",
         {-0.75, 0.25, 0.5},
         {1.875, -0.9375, -1.125}},
        {"quad, a zero edge",
         "quad corner -0.75 0.25 0.5 edge1 1.25 -0.625 -0.75 edge2 0 0 0",
         {-0.75, 0.25, 0.5},
         {1.25, -0.625, -0.75}},
    };
    struct outcome o = {0};
    char *note = o.note;
    size_t room = sizeof o.note;
    int total_bad = 0;
    for (size_t i = 0; i < sizeof shapes / sizeof shapes[0]; i++) {
        int hits = 0;
        int bad = 0;
        shoot_degenerate(&shapes[i], &hits, &bad);
        o.figure += hits;
        total_bad += bad;
        int n = snprintf(note, room, "%s%s: %d", i ? ", " : "", shapes[i].kind, hits);
        note += n > 0 && (size_t)n < room ? n : 0;
        room -= n > 0 && (size_t)n < room ? (size_t)n : 0;
    }
    snprintf(
        note,
        room,
        " hits of %d aimed rays each; normals not finite and unit: %d",
        DEGENERATE_RAYS,
        total_bad);
    o.passed = o.figure == 0;
    CHECK_MSG(total_bad == 0, "%d hits on degenerate shapes with a bad normal", total_bad);
    expect_judge(TAG, "degenerate_never_hit", REAL_NAME, &o);
}

TEST_MAIN(
    TEST_ENTRY(watertight_moller_trumbore),
    TEST_ENTRY(watertight_woop_benthin_wald),
    TEST_ENTRY(quadratic_cancellation),
    TEST_ENTRY(tangent_rays),
    TEST_ENTRY(degenerate_shapes_never_hit))
