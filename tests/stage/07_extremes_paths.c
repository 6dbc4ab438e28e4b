/*
 * 07_extremes_paths.c - the extremes battery, black-box part for the path
 * tracer (stage 07): albedo 1, where every bounce keeps all the light,
 * judged against tests/extremes/expect.tsv (tests/extremes/render.h has the
 * machinery, shared with 01_extremes_render.c, whose albedo cases check
 * the direct light of every stage).  docs/extremes.md describes the case.
 *
 *  - albedo_1_interreflection: the area-light Cornell box with every
 *    albedo 1 is brighter than twice the box with every albedo 0.5 (the
 *    light's own pixels subtracted from both): light bounces between the
 *    walls, so radiance grows faster than the albedo; and nothing is
 *    infinite or NaN although no path loses energy at a bounce.
 *
 * Interreflection is stage 07's own (BSDF sampling, lab 07): the case lives
 * in a stage-07 file so that lab 07's handout fails it among its own tests,
 * not in an earlier stage's file.
 */
#include <math.h>

#define TAG "paths"

#include "extremes/render.h"

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

TEST(second_precision_given)
{
    SKIP_WITHOUT_SECOND_PRECISION();
}

TEST_MAIN(TEST_ENTRY(second_precision_given), TEST_ENTRY(interreflection))
