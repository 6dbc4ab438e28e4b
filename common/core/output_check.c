/* output_check.c - outputs distinct, writable, and no input (see output_check.h). */
#include "output_check.h"

#include <errno.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Which file a name is, or would be once written. */
struct identity {
    dev_t dev;
    ino_t ino;
    const char *base; /* for a file not yet there: its name in the directory (dev, ino) */
    size_t base_len;
};

static bool
same_identity(const struct identity *a, const struct identity *b)
{
    return a->dev == b->dev && a->ino == b->ino && a->base_len == b->base_len
           && (a->base_len == 0 || memcmp(a->base, b->base, a->base_len) == 0);
}

/* The directory part of path ("." when there is none), into dir. */
static void
directory_of(const char *path, char *dir, size_t cap)
{
    const char *slash = strrchr(path, '/');
    if (!slash) {
        snprintf(dir, cap, ".");
    } else if (slash == path) {
        snprintf(dir, cap, "/");
    } else {
        snprintf(dir, cap, "%.*s", (int)(slash - path), path);
    }
}

/* Whether a file can be created in dir, tried: access() says yes to root
 * in /proc and /sys, where creating fails only after the render.  The
 * probe is not named as the outputs' temporaries are (a test takes one of
 * those for a write begun), and no signal comes between its creation and
 * its removal: they are held until it is gone.  errno says why not. */
static bool
can_create_in(const char *dir)
{
    char probe[4200];
    snprintf(probe, sizeof probe, "%s/.probe-stagelight-XXXXXX", dir);
    sigset_t all;
    sigset_t old;
    sigfillset(&all);
    sigprocmask(SIG_BLOCK, &all, &old);
    int fd = mkstemp(probe);
    int error = errno;
    if (fd >= 0) {
        close(fd);
        unlink(probe);
    }
    sigprocmask(SIG_SETMASK, &old, NULL);
    errno = error;
    return fd >= 0;
}

static bool
output_identity(const struct named_file *out, struct identity *id, struct diag *err)
{
    struct stat st;
    char dir[4096];
    directory_of(out->path, dir, sizeof dir);
    const char *why = NULL;
    if (stat(dir, &st) != 0) {
        why = errno == ENOENT ? "does not exist" : strerror(errno);
    } else if (!S_ISDIR(st.st_mode)) {
        why = "is not a directory";
    }
    if (why) {
        diag_set(err, NULL, 0, 0, "%s '%s': directory '%s' %s", out->what, out->path, dir, why);
        return false;
    }
    if (access(dir, W_OK | X_OK) != 0 || !can_create_in(dir)) {
        diag_set(
            err,
            NULL,
            0,
            0,
            "%s '%s': cannot create files in directory '%s': %s",
            out->what,
            out->path,
            dir,
            strerror(errno));
        return false;
    }
    *id = (struct identity){.dev = st.st_dev, .ino = st.st_ino};
    const char *slash = strrchr(out->path, '/');
    id->base = slash ? slash + 1 : out->path;
    id->base_len = strlen(id->base);
    if (lstat(out->path, &st) == 0) {
        if (S_ISDIR(st.st_mode)) {
            diag_set(err, NULL, 0, 0, "%s '%s' is a directory", out->what, out->path);
            return false;
        }
        *id = (struct identity){.dev = st.st_dev, .ino = st.st_ino};
    }
    return true;
}

enum output_check
output_check(
    const struct named_file *outputs,
    int n_outputs,
    const struct named_file *inputs,
    int n_inputs,
    struct diag *err)
{
    struct identity ids[8];
    if (n_outputs > (int)(sizeof ids / sizeof ids[0])) {
        diag_set(err, NULL, 0, 0, "too many outputs (%d)", n_outputs);
        return OUTPUTS_CLASH;
    }
    for (int i = 0; i < n_outputs; i++) {
        if (!output_identity(&outputs[i], &ids[i], err)) {
            return OUTPUTS_UNWRITABLE;
        }
        for (int j = 0; j < i; j++) {
            if (same_identity(&ids[i], &ids[j])) {
                diag_set(
                    err,
                    NULL,
                    0,
                    0,
                    "%s '%s' and %s '%s' are the same file",
                    outputs[j].what,
                    outputs[j].path,
                    outputs[i].what,
                    outputs[i].path);
                return OUTPUTS_CLASH;
            }
        }
    }
    for (int k = 0; k < n_inputs; k++) {
        struct stat st;
        if (stat(inputs[k].path, &st) != 0) {
            continue;
        }
        struct identity in = {.dev = st.st_dev, .ino = st.st_ino};
        for (int i = 0; i < n_outputs; i++) {
            if (same_identity(&ids[i], &in)) {
                diag_set(
                    err,
                    NULL,
                    0,
                    0,
                    "%s '%s' is %s '%s': an output would overwrite an input",
                    outputs[i].what,
                    outputs[i].path,
                    inputs[k].what,
                    inputs[k].path);
                return OUTPUTS_CLASH;
            }
        }
    }
    return OUTPUTS_OK;
}
