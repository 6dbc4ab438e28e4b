/*
 * 06_coverage.c - supersampled pixels are box-filtered averages over the
 * pixel's square (SCENES.md: "a sample at film position (x+u, y+v) counts
 * for pixel (x,y) only"), whatever the sampling pattern, from stage 06 on.
 *
 *  - Edge coverage (TESTING.md T19, T20): an area light of radiance 1 whose
 *    straight edge crosses the film at a known angle, against black.  A
 *    pixel's exact value is the area of its square the light covers
 *    (pathcheck_edge_coverage).  At 64 samples per pixel, jittered:
 *    pixels wholly inside are exactly 1, pixels wholly outside - the
 *    neighbours of edge pixels included - exactly 0 (no sample leaks to a
 *    neighbour: a box of one pixel), and over the pixels the edge crosses
 *    the error's mean is below 1% and passes a t-test for mean 0 (the
 *    estimator is unbiased), and the RMS error is at most that of 64
 *    independent uniform samples, sqrt(c (1 - c) / 64) (times 1.25 for the
 *    noise of the estimate over ~90 pixels).  A single pixel is not within
 *    1%: 64 jittered samples leave a per-pixel RMS error of about 0.016
 *    (one row of 8 strata straddles the edge, each a coin toss:
 *    sqrt(8 * 0.17) / 64), independent ones about 0.05.
 *  - Grid sampling needs a square number of samples: --aa grid --spp 8 is
 *    a command-line error (exit 2), 9 is fine.
 *  - Determinism with random sampling on (TESTING.md T26): -t 1 and -t 2
 *    give byte-identical PFMs, as do two runs with one seed; other seeds
 *    give other images whose means agree (Welch t-test).
 *
 * Every statistical test of the program shares alpha = 0.01, Sidak-
 * corrected for their number (N_STAT_TESTS).
 */
#include <string.h>

#include "check.h"
#include "pathcheck.h"
#include "stagecheck.h"
#include "stattest.h"
#include "testlib.h"

/* Three edges at unrelated angles, through points off the pixel grid.
 * Angles are of the normal, radians; none is a multiple of 45 degrees. */
static const struct pathcheck_edge edges[] = {
    {64, 31.37, 32.81, 0.4},
    {64, 30.52, 33.29, 1.9},
    {64, 33.11, 31.46, 4.1},
};
#define N_EDGES ((int)(sizeof edges / sizeof edges[0]))

/* Statistical tests in the program: one t-test per edge, and the image
 * means (3 channels) of two sets of seeds. */
#define N_STAT_TESTS (N_EDGES + 3)

static double
stat_level(void)
{
    return stattest_sidak(PATHCHECK_ALPHA, N_STAT_TESTS);
}

TEST(jittered_pixels_average_the_covered_area)
{
    uint64_t seed = pathcheck_seed(601);
    const char *const args[] = {"--spp", "64", "--aa", "jitter", NULL};
    for (int e = 0; e < N_EDGES; e++) {
        const struct pathcheck_edge *edge = &edges[e];
        const char *scene = pathcheck_edge_scene("edge.scene", edge);
        struct image img = {0};
        const char *stats = NULL;
        if (!scene || !pathcheck_render(scene, args, seed + (uint64_t)e, &img, &stats)) {
            CHECK(false);
            continue;
        }
        struct stattest_welford err = {0};
        double worst = 0;
        double iid_mse = 0; /* sum of c (1 - c) / 64: independent uniform samples */
        int bad_inside = 0;
        int bad_outside = 0;
        for (int y = 0; y < img.height; y++) {
            for (int x = 0; x < img.width; x++) {
                double cover = pathcheck_edge_coverage(edge, x, y);
                const float *p = image_pixel(&img, x, y);
                if (cover == 0) {
                    bad_outside += p[0] != 0 || p[1] != 0 || p[2] != 0;
                } else if (cover == 1) {
                    bad_inside += fabs(p[0] - 1) > 1e-6 || p[1] != p[0] || p[2] != p[0];
                } else {
                    double d = p[0] - cover;
                    iid_mse += cover * (1 - cover) / 64;
                    stattest_welford_add(&err, d);
                    worst = fmax(worst, fabs(d));
                }
            }
        }
        struct stattest_result t = stattest_t_test_welford_one_sample(&err, 0);
        double rms = sqrt(err.m2 / (double)err.n + err.mean * err.mean);
        double rms_iid = sqrt(iid_mse / (double)err.n);
        printf(
            "edge %d (normal %.2f rad): %lld edge pixels, mean error %+.5f, RMS %.4f "
            "(independent samples: %.4f), max %.4f, t = %.2f, p = %.3g (level %.3g)\n",
            e,
            edge->angle,
            (long long)err.n,
            err.mean,
            rms,
            rms_iid,
            worst,
            t.t,
            t.p,
            stat_level());
        CHECK_MSG(err.n > 64, "only %lld edge pixels", (long long)err.n);
        CHECK_MSG(bad_inside == 0, "%d covered pixels differ from 1", bad_inside);
        CHECK_MSG(bad_outside == 0, "%d uncovered pixels are not black", bad_outside);
        CHECK_MSG(fabs(err.mean) < 0.01, "mean error %.4f over the edge pixels", err.mean);
        CHECK_MSG(t.p >= stat_level(), "biased: p = %.3g", t.p);
        CHECK_MSG(rms < 1.25 * rms_iid, "RMS error %.4f: fewer than 64 samples' worth", rms);
        CHECK(stagecheck_stat(stats, "nan_pixels") == 0);
        image_free(&img);
    }
}

