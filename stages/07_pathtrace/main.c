/*
 * main.c - the stage's program: read the options, load the scene, render,
 * write the image and the statistics.  The only file that prints
 * diagnostics or chooses an exit status (CONTRACT.md): 0 success, 1 invalid
 * scene or input file, 2 bad command line, 3 an output could not be written.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "cli.h"
#include "driver.h"
#include "feature_table.h"
#include "image.h"
#include "render.h"
#include "scene.h"
#include "stats.h"

#define SUMMARY "Monte Carlo path tracing with next-event estimation and Russian roulette"

enum exit_status {
    EXIT_OK = 0,
    EXIT_INPUT = 1,
    EXIT_USAGE = 2,
    EXIT_OUTPUT = 3,
    EXIT_INTERRUPTED = 130, /* the shell's code for death by SIGINT */
};

/* Refuse an output name we cannot write before spending time rendering. */
static bool
check_output(const char *path, struct diag *err)
{
    enum image_format format = image_format_from_path(path);
    if (format == IMAGE_FORMAT_UNKNOWN) {
        diag_set(
            err,
            NULL,
            0,
            0,
            "cannot tell the format of '%s': use .png, .ppm, .pfm or .exr",
            path);
        return false;
    }
    if (format == IMAGE_FORMAT_EXR && !image_exr_available()) {
        diag_set(
            err,
            NULL,
            0,
            0,
            "'%s': built without OpenEXR; install libopenexr-dev and rebuild to write .exr",
            path);
        return false;
    }
    return true;
}

/* Camera samples per pixel: --spp, 64 by default, or as many as --time
 * allows; the grid pattern needs a square number. */
