/*
 * 07_triangle_lights.c - next-event estimation of emitting triangles (the
 * triangles of an emissive glTF mesh): each sampled like any area light,
 * by shadow rays to points uniform on it (light.h), white-box against the
 * stage's own functions and closed forms computed here.
 *
 *  - The estimator: the mean of direct_irradiance() with one shadow ray per
 *    light, at points below, beside and above the triangles, matches the
 *    sum of Lambert's polygon formula over the triangles that face the
 *    point (one-sided ones only from their front): t-tests, alpha = 0.01,
 *    Sidak-corrected.
 */
#include <stdlib.h>

#include "check.h"
#include "light.h"
#include "pathcheck.h"
#include "rng.h"
#include "stagecheck.h"
#include "stattest.h"
#include "testlib.h"

#define N_LIGHTS 3
#define N_POINTS 3
/* One t-test per point. */
#define N_STAT_TESTS (1.0 * N_POINTS)
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

/* The scene: the triangles as area lights, nothing else. */
struct fixture {
    struct scene s;
    struct area_light lights[N_LIGHTS];
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
    return true;
}

static double
level(void)
{
    return stattest_sidak(ALPHA, N_STAT_TESTS);
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
    for (int k = 0; k < N_POINTS; k++) {
        const double *x = points[k][0];
        const double *n = points[k][1];
        struct hit h = {.p = v3(x), .n = v3(n), .ng = v3(n), .light = -1};
        struct shadow_sampling sampling = {.samples = 1};
        struct rng rng = rng_make(pathcheck_seed(7103), (uint64_t)k);
        struct stattest_welford e = {0};
        for (int j = 0; j < 200000; j++) {
            vec3 sample = direct_irradiance(&w, &h, &sampling, &rng, &st);
            stattest_welford_add(&e, (double)sample.y);
        }
        double want = expected_irradiance(x, n, 1);
        struct stattest_result t = stattest_t_test_welford_one_sample(&e, want);
        printf(
            "point %d: E = %.6g +- %.2g, Lambert %.6g: p = %.3g\n",
            k,
            e.mean,
            sqrt(stattest_welford_var_of_mean(&e)),
            want,
            t.p);
        CHECK(want > 0.01);
        CHECK_MSG(t.p > level(), "point %d: %g against %g", k, e.mean, want);
    }
}

TEST_MAIN(TEST_ENTRY(estimate_matches_lambert_formula))
