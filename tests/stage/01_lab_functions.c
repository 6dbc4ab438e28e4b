/*
 * 01_lab_functions.c - lab 01's functions, each on its own (tests/lab/
 * README.md, "Function tests"), against formulas computed here in long
 * double, independently of the stage.
 *
 *  - camera_ray: the pinhole model (SCENES.md): the film point (x, y) in
 *    pixels from the top-left corner maps to the direction forward +
 *    (2x/w - 1) tan(vfov/2) (w/h) right + (1 - 2y/h) tan(vfov/2) up, unit,
 *    from the camera's origin (or the near plane), for a tilted camera and
 *    a wide image, at the corners, the centre and random points.
 *  - intersect_sphere: the nearest root in (0, t_max), from outside, from
 *    inside (the far root), behind (none), past t_max (none), and for a
 *    small sphere far away, where the textbook b^2 - c cancels: the hit
 *    lies on the sphere to 1e-6 of its radius (single precision: 1e-3).
 *  - intersect_triangle (and intersect_quad, which share solve_planar, the
 *    lab's Moller-Trumbore): hit or miss, t and (u, v) against the
 *    barycentric solution, from both sides, away from the edges (1e-6).
 *  - point_irradiance: I cos(theta) / r^2 for random points, normals and
 *    lights, 0 below the horizon.
 *
 * Deterministic (fixed seeds).  White-box: camera_make, camera_ray,
 * intersect_sphere, intersect_triangle, intersect_quad, point_irradiance
 * and struct hit, which every later stage keeps.
 */
#include <stdio.h>
#include <string.h>

#include "camera.h"
#include "check.h"
#include "geometry.h"
#include "light.h"
#include "rng.h"
#include "stagecheck.h"

#define SINGLE (sizeof(real) == sizeof(float))
/* Agreement with long double for directions, t and coordinates. */
#define TOL (SINGLE ? 1e-4 : 1e-9)

typedef long double ld;

