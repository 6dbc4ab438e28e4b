/*
 * metrics.h - how far a render is from a reference image: error metrics,
 * the "smooth pixels" mask, and per-block statistics for t-tests against a
 * reference (TESTING.md section 4 and T25).
 *
 * Conventions (every metric):
 *   - x is our render, r the reference; both struct image (linear RGB
 *     floats), of the same size.  Sums are accumulated in double.
 *   - A mask, when given, is width * height bytes, row 0 at the top like
 *     the image; a pixel is compared only where mask[y * width + x] != 0.
 *     NULL compares every pixel.
 *   - A compared pixel whose render or reference has a non-finite channel
 *     (NaN, +-Inf) is left out of every sum and counted in n_nonfinite
 *     instead: one NaN must not hide how the rest of the image compares,
 *     and callers must treat n_nonfinite > 0 as a failure of its own.
 *   - "Mean over pixels and channels": the sum over the N compared pixels
 *     and their 3 channels, divided by 3N (each channel weighs the same;
 *     no luminance weighting).  So for relMSE:
 *         relMSE = 1/(3N) sum_pixels sum_c (x_c - r_c)^2 / (r_c^2 + 0.01)
 *     which is tev's RelativeSquaredError averaged over the image and its
 *     channels.  RMSE = sqrt(1/(3N) sum (x_c - r_c)^2);
 *     MAE = 1/(3N) sum |x_c - r_c|.
 *   - frac5: the fraction of the N pixels where ANY channel has
 *     |x_c - r_c| > 0.05 * max(|r_c|, 0.01).  Per channel rather than on
 *     luminance, so a colour shift that keeps the luminance still counts;
 *     the 0.01 floor keeps near-black channels from counting every bit of
 *     noise.
 * With no pixel to compare, every metric is NaN.
 */
#ifndef METRICS_H
#define METRICS_H

#include <stdbool.h>
#include <stddef.h>

#include "diag.h"
#include "image.h"

/* The constant in relMSE's denominator (tev, mitsuba_refs.py). */
#define METRICS_RELMSE_EPS 0.01

/* frac5's relative tolerance and the floor of its denominator. */
#define METRICS_FRAC_TOLERANCE 0.05
#define METRICS_FRAC_FLOOR 0.01

/* Smooth-pixel mask: the tolerance of the 3x3 luminance window. */
#define METRICS_SMOOTH_TOLERANCE 0.05

struct metrics {
    size_t n_pixels; /* pixels compared (in the mask, all channels finite) */
    size_t n_nonfinite; /* pixels in the mask left out for a non-finite value */
    double relmse;
    double rmse;
    double mae;
    double frac5; /* fraction of n_pixels off by more than 5% */
    double mean[3]; /* the render's mean per channel over the compared pixels */
    double ref_mean[3]; /* the reference's, over the same pixels */
};

/* Compare render x with reference r (mask may be NULL).  Fails (diag) only
 * when the sizes differ; no compared pixel is not a failure (NaN metrics). */
bool metrics_compare(
    const struct image *x,
    const struct image *r,
    const unsigned char *mask,
    struct metrics *out,
    struct diag *err);

/* The single metrics, for callers that want one number; NaN when the sizes
 * differ or nothing is compared. */
double metrics_relmse(const struct image *x, const struct image *r, const unsigned char *mask);
double metrics_rmse(const struct image *x, const struct image *r, const unsigned char *mask);
double metrics_mae(const struct image *x, const struct image *r, const unsigned char *mask);
double metrics_frac5(const struct image *x, const struct image *r, const unsigned char *mask);

/* Mean of each channel over the masked pixels whose channels are all
 * finite; returns how many pixels that is (0: out is NaN). */
size_t metrics_mean(const struct image *img, const unsigned char *mask, double out[3]);

/* Pixels with at least one non-finite channel (the whole image). */
size_t metrics_count_nonfinite(const struct image *img);

/* Rec. 709 / sRGB-primaries luminance of a linear RGB pixel. */
double metrics_luminance(const float *rgb);

