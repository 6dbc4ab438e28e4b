/*
 * 01_cli.c - the outside contract of every stage's binary (CONTRACT.md):
 * exit codes, no partial output on failure, determinism across thread
 * counts and runs, the statistics JSON, and the one-line notes about scene
 * features the stage does not model.
 */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "course.h"
#include "testlib.h"

/* A small, fast scene using every kind of shape and a point light. */
static const char small_scene[] = "camera origin 0 1 3.9 target 0 1 0 up 0 1 0 fov 40\n"
                                  "image width 48 height 32\n"
                                  "material white diffuse albedo 0.73 0.73 0.73\n"
                                  "material red diffuse albedo 0.65 0.05 0.05\n"
                                  "quad corner -1 0 1 edge1 2 0 0 edge2 0 0 -2 material white\n"
                                  "quad corner -1 0 -1 edge1 0 2 0 edge2 0 0 2 material red\n"
                                  "sphere center -0.45 0.40 -0.30 radius 0.40 material white\n"
                                  "triangle v0 0.2 0 0.2 v1 0.8 0 0.2 v2 0.5 0.8 0 material red\n"
                                  "point_light position 0 1.9 0 intensity 3 2.5 2\n";

static const char *
small_scene_path(void)
{
    const char *path = test_tmp_path("small.scene");
    if (!test_file_exists(path)) {
        test_write_file(path, small_scene);
    }
    return path;
}

TEST(renders_every_output_format)
{
    const char *formats[] = {"png", "ppm", "pfm"};
    for (int i = 0; i < 3; i++) {
        char name[32];
        snprintf(name, sizeof name, "out.%s", formats[i]);
        const char *out = test_tmp_path(name);
        const char *args[] = {"-o", out, NULL};
        char log[4096];
        CHECK_MSG(test_render(small_scene_path(), args, log, sizeof log) == 0, "%s", log);
        CHECK(test_file_exists(out));
    }
}

TEST(same_image_whatever_the_thread_count)
{
    char one[1024];
    char two[1024];
    snprintf(one, sizeof one, "%s", test_tmp_path("t1.pfm"));
    snprintf(two, sizeof two, "%s", test_tmp_path("t2.pfm"));
    const char *args1[] = {"-t", "1", "-o", one, NULL};
    const char *args2[] = {"-t", "2", "-o", two, NULL};
    CHECK(test_render(small_scene_path(), args1, NULL, 0) == 0);
    CHECK(test_render(small_scene_path(), args2, NULL, 0) == 0);
    CHECK(test_same_file(one, two));
    /* and the same again on a second run */
    CHECK(test_render(small_scene_path(), args2, NULL, 0) == 0);
    CHECK(test_same_file(one, two));
}

TEST(stats_json_has_every_contract_key)
{
    const char *stats = test_tmp_path("stats.json");
    const char *args[] = {"--stats", stats, "-o", test_tmp_path("s.pfm"), "--seed", "7", NULL};
    CHECK(test_render(small_scene_path(), args, NULL, 0) == 0);
    for (int i = 0; test_contract_keys[i]; i++) {
        double v;
        CHECK_MSG(
            test_json_number(stats, test_contract_keys[i], &v),
            "key %s",
            test_contract_keys[i]);
    }
    char *text = test_read_file(stats, NULL);
    CHECK(text && strstr(text, "\"stage\": \"" STAGE_NAME "\""));
    CHECK(text && strstr(text, "\"scene\": \""));
    free(text);
    double v = -1;
    CHECK(test_json_number(stats, "width", &v) && v == 48);
    CHECK(test_json_number(stats, "height", &v) && v == 32);
    CHECK(test_json_number(stats, "seed", &v) && v == 7);
    CHECK(test_json_number(stats, "rays_camera", &v) && v >= 48 * 32);
    CHECK(test_json_number(stats, "nan_pixels", &v) && v == 0);
    CHECK(test_json_number(stats, "peak_rss_bytes", &v) && v > 0);
}

