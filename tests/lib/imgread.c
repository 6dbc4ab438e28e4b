/*
 * imgread.c - see imgread.h.  The PNG reader follows the PNG specification
 * (ISO/IEC 15948, W3C PNG 2nd ed.): chunks, the zlib stream (RFC 1950) of
 * DEFLATE data (RFC 1951), scanline filters; the inflater is written from
 * RFC 1951 section 3.2 (canonical Huffman codes, length/distance pairs).
 */
#include "imgread.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef HAVE_OPENEXR
bool imgread_exr_layer(const char *path, const char *layer, struct image *out, struct diag *err);
#endif

/* ---- inflate (RFC 1951) --------------------------------------------------- */

struct bit_reader {
    const uint8_t *data;
    size_t n, pos; /* bytes, and the next byte */
    uint32_t bits; /* buffered bits, least significant first */
    int count;
    bool overrun; /* read past the end */
};

static uint32_t
get_bits(struct bit_reader *r, int count)
{
    while (r->count < count) {
        uint32_t byte = 0;
        if (r->pos < r->n) {
            byte = r->data[r->pos++];
        } else {
            r->overrun = true;
        }
        r->bits |= byte << r->count;
        r->count += 8;
    }
    uint32_t v = r->bits & ((1u << count) - 1);
    r->bits >>= count;
    r->count -= count;
    return v;
}

/* A canonical Huffman code: counts[len] codes of each length, symbols in
 * code order (RFC 1951 3.2.2). */
#define HUFF_MAX_BITS 15

struct huffman {
    uint16_t counts[HUFF_MAX_BITS + 1];
    uint16_t symbols[288];
};

/* Build the code from n code lengths; false when the lengths over-subscribe
 * the code space (an incomplete code is allowed, as zlib does). */
static bool
huffman_build(struct huffman *h, const uint8_t *lengths, int n)
{
    memset(h->counts, 0, sizeof h->counts);
    for (int i = 0; i < n; i++) {
        h->counts[lengths[i]]++;
    }
    h->counts[0] = 0;
    int left = 1;
    for (int len = 1; len <= HUFF_MAX_BITS; len++) {
        left = 2 * left - h->counts[len];
        if (left < 0) {
            return false;
        }
    }
    uint16_t offsets[HUFF_MAX_BITS + 1];
    offsets[1] = 0;
    for (int len = 1; len < HUFF_MAX_BITS; len++) {
        offsets[len + 1] = (uint16_t)(offsets[len] + h->counts[len]);
    }
    for (int i = 0; i < n; i++) {
        if (lengths[i]) {
            h->symbols[offsets[lengths[i]]++] = (uint16_t)i;
        }
    }
    return true;
}

/* Decode one symbol bit by bit: codes are stored most significant bit
 * first, and the first code of each length follows from the counts. */
static int
huffman_decode(struct bit_reader *r, const struct huffman *h)
{
    int code = 0, first = 0, index = 0;
    for (int len = 1; len <= HUFF_MAX_BITS; len++) {
        code |= (int)get_bits(r, 1);
        int count = h->counts[len];
        if (code - first < count) {
            return h->symbols[index + code - first];
        }
        index += count;
        first = (first + count) << 1;
        code <<= 1;
    }
    return -1;
}

struct inflate_out {
    uint8_t *data;
    size_t n, cap; /* cap: the most the caller will accept */
};

static const uint16_t length_base[29] = {3,  4,  5,  6,   7,   8,   9,   10,  11, 13,
                                         15, 17, 19, 23,  27,  31,  35,  43,  51, 59,
                                         67, 83, 99, 115, 131, 163, 195, 227, 258};
