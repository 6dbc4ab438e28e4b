/*
 * 03_soft_shadows.c - area lights sampled with shadow rays, through the
 * stage's binary.
 *
 *  - One shadow ray per light (--shadow-samples 1) is an unbiased estimate:
 *    over a block of 16,384 penumbra pixels, one ray minus 32 rays, pixel
 *    by pixel, has mean 0 within 3.4 standard errors (t, stattest.h; 3 for
 *    each of four blocks), in the penumbra across the light's edges and
 *    across its corners, where a point sampled with u and v not independent (u = v:
 *    the light's diagonal) sees the wrong part of the light.
 *  - The adaptive mode (--adaptive 16,128) spends half the shadow rays of
 *    --shadow-samples 144, reports its penumbra points, and its refinement
 *    works: far better than its 16 probes alone.  Its error against 144 rays is
 *    printed (see the comment at the test for why it is not bounded by
 *    1.5x).
 *  - The light is seen with radiance exactly L from the front, black from
 *    behind, and lights nothing behind its plane (SCENES.md).
 *  - Irradiance at a point from a rectangle, estimated with 4096 shadow
 *    rays, matches Lambert's closed form for polygons (TESTING.md T9).
 *  - Irradiance from a sphere light, sampled by the cone of directions it
 *    subtends, matches pi L sin^2(theta_max) cos(alpha) where the whole
 *    sphere is above the horizon (exactly, in adaptive mode, where the
 *    probes all reach it) and a quadrature over the cone where the horizon
 *    cuts it, and pi L a^2 / (p^2 + a^2) where a black plane at height p
 *    cuts it in a circle of radius a (smallpt's lamp); the sphere is seen
 *    with radiance L from outside, black from inside.
 *
 * The scenes hold a floor, black (albedo 0) occluders and the light, which
 * is black as a surface, so no light is reflected twice: global
 * illumination (07) changes none of the expected values.  Every render
 * uses -s 1 (one camera ray per pixel) so that supersampling stages (06,
 * 07) cost what this one does.
 */
#include <inttypes.h>
#include <stdlib.h>

#include "check.h"
#include "metrics.h"
#include "pathcheck.h"
#include "stagecheck.h"
#include "stattest.h"
#include "testlib.h"

#define PI_D 3.14159265358979323846

/* A floor (albedo 0.5), a black sphere at height 2 and a small light (0.3
 * across, radiance 50, edges along x and z) at height 4.  The shadow on
 * the floor: umbra out to about 0.68 from the axis, penumbra from there to
 * about 0.98 (along x and z; across the light's corners, the diagonals,
 * about 0.62 to 1.04).  The camera at height 1 looks straight down at
 * (cam_x, 0, cam_z) with field of view fov degrees. */
static const char *
penumbra_scene(double cam_x, double cam_z, double fov, int size)
{
    return stagecheck_scene(
        "penumbra.scene",
        "camera origin %.17g 1 %.17g target %.17g 0 %.17g up 0 0 -1 fov %.17g\n"
        "image width %d height %d\n"
        "material floor diffuse albedo 0.5 0.5 0.5\n"
        "material black diffuse albedo 0 0 0\n"
        "quad corner -5 0 -5 edge1 0 0 10 edge2 10 0 0 material floor\n"
        "sphere center 0 2 0 radius 0.4 material black\n"
        "area_light corner -0.15 4 -0.15 edge1 0.3 0 0 edge2 0 0 0.3 radiance 50 50 50\n",
        cam_x,
        cam_z,
        cam_x,
        cam_z,
        fov,
        size,
        size);
}

/* The renders' seeds: first_seed() + k for the k-th of a set, 1 + k unless
 * PATHCHECK_SEED says otherwise (make test-seeds reruns the statistical
 * tests from other seeds: docs/calibration/README.md). */
static uint64_t
first_seed(void)
{
    return pathcheck_seed(1);
}

