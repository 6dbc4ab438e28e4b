/*
 * 07_compare.c - the compare and merge tools (tests/tools/) on real renders
 * of the path tracer, against the Mitsuba references of three scenes
 * (cornell_diffuse_area, cornell_specular_area, cornell_diffuse_point; the
 * *_gi.pfm files box-downsampled to SIZE x SIZE, as in 07_reference.c).
 *
 * Grading: make grade FULL=1 only (23 processor s: it tests the tools, not
 * the student's stage).
 *
 *  - Two correct renders with different seeds: compare says "consistent"
 *    (exit 0) in every scene.
 *  - The same renders with a planted bias of 2% (one 16x16 block of both
 *    renders scaled so that its mean is 1.02, then 0.98, times the
 *    reference's, whichever way noise had moved it): compare says "biased"
 *    (exit 1), names that block, and that block only.  The block is the
 *    one where the two renders themselves would show a 2% bias most
 *    clearly (their own standard errors and degrees of freedom), so the
 *    test does not depend on where a scene puts its noise (printed: how
 *    many standard errors 2% is there); where that block has so few
 *    degrees of freedom that 2% is under the level of compare's tests,
 *    more is planted (printed).
 *  - merge: MERGE_K renders of SPP / MERGE_K samples merge (spp from their
 *    stats files) into an image that equals, within noise, one render of
 *    SPP samples (block t-tests of their difference), and that passes
 *    compare's block tests against the reference given merge's variance.
 * All renders are SIZE x SIZE with fixed seeds, offset by PATHCHECK_SEED
 * when it is set (pathcheck.h): the outcome is the same on every run, and
 * the statistical level says how rarely a correct renderer fails it at
 * another seed (alpha = 0.01 per comparison; make calibrate-compare runs it at 50
 * offsets: docs/calibration/README.md).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "estimate.h"
#include "metrics.h"
#include "pathcheck.h"
#include "stattest.h"
#include "testlib.h"

/* Under AddressSanitizer renders are several times slower: a quarter of
 * the pixels (4 blocks instead of 16) with the same samples per pixel, and
 * a planted bias of 5% (as 07_reference.c's power check there): the tests
 * stay valid, with less power. */
#if PATHCHECK_SANITIZED
#define SIZE 32
#define BIAS 0.05
#else
#define SIZE 64
#define BIAS 0.02
#endif
#define TEXT_(x) #x
#define TEXT(x) TEXT_(x)
#define FACTOR (256 / SIZE)
/* Samples per render: stage 07's roulette (survivors at full weight) makes
 * the caustic noisier than 08's: at 256 spp a 2% bias in its clearest
 * block is only 5.0 standard errors there (measured), so 07 takes 512. */
#define SPP (atoi(STAGE_NAME) >= 8 ? 256 : 512)
#define BLOCK 16
#define MERGE_K 4
#define OUTPUT_CAP 16384

struct case_ {
    const char *name; /* a short name for the files */
    const char *scene;
    const char *reference;
};

static const struct case_ cases[] = {
    {"area", "scenes/cornell_diffuse_area.scene", "cornell_diffuse_area_gi"},
    {"specular", "scenes/cornell_specular_area.scene", "cornell_specular_area_gi"},
    {"point", "scenes/cornell_diffuse_point.scene", "cornell_diffuse_point_gi"},
};
#define N_CASES (int)(sizeof cases / sizeof cases[0])

/* tmp/<case>_<what>.<ext> */
static const char *
case_path(const struct case_ *c, const char *what, const char *ext)
{
    char name[128];
    snprintf(name, sizeof name, "%s_%s.%s", c->name, what, ext);
    return test_tmp_path(name);
}

/* Render to `path` (PFM) with its stats file beside it (path's stem
 * .json), unless an earlier test of this program already did. */
static bool
render_to(const struct case_ *c, int spp, int seed, const char *path)
{
    if (test_file_exists(path)) {
        return true;
    }
    char spp_text[16], seed_text[32], stats[4096];
    snprintf(spp_text, sizeof spp_text, "%d", spp);
    snprintf(seed_text, sizeof seed_text, "%llu", (unsigned long long)pathcheck_seed(0) + (unsigned)seed);
    snprintf(stats, sizeof stats, "%.*s.json", (int)(strlen(path) - 4), path);
    /* The independent sampler (stage 07's; from 08 on, asked for): the
     * merge test takes one render of SPP samples to have the variance of
     * MERGE_K renders of SPP / MERGE_K (check_equal_within_noise), true of
     * independent samples only (the Sobol sampler's long render converges
     * faster than 1/spp). */
    const char *const all[] = {
        "--sampler",
        "independent",
        "--aa",
        "jitter",
        "-W",
        TEXT(SIZE),
        "-H",
        TEXT(SIZE),
        "--spp",
        spp_text,
        "--seed",
        seed_text,
        "-o",
        path,
        "--stats",
        stats,
        NULL};
    const char *const *args = atoi(STAGE_NAME) >= 8 ? all : all + 4;
    char output[OUTPUT_CAP];
    int status = test_render(test_root_path(c->scene), args, output, sizeof output);
    if (status != 0) {
        printf("render of %s failed (status %d):\n%s\n", c->scene, status, output);
    }
    return status == 0;
}

