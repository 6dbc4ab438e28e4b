/*
 * 07_furnace.c - scenes whose radiance is known exactly (TESTING.md 3.5,
 * T21, T22): energy is neither lost nor created by the path tracer.
 *
 *  - White furnace (lousodrome.net "white furnace test"): a diffuse sphere
 *    of albedo 1 under a constant environment of radiance 0.5, no lights,
 *    is invisible.  The estimator has no variance here: the camera ray hits
 *    the sphere, the cosine-sampled bounce has weight albedo = 1 and, the
 *    sphere being convex, leaves to the sky (Russian roulette starts only
 *    at the third ray).  So every sample and every pixel is exactly 0.5.
 *    With albedo 0.5 the sphere shows exactly 0.25 (no interreflection).
 *  - Closed sphere (T22, pbrt's integrators_test "unit sphere, Kd = 0.5,
 *    point light of intensity pi at the centre"): the camera inside a
 *    sphere of radius R = 1 and albedo a, a point light of intensity I at
 *    its centre.  Direct irradiance is I / R^2 everywhere (cos = 1), and
 *    the radiance L is the same everywhere, so a wall point receives
 *    pi L more from the rest of the sphere (its whole hemisphere sees wall
 *    of radiance L):  L = a/pi (I/R^2 + pi L)  =>  L = a I / (pi R^2 (1 - a)).
 *    With I = pi: L = a / (1 - a): 1 for a = 0.5, 4 for a = 0.8.  A
 *    one-sample t-test of the pixels (independent estimates of L) against
 *    it, Russian roulette on, with the independent sampler at both
 *    albedos; from stage 08 on, the Sobol sampler takes albedo 0.8, whose
 *    longer paths use more of its dimensions (--sampler sobol: each
 *    pixel's pass scrambled on its own, so the pixels stay independent
 *    estimates; a render at 0.8 costs 0.5 processor s, one at 0.5 0.2).
 *  - Two seeds (of the Sobol sampler from 08 on) give uncorrelated errors
 *    in the closed sphere.
 *  - Depth-limited series: with --no-rr --max-depth N the same sphere has
 *    no variance either (every path bounces N - 1 times, the point light's
 *    shadow ray is deterministic).  --max-depth counts the path's segments,
 *    camera ray included, as Mitsuba's max_depth does (1: emitters seen
 *    directly; 2: direct light only): a path reaching the light after
 *    k bounces has k + 2 segments, so L_N = a (1 + a + ... + a^(N-2))
 *    = a (1 - a^(N-1)) / (1 - a), and exactly N - 1 secondary rays are
 *    traced per camera ray: rays_secondary = pixels * spp * (N - 1).
 *  - nan_pixels is 0 in every run.
 */
#include <stdlib.h>

#include "check.h"
#include "pathcheck.h"
#include "stagecheck.h"
#include "stattest.h"
#include "testlib.h"

/* The two t-tests of closed_sphere_interreflection, each at level
 * PATHCHECK_ALPHA shared four ways (Sidak), not two: their t spreads 1.17
 * wide, not 1 (docs/calibration: 100 renders; the pixels' standard error
 * a little low), so a nominal level understates how often they fail
 * correct work; a quarter of alpha keeps the pair near it. */
#define N_STAT_TESTS 2
#define N_SHARES 4

#define PI_D 3.14159265358979323846

static const char *
furnace_scene(double albedo)
{
    return stagecheck_scene(
        "furnace.scene",
        "camera origin 0 0 4 target 0 0 0 up 0 1 0 fov 40\n"
        "image width 32 height 32\n"
        "background color 0.5 0.5 0.5\n"
        "material ball diffuse albedo %.17g %.17g %.17g\n"
        "sphere center 0 0 0 radius 1 material ball\n",
        albedo,
        albedo,
        albedo);
}

TEST(white_furnace_sphere_is_invisible)
{
    struct image img = {0};
    const char *stats = NULL;
    const char *const args[] = {"--spp", "16", NULL};
    if (!pathcheck_render(furnace_scene(1), args, pathcheck_seed(701), &img, &stats)) {
        CHECK(false);
        return;
    }
    double worst = 0;
    for (int i = 0; i < img.width * img.height * 3; i++) {
        worst = fmax(worst, fabs(img.rgb[i] - 0.5));
    }
    printf("albedo 1 under a sky of 0.5: largest |pixel - 0.5| = %.3g\n", worst);
    CHECK_MSG(worst <= 1e-6, "the sphere shows: a pixel differs from the sky by %.3g", worst);
    CHECK(stagecheck_stat(stats, "nan_pixels") == 0);
    image_free(&img);
}

