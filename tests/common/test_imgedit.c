/*
 * test_imgedit.c - the imgedit tool (tests/tools/imgedit.c) of make
 * calibrate: a planted bias scales exactly the pixels of its rectangle, a
 * downsampled image is the mean of each square, and what it refuses.
 */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "image.h"
#include "testlib.h"

#define CAP 4096
#define TMP(name) test_tmp_path(name)

/* A 4x4 image whose sample i is i + 1. */
static bool
write_ramp(const char *name)
{
    struct image img = {0};
    struct diag err = {0};
    bool ok = image_alloc(&img, 4, 4, &err);
    for (int i = 0; ok && i < 48; i++) {
        img.rgb[i] = (float)(i + 1);
    }
    ok = ok && image_write(&img, TMP(name), &err);
    image_free(&img);
    return ok;
}

static int
imgedit(const char *const *args, char *out)
{
    return test_run_tool("imgedit", args, out, CAP);
}

TEST(scale_changes_only_the_rectangle)
{
    char out[CAP];
    CHECK(write_ramp("r.pfm"));
    const char *const args[] = {"--scale", "1.5", "--rect", "1,2,2,5", TMP("r.pfm"), TMP("s.pfm"), NULL};
    CHECK_MSG(imgedit(args, out) == 0, "%s", out);
    struct image img = {0};
    struct diag err = {0};
    CHECK(image_read_pfm(TMP("s.pfm"), &img, &err));
    for (int y = 0; img.rgb && y < 4; y++) {
        for (int x = 0; x < 4; x++) {
            /* The rectangle is clipped at the image's bottom edge. */
            double f = x >= 1 && x <= 2 && y >= 2 ? 1.5 : 1;
            for (int c = 0; c < 3; c++) {
                CHECK_NEAR(image_pixel(&img, x, y)[c], f * (3 * (4 * y + x) + c + 1), 1e-5);
            }
        }
    }
    image_free(&img);
    const char *const whole[] = {"--scale", "2", TMP("r.pfm"), TMP("w.pfm"), NULL};
    CHECK_MSG(imgedit(whole, out) == 0, "%s", out);
    CHECK(image_read_pfm(TMP("w.pfm"), &img, &err));
    CHECK(img.rgb && img.rgb[47] == 96.0f && img.rgb[0] == 2.0f);
    image_free(&img);
}

TEST(downsample_averages_squares)
{
    char out[CAP];
    CHECK(write_ramp("r.pfm"));
    const char *const args[] = {"--downsample", "2", TMP("r.pfm"), TMP("d.pfm"), NULL};
    CHECK_MSG(imgedit(args, out) == 0, "%s", out);
    struct image img = {0};
    struct diag err = {0};
    CHECK(image_read_pfm(TMP("d.pfm"), &img, &err));
    CHECK(img.width == 2 && img.height == 2);
    for (int y = 0; img.rgb && y < 2; y++) {
        for (int x = 0; x < 2; x++) {
            /* The mean of pixels (2x, 2y), (2x + 1, 2y), (2x, 2y + 1),
             * (2x + 1, 2y + 1) of the ramp, channel 0. */
            double p = 4 * 2 * y + 2 * x;
            CHECK_NEAR(image_pixel(&img, x, y)[0], 3 * (p + 2.5) + 1, 1e-5);
        }
    }
    image_free(&img);
}

TEST(what_imgedit_refuses)
{
    char out[CAP];
    CHECK(write_ramp("r.pfm"));
    const char *const uneven[] = {"--downsample", "3", TMP("r.pfm"), TMP("x.pfm"), NULL};
    CHECK_MSG(imgedit(uneven, out) == 1 && strstr(out, "multiple"), "%s", out);
    const char *const missing[] = {"--scale", "2", TMP("none.pfm"), TMP("x.pfm"), NULL};
    CHECK_MSG(imgedit(missing, out) == 1, "%s", out);
    CHECK(!test_file_exists(TMP("x.pfm")));
    const char *const both[] = {"--scale", "2", "--downsample", "2", TMP("r.pfm"), TMP("x.pfm"), NULL};
    const char *const rect_alone[] = {"--rect", "0,0,1,1", TMP("r.pfm"), TMP("x.pfm"), NULL};
    const char *const bad_scale[] = {"--scale", "-1", TMP("r.pfm"), TMP("x.pfm"), NULL};
    const char *const bad_rect[] = {"--scale", "2", "--rect", "0,0,0,1", TMP("r.pfm"), TMP("x.pfm"), NULL};
    const char *const one_path[] = {"--scale", "2", TMP("r.pfm"), NULL};
    const char *const *usage[] = {both, rect_alone, bad_scale, bad_rect, one_path};
    for (size_t i = 0; i < sizeof usage / sizeof usage[0]; i++) {
        CHECK_MSG(imgedit(usage[i], out) == 2, "usage case %zu: %s", i, out);
    }
    const char *const help[] = {"--help", NULL};
    CHECK(imgedit(help, out) == 0 && strstr(out, "--downsample"));
}

TEST_MAIN(
    TEST_ENTRY(scale_changes_only_the_rectangle),
    TEST_ENTRY(downsample_averages_squares),
    TEST_ENTRY(what_imgedit_refuses))
