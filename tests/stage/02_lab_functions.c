/*
 * 02_lab_functions.c - lab 02's functions, each on its own (tests/lab/
 * README.md, "Function tests").
 *
 *  - world_occluded: on a random soup of spheres, quads and triangles and
 *    random rays with random t_max, it says "blocked" exactly when the
 *    closest-hit query finds a hit with t < t_max (the two queries' answers
 *    are compared away from t_max, where rounding may differ).
 *  - spawn_ray: from hits on a sphere, a quad and a triangle, near the
 *    origin and 1e4 from it, a spawned ray keeps its direction, starts on
 *    the side of the surface d points to, within a few error bounds of the
 *    hit point (no large fixed epsilon), and never finds its own surface
 *    again.
 *  - visible: from a floor point to a point above it, false when a plate
 *    lies between them, true when the plate lies beyond the point or below
 *    the floor, true when the point lies on a surface, and one shadow ray
 *    each time.
 *
 * Deterministic (fixed seeds; no statistics).  White-box: world_make,
 * world_intersect, world_occluded, spawn_ray, visible and struct hit,
 * which every later stage keeps.
 */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "light.h"
#include "rng.h"
#include "stagecheck.h"

/* A scene of 12 spheres, 12 quads and 12 triangles in the cube [-1, 1]^3. */
static bool
random_soup(struct rng *rng, struct scene *s)
{
    static char text[8192];
    int n = snprintf(
        text,
        sizeof text,
        "camera origin 0 0 5 target 0 0 0 up 0 1 0 fov 40\nimage width 4 height 4\n"
        "material m diffuse albedo 0.5 0.5 0.5\n");
    for (int i = 0; i < 12 && n < (int)sizeof text - 600; i++) {
        double c[3];
        double e1[3];
        double e2[3];
        for (int k = 0; k < 3; k++) {
            c[k] = 2 * (double)rng_uniform(rng) - 1;
            e1[k] = 0.6 * (double)rng_uniform(rng) - 0.3;
            e2[k] = 0.6 * (double)rng_uniform(rng) - 0.3;
        }
        n += snprintf(
            text + n,
            sizeof text - (size_t)n,
            "sphere center %g %g %g radius %g material m\n"
            "quad corner %g %g %g edge1 %g %g %g edge2 %g %g %g material m\n"
            "triangle v0 %g %g %g v1 %g %g %g v2 %g %g %g material m\n",
            c[0],
            c[1],
            c[2],
            0.05 + 0.15 * (double)rng_uniform(rng),
            -c[1],
            c[2],
            c[0],
            e1[0],
            e1[1],
            e1[2],
            e2[0],
            e2[1],
            e2[2],
            c[2],
            -c[0],
            c[1],
            c[2] + e1[0],
            -c[0] + e1[1],
            c[1] + e1[2],
            c[2] + e2[0],
            -c[0] + e2[1],
            c[1] + e2[2]);
    }
    return stagecheck_load_text(text, s);
}

TEST(world_occluded_answers_as_the_closest_hit_does)
{
    struct rng rng = rng_make(2001, 1);
    int wrong = 0;
    int blocked = 0;
    int total = 0;
    for (int scene_no = 0; scene_no < 8; scene_no++) {
        struct scene s;
        CHECK(random_soup(&rng, &s));
        if (check_current.failed_checks) {
            return;
        }
        struct world w = world_make(&s);
        for (int i = 0; i < 500; i++) {
            vec3 o = vec3_scale(stagecheck_random_vec3(&rng), 3);
            vec3 target = vec3_scale(stagecheck_random_vec3(&rng), (real)0.5);
            ray r = {o, vec3_normalize(vec3_sub(target, o))};
            real t_max = (real)(6 * (double)rng_uniform(&rng));
            struct hit h;
            struct stats st = {0};
            bool closest = world_intersect(&w, r, REAL_MAX, &h, &st);
            if (closest && fabs((double)(h.t - t_max)) < 1e-6) {
                continue; /* at t_max the two may round differently */
            }
            bool expect = closest && h.t < t_max;
            bool got = world_occluded(&w, r, t_max, &st);
            total++;
            blocked += expect;
            if (got != expect && wrong++ == 0) {
                CHECK_FAIL(
                    "world_occluded (a soup of %d primitives, t_max %.4f): says %s, but the closest hit %s: "
                    "blocked means some primitive is hit with t in (0, t_max), and only then",
                    w.n_prims,
                    (double)t_max,
                    got ? "blocked" : "clear",
                    closest ? "is listed below" : "is none");
                if (closest) {
                    printf(
                        "    (the closest hit: primitive %d at t = %.6f)\n",
                        h.prim,
                        (double)h.t);
                }
            }
        }
        scene_free(&s);
    }
    printf("world_occluded: %d of %d rays answered wrongly (%d blocked)\n", wrong, total, blocked);
}

