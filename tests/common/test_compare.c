/*
 * test_compare.c - the compare tool (tests/tools/compare.c) and what it is
 * made of (tests/lib: imgread, estimate, errmap, compare_report) on
 * synthetic images whose noise and bias are known exactly: a smooth
 * reference, "renders" that are the reference times (1 + SIGMA * Gaussian
 * noise) per pixel and channel with a fixed seed each, and planted biases.
 * The renders of real scenes are tested in tests/stage/07_compare.c, the
 * report page in a browser in test_report_browser.c.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "errmap.h"
#include "estimate.h"
#include "image.h"
#include "imgread.h"
#include "testlib.h"

#define W 72 /* not a multiple of the block size: edge blocks are narrower */
#define H 40
#define SIGMA 0.05 /* per-pixel relative noise of a synthetic render */
#define CAP 16384

/* ---- synthetic images -------------------------------------------------------- */

/* SplitMix64 (Steele, Lea, Flood 2014), enough for test noise. */
static uint64_t
next_u64(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

/* A standard normal variate (Box-Muller). */
static double
gaussian(uint64_t *s)
{
    double u1 = ((double)(next_u64(s) >> 11) + 1) / 9007199254740993.0;
    double u2 = (double)(next_u64(s) >> 11) / 9007199254740992.0;
    return sqrt(-2 * log(u1)) * cos(6.283185307179586 * u2);
}

/* A smooth coloured gradient, never black. */
static void
make_reference(struct image *img)
{
    struct diag err;
    CHECK(image_alloc(img, W, H, &err));
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            float *p = image_pixel(img, x, y);
            p[0] = (float)(0.2 + 0.6 * x / W);
            p[1] = (float)(0.3 + 0.4 * y / H);
            p[2] = (float)(0.5 - 0.3 * x / W + 0.2 * y / H);
        }
    }
}

/* ref with noise of relative size SIGMA (seed), and, when scale != 1, the
 * block at (bx, by) of size 16 scaled by `scale`. */
static void
make_render(const struct image *ref, uint64_t seed, int bx, int by, double scale, struct image *out)
{
    struct diag err;
    CHECK(image_alloc(out, ref->width, ref->height, &err));
    uint64_t s = seed * 7919 + 1;
    for (int y = 0; y < ref->height; y++) {
        for (int x = 0; x < ref->width; x++) {
            bool planted = x >= bx * 16 && x < bx * 16 + 16 && y >= by * 16 && y < by * 16 + 16;
            for (int c = 0; c < 3; c++) {
                double v = image_pixel(ref, x, y)[c] * (1 + SIGMA * gaussian(&s));
                image_pixel(out, x, y)[c] = (float)(planted ? v * scale : v);
            }
        }
    }
}

static bool
write_image(const struct image *img, const char *name)
{
    struct diag err = {0};
    bool ok = image_write(img, test_tmp_path(name), &err);
    if (!ok) {
        diag_print(stdout, &err, "error");
    }
    return ok;
}

/* Write the reference ref.pfm and renders a.pfm, b.pfm (seeds sa, sb), with
 * `scale` planted in block (bx, by) of both renders. */
static bool
write_set(uint64_t sa, uint64_t sb, int bx, int by, double scale)
{
    struct image ref = {0}, a = {0}, b = {0};
    make_reference(&ref);
    make_render(&ref, sa, bx, by, scale, &a);
    make_render(&ref, sb, bx, by, scale, &b);
    bool ok = write_image(&ref, "ref.pfm") && write_image(&a, "a.pfm") && write_image(&b, "b.pfm");
    image_free(&ref);
    image_free(&a);
    image_free(&b);
    return ok;
}

/* Run compare with args (NULL-terminated, program left out). */
static int
compare(const char *const *args, char *out)
{
    return test_run_tool("compare", args, out, CAP);
}

#define TMP(name) test_tmp_path(name)

/* ---- image readers ----------------------------------------------------------- */

TEST(png_reader_reads_back_what_the_writer_wrote)
{
    struct image img = {0}, back = {0};
    struct diag err = {0};
    CHECK(image_alloc(&img, 37, 11, &err));
    uint64_t s = 5;
    for (size_t i = 0; i < 37 * 11 * 3; i++) {
        img.rgb[i] = (float)((next_u64(&s) >> 11) / 9007199254740992.0 * 1.2);
    }
    CHECK(write_image(&img, "rt.png"));
    CHECK(imgread(TMP("rt.png"), &back, &err));
    CHECK(back.width == 37 && back.height == 11);
    int wrong = 0;
    for (size_t i = 0; back.rgb && i < 37 * 11 * 3; i++) {
        wrong += image_srgb_encode8(back.rgb[i]) != image_srgb_encode8(img.rgb[i]);
    }
    CHECK_MSG(wrong == 0, "%d samples differ", wrong);
    image_free(&img);
    image_free(&back);
}

/* PNGs written by another encoder (zlib, dynamic and fixed Huffman codes):
 * 16-bit RGB, a palette, grey + alpha with the Sub filter. */
