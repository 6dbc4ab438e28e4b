/*
 * 02_trace.c - what a traced pixel says about shadows (docs/inspect.md),
 * from stage 02 on.  A ball of radius 0.3 floats at height 1 over the
 * origin of a floor; the middle pixel sees the floor at the origin
 * (tracecheck_ball_scene).  Under a point light straight above at height
 * 3, the pixel's shadow ray is blocked, by the ball of line 4, 0.7 from the
 * floor (3 - 1 - 0.3), and its origin is pushed off the floor by a small
 * offset (< 1e-3, the float build's bound on an 8-unit floor); a corner
 * pixel's shadow ray is clear.  Under an area light: 03_trace.c.
 */
#include "check.h"
#include "tracecheck.h"

TEST(blocked_shadow_ray_names_the_ball)
{
    const char *scene =
        tracecheck_ball_scene("point.scene", "point_light position 0 3 0 intensity 5 5 5");
    const char *trace = tracecheck_one_vertex(scene, 10, 10, NULL, NULL);
    CHECK(trace != NULL);
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
            "\"source\": {\"kind\": \"point_light\", "
            "\"index\": 0, \"line\": 5}")
        == 1);
    double t[2];
    CHECK(tracecheck_numbers(trace, "\"blocker_t\": ", t, 2) == 1);
    CHECK_NEAR(t[0], 0.7, 1e-3); /* the origin is offset by up to 3e-4 in float */
    double offset[4];
    int n_offsets = tracecheck_numbers(trace, "\"offset\": ", offset, 4);
    CHECK(n_offsets >= 1);
    CHECK_MSG(offset[0] > 0 && offset[0] < 1e-3, "shadow ray offset %g", offset[0]);
    const char *lit = tracecheck_one_vertex(scene, 1, 19, NULL, NULL);
    CHECK(lit && tracecheck_count(lit, "\"result\": \"clear\"") == 1);
    CHECK(lit && tracecheck_count(lit, "\"result\": \"blocked\"") == 0);
}

TEST_MAIN(TEST_ENTRY(blocked_shadow_ray_names_the_ball))