/* The render of `scene` with `samples` shadow rays at the seed; false
 * (and an empty image) when it fails.  From stage 08 on with the
 * independent sampler: these tests compare estimates over seeds, which
 * must spread as independent ones do.  Stage 08's Sobol shadow rays form a
 * scrambled net, whose estimate of a discontinuous integrand takes a few
 * values (the cut sphere light's 4096 rays: -9.8e-5 or +3.0e-4 of its
 * closed form, depending on the seed): 8 seeds can agree to 1e-9 and fail
 * a t-test (5 of 30 seed offsets on stage 08). */
static bool
render_seeded(const char *scene, const char *samples, uint64_t seed, struct image *img)
{
    char seed_text[32];
    snprintf(seed_text, sizeof seed_text, "%" PRIu64, seed);
    const char *args[] = {"-s", "1", "--seed", seed_text, "--shadow-samples", samples, NULL, NULL, NULL};
    if (atoi(STAGE_NAME) >= 8) {
        args[6] = "--sampler";
        args[7] = "independent";
    }
    return stagecheck_render(scene, args, img, NULL);
}

/* The mean of channel 0 over a whole render; NaN when it fails. */
static double
render_mean(const char *scene, const char *samples, uint64_t seed)
{
    struct image img = {0};
    if (!render_seeded(scene, samples, seed, &img)) {
        return NAN;
    }
    double mean = stagecheck_region_mean(&img, 0, 0, img.width, img.height, 0);
    image_free(&img);
    return mean;
}

/* A block 0.22 across, centred 0.83 from the axis in direction `degrees`
 * (from +x towards +z): mid-penumbra, in 128x128 pixels.  Each pixel is
 * its own random stream, so one render with one shadow ray gives 16,384
 * independent one-ray estimates, and a render with 32 rays a low-noise
 * estimate of the same pixels: their differences, pixel by pixel, have
 * mean 0 when one ray is unbiased.  (The same 16,384 one-ray estimates as
 * 64 renders of a 16x16 block, in 2 renders instead of 72.)  False when
 * the mean difference is more than noise explains. */
static bool
one_ray_agrees_with_many(double degrees)
{
    double angle = degrees * PI_D / 180;
    const char *scene =
        penumbra_scene(0.83 * cos(angle), 0.83 * sin(angle), 2 * atan(0.11) * 180 / PI_D, 128);
    struct image one = {0};
    struct image many = {0};
    bool rendered = render_seeded(scene, "1", first_seed(), &one)
                    && render_seeded(scene, "32", first_seed() + 1000, &many);
    CHECK(rendered);
    if (!rendered) {
        image_free(&one);
        return false;
    }
    struct stattest_welford diff = {0};
    for (int p = 0; p < one.width * one.height; p++) {
        stattest_welford_add(&diff, (double)one.rgb[3 * p] - (double)many.rgb[3 * p]);
    }
    double many_mean = stagecheck_region_mean(&many, 0, 0, many.width, many.height, 0);
    struct stattest_result t = stattest_t_test_welford_one_sample(&diff, 0);
    printf(
        "%3.0f degrees: block mean with 32 rays %.6g; one ray minus 32, pixel by pixel: %.3g +- %.2g "
        "(%d pixels), t = %.3g\n",
        degrees,
        many_mean,
        diff.mean,
        sqrt(stattest_welford_var_of_mean(&diff)),
        one.width * one.height,
        t.t);
    /* In the penumbra, neither fully lit (about 0.036) nor black. */
    CHECK(many_mean > 0.005 && many_mean < 0.03);
    image_free(&one);
    image_free(&many);
    /* Four tests: 3.4 keeps the chance that any fails near one test's at 3. */
    return fabs(t.t) < 3.4;
}

/* Across the light's edges (0 and 90 degrees) and across its corners (45
 * and 135): each pair of edges seen as u and v sweep them, the corners
 * only when u and v are drawn independently. */
