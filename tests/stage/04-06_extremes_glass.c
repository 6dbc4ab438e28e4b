/*
 * 04-06_extremes_glass.c - the extremes battery, black-box part for glass
 * in the Whitted stages (04-06): scenes at the edges of the Fresnel
 * equations rendered by the stage's binary and its float build, pixel by
 * pixel against the analytic radiance, judged against
 * tests/extremes/expect.tsv (the cases: tests/extremes/glass.h; the
 * machinery: render.h; 04_extremes_optics.c checks optics.h itself).
 * docs/extremes.md describes every case.
 *
 *  - optics_glass_furnace: a glass sphere of index 1, 1.0001, 2.42 and 10
 *    in a white furnace, pixel by pixel against the Fresnel series;
 *  - thin_glass: a glass slab 1e-5 thick before an area light, pixel by
 *    pixel against the Fresnel transmittance.
 *
 * Before stage 04 glass is shaded as white diffuse (stages/course.c),
 * and from 07 on the path tracer samples it (07_extremes_paths.c runs the
 * same cases there): each is another lab's work, so the cases run in the
 * stages of lab 04's glass only, and lab 04's handout fails them among its
 * own tests, not in an earlier or a later stage's file.
 */
#define TAG "glass"

#include "extremes/glass.h"

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
    TEST_ENTRY(optics_glass_furnace),
    TEST_ENTRY(thin_glass))
