/*
 * 03_trace.c - what a traced pixel says about soft shadows (docs/inspect.md),
 * from stage 03 on: the ball over the floor of 02_trace.c
 * (tracecheck_ball_scene) under an area light from x = 0 to 2 at height 3.
 * The middle pixel's 16 stratified shadow rays: the rays to the light's
 * points with x^2 + z^2 < 0.81 pass through the ball, so of the 4 x 4
 * cells the two nearest the axis are always blocked and the eight with
 * x >= 1 always clear: between 2 and 8 are blocked (all by the ball) and
 * at least 8 clear; with --adaptive 16,16 the trace says it took the
 * penumbra path.  (07 may draw the light's points by solid angle: there,
 * some are blocked and some not.)  The counts hold only for stratified
 * samples, lab 03's own work: a stage-03 file, so that lab 03's handout
 * fails it among its own tests.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "tracecheck.h"

TEST(penumbra_samples_partly_blocked)
{
    const char *stage = getenv("STAGE");
    const char *scene = tracecheck_ball_scene(
        "area.scene",
        "area_light corner 0 3 -0.5 edge1 2 0 0 edge2 0 0 1 radiance 5 5 5");
    const char *trace = tracecheck_one_vertex(scene, 10, 10, "--shadow-samples", "16");
    CHECK(trace != NULL);
    if (!trace) {
        return;
    }
    int blocked = tracecheck_count(trace, "\"result\": \"blocked\"");
    int clear = tracecheck_count(trace, "\"result\": \"clear\"");
    int by_ball =
        tracecheck_count(trace, "\"blocker\": {\"kind\": \"sphere\", \"index\": 0, \"line\": 4}");
    CHECK(by_ball == blocked);
    CHECK(tracecheck_count(trace, "\"type\": \"light_sample\"") == 16);
    if (stage && strcmp(stage, "07") >= 0) {
        /* 07 may draw the light's points otherwise than uniformly over
         * its area (by solid angle): the strata then fall elsewhere. */
        CHECK_MSG(
            blocked >= 1 && clear >= 1 && blocked + clear == 16,
            "%d blocked, %d clear",
            blocked,
            clear);
        return;
    }
    CHECK_MSG(
        blocked >= 2 && blocked <= 8 && clear >= 8 && blocked + clear == 16,
        "%d blocked, %d clear",
        blocked,
        clear);
    double pdf[16];
    CHECK(tracecheck_numbers(trace, "\"pdf_area\": ", pdf, 16) == 16);
    CHECK_NEAR(pdf[0], 0.5, 1e-6); /* 1 / (2 x 1) */
    const char *adaptive = tracecheck_one_vertex(scene, 10, 10, "--adaptive", "16,16");
    CHECK(adaptive && tracecheck_count(adaptive, "\"more_samples\": 16") == 1);
    CHECK(adaptive && tracecheck_count(adaptive, "penumbra") == 1);
}

TEST_MAIN(TEST_ENTRY(penumbra_samples_partly_blocked))
