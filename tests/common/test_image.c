/*
 * test_image.c - unit tests of common/image/image.c (and image_exr.c): the sRGB
 * transfer function, the PNG checksums, the PNG, PPM, PFM and EXR writers,
 * the PFM reader, and image_write()'s temporary-file-and-rename scheme.
 *
 * PNG files are checked by decoding them here with an independent little
 * decoder (chunks, CRCs, zlib header, stored and fixed-Huffman deflate,
 * Adler-32, the five row filters), and by Python's zlib when python3 exists.
 * EXR files are read back with OpenEXR's C API when this test is compiled
 * with HAVE_OPENEXR and OpenEXR's include flags; otherwise only their header
 * is checked.
 */
#include "check.h"
#include "testlib.h"

#include "image.h"
#include "imgread.h"
#include "rng.h"

#include <dirent.h>
#include <errno.h>
#include <float.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>

#ifdef HAVE_OPENEXR
#include <openexr.h>
#endif

/* ---- helpers ---------------------------------------------------------------- */

/* A smooth gradient (compressible) or noise (not), with some values outside
 * [0, 1] so clamping is exercised too. */
static void
fill_image(struct image *img, bool noisy, uint32_t seed)
{
    struct rng r = rng_make(seed, 0);
    for (int y = 0; y < img->height; y++) {
        for (int x = 0; x < img->width; x++) {
            float *p = image_pixel(img, x, y);
            for (int c = 0; c < 3; c++) {
                if (noisy) {
                    p[c] = (float)(rng_next_u32(&r) % 1000) / 800.0f - 0.1f;
                } else {
                    p[c] = (float)(x + 2 * y + 40 * c) / (float)(img->width + 2 * img->height + 80);
                }
            }
        }
    }
}

static uint32_t
load_be32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* Bit-at-a-time CRC-32, straight from the definition, to check image_crc32. */
static uint32_t
reference_crc32(const uint8_t *data, size_t n)
{
    uint32_t crc = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; i++) {
        crc ^= data[i];
        for (int bit = 0; bit < 8; bit++) {
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1)));
        }
    }
    return ~crc;
}

/* Adler-32 with a modulo after every byte, to check image_adler32. */
static uint32_t
reference_adler32(const uint8_t *data, size_t n)
{
    uint32_t a = 1;
    uint32_t b = 0;
    for (size_t i = 0; i < n; i++) {
        a = (a + data[i]) % 65521;
        b = (b + a) % 65521;
    }
    return b << 16 | a;
}

/* Names in dir containing ".tmp-" (leftover temporary files). */
static int
count_temp_files(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) {
        return -1;
    }
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strstr(e->d_name, ".tmp-")) {
            printf("leftover temporary file %s/%s\n", dir, e->d_name);
            n++;
        }
    }
    closedir(d);
    return n;
}

