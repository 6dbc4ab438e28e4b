/*
 * test_paired.c - the paired comparison tool (tests/tools/paired.c) on
 * synthetic images: a smooth "solution" with noise of a seed of its own,
 * "students" that are the same image (the same paths), scaled in a square
 * or everywhere, or made with other noise (other paths).
 *
 *  - the same image: consistent, paired (ratio 0), exit 0;
 *  - 2% more in one 32x32 square of the same paths: biased, exit 1, and the
 *    square is the block named first;
 *  - 0.5% more everywhere: under the 1% minimum effect: consistent;
 *  - other noise (independent paths): consistent, called unpaired; with 6%
 *    more in a square: biased;
 *  - a NaN: biased; images of two sizes: exit 2.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "image.h"
#include "rng.h"
#include "testlib.h"

#define W 128
#define H 96
#define SIGMA 0.05 /* per-pixel relative noise */
#define CAP 8192

/* The smooth image times (1 + SIGMA * noise of `seed`), scaled by `scale`
 * in the square [x0, x0 + 32) x [y0, y0 + 32) (x0 < 0: nowhere) and by
 * `all` everywhere. */
static bool
write_image(const char *name, int w, uint64_t seed, double all, double scale, int x0, int y0)
{
    struct image im;
    struct diag err;
    if (!image_alloc(&im, w, H, &err)) {
        return false;
    }
    struct rng rng = rng_make(seed, 1);
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < w; x++) {
            for (int c = 0; c < 3; c++) {
                double base = 0.2 + 0.6 * x / w + 0.1 * c + 0.1 * sin(y * 0.1);
                /* Two uniforms: noise of mean 0 and spread SIGMA * sqrt(2/3). */
                double noise = (double)rng_uniform(&rng) + (double)rng_uniform(&rng) - 1;
                double v = base * (1 + SIGMA * 2 * noise) * all;
                if (x0 >= 0 && x >= x0 && x < x0 + 32 && y >= y0 && y < y0 + 32) {
                    v *= scale;
                }
                im.rgb[((size_t)y * (size_t)w + (size_t)x) * 3 + (size_t)c] = (float)v;
            }
        }
    }
    bool ok = image_write(&im, test_tmp_path(name), &err);
    image_free(&im);
    return ok;
}

static int
paired(const char *student, const char *solution, char *out)
{
    char s[512];
    char r[512];
    snprintf(s, sizeof s, "%s", test_tmp_path(student));
    snprintf(r, sizeof r, "%s", test_tmp_path(solution));
    const char *args[] = {s, r, NULL};
    return test_run_tool("paired", args, out, CAP);
}

TEST(same_paths_are_consistent_and_paired)
{
    char out[CAP];
    CHECK(
        write_image("solution.pfm", W, 1, 1, 1, -1, 0)
        && write_image("same.pfm", W, 1, 1, 1, -1, 0));
    CHECK_MSG(paired("same.pfm", "solution.pfm", out) == 0, "%s", out);
    CHECK_MSG(strstr(out, "paired: 0.000 (paired), 0 of") != NULL, "%s", out);
}

TEST(two_percent_in_a_square_is_found_and_named)
{
    char out[CAP];
    CHECK(
        write_image("solution.pfm", W, 1, 1, 1, -1, 0)
        && write_image("square.pfm", W, 1, 1, 1.02, 64, 32));
    CHECK_MSG(paired("square.pfm", "solution.pfm", out) == 1, "%s", out);
    CHECK_MSG(
        strncmp(out, "  block x 64-95, y 32-63, ", 26) == 0,
        "the square is not named first: %s",
        out);
    CHECK_MSG(strstr(out, "(paired)") && strstr(out, ": biased"), "%s", out);
}

TEST(under_the_minimum_effect_is_consistent)
{
    char out[CAP];
    CHECK(
        write_image("solution.pfm", W, 1, 1, 1, -1, 0)
        && write_image("half.pfm", W, 1, 1.005, 1, -1, 0));
    CHECK_MSG(
        paired("half.pfm", "solution.pfm", out) == 0,
        "0.5%% everywhere is under the 1%% effect: %s",
        out);
}

TEST(other_paths_are_unpaired_and_still_judged)
{
    char out[CAP];
    CHECK(
        write_image("solution.pfm", W, 1, 1, 1, -1, 0)
        && write_image("other.pfm", W, 2, 1, 1, -1, 0));
    CHECK_MSG(paired("other.pfm", "solution.pfm", out) == 0, "%s", out);
    CHECK_MSG(
        strstr(out, "(unpaired") != NULL,
        "independent noise is not called unpaired: %s",
        out);
    CHECK(write_image("other_square.pfm", W, 2, 1, 1.06, 64, 32));
    CHECK_MSG(
        paired("other_square.pfm", "solution.pfm", out) == 1,
        "6%% in a square, other paths: %s",
        out);
}

TEST(nan_is_biased_and_sizes_must_match)
{
    char out[CAP];
    CHECK(
        write_image("solution.pfm", W, 1, 1, 1, -1, 0)
        && write_image("nan.pfm", W, 1, 1, NAN, 0, 0));
    CHECK_MSG(paired("nan.pfm", "solution.pfm", out) == 1, "%s", out);
    CHECK(write_image("narrow.pfm", W - 8, 1, 1, 1, -1, 0));
    CHECK_MSG(paired("narrow.pfm", "solution.pfm", out) == 2, "%s", out);
}

TEST_MAIN(
    TEST_ENTRY(same_paths_are_consistent_and_paired),
    TEST_ENTRY(two_percent_in_a_square_is_found_and_named),
    TEST_ENTRY(under_the_minimum_effect_is_consistent),
    TEST_ENTRY(other_paths_are_unpaired_and_still_judged),
    TEST_ENTRY(nan_is_biased_and_sizes_must_match))