TEST(one_shadow_ray_is_unbiased_in_the_penumbra)
{
    static const double directions[] = {0, 45, 90, 135};
    for (int i = 0; i < 4; i++) {
        CHECK_MSG(one_ray_agrees_with_many(directions[i]), "at %g degrees", directions[i]);
    }
}

/*
 * The adaptive mode against full sampling, both against a 1024-ray render
 * of a 48x48 view of the floor from x = 0.49 to 1.21: a quarter umbra, 40%
 * penumbra, a third lit.
 *
 * Measured on 03_soft_shadows (seed 1): 144 rays relMSE 7.4e-6; adaptive
 * 16,128 3.4e-5 with 50% of the shadow rays and 1019 penumbra points; 16
 * rays 2.0e-4.  The error ratio 4.6 is far above the 1.5 the Cornell box
 * reaches (03-05_reference_area.c), and a scheme that decides from 16
 * probes does not reach it on this harsh penumbra:
 * when a point sees (or misses) less than about a sixth of the light, all
 * 16 jittered probes often agree, and the point gets 0 (or the full value)
 * without refinement.  A variant that refines with a fresh 12x12 grid of
 * 144 rays (the full estimator exactly) still gives 3.9.  So the test
 * bounds what the design must achieve: the refinement must beat its probes
 * alone by 4x, the rays must drop, and the ratio to full sampling is
 * reported and held below 6 against regressions.  The reference's own
 * noise is a small part of these errors: against 1024 rays (a quarter
 * of 4096 rays' cost, the same verdicts), 15 seed offsets on stages 03
 * and 08 gave 144 rays 7.1e-6 to 8.2e-6, the probes 1.8e-4 to 2.2e-4,
 * adaptive at most 0.18 of its probes and 4.6 times full sampling.
 */
/* The options of one of the adaptive test's renders (NULL-terminated in
 * out[ADAPTIVE_ARGS]): one camera ray, the seed, the shadow-ray option and
 * its value, and what keeps the later stages' renders comparable:
 *  - from stage 06, the camera ray through the pixel's centre (--aa grid),
 *    as in stages 03-05.  Jittered (06's default), each render sees its
 *    own point of each pixel, and the 1024-ray reference differs from
 *    every render by that footprint noise too: a floor of about 2.5e-5
 *    under every relMSE (stage 06, 50 seed offsets: 144 rays 3.3e-5,
 *    adaptive 5.8e-5 against 0.22e-3 for the probes, a ratio of 0.26, and
 *    the 0.25 below failed 9 runs of the first 31);
 *  - from stage 08, the independent sampler: its default Sobol sampler
 *    draws a fixed number of shadow rays from stratified sequences, while
 *    the adaptive rays, whose count varies, keep the random stream. */
#define ADAPTIVE_ARGS 11

static void
adaptive_test_options(const char **out, const char *seed, const char *option, const char *value)
{
    int n = 0;
    const char *const common[] = {"-s", "1", "--seed", seed, option, value};
    for (int i = 0; i < 6; i++) {
        out[n++] = common[i];
    }
    if (atoi(STAGE_NAME) >= 6) {
        out[n++] = "--aa";
        out[n++] = "grid";
    }
    if (atoi(STAGE_NAME) >= 8) {
        out[n++] = "--sampler";
        out[n++] = "independent";
    }
    out[n] = NULL;
}

