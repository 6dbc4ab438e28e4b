/*
 * test_metrics.c - image error metrics (tests/lib/metrics.c) on synthetic
 * images whose answers are known by hand: identical images, constant
 * offsets, single bad pixels, an edge for the smooth mask, and block
 * and window statistics of renders with known noise.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "estimate.h"
#include "image.h"
#include "metrics.h"
#include "rng.h"
#include "stattest.h"

/* A w x h image with every pixel (r, g, b); aborts the test on failure. */
static struct image
constant_image(int w, int h, float r, float g, float b)
{
    struct image img = {0};
    if (!image_alloc(&img, w, h, NULL)) {
        printf("image_alloc failed\n");
        exit(1);
    }
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            float *p = image_pixel(&img, x, y);
            p[0] = r;
            p[1] = g;
            p[2] = b;
        }
    }
    return img;
}

static void
set_pixel(struct image *img, int x, int y, float v)
{
    float *p = image_pixel(img, x, y);
    p[0] = p[1] = p[2] = v;
}

TEST(identical_images_give_zero)
{
    struct image r = constant_image(7, 5, 0.3f, 1.5f, 0);
    set_pixel(&r, 2, 3, 12);
    struct metrics m;
    CHECK(metrics_compare(&r, &r, NULL, &m, NULL));
    CHECK(m.n_pixels == 35 && m.n_nonfinite == 0);
    CHECK(m.relmse == 0 && m.rmse == 0 && m.mae == 0 && m.frac5 == 0);
    CHECK(m.mean[0] == m.ref_mean[0] && m.mean[2] == m.ref_mean[2]);
    image_free(&r);
}

TEST(constant_offset_known_values)
{
    /* r = 0.5 everywhere, x = 0.6: d = 0.1 in every channel. */
    struct image r = constant_image(8, 8, 0.5f, 0.5f, 0.5f);
    struct image x = constant_image(8, 8, 0.6f, 0.6f, 0.6f);
    struct metrics m;
    CHECK(metrics_compare(&x, &r, NULL, &m, NULL));
    double d = (double)0.6f - (double)0.5f;
    CHECK_NEAR(m.relmse, d * d / (0.25 + 0.01), 1e-12);
    CHECK_NEAR(m.rmse, d, 1e-12);
    CHECK_NEAR(m.mae, d, 1e-12);
    CHECK(m.frac5 == 1);
    CHECK_NEAR(m.mean[1], 0.6, 1e-7);
    CHECK_NEAR(m.ref_mean[1], 0.5, 1e-7);

    /* Half the reference at 1.0 instead: relMSE averages the two terms. */
    for (int y = 0; y < 4; y++) {
        for (int i = 0; i < 8; i++) {
            set_pixel(&r, i, y, 1.0f);
            set_pixel(&x, i, y, 1.0f + (float)d);
        }
    }
    double d2 = (double)(1.0f + (float)d) - 1.0;
    double want = 0.5 * d * d / 0.26 + 0.5 * d2 * d2 / 1.01;
    CHECK_NEAR(metrics_relmse(&x, &r, NULL), want, 1e-12);
    CHECK_NEAR(metrics_mae(&x, &r, NULL), 0.5 * (d + d2), 1e-12);
    image_free(&r);
    image_free(&x);
}

TEST(channels_weigh_equally)
{
    /* Only the blue channel differs: the sums are divided by 3N. */
    struct image r = constant_image(4, 4, 1, 1, 1);
    struct image x = constant_image(4, 4, 1, 1, 1.5f);
    CHECK_NEAR(metrics_relmse(&x, &r, NULL), 0.25 / 1.01 / 3, 1e-12);
    CHECK_NEAR(metrics_rmse(&x, &r, NULL), sqrt(0.25 / 3), 1e-12);
    CHECK_NEAR(metrics_mae(&x, &r, NULL), 0.5 / 3, 1e-12);
    CHECK(metrics_frac5(&x, &r, NULL) == 1);
    image_free(&r);
    image_free(&x);
}

