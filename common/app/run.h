/*
 * run.h - what every stage's main() does around its render, in one place:
 * parse the command line, refuse a bad output before any work, load the
 * scene and say what the stage does not model, run the tile driver, write
 * the image and the statistics, and choose the exit status (CONTRACT.md).
 *
 * This is main()'s plumbing, shared by every stage: it prints the
 * diagnostics (stderr) but never exits.  Every step returns false (or a
 * status), and main() returns the status, so a stage's main.c holds only
 * its options and its render call.
 */
#ifndef RUN_H
#define RUN_H

#include <stdbool.h>

#include "aov.h"
#include "cli.h"
#include "diag.h"
#include "driver.h"
#include "output_check.h"
#include "scene.h"
#include "stats.h"

/* The exit statuses of CONTRACT.md. */
enum exit_status {
    EXIT_OK = 0,
    EXIT_INPUT = 1, /* invalid scene or input file */
    EXIT_USAGE = 2, /* bad command line */
    EXIT_OUTPUT = 3, /* an output could not be written */
    EXIT_RESOURCES = 4, /* memory or threads refused by the system (loading or rendering) */
    EXIT_INTERRUPTED = 130, /* the shell's code for death by SIGINT */
};

/* The most files a run writes (-o, --stats, --trace, --trace-svg and one
 * per --aov pass). */
#define RUN_MAX_OUTPUTS (6 + AOV_COUNT)

/* One run of `render`, from the command line to the written outputs. */
struct run {
    const char *stage; /* STAGE_NAME, e.g. "05_bvh" */
    struct options opt;
    const char *output; /* the image: -o, or <scene name>.png */
    char default_output[1024];
    struct named_file outputs[RUN_MAX_OUTPUTS]; /* every file the run writes */
    int n_outputs;
    double start; /* stats_clock_seconds() when the run began */
    struct scene scene; /* loaded by run_load_scene */
    bool scene_loaded;
    struct report rep; /* what --stats and the summary report */
    struct aov_source aov; /* set by the stage before run_render: what --aov asks of it */
    char aov_paths[AOV_COUNT][1024]; /* where each --aov pass goes (aov_path) */
    int status; /* the exit status once a step has returned false */
};

/* Parse the command line and check the outputs before any work: a format
 * this build writes, a directory that exists and takes new files (else
 * EXIT_OUTPUT), no two outputs one file and none the scene (else
 * EXIT_USAGE).  False: main() returns run->status (EXIT_OK after --help
 * or --version). */
bool run_parse(struct run *run, int argc, char **argv, const struct cli_stage *stage);

/* What a stage says of the scene features it does not model: up to max
 * notes, one per feature s uses and `modelled` lacks, each "what is not
 * modelled; what the stage does instead" (stages/course.h's
 * course_unmodelled: the stages, not common/, know the course). */
typedef int (*unmodelled_fn)(
    const struct scene *s,
    unsigned modelled,
    const char *stage,
    struct diag *notes,
    int max);

/* Load the scene, check that no output is one of the files it read
 * (meshes), and warn, once per feature, about what `modelled` (the stage's
 * RENDER_FEATURES) lacks, in the words of `unmodelled`, then the scene's
 * own notes (what no stage models); under --strict that refuses the scene.
 * False: main() returns run->status. */
bool run_load_scene(struct run *run, unsigned modelled, unmodelled_fn unmodelled);
/* The image's size: the scene's, or -W/-H's (one of them alone keeps the
 * scene's aspect ratio). */
void run_image_size(const struct scene *scene, const struct options *opt, int *width, int *height);
/* False, with the message printed and run->status set, when an output of
 * the run is one of these inputs (the same file by identity, not name). */
bool run_check_identities(struct run *run, const struct named_file *inputs, int n_inputs);

/* The job every stage starts from: the image size (the scene's, or -W/-H
 * keeping its aspect ratio), the threads, the seed, the progress bar, one
 * pass over ctx.  The stage sets its tile function (a progressive stage
 * also its passes and its time budget: 07's progressive_passes). */
struct render_job run_job(const struct run *run, const void *ctx);

/* Check that the job can be run at all before anything is allocated for
 * it: the one place for limits on the work a command line may ask for.
 * False: err says why (exit EXIT_USAGE). */
bool run_check_job(const struct render_job *job, int spp_per_pass, struct diag *err);

/* Render the job and write the image and the statistics, all of them or
 * none (each under a temporary name until all are complete); spp_per_pass
 * is the camera samples per pixel of one pass.  SIGINT, SIGTERM or SIGHUP
 * stops the render after the passes completed so far (signals.h).
 * Returns the exit status. */
int run_render(struct run *run, const struct render_job *job, int spp_per_pass);

/* Print err, release the run's resources, and return status: the way out
 * of main() for a check of the stage's own. */
int run_fail(struct run *run, const struct diag *err, int status);

/* Release what the run holds (the scene). */
void run_free(struct run *run);

#endif /* RUN_H */
