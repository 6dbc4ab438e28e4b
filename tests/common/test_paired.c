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

/* paired STUDENT solution.pfm exits `status` and prints `needle`. */
static void
expect(const char *student, int status, const char *needle, const char *what)
{
    char s[512];
    char r[512];
    char out[CAP];
    snprintf(s, sizeof s, "%s", test_tmp_path(student));
    snprintf(r, sizeof r, "%s", test_tmp_path("solution.pfm"));
    /* Blocks of 32, aligned with the planted square: it is one block. */
    const char *args[] = {"--block", "32", s, r, NULL};
    int got = test_run_tool("paired", args, out, CAP);
    CHECK_MSG(
        got == status && strstr(out, needle) != NULL,
        "%s: exit %d, expected %d and \"%s\":\n%s",
        what,
        got,
        status,
        needle,
        out);
}

TEST(same_paths_are_consistent_and_paired)
{
    CHECK(
        write_image("solution.pfm", W, 1, 1, 1, -1, 0)
        && write_image("same.pfm", W, 1, 1, 1, -1, 0));
    expect("same.pfm", 0, "paired: 0.000 (paired), 0 of", "the same image");
}

TEST(two_percent_in_a_square_is_found_and_named)
{
    CHECK(
        write_image("solution.pfm", W, 1, 1, 1, -1, 0)
        && write_image("square.pfm", W, 1, 1, 1.02, 64, 32));
    /* The square's block first (the output starts with it), paired. */
    expect("square.pfm", 1, "(paired)", "2% in a square of the same paths");
    expect("square.pfm", 1, "  block x 64-95, y 32-63, ", "the square named");
}

TEST(under_the_minimum_effect_is_consistent)
{
    CHECK(
        write_image("solution.pfm", W, 1, 1, 1, -1, 0)
        && write_image("half.pfm", W, 1, 1.005, 1, -1, 0));
    expect("half.pfm", 0, ": consistent", "0.5% everywhere, under the 1% effect");
}

TEST(other_paths_are_unpaired_and_still_judged)
{
    CHECK(
        write_image("solution.pfm", W, 1, 1, 1, -1, 0)
        && write_image("other.pfm", W, 2, 1, 1, -1, 0));
    expect("other.pfm", 0, "(unpaired", "independent noise");
    CHECK(write_image("other_square.pfm", W, 2, 1, 1.06, 64, 32));
    expect("other_square.pfm", 1, ": biased", "6% in a square, independent noise");
}

TEST(nan_is_biased_and_sizes_must_match)
{
    CHECK(
        write_image("solution.pfm", W, 1, 1, 1, -1, 0)
        && write_image("nan.pfm", W, 1, 1, NAN, 0, 0));
    expect("nan.pfm", 1, ": biased", "a NaN square");
    CHECK(write_image("narrow.pfm", W - 8, 1, 1, 1, -1, 0));
    expect("narrow.pfm", 2, "is 120x96", "two sizes");
}

TEST_MAIN(
    TEST_ENTRY(same_paths_are_consistent_and_paired),
    TEST_ENTRY(two_percent_in_a_square_is_found_and_named),
    TEST_ENTRY(under_the_minimum_effect_is_consistent),
    TEST_ENTRY(other_paths_are_unpaired_and_still_judged),
    TEST_ENTRY(nan_is_biased_and_sizes_must_match))
