/*
 * sampler.h - where a path's random numbers come from (--sampler): the
 * pixel's random stream, as in stage 07, or Owen-scrambled Sobol points
 * (lowdisc.h), a sequence for each use at each bounce, so that a pass's
 * samples of a pixel stratify every decision of their paths together.
 */
#ifndef SAMPLER_H
#define SAMPLER_H

#include "lowdisc.h"

/* ORDER: the --sampler choices. */
enum sampler_kind { SAMPLER_INDEPENDENT, SAMPLER_SOBOL };

/* The uses of numbers; DRAW_LIGHT + k: the shadow rays to light k. */
enum draw_use { DRAW_LOBE, DRAW_DIRECTION, DRAW_ROULETTE, DRAW_LIGHT };

/* Sample `index` of a set (a pixel's in a pass) keyed by `key`. */
struct sample_id {
    int kind; /* enum sampler_kind */
    uint64_t key;
    uint32_t index;
};

/* Two uniform numbers in [0, 1) for `use` at the depth-th vertex: the
 * random stream's, or point id.index of the use's Sobol sequence, whose
 * seed is a Weyl step from the key (as SplitMix64 takes its states).  A use of
 * one number passes u twice: each coordinate alone is a 1D sequence. */
static inline void
sampler_2d(struct sample_id id, int depth, int use, struct rng *rng, real *u, real *v)
{
    if (id.kind == SAMPLER_INDEPENDENT) {
        *u = rng_uniform(rng);
        *v = rng_uniform(rng);
        return;
    }
    uint64_t step = ((uint64_t)depth << 32) | (uint32_t)use;
    lowdisc_point2(id.index, id.key + step * 0x9e3779b97f4a7c15u, u, v);
}

#endif /* SAMPLER_H */
