/*
 * regions.h - where a render is wrong: its error against a reference,
 * broken down by the regions of a label image (the reference scene's
 * `feature` pass, docs/aov.md: diffuse-lit, penumbra, umbra, mirror, glass,
 * caustic, emitter, background).
 *
 * With the render's noise known (a per-pixel variance: the spread of k >= 2
 * renders, or given), each region is tested as a whole and in each of the
 * blocks it meets (block size as compare's; parts of at least
 * REGIONS_MIN_BLOCK_PIXELS pixels, not black in both images): per channel, Welch's t-test of
 * the render's mean over the region's pixels against the reference's
 * (metrics.h's block test restricted to the region's pixels).  Every test
 * of every region is one of a family, Sidak-corrected at level alpha (with
 * other_tests, compare's block tests): a region is biased when one of its
 * tests rejects.  The variance of a set of pixels is at least what the
 * blocks around them give (rare bright paths make means heavy-tailed:
 * regions.c, docs/calibration/README.md).  Without noise, each region's
 * relMSE is held against a limit instead.  A region's report
 * names the block of its most significant test and one of the region's
 * pixels in it: the pixel to replay with `render --pixel X,Y --trace -`.
 */
#ifndef REGIONS_H
#define REGIONS_H

#include <stdbool.h>
#include <stddef.h>

#include "diag.h"
#include "image.h"

/* Labels are whole numbers in [0, REGIONS_MAX). */
#define REGIONS_MAX 16

/* A region's part in a block is tested on its own only when it holds at
 * least this many pixels: the variance of a pixel estimated from two
 * renders has one degree of freedom, and a handful of such pixels (a
 * region's sliver along an edge) can look exact by chance and fail a
 * test they should pass.  Smaller parts still count in the region-wide
 * test. */
#define REGIONS_MIN_BLOCK_PIXELS 32

struct region_result {
    int label;
    size_t n_pixels; /* compared: in the region (and the mask), finite */
    double mean[3], ref_mean[3]; /* over the region */
    double relmse; /* over the region */
    /* The region-wide tests (NaN without noise). */
    double t[3], p[3];
    double min_p; /* smallest p of all its tests (1 without noise) */
    int n_blocks, n_failing_blocks; /* blocks the region is tested in, and those that reject */
    int x0, y0, w, h; /* the block of its most significant test (or largest error) */
    double block_mean[3], block_ref_mean[3], block_t[3], block_p[3];
    int pixel_x, pixel_y; /* a pixel of the region in that block */
    bool whole_rejects; /* the region-wide test rejects */
    bool biased;
};

struct region_report {
    struct region_result regions[REGIONS_MAX]; /* the regions present, by label */
    int n_regions;
    int n_tests; /* in the family (3 per region and per block of a region) */
    double level; /* the Sidak-corrected level of one test (of n_tests + other_tests) */
    bool noise; /* tested against noise (else against max_relmse) */
    double max_relmse; /* without noise: the limit (0: none, nothing judged) */
};

struct region_inputs {
    const struct image *render;
    const struct image *variance; /* per-pixel squared SE of render; rgb NULL: no noise */
    double pixel_dof; /* of variance (0: exact) */
    const struct image *reference;
    double ref_rel_se, ref_dof; /* the reference's noise per pixel (0: exact) */
    const struct image *labels; /* the label of each pixel in channel 0 */
    const unsigned char *mask; /* pixels compared (NULL: all) */
    int block_size;
    double alpha; /* family level */
    int other_tests; /* tests of the same family outside the regions (compare's
                      * block tests): all share alpha, Sidak-corrected */
    double max_relmse; /* without noise: a region above it is biased (0: none is) */
};

/* Compare in->render with in->reference region by region.  Fails (diag)
 * when the sizes differ, a label is not a whole number in [0,
 * REGIONS_MAX), or memory runs out. */
bool regions_compare(const struct region_inputs *in, struct region_report *out, struct diag *err);

/* Order the regions for a report: the biased ones first, the one whose
 * mean is relatively furthest from the reference's first, then the others
 * by label. */
void regions_sort(struct region_report *rep);

/* The name of a label (aov.h's label names; "label N" past them). */
const char *regions_label_name(int label, char *buf, size_t cap);

/* "3.1% darker than the reference (channel G), 5.8 standard errors": of
 * the channel of the smallest p (without noise: of the largest relative
 * difference; no standard errors then), numbers written plainly
 * (metrics_format_plain).  Returns snprintf's count. */
int regions_describe_difference(
    char *buf,
    size_t cap,
    const double mean[3],
    const double ref_mean[3],
    const double t[3],
    const double p[3],
    bool noise);

/* One line about region r of rep: "3.1% darker than the reference
 * (channel G), 5.8 standard errors: biased" (without the region's name);
 * without noise, its relMSE, and against the limit when there is one. */
void regions_describe(
    char *buf,
    size_t cap,
    const struct region_result *r,
    const struct region_report *rep);

#endif /* REGIONS_H */
