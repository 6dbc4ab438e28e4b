/*
 * 06_aa_patterns.c - the three camera sampling patterns of --aa do what
 * stage 06 says they do (render.c and render.h: grid, the centres of the
 * cells of a grid over the pixel; jitter, a uniform point in each cell;
 * adaptive, a few jittered probes and all spp samples only where they
 * disagree), in every stage that offers --aa.  From stage 07 on a render
 * is made of passes of at most 16 samples, each pass a pattern of its own
 * (grid -s 64: four passes of one 4x4 grid); the pattern checks of grid
 * and jitter then take the spp of one pass (1, 4, 9, 16).  (Stage 08's
 * Sobol sampler leaves the pixel positions to the pattern.)
 *
 *  - Stratification (TESTING.md T19, Mitchell, "Consequences of Stratified
 *    Sampling in Graphics", SIGGRAPH 96): on pixels crossed by a straight
 *    edge, the mean squared error of jittered sampling falls about as
 *    N^-1.5, faster than the N^-1 of independent samples.  Measured over
 *    spp 4, 16, 64, 256 (from 07 on 1, 4, 9, 16) and 8 seeds; the fitted
 *    log-log slope must be below -1.3.
 *  - Two seeds give uncorrelated errors (jitter) and an unbiased image.
 *  - Grid: with --aa grid --spp k^2 (k = 4, 5, 8, 12; from 07 on, one
 *    pass: 3, 4) a pixel is exactly the fraction of its k^2 cell centres
 *    ((i + 1/2) / k, (j + 1/2) / k) the light covers.
 *  - Aliasing: a checkerboard finer than the grid's sample spacing
 *    (squares of 0.127 pixel; grid samples 0.25 pixel apart at 16 spp).
 *    The grid samples it at nearly the same phase in every pixel and beats
 *    against it: a moire of period ~16 pixels and amplitude up to half the
 *    contrast.  Jitter turns that into fine-grained noise.  The
 *    low-frequency error - the RMS over 8x8 blocks of the block mean minus
 *    the true mean - must be at least 4 times larger for the grid.
 *  - Adaptive (stage 06; stage 07 below): --aa adaptive --spp 64 refines
 *    some pixels but not all
 *    (aa_refined_pixels), only pixels the edge crosses (a pixel left alone
 *    has 4 agreeing probes: exactly 0 or 1), spends 4 + 60 camera rays on
 *    those and 4 on the others (under 20% of full sampling's), is within
 *    2x of full sampling's error on the refined pixels, and beats uniform
 *    jittered sampling at a similar cost (4 spp) over the whole image.
 *    It does not match full sampling over the whole image: 4 probes miss
 *    pixels the light covers only a sliver of (measured RMS error 0.012,
 *    full 64 spp 0.0023, uniform 4 spp 0.018).
 *  - Adaptive in stage 07: each pass of 16 probes 4 samples and refines on
 *    its own, so aa_refined_pixels counts pixel-passes: camera rays are
 *    4 per pixel per pass plus 12 per refined pixel-pass, no more pixels
 *    lie strictly between 0 and 1 than were refined, and the refined
 *    pixel-passes are a small part of all.  The error claims of stage 06
 *    do not carry over (a pixel refined in one pass only keeps the 0-or-1
 *    estimates of its other passes) and are printed, not checked.
 */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "course.h"
#include "pathcheck.h"
#include "stagecheck.h"
#include "testlib.h"

static const struct pathcheck_edge edge = {64, 31.37, 32.81, 0.4};

/* Mean squared error over the pixels the edge crosses (0 < c < 1); their
 * number in *n. */
static double
edge_mse(const struct image *img, const struct pathcheck_edge *e, int *n)
{
    double sum = 0;
    *n = 0;
    for (int y = 0; y < img->height; y++) {
        for (int x = 0; x < img->width; x++) {
            double c = pathcheck_edge_coverage(e, x, y);
            if (c > 0 && c < 1) {
                double d = image_pixel(img, x, y)[0] - c;
                sum += d * d;
                (*n)++;
            }
        }
    }
    return sum / *n;
}

