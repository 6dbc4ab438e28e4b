/*
 * test_boxdown.c - the box downsampler of `make trade QUICK=1` (boxdown.c,
 * pfmbox) on synthetic images with known answers: constants, a ramp, the
 * pixel averages of an analytic function (which a box-filtered reference
 * is), non-finite pixels, bad factors, and the command-line tool through
 * files (its path in the environment variable PFMBOX).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "boxdown.h"
#include "check.h"
#include "image.h"
#include "testlib.h"

static struct image
new_image(int w, int h)
{
    struct image img = {0};
    if (!image_alloc(&img, w, h, NULL)) {
        printf("image_alloc failed\n");
        exit(1);
    }
    return img;
}

static void
set_rgb(struct image *img, int x, int y, float r, float g, float b)
{
    float *p = image_pixel(img, x, y);
    p[0] = r;
    p[1] = g;
    p[2] = b;
}

TEST(constant_stays_constant)
{
    struct image in = new_image(12, 8), out;
    for (int y = 0; y < 8; y++) {
        for (int x = 0; x < 12; x++) {
            set_rgb(&in, x, y, 0.25f, 3.0f, 0);
        }
    }
    CHECK(box_downsample(&in, 4, &out, NULL));
    CHECK(out.width == 3 && out.height == 2);
    for (int y = 0; y < out.height; y++) {
        for (int x = 0; x < out.width; x++) {
            const float *p = image_pixel(&out, x, y);
            CHECK(p[0] == 0.25f && p[1] == 3.0f && p[2] == 0);
        }
    }
    image_free(&in);
    image_free(&out);
}

TEST(factor_one_is_a_copy)
{
    struct image in = new_image(5, 3), out;
    for (int i = 0; i < 5 * 3 * 3; i++) {
        in.rgb[i] = (float)i * 0.37f - 2;
    }
    CHECK(box_downsample(&in, 1, &out, NULL));
    CHECK(out.width == 5 && out.height == 3);
    CHECK(memcmp(in.rgb, out.rgb, sizeof(float) * 5 * 3 * 3) == 0);
    image_free(&in);
    image_free(&out);
}

/* Pixel (x, y) = (x, 10 y, x + y): block (X, Y) of f x f averages to
 * (f X + (f-1)/2, 10 (f Y + (f-1)/2), ...); every value exact in float. */
TEST(ramp_block_means)
{
    const int f = 4;
    struct image in = new_image(16, 8), out;
    for (int y = 0; y < 8; y++) {
        for (int x = 0; x < 16; x++) {
            set_rgb(&in, x, y, (float)x, 10.0f * (float)y, (float)(x + y));
        }
    }
    CHECK(box_downsample(&in, f, &out, NULL));
    CHECK(out.width == 4 && out.height == 2);
    for (int y = 0; y < out.height; y++) {
        for (int x = 0; x < out.width; x++) {
            const float *p = image_pixel(&out, x, y);
            double mx = f * x + (f - 1) / 2.0, my = f * y + (f - 1) / 2.0;
            CHECK_NEAR(p[0], mx, 0);
            CHECK_NEAR(p[1], 10 * my, 0);
            CHECK_NEAR(p[2], mx + my, 0);
        }
    }
    image_free(&in);
    image_free(&out);
}

/* The integral of u^2 over [a, b], divided by (b - a). */
static double
mean_u2(double a, double b)
{
    return (b * b * b - a * a * a) / (3 * (b - a));
}

/* A box-filtered image of L(u, v) = u^2 + 3 v (pixel (x, y) holds the mean
 * of L over its unit square) shrunk by 4 is the box-filtered image of L at
 * 1/4 of the size: the claim that makes QUICK's comparisons exact. */
TEST(box_filtered_image_stays_box_filtered)
{
    const int f = 4, w = 32, h = 16;
    struct image in = new_image(w, h), out;
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            float v = (float)(mean_u2(x, x + 1) + 3 * (y + 0.5));
            set_rgb(&in, x, y, v, v, v);
        }
    }
    CHECK(box_downsample(&in, f, &out, NULL));
    double worst = 0;
    for (int y = 0; y < out.height; y++) {
        for (int x = 0; x < out.width; x++) {
            double want = mean_u2(f * x, f * (x + 1)) + 3 * (f * y + f / 2.0);
            double got = image_pixel(&out, x, y)[0];
            worst = fmax(worst, fabs(got - want) / want);
        }
    }
    CHECK_MSG(worst < 1e-6, "worst relative error %g", worst);
    image_free(&in);
    image_free(&out);
}

