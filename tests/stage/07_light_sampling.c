/*
 * 07_light_sampling.c - how stage 07 samples its lights: rectangles by
 * solid angle (Urena, Fajardo and King 2013) and the multiple importance
 * sampling of shadow rays and bounces (Veach and Guibas 1995), white-box
 * against the stage's own functions (light.h, bsdf.h) and closed forms
 * computed here, then black-box on a scene where both matter.
 *
 *  - The power heuristic: the weights of one point under two techniques
 *    sum to 1 (to rounding, for densities from 1e-300 to 1e300), a
 *    technique that cannot draw a point gets all of it, and the value is
 *    (n_f p_f)^2 / ((n_f p_f)^2 + (n_g p_g)^2).
 *  - Solid-angle sampling of a rectangle, seen from points under it, close
 *    to a corner, beside its plane and behind it: the density 1 / Omega
 *    matches the rectangle's solid angle (two triangles by Van Oosterom
 *    and Strackee's formula), so it integrates to 1 over that solid angle;
 *    every sample lands on the rectangle; the samples fall into the cells
 *    of a 4 x 4 grid over it in proportion to the cells' solid angles
 *    (chi-square), i.e. uniformly in solid angle.
 *  - Degenerate and grazing configurations (a point in the light's plane,
 *    on an edge's line, a hair from a corner, very far, a needle-thin
 *    light, u and v at 0 and next to 1; a parallelogram, a triangle) give
 *    no NaN: either a finite sample on the light with a finite density, or
 *    the refusal that makes the caller sample by area.
 *  - MIS adds up: at points under a large rectangle light (sampled by
 *    area, by solid angle, and by the auto mode's choice) and under a
 *    sphere light, the mean of the MIS-weighted shadow ray plus the
 *    MIS-weighted cosine-distributed bounce that hits the light equals the
 *    irradiance in closed form
 *    (Lambert's polygon formula; pi L sin^2(theta_max) for the sphere):
 *    t-tests.  Weights that did not sum to 1 over the two techniques would
 *    make it too bright or too dark.
 *  - Black-box: on a box lit by a large one-sided ceiling light, with a
 *    diffuse-and-mirror (blend) sphere, --mis off, --light-sampling
 *    solid-angle, both together, and --light-sampling auto converge to the
 *    default's image (block t-tests, as in 07_estimators), with no NaN
 *    pixel.
 * All statistical tests share alpha = 0.01, Sidak-corrected per group.
 */
#include <stdlib.h>

#include "bsdf.h"
#include "check.h"
#include "light.h"
#include "pathcheck.h"
#include "rng.h"
#include "stagecheck.h"
#include "stattest.h"
#include "testlib.h"

#define ALPHA 0.01

/* Tolerance of quantities computed in `real` against closed forms in
 * double: a float build keeps about 6 digits, less after the 2 pi
 * cancellation of the solid angle. */
#ifdef REAL_IS_FLOAT
#define REL_TOL 2e-3
#else
#define REL_TOL 1e-9
#endif

static double
level(double n_tests)
{
    return stattest_sidak(ALPHA, n_tests);
}

TEST(power_heuristic_weights_sum_to_one)
{
    CHECK_NEAR(mis_power_heuristic(1, 2, 1, 3), 4.0 / 13, 1e-6);
    CHECK_NEAR(mis_power_heuristic(2, 1, 1, 3), 4.0 / 13, 1e-6);
    CHECK(mis_power_heuristic(1, 5, 1, 0) == 1);
    CHECK(mis_power_heuristic(1, 0, 1, 5) == 0);
    CHECK(mis_power_heuristic(1, 0, 1, 0) == 0);
    struct rng rng = rng_make(7401, 0);
    double worst = 0;
    for (int k = 0; k < 100000; k++) {
        /* Densities spread over many orders of magnitude. */
        double range = k % 2 ? 600 : 60;
        real pf = (real)pow(10, (rng_uniform(&rng) - 0.5) * range);
        real pg = (real)pow(10, (rng_uniform(&rng) - 0.5) * range);
        real nf = (real)(1 + (int)(rng_uniform(&rng) * 16));
        real ng = (real)(1 + (int)(rng_uniform(&rng) * 16));
        if (!(pf > 0 && pg > 0 && isfinite(pf) && isfinite(pg))) {
            continue; /* out of a float build's range */
        }
        real a = mis_power_heuristic(nf, pf, ng, pg);
        real b = mis_power_heuristic(ng, pg, nf, pf);
        CHECK(a >= 0 && a <= 1 && b >= 0 && b <= 1);
        worst = fmax(worst, fabs((double)a + (double)b - 1));
    }
    printf("power heuristic: |w_f + w_g - 1| at most %.3g over 1e5 random pairs\n", worst);
    CHECK_MSG(worst < 8 * REAL_EPSILON, "weights sum to 1 + %g", worst);
}