/* The log-log slope of the edge pixels' MSE against spp (4 to 256, 8
 * seeds; for grid and jitter from stage 07 on, whose patterns are a pass's,
 * 1 to 16) with --aa pattern; the MSE at the largest spp in *mse_last. */
static double
edge_error_slope(const char *pattern, double *mse_last)
{
    static const int all_passes[] = {4, 16, 64, 256};
    static const int one_pass[] = {1, 4, 9, 16};
    bool per_pass = atoi(STAGE_NAME) >= 7;
    const int *spps = per_pass ? one_pass : all_passes;

    enum {
        N_SPP = 4,
        N_SEEDS = 8
    };

    const char *scene = pathcheck_edge_scene("edge.scene", &edge);
    uint64_t seed = pathcheck_seed(602);
    double lx[N_SPP];
    double ly[N_SPP];
    for (int i = 0; i < N_SPP; i++) {
        char spp[16];
        snprintf(spp, sizeof spp, "%d", spps[i]);
        const char *const args[] = {"--aa", pattern, "--spp", spp, NULL};
        struct pathcheck_batches b;
        if (!scene || !pathcheck_render_batches(scene, args, N_SEEDS, seed, &b)) {
            CHECK(false);
            return 0;
        }
        double mse = 0;
        int n = 0;
        for (int k = 0; k < b.k; k++) {
            mse += edge_mse(&b.images[k], &edge, &n) / b.k;
        }
        *mse_last = mse;
        printf(
            "--aa %s, spp %3d: MSE over %d edge pixels and %d seeds %.3g (spp * MSE %.3g)\n",
            pattern,
            spps[i],
            n,
            N_SEEDS,
            mse,
            mse * spps[i]);
        CHECK(b.nan_pixels == 0);
        lx[i] = log((double)spps[i]);
        ly[i] = log(mse);
        pathcheck_batches_free(&b);
    }
    /* Least-squares slope of log MSE against log spp. */
    double mx = 0;
    double my = 0;
    for (int i = 0; i < N_SPP; i++) {
        mx += lx[i] / N_SPP;
        my += ly[i] / N_SPP;
    }
    double sxy = 0;
    double sxx = 0;
    for (int i = 0; i < N_SPP; i++) {
        sxy += (lx[i] - mx) * (ly[i] - my);
        sxx += (lx[i] - mx) * (lx[i] - mx);
    }
    return sxy / sxx;
}

/* Jittered samples (about N^-1.5 for a discontinuity along a line): on
 * edge pixels their error falls faster than independent samples'. */
TEST(jitter_errors_fall_faster_than_independent_samples)
{
    double mse_jitter = NAN; /* set unless the renders failed */
    double slope_jitter = edge_error_slope("jitter", &mse_jitter);
    printf(
        "log-log slope of the edge pixels' MSE: jitter %.3f (independent samples: -1; "
        "stratified: about -1.5; limit -1.3); MSE at the largest spp %.3g\n",
        slope_jitter,
        mse_jitter);
    CHECK_MSG(
        slope_jitter < -1.3,
        "slope %.3f: the jittered samples are not stratified",
        slope_jitter);
}

/* Two seeds give independent jitter patterns: on a 128x128 edge, the
 * errors of the two renders over the edge pixels are uncorrelated (a
 * correlation below 4 standard errors, 4 / sqrt(n)), while each is an
 * unbiased estimate (mean error within 4 standard errors of 0). */
