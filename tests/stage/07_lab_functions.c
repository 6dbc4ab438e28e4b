/*
 * 07_lab_functions.c - lab 07's functions, each on its own (tests/lab/
 * README.md, "Function tests"): a failure names the function and says what
 * it got wrong, in well under a second.
 *
 *  - sample_cosine_hemisphere: unit directions of the upper hemisphere with
 *    density cos(theta) / pi: a chi-square test on 16 bands of cos(theta)
 *    x 32 sectors of phi (warptest.h, after Nori's warptest), 160,000
 *    samples, and the mean cos(theta) against its 2/3 in the message.
 *  - sample_bsdf: diffuse bounces follow cos / pi around the shading normal
 *    (the same chi-square, in a frame of the test's own), with weight
 *    albedo and pdf cos / pi; a mirror reflects, weight its reflectance; a
 *    blend picks each lobe in proportion to its mean reflectance, and the
 *    expected weight, mirror plus diffuse, is the sum of the reflectances
 *    (unbiased); glass reflects with the Fresnel probability (computed
 *    here from the textbook formula, not optics.c's), always past the
 *    critical angle, refracts by Snell's law otherwise, weight 1.  The
 *    proportions and expectations are quadratures over a grid of u (the
 *    function is given its random numbers): exact, no noise.
 *  - emitted: a light's emission counts after the camera ray and after
 *    specular bounces, and after every bounce without next-event
 *    estimation; never after a diffuse bounce with it (the shadow ray
 *    counted it); a one-sided light's back is black.
 *  - russian_roulette: no roulette before min_depth; from it on, survival
 *    with q = min(max(beta), RR_MAX_SURVIVAL) and a survivor's throughput
 *    divided by q, so the mean throughput over u in [0,1) is beta (a
 *    quadrature over u).
 *
 * The two chi-square tests share alpha 0.01 (Sidak: 0.005 each); their
 * seeds are pathcheck_seed()'s, so make calibrate and make
 * calibrate-functions can rerun them with others.  White-box: the test includes the stage's render.c for its static
 * emitted() and russian_roulette() (tests/Makefile links the stage's other
 * objects from an archive).
 */
#include "render.c"

#include <stdio.h>
#include <string.h>

#include "check.h"
#include "pathcheck.h"
#include "stagecheck.h"
#include "stattest.h"
#include "warptest.h"

#define N_CHI2_TESTS 2
#define CHI2_SAMPLES 160000
/* Agreement of computed directions and weights: round-off of the given
 * formulas in either precision. */
#define TOL (sizeof(real) == sizeof(float) ? 2e-4 : 1e-9)

static double
chi2_level(void)
{
    return stattest_sidak(PATHCHECK_ALPHA, N_CHI2_TESTS);
}

static double
cosine_pdf(double x, double y, double z, const void *ctx)
{
    (void)x;
    (void)y;
    (void)ctx;
    return z > 0 ? z / 3.14159265358979323846 : 0;
}

/* Checks a histogram of directions against cos / pi, naming `function`. */
static void
check_cosine_fit(const char *function, const struct warptest *w, double mean_cos)
{
    struct warptest_result fit = warptest_fit(w, cosine_pdf, NULL);
    char why[300];
    warptest_describe(w, &fit, why, sizeof why);
    printf("%s: %s\n", function, why);
    CHECK_MSG(
        fit.p >= chi2_level(),
        "%s: its directions do not have the density cos(theta)/pi (p %.2g < %.3g): %s; "
        "mean cos(theta) %.4f, where cosine-weighted directions have 2/3 "
        "(uniform ones 1/2)",
        function,
        fit.p,
        chi2_level(),
        why,
        mean_cos);
}

