/*
 * lowdisc.h - randomized low-discrepancy points: Owen-scrambled Sobol.
 *
 * The first two dimensions of Sobol's sequence ("On the distribution of
 * points in a cube", 1967) form a (0,2)-sequence in base 2: its first 2^m
 * points put exactly one point in every box of area 2^-m of the unit
 * square with power-of-two sides (2^m strips, 2^m x 1 cells, ..., and
 * 2^a x 2^b cells, a + b = m), and any 2^m consecutive aligned points do
 * too.  Independent points only do that on average.
 *
 * Owen scrambling ("Randomly permuted (t,m,s)-nets and (t,s)-sequences",
 * 1995) randomizes the points while keeping that structure: every point is
 * uniformly distributed in the square, so an estimate from them is
 * unbiased, and two seeds give independent estimates.  It is computed
 * here by hashing (Laine and Karras, "Stratified sampling for stochastic
 * transparency", 2011; Burley, "Practical Hash-based Owen Scrambling",
 * JCGT 9(4), 2020): with the bits reversed, so that the first digit of the
 * point is the lowest bit, an invertible mix in which every bit depends
 * only on itself and the bits below it flips each digit by a random
 * function of the digits before it - Owen's nested scramble.
 *
 * Each use (a pixel position, a bounce direction, ...) takes its own seed,
 * and the order of the points is shuffled with another scramble of the
 * index (Burley 2020, section 4), so that the uses of one sample are not
 * correlated with each other.
 */
#ifndef LOWDISC_H
#define LOWDISC_H

#include <stdint.h>

#include "rng.h"
#include "vec3.h"

static inline uint32_t
lowdisc_reverse_bits(uint32_t x)
{
    x = (x << 16) | (x >> 16);
    x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
    x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
    x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
    x = ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
    return x;
}

/* The bits of each 32-bit half of x reversed, by one pass over 64 bits
 * (which also swaps the halves: a << 32 | b becomes
 * reverse(b) << 32 | reverse(a)): two reversals for the price of one and
 * a little, since the steps are the same instructions on wider words. */
static inline uint64_t
lowdisc_reverse_bits_pair(uint64_t x)
{
    x = (x << 32) | (x >> 32);
    x = ((x & 0x0000ffff0000ffffu) << 16) | ((x & 0xffff0000ffff0000u) >> 16);
    x = ((x & 0x00ff00ff00ff00ffu) << 8) | ((x & 0xff00ff00ff00ff00u) >> 8);
    x = ((x & 0x0f0f0f0f0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0f0f0f0f0u) >> 4);
    x = ((x & 0x3333333333333333u) << 2) | ((x & 0xccccccccccccccccu) >> 2);
    x = ((x & 0x5555555555555555u) << 1) | ((x & 0xaaaaaaaaaaaaaaaau) >> 1);
    return x;
}

/* Owen's nested scramble done on the reversed bits r of a binary fraction
 * (its first digit the lowest bit of r): adding the seed and xoring with
 * multiples of r by even constants change each bit by a function of the
 * bits below it only, and every step is invertible (the constants are
 * Burley's, 2020). */
static inline uint32_t
lowdisc_scramble_reversed(uint32_t r, uint32_t seed)
{
    r += seed;
    r ^= r * 0x6c50b47cu;
    r ^= r * 0xb82f1e52u;
    r ^= r * 0xc7afe638u;
    r ^= r * 0x8d22f6e6u;
    return r;
}

/* Owen's nested scramble of the binary fraction x / 2^32 by seed, given
 * x's bits reversed (r = lowdisc_reverse_bits(x)): a caller that has them
 * saves a reversal. */
static inline uint32_t
lowdisc_owen_scramble_reversed(uint32_t r, uint32_t seed)
{
    return lowdisc_reverse_bits(lowdisc_scramble_reversed(r, seed));
}

/* The first two Sobol dimensions of point `index`, as 32-bit fractions.
 * Dimension 0 is the van der Corput sequence (the bits of the index
 * mirrored about the binary point).  Dimension 1 (Sobol's primitive
 * polynomial x + 1) xors, for each set bit k of the index, the direction
 * number whose digit d is binomial(k, d) mod 2, which by Lucas' theorem is
 * 1 when the bits of d are a subset of those of k.  So digit d is the xor
 * of the index bits k that contain d: five xor-shift steps (one per bit of
 * a bit position) sum every bit into the positions it contains, and the
 * result is mirrored like dimension 0.  Here, before the mirroring: the
 * digits as reversed bits, which is how the scramble takes them. */
