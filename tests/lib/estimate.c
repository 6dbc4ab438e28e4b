/*
 * estimate.c - see estimate.h for the formulas.
 */
#include "estimate.h"

#include <math.h>
#include <stddef.h>

/* Image j's weight: weights[j], or 1 when there are none (equal weights). */
static double
weight_of(const double *weights, int j)
{
    return weights ? weights[j] : 1;
}

static bool
check_inputs(const struct image *images, const double *weights, int k, struct diag *err)
{
    if (k < 1) {
        diag_set(err, NULL, 0, 0, "nothing to combine");
        return false;
    }
    for (int j = 0; j < k; j++) {
        double w = weight_of(weights, j);
        if (!(w > 0) || !isfinite(w)) {
            diag_set(
                err,
                NULL,
                0,
                0,
                "image %d: weight (samples per pixel) %g is not positive",
                j + 1,
                w);
            return false;
        }
        if (images[j].width != images[0].width || images[j].height != images[0].height) {
            diag_set(
                err,
                NULL,
                0,
                0,
                "image %d is %dx%d but image 1 is %dx%d",
                j + 1,
                images[j].width,
                images[j].height,
                images[0].width,
                images[0].height);
            return false;
        }
    }
    return true;
}

bool
estimate_combine(
    const struct image *images,
    const double *weights,
    int k,
    struct image *mean,
    struct image *variance,
    struct diag *err)
{
    *mean = (struct image){0};
    bool want_variance = variance && k >= 2;
    if (variance) {
        *variance = (struct image){0};
    }
    if (!check_inputs(images, weights, k, err)
        || !image_alloc(mean, images[0].width, images[0].height, err)
        || (want_variance && !image_alloc(variance, mean->width, mean->height, err))) {
        image_free(mean);
        return false;
    }
    double total = 0;
    for (int j = 0; j < k; j++) {
        total += weight_of(weights, j);
    }
    size_t n = (size_t)mean->width * (size_t)mean->height * 3;
    for (size_t i = 0; i < n; i++) {
        double m = 0;
        for (int j = 0; j < k; j++) {
            m += weight_of(weights, j) * images[j].rgb[i];
        }
        m /= total;
        mean->rgb[i] = (float)m;
        if (want_variance) {
            double ss = 0;
            for (int j = 0; j < k; j++) {
                double d = images[j].rgb[i] - m;
                ss += weight_of(weights, j) * d * d;
            }
            variance->rgb[i] = (float)(ss / ((k - 1) * total));
        }
    }
    return true;
}
