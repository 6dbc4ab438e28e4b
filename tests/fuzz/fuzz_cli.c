/*
 * fuzz_cli.c - render's command line (cli_parse) with a stage's own options.
 *
 * The input is the argument list after "render", arguments separated by NUL
 * bytes.  Each argument is its own exact-size allocation, so reading past its
 * end is an AddressSanitizer error.  The stage table has one option of every
 * kind (the knobs of stage 07).  A success must give values in the ranges the
 * table and CONTRACT.md state; a failure must say why.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "fuzz.h"

#define MAX_ARGS 64

struct knobs {
    int shadow_samples;
    int adaptive[2];
    int max_depth;
    bool bvh;
    int aa;
    real aa_threshold;
    real time_limit;
};

static void
check_options(const struct options *opt, const struct knobs *k)
{
    if (!opt->scene_path) {
        fuzz_fail("CLI_OK without a scene");
    }
    if (opt->width < 0 || opt->width > 16384 || opt->height < 0 || opt->height > 16384
        || opt->spp < 0 || opt->threads < 0 || opt->threads > 1024 || opt->max_memory_mib < 1) {
        fuzz_fail(
            "-W %d -H %d --spp %d -t %d --max-memory %d",
            opt->width,
            opt->height,
            opt->spp,
            opt->threads,
            opt->max_memory_mib);
    }
    if (k->shadow_samples < 1 || k->max_depth < 1 || k->aa < 0 || k->aa > 2
        || !(k->aa_threshold >= 0 && k->aa_threshold <= 1)
        || !(k->time_limit >= 0 && k->time_limit <= 1e9)) {
        fuzz_fail("a stage option out of its range");
    }
    int threads = cli_thread_count(opt);
    if (threads < 1 || threads > 1024) {
        fuzz_fail("cli_thread_count gave %d", threads);
    }
    char buf[64];
    const char *out = cli_output_path(opt, buf, sizeof buf);
    if (!out || memchr(out, '\0', out == buf ? sizeof buf : strlen(out) + 1) == NULL) {
        fuzz_fail("cli_output_path gave no terminated name");
    }
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct knobs k = {.shadow_samples = 1, .max_depth = 1 << 16, .aa = 1, .bvh = true};
    const struct option_spec extra[] = {
        {"shadow-samples", OPT_INT, &k.shadow_samples, 1, 1 << 16, NULL, "N", "rays"},
        {"adaptive", OPT_INT_PAIR, k.adaptive, 1, 1 << 16, NULL, "K,M", "probes"},
        {"max-depth", OPT_INT, &k.max_depth, 1, 1 << 16, NULL, "N", "depth"},
        {"no-bvh", OPT_UNSET, &k.bvh, 0, 0, NULL, NULL, "brute force"},
        {"aa", OPT_CHOICE, &k.aa, 0, 0, "grid|jitter|adaptive", "PATTERN", "pattern"},
        {"aa-threshold", OPT_REAL, &k.aa_threshold, 0, 1, NULL, "T", "contrast"},
        {"time", OPT_REAL, &k.time_limit, 0, 1e9, NULL, "SECONDS", "budget"},
        {.name = NULL},
    };
    const struct cli_stage stage = {"07_fuzz", "fuzzed", extra};
    static char program[] = "render";
    static FILE *sink;
    if (!sink && !(sink = fopen("/dev/null", "w"))) {
        abort();
    }
    char *argv[MAX_ARGS + 2] = {program};
    int argc = 1;
    size_t start = 0;
    while (start <= size && argc <= MAX_ARGS) {
        const uint8_t *nul = memchr(data + start, '\0', size - start);
        size_t len = nul ? (size_t)(nul - (data + start)) : size - start;
        argv[argc] = malloc(len + 1);
        if (!argv[argc]) {
            break;
        }
        memcpy(argv[argc], data + start, len);
        argv[argc++][len] = '\0';
        start += len + 1;
    }
    argv[argc] = NULL;
    struct options opt;
    struct diag err = {0};
    switch (cli_parse(argc, argv, &opt, &stage, sink, &err)) {
    case CLI_OK:
        check_options(&opt, &k);
        break;
    case CLI_ERROR:
        fuzz_require_message(&err, "cli_parse");
        break;
    case CLI_EXIT:
        break;
    }
    for (int i = 1; i < argc; i++) {
        free(argv[i]);
    }
    return 0;
}