TEST(half_albedo_sphere_is_half_the_sky)
{
    struct image img = {0};
    const char *stats = NULL;
    const char *const args[] = {"--spp", "16", NULL};
    if (!pathcheck_render(furnace_scene(0.5), args, pathcheck_seed(701), &img, &stats)) {
        CHECK(false);
        return;
    }
    /* The silhouette: a cone of half-angle asin(R / D) = asin(1/4); on the
     * film, a disk of radius tan(asin(1/4)) / tan(20 deg) * 16 pixels. */
    double radius = tan(asin(0.25)) / tan(20 * PI_D / 180) * 16;
    int on_sphere = 0;
    int wrong_sphere = 0;
    int wrong_sky = 0;
    int out_of_range = 0;
    for (int y = 0; y < img.height; y++) {
        for (int x = 0; x < img.width; x++) {
            double r = hypot(x + 0.5 - 16, y + 0.5 - 16);
            const float *p = image_pixel(&img, x, y);
            for (int c = 0; c < 3; c++) {
                /* Pixels wholly inside (the half-diagonal is 0.71) or outside. */
                if (r < radius - 0.75) {
                    wrong_sphere += fabs(p[c] - 0.25) > 1e-6;
                    on_sphere += c == 0;
                } else if (r > radius + 0.75) {
                    wrong_sky += p[c] != 0.5f;
                }
                out_of_range += !(p[c] >= 0.25f - 1e-6 && p[c] <= 0.5f + 1e-6);
            }
        }
    }
    printf(
        "albedo 0.5: %d pixels wholly on the sphere, %d channels of them not 0.25, %d sky "
        "channels not 0.5, %d values outside [0.25, 0.5]\n",
        on_sphere,
        wrong_sphere,
        wrong_sky,
        out_of_range);
    CHECK(on_sphere > 300);
    CHECK(wrong_sphere == 0);
    CHECK(wrong_sky == 0);
    CHECK(out_of_range == 0);
    CHECK(stagecheck_stat(stats, "nan_pixels") == 0);
    image_free(&img);
}

static const char *
closed_sphere_scene(double albedo)
{
    return stagecheck_scene(
        "closed.scene",
        "camera origin 0.1 -0.2 0.3 target 0.5 0.2 -1 up 0 1 0 fov 70\n"
        "image width 32 height 32\n"
        "material wall diffuse albedo %.17g %.17g %.17g\n"
        "sphere center 0 0 0 radius 1 material wall\n"
        "point_light position 0 0 0 intensity %.17g %.17g %.17g\n",
        albedo,
        albedo,
        albedo,
        PI_D,
        PI_D,
        PI_D);
}

TEST(closed_sphere_interreflection)
{
    static const double albedos[] = {0.5, 0.8};
    double level = stattest_sidak(PATHCHECK_ALPHA, N_SHARES);
    bool has_sobol = atoi(STAGE_NAME) >= 8; /* 07 has the independent sampler only */
    for (int i = 0; i < N_STAT_TESTS; i++) {
        double a = albedos[i];
        const char *sampler = has_sobol && i == 1 ? "sobol" : "independent";
        double expected = a / (1 - a);
        struct image img = {0};
        const char *stats = NULL;
        const char *const all[] = {"--spp", "256", "--sampler", sampler, NULL};
        const char *const plain[] = {"--spp", "256", NULL};
        const char *const *args = has_sobol ? all : plain;
        if (!pathcheck_render(
                closed_sphere_scene(a),
                args,
                pathcheck_seed(701) + 10 + i,
                &img,
                &stats)) {
            CHECK(false);
            continue;
        }
        /* Each pixel is an independent estimate of L (its own random
         * stream); all channels are equal, so one channel is tested. */
        struct stattest_welford w = {0};
        for (int p = 0; p < img.width * img.height; p++) {
            stattest_welford_add(&w, img.rgb[3 * p]);
        }
        struct stattest_result t = stattest_t_test_welford_one_sample(&w, expected);
        printf(
            "%s sampler, albedo %.1f: mean radiance %.5f (expected a/(1-a) = %.5f), SE %.2g, "
            "t = %.2f, p = %.3g (level %.3g)\n",
            sampler,
            a,
            w.mean,
            expected,
            sqrt(stattest_welford_var_of_mean(&w)),
            t.t,
            t.p,
            level);
        CHECK_MSG(t.p >= level, "albedo %.1f: %.5f, expected %.5f", a, w.mean, expected);
        /* Power: the test resolves 1% of L. */
        CHECK(sqrt(stattest_welford_var_of_mean(&w)) < 0.002 * expected);
        CHECK(stagecheck_stat(stats, "nan_pixels") == 0);
        image_free(&img);
    }
}

