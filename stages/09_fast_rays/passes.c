/*
 * passes.c - what the render passes (--aov, common/render/aov.h) ask of the
 * stage: the ray through a point of the film, the first surface along a ray
 * with the albedo the stage shades it with, and the ray from a surface
 * towards a point (none in a stage without shadow rays).  Every ray of the
 * passes is the stage's own, so they show what the stage renders.
 */
#include "render.h"

static ray
pass_camera_ray(const void *ctx, real film_x, real film_y)
{
    const struct renderer *renderer = ctx;
    return camera_ray(&renderer->camera, film_x, film_y);
}

static bool
pass_first_hit(const void *ctx, ray r, real t_max, struct aov_hit *out)
{
    const struct renderer *renderer = ctx;
    struct stats uncounted = {0};
    struct hit h;
    if (!world_intersect(&renderer->world, r, t_max, &h, &uncounted)) {
        return false;
    }
    const struct material *m = h.material >= 0 ? &renderer->scene->materials[h.material] : NULL;
    vec3 albedo = m ? diffuse_albedo(m, &h) : vec3_splat(0);
    *out = (struct aov_hit){h.t, h.p, h.n, h.prim, h.material, albedo, h.ng, h.error};
    return true;
}

static ray
pass_spawn_ray_to(const void *ctx, const struct aov_hit *from, vec3 to, real *t_max)
{
    (void)ctx;
    struct hit h = {.p = from->p, .ng = from->ng, .error = from->error};
    return spawn_ray_to(&h, to, t_max);
}

struct aov_source
render_passes_source(const struct renderer *renderer)
{
    return (struct aov_source){renderer, pass_camera_ray, pass_first_hit, pass_spawn_ray_to};
}
