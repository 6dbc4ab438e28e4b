/*
 * 08_lab_functions.c - lab 08's Owen scrambling, on its own (tests/lab/
 * README.md, "Function tests"); the points it makes are 08_lowdisc.c's.
 *
 * lowdisc_scramble_reversed(r, seed) takes a binary fraction as its bits
 * reversed (bit 0 of r is the fraction's first digit) and must be a nested
 * uniform scramble (Owen 1995): each digit flipped by a random function of
 * the seed and of the digits before it.  So:
 *  - nested: changing digit j changes digit j of the result and no digit
 *    before it (for 2,000 random r and seeds, every j);
 *  - each flip depends on the digits before it: over 4,000 seeds, digit k
 *    of the results for r and for r with its first digit changed differ
 *    for 10% to 90% of the seeds, k = 1..8 (a seed-only xor, a digital
 *    shift, never differs; a perfectly random function of the prefix
 *    would differ half the time, Burley's hash between 31% and 76%);
 *  - random over seeds: the first 6 digits of one input's scramble over
 *    16,384 seeds are uniform (chi-square, 64 bins), and two seeds give
 *    different scrambles;
 *  - (that the points stay (0,m,2)-nets is 08_lowdisc's
 *    first_points_and_aligned_blocks_are_nets, not repeated here).
 * The chi-square test is at alpha 0.01; seeds from pathcheck_seed().
 */
#include <stdio.h>

#include "check.h"
#include "lowdisc.h"
#include "pathcheck.h"
#include "stattest.h"
#include "warptest.h"

#define N_STAT_TESTS 1

static double
level(void)
{
    return stattest_sidak(PATHCHECK_ALPHA, N_STAT_TESTS);
}

TEST(lowdisc_scramble_reversed_is_nested)
{
    struct rng rng = rng_make(8001, 1);
    for (int i = 0; i < 2000; i++) {
        uint32_t r = rng_next_u32(&rng);
        uint32_t seed = rng_next_u32(&rng);
        uint32_t out = lowdisc_scramble_reversed(r, seed);
        for (int j = 0; j < 32; j++) {
            uint32_t changed = out ^ lowdisc_scramble_reversed(r ^ (1u << j), seed);
            uint32_t below = j == 0 ? 0 : changed & ((1u << j) - 1);
            if (below != 0 || !(changed >> j & 1)) {
                CHECK_FAIL(
                    "lowdisc_scramble_reversed (r 0x%08x, seed 0x%08x): changing digit %d of r (bit %d) changes "
                    "digits 0x%08x of the result: a nested scramble changes digit %d and none before it (flip "
                    "each digit by a function of the digits before it only)",
                    r,
                    seed,
                    j,
                    j,
                    changed,
                    j);
                return;
            }
        }
    }
}

TEST(lowdisc_scramble_reversed_flips_by_the_digits_before)
{
    struct rng rng = rng_make(8002, 2);
    int differ[9] = {0};
    const int seeds = 4000;
    for (int i = 0; i < seeds; i++) {
        uint32_t r = rng_next_u32(&rng);
        uint32_t seed = rng_next_u32(&rng);
        uint32_t d = lowdisc_scramble_reversed(r, seed) ^ lowdisc_scramble_reversed(r ^ 1u, seed);
        for (int k = 1; k <= 8; k++) {
            differ[k] += (int)(d >> k & 1);
        }
    }
    for (int k = 1; k <= 8; k++) {
        double share = (double)differ[k] / seeds;
        if (!(share > 0.1 && share < 0.9)) {
            CHECK_FAIL(
                "lowdisc_scramble_reversed: with the first digit changed, digit %d of the result differs for %d "
                "of %d seeds, where a function of the digits before it differs for some seeds and not others: "
                "Owen scrambling flips each digit by the seed and the digits before it, not by the seed alone",
                k,
                differ[k],
                seeds);
        }
    }
}

TEST(lowdisc_scramble_reversed_is_uniform_over_seeds)
{
    struct warptest w;
    CHECK(warptest_square(&w, 1, 64));
    uint64_t first = pathcheck_seed(8003);
    uint32_t r = 0x2b3c4d5eu;
    int same = 0;
    for (uint64_t s = first; s < first + 16384; s++) {
        uint32_t seed = (uint32_t)(rng_mix64(s) >> 32);
        uint32_t out = lowdisc_scramble_reversed(r, seed);
        same += out == lowdisc_scramble_reversed(r, seed ^ 0x80000001u);
        /* The first six digits, as a fraction: bits 0..5 reversed. */
        double u = (double)(lowdisc_reverse_bits(out) >> 26) / 64;
        warptest_add(&w, u + 1.0 / 128, 0.5, 0);
    }
    struct warptest_result fit = warptest_fit(&w, NULL, NULL);
    char why[300];
    warptest_describe(&w, &fit, why, sizeof why);
    printf("lowdisc_scramble_reversed over seeds: %s\n", why);
    if (fit.p < level() || same > 16) {
        CHECK_FAIL(
            "lowdisc_scramble_reversed: over 16,384 seeds the first six digits of one input's scramble are not "
            "uniform (p %.2g; %s), or %d seeds give the scramble of another: the seed must randomise every digit",
            fit.p,
            why,
            same);
    }
    warptest_free(&w);
}

TEST_MAIN(
    TEST_ENTRY(lowdisc_scramble_reversed_is_nested),
    TEST_ENTRY(lowdisc_scramble_reversed_flips_by_the_digits_before),
    TEST_ENTRY(lowdisc_scramble_reversed_is_uniform_over_seeds))
