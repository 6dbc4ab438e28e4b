/*
 * render.c - path tracing: for each pixel, random paths from the camera
 * through many points of its square, each bouncing off the surfaces it meets
 * (bsdf.c), collecting light from the lights by shadow rays at every diffuse
 * bounce (next-event estimation), ended by Russian roulette.  Their mean is
 * an unbiased estimate of the pixel: direct and indirect light, caustics
 * included.
 */
#include "render.h"

#include "bsdf.h"
#include "inspect.h"
#include "lowdisc.h"

/* Parity (0 or 1) of the cell of a 1D checkerboard that x falls in;
 * fmod keeps it exact for coordinates too large for an integer. */
static int
cell_parity(real x, real size)
{
    return fabs(fmod(floor(x / size), (real)2)) > (real)0.5;
}

/* A solid 3D checkerboard of cubes of edge checker_size, with a cube corner
 * at the origin.  A surface lying exactly on a cube face (the floor at
 * y = 0) would flicker between two cells with the rounding of p, so p is
 * first moved towards -infinity by more than its error bound, along the
 * axes the surface faces (the components of |ng|): such a surface always
 * takes the cell below, whichever way it faces.  Not along the others:
 * that would slide the pattern over the surface by the bound, a cell and
 * more in single precision 1e6 from the origin (2 x 64 ulps = 15 units). */
static vec3
checker_albedo(const struct material *m, const struct hit *h)
{
    vec3 q = vec3_sub(h->p, vec3_scale(vec3_abs(h->ng), 2 * h->error));
    int parity = cell_parity(q.x, m->checker_size) ^ cell_parity(q.y, m->checker_size)
                 ^ cell_parity(q.z, m->checker_size);
    return parity ? m->albedo2 : m->albedo;
}

/* The Lambertian albedo of a material's diffuse part (none for mirror and
 * glass). */
static vec3
diffuse_albedo(const struct material *m, const struct hit *h)
{
    switch (m->kind) {
    case MAT_DIFFUSE:
    case MAT_BLEND:
        return m->albedo;
    case MAT_MIRROR:
    case MAT_GLASS:
        return vec3_splat(0);
    case MAT_CHECKER:
        return checker_albedo(m, h);
    }
    return m->albedo;
}

/* Multiple importance sampling (Veach and Guibas, "Optimally Combining
 * Sampling Techniques for Monte Carlo Rendering", 1995): light from an
 * area or sphere light reaches a diffuse point by two techniques, a shadow
 * ray to a point drawn on the light (NEE, density p_light per steradian)
 * and the path's own bounce when it happens to hit the light (density
 * p_bsdf).  Each is good where the other is poor: NEE for a small light,
 * the bounce for a large, close one, whose far parts NEE draws seldom
 * (r^2 / cos(theta') is large there) though they add much.  Counting a
 * light by both, each sample weighted by w = (n p)^2 / sum over techniques
 * of (n_k p_k)^2 (the power heuristic, mis_power_heuristic() in light.c,
 * n the samples per technique), keeps the estimate unbiased since the
 * weights of every direction sum to 1, and takes the variance near the
 * better of the two everywhere.  Point lights (no area: NEE only) and
 * specular bounces (a single direction: the bounce only) keep weight 1.
 * The adaptive shadow rays replace some estimates by closed forms: no MIS
 * with them. */
static bool
mis_on(const struct renderer *renderer)
{
    return renderer->mis && renderer->nee && renderer->shadow.adaptive[0] == 0;
}

/* The probability that sample_bsdf() picks the diffuse lobe: its mean
 * albedo over all lobes' mean reflectance (mirror or blend). */
static real
diffuse_lobe_probability(const struct material *m, vec3 albedo)
{
    bool has_mirror = m->kind == MAT_MIRROR || m->kind == MAT_BLEND;
    real diffuse = albedo.x + albedo.y + albedo.z;
    real mirror = has_mirror ? m->reflectance.x + m->reflectance.y + m->reflectance.z : 0;
    return diffuse > 0 ? diffuse / (diffuse + mirror) : 0;
}