TEST(png_reader_reads_other_encoders_files)
{
    struct image img = {0};
    struct diag err = {0};
    CHECK(imgread(test_root_path("tests/common/data/rgb16.png"), &img, &err));
    for (int y = 0; img.rgb && y < 16; y++) {
        for (int x = 0; x < 16; x++) {
            const float *p = image_pixel(&img, x, y);
            CHECK_NEAR(p[0], image_linear_from_srgb((4096.0f * x + 17) / 65535), 1e-6);
            CHECK_NEAR(p[1], image_linear_from_srgb((4096.0f * y + 33) / 65535), 1e-6);
            CHECK_NEAR(p[2], image_linear_from_srgb((65535 - 4096.0f * x) / 65535), 1e-6);
        }
    }
    image_free(&img);
    static const float palette[4][3] =
        {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {128 / 255.0f, 128 / 255.0f, 128 / 255.0f}};
    CHECK(imgread(test_root_path("tests/common/data/palette.png"), &img, &err));
    for (int y = 0; img.rgb && y < 16; y++) {
        for (int x = 0; x < 16; x++) {
            for (int c = 0; c < 3; c++) {
                CHECK_NEAR(
                    image_pixel(&img, x, y)[c],
                    image_linear_from_srgb(palette[(x + y) % 4][c]),
                    1e-6);
            }
        }
    }
    image_free(&img);
    CHECK(imgread(test_root_path("tests/common/data/grey_alpha_sub.png"), &img, &err));
    for (int y = 0; img.rgb && y < 16; y++) {
        for (int x = 0; x < 16; x++) {
            float grey = image_linear_from_srgb((16.0f * x + y) / 255);
            const float *p = image_pixel(&img, x, y);
            CHECK(p[0] == grey && p[1] == grey && p[2] == grey);
        }
    }
    image_free(&img);
}

TEST(exr_reader_reads_back_what_the_writer_wrote)
{
    if (!image_exr_available()) {
        SKIP("built without OpenEXR");
    }
    struct image ref = {0}, back = {0};
    struct diag err = {0};
    make_reference(&ref);
    image_pixel(&ref, 3, 2)[1] = 1e6f; /* linear and unclamped */
    CHECK(write_image(&ref, "rt.exr"));
    CHECK(imgread(TMP("rt.exr"), &back, &err));
    CHECK(back.width == W && back.height == H);
    CHECK(back.rgb && memcmp(back.rgb, ref.rgb, sizeof(float) * 3 * W * H) == 0);
    image_free(&ref);
    image_free(&back);
}

/* Recompute the checksum of the first IDAT chunk, so that a corrupted byte
 * inside it reaches the decompressor. */
static void
fix_idat_crc(unsigned char *png, size_t n)
{
    for (size_t i = 8; i + 12 <= n;) {
        size_t len =
            (size_t)png[i] << 24 | (size_t)png[i + 1] << 16 | (size_t)png[i + 2] << 8 | png[i + 3];
        if (len > n - i - 12) {
            return;
        }
        if (memcmp(png + i + 4, "IDAT", 4) == 0) {
            uint32_t crc = image_crc32(0, png + i + 4, len + 4);
            for (int b = 0; b < 4; b++) {
                png[i + 8 + len + (size_t)b] = (unsigned char)(crc >> (24 - 8 * b));
            }
            return;
        }
        i += len + 12;
    }
}

TEST(bad_image_files_are_refused_with_a_message)
{
    struct image img = {0};
    size_t n = 0;
    char *png = test_read_file(test_root_path("tests/common/data/rgb16.png"), &n);
    CHECK(png != NULL);

    struct {
        const char *name;
        size_t len; /* bytes of the good file kept */
        long flip; /* byte to corrupt, -1: none */
    } cases[] = {
        {"empty.png", 0, -1},
        {"short.png", 8, -1},
        {"truncated.png", n / 2, -1},
        {"crc.png", n, 20}, /* inside IHDR: its checksum fails */
        {"data.png", n, 60}, /* inside IDAT's zlib stream (its CRC fixed) */
    };

    for (size_t i = 0; png && i < sizeof cases / sizeof cases[0]; i++) {
        char *copy = malloc(n);
        memcpy(copy, png, n);
        if (cases[i].flip >= 0) {
            copy[cases[i].flip] ^= 0x55;
            fix_idat_crc((unsigned char *)copy, n);
        }
        FILE *f = fopen(TMP(cases[i].name), "wb");
        CHECK(f && fwrite(copy, 1, cases[i].len, f) == cases[i].len);
        if (f) {
            fclose(f);
        }
        struct diag err = {0};
        CHECK_MSG(!imgread(TMP(cases[i].name), &img, &err), "%s was accepted", cases[i].name);
        CHECK_MSG(
            strstr(err.file, cases[i].name) != NULL && err.msg[0],
            "%s: '%s'",
            cases[i].name,
            err.msg);
        printf("%s: %s\n", cases[i].name, err.msg);
        free(copy);
    }
    free(png);
    struct diag err = {0};
    CHECK(test_write_file(TMP("image.txt"), "P3\n"));
    CHECK(!imgread(TMP("image.txt"), &img, &err) && strstr(err.msg, "unknown image format"));
    CHECK(!imgread(TMP("missing.pfm"), &img, &err));
}

/* ---- estimates --------------------------------------------------------------- */