static bool
same_bits(float a, float b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* ---- sRGB ------------------------------------------------------------------- */

TEST(srgb_known_values)
{
    CHECK(image_srgb_encode8(0.0f) == 0);
    CHECK(image_srgb_encode8(1.0f) == 255);
    // 0.5 -> 0.73536 * 255 = 187.5 -> 188; 0.18 -> 0.46136 * 255 = 117.6 -> 118
    CHECK(image_srgb_encode8(0.5f) == 188);
    CHECK(image_srgb_encode8(0.18f) == 118);
    CHECK_NEAR(image_srgb_from_linear(0.5f), 0.735356983, 1e-6);
    CHECK_NEAR(image_srgb_from_linear(0.0031308f), 0.040449936, 1e-6);
    CHECK_NEAR(image_linear_from_srgb(0.04045f), 0.04045 / 12.92, 1e-9);
    CHECK_NEAR(image_linear_from_srgb(1.0f), 1.0, 1e-6);
    CHECK_NEAR(image_srgb_from_linear(1.0f), 1.0, 1e-6);
}

TEST(srgb_clamps)
{
    CHECK(image_srgb_encode8(2.0f) == 255);
    CHECK(image_srgb_encode8(1.0001f) == 255);
    CHECK(image_srgb_encode8(-0.5f) == 0);
    CHECK(image_srgb_encode8(-0.0f) == 0);
    CHECK(image_srgb_encode8(NAN) == 0);
    CHECK(image_srgb_encode8(-NAN) == 0);
    CHECK(image_srgb_encode8(INFINITY) == 255);
    CHECK(image_srgb_encode8(-INFINITY) == 0);
    CHECK(image_srgb_encode8(FLT_MAX) == 255);
    CHECK(image_srgb_encode8(1e-30f) == 0);
}

TEST(srgb_continuity_and_round_trip)
{
    // The two pieces meet at 0.0031308: no visible step either side.
    float knee = 0.0031308f;
    CHECK_NEAR(image_srgb_from_linear(knee), image_srgb_from_linear(nextafterf(knee, 1.0f)), 1e-6);
    CHECK_NEAR(
        image_linear_from_srgb(0.04045f),
        image_linear_from_srgb(nextafterf(0.04045f, 1.0f)),
        1e-7);
    float last = -1.0f;
    for (int i = 0; i <= 10000; i++) {
        float x = (float)i / 10000.0f;
        float e = image_srgb_from_linear(x);
        CHECK_MSG(e > last, "not increasing at %g", (double)x);
        last = e;
        CHECK_NEAR(image_linear_from_srgb(e), x, 2e-7 + 2e-6 * x);
    }
    // Every 8-bit code survives decode then encode.
    for (int k = 0; k < 256; k++) {
        CHECK_MSG(image_srgb_encode8(image_linear_from_srgb((float)k / 255.0f)) == k, "code %d", k);
    }
}

/* ---- checksums -------------------------------------------------------------- */

TEST(crc32_and_adler32)
{
    const uint8_t *check = (const uint8_t *)"123456789";
    CHECK(image_crc32(0, check, 9) == 0xCBF43926u);
    CHECK(image_crc32(image_crc32(0, check, 4), check + 4, 5) == 0xCBF43926u);
    CHECK(image_crc32(0, NULL, 0) == 0);
    const uint8_t *wiki = (const uint8_t *)"Wikipedia";
    CHECK(image_adler32(1, wiki, 9) == 0x11E60398u);
    CHECK(image_adler32(image_adler32(1, wiki, 3), wiki + 3, 6) == 0x11E60398u);
    CHECK(image_adler32(1, NULL, 0) == 1);
    // Long runs of 0xFF are the worst case for the deferred modulo.
    size_t n = 100000;
    uint8_t *buf = malloc(n);
    CHECK(buf != NULL);
    if (!buf) {
        return;
    }
    memset(buf, 0xFF, n);
    CHECK(image_adler32(1, buf, n) == reference_adler32(buf, n));
    struct rng r = rng_make(12345, 0);
    for (size_t i = 0; i < n; i++) {
        buf[i] = (uint8_t)rng_next_u32(&r);
    }
    CHECK(image_adler32(1, buf, n) == reference_adler32(buf, n));
    CHECK(image_crc32(0, buf, n) == reference_crc32(buf, n));
    CHECK(image_crc32(image_crc32(0, buf, 777), buf + 777, n - 777) == reference_crc32(buf, n));
    free(buf);
}

/* ---- image basics ----------------------------------------------------------- */

TEST(alloc_limits_and_format_names)
{
    struct image img = {0};
    struct diag err = {0};
    CHECK(image_alloc(&img, 3, 2, &err));
    CHECK(img.width == 3 && img.height == 2 && img.rgb);
    for (int i = 0; img.rgb && i < 18; i++) {
        CHECK(img.rgb[i] == 0.0f);
    }
    image_free(&img);
    CHECK(img.rgb == NULL && img.width == 0);
    image_free(&img);  // a zero image is fine too
    const int bad[][2] = {{0, 1}, {1, 0}, {-1, 5}, {IMAGE_MAX_DIM + 1, 1}, {1, IMAGE_MAX_DIM + 1}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        err.msg[0] = '\0';
        CHECK(!image_alloc(&img, bad[i][0], bad[i][1], &err));
        CHECK(img.rgb == NULL);
        CHECK(strstr(err.msg, "out of range") != NULL);
    }
    CHECK(image_format_from_path("a.png") == IMAGE_FORMAT_PNG);
    CHECK(image_format_from_path("out/A.PNG") == IMAGE_FORMAT_PNG);
    CHECK(image_format_from_path("x.Ppm") == IMAGE_FORMAT_PPM);
    CHECK(image_format_from_path("x.pfm") == IMAGE_FORMAT_PFM);
    CHECK(image_format_from_path("x.y.EXR") == IMAGE_FORMAT_EXR);
    CHECK(image_format_from_path("x.png.bak") == IMAGE_FORMAT_UNKNOWN);
    CHECK(image_format_from_path("dir.png/x") == IMAGE_FORMAT_UNKNOWN);
    CHECK(image_format_from_path("png") == IMAGE_FORMAT_UNKNOWN);
    CHECK(image_format_from_path("x.pngx") == IMAGE_FORMAT_UNKNOWN);
    CHECK(image_format_from_path("") == IMAGE_FORMAT_UNKNOWN);
}

/* ---- PFM -------------------------------------------------------------------- */

TEST(pfm_round_trip_exact)
{
    // 1e-40 and 1e-45 are denormal.
    static const float special[] = {
        0.0f,
        -0.0f,
        1.0f,
        -1.0f,
        0.5f,
        -3.25f,
        1e-20f,
        1e20f,
        -1e20f,
        1e-40f,
        -1e-45f,
        FLT_MIN,
        FLT_MAX,
        -FLT_MAX,
        INFINITY,
        -INFINITY,
        3.14159274f,
        0.1f,
    };
    size_t n_special = sizeof special / sizeof special[0];
    struct image img = {0};
    struct diag err = {0};
    CHECK(image_alloc(&img, 7, 3, &err));
    for (size_t i = 0; i < 7 * 3 * 3; i++) {
        img.rgb[i] = special[i % n_special] * (i >= n_special ? -1.0f : 1.0f);
    }
    img.rgb[20] = NAN;
    const char *path = test_tmp_path("round.pfm");
    CHECK(image_write(&img, path, &err));
    struct image back = {0};
    CHECK(image_read_pfm(path, &back, &err));
    CHECK(back.width == 7 && back.height == 3);
    for (size_t i = 0; back.rgb && i < 7 * 3 * 3; i++) {
        CHECK_MSG(
            same_bits(back.rgb[i], img.rgb[i]),
            "value %zu: %g != %g",
            i,
            (double)back.rgb[i],
            (double)img.rgb[i]);
    }
    image_free(&img);
    image_free(&back);
}

TEST(pfm_rows_bottom_to_top)
{
    struct image img = {0};
    struct diag err = {0};
    CHECK(image_alloc(&img, 2, 3, &err));
    for (int y = 0; y < 3; y++) {
        for (int x = 0; x < 2; x++) {
            for (int c = 0; c < 3; c++) {
                image_pixel(&img, x, y)[c] = (float)(100 * y + 10 * x + c);
            }
        }
    }
    const char *path = test_tmp_path("rows.pfm");
    CHECK(image_write(&img, path, &err));
    size_t len = 0;
    uint8_t *file = (uint8_t *)test_read_file(path, &len);
    const char *header = "PF\n2 3\n-1.0\n";
    size_t hl = strlen(header);
    CHECK(file && len == hl + 2 * 3 * 3 * 4);
    CHECK(file && memcmp(file, header, hl) == 0);
    for (size_t i = 0; file && len == hl + 72 && i < 18; i++) {
        const uint8_t *p = file + hl + 4 * i;
        uint32_t bits =
            (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
        float v;
        memcpy(&v, &bits, 4);
        // File row r is image row 2 - r: the first row written is the bottom.
        int r = (int)i / 6;
        int x = (int)(i % 6) / 3;
        int c = (int)i % 3;
        CHECK_MSG(v == (float)(100 * (2 - r) + 10 * x + c), "float %zu is %g", i, (double)v);
    }
    free(file);
    image_free(&img);
}

static void
put_float_be(uint8_t *p, float v)
{
    uint32_t bits;
    memcpy(&bits, &v, 4);
    p[0] = (uint8_t)(bits >> 24);
    p[1] = (uint8_t)(bits >> 16);
    p[2] = (uint8_t)(bits >> 8);
    p[3] = (uint8_t)bits;
}

TEST(pfm_read_big_endian_and_grey)
{
    // Colour, big endian (positive scale), 2x2: file rows bottom first.
    const char *header = "PF\n2  2\n1.0\n";
    size_t hl = strlen(header);
    uint8_t buf[64];
    memcpy(buf, header, hl);
    for (int i = 0; i < 12; i++) {
        put_float_be(buf + hl + 4 * i, (float)i + 0.25f);
    }
    const char *path = test_tmp_path("be.pfm");
    CHECK(test_write_bytes(path, buf, hl + 48));
    struct image img = {0};
    struct diag err = {0};
    CHECK(image_read_pfm(path, &img, &err));
    CHECK(img.width == 2 && img.height == 2);
    if (img.rgb) {
        CHECK(image_pixel(&img, 0, 1)[0] == 0.25f);  // first in file: bottom left
        CHECK(image_pixel(&img, 1, 1)[2] == 5.25f);
        CHECK(image_pixel(&img, 0, 0)[0] == 6.25f);
        CHECK(image_pixel(&img, 1, 0)[2] == 11.25f);
    }
    image_free(&img);

    // Greyscale, little endian, 3x1, scale written as "-1".
    const char *grey = "Pf\n3 1\n-1\n";
    size_t gl = strlen(grey);
    memcpy(buf, grey, gl);
    const float values[3] = {0.5f, -2.0f, 1e20f};
    for (int i = 0; i < 3; i++) {
        uint32_t bits;
        memcpy(&bits, &values[i], 4);
        for (int b = 0; b < 4; b++) {
            buf[gl + 4 * i + b] = (uint8_t)(bits >> (8 * b));
        }
    }
    path = test_tmp_path("grey.pfm");
    CHECK(test_write_bytes(path, buf, gl + 12));
    CHECK(image_read_pfm(path, &img, &err));
    CHECK(img.width == 3 && img.height == 1);
    for (int x = 0; img.rgb && x < 3; x++) {
        for (int c = 0; c < 3; c++) {
            CHECK(image_pixel(&img, x, 0)[c] == values[x]);
        }
    }
    image_free(&img);
}

struct bad_pfm {
    const char *name;
    const char *header;
    size_t data_bytes; /* zero bytes appended after the header */
    const char *expect; /* in the message */
};

TEST(pfm_malformed)
{
    static const struct bad_pfm cases[] = {
        {"empty", "", 0, "not a PFM"},
        {"ppm", "P6\n2 2\n255\n", 12, "not a PFM"},
        {"pf4", "PF4\n2 2\n-1.0\n", 48, "not a PFM"},
        {"lowercase", "pf\n2 2\n-1.0\n", 48, "not a PFM"},
        {"zero_width", "PF\n0 2\n-1.0\n", 0, "width"},
        {"negative_width", "PF\n-2 2\n-1.0\n", 48, "width"},
        {"negative_height", "PF\n2 -2\n-1.0\n", 48, "height"},
        {"absurd", "PF\n100000 100000\n-1.0\n", 48, "width"},
        {"just_too_high", "PF\n1 32769\n-1.0\n", 48, "height"},
        {"overflowing", "PF\n99999999999999999999 1\n-1.0\n", 48, "width"},
        {"junk_width", "PF\n2x 2\n-1.0\n", 48, "width"},
        {"float_width", "PF\n2.0 2\n-1.0\n", 48, "width"},
        {"missing_height", "PF\n2\n", 0, "height"},
        {"zero_scale", "PF\n2 2\n0\n", 48, "scale"},
        {"nan_scale", "PF\n2 2\nnan\n", 48, "scale"},
        {"inf_scale", "PF\n2 2\n-inf\n", 48, "scale"},
        {"text_scale", "PF\n2 2\nabc\n", 48, "scale"},
        {"no_scale", "PF\n2 2\n", 0, "scale"},
        {"no_separator", "PF\n2 2\n-1.0", 0, "scale"},
        {"header_only", "PF\n2 2\n-1.0\n", 0, "truncated"},
        {"truncated", "PF\n2 2\n-1.0\n", 47, "truncated"},
        {"trailing", "PF\n2 2\n-1.0\n", 49, "after"},
        {"grey_truncated", "Pf\n3 3\n-1\n", 35, "truncated"},
        {"huge_claim", "PF\n32768 32768\n-1.0\n", 48, "truncated"},
    };
    uint8_t buf[256];
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        size_t hl = strlen(cases[i].header);
        memcpy(buf, cases[i].header, hl);
        memset(buf + hl, 0, cases[i].data_bytes);
        char name[64];
        snprintf(name, sizeof name, "bad-%s.pfm", cases[i].name);
        const char *path = test_tmp_path(name);
        CHECK(test_write_bytes(path, buf, hl + cases[i].data_bytes));
        struct image img = {0};
        struct diag err = {0};
        bool ok = image_read_pfm(path, &img, &err);
        CHECK_MSG(!ok, "%s was accepted", cases[i].name);
        CHECK(img.rgb == NULL && img.width == 0);
        CHECK_MSG(
            strstr(err.msg, cases[i].expect) != NULL,
            "%s: message '%s' lacks '%s'",
            cases[i].name,
            err.msg,
            cases[i].expect);
        CHECK(strcmp(err.file, path) == 0 && err.line == 0);
        image_free(&img);
    }
}

TEST(pfm_garbage_and_missing)
{
    uint8_t buf[4096];
    struct rng r = rng_make(99, 0);
    for (int round = 0; round < 20; round++) {
        size_t len = rng_next_u32(&r) % sizeof buf;
        for (size_t i = 0; i < len; i++) {
            buf[i] = (uint8_t)rng_next_u32(&r);
        }
        if (round % 2 == 0 && len > 3) {
            memcpy(buf, "PF\n", 3);  // get past the magic now and then
        }
        const char *path = test_tmp_path("garbage.pfm");
        CHECK(test_write_bytes(path, buf, len));
        struct image img = {0};
        struct diag err = {0};
        CHECK(!image_read_pfm(path, &img, &err));
        CHECK(err.msg[0] != '\0' && img.rgb == NULL);
    }
    struct image img = {0};
    struct diag err = {0};
    const char *missing = test_tmp_path("does-not-exist.pfm");
    CHECK(!image_read_pfm(missing, &img, &err));
    CHECK(strstr(err.msg, "cannot open") != NULL);
    CHECK(strcmp(err.file, missing) == 0);
}

/* ---- PPM -------------------------------------------------------------------- */

TEST(ppm_header_and_bytes)
{
    struct image img = {0};
    struct diag err = {0};
    CHECK(image_alloc(&img, 7, 3, &err));
    fill_image(&img, true, 7);
    img.rgb[0] = NAN;
    img.rgb[1] = INFINITY;
    const char *path = test_tmp_path("x.ppm");
    CHECK(image_write(&img, path, &err));
    size_t len = 0;
    uint8_t *file = (uint8_t *)test_read_file(path, &len);
    const char *header = "P6\n7 3\n255\n";
    size_t hl = strlen(header);
    CHECK(file && len == hl + 7 * 3 * 3);
    CHECK(file && memcmp(file, header, hl) == 0);
    for (size_t i = 0; file && len == hl + 63 && i < 63; i++) {
        CHECK_MSG(file[hl + i] == image_srgb_encode8(img.rgb[i]), "byte %zu", i);
    }
    free(file);
    image_free(&img);
}

/* ---- a small PNG decoder ------------------------------------------------------ */

struct bit_reader {
    const uint8_t *p;
    size_t n, pos;
    int bit;
    bool bad; /* ran past the end */
};

static unsigned
get_bit(struct bit_reader *br)
{
    if (br->pos >= br->n) {
        br->bad = true;
        return 0;
    }
    unsigned b = (br->p[br->pos] >> br->bit) & 1;
    if (++br->bit == 8) {
        br->bit = 0;
        br->pos++;
    }
    return b;
}

/* Data fields: least significant bit first (RFC 1951 3.1.1). */
static unsigned
get_bits(struct bit_reader *br, int count)
{
    unsigned v = 0;
    for (int i = 0; i < count; i++) {
        v |= get_bit(br) << i;
    }
    return v;
}

/* Huffman codes: most significant bit first. */
static unsigned
get_code(struct bit_reader *br, int count)
{
    unsigned v = 0;
    for (int i = 0; i < count; i++) {
        v = v << 1 | get_bit(br);
    }
    return v;
}

/* The fixed literal/length code of RFC 1951 3.2.6. */
static int
fixed_symbol(struct bit_reader *br)
{
    unsigned code = get_code(br, 7);
    if (code <= 0x17) {
        return 256 + (int)code;
    }
    code = code << 1 | get_bit(br);
    if (code >= 0x30 && code <= 0xBF) {
        return (int)code - 0x30;
    }
    if (code >= 0xC0 && code <= 0xC7) {
        return 280 + (int)code - 0xC0;
    }
    code = code << 1 | get_bit(br);
    return 144 + (int)code - 0x190;
}

/* Length and distance bases computed from their pattern (RFC 1951 3.2.5)
 * rather than copied from a table. */
static unsigned
match_length(struct bit_reader *br, int code)
{
    if (code < 8) {
        return 3 + (unsigned)code;
    }
    if (code == 28) {
        return 258;
    }
    int extra = code / 4 - 1;
    return ((4u + (unsigned)code % 4) << extra) + 3 + get_bits(br, extra);
}

static unsigned
match_distance(struct bit_reader *br, int code)
{
    if (code < 4) {
        return 1 + (unsigned)code;
    }
    int extra = code / 2 - 1;
    return ((2u + (unsigned)code % 2) << extra) + 1 + get_bits(br, extra);
}

struct byte_buf {
    uint8_t *data;
    size_t len, cap;
};

static bool
append(struct byte_buf *b, uint8_t v)
{
    if (b->len == b->cap) {
        size_t cap = b->cap ? 2 * b->cap : 4096;
        uint8_t *grown = realloc(b->data, cap);
        if (!grown) {
            return false;
        }
        b->data = grown;
        b->cap = cap;
    }
    b->data[b->len++] = v;
    return true;
}

static bool
inflate_fixed(struct bit_reader *br, struct byte_buf *out)
{
    for (;;) {
        int sym = fixed_symbol(br);
        if (br->bad || sym > 285) {
            return false;
        }
        if (sym < 256) {
            if (!append(out, (uint8_t)sym)) {
                return false;
            }
        } else if (sym == 256) {
            return true;
        } else {
            unsigned len = match_length(br, sym - 257);
            int dcode = (int)get_code(br, 5);
            if (dcode > 29) {
                return false;
            }
            unsigned dist = match_distance(br, dcode);
            if (dist > out->len || dist > 32768) {
                return false;
            }
            for (unsigned i = 0; i < len; i++) {
                if (!append(out, out->data[out->len - dist])) {
                    return false;
                }
            }
        }
    }
}

static bool
inflate_stored(struct bit_reader *br, struct byte_buf *out)
{
    if (br->bit != 0) {
        br->bit = 0;
        br->pos++;
    }
    unsigned len = get_bits(br, 16);
    unsigned nlen = get_bits(br, 16);
    if (br->bad || (len ^ 0xFFFF) != nlen || br->pos + len > br->n) {
        return false;
    }
    for (unsigned i = 0; i < len; i++) {
        if (!append(out, br->p[br->pos++])) {
            return false;
        }
    }
    return true;
}

/* Inflate a raw deflate stream; *used gets the bytes consumed, *types a
 * bit per block type seen (1: stored, 2: fixed). */
static bool
inflate(const uint8_t *in, size_t n, struct byte_buf *out, size_t *used, unsigned *types)
{
    struct bit_reader br = {.p = in, .n = n};
    unsigned final = 0;
    while (!final) {
        final = get_bit(&br);
        unsigned type = get_bits(&br, 2);
        *types |= 1u << type;
        bool ok = type == 0   ? inflate_stored(&br, out)
                  : type == 1 ? inflate_fixed(&br, out)
                              : false;
        if (!ok || br.bad) {
            return false;
        }
    }
    *used = br.pos + (br.bit != 0);
    return true;
}

struct png_info {
    uint32_t width, height;
    int n_idat;
    unsigned block_types;
    struct byte_buf raw; /* the inflated scanlines, unfiltered in the end */
    uint8_t *filtered; /* a copy taken before unfiltering */
};

/* Walk the chunks: signature, CRCs, IHDR first and IEND last; gather IDAT. */
static bool
read_chunks(const uint8_t *file, size_t len, struct png_info *info, struct byte_buf *z)
{
    static const uint8_t signature[8] = {137, 80, 78, 71, 13, 10, 26, 10};
    CHECK(len >= 8 && memcmp(file, signature, 8) == 0);
    size_t at = 8;
    int index = 0;
    bool ended = false;
    while (at + 12 <= len && !ended) {
        uint32_t n = load_be32(file + at);
        const uint8_t *type = file + at + 4;
        if (n > len - at - 12) {
            return false;
        }
        CHECK_MSG(
            load_be32(type + 4 + n) == reference_crc32(type, 4 + (size_t)n),
            "chunk %d CRC",
            index);
        CHECK(index > 0 || (memcmp(type, "IHDR", 4) == 0 && n == 13));
        if (index == 0 && n == 13) {
            info->width = load_be32(type + 4);
            info->height = load_be32(type + 8);
            CHECK(memcmp(type + 12, "\x08\x02\x00\x00\x00", 5) == 0);  // 8-bit RGB
        }
        if (memcmp(type, "IDAT", 4) == 0) {
            info->n_idat++;
            for (uint32_t i = 0; i < n; i++) {
                CHECK(append(z, type[4 + i]));
            }
        }
        ended = memcmp(type, "IEND", 4) == 0;
        at += 12 + (size_t)n;
        index++;
    }
    CHECK(ended && at == len);
    return ended && at == len;
}

/* Undo the row filters in place; true when every filter type is valid. */
static bool
unfilter(uint8_t *raw, uint32_t width, uint32_t height)
{
    size_t n = (size_t)width * 3;
    for (uint32_t y = 0; y < height; y++) {
        uint8_t *row = raw + y * (n + 1);
        const uint8_t *prior = y > 0 ? row - (n + 1) + 1 : NULL;
        int type = row[0];
        if (type > 4) {
            return false;
        }
        for (size_t i = 0; i < n; i++) {
            int a = i >= 3 ? row[1 + i - 3] : 0;
            int b = prior ? prior[i] : 0;
            int c = prior && i >= 3 ? prior[i - 3] : 0;
            int p = a + b - c;
            int pa = abs(p - a);
            int pb = abs(p - b);
            int pc = abs(p - c);
            int paeth = (pa <= pb && pa <= pc) ? a : pb <= pc ? b : c;
            int pred[5] = {0, a, b, (a + b) / 2, paeth};
            row[1 + i] = (uint8_t)(row[1 + i] + pred[type]);
        }
    }
    return true;
}

static bool
decode_png(const uint8_t *file, size_t len, struct png_info *info)
{
    struct byte_buf z = {0};
    bool ok = read_chunks(file, len, info, &z) && z.len >= 6;
    if (ok) {
        // RFC 1950: deflate with a 32 KiB window, no dictionary, FCHECK.
        CHECK(z.data[0] == 0x78);
        CHECK((z.data[0] * 256 + z.data[1]) % 31 == 0);
        CHECK((z.data[1] & 0x20) == 0);
        size_t used = 0;
        ok = inflate(z.data + 2, z.len - 2, &info->raw, &used, &info->block_types);
        CHECK_MSG(ok, "inflate failed");
        CHECK(ok && 2 + used + 4 == z.len);
        CHECK(
            ok
            && load_be32(z.data + z.len - 4) == reference_adler32(info->raw.data, info->raw.len));
    }
    size_t expect = ((size_t)info->width * 3 + 1) * info->height;
    ok = ok && info->raw.len == expect && (info->filtered = malloc(expect)) != NULL;
    if (ok) {
        memcpy(info->filtered, info->raw.data, expect);
        ok = unfilter(info->raw.data, info->width, info->height);
    }
    free(z.data);
    return ok;
}

/* Python's zlib as a second opinion: inflate the IDAT stream of png into
 * out_path.  0 when done, 1 when it failed, -1 when python3 is missing. */
static int
python_inflate(const char *png, const char *out_path)
{
    const char *const probe[] = {"python3", "-c", "import zlib", NULL};
    if (test_run(probe, NULL, 0) != 0) {
        return -1;
    }
    static const char script[] = "import sys, struct, zlib\n"
                                 "d = open(sys.argv[1], \"rb\").read()\n"
                                 "i, z = 8, b\"\"\n"
                                 "while i < len(d):\n"
                                 "    n, t = struct.unpack(\">I4s\", d[i:i + 8])\n"
                                 "    if t == b\"IDAT\": z += d[i + 8:i + 8 + n]\n"
                                 "    i += 12 + n\n"
                                 "open(sys.argv[2], \"wb\").write(zlib.decompress(z))\n";
    const char *const argv[] = {"python3", "-c", script, png, out_path, NULL};
    return test_run(argv, NULL, 0) == 0 ? 0 : 1;
}

/* Write img as PNG, decode it, compare with image_srgb_encode8; returns the file
 * size, and the decoder's findings in info. */
static size_t
check_png(const struct image *img, const char *name, struct png_info *info)
{
    const char *path = test_tmp_path(name);
    struct diag err = {0};
    CHECK_MSG(image_write(img, path, &err), "%s", err.msg);
    size_t len = 0;
    uint8_t *file = (uint8_t *)test_read_file(path, &len);
    CHECK(file != NULL);
    bool ok = file && decode_png(file, len, info);
    CHECK_MSG(ok, "%s did not decode", name);
    CHECK(info->width == (uint32_t)img->width && info->height == (uint32_t)img->height);
    size_t n = (size_t)img->width * 3;
    for (int y = 0; ok && y < img->height; y++) {
        const uint8_t *row = info->raw.data + (size_t)y * (n + 1) + 1;
        for (size_t i = 0; i < n; i++) {
            CHECK_MSG(
                row[i] == image_srgb_encode8(image_pixel(img, 0, y)[i]),
                "%s row %d byte %zu",
                name,
                y,
                i);
        }
    }
    const char *zpath = test_tmp_path("python-inflated.bin");
    int py = ok ? python_inflate(path, zpath) : -1;
    if (py >= 0) {
        CHECK_MSG(py == 0, "python3 zlib could not decompress %s", name);
        size_t zlen = 0;
        char *z = test_read_file(zpath, &zlen);
        CHECK(z && zlen == info->raw.len && memcmp(z, info->filtered, zlen) == 0);
        free(z);
    }
    free(file);
    return len;
}

TEST(png_small_images)
{
    struct image img = {0};
    struct diag err = {0};
    const int sizes[][2] = {{1, 1}, {7, 3}, {3, 7}, {2, 1}, {33, 1}};
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
        CHECK(image_alloc(&img, sizes[k][0], sizes[k][1], &err));
        fill_image(&img, k % 2 == 0, (uint32_t)k + 1);
        img.rgb[0] = NAN;
        img.rgb[img.width * img.height * 3 - 1] = 1e30f;
        struct png_info info = {0};
        check_png(&img, "small.png", &info);
        free(info.raw.data);
        free(info.filtered);
        image_free(&img);
    }
}

