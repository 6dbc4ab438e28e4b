/*
 * test_light_picker.c - the emitting triangles as one light
 * (common/scene/light_picker.h): each triangle's share of the picks is its
 * weight over the total, a light sampled on its own is never picked, every
 * u in [0, 1] picks a triangle (1 too: a stratified pick may round up to
 * it), and weights that overflow stay finite shares.
 */
#include <float.h>
#include <math.h>

#include "check.h"
#include "light_picker.h"

/* A right triangle light of legs a (area a^2 / 2), or a rectangle a x a. */
static struct area_light
light(double a, bool triangle)
{
    return (struct area_light){
        .corner = vec3_make(0, 0, 0),
        .edge1 = vec3_make((real)a, 0, 0),
        .edge2 = vec3_make(0, (real)a, 0),
        .radiance = vec3_splat(1),
        .triangle = triangle,
    };
}

/* The scene's lights: a triangle of area 0.5, a rectangle, a triangle of
 * area 1.5, a rectangle. */
TEST(shares_follow_the_weights_and_skip_lights_on_their_own)
{
    struct area_light lights[4] =
        {light(1, true), light(2, false), light(sqrt(3.0), true), light(1, false)};
    struct scene s = {.area_lights = lights, .n_area_lights = 4};
    struct light_picker p;
    struct diag err = {0};
    CHECK(light_picker_build(&s, light_weight_area, &p, &err));
    CHECK(p.n_own == 2 && p.own[0] == 1 && p.own[1] == 3);
    CHECK(p.cdf != NULL);
    CHECK_NEAR(light_pick_probability(&s, &p, 0), 0.25, 1e-12);
    CHECK_NEAR(light_pick_probability(&s, &p, 2), 0.75, 1e-12);
    CHECK(light_pick_probability(&s, &p, 1) == 1 && light_pick_probability(&s, &p, 3) == 1);
    CHECK(light_pick(&p, 0) == 0);
    CHECK(light_pick(&p, 0.2499) == 0);
    CHECK(light_pick(&p, 0.2501) == 2);
    CHECK(light_pick(&p, nextafter(1.0, 0.0)) == 2);
    /* u = 1, as (k + v) / n can round to: the last triangle, not the
     * rectangle after it. */
    CHECK(light_pick(&p, 1.0) == 2);
    /* No picker: every light on its own, probability 1. */
    CHECK(light_pick_probability(&s, NULL, 0) == 1);
    light_picker_free(&p);
    CHECK(p.cdf == NULL && p.own == NULL);
}

TEST(no_emitting_triangle_means_nothing_to_pick)
{
    struct area_light lights[2] = {light(1, false), light(2, false)};
    struct scene s = {.area_lights = lights, .n_area_lights = 2};
    struct light_picker p;
    struct diag err = {0};
    CHECK(light_picker_build(&s, light_weight_area, &p, &err));
    CHECK(p.cdf == NULL && p.n_own == 2);
    CHECK(light_pick_probability(&s, &p, 0) == 1);
    light_picker_free(&p);
    struct scene empty = {0};
    CHECK(light_picker_build(&empty, light_weight_area, &p, &err));
    CHECK(p.cdf == NULL && p.n_own == 0);
    light_picker_free(&p);
}

/* A weight past the largest double (a vast bright triangle) counts as the
 * largest double: two of them share the picks evenly, a small one gets
 * none (0 after the division), and no share is NaN. */
static double
vast(const struct area_light *l)
{
    return l->edge1.x > 1 ? INFINITY : 1;
}

TEST(overflowing_weights_stay_finite_shares)
{
    struct area_light lights[3] = {light(2, true), light(1, true), light(2, true)};
    struct scene s = {.area_lights = lights, .n_area_lights = 3};
    struct light_picker p;
    struct diag err = {0};
    CHECK(light_picker_build(&s, vast, &p, &err));
    double a = light_pick_probability(&s, &p, 0);
    double b = light_pick_probability(&s, &p, 1);
    double c = light_pick_probability(&s, &p, 2);
    CHECK(isfinite(a) && isfinite(b) && isfinite(c));
    CHECK_NEAR(a, 0.5, 1e-12);
    CHECK_NEAR(c, 0.5, 1e-12);
    CHECK(b >= 0 && b < 1e-300);
    CHECK(light_pick(&p, 0.7) == 2);
    light_picker_free(&p);
}

TEST_MAIN(
    TEST_ENTRY(shares_follow_the_weights_and_skip_lights_on_their_own),
    TEST_ENTRY(no_emitting_triangle_means_nothing_to_pick),
    TEST_ENTRY(overflowing_weights_stay_finite_shares))
