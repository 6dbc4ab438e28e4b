/*
 * render.c - Whitted ray tracing: for each pixel, the first surface seen
 * through its centre, lit directly by the lights it can see and by the
 * ambient term; mirrors and glass send the ray on, recursively.  Area lights
 * are seen as themselves.
 */
#include "render.h"

#include "inspect.h"
#include "optics.h"

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

/* Radiance arriving at h from direction d, along a new ray of the chain;
 * nothing once the chain is max_depth rays long. */
static vec3
trace_on(
    const struct renderer *renderer,
    const struct hit *h,
    vec3 d,
    int depth,
    struct rng *rng,
    struct stats *st)
{
    if (depth >= renderer->max_depth) {
        return vec3_splat(0);
    }
    st->rays_secondary++;
    return trace(renderer, spawn_ray(h, d), depth + 1, rng, st);
}

/* Smooth glass: the reflected and the refracted ray, weighted by the
 * Fresnel reflectance F and 1 - F.  Which side the ray arrives from decides
 * whether it enters (eta = 1 / ior) or leaves (eta = ior). */
static vec3
shade_glass(
    const struct renderer *renderer,
    const struct material *m,
    ray r,
    const struct hit *h,
    int depth,
    struct rng *rng,
    struct stats *st)
{
    /* LAB 04: glass */
    vec3 n = vec3_dot(r.d, h->n) < 0 ? h->n : h->ng;
    real eta = h->front_face ? 1 / m->ior : m->ior;
    real f = fresnel_dielectric(-vec3_dot(r.d, n), eta);
    inspect_specular(st, depth, f < 1 ? "reflect" : "total internal reflection", f, vec3_splat(f));
    vec3 l = vec3_scale(trace_on(renderer, h, reflect(r.d, n), depth, rng, st), f);
    vec3 refracted;
    if (f < 1 && refract(r.d, n, eta, &refracted)) {
        inspect_specular(st, depth, "refract", f, vec3_splat(1 - f));
        l = vec3_madd(l, trace_on(renderer, h, refracted, depth, rng, st), 1 - f);
    }
    return l;
    /* END LAB */
}

vec3
shade(
    const struct renderer *renderer,
    ray r,
    const struct hit *h,
    int depth,
    struct rng *rng,
    struct stats *st)
{
    const struct scene *s = renderer->scene;
    if (h->light >= 0) {
        /* An emitter (one-sided unless two_sided), black as a surface (SCENES.md). */
        vec3 emitted = light_emitted(s, h->light, h->front_face);
        inspect_emission(st, emitted, true);
        return emitted;
    }
    const struct material *m = &s->materials[h->material];
    vec3 albedo = diffuse_albedo(m, h);
    vec3 l = vec3_splat(0);
    if (!vec3_is_zero(albedo)) {
        /* Lambert: L = (albedo / pi) E, plus the ambient term albedo * L_ambient. */
        vec3 e = direct_irradiance(&renderer->world, h, &renderer->shadow, rng, st);
        vec3 reflected = vec3_scale(e, INV_PI);
        l = vec3_mul(albedo, vec3_add(reflected, s->ambient));
        inspect_shade(st, albedo, e, s->ambient, l);
    }
    if (m->kind == MAT_MIRROR || m->kind == MAT_BLEND) {
        inspect_specular(st, depth, "mirror", NAN, m->reflectance);
        vec3 mirrored = trace_on(renderer, h, reflect(r.d, h->n), depth, rng, st);
        l = vec3_add(l, vec3_mul(m->reflectance, mirrored));
    } else if (m->kind == MAT_GLASS) {
        l = vec3_add(l, shade_glass(renderer, m, r, h, depth, rng, st));
    }
    return l;
}

vec3
trace(const struct renderer *renderer, ray r, int depth, struct rng *rng, struct stats *st)
{
    struct hit h;
    if (!world_intersect(&renderer->world, r, REAL_MAX, &h, st)) {
        inspect_miss(st, depth, r, renderer->scene->background);
        return renderer->scene->background;
    }
    inspect_hit(st, depth, r, &h);
    return shade(renderer, r, &h, depth, rng, st);
}

vec3
render_pixel(const struct renderer *renderer, int px, int py, struct rng *rng, struct stats *st)
{
    real x = (real)px + (real)0.5;
    real y = (real)py + (real)0.5;
    ray primary = camera_ray(&renderer->camera, x, y);
    st->rays_camera++;
    inspect_sample(st, 0, x, y, primary);
    vec3 l = trace(renderer, primary, 1, rng, st);
    inspect_sample_done(st, l);
    return l;
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