TEST(renders_are_combined_weighted_by_their_samples)
{
    struct image in[2] = {{0}, {0}}, mean = {0}, var = {0};
    struct diag err;
    CHECK(image_alloc(&in[0], 1, 1, &err) && image_alloc(&in[1], 1, 1, &err));
    for (int c = 0; c < 3; c++) {
        in[0].rgb[c] = 1.0f + c;
        in[1].rgb[c] = 3.0f + c;
    }
    const double spp[2] = {1, 3};
    CHECK(estimate_combine(in, spp, 2, &mean, &var, &err));
    for (int c = 0; mean.rgb && c < 3; c++) {
        CHECK_NEAR(mean.rgb[c], 2.5 + c, 1e-6);
        /* (1 (1 - 2.5)^2 + 3 (3 - 2.5)^2) / ((2 - 1) 4) */
        CHECK_NEAR(var.rgb[c], 0.75, 1e-6);
    }
    image_free(&mean);
    image_free(&var);
    /* No weights: equal ones, the mean 2 + c and (1 + 1) / ((2 - 1) 2). */
    CHECK(estimate_combine(in, NULL, 2, &mean, &var, &err));
    for (int c = 0; mean.rgb && c < 3; c++) {
        CHECK_NEAR(mean.rgb[c], 2 + c, 1e-6);
        CHECK_NEAR(var.rgb[c], 1, 1e-6);
    }
    image_free(&mean);
    image_free(&var);
    const double bad[2] = {1, 0};
    CHECK(!estimate_combine(in, bad, 2, &mean, NULL, &err));
    image_free(&in[0]);
    image_free(&in[1]);
}

/* ---- the verdict --------------------------------------------------------------- */

TEST(renders_with_only_noise_are_consistent_for_many_seeds)
{
    char out[CAP];
    for (uint64_t seed = 1; seed <= 10; seed++) {
        CHECK(write_set(2 * seed, 2 * seed + 1, 0, 0, 1));
        const char *const args[] = {TMP("a.pfm"), TMP("b.pfm"), TMP("ref.pfm"), NULL};
        int status = compare(args, out);
        CHECK_MSG(
            status == 0,
            "seeds %d, %d: exit %d\n%s",
            (int)(2 * seed),
            (int)(2 * seed + 1),
            status,
            out);
    }
    CHECK(strstr(out, "consistent with the reference (noise only)") != NULL);
    CHECK(strstr(out, "15 blocks of 16x16") != NULL); /* 5 x 3, the right and bottom ones cut */
}

/* A 2% bias in one block, brighter and darker, in every block position of
 * the top row and at the image's cut edge: found, named, and alone. */
TEST(a_planted_two_percent_bias_is_found_and_named)
{
    char out[CAP], expected[128];
    for (int bx = 0; bx < 5; bx++) {
        for (int sign = -1; sign <= 1; sign += 2) {
            int by = bx == 4 ? 2 : 0; /* block (4, 2) is 8x8, cut by both edges */
            CHECK(write_set(100 + bx, 200 + bx, bx, by, 1 + sign * 0.02 * (bx == 4 ? 2 : 1)));
            const char *const args[] = {TMP("a.pfm"), TMP("b.pfm"), TMP("ref.pfm"), NULL};
            int status = compare(args, out);
            int x1 = bx * 16 + 15 < W ? bx * 16 + 15 : W - 1,
                y1 = by * 16 + 15 < H ? by * 16 + 15 : H - 1;
            snprintf(
                expected,
                sizeof expected,
                "the block at x %d-%d, y %d-%d is",
                bx * 16,
                x1,
                by * 16,
                y1);
            CHECK_MSG(
                status == 1 && strstr(out, expected) && strstr(out, "biased: 1 of 15 blocks")
                    && strstr(out, sign > 0 ? "brighter than" : "darker than"),
                "block %d, %d, sign %d: exit %d\n%s",
                bx,
                by,
                sign,
                status,
                out);
        }
    }
    printf("%s", out);
}

TEST(one_render_and_its_variance_image)
{
    struct image ref = {0}, a = {0}, var = {0};
    char out[CAP];
    make_reference(&ref);
    struct diag err;
    CHECK(image_alloc(&var, W, H, &err));
    for (size_t i = 0; var.rgb && i < (size_t)W * H * 3; i++) {
        var.rgb[i] = (float)(SIGMA * SIGMA * ref.rgb[i] * ref.rgb[i]); /* the exact variance */
    }
    CHECK(write_image(&var, "var.pfm") && write_image(&ref, "ref.pfm"));
    const char *const args[] = {TMP("a.pfm"), "--variance", TMP("var.pfm"), TMP("ref.pfm"), NULL};
    make_render(&ref, 77, 0, 0, 1, &a);
    CHECK(write_image(&a, "a.pfm"));
    CHECK_MSG(compare(args, out) == 0, "%s", out);
    CHECK(strstr(out, "from the variance image") != NULL);
    image_free(&a);
    make_render(&ref, 77, 2, 1, 1.03, &a);
    CHECK(write_image(&a, "a.pfm"));
    CHECK_MSG(compare(args, out) == 1 && strstr(out, "x 32-47, y 16-31"), "%s", out);
    var.rgb[100] = -1; /* not a variance: bad input */
    CHECK(write_image(&var, "var.pfm"));
    CHECK_MSG(compare(args, out) == 2 && strstr(out, "finite and >= 0"), "%s", out);
    image_free(&a);
    image_free(&ref);
    image_free(&var);
}

/* The text of compare's line `label` (e.g. "power      ") with its
 * continuation lines joined, into buf; "" when there is no such line. */