/* --- solid-angle sampling of a rectangle ----------------------------------- */

/* A 2 x 1.5 rectangle light in the plane y = 2, facing down. */
static struct area_light
rect_light(void)
{
    return (struct area_light){
        .corner = {-1, 2, -0.75},
        .edge1 = {2, 0, 0},
        .edge2 = {0, 0, 1.5},
        .radiance = {3, 3, 3},
    };
}

static void
to_double(vec3 v, double out[3])
{
    out[0] = (double)v.x;
    out[1] = (double)v.y;
    out[2] = (double)v.z;
}

/* The solid angle at x of the part [s0, s1] x [t0, t1] (edge fractions) of
 * the light: two triangles. */
static double
part_solid_angle(const struct area_light *l, double s0, double s1, double t0, double t1, vec3 x)
{
    double c[4][3];
    double st[4][2] = {{s0, t0}, {s1, t0}, {s1, t1}, {s0, t1}};
    for (int i = 0; i < 4; i++) {
        vec3 p =
            vec3_madd(vec3_madd(l->corner, l->edge1, (real)st[i][0]), l->edge2, (real)st[i][1]);
        to_double(p, c[i]);
    }
    double xd[3];
    to_double(x, xd);
    double t1c[3][3] = {
        {c[0][0], c[0][1], c[0][2]},
        {c[1][0], c[1][1], c[1][2]},
        {c[2][0], c[2][1], c[2][2]}};
    double t2c[3][3] = {
        {c[0][0], c[0][1], c[0][2]},
        {c[2][0], c[2][1], c[2][2]},
        {c[3][0], c[3][1], c[3][2]}};
    return stagecheck_triangle_solid_angle(t1c, xd) + stagecheck_triangle_solid_angle(t2c, xd);
}

/* The edge fractions (s, t) of the point y of the light and its distance
 * from the light's plane. */
static void
light_coordinates(const struct area_light *l, vec3 y, double *s, double *t, double *off)
{
    vec3 d = vec3_sub(y, l->corner);
    *s = (double)(vec3_dot(d, l->edge1) / vec3_length2(l->edge1));
    *t = (double)(vec3_dot(d, l->edge2) / vec3_length2(l->edge2));
    *off = (double)fabs(vec3_dot(d, area_light_normal(l)));
}

#define GRID 4
#define N_POINTS 4
static const real rect_points[N_POINTS][3] = {
    {0, 0, 0}, /* under the centre */
    {0.9, 1.9, 0.6}, /* a hair below, near a corner: a large, lopsided solid angle */
    {3, 1.9, 0.2}, /* beside it, close to its plane: grazing */
    {-0.3, 2.6, 0.1}, /* behind it (the sampling ignores the side it emits to) */
};