TEST(width_override_keeps_aspect_ratio)
{
    const char *stats = test_tmp_path("wstats.json");
    const char *args[] = {"-W", "24", "--stats", stats, "-o", test_tmp_path("w.pfm"), NULL};
    CHECK(test_render(small_scene_path(), args, NULL, 0) == 0);
    double w = 0;
    double h = 0;
    CHECK(test_json_number(stats, "width", &w) && w == 24);
    CHECK(test_json_number(stats, "height", &h) && h == 16);
}

TEST(bad_command_lines_exit_2_and_write_nothing)
{
    char out[1024];
    snprintf(out, sizeof out, "%s", test_tmp_path("never.png"));
    const char *cases[][5] = {
        {"--no-such-option", NULL},
        {"-o", test_tmp_path("never.xyz"), NULL},
        {"-t", "0", "-o", out},
        {"-W", "abc", "-o", out},
        {"--seed", "-3", "-o", out},
        /* A glTF scene's camera, asked of a .scene file. */
        {"--camera", "front", "-o", out},
        /* Passes named after an image --pixel does not write without -o. */
        {"--pixel", "3,3", "--aov", "depth", NULL},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char log[4096];
        int status = test_render(small_scene_path(), cases[i], log, sizeof log);
        CHECK_MSG(status == 2, "case %zu exited %d: %s", i, status, log);
        CHECK(strstr(log, "error: ") != NULL);
    }
    CHECK(!test_file_exists(out));
    CHECK(
        !test_file_exists(test_tmp_path("small.depth.pfm"))
        && !test_file_exists("small.depth.pfm"));
    const char *no_scene[] = {test_render_binary(), NULL};
    CHECK(test_run(no_scene, NULL, 0) == 2);
    const char *help[] = {test_render_binary(), "--help", NULL};
    char log[8192];
    CHECK(test_run(help, log, sizeof log) == 0 && strstr(log, "--threads"));
}

TEST(invalid_scene_exits_1_with_location_and_writes_nothing)
{
    const char *scene = test_tmp_path("bad.scene");
    test_write_file(
        scene,
        "camera origin 0 1 3.9 target 0 1 0 up 0 1 0 fov 40\n"
        "image width 8 height 8\n"
        "sphere center 0 0 0 radius abc material white\n");
    const char *out = test_tmp_path("bad.png");
    const char *args[] = {"-o", out, NULL};
    char log[4096];
    CHECK(test_render(scene, args, log, sizeof log) == 1);
    CHECK_MSG(strstr(log, "bad.scene:3:") != NULL, "%s", log);
    CHECK(!test_file_exists(out));
    const char *missing[] = {"-o", out, NULL};
    CHECK(test_render(test_tmp_path("no-such.scene"), missing, NULL, 0) == 1);
    CHECK(!test_file_exists(out));
}

TEST(unwritable_output_exits_3)
{
    const char *args[] = {"-o", test_tmp_path("no-such-dir/out.png"), NULL};
    char log[4096];
    CHECK(test_render(small_scene_path(), args, log, sizeof log) == 3);
    const char *stats_args[] =
        {"-o", test_tmp_path("ok.pfm"), "--stats", test_tmp_path("no-such-dir/s.json"), NULL};
    CHECK(test_render(small_scene_path(), stats_args, log, sizeof log) == 3);
}

/* Where creating a file fails although access() allows it (root in /proc
 * and /sys), the output is refused before the render, not after it: the
 * pre-check creates the output's temporary file and removes it. */
TEST(outputs_in_proc_and_sys_are_refused_before_the_render)
{
    const char *const dirs[] = {"/proc", "/sys"};
    for (int i = 0; i < 2; i++) {
        char out[64];
        snprintf(out, sizeof out, "%s/stagelight-test.png", dirs[i]);
        const char *args[] = {"-o", out, NULL};
        char log[4096];
        int status = test_render(small_scene_path(), args, log, sizeof log);
        CHECK_MSG(
            status == 3 && strstr(log, "cannot create files in directory"),
            "%s: exit %d: %s",
            out,
            status,
            log);
    }
}