TEST(adaptive_sampling_saves_rays_where_the_probes_agree)
{
    const char *scene = penumbra_scene(0.85, 0, 40, 48);
    char ref_seed[32], seed[32];
    snprintf(ref_seed, sizeof ref_seed, "%" PRIu64, first_seed() + 98);
    snprintf(seed, sizeof seed, "%" PRIu64, first_seed());
    const char *ref_args[ADAPTIVE_ARGS], *full_args[ADAPTIVE_ARGS];
    const char *probe_args[ADAPTIVE_ARGS], *adaptive_args[ADAPTIVE_ARGS];
    adaptive_test_options(ref_args, ref_seed, "--shadow-samples", "1024");
    adaptive_test_options(full_args, seed, "--shadow-samples", "144");
    adaptive_test_options(probe_args, seed, "--shadow-samples", "16");
    adaptive_test_options(adaptive_args, seed, "--adaptive", "16,128");
    struct image ref = {0};
    struct image full = {0};
    struct image probes = {0};
    struct image adaptive = {0};
    const char *full_stats = NULL;
    const char *adaptive_stats = NULL;
    if (!stagecheck_render(scene, ref_args, &ref, NULL)
        || !stagecheck_render(scene, full_args, &full, &full_stats)
        || !stagecheck_render(scene, probe_args, &probes, NULL)
        || !stagecheck_render(scene, adaptive_args, &adaptive, &adaptive_stats)) {
        CHECK(false);
    } else {
        double err_full = metrics_relmse(&full, &ref, NULL);
        double err_probes = metrics_relmse(&probes, &ref, NULL);
        double err_adaptive = metrics_relmse(&adaptive, &ref, NULL);
        double rays_full = stagecheck_stat(full_stats, "rays_shadow");
        double rays_adaptive = stagecheck_stat(adaptive_stats, "rays_shadow");
        double penumbra = stagecheck_stat(adaptive_stats, "penumbra_pixels");
        double error_ratio = err_adaptive / err_full;
        double rays_ratio = rays_adaptive / rays_full;
        printf(
            "relMSE: 144 rays %.3g, 16 rays %.3g, adaptive 16,128 %.3g\n",
            err_full,
            err_probes,
            err_adaptive);
        printf(
            "adaptive / full: error ratio %.3g, shadow-ray ratio %.3g; penumbra points %.0f\n",
            error_ratio,
            rays_ratio,
            penumbra);
        CHECK(stagecheck_stat(full_stats, "penumbra_pixels") == 0);
        CHECK(penumbra > 0);
        CHECK_MSG(rays_ratio < 0.6, "shadow-ray ratio %g", rays_ratio);
        CHECK_MSG(
            err_adaptive < 0.25 * err_probes,
            "adaptive %g, probes alone %g",
            err_adaptive,
            err_probes);
        CHECK_MSG(error_ratio < 6, "error ratio %g", error_ratio);
    }
    image_free(&ref);
    image_free(&full);
    image_free(&probes);
    image_free(&adaptive);
}

/* ---- The light as a surface ------------------------------------------------ */

/* The Cornell light (0.5 x 0.5 at height 2, facing down, radiance
 * (12, 10, 8)), a camera on its axis at height cam_y looking at height
 * look_y with a 60 degree field of view, 32x32, and optional extra lines. */
static bool
render_light_view(double cam_y, double look_y, const char *extra, struct image *img)
{
    const char *scene = stagecheck_scene(
        "light_view.scene",
        "camera origin 0 %.17g 0 target 0 %.17g 0 up 0 0 -1 fov 60\n"
        "image width 32 height 32\n"
        "material white diffuse albedo 0.8 0.8 0.8\n"
        "%s"
        "area_light corner -0.25 2 -0.25 edge1 0.5 0 0 edge2 0 0 0.5 radiance 12 10 8\n",
        cam_y,
        look_y,
        extra);
    const char *const args[] = {"-s", "1", NULL};
    return stagecheck_render(scene, args, img, NULL);
}

/* From 1 unit away with a 60 degree view the light spans film positions
 * 16 +- 16 * 0.25 / tan(30 deg) = 16 +- 6.93 on both axes: pixels 10..21
 * lie inside it, pixels 0..7 and 24..31 (on either axis) outside. */
static int
light_coverage(int px, int py)
{
    bool inside = px >= 10 && px <= 21 && py >= 10 && py <= 21;
    bool outside = px <= 7 || px >= 24 || py <= 7 || py >= 24;
    return inside ? 1 : outside ? -1 : 0;
}

static bool
is_light_radiance(const float *p)
{
    return p[0] == 12 && p[1] == 10 && p[2] == 8;
}