TEST(rect_solid_angle_sampling_is_uniform_in_solid_angle)
{
    struct area_light l = rect_light();
    double n_tests = 2.0 * N_POINTS;
    for (int k = 0; k < N_POINTS; k++) {
        vec3 x = {rect_points[k][0], rect_points[k][1], rect_points[k][2]};
        double omega = part_solid_angle(&l, 0, 1, 0, 1, x);
        struct rng rng = rng_make(7402, (uint64_t)k);
        long counts[GRID * GRID] = {0};
        long n = 100000;
        long off_light = 0;
        double pdf_seen = 0;
        /* "The pdf integrates to 1": the mean of pdf(y) dw/dA A over points
         * y uniform in area is the integral of the pdf over the solid angle. */
        struct stattest_welford integral = {0};
        for (long j = 0; j < n; j++) {
            vec3 y;
            real pdf;
            real u = rng_uniform(&rng);
            real v = rng_uniform(&rng);
            if (!sample_rect_solid_angle(&l, x, u, v, &y, &pdf)) {
                CHECK_MSG(false, "point %d: the sample was refused", k);
                break;
            }
            pdf_seen = (double)pdf;
            double s;
            double t;
            double off;
            light_coordinates(&l, y, &s, &t, &off);
            double tol = 64 * (double)REAL_EPSILON * 4;
            if (!(s >= -tol && s <= 1 + tol && t >= -tol && t <= 1 + tol && off <= tol)) {
                off_light++;
            }
            int cs = (int)fmin(fmax(floor(s * GRID), 0), GRID - 1);
            int ct = (int)fmin(fmax(floor(t * GRID), 0), GRID - 1);
            counts[ct * GRID + cs]++;
            vec3 ya = sample_area_light(&l, rng_uniform(&rng), rng_uniform(&rng));
            struct shadow_sampling by_solid_angle = {.samples = 1, .rect = RECT_BY_SOLID_ANGLE};
            struct scene s1 = {.area_lights = &l, .n_area_lights = 1};
            struct light_picker none = {0};
            real p = light_pdf(&s1, &by_solid_angle, &none, 0, x, ya);
            vec3 d = vec3_sub(ya, x);
            double r2 = (double)vec3_length2(d);
            double cos_l = fabs((double)vec3_dot(area_light_normal(&l), d)) / sqrt(r2);
            stattest_welford_add(&integral, (double)p * cos_l / r2 * (double)area_light_area(&l));
        }
        CHECK_MSG(off_light == 0, "point %d: %ld samples off the light", k, off_light);
        CHECK_MSG(
            fabs(1 / pdf_seen - omega) <= REL_TOL * omega,
            "point %d: 1/pdf %.9g, solid angle %.9g",
            k,
            1 / pdf_seen,
            omega);
        double chi2 = 0;
        for (int c = 0; c < GRID * GRID; c++) {
            double s0 = (double)(c % GRID) / GRID;
            double t0 = (double)(c / GRID) / GRID;
            double expect = (double)n
                            * part_solid_angle(&l, s0, s0 + 1.0 / GRID, t0, t0 + 1.0 / GRID, x)
                            / omega;
            chi2 += (counts[c] - expect) * (counts[c] - expect) / expect;
        }
        double p_chi2 = stattest_chi2_pvalue(chi2, GRID * GRID - 1);
        struct stattest_result t = stattest_t_test_welford_one_sample(&integral, 1);
        printf(
            "point %d: solid angle %.6g sr, 1/pdf %.6g; integral of the pdf %.5f +- %.2g (p = "
            "%.3g); cells: chi-square %.3g, p = %.3g\n",
            k,
            omega,
            1 / pdf_seen,
            integral.mean,
            sqrt(stattest_welford_var_of_mean(&integral)),
            t.p,
            chi2,
            p_chi2);
        CHECK_MSG(p_chi2 > level(n_tests), "point %d: not uniform in solid angle", k);
        CHECK_MSG(t.p > level(n_tests), "point %d: the pdf integrates to %g", k, integral.mean);
    }
}

/* A sample is either refused or finite, on the light, with a finite
 * positive density. */
static bool
sample_is_sane(const struct area_light *l, vec3 x, real u, real v, bool *refused)
{
    vec3 y;
    real pdf = -1;
    *refused = !sample_rect_solid_angle(l, x, u, v, &y, &pdf);
    if (*refused) {
        return pdf == -1;
    }
    double s;
    double t;
    double off;
    light_coordinates(l, y, &s, &t, &off);
    double size = (double)(vec3_length(l->edge1) + vec3_length(l->edge2));
    double scale = size + (double)vec3_length(vec3_sub(x, l->corner));
    double tol = 1e-3;
    return isfinite(y.x) && isfinite(y.y) && isfinite(y.z) && isfinite(pdf) && pdf > 0 && s >= -tol
           && s <= 1 + tol && t >= -tol && t <= 1 + tol && off <= 1e-4 * scale;
}

