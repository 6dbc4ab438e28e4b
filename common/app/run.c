/*
 * run.c - the plumbing around a stage's render (run.h): the steps every
 * stage's main() takes, in the order it takes them.
 */
#include "run.h"

#include <limits.h>
#include <stdint.h>
#include <string.h>
#include <unistd.h>

#include "image.h"
#include "recorder.h"
#include "run_outputs.h"
#include "signals.h"

/* Print err, remember the exit status, and tell the caller to stop. */
static bool
stop(struct run *run, const struct diag *err, int status)
{
    diag_print(stderr, err, "error");
    run->status = status;
    return false;
}

bool
run_check_identities(struct run *run, const struct named_file *inputs, int n_inputs)
{
    struct diag err;
    switch (output_check(run->outputs, run->n_outputs, inputs, n_inputs, &err)) {
    case OUTPUTS_OK:
        return true;
    case OUTPUTS_CLASH:
        return stop(run, &err, EXIT_USAGE);
    case OUTPUTS_UNWRITABLE:
        return stop(run, &err, EXIT_OUTPUT);
    }
    return true;
}

bool
run_parse(struct run *run, int argc, char **argv, const struct cli_stage *stage)
{
    *run = (struct run){.stage = stage->name, .start = stats_clock_seconds(), .status = EXIT_OK};
    struct diag err;
    switch (cli_parse(argc, argv, &run->opt, stage, stdout, &err)) {
    case CLI_EXIT:
        return false;
    case CLI_ERROR:
        return stop(run, &err, EXIT_USAGE);
    case CLI_OK:
        break;
    }
    run->output = cli_output_path(&run->opt, run->default_output, sizeof run->default_output);
    if (run_writes_image(run) && !run_check_image_output(run->output, &err)) {
        return stop(run, &err, EXIT_USAGE);
    }
    if (!run_collect_outputs(run, &err)) {
        return stop(run, &err, EXIT_USAGE);
    }
    const struct named_file scene = {"the scene", run->opt.scene_path};
    return run_check_identities(run, &scene, 1);
}

/* -W alone keeps the scene's aspect ratio; -H alone likewise. */
void
run_image_size(const struct scene *scene, const struct options *opt, int *width, int *height)
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

struct render_job
run_job(const struct run *run, const void *ctx)
{
    struct render_job job = {
        .threads = cli_thread_count(&run->opt),
        .passes = 1,
        .seed = run->opt.seed,
        .progress = !run->opt.quiet && isatty(STDERR_FILENO),
        .ctx = ctx,
    };
    run_image_size(&run->scene, &run->opt, &job.width, &job.height);
    return job;
}

bool
run_check_job(const struct render_job *job, int spp_per_pass, struct diag *err)
{
    /* -W or -H alone scales the other side by the scene's aspect ratio,
     * which can take it past what a scene may ask for. */
    if (job->width > SCENE_MAX_IMAGE_DIM || job->height > SCENE_MAX_IMAGE_DIM) {
        diag_set(
            err,
            NULL,
            0,
            0,
            "the image would be %dx%d pixels (the scene's aspect ratio); each side must be in "
            "[1, %d]: give both -W and -H",
            job->width,
            job->height,
            SCENE_MAX_IMAGE_DIM);
        return false;
    }
    /* The report counts samples per pixel in an int. */
    if (spp_per_pass > INT_MAX / job->passes) {
        diag_set(
            err,
            NULL,
            0,
            0,
            "%d passes of %d samples per pixel: more than %d samples",
            job->passes,
            spp_per_pass,
            INT_MAX);
        return false;
    }
    return true;
}

static void
fill_report(
    struct run *run,
    const struct render_job *job,
    const struct render_result *result,
    int spp_per_pass)
{
    struct report *rep = &run->rep;
    rep->stage = run->stage;
    rep->scene = run->opt.scene_path;
    rep->width = job->width;
    rep->height = job->height;
    rep->spp = result->passes_done * spp_per_pass;
    rep->threads = job->threads;
    rep->seed = run->opt.seed;
    rep->seconds_render = result->seconds;
    rep->seconds_render_cpu = result->cpu_seconds;
    rep->counts = result->counts;
    rep->nan_pixels = result->nan_pixels;
}

/* Render the whole image; EXIT_OK, or the status of a render that failed
 * or was interrupted before its first pass (then nothing is left). */
static int
render_full(const struct render_job *job, struct image *image, struct render_result *result)
{
    struct diag err;
    if (!driver_render_image(job, image, result, &err)) {
        diag_print(stderr, &err, "error");
        return EXIT_RESOURCES;
    }
    if (result->passes_done == 0) {
        fprintf(stderr, "interrupted before the image was complete; nothing written\n");
        image_free(image);
        return EXIT_INTERRUPTED;
    }
    if (result->interrupted) {
        fprintf(
            stderr,
            "interrupted: writing the image after %d complete passes\n",
            result->passes_done);
    }
    return EXIT_OK;
}

