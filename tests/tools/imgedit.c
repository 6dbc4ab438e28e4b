/*
 * imgedit.c - the two image edits of the calibration harness (make
 * calibrate, tests/calibrate/): a planted bias and a smaller reference.
 *
 *     imgedit --scale F [--rect X,Y,W,H] IN OUT
 *     imgedit --downsample N IN OUT
 *
 * --scale multiplies every channel of the pixels in the rectangle (the
 * whole image without --rect) by F: a render with a known bias of F - 1
 * there, to measure how often a verdict finds it.  --downsample averages
 * each NxN square of pixels into one: with a box pixel filter (the
 * stages' and the Mitsuba references'), the image the same camera would
 * give at 1/N of the size, so the references serve small, cheap renders.
 * Linear images only (.pfm, or .exr with OpenEXR); OUT is written to a
 * temporary name and renamed.
 * Exit status: 0 written, 1 unreadable input or unwritable output, 2 usage.
 */
#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "diag.h"
#include "image.h"
#include "imgread.h"

struct args {
    double scale; /* 0: not --scale */
    int rect[4]; /* x, y, w, h; w 0: the whole image */
    int downsample; /* 0: not --downsample */
    const char *in, *out;
};

static const char usage_text[] =
    "usage: imgedit --scale F [--rect X,Y,W,H] IN OUT\n"
    "       imgedit --downsample N IN OUT\n"
    "\n"
    "  --scale F        multiply the pixels by F (a planted bias of F - 1)\n"
    "  --rect X,Y,W,H   only those of this rectangle (0,0 top left; clipped)\n"
    "  --downsample N   average each NxN square into one pixel (the size must\n"
    "                   be a multiple of N)\n"
    "  -h, --help       this text\n"
    "Exit status: 0 written, 1 bad input or output, 2 usage.\n";

static bool
parse_whole(const char *text, int lo, int *out)
{
    char *end;
    errno = 0;
    long v = strtol(text, &end, 10);
    if (end == text || *end != '\0' || errno == ERANGE || v < lo || v > IMAGE_MAX_DIM) {
        return false;
    }
    *out = (int)v;
    return true;
}

/* 0: parsed; 1: --help; 2: bad usage (message printed). */
static int
parse_args(int argc, char **argv, struct args *a)
{
    int n_paths = 0;
    for (int i = 1; i < argc; i++) {
        const char *s = argv[i];
        const char *value = i + 1 < argc ? argv[i + 1] : NULL;
        char *end = NULL;
        if (strcmp(s, "-h") == 0 || strcmp(s, "--help") == 0) {
            return 1;
        } else if (strcmp(s, "--scale") == 0 && value) {
            a->scale = strtod(value, &end);
            if (end == value || *end != '\0' || !(a->scale > 0 && a->scale < 1e6)) {
                fprintf(stderr, "imgedit: error: --scale expects a positive number, got '%s'\n", value);
                return 2;
            }
            i++;
        } else if (strcmp(s, "--rect") == 0 && value) {
            int *r = a->rect;
            if (sscanf(value, "%d,%d,%d,%d", &r[0], &r[1], &r[2], &r[3]) != 4 || r[0] < 0 || r[1] < 0
                || r[2] < 1 || r[3] < 1) {
                fprintf(stderr, "imgedit: error: --rect expects X,Y,W,H (W, H >= 1), got '%s'\n", value);
                return 2;
            }
            i++;
        } else if (strcmp(s, "--downsample") == 0 && value) {
            if (!parse_whole(value, 1, &a->downsample)) {
                fprintf(stderr, "imgedit: error: --downsample expects a whole number >= 1, got '%s'\n", value);
                return 2;
            }
            i++;
        } else if (s[0] == '-' && s[1] != '\0') {
            fprintf(stderr, "imgedit: error: unknown option '%s' (or its value is missing)\n", s);
            return 2;
        } else if (n_paths < 2) {
            *(n_paths++ == 0 ? &a->in : &a->out) = s;
        } else {
            fprintf(stderr, "imgedit: error: too many arguments ('%s')\n", s);
            return 2;
        }
    }
    if (n_paths != 2 || (a->scale > 0) == (a->downsample > 0) || (a->rect[2] && !(a->scale > 0))) {
        fprintf(stderr, "imgedit: error: expected --scale F [--rect ...] or --downsample N, IN and OUT\n");
        return 2;
    }
    return 0;
}

static void
scale_rect(struct image *img, double f, const int rect[4])
{
    int x1 = rect[2] ? rect[0] + rect[2] : img->width, y1 = rect[2] ? rect[1] + rect[3] : img->height;
    for (int y = rect[1]; y < y1 && y < img->height; y++) {
        for (int x = rect[0]; x < x1 && x < img->width; x++) {
            float *p = image_pixel(img, x, y);
            for (int c = 0; c < 3; c++) {
                p[c] = (float)(p[c] * f);
            }
        }
    }
}

static bool
downsample(const struct image *in, int n, struct image *out, struct diag *err)
{
    if (in->width % n || in->height % n) {
        diag_set(err, NULL, 0, 0, "%dx%d is not a multiple of %d", in->width, in->height, n);
        return false;
    }
    if (!image_alloc(out, in->width / n, in->height / n, err)) {
        return false;
    }
    for (int y = 0; y < out->height; y++) {
        for (int x = 0; x < out->width; x++) {
            double sum[3] = {0, 0, 0};
            for (int j = 0; j < n * n; j++) {
                const float *p = image_pixel(in, x * n + j % n, y * n + j / n);
                for (int c = 0; c < 3; c++) {
                    sum[c] += p[c];
                }
            }
            for (int c = 0; c < 3; c++) {
                image_pixel(out, x, y)[c] = (float)(sum[c] / (n * n));
            }
        }
    }
    return true;
}

int
main(int argc, char **argv)
{
    struct args a = {0};
    int status = parse_args(argc, argv, &a);
    if (status != 0) {
        fputs(usage_text, status == 1 ? stdout : stderr);
        return status == 1 ? 0 : 2;
    }
    struct diag err = {0};
    struct image img = {0}, small = {0};
    bool ok = imgread(a.in, &img, &err);
    if (ok && a.downsample) {
        ok = downsample(&img, a.downsample, &small, &err) && image_write(&small, a.out, &err);
    } else if (ok) {
        scale_rect(&img, a.scale, a.rect);
        ok = image_write(&img, a.out, &err);
    }
    if (!ok) {
        diag_print(stderr, &err, "error");
    }
    image_free(&img);
    image_free(&small);
    return ok ? 0 : 1;
}
