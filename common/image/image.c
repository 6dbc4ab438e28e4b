/*
 * image.c - the framebuffer (image.h), and the byte sink every encoder
 * writes through (image_codec.h): the lowest layer of the image files.
 * Above it, the encoders, each in its file, behind image_codec.h:
 *   image_srgb.c   the sRGB transfer function, 8-bit rows
 *   image_zlib.c   CRC-32, Adler-32 and a zlib (deflate) stream, for PNG
 *   image_png.c    PNG: filters and chunks
 *   image_ppm.c    binary PPM (P6)
 *   image_pfm.c    PFM, written and read
 *   image_exr.c    OpenEXR, built only with the library
 * and above them image_write.c, which picks the encoder from the file name.
 */
#include "image.h"

#include "image_codec.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

bool
image_alloc(struct image *img, int width, int height, struct diag *err)
{
    img->width = 0;
    img->height = 0;
    img->rgb = NULL;
    if (width < 1 || width > IMAGE_MAX_DIM || height < 1 || height > IMAGE_MAX_DIM) {
        diag_set(
            err,
            NULL,
            0,
            0,
            "image size %dx%d out of range: width and height must be from 1 to %d",
            width,
            height,
            IMAGE_MAX_DIM);
        return false;
    }
    // Both sides are now small, but a 32-bit size_t could still overflow.
    if ((size_t)width > SIZE_MAX / sizeof(float) / 3 / (size_t)height) {
        diag_set(err, NULL, 0, 0, "image size %dx%d is too large for memory", width, height);
        return false;
    }
    img->rgb = calloc((size_t)width * (size_t)height * 3, sizeof(float));
    if (!img->rgb) {
        diag_set(err, NULL, 0, 0, "out of memory for a %dx%d image", width, height);
        return false;
    }
    img->width = width;
    img->height = height;
    return true;
}

void
image_free(struct image *img)
{
    free(img->rgb);
    img->rgb = NULL;
    img->width = 0;
    img->height = 0;
}

void
image_sink_put(struct sink *s, const void *data, size_t n)
{
    if (s->error || n == 0) {
        return;
    }
    errno = 0;
    if (fwrite(data, 1, n, s->f) != n) {
        s->error = errno ? errno : EIO;
    }
}