TEST(renders_with_two_seeds_are_uncorrelated)
{
    static const struct pathcheck_edge big = {128, 60.37, 65.81, 0.7};
    const char *scene = pathcheck_edge_scene("edge128.scene", &big);
    const char *pattern = "jitter";
    const char *const args[] = {"--aa", pattern, "--spp", "16", NULL};
    struct image a = {0};
    struct image b = {0};
    const char *stats_a = NULL;
    const char *stats_b = NULL;
    uint64_t seed = pathcheck_seed(603);
    if (!scene || !pathcheck_render(scene, args, seed, &a, &stats_a)
        || !pathcheck_render(scene, args, seed + 1, &b, &stats_b)) {
        CHECK(false);
        image_free(&a);
        return;
    }
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    int n = 0;
    for (int y = 0; y < big.size; y++) {
        for (int x = 0; x < big.size; x++) {
            double c = pathcheck_edge_coverage(&big, x, y);
            if (c > 0 && c < 1) {
                double ea = image_pixel(&a, x, y)[0] - c;
                double eb = image_pixel(&b, x, y)[0] - c;
                sa += ea;
                sb += eb;
                saa += ea * ea;
                sbb += eb * eb;
                sab += ea * eb;
                n++;
            }
        }
    }
    double cov = sab / n - (sa / n) * (sb / n);
    double va = saa / n - (sa / n) * (sa / n);
    double vb = sbb / n - (sb / n) * (sb / n);
    double r = cov / sqrt(va * vb);
    double se_mean = sqrt(va / n);
    printf(
        "--aa %s --spp 16, seeds %llu and %llu: %d edge pixels, correlation of their errors "
        "%.3f (limit %.3f); mean error %.2g (standard error %.2g)\n",
        pattern,
        (unsigned long long)seed,
        (unsigned long long)(seed + 1),
        n,
        r,
        4 / sqrt(n),
        sa / n,
        se_mean);
    CHECK(n > 100);
    CHECK_MSG(va > 0 && vb > 0, "a render without noise");
    CHECK_MSG(fabs(r) < 4 / sqrt(n), "correlation %.3f between two seeds", r);
    CHECK_MSG(fabs(sa / n) < 4 * se_mean, "mean error %.3g", sa / n);
    image_free(&a);
    image_free(&b);
}

/* One --aa grid render at spp k^2: every pixel is exactly the fraction of
 * the k x k cell centres inside the edge's light. */
static void
check_grid(int k)
{
    const char *scene = pathcheck_edge_scene("edge.scene", &edge);
    char spp[16];
    snprintf(spp, sizeof spp, "%d", k * k);
    const char *const args[] = {"--aa", "grid", "--spp", spp, NULL};
    struct image img = {0};
    const char *stats = NULL;
    if (!scene || !pathcheck_render(scene, args, 1, &img, &stats)) {
        CHECK(false);
        return;
    }
    int wrong = 0;
    int partial = 0;
    double worst = 0;
    for (int y = 0; y < img.height; y++) {
        for (int x = 0; x < img.width; x++) {
            int inside = 0;
            for (int j = 0; j < k; j++) {
                for (int i = 0; i < k; i++) {
                    inside += pathcheck_edge_inside(&edge, x + (i + 0.5) / k, y + (j + 0.5) / k);
                }
            }
            double d = fabs(image_pixel(&img, x, y)[0] - inside / (double)(k * k));
            worst = fmax(worst, d);
            wrong += d > 1e-6;
            partial += inside > 0 && inside < k * k;
        }
    }
    printf(
        "--aa grid --spp %d: %d pixels differ from their covered cell-centre fraction "
        "(largest difference %.4f); %d pixels partly covered\n",
        k * k,
        wrong,
        worst,
        partial);
    CHECK(partial > 50);
    CHECK_MSG(wrong == 0, "%d pixels are not sampled at the %dx%d cell centres", wrong, k, k);
    CHECK(stagecheck_stat(stats, "rays_camera") == (double)k * k * img.width * img.height);
    CHECK(stagecheck_stat(stats, "nan_pixels") == 0);
    image_free(&img);
}

TEST(grid_samples_the_cell_centres)
{
    static const int all_passes[] = {4, 5, 8, 12};
    static const int one_pass[] = {3, 4};
    bool per_pass = atoi(STAGE_NAME) >= 7;
    const int *sides = per_pass ? one_pass : all_passes;
    for (int i = 0; i < (per_pass ? 2 : 4); i++) {
        check_grid(sides[i]);
    }
}

