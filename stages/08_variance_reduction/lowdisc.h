/*
 * lowdisc.h - Owen-scrambled Sobol points.  The first two Sobol dimensions
 * are a (0,2)-sequence: any 2^m aligned consecutive points put one point in
 * every power-of-two box of area 2^-m of the unit square.  Owen's scramble
 * (1995) keeps that and makes each point uniform (unbiased estimates,
 * independent seeds); computed by hashing the reversed bits (Burley,
 * "Practical Hash-based Owen Scrambling", JCGT 9(4), 2020), the index
 * shuffled by another scramble so that a sample's uses are unrelated.
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
    return ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
}

/* Both 32-bit halves reversed (and swapped): two reversals for one. */
static inline uint64_t
lowdisc_reverse_bits_pair(uint64_t x)
{
    x = (x << 32) | (x >> 32);
    x = ((x & 0x0000ffff0000ffffu) << 16) | ((x & 0xffff0000ffff0000u) >> 16);
    x = ((x & 0x00ff00ff00ff00ffu) << 8) | ((x & 0xff00ff00ff00ff00u) >> 8);
    x = ((x & 0x0f0f0f0f0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0f0f0f0f0u) >> 4);
    x = ((x & 0x3333333333333333u) << 2) | ((x & 0xccccccccccccccccu) >> 2);
    return ((x & 0x5555555555555555u) << 1) | ((x & 0xaaaaaaaaaaaaaaaau) >> 1);
}

/* Owen's nested scramble of a binary fraction given as its reversed bits
 * r: adding the seed and xoring with multiples of r by even constants
 * (Burley's) change each bit by a function of the bits below it only. */
static inline uint32_t
lowdisc_scramble_reversed(uint32_t r, uint32_t seed)
{
    /* LAB 08: Owen scrambling */
    r += seed;
    r ^= r * 0x6c50b47cu;
    r ^= r * 0xb82f1e52u;
    r ^= r * 0xc7afe638u;
    r ^= r * 0x8d22f6e6u;
    return r;
    /* END LAB */
}

/* The first two Sobol dimensions of point `index`, as reversed digits: the
 * index's bits (van der Corput); digit d of dimension 1 is the xor of the
 * index bits k that contain d's bits (Lucas: binomial(k, d) mod 2). */
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

/* The seed of sequence `counter` of a family keyed by key: a Weyl step, as
 * SplitMix64 takes its states (the points mix the seed with rng_mix64). */
static inline uint64_t
lowdisc_family_seed(uint64_t key, uint64_t counter)
{
    return key + counter * 0x9e3779b97f4a7c15u;
}

/* Point `index` of the 2D sequence chosen by seed, given the index's bits
 * reversed (reversed once per sample, for all its sequences): the index
 * shuffled, then each dimension scrambled, both mirrored at the end. */
static inline void
lowdisc_point2_reversed(uint32_t index_reversed, uint64_t seed, real *u, real *v)
{
    uint64_t h = rng_mix64(seed);
    uint32_t seed_x = (uint32_t)(h >> 32);
    /* The y seed from the x seed by Boost's hash_combine, as Burley does. */
    uint32_t seed_y = seed_x ^ (0x9e3779bau + (seed_x << 6) + (seed_x >> 2));
    uint32_t r = lowdisc_scramble_reversed(index_reversed, (uint32_t)h);
    uint32_t shuffled = lowdisc_reverse_bits(r);
    uint32_t x;
    uint32_t y;
    lowdisc_sobol2_reversed(shuffled, &x, &y);
    uint64_t both = (uint64_t)lowdisc_scramble_reversed(x, seed_x) << 32;
    both = lowdisc_reverse_bits_pair(both | lowdisc_scramble_reversed(y, seed_y));
    *u = lowdisc_to_real((uint32_t)both);
    *v = lowdisc_to_real((uint32_t)(both >> 32));
}

/* Point `index` of the 1D sequence chosen by seed (van der Corput's digits
 * are the index's bits), given the index's bits reversed. */
static inline real
lowdisc_point1_reversed(uint32_t index_reversed, uint64_t seed)
{
    uint64_t h = rng_mix64(seed);
    uint32_t r = lowdisc_scramble_reversed(index_reversed, (uint32_t)h);
    r = lowdisc_scramble_reversed(lowdisc_reverse_bits(r), (uint32_t)(h >> 32));
    return lowdisc_to_real(lowdisc_reverse_bits(r));
}

#endif /* LOWDISC_H */
