/*
 * run_outputs.h - the outputs of a run, for run.c alone (the stages use
 * run.h): collecting and checking them before the render, writing them
 * after it.
 */
#ifndef RUN_OUTPUTS_H
#define RUN_OUTPUTS_H

#include <stdbool.h>

#include "diag.h"
#include "image.h"
#include "recorder.h"
#include "run.h"

/* Whether the run writes the image: always, but with --pixel only when -o
 * asks for it. */
bool run_writes_image(const struct run *run);

/* Whether this build writes the format of the image `path` (its
 * extension); else err says why. */
bool run_check_image_output(const char *path, struct diag *err);

/* Fill run->outputs with every file the run will write ("-" is standard
 * output, no file); false when an --aov pass name would not fit. */
bool run_collect_outputs(struct run *run, struct diag *err);

/* Write the image, the statistics, the passes and the trace, all or none;
 * returns the exit status.  An output named "-" goes to standard output
 * once the files are in place.  image is NULL when --pixel renders no
 * image, trace NULL without --pixel. */
int run_write_outputs(
    struct run *run,
    const struct image *image,
    const struct image *passes,
    const struct recorder *trace);

#endif /* RUN_OUTPUTS_H */
