/*
 * 03_lab_functions.c - lab 03's functions, each on its own (tests/lab/
 * README.md, "Function tests").
 *
 *  - sample_area_light: every point lies on the light, and the points are
 *    uniform over its area: the coordinates (s, t) of each point along the
 *    light's edges, p = corner + s edge1 + t edge2, pass a chi-square test
 *    of 16 x 16 cells against the uniform density, for a skewed
 *    parallelogram ((s, t) uniform on [0,1)^2) and a triangle (((s + t)^2,
 *    t / (s + t)) uniform on [0,1)^2), from 100,000 points each
 *    (warptest.h).
 *  - light_irradiance, through direct_irradiance (its only caller): at a
 *    point under a rectangular light of radiance L, the estimate's mean over
 *    4,000 draws matches Lambert's closed form for polygons (computed
 *    here, stagecheck.h) with one shadow ray and with a stratified 4 x 4
 *    set; so it does with a black plate just under the light hiding half
 *    of it (the closed form of the other half); the adaptive scheme
 *    returns the closed form exactly where its probes all see the light
 *    and exactly 0 where a plate hides the whole light, and with half the
 *    light hidden (a penumbra) its mean is the closed form too.
 *
 * The two chi-square tests and the four means share alpha 0.01 (Sidak);
 * seeds from pathcheck_seed().  White-box: sample_area_light(),
 * direct_irradiance(), world_intersect() and struct area_light, which every
 * later stage keeps.
 */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "light.h"
#include "pathcheck.h"
#include "stagecheck.h"
#include "stattest.h"
#include "warptest.h"

#define N_STAT_TESTS 7
#define POINTS 100000
#define DRAWS 4000

static double
level(void)
{
    return stattest_sidak(PATHCHECK_ALPHA, N_STAT_TESTS);
}

/* (s, t) with p = corner + s edge1 + t edge2, and p's distance from the
 * light's plane. */
static void
light_coordinates(const struct area_light *light, vec3 p, double *s, double *t, double *off_plane)
{
    vec3 q = vec3_sub(p, light->corner);
    double a = (double)vec3_dot(light->edge1, light->edge1);
    double b = (double)vec3_dot(light->edge1, light->edge2);
    double c = (double)vec3_dot(light->edge2, light->edge2);
    double d = (double)vec3_dot(q, light->edge1);
    double e = (double)vec3_dot(q, light->edge2);
    double det = a * c - b * b;
    *s = (c * d - b * e) / det;
    *t = (a * e - b * d) / det;
    vec3 n = vec3_normalize(vec3_cross(light->edge1, light->edge2));
    *off_plane = fabs((double)vec3_dot(q, n));
}

static void
check_uniform(const struct area_light *light, const char *shape, uint64_t seed)
{
    struct warptest w;
    CHECK(warptest_square(&w, 16, 16));
    struct rng rng = rng_make(pathcheck_seed(seed), 1);
    int reported = 0;
    for (int i = 0; i < POINTS; i++) {
        real u = rng_uniform(&rng);
        real v = rng_uniform(&rng);
        vec3 p = sample_area_light(light, u, v);
        double s;
        double t;
        double off;
        light_coordinates(light, p, &s, &t, &off);
        bool inside = off < 1e-4 && s > -1e-6 && t > -1e-6
                      && (light->triangle ? s + t < 1 + 1e-6 : s < 1 + 1e-6 && t < 1 + 1e-6);
        if (!inside && reported++ == 0) {
            CHECK_FAIL(
                "sample_area_light (%s): (u, v) = (%.4f, %.4f) gives (%g %g %g), which is not on the light "
                "(along its edges s %.4f, t %.4f; %.2g off its plane)",
                shape,
                (double)u,
                (double)v,
                (double)p.x,
                (double)p.y,
                (double)p.z,
                s,
                t,
                off);
        }
        /* A triangle's (s, t) is uniform on s + t < 1 exactly when
         * ((s + t)^2, t / (s + t)) is uniform on the square (P(s + t < x) =
         * x^2; along a line of constant s + t, t is uniform), whose cells
         * are whole: no cell straddles the triangle's edge. */
        double a = light->triangle ? (s + t) * (s + t) : s;
        double b = light->triangle ? (s + t > 0 ? t / (s + t) : 0) : t;
        /* Points on the far edge (1 in rounding) count in the last cells. */
        warptest_add(&w, fmin(fmax(a, 0), 0.999999), fmin(fmax(b, 0), 0.999999), 0);
    }
    struct warptest_result fit = warptest_fit(&w, NULL, NULL);
    char why[300];
    warptest_describe(&w, &fit, why, sizeof why);
    printf("sample_area_light (%s): %s\n", shape, why);
    if (fit.p < level()) {
        CHECK_FAIL(
            "sample_area_light (%s): the points are not uniform over the light's area (p %.2g < %.3g); "
            "in the light's own coordinates (s, t) along its edges (a triangle's as ((s + t)^2, t / (s + t))): %s",
            shape,
            fit.p,
            level(),
            why);
    }
    warptest_free(&w);
}