static bool
choose_spp(struct renderer *renderer, const struct options *opt, struct diag *err)
{
    int unlimited = 1 << 24;
    renderer->spp = opt->spp ? opt->spp : renderer->time_limit > 0 ? unlimited : 64;
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

/* Say, once per feature, what this stage does not model; under --strict
 * that is an error.  Returns false when the scene is refused. */
static bool
report_unmodelled(const struct scene *scene, bool strict)
{
    struct diag notes[FEAT_COUNT];
    int n = features_unmodelled(scene, RENDER_FEATURES, STAGE_NAME, notes, FEAT_COUNT);
    for (int i = 0; i < n; i++) {
        diag_print(stderr, &notes[i], strict ? "error" : "warning");
    }
    return !(strict && n > 0);
}

/* -W alone keeps the scene's aspect ratio; -H alone likewise. */
static void
image_size(const struct scene *scene, const struct options *opt, int *width, int *height)
{
    double aspect = (double)scene->height / scene->width;
    *width = scene->width;
    *height = scene->height;
    if (opt->width && opt->height) {
        *width = opt->width;
        *height = opt->height;
    } else if (opt->width) {
        *width = opt->width;
        *height = (int)(opt->width * aspect + 0.5) > 0 ? (int)(opt->width * aspect + 0.5) : 1;
    } else if (opt->height) {
        *height = opt->height;
        *width = (int)(opt->height / aspect + 0.5) > 0 ? (int)(opt->height / aspect + 0.5) : 1;
    }
}

static void
fill_report(
    struct report *rep,
    const struct options *opt,
    const struct render_job *job,
    const struct render_result *result,
    int spp_per_pass)
{
    rep->stage = STAGE_NAME;
    rep->scene = opt->scene_path;
    rep->width = job->width;
    rep->height = job->height;
    rep->spp = result->passes_done * spp_per_pass;
    rep->threads = job->threads;
    rep->seed = opt->seed;
    rep->seconds_render = result->seconds;
    rep->seconds_render_cpu = result->cpu_seconds;
    rep->counts = result->counts;
    rep->nan_pixels = result->nan_pixels;
    rep->extra_names[STAT_PENUMBRA] = "penumbra_pixels";
    rep->extra_names[STAT_AA_REFINED] = "aa_refined_pixels";
}

/* Write the image and the statistics; returns the exit status. */
static int
write_outputs(
    const struct image *image,
    const char *output,
    const struct options *opt,
    struct report *rep,
    double start)
{
    struct diag err;
    if (!image_write(image, output, &err)) {
        diag_print(stderr, &err, "error");
        return EXIT_OUTPUT;
    }
    rep->seconds_total = clock_seconds() - start;
    rep->peak_rss_bytes = peak_rss_bytes();
    if (!opt->quiet) {
        report_print(stderr, rep);
    }
    if (opt->stats_path && !report_write_json(rep, opt->stats_path, &err)) {
        diag_print(stderr, &err, "error");
        return EXIT_OUTPUT;
    }
    return EXIT_OK;
}

/* Build the BVH (unless --no-bvh) and report its shape. */
static bool
build_acceleration(struct renderer *renderer, bool use_bvh, struct report *rep, struct diag *err)
{
    if (!use_bvh) {
        return true;
    }
    double start = clock_seconds();
    if (!world_build_bvh(&renderer->world, err)) {
        return false;
    }
    const struct bvh *bvh = &renderer->world.bvh;
    rep->seconds_build = clock_seconds() - start;
    report_set(rep, "bvh_nodes", bvh->n_nodes, true);
    report_set(rep, "bvh_depth", bvh->depth, true);
    report_set(rep, "bvh_max_leaf", bvh->max_leaf, true);
    report_set(rep, "bvh_mean_leaf", bvh->mean_leaf, false);
    report_set(rep, "bvh_bytes", (double)bvh->bytes, true);
    return true;
}

/* Samples per pixel in one pass: the largest divisor of spp up to 16, so
 * a pass is short (a Ctrl-C loses little) yet stratified. */
static int
samples_per_pass(int spp)
{
    int per_pass = spp < 16 ? spp : 16;
    while (spp % per_pass != 0) {
        per_pass--;
    }
    return per_pass;
}

static int
render_and_write(
    struct renderer *renderer,
    const struct options *opt,
    const char *output,
    struct report *rep,
    double start)
{
    const struct scene *scene = renderer->scene;
    struct render_job job = {
        .threads = cli_thread_count(opt),
        .passes = 1,
        .time_limit = renderer->time_limit,
        .seed = opt->seed,
        .progress = !opt->quiet && isatty(STDERR_FILENO),
        .pass_pixel = render_pixel,
        .ctx = renderer,
    };
    /* Progressive: the image is built in passes of a few samples per pixel,
     * placed together by the --aa pattern (render.c), so it can be stopped (Ctrl-C,
     * --time) after any pass. */
    renderer->spp_pass = samples_per_pass(renderer->spp);
    renderer->seed = opt->seed;
    job.passes = renderer->spp / renderer->spp_pass;
    image_size(scene, opt, &job.width, &job.height);
    renderer->camera = camera_make(&scene->camera, job.width, job.height);
    struct image image = {0};
    struct render_result result;
    struct diag err;
    if (!render_image(&job, &image, &result, &err)) {
        diag_print(stderr, &err, "error");
        return EXIT_INPUT;
    }
    if (result.passes_done == 0) {
        fprintf(stderr, "interrupted before the image was complete; nothing written\n");
        image_free(&image);
        return EXIT_INTERRUPTED;
    }
    if (result.interrupted) {
        fprintf(
            stderr,
            "interrupted: writing the image after %d complete passes\n",
            result.passes_done);
    }
    fill_report(rep, opt, &job, &result, renderer->spp_pass);
    int status = write_outputs(&image, output, opt, rep, start);
    image_free(&image);
    return status;
}

int
main(int argc, char **argv)
{
    double start = clock_seconds();
    struct renderer renderer = {
        .shadow = {.samples = 1},
        .max_depth = 1 << 16,
        .aa = AA_JITTER,
        .aa_threshold = (real)0.05,
        .nee = true,
        .rr = true,
    };
    bool use_bvh = true;
    const struct option_spec stage_options[] = {
        {
            .name = "shadow-samples",
            .kind = OPT_INT,
            .dest = &renderer.shadow.samples,
            .min = 1,
            .max = 1 << 16,
            .arg = "N",
            .help = "shadow rays per area light per path vertex (default 1)",
        },
        {
            .name = "adaptive",
            .kind = OPT_INT_PAIR,
            .dest = renderer.shadow.adaptive,
            .min = 1,
            .max = 1 << 16,
            .arg = "K,M",
            .help = "K probe rays per light; M more where they disagree (penumbra)",
        },
        {
            .name = "max-depth",
            .kind = OPT_INT,
            .dest = &renderer.max_depth,
            .min = 1,
            .max = 1 << 16,
            .arg = "N",
            .help = "longest path, the camera ray included (default 65536: unbounded)",
        },
        {
            .name = "no-bvh",
            .kind = OPT_UNSET,
            .dest = &use_bvh,
            .help = "test every primitive for every ray (the brute-force reference)",
        },
        {
            .name = "aa",
            .kind = OPT_CHOICE,
            .dest = &renderer.aa,
            .choices = "grid|jitter|adaptive",
            .arg = "PATTERN",
            .help = "where camera samples go in a pixel: grid, jitter (default), adaptive",
        },
        {
            .name = "aa-threshold",
            .kind = OPT_REAL,
            .dest = &renderer.aa_threshold,
            .min = 0,
            .max = 1,
            .arg = "T",
            .help = "adaptive: refine pixels whose probe contrast exceeds T (default 0.05)",
        },
        {
            .name = "no-nee",
            .kind = OPT_UNSET,
            .dest = &renderer.nee,
            .help = "no shadow rays to area lights: paths must hit them",
        },
        {
            .name = "no-rr",
            .kind = OPT_UNSET,
            .dest = &renderer.rr,
            .help = "no Russian roulette: paths end only at max-depth or when nothing reflects",
        },
        {
            .name = "time",
            .kind = OPT_REAL,
            .dest = &renderer.time_limit,
            .min = 0,
            .max = 1e9,
            .arg = "SECONDS",
            .help = "stop after the pass that ends past this time budget",
        },
        {.name = NULL},
    };
    const struct cli_stage stage = {STAGE_NAME, SUMMARY, stage_options};
    struct options opt;
    struct diag err;
    switch (cli_parse(argc, argv, &opt, &stage, stdout, &err)) {
    case CLI_EXIT:
        return EXIT_OK;
    case CLI_ERROR:
        diag_print(stderr, &err, "error");
        return EXIT_USAGE;
    case CLI_OK:
        break;
    }
    char default_output[1024];
    const char *output = cli_output_path(&opt, default_output, sizeof default_output);
    if (!check_output(output, &err)) {
        diag_print(stderr, &err, "error");
        return EXIT_USAGE;
    }
    if (!choose_spp(&renderer, &opt, &err)) {
        diag_print(stderr, &err, "error");
        return EXIT_USAGE;
    }
    struct scene scene = {0};
    if (!scene_load(opt.scene_path, &scene, &err)) {
        diag_print(stderr, &err, "error");
        return EXIT_INPUT;
    }
    if (!report_unmodelled(&scene, opt.strict)) {
        scene_free(&scene);
        return EXIT_INPUT;
    }
    struct report rep = {0};
    rep.seconds_load = clock_seconds() - start;
    renderer.scene = &scene;
    renderer.world = world_make(&scene);
    if (!light_picker_build(&renderer.lights, &scene, &err)
        || !build_acceleration(&renderer, use_bvh, &rep, &err)) {
        diag_print(stderr, &err, "error");
        light_picker_free(&renderer.lights);
        scene_free(&scene);
        return EXIT_INPUT;
    }
    render_stop_on_interrupt();
    int status = render_and_write(&renderer, &opt, output, &rep, start);
    light_picker_free(&renderer.lights);
    world_free(&renderer.world);
    scene_free(&scene);
    return status;
}