/* --pixel names a pixel of the image: else a usage error giving the range. */
static bool
check_pixel(const struct run *run, const struct render_job *job, struct diag *err)
{
    int x = run->opt.pixel[0];
    int y = run->opt.pixel[1];
    if (x < job->width && y < job->height) {
        return true;
    }
    diag_set(
        err,
        NULL,
        0,
        0,
        "--pixel %d,%d is outside the %dx%d image: X in [0, %d], Y in [0, %d]",
        x,
        y,
        job->width,
        job->height,
        job->width - 1,
        job->height - 1);
    return false;
}

/* --pixel: render that pixel alone, recording its rays; the whole image
 * too when it is written (-o) or drawn under the paths (--trace-svg),
 * which then checks the pixel's value against it. */
static int
render_traced(
    struct run *run,
    const struct render_job *job,
    int spp_per_pass,
    const struct image *passes)
{
    struct diag err;
    if (!check_pixel(run, job, &err)) {
        diag_print(stderr, &err, "error");
        return EXIT_USAGE;
    }
    if (job->time_limit > 0) {
        fprintf(
            stderr,
            "error: --pixel replays a fixed number of samples: give --spp, not --time\n");
        return EXIT_USAGE;
    }
    int px = run->opt.pixel[0];
    int py = run->opt.pixel[1];
    struct recorder *trace = recorder_new(&run->scene, px, py);
    if (!trace) {
        fprintf(stderr, "error: out of memory for the trace\n");
        return EXIT_RESOURCES;
    }
    float rgb[3];
    struct render_result result;
    driver_render_pixel_traced(job, px, py, trace, rgb, &result);
    struct image image = {0};
    bool full = run->opt.trace_svg_path || run->opt.output;
    int status = EXIT_OK;
    if (full) {
        status = render_full(job, &image, &result);
    }
    if (status == EXIT_OK && full && memcmp(image_pixel(&image, px, py), rgb, sizeof rgb) != 0) {
        fprintf(stderr, "warning: the traced pixel's value differs from the full render's\n");
    }
    if (status == EXIT_OK) {
        fill_report(run, job, &result, spp_per_pass);
        status = run_write_outputs(run, full ? &image : NULL, passes, trace);
    }
    image_free(&image);
    recorder_free(trace);
    return status;
}

/* The --aov passes (none asked for: nothing to do, nothing spent). */
static int
render_passes(struct run *run, const struct render_job *job, struct image passes[AOV_COUNT])
{
    struct diag err;
    if (!run->opt.aov) {
        return EXIT_OK;
    }
    if (!run->aov.first_hit) {
        diag_set(&err, NULL, 0, 0, "--aov: %s does not write render passes", run->stage);
        diag_print(stderr, &err, "error");
        return EXIT_USAGE;
    }
    bool interrupted;
    double start = stats_clock_seconds();
    if (!aov_render(&run->aov, &run->scene, run->opt.aov, job, passes, &interrupted, &err)) {
        if (interrupted) {
            fprintf(
                stderr,
                "interrupted before the render passes were complete; nothing written\n");
            return EXIT_INTERRUPTED;
        }
        diag_print(stderr, &err, "error");
        return EXIT_RESOURCES;
    }
    stats_report_set(&run->rep, "seconds_aov", stats_clock_seconds() - start, false);
    return EXIT_OK;
}

int
run_render(struct run *run, const struct render_job *job, int spp_per_pass)
{
    struct diag err;
    if (!run_check_job(job, spp_per_pass, &err)) {
        diag_print(stderr, &err, "error");
        return EXIT_USAGE;
    }
    signals_install();
    /* The passes first: an interrupted progressive render still writes
     * its image, and then every output. */
    struct image passes[AOV_COUNT] = {{0}};
    int status = render_passes(run, job, passes);
    if (status == EXIT_OK && run->opt.has_pixel) {
        status = render_traced(run, job, spp_per_pass, passes);
    } else if (status == EXIT_OK) {
        struct image image = {0};
        struct render_result result;
        status = render_full(job, &image, &result);
        if (status == EXIT_OK) {
            fill_report(run, job, &result, spp_per_pass);
            status = run_write_outputs(run, &image, passes, NULL);
        }
        image_free(&image);
    }
    for (int pass = 0; pass < AOV_COUNT; pass++) {
        image_free(&passes[pass]);
    }
    return status;
}

int
run_fail(struct run *run, const struct diag *err, int status)
{
    diag_print(stderr, err, "error");
    run_free(run);
    return status;
}

void
run_free(struct run *run)
{
    if (run->scene_loaded) {
        scene_free(&run->scene);
        run->scene_loaded = false;
    }
}