TEST(rect_solid_angle_degenerate_cases_give_no_nan)
{
    struct area_light l = rect_light();
    struct area_light needle = l;
    needle.edge2 = (vec3){0, 0, 1e-6};
    struct area_light huge = l;
    huge.corner = (vec3){-1e4, 2, -1e4};
    huge.edge1 = (vec3){2e4, 0, 0};
    huge.edge2 = (vec3){0, 0, 2e4};
    struct area_light *lights[3] = {&l, &needle, &huge};
    const vec3 points[] = {
        {0, 2, 0}, /* in the plane, inside the rectangle */
        {5, 2, 0}, /* in the plane, outside */
        {5, 2, -0.75}, /* on the line of an edge */
        {1 + 1e-9, 2 - 1e-9, 0.75 + 1e-9}, /* a hair from a corner */
        {0, 1.999999, 0}, /* a hair below the middle: almost a hemisphere */
        {0, -1e7, 0}, /* very far: a tiny solid angle */
        {1e7, 1.9, 0}, /* very far and grazing */
        {0, 0, 0},
    };
    const real us[] = {0, (real)1e-7, (real)0.5, 1 - REAL_EPSILON, 1 - REAL_EPSILON / 2};
    int n_points = (int)(sizeof points / sizeof points[0]);
    int n_u = (int)(sizeof us / sizeof us[0]);
    int refused = 0;
    int sampled = 0;
    for (int li = 0; li < 3; li++) {
        for (int k = 0; k < n_points; k++) {
            for (int a = 0; a < n_u; a++) {
                for (int b = 0; b < n_u; b++) {
                    bool r;
                    CHECK_MSG(
                        sample_is_sane(lights[li], points[k], us[a], us[b], &r),
                        "light %d, point %d, u %g, v %g: a bad sample",
                        li,
                        k,
                        (double)us[a],
                        (double)us[b]);
                    refused += r;
                    sampled += !r;
                }
            }
            struct shadow_sampling sa = {.samples = 1, .rect = RECT_BY_SOLID_ANGLE};
            struct scene s1 = {.area_lights = lights[li], .n_area_lights = 1};
            struct light_picker none = {0};
            real p = light_pdf(&s1, &sa, &none, 0, points[k], lights[li]->corner);
            CHECK_MSG(isfinite(p) && p >= 0, "light %d, point %d: pdf %g", li, k, (double)p);
        }
    }
    printf(
        "degenerate configurations: %d samples checked, %d refused (sampled by area)\n",
        sampled,
        refused);
    CHECK(sampled > 0 && refused > 0);
    /* In the plane it is always refused. */
    bool r;
    CHECK(sample_is_sane(&l, points[0], (real)0.5, (real)0.5, &r) && r);
    /* A parallelogram and a triangle are no rectangles. */
    struct area_light slanted = l;
    slanted.edge2 = (vec3){0.5, 0, 1.5};
    struct area_light tri = l;
    tri.triangle = true;
    vec3 y;
    real pdf;
    CHECK(!sample_rect_solid_angle(&slanted, points[7], (real)0.5, (real)0.5, &y, &pdf));
    CHECK(!sample_rect_solid_angle(&tri, points[7], (real)0.5, (real)0.5, &y, &pdf));
}

/* --- MIS adds up --------------------------------------------------------------- */

/* One estimate of the irradiance at h (normal up): the MIS-weighted shadow
 * ray (direct_irradiance with bsdf_pdf_cos = 1 / pi: a white diffuse
 * surface) plus the MIS-weighted cosine-distributed bounce when it hits a
 * light, L pi w (L cos / (cos / pi)). */