TEST(png_compresses_smooth_images)
{
    struct image img = {0};
    struct diag err = {0};
    CHECK(image_alloc(&img, 200, 150, &err));
    fill_image(&img, false, 0);
    struct png_info info = {0};
    size_t len = check_png(&img, "smooth.png", &info);
    size_t raw = (200 * 3 + 1) * 150;
    CHECK_MSG(len < raw / 4, "%zu bytes for %zu raw", len, raw);
    CHECK(info.block_types & 2);  // fixed Huffman blocks
    free(info.raw.data);
    free(info.filtered);
    // A flat image compresses to almost nothing (long matches).
    for (size_t i = 0; i < 200 * 150 * 3; i++) {
        img.rgb[i] = 0.25f;
    }
    struct png_info flat = {0};
    len = check_png(&img, "flat.png", &flat);
    CHECK_MSG(len < 2000, "%zu bytes for a flat image", len);
    free(flat.raw.data);
    free(flat.filtered);
    image_free(&img);
}

TEST(png_noise_uses_stored_blocks)
{
    // Noise does not compress: blocks are stored, and > 1 MiB of zlib data
    // is split over several IDAT chunks.
    struct image img = {0};
    struct diag err = {0};
    CHECK(image_alloc(&img, 640, 560, &err));
    struct rng r = rng_make(4242, 0);
    for (size_t i = 0; i < 640 * 560 * 3; i++) {
        img.rgb[i] = (float)(rng_next_u32(&r) % 65536) / 65535.0f;
    }
    struct png_info info = {0};
    size_t len = check_png(&img, "noise.png", &info);
    CHECK(info.block_types & 1);
    CHECK(info.n_idat >= 2);
    CHECK_MSG(len < (640 * 3 + 1) * 560 + 1000, "%zu bytes", len);
    free(info.raw.data);
    free(info.filtered);
    image_free(&img);
}

