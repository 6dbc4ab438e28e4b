/*
 * 07_triangle_lights.c - next-event estimation of emitting triangles (the
 * triangles of an emissive glTF mesh): a triangle picked by power, then a
 * point uniform on it (light.h), white-box against the stage's own
 * functions and closed forms computed here.
 *
 *  - Picking follows power: over many picks, the counts of three triangles
 *    of different areas and radiances (one two-sided) fit p_i = Phi_i / Phi,
 *    Phi_i = A_i lum(L_i) (x2 two-sided), by a chi-square test.
 *  - The densities: pdf_area is p_i / A_i exactly, and 1 / pdf_solid_angle
 *    (the area-to-solid-angle conversion r^2 / |cos theta'|) has as its
 *    expectation the total solid angle of the triangles seen from x (each
 *    y is drawn once, wherever it faces): a t-test against the sum of Van
 *    Oosterom and Strackee's closed form.
 *  - The estimator: the mean of direct_irradiance() with one shadow ray,
 *    at points below, beside and above the triangles, matches the sum
 *    of Lambert's polygon formula over the triangles that face the point
 *    (one-sided ones only from their front): t-tests, with the numbers
 *    from the random stream and from the Sobol sampler's sequences
 *    (shadow_sampling.lowdisc, each estimate scrambled by its own seed).
 * All t-tests and the chi-square test share alpha = 0.01, Sidak-corrected.
 */
#include <stdlib.h>

#include "check.h"
#include "light.h"
#include "rng.h"
#include "stagecheck.h"
#include "stattest.h"
#include "testlib.h"

#define N_LIGHTS 3
#define N_POINTS 3
/* The chi-square test, one t-test of the solid angle, one per point and
 * sampler. */
#define N_STAT_TESTS (1.0 + 1 + 2 * N_POINTS)
#define ALPHA 0.01

struct tri {
    double corner[3], edge1[3], edge2[3];
    double radiance[3];
    bool two_sided;
};

/* Three triangles in the plane y = 2, side by side (so none shades
 * another): a large dim one and a small bright one facing down, one-sided,
 * and a two-sided one. */
