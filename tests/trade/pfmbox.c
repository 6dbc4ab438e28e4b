/*
 * pfmbox.c - shrink a PFM image by an integer factor with a box filter.
 *
 *     pfmbox FACTOR IN.pfm OUT.pfm
 *
 * Used by `make trade QUICK=1` to compare 64 x 64 renders with the 256 x 256
 * references of tests/reference/ (factor 4): see boxdown.h for why this is
 * exact for box-filtered pixels.  The output is written atomically.  Exit
 * status: 0 written, 1 unreadable input, bad factor or unwritable output,
 * 2 bad usage.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "boxdown.h"
#include "diag.h"
#include "image.h"

static void
usage(FILE *f)
{
    fputs(
        "usage: pfmbox FACTOR IN.pfm OUT.pfm\n"
        "\n"
        "Writes IN shrunk by FACTOR (an integer >= 1 that divides its width and\n"
        "height): each output pixel is the mean of FACTOR x FACTOR input pixels\n"
        "(a box filter), per channel.  OUT is written atomically (.pfm, or any\n"
        "format the renderer writes, by its extension).\n"
        "\n"
        "Exit status: 0 written, 1 bad input, factor or output, 2 bad usage.\n",
        f);
}

/* A whole decimal integer in [1, 32768]. */
static bool
parse_factor(const char *s, int *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno != 0 || v < 1 || v > 32768) {
        return false;
    }
    *out = (int)v;
    return true;
}

int
main(int argc, char **argv)
{
    if (argc == 2 && (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0)) {
        usage(stdout);
        return 0;
    }
    int f;
    if (argc != 4 || !parse_factor(argv[1], &f)) {
        fputs("usage: pfmbox FACTOR IN.pfm OUT.pfm (FACTOR an integer >= 1; see --help)\n", stderr);
        return 2;
    }
    struct image in = {0}, out = {0};
    struct diag err = {0};
    bool ok = image_read_pfm(argv[2], &in, &err);
    if (ok && !box_downsample(&in, f, &out, &err)) {
        snprintf(err.file, sizeof err.file, "%s", argv[2]);
        ok = false;
    }
    ok = ok && image_write(&out, argv[3], &err);
    if (!ok) {
        diag_print(stderr, &err, "error");
    }
    image_free(&in);
    image_free(&out);
    return ok ? 0 : 1;
}
