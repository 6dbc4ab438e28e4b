/*
 * main.c - the stage's program: read the options, load the scene, render,
 * write the image and the statistics.  The only file that prints
 * diagnostics or chooses an exit status (CONTRACT.md): 0 success, 1 invalid
 * scene or input file, 2 bad command line, 3 an output could not be written.
 */
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

#define SUMMARY "primary rays, direct light, soft shadows from sampled area lights"

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
    const struct render_result *result)
{
    rep->stage = STAGE_NAME;
    rep->scene = opt->scene_path;
    rep->width = job->width;
    rep->height = job->height;
    rep->spp = result->passes_done;
    rep->threads = job->threads;
    rep->seed = opt->seed;
    rep->seconds_render = result->seconds;
    rep->seconds_render_cpu = result->cpu_seconds;
    rep->counts = result->counts;
    rep->nan_pixels = result->nan_pixels;
    rep->extra_names[STAT_PENUMBRA] = "penumbra_pixels";
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
        .seed = opt->seed,
        .progress = !opt->quiet && isatty(STDERR_FILENO),
        .pixel = render_pixel,
        .ctx = renderer,
    };
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
    fill_report(rep, opt, &job, &result);
    int status = write_outputs(&image, output, opt, rep, start);
    image_free(&image);
    return status;
}

int
main(int argc, char **argv)
{
    double start = clock_seconds();
    struct renderer renderer = {.shadow = {.samples = 16}};
    const struct option_spec stage_options[] = {
        {
            .name = "shadow-samples",
            .kind = OPT_INT,
            .dest = &renderer.shadow.samples,
            .min = 1,
            .max = 1 << 16,
            .arg = "N",
            .help = "shadow rays per area light per shading point (default 16)",
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
    if (opt.spp > 1) {
        fprintf(
            stderr,
            "warning: --spp ignored: %s traces one ray through each pixel centre "
            "(06_supersample adds samples per pixel)\n",
            STAGE_NAME);
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
    render_stop_on_interrupt();
    int status = render_and_write(&renderer, &opt, output, &rep, start);
    scene_free(&scene);
    return status;
}