/* ---- image_write: failures leave nothing behind --------------------------------- */

TEST(write_into_missing_directory)
{
    struct image img = {0};
    struct diag err = {0};
    CHECK(image_alloc(&img, 4, 4, &err));
    const char *formats[] = {"x.png", "x.ppm", "x.pfm", "x.exr"};
    for (size_t i = 0; i < 4; i++) {
        char rel[64];
        snprintf(rel, sizeof rel, "no-such-dir/%s", formats[i]);
        const char *path = test_tmp_path(rel);
        err.msg[0] = '\0';
        CHECK(!image_write(&img, path, &err));
        CHECK(strcmp(err.file, path) == 0);
        if (image_exr_available() || i < 3) {
            CHECK_MSG(
                strstr(err.msg, "cannot write: No such file or directory") != NULL,
                "%s",
                err.msg);
        }
    }
    CHECK(!test_file_exists(test_tmp_path("no-such-dir")));
    image_free(&img);
}

TEST(write_unknown_extension)
{
    struct image img = {0};
    struct diag err = {0};
    CHECK(image_alloc(&img, 2, 2, &err));
    const char *names[] = {"x.bmp", "noext", "x.png.bak", "x.jpg"};
    for (size_t i = 0; i < 4; i++) {
        const char *path = test_tmp_path(names[i]);
        CHECK(!image_write(&img, path, &err));
        CHECK_MSG(strstr(err.msg, ".png, .ppm, .pfm or .exr") != NULL, "%s", err.msg);
        CHECK(strcmp(err.file, path) == 0);
        CHECK(!test_file_exists(path));
    }
    image_free(&img);
}

