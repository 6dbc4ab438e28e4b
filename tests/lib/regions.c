/*
 * regions.c - a render's error by region of a label image (regions.h).
 */
#include "regions.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "aov.h"
#include "metrics.h"
#include "stattest.h"

/* Sums over the compared pixels of one region, or of its part in one
 * block. */
struct sums {
    size_t n;
    bool nonfinite; /* a pixel had a NaN or infinite value */
    double x[3], r[3]; /* render, reference */
    double v[3], v2[3]; /* the render's per-pixel variance, and its square */
    double rel2; /* relMSE's numerator summed over pixels (mean of channels) */
    double px, py; /* pixel coordinates, for the centroid */
};

static void
add_pixel(struct sums *s, const struct region_inputs *in, int x, int y)
{
    const float *a = image_pixel(in->render, x, y);
    const float *b = image_pixel(in->reference, x, y);
    const float *v = in->variance->rgb ? image_pixel(in->variance, x, y) : NULL;
    bool finite = true;
    for (int c = 0; c < 3; c++) {
        finite = finite && isfinite(a[c]) && isfinite(b[c]);
    }
    if (!finite) {
        s->nonfinite = true;
        return;
    }
    s->n++;
    double rel2 = 0;
    for (int c = 0; c < 3; c++) {
        s->x[c] += a[c];
        s->r[c] += b[c];
        s->v[c] += v ? v[c] : 0;
        s->v2[c] += v ? (double)v[c] * v[c] : 0;
        rel2 += ((double)a[c] - b[c]) * ((double)a[c] - b[c])
                / ((double)b[c] * b[c] + METRICS_RELMSE_EPS);
    }
    s->rel2 += rel2 / 3;
    s->px += x;
    s->py += y;
}

static void
add_sums(struct sums *into, const struct sums *from)
{
    into->n += from->n;
    into->nonfinite = into->nonfinite || from->nonfinite;
    for (int c = 0; c < 3; c++) {
        into->x[c] += from->x[c];
        into->r[c] += from->r[c];
        into->v[c] += from->v[c];
        into->v2[c] += from->v2[c];
    }
    into->rel2 += from->rel2;
    into->px += from->px;
    into->py += from->py;
}

/* The t-tests of the pixels summed in s, one per channel: the render's
 * mean (its squared SE the summed variances over n^2, pixels being
 * independent; Welch-Satterthwaite's degrees of freedom from pixel_dof
 * each) against the reference's (SE ref_rel_se (|mean| + 0.01) / sqrt(n)).
 * The summed variance is at least floor (NULL: no floor), what the
 * pixels around them give (floors()).  Rare bright paths (caustics,
 * light through glass, their images in a mirror) make a mean heavy-tailed,
 * and its own variance falls with it: two renders that missed more of
 * them than usual look darker and less noisy at once (correct renders of
 * cornell_specular_area flagged in 7 of 19 pairs, 256x256, 64 spp, without
 * a floor: docs/calibration/README.md).  The pixels around saw such paths;
 * the degrees of freedom stay the pixels' own (fewer: conservative). */
static void
test_sums(
    const struct sums *s,
    const double *floor,
    const struct region_inputs *in,
    double mean[3],
    double ref_mean[3],
    double t[3],
    double p[3])
{
    double n = (double)s->n;
    for (int c = 0; c < 3; c++) {
        mean[c] = s->n ? s->x[c] / n : NAN;
        ref_mean[c] = s->n ? s->r[c] / n : NAN;
        if (s->nonfinite || s->n == 0) {
            t[c] = NAN;
            p[c] = s->nonfinite ? 0 : 1;
            continue;
        }
        double var_mean = fmax(s->v[c], floor ? floor[c] : 0) / (n * n);
        double dof =
            in->pixel_dof > 0 && s->v2[c] > 0 ? s->v[c] * s->v[c] / (s->v2[c] / in->pixel_dof) : 0;
        /* Near black a relative SE means nothing (a sliver of light at a
         * shadow's edge is 100% noise): relative to the value plus relMSE's
         * floor, the scale below which errors count as noise. */
        double ref_se = in->ref_rel_se * (fabs(ref_mean[c]) + METRICS_RELMSE_EPS) / sqrt(n);
        struct stattest_result res = stattest_t_test_estimates(
            mean[c],
            var_mean,
            dof,
            ref_mean[c],
            ref_se * ref_se,
            in->ref_dof);
        t[c] = res.t;
        p[c] = isnan(res.p) ? 0 : res.p;
    }
}

