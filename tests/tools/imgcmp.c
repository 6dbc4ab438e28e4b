/*
 * imgcmp.c - compare a render with a reference image from the command line.
 *
 *     imgcmp [--mask smooth] [--csv | --json] RENDER.pfm REFERENCE.pfm
 *
 * Prints the metrics of tests/lib/metrics.h (relMSE, RMSE, MAE, frac5, the
 * means of both images, pixel counts).  Exit status: 0 when the images were
 * compared, 1 when a file cannot be read or the sizes differ, 2 on bad
 * usage.
 */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "diag.h"
#include "image.h"
#include "metrics.h"

enum output_format {
    FORMAT_TEXT,
    FORMAT_CSV,
    FORMAT_JSON,
};

struct args {
    bool smooth_mask;
    enum output_format format;
    const char *render_path;
    const char *reference_path;
};

static void
usage(FILE *f)
{
    fputs(
        "usage: imgcmp [--mask smooth] [--csv | --json] RENDER.pfm REFERENCE.pfm\n"
        "\n"
        "Compares a render with a reference (linear-radiance PFM files of the same\n"
        "size) and prints, over all 3 channels of the compared pixels:\n"
        "  relmse     mean of (x - r)^2 / (r^2 + 0.01)\n"
        "  rmse       sqrt(mean of (x - r)^2)\n"
        "  mae        mean of |x - r|\n"
        "  frac5      fraction of pixels where some channel has\n"
        "             |x - r| > 0.05 * max(|r|, 0.01)\n"
        "  mean_*     the render's mean per channel, ref_mean_* the reference's\n"
        "  pixels     pixels compared; nonfinite: pixels left out for NaN/Inf\n"
        "\n"
        "  --mask smooth  compare only the reference's smooth pixels (3x3\n"
        "                 luminance window within 5% of its centre, no border)\n"
        "  --csv          a header line and one line of values\n"
        "  --json         one flat JSON object\n"
        "  -h, --help     this text\n"
        "\n"
        "Exit status: 0 compared, 1 unreadable file or size mismatch, 2 bad usage.\n",
        f);
}

/* 0: parsed; 1: --help given; 2: bad usage (message printed). */
static int
parse_args(int argc, char **argv, struct args *a)
{
    const char *paths[2] = {NULL, NULL};
    int n_paths = 0;
    for (int i = 1; i < argc; i++) {
        const char *s = argv[i];
        if (strcmp(s, "-h") == 0 || strcmp(s, "--help") == 0) {
            return 1;
        } else if (strcmp(s, "--mask") == 0 && i + 1 < argc && strcmp(argv[i + 1], "smooth") == 0) {
            a->smooth_mask = true;
            i++;
        } else if (strcmp(s, "--mask") == 0) {
            fprintf(stderr, "imgcmp: error: --mask takes 'smooth'\n");
            return 2;
        } else if (strcmp(s, "--csv") == 0 || strcmp(s, "--json") == 0) {
            a->format = s[2] == 'c' ? FORMAT_CSV : FORMAT_JSON;
        } else if (s[0] == '-' && s[1] != '\0') {
            fprintf(stderr, "imgcmp: error: unknown option '%s'\n", s);
            return 2;
        } else if (n_paths < 2) {
            paths[n_paths++] = s;
        } else {
            fprintf(stderr, "imgcmp: error: too many arguments ('%s')\n", s);
            return 2;
        }
    }
    if (n_paths != 2) {
        fprintf(stderr, "imgcmp: error: expected RENDER.pfm and REFERENCE.pfm\n");
        return 2;
    }
    a->render_path = paths[0];
    a->reference_path = paths[1];
    return 0;
}

static void
print_text(const struct metrics *m)
{
    printf("pixels     %zu\n", m->n_pixels);
    printf("nonfinite  %zu\n", m->n_nonfinite);
    printf("relmse     %.9g\n", m->relmse);
    printf("rmse       %.9g\n", m->rmse);
    printf("mae        %.9g\n", m->mae);
    printf("frac5      %.9g\n", m->frac5);
    printf("mean       %.9g %.9g %.9g\n", m->mean[0], m->mean[1], m->mean[2]);
    printf("ref_mean   %.9g %.9g %.9g\n", m->ref_mean[0], m->ref_mean[1], m->ref_mean[2]);
}

static void
print_csv(const struct metrics *m)
{
    puts("pixels,nonfinite,relmse,rmse,mae,frac5,mean_r,mean_g,mean_b,ref_mean_r,ref_mean_g,"
         "ref_mean_b");
    printf(
        "%zu,%zu,%.9g,%.9g,%.9g,%.9g",
        m->n_pixels,
        m->n_nonfinite,
        m->relmse,
        m->rmse,
        m->mae,
        m->frac5);
    printf(",%.9g,%.9g,%.9g", m->mean[0], m->mean[1], m->mean[2]);
    printf(",%.9g,%.9g,%.9g\n", m->ref_mean[0], m->ref_mean[1], m->ref_mean[2]);
}

/* JSON has no NaN: a metric over no pixels is written as null. */
static void
json_number(const char *key, double v, bool last)
{
    if (v == v) {
        printf("  \"%s\": %.9g%s\n", key, v, last ? "" : ",");
    } else {
        printf("  \"%s\": null%s\n", key, last ? "" : ",");
    }
}

static void
print_json(const struct metrics *m)
{
    printf("{\n  \"pixels\": %zu,\n  \"nonfinite\": %zu,\n", m->n_pixels, m->n_nonfinite);
    json_number("relmse", m->relmse, false);
    json_number("rmse", m->rmse, false);
    json_number("mae", m->mae, false);
    json_number("frac5", m->frac5, false);
    static const char *const names[6] =
        {"mean_r", "mean_g", "mean_b", "ref_mean_r", "ref_mean_g", "ref_mean_b"};
    for (int c = 0; c < 6; c++) {
        json_number(names[c], c < 3 ? m->mean[c] : m->ref_mean[c - 3], c == 5);
    }
    puts("}");
}

/* Read both images, build the mask, compare; false with err on failure. */
static bool
compare_files(const struct args *a, struct metrics *m, struct diag *err)
{
    struct image x = {0}, r = {0};
    unsigned char *mask = NULL;
    bool ok = image_read_pfm(a->render_path, &x, err) && image_read_pfm(a->reference_path, &r, err);
    if (ok && a->smooth_mask) {
        mask = metrics_smooth_mask(&r, METRICS_SMOOTH_TOLERANCE, NULL, err);
        ok = mask != NULL;
    }
    if (ok && !metrics_compare(&x, &r, mask, m, err)) {
        /* Name the render in the message, as for a read error. */
        snprintf(err->file, sizeof err->file, "%s", a->render_path);
        ok = false;
    }
    free(mask);
    image_free(&x);
    image_free(&r);
    return ok;
}

int
main(int argc, char **argv)
{
    struct args a = {0};
    int status = parse_args(argc, argv, &a);
    if (status == 1) {
        usage(stdout);
        return 0;
    }
    if (status == 2) {
        fputs("usage: imgcmp [--mask smooth] [--csv | --json] RENDER.pfm REFERENCE.pfm\n", stderr);
        return 2;
    }
    struct metrics m;
    struct diag err = {0};
    if (!compare_files(&a, &m, &err)) {
        diag_print(stderr, &err, "error");
        return 1;
    }
    if (a.format == FORMAT_CSV) {
        print_csv(&m);
    } else if (a.format == FORMAT_JSON) {
        print_json(&m);
    } else {
        print_text(&m);
    }
    return fflush(stdout) == 0 && !ferror(stdout) ? 0 : 1;
}
