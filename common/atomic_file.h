/*
 * atomic_file.h - write a file under a temporary name, then rename it into
 * place, so that no reader ever sees a half-written file and a failed write
 * leaves nothing behind (an older file of the same name stays untouched).
 */
#ifndef ATOMIC_FILE_H
#define ATOMIC_FILE_H

#include <stdbool.h>
#include <stdio.h>

#include "diag.h"

struct atomic_file {
    FILE *f;
    char tmp_path[4096]; /* the temporary file, beside the target */
    const char *path; /* the target */
};

/* Create the temporary file beside path and open it for writing. */
bool atomic_file_open(struct atomic_file *af, const char *path, struct diag *err);

/* Close the temporary file, checking every error, and rename it to the
 * target.  On failure the temporary file is removed. */
bool atomic_file_commit(struct atomic_file *af, struct diag *err);

/* Give up: close and remove the temporary file. */
void atomic_file_abort(struct atomic_file *af);

#endif /* ATOMIC_FILE_H */
