/*
 * paired.c - a student's render against the solution's render made with the
 * same seeds: the paired differences per block, tested against a minimum
 * effect (issue 50's paired pages; docs/calibration/README.md, "Paired
 * comparison").
 *
 *   paired [--block N] [--effect F] [--alpha A] STUDENT.pfm SOLUTION.pfm
 *
 * Where the student's code draws its random numbers as the solution does
 * (lab 07's functions are given theirs: sample_bsdf(..., u, ...)), the two
 * renders share their paths and differ only by what the code computes
 * differently: the difference d = student - solution has almost no noise,
 * and a bias shows at a few samples per pixel.  Where the student draws
 * them otherwise, d holds both renders' noise: the test stays valid (its
 * standard error is d's own spread) and is as weak as the comparison of
 * two independent renders, which the output says ("unpaired").
 *
 * For each N x N block (default 16: any 32x32 square holds a whole one, so
 * a bias in a 32x32 square is a bias of at least one block) and channel:
 * the mean of d, its standard error from d's spread over the block's
 * pixels, and the solution's mean m.  The block is "off" when |mean d|
 * exceeds F |m| (the minimum effect, default 0.01: a difference of
 * floating-point order or a fraction of a percent is never a failure) by
 * more than t standard errors, t Student's quantile (pixels - 1 degrees of
 * freedom) of alpha (default 0.01) Sidak-corrected for the number of
 * blocks and channels.  A block whose d is exactly 0 is identical.
 *
 * Pairing: the ratio of d's noise variance to the sum of the two renders'
 * (Immerkaer's estimator, which cancels most of an image's structure):
 * about 1 for independent renders, near 0 for paired ones.  Below 0.5 the
 * renders are called paired.
 *
 * Prints one line per off block and channel (worst first, at most 10), then
 *   paired: RATIO (paired|unpaired...), OFF of N blocks and channels off by more than F%:
 * biased|consistent Exit status: 0 consistent, 1 biased, 2 unreadable input, size mismatch or bad
 * usage.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "imgread.h"
#include "stattest.h"

struct options {
    int block;
    double effect, alpha;
    const char *student, *solution;
};

static int
usage(FILE *f)
{
    fputs("usage: paired [--block N] [--effect F] [--alpha A] STUDENT.pfm SOLUTION.pfm\n", f);
    return 2;
}

static bool
parse(int argc, char **argv, struct options *o)
{
    *o = (struct options){.block = 16, .effect = 0.01, .alpha = 0.01};
    int i = 1;
    for (; i + 1 < argc && argv[i][0] == '-' && argv[i][1] == '-'; i += 2) {
        char *end = NULL;
        double v = strtod(argv[i + 1], &end);
        if (!end || *end || !(v > 0)) {
            fprintf(stderr, "paired: %s needs a positive number, got '%s'\n", argv[i], argv[i + 1]);
            return false;
        }
        if (strcmp(argv[i], "--block") == 0 && v == floor(v) && v <= 4096) {
            o->block = (int)v;
        } else if (strcmp(argv[i], "--effect") == 0 && v < 1) {
            o->effect = v;
        } else if (strcmp(argv[i], "--alpha") == 0 && v < 1) {
            o->alpha = v;
        } else {
            fprintf(stderr, "paired: unknown option or bad value: %s %s\n", argv[i], argv[i + 1]);
            return false;
        }
    }
    if (argc - i != 2) {
        return false;
    }
    o->student = argv[i];
    o->solution = argv[i + 1];
    return true;
}

/* Immerkaer's noise filter at an interior pixel ("Fast Noise Variance
 * Estimation", CVIU 64(2), 1996): the 3x3 mask [1 -2 1; -2 4 -2; 1 -2 1],
 * a difference of two Laplacians that cancels flat areas and linear
 * gradients, and much of an edge, leaving noise: its mean absolute value
 * times sqrt(pi / 2) / 6 estimates the noise's standard deviation. */
static double
noise_filter(const struct image *im, int x, int y, int c)
{
    static const int mask[3][3] = {{1, -2, 1}, {-2, 4, -2}, {1, -2, 1}};
    double sum = 0;
    for (int dy = -1; dy <= 1; dy++) {
        for (int dx = -1; dx <= 1; dx++) {
            size_t k = ((size_t)(y + dy) * (size_t)im->width + (size_t)(x + dx)) * 3 + (size_t)c;
            sum += mask[dy + 1][dx + 1] * (double)im->rgb[k];
        }
    }
    return sum;
}

/* The difference's noise variance over the sum of the two renders' (each
 * by Immerkaer's estimator, over the interior pixels): about 1 for
 * independent renders, near 0 for renders of the same paths. */