static void
joined_line(const char *out, const char *label, char *buf, size_t cap)
{
    size_t n = 0, indent = strlen(label);
    const char *p = strstr(out, label);
    buf[0] = 0;
    if (!p) {
        return;
    }
    for (p += indent; *p && n + 1 < cap; p++) {
        if (*p == '\n') {
            if (strncmp(p + 1, "           ", indent) != 0) {
                break;
            }
            p += indent;
            buf[n++] = ' ';
            continue;
        }
        buf[n++] = *p;
    }
    buf[n] = 0;
}

/* What compare says it can find, on one render with its exact variance
 * (relative 4 SIGMA per pixel, then 2 SIGMA): the windows are 32x32, 32x24 and (at the
 * corner) 24x24, cut by the image's edges, so the median window's
 * detectable bias is (z_level + z_0.9) SIGMA / sqrt(768) and 9 windows in
 * 10 reach (z_level + z_0.9) SIGMA / 24, with SIGMA the pixels' relative
 * noise and z_level the level of one of the 3 x (15 blocks + 8 windows)
 * tests; four times the samples halve both. */
TEST(power_line_says_what_a_comparison_can_find)
{
    struct image ref = {0}, a = {0}, var = {0};
    char out[CAP], line[1024];
    make_reference(&ref);
    struct diag err;
    CHECK(image_alloc(&var, W, H, &err));
    const char *const args[] = {TMP("a.pfm"), "--variance", TMP("var.pfm"), TMP("ref.pfm"), NULL};
    make_render(&ref, 78, 0, 0, 1, &a);
    CHECK(write_image(&a, "a.pfm") && write_image(&ref, "ref.pfm"));
    double z = 3.798377; /* the two-sided normal critical value at 1 - 0.99^(1/69) */
    double half = 0, most = 0, times = 0;
    for (int quarter = 0; quarter < 2; quarter++) {
        double scale = quarter ? 4 : 16; /* SIGMA 4 and 2 times as large: 2% needs more */
        for (size_t i = 0; var.rgb && i < (size_t)W * H * 3; i++) {
            var.rgb[i] = (float)(scale * SIGMA * SIGMA * ref.rgb[i] * ref.rgb[i]);
        }
        CHECK(write_image(&var, "var.pfm"));
        CHECK_MSG(compare(args, out) == 0, "%s", out);
        joined_line(out, "power      ", line, sizeof line);
        double h, m, t;
        int got = sscanf(
            line,
            "a bias that brightens or darkens a 32x32 window by %lf%% is found 9 times in 10 in "
            "half the windows, and one of %lf%% in 9 windows of 10; to find 2.0%% so in 9 windows "
            "of 10: about %lf times",
            &h,
            &m,
            &t);
        CHECK_MSG(got == 3, "%s", out);
        if (!quarter) {
            CHECK_REL(h / 100, (z + 1.28155) * 4 * SIGMA / sqrt(768), 0.05);
            CHECK_REL(m / 100, (z + 1.28155) * 4 * SIGMA / 24, 0.05);
            CHECK_REL(t, pow(m / 100 / 0.02, 2), 0.05);
            half = h, most = m, times = t;
        } else {
            /* The line prints two significant digits: 1.85 may read 1.8. */
            CHECK_REL(h, half / 2, 0.05);
            CHECK_REL(m, most / 2, 0.05);
            CHECK_REL(t, times / 4, 0.06);
        }
    }
    /* -q: the verdict, then the same line unwrapped. */
    const char *const quiet[] =
        {"-q", TMP("a.pfm"), "--variance", TMP("var.pfm"), TMP("ref.pfm"), NULL};
    CHECK(compare(quiet, out) == 0);
    const char *second = strchr(out, '\n');
    CHECK_MSG(
        second && strncmp(second + 1, "power: ", 7) == 0 && strstr(second + 1, line),
        "%s",
        out);
    /* With no noise estimate there is no test, and no power line. */
    const char *const alone[] = {TMP("a.pfm"), TMP("ref.pfm"), NULL};
    CHECK(compare(alone, out) == 0 && !strstr(out, "power "));
    image_free(&a);
    image_free(&ref);
    image_free(&var);
}

TEST(one_render_alone_is_compared_but_not_tested)
{
    char out[CAP];
    CHECK(write_set(1, 2, 0, 0, 1));
    const char *const alone[] = {TMP("a.pfm"), TMP("ref.pfm"), NULL};
    CHECK(compare(alone, out) == 0);
    CHECK(strstr(out, "not tested for bias") && strstr(out, "relMSE") && strstr(out, "worst"));
    const char *const limited[] = {TMP("a.pfm"), TMP("ref.pfm"), "--max-relmse", "1e-6", NULL};
    CHECK_MSG(compare(limited, out) == 1 && strstr(out, "above the limit"), "%s", out);
    const char *const quiet[] = {"-q", TMP("a.pfm"), TMP("ref.pfm"), NULL};
    CHECK(compare(quiet, out) == 0 && strncmp(out, "not tested", 10) == 0);
}

/* A render whose only error is at an edge (a stage without anti-aliasing)
 * passes a relMSE limit over the reference's smooth pixels only. */