TEST(grid_needs_a_square_sample_count)
{
    const char *edge = pathcheck_edge_scene("grid.scene", &edges[0]);
    const char *out = test_tmp_path("grid.pfm");
    char log[4096];
    const char *const bad[] = {"-o", out, "--aa", "grid", "--spp", "8", NULL};
    remove(out);
    int status = test_render(edge, bad, log, sizeof log);
    printf("--aa grid --spp 8: exit %d: %s", status, log);
    CHECK_MSG(status == 2, "exit %d", status);
    CHECK(strstr(log, "grid") != NULL);
    CHECK(!test_file_exists(out));
    const char *const good[] = {"-o", out, "--aa", "grid", "--spp", "9", NULL};
    status = test_render(edge, good, log, sizeof log);
    CHECK_MSG(status == 0, "--aa grid --spp 9: exit %d: %s", status, log);
    CHECK(test_file_exists(out));
}

/* Render the soft-shadowed Cornell box at 64x64 with random sampling (the
 * area light's shadow rays and the camera's jitter) to `name`. */
static bool
render_to(const char *name, const char *threads, const char *seed)
{
    const char *stats = test_tmp_path("determinism.json");
    const char *const args[] = {
        "-o",
        test_tmp_path(name),
        "-W",
        "64",
        "-H",
        "64",
        "--spp",
        "8",
        "-t",
        threads,
        "--seed",
        seed,
        "--stats",
        stats,
        NULL};
    char log[4096];
    int status =
        test_render(test_root_path("scenes/cornell_diffuse_area.scene"), args, log, sizeof log);
    if (status != 0) {
        printf("render failed with status %d: %s\n", status, log);
    }
    CHECK(status != 0 || stagecheck_stat(stats, "nan_pixels") == 0);
    return status == 0;
}

TEST(sampling_is_deterministic)
{
    bool ok = render_to("t1.pfm", "1", "7") && render_to("t2.pfm", "2", "7")
              && render_to("t2again.pfm", "2", "7") && render_to("seed8.pfm", "2", "8");
    CHECK(ok);
    if (!ok) {
        return;
    }
    CHECK_MSG(
        test_same_file(test_tmp_path("t1.pfm"), test_tmp_path("t2.pfm")),
        "-t 1 and -t 2 differ");
    CHECK_MSG(
        test_same_file(test_tmp_path("t2.pfm"), test_tmp_path("t2again.pfm")),
        "the same seed twice differs");
    CHECK_MSG(
        !test_same_file(test_tmp_path("t2.pfm"), test_tmp_path("seed8.pfm")),
        "seeds 7 and 8 give the same image: the seed is ignored");
}

TEST(other_seeds_give_the_same_image_mean)
{
    /* Two sets of 4 seeds; their image means must agree (Welch t-test on
     * each channel: one block the size of the image). */
    uint64_t seed = pathcheck_seed(601);
    const char *scene = test_root_path("scenes/cornell_diffuse_area.scene");
    const char *const args[] = {"-W", "64", "-H", "64", "--spp", "8", NULL};
    struct pathcheck_batches a;
    struct pathcheck_batches b;
    if (!pathcheck_render_batches(scene, args, 4, seed + 100, &a)) {
        CHECK(false);
        return;
    }
    if (!pathcheck_render_batches(scene, args, 4, seed + 200, &b)) {
        CHECK(false);
        pathcheck_batches_free(&a);
        return;
    }
    struct pathcheck_tally t = pathcheck_tally_start();
    CHECK(pathcheck_block_welch(a.images, a.k, b.images, b.k, 64, stat_level(), &t));
    printf(
        "image means of seeds %llu.. and %llu..: %zu tests, min p %.3g, %zu rejected "
        "(level %.3g)\n",
        (unsigned long long)seed + 100,
        (unsigned long long)seed + 200,
        t.tests,
        t.min_p,
        t.rejected,
        stat_level());
    CHECK(t.tests == 3);
    CHECK(t.rejected == 0);
    CHECK(a.nan_pixels == 0 && b.nan_pixels == 0);
    pathcheck_batches_free(&a);
    pathcheck_batches_free(&b);
}

TEST_MAIN(
    TEST_ENTRY(jittered_pixels_average_the_covered_area),
    TEST_ENTRY(grid_needs_a_square_sample_count),
    TEST_ENTRY(sampling_is_deterministic),
    TEST_ENTRY(other_seeds_give_the_same_image_mean))
