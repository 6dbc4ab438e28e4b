/* cull.c - balls around boxes (cull.h). */
#include "cull.h"

struct cull_ball
cull_ball_around(vec3 lo, vec3 hi)
{
    double d[3] = {(double)hi.x - lo.x, (double)hi.y - lo.y, (double)hi.z - lo.z};
    struct cull_ball b = {
        .center = {((double)lo.x + hi.x) / 2, ((double)lo.y + hi.y) / 2, ((double)lo.z + hi.z) / 2},
        .radius2 = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / 4 * 1.01};
    b.center2 = b.center[0] * b.center[0] + b.center[1] * b.center[1] + b.center[2] * b.center[2];
    return b;
}