TEST(mask_smooth_leaves_edges_out)
{
    struct image ref = {0}, a = {0};
    struct diag err;
    char out[CAP];
    make_reference(&ref);
    CHECK(image_alloc(&a, W, H, &err));
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            for (int c = 0; c < 3; c++) {
                /* A sharp edge at x = 30 in the reference, at x = 31 in the render. */
                image_pixel(&ref, x, y)[c] *= x < 30 ? 1.0f : 0.25f;
                image_pixel(&a, x, y)[c] = image_pixel(&ref, x, y)[c] * (x == 30 ? 4.0f : 1.0f);
            }
        }
    }
    CHECK(write_image(&ref, "ref.pfm") && write_image(&a, "a.pfm"));
    const char *const all[] = {TMP("a.pfm"), TMP("ref.pfm"), "--max-relmse", "1e-6", NULL};
    CHECK(compare(all, out) == 1);
    const char *const smooth[] = {
        TMP("a.pfm"),
        TMP("ref.pfm"),
        "--max-relmse",
        "1e-6",
        "--mask",
        "smooth",
        "--map",
        TMP("masked.png"),
        NULL};
    CHECK_MSG(compare(smooth, out) == 0 && strstr(out, "smooth ones"), "%s", out);
    struct image map = {0};
    CHECK(imgread(TMP("masked.png"), &map, &err));
    int scale = (ERRMAP_MIN_WIDTH + W - 1) / W;
    if (map.rgb) { /* the edge and the border are grey: not compared */
        const float *edge = image_pixel(&map, 30 * scale + scale / 2, 20 * scale);
        const float *border = image_pixel(&map, scale / 2, scale / 2);
        CHECK(image_srgb_encode8(edge[0]) == 120 && image_srgb_encode8(edge[1]) == 120);
        CHECK(image_srgb_encode8(border[2]) == 120);
    }
    image_free(&map);
    const char *const pair[] =
        {TMP("a.pfm"), TMP("a.pfm"), TMP("ref.pfm"), "--mask", "smooth", NULL};
    CHECK(compare(pair, out) == 2);
    image_free(&ref);
    image_free(&a);
}

TEST(identical_renders_are_called_out)
{
    char out[CAP];
    CHECK(write_set(1, 1, 0, 0, 1));
    const char *const args[] = {TMP("a.pfm"), TMP("b.pfm"), TMP("ref.pfm"), NULL};
    CHECK(compare(args, out) == 1); /* no noise: the render's own noise is a difference */
    CHECK(strstr(out, "the renders are identical") != NULL);
}

/* A NaN or infinite pixel in any input, the reference too, is bad input:
 * exit 2, naming the file and the pixel (to replay it). */
TEST(nan_or_infinite_pixels_are_refused_naming_the_file_and_the_pixel)
{
    struct image ref = {0}, a = {0}, b = {0};
    char out[CAP];
    make_reference(&ref);
    make_render(&ref, 3, 0, 0, 1, &a);
    make_render(&ref, 4, 0, 0, 1, &b);
    image_pixel(&a, 40, 20)[1] = NAN;
    image_pixel(&b, 7, 30)[2] = INFINITY;
    CHECK(write_image(&ref, "ref.pfm") && write_image(&a, "nan.pfm") && write_image(&b, "inf.pfm"));
    image_pixel(&ref, 70, 0)[0] = NAN;
    CHECK(write_image(&ref, "nanref.pfm"));
    image_pixel(&ref, 70, 0)[0] = 0.5f;
    image_free(&a);
    make_render(&ref, 5, 0, 0, 1, &a);
    CHECK(write_image(&a, "a.pfm"));
    const char *const alone[] = {TMP("nan.pfm"), TMP("ref.pfm"), NULL};
    const char *const pair[] = {TMP("a.pfm"), TMP("inf.pfm"), TMP("ref.pfm"), NULL};
    const char *const reference[] = {TMP("a.pfm"), TMP("nanref.pfm"), NULL};
    const char *const *cases[] = {alone, pair, reference};
    const char *const files[] = {"nan.pfm: error", "inf.pfm: error", "nanref.pfm: error"};
    const char *const pixels[] = {
        "pixel 40,20 is NaN in channel G",
        "pixel 7,30 is infinite in channel B",
        "pixel 70,0 is NaN in channel R"};
    for (int i = 0; i < 3; i++) {
        int status = compare(cases[i], out);
        CHECK_MSG(
            status == 2 && strstr(out, files[i]) && strstr(out, pixels[i]) && !strstr(out, "nan%"),
            "case %d: exit %d: %s",
            i,
            status,
            out);
    }
    image_free(&ref);
    image_free(&a);
    image_free(&b);
}

/* Percentages and standard errors as plain numbers (no 1e+02%), channels
 * by letter (the map's blue means darker, not a channel), and the hint
 * about rare bright paths only beside a darker block. */
TEST(verdict_lines_are_plain_words_and_numbers)
{
    char out[CAP];
    const char *const args[] = {TMP("a.pfm"), TMP("b.pfm"), TMP("ref.pfm"), NULL};
    CHECK(write_set(81, 82, 1, 1, 15)); /* 1400% brighter */
    int status = compare(args, out);
    const char *line = strstr(out, "y 16-31 is ");
    int percent = 0, end = 0;
    CHECK_MSG(
        line
            && sscanf(
                   line,
                   "y 16-31 is %d%% brighter than the reference (channel %n",
                   &percent,
                   &end)
                   == 1
            && end > 0 && percent > 1300 && percent < 1500,
        "%s",
        out);
    CHECK_MSG(
        status == 1 && strstr(out, " standard errors") && !strstr(out, "e+")
            && !strstr(out, "(blue)") && !strstr(out, "(red)") && !strstr(out, "(green)")
            && !strstr(out, "hint"),
        "%s",
        out);
    CHECK(write_set(83, 84, 1, 1, 0.5)); /* 50% darker */
    status = compare(args, out);
    CHECK_MSG(
        status == 1 && strstr(out, "is 50% darker") && strstr(out, "hint       to tell a bias"),
        "%s",
        out);
}