static const char *
make_dir(const char *name)
{
    const char *dir = test_tmp_path(name);
    CHECK(mkdir(dir, 0777) == 0 || errno == EEXIST);
    return dir;
}

TEST(write_replaces_existing_file)
{
    const char *dir = make_dir("replace");
    char path[1024];
    snprintf(path, sizeof path, "%s/img.pfm", dir);
    CHECK(test_write_file(path, "old contents"));
    struct image img = {0};
    struct diag err = {0};
    CHECK(image_alloc(&img, 5, 4, &err));
    fill_image(&img, true, 3);
    CHECK(image_write(&img, path, &err));
    struct image back = {0};
    CHECK(image_read_pfm(path, &back, &err));
    CHECK(back.rgb && memcmp(back.rgb, img.rgb, 5 * 4 * 3 * sizeof(float)) == 0);
    // The new file gets the usual permissions, not mkstemp()'s 0600.
    mode_t mask = umask(022);
    umask(mask);
    struct stat st;
    CHECK(stat(path, &st) == 0 && (st.st_mode & 0777) == (0666 & ~mask));
    CHECK(count_temp_files(dir) == 0);
    image_free(&back);
    image_free(&img);
}

TEST(write_onto_directory_fails_cleanly)
{
    // rename() cannot replace a directory: the failure comes after the
    // temporary file was written, which must then be removed.
    const char *dir = make_dir("ontodir");
    const char *names[] = {"a.png", "a.ppm", "a.pfm", "a.exr"};
    struct image img = {0};
    struct diag err = {0};
    CHECK(image_alloc(&img, 3, 3, &err));
    for (size_t i = 0; i < 4; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        CHECK(mkdir(path, 0777) == 0);
        CHECK(!image_write(&img, path, &err));
        CHECK(strstr(err.msg, "cannot write") != NULL || strstr(err.msg, "OpenEXR") != NULL);
        struct stat st;
        CHECK(stat(path, &st) == 0 && S_ISDIR(st.st_mode));
    }
    CHECK(count_temp_files(dir) == 0);
    image_free(&img);
}

