/*
 * lowdisc.h - Owen-scrambled Sobol points: any 2^m aligned consecutive
 * points put one in every power-of-two box of area 2^-m of the unit square,
 * and each is uniform (Owen 1995; hashed: Burley, "Practical Hash-based
 * Owen Scrambling", JCGT 9(4), 2020).
 */
#ifndef LOWDISC_H
#define LOWDISC_H

#include <stdint.h>

#include "rng.h"

static inline uint32_t
lowdisc_reverse_bits(uint32_t x)
{
    x = (x << 16) | (x >> 16);
    x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
    x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
    x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
    return ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
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

/* Point `index` of the 2D sequence chosen by seed: the index shuffled by a
 * scramble of its own, then each dimension scrambled.  Its u alone is a 1D
 * sequence (van der Corput's digits are the index's bits). */
static inline void
lowdisc_point2(uint32_t index, uint64_t seed, real *u, real *v)
{
    uint64_t h = rng_mix64(seed);
    uint32_t seed_x = (uint32_t)(h >> 32);
    /* The y seed from the x seed by Boost's hash_combine, as Burley does. */
    uint32_t seed_y = seed_x ^ (0x9e3779bau + (seed_x << 6) + (seed_x >> 2));
    uint32_t r = lowdisc_scramble_reversed(lowdisc_reverse_bits(index), (uint32_t)h);
    uint32_t x;
    uint32_t y;
    lowdisc_sobol2_reversed(lowdisc_reverse_bits(r), &x, &y);
    *u = rng_to_real(lowdisc_reverse_bits(lowdisc_scramble_reversed(x, seed_x)));
    *v = rng_to_real(lowdisc_reverse_bits(lowdisc_scramble_reversed(y, seed_y)));
}

#endif /* LOWDISC_H */