TEST(bad_input_exits_2)
{
    char out[CAP];
    CHECK(write_set(1, 2, 0, 0, 1));
    struct image small = {0};
    struct diag err;
    CHECK(image_alloc(&small, 8, 8, &err) && write_image(&small, "small.pfm"));
    image_free(&small);
    const char *const missing[] = {TMP("a.pfm"), TMP("nothing.pfm"), NULL};
    const char *const size[] = {TMP("a.pfm"), TMP("small.pfm"), NULL};
    const char *const one[] = {TMP("a.pfm"), NULL};
    const char *const option[] = {"--frobnicate", TMP("a.pfm"), TMP("ref.pfm"), NULL};
    const char *const number[] = {"--block", "0", TMP("a.pfm"), TMP("ref.pfm"), NULL};
    const char *const variance[] =
        {TMP("a.pfm"), TMP("b.pfm"), "--variance", TMP("a.pfm"), TMP("ref.pfm"), NULL};
    const char *const *cases[] = {missing, size, one, option, number, variance};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        int status = compare(cases[i], out);
        CHECK_MSG(status == 2 && strstr(out, "error"), "case %zu: exit %d: %s", i, status, out);
    }
    const char *const help[] = {"--help", NULL};
    CHECK(compare(help, out) == 0 && strstr(out, "Exit status"));
}

/* ---- the error map and the page ------------------------------------------------- */

/* The map's pixel (x, y) of image pixel (x, y), as 8-bit sRGB. */
static void
map_rgb(const struct image *map, int scale, int x, int y, int rgb[3])
{
    const float *p = image_pixel(map, x * scale + scale / 2, y * scale + scale / 2);
    for (int c = 0; c < 3; c++) {
        rgb[c] = image_srgb_encode8(p[c]);
    }
}

TEST(error_map_shows_sign_outlines_failing_blocks_and_has_a_legend)
{
    char out[CAP];
    CHECK(write_set(11, 12, 1, 1, 1.3)); /* block x 16-31, y 16-31, 30% brighter */
    const char *const args[] = {
        TMP("a.pfm"),
        TMP("b.pfm"),
        TMP("ref.pfm"),
        "--map",
        TMP("map.png"),
        "--range",
        "0.5",
        NULL};
    CHECK(compare(args, out) == 1);
    struct image map = {0};
    struct diag err = {0};
    CHECK(imgread(TMP("map.png"), &map, &err));
    if (!map.rgb) {
        return;
    }
    int scale = (ERRMAP_MIN_WIDTH + W - 1) / W;
    CHECK(map.width >= W * scale && map.height > H * scale + 20); /* a legend below */
    int rgb[3], red = 0, white = 0;
    for (int y = 18; y < 30; y++) { /* inside the block, off its outline */
        for (int x = 18; x < 30; x++) {
            map_rgb(&map, scale, x, y, rgb);
            red += rgb[0] > rgb[2] + 60;
        }
    }
    for (int y = 2; y < 14; y++) { /* the unbiased top-left block: pale */
        for (int x = 2; x < 14; x++) {
            map_rgb(&map, scale, x, y, rgb);
            white += rgb[0] > 150 && rgb[1] > 150 && rgb[2] > 150;
        }
    }
    CHECK_MSG(red > 130, "%d of 144 red", red);
    CHECK_MSG(white > 130, "%d of 144 pale", white);
    /* The outline: black along the block's top edge in the map. */
    int black = 0;
    for (int x = 16 * scale; x < 32 * scale; x++) {
        const float *p = image_pixel(&map, x, 16 * scale);
        black += p[0] == 0 && p[1] == 0 && p[2] == 0;
    }
    CHECK_MSG(black == 16 * scale, "%d of %d outline pixels black", black, 16 * scale);
    image_free(&map);
}

TEST(report_page_is_one_self_contained_file)
{
    char out[CAP];
    CHECK(write_set(11, 12, 1, 1, 1.3));
    const char *const args[] = {
        TMP("a.pfm"),
        TMP("b.pfm"),
        TMP("ref.pfm"),
        "--html",
        TMP("page.html"),
        "--title",
        "lab <07> & \"friends\"",
        NULL};
    CHECK(compare(args, out) == 1);
    size_t n = 0;
    char *html = test_read_file(TMP("page.html"), &n);
    CHECK(html != NULL);
    if (!html) {
        return;
    }
    int images = 0;
    for (const char *p = html; (p = strstr(p, "src=\"")) != NULL; p++) {
        images++;
        CHECK_MSG(strncmp(p, "src=\"data:image/png;base64,", 27) == 0, "%.60s", p);
    }
    CHECK(images == 5); /* render, reference, map; reference and render of the slider */
    CHECK(
        strstr(html, "http:") == NULL && strstr(html, "https:") == NULL
        && strstr(html, "<link") == NULL && strstr(html, "@import") == NULL
        && strstr(html, "url(") == NULL);
    CHECK(strstr(html, "lab &lt;07&gt; &amp; &quot;friends&quot;") && !strstr(html, "<07>"));
    CHECK(strstr(html, "biased: 1 of 15 blocks") && strstr(html, "x 16-31, y 16-31"));
    CHECK(strstr(html, "id=\"power\">What it can find: a bias that brightens or darkens"));
    CHECK(strstr(html, "name=\"viewport\""));
    free(html);
}