/* The error bound's scale: the hit's error, or 1e-300 where it is 0. */
static double
bound(const struct hit *h)
{
    return fmax((double)h->error, 1e-300);
}

static void
check_spawn(const char *shape, const char *statement, double offset)
{
    char text[512];
    snprintf(
        text,
        sizeof text,
        "camera origin 0 0 5 target 0 0 0 up 0 1 0 fov 40\nimage width 4 height 4\n"
        "material m diffuse albedo 0.5 0.5 0.5\n%s\n",
        statement);
    struct scene s;
    CHECK(stagecheck_load_text(text, &s));
    if (check_current.failed_checks) {
        return;
    }
    struct world w = world_make(&s);
    struct rng rng = rng_make(2002, 2);
    vec3 centre = {(real)offset, (real)offset, 0};
    int reported = 0;
    for (int i = 0; i < 2000 && reported == 0; i++) {
        vec3 o = vec3_add(centre, vec3_scale(stagecheck_random_vec3(&rng), 3));
        vec3 target = vec3_add(centre, vec3_scale(stagecheck_random_vec3(&rng), (real)0.3));
        ray r = {o, vec3_normalize(vec3_sub(target, o))};
        struct hit h;
        struct stats st = {0};
        if (!world_intersect(&w, r, REAL_MAX, &h, &st)) {
            continue;
        }
        /* Away from the surface it was hit from, and (flat shapes) through it. */
        for (int side = 0; side < 2; side++) {
            vec3 d = stagecheck_random_vec3(&rng);
            real toward = vec3_dot(d, h.ng);
            if ((side == 0) != (toward > 0)) {
                d = vec3_neg(d);
            }
            if (side == 1 && h.prim == 0 && s.n_spheres == 1) {
                continue; /* into a sphere it would hit the far side */
            }
            if (fabs((double)vec3_dot(d, h.ng)) < 1e-3) {
                continue;
            }
            ray sp = spawn_ray(&h, d);
            double moved = (double)vec3_length(vec3_sub(sp.o, h.p));
            double side_of =
                (double)vec3_dot(vec3_sub(sp.o, h.p), h.ng) * (double)vec3_dot(d, h.ng);
            struct hit again;
            bool self = world_intersect(&w, sp, REAL_MAX, &again, &st) && again.prim == h.prim;
            bool ok = vec3_length2(vec3_sub(sp.d, d)) == 0 && side_of > 0 && moved <= 8 * bound(&h)
                      && !self;
            if (!ok) {
                reported++;
                CHECK_FAIL(
                    "spawn_ray (%s%s, hit at (%g %g %g), error bound %.3g, d %s the surface): the origin moved "
                    "%.3g, %s the side d points to, direction %s, %s: push the origin off the surface by "
                    "(a small multiple of) the hit's error bound along the normal, to d's side",
                    shape,
                    offset != 0 ? " 1e4 from the origin" : "",
                    (double)h.p.x,
                    (double)h.p.y,
                    (double)h.p.z,
                    (double)h.error,
                    side == 0 ? "leaving" : "going through",
                    moved,
                    side_of > 0 ? "to" : "not to",
                    vec3_length2(vec3_sub(sp.d, d)) == 0 ? "kept" : "changed",
                    self ? "and the ray hits the same surface again"
                         : "it does not hit the surface again");
            }
        }
    }
    scene_free(&s);
}