/* A NaN or Inf spoils its own output pixel and no other. */
TEST(nonfinite_stays_in_its_block)
{
    struct image in = new_image(4, 4), out;
    for (int y = 0; y < 4; y++) {
        for (int x = 0; x < 4; x++) {
            set_rgb(&in, x, y, 1, 1, 1);
        }
    }
    set_rgb(&in, 3, 0, NAN, 1, INFINITY);
    CHECK(box_downsample(&in, 2, &out, NULL));
    const float *bad = image_pixel(&out, 1, 0);
    CHECK(isnan(bad[0]) && bad[1] == 1 && isinf(bad[2]));
    CHECK(image_pixel(&out, 0, 0)[0] == 1 && image_pixel(&out, 0, 1)[0] == 1);
    CHECK(image_pixel(&out, 1, 1)[2] == 1);
    image_free(&in);
    image_free(&out);
}

TEST(bad_factors_fail)
{
    struct image in = new_image(6, 4), out;
    struct diag err = {0};
    CHECK(!box_downsample(&in, 4, &out, &err)); /* 4 does not divide 6 */
    CHECK(strstr(err.msg, "does not divide") != NULL);
    CHECK(out.rgb == NULL);
    CHECK(!box_downsample(&in, 0, &out, NULL));
    CHECK(!box_downsample(&in, -2, &out, NULL));
    CHECK(!box_downsample(&in, 3, &out, NULL)); /* divides 6, not 4 */
    CHECK(box_downsample(&in, 2, &out, NULL));
    CHECK(out.width == 3 && out.height == 2);
    image_free(&in);
    image_free(&out);
}

/* The tool: a PFM in, a PFM out; bad usage exits 2 and bad input 1, with
 * no output file left behind. */
TEST(tool_through_files)
{
    const char *tool = getenv("PFMBOX");
    if (!tool || !*tool) {
        SKIP("PFMBOX (the pfmbox binary) not set");
    }
    struct image in = new_image(8, 4), back = {0};
    for (int y = 0; y < 4; y++) {
        for (int x = 0; x < 8; x++) {
            set_rgb(&in, x, y, (float)x, (float)y, 0.5f);
        }
    }
    char src[1024], dst[1024], none[1024];
    snprintf(src, sizeof src, "%s", test_tmp_path("in.pfm"));
    snprintf(dst, sizeof dst, "%s", test_tmp_path("out.pfm"));
    snprintf(none, sizeof none, "%s", test_tmp_path("never.pfm"));
    CHECK(image_write(&in, src, NULL));
    char output[2048];
    const char *ok_args[] = {tool, "2", src, dst, NULL};
    CHECK(test_run(ok_args, output, sizeof output) == 0);
    CHECK(image_read_pfm(dst, &back, NULL));
    CHECK(back.width == 4 && back.height == 2);
    if (back.rgb) {
        const float *p = image_pixel(&back, 3, 1); /* x 6..7, y 2..3 */
        CHECK(p[0] == 6.5f && p[1] == 2.5f && p[2] == 0.5f);
    }
    const char *bad_factor[] = {tool, "3", src, none, NULL};
    CHECK(test_run(bad_factor, output, sizeof output) == 1);
    CHECK(strstr(output, "does not divide") != NULL);
    const char *missing[] = {tool, "2", test_tmp_path("missing.pfm"), none, NULL};
    CHECK(test_run(missing, output, sizeof output) == 1);
    const char *usage1[] = {tool, "two", src, none, NULL};
    CHECK(test_run(usage1, output, sizeof output) == 2);
    const char *usage2[] = {tool, "2", src, NULL};
    CHECK(test_run(usage2, output, sizeof output) == 2);
    CHECK(!test_file_exists(none));
    image_free(&in);
    image_free(&back);
}

TEST_MAIN(
    TEST_ENTRY(constant_stays_constant),
    TEST_ENTRY(factor_one_is_a_copy),
    TEST_ENTRY(ramp_block_means),
    TEST_ENTRY(box_filtered_image_stays_box_filtered),
    TEST_ENTRY(nonfinite_stays_in_its_block),
    TEST_ENTRY(bad_factors_fail),
    TEST_ENTRY(tool_through_files))
