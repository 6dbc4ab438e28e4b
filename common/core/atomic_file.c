/* atomic_file.c - temporary file + rename (see atomic_file.h). */
#include "atomic_file.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Names tried for the temporary file before giving up. */
#define TEMP_ATTEMPTS 100

/* Temporary files that may exist at once (a run writes an image and its
 * statistics; tools write one file at a time). */
#define MAX_TEMPORARIES 8

/* The list a signal handler reads: a slot's path is written before the
 * slot is marked in use, and the mark is cleared before the path is
 * reused, so the handler never reads a half-written name. */
static char temporaries[MAX_TEMPORARIES][ATOMIC_FILE_PATH_MAX];
static volatile sig_atomic_t temporary_in_use[MAX_TEMPORARIES];

static bool
write_failed(const char *path, int error, struct diag *err)
{
    diag_set(err, path, 0, 0, "cannot write: %s", strerror(error));
    return false;
}

static int
take_slot(const char *tmp_path)
{
    for (int i = 0; i < MAX_TEMPORARIES; i++) {
        if (!temporary_in_use[i]) {
            memcpy(temporaries[i], tmp_path, strlen(tmp_path) + 1);
            temporary_in_use[i] = 1;
            return i;
        }
    }
    return -1;
}

static void
release_slot(struct atomic_file *af)
{
    if (af->slot >= 0) {
        temporary_in_use[af->slot] = 0;
        af->slot = -1;
    }
}

void
atomic_file_remove_temporaries(void)
{
    for (int i = 0; i < MAX_TEMPORARIES; i++) {
        if (temporary_in_use[i]) {
            unlink(temporaries[i]);
        }
    }
}

/* The temporary name for attempt n: the target's directory, then a short
 * name of our own, so that a target name of the longest length a file
 * system allows (255 bytes) still has a valid temporary name. */
static bool
temporary_name(struct atomic_file *af, const char *path, int attempt)
{
    const char *slash = strrchr(path, '/');
    int dir_len = slash ? (int)(slash - path) + 1 : 0;
    int n = snprintf(
        af->tmp_path,
        sizeof af->tmp_path,
        "%.*s.stagelight-%ld-%d.tmp",
        dir_len,
        path,
        (long)getpid(),
        attempt);
    return n > 0 && (size_t)n < sizeof af->tmp_path;
}

/* Create the temporary file exclusively, beside the target so that
 * rename() stays within one file system.  Not mkstemp(): it makes files of
 * mode 0600, and an output should get the usual 0666 less the umask.  The
 * name is listed before the file exists, so no signal can come between. */
bool
atomic_file_open(struct atomic_file *af, const char *path, struct diag *err)
{
    af->f = NULL;
    af->path = path;
    af->slot = -1;
    for (int attempt = 0; attempt < TEMP_ATTEMPTS; attempt++) {
        if (!temporary_name(af, path, attempt)) {
            return write_failed(path, ENAMETOOLONG, err);
        }
        af->slot = take_slot(af->tmp_path);
        if (af->slot < 0) {
            diag_set(err, path, 0, 0, "cannot write: more than %d files at once", MAX_TEMPORARIES);
            return false;
        }
        int fd = open(af->tmp_path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0) {
            int error = errno;
            release_slot(af); /* the name is someone else's file, or none */
            if (error == EEXIST) {
                continue;
            }
            return write_failed(path, error, err);
        }
        af->f = fdopen(fd, "wb");
        if (!af->f) {
            int error = errno;
            close(fd);
            atomic_file_abort(af);
            return write_failed(path, error, err);
        }
        return true;
    }
    return write_failed(path, EEXIST, err);
}

/* Flush to the disk before the rename, so that the rename can never expose
 * a half-written file, even after a power loss. */
bool
atomic_file_finish(struct atomic_file *af, struct diag *err)
{
    int error = ferror(af->f) ? EIO : 0;
    if (!error && fflush(af->f) != 0) {
        error = errno;
    }
    if (!error && fsync(fileno(af->f)) != 0) {
        error = errno;
    }
    if (fclose(af->f) != 0 && !error) {
        error = errno;
    }
    af->f = NULL;
    if (error) {
        atomic_file_abort(af);
        return write_failed(af->path, error, err);
    }
    return true;
}

bool
atomic_file_publish(struct atomic_file *af, struct diag *err)
{
    if (rename(af->tmp_path, af->path) != 0) {
        int error = errno;
        atomic_file_abort(af);
        return write_failed(af->path, error, err);
    }
    release_slot(af);
    return true;
}

bool
atomic_file_commit(struct atomic_file *af, struct diag *err)
{
    return atomic_file_finish(af, err) && atomic_file_publish(af, err);
}

void
atomic_file_abort(struct atomic_file *af)
{
    if (af->f) {
        fclose(af->f);
        af->f = NULL;
    }
    if (af->slot >= 0) {
        remove(af->tmp_path);
        release_slot(af);
    }
}