static double
min3(const double v[3])
{
    return fmin(v[0], fmin(v[1], v[2]));
}

/* The largest |t| of three (NaN: infinite, a certain rejection). */
static double
max_abs3(const double t[3])
{
    double m = 0;
    for (int c = 0; c < 3; c++) {
        m = fmax(m, isnan(t[c]) ? INFINITY : fabs(t[c]));
    }
    return m;
}

/* Whether every channel of both means is below relMSE's floor: a part of
 * a region that is black in both images (an umbra's corner under direct
 * light) is not tested on its own, where a sliver of light at its edge
 * that a few samples missed would be "infinitely" significant. */
static bool
near_black(const double mean[3], const double ref_mean[3])
{
    for (int c = 0; c < 3; c++) {
        if (!(fabs(mean[c]) < METRICS_RELMSE_EPS && fabs(ref_mean[c]) < METRICS_RELMSE_EPS)) {
            return false;
        }
    }
    return true;
}

/* Whether a region's part in a block is tested on its own. */
static bool
block_tested(const struct sums *cell)
{
    return cell->n >= REGIONS_MIN_BLOCK_PIXELS || cell->nonfinite;
}

static bool
check_inputs(const struct region_inputs *in, struct diag *err)
{
    const struct image *ref = in->reference;
    const struct image *others[3] = {in->render, in->labels, in->variance};
    const char *names[3] = {"render", "label image", "variance image"};
    for (int i = 0; i < 3; i++) {
        if (others[i]->rgb
            && (others[i]->width != ref->width || others[i]->height != ref->height)) {
            diag_set(
                err,
                NULL,
                0,
                0,
                "the %s is %dx%d but the reference is %dx%d",
                names[i],
                others[i]->width,
                others[i]->height,
                ref->width,
                ref->height);
            return false;
        }
    }
    if (in->block_size < 1) {
        diag_set(err, NULL, 0, 0, "bad block size %d", in->block_size);
        return false;
    }
    size_t n = (size_t)ref->width * (size_t)ref->height;
    for (size_t i = 0; i < n; i++) {
        float v = in->labels->rgb[3 * i];
        if (!(v >= 0 && v < REGIONS_MAX && v == floorf(v))) {
            diag_set(
                err,
                NULL,
                0,
                0,
                "the label image holds %g at pixel (%zu, %zu): labels are whole numbers in "
                "[0, %d) (a --aov feature pass)",
                v,
                i % (size_t)ref->width,
                i / (size_t)ref->width,
                REGIONS_MAX);
            return false;
        }
    }
    return true;
}

static int
label_at(const struct region_inputs *in, int x, int y)
{
    return (int)image_pixel(in->labels, x, y)[0];
}

/* The region's pixel in block (bx, by) nearest the centroid of its pixels
 * there. */
static void
pick_pixel(const struct region_inputs *in, const struct sums *cell, struct region_result *r)
{
    double cx = cell->px / (double)cell->n, cy = cell->py / (double)cell->n;
    double best = INFINITY;
    for (int y = r->y0; y < r->y0 + r->h; y++) {
        for (int x = r->x0; x < r->x0 + r->w; x++) {
            size_t i = (size_t)y * (size_t)in->reference->width + (size_t)x;
            double d = (x - cx) * (x - cx) + (y - cy) * (y - cy);
            if (label_at(in, x, y) == r->label && (!in->mask || in->mask[i]) && d < best) {
                best = d;
                r->pixel_x = x;
                r->pixel_y = y;
            }
        }
    }
}

/* The mean per-pixel variance of the 3x3 blocks around each block, all
 * regions together (around: 3 per block): a set of pixels' summed variance
 * is at least, pixel by pixel, what the blocks around them give, as a
 * block's is in metrics.c.  A small region (a penumbra's sliver, what the
 * mirror shows of the background) that missed the rare paths as a whole
 * is held to the variance of the pixels around it. */
