/*
 * imgread.h - read the images the compare and merge tools take: PFM (the
 * renderer's linear output), OpenEXR (when built with OpenEXR) and PNG (8-
 * or 16-bit sRGB, for a quick look at a picture that is all one has).
 *
 * Every reader gives linear RGB floats, row 0 at the top (image.h).  A PNG
 * is decoded from sRGB to linear and its alpha is dropped; it has been
 * clamped to [0, 1] and quantised when written, so comparisons of PNGs are
 * only rough.  Bad files give a diagnostic naming the file, never a crash;
 * sizes are bounded by IMAGE_MAX_DIM.
 */
#ifndef IMGREAD_H
#define IMGREAD_H

#include <stdbool.h>

#include "diag.h"
#include "image.h"

/* Read path in the format its extension names (.pfm, .exr, .png). */
bool imgread(const char *path, struct image *out, struct diag *err);

/* Read one layer of an OpenEXR file (a render pass written with --aov,
 * docs/aov.md: "depth", "normal", "feature"...): its channels LAYER.C as
 * R, G, B, or its one channel in all three.  False (diag) for another
 * format, a build without OpenEXR, or a file without that layer. */
bool imgread_layer(const char *path, const char *layer, struct image *out, struct diag *err);

/* Decode a PNG held in memory (n bytes); path names it in messages. */
bool imgread_png_memory(
    const unsigned char *data,
    size_t n,
    const char *path,
    struct image *out,
    struct diag *err);

#endif /* IMGREAD_H */
