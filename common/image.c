/*
 * image.c - the framebuffer, and image_write(), which picks the encoder from
 * the file name and writes through a temporary file renamed into place (see
 * image.h).  The encoders each have their file, behind image_codec.h:
 *   image_srgb.c   the sRGB transfer function, 8-bit rows
 *   image_zlib.c   CRC-32, Adler-32 and a zlib (deflate) stream, for PNG
 *   image_png.c    PNG: filters and chunks
 *   image_ppm.c    binary PPM (P6)
 *   image_pfm.c    PFM, written and read
 *   image_exr.c    OpenEXR, built only with the library
 */
#include "image.h"

#include "atomic_file.h"
#include "image_codec.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef HAVE_OPENEXR
#include "image_exr.h"
#endif

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

/* ASCII case-insensitive equality (strcasecmp is POSIX, not ISO C). */
static bool
equal_ignoring_case(const char *a, const char *b)
{
    for (; *a && *b; a++, b++) {
        char ca = (*a >= 'A' && *a <= 'Z') ? (char)(*a - 'A' + 'a') : *a;
        char cb = (*b >= 'A' && *b <= 'Z') ? (char)(*b - 'A' + 'a') : *b;
        if (ca != cb) {
            return false;
        }
    }
    return *a == *b;
}

enum image_format
image_format_from_path(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash + 1 : path, '.');
    if (!dot) {
        return IMAGE_FORMAT_UNKNOWN;
    }
    if (equal_ignoring_case(dot, ".png")) {
        return IMAGE_FORMAT_PNG;
    }
    if (equal_ignoring_case(dot, ".ppm")) {
        return IMAGE_FORMAT_PPM;
    }
    if (equal_ignoring_case(dot, ".pfm")) {
        return IMAGE_FORMAT_PFM;
    }
    if (equal_ignoring_case(dot, ".exr")) {
        return IMAGE_FORMAT_EXR;
    }
    return IMAGE_FORMAT_UNKNOWN;
}

bool
image_exr_available(void)
{
#ifdef HAVE_OPENEXR
    return true;
#else
    return false;
#endif
}

/* ---- output helpers ------------------------------------------------------- */

void
put(struct sink *s, const void *data, size_t n)
{
    if (s->error || n == 0) {
        return;
    }
    errno = 0;
    if (fwrite(data, 1, n, s->f) != n) {
        s->error = errno ? errno : EIO;
    }
}

/* ---- image_write ------------------------------------------------------------ */

static bool
write_failed(const char *path, int error, struct diag *err)
{
    diag_set(err, path, 0, 0, "cannot write: %s", strerror(error));
    return false;
}

/* Encode into f, the open temporary file; false (err set) on a write error. */
static bool
encode_stdio(
    const struct image *img,
    enum image_format format,
    FILE *f,
    const char *path,
    struct diag *err)
{
    struct sink s = {.f = f};
    if (format == IMAGE_FORMAT_PNG) {
        write_png(&s, img);
    } else if (format == IMAGE_FORMAT_PPM) {
        write_ppm(&s, img);
    } else {
        write_pfm(&s, img);
    }
    return s.error ? write_failed(path, s.error, err) : true;
}

/* Encode img and its layers into f, the temporary file (OpenEXR writes to
 * its descriptor). */
static bool
encode(
    const struct image *img,
    const struct image_layer *layers,
    int n_layers,
    enum image_format format,
    FILE *f,
    const char *path,
    struct diag *err)
{
#ifdef HAVE_OPENEXR
    if (format == IMAGE_FORMAT_EXR) {
        return image_exr_write_layers(img, layers, n_layers, fileno(f), path, err);
    }
#endif
    if (n_layers > 0) {
        diag_set(err, path, 0, 0, "only an OpenEXR file holds layers");
        return false;
    }
    (void)layers;
    return encode_stdio(img, format, f, path, err);
}

/* Formats this build cannot write, with the reason; true when format is OK. */
static bool
check_format(enum image_format format, const char *path, struct diag *err)
{
    if (format == IMAGE_FORMAT_UNKNOWN) {
        diag_set(
            err,
            path,
            0,
            0,
            "unknown image format: the file name must end in .png, .ppm, .pfm or .exr");
        return false;
    }
    if (format == IMAGE_FORMAT_EXR && !image_exr_available()) {
        diag_set(
            err,
            path,
            0,
            0,
            "built without OpenEXR; install libopenexr-dev and rebuild to write .exr");
        return false;
    }
    return true;
}

/* The temporary file is renamed over path, so a symbolic link at path is
 * replaced by the new file rather than followed. */
bool
image_write_layers_to(
    const struct image *img,
    const struct image_layer *layers,
    int n_layers,
    struct atomic_file *af,
    struct diag *err)
{
    enum image_format format = image_format_from_path(af->path);
    return check_format(format, af->path, err)
           && encode(img, layers, n_layers, format, af->f, af->path, err);
}

bool
image_write_to(const struct image *img, struct atomic_file *af, struct diag *err)
{
    return image_write_layers_to(img, NULL, 0, af, err);
}

bool
image_write(const struct image *img, const char *path, struct diag *err)
{
    struct atomic_file af;
    if (!check_format(image_format_from_path(path), path, err)
        || !atomic_file_open(&af, path, err)) {
        return false;
    }
    if (!image_write_to(img, &af, err)) {
        atomic_file_abort(&af);
        return false;
    }
    return atomic_file_commit(&af, err);
}
