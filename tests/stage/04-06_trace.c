/*
 * 04-06_trace.c - what a traced pixel says about mirrors and glass
 * (docs/inspect.md), stages 04 to 06 (07 samples one lobe: 07_trace.c).
 * A sphere of radius 1 five units in front of the camera, against a grey
 * background:
 *   - of glass (ior 1.5), the middle pixel meets it head on: the first
 *     Fresnel term is ((n - 1) / (n + 1))^2 = 0.04, and both the reflected
 *     and the refracted ray follow; a pixel near the rim meets it at about
 *     69 degrees: the Fresnel term is larger (0.2);
 *   - of ior 0.6 (a bubble), the same rim pixel is past the critical angle
 *     asin(0.6) = 37 degrees: total internal reflection, Fresnel term 1,
 *     no refracted ray;
 *   - a mirror sphere's first event is a mirror reflection weighted by its
 *     reflectance.
 * One camera ray through the pixel's centre in every stage.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "stagecheck.h"
#include "testlib.h"
#include "tracecheck.h"

#define MIDDLE 15
#define RIM 26

static const char *
sphere_scene(const char *name, const char *material)
{
    return stagecheck_scene(
        name,
        "camera origin 0 0 5 target 0 0 0 up 0 1 0 fov 30\n"
        "image width 31 height 31\n"
        "background color 0.5 0.5 0.5\n"
        "material m %s\n"
        "sphere center 0 0 0 radius 1 material m\n",
        material);
}

/* One camera ray through the pixel's centre (stage 06 samples). */
static const char *const *
centre_ray(void)
{
    static const char *const args[] = {"-s", "1", "--aa", "grid", NULL};
    const char *stage = getenv("STAGE");
    return stage && strcmp(stage, "06") >= 0 ? args : NULL;
}

/* The first Fresnel term of pixel (x, MIDDLE)'s trace. */
static double
first_fresnel(const char *scene, int x, const char **trace)
{
    *trace = tracecheck_pixel(scene, x, MIDDLE, centre_ray());
    double f[1] = {-1};
    CHECK(*trace && tracecheck_numbers(*trace, "\"fresnel\": ", f, 1) >= 1);
    return f[0];
}

TEST(glass_fresnel_head_on_and_at_the_rim)
{
    const char *scene = sphere_scene("glass.scene", "glass ior 1.5");
    const char *trace;
    double head_on = first_fresnel(scene, MIDDLE, &trace);
    CHECK_NEAR(head_on, 0.04, 1e-5);
    CHECK(trace && tracecheck_count(trace, "\"event\": \"reflect\"") >= 1);
    CHECK(trace && tracecheck_count(trace, "\"event\": \"refract\"") >= 1);
    double rim = first_fresnel(scene, RIM, &trace);
    CHECK_MSG(rim > 0.1 && rim < 0.5, "Fresnel term at the rim: %g", rim);
}

TEST(bubble_rim_is_total_internal_reflection)
{
    const char *scene = sphere_scene("bubble.scene", "glass ior 0.6");
    const char *trace;
    double rim = first_fresnel(scene, RIM, &trace);
    CHECK_NEAR(rim, 1.0, 0.0);
    CHECK(trace && tracecheck_count(trace, "\"event\": \"total internal reflection\"") >= 1);
    double weight[3];
    CHECK(trace && tracecheck_numbers(trace, "\"weight\": [", weight, 1) >= 1);
    CHECK_NEAR(weight[0], 1.0, 0.0);
}

TEST(mirror_is_weighted_by_its_reflectance)
{
    const char *scene = sphere_scene("mirror.scene", "mirror reflectance 0.9 0.6 0.3");
    const char *trace = tracecheck_pixel(scene, MIDDLE, MIDDLE, centre_ray());
    CHECK(trace && tracecheck_count(trace, "\"event\": \"mirror\"") == 1);
    double weight[1];
    CHECK(trace && tracecheck_numbers(trace, "\"weight\": [", weight, 1) == 1);
    CHECK_NEAR(weight[0], 0.9, 1e-6);
    CHECK(trace && tracecheck_count(trace, "\"fresnel\": null") == 1);
}

TEST_MAIN(
    TEST_ENTRY(glass_fresnel_head_on_and_at_the_rim),
    TEST_ENTRY(bubble_rim_is_total_internal_reflection),
    TEST_ENTRY(mirror_is_weighted_by_its_reflectance))
