/*
 * test_merge.c - the merge tool (tests/tools/merge.c) on small synthetic
 * images: the weighted mean and variance exactly, spp from the command
 * line and from stats files, merges of merges, and what it refuses.  Real
 * renders are merged in tests/stage/07_compare.c.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "image.h"
#include "testlib.h"

#define CAP 4096
#define TMP(name) test_tmp_path(name)

/* A 3x2 image whose every sample is `v` plus its index. */
static bool
write_flat(const char *name, float v)
{
    struct image img = {0};
    struct diag err = {0};
    bool ok = image_alloc(&img, 3, 2, &err);
    for (int i = 0; ok && i < 18; i++) {
        img.rgb[i] = v + (float)i;
    }
    ok = ok && image_write(&img, TMP(name), &err);
    image_free(&img);
    return ok;
}

static bool
write_stats(const char *name, int spp, int seed)
{
    char text[128];
    snprintf(text, sizeof text, "{\n  \"spp\": %d,\n  \"seed\": %d\n}\n", spp, seed);
    return test_write_file(TMP(name), text);
}

static int
merge(const char *const *args, char *out)
{
    return test_run_tool("merge", args, out, CAP);
}

/* Every sample of the image at path is `v` plus its index (within tol). */
static void
check_flat(const char *path, double v, double tol)
{
    struct image img = {0};
    struct diag err = {0};
    CHECK(image_read_pfm(path, &img, &err));
    for (int i = 0; img.rgb && i < 18; i++) {
        CHECK_NEAR(img.rgb[i], v + i, tol);
    }
    image_free(&img);
}

TEST(inputs_are_weighted_by_their_samples)
{
    char out[CAP];
    CHECK(write_flat("a.pfm", 1) && write_flat("b.pfm", 3));
    const char *const args[] = {
        "-o",
        TMP("m.pfm"),
        "--variance",
        TMP("v.pfm"),
        "--spp",
        "1",
        TMP("a.pfm"),
        "--spp",
        "3",
        TMP("b.pfm"),
        NULL};
    CHECK_MSG(merge(args, out) == 0, "%s", out);
    check_flat(TMP("m.pfm"), 2.5, 1e-5);
    struct image var = {0};
    struct diag err = {0};
    CHECK(image_read_pfm(TMP("v.pfm"), &var, &err));
    for (int i = 0; var.rgb && i < 18; i++) {
        CHECK_NEAR(var.rgb[i], 0.75, 1e-6); /* (1 * 1.5^2 + 3 * 0.5^2) / (1 * 4) */
    }
    image_free(&var);
}

TEST(spp_comes_from_stats_files_and_merges_merge_again)
{
    char out[CAP];
    CHECK(write_flat("r1.pfm", 0) && write_flat("r2.pfm", 2) && write_flat("r3.pfm", 10));
    CHECK(
        write_stats("r1.json", 4, 1) && write_stats("r2.json", 4, 2)
        && write_stats("r3.pfm.json", 8, 3));
    const char *const first[] =
        {"-o", TMP("m12.pfm"), "--stats", TMP("m12.json"), TMP("r1.pfm"), TMP("r2.pfm"), NULL};
    CHECK_MSG(merge(first, out) == 0, "%s", out);
    double spp = 0, dof = 0;
    CHECK(test_json_number(TMP("m12.json"), "spp", &spp) && spp == 8);
    CHECK(test_json_number(TMP("m12.json"), "variance_dof", &dof) && dof == 1);
    check_flat(TMP("m12.pfm"), 1, 1e-5);
    /* The merge of the merge and r3 (8 + 8 spp) is the merge of all three. */
    const char *const second[] = {"-o", TMP("all.pfm"), TMP("m12.pfm"), TMP("r3.pfm"), NULL};
    CHECK_MSG(merge(second, out) == 0, "%s", out);
    check_flat(TMP("all.pfm"), 5.5, 1e-5);
}

