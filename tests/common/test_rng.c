/*
 * test_rng.c - the per-pixel PCG32 streams: reproducible, uniform
 * (chi-square with a fixed seed), independent between neighbouring pixels
 * and passes, and never returning 1.
 */
#include "check.h"
#include "rng.h"

/* Chi-square statistic of n draws over `bins` equal bins. */
static double
chi_square_uniform(struct rng *r, int n, int bins)
{
    int counts[256] = {0};
    for (int i = 0; i < n; i++) {
        int b = (int)(rng_uniform(r) * bins);
        counts[b]++;
    }
    double expected = (double)n / bins;
    double chi2 = 0;
    for (int b = 0; b < bins; b++) {
        chi2 += (counts[b] - expected) * (counts[b] - expected) / expected;
    }
    return chi2;
}

TEST(reference_sequence_is_pcg32)
{
    /* pcg32_srandom_r(42, 54) from the PCG reference, first outputs. */
    struct rng r = {0, (54u << 1) | 1u};
    rng_next_u32(&r);
    r.state += 42;
    rng_next_u32(&r);
    static const uint32_t expected[] = {0xa15c02b7, 0x7b47f409, 0xba1d3330, 0x83d2f293};
    for (int i = 0; i < 4; i++) {
        CHECK(rng_next_u32(&r) == expected[i]);
    }
}

TEST(same_seed_same_stream)
{
    struct rng a = rng_for_pixel(1, 12345, 3);
    struct rng b = rng_for_pixel(1, 12345, 3);
    for (int i = 0; i < 100; i++) {
        CHECK(rng_next_u32(&a) == rng_next_u32(&b));
    }
}

TEST(uniform_by_chi_square)
{
    /* 63 degrees of freedom: the 0.999 quantile is 103.4.  A fixed seed
     * makes the outcome deterministic. */
    struct rng r = rng_for_pixel(1, 0, 0);
    CHECK(chi_square_uniform(&r, 1 << 20, 64) < 103.4);
}

TEST(neighbouring_streams_are_uncorrelated)
{
    /* Pearson correlation between pixel i and pixel i+1 draws, and between
     * passes 0 and 1 of one pixel: |rho| small for 2^16 pairs. */
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    double tx = 0, ty = 0, txx = 0, tyy = 0, txy = 0;
    int n = 1 << 16;
    for (int i = 0; i < n; i++) {
        struct rng a = rng_for_pixel(5, (uint64_t)i, 0);
        struct rng b = rng_for_pixel(5, (uint64_t)i + 1, 0);
        struct rng c = rng_for_pixel(5, (uint64_t)i, 1);
        double x = rng_uniform(&a), y = rng_uniform(&b), z = rng_uniform(&c);
        sx += x, sy += y, sxx += x * x, syy += y * y, sxy += x * y;
        tx += x, ty += z, txx += x * x, tyy += z * z, txy += x * z;
    }
    double rho = (n * sxy - sx * sy) / sqrt((n * sxx - sx * sx) * (n * syy - sy * sy));
    double rho2 = (n * txy - tx * ty) / sqrt((n * txx - tx * tx) * (n * tyy - ty * ty));
    CHECK_MSG(fabs(rho) < 0.02, "pixel rho %g", rho);
    CHECK_MSG(fabs(rho2) < 0.02, "pass rho %g", rho2);
}

TEST(seeds_change_the_stream)
{
    struct rng a = rng_for_pixel(1, 0, 0);
    struct rng b = rng_for_pixel(2, 0, 0);
    int same = 0;
    for (int i = 0; i < 64; i++) {
        same += rng_next_u32(&a) == rng_next_u32(&b);
    }
    CHECK(same < 2);
}

TEST(uniform_is_in_unit_interval)
{
    struct rng r = {0xffffffffffffffffu, 1};
    for (int i = 0; i < 1 << 20; i++) {
        real u = rng_uniform(&r);
        CHECK(u >= 0 && u < 1);
    }
    for (int i = 0; i < 10000; i++) {
        CHECK(rng_below(&r, 7) < 7);
    }
}

TEST_MAIN(
    TEST_ENTRY(reference_sequence_is_pcg32),
    TEST_ENTRY(same_seed_same_stream),
    TEST_ENTRY(uniform_by_chi_square),
    TEST_ENTRY(neighbouring_streams_are_uncorrelated),
    TEST_ENTRY(seeds_change_the_stream),
    TEST_ENTRY(uniform_is_in_unit_interval))