static double
mis_estimate(
    const struct world *w,
    const struct hit *h,
    const struct shadow_sampling *sampling,
    const struct light_picker *lp,
    struct rng *rng,
    struct stats *st)
{
    vec3 e = direct_irradiance(w, h, sampling, lp, rng, st);
    vec3 local = sample_cosine_hemisphere(rng_uniform(rng), rng_uniform(rng));
    vec3 d = onb_to_world(onb_from_normal(h->n), local);
    struct hit at;
    if (world_intersect(w, (ray){h->p, d}, REAL_MAX, &at, st) && at.light >= 0) {
        real pdf_bsdf = local.z * INV_PI;
        real pdf_light = light_pdf(w->scene, sampling, lp, at.light, h->p, at.p);
        real weight = mis_power_heuristic(1, pdf_bsdf, (real)sampling->samples, pdf_light);
        vec3 le = light_emitted(w->scene, at.light, at.front_face);
        e = vec3_add(e, vec3_scale(le, PI * weight));
    }
    return (double)e.y;
}

/* A t-test of the mean of many MIS estimates at (p, up) against want. */
static void
check_mis_sum(
    const char *what,
    const struct scene *s,
    int rect,
    vec3 p,
    double want,
    double n_tests)
{
    struct world w = world_make(s);
    struct light_picker lp;
    struct diag err;
    CHECK(light_picker_build(&lp, s, &err));
    struct shadow_sampling sampling = {.samples = 1, .rect = rect, .bsdf_pdf_cos = INV_PI};
    struct hit h = {.p = p, .n = {0, 1, 0}, .ng = {0, 1, 0}, .light = -1};
    struct rng rng = rng_make(7403, (uint64_t)(p.x * 1000) + (uint64_t)rect);
    struct stats st = {0};
    struct stattest_welford e = {0};
    for (int j = 0; j < 200000; j++) {
        stattest_welford_add(&e, mis_estimate(&w, &h, &sampling, &lp, &rng, &st));
    }
    struct stattest_result t = stattest_t_test_welford_one_sample(&e, want);
    printf(
        "%s: MIS estimate %.6g +- %.2g, closed form %.6g: p = %.3g\n",
        what,
        e.mean,
        sqrt(stattest_welford_var_of_mean(&e)),
        want,
        t.p);
    CHECK_MSG(t.p > level(n_tests), "%s: %g against %g", what, e.mean, want);
    light_picker_free(&lp);
}

TEST(mis_weights_sum_to_one_over_both_techniques)
{
    struct area_light l = rect_light();
    struct scene rect_scene = {.area_lights = &l, .n_area_lights = 1};
    /* Under the light, close to it, and far below it (where the auto mode
     * samples it by area). */
    const vec3 points[3] = {{0, 0, 0}, {0.8, 1.7, 0.5}, {0.3, -4, 0.2}};
    static const char *const modes[3] = {"area", "solid angle", "auto"};
    double n_tests = 3 * 3 + 1;
    for (int k = 0; k < 3; k++) {
        double c[4][3];
        for (int i = 0; i < 4; i++) {
            real s = (real)(i == 1 || i == 2);
            real t = (real)(i >= 2);
            to_double(vec3_madd(vec3_madd(l.corner, l.edge1, s), l.edge2, t), c[i]);
        }
        double x[3];
        to_double(points[k], x);
        double up[3] = {0, 1, 0};
        double want = stagecheck_polygon_irradiance(c, 4, x, up, (double)l.radiance.y);
        for (int mode = RECT_BY_AREA; mode <= RECT_BY_SIZE; mode++) {
            char what[96];
            snprintf(what, sizeof what, "rectangle, point %d, %s", k, modes[mode]);
            check_mis_sum(what, &rect_scene, mode, points[k], want, n_tests);
        }
    }
    /* A sphere light wholly above the horizon: E = pi L sin^2(theta_max). */
    struct sphere_light ball = {.center = {0.2, 1.2, 0}, .radius = 0.6, .radiance = {2, 2, 2}};
    struct scene sphere_scene = {.sphere_lights = &ball, .n_sphere_lights = 1};
    vec3 p = {0.2, 0, 0};
    double want = (double)PI * 2 * (0.36 / 1.44);
    check_mis_sum("sphere light", &sphere_scene, RECT_BY_AREA, p, want, n_tests);
}

/* --- black-box: the knobs change the noise, not the image ------------------ */

