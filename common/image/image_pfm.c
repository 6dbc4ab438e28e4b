/*
 * image_pfm.c - PFM, the linear float format: the writer (little endian, rows
 * bottom to top as the format wants) and image_read_pfm(), which takes
 * colour or greyscale in either byte order and checks the data length
 * against the header before reading.
 */
#include "image.h"

#include "image_codec.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* PFM stores IEEE 754 binary32; the byte order is handled explicitly. */
_Static_assert(sizeof(float) == 4, "float must be IEEE 754 binary32");

static void
store_le32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

/* PFM: a negative scale says little endian; rows run bottom to top. */
void
image_write_pfm(struct sink *s, const struct image *img)
{
    errno = 0;
    if (fprintf(s->f, "PF\n%d %d\n-1.0\n", img->width, img->height) < 0) {
        s->error = errno ? errno : EIO;
    }
    size_t n = (size_t)img->width * 3;
    uint8_t *row = malloc(n * 4);
    if (!row) {
        s->error = ENOMEM;
        return;
    }
    for (int y = img->height - 1; y >= 0; y--) {
        const float *p = image_pixel(img, 0, y);
        for (size_t i = 0; i < n; i++) {
            uint32_t bits;
            memcpy(&bits, &p[i], 4);
            store_le32(row + 4 * i, bits);
        }
        image_sink_put(s, row, n * 4);
    }
    free(row);
}

/* ---- image_read_pfm --------------------------------------------------------- */

#define PFM_TOKEN_MAX 32 /* longer header fields are not numbers we accept */

