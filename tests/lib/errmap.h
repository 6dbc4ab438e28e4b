/*
 * errmap.h - the error map of compare: where a render is darker or brighter
 * than its reference, as a picture.
 *
 * Each pixel shows the signed relative error of its luminance (Rec. 709),
 *     e = (L_render - L_ref) / sqrt(L_ref^2 + 0.01),
 * the square root of relMSE's per-pixel term (metrics.h) with its sign, in
 * a diverging scale: blue where the render is darker, white where it
 * agrees, red where it is brighter, saturating at -range and +range (the
 * colours of ColorBrewer's RdBu scheme, Brewer & Harrower,
 * colorbrewer2.org).  Pixels whose render or reference is NaN or infinite
 * are green (compare refuses such images: a caller that passes them);
 * pixels left out by a mask grey.  Failing blocks are outlined in black.
 * Below the map a legend: the colour bar with its ends and centre
 * labelled, and the key of the outline, and of green and grey when the map
 * has them.  Small images are magnified by a whole factor
 * so the map is at least ERRMAP_MIN_WIDTH pixels wide.
 */
#ifndef ERRMAP_H
#define ERRMAP_H

#include <stdbool.h>

#include "diag.h"
#include "image.h"

#define ERRMAP_MIN_WIDTH 320

/* A failing block's rectangle, in pixels of the compared images. */
struct errmap_box {
    int x0, y0, w, h;
};

/* The signed relative error of pixel (x, y) as defined above (NaN when
 * either pixel is not finite). */
double errmap_pixel_error(const struct image *render, const struct image *ref, int x, int y);

/* A round scale for the map: the 99th percentile of |e| over the finite
 * pixels, rounded up to 1, 2 or 5 times a power of ten (at least 0.001,
 * at most 10). */
double errmap_auto_range(const struct image *render, const struct image *ref);

/* Draw the map of render against ref (same size) with the boxes outlined
 * into out (allocated here; linear RGB, to be written as PNG).  With a mask
 * (width * height bytes, metrics.h), pixels outside it are grey and the
 * legend says "not compared". */
bool errmap_draw(
    const struct image *render,
    const struct image *ref,
    double range,
    const unsigned char *mask,
    const struct errmap_box *boxes,
    int n_boxes,
    struct image *out,
    struct diag *err);

#endif /* ERRMAP_H */