/* ---- by region (--regions) ------------------------------------------------------ */

/* The label of (x, y) in the synthetic feature pass: diffuse-lit (1) on
 * the left half, penumbra (2) in a diagonal band on the right, umbra (3)
 * elsewhere. */
static int
region_of(int x, int y)
{
    if (x < W / 2) {
        return 1;
    }
    int band = x - W / 2 - y;
    return band >= -6 && band <= 6 ? 2 : 3;
}

/* labels.pfm, and renders a.pfm, b.pfm (seeds sa, sb) whose pixels of
 * region `planted` are scaled by `scale`. */
static bool
write_region_set(uint64_t sa, uint64_t sb, int planted, double scale)
{
    struct image ref = {0}, labels = {0}, r[2] = {{0}};
    struct diag err;
    make_reference(&ref);
    CHECK(image_alloc(&labels, W, H, &err));
    for (int k = 0; k < 2; k++) {
        make_render(&ref, k ? sb : sa, 0, 0, 1, &r[k]);
    }
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            for (int c = 0; c < 3; c++) {
                image_pixel(&labels, x, y)[c] = (float)region_of(x, y);
                for (int k = 0; k < 2; k++) {
                    float *v = image_pixel(&r[k], x, y);
                    v[c] = region_of(x, y) == planted ? (float)(v[c] * scale) : v[c];
                }
            }
        }
    }
    bool ok = write_image(&ref, "ref.pfm") && write_image(&labels, "labels.pfm")
              && write_image(&r[0], "a.pfm") && write_image(&r[1], "b.pfm");
    image_free(&ref);
    image_free(&labels);
    image_free(&r[0]);
    image_free(&r[1]);
    return ok;
}

/* A 2% bias confined to the penumbra band is named first, with a pixel of
 * the band to replay; the other regions are consistent; with no bias, no
 * region is biased for ten pairs of seeds. */
TEST(regions_name_the_biased_region_and_one_of_its_pixels)
{
    char out[CAP];
    const char *const args[] =
        {"--regions", TMP("labels.pfm"), TMP("a.pfm"), TMP("b.pfm"), TMP("ref.pfm"), NULL};
    for (int sign = -1; sign <= 1; sign += 2) {
        CHECK(write_region_set(31, 32, 2, 1 + sign * 0.02));
        int status = compare(args, out);
        const char *line = strstr(out, "\n  penumbra");
        const char *first = strstr(out, "regions    1 of 3 biased");
        CHECK_MSG(status == 1 && line && first && strstr(first, "\n  penumbra") == line, "%s", out);
        CHECK_MSG(
            line && strstr(line, sign > 0 ? "brighter" : "darker") && strstr(line, ": biased\n"),
            "%s",
            out);
        int x = -1, y = -1;
        const char *replay = strstr(out, "replay pixel ");
        CHECK(replay && sscanf(replay, "replay pixel %d,%d", &x, &y) == 2);
        CHECK_MSG(x >= 0 && x < W && y >= 0 && y < H && region_of(x, y) == 2, "pixel %d,%d", x, y);
        CHECK(strstr(out, "render --pixel") != NULL);
        CHECK(strstr(out, "diffuse-lit") && strstr(out, "umbra"));
    }
    /* The report page has the same lines. */
    const char *const html[] = {
        "--regions",
        TMP("labels.pfm"),
        "--html",
        TMP("regions.html"),
        TMP("a.pfm"),
        TMP("b.pfm"),
        TMP("ref.pfm"),
        NULL};
    CHECK(compare(html, out) == 1);
    size_t len = 0;
    char *page = test_read_file(TMP("regions.html"), &len);
    CHECK(
        page && strstr(page, "<h2>By region</h2>") && strstr(page, "<th>penumbra</th>")
        && strstr(page, "replay pixel"));
    free(page);
    for (uint64_t seed = 1; seed <= 10; seed++) {
        CHECK(write_region_set(2 * seed + 40, 2 * seed + 41, 0, 1));
        int status = compare(args, out);
        CHECK_MSG(
            status == 0 && strstr(out, "regions    0 of 3 biased"),
            "seed %d:\n%s",
            (int)seed,
            out);
    }
    printf("%s", out);
}

/* One render alone: each region's relMSE against --max-relmse. */
TEST(regions_without_noise_hold_each_region_to_the_limit)
{
    char out[CAP];
    CHECK(write_region_set(51, 52, 3, 1.2));
    const char *const args[] = {
        "--regions",
        TMP("labels.pfm"),
        "--max-relmse",
        "0.01",
        TMP("a.pfm"),
        TMP("ref.pfm"),
        NULL};
    int status = compare(args, out);
    CHECK_MSG(status == 1 && strstr(out, "regions    1 of 3 over the limit"), "%s", out);
    const char *umbra = strstr(out, "\n  umbra");
    CHECK_MSG(
        umbra && strstr(umbra, "over the limit") && strstr(out, "under the limit"),
        "%s",
        out);
    /* Without a limit nothing is judged: no limit named, nothing biased. */
    const char *const unlimited[] =
        {"--regions", TMP("labels.pfm"), TMP("a.pfm"), TMP("ref.pfm"), NULL};
    status = compare(unlimited, out);
    CHECK_MSG(
        status == 0 && strstr(out, "regions    3, by") && strstr(out, "noise not told from bias")
            && !strstr(out, "limit") && !strstr(out, "biased"),
        "%s",
        out);
}