/* The reference downsampled to SIZE, written to tmp, and its noise as
 * compare's options. */
static bool
reference_to(const struct case_ *c, const char *path, char *rel_se, char *dof, size_t cap)
{
    struct pathcheck_reference ref;
    if (!pathcheck_reference_load(c->reference, FACTOR, &ref)) {
        return false;
    }
    struct diag err = {0};
    bool ok = test_file_exists(path) || image_write(&ref.image, path, &err);
    /* A downsampled pixel averages FACTOR^2 independent reference pixels. */
    snprintf(rel_se, cap, "%.6g", ref.rel_se_pixel / FACTOR);
    snprintf(dof, cap, "%.6g", ref.dof);
    pathcheck_reference_free(&ref);
    if (!ok) {
        diag_print(stdout, &err, "error");
    }
    return ok;
}

/* Run compare with args (NULL-terminated, without the program). */
static int
run_compare(const char *const *args, char *output, size_t cap)
{
    return test_run_tool("compare", args, output, cap);
}

/* The two renders and the reference of case c. */
struct inputs {
    const char *a, *b, *ref;
    char rel_se[32], dof[32];
};

static bool
prepare(const struct case_ *c, struct inputs *in)
{
    in->a = case_path(c, "seed101", "pfm");
    in->b = case_path(c, "seed102", "pfm");
    in->ref = case_path(c, "ref", "pfm");
    return render_to(c, SPP, 101, in->a) && render_to(c, SPP, 102, in->b)
           && reference_to(c, in->ref, in->rel_se, in->dof, sizeof in->rel_se);
}

TEST(two_correct_renders_are_consistent_with_the_reference)
{
    for (int i = 0; i < N_CASES; i++) {
        struct inputs in;
        if (!prepare(&cases[i], &in)) {
            CHECK(false);
            continue;
        }
        char output[OUTPUT_CAP];
        const char *const args[] =
            {in.a, in.b, in.ref, "--ref-rel-se", in.rel_se, "--ref-dof", in.dof, NULL};
        int status = run_compare(args, output, sizeof output);
        printf(
            "%s: exit %d: %s",
            cases[i].name,
            status,
            strstr(output, "verdict") ? strstr(output, "verdict") : output);
        CHECK_MSG(status == 0, "%s", output);
        CHECK(strstr(output, "consistent with the reference") != NULL);
    }
}

/* The block where the renders would show a bias of BIAS most clearly: the
 * smallest p-value of BIAS / (its relative SE) with its degrees of freedom
 * (green channel), from their mean and per-pixel variance.  A block whose
 * noise comes from a few pixels (a light's edge) has few degrees of freedom
 * and is passed over. */
static int
most_precise_block(
    const struct image *a,
    const struct image *b,
    const struct image *ref,
    struct metrics_block_stats *s,
    double *bias)
{
    const struct image pair[2] = {*a, *b};
    struct image mean = {0}, variance = {0};
    struct diag err = {0};
    /* compare's family: the blocks and the windows of 2x2 blocks. */
    struct metrics_block_params params = {.block_size = BLOCK, .windows = true};
    int best = -1;
    if (estimate_combine(pair, NULL, 2, &mean, &variance, &err)
        && metrics_block_stats_variance(&mean, &variance, 1, ref, &params, s, &err)) {
        double best_p = INFINITY, best_t = 0;
        for (int i = 0; i < s->n_blocks; i++) {
            const struct metrics_block *blk = &s->blocks[i];
            double t = BIAS * fabs(blk->mean[1]) / sqrt(blk->var_mean[1]);
            double p = stattest_t_pvalue(t, blk->dof[1]);
            if (blk->mean[1] > 0 && p < best_p) {
                best_p = p;
                best_t = t;
                best = i;
            }
        }
        /* More than BIAS where the block's few degrees of freedom would
         * leave BIAS under the level of one of compare's tests (Sidak over
         * the blocks' and windows' three channels at compare's default
         * alpha, which is PATHCHECK_ALPHA), with a tenfold margin: the specular box's
         * clearest block has 4 to 7 degrees of freedom at some seeds. */
        double level = stattest_sidak(PATHCHECK_ALPHA, 3.0 * (s->n_blocks + s->n_windows));
        *bias = BIAS;
        while (best >= 0 && *bias < 0.5
               && stattest_t_pvalue(*bias / BIAS * best_t, s->blocks[best].dof[1]) > level / 10) {
            *bias *= 1.05;
        }
        printf(
            "  clearest block: %d: a %.0f%% bias is %.1f SE, %.0f dof, p %.2g; planted: %.2g%%\n",
            best,
            100 * BIAS,
            best_t,
            best >= 0 ? s->blocks[best].dof[1] : NAN,
            best_p,
            100 * *bias);
    }
    image_free(&mean);
    image_free(&variance);
    return best;
}

