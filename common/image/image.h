/*
 * image.h - a float RGB framebuffer and the files it is written to.
 *
 * Pixels hold linear radiance, three floats per pixel, row-major, row 0 at
 * the TOP of the picture (SCENES.md: pixel (0,0) is the top-left pixel).
 * Only the writers convert: PNG and PPM apply the sRGB transfer function and
 * clamp to 8 bits; PFM and EXR keep linear floats.  PFM stores rows bottom to
 * top, and the PFM writer and reader are the only places that flip.
 *
 * Every writer goes through image_write(), which writes a temporary file
 * beside the target and renames it into place: a failed or interrupted write
 * never leaves a half-written image under the requested name.
 */
#ifndef IMAGE_H
#define IMAGE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "diag.h"

/* Largest width or height accepted anywhere (reading or allocating). */
#define IMAGE_MAX_DIM 32768

struct image {
    int width, height;
    float *rgb; /* width * height * 3 floats */
};

enum image_format {
    IMAGE_FORMAT_UNKNOWN,
    IMAGE_FORMAT_PNG,
    IMAGE_FORMAT_PPM,
    IMAGE_FORMAT_PFM,
    IMAGE_FORMAT_EXR,
};

/* Allocate a zero-filled image; fails (diag) for sizes outside
 * [1, IMAGE_MAX_DIM] or when memory runs out. */
bool image_alloc(struct image *img, int width, int height, struct diag *err);

/* Free the pixels; accepts a zero-initialised image. */
void image_free(struct image *img);

static inline float *
image_pixel(const struct image *img, int x, int y)
{
    return img->rgb + ((size_t)y * (size_t)img->width + (size_t)x) * 3;
}

/* Format from the file name's extension (case-insensitive). */
enum image_format image_format_from_path(const char *path);

/* True when this build can write OpenEXR (built with HAVE_OPENEXR). */
bool image_exr_available(void);

/* Write img to path in the format its extension names, through a temporary
 * file renamed into place.  On failure nothing is left at path (an older file
 * of that name is left untouched) and err says why. */
bool image_write(const struct image *img, const char *path, struct diag *err);

struct atomic_file;

/* Encode img into af, an atomic file opened for af->path, in the format
 * af->path names; the caller finishes and publishes it (atomic_file.h), so
 * several outputs can be put in place together. */
bool image_write_to(const struct image *img, struct atomic_file *af, struct diag *err);

/* A layer of an OpenEXR file beside the image's R, G and B: the channels
 * "NAME.C" for each letter C of `channels`, taken from img's channels in
 * order ("Z": one channel, from img's first; "XYZ": three). */
struct image_layer {
    const char *name;
    const char *channels;
    const struct image *img; /* the size of the image it goes with */
};

/* image_write_to with n_layers more layers (an .exr file only: any other
 * format refuses layers). */
bool image_write_layers_to(
    const struct image *img,
    const struct image_layer *layers,
    int n_layers,
    struct atomic_file *af,
    struct diag *err);

/* Read a PFM (colour "PF" or greyscale "Pf", either byte order) into a
 * freshly allocated RGB image (greyscale is copied to all three channels). */
bool image_read_pfm(const char *path, struct image *out, struct diag *err);

/* The sRGB transfer function (IEC 61966-2-1) and its inverse, on [0, 1]. */
float image_srgb_from_linear(float linear);
float image_linear_from_srgb(float encoded);

/* Linear radiance to an 8-bit sRGB code: clamped to [0, 1], NaN gives 0. */
uint8_t image_srgb_encode8(float linear);

/* Checksums of the PNG format, exposed for tests.  Start crc at 0 and
 * adler at 1; each call continues the running value. */
uint32_t image_crc32(uint32_t crc, const uint8_t *data, size_t n);
uint32_t image_adler32(uint32_t adler, const uint8_t *data, size_t n);

/* The image as an 8-bit sRGB PNG in memory (malloc'd; *len bytes), for a
 * page that embeds it; NULL (err says why) when memory runs out. */
unsigned char *image_png_bytes(const struct image *img, size_t *len, struct diag *err);

/* data as base64 (RFC 4648, section 4) into f: the body of a
 * "data:image/png;base64," URI (RFC 2397). */
void image_write_base64(FILE *f, const unsigned char *data, size_t n);

#endif /* IMAGE_H */
