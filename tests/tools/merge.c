/*
 * merge.c - renders of one image with different seeds, merged into one.
 *
 *     merge [options] -o OUT.pfm INPUT.pfm...
 *
 * A render with --seed k is an independent estimate of the image; the
 * mean of several, each weighted by its samples per pixel, is the render
 * of all their samples together (estimate.h).  So one image can be
 * rendered on many machines or cores at once and merged afterwards
 * (README: "Rendering on many machines").  Inputs and output are linear
 * (.pfm, or .exr in a build with OpenEXR): a PNG is clamped and quantised,
 * and merging those would be biased.
 * Exit status: 0 merged, 1 an input or output failed, 2 bad usage.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "atomic_file.h"
#include "estimate.h"
#include "image.h"
#include "imgread.h"
#include "testlib.h"

#define MAX_INPUTS 4096

struct input {
    const char *path;
    double spp; /* 0: from its stats file */
    char stats[4096]; /* its stats file, when one was found */
    double seed; /* from the stats file; -1: unknown */
    char what[1200]; /* its stage and scene, as the stats file writes them */
};

struct args {
    const char *output;
    const char *variance;
    const char *stats;
    struct input *inputs;
    int n;
};

static const char usage_line[] = "usage: merge [options] -o OUT.pfm INPUT.pfm...\n";

static void
usage(FILE *f)
{
    fputs(usage_line, f);
    fputs(
        "\n"
        "Merges renders of one scene made with different --seed values into the\n"
        "render of all their samples: the mean of the inputs, each weighted by its\n"
        "samples per pixel (spp).  Inputs and output: .pfm, or .exr when built with\n"
        "OpenEXR.\n"
        "\n"
        "An input's spp comes from --spp, else from its stats file (render --stats):\n"
        "the input's name with .json for its extension (a.pfm: a.json), or the\n"
        "input's name with .json added (a.pfm.json).  Inputs whose stats files\n"
        "hold the same seed are refused: they are the same samples twice; so are\n"
        "inputs whose stats files name another stage or scene file.\n"
        "\n"
        "  -o, --output FILE   the merged image\n"
        "  --spp N             the inputs after this option have N spp each\n"
        "  --variance FILE     also write the per-pixel variance of the merged image\n"
        "                      (2 inputs or more; for compare --variance)\n"
        "  --stats FILE        write the merged image's stats: spp (the sum), inputs,\n"
        "                      variance_dof (inputs - 1), so merges can be merged\n"
        "  -h, --help          this text\n"
        "\n"
        "Exit status: 0 merged, 1 an input or output failed, 2 bad usage.\n",
        f);
}

static bool
parse_spp(const char *value, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(value, &end);
    if (end == value || *end || errno == ERANGE || !(v >= 1 && v <= 1e15)) {
        fprintf(stderr, "merge: error: --spp expects a number of samples >= 1, got '%s'\n", value);
        return false;
    }
    *out = v;
    return true;
}

/* 0: parsed; 1: --help; 2: bad usage (message printed). */
static int
parse_args(int argc, char **argv, struct args *a)
{
    double spp = 0;
    for (int i = 1; i < argc; i++) {
        const char *s = argv[i];
        bool valued = strcmp(s, "-o") == 0 || strcmp(s, "--output") == 0 || strcmp(s, "--spp") == 0
                      || strcmp(s, "--variance") == 0 || strcmp(s, "--stats") == 0;
        if (strcmp(s, "-h") == 0 || strcmp(s, "--help") == 0) {
            return 1;
        } else if (valued && i + 1 >= argc) {
            fprintf(stderr, "merge: error: %s needs a value\n", s);
            return 2;
        } else if (strcmp(s, "-o") == 0 || strcmp(s, "--output") == 0) {
            a->output = argv[++i];
        } else if (strcmp(s, "--variance") == 0) {
            a->variance = argv[++i];
        } else if (strcmp(s, "--stats") == 0) {
            a->stats = argv[++i];
        } else if (strcmp(s, "--spp") == 0) {
            if (!parse_spp(argv[++i], &spp)) {
                return 2;
            }
        } else if (s[0] == '-' && s[1] != '\0') {
            fprintf(stderr, "merge: error: unknown option '%s'\n", s);
            return 2;
        } else if (a->n < MAX_INPUTS) {
            a->inputs[a->n++] = (struct input){.path = s, .spp = spp, .seed = -1};
        } else {
            fprintf(stderr, "merge: error: at most %d inputs\n", MAX_INPUTS);
            return 2;
        }
    }
    if (!a->output || a->n < 1) {
        fprintf(stderr, "merge: error: expected -o OUT and at least one input\n");
        return 2;
    }
    if (a->variance && a->n < 2) {
        fprintf(stderr, "merge: error: --variance needs 2 inputs or more\n");
        return 2;
    }
    return 0;
}

