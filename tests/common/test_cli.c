/* test_cli.c - the shared command line and a stage's own options. */
#include <string.h>

#include "check.h"
#include "cli.h"
#include "gltf.h"
#include "image.h"

struct knobs {
    int samples;
    int pair[2];
    real limit;
    bool flag;
    bool on;
    int choice;
};

static enum cli_result
parse(struct knobs *k, struct options *opt, struct diag *err, int argc, const char **argv)
{
    const struct option_spec extra[] = {
        {.name = "samples", .kind = OPT_INT, .dest = &k->samples, .min = 1, .max = 64, .arg = "N"},
        {.name = "adaptive", .kind = OPT_INT_PAIR, .dest = k->pair, .min = 1, .max = 4096},
        {.name = "time", .kind = OPT_REAL, .dest = &k->limit, .min = 0, .max = 1e6},
        {.name = "thing", .kind = OPT_FLAG, .dest = &k->flag},
        {.name = "no-other", .kind = OPT_UNSET, .dest = &k->on},
        {.name = "aa", .kind = OPT_CHOICE, .dest = &k->choice, .choices = "grid|jitter|adaptive"},
        {.name = NULL},
    };
    const struct cli_stage stage = {"99_test", "a test", extra, 16};
    FILE *sink = fopen("/dev/null", "w");
    enum cli_result result = cli_parse(argc, (char **)argv, opt, &stage, sink, err);
    fclose(sink);
    return result;
}

/* What `render --version` prints, into line (empty when it printed nothing). */
static void
version_line(char *line, int size)
{
    const struct option_spec none[] = {{.name = NULL}};
    const struct cli_stage stage = {"99_test", "a test", none, 1};
    const char *argv[] = {"render", "--version"};
    struct options opt;
    struct diag err;
    FILE *out = tmpfile();
    line[0] = '\0';
    if (out) {
        CHECK(cli_parse(2, (char **)argv, &opt, &stage, out, &err) == CLI_EXIT);
        rewind(out);
        if (!fgets(line, size, out)) {
            line[0] = '\0';
        }
        fclose(out);
    }
}

TEST(defaults)
{
    struct knobs k = {0};
    struct options opt;
    struct diag err;
    const char *argv[] = {"render", "a.scene"};
    CHECK(parse(&k, &opt, &err, 2, argv) == CLI_OK);
    CHECK(strcmp(opt.scene_path, "a.scene") == 0);
    CHECK(opt.seed == 1 && opt.threads == 0 && opt.spp == 0 && !opt.quiet && !opt.strict);
    char buf[64];
    CHECK(strcmp(cli_output_path(&opt, buf, sizeof buf), "a.png") == 0);
    CHECK(cli_thread_count(&opt) >= 1);
}

TEST(shared_options_long_short_and_equals)
{
    struct knobs k = {0};
    struct options opt;
    struct diag err;
    const char *argv[] = {
        "render",
        "-o",
        "x.pfm",
        "-W",
        "64",
        "--height=32",
        "-s",
        "16",
        "-t",
        "3",
        "--seed",
        "99",
        "--stats",
        "s.json",
        "-q",
        "--strict",
        "dir/b.scene"};
    CHECK(parse(&k, &opt, &err, 17, argv) == CLI_OK);
    CHECK(strcmp(opt.output, "x.pfm") == 0);
    CHECK(opt.width == 64 && opt.height == 32 && opt.spp == 16 && opt.threads == 3);
    CHECK(opt.seed == 99 && strcmp(opt.stats_path, "s.json") == 0 && opt.quiet && opt.strict);
    CHECK(strcmp(opt.scene_path, "dir/b.scene") == 0);
}

TEST(stage_options)
{
    struct knobs k = {.on = true};
    struct options opt;
    struct diag err;
    const char *argv[] = {
        "render",
        "--samples",
        "8",
        "--adaptive",
        "16,128",
        "--time=2.5",
        "--thing",
        "--aa",
        "adaptive",
        "--no-other",
        "s.scene"};
    CHECK(parse(&k, &opt, &err, 11, argv) == CLI_OK);
    CHECK(k.samples == 8 && k.pair[0] == 16 && k.pair[1] == 128);
    CHECK(k.limit == (real)2.5 && k.flag && !k.on && k.choice == 2);
    const char *value_given[] = {"render", "--no-other=1", "s.scene"};
    CHECK(parse(&k, &opt, &err, 3, value_given) == CLI_ERROR);
}

