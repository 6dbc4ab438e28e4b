/*
 * estimate.h - independent renders of one image as estimates of it: their
 * sample-weighted mean, and the per-pixel variance of that mean.
 *
 * Render j is the mean of n_j samples per pixel, so its pixel x_j has
 * variance sigma^2 / n_j for the per-sample variance sigma^2 of that pixel.
 * The weighted mean m = sum n_j x_j / N (N = sum n_j) is then exactly the
 * render one run of N samples would give in expectation, with variance
 * sigma^2 / N.  An unbiased estimate of sigma^2 from the k renders is
 * sum n_j (x_j - m)^2 / (k - 1), so
 *     Var(m) ~ sum n_j (x_j - m)^2 / ((k - 1) N),  k - 1 degrees of freedom
 * (the weighted sample variance of, e.g., Cochran, "Sampling Techniques",
 * 3rd ed., section 5A.13; with equal n_j it is the usual s^2 / k).
 * Sums are in double; a non-finite input pixel gives a non-finite result.
 */
#ifndef ESTIMATE_H
#define ESTIMATE_H

#include <stdbool.h>

#include "diag.h"
#include "image.h"

/* Combine k >= 1 images of one size with positive weights (their samples
 * per pixel; NULL: all equal) into mean (allocated here) and, when variance is not NULL and
 * k >= 2, the per-pixel variance of that mean (allocated here).  Fails
 * (diag) on mismatched sizes, bad weights or no memory. */
bool estimate_combine(
    const struct image *images,
    const double *weights,
    int k,
    struct image *mean,
    struct image *variance,
    struct diag *err);

#endif /* ESTIMATE_H */
