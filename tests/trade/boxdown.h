/*
 * boxdown.h - shrink an image by an integer factor with a box filter.
 *
 * Output pixel (X, Y) is the plain mean of the f x f input pixels
 * (f X .. f X + f - 1, f Y .. f Y + f - 1), per channel, summed in double.
 * A reference image whose pixels are box-filtered averages of radiance over
 * their footprints (Mitsuba's "box" rfilter of radius 0.5; stagelight's own
 * pixels) stays exactly that after this: the mean of the f^2 small
 * footprints' averages is the average over the big footprint.  So a render
 * at 1/f of the size can be compared with the shrunk reference without any
 * resampling error.  A non-finite input pixel makes its output pixel
 * non-finite (metrics.h leaves such pixels out and counts them).
 */
#ifndef BOXDOWN_H
#define BOXDOWN_H

#include <stdbool.h>

#include "diag.h"
#include "image.h"

/* Shrink in by factor f (>= 1; f must divide both sides) into a freshly
 * allocated *out.  Fails (diag) on a bad factor or no memory. */
bool box_downsample(const struct image *in, int f, struct image *out, struct diag *err);

#endif /* BOXDOWN_H */
