/*
 * image_exr.h - the OpenEXR encoder behind image_write(), private to
 * common/.  image_exr.c is compiled only when OpenEXR is found (HAVE_OPENEXR);
 * image_write.c calls it under the same #ifdef.
 */
#ifndef IMAGE_EXR_H
#define IMAGE_EXR_H

#include <stdbool.h>

#include "diag.h"
#include "image.h"

/* Write img as a single-part scanline EXR with 32-bit float R, G and B
 * channels (ZIP compressed) to fd, an empty file open for writing, which the
 * caller closes.  path names the file in messages only. */
bool image_exr_write(const struct image *img, int fd, const char *path, struct diag *err);

/* The same with more layers (image.h), each a set of 32-bit float
 * channels named "LAYER.C" in the same part. */
bool image_exr_write_layers(
    const struct image *img,
    const struct image_layer *layers,
    int n_layers,
    int fd,
    const char *path,
    struct diag *err);

#endif /* IMAGE_EXR_H */
