/*
 * cli.c - parse the shared command line and a stage's own options.
 *
 * ISO C has no getopt (it is POSIX), so this is a small table-driven parser:
 * "--name value", "--name=value", and the short forms of CONTRACT.md.
 */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "aov.h"
#include "cli_value.h"
#include "gltf.h"
#include "image.h"
#include "scene.h"
#include "scene_parser.h"

#define STAGELIGHT_VERSION "1.0"

/* The shared options: the same table drives parsing and --help. */
enum shared_id {
    ID_OUTPUT,
    ID_WIDTH,
    ID_HEIGHT,
    ID_SPP,
    ID_THREADS,
    ID_SEED,
    ID_STATS,
    ID_QUIET,
    ID_STRICT,
    ID_CAMERA,
    ID_MAX_MEMORY,
    ID_AOV,
    ID_PIXEL,
    ID_TRACE,
    ID_TRACE_SVG,
    ID_HELP,
    ID_VERSION,
};

struct shared_option {
    enum shared_id id;
    char short_name; /* 0: none */
    const char *name;
    const char *arg; /* NULL: a flag */
    const char *help;
};

static const struct shared_option shared_options[] = {
    {ID_OUTPUT, 'o', "output", "FILE", ".png (8-bit sRGB), .ppm, .pfm (linear float), .exr"},
    {ID_WIDTH, 'W', "width", "N", "override the scene's image width (height scales unless -H)"},
    {ID_HEIGHT, 'H', "height", "N", "override the scene's image height"},
    {ID_SPP, 's', "spp", "N", "samples per pixel (the stage's default: print_help)"},
    {ID_THREADS,
     't',
     "threads",
     "N",
     "threads (default: all cores); the image does not depend on N"},
    {ID_SEED, 0, "seed", "N", "random seed (default 1); same seed and options, same image"},
    {ID_STATS, 0, "stats", "FILE", "write the run's statistics as one JSON object"},
    {ID_QUIET, 'q', "quiet", NULL, "no progress bar"},
    {ID_STRICT, 0, "strict", NULL, "refuse a scene that needs what this stage does not model"},
    {ID_CAMERA, 0, "camera", "NAME", "a glTF scene's camera (default: its first)"},
    {ID_MAX_MEMORY,
     0,
     "max-memory",
     "MIB",
     "refuse a render estimated to need more memory than this (default 4096)"},
    {ID_AOV,
     0,
     "aov",
     "LIST",
     "also write render passes: depth,normal,albedo,id,material,feature (docs/aov.md)"},
    {ID_PIXEL,
     0,
     "pixel",
     "X,Y",
     "render only this pixel (0,0 top left), as in the full render, and trace it"},
    {ID_TRACE,
     0,
     "trace",
     "FILE",
     "with --pixel: its every ray, as text (- for standard output) or .json"},
    {ID_TRACE_SVG, 0, "trace-svg", "FILE", "with --pixel: its paths drawn over the image (SVG)"},
    {ID_HELP, 0, "help", NULL, "print this help"},
    {ID_VERSION, 0, "version", NULL, "print the version"},
};

#define N_SHARED ((int)(sizeof shared_options / sizeof shared_options[0]))

static bool
apply_extra(const struct option_spec *spec, const char *value, struct diag *err)
{
    switch (spec->kind) {
    case OPT_FLAG:
    case OPT_UNSET:
        *(bool *)spec->dest = spec->kind == OPT_FLAG;
        return true;
    case OPT_INT:
        return cli_parse_int(spec->name, value, spec->min, spec->max, spec->dest, err);
    case OPT_REAL:
        return cli_parse_real(spec->name, value, spec->min, spec->max, spec->dest, err);
    case OPT_INT_PAIR:
        return cli_parse_pair(spec, value, err);
    case OPT_CHOICE:
        return cli_parse_choice(spec, value, err);
    }
    return false;
}

