/*
 * image.c - the framebuffer, and the PNG, PPM and PFM files it is written to
 * (see image.h).  OpenEXR lives in image_exr.c, built only with the library.
 *
 * The PNG writer is self-contained: CRC-32 and Adler-32, a zlib stream
 * (RFC 1950) holding fixed-Huffman deflate blocks (RFC 1951) fed by a small
 * hash-chain LZ77 matcher, and per-row filters (PNG, ISO/IEC 15948).  It aims
 * at reasonably small files from simple code, not at zlib's ratios: fixed
 * Huffman codes need no code-length tables, and a block that would come out
 * larger than the data is stored instead.
 */
#include "image.h"

#include "atomic_file.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>

#ifdef HAVE_OPENEXR
#include "image_exr.h"
#endif

/* PFM and EXR store IEEE 754 binary32; the byte order is handled explicitly. */
_Static_assert(sizeof(float) == 4, "float must be IEEE 754 binary32");

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

/* ---- sRGB (IEC 61966-2-1) ---------------------------------------------- */

float
srgb_from_linear(float linear)
{
    // The linear segment near black meets the power curve at 0.0031308.
    if (linear <= 0.0031308f) {
        return 12.92f * linear;
    }
    return (float)(1.055 * pow(linear, 1.0 / 2.4) - 0.055);
}

float
linear_from_srgb(float encoded)
{
    if (encoded <= 0.04045f) {
        return encoded / 12.92f;
    }
    return (float)pow((encoded + 0.055) / 1.055, 2.4);
}

uint8_t
srgb_encode8(float linear)
{
    // Written so that NaN takes the first branch: !(NaN > 0) is true.
    if (!(linear > 0.0f)) {
        return 0;
    }
    if (linear >= 1.0f) {
        return 255;
    }
    return (uint8_t)(srgb_from_linear(linear) * 255.0f + 0.5f);
}

/* ---- checksums ------------------------------------------------------------ */

/* The reflected CRC-32 polynomial of PNG (ISO/IEC 15948 annex D), as in zlib. */
#define CRC32_POLY 0xEDB88320u

uint32_t
png_crc32(uint32_t crc, const uint8_t *data, size_t n)
{
    // A 16-entry table, one input nibble per step: built on the stack in 64
    // shifts, so there is no shared state to initialise across threads.
    uint32_t table[16];
    for (uint32_t i = 0; i < 16; i++) {
        uint32_t c = i;
        for (int bit = 0; bit < 4; bit++) {
            c = (c & 1) ? CRC32_POLY ^ (c >> 1) : c >> 1;
        }
        table[i] = c;
    }
    // The register is inverted before and after, so running values chain.
    crc = ~crc;
    for (size_t i = 0; i < n; i++) {
        crc ^= data[i];
        crc = (crc >> 4) ^ table[crc & 0xF];
        crc = (crc >> 4) ^ table[crc & 0xF];
    }
    return ~crc;
}

/* Adler-32 (RFC 1950 section 8.2): sums modulo the largest prime < 2^16. */
#define ADLER_MOD 65521u
/* Largest n for which 255 n (n + 1) / 2 + (n + 1) (ADLER_MOD - 1) fits in 32
 * bits, so the modulo can wait until after n bytes. */
#define ADLER_NMAX 5552

uint32_t
png_adler32(uint32_t adler, const uint8_t *data, size_t n)
{
    uint32_t a = adler & 0xFFFF;
    uint32_t b = adler >> 16;
    while (n > 0) {
        size_t k = n < ADLER_NMAX ? n : ADLER_NMAX;
        n -= k;
        for (; k > 0; k--) {
            a += *data++;
            b += a;
        }
        a %= ADLER_MOD;
        b %= ADLER_MOD;
    }
    return b << 16 | a;
}

/* ---- output helpers ------------------------------------------------------- */

/* A FILE that remembers the first error, so encoders need not check each
 * write: once error is set, further writes are skipped. */
struct sink {
    FILE *f;
    int error; /* errno of the first failure, 0 while all is well */
};

static void
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

static void
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