/* What a path draws its numbers for at each vertex (the Sobol sampler
 * gives each its own sequence). */
enum draw_use {
    DRAW_LOBE,
    DRAW_DIRECTION,
    DRAW_ROULETTE,
    DRAW_LIGHT, /* the shadow rays' (light.c derives one sequence per light) */
};

/* The sequence of one use at one depth: a seed of its own in the family
 * of the pixel's key (the camera samples' sequence is the key's own). */
static uint64_t
draw_seed(const struct path *path, enum draw_use use)
{
    return lowdisc_family_seed(path->id.key, ((uint64_t)path->depth << 8) | (uint64_t)use);
}

/* Next-event estimation: the direct light reaching the diffuse part of the
 * surface at h, by shadow rays to the lights (light.c), times albedo / pi;
 * with MIS, each shadow ray weighted against the diffuse bounce, whose
 * density is P(diffuse) cos(theta) / pi. */
static vec3
direct_light(
    const struct renderer *renderer,
    const struct hit *h,
    const struct material *m,
    vec3 albedo,
    const struct path *path,
    struct rng *rng,
    struct stats *st)
{
    struct shadow_sampling sampling = renderer->shadow;
    if (!renderer->nee) {
        sampling.samples = 0; /* area lights are left to the paths that hit them */
        sampling.adaptive[0] = 0;
    }
    if (mis_on(renderer)) {
        sampling.bsdf_pdf_cos = diffuse_lobe_probability(m, albedo) * INV_PI;
    }
    if (renderer->sampler == SAMPLER_SOBOL && sampling.adaptive[0] == 0) {
        /* The adaptive rays' count varies from vertex to vertex: they keep
         * the random stream. */
        sampling.lowdisc = true;
        sampling.lowdisc_seed = draw_seed(path, DRAW_LIGHT);
        sampling.lowdisc_index = path->id.index;
    }
    vec3 e = direct_irradiance(&renderer->world, h, &sampling, &renderer->lights, rng, st);
    return vec3_scale(vec3_mul(albedo, e), INV_PI);
}

/* Emitted radiance the path finds at a light it hit.  With next-event
 * estimation on, light found by a diffuse bounce was already counted by the
 * shadow rays at the previous vertex: only camera rays and specular bounces,
 * which shadow rays cannot imitate, count it here. */
static vec3
emitted(const struct renderer *renderer, const struct hit *h, const struct path *path)
{
    /* LAB 07: emission */
    bool counted_by_nee = renderer->nee && !path->specular;
    if (counted_by_nee) {
        return vec3_splat(0);
    }
    return light_emitted(renderer->scene, h->light, h->front_face);
    /* END LAB */
}

/* The light a diffuse bounce found, with MIS: Le weighted against the
 * shadow rays of the vertex it left (path->from), which could have drawn
 * the same point with density *pdf_light (light_pdf(), per steradian);
 * *weight is the bounce's power-heuristic weight. */
static vec3
emitted_mis(
    const struct renderer *renderer,
    const struct hit *h,
    const struct path *path,
    real *pdf_light,
    real *weight)
{
    const struct scene *s = renderer->scene;
    *pdf_light = light_pdf(s, &renderer->shadow, &renderer->lights, h->light, path->from, h->p);
    real samples = (real)renderer->shadow.samples;
    *weight = mis_power_heuristic(1, path->pdf_bsdf, samples, *pdf_light);
    return vec3_scale(light_emitted(s, h->light, h->front_face), *weight);
}

/* Three uniform numbers in [0, 1) for this vertex's bounce: u[0] picks
 * the lobe, u[1] and u[2] the direction.  The Sobol sampler draws u[0]
 * only for the materials with a choice to make (glass: reflect or refract;
 * blend: which lobe); the others never read it. */