/* Writes fail part-way once the file size limit is hit, as on a full disk:
 * the old file must survive and no temporary file may stay. */
static void
check_write_fails_when_full(const struct image *img, const char *dir, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    CHECK(test_write_file(path, "old contents"));
    struct rlimit saved;
    CHECK(getrlimit(RLIMIT_FSIZE, &saved) == 0);
    struct rlimit small = saved;
    small.rlim_cur = 4096;  // bytes: far less than the image needs
    void (*old_handler)(int) = signal(SIGXFSZ, SIG_IGN);
    CHECK(setrlimit(RLIMIT_FSIZE, &small) == 0);
    struct diag err = {0};
    bool ok = image_write(img, path, &err);
    CHECK(setrlimit(RLIMIT_FSIZE, &saved) == 0);
    signal(SIGXFSZ, old_handler);
    CHECK_MSG(!ok, "%s was written despite the limit", name);
    CHECK_MSG(strstr(err.msg, "cannot write: File too large") != NULL, "%s: %s", name, err.msg);
    CHECK(strcmp(err.file, path) == 0);
    char *text = test_read_file(path, NULL);
    CHECK(text && strcmp(text, "old contents") == 0);
    free(text);
    CHECK(count_temp_files(dir) == 0);
}

TEST(write_failure_keeps_old_file)
{
    const char *dir = make_dir("full");
    struct image img = {0};
    struct diag err = {0};
    CHECK(image_alloc(&img, 64, 64, &err));
    fill_image(&img, true, 11);
    check_write_fails_when_full(&img, dir, "big.pfm");
    check_write_fails_when_full(&img, dir, "big.ppm");
    check_write_fails_when_full(&img, dir, "big.png");
    if (image_exr_available()) {
        check_write_fails_when_full(&img, dir, "big.exr");
    }
    image_free(&img);
}