TEST(sample_cosine_hemisphere_has_density_cos_theta_over_pi)
{
    struct warptest w;
    CHECK(warptest_directions(&w, 16, 32, false));
    struct rng rng = rng_make(pathcheck_seed(7001), 1);
    double sum_cos = 0;
    int bad = 0;
    for (int i = 0; i < CHI2_SAMPLES; i++) {
        real u = rng_uniform(&rng);
        real v = rng_uniform(&rng);
        vec3 d = sample_cosine_hemisphere(u, v);
        double len = sqrt((double)vec3_length2(d));
        if (!(fabs(len - 1) < 1e-4 && d.z >= 0) && bad++ == 0) {
            CHECK_FAIL(
                "sample_cosine_hemisphere(%.4f, %.4f) = (%g, %g, %g): not a unit direction "
                "with z >= 0 (length %g)",
                (double)u,
                (double)v,
                (double)d.x,
                (double)d.y,
                (double)d.z,
                len);
        }
        sum_cos += (double)d.z;
        warptest_add(&w, (double)d.x, (double)d.y, (double)d.z);
    }
    check_cosine_fit("sample_cosine_hemisphere", &w, sum_cos / CHI2_SAMPLES);
    warptest_free(&w);
}

/* A hit at the origin with unit normal n (shading and geometric alike). */
static struct hit
hit_with_normal(vec3 n, bool front_face)
{
    struct hit h = {0};
    h.n = n;
    h.ng = n;
    h.front_face = front_face;
    h.light = -1;
    h.error = (real)1e-12;
    return h;
}

static struct material
material_of(enum material_kind kind, vec3 albedo, vec3 reflectance, real ior)
{
    struct material m = {.kind = kind, .albedo = albedo, .reflectance = reflectance, .ior = ior};
    return m;
}

/* A random unit vector, and one in the hemisphere around n. */
static vec3
random_unit(struct rng *rng)
{
    double d[3];
    stagecheck_random_unit(rng, d);
    return (vec3){(real)d[0], (real)d[1], (real)d[2]};
}

static vec3
incoming_towards(vec3 n, struct rng *rng)
{
    vec3 d = random_unit(rng);
    return vec3_dot(d, n) < 0 ? d : vec3_neg(d);
}

static bool
vec3_near(vec3 a, vec3 b, double tol)
{
    return fabs((double)(a.x - b.x)) <= tol && fabs((double)(a.y - b.y)) <= tol
           && fabs((double)(a.z - b.z)) <= tol;
}

TEST(sample_bsdf_diffuse_bounces_have_density_cos_over_pi_and_weight_albedo)
{
    struct warptest w;
    CHECK(warptest_directions(&w, 16, 32, false));
    struct rng rng = rng_make(pathcheck_seed(7002), 2);
    vec3 albedo = {(real)0.6, (real)0.3, (real)0.1};
    struct material m = material_of(MAT_DIFFUSE, albedo, vec3_splat(0), 1);
    /* One normal for the histogram, in a frame of the test's own. */
    vec3 n = vec3_normalize((vec3){(real)0.3, (real)-0.5, (real)0.8});
    vec3 s = vec3_normalize(vec3_cross(n, (vec3){1, 0, 0}));
    vec3 t = vec3_cross(n, s);
    struct hit h = hit_with_normal(n, true);
    double sum_cos = 0;
    int reported = 0;
    for (int i = 0; i < CHI2_SAMPLES; i++) {
        real u[3] = {rng_uniform(&rng), rng_uniform(&rng), rng_uniform(&rng)};
        vec3 d = incoming_towards(n, &rng);
        struct bsdf_sample bs = {0};
        bool ok = sample_bsdf(&m, albedo, &h, d, u, &bs);
        double c = (double)vec3_dot(bs.d, n);
        bool good = ok && !bs.specular && vec3_near(bs.weight, albedo, TOL) && c > 0
                    && fabs((double)bs.pdf - c / 3.14159265358979323846) <= 1e-4 * (1 + c);
        if (!good && reported++ < 3) {
            CHECK_FAIL(
                "sample_bsdf (diffuse, albedo 0.6 0.3 0.1, u %.4f %.4f %.4f): returned %s, specular %d, "
                "weight (%g %g %g), pdf %g, cos(theta) %g: a diffuse bounce returns true, "
                "leaves above the surface with weight f cos/pdf = albedo and pdf cos(theta)/pi",
                (double)u[0],
                (double)u[1],
                (double)u[2],
                ok ? "true" : "false",
                bs.specular,
                (double)bs.weight.x,
                (double)bs.weight.y,
                (double)bs.weight.z,
                (double)bs.pdf,
                c);
        }
        sum_cos += c;
        warptest_add(&w, (double)vec3_dot(bs.d, s), (double)vec3_dot(bs.d, t), c);
    }
    check_cosine_fit("sample_bsdf (diffuse)", &w, sum_cos / CHI2_SAMPLES);
    warptest_free(&w);
}