static bool
is_space(int c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

/* The next whitespace-separated header field, and the one whitespace
 * character after it (the last one separates the header from the data). */
static bool
read_token(FILE *f, char *buf)
{
    int c;
    do {
        c = getc(f);
    } while (is_space(c));
    size_t n = 0;
    while (c != EOF && !is_space(c)) {
        if (n + 1 == PFM_TOKEN_MAX) {
            return false;
        }
        buf[n++] = (char)c;
        c = getc(f);
    }
    buf[n] = '\0';
    return n > 0 && c != EOF;
}

/* A width or height: decimal digits only, in [1, IMAGE_MAX_DIM]. */
static bool
parse_dim(const char *tok, int *out)
{
    long v = 0;
    for (const char *p = tok; *p; p++) {
        if (*p < '0' || *p > '9' || v > IMAGE_MAX_DIM) {
            return false;
        }
        v = v * 10 + (*p - '0');
    }
    *out = (int)v;
    return tok[0] != '\0' && v >= 1 && v <= IMAGE_MAX_DIM;
}

struct pfm_header {
    int width, height;
    int channels; /* 3 for "PF", 1 for "Pf" */
    bool little_endian; /* the scale's sign */
};

static bool
read_pfm_header(FILE *f, const char *path, struct pfm_header *h, struct diag *err)
{
    char magic[3] = {0};
    int sep = EOF;
    if (fread(magic, 1, 2, f) == 2) {
        sep = getc(f);
    }
    if ((strcmp(magic, "PF") != 0 && strcmp(magic, "Pf") != 0) || !is_space(sep)) {
        diag_set(err, path, 0, 0, "not a PFM file: it must start with 'PF' or 'Pf'");
        return false;
    }
    h->channels = magic[1] == 'F' ? 3 : 1;
    char tok[PFM_TOKEN_MAX];
    if (!read_token(f, tok) || !parse_dim(tok, &h->width)) {
        diag_set(err, path, 0, 0, "bad PFM width: expected an integer from 1 to %d", IMAGE_MAX_DIM);
        return false;
    }
    if (!read_token(f, tok) || !parse_dim(tok, &h->height)) {
        diag_set(
            err,
            path,
            0,
            0,
            "bad PFM height: expected an integer from 1 to %d",
            IMAGE_MAX_DIM);
        return false;
    }
    char *end = NULL;
    double scale = read_token(f, tok) ? strtod(tok, &end) : 0.0;
    if (!end || *end != '\0' || !isfinite(scale) || scale == 0.0) {
        diag_set(err, path, 0, 0, "bad PFM scale: expected a finite non-zero number");
        return false;
    }
    h->little_endian = scale < 0;
    return true;
}

/* When the file can seek, compare its remaining length with the pixel data
 * before allocating, so a tiny file claiming a huge image fails at once. */
static bool
check_data_length(FILE *f, const char *path, uint64_t expected, struct diag *err)
{
    off_t start = ftello(f);
    if (start < 0 || fseeko(f, 0, SEEK_END) != 0) {
        return true;  // a pipe: the reads below will find out
    }
    off_t end = ftello(f);
    if (fseeko(f, start, SEEK_SET) != 0) {
        diag_set(err, path, 0, 0, "cannot read: %s", strerror(errno));
        return false;
    }
    uint64_t found = end >= start ? (uint64_t)(end - start) : 0;
    if (found != expected) {
        diag_set(
            err,
            path,
            0,
            0,
            "%s: expected %llu bytes of pixel data after the header, found %llu",
            found < expected ? "truncated PFM" : "unexpected bytes after the PFM pixel data",
            (unsigned long long)expected,
            (unsigned long long)found);
        return false;
    }
    return true;
}

static float
load_float(const uint8_t *p, bool little_endian)
{
    uint32_t bits =
        little_endian
            ? (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24
            : (uint32_t)p[3] | (uint32_t)p[2] << 8 | (uint32_t)p[1] << 16 | (uint32_t)p[0] << 24;
    float v;
    memcpy(&v, &bits, 4);
    return v;
}

/* Read the rows (bottom to top in the file) into out; row is scratch. */
static bool
read_pfm_rows(
    FILE *f,
    const char *path,
    const struct pfm_header *h,
    uint8_t *row,
    struct image *out,
    struct diag *err)
{
    size_t row_bytes = (size_t)h->width * (size_t)h->channels * 4;
    for (int y = h->height - 1; y >= 0; y--) {
        if (fread(row, 1, row_bytes, f) != row_bytes) {
            if (ferror(f)) {
                diag_set(err, path, 0, 0, "cannot read: %s", strerror(errno));
            } else {
                diag_set(err, path, 0, 0, "truncated PFM: the pixel data ends early");
            }
            return false;
        }
        float *p = image_pixel(out, 0, y);
        for (size_t i = 0; i < (size_t)h->width * 3; i++) {
            size_t src = h->channels == 3 ? i : i / 3;  // greyscale feeds all three
            p[i] = load_float(row + 4 * src, h->little_endian);
        }
    }
    if (getc(f) != EOF) {
        diag_set(err, path, 0, 0, "unexpected bytes after the pixel data");
        return false;
    }
    return true;
}

bool
image_read_pfm(const char *path, struct image *out, struct diag *err)
{
    *out = (struct image){0};
    FILE *f = fopen(path, "rb");
    if (!f) {
        diag_set(err, path, 0, 0, "cannot open: %s", strerror(errno));
        return false;
    }
    struct pfm_header h;
    uint8_t *row = NULL;
    bool ok = read_pfm_header(f, path, &h, err)
              && check_data_length(
                  f,
                  path,
                  (uint64_t)h.width * (uint64_t)h.height * (uint64_t)h.channels * 4,
                  err);
    if (ok && !image_alloc(out, h.width, h.height, NULL)) {
        diag_set(err, path, 0, 0, "out of memory for a %dx%d image", h.width, h.height);
        ok = false;
    }
    if (ok) {
        row = malloc((size_t)h.width * (size_t)h.channels * 4);
        ok = row && read_pfm_rows(f, path, &h, row, out, err);
        if (!row) {
            diag_set(err, path, 0, 0, "out of memory");
        }
    }
    free(row);
    fclose(f);
    if (!ok) {
        image_free(out);
    }
    return ok;
}
