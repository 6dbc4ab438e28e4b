/*
 * fuzz_cli.c - render's command line as every stage runs it.
 *
 * The first byte of an input chooses the stage (its value modulo the number
 * of stages); the rest is the argument list after "render", arguments
 * separated by NUL bytes, each its own exact-size allocation (reading past
 * its end is an AddressSanitizer error).  The stage's own main() runs
 * (fuzz_cli_stage.c: its main.c compiled as it is): its option table, and
 * every check before the scene is loaded, the output name and the
 * identity checks of run_parse (common/app/run.c) included.  The run stops
 * where main() would load the scene, so nothing is read, rendered or
 * written.
 *
 * Promises checked:
 *   - a success gives values in their documented ranges (the shared
 *     options, and each stage option within the bounds of the table main()
 *     passed), an output of a format the build writes, outputs that are
 *     not the same name twice and none the scene;
 *   - a refusal exits with a status of the contract (2: bad command line,
 *     3: an output that cannot be written) and prints an error;
 *   - --help and --version exit 0 and print something.
 *
 * The run takes place in the harness's private directory (fuzz_dir()),
 * which holds an existing scene "a.scene" and an existing image "b.png",
 * so relative names meet real files.  What the stage prints goes to memory
 * (stdout and stderr are swapped for in-memory streams during the call, as
 * glibc allows) and is only looked at, so a long run prints nothing.
 */
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fuzz.h"
#include "image.h"
#include "run.h"

#define MAX_ARGS 64
#define MAX_STAGE_OPTIONS 64

/* The stages' main(), renamed (fuzz_cli_stage.c, tests/fuzz/Makefile). */
int fuzz_cli_main_01(int argc, char **argv);
int fuzz_cli_main_02(int argc, char **argv);
int fuzz_cli_main_03(int argc, char **argv);
int fuzz_cli_main_04(int argc, char **argv);
int fuzz_cli_main_05(int argc, char **argv);
int fuzz_cli_main_06(int argc, char **argv);
int fuzz_cli_main_07(int argc, char **argv);
int fuzz_cli_main_08(int argc, char **argv);

/* The hooks fuzz_cli_stage.c puts in place of run_parse and run_load_scene. */
bool fuzz_cli_run_parse(struct run *run, int argc, char **argv, const struct cli_stage *stage);
bool fuzz_cli_load_scene(struct run *run, unsigned modelled, unmodelled_fn unmodelled);

static int (*const stage_mains[])(int, char **) = {
    fuzz_cli_main_01,
    fuzz_cli_main_02,
    fuzz_cli_main_03,
    fuzz_cli_main_04,
    fuzz_cli_main_05,
    fuzz_cli_main_06,
    fuzz_cli_main_07,
    fuzz_cli_main_08,
};
#define N_STAGES (sizeof stage_mains / sizeof stage_mains[0])

/* The exit status main() returns when the run reached the scene's loading. */
#define STOPPED_AT_LOAD 200

/* What one call did, as the hooks saw it. */
static struct {
    bool parsed; /* run_parse said yes */
    bool reached_load; /* main() went on to load the scene */
    bool printed_out, printed_err; /* it printed to stdout, to stderr */
    char broken[512]; /* the first broken promise, reported after the call */
} call;

/* In-memory streams standing in for stdout and stderr during a call. */
#define SINK_BYTES 65536
static char out_text[SINK_BYTES], err_text[SINK_BYTES];
static FILE *out_sink, *err_sink;
static FILE *real_stdout, *real_stderr;

static void DIAG_PRINTF(1, 2) broken(const char *fmt, ...)
{
    if (call.broken[0]) {
        return;
    }
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(call.broken, sizeof call.broken, fmt, ap);
    va_end(ap);
}

/* A stage option's value: two numbers at most (OPT_INT_PAIR). */
struct value {
    double v[2];
};

