/*
 * 08_lowdisc.c - the Owen-scrambled Sobol points of lowdisc.h (stage 08): the
 * first 2^m points of every scramble, and every aligned block of 2^m, are
 * a (0,m,2)-net (one point in each of the 2^m cells of every shape
 * 2^a x 2^(m-a)); the 1D points are stratified likewise; one point over
 * many seeds is uniform (chi-square); the two Sobol dimensions match the
 * definition by direction numbers; seeds give different points; the
 * sequences of one family (family_seed(), one per use of a
 * sample) are independent of each other; the paired bit reversal reverses
 * each half.
 */
#include "check.h"
#include "lowdisc.h"
#include "pathcheck.h"

/* Point i of a 1D sequence: either coordinate of a 2D point (sampler.h). */
static real
point1(uint32_t i, uint64_t seed)
{
    real u;
    real v;
    lowdisc_point2(i, seed, &u, &v);
    return seed % 2 ? u : v;
}

static void
point2(uint32_t i, uint64_t seed, real *u, real *v)
{
    lowdisc_point2(i, seed, u, v);
}

/* Sequence `counter` of a family keyed by key, as the sampler derives
 * them (sampler_2d(): a Weyl step). */
static uint64_t
family_seed(uint64_t key, uint64_t counter)
{
    return key + counter * 0x9e3779b97f4a7c15u;
}

/* Whether points i0 .. i0 + 2^m - 1 of the scramble `seed` put exactly one
 * point in every cell of every 2^a x 2^(m-a) grid. */
static bool
is_net(uint32_t i0, int m, uint64_t seed)
{
    int n = 1 << m;
    for (int a = 0; a <= m; a++) {
        int cols = 1 << a;
        int rows = 1 << (m - a);
        unsigned char seen[1 << 10] = {0};
        for (int i = 0; i < n; i++) {
            real u;
            real v;
            point2(i0 + (uint32_t)i, seed, &u, &v);
            int cell = (int)(v * rows) * cols + (int)(u * cols);
            if (u < 0 || u >= 1 || v < 0 || v >= 1 || seen[cell]++) {
                return false;
            }
        }
    }
    return true;
}

TEST(first_points_and_aligned_blocks_are_nets)
{
    int failures = 0;
    for (uint64_t seed = 1; seed <= 16; seed++) {
        for (int m = 1; m <= 10; m++) {
            failures += !is_net(0, m, seed);
            failures += !is_net(5u << m, m, seed); /* the sixth block of 2^m */
        }
    }
    CHECK_MSG(failures == 0, "%d of 320 point sets are not (0,m,2)-nets", failures);
}

TEST(one_dimensional_points_are_stratified)
{
    int failures = 0;
    for (uint64_t seed = 1; seed <= 16; seed++) {
        for (int m = 0; m <= 10; m++) {
            unsigned char seen[1 << 10] = {0};
            for (int i = 0; i < (1 << m); i++) {
                real u = point1((uint32_t)i, seed);
                int cell = (int)(u * (1 << m));
                failures += u < 0 || u >= 1 || seen[cell]++ > 0;
            }
        }
    }
    CHECK_MSG(failures == 0, "%d points share their stratum", failures);
}

TEST(a_point_is_uniform_over_seeds)
{
    /* Point 5 (and the 1D point 5) of 16384 scrambles in 16 x 16 cells /
     * 64 intervals: chi-square below its 0.001 quantile (df 255: 330.5;
     * df 63: 103.4). */
    enum {
        SEEDS = 16384
    };

    /* The scrambles: hashes of first .. first + SEEDS - 1 (PATHCHECK_SEED,
     * default 0, so that make test-seeds can draw other sets). */
    uint64_t first = pathcheck_seed(0);
    int cells[256] = {0};
    int strata[64] = {0};
    for (uint64_t seed = first; seed < first + SEEDS; seed++) {
        real u;
        real v;
        point2(5, rng_mix64(seed), &u, &v);
        cells[(int)(v * 16) * 16 + (int)(u * 16)]++;
        strata[(int)(point1(5, rng_mix64(seed)) * 64)]++;
    }
    double chi2_cells = 0;
    double chi2_strata = 0;
    for (int c = 0; c < 256; c++) {
        double e = SEEDS / 256.0;
        chi2_cells += (cells[c] - e) * (cells[c] - e) / e;
    }
    for (int c = 0; c < 64; c++) {
        double e = SEEDS / 64.0;
        chi2_strata += (strata[c] - e) * (strata[c] - e) / e;
    }
    printf("chi-square: 2D %.1f (df 255), 1D %.1f (df 63)\n", chi2_cells, chi2_strata);
    CHECK(chi2_cells < 330.5);
    CHECK(chi2_strata < 103.4);
}

