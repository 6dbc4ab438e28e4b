/*
 * rng.h - PCG32 random numbers with one independent stream per pixel.
 *
 * PCG32 (M. E. O'Neill, "PCG: A Family of Simple Fast Space-Efficient
 * Statistically Good Algorithms for Random Number Generation", 2014):
 * 64-bit LCG state, 32-bit output by an xorshift and a random rotation.
 * Its increment selects one of 2^63 distinct streams.
 *
 * Every pixel draws from its own stream, seeded from (seed, pixel index,
 * pass), never from a generator shared between threads: an image is the same
 * bit for bit whatever the number of threads or the order tiles are taken in.
 */
#ifndef RNG_H
#define RNG_H

#include <stdint.h>

#include "vec3.h"

struct rng {
    uint64_t state;
    uint64_t inc; /* stream selector; always odd */
};

/* SplitMix64 finaliser (Steele, Lea, Flood 2014): scrambles a counter into
 * 64 well-mixed bits, so neighbouring pixel indices give unrelated seeds. */
static inline uint64_t
rng_mix64(uint64_t x)
{
    x += 0x9e3779b97f4a7c15u;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9u;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebu;
    return x ^ (x >> 31);
}

static inline uint32_t
rng_next_u32(struct rng *r)
{
    uint64_t old = r->state;
    r->state = old * 6364136223846793005u + r->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18) ^ old) >> 27);
    uint32_t rot = (uint32_t)(old >> 59);
    return (xorshifted >> rot) | (xorshifted << ((32 - rot) & 31));
}

/* Stream `stream` of the generator, started at a state derived from `seed`.
 * Follows the reference pcg32_srandom_r. */
static inline struct rng
rng_make(uint64_t seed, uint64_t stream)
{
    struct rng r;
    r.state = 0;
    r.inc = (stream << 1) | 1u;
    rng_next_u32(&r);
    r.state += rng_mix64(seed);
    rng_next_u32(&r);
    return r;
}

/* The generator for one pixel in one pass (pass 0 for single-pass stages).
 * The starting state hashes all three numbers: starting states that differ
 * by the same constant in every pixel (say, pass 0 and pass 1) would give
 * measurably correlated first draws. */
static inline struct rng
rng_for_pixel(uint64_t seed, uint64_t pixel_index, uint64_t pass)
{
    uint64_t start = rng_mix64(rng_mix64(rng_mix64(seed) + pass) + pixel_index);
    return rng_make(start, pixel_index);
}

/* A 32-bit fraction x / 2^32 as a real in [0, 1): its 24 (float) or 32
 * (double) top bits, so the result is exactly representable and never
 * rounds up to 1. */
static inline real
rng_to_real(uint32_t x)
{
#ifdef REAL_IS_FLOAT
    return (real)(x >> 8) * 0x1p-24f;
#else
    return (real)x * 0x1p-32;
#endif
}

/* Uniform real in [0, 1). */
static inline real
rng_uniform(struct rng *r)
{
    return rng_to_real(rng_next_u32(r));
}

/* Uniform integer in [0, n), n > 0, without modulo bias (Lemire 2019). */
static inline uint32_t
rng_below(struct rng *r, uint32_t n)
{
    uint64_t m = (uint64_t)rng_next_u32(r) * n;
    uint32_t low = (uint32_t)m;
    if (low < n) {
        uint32_t threshold = (uint32_t)(-n) % n;
        while (low < threshold) {
            m = (uint64_t)rng_next_u32(r) * n;
            low = (uint32_t)m;
        }
    }
    return (uint32_t)(m >> 32);
}

/* Columns k of the most nearly square k x m grid with k m = n (k <= m):
 * stratified sampling puts one sample in each cell of such a grid, for any
 * sample count n > 0 (a prime n gives a 1 x n grid of strips). */
static inline int
strata_columns(int n)
{
    int k = 1;
    while ((k + 1) * (k + 1) <= n) {
        k++;
    }
    while (n % k != 0) {
        k--;
    }
    return k;
}

#endif /* RNG_H */