#define N_VARIANTS 4

/* A closed box lit by a large one-sided light covering most of the
 * ceiling (where MIS and solid-angle sampling matter most), a blend
 * sphere (diffuse + mirror: the diffuse lobe's probability enters the
 * bounce's density) and a diffuse one. */
static const char big_light_scene[] =
    "camera origin 0 1 3.2 target 0 1 0 up 0 1 0 fov 45\n"
    "image width 64 height 64\n"
    "material white diffuse albedo 0.7 0.7 0.7\n"
    "material red diffuse albedo 0.6 0.1 0.1\n"
    "material shiny blend albedo 0.4 0.5 0.4 reflectance 0.4 0.4 0.4\n"
    "quad corner -1 0 -1 edge1 0 0 2 edge2 2 0 0 material white\n"
    "quad corner -1 2 -1 edge1 2 0 0 edge2 0 0 2 material white\n"
    "quad corner -1 0 -1 edge1 2 0 0 edge2 0 2 0 material white\n"
    "quad corner -1 0 -1 edge1 0 2 0 edge2 0 0 2 material red\n"
    "quad corner 1 0 -1 edge1 0 0 2 edge2 0 2 0 material white\n"
    "sphere center -0.4 0.4 -0.3 radius 0.4 material shiny\n"
    "sphere center 0.45 0.3 0.3 radius 0.3 material white\n"
    "area_light corner -0.8 1.99 -0.8 edge1 1.6 0 0 edge2 0 0 1.6 radiance 1.5 1.5 1.5\n";

TEST(mis_and_solid_angle_keep_the_image)
{
    const char *scene = test_tmp_path("big_light.scene");
    test_write_file(scene, big_light_scene);
    static const char *const mis_off[] = {"--mis", "off", NULL};
    static const char *const solid[] = {"--light-sampling", "solid-angle", NULL};
    static const char *const both[] = {"--mis", "off", "--light-sampling", "solid-angle", NULL};
    static const char *const by_size[] = {"--light-sampling", "auto", NULL};
    const char *const *variants[N_VARIANTS] = {mis_off, solid, both, by_size};
    const char *names[N_VARIANTS] =
        {"--mis off", "--light-sampling solid-angle", "both", "--light-sampling auto"};
    double n_tests = N_VARIANTS
                     * pathcheck_sets_agree_tests(
                         PATHCHECK_SETS_SIZE,
                         PATHCHECK_SETS_SIZE,
                         PATHCHECK_SETS_BLOCK);
    uint64_t seed = pathcheck_seed(7400);
    struct pathcheck_batches base = {0};
    if (!pathcheck_render_sized(
            scene,
            PATHCHECK_SETS_SIZE,
            16,
            NULL,
            PATHCHECK_SETS_K,
            seed,
            &base)) {
        CHECK(false);
        return;
    }
    for (int v = 0; v < N_VARIANTS; v++) {
        struct pathcheck_batches other = {0};
        if (!pathcheck_render_sized(
                scene,
                PATHCHECK_SETS_SIZE,
                16,
                variants[v],
                PATHCHECK_SETS_K,
                seed + 100 * (v + 1),
                &other)) {
            CHECK(false);
            continue;
        }
        char what[128];
        snprintf(
            what,
            sizeof what,
            "large light, default vs %s (%.1f s + %.1f s)",
            names[v],
            base.seconds,
            other.seconds);
        CHECK_MSG(
            pathcheck_sets_agree(what, &base, &other, PATHCHECK_SETS_BLOCK, level(n_tests)),
            "%s changes the image",
            names[v]);
        pathcheck_batches_free(&other);
    }
    pathcheck_batches_free(&base);
}

TEST_MAIN(
    TEST_ENTRY(power_heuristic_weights_sum_to_one),
    TEST_ENTRY(rect_solid_angle_sampling_is_uniform_in_solid_angle),
    TEST_ENTRY(rect_solid_angle_degenerate_cases_give_no_nan),
    TEST_ENTRY(mis_weights_sum_to_one_over_both_techniques),
    TEST_ENTRY(mis_and_solid_angle_keep_the_image))