static const struct tri tris[N_LIGHTS] = {
    {{-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, {1, 1, 1}, false},
    {{0.5, 2, 0.2}, {0.3, 0, 0}, {0, 0, 0.2}, {20, 10, 5}, false},
    {{1.2, 2, -0.9}, {0, 0, 0.5}, {0.6, 0, 0}, {2, 3, 4}, true},
};

static double
luminance(const double l[3])
{
    return 0.2126 * l[0] + 0.7152 * l[1] + 0.0722 * l[2];
}

static double
tri_area(const struct tri *t)
{
    double c[3];
    stagecheck_cross3(t->edge1, t->edge2, c);
    return sqrt(stagecheck_dot3(c, c)) / 2;
}

static void
tri_corners(const struct tri *t, double out[3][3])
{
    for (int j = 0; j < 3; j++) {
        out[0][j] = t->corner[j];
        out[1][j] = t->corner[j] + t->edge1[j];
        out[2][j] = t->corner[j] + t->edge2[j];
    }
}

static vec3
v3(const double a[3])
{
    return vec3_make((real)a[0], (real)a[1], (real)a[2]);
}

/* The scene (the triangles as area lights, nothing else) and its picker. */
struct fixture {
    struct scene s;
    struct area_light lights[N_LIGHTS];
    struct light_picker lp;
};

static bool
fixture_make(struct fixture *f)
{
    f->s = (struct scene){0};
    for (int i = 0; i < N_LIGHTS; i++) {
        f->lights[i] = (struct area_light){
            .corner = v3(tris[i].corner),
            .edge1 = v3(tris[i].edge1),
            .edge2 = v3(tris[i].edge2),
            .radiance = v3(tris[i].radiance),
            .triangle = true,
            .two_sided = tris[i].two_sided,
        };
    }
    f->s.area_lights = f->lights;
    f->s.n_area_lights = N_LIGHTS;
    struct diag err;
    return light_picker_build(&f->lp, &f->s, &err);
}

static double
expected_probability(int i)
{
    double total = 0;
    double mine = 0;
    for (int k = 0; k < N_LIGHTS; k++) {
        double p = tri_area(&tris[k]) * luminance(tris[k].radiance) * (tris[k].two_sided ? 2 : 1);
        total += p;
        mine = k == i ? p : mine;
    }
    return mine / total;
}

static double
level(void)
{
    return stattest_sidak(ALPHA, N_STAT_TESTS);
}

TEST(picking_follows_power)
{
    struct fixture f;
    CHECK(fixture_make(&f));
    CHECK(f.lp.n == N_LIGHTS);
    struct rng rng = rng_make(7101, 0);
    long counts[N_LIGHTS] = {0};
    long n = 200000;
    for (long k = 0; k < n; k++) {
        vec3 y;
        real pdf;
        real u0 = rng_uniform(&rng);
        int i =
            light_picker_sample(&f.lp, &f.s, u0, rng_uniform(&rng), rng_uniform(&rng), &y, &pdf);
        CHECK(i >= 0 && i < N_LIGHTS);
        if (i >= 0 && i < N_LIGHTS) {
            counts[i]++;
            /* The density per unit area is p_i / A_i. */
            double want = expected_probability(i) / tri_area(&tris[i]);
            CHECK_NEAR(pdf, want, 1e-5 * want);
        }
    }
    double chi2 = 0;
    for (int i = 0; i < N_LIGHTS; i++) {
        double expect = (double)n * expected_probability(i);
        chi2 += (counts[i] - expect) * (counts[i] - expect) / expect;
        printf("triangle %d: %ld picks, expected %.0f\n", i, counts[i], expect);
    }
    double p = stattest_chi2_pvalue(chi2, N_LIGHTS - 1);
    printf("chi-square %.3g, p = %.3g\n", chi2, p);
    CHECK_MSG(p > level(), "picks do not follow power: p = %g", p);
    /* No triangle: nothing to pick. */
    struct scene empty = {0};
    struct light_picker none;
    struct diag err;
    CHECK(light_picker_build(&none, &empty, &err));
    vec3 y;
    real pdf;
    CHECK(light_picker_sample(&none, &empty, 0.5, 0.5, 0.5, &y, &pdf) == -1);
    light_picker_free(&none);
    light_picker_free(&f.lp);
}

TEST(solid_angle_density_integrates_to_the_solid_angle)
{
    struct fixture f;
    CHECK(fixture_make(&f));
    static const double x[3] = {0.1, 0, 0.05};
    double omega = 0;
    for (int i = 0; i < N_LIGHTS; i++) {
        double c[3][3];
        tri_corners(&tris[i], c);
        omega += stagecheck_triangle_solid_angle(c, x);
    }
    struct rng rng = rng_make(7102, 0);
    struct stattest_welford w = {0};
    for (int k = 0; k < 400000; k++) {
        vec3 y;
        real pdf_area;
        real u0 = rng_uniform(&rng);
        int i = light_picker_sample(
            &f.lp,
            &f.s,
            u0,
            rng_uniform(&rng),
            rng_uniform(&rng),
            &y,
            &pdf_area);
        real pdf = light_picker_pdf_solid_angle(&f.lp, &f.s, i, v3(x), y);
        stattest_welford_add(&w, pdf > 0 ? 1 / (double)pdf : 0);
    }
    struct stattest_result t = stattest_t_test_welford_one_sample(&w, omega);
    printf(
        "E[1/pdf] = %.6g +- %.2g, solid angle %.6g sr: p = %.3g\n",
        w.mean,
        sqrt(stattest_welford_var_of_mean(&w)),
        omega,
        t.p);
    CHECK_MSG(t.p > level(), "E[1/pdf] %g differs from the solid angle %g", w.mean, omega);
    light_picker_free(&f.lp);
}

/* The irradiance at x (normal n) from the triangles facing it. */
static double
expected_irradiance(const double x[3], const double n[3], int channel)
{
    double e = 0;
    for (int i = 0; i < N_LIGHTS; i++) {
        double c[3][3];
        tri_corners(&tris[i], c);
        double normal[3];
        stagecheck_cross3(tris[i].edge1, tris[i].edge2, normal);
        double to_x[3] = {x[0] - c[0][0], x[1] - c[0][1], x[2] - c[0][2]};
        if (tris[i].two_sided || stagecheck_dot3(normal, to_x) > 0) {
            e += stagecheck_polygon_irradiance(c, 3, x, n, tris[i].radiance[channel]);
        }
    }
    return e;
}

/* Points whose horizon every triangle lies above (Lambert's formula needs
 * no clipping): under the lights, off to the side, and above them (where
 * only the two-sided one shines). */
TEST(estimate_matches_lambert_formula)
{
    static const double points[N_POINTS][2][3] = {
        {{0, 0, 0}, {0, 1, 0}},
        {{1.5, 0.5, 0.5}, {0, 1, 0}},
        {{0.5, 3, 0}, {0, -1, 0}},
    };
    struct fixture f;
    CHECK(fixture_make(&f));
    struct world w = world_make(&f.s);
    struct stats st = {0};
    for (int k = 0; k < 2 * N_POINTS; k++) {
        const double *x = points[k % N_POINTS][0];
        const double *n = points[k % N_POINTS][1];
        struct hit h = {.p = v3(x), .n = v3(n), .ng = v3(n), .light = -1};
        struct shadow_sampling sampling = {.samples = 1, .lowdisc = k >= N_POINTS};
        struct rng rng = rng_make(7103, (uint64_t)k);
        struct stattest_welford e = {0};
        for (int j = 0; j < 200000; j++) {
            /* Sobol: point j of a sequence scrambled anew each time, so
             * that the estimates are independent, as the t-test needs. */
            sampling.lowdisc_seed = rng_mix64(rng_next_u32(&rng));
            sampling.lowdisc_index = (uint32_t)j;
            vec3 sample = direct_irradiance(&w, &h, &sampling, &f.lp, &rng, &st);
            stattest_welford_add(&e, (double)sample.y);
        }
        double want = expected_irradiance(x, n, 1);
        struct stattest_result t = stattest_t_test_welford_one_sample(&e, want);
        printf(
            "point %d, %s: E = %.6g +- %.2g, Lambert %.6g: p = %.3g\n",
            k % N_POINTS,
            sampling.lowdisc ? "sobol" : "independent",
            e.mean,
            sqrt(stattest_welford_var_of_mean(&e)),
            want,
            t.p);
        CHECK(want > 0.01);
        CHECK_MSG(t.p > level(), "point %d: %g against %g", k % N_POINTS, e.mean, want);
    }
    light_picker_free(&f.lp);
}

TEST_MAIN(
    TEST_ENTRY(picking_follows_power),
    TEST_ENTRY(solid_angle_density_integrates_to_the_solid_angle),
    TEST_ENTRY(estimate_matches_lambert_formula))