static inline void
lowdisc_sobol2_reversed(uint32_t index, uint32_t *x, uint32_t *y)
{
    uint32_t w = index;
    w ^= (w >> 1) & 0x55555555u;
    w ^= (w >> 2) & 0x33333333u;
    w ^= (w >> 4) & 0x0f0f0f0fu;
    w ^= (w >> 8) & 0x00ff00ffu;
    w ^= (w >> 16) & 0x0000ffffu;
    *x = index;
    *y = w;
}

/* The same two dimensions as fractions: the reversed digits mirrored. */
static inline void
lowdisc_sobol2(uint32_t index, uint32_t *x, uint32_t *y)
{
    lowdisc_sobol2_reversed(index, x, y);
    *x = lowdisc_reverse_bits(*x);
    *y = lowdisc_reverse_bits(*y);
}

/* A 32-bit fraction as a real in [0, 1), never rounding up to 1. */
static inline real
lowdisc_to_real(uint32_t x)
{
#ifdef REAL_IS_FLOAT
    return (real)(x >> 8) * 0x1p-24f;
#else
    return (real)x * 0x1p-32;
#endif
}

/* The seed of sequence `counter` of a family of sequences keyed by key
 * (a pixel's, say): a Weyl step, as SplitMix64 takes its states (Steele,
 * Lea and Flood, "Fast Splittable Pseudorandom Number Generators", 2014).
 * lowdisc_point1/2 mix the seed with rng_mix64 (SplitMix64's output
 * function), so distinct counters give unrelated sequences without a hash
 * here. */
static inline uint64_t
lowdisc_family_seed(uint64_t key, uint64_t counter)
{
    return key + counter * 0x9e3779b97f4a7c15u;
}

/* A second 32-bit seed from a first, cheaply (Burley 2020 derives each
 * dimension's scramble seed by this hash_combine, after Boost's). */
static inline uint32_t
lowdisc_next_seed(uint32_t seed)
{
    return seed ^ (0x9e3779bau + (seed << 6) + (seed >> 2));
}

/* Point `index` of the scrambled 2D sequence chosen by seed (any 64 bits:
 * lowdisc_family_seed() of a hash of the image seed and the pixel, and
 * the use), given the index's bits reversed (lowdisc_reverse_bits(index),
 * where the shuffle takes them: a caller that draws many sequences at one
 * index reverses it once).  Three scrambles, with three 32-bit seeds: the
 * index's (the shuffle) and each dimension's. */
static inline void
lowdisc_point2_reversed(uint32_t index_reversed, uint64_t seed, real *u, real *v)
{
    uint64_t h = rng_mix64(seed);
    uint32_t seed_x = (uint32_t)(h >> 32);
    uint32_t shuffled = lowdisc_owen_scramble_reversed(index_reversed, (uint32_t)h);
    uint32_t x;
    uint32_t y;
    /* Scrambled in the reversed domain, mirrored once at the end:
     * reverse(scramble(reverse(reverse(r)))) = reverse(scramble(r)); both
     * dimensions mirrored together. */
    lowdisc_sobol2_reversed(shuffled, &x, &y);
    uint64_t both = lowdisc_reverse_bits_pair(
        (uint64_t)lowdisc_scramble_reversed(x, seed_x) << 32
        | lowdisc_scramble_reversed(y, lowdisc_next_seed(seed_x)));
    *u = lowdisc_to_real((uint32_t)both);
    *v = lowdisc_to_real((uint32_t)(both >> 32));
}

/* Point `index` of the scrambled 2D sequence chosen by seed. */
static inline void
lowdisc_point2(uint32_t index, uint64_t seed, real *u, real *v)
{
    lowdisc_point2_reversed(lowdisc_reverse_bits(index), seed, u, v);
}

/* Point `index` of the scrambled 1D sequence chosen by seed, given the
 * index's bits reversed: a stratified sequence (the first 2^m points, one
 * in each interval of length 2^-m). */
static inline real
lowdisc_point1_reversed(uint32_t index_reversed, uint64_t seed)
{
    uint64_t h = rng_mix64(seed);
    uint32_t shuffled = lowdisc_owen_scramble_reversed(index_reversed, (uint32_t)h);
    /* The 1D Sobol point (van der Corput's) has the index's bits as its
     * digits reversed. */
    return lowdisc_to_real(lowdisc_owen_scramble_reversed(shuffled, (uint32_t)(h >> 32)));
}

/* Point `index` of the scrambled 1D sequence chosen by seed. */
static inline real
lowdisc_point1(uint32_t index, uint64_t seed)
{
    return lowdisc_point1_reversed(lowdisc_reverse_bits(index), seed);
}

#endif /* LOWDISC_H */