/* Copy of img with block blk's channels scaled by factor[], written to path. */
static bool
write_planted(
    const struct image *img,
    const struct metrics_block *blk,
    const double factor[3],
    const char *path)
{
    struct image copy = {0};
    struct diag err = {0};
    bool ok = image_alloc(&copy, img->width, img->height, &err);
    if (ok) {
        memcpy(copy.rgb, img->rgb, (size_t)img->width * (size_t)img->height * 3 * sizeof(float));
        for (int y = blk->y0; y < blk->y0 + blk->h; y++) {
            for (int x = blk->x0; x < blk->x0 + blk->w; x++) {
                float *p = image_pixel(&copy, x, y);
                for (int ch = 0; ch < 3; ch++) {
                    p[ch] = (float)(p[ch] * factor[ch]);
                }
            }
        }
        ok = image_write(&copy, path, &err);
    }
    if (!ok) {
        diag_print(stdout, &err, "error");
    }
    image_free(&copy);
    return ok;
}

static void
check_planted(
    const struct case_ *c,
    const struct inputs *in,
    const struct image *a,
    const struct image *b,
    const struct metrics_block *blk,
    double scale)
{
    const char *pa = case_path(c, scale > 1 ? "planted_up_a" : "planted_down_a", "pfm");
    const char *pb = case_path(c, scale > 1 ? "planted_up_b" : "planted_down_b", "pfm");
    /* The block's mean made `scale` times the reference's, whatever noise
     * put it above or below the reference: a planted +2% on a block that
     * chance made 1.5% dark would show as 0.5% (seed offset 11 of make
     * test-seeds missed it so). */
    double factor[3];
    for (int ch = 0; ch < 3; ch++) {
        bool usable = blk->mean[ch] > 0 && isfinite(blk->ref_mean[ch] / blk->mean[ch]);
        factor[ch] = usable ? scale * blk->ref_mean[ch] / blk->mean[ch] : scale;
    }
    if (!write_planted(a, blk, factor, pa) || !write_planted(b, blk, factor, pb)) {
        CHECK(false);
        return;
    }
    char output[OUTPUT_CAP], expected[128];
    const char *const args[] =
        {pa, pb, in->ref, "--ref-rel-se", in->rel_se, "--ref-dof", in->dof, NULL};
    int status = run_compare(args, output, sizeof output);
    const char *verdict = strstr(output, "verdict");
    printf(
        "%s, block x %d, y %d made %.3g times the reference: exit %d: %s",
        c->name,
        blk->x0,
        blk->y0,
        scale,
        status,
        verdict ? verdict : output);
    CHECK_MSG(status == 1, "%s", output);
    char one_of[64];
    snprintf(one_of, sizeof one_of, "biased: 1 of %d blocks", (SIZE / BLOCK) * (SIZE / BLOCK));
    CHECK(strstr(output, one_of) != NULL);
    snprintf(
        expected,
        sizeof expected,
        "the block at x %d-%d, y %d-%d is",
        blk->x0,
        blk->x0 + blk->w - 1,
        blk->y0,
        blk->y0 + blk->h - 1);
    CHECK_MSG(strstr(output, expected) != NULL, "expected '%s' in\n%s", expected, output);
    CHECK(
        strstr(output, scale > 1 ? "brighter than the reference" : "darker than the reference")
        != NULL);
}

TEST(a_planted_two_percent_bias_in_one_block_is_found_both_ways)
{
    for (int i = 0; i < N_CASES; i++) {
        struct inputs in;
        struct image a = {0}, b = {0}, ref = {0};
        struct metrics_block_stats s = {0};
        struct diag err = {0};
        bool ok = prepare(&cases[i], &in) && image_read_pfm(in.a, &a, &err)
                  && image_read_pfm(in.b, &b, &err) && image_read_pfm(in.ref, &ref, &err);
        double bias = BIAS;
        int best = ok ? most_precise_block(&a, &b, &ref, &s, &bias) : -1;
        CHECK(best >= 0);
        if (best >= 0) {
            check_planted(&cases[i], &in, &a, &b, &s.blocks[best], 1 + bias);
            check_planted(&cases[i], &in, &a, &b, &s.blocks[best], 1 - bias);
        }
        metrics_block_stats_free(&s);
        image_free(&a);
        image_free(&b);
        image_free(&ref);
    }
}