static void
bounce_numbers(
    const struct renderer *renderer,
    const struct material *m,
    const struct path *path,
    struct rng *rng,
    real u[3])
{
    if (renderer->sampler == SAMPLER_SOBOL) {
        bool choice = m->kind == MAT_GLASS || m->kind == MAT_BLEND;
        uint32_t index = path->id.index_reversed;
        u[0] = choice ? lowdisc_point1_reversed(index, draw_seed(path, DRAW_LOBE)) : 0;
        lowdisc_point2_reversed(index, draw_seed(path, DRAW_DIRECTION), &u[1], &u[2]);
        return;
    }
    for (int i = 0; i < 3; i++) {
        u[i] = rng_uniform(rng);
    }
}

vec3
shade(
    const struct renderer *renderer,
    ray *r,
    const struct hit *h,
    struct path *path,
    struct rng *rng,
    struct stats *st)
{
    const struct scene *s = renderer->scene;
    if (h->light >= 0) {
        /* Lights are black as surfaces (SCENES.md): the path ends here. */
        real pdf_light = 0;
        real weight = 1;
        vec3 le = path->pdf_bsdf > 0 ? emitted_mis(renderer, h, path, &pdf_light, &weight)
                                     : emitted(renderer, h, path);
        vec3 l = vec3_mul(path->beta, le);
        inspect_emission(st, l, path->specular);
        inspect_mis(st, pdf_light, path->pdf_bsdf, weight); /* only where MIS weighed it */
        path->beta = vec3_splat(0);
        return l;
    }
    if (path->depth >= renderer->max_depth) {
        /* No ray may follow this vertex: not a shadow ray, not a bounce. */
        inspect_end(st, "max-depth: no ray may follow this vertex");
        path->beta = vec3_splat(0);
        return vec3_splat(0);
    }
    const struct material *m = &s->materials[h->material];
    vec3 albedo = diffuse_albedo(m, h);
    vec3 l = vec3_splat(0);
    if (!vec3_is_zero(albedo)) {
        l = vec3_mul(path->beta, direct_light(renderer, h, m, albedo, path, rng, st));
        inspect_nee(st, l);
    }
    struct bsdf_sample bs = {0};
    real u[3];
    bounce_numbers(renderer, m, path, rng, u);
    if (!sample_bsdf(m, albedo, h, r->d, u, &bs)) {
        inspect_end(st, "no bounce: nothing reflects here, or the direction is below the surface");
        path->beta = vec3_splat(0);
        return l;
    }
    inspect_bounce(st, bs.lobe, bs.d, bs.pdf, path->beta, vec3_mul(path->beta, bs.weight));
    path->beta = vec3_mul(path->beta, bs.weight);
    path->specular = bs.specular;
    path->pdf_bsdf = 0;
    if (!bs.specular && mis_on(renderer)) {
        /* The density of the diffuse direction: P(diffuse) cos(theta) / pi. */
        path->pdf_bsdf = diffuse_lobe_probability(m, albedo) * vec3_dot(h->n, bs.d) * INV_PI;
        path->from = h->p;
    }
    *r = spawn_ray(h, bs.d);
    st->rays_secondary++;
    return l;
}

/* Russian roulette (Arvo and Kirk, "Particle Transport and Image Synthesis",
 * 1990): past the first few bounces a path survives with probability q
 * taken from its throughput, and a survivor's throughput is divided by q, so
 * the expected value is unchanged while dim paths stop early.  With
 * q = max(beta) / threshold a survivor carries the throughput `threshold`
 * (in its largest channel): roulette holds the paths' weights near that
 * level, as the weight windows of neutron transport do (used for light
 * by Vorba and Krivanek, "Adjoint-Driven Russian Roulette and Splitting
 * in Light Transport Simulation", 2016), instead of raising them to 1,
 * which made each rare long path a bright sample.  Returns q (1 before
 * min_depth). */
static real
russian_roulette(struct path *path, int min_depth, real threshold, real u)
{
    /* LAB 07: Russian roulette */
    if (path->depth < min_depth) {
        return 1;
    }
    real q = fmin(vec3_max_comp(path->beta) / threshold, (real)RR_MAX_SURVIVAL);
    if (u >= q) {
        path->beta = vec3_splat(0);
    } else {
        path->beta = vec3_scale(path->beta, 1 / q);
    }
    return q;
    /* END LAB */
}

