/*
 * image_zlib.c - the compression inside a PNG: CRC-32 and Adler-32, and a
 * zlib stream (RFC 1950) holding fixed-Huffman deflate blocks (RFC 1951)
 * fed by a small hash-chain LZ77 matcher.  It aims at reasonably small files
 * from simple code, not at zlib's ratios: fixed Huffman codes need no
 * code-length tables, and a block that would come out larger than the data
 * is stored instead.
 */
#include "image.h"

#include "image_codec.h"

#include <stdlib.h>

/* ---- checksums ------------------------------------------------------------ */

/* The reflected CRC-32 polynomial of PNG (ISO/IEC 15948 annex D), as in zlib. */
#define CRC32_POLY 0xEDB88320u

uint32_t
image_crc32(uint32_t crc, const uint8_t *data, size_t n)
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
image_adler32(uint32_t adler, const uint8_t *data, size_t n)
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
bool
image_zlib_compress(const uint8_t *data, size_t n, struct bytes *out)
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
    store_be32(trailer, image_adler32(1, data, n));
    for (int i = 0; i < 4; i++) {
        push_byte(&d.w.out, trailer[i]);
    }
    *out = d.w.out;
    free(d.head);
    free(d.prev);
    return !out->failed;
}