static void
push_byte(struct bytes *b, uint8_t v)
{
    if (b->len == b->cap) {
        size_t cap = b->cap ? b->cap * 2 : 4096;  // doubling: amortised O(1) pushes
        uint8_t *grown = b->failed ? NULL : realloc(b->data, cap);
        if (!grown) {
            b->failed = true;
            return;
        }
        b->data = grown;
        b->cap = cap;
    }
    b->data[b->len++] = v;
}

/* ---- deflate (RFC 1951) --------------------------------------------------- */

#define WINDOW_SIZE 32768 /* largest distance a match may reach back */
#define MIN_MATCH 3
#define MAX_MATCH 258
#define HASH_BITS 15
#define MAX_PROBES 64 /* chain links followed per position: speed vs ratio */
#define MAX_STORED 65535 /* LEN of a stored block is 16 bits */
#define END_OF_BLOCK 256

/* Deflate packs bits from the least significant end of each byte. */
struct bit_writer {
    struct bytes out;
    uint64_t bits;
    int n_bits;
};

static void
put_bits(struct bit_writer *w, uint32_t value, int count)
{
    w->bits |= (uint64_t)value << w->n_bits;
    w->n_bits += count;
    while (w->n_bits >= 8) {
        push_byte(&w->out, (uint8_t)w->bits);
        w->bits >>= 8;
        w->n_bits -= 8;
    }
}

/* Huffman codes are defined most significant bit first (RFC 1951 3.1.1). */
static void
put_code(struct bit_writer *w, uint32_t code, int length)
{
    uint32_t reversed = 0;
    for (int i = 0; i < length; i++) {
        reversed = reversed << 1 | ((code >> i) & 1);
    }
    put_bits(w, reversed, length);
}

/* A literal/length symbol in the fixed code of RFC 1951 section 3.2.6. */
static void
put_symbol(struct bit_writer *w, int symbol)
{
    if (symbol < 144) {
        put_code(w, 0x30 + (uint32_t)symbol, 8);
    } else if (symbol < 256) {
        put_code(w, 0x190 + (uint32_t)(symbol - 144), 9);
    } else if (symbol < 280) {
        put_code(w, (uint32_t)(symbol - 256), 7);
    } else {
        put_code(w, 0xC0 + (uint32_t)(symbol - 280), 8);
    }
}

/* Lengths 3..258 as codes 257..285 plus extra bits (RFC 1951 3.2.5). */
static const uint16_t length_base[29] = {
    3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23,  27,
    31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258,
};
static const uint8_t length_extra[29] = {
    0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0,
};

/* Distances 1..32768 as codes 0..29 plus extra bits (RFC 1951 3.2.5). */
static const uint16_t dist_base[30] = {
    1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,   65,    97,    129,
    193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577,
};
static const uint8_t dist_extra[30] = {
    0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
    6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13,
};

/* The code whose range holds value: the last base not above it. */
static int
find_code(const uint16_t *base, int n_codes, size_t value)
{
    int code = n_codes - 1;
    while (base[code] > value) {
        code--;
    }
    return code;
}

static void
put_match(struct bit_writer *w, size_t length, size_t distance)
{
    int lc = find_code(length_base, 29, length);
    put_symbol(w, 257 + lc);
    put_bits(w, (uint32_t)(length - length_base[lc]), length_extra[lc]);
    int dc = find_code(dist_base, 30, distance);
    put_code(w, (uint32_t)dc, 5);  // fixed distance codes are 5 bits
    put_bits(w, (uint32_t)(distance - dist_base[dc]), dist_extra[dc]);
}

/* LZ77 state: head[h] is the latest position whose next three bytes hash to
 * h, prev[p % WINDOW_SIZE] the one before p with the same hash.  Positions
 * are stored plus one, so zero (calloc) means none. */
struct deflate {
    const uint8_t *data;
    size_t n;
    size_t *head;
    size_t *prev;
    struct bit_writer w;
};

static uint32_t
hash3(const uint8_t *p)
{
    uint32_t v = (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2];
    // Knuth's multiplicative hash: 2654435761 is close to 2^32 / golden ratio.
    return (v * 2654435761u) >> (32 - HASH_BITS);
}

