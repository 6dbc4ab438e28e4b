/*
 * output_check.h - the files a run will write, checked before any work:
 * each can be written (its directory exists and takes new files), no two
 * are the same file, and none is a file the run reads.  "The same file" is
 * decided by file identity (device and inode), not by spelling: "a.png",
 * "./a.png" and a hard link to it are one file.
 */
#ifndef OUTPUT_CHECK_H
#define OUTPUT_CHECK_H

#include "diag.h"

/* A file and how the user named it: "-o", "--stats", "the scene". */
struct named_file {
    const char *what;
    const char *path;
};

enum output_check {
    OUTPUTS_OK,
    OUTPUTS_CLASH, /* two outputs, or an output and an input, are one file */
    OUTPUTS_UNWRITABLE, /* an output's directory is missing or read-only */
};

/* Check outputs[0..n_outputs) against each other and against
 * inputs[0..n_inputs) (an input that does not exist is skipped: reading
 * it reports that).  An output that exists is compared as the name itself
 * (a symbolic link there is replaced, not followed); one that does not yet
 * exist, as its directory and base name.  err names both paths. */
enum output_check output_check(
    const struct named_file *outputs,
    int n_outputs,
    const struct named_file *inputs,
    int n_inputs,
    struct diag *err);

#endif /* OUTPUT_CHECK_H */