TEST(sample_area_light_is_uniform_over_the_light)
{
    struct area_light quad = {
        .corner = {1, 2, 3},
        .edge1 = {2, 0, (real)0.5},
        .edge2 = {(real)0.7, (real)0.3, 1},
        .radiance = {1, 1, 1},
    };
    check_uniform(&quad, "parallelogram", 3001);
    struct area_light tri = quad;
    tri.triangle = true;
    check_uniform(&tri, "triangle", 3002);
}

/* A floor (y = 0) under a 0.8 x 0.6 light of radiance 1 at height 1 (an
 * area other than 1, so that a sample that forgets it is wrong), with a
 * black plate 1e-3 under the light hiding x < plate_x of it (none when
 * plate_x is below the light's -0.4). */
struct room {
    struct scene scene;
    struct world world;
    struct hit h; /* the floor point (0.2, 0, 0.1), seen from above */
};

static bool
room_make(struct room *r, double plate_x)
{
    char text[1024];
    int n = snprintf(
        text,
        sizeof text,
        "camera origin 0 5 0.1 target 0 0 0 up 0 0 -1 fov 40\n"
        "image width 4 height 4\n"
        "material white diffuse albedo 0.5 0.5 0.5\n"
        "material black diffuse albedo 0 0 0\n"
        "quad corner -5 0 -5 edge1 0 0 10 edge2 10 0 0 material white\n"
        "area_light corner -0.4 1 -0.3 edge1 0.8 0 0 edge2 0 0 0.6 radiance 1 1 1\n");
    if (plate_x > -0.4) {
        snprintf(
            text + n,
            sizeof text - (size_t)n,
            "quad corner -2 0.999 -2 edge1 %.17g 0 0 edge2 0 0 4 material black\n",
            plate_x + 2);
    }
    memset(r, 0, sizeof *r);
    if (!stagecheck_load_text(text, &r->scene)) {
        return false;
    }
    r->world = world_make(&r->scene);
    ray down = {{(real)0.2, (real)0.5, (real)0.1}, {0, -1, 0}};
    struct stats st = {0};
    return world_intersect(&r->world, down, REAL_MAX, &r->h, &st) && r->h.prim == 0;
}

/* The closed form at the room's floor point from the part x >= x0 of the
 * light. */
static double
closed_form(double x0)
{
    double corners[4][3] = {{x0, 1, -0.3}, {0.4, 1, -0.3}, {0.4, 1, 0.3}, {x0, 1, 0.3}};
    double x[3] = {0.2, 0, 0.1};
    double n[3] = {0, 1, 0};
    return stagecheck_polygon_irradiance(corners, 4, x, n, 1);
}

/* Mean and spread of DRAWS estimates of direct_irradiance at the room's
 * floor point (its green channel). */
static struct stattest_welford
estimates(const struct room *r, struct shadow_sampling sampling, uint64_t seed)
{
    struct stattest_welford w = {0};
    struct rng rng = rng_make(pathcheck_seed(seed), 2);
    for (int i = 0; i < DRAWS; i++) {
        struct stats st = {0};
        vec3 e = direct_irradiance(&r->world, &r->h, &sampling, &rng, &st);
        stattest_welford_add(&w, (double)e.y);
    }
    return w;
}

