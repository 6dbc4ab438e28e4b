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
vec3
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

/* Next-event estimation: the direct light reaching the diffuse part of the
 * surface at h, by shadow rays to the lights (light.c), times albedo / pi. */
static vec3
direct_light(
    const struct renderer *renderer,
    const struct hit *h,
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
    sampling.id = path->id;
    sampling.depth = path->depth;
    vec3 e = direct_irradiance(&renderer->world, h, &sampling, rng, st);
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
        vec3 le = path->pdf_bsdf > 0 ? mis_emitted(renderer, h, path) : emitted(renderer, h, path);
        vec3 l = vec3_mul(path->beta, le);
        inspect_emission(st, l, path->specular);
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
        l = vec3_mul(path->beta, direct_light(renderer, h, albedo, path, rng, st));
        inspect_nee(st, l);
    }
    struct bsdf_sample bs = {0};
    real u[3];
    sampler_2d(path->id, path->depth, DRAW_LOBE, rng, &u[0], &u[0]);
    sampler_2d(path->id, path->depth, DRAW_DIRECTION, rng, &u[1], &u[2]);
    if (!sample_bsdf(m, albedo, h, r->d, u, &bs)) {
        inspect_end(st, "no bounce: nothing reflects here, or the direction is below the surface");
        path->beta = vec3_splat(0);
        return l;
    }
    inspect_bounce(st, bs.lobe, bs.d, bs.pdf, path->beta, vec3_mul(path->beta, bs.weight));
    path->beta = vec3_mul(path->beta, bs.weight);
    path->specular = bs.specular;
    /* For MIS (mis.c): where a diffuse bounce left, and its density cos / pi. */
    path->from = h->p;
    path->pdf_bsdf = renderer->shadow.mis && !bs.specular ? vec3_dot(h->n, bs.d) * INV_PI : 0;
    *r = spawn_ray(h, bs.d);
    st->rays_secondary++;
    return l;
}

/* Russian roulette (Arvo and Kirk, "Particle Transport and Image Synthesis",
 * 1990): past the first few bounces a path survives with probability q
 * taken from its throughput, q = max(beta) / threshold (at most RR_MAX_SURVIVAL), and a
 * survivor's throughput is divided by q, so the expected value is unchanged
 * while dim paths stop early.  Returns q (1 before min_depth).  Survivors
 * carry `threshold`, as in weight windows (Vorba and Krivanek,
 * "Adjoint-Driven Russian Roulette and Splitting", 2016). */
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
        /* A path that shade() ended (at an emitter, at the depth limit, with
         * no bounce) plays no roulette: there is nothing left to stop. */
        if (renderer->rr && !vec3_is_zero(path.beta)) {
            real u;
            sampler_2d(path.id, path.depth, DRAW_ROULETTE, rng, &u, &u);
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

/* The sum of n samples of pixel (px, py); widens [*lum_min, *lum_max] to
 * the range of their luminances. */
static vec3
sum_samples(
    const struct renderer *renderer,
    int px,
    int py,
    int pattern,
    int n,
    struct rng *rng,
    struct stats *st,
    real *lum_min,
    real *lum_max)
{
    vec3 sum = vec3_splat(0);
    /* The n samples' Sobol points: a scramble of their own (sampler.h). */
    struct sample_id id = {renderer->sampler, rng_next_u32(rng), 0};
    for (int i = 0; i < n; i++) {
        real dx;
        real dy;
        sample_position(pattern, i, n, rng, &dx, &dy);
        ray primary = camera_ray(&renderer->camera, (real)px + dx, (real)py + dy);
        st->rays_camera++;
        inspect_sample(st, i, (real)px + dx, (real)py + dy, primary);
        id.index = (uint32_t)i;
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
 * edge, a shadow boundary, a texture - the pixel gets all spp samples. */
static vec3
adaptive_pixel(const struct renderer *renderer, int px, int py, struct rng *rng, struct stats *st)
{
    /* LAB 06: adaptive sampling */
    real lo = REAL_MAX;
    real hi = -REAL_MAX;
    int probes = renderer->spp < AA_PROBES ? renderer->spp : AA_PROBES;
    vec3 sum = sum_samples(renderer, px, py, AA_JITTER, probes, rng, st, &lo, &hi);
    bool agree = !(hi - lo > renderer->aa_threshold * (hi + lo));
    if (agree || probes == renderer->spp) {
        return vec3_scale(sum, 1 / (real)probes);
    }
    st->extra[STAT_AA_REFINED]++;
    int rest = renderer->spp - probes;
    sum = vec3_add(sum, sum_samples(renderer, px, py, AA_JITTER, rest, rng, st, &lo, &hi));
    return vec3_scale(sum, 1 / (real)renderer->spp);
    /* END LAB */
}

vec3
render_pixel(const struct renderer *renderer, int px, int py, struct rng *rng, struct stats *st)
{
    if (renderer->aa == AA_ADAPTIVE) {
        return adaptive_pixel(renderer, px, py, rng, st);
    }
    real lo = REAL_MAX;
    real hi = -REAL_MAX;
    vec3 sum = sum_samples(renderer, px, py, renderer->aa, renderer->spp, rng, st, &lo, &hi);
    return vec3_scale(sum, 1 / (real)renderer->spp);
}

bool
render_tile(const void *ctx, const struct tile *tile, struct stats *st)
{
    const struct renderer *renderer = ctx;
    for (int py = tile->y0; py < tile->y1; py++) {
        for (int px = tile->x0; px < tile->x1; px++) {
            if (driver_stop_requested()) {
                return false; /* after the pixel at hand: a stop comes within a second */
            }
            struct rng rng = tile_pixel_rng(tile, px, py); /* the pixel's own stream */
            tile_put(tile, px, py, render_pixel(renderer, px, py, &rng, st));
        }
    }
    return true;
}