static double
pairing_ratio(const struct image *s, const struct image *r)
{
    double ns = 0;
    double nr = 0;
    double nd = 0;
    for (int y = 1; y + 1 < s->height; y++) {
        for (int x = 1; x + 1 < s->width; x++) {
            for (int c = 0; c < 3; c++) {
                double fs = noise_filter(s, x, y, c);
                double fr = noise_filter(r, x, y, c);
                ns += fabs(fs);
                nr += fabs(fr);
                nd += fabs(fs - fr);
            }
        }
    }
    return ns + nr > 0 ? nd * nd / (ns * ns + nr * nr) : 0;
}

struct block_result {
    int x, y, c;
    double mean_d, se, mean_r, excess; /* (|mean d| - F |m|) / se, less the block's critical t */
};

static int
by_excess(const void *a, const void *b)
{
    double ea = ((const struct block_result *)a)->excess;
    double eb = ((const struct block_result *)b)->excess;
    return (ea < eb) - (ea > eb);
}

/* The verdict on two images of one size: 0 consistent, 1 biased, 2 out of
 * memory.  The caller owns (and frees) the images. */
static int
compare_images(const struct options *o, const struct image *s, const struct image *r)
{
    int bx = (s->width + o->block - 1) / o->block;
    int by = (s->height + o->block - 1) / o->block;
    int tests = bx * by * 3;
    double level = stattest_sidak(o->alpha, tests);
    struct block_result *res = calloc((size_t)tests, sizeof *res);
    if (!res) {
        fputs("paired: out of memory\n", stderr);
        return 2;
    }
    int off = 0;
    int n_res = 0;
    for (int j = 0; j < by; j++) {
        for (int i = 0; i < bx; i++) {
            for (int c = 0; c < 3; c++) {
                struct stattest_welford wd = {0};
                double sum_r = 0;
                int n = 0;
                for (int y = j * o->block; y < (j + 1) * o->block && y < s->height; y++) {
                    for (int x = i * o->block; x < (i + 1) * o->block && x < s->width; x++) {
                        size_t k = ((size_t)y * (size_t)s->width + (size_t)x) * 3 + (size_t)c;
                        stattest_welford_add(&wd, (double)s->rgb[k] - (double)r->rgb[k]);
                        sum_r += r->rgb[k];
                        n++;
                    }
                }
                double mean_r = sum_r / n;
                double se = n > 1 ? sqrt(stattest_welford_var_of_mean(&wd)) : 0;
                double gap = fabs(wd.mean) - o->effect * fabs(mean_r);
                double excess = gap <= 0 ? -INFINITY : se > 0 ? gap / se : INFINITY;
                /* One-sided: the block is off only when it exceeds the
                 * effect by more than Student's t quantile of its pixels. */
                double z = n > 1 ? stattest_t_critical(2 * level, n - 1) : INFINITY;
                if (!isfinite(wd.mean)) {
                    excess = INFINITY; /* a NaN or an infinity is never consistent */
                }
                res[n_res++] = (struct block_result){i, j, c, wd.mean, se, mean_r, excess - z};
                off += excess > z;
            }
        }
    }
    qsort(res, (size_t)n_res, sizeof *res, by_excess);
    static const char *const channel[] = {"red", "green", "blue"};
    for (int k = 0; k < n_res && k < 10 && res[k].excess > 0; k++) {
        printf(
            "  block x %d-%d, y %d-%d, %s: the student's mean differs by %+.3g (%+.2f%% of %.4g), +- %.2g\n",
            res[k].x * o->block,
            res[k].x * o->block + o->block - 1,
            res[k].y * o->block,
            res[k].y * o->block + o->block - 1,
            channel[res[k].c],
            res[k].mean_d,
            res[k].mean_r != 0 ? 100 * res[k].mean_d / res[k].mean_r : 0.0,
            res[k].mean_r,
            res[k].se);
    }
    double ratio = pairing_ratio(s, r);
    printf(
        "paired: %.3f (%s), %d of %d blocks and channels off by more than %g%%: %s\n",
        ratio,
        ratio < 0.5 ? "paired" : "unpaired: as two independent renders",
        off,
        tests,
        100 * o->effect,
        off > 0 ? "biased" : "consistent");
    free(res);
    return off > 0;
}

int
main(int argc, char **argv)
{
    struct options o;
    if (argc == 2 && strcmp(argv[1], "--help") == 0) {
        usage(stdout);
        return 0;
    }
    if (!parse(argc, argv, &o)) {
        return usage(stderr);
    }
    struct image s = {0};
    struct image r = {0};
    struct diag err;
    int status = 2;
    if (!imgread(o.student, &s, &err) || !imgread(o.solution, &r, &err)) {
        diag_print(stderr, &err, "error");
    } else if (s.width != r.width || s.height != r.height) {
        fprintf(
            stderr,
            "paired: %s is %dx%d, %s %dx%d\n",
            o.student,
            s.width,
            s.height,
            o.solution,
            r.width,
            r.height);
    } else {
        status = compare_images(&o, &s, &r);
    }
    image_free(&s);
    image_free(&r);
    return status;
}