static bool
is_black(const float *p)
{
    return p[0] == 0 && p[1] == 0 && p[2] == 0;
}

static bool
is_lit(const float *p)
{
    return p[0] > 0.01f;
}

/* The pixels wholly inside the light that fail `inside`, plus those wholly
 * outside it that fail `outside` (pixels on its edge are not judged). */
static int
count_unexpected(
    const struct image *img,
    bool (*inside)(const float *),
    bool (*outside)(const float *))
{
    int wrong = 0;
    for (int py = 0; py < 32; py++) {
        for (int px = 0; px < 32; px++) {
            const float *p = image_pixel(img, px, py);
            int c = light_coverage(px, py);
            wrong += (c == 1 && !inside(p)) || (c == -1 && !outside(p));
        }
    }
    return wrong;
}

TEST(light_seen_from_the_front_has_radiance_l)
{
    struct image img = {0};
    /* From below, looking up; a floor, but nothing above the light. */
    if (!render_light_view(
            1,
            2,
            "quad corner -5 0 -5 edge1 0 0 10 edge2 10 0 0 material white\n",
            &img)) {
        CHECK(false);
        return;
    }
    int wrong = count_unexpected(&img, is_light_radiance, is_black);
    CHECK_MSG(wrong == 0, "%d pixels are not exactly L inside the light or 0 beside it", wrong);
    image_free(&img);
}

TEST(light_seen_from_behind_is_black)
{
    struct image img = {0};
    /* From above, looking down at its back, with the lit floor beyond. */
    if (!render_light_view(
            3,
            0,
            "quad corner -5 0 -5 edge1 0 0 10 edge2 10 0 0 material white\n",
            &img)) {
        CHECK(false);
        return;
    }
    int wrong = count_unexpected(&img, is_black, is_lit); /* the floor around it is lit */
    CHECK_MSG(wrong == 0, "%d pixels: back of the light not black, or floor not lit", wrong);
    image_free(&img);
}

TEST(nothing_behind_the_light_is_lit)
{
    /* A ceiling 1 above the light, seen from between the two: the light
     * emits downwards only, so every pixel is exactly 0.  The same light
     * turned over (edges swapped) must light it: the control. */
    static const char ceiling[] = "quad corner -5 3 -5 edge1 10 0 0 edge2 0 0 10 material white\n";
    struct image img = {0};
    if (!render_light_view(2.5, 3, ceiling, &img)) {
        CHECK(false);
        return;
    }
    double brightest = 0;
    for (int i = 0; i < 32 * 32 * 3; i++) {
        brightest = fmax(brightest, img.rgb[i]);
    }
    CHECK_MSG(brightest == 0, "brightest pixel %g", brightest);
    image_free(&img);

    const char *scene = stagecheck_scene(
        "light_up.scene",
        "camera origin 0 2.5 0 target 0 3 0 up 0 0 -1 fov 60\n"
        "image width 32 height 32\n"
        "material white diffuse albedo 0.8 0.8 0.8\n"
        "%s"
        "area_light corner -0.25 2 -0.25 edge1 0 0 0.5 edge2 0.5 0 0 radiance 12 10 8\n",
        ceiling);
    const char *const args[] = {"-s", "1", NULL};
    if (!stagecheck_render(scene, args, &img, NULL)) {
        CHECK(false);
        return;
    }
    CHECK(image_pixel(&img, 16, 16)[0] > 0.1f);
    image_free(&img);
}

/* ---- Irradiance from a polygon (T9) ----------------------------------------- */

/* Irradiance at the origin (normal +y) from a polygon of radiance L that
 * faces it and lies wholly above its horizon (stagecheck.h). */
static double
polygon_irradiance(double corners[][3], int n, double radiance)
{
    static const double origin[3] = {0, 0, 0};
    static const double normal[3] = {0, 1, 0};
    return stagecheck_polygon_irradiance(corners, n, origin, normal, radiance);
}

/* The estimates checked against a closed form: three rectangles, four
 * spheres. */
#define N_ESTIMATES 7