/* Only linear formats go in or out. */
static bool
linear_format(const char *path)
{
    enum image_format f = image_format_from_path(path);
    return f == IMAGE_FORMAT_PFM || f == IMAGE_FORMAT_EXR;
}

/* The JSON string after "key": in text, quotes and escapes kept (two
 * equal strings are written the same way); empty when there is none. */
static void
raw_json_string(const char *text, const char *key, char *out, size_t cap)
{
    char pattern[64];
    snprintf(pattern, sizeof pattern, "\"%s\": \"", key);
    const char *p = text ? strstr(text, pattern) : NULL;
    size_t n = 0;
    if (p) {
        p += strlen(pattern);
        while (*p && *p != '"' && n + 2 < cap) {
            if (*p == '\\' && p[1]) {
                out[n++] = *p++; /* an escape and the character it escapes */
            }
            out[n++] = *p++;
        }
    }
    out[n] = '\0';
}

/* Find the input's stats file and read its spp (unless given), seed, stage
 * and scene. */
static bool
read_input_stats(struct input *in, struct diag *err)
{
    const char *dot = strrchr(in->path, '.');
    const char *slash = strrchr(in->path, '/');
    int stem = dot && (!slash || dot > slash) ? (int)(dot - in->path) : (int)strlen(in->path);
    snprintf(in->stats, sizeof in->stats, "%.*s.json", stem, in->path);
    if (!test_file_exists(in->stats)) {
        snprintf(in->stats, sizeof in->stats, "%s.json", in->path);
    }
    if (!test_file_exists(in->stats)) {
        in->stats[0] = '\0';
    } else {
        if (!test_json_number(in->stats, "seed", &in->seed)) {
            in->seed = -1;
        }
        char *text = test_read_file(in->stats, NULL);
        char stage[128], scene[1024];
        raw_json_string(text, "stage", stage, sizeof stage);
        raw_json_string(text, "scene", scene, sizeof scene);
        /* The scene's file name only: other machines may keep it elsewhere. */
        const char *name = strrchr(scene, '/') ? strrchr(scene, '/') + 1 : scene;
        snprintf(in->what, sizeof in->what, "stage %s, scene %s", stage, name);
        free(text);
    }
    if (in->spp > 0) {
        return true;
    }
    if (!in->stats[0] || !test_json_number(in->stats, "spp", &in->spp) || !(in->spp >= 1)) {
        diag_set(
            err,
            in->path,
            0,
            0,
            "no spp: give --spp N before it, or keep its stats file (%.*s.json)",
            stem,
            in->path);
        return false;
    }
    return true;
}