TEST(sample_bsdf_mirror_reflects_with_its_reflectance)
{
    struct rng rng = rng_make(7003, 3);
    vec3 r = {(real)0.9, (real)0.8, (real)0.7};
    struct material m = material_of(MAT_MIRROR, vec3_splat(0), r, 1);
    for (int i = 0; i < 200; i++) {
        vec3 n = random_unit(&rng);
        vec3 d = incoming_towards(n, &rng);
        struct hit h = hit_with_normal(n, true);
        real u[3] = {rng_uniform(&rng), rng_uniform(&rng), rng_uniform(&rng)};
        struct bsdf_sample bs = {0};
        bool ok = sample_bsdf(&m, vec3_splat(0), &h, d, u, &bs);
        vec3 mirror = vec3_sub(d, vec3_scale(n, 2 * vec3_dot(d, n)));
        if (!(ok && bs.specular && vec3_near(bs.d, mirror, 1e3 * TOL)
              && vec3_near(bs.weight, r, TOL))) {
            CHECK_FAIL(
                "sample_bsdf (mirror, reflectance 0.9 0.8 0.7): returned %s, specular %d, d (%g %g %g) "
                "where the mirror direction is (%g %g %g), weight (%g %g %g): a mirror always "
                "reflects (d - 2 (d.n) n), is specular, and weighs its reflectance",
                ok ? "true" : "false",
                bs.specular,
                (double)bs.d.x,
                (double)bs.d.y,
                (double)bs.d.z,
                (double)mirror.x,
                (double)mirror.y,
                (double)mirror.z,
                (double)bs.weight.x,
                (double)bs.weight.y,
                (double)bs.weight.z);
            return;
        }
    }
}

/* The mean over a grid of u (GRID_U0 x GRID_U x GRID_U midpoints) of
 * what sample_bsdf does: the fraction of specular bounces, the mean weight
 * (0 where it returns false), and the fraction that return false. */
#define GRID_U0 2048
#define GRID_U 4

struct lobe_means {
    double specular, refracted, ended;
    vec3 weight;
};

static struct lobe_means
quadrature(const struct material *m, vec3 albedo, const struct hit *h, vec3 d)
{
    struct lobe_means q = {0};
    q.weight = vec3_splat(0);
    double n = (double)GRID_U0 * GRID_U * GRID_U;
    for (int i = 0; i < GRID_U0; i++) {
        for (int j = 0; j < GRID_U * GRID_U; j++) {
            real u[3] = {
                (real)((i + 0.5) / GRID_U0),
                (real)((j % GRID_U + 0.5) / GRID_U),
                (real)((j / GRID_U + 0.5) / GRID_U),
            };
            struct bsdf_sample bs = {0};
            if (!sample_bsdf(m, albedo, h, d, u, &bs)) {
                q.ended += 1 / n;
                continue;
            }
            q.specular += bs.specular / n;
            q.refracted += (vec3_dot(bs.d, h->ng) * vec3_dot(d, h->ng) > 0) / n;
            q.weight = vec3_madd(q.weight, bs.weight, (real)(1 / n));
        }
    }
    return q;
}