static void
insert_position(struct deflate *d, size_t pos)
{
    if (pos + MIN_MATCH > d->n) {
        return;
    }
    uint32_t h = hash3(d->data + pos);
    d->prev[pos % WINDOW_SIZE] = d->head[h];
    d->head[h] = pos + 1;
}

/* Longest earlier occurrence of the bytes at pos, not reaching past end;
 * 0 when there is none of at least MIN_MATCH bytes. */
static size_t
longest_match(const struct deflate *d, size_t pos, size_t end, size_t *out_dist)
{
    size_t limit = end - pos < MAX_MATCH ? end - pos : MAX_MATCH;
    if (limit < MIN_MATCH) {
        return 0;
    }
    size_t best = 0;
    size_t link = d->head[hash3(d->data + pos)];
    for (int probe = 0; link != 0 && probe < MAX_PROBES; probe++) {
        size_t cand = link - 1;
        // Beyond the window, prev[] slots may have been reused: stop there.
        if (cand >= pos || pos - cand > WINDOW_SIZE) {
            break;
        }
        size_t len = 0;
        while (len < limit && d->data[cand + len] == d->data[pos + len]) {
            len++;
        }
        if (len > best) {
            best = len;
            *out_dist = pos - cand;
            if (len == limit) {
                break;
            }
        }
        link = d->prev[cand % WINDOW_SIZE];
    }
    return best >= MIN_MATCH ? best : 0;
}

static size_t
bit_count(const struct bit_writer *w)
{
    return w->out.len * 8 + (size_t)w->n_bits;
}

static void
put_stored_block(struct bit_writer *w, const uint8_t *data, size_t len, bool final)
{
    put_bits(w, final, 1);
    put_bits(w, 0, 2);  // BTYPE 00: no compression
    if (w->n_bits > 0) {
        put_bits(w, 0, 8 - w->n_bits);  // stored data starts on a byte boundary
    }
    put_bits(w, (uint32_t)len, 16);
    put_bits(w, (uint32_t)len ^ 0xFFFF, 16);  // NLEN, the one's complement
    for (size_t i = 0; i < len; i++) {
        push_byte(&w->out, data[i]);
    }
}

static void
put_fixed_block(struct deflate *d, size_t start, size_t end, bool final)
{
    put_bits(&d->w, final, 1);
    put_bits(&d->w, 1, 2);  // BTYPE 01: fixed Huffman codes
    size_t pos = start;
    while (pos < end) {
        size_t dist = 0;
        size_t len = longest_match(d, pos, end, &dist);
        if (len > 0) {
            put_match(&d->w, len, dist);
        } else {
            put_symbol(&d->w, d->data[pos]);
            len = 1;
        }
        for (size_t i = 0; i < len; i++) {
            insert_position(d, pos + i);
        }
        pos += len;
    }
    put_symbol(&d->w, END_OF_BLOCK);
}

/* One block of at most MAX_STORED bytes: compressed, unless storing it is
 * smaller (noisy images often are), in which case the bits are taken back. */
static void
put_block(struct deflate *d, size_t start, size_t end, bool final)
{
    size_t saved_len = d->w.out.len;
    uint64_t saved_bits = d->w.bits;
    int saved_n_bits = d->w.n_bits;
    size_t before = bit_count(&d->w);
    put_fixed_block(d, start, end, final);
    size_t fixed_bits = bit_count(&d->w) - before;
    // A stored block: 3 header bits, up to 7 padding bits, LEN and NLEN.
    size_t stored_bits = 3 + 7 + 32 + (end - start) * 8;
    if (fixed_bits > stored_bits) {
        d->w.out.len = saved_len;
        d->w.bits = saved_bits;
        d->w.n_bits = saved_n_bits;
        put_stored_block(&d->w, d->data + start, end - start, final);
    }
}

/* A zlib stream (RFC 1950) of data, appended to out; false when memory ran
 * out. */
