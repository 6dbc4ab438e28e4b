/*
 * render.c - ray casting: for each pixel, the first surface seen through its
 * centre, lit directly by the lights (no shadows) and by the ambient term.
 */
#include "render.h"

#include "inspect.h"
#include "light.h"

/* The Lambertian albedo this stage shades a material with.  Materials whose
 * optics arrive in a later stage get the simplification ../course.c
 * states for them. */
vec3
diffuse_albedo(const struct material *m)
{
    switch (m->kind) {
    case MAT_DIFFUSE:
    case MAT_BLEND:
        return m->albedo;
    case MAT_MIRROR:
        return m->reflectance;
    case MAT_GLASS:
        return vec3_splat(1);
    case MAT_CHECKER:
        return vec3_scale(vec3_add(m->albedo, m->albedo2), (real)0.5);
    }
    return m->albedo;
}

vec3
shade(const struct renderer *renderer, const struct hit *h, struct stats *st)
{
    const struct scene *s = renderer->scene;
    vec3 albedo = diffuse_albedo(&s->materials[h->material]);
    /* Lambert: L = (albedo / pi) E, plus the ambient term albedo * L_ambient. */
    vec3 e = direct_irradiance(s, h);
    vec3 reflected = vec3_scale(e, INV_PI);
    vec3 l = vec3_mul(albedo, vec3_add(reflected, s->ambient));
    inspect_shade(st, albedo, e, s->ambient, l);
    return l;
}

vec3
trace(const struct renderer *renderer, ray r, struct stats *st)
{
    struct hit h;
    if (!world_intersect(&renderer->world, r, REAL_MAX, &h, st)) {
        inspect_miss(st, 1, r, renderer->scene->background);
        return renderer->scene->background;
    }
    inspect_hit(st, 1, r, &h);
    return shade(renderer, &h, st);
}

vec3
render_pixel(const struct renderer *renderer, int px, int py, struct stats *st)
{
    real x = (real)px + (real)0.5;
    real y = (real)py + (real)0.5;
    ray primary = camera_ray(&renderer->camera, x, y);
    st->rays_camera++;
    inspect_sample(st, 0, x, y, primary);
    vec3 l = trace(renderer, primary, st);
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
            tile_put(tile, px, py, render_pixel(renderer, px, py, st));
        }
    }
    return true;
}