/* A checkerboard plane filling the view of a 64x64 camera, one scene unit
 * per pixel (fov 90 at distance 32), squares of 0.127 units, albedos 0.9
 * and 0.1.  Lit so that a square's radiance is its albedo in every stage:
 * a point light 1e5 units away on the axis, behind the camera, of
 * intensity pi 1e10, so E = I cos / r^2 = pi (to 3e-7 over the view) and
 * L = albedo / pi E = albedo.  Direct light only, the same in the Whitted
 * stages and in the path tracer (the plane sees only a black sky): the
 * pattern the camera samples does not depend on stage 07's own lab (BSDF
 * sampling), whose stubs end every path at its first hit. */
static const char checker_scene[] =
    "camera origin 0 0 0 target 0 0 -1 up 0 1 0 fov 90\n"
    "image width 64 height 64\n"
    "material board checker albedo 0.9 0.9 0.9 albedo2 0.1 0.1 0.1 size 0.127\n"
    "quad corner -100 -100 -32 edge1 200 0 0 edge2 0 200 0 material board\n"
    "point_light position 0 0 99968 intensity 31415926535.897932 31415926535.897932 "
    "31415926535.897932\n";

#define CHECKER_MEAN 0.5 /* (0.9 + 0.1) / 2 */

/* RMS over 8x8 blocks of (block mean - CHECKER_MEAN).  A block spans 63
 * squares a side, so its true mean is CHECKER_MEAN to within
 * 0.4 * 0.127^2 / 64 = 1e-4. */
static double
low_frequency_error(const struct image *img)
{
    double sum = 0;
    int n = 0;
    for (int y = 0; y < img->height; y += 8) {
        for (int x = 0; x < img->width; x += 8) {
            double d = stagecheck_region_mean(img, x, y, 8, 8, 0) - CHECKER_MEAN;
            sum += d * d;
            n++;
        }
    }
    return sqrt(sum / n);
}

TEST(grid_aliases_where_jitter_does_not)
{
    const char *scene = stagecheck_scene("checker.scene", "%s", checker_scene);
    const char *const grid_args[] = {"--aa", "grid", "--spp", "16", NULL};
    const char *const jitter_args[] = {"--aa", "jitter", "--spp", "16", NULL};
    struct image grid = {0};
    struct image jitter = {0};
    const char *grid_stats = NULL;
    const char *jitter_stats = NULL;
    uint64_t seed = pathcheck_seed(602);
    if (!scene || !pathcheck_render(scene, grid_args, seed, &grid, &grid_stats)
        || !pathcheck_render(scene, jitter_args, seed, &jitter, &jitter_stats)) {
        CHECK(false);
        image_free(&grid);
        return;
    }
    double e_grid = low_frequency_error(&grid);
    double e_jitter = low_frequency_error(&jitter);
    double mean_grid[3];
    double mean_jitter[3];
    metrics_mean(&grid, NULL, mean_grid);
    metrics_mean(&jitter, NULL, mean_jitter);
    /* Jitter's expected block error: 16 strata each a coin toss between
     * 0.9 and 0.1 (sd 0.4), 64 pixels: 0.4 / sqrt(16 * 64) = 0.0125. */
    printf(
        "fine checker, 16 spp: low-frequency (8x8 block) RMS error: grid %.4f, jitter %.4f "
        "(noise alone: about 0.0125); image mean: grid %.4f, jitter %.4f (true 0.5)\n",
        e_grid,
        e_jitter,
        mean_grid[0],
        mean_jitter[0]);
    printf(
        "the grid's error is %s than jitter's: %s\n",
        e_grid > e_jitter ? "larger" : "smaller",
        e_grid > 4 * e_jitter ? "aliasing (moire)" : "no clear moire");
    CHECK_MSG(e_grid > 4 * e_jitter, "grid %.4f, jitter %.4f", e_grid, e_jitter);
    CHECK_MSG(e_jitter < 0.03, "jittered blocks off by %.4f: not noise alone", e_jitter);
    CHECK(stagecheck_stat(grid_stats, "nan_pixels") == 0);
    CHECK(stagecheck_stat(jitter_stats, "nan_pixels") == 0);
    image_free(&grid);
    image_free(&jitter);
}

