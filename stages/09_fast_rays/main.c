/*
 * main.c - the stage's program: its options and its render call.  The steps
 * around them (parse the command line, load the scene, write the image and
 * the statistics, the exit status) are the same in every stage: run.h.
 */
#include <math.h>
#include <stdlib.h>

#include "course.h"
#include "render.h"
#include "run.h"

#define SUMMARY "Path tracing with variance reduction: Sobol points, MIS, a light picker"
#define SPP_DEFAULT 64 /* camera samples per pixel without --spp */

/* The command line: the options every stage shares (cli.h), then this
 * stage's own. */
static bool
parse_command_line(struct run *run, int argc, char **argv, struct renderer *renderer, bool *use_bvh)
{
    const struct option_spec stage_options[] = {
        {
            .name = "shadow-samples",
            .kind = OPT_INT,
            .dest = &renderer->shadow.samples,
            .min = 1,
            .max = 1 << 16,
            .arg = "N",
            .help = "shadow rays per area light per path vertex (default 1)",
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
            .help = "longest path, the camera ray included (default 65536: unbounded)",
        },
        {
            .name = "no-bvh",
            .kind = OPT_UNSET,
            .dest = use_bvh,
            .help = "test every primitive for every ray (the brute-force reference)",
        },
        {
            .name = "rr-depth",
            .kind = OPT_INT,
            .dest = &renderer->rr_depth,
            .min = 1,
            .max = 1 << 16,
            .arg = "N",
            .help = "Russian roulette from the N-th ray on, camera ray = 1 (default 3)",
        },
        {
            .name = "rr-threshold",
            .kind = OPT_REAL,
            .dest = &renderer->rr_threshold,
            .min = 0.001,
            .max = 1,
            .arg = "T",
            .help = "roulette: survive with probability max(throughput) / T (default 0.4)",
        },
        {
            .name = "sampler",
            .kind = OPT_CHOICE,
            .dest = &renderer->sampler,
            .choices = "independent|sobol",
            .arg = "KIND",
            .help = "random numbers of the paths: independent, sobol (default)",
        },
        {
            .name = "brute-force-max",
            .kind = OPT_INT,
            .dest = &renderer->brute_force_max,
            .min = 0,
            .max = 1 << 30,
            .arg = "N",
            .help = "no BVH for scenes of at most N primitives (default 16; 0: always a BVH)",
        },
        {
            .name = "aa",
            .kind = OPT_CHOICE,
            .dest = &renderer->aa,
            .choices = "grid|jitter|adaptive",
            .arg = "PATTERN",
            .help = "where camera samples go in a pixel: grid, jitter (default), adaptive",
        },
        {
            .name = "aa-threshold",
            .kind = OPT_REAL,
            .dest = &renderer->aa_threshold,
            .min = 0,
            .max = 1,
            .arg = "T",
            .help = "adaptive: refine pixels whose probe contrast exceeds T (default 0.05)",
        },
        {
            .name = "no-nee",
            .kind = OPT_UNSET,
            .dest = &renderer->nee,
            .help = "no shadow rays to area lights: paths must hit them",
        },
        {
            .name = "no-rr",
            .kind = OPT_UNSET,
            .dest = &renderer->rr,
            .help = "no Russian roulette: paths end only at max-depth or when nothing reflects",
        },
        {
            .name = "no-mis",
            .kind = OPT_UNSET,
            .dest = &renderer->shadow.mis,
            .help = "no multiple importance sampling: a light a diffuse bounce hits adds nothing",
        },
        {
            .name = "no-light-pick",
            .kind = OPT_UNSET,
            .dest = &renderer->pick_lights,
            .help = "emitting triangles picked by area (stage 07's way), not by power",
        },
        {
            .name = "time",
            .kind = OPT_REAL,
            .dest = &renderer->time_limit,
            .min = 0,
            .max = 1e9,
            .arg = "SECONDS",
            .help = "stop after the pass that ends past this time budget",
        },
        {.name = NULL},
    };
    const struct cli_stage stage = {STAGE_NAME, SUMMARY, stage_options, SPP_DEFAULT};
    return run_parse(run, argc, argv, &stage);
}

/* Camera samples per pixel: --spp, 64 by default, or as many as --time
 * allows; the grid pattern needs a square number. */