TEST(one_bad_pixel_fraction)
{
    struct image r = constant_image(10, 10, 0.8f, 0.4f, 0);
    struct image x = constant_image(10, 10, 0.8f, 0.4f, 0);
    /* 10% off in one channel: counts.  4% off: does not. */
    image_pixel(&x, 3, 7)[1] = 0.44f;
    image_pixel(&x, 5, 5)[0] = 0.832f;
    CHECK_NEAR(metrics_frac5(&x, &r, NULL), 1.0 / 100, 1e-15);
    /* The floor 0.01 on a black channel: 0.0004 < 0.05 * 0.01, 0.001 is not. */
    image_pixel(&x, 0, 0)[2] = 0.0004f;
    CHECK_NEAR(metrics_frac5(&x, &r, NULL), 1.0 / 100, 1e-15);
    image_pixel(&x, 0, 1)[2] = 0.001f;
    CHECK_NEAR(metrics_frac5(&x, &r, NULL), 2.0 / 100, 1e-15);
    image_free(&r);
    image_free(&x);
}

TEST(nonfinite_pixels_counted_and_left_out)
{
    struct image r = constant_image(5, 4, 1, 1, 1);
    struct image x = constant_image(5, 4, 1, 1, 1);
    image_pixel(&x, 1, 1)[0] = NAN;
    image_pixel(&x, 2, 1)[2] = INFINITY;
    struct metrics m;
    CHECK(metrics_compare(&x, &r, NULL, &m, NULL));
    CHECK(m.n_nonfinite == 2 && m.n_pixels == 18);
    CHECK(m.relmse == 0 && m.mean[0] == 1);
    CHECK(metrics_count_nonfinite(&x) == 2);
    CHECK(metrics_count_nonfinite(&r) == 0);
    double mean[3];
    CHECK(metrics_mean(&x, NULL, mean) == 18);
    CHECK(mean[2] == 1);
    image_free(&r);
    image_free(&x);
}

TEST(size_mismatch_fails)
{
    struct image r = constant_image(5, 4, 1, 1, 1);
    struct image x = constant_image(4, 5, 1, 1, 1);
    struct metrics m;
    struct diag err = {0};
    CHECK(!metrics_compare(&x, &r, NULL, &m, &err));
    CHECK(strstr(err.msg, "4x5") && strstr(err.msg, "5x4"));
    CHECK(isnan(metrics_relmse(&x, &r, NULL)));
    image_free(&r);
    image_free(&x);
}

TEST(mean_with_mask)
{
    struct image img = constant_image(4, 2, 1, 2, 3);
    set_pixel(&img, 0, 0, 10);
    unsigned char mask[8] = {1, 1, 0, 0, 0, 0, 0, 0};
    double mean[3];
    CHECK(metrics_mean(&img, mask, mean) == 2);
    CHECK_NEAR(mean[0], 5.5, 1e-12);
    CHECK_NEAR(mean[2], 6.5, 1e-12);
    unsigned char none[8] = {0};
    CHECK(metrics_mean(&img, none, mean) == 0 && isnan(mean[1]));
    image_free(&img);
}

/* 10 x 6: columns 0-4 at 0.2, columns 5-9 at 1.0, an edge between
 * columns 4 and 5. */
static struct image
edge_image(void)
{
    struct image ref = constant_image(10, 6, 0.2f, 0.2f, 0.2f);
    for (int y = 0; y < 6; y++) {
        for (int x = 5; x < 10; x++) {
            set_pixel(&ref, x, y, 1.0f);
        }
    }
    return ref;
}

TEST(smooth_mask_on_an_edge)
{
    /* Interior pixels away from the edge are smooth: x in {1, 2, 3, 6, 7,
     * 8}, y in 1..4.  A +4% variation stays inside the tolerance. */
    struct image ref = edge_image();
    set_pixel(&ref, 7, 0, 1.04f);
    size_t n = 0;
    unsigned char *mask = metrics_smooth_mask(&ref, METRICS_SMOOTH_TOLERANCE, &n, NULL);
    CHECK(mask != NULL);
    if (!mask) {
        return;
    }
    CHECK(n == 24);
    for (int y = 0; y < 6; y++) {
        for (int x = 0; x < 10; x++) {
            bool want = y >= 1 && y <= 4 && x != 0 && x != 9 && x != 4 && x != 5;
            CHECK_MSG(mask[y * 10 + x] == want, "pixel (%d, %d)", x, y);
        }
    }
    /* A render wrong only on the edge compares perfectly on the mask. */
    struct image x = edge_image();
    set_pixel(&x, 4, 2, 5.0f);
    set_pixel(&x, 5, 3, 0.0f);
    CHECK(metrics_relmse(&x, &ref, mask) == 0);
    CHECK(metrics_relmse(&x, &ref, NULL) > 0);
    free(mask);
    image_free(&x);
    image_free(&ref);
}