TEST(sample_bsdf_blend_picks_lobes_by_reflectance_and_is_unbiased)
{
    vec3 albedo = {(real)0.5, (real)0.2, (real)0.1};
    vec3 r = {(real)0.3, (real)0.3, (real)0.6};
    struct material m = material_of(MAT_BLEND, albedo, r, 1);
    vec3 n = vec3_normalize((vec3){(real)-0.2, (real)0.9, (real)0.1});
    struct hit h = hit_with_normal(n, true);
    vec3 d = vec3_normalize((vec3){(real)0.5, (real)-1, (real)0.3});
    struct lobe_means q = quadrature(&m, albedo, &h, d);
    double p_mirror = 0.4 / (0.4 + 0.8 / 3);
    /* The lobe is chosen by one number: a grid of GRID_U0 steps finds its
     * probability to 1 / GRID_U0. */
    CHECK_MSG(
        fabs(q.specular - p_mirror) < 2.0 / GRID_U0,
        "sample_bsdf (blend, albedo 0.5 0.2 0.1, reflectance 0.3 0.3 0.6): the mirror lobe is "
        "chosen for %.4f of u, not %.4f: pick each lobe in proportion to its mean reflectance "
        "(0.4 mirror, 0.267 diffuse)",
        q.specular,
        p_mirror);
    vec3 expected = vec3_add(albedo, r);
    CHECK_MSG(
        vec3_near(q.weight, expected, 4.0 / GRID_U0),
        "sample_bsdf (blend): the mean weight over u is (%.4f %.4f %.4f), not the sum of the "
        "reflectances (%.4f %.4f %.4f): each lobe's weight must be divided by the probability "
        "of choosing it (the estimate is biased)",
        (double)q.weight.x,
        (double)q.weight.y,
        (double)q.weight.z,
        (double)expected.x,
        (double)expected.y,
        (double)expected.z);
    CHECK_MSG(
        q.ended == 0,
        "sample_bsdf (blend): ended %.4f of the paths above a plain surface",
        q.ended);
}

/* Glass of index 1.5 hit at angle theta_deg from the front (entering) or
 * the back (leaving). */
static void
check_glass(double theta_deg, bool front_face)
{
    struct material m = material_of(MAT_GLASS, vec3_splat(0), vec3_splat(0), (real)1.5);
    /* The outward normal is +z; a hit's normals face the ray's origin. */
    vec3 n = front_face ? (vec3){0, 0, 1} : (vec3){0, 0, -1};
    struct hit h = hit_with_normal(n, front_face);
    double th = theta_deg * 3.14159265358979323846 / 180;
    vec3 d = vec3_normalize(vec3_sub((vec3){(real)sin(th), 0, 0}, vec3_scale(n, (real)cos(th))));
    double eta = front_face ? 1 / 1.5 : 1.5;
    double f = stagecheck_fresnel(cos(th), eta);
    struct lobe_means q = quadrature(&m, vec3_splat(0), &h, d);
    const char *side = front_face ? "entering" : "leaving";
    double reflected = 1 - q.refracted - q.ended;
    CHECK_MSG(
        fabs(reflected - f) < 2.0 / GRID_U0 && q.ended == 0,
        "sample_bsdf (glass 1.5, %s at %.0f deg): reflects for %.4f of u (ends %.4f), where the "
        "Fresnel reflectance is %.4f: reflect when u[0] < F, refract otherwise%s",
        side,
        theta_deg,
        reflected,
        q.ended,
        f,
        f >= 1 ? " (past the critical angle F = 1: always reflect)" : "");
    CHECK_MSG(
        vec3_near(q.weight, vec3_splat(1), 4.0 / GRID_U0) && fabs(q.specular - 1) < 1e-12,
        "sample_bsdf (glass 1.5, %s at %.0f deg): mean weight (%.4f %.4f %.4f), specular for %.4f: "
        "choosing reflection with probability F and refraction with 1 - F makes every weight 1",
        side,
        theta_deg,
        (double)q.weight.x,
        (double)q.weight.y,
        (double)q.weight.z,
        q.specular);
    /* Directions: one draw of each lobe. */
    for (int k = 0; k < 2; k++) {
        real u[3] = {k == 0 ? (real)(f / 2) : (real)((1 + f) / 2), (real)0.5, (real)0.5};
        struct bsdf_sample bs = {0};
        if (!sample_bsdf(&m, vec3_splat(0), &h, d, u, &bs)) {
            continue; /* reported above */
        }
        bool refracted = bs.d.z * d.z > 0;
        char where[200];
        snprintf(
            where,
            sizeof where,
            "sample_bsdf (glass, %s at %.0f deg, u[0] %.4f, F %.4f): d (%g %g %g)",
            side,
            theta_deg,
            (double)u[0],
            f,
            (double)bs.d.x,
            (double)bs.d.y,
            (double)bs.d.z);
        if (k == 0 || f >= 1) {
            vec3 mirror = {d.x, d.y, -d.z};
            CHECK_MSG(
                !refracted && vec3_near(bs.d, mirror, 1e3 * TOL),
                "%s, not the mirror direction (%g %g %g) of u[0] < F",
                where,
                (double)mirror.x,
                (double)mirror.y,
                (double)mirror.z);
        } else {
            double sin_t = eta * sin(th);
            CHECK_MSG(
                refracted && fabs((double)bs.d.x - sin_t) < 1e3 * TOL
                    && fabs((double)bs.d.y) < 1e3 * TOL,
                "%s, where u[0] >= F refracts: Snell's law gives sin(theta_t) = %.5f on the far side",
                where,
                sin_t);
        }
    }
}