static void
floors(const struct sums *cells, int blocks_x, int blocks_y, double *around)
{
    for (int b = 0; b < blocks_x * blocks_y; b++) {
        int bx = b % blocks_x, by = b / blocks_x;
        double v[3] = {0, 0, 0}, n = 0;
        for (int j = by - 1; j <= by + 1; j++) {
            for (int i = bx - 1; i <= bx + 1; i++) {
                if (i < 0 || j < 0 || i >= blocks_x || j >= blocks_y) {
                    continue;
                }
                for (int label = 0; label < REGIONS_MAX; label++) {
                    const struct sums *cell = &cells[(size_t)(j * blocks_x + i) * REGIONS_MAX + (size_t)label];
                    n += (double)cell->n;
                    for (int c = 0; c < 3; c++) {
                        v[c] += cell->v[c];
                    }
                }
            }
        }
        for (int c = 0; c < 3; c++) {
            around[3 * (size_t)b + (size_t)c] = n > 0 ? v[c] / n : 0;
        }
    }
}

/* The region's block tests (or, without noise, its block of largest
 * error): the most significant one becomes the region's block. */
static void
judge_blocks(
    const struct region_inputs *in,
    const struct sums *cells,
    const struct sums *whole,
    const double *around,
    int blocks_x,
    int n_blocks,
    double level,
    bool noise,
    struct region_result *r)
{
    double best = INFINITY;
    int best_block = -1;
    for (int b = 0; b < n_blocks; b++) {
        const struct sums *cell = &cells[(size_t)b * REGIONS_MAX + (size_t)r->label];
        if (cell->n == 0 && !cell->nonfinite) {
            continue;
        }
        double mean[3], ref_mean[3], t[3], p[3], floor[3];
        for (int c = 0; c < 3; c++) {
            double region_pixel = whole->n ? whole->v[c] / (double)whole->n : 0;
            floor[c] = (double)cell->n * fmax(region_pixel, around[3 * (size_t)b + (size_t)c]);
        }
        test_sums(cell, floor, in, mean, ref_mean, t, p);
        /* Parts too small to test are chosen only when none is tested:
         * then the largest. */
        bool tested = !noise || (block_tested(cell) && !near_black(mean, ref_mean));
        double score = !tested ? 2 + 1 / (1 + (double)cell->n) : noise ? min3(p) : -cell->rel2;
        if (tested) {
            r->n_blocks++;
            r->n_failing_blocks += noise && !(min3(p) >= level);
        }
        double best_t = best_block >= 0 ? max_abs3(r->block_t) : 0;
        bool more = score < best || (score == best && max_abs3(t) > best_t);
        if (more || best_block < 0) {
            best = score;
            best_block = b;
            for (int c = 0; c < 3; c++) {
                r->block_mean[c] = mean[c];
                r->block_ref_mean[c] = ref_mean[c];
                r->block_t[c] = t[c];
                r->block_p[c] = p[c];
            }
        }
    }
    if (best_block < 0) {
        return;
    }
    int bs = in->block_size;
    r->x0 = (best_block % blocks_x) * bs;
    r->y0 = (best_block / blocks_x) * bs;
    r->w = r->x0 + bs <= in->reference->width ? bs : in->reference->width - r->x0;
    r->h = r->y0 + bs <= in->reference->height ? bs : in->reference->height - r->y0;
    r->min_p = noise && best <= 1 ? fmin(r->min_p, best) : r->min_p;
    const struct sums *cell = &cells[(size_t)best_block * REGIONS_MAX + (size_t)r->label];
    if (cell->n > 0) {
        pick_pixel(in, cell, r);
    }
}