TEST(smooth_mask_tolerance_and_black)
{
    /* +6% breaks every window that holds it; a black pixel among grey
     * ones is not smooth, nor are its neighbours. */
    struct image ref = edge_image();
    set_pixel(&ref, 7, 2, 1.06f);
    set_pixel(&ref, 2, 2, 0);
    size_t n;
    unsigned char *mask = metrics_smooth_mask(&ref, METRICS_SMOOTH_TOLERANCE, &n, NULL);
    CHECK(mask && !mask[2 * 10 + 7] && !mask[1 * 10 + 6] && mask[4 * 10 + 7]);
    CHECK(mask && !mask[2 * 10 + 2] && !mask[1 * 10 + 1]);
    free(mask);
    image_free(&ref);

    /* Black among black is smooth (the window's only interior pixel). */
    struct image black = constant_image(3, 3, 0, 0, 0);
    mask = metrics_smooth_mask(&black, METRICS_SMOOTH_TOLERANCE, &n, NULL);
    CHECK(mask && n == 1 && mask[4] == 1);
    free(mask);
    image_free(&black);
}

/* k renders of ref plus uniform noise in [-a, a] per value and a relative
 * bias, seeded by the render's index. */
static void
noisy_renders(const struct image *ref, struct image *out, int k, double a, double bias)
{
    for (int i = 0; i < k; i++) {
        out[i] = constant_image(ref->width, ref->height, 0, 0, 0);
        struct rng r = rng_make(1234, (uint64_t)i);
        size_t n = (size_t)ref->width * (size_t)ref->height * 3;
        for (size_t j = 0; j < n; j++) {
            double u = 2 * (double)rng_uniform(&r) - 1;
            out[i].rgb[j] = (float)(ref->rgb[j] * (1 + bias) + a * u);
        }
    }
}

/* The block tests of the mean of k renders, their per-pixel variance
 * from the renders' spread (estimate_combine), as compare runs them. */
static bool
block_stats_of(
    const struct image *renders,
    int k,
    const struct image *ref,
    const struct metrics_block_params *params,
    struct metrics_block_stats *s)
{
    struct image mean = {0}, variance = {0};
    bool ok = estimate_combine(renders, NULL, k, &mean, &variance, NULL)
              && metrics_block_stats_variance(&mean, &variance, k - 1, ref, params, s, NULL);
    image_free(&mean);
    image_free(&variance);
    return ok;
}

TEST(block_stats_hand_computed)
{
    /* Two constant renders 1 and 3 against reference 2.5: mean 2, each
     * pixel's variance of the mean s^2 / k = 2 / 2 = 1 with 1 dof.  Block 3
     * is the 2x1 corner: var_mean = (1 + 1) / 2^2 = 0.5, t = -0.5 /
     * sqrt(0.5), Welch-Satterthwaite dof (1 + 1)^2 / (1 + 1) = 2, and with
     * 2 dof p = 1 - |t| / sqrt(2 + t^2). */
    struct image renders[2] = {constant_image(6, 5, 1, 1, 1), constant_image(6, 5, 3, 3, 3)};
    struct image ref = constant_image(6, 5, 2.5f, 2, 2.5f);
    struct metrics_block_params params = {.block_size = 4};
    struct metrics_block_stats s;
    CHECK(block_stats_of(renders, 2, &ref, &params, &s));
    CHECK(s.blocks_x == 2 && s.blocks_y == 2 && s.n_blocks == 4);
    struct metrics_block *b = &s.blocks[3];
    CHECK(b->x0 == 4 && b->y0 == 4 && b->w == 2 && b->h == 1);
    CHECK_NEAR(b->mean[0], 2, 1e-12);
    CHECK_NEAR(b->var_mean[0], 0.5, 1e-12);
    CHECK_NEAR(b->t[0], -0.5 / sqrt(0.5), 1e-12);
    CHECK_NEAR(b->dof[0], 2, 1e-12);
    CHECK_NEAR(b->p[0], 1 - sqrt(0.5) / sqrt(2.5), 1e-9);
    CHECK(b->t[1] == 0 && b->p[1] == 1);
    /* A 4x4 block: var_mean 16 / 16^2. */
    CHECK_NEAR(s.blocks[0].var_mean[0], 1.0 / 16, 1e-12);
    metrics_block_stats_free(&s);

    /* A reference SE of its own: relative 0.1 of 2.5 adds 0.0625 to var. */
    params.ref_rel_se = 0.1;
    params.ref_dof = 15;
    CHECK(block_stats_of(renders, 2, &ref, &params, &s));
    CHECK_NEAR(s.blocks[0].ref_se[0], 0.25, 1e-12);
    CHECK_NEAR(s.blocks[0].t[0], -0.5 / sqrt(1.0 / 16 + 0.0625), 1e-12);
    /* The 2x1 corner averages 2 pixels, not 16: sqrt(8) times the SE. */
    CHECK_NEAR(s.blocks[3].ref_se[0], 0.25 * sqrt(8.0), 1e-12);
    metrics_block_stats_free(&s);

    struct diag err = {0};
    CHECK(!metrics_block_stats_variance(&renders[0], &renders[1], -1, &ref, &params, &s, &err));
    CHECK(strstr(err.msg, "degrees of freedom") != NULL);
    for (int i = 0; i < 2; i++) {
        image_free(&renders[i]);
    }
    image_free(&ref);
}

