/*
 * metrics.c - see metrics.h for the definitions of every metric.
 */
#include "metrics.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "stattest.h"

/* Running sums of one comparison, all in double. */
struct sums {
    size_t n; /* compared pixels */
    size_t nonfinite; /* masked pixels left out */
    double rel_sq; /* sum of (x - r)^2 / (r^2 + eps) */
    double sq; /* sum of (x - r)^2 */
    double abs; /* sum of |x - r| */
    size_t over; /* pixels off by more than the frac5 tolerance */
    double x[3], r[3];
};

static bool
same_size(const struct image *x, const struct image *r)
{
    return x->width == r->width && x->height == r->height;
}

static bool
pixel_finite(const float *p)
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

static void
add_pixel(struct sums *s, const float *px, const float *pr)
{
    bool over = false;
    for (int c = 0; c < 3; c++) {
        double x = px[c];
        double r = pr[c];
        double d = x - r;
        s->rel_sq += d * d / (r * r + METRICS_RELMSE_EPS);
        s->sq += d * d;
        s->abs += fabs(d);
        over = over || fabs(d) > METRICS_FRAC_TOLERANCE * fmax(fabs(r), METRICS_FRAC_FLOOR);
        s->x[c] += x;
        s->r[c] += r;
    }
    s->over += over;
    s->n++;
}

/* Sums over the masked pixels; the sizes must already match. */
static struct sums
accumulate(const struct image *x, const struct image *r, const unsigned char *mask)
{
    struct sums s = {0};
    size_t n = (size_t)x->width * (size_t)x->height;
    for (size_t i = 0; i < n; i++) {
        if (mask && !mask[i]) {
            continue;
        }
        const float *px = x->rgb + 3 * i;
        const float *pr = r->rgb + 3 * i;
        if (pixel_finite(px) && pixel_finite(pr)) {
            add_pixel(&s, px, pr);
        } else {
            s.nonfinite++;
        }
    }
    return s;
}

static void
finish(const struct sums *s, struct metrics *out)
{
    /* 0/0 gives the documented NaN when nothing was compared. */
    double pixels = (double)s->n;
    double values = 3 * pixels;
    out->n_pixels = s->n;
    out->n_nonfinite = s->nonfinite;
    out->relmse = s->n ? s->rel_sq / values : NAN;
    out->rmse = s->n ? sqrt(s->sq / values) : NAN;
    out->mae = s->n ? s->abs / values : NAN;
    out->frac5 = s->n ? (double)s->over / pixels : NAN;
    for (int c = 0; c < 3; c++) {
        out->mean[c] = s->n ? s->x[c] / pixels : NAN;
        out->ref_mean[c] = s->n ? s->r[c] / pixels : NAN;
    }
}

bool
metrics_compare(
    const struct image *x,
    const struct image *r,
    const unsigned char *mask,
    struct metrics *out,
    struct diag *err)
{
    if (!same_size(x, r)) {
        diag_set(
            err,
            NULL,
            0,
            0,
            "render is %dx%d but the reference is %dx%d",
            x->width,
            x->height,
            r->width,
            r->height);
        return false;
    }
    struct sums s = accumulate(x, r, mask);
    finish(&s, out);
    return true;
}

/* metrics_compare for the one-number wrappers: NaN metrics on a mismatch. */
static struct metrics
compare_or_nan(const struct image *x, const struct image *r, const unsigned char *mask)
{
    struct metrics m;
    if (!metrics_compare(x, r, mask, &m, NULL)) {
        struct sums none = {0};
        finish(&none, &m);
    }
    return m;
}

double
metrics_relmse(const struct image *x, const struct image *r, const unsigned char *mask)
{
    return compare_or_nan(x, r, mask).relmse;
}

double
metrics_rmse(const struct image *x, const struct image *r, const unsigned char *mask)
{
    return compare_or_nan(x, r, mask).rmse;
}

double
metrics_mae(const struct image *x, const struct image *r, const unsigned char *mask)
{
    return compare_or_nan(x, r, mask).mae;
}