static bool
zlib_compress(const uint8_t *data, size_t n, struct bytes *out)
{
    struct deflate d = {.data = data, .n = n, .w = {.out = *out}};
    d.head = calloc((size_t)1 << HASH_BITS, sizeof *d.head);
    d.prev = calloc(WINDOW_SIZE, sizeof *d.prev);
    if (!d.head || !d.prev) {
        free(d.head);
        free(d.prev);
        return false;
    }
    // CMF: method 8 (deflate), CINFO 7 (32 KiB window).  FLG: FLEVEL 1
    // ("fast"), and FCHECK makes CMF * 256 + FLG a multiple of 31.
    const uint32_t cmf = 0x78;
    const uint32_t flevel = 1u << 6;
    put_bits(&d.w, cmf, 8);
    put_bits(&d.w, flevel + 31 - (cmf * 256 + flevel) % 31, 8);
    size_t start = 0;
    do {
        size_t end = n - start > MAX_STORED ? start + MAX_STORED : n;
        put_block(&d, start, end, end == n);
        start = end;
    } while (start < n);
    if (d.w.n_bits > 0) {
        put_bits(&d.w, 0, 8 - d.w.n_bits);
    }
    uint8_t trailer[4];
    store_be32(trailer, png_adler32(1, data, n));
    for (int i = 0; i < 4; i++) {
        push_byte(&d.w.out, trailer[i]);
    }
    *out = d.w.out;
    free(d.head);
    free(d.prev);
    return !out->failed;
}

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
    uint32_t crc = png_crc32(png_crc32(0, head + 4, 4), data, len);
    uint8_t tail[4];
    store_be32(tail, crc);
    put(s, head, sizeof head);
    put(s, data, len);
    put(s, tail, sizeof tail);
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

static void
encode_row(const struct image *img, int y, uint8_t *out)
{
    const float *p = image_pixel(img, 0, y);
    for (size_t i = 0; i < (size_t)img->width * 3; i++) {
        out[i] = srgb_encode8(p[i]);
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
            encode_row(img, y, cur);
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

static void
write_png(struct sink *s, const struct image *img)
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
    if (!raw || !zlib_compress(raw, raw_len, &z)) {
        s->error = ENOMEM;
    }
    put(s, signature, sizeof signature);
    put_chunk(s, "IHDR", ihdr, sizeof ihdr);
    put_chunk(s, "sRGB", srgb_intent, sizeof srgb_intent);
    for (size_t at = 0; at < z.len; at += IDAT_MAX) {
        put_chunk(s, "IDAT", z.data + at, z.len - at < IDAT_MAX ? z.len - at : IDAT_MAX);
    }
    put_chunk(s, "IEND", NULL, 0);
    free(raw);
    free(z.data);
}

/* ---- PPM and PFM ---------------------------------------------------------- */

static void
write_ppm(struct sink *s, const struct image *img)
{
    errno = 0;
    if (fprintf(s->f, "P6\n%d %d\n255\n", img->width, img->height) < 0) {
        s->error = errno ? errno : EIO;
    }
    size_t n = (size_t)img->width * 3;
    uint8_t *row = malloc(n);
    if (!row) {
        s->error = ENOMEM;
        return;
    }
    for (int y = 0; y < img->height; y++) {
        encode_row(img, y, row);
        put(s, row, n);
    }
    free(row);
}

static void
store_le32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

/* PFM: a negative scale says little endian; rows run bottom to top. */
static void
write_pfm(struct sink *s, const struct image *img)
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
        put(s, row, n * 4);
    }
    free(row);
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

/* Encode img into f, the temporary file (OpenEXR writes to its descriptor). */
static bool
encode(
    const struct image *img,
    enum image_format format,
    FILE *f,
    const char *path,
    struct diag *err)
{
#ifdef HAVE_OPENEXR
    if (format == IMAGE_FORMAT_EXR) {
        return image_exr_write(img, fileno(f), path, err);
    }
#endif
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
image_write(const struct image *img, const char *path, struct diag *err)
{
    enum image_format format = image_format_from_path(path);
    struct atomic_file af;
    if (!check_format(format, path, err) || !atomic_file_open(&af, path, err)) {
        return false;
    }
    if (!encode(img, format, af.f, path, err)) {
        atomic_file_abort(&af);
        return false;
    }
    return atomic_file_commit(&af, err);
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