/* The reference's smooth pixels: pixel (x, y) is smooth when the luminance
 * of every pixel of its 3x3 window lies within tolerance (relative) of the
 * centre's, i.e. max <= c (1 + tol) and min >= c (1 - tol), with c the
 * centre's luminance; so a black pixel is smooth only among black ones.
 * Border pixels (no full window) and windows with non-finite values are
 * never smooth.  Stages 02/03 compare only on these pixels, where a
 * reference's edges and penumbrae cannot dominate the error.  Returns a
 * malloc'd width * height mask (free it) and the count of smooth pixels in
 * *n_smooth (may be NULL); NULL with err filled when memory runs out. */
unsigned char *
metrics_smooth_mask(const struct image *ref, double tolerance, size_t *n_smooth, struct diag *err);

/* ---- Block statistics for render-vs-reference t-tests --------------------
 *
 * An estimate of a scene (one render, or the mean of renders with
 * different seeds: estimate_combine) with the variance of each of its
 * pixels is cut into square blocks of block_size pixels (blocks at the
 * right and bottom edges may be smaller; block_size 1 gives per-pixel
 * tests, block_size >= the image size one image-mean test).  Per block and
 * channel:
 *   mean     = the estimate's block mean
 *   var_mean = its squared standard error (metrics_block_stats_variance)
 *   ref_mean = the reference's block mean, ref_se its standard error
 *   t, dof, p from stattest_t_test_estimates(mean, var_mean, dof,
 *              ref_mean, ref_se^2, ref_dof): Welch's test with the
 *              Welch-Satterthwaite degrees of freedom.
 * A block with a non-finite value gets t = dof = NaN and p = 0 (a certain
 * rejection).
 */
struct metrics_block_params {
    int block_size;
    /* The reference's standard error per block and channel (n_blocks * 3,
     * block-major, blocks in row-major order), or NULL to use ref_rel_se. */
    const double *ref_se;
    /* With ref_se NULL: SE = ref_rel_se * |ref_mean| for a whole block
     * (block_size^2 pixels), sqrt(block_size^2 / pixels) times that for a
     * block the image's edge cuts (a window sums its blocks').  Passing
     * META.json's per-pixel relative SE (median_rel_se_pixel) overestimates
     * a block's SE (averaging pixels shrinks it), which errs on the side of
     * accepting.  0: the reference is taken as exact. */
    double ref_rel_se;
    /* Degrees of freedom of the reference's SE: batches - 1 (META.json's
     * "batches"), or 0 for infinitely many. */
    double ref_dof;
    /* metrics_block_stats_variance only: also test every window of 2x2
     * neighbouring blocks (overlapping, one block apart).  A bias the size
     * of a window but not aligned with the blocks is split over up to nine
     * blocks; the window that covers most of it sees it with half a
     * block's standard error. */
    bool windows;
};

struct metrics_block {
    int x0, y0, w, h; /* the pixel rectangle */
    double mean[3];
    double var_mean[3];
    double ref_mean[3];
    double ref_se[3];
    double t[3];
    double dof[3];
    double p[3];
    bool window; /* a window of 2x2 blocks (params.windows), not a block */
};

struct metrics_block_stats {
    int blocks_x, blocks_y; /* blocks across and down */
    int n_blocks; /* blocks_x * blocks_y; blocks in row-major order */
    struct metrics_block *blocks;
    /* With params.windows: (blocks_x - 1) * (blocks_y - 1) windows in
     * row-major order, window (i, j) the blocks (i..i+1, j..j+1). */
    int n_windows;
    struct metrics_block *windows;
};

/* How many blocks (and, with windows, windows of 2x2 blocks) a
 * width x height image is cut into: the tests per channel of
 * metrics_block_stats_variance, before it runs. */
int metrics_block_test_count(int width, int height, int block_size, bool windows);

/* Test i of s's family, 0 <= i < n_blocks + n_windows: the blocks, then
 * the windows. */