static bool
apply_shared(
    enum shared_id id,
    const char *name,
    const char *value,
    struct options *opt,
    struct diag *err)
{
    /* The image's size is known once the scene is loaded: run.c checks
     * that the pixel is in it. */
    const struct option_spec pixel_spec = {
        .name = "pixel",
        .dest = opt->pixel,
        .min = 0,
        .max = SCENE_MAX_IMAGE_DIM - 1,
        .arg = "X,Y",
    };
    long long seed;
    const long long max_seed = 0x7fffffffffffffffLL;
    switch (id) {
    case ID_OUTPUT:
        opt->output = value;
        return true;
    case ID_WIDTH:
        return cli_parse_int(name, value, 1, 16384, &opt->width, err);
    case ID_HEIGHT:
        return cli_parse_int(name, value, 1, 16384, &opt->height, err);
    case ID_SPP:
        return cli_parse_int(name, value, 1, 1 << 24, &opt->spp, err);
    case ID_THREADS:
        return cli_parse_int(name, value, 1, 1024, &opt->threads, err);
    case ID_SEED:
        if (!cli_parse_whole(name, value, 0, max_seed, &seed, err)) {
            return false;
        }
        opt->seed = (uint64_t)seed;
        return true;
    case ID_STATS:
        opt->stats_path = value;
        return true;
    case ID_QUIET:
        opt->quiet = true;
        return true;
    case ID_STRICT:
        opt->strict = true;
        return true;
    case ID_CAMERA:
        opt->camera = value;
        return true;
    case ID_MAX_MEMORY:
        return cli_parse_int(name, value, 1, 1 << 30, &opt->max_memory_mib, err);
    case ID_AOV:
        return aov_parse_list(value, &opt->aov, err);
    case ID_PIXEL:
        opt->has_pixel = true;
        return cli_parse_pair(&pixel_spec, value, err);
    case ID_TRACE:
        opt->trace_path = value;
        return true;
    case ID_TRACE_SVG:
        opt->trace_svg_path = value;
        return true;
    case ID_HELP:
    case ID_VERSION:
        return true;
    }
    return false;
}

static void
print_help(FILE *out, const struct cli_stage *stage)
{
    const struct option_spec *extra = stage->extra;
    fprintf(
        out,
        "usage: render [options] SCENE\n%s: %s\n\noptions:\n",
        stage->name,
        stage->summary);
    for (int i = 0; i < N_SHARED; i++) {
        const struct shared_option *o = &shared_options[i];
        char left[64];
        snprintf(
            left,
            sizeof left,
            "%c%c%s--%s %s",
            o->short_name ? '-' : ' ',
            o->short_name ? o->short_name : ' ',
            o->short_name ? ", " : "  ",
            o->name,
            o->arg ? o->arg : "");
        if (o->id == ID_SPP && stage->spp_default > 1) {
            fprintf(out, "  %-26s samples per pixel (default %d)\n", left, stage->spp_default);
        } else if (o->id == ID_SPP) {
            fprintf(
                out,
                "  %-26s samples per pixel: one, through its centre (more are ignored)\n",
                left);
        } else {
            fprintf(out, "  %-26s %s\n", left, o->help);
        }
    }
    if (extra[0].name) {
        fprintf(out, "\noptions of this stage:\n");
    }
    for (int i = 0; extra[i].name; i++) {
        char left[64];
        snprintf(left, sizeof left, "    --%s %s", extra[i].name, extra[i].arg ? extra[i].arg : "");
        fprintf(out, "  %-26s %s\n", left, extra[i].help);
    }
}

/* Find the option an argument names; sets *shared or *extra_spec. */
static bool
find_option(
    const char *arg,
    const struct option_spec *extra,
    size_t name_len,
    const struct shared_option **shared,
    const struct option_spec **extra_spec)
{
    bool is_long = arg[1] == '-';
    const char *name = arg + (is_long ? 2 : 1);
    for (int i = 0; i < N_SHARED; i++) {
        const struct shared_option *o = &shared_options[i];
        bool match = is_long ? strlen(o->name) == name_len && strncmp(o->name, name, name_len) == 0
                             : o->short_name && name_len == 1 && name[0] == o->short_name;
        if (match) {
            *shared = o;
            return true;
        }
    }
    for (int i = 0; is_long && extra[i].name; i++) {
        if (strlen(extra[i].name) == name_len && strncmp(extra[i].name, name, name_len) == 0) {
            *extra_spec = &extra[i];
            return true;
        }
    }
    return false;
}

/* Handle argv[*i], an option; advances *i past its value. */
static enum cli_result
parse_option(
    int argc,
    char **argv,
    int *i,
    struct options *opt,
    const struct option_spec *extra,
    struct diag *err,
    enum shared_id *seen)
{
    const char *arg = argv[*i];
    const char *eq = arg[1] == '-' ? strchr(arg, '=') : NULL;
    size_t name_len = eq ? (size_t)(eq - arg - 2) : strlen(arg) - (arg[1] == '-' ? 2 : 1);
    const struct shared_option *shared = NULL;
    const struct option_spec *spec = NULL;
    if (!find_option(arg, extra, name_len, &shared, &spec)) {
        diag_set(err, NULL, 0, 0, "unknown option '%s' (see --help)", arg);
        return CLI_ERROR;
    }
    bool takes_value =
        shared ? shared->arg != NULL : spec->kind != OPT_FLAG && spec->kind != OPT_UNSET;
    const char *value = eq ? eq + 1 : NULL;
    if (takes_value && !value) {
        if (*i + 1 >= argc) {
            diag_set(err, NULL, 0, 0, "option '%s' expects a value", arg);
            return CLI_ERROR;
        }
        value = argv[++*i];
    } else if (!takes_value && value) {
        diag_set(err, NULL, 0, 0, "option '%s' takes no value", arg);
        return CLI_ERROR;
    }
    if (shared) {
        *seen = shared->id;
        return apply_shared(shared->id, shared->name, value, opt, err) ? CLI_OK : CLI_ERROR;
    }
    return apply_extra(spec, value, err) ? CLI_OK : CLI_ERROR;
}

