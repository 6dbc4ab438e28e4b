/*
 * cull.h - brute force, sooner: a ball around each primitive, and whether a
 * ray's line passes within it.  A brute-force reference (05_bvh's, the
 * watertightness count of 01_extremes_geometry) need not test a primitive
 * whose ball the ray's line passes by: it can only be hit at points of its
 * box, which the ball holds.  The line may pass 64 units of rounding
 * (REAL_EPSILON) of the numbers' magnitude C outside the ball (C^2: the
 * squares of the ball's distance from the ray's origin and of the
 * origin's and the centre's from 0; 64 units: 7.6e-6 C in float, 1.4e-14
 * C in double), where the exact test's rounding moves the ray by a few
 * units.  Without a square root: (r + s)^2 <= 1.01 r^2 + 101 s^2.  So a
 * hit the exact test finds is never passed by, except a degenerate
 * triangle's "hit" far off it (rounding noise for a determinant), which
 * no bounding volume holds: 05_bvh asks full brute force whenever the two
 * answers differ.  Passing a primitive by costs ten multiplications; a
 * triangle test some forty operations.
 */
#ifndef CULL_H
#define CULL_H

#include <stdbool.h>

#include "vec3.h"

struct cull_ball {
    double center[3];
    double radius2; /* squared; 1.01 times the box's half diagonal's */
    double center2; /* |center|^2 */
};

/* The ball around the box from lo to hi. */
struct cull_ball cull_ball_around(vec3 lo, vec3 hi);

/* A ray's line, in double, with its origin's squared distance from 0 and
 * its direction's inverse squared length. */
struct cull_line {
    double o[3], d[3], o2, inv_d2;
};

/* The line through o along d (d not 0). */
static inline struct cull_line
cull_line_make(vec3 o, vec3 d)
{
    struct cull_line l = {{o.x, o.y, o.z}, {d.x, d.y, d.z}, 0, 0};
    l.o2 = l.o[0] * l.o[0] + l.o[1] * l.o[1] + l.o[2] * l.o[2];
    l.inv_d2 = 1 / (l.d[0] * l.d[0] + l.d[1] * l.d[1] + l.d[2] * l.d[2]);
    return l;
}

/* Whether line l passes within ball b, with the slack above. */
static inline bool
cull_line_meets(const struct cull_ball *b, const struct cull_line *l)
{
    const double slack = 101 * (64 * (double)REAL_EPSILON) * (64 * (double)REAL_EPSILON);
    double vx = b->center[0] - l->o[0];
    double vy = b->center[1] - l->o[1];
    double vz = b->center[2] - l->o[2];
    double v2 = vx * vx + vy * vy + vz * vz;
    double along = vx * l->d[0] + vy * l->d[1] + vz * l->d[2];
    return v2 - along * along * l->inv_d2 <= b->radius2 + slack * (v2 + l->o2 + b->center2);
}

#endif