TEST(sample_bsdf_glass_reflects_with_the_fresnel_probability)
{
    static const double angles[] = {0, 30, 60, 85};
    for (int i = 0; i < 4; i++) {
        check_glass(angles[i], true);
        check_glass(angles[i] * 0.45, false); /* under the critical angle, 41.8 deg */
    }
    check_glass(50, false); /* total internal reflection */
    check_glass(75, false);
}

/* A scene with one one-sided area light of radiance (4, 2, 1). */
static bool
light_scene(struct scene *s)
{
    return stagecheck_load_text(
        "camera origin 0 0 5 target 0 0 0 up 0 1 0 fov 40\n"
        "image width 8 height 8\n"
        "area_light corner -1 -1 0 edge1 2 0 0 edge2 0 2 0 radiance 4 2 1\n",
        s);
}

TEST(emitted_counts_light_only_where_nee_cannot_find_it)
{
    struct scene s;
    CHECK(light_scene(&s));
    if (check_current.failed_checks) {
        return;
    }
    struct renderer renderer = {.scene = &s};
    struct hit h = {0};
    h.light = 0;
    for (int nee = 0; nee <= 1; nee++) {
        for (int specular = 0; specular <= 1; specular++) {
            for (int front = 0; front <= 1; front++) {
                renderer.nee = nee;
                struct path path = {.beta = vec3_splat(1), .specular = specular, .depth = 2};
                h.front_face = front;
                vec3 got = emitted(&renderer, &h, &path);
                bool counts = front && (!nee || specular);
                vec3 want = counts ? (vec3){4, 2, 1} : vec3_splat(0);
                CHECK_MSG(
                    vec3_near(got, want, 0),
                    "emitted (next-event estimation %s, after a %s bounce, the light's %s): (%g %g %g), "
                    "expected (%g %g %g)%s",
                    nee ? "on" : "off",
                    specular ? "specular (or the camera ray)" : "diffuse",
                    front ? "front" : "back",
                    (double)got.x,
                    (double)got.y,
                    (double)got.z,
                    (double)want.x,
                    (double)want.y,
                    (double)want.z,
                    !front   ? ": a one-sided light is black from behind (light_emitted says so)"
                    : counts ? ": nothing else can find this light's emission"
                             : ": the shadow ray at the previous vertex already counted it");
            }
        }
    }
    scene_free(&s);
}

/* russian_roulette at one u: 08 adds a threshold, 1 here (07's rule). */
static real
roulette(struct path *path, int min_depth, real u)
{
#ifdef RR_THRESHOLD
    return russian_roulette(path, min_depth, 1, u);
#else
    return russian_roulette(path, min_depth, u);
#endif
}