TEST(block_stats_detect_bias_only)
{
    enum {
        K = 8
    };
    struct image ref = constant_image(64, 48, 0.5f, 0.25f, 1.0f);
    set_pixel(&ref, 10, 10, 2.0f);
    struct image renders[K];
    struct metrics_block_params params = {.block_size = 16, .ref_rel_se = 1e-4, .ref_dof = 15};
    struct metrics_block_stats s;
    double min_p;

    /* Unbiased noise: no block rejects at the family level 0.01. */
    noisy_renders(&ref, renders, K, 0.02, 0);
    CHECK(block_stats_of(renders, K, &ref, &params, &s));
    CHECK(s.n_blocks == 12);
    CHECK_MSG(metrics_block_rejections(&s, 0.01, &min_p) == 0, "min p %g", min_p);
    metrics_block_stats_free(&s);

    /* A NaN in one render: its block rejects with p = 0. */
    renders[3].rgb[3 * (20 * 64 + 40) + 1] = NAN;
    CHECK(block_stats_of(renders, K, &ref, &params, &s));
    CHECK(metrics_block_rejections(&s, 0.01, &min_p) >= 1 && min_p == 0);
    CHECK(s.blocks[1 * 4 + 2].p[1] == 0 && isnan(s.blocks[1 * 4 + 2].t[1]));
    metrics_block_stats_free(&s);
    for (int i = 0; i < K; i++) {
        image_free(&renders[i]);
    }

    /* A 3% bias, many standard errors of a block mean in every channel:
     * every block of every channel rejects. */
    noisy_renders(&ref, renders, K, 0.02, 0.03);
    CHECK(block_stats_of(renders, K, &ref, &params, &s));
    CHECK(metrics_block_rejections(&s, 0.01, NULL) == 36);
    metrics_block_stats_free(&s);
    for (int i = 0; i < K; i++) {
        image_free(&renders[i]);
    }
    image_free(&ref);
}

/* Windows of 2x2 blocks: a 2% bias over the 32x32 square x, y 16-47 of a
 * 64x64 image, where every pixel's standard error is 0.02 * 16 / 3, is 3
 * standard errors in each of its four blocks and 6 in the window that is
 * those blocks; at the family level 0.01 over 16 blocks and 9 windows
 * (75 tests, one at z = 3.8), only that window rejects. */