/* A label image that is not one: exit 2, saying why. */
TEST(regions_refuse_a_bad_label_image)
{
    char out[CAP];
    CHECK(write_region_set(61, 62, 0, 1));
    const char *const mismatched[] =
        {"--regions", TMP("a.pfm"), TMP("a.pfm"), TMP("b.pfm"), TMP("ref.pfm"), NULL};
    CHECK(compare(mismatched, out) == 2);
    CHECK_MSG(strstr(out, "labels are whole numbers") != NULL, "%s", out);
    struct image small = {0};
    struct diag err;
    CHECK(image_alloc(&small, 8, 8, &err) && write_image(&small, "small.pfm"));
    image_free(&small);
    const char *const sized[] =
        {"--regions", TMP("small.pfm"), TMP("a.pfm"), TMP("b.pfm"), TMP("ref.pfm"), NULL};
    CHECK(compare(sized, out) == 2);
    CHECK_MSG(strstr(out, "8x8") != NULL, "%s", out);
}

/* --map and --html never overwrite an input or each other, however they
 * are spelt (file identity, as render checks its outputs): exit 2 and the
 * input untouched. */
TEST(outputs_that_are_inputs_or_each_other_are_refused)
{
    CHECK(write_region_set(71, 72, 0, 1));
    size_t before = 0, after = 0;
    char *ref_bytes = test_read_file(TMP("ref.pfm"), &before);
    char dotted[4200];
    snprintf(dotted, sizeof dotted, "%s/./map.png", test_tmp_path(""));
    const char *const map_ref[] =
        {TMP("a.pfm"), TMP("b.pfm"), TMP("ref.pfm"), "--map", TMP("ref.pfm"), NULL};
    const char *const html_render[] =
        {TMP("a.pfm"), TMP("b.pfm"), TMP("ref.pfm"), "--html", TMP("b.pfm"), NULL};
    const char *const both[] = {
        TMP("a.pfm"),
        TMP("b.pfm"),
        TMP("ref.pfm"),
        "--map",
        TMP("map.png"),
        "--html",
        dotted,
        NULL};
    const char *const variance[] =
        {TMP("a.pfm"), "--variance", TMP("b.pfm"), TMP("ref.pfm"), "--map", TMP("b.pfm"), NULL};
    const char *const regions[] = {
        "--regions",
        TMP("labels.pfm"),
        TMP("a.pfm"),
        TMP("b.pfm"),
        TMP("ref.pfm"),
        "--html",
        TMP("labels.pfm"),
        NULL};
    /* The reference's noise figures beside it (none here: an empty object). */
    CHECK(test_write_file(TMP("META.json"), "{}\n"));
    const char *const meta[] =
        {TMP("a.pfm"), TMP("b.pfm"), TMP("ref.pfm"), "--html", TMP("META.json"), NULL};
    const char *const *cases[] = {map_ref, html_render, both, variance, regions, meta};
    const char *const said[] = {
        "is the reference",
        "is the render",
        "are the same file",
        "is --variance",
        "is --regions",
        "is the reference's META.json"};
    CHECK(test_tool_cases("compare", cases, said, sizeof cases / sizeof cases[0], 2));
    char *now = test_read_file(TMP("ref.pfm"), &after);
    CHECK(ref_bytes && now && before == after && memcmp(ref_bytes, now, before) == 0);
    CHECK(!test_file_exists(TMP("map.png")));
    free(ref_bytes);
    free(now);
}

TEST_MAIN(
    TEST_ENTRY(png_reader_reads_back_what_the_writer_wrote),
    TEST_ENTRY(png_reader_reads_other_encoders_files),
    TEST_ENTRY(exr_reader_reads_back_what_the_writer_wrote),
    TEST_ENTRY(bad_image_files_are_refused_with_a_message),
    TEST_ENTRY(renders_are_combined_weighted_by_their_samples),
    TEST_ENTRY(renders_with_only_noise_are_consistent_for_many_seeds),
    TEST_ENTRY(a_planted_two_percent_bias_is_found_and_named),
    TEST_ENTRY(one_render_and_its_variance_image),
    TEST_ENTRY(power_line_says_what_a_comparison_can_find),
    TEST_ENTRY(one_render_alone_is_compared_but_not_tested),
    TEST_ENTRY(mask_smooth_leaves_edges_out),
    TEST_ENTRY(identical_renders_are_called_out),
    TEST_ENTRY(nan_or_infinite_pixels_are_refused_naming_the_file_and_the_pixel),
    TEST_ENTRY(outputs_that_are_inputs_or_each_other_are_refused),
    TEST_ENTRY(verdict_lines_are_plain_words_and_numbers),
    TEST_ENTRY(bad_input_exits_2),
    TEST_ENTRY(error_map_shows_sign_outlines_failing_blocks_and_has_a_legend),
    TEST_ENTRY(report_page_is_one_self_contained_file),
    TEST_ENTRY(regions_name_the_biased_region_and_one_of_its_pixels),
    TEST_ENTRY(regions_without_noise_hold_each_region_to_the_limit),
    TEST_ENTRY(regions_refuse_a_bad_label_image))