const struct metrics_block *metrics_block_test(const struct metrics_block_stats *s, int i);

/* The block tests of ONE estimate whose per-pixel variance is known (the
 * squared standard error of each pixel, e.g. from merge or from the spread
 * of a few renders): a block's var_mean is the sum of its pixels' variances
 * over n^2 (pixels are independent estimates), with Welch-Satterthwaite's
 * degrees of freedom from pixel_dof per pixel (0: exact variances).  Far
 * more powerful than a test on the spread of K renders' block means when
 * K is small: two renders give that one degree of freedom per block, but
 * hundreds here.
 * A block's var_mean is at least what the mean per-pixel variance of the
 * 3x3 blocks around it gives: where rare bright paths (caustics) carry
 * light, renders that missed them look darker and less noisy at once,
 * and the block's own variance alone would accuse correct code
 * (metrics.c, docs/calibration/README.md).  With
 * params->windows, also the windows of 2x2 blocks: a window's variance is
 * the sum of its blocks' (each at least its neighbourhood's). */
bool metrics_block_stats_variance(
    const struct image *render,
    const struct image *variance,
    double pixel_dof,
    const struct image *ref,
    const struct metrics_block_params *params,
    struct metrics_block_stats *out,
    struct diag *err);

/* ---- What the block tests can find -------------------------------------
 *
 * A test finds a shift of d standard errors with probability `power` when
 * d = t_level + t_power (the shifted-t approximation of its power: the
 * test's t is the shift plus a t-distributed error; t_level is the test's
 * two-sided critical value, t_power the error's one-sided power quantile).
 * A bias here scales every channel of a block by 1 + delta, as a wrong
 * factor in an estimator does; the block's most sensitive channel finds it
 * first.  A channel whose reference mean is 0 sees no relative bias.
 */

/* The smallest delta that the tests of b, each at the per-test level
 * `level`, find with probability `power` in its most sensitive channel.
 * NaN when no channel can tell (a zero or non-finite reference). */
double metrics_detectable_bias(const struct metrics_block *b, double level, double power);

/* How many times the render's samples b needs for its tests to find a
 * bias of `bias` (a fraction) with probability `power`: the render's
 * variance falls with the samples, the reference's does not, so INFINITY
 * when the reference's own noise alone hides the bias.  Below 1 when b
 * already finds it; NaN as for metrics_detectable_bias. */
double
metrics_samples_for_bias(const struct metrics_block *b, double level, double power, double bias);

/* What a comparison can find, over its windows of 2x2 blocks (its blocks
 * when it has no windows), each tested at `level`: */
struct metrics_power {
    int n; /* windows (or blocks) that can tell a relative bias */
    double bias_half; /* the detectable bias of the median window */
    double bias_most; /* ... that 9 windows in 10 reach */
    double samples_most; /* samples_for_bias(target) that 9 windows in 10 need */
};

/* Fill out for target bias `target` (e.g. 0.02).  Fails (diag) only when
 * memory runs out; n 0 (and NaN figures) when no window can tell. */
bool metrics_block_power(
    const struct metrics_block_stats *s,
    double level,
    double power,
    double target,
    struct metrics_power *out,
    struct diag *err);

/* v as a reader writes it, never with an exponent: at least two
 * significant digits, and every digit before the point ("1400", "16",
 * "2.5", "0.0031"), into buf.  For percentages and standard errors, where
 * printf's %g writes 1e+02 and 1.4e+03. */
void metrics_format_plain(char *buf, size_t cap, double v);

/* Free the blocks; accepts a zero-initialised struct. */
void metrics_block_stats_free(struct metrics_block_stats *s);

/* How many of the 3 * (n_blocks + n_windows) tests reject at the Sidak-corrected level
 * for family level alpha (e.g. 0.01); *min_p (may be NULL) gets the
 * smallest p-value. */
size_t metrics_block_rejections(const struct metrics_block_stats *s, double alpha, double *min_p);

#endif /* METRICS_H */