TEST(spawn_ray_starts_just_off_the_surface_on_d_s_side)
{
    static const double offsets[] = {0, 1e4};
    for (int k = 0; k < 2; k++) {
        char statement[256];
        double c = offsets[k];
        snprintf(
            statement,
            sizeof statement,
            "sphere center %.17g %.17g 0 radius 1 material m",
            c,
            c);
        check_spawn("a sphere", statement, c);
        snprintf(
            statement,
            sizeof statement,
            "quad corner %.17g %.17g -1 edge1 2 0.3 0 edge2 0.2 2 2 material m",
            c - 1,
            c - 1);
        check_spawn("a quad", statement, c);
        snprintf(
            statement,
            sizeof statement,
            "triangle v0 %.17g %.17g -1 v1 %.17g %.17g 0.5 v2 %.17g %.17g 1 material m",
            c - 1,
            c - 1,
            c + 1.5,
            c - 0.8,
            c - 0.2,
            c + 1.4);
        check_spawn("a triangle", statement, c);
    }
}

/* From the floor point (0, 0, 0) to `to`, with or without a 2 x 2 plate
 * at height plate_y (none: NaN). */
static void
check_visible(double plate_y, vec3 to, bool expect, const char *what)
{
    char text[512];
    int n = snprintf(
        text,
        sizeof text,
        "camera origin 0 5 0.1 target 0 0 0 up 0 0 -1 fov 40\nimage width 4 height 4\n"
        "material m diffuse albedo 0.5 0.5 0.5\n"
        "quad corner -5 0 -5 edge1 0 0 10 edge2 10 0 0 material m\n");
    if (!isnan(plate_y)) {
        snprintf(
            text + n,
            sizeof text - (size_t)n,
            "quad corner -1 %.17g -1 edge1 2 0 0 edge2 0 0 2 material m\n",
            plate_y);
    }
    struct scene s;
    CHECK(stagecheck_load_text(text, &s));
    if (check_current.failed_checks) {
        return;
    }
    struct world w = world_make(&s);
    struct hit h;
    struct stats st = {0};
    /* The floor seen from above, under any plate: its normal faces up. */
    ray down = {{0, (real)0.5, 0}, {0, -1, 0}};
    CHECK(world_intersect(&w, down, REAL_MAX, &h, &st) && h.prim == 0);
    struct stats vs = {0};
    bool got = visible(&w, &h, to, &vs);
    if (got != expect || vs.rays_shadow != 1) {
        CHECK_FAIL(
            "visible (from the floor point (0 0 0) to (%g %g %g), %s): %s, expected %s, after %ld shadow "
            "ray(s) (one is enough: a ray from the surface towards `to`, blocked only by what lies in between)",
            (double)to.x,
            (double)to.y,
            (double)to.z,
            what,
            got ? "true" : "false",
            expect ? "true" : "false",
            (long)vs.rays_shadow);
    }
    scene_free(&s);
}

TEST(visible_is_blocked_only_by_what_lies_between)
{
    vec3 above = {0, 2, 0};
    check_visible(NAN, above, true, "nothing in the way");
    check_visible(1, above, false, "a plate at height 1 in between");
    check_visible(3, above, true, "a plate at height 3, beyond the point");
    check_visible(-1, above, true, "a plate under the floor");
    check_visible(1, (vec3){0, 1, 0}, true, "the point lies on a plate at height 1");
}

TEST_MAIN(
    TEST_ENTRY(world_occluded_answers_as_the_closest_hit_does),
    TEST_ENTRY(spawn_ray_starts_just_off_the_surface_on_d_s_side),
    TEST_ENTRY(visible_is_blocked_only_by_what_lies_between))