/* The mean over 8 seeds of 4096 shadow rays of the 1x1 scene's radiance
 * against `expected`: within Student's t of standard errors (plus the float
 * image's rounding, 2^-24) and, as a sanity bound, within 0.3%.  The SE
 * comes from 8 renders, 7 degrees of freedom: the t of the two-sided level
 * that keeps all N_ESTIMATES checks within alpha 0.01 (Sidak) is 5.08 (4.94
 * for the first six), where a normal bound of 4 failed 2 runs of 50 seed
 * offsets (at 4.0 and 4.2 standard errors: docs/calibration/README.md). */
static void
check_estimate(const char *scene, double expected, const char *what)
{
    struct stattest_welford w = {0};
    for (uint64_t k = 0; k < 8; k++) {
        stattest_welford_add(&w, render_mean(scene, "4096", first_seed() + k));
    }
    double se = sqrt(stattest_welford_var_of_mean(&w));
    double bound = stattest_t_critical(stattest_sidak(0.01, N_ESTIMATES), 7);
    printf(
        "radiance %.9g +- %.2g, %s %.9g (relative difference %.2g)\n",
        w.mean,
        se,
        what,
        expected,
        (w.mean - expected) / expected);
    CHECK_MSG(
        fabs(w.mean - expected) <= bound * se + 1e-6 * expected,
        "%.9g vs %.9g: %.2g standard errors, over %.2g",
        w.mean,
        expected,
        fabs(w.mean - expected) / se,
        bound);
    CHECK(fabs(w.mean - expected) <= 3e-3 * expected);
}

struct rect_light {
    double corner[3], edge1[3], edge2[3];
};

/* Estimate of the radiance of the floor point at the origin (albedo 0.5),
 * lit by one rectangle of radiance 1, over 8 seeds of 4096 shadow rays,
 * against 0.5/pi times Lambert's formula. */
static void
check_rectangle(const struct rect_light *light)
{
    const char *scene = stagecheck_scene(
        "polygon.scene",
        "camera origin 0.05 0.3 0.4 target 0 0 0 up 0 1 0 fov 0.001\n"
        "image width 1 height 1\n"
        "material floor diffuse albedo 0.5 0.5 0.5\n"
        "quad corner -5 0 -5 edge1 0 0 10 edge2 10 0 0 material floor\n"
        "area_light corner %.17g %.17g %.17g edge1 %.17g %.17g %.17g edge2 %.17g %.17g %.17g "
        "radiance 1 1 1\n",
        light->corner[0],
        light->corner[1],
        light->corner[2],
        light->edge1[0],
        light->edge1[1],
        light->edge1[2],
        light->edge2[0],
        light->edge2[1],
        light->edge2[2]);
    double corners[4][3];
    for (int k = 0; k < 3; k++) {
        corners[0][k] = light->corner[k];
        corners[1][k] = light->corner[k] + light->edge1[k];
        corners[2][k] = light->corner[k] + light->edge1[k] + light->edge2[k];
        corners[3][k] = light->corner[k] + light->edge2[k];
    }
    double expected = 0.5 / PI_D * polygon_irradiance(corners, 4, 1);
    check_estimate(scene, expected, "Lambert's formula");
}

TEST(rectangle_irradiance_matches_lambert_formula)
{
    static const struct rect_light lights[] = {
        /* Horizontal, off to one side, facing down. */
        {{0.2, 1.0, -0.3}, {0.5, 0, 0}, {0, 0, 0.4}},
        /* Tilted towards the point, to its left. */
        {{-0.6, 0.5, -0.4}, {0.3, 0.4, 0}, {0, 0.1, 0.5}},
        /* A long sliver low over the point: cos/r^2 varies strongly. */
        {{-1, 0.2, 0.1}, {2, 0, 0}, {0, 0, 0.05}},
    };
    for (int i = 0; i < 3; i++) {
        check_rectangle(&lights[i]);
    }
}