double
metrics_frac5(const struct image *x, const struct image *r, const unsigned char *mask)
{
    return compare_or_nan(x, r, mask).frac5;
}

size_t
metrics_mean(const struct image *img, const unsigned char *mask, double out[3])
{
    /* The image against itself: the render's mean is the mean asked for. */
    struct sums s = accumulate(img, img, mask);
    struct metrics m;
    finish(&s, &m);
    for (int c = 0; c < 3; c++) {
        out[c] = m.mean[c];
    }
    return s.n;
}

size_t
metrics_count_nonfinite(const struct image *img)
{
    size_t n = (size_t)img->width * (size_t)img->height;
    size_t bad = 0;
    for (size_t i = 0; i < n; i++) {
        bad += !pixel_finite(img->rgb + 3 * i);
    }
    return bad;
}

double
metrics_luminance(const float *rgb)
{
    /* ITU-R BT.709 weights: the sRGB primaries are BT.709's. */
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

/* Is the 3x3 window around interior pixel (x, y) within tol of its centre? */
static bool
window_smooth(const struct image *ref, int x, int y, double tol)
{
    double c = metrics_luminance(image_pixel(ref, x, y));
    double lo = c;
    double hi = c;
    for (int dy = -1; dy <= 1; dy++) {
        for (int dx = -1; dx <= 1; dx++) {
            double l = metrics_luminance(image_pixel(ref, x + dx, y + dy));
            lo = fmin(lo, l);
            hi = fmax(hi, l);
            if (!isfinite(l)) {
                return false;
            }
        }
    }
    return isfinite(c) && hi <= c * (1 + tol) && lo >= c * (1 - tol);
}

unsigned char *
metrics_smooth_mask(const struct image *ref, double tolerance, size_t *n_smooth, struct diag *err)
{
    size_t n = (size_t)ref->width * (size_t)ref->height;
    unsigned char *mask = calloc(n ? n : 1, 1);
    if (!mask) {
        diag_set(err, NULL, 0, 0, "out of memory for a %dx%d mask", ref->width, ref->height);
        return NULL;
    }
    size_t count = 0;
    for (int y = 1; y + 1 < ref->height; y++) {
        for (int x = 1; x + 1 < ref->width; x++) {
            bool smooth = window_smooth(ref, x, y, tolerance);
            mask[(size_t)y * (size_t)ref->width + (size_t)x] = smooth;
            count += smooth;
        }
    }
    if (n_smooth) {
        *n_smooth = count;
    }
    return mask;
}

/* ---- block statistics ---------------------------------------------------- */

/* Mean of each channel over block b of img; a non-finite pixel makes the
 * mean non-finite, which the caller turns into a rejection. */
static void
block_mean(const struct image *img, const struct metrics_block *b, double out[3])
{
    double sum[3] = {0, 0, 0};
    for (int y = b->y0; y < b->y0 + b->h; y++) {
        for (int x = b->x0; x < b->x0 + b->w; x++) {
            const float *p = image_pixel(img, x, y);
            for (int c = 0; c < 3; c++) {
                sum[c] += p[c];
            }
        }
    }
    double count = (double)b->w * (double)b->h;
    for (int c = 0; c < 3; c++) {
        out[c] = sum[c] / count;
    }
}

/* The test of one channel of one block, its inputs already in b; dof is
 * the degrees of freedom of var_mean. */
static void
test_channel(struct metrics_block *b, int c, double dof, double ref_dof)
{
    bool finite = isfinite(b->mean[c]) && isfinite(b->var_mean[c]) && isfinite(b->ref_mean[c])
                  && isfinite(b->ref_se[c]);
    if (!finite) {
        b->t[c] = NAN;
        b->dof[c] = NAN;
        b->p[c] = 0;
        return;
    }
    struct stattest_result r = stattest_t_test_estimates(
        b->mean[c],
        b->var_mean[c],
        dof,
        b->ref_mean[c],
        b->ref_se[c] * b->ref_se[c],
        ref_dof);
    b->t[c] = r.t;
    b->dof[c] = r.dof;
    b->p[c] = isnan(r.p) ? 0 : r.p;
}

/* The reference's side of block `index` and the three tests, the render's
 * mean and var_mean already in b with dof degrees of freedom. */
static void
test_block(
    const struct image *ref,
    const struct metrics_block_params *params,
    int index,
    double dof,
    struct metrics_block *b)
{
    block_mean(ref, b, b->ref_mean);
    /* ref_rel_se is a whole block's: a block the image's edge cuts averages
     * fewer pixels, so its SE is sqrt(whole / its pixels) times larger. */
    double whole = (double)params->block_size * (double)params->block_size;
    double cut = sqrt(fmax(1, whole / ((double)b->w * (double)b->h)));
    for (int c = 0; c < 3; c++) {
        b->ref_se[c] = params->ref_se ? params->ref_se[3 * (size_t)index + (size_t)c]
                                      : params->ref_rel_se * fabs(b->ref_mean[c]) * cut;
        test_channel(b, c, dof, params->ref_dof);
    }
}

/* The per-pixel variances of a block summed: sum v and sum v^2 per channel. */
static void
block_variance_sums(const struct image *variance, const struct metrics_block *b, double sum[6])
{
    for (int c = 0; c < 6; c++) {
        sum[c] = 0;
    }
    for (int y = b->y0; y < b->y0 + b->h; y++) {
        for (int x = b->x0; x < b->x0 + b->w; x++) {
            const float *v = image_pixel(variance, x, y);
            for (int c = 0; c < 3; c++) {
                sum[c] += v[c];
                sum[3 + c] += (double)v[c] * v[c];
            }
        }
    }
}

/* The degrees of freedom of a sum of per-pixel variances (own: sum v and
 * sum v^2 per channel), each of pixel_dof (0: exact, infinitely many):
 * Welch-Satterthwaite's (sum v)^2 / sum(v^2 / d), one for the three
 * channels, the smallest: they share pixels. */
static double
sum_dof(const double own[6], double pixel_dof)
{
    double dof = INFINITY;
    for (int c = 0; c < 3; c++) {
        if (pixel_dof > 0 && own[3 + c] > 0) {
            dof = fmin(dof, own[c] * own[c] / (own[3 + c] / pixel_dof));
        }
    }
    return dof;
}

/* Block `index` of one estimate with per-pixel variances: the pixels of a
 * block are independent estimates, so the variance of their mean is
 * sum(v_i) / n^2, and its degrees of freedom Welch-Satterthwaite's,
 * (sum v_i)^2 / sum(v_i^2 / d) for per-pixel variances of d degrees of
 * freedom (d = 0: exact variances, infinitely many).
 * The variance is at least what the pixels around the block give: n times
 * the mean per-pixel variance of the 3x3 blocks centred on it, over n^2.
 * Light carried by rare bright paths (caustics, their images in a mirror,
 * light through glass) makes a block's mean heavy-tailed, and its own
 * variance estimate falls with its mean: renders that missed more of those
 * paths than usual there are darker AND look less noisy, and the t-test
 * accuses correct code (measured on cornell_specular_area, 256x256, two
 * renders of 64 spp: 7 of 19 pairs flagged at family alpha 0.01; with the
 * neighbourhood's variance, 0 of 19: docs/calibration/README.md).  The
 * neighbours saw such paths, so their variance stands for the block's
 * when its own is smaller; the degrees of freedom stay the block's own
 * (fewer: the conservative side). */
static void
fill_block_variance(
    const struct image *render,
    const double *sums,
    const struct metrics_block_stats *s,
    double pixel_dof,
    const struct image *ref,
    const struct metrics_block_params *params,
    int index,
    struct metrics_block *b)
{
    const double *own = &sums[6 * (size_t)index];
    double around[3] = {0, 0, 0}, pixels_around = 0;
    int bx = index % s->blocks_x, by = index / s->blocks_x;
    for (int j = by - 1; j <= by + 1; j++) {
        for (int i = bx - 1; i <= bx + 1; i++) {
            if (i < 0 || j < 0 || i >= s->blocks_x || j >= s->blocks_y) {
                continue;
            }
            const struct metrics_block *nb = &s->blocks[j * s->blocks_x + i];
            pixels_around += (double)nb->w * (double)nb->h;
            for (int c = 0; c < 3; c++) {
                around[c] += sums[6 * (size_t)(j * s->blocks_x + i) + (size_t)c];
            }
        }
    }
    block_mean(render, b, b->mean);
    double n = (double)b->w * (double)b->h;
    for (int c = 0; c < 3; c++) {
        b->var_mean[c] = fmax(own[c], n * around[c] / pixels_around) / (n * n);
    }
    test_block(ref, params, index, sum_dof(own, pixel_dof), b);
}

/* The block parameters, and the render and its variance the reference's size. */
static bool
check_block_inputs(
    const struct image *render,
    const struct image *variance,
    const struct image *ref,
    const struct metrics_block_params *params,
    struct diag *err)
{
    if (params->block_size < 1 || !(params->ref_rel_se >= 0) || !(params->ref_dof >= 0)) {
        diag_set(err, NULL, 0, 0, "bad block parameters (size %d)", params->block_size);
        return false;
    }
    const struct image *images[2] = {render, variance};
    const char *names[2] = {"render", "variance"};
    for (int i = 0; i < 2; i++) {
        if (!same_size(images[i], ref)) {
            diag_set(
                err,
                NULL,
                0,
                0,
                "the %s is %dx%d but the reference is %dx%d",
                names[i],
                images[i]->width,
                images[i]->height,
                ref->width,
                ref->height);
            return false;
        }
    }
    return true;
}

/* The block size used (at most IMAGE_MAX_DIM: width + size - 1 fits an int) and
 * the blocks across (*bx) and down (*by) of a width x height image. */
static int
block_grid(int width, int height, int block_size, int *bx, int *by)
{
    int bs = block_size < IMAGE_MAX_DIM ? block_size : IMAGE_MAX_DIM;
    *bx = (width + bs - 1) / bs;
    *by = (height + bs - 1) / bs;
    return bs;
}

/* The windows of 2x2 blocks of a bx x by grid of blocks. */
static int
windows_of(int bx, int by)
{
    return bx > 1 && by > 1 ? (bx - 1) * (by - 1) : 0;
}

int
metrics_block_test_count(int width, int height, int block_size, bool windows)
{
    int bx, by;
    block_grid(width, height, block_size, &bx, &by);
    return bx * by + (windows ? windows_of(bx, by) : 0);
}

/* Cut ref's frame into blocks (rectangles set, statistics not). */
static bool
block_layout(
    const struct image *ref,
    const struct metrics_block_params *params,
    struct metrics_block_stats *out,
    struct diag *err)
{
    int bs = block_grid(ref->width, ref->height, params->block_size, &out->blocks_x, &out->blocks_y);
    out->n_blocks = out->blocks_x * out->blocks_y;
    out->blocks = calloc((size_t)out->n_blocks, sizeof *out->blocks);
    if (!out->blocks) {
        diag_set(err, NULL, 0, 0, "out of memory for %d blocks", out->n_blocks);
        return false;
    }
    for (int i = 0; i < out->n_blocks; i++) {
        struct metrics_block *b = &out->blocks[i];
        b->x0 = (i % out->blocks_x) * bs;
        b->y0 = (i / out->blocks_x) * bs;
        b->w = ref->width - b->x0 < bs ? ref->width - b->x0 : bs;
        b->h = ref->height - b->y0 < bs ? ref->height - b->y0 : bs;
    }
    return true;
}

/* Window w of s: blocks (i..i+1, j..j+1) merged.  The variance of its
 * mean is the sum of its blocks' (n_b^2 var_mean_b, each already at least
 * its neighbourhood's) over N^2; its degrees of freedom are
 * Welch-Satterthwaite's over its pixels, as for a block; the reference's
 * SE combines its blocks' the same way. */
static void
fill_window(
    const struct image *render,
    const double *sums,
    double pixel_dof,
    const struct image *ref,
    const struct metrics_block_params *params,
    const struct metrics_block_stats *s,
    int w,
    struct metrics_block *out)
{
    int i = w % (s->blocks_x - 1), j = w / (s->blocks_x - 1);
    const struct metrics_block *b00 = &s->blocks[j * s->blocks_x + i];
    *out = (struct metrics_block){
        .x0 = b00->x0,
        .y0 = b00->y0,
        .w = b00->w + b00[1].w,
        .h = b00->h + b00[s->blocks_x].h,
        .window = true,
    };
    double n_total = (double)out->w * (double)out->h, var[3] = {0}, se2[3] = {0}, own[6] = {0};
    for (int q = 0; q < 4; q++) {
        int index = (j + q / 2) * s->blocks_x + i + q % 2;
        const struct metrics_block *b = &s->blocks[index];
        double n = (double)b->w * (double)b->h;
        for (int c = 0; c < 3; c++) {
            var[c] += n * n * b->var_mean[c];
            se2[c] += n * n * b->ref_se[c] * b->ref_se[c];
            own[c] += sums[6 * (size_t)index + (size_t)c];
            own[3 + c] += sums[6 * (size_t)index + 3 + (size_t)c];
        }
    }
    block_mean(render, out, out->mean);
    block_mean(ref, out, out->ref_mean);
    double dof = sum_dof(own, pixel_dof);
    for (int c = 0; c < 3; c++) {
        out->var_mean[c] = var[c] / (n_total * n_total);
        out->ref_se[c] = sqrt(se2[c]) / n_total;
        test_channel(out, c, dof, params->ref_dof);
    }
}

bool
metrics_block_stats_variance(
    const struct image *render,
    const struct image *variance,
    double pixel_dof,
    const struct image *ref,
    const struct metrics_block_params *params,
    struct metrics_block_stats *out,
    struct diag *err)
{
    *out = (struct metrics_block_stats){0};
    if (!(pixel_dof >= 0)) {
        diag_set(err, NULL, 0, 0, "bad degrees of freedom %g", pixel_dof);
        return false;
    }
    if (!check_block_inputs(render, variance, ref, params, err) || !block_layout(ref, params, out, err)) {
        return false;
    }
    double *sums = malloc((size_t)out->n_blocks * 6 * sizeof *sums);
    if (!sums) {
        metrics_block_stats_free(out);
        diag_set(err, NULL, 0, 0, "out of memory for %d blocks", out->n_blocks);
        return false;
    }
    for (int i = 0; i < out->n_blocks; i++) {
        block_variance_sums(variance, &out->blocks[i], &sums[6 * (size_t)i]);
    }
    for (int i = 0; i < out->n_blocks; i++) {
        fill_block_variance(render, sums, out, pixel_dof, ref, params, i, &out->blocks[i]);
    }
    out->n_windows = params->windows ? windows_of(out->blocks_x, out->blocks_y) : 0;
    out->windows = out->n_windows ? calloc((size_t)out->n_windows, sizeof *out->windows) : NULL;
    bool ok = out->n_windows == 0 || out->windows;
    for (int w = 0; ok && w < out->n_windows; w++) {
        fill_window(render, sums, pixel_dof, ref, params, out, w, &out->windows[w]);
    }
    free(sums);
    if (!ok) {
        diag_set(err, NULL, 0, 0, "out of memory for %d windows", out->n_windows);
        metrics_block_stats_free(out);
    }
    return ok;
}

void
metrics_block_stats_free(struct metrics_block_stats *s)
{
    free(s->blocks);
    free(s->windows);
    *s = (struct metrics_block_stats){0};
}

const struct metrics_block *
metrics_block_test(const struct metrics_block_stats *s, int i)
{
    return i < s->n_blocks ? &s->blocks[i] : &s->windows[i - s->n_blocks];
}

size_t
metrics_block_rejections(const struct metrics_block_stats *s, double alpha, double *min_p)
{
    int n = s->n_blocks + s->n_windows;
    double level = stattest_sidak(alpha, 3.0 * n);
    double lowest = 1;
    size_t rejected = 0;
    for (int i = 0; i < n; i++) {
        for (int c = 0; c < 3; c++) {
            double p = metrics_block_test(s, i)->p[c];
            lowest = fmin(lowest, p);
            rejected += !(p >= level);
        }
    }
    if (min_p) {
        *min_p = lowest;
    }
    return rejected;
}

/* ---- what the tests can find ------------------------------------------- */

/* The shift, in standard errors, that a test at `level` finds with
 * probability `power` (metrics.h): t_level + t_power at the test's dof. */
static double
findable_shift(double level, double power, double dof)
{
    return stattest_t_critical(level, dof) + stattest_t_critical(2 * (1 - power), dof);
}

double
metrics_detectable_bias(const struct metrics_block *b, double level, double power)
{
    double best = NAN;
    for (int c = 0; c < 3; c++) {
        double se = sqrt(b->var_mean[c] + b->ref_se[c] * b->ref_se[c]);
        double delta = findable_shift(level, power, b->dof[c]) * se / fabs(b->ref_mean[c]);
        if (isfinite(delta) && !(delta >= best)) {
            best = delta;
        }
    }
    return best;
}

double
metrics_samples_for_bias(const struct metrics_block *b, double level, double power, double bias)
{
    double best = NAN;
    for (int c = 0; c < 3; c++) {
        /* The variance that lets the bias show: (bias |ref| / shift)^2 =
         * var_mean / factor + ref_se^2. */
        double se_needed = bias * fabs(b->ref_mean[c]) / findable_shift(level, power, b->dof[c]);
        double room = se_needed * se_needed - b->ref_se[c] * b->ref_se[c];
        double factor = room > 0 ? b->var_mean[c] / room : INFINITY;
        if (b->ref_mean[c] != 0 && !isnan(se_needed) && !(factor >= best)) {
            best = factor;
        }
    }
    return best;
}

static int
by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The q-quantile of the n sorted values v (the smallest value at least a
 * fraction q of them do not exceed). */
static double
quantile_sorted(const double *v, int n, double q)
{
    int i = (int)ceil(q * n) - 1;
    return v[i < 0 ? 0 : i];
}

bool
metrics_block_power(
    const struct metrics_block_stats *s,
    double level,
    double power,
    double target,
    struct metrics_power *out,
    struct diag *err)
{
    *out = (struct metrics_power){0, NAN, NAN, NAN};
    const struct metrics_block *tests = s->n_windows > 0 ? s->windows : s->blocks;
    int n = s->n_windows > 0 ? s->n_windows : s->n_blocks;
    size_t cap = n > 0 ? (size_t)n : 1;
    double *bias = malloc(2 * cap * sizeof *bias);
    if (!bias) {
        diag_set(err, NULL, 0, 0, "out of memory");
        return false;
    }
    double *samples = bias + cap;
    for (int i = 0; i < n; i++) {
        double d = metrics_detectable_bias(&tests[i], level, power);
        if (!isnan(d)) {
            samples[out->n] = metrics_samples_for_bias(&tests[i], level, power, target);
            bias[out->n++] = d;
        }
    }
    if (out->n > 0) {
        qsort(bias, (size_t)out->n, sizeof *bias, by_value);
        qsort(samples, (size_t)out->n, sizeof *samples, by_value);
        out->bias_half = quantile_sorted(bias, out->n, 0.5);
        out->bias_most = quantile_sorted(bias, out->n, 0.9);
        out->samples_most = quantile_sorted(samples, out->n, 0.9);
    }
    free(bias);
    return true;
}

void
metrics_format_plain(char *buf, size_t cap, double v)
{
    double a = fabs(v);
    /* Decimals for two significant digits below 10 (0.0031: 4); none at
     * 10 and above.  At most 9: smaller numbers print as 0. */
    int decimals = a > 0 && a < 10 ? 1 - (int)floor(log10(a)) : 0;
    snprintf(buf, cap, "%.*f", decimals < 9 ? decimals : 9, v);
}
