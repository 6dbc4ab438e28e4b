/* atomic_file.c - temporary file + rename (see atomic_file.h). */
#include "atomic_file.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

bool
atomic_file_open(struct atomic_file *af, const char *path, struct diag *err)
{
    af->f = NULL;
    af->path = path;
    /* Same directory as the target, so rename() never crosses file systems. */
    int n = snprintf(af->tmp_path, sizeof af->tmp_path, "%s.tmp-XXXXXX", path);
    if (n < 0 || (size_t)n >= sizeof af->tmp_path) {
        diag_set(err, path, 0, 0, "cannot write: file name too long");
        return false;
    }
    int fd = mkstemp(af->tmp_path);
    if (fd < 0) {
        diag_set(err, path, 0, 0, "cannot write: %s", strerror(errno));
        return false;
    }
    /* mkstemp creates the file private (0600); an image is for everyone to read. */
    fchmod(fd, 0644);
    af->f = fdopen(fd, "wb");
    if (!af->f) {
        diag_set(err, path, 0, 0, "cannot write: %s", strerror(errno));
        close(fd);
        remove(af->tmp_path);
        return false;
    }
    return true;
}

bool
atomic_file_commit(struct atomic_file *af, struct diag *err)
{
    bool ok = !ferror(af->f);
    int saved = errno;
    if (fclose(af->f) != 0 && ok) {
        ok = false;
        saved = errno;
    }
    af->f = NULL;
    if (ok && rename(af->tmp_path, af->path) != 0) {
        ok = false;
        saved = errno;
    }
    if (!ok) {
        diag_set(err, af->path, 0, 0, "cannot write: %s", strerror(saved ? saved : EIO));
        remove(af->tmp_path);
    }
    return ok;
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