/* Two seeds of the Sobol sampler (stage 08; 07's independent one before)
 * scramble every sequence differently: in
 * the closed sphere (albedo 0.5, L = 1 exactly everywhere, 4 spp, 32 x 32)
 * the errors of two renders are uncorrelated over the pixels (below 4
 * standard errors of a correlation, 4 / sqrt(n)); the same scramble would
 * give a correlation of 1.  A scene whose radiance is known exactly and
 * has no fireflies: against a noisy reference, or where a few pixels carry
 * most of the variance, a correlation over pixels says little. */
TEST(renders_with_two_seeds_are_uncorrelated)
{
    const char *const sobol[] = {"--spp", "4", "--sampler", "sobol", NULL};
    const char *const plain[] = {"--spp", "4", NULL};
    const char *const *args = atoi(STAGE_NAME) >= 8 ? sobol : plain;
    struct image a = {0};
    struct image b = {0};
    const char *stats_a = NULL;
    const char *stats_b = NULL;
    uint64_t seed = pathcheck_seed(702);
    if (!pathcheck_render(closed_sphere_scene(0.5), args, seed, &a, &stats_a)
        || !pathcheck_render(closed_sphere_scene(0.5), args, seed + 1, &b, &stats_b)) {
        CHECK(false);
        image_free(&a);
        return;
    }
    int n = a.width * a.height;
    double saa = 0;
    double sbb = 0;
    double sab = 0;
    for (int p = 0; p < n; p++) {
        double ea = a.rgb[3 * p] - 1; /* L = a / (1 - a) = 1 */
        double eb = b.rgb[3 * p] - 1;
        saa += ea * ea;
        sbb += eb * eb;
        sab += ea * eb;
    }
    double r = sab / sqrt(saa * sbb); /* the mean error is 0: the estimates are unbiased */
    printf(
        "closed sphere, %s, 4 spp, seeds %llu and %llu: correlation of "
        "the errors over %d pixels %.4f (limit %.4f)\n",
        atoi(STAGE_NAME) >= 8 ? "--sampler sobol" : "the independent sampler",
        (unsigned long long)seed,
        (unsigned long long)seed + 1,
        n,
        r,
        4 / sqrt(n));
    CHECK(saa > 0 && sbb > 0);
    CHECK_MSG(fabs(r) < 4 / sqrt(n), "correlation %.4f between two seeds", r);
    image_free(&a);
    image_free(&b);
}

TEST(depth_limited_series)
{
    static const int depths[] = {1, 2, 3, 6};
    const double a = 0.5;
    for (int i = 0; i < 4; i++) {
        int n = depths[i];
        char depth[16];
        snprintf(depth, sizeof depth, "%d", n);
        const char *const args[] = {"--spp", "4", "--no-rr", "--max-depth", depth, NULL};
        struct image img = {0};
        const char *stats = NULL;
        if (!pathcheck_render(closed_sphere_scene(a), args, pathcheck_seed(701), &img, &stats)) {
            CHECK(false);
            continue;
        }
        double expected = a * (1 - pow(a, n - 1)) / (1 - a);
        double lo = INFINITY;
        double hi = -INFINITY;
        for (int p = 0; p < img.width * img.height * 3; p++) {
            lo = fmin(lo, img.rgb[p]);
            hi = fmax(hi, img.rgb[p]);
        }
        double rays = stagecheck_stat(stats, "rays_secondary");
        double bound = (double)img.width * img.height * 4 * (n - 1);
        printf(
            "--no-rr --max-depth %d: pixels in [%.6f, %.6f], expected %.6f; rays_secondary "
            "%.0f, (N-1) per camera ray: %.0f\n",
            n,
            lo,
            hi,
            expected,
            rays,
            bound);
        CHECK_MSG(
            fabs(lo - expected) <= 1e-5 && fabs(hi - expected) <= 1e-5,
            "--max-depth %d: pixels in [%.6f, %.6f], expected %.6f",
            n,
            lo,
            hi,
            expected);
        CHECK_MSG(
            rays <= bound,
            "--max-depth %d: %.0f secondary rays, at most %.0f",
            n,
            rays,
            bound);
        CHECK(stagecheck_stat(stats, "nan_pixels") == 0);
        image_free(&img);
    }
}

TEST_MAIN(
    TEST_ENTRY(white_furnace_sphere_is_invisible),
    TEST_ENTRY(half_albedo_sphere_is_half_the_sky),
    TEST_ENTRY(closed_sphere_interreflection),
    TEST_ENTRY(renders_with_two_seeds_are_uncorrelated),
    TEST_ENTRY(depth_limited_series))