TEST(what_merge_refuses)
{
    char out[CAP];
    CHECK(
        write_flat("s1.pfm", 0) && write_flat("s2.pfm", 1) && write_stats("s1.json", 4, 7)
        && write_stats("s2.json", 4, 7));
    struct image small = {0};
    struct diag err = {0};
    CHECK(image_alloc(&small, 2, 2, &err) && image_write(&small, TMP("small.pfm"), &err));
    image_free(&small);
    CHECK(write_flat("nostats.pfm", 0) && write_flat("png.png", 0));
    const char *const same_seed[] = {"-o", TMP("x.pfm"), TMP("s1.pfm"), TMP("s2.pfm"), NULL};
    const char *const no_spp[] = {"-o", TMP("x.pfm"), TMP("nostats.pfm"), TMP("s1.pfm"), NULL};
    const char *const png_in[] =
        {"-o", TMP("x.pfm"), "--spp", "1", TMP("png.png"), TMP("s1.pfm"), NULL};
    const char *const png_out[] = {"-o", TMP("x.png"), TMP("s1.pfm"), NULL};
    const char *const sizes[] =
        {"-o", TMP("x.pfm"), "--spp", "2", TMP("small.pfm"), TMP("s1.pfm"), NULL};
    CHECK(write_flat("o1.pfm", 0) && write_flat("o2.pfm", 1));
    CHECK(test_write_file(
        TMP("o1.json"),
        "{\"stage\": \"07_pathtrace\", \"scene\": \"a.scene\", \"spp\": 4, \"seed\": 1}"));
    CHECK(test_write_file(
        TMP("o2.json"),
        "{\"stage\": \"07_pathtrace\", \"scene\": \"b.scene\", \"spp\": 4, \"seed\": 2}"));
    const char *const scenes[] = {"-o", TMP("x.pfm"), TMP("o1.pfm"), TMP("o2.pfm"), NULL};
    const char *const *failures[] = {same_seed, no_spp, png_in, png_out, scenes, sizes};
    for (size_t i = 0; i < sizeof failures / sizeof failures[0]; i++) {
        int status = merge(failures[i], out);
        CHECK_MSG(status == 1 && strstr(out, "error"), "case %zu: exit %d: %s", i, status, out);
        CHECK(!test_file_exists(TMP("x.pfm")) && !test_file_exists(TMP("x.png")));
    }
    CHECK(strstr(out, "small.pfm") != NULL);
    const char *const no_output[] = {TMP("s1.pfm"), NULL};
    const char *const lone_variance[] =
        {"-o", TMP("x.pfm"), "--variance", TMP("v.pfm"), TMP("s1.pfm"), NULL};
    const char *const bad_spp[] = {"-o", TMP("x.pfm"), "--spp", "0", TMP("s1.pfm"), NULL};
    const char *const *usage[] = {no_output, lone_variance, bad_spp};
    for (size_t i = 0; i < sizeof usage / sizeof usage[0]; i++) {
        CHECK_MSG(merge(usage[i], out) == 2, "usage case %zu: %s", i, out);
    }
    const char *const help[] = {"--help", NULL};
    CHECK(merge(help, out) == 0 && strstr(out, "spp"));
}

/* A render's stats as render --stats writes them (the keys merge reads). */
static bool
write_render_stats(const char *name, int spp, int seed)
{
    char text[256];
    snprintf(
        text,
        sizeof text,
        "{\n  \"stage\": \"07_pathtrace\",\n  \"scene\": \"scenes/box.scene\",\n  \"spp\": %d,\n"
        "  \"seed\": %d\n}\n",
        spp,
        seed);
    return test_write_file(TMP(name), text);
}

/* Merges of merges, as the README says: the merged stats keep the stage,
 * the scene and every seed, so a merge of merges is checked like a merge of
 * renders, and two merges that share a seed are refused, naming it. */