#define GRID_RR 20000

TEST(russian_roulette_keeps_the_expected_throughput)
{
    static const vec3 betas[] = {
        {(real)0.9, (real)0.5, (real)0.1},
        {(real)0.02, (real)0.01, 0},
        {2, 1, 1},
    };
    for (int b = 0; b < 3; b++) {
        vec3 beta = betas[b];
        double q_want = fmin((double)vec3_max_comp(beta), RR_MAX_SURVIVAL);
        /* Before min_depth: no roulette at all. */
        struct path early = {.beta = beta, .depth = 2};
        real q0 = roulette(&early, 3, (real)0.999);
        CHECK_MSG(
            q0 == 1 && vec3_near(early.beta, beta, 0),
            "russian_roulette (depth 2, min_depth 3, u 0.999): returned q %g, throughput "
            "(%g %g %g): before min_depth a path always survives unchanged and q is 1",
            (double)q0,
            (double)early.beta.x,
            (double)early.beta.y,
            (double)early.beta.z);
        double survived = 0;
        vec3 mean = vec3_splat(0);
        double q_seen = -1;
        bool wrong_survivor = false;
        for (int i = 0; i < GRID_RR; i++) {
            real u = (real)((i + 0.5) / GRID_RR);
            struct path path = {.beta = beta, .depth = 3};
            real q = roulette(&path, 3, u);
            q_seen = (double)q;
            bool alive = !vec3_is_zero(path.beta);
            survived += alive;
            mean = vec3_madd(mean, path.beta, (real)(1.0 / GRID_RR));
            wrong_survivor |=
                alive && !vec3_near(path.beta, vec3_scale(beta, 1 / q), 1e-6 * (1 + (double)q));
        }
        survived /= GRID_RR;
        CHECK_MSG(
            fabs(q_seen - q_want) < 1e-6,
            "russian_roulette (throughput %g %g %g): q %g, expected min(max(beta), %g) = %g",
            (double)beta.x,
            (double)beta.y,
            (double)beta.z,
            q_seen,
            RR_MAX_SURVIVAL,
            q_want);
        CHECK_MSG(
            fabs(survived - q_want) < 2.0 / GRID_RR,
            "russian_roulette (throughput %g %g %g): survives for %.4f of u in [0,1), not q = %.4f",
            (double)beta.x,
            (double)beta.y,
            (double)beta.z,
            survived,
            q_want);
        CHECK_MSG(
            !wrong_survivor,
            "russian_roulette (throughput %g %g %g): a survivor's throughput is not beta / q",
            (double)beta.x,
            (double)beta.y,
            (double)beta.z);
        CHECK_MSG(
            vec3_near(mean, beta, 1e-3 * (double)vec3_max_comp(beta) + 2.0 / GRID_RR),
            "russian_roulette (throughput %g %g %g): the mean throughput over u in [0,1) is "
            "(%.5f %.5f %.5f), not beta: roulette must keep the expected value (divide the "
            "survivors by q)",
            (double)beta.x,
            (double)beta.y,
            (double)beta.z,
            (double)mean.x,
            (double)mean.y,
            (double)mean.z);
    }
}

TEST_MAIN(
    TEST_ENTRY(sample_cosine_hemisphere_has_density_cos_theta_over_pi),
    TEST_ENTRY(sample_bsdf_diffuse_bounces_have_density_cos_over_pi_and_weight_albedo),
    TEST_ENTRY(sample_bsdf_mirror_reflects_with_its_reflectance),
    TEST_ENTRY(sample_bsdf_blend_picks_lobes_by_reflectance_and_is_unbiased),
    TEST_ENTRY(sample_bsdf_glass_reflects_with_the_fresnel_probability),
    TEST_ENTRY(emitted_counts_light_only_where_nee_cannot_find_it),
    TEST_ENTRY(russian_roulette_keeps_the_expected_throughput))