static const uint8_t length_extra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                         2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
static const uint16_t dist_base[30] = {
    1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,   65,    97,    129,
    193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
static const uint8_t dist_extra[30] = {0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
                                       6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};

/* The symbols of one compressed block up to its end code. */
static const char *
inflate_codes(
    struct bit_reader *r,
    struct inflate_out *o,
    const struct huffman *lit,
    const struct huffman *dist)
{
    for (;;) {
        int sym = huffman_decode(r, lit);
        if (sym < 0 || r->overrun) {
            return "bad literal/length code";
        }
        if (sym < 256) {
            if (o->n >= o->cap) {
                return "more image data than the header says";
            }
            o->data[o->n++] = (uint8_t)sym;
        } else if (sym == 256) {
            return NULL;
        } else {
            sym -= 257;
            if (sym >= 29) {
                return "bad length code";
            }
            size_t len = length_base[sym] + get_bits(r, length_extra[sym]);
            int dsym = huffman_decode(r, dist);
            if (dsym < 0 || dsym >= 30) {
                return "bad distance code";
            }
            size_t d = dist_base[dsym] + get_bits(r, dist_extra[dsym]);
            if (d > o->n) {
                return "distance reaches before the start";
            }
            if (len > o->cap - o->n) {
                return "more image data than the header says";
            }
            for (size_t i = 0; i < len; i++, o->n++) {
                o->data[o->n] = o->data[o->n - d];
            }
        }
    }
}

/* The fixed codes of RFC 1951 3.2.6. */
static void
fixed_codes(struct huffman *lit, struct huffman *dist)
{
    uint8_t lengths[288];
    for (int i = 0; i < 288; i++) {
        lengths[i] = i < 144 ? 8 : i < 256 ? 9 : i < 280 ? 7 : 8;
    }
    huffman_build(lit, lengths, 288);
    for (int i = 0; i < 30; i++) {
        lengths[i] = 5;
    }
    huffman_build(dist, lengths, 30);
}

/* The code lengths of a dynamic block (RFC 1951 3.2.7). */
static const char *
dynamic_codes(struct bit_reader *r, struct huffman *lit, struct huffman *dist)
{
    static const uint8_t order[19] =
        {16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15};
    int nlen = (int)get_bits(r, 5) + 257;
    int ndist = (int)get_bits(r, 5) + 1;
    int ncode = (int)get_bits(r, 4) + 4;
    if (nlen > 286 || ndist > 30) {
        return "bad code counts";
    }
    uint8_t lengths[320] = {0};
    for (int i = 0; i < ncode; i++) {
        lengths[order[i]] = (uint8_t)get_bits(r, 3);
    }
    struct huffman lencode;
    if (!huffman_build(&lencode, lengths, 19)) {
        return "bad code-length code";
    }
    memset(lengths, 0, sizeof lengths);
    for (int i = 0; i < nlen + ndist;) {
        int sym = huffman_decode(r, &lencode);
        if (sym < 0 || r->overrun) {
            return "bad code length";
        }
        if (sym < 16) {
            lengths[i++] = (uint8_t)sym;
            continue;
        }
        int repeat, value = 0;
        if (sym == 16) {
            if (i == 0) {
                return "repeat with no previous length";
            }
            value = lengths[i - 1];
            repeat = 3 + (int)get_bits(r, 2);
        } else if (sym == 17) {
            repeat = 3 + (int)get_bits(r, 3);
        } else {
            repeat = 11 + (int)get_bits(r, 7);
        }
        if (i + repeat > nlen + ndist) {
            return "too many code lengths";
        }
        while (repeat--) {
            lengths[i++] = (uint8_t)value;
        }
    }
    if (lengths[256] == 0) {
        return "no end-of-block code";
    }
    if (!huffman_build(lit, lengths, nlen) || !huffman_build(dist, lengths + nlen, ndist)) {
        return "bad Huffman code";
    }
    return NULL;
}

/* Inflate a zlib stream into o (at most o->cap bytes); NULL or what is wrong. */
static const char *
zlib_inflate(const uint8_t *data, size_t n, struct inflate_out *o)
{
    if (n < 6 || (data[0] & 0x0f) != 8 || ((data[0] << 8) | data[1]) % 31 != 0
        || (data[1] & 0x20)) {
        return "not a zlib stream";
    }
    struct bit_reader r = {.data = data + 2, .n = n - 6};
    for (bool last = false; !last;) {
        last = get_bits(&r, 1);
        uint32_t type = get_bits(&r, 2);
        const char *why = NULL;
        if (type == 0) {
            r.bits = 0;
            r.count = 0; /* a stored block starts at a byte boundary */
            if (r.pos + 4 > r.n) {
                return "truncated stored block";
            }
            size_t len = r.data[r.pos] | (size_t)r.data[r.pos + 1] << 8;
            size_t nlen = r.data[r.pos + 2] | (size_t)r.data[r.pos + 3] << 8;
            r.pos += 4;
            if (len != (~nlen & 0xffff) || len > r.n - r.pos || len > o->cap - o->n) {
                return "bad stored block";
            }
            memcpy(o->data + o->n, r.data + r.pos, len);
            o->n += len;
            r.pos += len;
        } else if (type == 1 || type == 2) {
            struct huffman lit, dist;
            if (type == 1) {
                fixed_codes(&lit, &dist);
            } else {
                why = dynamic_codes(&r, &lit, &dist);
            }
            why = why ? why : inflate_codes(&r, o, &lit, &dist);
        } else {
            why = "bad block type";
        }
        if (why || r.overrun) {
            return why ? why : "truncated data";
        }
    }
    const uint8_t *a = data + n - 4;
    uint32_t adler = (uint32_t)a[0] << 24 | (uint32_t)a[1] << 16 | (uint32_t)a[2] << 8 | a[3];
    return image_adler32(1, o->data, o->n) == adler ? NULL : "zlib checksum mismatch";
}

/* ---- PNG ------------------------------------------------------------------- */

struct png_header {
    uint32_t width, height;
    int depth, colour, channels; /* bit depth, colour type, samples per pixel */
    uint8_t palette[256][3];
    int palette_size;
};

static uint32_t
load_be32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static const char *
parse_ihdr(const uint8_t *d, uint32_t len, struct png_header *h)
{
    if (len != 13) {
        return "bad IHDR chunk";
    }
    h->width = load_be32(d);
    h->height = load_be32(d + 4);
    h->depth = d[8];
    h->colour = d[9];
    if (h->width < 1 || h->height < 1 || h->width > IMAGE_MAX_DIM || h->height > IMAGE_MAX_DIM) {
        return "image size out of range";
    }
    static const int channels[7] = {1, 0, 3, 1, 2, 0, 4};
    h->channels = h->colour <= 6 ? channels[h->colour] : 0;
    bool depth_ok = h->depth == 8 || h->depth == 16 || (h->colour == 3 && h->depth == 8);
    if (h->channels == 0 || !depth_ok || (h->colour == 3 && h->depth != 8)) {
        return "unsupported PNG type (8- or 16-bit grey, RGB, palette or alpha only)";
    }
    if (d[10] != 0 || d[11] != 0) {
        return "unknown compression or filter method";
    }
    if (d[12] != 0) {
        return "interlaced PNG not supported (save it without interlacing)";
    }
    return NULL;
}

/* Undo the scanline filters in place (PNG spec. section 9). */
static const char *
unfilter(uint8_t *raw, const struct png_header *h, size_t stride, int bpp)
{
    uint8_t *prior = NULL;
    for (uint32_t y = 0; y < h->height; y++) {
        uint8_t *line = raw + y * (stride + 1);
        int type = line[0];
        uint8_t *cur = line + 1;
        for (size_t i = 0; i < stride; i++) {
            int a = i >= (size_t)bpp ? cur[i - (size_t)bpp] : 0;
            int b = prior ? prior[i] : 0;
            int c = prior && i >= (size_t)bpp ? prior[i - (size_t)bpp] : 0;
            int pred = 0;
            if (type == 1) {
                pred = a;
            } else if (type == 2) {
                pred = b;
            } else if (type == 3) {
                pred = (a + b) / 2;
            } else if (type == 4) {
                int p = a + b - c, pa = abs(p - a), pb = abs(p - b), pc = abs(p - c);
                pred = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
            } else if (type != 0) {
                return "bad scanline filter";
            }
            cur[i] = (uint8_t)(cur[i] + pred);
        }
        prior = cur;
    }
    return NULL;
}

/* Sample s of a pixel's samples, as a fraction of full scale. */
static float
sample_value(const uint8_t *p, int depth, int s)
{
    if (depth == 16) {
        return (float)(p[2 * s] << 8 | p[2 * s + 1]) / 65535.0f;
    }
    return (float)p[s] / 255.0f;
}

static const char *
convert_pixels(const uint8_t *raw, const struct png_header *h, size_t stride, struct image *out)
{
    int bytes = h->channels * h->depth / 8;
    for (uint32_t y = 0; y < h->height; y++) {
        const uint8_t *line = raw + y * (stride + 1) + 1;
        for (uint32_t x = 0; x < h->width; x++) {
            const uint8_t *p = line + (size_t)x * (size_t)bytes;
            float *q = image_pixel(out, (int)x, (int)y);
            float rgb[3];
            if (h->colour == 3) {
                if (p[0] >= h->palette_size) {
                    return "palette index out of range";
                }
                for (int c = 0; c < 3; c++) {
                    rgb[c] = h->palette[p[0]][c] / 255.0f;
                }
            } else {
                bool grey = h->colour == 0 || h->colour == 4;
                for (int c = 0; c < 3; c++) {
                    rgb[c] = sample_value(p, h->depth, grey ? 0 : c);
                }
            }
            for (int c = 0; c < 3; c++) {
                q[c] = image_linear_from_srgb(rgb[c]);
            }
        }
    }
    return NULL;
}

/* Collect the IDAT data and the header; NULL or what is wrong. */
static const char *
read_chunks(const uint8_t *data, size_t n, struct png_header *h, uint8_t **idat, size_t *idat_n)
{
    static const uint8_t signature[8] = {137, 80, 78, 71, 13, 10, 26, 10};
    if (n < 8 || memcmp(data, signature, 8) != 0) {
        return "not a PNG file";
    }
    bool have_header = false;
    for (size_t pos = 8;;) {
        if (n - pos < 12) {
            return "truncated PNG (no IEND chunk)";
        }
        uint32_t len = load_be32(data + pos);
        const uint8_t *type = data + pos + 4;
        const uint8_t *body = data + pos + 8;
        if (len > n - pos - 12) {
            return "truncated chunk";
        }
        if (image_crc32(0, type, (size_t)len + 4) != load_be32(body + len)) {
            return "chunk checksum mismatch";
        }
        if (memcmp(type, "IHDR", 4) == 0) {
            const char *why = parse_ihdr(body, len, h);
            if (why) {
                return why;
            }
            have_header = true;
        } else if (!have_header) {
            return "the first chunk is not IHDR";
        } else if (memcmp(type, "PLTE", 4) == 0) {
            if (len % 3 || len > 768) {
                return "bad palette";
            }
            h->palette_size = (int)(len / 3);
            memcpy(h->palette, body, len);
        } else if (memcmp(type, "IDAT", 4) == 0) {
            uint8_t *grown = realloc(*idat, *idat_n + len + 1);
            if (!grown) {
                return "out of memory";
            }
            *idat = grown;
            memcpy(*idat + *idat_n, body, len);
            *idat_n += len;
        } else if (memcmp(type, "IEND", 4) == 0) {
            return *idat_n ? NULL : "no image data";
        } else if (!(type[0] & 0x20)) {
            return "unknown critical chunk";
        }
        pos += (size_t)len + 12;
    }
}

bool
imgread_png_memory(
    const unsigned char *data,
    size_t n,
    const char *path,
    struct image *out,
    struct diag *err)
{
    *out = (struct image){0};
    struct png_header h = {0};
    uint8_t *idat = NULL;
    size_t idat_n = 0;
    const char *why = read_chunks(data, n, &h, &idat, &idat_n);
    int bpp = h.channels * h.depth / 8; /* bytes per complete pixel */
    size_t stride = (size_t)h.width * (size_t)bpp;
    struct inflate_out raw = {0};
    /* DEFLATE expands at most 1032:1 (a 258-byte match in 2 bits), so a
     * header promising more than that is refused before allocating. */
    if (!why && (stride + 1) * h.height / 1032 > idat_n + 1024) {
        why = "less image data than the header says";
    }
    if (!why) {
        raw.cap = (stride + 1) * h.height;
        raw.data = malloc(raw.cap);
        why = raw.data ? zlib_inflate(idat, idat_n, &raw) : "out of memory";
    }
    if (!why && raw.n != raw.cap) {
        why = "less image data than the header says";
    }
    why = why ? why : unfilter(raw.data, &h, stride, bpp);
    if (!why && !image_alloc(out, (int)h.width, (int)h.height, err)) {
        why = "out of memory";
    }
    why = why ? why : convert_pixels(raw.data, &h, stride, out);
    free(idat);
    free(raw.data);
    if (why) {
        image_free(out);
        diag_set(err, path, 0, 0, "%s", why);
        return false;
    }
    return true;
}

/* Read a whole file (at most `limit` bytes). */
static unsigned char *
read_whole(const char *path, size_t limit, size_t *n, struct diag *err)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        diag_set(err, path, 0, 0, "cannot open");
        return NULL;
    }
    size_t cap = 1 << 16, len = 0;
    unsigned char *buf = malloc(cap);
    while (buf) {
        len += fread(buf + len, 1, cap - len, f);
        if (len < cap || cap >= limit) {
            break;
        }
        unsigned char *grown = realloc(buf, cap * 2);
        if (!grown) {
            free(buf);
            buf = NULL;
            break;
        }
        buf = grown;
        cap *= 2;
    }
    bool bad = !buf || ferror(f) || (len == cap && cap >= limit);
    fclose(f);
    if (!buf) {
        diag_set(err, path, 0, 0, "out of memory");
        return NULL;
    }
    if (bad) {
        free(buf);
        diag_set(err, path, 0, 0, "cannot read (or larger than %zu bytes)", limit);
        return NULL;
    }
    *n = len;
    return buf;
}

