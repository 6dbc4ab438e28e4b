/*
 * 06-06_reference_point.c - the point-light Cornell box against Mitsuba 3's
 * direct-light reference (tests/reference/cornell_diffuse_point_direct.pfm)
 * over EVERY pixel, edges and shadow boundaries included.
 *
 * 02-05_reference_point compares only the reference's smooth pixels,
 * because one ray through the pixel centre cannot match a pixel average at
 * an edge.  Stage 06 averages 64 jittered samples over the pixel's square
 * (SCENES.md's box filter), so the whole image must agree: relMSE < 1e-3
 * (measured 6.9e-6; one sample at the pixel centre gives 1.6e-3, which the
 * test also checks, so it can fail).  Adaptive sampling at 64 spp must stay
 * below the limit too (measured 2.6e-4) with under half the camera rays
 * (measured 14%).  Only stage 06: stage 07 renders global illumination, which this
 * reference leaves out.
 */
#include "check.h"
#include "metrics.h"
#include "pathcheck.h"
#include "stagecheck.h"
#include "testlib.h"

#define MAX_RELMSE 1e-3

/* Render the scene with `args`, compare every pixel with the reference;
 * returns relMSE (NaN on failure) and the camera rays in *rays. */
static double
relmse_all_pixels(const struct image *ref, const char *const args[], const char *what, double *rays)
{
    struct image img = {0};
    const char *stats = NULL;
    const char *scene = test_root_path("scenes/cornell_diffuse_point.scene");
    if (!pathcheck_render(scene, args, pathcheck_seed(606), &img, &stats)) {
        return NAN;
    }
    struct metrics m;
    struct diag err;
    if (!metrics_compare(&img, ref, NULL, &m, &err)) {
        diag_print(stdout, &err, "error");
        image_free(&img);
        return NAN;
    }
    *rays = stagecheck_stat(stats, "rays_camera");
    printf(
        "%-22s relMSE over all %zu pixels %.3g, %zu non-finite, %.0f camera rays, "
        "%.0f refined\n",
        what,
        m.n_pixels,
        m.relmse,
        m.n_nonfinite,
        *rays,
        stagecheck_stat(stats, "aa_refined_pixels"));
    CHECK(m.n_nonfinite == 0);
    CHECK(stagecheck_stat(stats, "nan_pixels") == 0);
    image_free(&img);
    return m.relmse;
}

TEST(supersampled_cornell_matches_mitsuba_everywhere)
{
    struct image ref = {0};
    if (!stagecheck_reference("cornell_diffuse_point_direct", &ref)) {
        CHECK(false);
        return;
    }
    const char *const one[] = {"--spp", "1", "--aa", "grid", NULL};
    const char *const jitter[] = {"--spp", "64", "--aa", "jitter", NULL};
    const char *const adaptive[] = {"--spp", "64", "--aa", "adaptive", NULL};
    double rays_one;
    double rays_jitter;
    double rays_adaptive;
    double r_one = relmse_all_pixels(&ref, one, "1 sample (centre):", &rays_one);
    double r_jitter = relmse_all_pixels(&ref, jitter, "jitter, 64 spp:", &rays_jitter);
    double r_adaptive = relmse_all_pixels(&ref, adaptive, "adaptive, 64 spp:", &rays_adaptive);
    printf(
        "limit %g; adaptive uses %.1f%% of the camera rays\n",
        MAX_RELMSE,
        100 * rays_adaptive / rays_jitter);
    CHECK_MSG(r_jitter < MAX_RELMSE, "jitter: relMSE %.3g", r_jitter);
    /* The test can fail: pixel-centre sampling is far off at the edges. */
    CHECK_MSG(r_one > 10 * r_jitter, "one sample %.3g, 64 jittered %.3g", r_one, r_jitter);
    CHECK_MSG(r_adaptive < MAX_RELMSE, "adaptive: relMSE %.3g", r_adaptive);
    CHECK_MSG(rays_adaptive < 0.5 * rays_jitter, "adaptive: %.0f camera rays", rays_adaptive);
    image_free(&ref);
}

TEST_MAIN(TEST_ENTRY(supersampled_cornell_matches_mitsuba_everywhere))