static bool
choose_spp(struct renderer *renderer, const struct options *opt, struct diag *err)
{
    int unlimited = 1 << 24;
    renderer->spp = opt->spp ? opt->spp : renderer->time_limit > 0 ? unlimited : SPP_DEFAULT;
    int k = (int)sqrt((double)renderer->spp);
    if (renderer->aa == AA_GRID && k * k != renderer->spp) {
        diag_set(
            err,
            NULL,
            0,
            0,
            "--aa grid needs a square --spp (1, 4, 9, 16, ...), got %d",
            renderer->spp);
        return false;
    }
    return true;
}

/* Progressive rendering: spp camera samples per pixel as passes of a few
 * samples, each pass a pattern of its own, so that --time or a Ctrl-C can
 * stop the render after any pass and the image is the mean of the passes
 * done.  A pass takes the largest divisor of spp up to 16: short (a stop
 * loses little), yet stratified.  Returns the samples of one pass. */
static int
progressive_passes(struct render_job *job, int spp, double time_limit)
{
    int per_pass = spp < 16 ? spp : 16;
    while (spp % per_pass != 0) {
        per_pass--;
    }
    job->passes = spp / per_pass;
    job->time_limit = time_limit;
    return per_pass;
}

/* spp camera rays through each pixel, in passes. */
static int
render(struct renderer *renderer, struct run *run)
{
    struct render_job job = run_job(run, renderer);
    job.tile = render_tile;
    /* renderer->spp becomes a pass's. */
    renderer->spp = progressive_passes(&job, renderer->spp, renderer->time_limit);
    renderer->camera = camera_make(&renderer->scene->camera, job.width, job.height);
    run->rep.extra_names[STAT_PENUMBRA] = "penumbra_pixels";
    run->rep.extra_names[STAT_AA_REFINED] = "aa_refined_pixels";
    run->aov = render_passes_source(renderer);
    return run_render(run, &job, renderer->spp);
}

int
main(int argc, char **argv)
{
    struct renderer renderer = {
        .shadow = {.samples = 1, .mis = true},
        .max_depth = 1 << 16,
        .aa = AA_JITTER,
        .aa_threshold = (real)0.05,
        .nee = true,
        .rr = true,
        .rr_depth = RR_MIN_DEPTH,
        .rr_threshold = (real)RR_THRESHOLD,
        .sampler = SAMPLER_SOBOL,
        .brute_force_max = BRUTE_FORCE_MAX_PRIMS,
        .pick_lights = true,
    };
    bool use_bvh = true;
    struct run run;
    if (!parse_command_line(&run, argc, argv, &renderer, &use_bvh)) {
        return run.status;
    }
    struct diag err;
    if (!choose_spp(&renderer, &run.opt, &err)) {
        return run_fail(&run, &err, EXIT_USAGE);
    }
    if (!run_load_scene(&run, RENDER_FEATURES, course_unmodelled)) {
        return run.status;
    }
    renderer.scene = &run.scene;
    renderer.world = world_make(&run.scene);
    /* Testing a few primitives costs less than a tree (docs/stages/08_*.md). */
    use_bvh = use_bvh && renderer.world.n_prims > renderer.brute_force_max;
    /* MIS refines the fixed shadow rays (not the adaptive ones). */
    bool fixed = renderer.nee && renderer.shadow.adaptive[0] == 0;
    renderer.shadow.mis = renderer.shadow.mis && fixed;
    light_weight_fn weight = renderer.pick_lights ? light_weight_power : light_weight_area;
    struct light_picker picker;
    if (!light_picker_build(&run.scene, weight, &picker, &err)) {
        return run_fail(&run, &err, EXIT_RESOURCES);
    }
    renderer.shadow.picker = &picker;
    double start = stats_clock_seconds(); /* the tree, unless --no-bvh; its size in --stats */
    if (use_bvh && !bvh_build(&renderer.world.bvh, &renderer.world, &err)) {
        light_picker_free(&picker);
        return run_fail(&run, &err, EXIT_RESOURCES);
    }
    run.rep.seconds_build = use_bvh ? stats_clock_seconds() - start : 0;
    stats_report_set(&run.rep, "bvh_nodes", renderer.world.bvh.n_nodes, true);
    stats_report_set(&run.rep, "bvh_aside", renderer.world.bvh.n_aside, true);
    int status = render(&renderer, &run);
    light_picker_free(&picker);
    bvh_free(&renderer.world.bvh);
    run_free(&run);
    return status;
}
