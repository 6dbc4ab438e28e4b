/*
 * fuzz_util.c - the private directory and checks every harness shares.
 */
#include "fuzz.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char dir[4096];
static char paths[FUZZ_MAX_FILES][4096 + 64];
static int n_paths;

static void
remove_dir(void)
{
    for (int i = 0; i < n_paths; i++) {
        unlink(paths[i]);
    }
    rmdir(dir);
}

const char *
fuzz_dir(void)
{
    if (dir[0] == '\0') {
        const char *tmp = getenv("TMPDIR");
        snprintf(dir, sizeof dir, "%s/stagelight-fuzz-XXXXXX", tmp && *tmp ? tmp : "/tmp");
        if (!mkdtemp(dir)) {
            perror("fuzz harness: mkdtemp");
            abort();
        }
        atexit(remove_dir);
    }
    return dir;
}

/* The full path of name in the directory, remembered for removal at exit. */
static const char *
slot_for(const char *name)
{
    char path[sizeof paths[0]];
    snprintf(path, sizeof path, "%s/%s", fuzz_dir(), name);
    for (int i = 0; i < n_paths; i++) {
        if (strcmp(paths[i], path) == 0) {
            return paths[i];
        }
    }
    if (n_paths == FUZZ_MAX_FILES) {
        fuzz_fail("more than %d file names in fuzz_dir()", FUZZ_MAX_FILES);
    }
    memcpy(paths[n_paths], path, sizeof path);
    return paths[n_paths++];
}

const char *
fuzz_write(const char *name, const uint8_t *data, size_t size)
{
    const char *path = slot_for(name);
    FILE *f = fopen(path, "wb");
    if (!f || (size > 0 && fwrite(data, 1, size, f) != size) || fclose(f) != 0) {
        perror(path);
        abort();
    }
    return path;
}

void
fuzz_remove(const char *name)
{
    unlink(slot_for(name));
}

void
fuzz_fail(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "fuzz harness: broken promise: ");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n");
    va_end(ap);
    abort();
}

void
fuzz_require_message(const struct diag *err, const char *what)
{
    if (err->msg[0] == '\0') {
        fuzz_fail("%s failed without a message", what);
    }
    if (memchr(err->msg, '\0', sizeof err->msg) == NULL) {
        fuzz_fail("%s: message not terminated", what);
    }
}