static void
ld_normalize(ld v[3])
{
    ld n = sqrtl(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= n;
    v[1] /= n;
    v[2] /= n;
}

static void
ld_cross(const ld a[3], const ld b[3], ld out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* The pinhole model's direction through film (x, y). */
static void
pinhole(const struct camera_desc *desc, int w, int h, double x, double y, ld out[3])
{
    ld f[3] = {
        desc->target.x - desc->origin.x,
        desc->target.y - desc->origin.y,
        desc->target.z - desc->origin.z};
    ld up[3] = {desc->up.x, desc->up.y, desc->up.z};
    ld r[3];
    ld u[3];
    ld_normalize(f);
    ld_cross(f, up, r);
    ld_normalize(r);
    ld_cross(r, f, u);
    ld th = tanl((ld)desc->vfov_deg * 3.14159265358979323846264L / 360);
    ld sx = (2 * (ld)x / w - 1) * th * w / h;
    ld sy = (1 - 2 * (ld)y / h) * th;
    for (int k = 0; k < 3; k++) {
        out[k] = f[k] + sx * r[k] + sy * u[k];
    }
    ld_normalize(out);
}

TEST(camera_ray_follows_the_pinhole_model)
{
    struct camera_desc desc = {
        .origin = {1, 2, 3},
        .target = {(real)-0.5, (real)0.7, (real)-1.2},
        .up = {(real)0.1, 1, 0},
        .vfov_deg = 50,
    };
    const int w = 320;
    const int h = 180;
    struct camera cam = camera_make(&desc, w, h);
    struct rng rng = rng_make(1001, 1);
    double points[8][2] = {{0, 0}, {w, 0}, {0, h}, {w, h}, {w / 2.0, h / 2.0}};
    for (int i = 5; i < 8; i++) {
        points[i][0] = w * (double)rng_uniform(&rng);
        points[i][1] = h * (double)rng_uniform(&rng);
    }
    static const char *const names[] = {
        "top-left corner",
        "top-right corner",
        "bottom-left corner",
        "bottom-right corner",
        "centre",
        "a random point",
        "a random point",
        "a random point"};
    for (int i = 0; i < 8; i++) {
        ray r = camera_ray(&cam, (real)points[i][0], (real)points[i][1]);
        ld want[3];
        pinhole(&desc, w, h, points[i][0], points[i][1], want);
        double err = fabsl(r.d.x - want[0]) + fabsl(r.d.y - want[1]) + fabsl(r.d.z - want[2]);
        double from_eye = (double)vec3_length(vec3_sub(r.o, desc.origin));
        if (!(err < 3 * TOL && from_eye < TOL)) {
            CHECK_FAIL(
                "camera_ray (320 x 180 image, vertical field of view 50 deg, film point (%g, %g), the %s): "
                "origin (%g %g %g), direction (%.6f %.6f %.6f), where the pinhole model gives the camera's "
                "origin (1 2 3) and (%.6f %.6f %.6f): x runs left to right over 2 tan(vfov/2) w/h, y top to "
                "bottom over 2 tan(vfov/2), at distance 1 along forward; the direction is unit",
                points[i][0],
                points[i][1],
                names[i],
                (double)r.o.x,
                (double)r.o.y,
                (double)r.o.z,
                (double)r.d.x,
                (double)r.d.y,
                (double)r.d.z,
                (double)want[0],
                (double)want[1],
                (double)want[2]);
            return;
        }
    }
    /* With a near plane, rays start on it (at depth `near` along forward). */
    desc.near = (real)0.5;
    cam = camera_make(&desc, w, h);
    ray r = camera_ray(&cam, 0, 0);
    double depth = (double)vec3_dot(vec3_sub(r.o, desc.origin), cam.forward);
    if (fabs(depth - 0.5) > TOL) {
        CHECK_FAIL(
            "camera_ray (near plane 0.5, the top-left corner): the ray starts at depth %g along forward, "
            "not on the near plane",
            depth);
    }
}

/* The sphere's roots in long double: t0 <= t1; false when the line misses. */
static bool
sphere_roots(const struct sphere *s, ray r, ld *t0, ld *t1)
{
    ld f[3] = {(ld)r.o.x - s->center.x, (ld)r.o.y - s->center.y, (ld)r.o.z - s->center.z};
    ld d[3] = {r.d.x, r.d.y, r.d.z};
    ld dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    ld b = (f[0] * d[0] + f[1] * d[1] + f[2] * d[2]) / dd;
    ld p[3] = {f[0] - b * d[0], f[1] - b * d[1], f[2] - b * d[2]};
    ld disc = ((ld)s->radius * s->radius - (p[0] * p[0] + p[1] * p[1] + p[2] * p[2])) / dd;
    if (disc < 0) {
        return false;
    }
    *t0 = -b - sqrtl(disc);
    *t1 = -b + sqrtl(disc);
    return true;
}

static void
check_sphere(const char *what, const struct sphere *s, ray r, real t_max, double tol)
{
    ld t0 = 0;
    ld t1 = 0;
    bool line_hits = sphere_roots(s, r, &t0, &t1);
    ld want = line_hits && t0 > 0 ? t0 : t1;
    bool expect = line_hits && want > 0 && want < t_max;
    real t = -1;
    bool got = intersect_sphere(s, r, t_max, &t);
    if (got != expect || (got && fabsl((ld)t - want) > tol)) {
        CHECK_FAIL(
            "intersect_sphere (%s: centre (%g %g %g), radius %g, ray from (%g %g %g), t_max %g): %s t = %.10g, "
            "expected %s t = %.10Lg: the nearest root of the quadratic in (0, t_max)",
            what,
            (double)s->center.x,
            (double)s->center.y,
            (double)s->center.z,
            (double)s->radius,
            (double)r.o.x,
            (double)r.o.y,
            (double)r.o.z,
            (double)t_max,
            got ? "a hit at" : "no hit,",
            (double)t,
            expect ? "a hit at" : "no hit; the line's root",
            want);
    }
}

TEST(intersect_sphere_finds_the_nearest_root_in_range)
{
    struct sphere s = {.center = {1, -2, 3}, .radius = 2};
    vec3 d = vec3_normalize((vec3){1, (real)0.2, (real)-0.1});
    ray outside = {vec3_sub(s.center, vec3_scale(d, 5)), d};
    check_sphere("from outside", &s, outside, REAL_MAX, TOL * 10);
    check_sphere("from outside, t_max before the sphere", &s, outside, 2, TOL * 10);
    check_sphere("from outside, t_max inside it", &s, outside, 4, TOL * 10);
    ray inside = {vec3_add(s.center, (vec3){(real)0.3, (real)-0.5, (real)0.2}), d};
    check_sphere("from inside", &s, inside, REAL_MAX, TOL * 10);
    ray behind = {vec3_add(s.center, vec3_scale(d, 5)), d};
    check_sphere("behind the ray", &s, behind, REAL_MAX, TOL * 10);
    struct rng rng = rng_make(1002, 2);
    for (int i = 0; i < 200 && !check_current.failed_checks; i++) {
        vec3 o = vec3_add(s.center, vec3_scale(stagecheck_random_vec3(&rng), 4));
        vec3 aim = vec3_add(s.center, vec3_scale(stagecheck_random_vec3(&rng), (real)2.5));
        ray r = {o, vec3_normalize(vec3_sub(aim, o))};
        check_sphere("a random ray", &s, r, (real)(8 * (double)rng_uniform(&rng)), TOL * 10);
    }
    /* A small sphere far away: the hit on the sphere to 1e-6 of its radius
     * (single precision: a nearer, larger one, 1e-3). */
    double far = SINGLE ? 100 : 1e4;
    struct sphere small = {
        .center = {(real)far, (real)(far / 3), 0},
        .radius = (real)(SINGLE ? 0.1 : 1e-3)};
    for (int i = 0; i < 50 && !check_current.failed_checks; i++) {
        vec3 aim = vec3_add(
            small.center,
            vec3_scale(stagecheck_random_vec3(&rng), small.radius * (real)0.9));
        ray r = {{0, 0, 0}, vec3_normalize(aim)};
        check_sphere(
            "a small sphere far away, where b^2 - c cancels",
            &small,
            r,
            REAL_MAX,
            (SINGLE ? 1e-3 : 1e-6) * (double)small.radius);
    }
}

/* The plane solution o + t d = p0 + u e1 + v e2 in long double (Cramer). */
static bool
solve_ld(vec3 p0, vec3 p1, vec3 p2, ray r, ld *t, ld *u, ld *v)
{
    ld e1[3] = {(ld)p1.x - p0.x, (ld)p1.y - p0.y, (ld)p1.z - p0.z};
    ld e2[3] = {(ld)p2.x - p0.x, (ld)p2.y - p0.y, (ld)p2.z - p0.z};
    ld d[3] = {r.d.x, r.d.y, r.d.z};
    ld s[3] = {(ld)r.o.x - p0.x, (ld)r.o.y - p0.y, (ld)r.o.z - p0.z};
    ld p[3];
    ld q[3];
    ld_cross(d, e2, p);
    ld det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (fabsl(det) < 1e-12L) {
        return false;
    }
    ld_cross(s, e1, q);
    *u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) / det;
    *v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / det;
    *t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
    return true;
}

TEST(intersect_triangle_and_quad_solve_the_plane_equation)
{
    struct rng rng = rng_make(1003, 3);
    int reported = 0;
    for (int i = 0; i < 4000 && reported == 0; i++) {
        vec3 p0 = stagecheck_random_vec3(&rng);
        vec3 p1 = vec3_add(p0, stagecheck_random_vec3(&rng));
        vec3 p2 = vec3_add(p0, stagecheck_random_vec3(&rng));
        vec3 o = vec3_scale(stagecheck_random_vec3(&rng), 4);
        vec3 aim =
            vec3_scale(stagecheck_random_vec3(&rng), (real)(0.8 * (double)rng_uniform(&rng)));
        ray r = {o, vec3_normalize(vec3_sub(aim, o))};
        real t_max = (real)(1 + 6 * (double)rng_uniform(&rng));
        ld tw;
        ld uw;
        ld vw;
        if (!solve_ld(p0, p1, p2, r, &tw, &uw, &vw)) {
            continue;
        }
        bool quad = i % 2;
        ld margin = 1e-6L;
        ld edges =
            quad ? fminl(fminl(uw, 1 - uw), fminl(vw, 1 - vw)) : fminl(fminl(uw, vw), 1 - uw - vw);
        if (fabsl(edges) < margin || fabsl(tw) < margin || fabsl(tw - t_max) < margin) {
            continue; /* on an edge or at a limit: either answer */
        }
        bool expect = edges > 0 && tw > 0 && tw < t_max;
        real t = 0;
        real u = 0;
        real v = 0;
        bool got;
        if (quad) {
            struct quad q = {.corner = p0, .edge1 = vec3_sub(p1, p0), .edge2 = vec3_sub(p2, p0)};
            got = intersect_quad(&q, r, t_max, &t, &u, &v);
        } else {
            got = intersect_triangle(p0, p1, p2, r, t_max, &t, &u, &v);
        }
        double scale = 1e3 * TOL;
        if (got != expect
            || (got
                && (fabsl(t - tw) > scale * (1 + fabsl(tw)) || fabsl(u - uw) > scale
                    || fabsl(v - vw) > scale))) {
            reported++;
            CHECK_FAIL(
                "%s (corner (%g %g %g), ray direction (%g %g %g), t_max %g, the ray %s): %s t %g, u %g, v %g; the "
                "plane equation o + t d = p0 + u e1 + v e2 gives t %.6Lg, u %.6Lg, v %.6Lg (Moller-Trumbore: "
                "Cramer's rule, both faces)",
                quad ? "intersect_quad" : "intersect_triangle",
                (double)p0.x,
                (double)p0.y,
                (double)p0.z,
                (double)r.d.x,
                (double)r.d.y,
                (double)r.d.z,
                (double)t_max,
                vec3_dot(r.d, vec3_cross(vec3_sub(p1, p0), vec3_sub(p2, p0))) < 0
                    ? "meets its front"
                    : "meets its back",
                got ? "a hit at" : "no hit;",
                (double)t,
                (double)u,
                (double)v,
                tw,
                uw,
                vw);
        }
    }
}

TEST(point_irradiance_is_intensity_cos_over_r_squared)
{
    struct rng rng = rng_make(1004, 4);
    for (int i = 0; i < 500; i++) {
        struct hit h = {0};
        h.p = vec3_scale(stagecheck_random_vec3(&rng), 3);
        h.n = stagecheck_random_vec3(&rng);
        h.ng = h.n;
        vec3 from = vec3_add(
            h.p,
            vec3_scale(stagecheck_random_vec3(&rng), (real)(0.2 + 5 * (double)rng_uniform(&rng))));
        vec3 intensity = {(real)2, (real)0.5, (real)7};
        ld l[3] = {(ld)from.x - h.p.x, (ld)from.y - h.p.y, (ld)from.z - h.p.z};
        ld r2 = l[0] * l[0] + l[1] * l[1] + l[2] * l[2];
        ld c = (l[0] * h.n.x + l[1] * h.n.y + l[2] * h.n.z) / sqrtl(r2);
        ld e = c > 0 ? c / r2 : 0;
        vec3 got = point_irradiance(&h, from, intensity);
        double tol = 1e3 * TOL * (double)e + 1e-300;
        bool ok = fabsl(got.x - 2 * e) <= 2 * tol && fabsl(got.y - e / 2) <= tol
                  && fabsl(got.z - 7 * e) <= 7 * tol;
        if (!ok) {
            CHECK_FAIL(
                "point_irradiance (intensity 2 0.5 7, light %.4Lg away, cos(theta) %.4Lg): (%g %g %g), expected "
                "I cos(theta) / r^2 = (%.6Lg %.6Lg %.6Lg)%s",
                sqrtl(r2),
                c,
                (double)got.x,
                (double)got.y,
                (double)got.z,
                2 * e,
                e / 2,
                7 * e,
                c <= 0 ? ": a light below the surface's horizon gives nothing" : "");
            return;
        }
    }
}

TEST_MAIN(
    TEST_ENTRY(camera_ray_follows_the_pinhole_model),
    TEST_ENTRY(intersect_sphere_finds_the_nearest_root_in_range),
    TEST_ENTRY(intersect_triangle_and_quad_solve_the_plane_equation),
    TEST_ENTRY(point_irradiance_is_intensity_cos_over_r_squared))