bool
regions_compare(const struct region_inputs *in, struct region_report *out, struct diag *err)
{
    *out = (struct region_report){.noise = in->variance->rgb != NULL, .max_relmse = in->max_relmse};
    if (!check_inputs(in, err)) {
        return false;
    }
    int width = in->reference->width, height = in->reference->height, bs = in->block_size;
    int blocks_x = (width + bs - 1) / bs, blocks_y = (height + bs - 1) / bs;
    int n_blocks = blocks_x * blocks_y;
    struct sums *cells = calloc((size_t)n_blocks * REGIONS_MAX, sizeof *cells);
    double *around = malloc((size_t)n_blocks * 3 * sizeof *around);
    if (!cells || !around) {
        free(cells);
        free(around);
        diag_set(err, NULL, 0, 0, "out of memory");
        return false;
    }
    struct sums whole[REGIONS_MAX] = {{0}};
    for (int y = 0; y < height; y++) {
        for (int x = 0; x < width; x++) {
            if (in->mask && !in->mask[(size_t)y * (size_t)width + (size_t)x]) {
                continue;
            }
            int b = (y / bs) * blocks_x + x / bs;
            add_pixel(&cells[(size_t)b * REGIONS_MAX + (size_t)label_at(in, x, y)], in, x, y);
        }
    }
    int present_blocks = 0;
    for (int b = 0; b < n_blocks; b++) {
        for (int label = 0; label < REGIONS_MAX; label++) {
            const struct sums *cell = &cells[(size_t)b * REGIONS_MAX + (size_t)label];
            add_sums(&whole[label], cell);
            present_blocks += block_tested(cell);
        }
    }
    for (int label = 0; label < REGIONS_MAX; label++) {
        if (whole[label].n > 0 || whole[label].nonfinite) {
            out->n_regions++;
        }
    }
    floors(cells, blocks_x, blocks_y, around);
    out->n_tests = 3 * (out->n_regions + present_blocks);
    int family = out->n_tests + in->other_tests;
    out->level = family > 0 ? stattest_sidak(in->alpha, family) : in->alpha;
    int k = 0;
    for (int label = 0; label < REGIONS_MAX; label++) {
        const struct sums *s = &whole[label];
        if (s->n == 0 && !s->nonfinite) {
            continue;
        }
        struct region_result *r = &out->regions[k++];
        *r = (struct region_result){.label = label, .n_pixels = s->n, .pixel_x = -1, .pixel_y = -1};
        r->relmse = s->n ? s->rel2 / (double)s->n : NAN;
        double floor[3] = {0, 0, 0};
        for (int b = 0; b < n_blocks; b++) {
            for (int c = 0; c < 3; c++) {
                floor[c] += (double)cells[(size_t)b * REGIONS_MAX + (size_t)label].n
                            * around[3 * (size_t)b + (size_t)c];
            }
        }
        test_sums(s, floor, in, r->mean, r->ref_mean, r->t, r->p);
        r->min_p = out->noise ? min3(r->p) : 1;
        r->whole_rejects = out->noise && !(min3(r->p) >= out->level);
        judge_blocks(in, cells, s, around, blocks_x, n_blocks, out->level, out->noise, r);
        if (out->noise) {
            r->biased = r->whole_rejects || r->n_failing_blocks > 0;
        } else {
            r->biased = s->nonfinite || (in->max_relmse > 0 && !(r->relmse <= in->max_relmse));
        }
    }
    free(cells);
    free(around);
    return true;
}

/* How far a region's mean is from the reference's: the largest over the
 * channels of |mean - ref| / (|ref| + 0.01) (relMSE's floor keeps black
 * regions from dividing by 0). */
static double
mean_error(const struct region_result *r)
{
    double e = 0;
    for (int c = 0; c < 3; c++) {
        double d = fabs(r->mean[c] - r->ref_mean[c]) / (fabs(r->ref_mean[c]) + 0.01);
        e = fmax(e, isnan(d) ? INFINITY : d);
    }
    return e;
}

/* Biased first, the one whose mean is furthest from the reference's
 * first: where the error is largest, not where it is most certain (a
 * small bias over a large region can be more significant than a large
 * one over a small region, and p-values of different degrees of freedom
 * underflow at different |t|); then by label. */
static int
by_significance(const void *pa, const void *pb)
{
    const struct region_result *a = pa, *b = pb;
    if (a->biased != b->biased) {
        return a->biased ? -1 : 1;
    }
    double ea = mean_error(a), eb = mean_error(b);
    if (a->biased && ea != eb) {
        return ea > eb ? -1 : 1;
    }
    return (a->label > b->label) - (a->label < b->label);
}

