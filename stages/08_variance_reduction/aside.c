/*
 * aside.c - the primitives set aside: a wall of a room, placed by its
 * centroid in a leaf beside a few triangles of the statue in it, would make
 * that leaf's box and its ancestors' span the room.  A ray meets a box with
 * a chance estimated by its surface area over the scene box's (MacDonald
 * and Booth 1990), a light at least 1 / (number of lights): shadow rays aim
 * at one.  docs/stages/05_bvh.md has the measurements.
 */
#include "bvh.h"

#include "geometry.h"

static real
box_area(struct box b)
{
    vec3 e = vec3_max(vec3_sub(b.hi, b.lo), vec3_splat(0));
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

/* The BVH_MAX_ASIDE likeliest of those with a chance of at least
 * 1/BVH_ASIDE_DIVISOR (ties to the lower number).  The k-th chosen,
 * primitive p >= k, is swapped with refs[k], which no later swap moves.  A
 * scene box of zero or infinite area sets none aside. */
int
set_aside(const struct world *w, struct build_ref *refs, struct box scene)
{
    struct {
        real chance;
        int prim;
    } top[BVH_MAX_ASIDE + 1]; /* the likeliest so far, most likely first */
    real area = box_area(scene);
    int n = 0;
    for (int p = 0; area > 0 && area <= REAL_MAX && p < w->n_prims; p++) {
        real chance = chance_of_meeting(w, p, area);
        if (chance < (real)1 / BVH_ASIDE_DIVISOR) {
            continue;
        }
        int at = n;
        for (; at > 0 && top[at - 1].chance < chance; at--) {
            top[at] = top[at - 1];
        }
        top[at].chance = chance;
        top[at].prim = p;
        n += n < BVH_MAX_ASIDE;
    }
    for (int p = 0, k = 0; k < n; p++) {
        bool chosen = false;
        for (int i = 0; i < n; i++) {
            chosen = chosen || top[i].prim == p;
        }
        if (chosen) {
            struct build_ref ref = refs[p];
            refs[p] = refs[k];
            refs[k++] = ref;
        }
    }
    return n;
}