TEST(block_windows_find_what_their_blocks_share)
{
    struct image ref = constant_image(64, 64, 1, 1, 1);
    struct image render = constant_image(64, 64, 1, 1, 1);
    double sigma = 0.02 * 16 / 3;
    struct image variance = constant_image(64, 64, 0, 0, 0);
    for (size_t i = 0; i < (size_t)64 * 64 * 3; i++) {
        variance.rgb[i] = (float)(sigma * sigma);
    }
    for (int y = 16; y < 48; y++) {
        for (int x = 16; x < 48; x++) {
            set_pixel(&render, x, y, 1.02f);
        }
    }
    struct metrics_block_params params = {.block_size = 16};
    struct metrics_block_stats s;
    double min_p;
    CHECK(metrics_block_stats_variance(&render, &variance, 0, &ref, &params, &s, NULL));
    CHECK(s.n_blocks == 16 && s.n_windows == 0 && s.windows == NULL);
    CHECK_NEAR(s.blocks[1 * 4 + 1].t[0], 3, 1e-5);
    CHECK_MSG(metrics_block_rejections(&s, 0.01, &min_p) == 0, "min p %g", min_p);
    metrics_block_stats_free(&s);

    params.windows = true;
    CHECK(metrics_block_stats_variance(&render, &variance, 0, &ref, &params, &s, NULL));
    CHECK(s.n_blocks == 16 && s.n_windows == 9);
    const struct metrics_block *w = &s.windows[1 * 3 + 1];
    CHECK(w->window && !s.blocks[0].window);
    CHECK(w->x0 == 16 && w->y0 == 16 && w->w == 32 && w->h == 32);
    CHECK(metrics_block_test(&s, 16 + 1 * 3 + 1) == w);
    CHECK_NEAR(w->mean[1], 1.02, 1e-6);
    CHECK_NEAR(w->var_mean[1], sigma * sigma / 1024, 1e-12);
    CHECK_NEAR(w->t[1], 6, 1e-5);
    CHECK_NEAR(s.windows[0].t[1], 1.5, 1e-5); /* a quarter of it biased */
    CHECK(metrics_block_rejections(&s, 0.01, &min_p) == 3);
    CHECK(w->p[0] == min_p);
    metrics_block_stats_free(&s);

    /* The reference's SE of a window combines its blocks': half theirs. */
    params.ref_rel_se = 0.01;
    CHECK(metrics_block_stats_variance(&render, &variance, 0, &ref, &params, &s, NULL));
    CHECK_NEAR(s.windows[0].ref_se[2], 0.005, 1e-12);
    metrics_block_stats_free(&s);
    image_free(&ref);
    image_free(&render);
    image_free(&variance);
}

/* What the tests can find, by hand: the window x, y 16-47 of the test
 * above has standard error sigma / 32 in every channel, with exact
 * variances (a z-test), so it finds a bias delta with probability 0.9 when
 * delta = (z_level + z_0.9) sigma / 32. */
TEST(detectable_bias_hand_computed)
{
    struct image ref = constant_image(64, 64, 1, 0.5f, 2);
    double sigma = 0.01;
    struct image variance = constant_image(64, 64, 0, 0, 0);
    for (size_t i = 0; i < (size_t)64 * 64 * 3; i++) {
        variance.rgb[i] = (float)(sigma * sigma * ref.rgb[i] * ref.rgb[i]); /* relative: sigma */
    }
    struct metrics_block_params params = {.block_size = 16, .windows = true};
    struct metrics_block_stats s;
    CHECK(metrics_block_stats_variance(&ref, &variance, 0, &ref, &params, &s, NULL));
    double level = stattest_sidak(0.01, 75);
    double z_level = stattest_t_critical(level, INFINITY), z_power = 1.2815515655446004;
    double delta = (z_level + z_power) * sigma / 32;
    const struct metrics_block *w = &s.windows[4];
    CHECK_REL(metrics_detectable_bias(w, level, 0.9), delta, 1e-6);
    /* Twice that bias needs a quarter of the samples; the same, the same. */
    CHECK_REL(metrics_samples_for_bias(w, level, 0.9, 2 * delta), 0.25, 1e-5);
    CHECK_REL(metrics_samples_for_bias(w, level, 0.9, delta), 1, 1e-5);
    struct metrics_power power;
    CHECK(metrics_block_power(&s, level, 0.9, delta / 3, &power, NULL));
    CHECK(power.n == 9);
    CHECK_REL(power.bias_half, delta, 1e-6);
    CHECK_REL(power.bias_most, delta, 1e-6);
    CHECK_REL(power.samples_most, 9, 1e-5);
    metrics_block_stats_free(&s);

    /* A reference whose own noise per window exceeds the bias: no number
     * of samples finds it. */
    params.ref_rel_se = 0.01;
    CHECK(metrics_block_stats_variance(&ref, &variance, 0, &ref, &params, &s, NULL));
    CHECK(isinf(metrics_samples_for_bias(&s.windows[4], level, 0.9, 0.001)));
    metrics_block_stats_free(&s);

    /* A black reference tells no relative bias. */
    struct image black = constant_image(64, 64, 0, 0, 0);
    params.ref_rel_se = 0;
    CHECK(metrics_block_stats_variance(&black, &variance, 0, &black, &params, &s, NULL));
    CHECK(isnan(metrics_detectable_bias(&s.windows[4], level, 0.9)));
    CHECK(metrics_block_power(&s, level, 0.9, 0.02, &power, NULL));
    CHECK(power.n == 0 && isnan(power.bias_half));
    metrics_block_stats_free(&s);
    image_free(&black);
    image_free(&ref);
    image_free(&variance);
}