/* An OpenEXR file's R, G, B (layer NULL) or one layer's channels. */
static bool
read_exr(const char *path, const char *layer, struct image *out, struct diag *err)
{
#ifdef HAVE_OPENEXR
    return imgread_exr_layer(path, layer, out, err);
#else
    (void)layer;
    (void)out;
    diag_set(
        err,
        path,
        0,
        0,
        "this build has no OpenEXR (apt-get install libopenexr-dev, then make)");
    return false;
#endif
}

bool
imgread(const char *path, struct image *out, struct diag *err)
{
    *out = (struct image){0};
    switch (image_format_from_path(path)) {
    case IMAGE_FORMAT_PFM:
        return image_read_pfm(path, out, err);
    case IMAGE_FORMAT_EXR:
        return read_exr(path, NULL, out, err);
    case IMAGE_FORMAT_PNG: {
        size_t n = 0;
        /* A PNG this size inflates to more than IMAGE_MAX_DIM^2 pixels. */
        unsigned char *data = read_whole(path, (size_t)1 << 31, &n, err);
        bool ok = data && imgread_png_memory(data, n, path, out, err);
        free(data);
        return ok;
    }
    default:
        diag_set(err, path, 0, 0, "unknown image format (expected .pfm, .exr or .png)");
        return false;
    }
}

bool
imgread_layer(const char *path, const char *layer, struct image *out, struct diag *err)
{
    *out = (struct image){0};
    if (image_format_from_path(path) != IMAGE_FORMAT_EXR) {
        diag_set(err, path, 0, 0, "only an OpenEXR file has layers (here: %s)", layer);
        return false;
    }
    return read_exr(path, layer, out, err);
}
