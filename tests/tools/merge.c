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
 * An output that is an input (or its stats file) or another output is
 * refused before any work, by file identity (output_check.h), and so is a
 * stats file beside the output that would describe another image.
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
#include "output_check.h"
#include "testlib.h"

#define MAX_INPUTS 4096

struct input {
    const char *path;
    double spp; /* 0: from its stats file */
    char stats[4096]; /* its stats file, when one was found */
    double *seeds; /* from the stats file: "seed", or a merge's "seeds" */
    int n_seeds; /* 0: unknown */
    char stage[128], scene[1024]; /* as the stats file writes them (empty: not there) */
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
        "No output may be an input, an input's stats file or another output, and\n"
        "a stats file beside -o (OUT's name with .json, or OUT.json) must be the\n"
        "one --stats writes: else a later merge would read it as the merged\n"
        "image's.\n"
        "\n"
        "  -o, --output FILE   the merged image\n"
        "  --spp N             the inputs after this option have N spp each\n"
        "  --variance FILE     also write the per-pixel variance of the merged image\n"
        "                      (2 inputs or more; for compare --variance)\n"
        "  --stats FILE        write the merged image's stats: spp (the sum), inputs,\n"
        "                      variance_dof (inputs - 1), the inputs' stage, scene\n"
        "                      and seeds, so merges can be merged (and merges that\n"
        "                      share a seed are refused)\n"
        "  -h, --help          this text\n"
        "\n"
        "Exit status: 0 merged, 1 an input or output failed, 2 bad usage (an output\n"
        "that is an input or another output).\n",
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
            a->inputs[a->n++] = (struct input){.path = s, .spp = spp};
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

/* The numbers of the JSON array after "key": in text, as a new array
 * (*out, free it); their count, or -1 when there is no such array of
 * numbers or memory ran out. */
static int
json_numbers(const char *text, const char *key, double **out)
{
    char pattern[64];
    snprintf(pattern, sizeof pattern, "\"%s\": [", key);
    const char *p = text ? strstr(text, pattern) : NULL;
    *out = NULL;
    if (!p) {
        return -1;
    }
    p += strlen(pattern);
    int n = 0, cap = 0;
    for (p += strspn(p, " \t\r\n"); *p != ']'; p += strspn(p, " \t\r\n")) {
        char *end;
        double v = strtod(p, &end);
        double *grown = n < cap ? *out : realloc(*out, (size_t)(cap = 2 * cap + 8) * sizeof **out);
        if (end == p || !grown) {
            free(grown ? grown : *out);
            *out = NULL;
            return -1;
        }
        *out = grown;
        (*out)[n++] = v;
        p = end + strspn(end, " \t\r\n");
        p += *p == ',';
    }
    return n;
}

/* The seeds of an input's stats file: a render's "seed", or the "seeds" a
 * merge's stats list. */
static void
read_seeds(struct input *in, const char *text)
{
    double seed;
    in->n_seeds = json_numbers(text, "seeds", &in->seeds);
    if (in->n_seeds < 0 && test_json_number(in->stats, "seed", &seed)
        && (in->seeds = malloc(sizeof *in->seeds)) != NULL) {
        in->seeds[0] = seed;
        in->n_seeds = 1;
    }
    in->n_seeds = in->n_seeds > 0 ? in->n_seeds : 0;
}

/* The stats file of the image at path, as render --stats is told to name
 * it beside the image: the name with .json for its extension (a.json), or
 * with .json added (a.pfm.json), looked for in that order.  False when
 * neither is there; out then holds the first. */
static bool
stats_beside(const char *path, char *out, size_t cap)
{
    const char *dot = strrchr(path, '.');
    const char *slash = strrchr(path, '/');
    int stem = dot && (!slash || dot > slash) ? (int)(dot - path) : (int)strlen(path);
    size_t n = strlen(path);
    if (n + sizeof ".json" <= cap) {
        memcpy(out, path, n);
        memcpy(out + n, ".json", sizeof ".json");
        if (test_file_exists(out)) {
            return true;
        }
    }
    snprintf(out, cap, "%.*s.json", stem, path);
    return test_file_exists(out);
}

/* Find the input's stats file and read its spp (unless given), seeds,
 * stage and scene. */
static bool
read_input_stats(struct input *in, struct diag *err)
{
    bool found = stats_beside(in->path, in->stats, sizeof in->stats);
    if (found) {
        char *text = test_read_file(in->stats, NULL);
        read_seeds(in, text);
        raw_json_string(text, "stage", in->stage, sizeof in->stage);
        raw_json_string(text, "scene", in->scene, sizeof in->scene);
        free(text);
    }
    if (in->spp > 0) {
        return true;
    }
    if (!found || !test_json_number(in->stats, "spp", &in->spp) || !(in->spp >= 1)) {
        diag_set(
            err,
            in->path,
            0,
            0,
            "no spp: give --spp N before it, or keep its stats file (%s)",
            in->stats);
        return false;
    }
    return true;
}

/* The scene's file name only: other machines may keep it elsewhere. */
static const char *
scene_name(const struct input *in)
{
    const char *slash = strrchr(in->scene, '/');
    return slash ? slash + 1 : in->scene;
}

/* in and other render one image, as far as their stats files say. */
static bool
same_image(const struct input *in, const struct input *other, struct diag *err)
{
    if (in->stage[0] && other->stage[0]
        && (strcmp(in->stage, other->stage) != 0
            || strcmp(scene_name(in), scene_name(other)) != 0)) {
        diag_set(
            err,
            in->path,
            0,
            0,
            "not a render of the same image as %s (stage %s, scene %s; stage %s, scene %s)",
            other->path,
            in->stage,
            scene_name(in),
            other->stage,
            scene_name(other));
        return false;
    }
    for (int i = 0; i < in->n_seeds; i++) {
        for (int j = 0; j < other->n_seeds; j++) {
            if (in->seeds[i] == other->seeds[j]) {
                diag_set(
                    err,
                    in->path,
                    0,
                    0,
                    "holds the samples of seed %.17g, as %s does (by their stats files %s and "
                    "%s): the same samples twice",
                    in->seeds[i],
                    other->path,
                    in->stats,
                    other->stats);
                return false;
            }
        }
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
            if (!same_image(in, &a->inputs[j], err)) {
                return false;
            }
        }
    }
    return true;
}