static struct value
value_of(const struct option_spec *spec)
{
    struct value val = {{0, 0}};
    switch (spec->kind) {
    case OPT_FLAG:
    case OPT_UNSET:
        val.v[0] = *(const bool *)spec->dest;
        break;
    case OPT_INT:
    case OPT_CHOICE:
        val.v[0] = *(const int *)spec->dest;
        break;
    case OPT_REAL:
        val.v[0] = (double)*(const real *)spec->dest;
        break;
    case OPT_INT_PAIR:
        val.v[0] = ((const int *)spec->dest)[0];
        val.v[1] = ((const int *)spec->dest)[1];
        break;
    }
    return val;
}

static int
choice_count(const char *choices)
{
    int n = 1;
    for (const char *c = choices; *c; c++) {
        n += *c == '|';
    }
    return n;
}

/* A stage option the command line set must lie within its table's bounds. */
static void
check_stage_option(const struct option_spec *spec, struct value before)
{
    struct value now = value_of(spec);
    if (now.v[0] == before.v[0] && now.v[1] == before.v[1]) {
        return;
    }
    int n_values = spec->kind == OPT_INT_PAIR ? 2 : 1;
    for (int i = 0; i < n_values; i++) {
        double v = now.v[i];
        bool ok = true;
        switch (spec->kind) {
        case OPT_FLAG:
            ok = v == 1;
            break;
        case OPT_UNSET:
            ok = v == 0;
            break;
        case OPT_CHOICE:
            ok = v >= 0 && v < choice_count(spec->choices);
            break;
        case OPT_INT:
        case OPT_REAL:
        case OPT_INT_PAIR:
            ok = isfinite(v) && v >= spec->min && v <= spec->max;
            break;
        }
        if (!ok) {
            broken("--%s set to %g, outside its table's range", spec->name, v);
        }
    }
}

/* The shared options, the output names and the threads after a success. */
static void
check_parsed(const struct run *run)
{
    const struct options *opt = &run->opt;
    if (!opt->scene_path) {
        broken("a command line without a scene was accepted");
        return;
    }
    if (opt->width < 0 || opt->width > 16384 || opt->height < 0 || opt->height > 16384
        || opt->spp < 0 || opt->spp > (1 << 24) || opt->threads < 0 || opt->threads > 1024
        || opt->max_memory_mib < 1) {
        broken(
            "-W %d -H %d --spp %d -t %d --max-memory %d accepted",
            opt->width,
            opt->height,
            opt->spp,
            opt->threads,
            opt->max_memory_mib);
    }
    int threads = cli_thread_count(opt);
    if (threads < 1 || threads > 1024) {
        broken("cli_thread_count gave %d", threads);
    }
    if (!run->output || memchr(run->default_output, '\0', sizeof run->default_output) == NULL) {
        broken("no terminated output name");
        return;
    }
    if (image_format_from_path(run->output) == IMAGE_FORMAT_UNKNOWN) {
        broken("output '%s' of no known format accepted", run->output);
    }
    if (run->n_outputs < 1 || run->n_outputs > RUN_MAX_OUTPUTS
        || run->outputs[0].path != run->output) {
        broken("%d outputs, the first not the image", run->n_outputs);
        return;
    }
    struct stat st;
    bool scene_exists = stat(opt->scene_path, &st) == 0;
    for (int i = 0; i < run->n_outputs; i++) {
        const char *path = run->outputs[i].path;
        for (int j = 0; j < i; j++) {
            if (strcmp(path, run->outputs[j].path) == 0) {
                broken(
                    "outputs %s and %s are both '%s'",
                    run->outputs[j].what,
                    run->outputs[i].what,
                    path);
            }
        }
        if (scene_exists && strcmp(path, opt->scene_path) == 0) {
            broken("output %s '%s' is the scene", run->outputs[i].what, path);
        }
    }
}