void
regions_sort(struct region_report *rep)
{
    qsort(rep->regions, (size_t)rep->n_regions, sizeof rep->regions[0], by_significance);
}

const char *
regions_label_name(int label, char *buf, size_t cap)
{
    if (label >= 0 && label < LABEL_COUNT) {
        return aov_label_names[label];
    }
    snprintf(buf, cap, "label %d", label);
    return buf;
}

int
regions_describe_difference(
    char *buf,
    size_t cap,
    const double mean[3],
    const double ref_mean[3],
    const double t[3],
    const double p[3],
    bool noise)
{
    /* Channels by letter: the error map's colours (blue darker, red
     * brighter) are not the channels'. */
    static const char names[3] = {'R', 'G', 'B'};
    int ch = 0;
    for (int c = 1; c < 3; c++) {
        double rel_c = fabs(mean[c] - ref_mean[c]) / fmax(fabs(ref_mean[c]), 1e-12);
        double rel_ch = fabs(mean[ch] - ref_mean[ch]) / fmax(fabs(ref_mean[ch]), 1e-12);
        if (noise ? p[c] < p[ch] : rel_c > rel_ch) {
            ch = c;
        }
    }
    double diff = mean[ch] - ref_mean[ch];
    if (!isfinite(mean[ch])) {
        return snprintf(buf, cap, "NaN or infinite pixels");
    }
    if (diff == 0) {
        return snprintf(buf, cap, "equal to the reference");
    }
    char size[64];
    double size_of = ref_mean[ch] != 0 ? fabs(100 * diff / ref_mean[ch]) : fabs(diff);
    metrics_format_plain(size, sizeof size, size_of);
    int n = snprintf(
        buf,
        cap,
        ref_mean[ch] != 0 ? "%s%% %s than the reference (channel %c)"
                          : "%s %s than the reference's 0 (channel %c)",
        size,
        diff < 0 ? "darker" : "brighter",
        names[ch]);
    if (noise && n >= 0 && (size_t)n < cap) {
        metrics_format_plain(size, sizeof size, fabs(t[ch]));
        n += isinf(t[ch]) ? snprintf(buf + n, cap - (size_t)n, ", and no noise to explain it")
                          : snprintf(buf + n, cap - (size_t)n, ", %s standard errors", size);
    }
    return n;
}

void
regions_describe(
    char *buf,
    size_t cap,
    const struct region_result *r,
    const struct region_report *rep)
{
    int n;
    if (!rep->noise) {
        n = regions_describe_difference(buf, cap, r->mean, r->ref_mean, r->t, r->p, false);
        if (n >= 0 && (size_t)n < cap) {
            snprintf(
                buf + n,
                cap - (size_t)n,
                ", relMSE %.3g%s",
                r->relmse,
                !(rep->max_relmse > 0) ? ""
                : r->biased            ? ": over the limit"
                                       : ": under the limit");
        }
        return;
    }
    if (!r->biased || r->whole_rejects) {
        n = regions_describe_difference(buf, cap, r->mean, r->ref_mean, r->t, r->p, true);
        if (n >= 0 && (size_t)n < cap) {
            snprintf(buf + n, cap - (size_t)n, ": %s", r->biased ? "biased" : "consistent");
        }
        return;
    }
    /* The region as a whole is within noise, a block of it is not. */
    n = snprintf(
        buf,
        cap,
        "consistent as a whole, but in the block at x %d-%d, y %d-%d ",
        r->x0,
        r->x0 + r->w - 1,
        r->y0,
        r->y0 + r->h - 1);
    if (n >= 0 && (size_t)n < cap) {
        n += regions_describe_difference(
            buf + n,
            cap - (size_t)n,
            r->block_mean,
            r->block_ref_mean,
            r->block_t,
            r->block_p,
            true);
    }
    if (n >= 0 && (size_t)n < cap) {
        snprintf(buf + n, cap - (size_t)n, ": biased");
    }
}