/* A standard normal deviate (Box-Muller). */
static double
normal_deviate(struct rng *r)
{
    double u = 1 - (double)rng_uniform(r), v = (double)rng_uniform(r);
    return sqrt(-2 * log(u)) * cos(6.283185307179586 * v);
}

/* The claim checked by trial: renders of K = 4 seeds, their noise
 * estimated from their spread as compare does (3 dof per pixel), a bias
 * of metrics_detectable_bias's size planted over one window: that window's
 * test finds it in about 9 trials of 10 (399 trials: 359 expected, SD 6;
 * the bounds are 4.5 SD), and half that bias about 1 time in 7. */
TEST(detectable_bias_is_found_nine_times_in_ten)
{
    enum {
        K = 4,
        N = 32,
        TRIALS = 400
    };
    struct image ref = constant_image(N, N, 1, 1, 1);
    struct image mean = constant_image(N, N, 0, 0, 0);
    struct image variance = constant_image(N, N, 0, 0, 0);
    struct metrics_block_params params = {.block_size = 16, .windows = true};
    double level = stattest_sidak(0.01, 15), planted = 0;
    int found[2] = {0, 0};
    for (int trial = 0; trial < TRIALS; trial++) {
        struct rng r = rng_make(99, (uint64_t)trial);
        for (int half = 0; half < 2; half++) {
            double bias = half ? planted / 2 : planted;
            for (size_t j = 0; j < (size_t)N * N; j++) {
                /* The channels share their noise, as a path's colours do. */
                double sum = 0, sum2 = 0;
                for (int k = 0; k < K; k++) {
                    double x = (1 + bias) * (1 + 0.1 * normal_deviate(&r));
                    sum += x;
                    sum2 += x * x;
                }
                for (int c = 0; c < 3; c++) {
                    mean.rgb[3 * j + (size_t)c] = (float)(sum / K);
                    variance.rgb[3 * j + (size_t)c] = (float)((sum2 - sum * sum / K) / (K - 1) / K);
                }
            }
            struct metrics_block_stats s;
            CHECK(metrics_block_stats_variance(&mean, &variance, K - 1, &ref, &params, &s, NULL));
            if (trial == 0 && half == 0) {
                /* The size comes from the noise alone (no bias planted yet). */
                planted = metrics_detectable_bias(&s.windows[0], level, 0.9);
                CHECK(planted > 0 && planted < 0.05);
            } else {
                const struct metrics_block *w = &s.windows[0];
                found[half] += w->p[0] < level || w->p[1] < level || w->p[2] < level;
            }
            metrics_block_stats_free(&s);
        }
    }
    CHECK_MSG(found[0] >= 332 && found[0] <= 386, "found %d of %d", found[0], TRIALS - 1);
    /* Half the bias is z_level - (z_level + z_0.9) / 2 = 1.06 standard
     * errors short of the level: found with probability 0.145, 58 times. */
    CHECK_MSG(found[1] >= 25 && found[1] <= 100, "half the bias found %d of %d", found[1], TRIALS);
    image_free(&ref);
    image_free(&mean);
    image_free(&variance);
}

TEST_MAIN(
    TEST_ENTRY(identical_images_give_zero),
    TEST_ENTRY(constant_offset_known_values),
    TEST_ENTRY(channels_weigh_equally),
    TEST_ENTRY(one_bad_pixel_fraction),
    TEST_ENTRY(nonfinite_pixels_counted_and_left_out),
    TEST_ENTRY(size_mismatch_fails),
    TEST_ENTRY(mean_with_mask),
    TEST_ENTRY(smooth_mask_on_an_edge),
    TEST_ENTRY(smooth_mask_tolerance_and_black),
    TEST_ENTRY(block_stats_hand_computed),
    TEST_ENTRY(block_stats_detect_bias_only),
    TEST_ENTRY(block_windows_find_what_their_blocks_share),
    TEST_ENTRY(detectable_bias_hand_computed),
    TEST_ENTRY(detectable_bias_is_found_nine_times_in_ten))