/* --trace and --trace-svg trace the pixel --pixel names; --pixel alone
 * prints its trace on standard output. */
static bool
check_trace_options(struct options *opt, struct diag *err)
{
    const char *needs = opt->trace_path ? "--trace" : opt->trace_svg_path ? "--trace-svg" : NULL;
    if (needs && !opt->has_pixel) {
        diag_set(err, NULL, 0, 0, "%s needs --pixel X,Y: the pixel to trace", needs);
        return false;
    }
    if (opt->has_pixel && !opt->trace_path && !opt->trace_svg_path) {
        opt->trace_path = "-";
    }
    const char *streams[] = {opt->stats_path, opt->trace_path, opt->trace_svg_path};
    int to_stdout = 0;
    for (int i = 0; i < 3; i++) {
        to_stdout += streams[i] && strcmp(streams[i], "-") == 0;
    }
    if (to_stdout > 1) {
        diag_set(
            err,
            NULL,
            0,
            0,
            "--stats, --trace and --trace-svg: only one of them can be - (standard output)");
        return false;
    }
    return true;
}

enum cli_result
cli_parse(
    int argc,
    char **argv,
    struct options *opt,
    const struct cli_stage *stage,
    FILE *out,
    struct diag *err)
{
    *opt = (struct options){.seed = 1, .max_memory_mib = (int)(SCENE_DEFAULT_MAX_BYTES >> 20)};
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (arg[0] != '-' || arg[1] == '\0') {
            if (opt->scene_path) {
                diag_set(
                    err,
                    NULL,
                    0,
                    0,
                    "more than one scene given: '%s' and '%s'",
                    opt->scene_path,
                    arg);
                return CLI_ERROR;
            }
            opt->scene_path = arg;
            continue;
        }
        enum shared_id seen = ID_OUTPUT;
        if (parse_option(argc, argv, &i, opt, stage->extra, err, &seen) != CLI_OK) {
            return CLI_ERROR;
        }
        if (seen == ID_HELP) {
            print_help(out, stage);
            return CLI_EXIT;
        }
        if (seen == ID_VERSION) {
            /* The optional libraries too: what a scene may need that this
             * build lacks (glTF meshes, .exr output) shows here first. */
            fprintf(
                out,
                "render (%s) stagelight %s, %s precision, glTF: %s, OpenEXR: %s\n",
                stage->name,
                STAGELIGHT_VERSION,
                REAL_NAME,
                gltf_available() ? "yes" : "no",
                image_exr_available() ? "yes" : "no");
            return CLI_EXIT;
        }
    }
    if (!opt->scene_path) {
        diag_set(err, NULL, 0, 0, "no scene given (usage: render [options] SCENE; see --help)");
        return CLI_ERROR;
    }
    if (opt->camera && !scene_path_is_gltf(opt->scene_path)) {
        diag_set(
            err,
            NULL,
            0,
            0,
            "--camera chooses a camera of a glTF scene (.glb, .gltf); '%s' is not one",
            opt->scene_path);
        return CLI_ERROR;
    }
    /* The passes are named after the image, which --pixel writes only
     * with -o: without it they would land under a name nobody gave. */
    if (opt->aov && opt->has_pixel && !opt->output) {
        diag_set(
            err,
            NULL,
            0,
            0,
            "--aov with --pixel: give -o FILE, the image the passes are named after (--pixel "
            "writes no image without it)");
        return CLI_ERROR;
    }
    return check_trace_options(opt, err) ? CLI_OK : CLI_ERROR;
}

int
cli_thread_count(const struct options *opt)
{
    if (opt->threads > 0) {
        return opt->threads;
    }
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    return cores < 1 ? 1 : cores > 1024 ? 1024 : (int)cores;
}

const char *
cli_output_path(const struct options *opt, char *buf, size_t cap)
{
    if (opt->output) {
        return opt->output;
    }
    const char *base = strrchr(opt->scene_path, '/');
    base = base ? base + 1 : opt->scene_path;
    size_t len = strcspn(base, ".");
    snprintf(buf, cap, "%.*s.png", (int)len, base);
    return buf;
}
