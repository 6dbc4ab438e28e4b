/*
 * aside.c - the primitives set aside: a wall, put in a leaf beside a few triangles of the statue in
 * the room, would stretch that leaf's box and its ancestors' over the room.  A ray meets a box with
 * a chance of its area over the scene box's (MacDonald and Booth 1990), a light 1 / lights or more.
 */
#include "bvh.h"

#include "geometry.h"

#define BVH_ASIDE_DIVISOR 16 /* set aside: a chance of meeting a ray of 1/16 or more */

real
box_area(struct box b)
{
    vec3 e = vec3_sub(b.hi, b.lo);
    e = vec3_make(e.x > 0 ? e.x : 0, e.y > 0 ? e.y : 0, e.z > 0 ? e.z : 0); /* fmax: a call */
    return 2 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

static real
chance_of_meeting(const struct world *w, int prim, real scene_area)
{
    const struct scene *s = w->scene;
    real chance = box_area(prim_bounds(w, prim)) / scene_area;
    real aimed_at = (real)1 / (s->n_area_lights + s->n_sphere_lights);
    bool light = prim >= s->n_spheres + s->n_quads + s->n_triangles;
    return light && aimed_at > chance ? aimed_at : chance;
}

/* The BVH_MAX_ASIDE likeliest (ties to the lower number), likeliest first.
 * A scene box of zero or infinite area sets none aside. */
int
set_aside(const struct world *w, struct build_ref *refs, struct box scene)
{
    int top[BVH_MAX_ASIDE + 1]; /* the likeliest so far, most likely first */
    real area = box_area(scene);
    int n = 0;
    for (int p = 0; area > 0 && area <= REAL_MAX && p < w->n_prims; p++) {
        real chance = chance_of_meeting(w, p, area);
        if (chance < (real)1 / BVH_ASIDE_DIVISOR) {
            continue;
        }
        int at = n;
        for (; at > 0 && chance_of_meeting(w, top[at - 1], area) < chance; at--) {
            top[at] = top[at - 1];
        }
        top[at] = p;
        n += n < BVH_MAX_ASIDE;
    }
    for (int k = 0; k < n; k++) { /* refs[0, k) hold top[0, k): top[k] is further on */
        int at = k;
        while (refs[at].prim != top[k]) {
            at++;
        }
        struct build_ref ref = refs[at];
        refs[at] = refs[k];
        refs[k] = ref;
    }
    return n;
}