/* ---- Irradiance from a sphere light ---------------------------------------- */

/*
 * Irradiance at the origin (normal +y) from a sphere of radiance 1, centre
 * c and radius r: the integral of max(0, cos) over the cone of directions
 * it subtends, by the midpoint rule on n x n cells in (theta, phi) around
 * the axis, theta in [0, theta_max], with sin(theta) dtheta dphi the solid
 * angle of a cell.  Where the whole sphere is above the horizon this is
 * pi sin^2(theta_max) cos(alpha), alpha the angle between the normal and
 * the axis (the same as a point of intensity pi r^2 at the centre).
 */
static double
sphere_irradiance_quadrature(const double c[3], double r, int n)
{
    double d = sqrt(stagecheck_dot3(c, c));
    double axis[3] = {c[0] / d, c[1] / d, c[2] / d};
    /* Two unit vectors perpendicular to the axis. */
    double helper[3] = {fabs(axis[0]) < 0.9 ? 1 : 0, fabs(axis[0]) < 0.9 ? 0 : 1, 0};
    double s[3];
    double t[3];
    stagecheck_cross3(axis, helper, s);
    double ls = sqrt(stagecheck_dot3(s, s));
    for (int k = 0; k < 3; k++) {
        s[k] /= ls;
    }
    stagecheck_cross3(axis, s, t);
    double theta_max = asin(r / d);
    double sum = 0;
    for (int i = 0; i < n; i++) {
        double theta = (i + 0.5) * theta_max / n;
        for (int j = 0; j < n; j++) {
            double phi = (j + 0.5) * 2 * PI_D / n;
            double y = sin(theta) * (cos(phi) * s[1] + sin(phi) * t[1]) + cos(theta) * axis[1];
            sum += fmax(0, y) * sin(theta);
        }
    }
    return sum * (theta_max / n) * (2 * PI_D / n);
}

static const char *
sphere_light_scene(const double c[3], double r)
{
    return stagecheck_scene(
        "sphere.scene",
        "camera origin 0.05 0.3 0.4 target 0 0 0 up 0 1 0 fov 0.001\n"
        "image width 1 height 1\n"
        "material floor diffuse albedo 0.5 0.5 0.5\n"
        "quad corner -5 0 -5 edge1 0 0 10 edge2 10 0 0 material floor\n"
        "sphere_light center %.17g %.17g %.17g radius %.17g radiance 1 1 1\n",
        c[0],
        c[1],
        c[2],
        r);
}

TEST(sphere_light_irradiance_matches_closed_form)
{
    static const struct {
        double center[3], radius;
        bool above_horizon;
    } cases[] = {
        {{0, 2, 0}, 0.5, true}, /* overhead */
        {{1.5, 1, -0.5}, 0.4, true}, /* off to one side, tilted */
        {{1.2, 0.2, 0}, 0.5, false}, /* low: the horizon cuts it */
    };

    for (int i = 0; i < 3; i++) {
        const double *c = cases[i].center;
        double r = cases[i].radius;
        double d2 = stagecheck_dot3(c, c);
        double quadrature = sphere_irradiance_quadrature(c, r, 1000);
        double closed = PI_D * r * r / d2 * (c[1] / sqrt(d2));
        if (cases[i].above_horizon) {
            CHECK_NEAR(quadrature, closed, 1e-5 * closed); /* the test's own check */
        }
        double expected = 0.5 / PI_D * (cases[i].above_horizon ? closed : quadrature);
        const char *scene = sphere_light_scene(c, r);
        check_estimate(scene, expected, cases[i].above_horizon ? "closed form" : "quadrature");
        if (cases[i].above_horizon) {
            /* Adaptive mode: 4 unblocked probes take the closed form, with no
             * noise (4 samples alone would be off by about 1%).  Stages 06
             * and 07 place the camera sample anywhere in the pixel, 1e-5
             * units of floor: the irradiance there differs by about 5e-6. */
            const char *const args[] = {"-s", "1", "--adaptive", "4,16", NULL};
            struct image img = {0};
            CHECK(stagecheck_render(scene, args, &img, NULL));
            if (img.rgb) {
                CHECK_NEAR(img.rgb[0], expected, 1e-4 * expected);
                image_free(&img);
            }
        }
    }
}

