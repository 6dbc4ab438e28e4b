/*
 * sampler.c - the Sobol sampler: each number a path draws is point `index`
 * of a sequence (lowdisc.h) of its pixel, bounce and use.
 */
#include "sampler.h"

#include "lowdisc.h"

/* What a path draws numbers for at each vertex (each its own sequence). */
enum draw_use { DRAW_LOBE, DRAW_DIRECTION, DRAW_ROULETTE, DRAW_LIGHT };

/* The sequence of one use at one depth: a seed in the family of the
 * pixel's key (the camera samples' sequence is the key's own). */
static uint64_t
draw_seed(struct sample_id id, int depth, enum draw_use use)
{
    return lowdisc_family_seed(id.key, ((uint64_t)depth << 8) | (uint64_t)use);
}

struct sample_id
sample_id_make(uint64_t seed, int px, int py, uint32_t index)
{
    uint64_t key = rng_mix64(seed ^ rng_mix64(((uint64_t)py << 32) | (uint32_t)px));
    return (struct sample_id){key, index, lowdisc_reverse_bits(index)};
}

void
sampler_pixel_position(struct sample_id id, real *dx, real *dy)
{
    lowdisc_point2_reversed(id.index_reversed, id.key, dx, dy);
}

void
sampler_bounce_numbers(
    int kind,
    struct sample_id id,
    int depth,
    const struct material *m,
    struct rng *rng,
    real u[3])
{
    if (kind == SAMPLER_SOBOL) {
        /* Only glass (reflect or refract) and blend (which lobe) read u[0]. */
        bool choice = m->kind == MAT_GLASS || m->kind == MAT_BLEND;
        uint32_t index = id.index_reversed;
        u[0] = choice ? lowdisc_point1_reversed(index, draw_seed(id, depth, DRAW_LOBE)) : 0;
        lowdisc_point2_reversed(index, draw_seed(id, depth, DRAW_DIRECTION), &u[1], &u[2]);
        return;
    }
    for (int i = 0; i < 3; i++) {
        u[i] = rng_uniform(rng);
    }
}

real
sampler_roulette_number(int kind, struct sample_id id, int depth, int rr_depth, struct rng *rng)
{
    if (kind != SAMPLER_SOBOL) {
        return rng_uniform(rng);
    }
    uint64_t seed = draw_seed(id, depth, DRAW_ROULETTE);
    return depth < rr_depth ? 0 : lowdisc_point1_reversed(id.index_reversed, seed);
}

void
sampler_for_lights(struct shadow_sampling *sampling, struct sample_id id, int depth)
{
    /* The adaptive rays' count varies from vertex to vertex: not those. */
    sampling->lowdisc = sampling->adaptive[0] == 0;
    sampling->lowdisc_seed = draw_seed(id, depth, DRAW_LIGHT);
    sampling->lowdisc_index = id.index;
}

bool
sampler_light_numbers(
    const struct shadow_sampling *sampling,
    int light,
    int i,
    int n,
    real *u,
    real *v)
{
    if (!sampling->lowdisc) {
        return false;
    }
    /* A vertex's n rays to a light: consecutive points of its sequence. */
    uint64_t seed = lowdisc_family_seed(sampling->lowdisc_seed, ((uint64_t)light + 1) << 32);
    uint32_t index = sampling->lowdisc_index * (uint32_t)n + (uint32_t)i;
    lowdisc_point2_reversed(lowdisc_reverse_bits(index), seed, u, v);
    return true;
}