static void
check_mean(const struct room *r, int samples, int adaptive, double plate_x, uint64_t seed)
{
    struct shadow_sampling sampling = {
        .samples = samples,
        .adaptive = {adaptive ? 4 : 0, adaptive}};
    struct stattest_welford w = estimates(r, sampling, seed);
    double expected = closed_form(plate_x > -0.4 ? plate_x : -0.4);
    /* The plate's 1e-3 below the light moves its shadow's edge by
     * < 1e-3 of the light: a slack of 0.3% of the expected value. */
    double se = sqrt(stattest_welford_var_of_mean(&w));
    double slack = plate_x > -0.4 ? 3e-3 * expected : 0;
    double z = fmax(fabs(w.mean - expected) - slack, 0) / (se > 0 ? se : 1e-300);
    double p = w.m2 > 0 ? stattest_normal_pvalue(z)
                        : (fabs(w.mean - expected) > 1e-6 * expected + slack ? 0 : 1);
    printf(
        "light_irradiance (%s%d shadow ray(s)%s): mean %.6f +- %.6f, closed form %.6f\n",
        adaptive ? "adaptive 4 probes + " : "",
        adaptive ? adaptive : samples,
        plate_x > -0.4 ? ", half the light hidden" : "",
        w.mean,
        se,
        expected);
    if (p < level()) {
        CHECK_FAIL(
            "light_irradiance (%s%d shadow ray(s) a light%s): the estimates' mean over %d draws is %.5f "
            "+- %.5f, where the irradiance is %.5f (p %.2g): one sample is L cos(theta) cos(theta') / r^2 "
            "times the light's area (1 / pdf), blocked samples count 0, and the light's value is the "
            "mean of its samples (in a penumbra: the probes' and the others')",
            adaptive ? "adaptive 4 probes + " : "",
            adaptive ? adaptive : samples,
            plate_x > -0.4 ? ", half of it hidden" : "",
            DRAWS,
            w.mean,
            se,
            expected,
            p);
    }
}

TEST(light_irradiance_is_unbiased_with_one_or_many_shadow_rays)
{
    struct room open;
    struct room half;
    CHECK(room_make(&open, -1) && room_make(&half, 0));
    if (check_current.failed_checks) {
        return;
    }
    check_mean(&open, 1, 0, -1, 3003);
    check_mean(&open, 16, 0, -1, 3004);
    check_mean(&half, 1, 0, 0, 3005);
    check_mean(&half, 16, 0, 0, 3006);
    scene_free(&open.scene);
    scene_free(&half.scene);
}

TEST(light_irradiance_adaptive_is_exact_in_light_and_umbra_unbiased_in_penumbra)
{
    struct room open;
    struct room hidden;
    CHECK(room_make(&open, -1) && room_make(&hidden, 0.6));
    if (check_current.failed_checks) {
        return;
    }
    struct shadow_sampling sampling = {.samples = 1, .adaptive = {4, 16}};
    struct rng rng = rng_make(3007, 3);
    double expected = closed_form(-0.4);
    for (int i = 0; i < 20; i++) {
        struct stats st = {0};
        vec3 e = direct_irradiance(&open.world, &open.h, &sampling, &rng, &st);
        if (fabs((double)e.y - expected) > 1e-6 * expected || st.extra[STAT_PENUMBRA] != 0) {
            CHECK_FAIL(
                "light_irradiance (adaptive 4,16, the whole light in view): %.6f, where the probes all "
                "reach the light and the closed form (unoccluded_irradiance) is %.6f%s",
                (double)e.y,
                expected,
                st.extra[STAT_PENUMBRA] ? "; the point was counted as penumbra" : "");
            break;
        }
        e = direct_irradiance(&hidden.world, &hidden.h, &sampling, &rng, &st);
        if (e.y != 0) {
            CHECK_FAIL(
                "light_irradiance (adaptive 4,16, the whole light hidden): %g, where every probe is "
                "blocked: 0 (umbra)",
                (double)e.y);
            break;
        }
    }
    /* Half the light hidden: the probes always disagree (two of the 2 x 2
     * cells are hidden whole), so the penumbra's estimate is unbiased. */
    struct room half;
    CHECK(room_make(&half, 0));
    check_mean(&half, 1, 16, 0, 3008);
    scene_free(&half.scene);
    scene_free(&open.scene);
    scene_free(&hidden.scene);
}

TEST_MAIN(
    TEST_ENTRY(sample_area_light_is_uniform_over_the_light),
    TEST_ENTRY(light_irradiance_is_unbiased_with_one_or_many_shadow_rays),
    TEST_ENTRY(light_irradiance_adaptive_is_exact_in_light_and_umbra_unbiased_in_penumbra))
