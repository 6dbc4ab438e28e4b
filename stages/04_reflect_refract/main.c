/*
 * main.c - the stage's program: its options and its render call.  The steps
 * around them (parse the command line, load the scene, write the image and
 * the statistics, the exit status) are the same in every stage: run.h.
 */
#include <stdio.h>

#include "course.h"
#include "render.h"
#include "run.h"

#define SUMMARY "Whitted ray tracing: soft shadows, mirrors, glass with Fresnel"

/* The command line: the options every stage shares (cli.h), then this
 * stage's own. */
static bool
parse_command_line(struct run *run, int argc, char **argv, struct renderer *renderer)
{
    const struct option_spec stage_options[] = {
        {
            .name = "shadow-samples",
            .kind = OPT_INT,
            .dest = &renderer->shadow.samples,
            .min = 1,
            .max = 1 << 16,
            .arg = "N",
            .help = "shadow rays per area light per shading point (default 16)",
        },
        {
            .name = "adaptive",
            .kind = OPT_INT_PAIR,
            .dest = renderer->shadow.adaptive,
            .min = 1,
            .max = 1 << 16,
            .arg = "K,M",
            .help = "K probe rays per light; M more where they disagree (penumbra)",
        },
        {
            .name = "max-depth",
            .kind = OPT_INT,
            .dest = &renderer->max_depth,
            .min = 1,
            .max = 1 << 16,
            .arg = "N",
            .help = "longest chain of rays, the camera ray included (default 8)",
        },
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
    run->rep.extra_names[STAT_PENUMBRA] = "penumbra_pixels";
    run->aov = render_passes_source(renderer);
    return run_render(run, &job, 1);
}

int
main(int argc, char **argv)
{
    struct renderer renderer = {.shadow = {.samples = 16}, .max_depth = 8};
    struct run run;
    if (!parse_command_line(&run, argc, argv, &renderer)) {
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
    struct light_picker picker;
    struct diag err;
    if (!light_picker_build(&run.scene, light_weight_area, &picker, &err)) {
        return run_fail(&run, &err, EXIT_RESOURCES);
    }
    renderer.shadow.picker = &picker;
    int status = render(&renderer, &run);
    light_picker_free(&picker);
    run_free(&run);
    return status;
}