/* The uniform number Russian roulette draws at this vertex.  The Sobol
 * sampler draws none before the roulette starts (0: unused). */
static real
roulette_number(const struct renderer *renderer, const struct path *path, struct rng *rng)
{
    if (renderer->sampler == SAMPLER_SOBOL) {
        if (path->depth < renderer->rr_depth) {
            return 0;
        }
        return lowdisc_point1_reversed(path->id.index_reversed, draw_seed(path, DRAW_ROULETTE));
    }
    return rng_uniform(rng);
}

vec3
trace(
    const struct renderer *renderer,
    ray r,
    int depth,
    struct sample_id id,
    struct rng *rng,
    struct stats *st)
{
    struct path path = {.beta = vec3_splat(1), .specular = true, .depth = depth, .id = id};
    vec3 l = vec3_splat(0);
    while (!vec3_is_zero(path.beta) && path.depth <= renderer->max_depth) {
        struct hit h;
        if (!world_intersect(&renderer->world, r, REAL_MAX, &h, st)) {
            /* The background is a constant environment light. */
            inspect_miss(st, path.depth, r, vec3_mul(path.beta, renderer->scene->background));
            l = vec3_add(l, vec3_mul(path.beta, renderer->scene->background));
            break;
        }
        inspect_hit(st, path.depth, r, &h);
        l = vec3_add(l, shade(renderer, &r, &h, &path, rng, st));
        if (renderer->rr) {
            real u = roulette_number(renderer, &path, rng);
            real q = russian_roulette(&path, renderer->rr_depth, renderer->rr_threshold, u);
            inspect_roulette(st, q, u, !vec3_is_zero(path.beta));
        }
        path.depth++;
    }
    return l;
}

/* Position (in [0,1)^2 of the pixel) of sample i of n, in cell i of a
 * k x m grid over the pixel (k m = n, as square as n allows).  Grid: the
 * cell's centre.  Jitter: a uniform point in the cell, which keeps every
 * sample unbiased and no two crowded together (Cook, "Stochastic Sampling
 * in Computer Graphics", 1986). */
static void
sample_position(int pattern, int i, int n, struct rng *rng, real *dx, real *dy)
{
    /* LAB 06: sample position */
    int k = strata_columns(n);
    int m = n / k;
    real u = pattern == AA_GRID ? (real)0.5 : rng_uniform(rng);
    real v = pattern == AA_GRID ? (real)0.5 : rng_uniform(rng);
    *dx = ((real)(i % k) + u) / (real)k;
    *dy = ((real)(i / k) + v) / (real)m;
    /* END LAB */
}

static real
luminance(vec3 c)
{
    return (real)0.2126 * c.x + (real)0.7152 * c.y + (real)0.0722 * c.z;
}

/* Place i (0 <= i < n) takes in a random order of 0 .. n-1 chosen by key.
 * Steps that are invertible on b bits, 2^b >= n (xor with the key,
 * multiplication by an odd number, xor with a right shift of itself),
 * permute 0 .. 2^b - 1; a result past n is permuted again until it falls
 * below n (cycle walking, Black and Rogaway, "Ciphers with Arbitrary Finite
 * Domains", 2002; Kensler, "Correlated Multi-Jittered Sampling", 2013).  A
 * rotation by an offset from the key ends it, so that every place is
 * exactly equally likely for every i. */
static int
shuffled_index(int i, int n, uint64_t key)
{
    uint32_t mask = (uint32_t)n - 1;
    int bits = 0;
    for (int s = 1; s < 32; s *= 2) {
        mask |= mask >> s;
    }
    for (uint32_t m = mask; m; m >>= 1) {
        bits++;
    }
    int shift = bits / 2 > 0 ? bits / 2 : 1;
    uint32_t x = (uint32_t)i;
    do {
        for (int round = 0; round < 4; round++) {
            x = (x ^ (uint32_t)(key >> (16 * round))) & mask;
            x = (x * 0x9e3779b1u) & mask; /* odd: invertible modulo 2^b */
            x ^= x >> shift;
        }
    } while (x >= (uint32_t)n);
    uint32_t offset = (uint32_t)(rng_mix64(key) % (uint64_t)n);
    return (int)((x + offset) % (uint32_t)n);
}