/* ---- EXR -------------------------------------------------------------------- */

#ifdef HAVE_OPENEXR
static void
quiet(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    (void)code;
    (void)msg;
}

/* Read path back: the header with OpenEXR's C API, the pixels with
 * imgread (dw.max.x + 1 by dw.max.y + 1, checked by the caller). */
static bool
read_exr(const char *path, struct image *out)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = quiet;
    exr_context_t ctxt = NULL;
    if (exr_start_read(&ctxt, path, &init) != EXR_ERR_SUCCESS) {
        CHECK_MSG(false, "OpenEXR cannot open %s", path);
        return false;
    }
    exr_attr_box2i_t dw;
    const exr_attr_chlist_t *channels = NULL;
    bool ok = exr_get_data_window(ctxt, 0, &dw) == EXR_ERR_SUCCESS
              && exr_get_channels(ctxt, 0, &channels) == EXR_ERR_SUCCESS;
    CHECK(ok && dw.min.x == 0 && dw.min.y == 0);
    CHECK(ok && channels->num_channels == 3);
    static const char *const sorted[] = {"B", "G", "R"};
    for (int c = 0; ok && c < channels->num_channels && c < 3; c++) {
        CHECK(channels->entries[c].pixel_type == EXR_PIXEL_FLOAT);
        CHECK(strcmp(channels->entries[c].name.str, sorted[c]) == 0);
    }
    exr_finish(&ctxt);
    /* The pixels through the EXR reader of compare and merge (tests/lib). */
    struct diag err = {0};
    ok = ok && imgread(path, out, &err);
    CHECK_MSG(ok, "%s", err.msg);
    return ok;
}
#endif