/* merge MERGE_K renders (spp from their stats files) into tmp files. */
static bool
merge_renders(const struct case_ *c, const char *merged, const char *variance, const char *stats)
{
    const char *argv[16] =
        {test_tool_binary("merge"), "-o", merged, "--variance", variance, "--stats", stats};
    int n = 7;
    for (int k = 0; k < MERGE_K; k++) {
        char what[32];
        snprintf(what, sizeof what, "part%d", k);
        argv[n] = case_path(c, what, "pfm");
        if (!render_to(c, SPP / MERGE_K, 201 + k, argv[n++])) {
            return false;
        }
    }
    argv[n] = NULL;
    char output[OUTPUT_CAP];
    int status = test_run(argv, output, sizeof output);
    CHECK_MSG(status == 0, "merge: %s", output);
    return status == 0;
}

/* The merged image against one long render: their difference has twice
 * the merged image's variance (the same spp, independent samples). */
static void
check_equal_within_noise(
    const char *merged_path,
    const char *variance_path,
    const char *single_path)
{
    struct image merged = {0}, variance = {0}, single = {0};
    struct diag err = {0};
    struct metrics_block_stats s = {0};
    struct metrics_block_params params = {.block_size = BLOCK};
    bool ok = image_read_pfm(merged_path, &merged, &err)
              && image_read_pfm(variance_path, &variance, &err)
              && image_read_pfm(single_path, &single, &err);
    for (size_t i = 0; ok && i < (size_t)variance.width * (size_t)variance.height * 3; i++) {
        variance.rgb[i] *= 2;
    }
    ok = ok
         && metrics_block_stats_variance(
             &merged,
             &variance,
             MERGE_K - 1,
             &single,
             &params,
             &s,
             &err);
    CHECK(ok);
    if (ok) {
        double min_p = 1;
        size_t rejected = metrics_block_rejections(&s, PATHCHECK_ALPHA, &min_p);
        printf(
            "  merged vs one render of %d spp: %d block tests, min p %.3g, %zu rejected\n",
            SPP,
            3 * s.n_blocks,
            min_p,
            rejected);
        CHECK(rejected == 0);
        double mean_m[3], mean_s[3];
        metrics_mean(&merged, NULL, mean_m);
        metrics_mean(&single, NULL, mean_s);
        CHECK_NEAR(mean_m[1] / mean_s[1], 1, 0.02);
    }
    metrics_block_stats_free(&s);
    image_free(&merged);
    image_free(&variance);
    image_free(&single);
}

TEST(merged_renders_equal_one_long_render_and_pass_the_block_tests)
{
    for (int i = 0; i < N_CASES; i++) {
        const struct case_ *c = &cases[i];
        struct inputs in;
        const char *merged = case_path(c, "merged", "pfm");
        const char *variance = case_path(c, "merged_variance", "pfm");
        const char *stats = case_path(c, "merged_stats", "json");
        const char *single = case_path(c, "single", "pfm");
        if (!prepare(c, &in) || !merge_renders(c, merged, variance, stats)
            || !render_to(c, SPP, 301, single)) {
            CHECK(false);
            continue;
        }
        double spp = 0;
        CHECK(test_json_number(stats, "spp", &spp) && spp == SPP);
        check_equal_within_noise(merged, variance, single);
        char output[OUTPUT_CAP], dof[16];
        snprintf(dof, sizeof dof, "%d", MERGE_K - 1);
        const char *const args[] = {
            merged,
            "--variance",
            variance,
            "--variance-dof",
            dof,
            in.ref,
            "--ref-rel-se",
            in.rel_se,
            "--ref-dof",
            in.dof,
            NULL};
        int status = run_compare(args, output, sizeof output);
        const char *verdict = strstr(output, "verdict");
        printf("%s merged: exit %d: %s", c->name, status, verdict ? verdict : output);
        CHECK_MSG(status == 0, "%s", output);
    }
}

TEST_MAIN(
    TEST_ENTRY(two_correct_renders_are_consistent_with_the_reference),
    TEST_ENTRY(a_planted_two_percent_bias_in_one_block_is_found_both_ways),
    TEST_ENTRY(merged_renders_equal_one_long_render_and_pass_the_block_tests))
