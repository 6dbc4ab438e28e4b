/*
 * image_write.c - image_write() and its variants (image.h): the format from
 * the file name, the encoder it names (image_codec.h, image_exr.h), and the
 * temporary file renamed into place.  The dispatch layer of the image
 * files: it calls the encoders, which call only image.c below them.
 */
#include "image.h"

#include "atomic_file.h"
#include "image_codec.h"

#include <stdio.h>
#include <string.h>

#ifdef HAVE_OPENEXR
#include "image_exr.h"
#endif

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
        image_write_png(&s, img);
    } else if (format == IMAGE_FORMAT_PPM) {
        image_write_ppm(&s, img);
    } else {
        image_write_pfm(&s, img);
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
