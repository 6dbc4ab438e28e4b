/*
 * run_outputs.c - the outputs of a run (run.h): which files it writes,
 * whether this build can write the image's format, and writing them all
 * or none once the render is done (images, render passes, statistics,
 * traces), then those that go to standard output.
 */
#include "run_outputs.h"

#include <string.h>

#include "atomic_file.h"
#include "image.h"
#include "recorder.h"
#include "signals.h"

/* The name that makes an output go to standard output (--stats -). */
#define STDOUT_NAME "-"

/* Refuse an output name we cannot write before spending time rendering. */
bool
run_check_image_output(const char *path, struct diag *err)
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

/* Whether the run writes the image: always, but with --pixel only when -o
 * asks for it. */
bool
run_writes_image(const struct run *run)
{
    return !run->opt.has_pixel || run->opt.output;
}

static void
add_output(struct run *run, const char *what, const char *path)
{
    if (path && strcmp(path, STDOUT_NAME) != 0) {
        run->outputs[run->n_outputs++] = (struct named_file){what, path};
    }
}

/* Every file the run will write (an output option added later adds its
 * line here).  "-" is standard output, which is no file. */
bool
run_collect_outputs(struct run *run, struct diag *err)
{
    if (run_writes_image(run)) {
        run->outputs[run->n_outputs++] = (struct named_file){"-o", run->output};
    }
    add_output(run, "--stats", run->opt.stats_path);
    add_output(run, "--trace", run->opt.trace_path);
    add_output(run, "--trace-svg", run->opt.trace_svg_path);
    for (int pass = 0; pass < AOV_COUNT; pass++) {
        if (!(run->opt.aov & (1u << pass)) || aov_as_layers(run->output)) {
            continue;
        }
        char *path = run->aov_paths[pass];
        if (!aov_path(run->output, pass, path, sizeof run->aov_paths[pass])) {
            diag_set(err, NULL, 0, 0, "--aov: the name of '%s' is too long", run->output);
            return false;
        }
        run->outputs[run->n_outputs++] = (struct named_file){"--aov", path};
    }
    return true;
}

/* Give up on the outputs: none is left, under its name or a temporary one. */
static int
abandon(struct atomic_file *files, int n, const struct diag *err)
{
    diag_print(stderr, err, "error");
    for (int i = 0; i < n; i++) {
        atomic_file_abort(&files[i]);
    }
    return EXIT_OUTPUT;
}

/* Put every finished file in place, with the signals held so that the
 * run ends with all of them or none.  If a rename fails (it should not:
 * each temporary file is beside its target), those already in place are
 * removed again. */
static int
publish_all(struct atomic_file *files, int n)
{
    struct diag err;
    int status = EXIT_OK;
    signals_hold();
    for (int i = 0; i < n; i++) {
        if (!atomic_file_publish(&files[i], &err)) {
            for (int j = 0; j < i; j++) {
                remove(files[j].path);
            }
            status = abandon(files + i + 1, n - i - 1, &err);
            break;
        }
    }
    signals_release();
    return status;
}

/* Which image output i is: the render, a pass, or none (the statistics,
 * a trace). */
static const struct image *
output_image(const struct run *run, int i, const struct image *image, const struct image *passes)
{
    const char *path = run->outputs[i].path;
    if (path == run->output) {
        return image;
    }
    for (int pass = 0; pass < AOV_COUNT; pass++) {
        if (path == run->aov_paths[pass]) {
            return &passes[pass];
        }
    }
    return NULL;
}

/* Write an image; the image itself, when its format is EXR, with the
 * passes as its layers. */
static bool
write_image(
    const struct run *run,
    const struct image *img,
    const struct image *passes,
    struct atomic_file *af,
    struct diag *err)
{
    struct image_layer layers[AOV_COUNT];
    int n = 0;
    bool is_render = af->path == run->output; /* atomic_file_open keeps the pointer */
    for (int pass = 0; pass < AOV_COUNT && is_render; pass++) {
        if ((run->opt.aov & (1u << pass)) && aov_as_layers(run->output)) {
            layers[n++] = (struct image_layer){
                aov_pass_names[pass],
                aov_exr_channels[pass],
                &passes[pass],
            };
        }
    }
    return image_write_layers_to(img, layers, n, af, err);
}

/* Whether a trace file is asked for as JSON (by its extension). */
static bool
is_json(const char *path)
{
    size_t len = strlen(path);
    return len >= 5 && strcmp(path + len - 5, ".json") == 0;
}

/* Write output `path`, one of the run's that is not an image, to the open
 * stream f. */
static bool
write_one(
    struct run *run,
    const char *path,
    FILE *f,
    const struct image *image,
    const struct recorder *trace,
    struct diag *err)
{
    if (path == run->opt.trace_svg_path) {
        const struct recorder_camera camera = {run->aov.ctx, run->aov.camera_ray};
        return recorder_write_svg(f, trace, image, &camera, err);
    }
    if (path == run->opt.trace_path && is_json(path)) {
        recorder_write_json(f, trace);
    } else if (path == run->opt.trace_path) {
        recorder_write_text(f, trace);
    } else {
        stats_report_write_json_to(f, &run->rep);
    }
    return true;
}

/* The outputs that go to standard output ("-"), once the files are in
 * place. */
static int
write_stdout(struct run *run, const struct image *image, const struct recorder *trace)
{
    const char *streams[] = {run->opt.stats_path, run->opt.trace_path, run->opt.trace_svg_path};
    for (int i = 0; i < 3; i++) {
        if (!streams[i] || strcmp(streams[i], STDOUT_NAME) != 0) {
            continue;
        }
        struct diag err;
        if (!write_one(run, streams[i], stdout, image, trace, &err)) {
            diag_print(stderr, &err, "error");
            return EXIT_OUTPUT;
        }
        if (fflush(stdout) != 0 || ferror(stdout)) {
            fprintf(stderr, "error: standard output: cannot write to it\n");
            return EXIT_OUTPUT;
        }
    }
    return EXIT_OK;
}

/* Write the image, the statistics, the passes and the trace, all or none;
 * returns the exit status.  An output named "-" goes to standard output
 * once the files are in place.  image is NULL when --pixel renders no
 * image, trace NULL without --pixel. */
int
run_write_outputs(
    struct run *run,
    const struct image *image,
    const struct image *passes,
    const struct recorder *trace)
{
    run->rep.peak_rss_bytes = stats_peak_rss_bytes();
    run->rep.seconds_total = stats_clock_seconds() - run->start;
    struct atomic_file files[RUN_MAX_OUTPUTS];
    struct diag err;
    int n = 0;
    for (int i = 0; i < run->n_outputs; i++) {
        const char *path = run->outputs[i].path;
        if (!atomic_file_open(&files[n], path, &err)) {
            return abandon(files, n, &err);
        }
        n++;
        const struct image *img = output_image(run, i, image, passes);
        bool written = img ? write_image(run, img, passes, &files[n - 1], &err)
                           : write_one(run, path, files[n - 1].f, image, trace, &err);
        if (!written) {
            return abandon(files, n, &err);
        }
        if (!atomic_file_finish(&files[n - 1], &err)) {
            return abandon(files, n - 1, &err);
        }
    }
    int status = publish_all(files, n);
    if (status != EXIT_OK) {
        return status;
    }
    if (!run->opt.quiet) {
        stats_report_print(stderr, &run->rep);
    }
    return write_stdout(run, image, trace);
}
