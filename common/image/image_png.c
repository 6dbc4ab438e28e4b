/*
 * image_png.c - the PNG writer (ISO/IEC 15948): 8-bit sRGB truecolour, each
 * row filtered with the filter the specification's heuristic picks, the
 * scanlines compressed by image_zlib.c and cut into IDAT chunks.
 */
#include "image.h"

#include "image_codec.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

/* ---- PNG (ISO/IEC 15948) -------------------------------------------------- */

#define PNG_BYTES_PER_PIXEL 3 /* colour type 2, bit depth 8 */
#define IDAT_MAX ((size_t)1 << 20) /* chunks may hold 2^31 - 1; keep them modest */

enum png_filter {
    FILTER_NONE = 0,
    FILTER_SUB = 1,
    FILTER_UP = 2,
    FILTER_PAETH = 4,
};

static void
put_chunk(struct sink *s, const char *type, const uint8_t *data, size_t len)
{
    uint8_t head[8];
    store_be32(head, (uint32_t)len);
    memcpy(head + 4, type, 4);
    // The CRC covers the chunk type and data, not the length.
    uint32_t crc = image_crc32(image_crc32(0, head + 4, 4), data, len);
    uint8_t tail[4];
    store_be32(tail, crc);
    image_sink_put(s, head, sizeof head);
    image_sink_put(s, data, len);
    image_sink_put(s, tail, sizeof tail);
}

/* Paeth's predictor (PNG 9.4): whichever neighbour is closest to a + b - c. */
static uint8_t
paeth(int a, int b, int c)
{
    int p = a + b - c;
    int pa = abs(p - a);
    int pb = abs(p - b);
    int pc = abs(p - c);
    if (pa <= pb && pa <= pc) {
        return (uint8_t)a;
    }
    return (uint8_t)(pb <= pc ? b : c);
}

static void
apply_filter(enum png_filter type, const uint8_t *cur, const uint8_t *prior, size_t n, uint8_t *out)
{
    for (size_t i = 0; i < n; i++) {
        // a: left, b: above, c: above-left; zero outside the image (PNG 9.2).
        int a = i >= PNG_BYTES_PER_PIXEL ? cur[i - PNG_BYTES_PER_PIXEL] : 0;
        int b = prior[i];
        int c = i >= PNG_BYTES_PER_PIXEL ? prior[i - PNG_BYTES_PER_PIXEL] : 0;
        int pred = type == FILTER_SUB     ? a
                   : type == FILTER_UP    ? b
                   : type == FILTER_PAETH ? paeth(a, b, c)
                                          : 0;
        out[i] = (uint8_t)(cur[i] - pred);
    }
}

/* Filter one row into out (type byte, then bytes), choosing the filter with
 * the smallest sum of absolute values as signed bytes, the heuristic the PNG
 * specification recommends (12.8).  trial is scratch of n bytes. */
static void
filter_row(const uint8_t *cur, const uint8_t *prior, size_t n, uint8_t *out, uint8_t *trial)
{
    static const enum png_filter candidates[] = {FILTER_NONE, FILTER_SUB, FILTER_UP, FILTER_PAETH};

    uint64_t best = UINT64_MAX;
    for (size_t k = 0; k < sizeof candidates / sizeof candidates[0]; k++) {
        apply_filter(candidates[k], cur, prior, n, trial);
        uint64_t cost = 0;
        for (size_t i = 0; i < n; i++) {
            cost += trial[i] < 128 ? trial[i] : 256 - trial[i];  // |byte as signed|
        }
        if (cost < best) {
            best = cost;
            out[0] = (uint8_t)candidates[k];
            memcpy(out + 1, trial, n);
        }
    }
}

/* The filtered scanlines, height rows of 1 + 3 * width bytes (at most about
 * 3.2e9, which fits even a 32-bit size_t); NULL when memory runs out. */
static uint8_t *
filtered_scanlines(const struct image *img, size_t *out_len)
{
    size_t n = (size_t)img->width * PNG_BYTES_PER_PIXEL;
    *out_len = (n + 1) * (size_t)img->height;
    uint8_t *raw = malloc(*out_len);
    uint8_t *rows = calloc(3, n);  // prior row (zeros above the top), current, trial
    if (raw && rows) {
        uint8_t *prior = rows;
        uint8_t *cur = rows + n;
        for (int y = 0; y < img->height; y++) {
            image_encode_row(img, y, cur);
            filter_row(cur, prior, n, raw + (size_t)y * (n + 1), rows + 2 * n);
            uint8_t *swap = prior;
            prior = cur;
            cur = swap;
        }
    } else {
        free(raw);
        raw = NULL;
    }
    free(rows);
    return raw;
}

void
image_write_png(struct sink *s, const struct image *img)
{
    static const uint8_t signature[8] = {137, 'P', 'N', 'G', '\r', '\n', 26, '\n'};
    uint8_t ihdr[13];
    store_be32(ihdr, (uint32_t)img->width);
    store_be32(ihdr + 4, (uint32_t)img->height);
    ihdr[8] = 8;  // bit depth
    ihdr[9] = 2;  // colour type 2: truecolour RGB
    ihdr[10] = 0;  // compression method 0: zlib deflate
    ihdr[11] = 0;  // filter method 0: the five adaptive filters
    ihdr[12] = 0;  // no interlace
    static const uint8_t srgb_intent[1] = {0};  // sRGB chunk: perceptual intent
    size_t raw_len = 0;
    uint8_t *raw = filtered_scanlines(img, &raw_len);
    struct bytes z = {0};
    if (!raw || !image_zlib_compress(raw, raw_len, &z)) {
        s->error = ENOMEM;
    }
    image_sink_put(s, signature, sizeof signature);
    put_chunk(s, "IHDR", ihdr, sizeof ihdr);
    put_chunk(s, "sRGB", srgb_intent, sizeof srgb_intent);
    for (size_t at = 0; at < z.len; at += IDAT_MAX) {
        put_chunk(s, "IDAT", z.data + at, z.len - at < IDAT_MAX ? z.len - at : IDAT_MAX);
    }
    put_chunk(s, "IEND", NULL, 0);
    free(raw);
    free(z.data);
}

unsigned char *
image_png_bytes(const struct image *img, size_t *len, struct diag *err)
{
    char *buf = NULL;
    size_t n = 0;
    FILE *mem = open_memstream(&buf, &n);
    struct sink sink = {.f = mem};
    if (mem) {
        image_write_png(&sink, img);
    }
    if (!mem || fclose(mem) != 0 || sink.error != 0) {
        free(buf);
        diag_set(err, NULL, 0, 0, "out of memory for a %dx%d PNG", img->width, img->height);
        return NULL;
    }
    *len = n;
    return (unsigned char *)buf;
}

void
image_write_base64(FILE *f, const unsigned char *data, size_t n)
{
    static const char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (size_t i = 0; i < n; i += 3) {
        uint32_t v = (uint32_t)data[i] << 16;
        v |= i + 1 < n ? (uint32_t)data[i + 1] << 8 : 0;
        v |= i + 2 < n ? data[i + 2] : 0;
        fputc(digits[v >> 18 & 63], f);
        fputc(digits[v >> 12 & 63], f);
        fputc(i + 1 < n ? digits[v >> 6 & 63] : '=', f);
        fputc(i + 2 < n ? digits[v & 63] : '=', f);
    }
}
