/*
 * 07_extremes_paths.c - the extremes battery, black-box part for the path
 * tracer (stage 07), judged against tests/extremes/expect.tsv (the
 * machinery: tests/extremes/render.h; the glass cases: glass.h).
 * docs/extremes.md describes every case.
 *
 *  - interreflection (case albedo_1_interreflection): the area-light
 *    Cornell box with every albedo 1 is brighter than twice the box with
 *    every albedo 0.5 (the light's own pixels subtracted from both): light
 *    bounces between the walls, so radiance grows faster than the albedo;
 *    and nothing is infinite or NaN although no path loses energy at a
 *    bounce.  (01_extremes_render.c's albedo cases check the direct light
 *    of every stage.)
 *  - optics_glass_furnace, thin_glass: the cases of 04-06_extremes_glass.c,
 *    whose values the path tracer reaches by sampling reflection or
 *    refraction with the Fresnel probability (glass.h has both stages'
 *    expected values).
 *
 * Interreflection and the path tracer's glass are BSDF sampling, lab 07's
 * own work: they live in a stage-07 file so that lab 07's handout fails
 * them among its own tests, not in an earlier stage's file.
 */
#define TAG "paths"

#include "extremes/glass.h"

/* Albedo 1 against twice albedo 0.5, by the ratio of their means. */
static void
run_interreflection(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    (void)c;
    (void)p;
    struct albedo_pair pair;
    if (!render_albedo_pair(&pair, o)) {
        return;
    }
    double sum_one = 0;
    double sum_twice_half = 0;
    for (int i = 0; i < 3 * pair.one.width * pair.one.height; i++) {
        sum_one += pair.one.rgb[i];
        sum_twice_half += pair.twice_half.rgb[i];
    }
    o->figure = sum_one / sum_twice_half;
    o->passed = o->figure > 1 && pair.finite && pair.nan == 0;
    snprintf(
        o->note,
        sizeof o->note,
        "mean radiance (light excluded), albedo 1 / (2 x albedo 0.5): %.4g; nan_pixels %g",
        o->figure,
        pair.nan);
    albedo_pair_free(&pair);
}

TEST(interreflection)
{
    static const struct render_case cases[] = {
        {"albedo_1_interreflection", run_interreflection, 1, 0},
    };
    RUN_CASES(cases);
}

TEST(optics_glass_furnace)
{
    RUN_CASES(glass_furnace_cases);
}

TEST(thin_glass)
{
    RUN_CASES(thin_glass_cases);
}

TEST(second_precision_given)
{
    SKIP_WITHOUT_SECOND_PRECISION();
}

TEST_MAIN(
    TEST_ENTRY(second_precision_given),
    TEST_ENTRY(interreflection),
    TEST_ENTRY(optics_glass_furnace),
    TEST_ENTRY(thin_glass))
