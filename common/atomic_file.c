/* atomic_file.c - temporary file + rename (see atomic_file.h). */
#include "atomic_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Names tried for the temporary file before giving up. */
#define TEMP_ATTEMPTS 100

static bool
write_failed(const char *path, int error, struct diag *err)
{
    diag_set(err, path, 0, 0, "cannot write: %s", strerror(error));
    return false;
}

/* Create "path.tmp-PID-N" exclusively, beside the target so that rename()
 * stays within one file system.  Not mkstemp(): it makes files of mode 0600,
 * and an output should get the usual 0666 less the umask. */
bool
atomic_file_open(struct atomic_file *af, const char *path, struct diag *err)
{
    af->f = NULL;
    af->path = path;
    for (int attempt = 0; attempt < TEMP_ATTEMPTS; attempt++) {
        int n = snprintf(
            af->tmp_path,
            sizeof af->tmp_path,
            "%s.tmp-%ld-%d",
            path,
            (long)getpid(),
            attempt);
        if (n < 0 || (size_t)n >= sizeof af->tmp_path) {
            return write_failed(path, ENAMETOOLONG, err);
        }
        int fd = open(af->tmp_path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0 && errno == EEXIST) {
            continue;
        }
        if (fd < 0) {
            return write_failed(path, errno, err);
        }
        af->f = fdopen(fd, "wb");
        if (!af->f) {
            int error = errno;
            close(fd);
            remove(af->tmp_path);
            return write_failed(path, error, err);
        }
        return true;
    }
    return write_failed(path, EEXIST, err);
}

/* Flush to the disk before the rename, so that the rename can never expose
 * a half-written file, even after a power loss. */
bool
atomic_file_commit(struct atomic_file *af, struct diag *err)
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
    if (!error && rename(af->tmp_path, af->path) != 0) {
        error = errno;
    }
    if (error) {
        remove(af->tmp_path);
        return write_failed(af->path, error, err);
    }
    return true;
}

void
atomic_file_abort(struct atomic_file *af)
{
    if (af->f) {
        fclose(af->f);
        af->f = NULL;
    }
    remove(af->tmp_path);
}