TEST(errors_say_what_was_expected)
{
    const char *cases[][3] = {
        {"--samples", "0", "s"}, /* below range */
        {"--samples", "x", "s"}, /* not a number */
        {"--adaptive", "16", "s"}, /* not a pair */
        {"--aa", "fancy", "s"}, /* not a choice */
        {"--time", "nan", "s"}, /* not finite */
        {"--frobnicate", "s", "t"}, /* unknown */
        {"-W", "99999", "s"}, /* too large */
        {"s", "t", "-q"}, /* two scenes */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct knobs k = {0};
        struct options opt;
        struct diag err;
        const char *argv[] = {"render", cases[i][0], cases[i][1], cases[i][2]};
        CHECK_MSG(parse(&k, &opt, &err, 4, argv) == CLI_ERROR, "case %zu", i);
        CHECK(err.msg[0] != '\0');
    }
    struct knobs k = {0};
    struct options opt;
    struct diag err;
    const char *missing[] = {"render", "-o"};
    CHECK(parse(&k, &opt, &err, 2, missing) == CLI_ERROR);
    CHECK(strstr(err.msg, "expects a value") != NULL);
    const char *none[] = {"render"};
    CHECK(parse(&k, &opt, &err, 1, none) == CLI_ERROR);
    const char *help[] = {"render", "--help"};
    CHECK(parse(&k, &opt, &err, 2, help) == CLI_EXIT);
}

/* --version names the stage, its precision, and whether this build reads
 * glTF and writes OpenEXR (both optional), as the build really does. */
TEST(version_names_the_optional_libraries)
{
    char line[256];
    version_line(line, sizeof line);
    char expected[256];
    snprintf(
        expected,
        sizeof expected,
        "render (99_test) stagelight 1.0, %s precision, glTF: %s, OpenEXR: %s\n",
        REAL_NAME,
        gltf_available() ? "yes" : "no",
        image_exr_available() ? "yes" : "no");
    CHECK_MSG(strcmp(line, expected) == 0, "got '%s', expected '%s'", line, expected);
}

/* One number syntax for every option: decimal only, the range in every
 * message. */
TEST(one_number_syntax_for_every_option)
{
    const char *refused[][2] = {
        {"--time", "0x10"},
        {"--time", "inf"},
        {"--time", " 1"},
        {"--time", "1e"},
        {"--samples", "0x10"},
        {"--samples", "8.0"},
        {"--samples", " 8"},
        {"--seed", "0x10"},
        {"--seed", "-1"},
        {"-W", "1e3"},
    };
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++) {
        struct knobs k = {0};
        struct options opt;
        struct diag err;
        const char *argv[] = {"render", refused[i][0], refused[i][1], "s"};
        CHECK_MSG(parse(&k, &opt, &err, 4, argv) == CLI_ERROR, "%s %s", argv[1], argv[2]);
    }
    const char *accepted[][2] =
        {{"--time", "1.5e1"}, {"--time", ".5"}, {"--time", "+2"}, {"--samples", "+8"}};
    for (size_t i = 0; i < sizeof accepted / sizeof accepted[0]; i++) {
        struct knobs k = {0};
        struct options opt;
        struct diag err;
        const char *argv[] = {"render", accepted[i][0], accepted[i][1], "s"};
        CHECK_MSG(parse(&k, &opt, &err, 4, argv) == CLI_OK, "%s %s: %s", argv[1], argv[2], err.msg);
    }
    struct knobs k = {0};
    struct options opt;
    struct diag err;
    const char *seed[] = {"render", "--seed", "99999999999999999999", "s"};
    CHECK(parse(&k, &opt, &err, 4, seed) == CLI_ERROR);
    CHECK_MSG(strstr(err.msg, "[0, 9223372036854775807]") != NULL, "%s", err.msg);
}

TEST_MAIN(
    TEST_ENTRY(defaults),
    TEST_ENTRY(shared_options_long_short_and_equals),
    TEST_ENTRY(stage_options),
    TEST_ENTRY(errors_say_what_was_expected),
    TEST_ENTRY(version_names_the_optional_libraries),
    TEST_ENTRY(one_number_syntax_for_every_option))
