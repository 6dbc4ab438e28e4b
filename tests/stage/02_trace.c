/*
 * 02_trace.c - what a traced pixel says about shadows (docs/inspect.md),
 * from stage 02 on.  A ball of radius 0.3 floats at height 1 over the
 * origin of a floor; the middle pixel sees the floor at the origin.
 *   - Under a point light straight above at height 3, the pixel's shadow
 *     ray is blocked, by the ball of line 4, 0.7 from the floor (3 - 1 -
 *     0.3), and its origin is pushed off the floor by a small offset (< 1e-3,
 *     the float build's bound on an 8-unit floor); a
 *     corner pixel's shadow ray is clear.
 *   - Under an area light from x = 0 to 2 at height 3 (03 on), 16 stratified
 *     shadow rays: the rays to the light's points with x^2 + z^2 < 0.81 pass
 *     through the ball, so of the 4 x 4 cells the two nearest the axis are
 *     always blocked and the eight with x >= 1 always clear: between 2 and 8
 *     are blocked (all by the ball) and at least 8 clear; with --adaptive
 *     16,16 the trace says it took the penumbra path.  (07 may draw the
 *     light's points by solid angle: there, some are blocked and some not.)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "stagecheck.h"
#include "testlib.h"
#include "tracecheck.h"

#define CAP 4096

/* The scene with `light` (a statement) on line 5. */
static const char *
ball_scene(const char *name, const char *light)
{
    return stagecheck_scene(
        name,
        "camera origin 0 4 4 target 0 0 0 up 0 1 0 fov 40\n"
        "image width 21 height 21\n"
        "material white diffuse albedo 0.8 0.8 0.8\n"
        "sphere center 0 1 0 radius 0.3 material white\n"
        "%s\n"
        "quad corner -4 0 -4 edge1 0 0 8 edge2 8 0 0 material white\n",
        light);
}

/* Trace pixel (x, y) of scene with one camera ray through its centre
 * (--aa grid from stage 06 on) and, from stage 07 on, shadow rays at its
 * first vertex only (--max-depth 2); option and value (may be NULL) are
 * added.  The trace's path, or NULL after a failed check. */
static const char *
trace_one_vertex(const char *scene, int x, int y, const char *option, const char *value)
{
    const char *args[12] = {"-s", "1"};
    int n = 2;
    const char *stage = getenv("STAGE");
    if (stage && strcmp(stage, "06") >= 0) {
        args[n++] = "--aa";
        args[n++] = "grid";
    }
    if (stage && strcmp(stage, "07") >= 0) {
        args[n++] = "--max-depth";
        args[n++] = "2";
    }
    if (option) {
        args[n++] = option;
        args[n++] = value;
    }
    args[n] = NULL;
    const char *trace = tracecheck_pixel(scene, x, y, args);
    CHECK(trace != NULL);
    return trace;
}

TEST(blocked_shadow_ray_names_the_ball)
{
    const char *scene = ball_scene("point.scene", "point_light position 0 3 0 intensity 5 5 5");
    const char *trace = trace_one_vertex(scene, 10, 10, NULL, NULL);
    if (!trace) {
        return;
    }
    CHECK(tracecheck_count(trace, "\"result\": \"blocked\"") == 1);
    CHECK(
        tracecheck_count(trace, "\"blocker\": {\"kind\": \"sphere\", \"index\": 0, \"line\": 4}")
        == 1);
    CHECK(
        tracecheck_count(
            trace,
            "\"source\": {\"kind\": \"point_light\", \"index\": 0, \"line\": 5}")
        == 1);
    double t[2];
    CHECK(tracecheck_numbers(trace, "\"blocker_t\": ", t, 2) == 1);
    CHECK_NEAR(t[0], 0.7, 1e-3); /* the origin is offset by up to 3e-4 in float */
    double offset[4];
    int n_offsets = tracecheck_numbers(trace, "\"offset\": ", offset, 4);
    CHECK(n_offsets >= 1);
    CHECK_MSG(offset[0] > 0 && offset[0] < 1e-3, "shadow ray offset %g", offset[0]);
    const char *lit = trace_one_vertex(scene, 1, 19, NULL, NULL);
    CHECK(lit && tracecheck_count(lit, "\"result\": \"clear\"") == 1);
    CHECK(lit && tracecheck_count(lit, "\"result\": \"blocked\"") == 0);
}

TEST(penumbra_samples_partly_blocked)
{
    const char *stage = getenv("STAGE");
    if (stage && strcmp(stage, "03") < 0) {
        SKIP("stage 02 lights from the area light's centre");
    }
    const char *scene = ball_scene(
        "area.scene",
        "area_light corner 0 3 -0.5 edge1 2 0 0 edge2 0 0 1 radiance 5 5 5");
    const char *trace = trace_one_vertex(scene, 10, 10, "--shadow-samples", "16");
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
    const char *adaptive = trace_one_vertex(scene, 10, 10, "--adaptive", "16,16");
    CHECK(adaptive && tracecheck_count(adaptive, "\"more_samples\": 16") == 1);
    CHECK(adaptive && tracecheck_count(adaptive, "penumbra") == 1);
}

TEST_MAIN(
    TEST_ENTRY(blocked_shadow_ray_names_the_ball),
    TEST_ENTRY(penumbra_samples_partly_blocked))
