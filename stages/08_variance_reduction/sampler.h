/*
 * sampler.h - where a path's random numbers come from (--sampler): the
 * pixel's random stream, as in stage 07, or Owen-scrambled Sobol points
 * (lowdisc.h), a sequence for each use at each bounce, so that a pixel's
 * samples stratify every decision of their paths together.
 */
#ifndef SAMPLER_H
#define SAMPLER_H

#include "light.h"

/* ORDER: the --sampler choices. */
enum sampler_kind { SAMPLER_INDEPENDENT, SAMPLER_SOBOL };

/* Sample `index` of a pixel (its key from the seed and the pixel), the
 * index also with its bits reversed, once per sample (lowdisc.h). */
struct sample_id {
    uint64_t key;
    uint32_t index;
    uint32_t index_reversed;
};

struct sample_id sample_id_make(uint64_t seed, int px, int py, uint32_t index);

/* The sample's position in [0,1)^2 of its pixel (--aa sobol). */
void sampler_pixel_position(struct sample_id id, real *dx, real *dy);

/* The numbers of the bounce at the depth-th vertex (sample_bsdf()'s u). */
void sampler_bounce_numbers(
    int kind,
    struct sample_id id,
    int depth,
    const struct material *m,
    struct rng *rng,
    real u[3]);

/* Russian roulette's number at the depth-th vertex (0 before rr_depth). */
real sampler_roulette_number(
    int kind,
    struct sample_id id,
    int depth,
    int rr_depth,
    struct rng *rng);

/* The shadow rays' numbers at the depth-th vertex: false where they keep
 * the random stream (the independent sampler, adaptive shadow rays). */
void sampler_for_lights(struct shadow_sampling *sampling, struct sample_id id, int depth);
bool sampler_light_numbers(
    const struct shadow_sampling *sampling,
    int light,
    int i,
    int n,
    real *u,
    real *v);

#endif /* SAMPLER_H */