bool
fuzz_cli_run_parse(struct run *run, int argc, char **argv, const struct cli_stage *stage)
{
    struct value before[MAX_STAGE_OPTIONS];
    int n = 0;
    while (stage->extra[n].name) {
        if (n == MAX_STAGE_OPTIONS) {
            broken("more than %d stage options", MAX_STAGE_OPTIONS);
            return false;
        }
        before[n] = value_of(&stage->extra[n]);
        n++;
    }
    call.parsed = run_parse(run, argc, argv, stage);
    if (call.parsed) {
        for (int i = 0; i < n; i++) {
            check_stage_option(&stage->extra[i], before[i]);
        }
        check_parsed(run);
    }
    return call.parsed;
}

bool
fuzz_cli_load_scene(struct run *run, unsigned modelled, unmodelled_fn unmodelled)
{
    (void)modelled;
    (void)unmodelled;
    call.reached_load = true;
    run->status = STOPPED_AT_LOAD;
    return false;
}

/* End the text the call printed to sink (fmemopen does not, after a
 * rewind); true when it printed anything. */
static bool
printed(FILE *sink, char *text)
{
    fflush(sink);
    long end = ftell(sink);
    text[end > 0 && end < SINK_BYTES ? end : end > 0 ? SINK_BYTES - 1 : 0] = '\0';
    return end > 0;
}

/* The exit status and what was printed must agree with what happened. */
static void
check_outcome(int status)
{
    if (call.reached_load) {
        if (!call.parsed || status != STOPPED_AT_LOAD) {
            broken("the scene's loading reached with status %d", status);
        }
        return;
    }
    if (status == EXIT_OK) {
        if (call.parsed || !call.printed_out) {
            broken("exit 0 without --help or --version text");
        }
        return;
    }
    if (status != EXIT_USAGE && status != EXIT_OUTPUT) {
        broken("a command line refused with exit %d", status);
    }
    if (!call.printed_err || !strstr(err_text, "error: ")) {
        broken("exit %d without an error message", status);
    }
}

/* Once: the sinks, the private directory and the files it holds. */
static void
set_up(void)
{
    out_sink = fmemopen(out_text, sizeof out_text, "w");
    err_sink = fmemopen(err_text, sizeof err_text, "w");
    if (!out_sink || !err_sink) {
        fuzz_fail("fmemopen failed");
    }
    static const uint8_t scene[] = "image width 4 height 4\n";
    fuzz_write("a.scene", scene, sizeof scene - 1);
    static const uint8_t png[] = "not read";
    fuzz_write("b.png", png, sizeof png - 1);
}

/* Start a call: empty sinks standing in for stdout and stderr, the private
 * directory as the current one.  Returns the directory to go back to. */
static int
enter_call(void)
{
    memset(&call, 0, sizeof call);
    rewind(out_sink);
    rewind(err_sink);
    int here = open(".", O_RDONLY | O_DIRECTORY);
    if (here < 0 || chdir(fuzz_dir()) != 0) {
        fuzz_fail("cannot enter %s", fuzz_dir());
    }
    real_stdout = stdout;
    real_stderr = stderr;
    stdout = out_sink;
    stderr = err_sink;
    return here;
}

static void
leave_call(int here)
{
    stdout = real_stdout;
    stderr = real_stderr;
    if (fchdir(here) != 0) {
        fuzz_fail("cannot return to the starting directory");
    }
    close(here);
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0) {
        return 0;
    }
    if (!out_sink) {
        set_up();
    }
    size_t stage = data[0] % N_STAGES;
    data++;
    size--;
    static char program[] = "render";
    char *argv[MAX_ARGS + 2] = {program};
    int argc = 1;
    size_t start = 0;
    while (start <= size && argc <= MAX_ARGS) {
        const uint8_t *nul = size > start ? memchr(data + start, '\0', size - start) : NULL;
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
    int here = enter_call();
    int status = stage_mains[stage](argc, argv);
    leave_call(here);
    call.printed_out = printed(out_sink, out_text);
    call.printed_err = printed(err_sink, err_text);
    check_outcome(status);
    if (call.broken[0]) {
        fuzz_fail("stage %02zu: %s (stderr: %.200s)", stage + 1, call.broken, err_text);
    }
    for (int i = 1; i < argc; i++) {
        free(argv[i]);
    }
    return 0;
}