/*
 * A sphere light cut by a black plane below its centre (smallpt's lamp,
 * which pokes through the ceiling): from the floor point below, the part
 * it sees is the cap under the plane, whose rim is a circle of radius a at
 * height p; where the rim lies below the circle of the sphere's outline
 * from the point (p < y_c - r^2 / y_c), the cap's projected solid angle is
 * the rim's disk's, so E = pi L a^2 / (p^2 + a^2).  Mitsuba 3.9.1 (LLVM)
 * renders this point 0.4-0.6% too bright (three seeds of a million
 * samples), and 2.3% where the cap is thinner (tests/bench/README.md).
 */
TEST(sphere_light_cut_by_a_plane_matches_closed_form)
{
    const double yc = 1.6, r = 0.7, p = 1.0; /* outline from the point: at y = 1.29 */
    double a2 = r * r - (yc - p) * (yc - p);
    const char *scene = stagecheck_scene(
        "cut_sphere.scene",
        "camera origin 0.05 0.3 0.4 target 0 0 0 up 0 1 0 fov 0.001\n"
        "image width 1 height 1\n"
        "material floor diffuse albedo 0.5 0.5 0.5\n"
        "material black diffuse albedo 0 0 0\n"
        "quad corner -5 0 -5 edge1 0 0 10 edge2 10 0 0 material floor\n"
        "quad corner -5 %.17g -5 edge1 10 0 0 edge2 0 0 10 material black\n"
        "sphere_light center 0 %.17g 0 radius %.17g radiance 1 1 1\n",
        p,
        yc,
        r);
    check_estimate(scene, 0.5 * a2 / (p * p + a2), "the cap's closed form");
}

TEST(sphere_light_seen_with_radiance_l_from_outside_black_inside)
{
    static const char *const views[] = {
        /* from outside, straight at its centre */
        "camera origin 0 1 5 target 0 1 0 up 0 1 0 fov 1\n",
        /* from inside, looking out */
        "camera origin 0 1 0.2 target 0 1 5 up 0 1 0 fov 60\n",
    };
    for (int i = 0; i < 2; i++) {
        const char *scene = stagecheck_scene(
            "sphere_view.scene",
            "%simage width 4 height 4\n"
            "sphere_light center 0 1 0 radius 0.5 radiance 12 10 8\n",
            views[i]);
        const char *const args[] = {"-s", "1", NULL};
        struct image img = {0};
        CHECK(stagecheck_render(scene, args, &img, NULL));
        int wrong = 0;
        for (int k = 0; img.rgb && k < 16; k++) {
            const float *p = img.rgb + 3 * k;
            wrong += i == 0 ? !(p[0] == 12 && p[1] == 10 && p[2] == 8)
                            : !(p[0] == 0 && p[1] == 0 && p[2] == 0);
        }
        CHECK_MSG(wrong == 0, "view %d: %d pixels wrong", i, wrong);
        image_free(&img);
    }
}

TEST_MAIN(
    TEST_ENTRY(one_shadow_ray_is_unbiased_in_the_penumbra),
    TEST_ENTRY(adaptive_sampling_saves_rays_where_the_probes_agree),
    TEST_ENTRY(light_seen_from_the_front_has_radiance_l),
    TEST_ENTRY(light_seen_from_behind_is_black),
    TEST_ENTRY(nothing_behind_the_light_is_lit),
    TEST_ENTRY(rectangle_irradiance_matches_lambert_formula),
    TEST_ENTRY(sphere_light_irradiance_matches_closed_form),
    TEST_ENTRY(sphere_light_cut_by_a_plane_matches_closed_form),
    TEST_ENTRY(sphere_light_seen_with_radiance_l_from_outside_black_inside))
