/*
 * 04-06_lab_functions.c - lab 04's glass shading in the Whitted stages,
 * on its own (tests/lab/README.md, "Function tests"); the optics it uses
 * are 04_lab_functions.c's.  (Stage 07 samples glass instead:
 * 07_lab_functions.c tests sample_bsdf.)
 *
 *  - shade_glass: a thin sheet of glass (index 1.5) in the plane z = 0, a
 *    red light above it and a green one below, nothing else: a ray that
 *    meets the sheet sees the light its reflection reaches weighted by F
 *    and the one its refraction reaches weighted by 1 - F, F the textbook
 *    Fresnel reflectance, from the front (entering) and from the back
 *    (leaving), at several angles; past the critical angle only the
 *    reflection.
 *
 * Deterministic.  White-box: includes the stage's render.c for its static
 * shade_glass().
 */
#include "render.c"

#include <stdio.h>
#include <string.h>

#include "check.h"
#include "stagecheck.h"

#define TOL (sizeof(real) == sizeof(float) ? 1e-4 : 1e-9)

static bool
sheet_scene(struct scene *s)
{
    return stagecheck_load_text(
        "camera origin 0 0 5 target 0 0 0 up 0 1 0 fov 40\n"
        "image width 4 height 4\n"
        "material glass glass ior 1.5\n"
        "quad corner -1 -1 0 edge1 2 0 0 edge2 0 2 0 material glass\n"
        "area_light corner -100 -100 5 edge1 0 200 0 edge2 200 0 0 radiance 1 0 0\n"
        "area_light corner -100 -100 -5 edge1 200 0 0 edge2 0 200 0 radiance 0 1 0\n",
        s);
}

static void
check_sheet(const struct renderer *renderer, double theta_deg, bool from_front)
{
    double th = theta_deg * 3.14159265358979323846 / 180;
    real z = from_front ? 1 : -1;
    vec3 d = {(real)sin(th), 0, -z * (real)cos(th)};
    ray r = {vec3_sub((vec3){0, 0, 0}, vec3_scale(d, 2)), d};
    struct hit h;
    struct stats st = {0};
    struct rng rng = rng_make(1, 1);
    CHECK(world_intersect(&renderer->world, r, REAL_MAX, &h, &st) && h.prim == 0);
    const struct material *m = &renderer->scene->materials[h.material];
    vec3 got = shade_glass(renderer, m, r, &h, 1, &rng, &st);
    double f = stagecheck_fresnel(cos(th), from_front ? 1 / 1.5 : 1.5);
    /* Reflection goes back to the side the ray came from. */
    double red = from_front ? f : 1 - f;
    double green = from_front ? 1 - f : f;
    if (fabs((double)got.x - red) > 1e3 * TOL || fabs((double)got.y - green) > 1e3 * TOL
        || got.z != 0) {
        CHECK_FAIL(
            "shade_glass (a sheet of glass 1.5, %s at %.0f deg; a red light on the front's side, a green one "
            "on the back's): (%.5f %.5f %.5f), expected (%.5f %.5f 0): the reflected ray's light times F = %.5f, "
            "the refracted ray's times 1 - F%s",
            from_front ? "entering" : "leaving",
            theta_deg,
            (double)got.x,
            (double)got.y,
            (double)got.z,
            red,
            green,
            f,
            f >= 1 ? " (past the critical angle F = 1: no refracted ray)" : "");
    }
}

TEST(shade_glass_weights_reflection_by_f_and_refraction_by_1_minus_f)
{
    struct scene s;
    CHECK(sheet_scene(&s));
    if (check_current.failed_checks) {
        return;
    }
    struct renderer renderer = {.scene = &s, .max_depth = 3};
    renderer.world = world_make(&s);
    static const double angles[] = {0, 20, 45, 70, 85};
    for (int i = 0; i < 5; i++) {
        check_sheet(&renderer, angles[i], true);
        check_sheet(&renderer, angles[i] / 2.5, false);
    }
    check_sheet(&renderer, 50, false); /* total internal reflection */
    scene_free(&s);
}

TEST_MAIN(TEST_ENTRY(shade_glass_weights_reflection_by_f_and_refraction_by_1_minus_f))
