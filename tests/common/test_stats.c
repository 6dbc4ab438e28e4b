/* test_stats.c - the report: JSON with every contract key, valid escapes,
 * stage values, atomic writing. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "stats.h"
#include "testlib.h"

static struct report
sample_report(void)
{
    struct report r = {
        .stage = "01_raycast",
        .scene = "dir/with \"quote\".scene",
        .width = 64,
        .height = 48,
        .spp = 1,
        .threads = 2,
        .seed = 5,
        .seconds_total = 1.5,
        .seconds_render = 1.25,
        .counts = {.rays_camera = 3072, .rays_shadow = 100, .prim_tests = 9000},
    };
    r.extra_names[0] = "penumbra_pixels";
    r.counts.extra[0] = 17;
    stats_report_set(&r, "bvh_nodes", 123, true);
    stats_report_set(&r, "bvh_nodes", 125, true);
    stats_report_set(&r, "mean_leaf", 1.75, false);
    return r;
}

TEST(json_has_every_key_and_stage_values)
{
    struct report r = sample_report();
    const char *path = test_tmp_path("stats.json");
    struct diag err;
    CHECK(stats_report_write_json(&r, path, &err));
    static const char *const stage_keys[] = {"penumbra_pixels", "bvh_nodes", "mean_leaf"};
    for (int i = 0; test_contract_keys[i]; i++) {
        double v;
        CHECK_MSG(test_json_number(path, test_contract_keys[i], &v), "%s", test_contract_keys[i]);
    }
    for (size_t i = 0; i < sizeof stage_keys / sizeof stage_keys[0]; i++) {
        double v;
        CHECK_MSG(test_json_number(path, stage_keys[i], &v), "%s", stage_keys[i]);
    }
    double v;
    CHECK(test_json_number(path, "bvh_nodes", &v) && v == 125);
    CHECK(test_json_number(path, "penumbra_pixels", &v) && v == 17);
    CHECK(test_json_number(path, "mean_leaf", &v) && v == 1.75);
    char *text = test_read_file(path, NULL);
    CHECK(text && strstr(text, "\"scene\": \"dir/with \\\"quote\\\".scene\""));
    free(text);
}

TEST(json_write_failure_leaves_nothing)
{
    struct report r = sample_report();
    struct diag err;
    CHECK(!stats_report_write_json(&r, test_tmp_path("missing/dir/s.json"), &err));
    CHECK(strstr(err.msg, "cannot write") != NULL);
}

TEST(printed_report_names_rays_and_rate)
{
    struct report r = sample_report();
    const char *path = test_tmp_path("report.txt");
    FILE *f = fopen(path, "w");
    stats_report_print(f, &r);
    fclose(f);
    char *text = test_read_file(path, NULL);
    CHECK(text && strstr(text, "camera") && strstr(text, "shadow") && strstr(text, "Mrays/s"));
    CHECK(text && strstr(text, "penumbra_pixels"));
    free(text);
    CHECK(stats_peak_rss_bytes() > 0);
    double t0 = stats_clock_seconds();
    CHECK(stats_clock_seconds() >= t0);
}

TEST_MAIN(
    TEST_ENTRY(json_has_every_key_and_stage_values),
    TEST_ENTRY(json_write_failure_leaves_nothing),
    TEST_ENTRY(printed_report_names_rays_and_rate))
