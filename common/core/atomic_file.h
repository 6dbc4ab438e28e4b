/*
 * atomic_file.h - write a file under a temporary name, then rename it into
 * place, so that no reader ever sees a half-written file and a failed write
 * leaves nothing behind (an older file of the same name stays untouched).
 *
 * The temporary name is short (".stagelight-PID-N.tmp" in the target's
 * directory), so it is valid whenever the target's name is.  Every
 * temporary file that exists is also listed where a signal handler can
 * find it: atomic_file_remove_temporaries() removes them all (signals.h).
 *
 * Writing several files all-or-nothing: open, write and finish each, then
 * publish each; abort the rest if one fails.
 */
#ifndef ATOMIC_FILE_H
#define ATOMIC_FILE_H

#include <stdbool.h>
#include <stdio.h>

#include "diag.h"

#define ATOMIC_FILE_PATH_MAX 4096

struct atomic_file {
    FILE *f; /* open while being written; NULL once finished */
    char tmp_path[ATOMIC_FILE_PATH_MAX]; /* the temporary file, beside the target */
    const char *path; /* the target */
    int slot; /* in the list of temporary files; -1: none */
};

/* Create the temporary file beside path and open it for writing. */
bool atomic_file_open(struct atomic_file *af, const char *path, struct diag *err);

/* Flush the temporary file to the disk and close it, checking every
 * error: it is complete, not yet in place.  On failure it is removed. */
bool atomic_file_finish(struct atomic_file *af, struct diag *err);

/* Rename a finished temporary file to the target.  On failure it is
 * removed. */
bool atomic_file_publish(struct atomic_file *af, struct diag *err);

/* Finish, then publish. */
bool atomic_file_commit(struct atomic_file *af, struct diag *err);

/* Give up: close (if open) and remove the temporary file. */
void atomic_file_abort(struct atomic_file *af);

/* Remove every temporary file this process has open or finished and not
 * yet published.  Async-signal-safe. */
void atomic_file_remove_temporaries(void);

#endif /* ATOMIC_FILE_H */