TEST(sobol_dimensions_match_their_direction_numbers)
{
    int wrong = 0;
    for (uint32_t index = 0; index < 70000; index += 7) {
        uint32_t x;
        uint32_t y;
        lowdisc_sobol2_reversed(index, &x, &y);
        x = lowdisc_reverse_bits(x);
        y = lowdisc_reverse_bits(y);
        /* Dimension 0: v_k = 2^-(k+1); dimension 1: v_0 = 1/2,
         * v_k = v_(k-1) xor v_(k-1) / 2. */
        uint32_t ex = 0;
        uint32_t ey = 0;
        uint32_t v = 0x80000000u;
        for (int k = 0; k < 32; k++, v ^= v >> 1) {
            if (index >> k & 1u) {
                ex ^= 0x80000000u >> k;
                ey ^= v;
            }
        }
        wrong += x != ex || y != ey;
    }
    CHECK_MSG(wrong == 0, "%d points differ from the definition", wrong);
}

TEST(seeds_give_different_points)
{
    int same = 0;
    for (uint32_t i = 0; i < 64; i++) {
        real u1;
        real v1;
        real u2;
        real v2;
        point2(i, 1, &u1, &v1);
        point2(i, 2, &u2, &v2);
        same += u1 == u2 && v1 == v2;
    }
    CHECK(same == 0);
}

/* Point i of the sequences of two neighbouring counters of one family,
 * over many keys: their pairs fall evenly in 8 x 8 cells (chi-square below
 * its 0.001 quantile, df 63: 103.4), as independent points do; the same
 * sequence would put them all on the diagonal.  For the 1D points (the
 * roulette's, say) and the 2D ones (a bounce's direction against the
 * shadow ray's point), and u against v of one 2D point. */
TEST(sequences_of_one_family_are_independent)
{
    enum {
        KEYS = 16384
    };

    int pairs_1d[64] = {0};
    int pairs_2d[64] = {0};
    int within[64] = {0};
    uint64_t first = pathcheck_seed(0);
    for (uint64_t k = 0; k < KEYS; k++) {
        uint64_t key = rng_mix64(first + k);
        uint32_t i = (uint32_t)(k % 16);
        real a = point1(i, family_seed(key, 256));
        real b = point1(i, family_seed(key, 257));
        pairs_1d[(int)(a * 8) * 8 + (int)(b * 8)]++;
        real u1;
        real v1;
        real u2;
        real v2;
        point2(i, family_seed(key, 258), &u1, &v1);
        point2(i, family_seed(key, 259), &u2, &v2);
        pairs_2d[(int)(u1 * 8) * 8 + (int)(u2 * 8)]++;
        within[(int)(u1 * 8) * 8 + (int)(v1 * 8)]++;
    }
    double chi2[3] = {0, 0, 0};
    double e = KEYS / 64.0;
    for (int c = 0; c < 64; c++) {
        chi2[0] += (pairs_1d[c] - e) * (pairs_1d[c] - e) / e;
        chi2[1] += (pairs_2d[c] - e) * (pairs_2d[c] - e) / e;
        chi2[2] += (within[c] - e) * (within[c] - e) / e;
    }
    printf("chi-square (df 63): 1D pairs %.1f, 2D pairs %.1f, u and v %.1f\n", chi2[0], chi2[1],
           chi2[2]);
    CHECK(chi2[0] < 103.4);
    CHECK(chi2[1] < 103.4);
    CHECK(chi2[2] < 103.4);
}

TEST_MAIN(
    TEST_ENTRY(first_points_and_aligned_blocks_are_nets),
    TEST_ENTRY(one_dimensional_points_are_stratified),
    TEST_ENTRY(a_point_is_uniform_over_seeds),
    TEST_ENTRY(sobol_dimensions_match_their_direction_numbers),
    TEST_ENTRY(seeds_give_different_points),
    TEST_ENTRY(sequences_of_one_family_are_independent))