static bool
check_inputs(struct args *a, struct diag *err)
{
    for (int i = 0; i < a->n; i++) {
        struct input *in = &a->inputs[i];
        if (!linear_format(in->path)) {
            diag_set(
                err,
                in->path,
                0,
                0,
                "merge reads .pfm or .exr (a PNG is clamped and quantised)");
            return false;
        }
        if (!read_input_stats(in, err)) {
            return false;
        }
        for (int j = 0; j < i; j++) {
            const struct input *other = &a->inputs[j];
            if (in->what[0] && other->what[0] && strcmp(in->what, other->what) != 0) {
                diag_set(
                    err,
                    in->path,
                    0,
                    0,
                    "not a render of the same image as %s (%s; %s)",
                    other->path,
                    in->what,
                    other->what);
                return false;
            }
            if (in->seed >= 0 && in->seed == a->inputs[j].seed) {
                diag_set(
                    err,
                    in->path,
                    0,
                    0,
                    "rendered with the same seed (%.0f) as %s: the same samples twice",
                    in->seed,
                    a->inputs[j].path);
                return false;
            }
        }
    }
    return true;
}

static bool
write_stats(const struct args *a, double spp, int width, int height, struct diag *err)
{
    struct atomic_file af;
    if (!atomic_file_open(&af, a->stats, err)) {
        return false;
    }
    fprintf(
        af.f,
        "{\n  \"tool\": \"merge\",\n  \"width\": %d,\n  \"height\": %d,\n  \"spp\": %.17g,\n",
        width,
        height,
        spp);
    fprintf(af.f, "  \"inputs\": %d,\n  \"variance_dof\": %d\n}\n", a->n, a->n - 1);
    return atomic_file_commit(&af, err);
}

static bool
merge(struct args *a, struct diag *err)
{
    if (!linear_format(a->output) || (a->variance && !linear_format(a->variance))) {
        diag_set(
            err,
            a->variance && !linear_format(a->variance) ? a->variance : a->output,
            0,
            0,
            "merge writes .pfm or .exr (linear radiance)");
        return false;
    }
    if (!check_inputs(a, err)) {
        return false;
    }
    struct image *images = calloc((size_t)a->n, sizeof *images);
    double *weights = calloc((size_t)a->n, sizeof *weights);
    struct image mean = {0}, variance = {0};
    bool ok = images && weights;
    if (!ok) {
        diag_set(err, NULL, 0, 0, "out of memory");
    }
    double total = 0;
    for (int i = 0; ok && i < a->n; i++) {
        weights[i] = a->inputs[i].spp;
        total += weights[i];
        ok = imgread(a->inputs[i].path, &images[i], err);
        if (ok && (images[i].width != images[0].width || images[i].height != images[0].height)) {
            diag_set(
                err,
                a->inputs[i].path,
                0,
                0,
                "the image is %dx%d but %s is %dx%d",
                images[i].width,
                images[i].height,
                a->inputs[0].path,
                images[0].width,
                images[0].height);
            ok = false;
        }
    }
    ok = ok && estimate_combine(images, weights, a->n, &mean, a->variance ? &variance : NULL, err);
    ok = ok && image_write(&mean, a->output, err);
    ok = ok && (!a->variance || image_write(&variance, a->variance, err));
    ok = ok && (!a->stats || write_stats(a, total, mean.width, mean.height, err));
    if (ok) {
        printf("merged %d renders, %.17g spp in all, into %s\n", a->n, total, a->output);
    }
    for (int i = 0; images && i < a->n; i++) {
        image_free(&images[i]);
    }
    free(images);
    free(weights);
    image_free(&mean);
    image_free(&variance);
    return ok;
}

int
main(int argc, char **argv)
{
    struct args a = {0};
    a.inputs = calloc(MAX_INPUTS, sizeof *a.inputs);
    if (!a.inputs) {
        fputs("merge: error: out of memory\n", stderr);
        return 1;
    }
    int parsed = parse_args(argc, argv, &a);
    int status = parsed == 2 ? 2 : 0;
    struct diag err = {0};
    if (parsed == 1) {
        usage(stdout);
    } else if (parsed == 2) {
        fputs(usage_line, stderr);
    } else if (!merge(&a, &err)) {
        diag_print(stderr, &err, "error");
        status = 1;
    }
    free(a.inputs);
    return status;
}