/* Squared error against the exact coverage, summed over all pixels and
 * over the pixels strictly between 0 and 1 (*sum_mixed, their number in
 * *n_mixed). */
static double
coverage_sq_error(
    const struct image *img,
    const struct pathcheck_edge *e,
    double *sum_mixed,
    int *n_mixed)
{
    double sum = 0;
    for (int y = 0; y < img->height; y++) {
        for (int x = 0; x < img->width; x++) {
            double v = image_pixel(img, x, y)[0];
            double d = v - pathcheck_edge_coverage(e, x, y);
            sum += d * d;
            if (v > 0 && v < 1) {
                *sum_mixed += d * d;
                (*n_mixed)++;
            }
        }
    }
    return sum;
}

TEST(adaptive_refines_only_the_edge)
{
    /* Four seeds of adaptive sampling at 64 spp, of full jittered sampling
     * at 64 spp, and of jittered sampling at 4 spp (fewer camera rays than
     * adaptive spends). */
    enum {
        SEEDS = 4,
        PROBES = 4
    };

    /* Stage 07 renders 64 spp as 4 passes of 16, each adaptive on its own. */
    bool per_pass = course_stage_number(STAGE_NAME) >= 7;
    int passes = per_pass ? 4 : 1;
    int pass_spp = 64 / passes;

    const char *scene = pathcheck_edge_scene("edge.scene", &edge);
    const char *const modes[3][5] = {
        {"--aa", "adaptive", "--spp", "64", NULL},
        {"--aa", "jitter", "--spp", "64", NULL},
        {"--aa", "jitter", "--spp", "4", NULL},
    };
    double mse[3] = {0, 0, 0};
    double rays[3] = {0, 0, 0};
    double mixed_adaptive = 0; /* squared error over the pixels adaptive refined */
    double mixed_full = 0; /* full jitter's over the same pixels */
    double refined = 0;
    int n_mixed = 0; /* pixels strictly between 0 and 1 in the adaptive renders */
    double pixels = (double)edge.size * edge.size;
    int n_edge = 0;
    uint64_t seed = pathcheck_seed(602);
    for (int s = 0; s < SEEDS; s++) {
        struct image img[3] = {{0}, {0}, {0}};
        const char *stats[3] = {NULL, NULL, NULL};
        bool ok = scene != NULL;
        for (int m = 0; m < 3 && ok; m++) {
            ok = pathcheck_render(scene, modes[m], seed + (uint64_t)s, &img[m], &stats[m]);
        }
        if (!ok) {
            CHECK(false);
            for (int m = 0; m < 3; m++) {
                image_free(&img[m]);
            }
            return;
        }
        /* A pixel adaptive sampling left alone has 4 agreeing probes, so it
         * is exactly 0 or 1; a refined one saw both sides. */
        int n_refined = 0;
        double ignored = 0;
        int ignored_n = 0;
        double sum_a = coverage_sq_error(&img[0], &edge, &mixed_adaptive, &n_refined);
        double r = stagecheck_stat(stats[0], "aa_refined_pixels");
        CHECK_MSG(
            per_pass ? n_refined <= r : n_refined == r,
            "%d pixels between 0 and 1, %.0f refined",
            n_refined,
            r);
        n_mixed += n_refined;
        /* Full jitter's error on the pixels adaptive refined. */
        for (int y = 0; y < edge.size; y++) {
            for (int x = 0; x < edge.size; x++) {
                double v = image_pixel(&img[0], x, y)[0];
                if (v > 0 && v < 1) {
                    double d = image_pixel(&img[1], x, y)[0] - pathcheck_edge_coverage(&edge, x, y);
                    mixed_full += d * d;
                }
            }
        }
        mse[0] += sum_a / pixels / SEEDS;
        mse[1] += coverage_sq_error(&img[1], &edge, &ignored, &ignored_n) / pixels / SEEDS;
        mse[2] += coverage_sq_error(&img[2], &edge, &ignored, &ignored_n) / pixels / SEEDS;
        for (int m = 0; m < 3; m++) {
            rays[m] += stagecheck_stat(stats[m], "rays_camera") / SEEDS;
            CHECK(stagecheck_stat(stats[m], "nan_pixels") == 0);
        }
        refined += r / SEEDS;
        CHECK_MSG(
            r > 0 && r < 0.1 * passes * pixels,
            "seed %d: %.0f of %.0f pixel-passes refined",
            s,
            r,
            passes * pixels);
        CHECK_MSG(
            stagecheck_stat(stats[0], "rays_camera")
                == PROBES * passes * pixels + (pass_spp - PROBES) * r,
            "seed %d: %.0f camera rays for %.0f refined pixels",
            s,
            stagecheck_stat(stats[0], "rays_camera"),
            r);
        edge_mse(&img[0], &edge, &n_edge);
        for (int m = 0; m < 3; m++) {
            image_free(&img[m]);
        }
    }
    double rms_refined_a = sqrt(mixed_adaptive / n_mixed);
    double rms_refined_j = sqrt(mixed_full / n_mixed);
    printf(
        "adaptive 64 spp: %.1f of %.0f pixels refined on average (%d crossed by the edge)\n",
        refined,
        pixels,
        n_edge);
    printf(
        "  camera rays: adaptive %.0f, jitter 64 spp %.0f, jitter 4 spp %.0f\n",
        rays[0],
        rays[1],
        rays[2]);
    printf(
        "  RMS error over all pixels: adaptive %.4f, jitter 64 spp %.4f, jitter 4 spp %.4f\n",
        sqrt(mse[0]),
        sqrt(mse[1]),
        sqrt(mse[2]));
    printf(
        "  RMS error over the refined pixels: adaptive %.4f, jitter 64 spp %.4f\n",
        rms_refined_a,
        rms_refined_j);
    printf("  (the 4 jittered probes miss edge pixels the light covers only a sliver of: "
           "there adaptive keeps an error of up to the sliver's area)\n");
    if (per_pass) {
        printf("  (passes refined on their own: the error claims of a single pass are not "
               "checked)\n");
        CHECK_MSG(
            rays[0] < 0.4 * rays[1],
            "%.0f camera rays, full sampling %.0f",
            rays[0],
            rays[1]);
        return;
    }
    CHECK_MSG(refined >= 0.3 * n_edge, "only %.1f of %d edge pixels refined", refined, n_edge);
    CHECK_MSG(rays[0] < 0.2 * rays[1], "%.0f camera rays, full sampling %.0f", rays[0], rays[1]);
    /* Refined pixels are as good as full sampling (64 samples, 60 of them
     * in a 7x7 jittered grid plus 11 unstratified: slightly noisier than
     * the 8x8 grid). */
    CHECK_MSG(
        rms_refined_a < 2 * rms_refined_j,
        "refined pixels: RMS %.4f, full jitter %.4f",
        rms_refined_a,
        rms_refined_j);
    /* Overall it beats spending about as many rays evenly (4 spp). */
    CHECK_MSG(mse[0] < mse[2], "adaptive MSE %.3g, jitter at 4 spp %.3g", mse[0], mse[2]);
}

TEST_MAIN(
    TEST_ENTRY(jitter_errors_fall_faster_than_independent_samples),
    TEST_ENTRY(renders_with_two_seeds_are_uncorrelated),
    TEST_ENTRY(grid_samples_the_cell_centres),
    TEST_ENTRY(grid_aliases_where_jitter_does_not),
    TEST_ENTRY(adaptive_refines_only_the_edge))