/* The sum of samples first .. first + count - 1 of the spp of pixel
 * (px, py); widens [*lum_min, *lum_max] to the range of their luminances.
 * Sample i goes to cell shuffled_index(i) of the pattern's grid of spp
 * cells: the passes together fill every cell once, and the cells of any
 * one pass are spread over the whole pixel, so a render stopped after a
 * few passes is not biased towards part of the pixel.  The Sobol pattern
 * takes point i of a sequence scrambled by the seed and the pixel: each
 * pass's points are an aligned block of it, stratified on their own. */
static vec3
sum_samples(
    const struct renderer *renderer,
    int px,
    int py,
    int pattern,
    int first,
    int count,
    struct rng *rng,
    struct stats *st,
    real *lum_min,
    real *lum_max)
{
    uint64_t key = rng_mix64(renderer->seed ^ rng_mix64(((uint64_t)py << 32) | (uint32_t)px));
    vec3 sum = vec3_splat(0);
    for (int i = first; i < first + count; i++) {
        struct sample_id id = {key, (uint32_t)i, lowdisc_reverse_bits((uint32_t)i)};
        real dx;
        real dy;
        if (pattern == AA_SOBOL) {
            lowdisc_point2_reversed(id.index_reversed, key, &dx, &dy);
        } else {
            int cell = shuffled_index(i, renderer->spp, key);
            sample_position(pattern, cell, renderer->spp, rng, &dx, &dy);
        }
        ray primary = camera_ray(&renderer->camera, (real)px + dx, (real)py + dy);
        st->rays_camera++;
        inspect_sample(st, i, (real)px + dx, (real)py + dy, primary);
        vec3 l = trace(renderer, primary, 1, id, rng, st);
        inspect_sample_done(st, l);
        *lum_min = fmin(*lum_min, luminance(l));
        *lum_max = fmax(*lum_max, luminance(l));
        sum = vec3_add(sum, l);
    }
    return sum;
}

/* Adaptive supersampling (Whitted 1980, Mitchell 1987): a few probe samples;
 * where their contrast (max - min) / (max + min) exceeds the threshold - an
 * edge, a shadow boundary, a texture - the pixel gets all spp samples
 * (here: all spp_pass of this pass). */
static vec3
adaptive_pixel(
    const struct renderer *renderer,
    int px,
    int py,
    int first,
    struct rng *rng,
    struct stats *st)
{
    /* LAB 06: adaptive sampling */
    real lo = REAL_MAX;
    real hi = -REAL_MAX;
    int n = renderer->spp_pass;
    int probes = n < AA_PROBES ? n : AA_PROBES;
    vec3 sum = sum_samples(renderer, px, py, AA_JITTER, first, probes, rng, st, &lo, &hi);
    bool agree = !(hi - lo > renderer->aa_threshold * (hi + lo));
    if (agree || probes == n) {
        return vec3_scale(sum, 1 / (real)probes);
    }
    st->extra[STAT_AA_REFINED]++;
    int rest = n - probes;
    sum = vec3_add(
        sum,
        sum_samples(renderer, px, py, AA_JITTER, first + probes, rest, rng, st, &lo, &hi));
    return vec3_scale(sum, 1 / (real)n);
    /* END LAB */
}

vec3
render_pixel(const void *ctx, int px, int py, int pass, struct rng *rng, struct stats *st)
{
    const struct renderer *renderer = ctx;
    int first = pass * renderer->spp_pass;
    if (renderer->aa == AA_ADAPTIVE) {
        return adaptive_pixel(renderer, px, py, first, rng, st);
    }
    real lo = REAL_MAX;
    real hi = -REAL_MAX;
    int n = renderer->spp_pass;
    vec3 sum = sum_samples(renderer, px, py, renderer->aa, first, n, rng, st, &lo, &hi);
    return vec3_scale(sum, 1 / (real)n);
}