/* --help gives the --spp default, and a render without --spp takes it. */
TEST(help_states_the_spp_default)
{
    const char *args[] = {"--help", NULL};
    static char help[16384];
    CHECK(test_render(NULL, args, help, sizeof help) == 0);
    char line[256] = "";
    const char *at = strstr(help, "--spp N");
    if (at) {
        snprintf(line, sizeof line, "%.*s", (int)strcspn(at, "\n"), at);
    }
    const char *number = strstr(line, "samples per pixel (default ");
    double expected = number ? atof(number + strlen("samples per pixel (default ")) : -1;
    if (strstr(line, "samples per pixel: one, through its centre")) {
        expected = 1;
    }
    CHECK_MSG(expected >= 1, "no default in the --spp line of --help:\n%s", help);
    const char *stats = test_tmp_path("spp.json");
    const char *render_args[] = {"-W", "8", "--stats", stats, "-o", test_tmp_path("spp.pfm"), NULL};
    CHECK(test_render(small_scene_path(), render_args, NULL, 0) == 0);
    double spp = 0;
    CHECK_MSG(
        test_json_number(stats, "spp", &spp) && spp == expected,
        "spp %g, --help says %g",
        spp,
        expected);
}

/* Every feature a stage lacks is named in one line with the stage that adds
 * it; --strict refuses the scene instead. */
TEST(unmodelled_features_are_reported_or_refused)
{
    int here = course_stage_number(STAGE_NAME);
    const char *scene = test_tmp_path("features.scene");
    test_write_file(
        scene,
        "camera origin 0 1 3.9 target 0 1 0 up 0 1 0 fov 40\n"
        "image width 8 height 8\n"
        "background color 0.1 0.1 0.1\n"
        "material chrome mirror reflectance 0.9 0.9 0.9\n"
        "sphere center 0 1 0 radius 0.5 material chrome\n"
        "area_light corner -0.25 1.98 -0.25 edge1 0.5 0 0 edge2 0 0 0.5 "
        "radiance 12 10 8\n");
    const char *out = test_tmp_path("f.pfm");
    const char *args[] = {"-o", out, NULL};
    char log[8192];
    CHECK(test_render(scene, args, log, sizeof log) == 0);

    const enum feature used[] = {FEAT_AREA_LIGHT, FEAT_MIRROR, FEAT_ENVIRONMENT};

    unsigned modelled = course_features_of_stage(here);
    for (int i = 0; i < 3; i++) {
        const struct course_feature *info = course_feature(used[i]);
        bool said = strstr(log, info->name) != NULL;
        CHECK_MSG(said == !(modelled & FEATURE_BIT(used[i])), "%s: %s", info->name, log);
        if (here < info->first_stage) {
            CHECK_MSG(strstr(log, course_stage_name(info->first_stage)) != NULL, "%s", log);
        }
    }
    remove(out);
    const char *strict[] = {"--strict", "-o", out, NULL};
    bool lacks_some = (modelled & FEATURE_BIT(FEAT_AREA_LIGHT)) == 0
                      || (modelled & FEATURE_BIT(FEAT_ENVIRONMENT)) == 0;
    CHECK(test_render(scene, strict, log, sizeof log) == (lacks_some ? 1 : 0));
    CHECK(test_file_exists(out) == !lacks_some);
}

TEST_MAIN(
    TEST_ENTRY(renders_every_output_format),
    TEST_ENTRY(same_image_whatever_the_thread_count),
    TEST_ENTRY(stats_json_has_every_contract_key),
    TEST_ENTRY(width_override_keeps_aspect_ratio),
    TEST_ENTRY(bad_command_lines_exit_2_and_write_nothing),
    TEST_ENTRY(invalid_scene_exits_1_with_location_and_writes_nothing),
    TEST_ENTRY(unwritable_output_exits_3),
    TEST_ENTRY(outputs_in_proc_and_sys_are_refused_before_the_render),
    TEST_ENTRY(help_states_the_spp_default),
    TEST_ENTRY(unmodelled_features_are_reported_or_refused))
