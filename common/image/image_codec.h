/*
 * image_codec.h - what image_write() and the encoders share; internal to
 * the image files of common/ (the API is image.h).
 *
 * An encoder writes the whole file for img to a sink; image_write() opens
 * the temporary file and reports the sink's first error.
 */
#ifndef IMAGE_CODEC_H
#define IMAGE_CODEC_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "image.h"

/* A FILE that remembers the first error, so encoders need not check each
 * write: once error is set, further writes are skipped. */
struct sink {
    FILE *f;
    int error; /* errno of the first failure, 0 while all is well */
};

/* Write n bytes to s, unless an earlier write failed (image.c). */
void image_sink_put(struct sink *s, const void *data, size_t n);

static inline void
store_be32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

/* A growable byte buffer; failed records that memory ran out. */
struct bytes {
    uint8_t *data;
    size_t len, cap;
    bool failed;
};

/* A zlib stream (RFC 1950) of data, appended to out; false when memory ran
 * out (image_zlib.c). */
bool image_zlib_compress(const uint8_t *data, size_t n, struct bytes *out);

/* Row y of img as 8-bit sRGB, 3 * width bytes (image_srgb.c). */
void image_encode_row(const struct image *img, int y, uint8_t *out);

/* The encoders, one file each. */
void image_write_png(struct sink *s, const struct image *img);
void image_write_ppm(struct sink *s, const struct image *img);
void image_write_pfm(struct sink *s, const struct image *img);

#endif /* IMAGE_CODEC_H */