TEST(merges_of_merges_keep_stage_scene_and_seeds)
{
    char out[CAP];
    for (int seed = 1; seed <= 5; seed++) {
        char image[32], stats[32];
        snprintf(image, sizeof image, "d%d.pfm", seed);
        snprintf(stats, sizeof stats, "d%d.json", seed);
        CHECK(write_flat(image, (float)seed) && write_render_stats(stats, 16, seed));
    }
    const char *const m[] =
        {"-o", TMP("m.pfm"), "--stats", TMP("m.json"), TMP("d1.pfm"), TMP("d2.pfm"), TMP("d5.pfm"),
         NULL};
    CHECK_MSG(merge(m, out) == 0, "%s", out);
    char *stats = test_read_file(TMP("m.json"), NULL);
    CHECK_MSG(
        stats && strstr(stats, "\"stage\": \"07_pathtrace\"")
            && strstr(stats, "\"scene\": \"scenes/box.scene\"")
            && strstr(stats, "\"seeds\": [1, 2, 5]"),
        "%s",
        stats ? stats : "(none)");
    free(stats);
    const char *const mm[] =
        {"-o", TMP("mm.pfm"), "--stats", TMP("mm.json"), TMP("m.pfm"), TMP("d3.pfm"), NULL};
    CHECK_MSG(merge(mm, out) == 0 && strstr(out, "64 spp"), "%s", out);
    check_flat(TMP("mm.pfm"), (1 + 2 + 5 + 3) / 4.0, 1e-5);
    double spp = 0;
    CHECK(test_json_number(TMP("mm.json"), "spp", &spp) && spp == 64);
    /* m holds seed 1; so does m2: refused, naming the seed. */
    const char *const m2[] =
        {"-o", TMP("m2.pfm"), "--stats", TMP("m2.json"), TMP("d1.pfm"), TMP("d4.pfm"), NULL};
    CHECK_MSG(merge(m2, out) == 0, "%s", out);
    const char *const shared[] = {"-o", TMP("x.pfm"), TMP("m.pfm"), TMP("m2.pfm"), NULL};
    int status = merge(shared, out);
    CHECK_MSG(
        status == 1 && strstr(out, "seed 1") && strstr(out, "the same samples twice"),
        "%s",
        out);
    const char *const again[] = {"-o", TMP("x.pfm"), TMP("mm.pfm"), TMP("d5.pfm"), NULL};
    status = merge(again, out);
    CHECK_MSG(status == 1 && strstr(out, "seed 5"), "%s", out);
    CHECK(!test_file_exists(TMP("x.pfm")));
}

/* No output overwrites an input, an input's stats or another output, and
 * no stale stats file is left beside -o: exit 2 before any work, the
 * inputs untouched. */
TEST(outputs_never_overwrite_inputs_or_leave_stale_stats)
{
    char out[CAP];
    CHECK(
        write_flat("i1.pfm", 1) && write_flat("i2.pfm", 2) && write_render_stats("i1.json", 4, 1)
        && write_render_stats("i2.json", 4, 2) && test_write_file(TMP("old.json"), "{}\n"));
    char dotted[4200];
    snprintf(dotted, sizeof dotted, "%s/./w.pfm", test_tmp_path(""));
    const char *const onto_input[] = {"-o", TMP("i2.pfm"), TMP("i1.pfm"), TMP("i2.pfm"), NULL};
    const char *const onto_stats[] =
        {"-o", TMP("y.pfm"), "--stats", TMP("i1.json"), TMP("i1.pfm"), TMP("i2.pfm"), NULL};
    const char *const twice[] =
        {"-o", TMP("w.pfm"), "--variance", dotted, TMP("i1.pfm"), TMP("i2.pfm"), NULL};
    const char *const stale[] = {"-o", TMP("old.pfm"), TMP("i1.pfm"), TMP("i2.pfm"), NULL};
    const char *const stale_other[] =
        {"-o", TMP("old.pfm"), "--stats", TMP("new.json"), TMP("i1.pfm"), TMP("i2.pfm"), NULL};
    const char *const *cases[] = {onto_input, onto_stats, twice, stale, stale_other};
    const char *const said[] = {
        "is the input",
        "is the stats of the input",
        "are the same file",
        "old.json: error: beside -o",
        "old.json: error: beside -o"};
    CHECK(test_tool_cases("merge", cases, said, sizeof cases / sizeof cases[0], 2));
    check_flat(TMP("i2.pfm"), 2, 0);
    double seed = 0;
    CHECK(test_json_number(TMP("i1.json"), "seed", &seed) && seed == 1);
    CHECK(
        !test_file_exists(TMP("y.pfm")) && !test_file_exists(TMP("w.pfm"))
        && !test_file_exists(TMP("old.pfm")));
    /* --stats onto the stale file replaces it. */
    const char *const replaced[] =
        {"-o", TMP("old.pfm"), "--stats", TMP("old.json"), TMP("i1.pfm"), TMP("i2.pfm"), NULL};
    CHECK_MSG(merge(replaced, out) == 0, "%s", out);
    double spp = 0;
    CHECK(test_json_number(TMP("old.json"), "spp", &spp) && spp == 8);
}

TEST_MAIN(
    TEST_ENTRY(inputs_are_weighted_by_their_samples),
    TEST_ENTRY(spp_comes_from_stats_files_and_merges_merge_again),
    TEST_ENTRY(what_merge_refuses),
    TEST_ENTRY(merges_of_merges_keep_stage_scene_and_seeds),
    TEST_ENTRY(outputs_never_overwrite_inputs_or_leave_stale_stats))
