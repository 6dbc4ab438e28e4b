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

/* One ray through each pixel centre, once. */
static int
render(struct renderer *renderer, struct run *run)
{
    struct render_job job = run_job(run, renderer);
    job.tile = render_tile;
    renderer->camera = camera_make(&renderer->scene->camera, job.width, job.height);
    run->aov = render_passes_source(renderer);
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
