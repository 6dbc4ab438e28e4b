/*
 * main.c - the stage's program: its options and its render call.  The steps
 * around them (parse the command line, load the scene, write the image and
 * the statistics, the exit status) are the same in every stage: run.h.
 */
#include <stdio.h>

#include "course.h"
#include "render.h"
#include "run.h"

#define SUMMARY "primary rays, closest hit, direct light with hard shadows"

/* The command line: the options every stage shares (cli.h), then this
 * stage's own. */
static bool
parse_command_line(struct run *run, int argc, char **argv)
{
    const struct option_spec stage_options[] = {
        {.name = NULL},
    };
    const struct cli_stage stage = {STAGE_NAME, SUMMARY, stage_options, 1};
    return run_parse(run, argc, argv, &stage);
}

/* What the render passes (--aov, aov.h) ask of the stage: the ray through
 * a point of the film, the first surface along a ray with its albedo, and
 * the ray from a surface towards a point. */
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
    vec3 albedo = m ? diffuse_albedo(m) : vec3_splat(0);
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

/* One ray through each pixel centre, once. */
static int
render(struct renderer *renderer, struct run *run)
{
    struct render_job job = run_job(run, renderer);
    job.tile = render_tile;
    renderer->camera = camera_make(&renderer->scene->camera, job.width, job.height);
    run->aov = (struct aov_source){renderer, pass_camera_ray, pass_first_hit, pass_spawn_ray_to};
    return run_render(run, &job, 1);
}

int
main(int argc, char **argv)
{
    struct renderer renderer = {0};
    struct run run;
    if (!parse_command_line(&run, argc, argv)) {
        return run.status;
    }
    if (run.opt.spp > 1) {
        fprintf(
            stderr,
            "warning: --spp ignored: %s traces one ray through each pixel centre "
            "(06_supersample adds samples per pixel)\n",
            STAGE_NAME);
    }
    if (!run_load_scene(&run, RENDER_FEATURES, course_unmodelled)) {
        return run.status;
    }
    renderer.scene = &run.scene;
    renderer.world = world_make(&run.scene);
    int status = render(&renderer, &run);
    run_free(&run);
    return status;
}