TEST(exr_write)
{
    struct image img = {0};
    struct diag err = {0};
    CHECK(image_alloc(&img, 37, 41, &err));  // odd sizes, several 16-line chunks
    fill_image(&img, true, 5);
    img.rgb[0] = -2.5f;
    img.rgb[1] = 1e20f;
    img.rgb[2] = 1e-40f;
    const char *path = test_tmp_path("x.exr");
    bool ok = image_write(&img, path, &err);
    if (!image_exr_available()) {
        CHECK(!ok);
        CHECK(
            strcmp(
                err.msg,
                "built without OpenEXR; install libopenexr-dev and rebuild to write .exr")
            == 0);
        CHECK(!test_file_exists(path));
        image_free(&img);
        return;
    }
    CHECK_MSG(ok, "%s", err.msg);
    size_t len = 0;
    uint8_t *file = (uint8_t *)test_read_file(path, &len);
    // Magic number 20000630 little endian, then version 2 (single part).
    CHECK(file && len > 8 && memcmp(file, "\x76\x2f\x31\x01\x02", 5) == 0);
    free(file);
#ifdef HAVE_OPENEXR
    struct image back = {0};
    if (read_exr(path, &back)) {
        CHECK(back.width == img.width && back.height == img.height);
        for (size_t i = 0; i < (size_t)img.width * (size_t)img.height * 3; i++) {
            CHECK_MSG(
                same_bits(back.rgb[i], img.rgb[i]),
                "value %zu: %g != %g",
                i,
                (double)back.rgb[i],
                (double)img.rgb[i]);
        }
    }
    image_free(&back);
    image_free(&img);
#else
    image_free(&img);
    SKIP("header checked only: compile the test with OpenEXR's flags to read the pixels back");
#endif
}

TEST(no_temp_files_left)
{
    CHECK(count_temp_files(test_tmpdir()) == 0);
}

TEST_MAIN(
    TEST_ENTRY(srgb_known_values),
    TEST_ENTRY(srgb_clamps),
    TEST_ENTRY(srgb_continuity_and_round_trip),
    TEST_ENTRY(crc32_and_adler32),
    TEST_ENTRY(alloc_limits_and_format_names),
    TEST_ENTRY(pfm_round_trip_exact),
    TEST_ENTRY(pfm_rows_bottom_to_top),
    TEST_ENTRY(pfm_read_big_endian_and_grey),
    TEST_ENTRY(pfm_malformed),
    TEST_ENTRY(pfm_garbage_and_missing),
    TEST_ENTRY(ppm_header_and_bytes),
    TEST_ENTRY(png_small_images),
    TEST_ENTRY(png_compresses_smooth_images),
    TEST_ENTRY(png_noise_uses_stored_blocks),
    TEST_ENTRY(write_into_missing_directory),
    TEST_ENTRY(write_unknown_extension),
    TEST_ENTRY(write_replaces_existing_file),
    TEST_ENTRY(write_onto_directory_fails_cleanly),
    TEST_ENTRY(write_failure_keeps_old_file),
    TEST_ENTRY(exr_write),
    TEST_ENTRY(no_temp_files_left))