/* The merged image's stats: what a later merge reads (spp, seeds, stage,
 * scene: of the first input that has them) and compare's --variance-dof. */
static bool
write_stats(const struct args *a, double spp, int width, int height, struct diag *err)
{
    struct atomic_file af;
    if (!atomic_file_open(&af, a->stats, err)) {
        return false;
    }
    fputs("{\n  \"tool\": \"merge\",\n", af.f);
    for (int i = 0; i < a->n; i++) {
        if (a->inputs[i].stage[0]) {
            fprintf(
                af.f,
                "  \"stage\": \"%s\",\n  \"scene\": \"%s\",\n",
                a->inputs[i].stage,
                a->inputs[i].scene);
            break;
        }
    }
    fprintf(
        af.f,
        "  \"width\": %d,\n  \"height\": %d,\n  \"spp\": %.17g,\n  \"seeds\": [",
        width,
        height,
        spp);
    const char *separator = "";
    for (int i = 0; i < a->n; i++) {
        for (int j = 0; j < a->inputs[i].n_seeds; j++) {
            fprintf(af.f, "%s%.17g", separator, a->inputs[i].seeds[j]);
            separator = ", ";
        }
    }
    fprintf(af.f, "],\n  \"inputs\": %d,\n  \"variance_dof\": %d\n}\n", a->n, a->n - 1);
    return atomic_file_commit(&af, err);
}

/* The files merge writes, checked before any work (output_check.h): none
 * is an input or an input's stats file, none is another, and the stats
 * file a later merge would read beside -o is --stats (or not there): a
 * stale one would be taken for the merged image's. */
static int
check_outputs(const struct args *a, struct diag *err)
{
    struct named_file outputs[3] = {{"-o", a->output}};
    int n_out = 1;
    if (a->variance) {
        outputs[n_out++] = (struct named_file){"--variance", a->variance};
    }
    if (a->stats) {
        outputs[n_out++] = (struct named_file){"--stats", a->stats};
    }
    struct named_file *inputs = calloc(2 * (size_t)a->n, sizeof *inputs);
    if (!inputs) {
        diag_set(err, NULL, 0, 0, "out of memory");
        return 1;
    }
    int n_in = 0;
    for (int i = 0; i < a->n; i++) {
        inputs[n_in++] = (struct named_file){"the input", a->inputs[i].path};
        if (a->inputs[i].stats[0]) {
            inputs[n_in++] = (struct named_file){"the stats of the input", a->inputs[i].stats};
        }
    }
    enum output_check verdict = output_check(outputs, n_out, inputs, n_in, err);
    free(inputs);
    if (verdict != OUTPUTS_OK) {
        return verdict == OUTPUTS_CLASH ? 2 : 1;
    }
    char beside[4096];
    const struct named_file stale = {"the stats file beside -o", beside};
    if (stats_beside(a->output, beside, sizeof beside)
        && (!a->stats || output_check(&outputs[n_out - 1], 1, &stale, 1, err) == OUTPUTS_OK)) {
        diag_set(
            err,
            beside,
            0,
            0,
            "beside -o %s, it would be read as the merged image's stats by a later merge: write "
            "them there with --stats %s, or remove it",
            a->output,
            beside);
        return 2;
    }
    return 0;
}

/* Everything merge checks before reading an image: the exit status (0:
 * go on; err says why not). */
static int
check(struct args *a, struct diag *err)
{
    if (!linear_format(a->output) || (a->variance && !linear_format(a->variance))) {
        diag_set(
            err,
            a->variance && !linear_format(a->variance) ? a->variance : a->output,
            0,
            0,
            "merge writes .pfm or .exr (linear radiance)");
        return 1;
    }
    return check_inputs(a, err) ? check_outputs(a, err) : 1;
}

static bool
merge(struct args *a, struct diag *err)
{
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
    } else if ((status = check(&a, &err)) != 0 || (status = merge(&a, &err) ? 0 : 1) != 0) {
        diag_print(stderr, &err, "error");
    }
    for (int i = 0; i < a.n; i++) {
        free(a.inputs[i].seeds);
    }
    free(a.inputs);
    return status;
}
