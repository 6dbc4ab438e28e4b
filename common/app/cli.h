/*
 * cli.h - the command line every stage's `render` shares (CONTRACT.md),
 * parsed in one place.  A stage adds its own options with a table of
 * struct option_spec, so a new knob is one line in that stage's main.c.
 */
#ifndef CLI_H
#define CLI_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "diag.h"
#include "vec3.h"

struct options {
    const char *scene_path;
    const char *output; /* -o; NULL: <scene name>.png in the current directory */
    int width, height; /* -W, -H; 0: the scene's */
    int spp; /* -s; 0: the stage's default */
    int threads; /* -t; 0: all cores */
    uint64_t seed; /* --seed; default 1 */
    const char *stats_path; /* --stats */
    bool quiet; /* -q */
    bool strict; /* --strict */
    const char *camera; /* --camera: a glTF scene's camera by name; NULL: its first */
    int max_memory_mib; /* --max-memory: refuse a render estimated to need more (MiB);
                           default SCENE_DEFAULT_MAX_BYTES */
    unsigned aov; /* --aov: the render passes to write, bit 1u << enum aov_pass (aov.h) */
    bool has_pixel; /* --pixel X,Y: render and trace only that pixel */
    int pixel[2];
    const char *trace_path; /* --trace: "-" standard output; .json JSON; else text */
    const char *trace_svg_path; /* --trace-svg */
};

enum option_kind {
    OPT_FLAG, /* sets a bool to true */
    OPT_UNSET, /* sets a bool to false (--no-something) */
    OPT_INT, /* int in [min, max] */
    OPT_REAL, /* finite real in [min, max] */
    OPT_INT_PAIR, /* "K,M": two ints in [min, max], stored in int[2] */
    OPT_CHOICE, /* one of the '|'-separated words in choices; stores its index in an int */
};

struct option_spec {
    const char *name; /* long name, without the leading "--" */
    enum option_kind kind;
    void *dest;
    double min, max; /* OPT_INT, OPT_REAL, OPT_INT_PAIR */
    const char *choices; /* OPT_CHOICE, e.g. "grid|jitter|adaptive" */
    const char *arg; /* the argument's name in --help, e.g. "K,M" */
    const char *help;
};

enum cli_result {
    CLI_OK, /* render */
    CLI_EXIT, /* --help or --version was printed: exit 0 */
    CLI_ERROR, /* bad command line (err says why): exit 2 */
};

/* What a stage tells the parser about itself. */
struct cli_stage {
    const char *name; /* STAGE_NAME, e.g. "05_bvh" */
    const char *summary; /* one line for --help */
    const struct option_spec *extra; /* the stage's own options, ended by {.name = NULL} */
    int spp_default; /* --spp's default, for --help; 1: one ray through each pixel's
                        centre, more ignored */
};

/* Parse argv.  opt is filled with defaults first.  --help and --version
 * print to `out`. */
enum cli_result cli_parse(
    int argc,
    char **argv,
    struct options *opt,
    const struct cli_stage *stage,
    FILE *out,
    struct diag *err);

/* Threads to use: opt->threads, or the number of online cores. */
int cli_thread_count(const struct options *opt);

/* The output path: opt->output, or "<scene basename>.png" written into buf. */
const char *cli_output_path(const struct options *opt, char *buf, size_t cap);

#endif /* CLI_H */
