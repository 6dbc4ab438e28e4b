/*
 * compare_report.h - what the compare tool (tests/tools/compare.c) found,
 * and its report page (compare_report.c).
 */
#ifndef COMPARE_REPORT_H
#define COMPARE_REPORT_H

#include <stdbool.h>
#include <stdio.h>

#include "diag.h"
#include "image.h"
#include "metrics.h"
#include "regions.h"

/* What compare says it can find: a bias found this often (9 times in 10)
 * ... */
#define COMPARE_POWER 0.9
/* ... and the bias it says how many samples find: 2% over a window, the
 * bias make calibrate plants (docs/calibration/README.md). */
#define COMPARE_TARGET_BIAS 0.02

/* Exit statuses: the images agree, the render is biased, bad input. */
enum compare_status {
    COMPARE_AGREE = 0,
    COMPARE_BIASED = 1,
    COMPARE_BAD_INPUT = 2,
};

/* How the noise of the render was estimated. */
enum compare_noise {
    NOISE_NONE, /* one render, no variance: noise cannot be told from bias */
    NOISE_RENDERS, /* the spread of k >= 2 renders with different seeds */
    NOISE_VARIANCE, /* a per-pixel variance image given with the render */
};

struct comparison {
    /* Inputs, as given. */
    const char *const *render_paths;
    int k; /* renders */
    const char *reference_path;
    const char *variance_path; /* NULL unless NOISE_VARIANCE */
    const char *title; /* of the report page; NULL: the render's name */
    int block_size;
    double alpha; /* family significance level */
    double ref_rel_se, ref_dof; /* the reference's noise (0: exact) */
    bool ref_se_from_meta; /* ref_rel_se and ref_dof came from a META.json */
    double max_relmse; /* NOISE_NONE: relMSE above this fails; 0: no limit */
    unsigned char *mask; /* --mask smooth: the pixels compared (NULL: all) */
    size_t n_masked; /* pixels in the mask */

    /* What was compared: the mean of the renders (or the one render). */
    struct image render;
    struct image reference;
    struct image variance; /* per-pixel variance of `render` (rgb NULL: none) */
    double pixel_dof; /* degrees of freedom of `variance` (0: exact) */
    enum compare_noise noise;
    bool renders_identical; /* k >= 2 renders, all the same bit for bit */

    struct metrics m;
    struct metrics_block_stats blocks; /* n_blocks 0 when NOISE_NONE */
    double level; /* the Sidak-corrected level of one block or window test */
    struct metrics_power power; /* what the tests can find (COMPARE_POWER, COMPARE_TARGET_BIAS) */
    int *failing; /* failing tests (metrics_block_test's index), most significant first */
    int n_failing;
    int n_failing_windows; /* of them, windows */
    int worst; /* the block whose luminance is furthest off, relatively */
    double worst_error; /* its signed relative error */
    double map_range; /* the error map's scale, +-map_range */

    const struct region_report *regions; /* --regions (regions.h); NULL: none */

    enum compare_status status;
    char verdict[256]; /* one line: "consistent with ..." or "biased: ..." */
};

/* The channel of block b whose test is most significant (smallest p). */
int compare_block_channel(const struct metrics_block *b);

/* One sentence about failing block b: "the block at x 0-15, y 32-47 is 2.5%
 * darker than the reference (channel G), 6.1 standard errors". */
void compare_describe_block(char *buf, size_t cap, const struct metrics_block *b);

/* What to do next about failing blocks that are darker than the
 * reference: render again with more samples. */
extern const char compare_bias_hint[];

/* Whether the hint is about c: a failing block is darker than the
 * reference (rare bright paths missed); a block that is only brighter is
 * not explained by paths the samples missed. */
bool compare_bias_hint_applies(const struct comparison *c);

/* What a verdict's false-alarm rate is: the family level every test of the
 * comparison shares, what make calibrate measured at make grade's settings
 * (docs/calibration/README.md), and what to do about a "biased" one doubts.
 * Empty when the comparison has no noise (no statistical test). */
void compare_format_alarms(char *buf, size_t cap, const struct comparison *c);

/* What the comparison can find (c->power): the bias over a window that
 * its tests find 9 times in 10, for the median window and for 9 windows in
 * 10, and how many times the renders' samples find COMPARE_TARGET_BIAS in 9
 * windows of 10.  Empty when the comparison has no noise. */
void compare_format_power(char *buf, size_t cap, const struct comparison *c);

/* "render R G B, reference R G B": the means of both images, per channel. */
void compare_format_means(char *buf, size_t cap, const struct metrics *m, const char *separator);

/* Write the report page of c with the error map (already drawn) to path,
 * through a temporary file renamed into place. */
bool compare_write_html(
    const struct comparison *c,
    const struct image *map,
    const char *path,
    struct diag *err);

#endif /* COMPARE_REPORT_H */
