/*
 * 05-08_lab_functions.c - lab 05's functions, each on its own (tests/lab/
 * README.md, "Function tests"), in the stages whose tree is lab 05's (from
 * stage 09 on it is split by the surface area heuristic, widened and
 * traversed by lab 09's functions: 09_lab_functions.c).
 *
 *  - build_subtree, through bvh_build, on random soups of spheres, quads
 *    and triangles (a few large quads among them, which the build sets
 *    aside): every primitive is in the tree (or set aside) exactly once;
 *    leaves hold 1 to BVH_MAX_LEAF primitives; the nodes are laid out depth
 *    first (an interior node's first child next to it); every node's box
 *    contains the bounds (prim_bounds) of every primitive below it; an
 *    interior node splits its primitives at the median (the halves differ
 *    by at most one) along the axis where their centroids spread most, the
 *    lower centroids in the first child.
 *  - bvh_intersect: on 3,000 rays per soup, from outside and inside, with
 *    and without a t_max, the closest hit is brute force's (the same
 *    primitive and t; ties to the lower number), the any-hit query
 *    answers as the closest-hit one, and a ray tests under a tenth of the
 *    primitives on average (the tree is used: brute force tests all).
 *
 * Deterministic (fixed seeds).  White-box: bvh_build, bvh_intersect,
 * prim_bounds, struct bvh and intersect_prim.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "check.h"
#include "geometry.h"
#include "rng.h"
#include "stagecheck.h"

/* A primitive's centroid as the build computes it (float, rounded down). */
static float
centroid(const struct world *w, int prim, int axis)
{
    struct box b = prim_bounds(w, prim);
    return float_below((vec3_axis(b.lo, axis) + vec3_axis(b.hi, axis)) / 2);
}

/* Checks the subtree at node id, which must cover slots [first, ...);
 * returns the slot after its last, or -1 after reporting a fault. */
static int
check_node(const struct world *w, uint32_t id, int first, int depth)
{
    const struct bvh *bvh = &w->bvh;
    if ((int)id >= bvh->n_nodes || depth > 64) {
        CHECK_FAIL(
            "build_subtree: node %u is not among the %d nodes written (or the tree is %d deep)",
            id,
            bvh->n_nodes,
            depth);
        return -1;
    }
    const struct bvh_node *node = &bvh->nodes[id];
    int end;
    if (node->count > 0) {
        if (node->count > BVH_MAX_LEAF || (int)node->index != first) {
            CHECK_FAIL(
                "build_subtree: leaf %u holds %u primitives from slot %u (expected at most %d, from slot %d: "
                "leaves in depth-first order)",
                id,
                node->count,
                node->index,
                BVH_MAX_LEAF,
                first);
            return -1;
        }
        end = first + node->count;
    } else {
        int mid = check_node(w, id + 1, first, depth + 1);
        if (mid < 0) {
            return -1;
        }
        end = check_node(w, node->index, mid, depth + 1);
        if (end < 0) {
            return -1;
        }
        /* The median split along the widest centroid spread. */
        float lo[3] = {INFINITY, INFINITY, INFINITY};
        float hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int s = first; s < end; s++) {
            for (int a = 0; a < 3; a++) {
                float c = centroid(w, bvh->prims[s], a);
                lo[a] = fminf(lo[a], c);
                hi[a] = fmaxf(hi[a], c);
            }
        }
        float widest = fmaxf(hi[0] - lo[0], fmaxf(hi[1] - lo[1], hi[2] - lo[2]));
        int n_first = mid - first;
        int n_second = end - mid;
        float first_max = -INFINITY;
        float second_min = INFINITY;
        for (int s = first; s < end; s++) {
            float c = centroid(w, bvh->prims[s], node->axis);
            if (s < mid) {
                first_max = fmaxf(first_max, c);
            } else {
                second_min = fminf(second_min, c);
            }
        }
        bool ok = abs(n_first - n_second) <= 1 && node->axis < 3
                  && hi[node->axis] - lo[node->axis] == widest && first_max <= second_min;
        if (!ok) {
            CHECK_FAIL(
                "build_subtree: node %u splits its %d primitives into %d and %d along axis %d (centroid "
                "spreads x %g, y %g, z %g; the first child's highest centroid %g, the second's lowest %g): "
                "split at the median (halves differ by at most one) along the axis where the centroids "
                "spread most, the lower half first",
                id,
                end - first,
                n_first,
                n_second,
                node->axis,
                (double)(hi[0] - lo[0]),
                (double)(hi[1] - lo[1]),
                (double)(hi[2] - lo[2]),
                (double)first_max,
                (double)second_min);
            return -1;
        }
    }
    for (int s = first; s < end; s++) {
        struct box b = prim_bounds(w, bvh->prims[s]);
        for (int a = 0; a < 3; a++) {
            if (!(node->lo[a] <= vec3_axis(b.lo, a) && node->hi[a] >= vec3_axis(b.hi, a))) {
                CHECK_FAIL(
                    "build_subtree: node %u's box [%g, %g] on axis %d does not contain primitive %d below it "
                    "([%g, %g]): a node's box bounds every primitive of its subtree, rounded outward",
                    id,
                    (double)node->lo[a],
                    (double)node->hi[a],
                    a,
                    bvh->prims[s],
                    (double)vec3_axis(b.lo, a),
                    (double)vec3_axis(b.hi, a));
                return -1;
            }
        }
    }
    return end;
}

TEST(build_subtree_splits_at_the_median_of_the_widest_axis)
{
    struct rng rng = rng_make(5001, 1);
    static const int sizes[] = {1, 2, 5, 40, 300};
    for (int k = 0; k < 5 && !check_current.failed_checks; k++) {
        struct scene s;
        CHECK(stagecheck_random_soup(&rng, sizes[k], &s));
        if (check_current.failed_checks) {
            return;
        }
        struct world w = world_make(&s);
        struct diag err;
        CHECK(bvh_build(&w.bvh, &w, &err));
        /* Each primitive once. */
        char *seen = calloc((size_t)w.n_prims, 1);
        bool once = seen != NULL && w.bvh.n_prims == w.n_prims;
        for (int slot = 0; once && slot < w.bvh.n_prims; slot++) {
            int p = w.bvh.prims[slot];
            once = p >= 0 && p < w.n_prims && !seen[p]++;
        }
        free(seen);
        if (!once) {
            CHECK_FAIL(
                "build_subtree: the tree's slots do not hold each of the %d primitives exactly once",
                w.n_prims);
        } else if (w.bvh.n_aside < w.bvh.n_prims) {
            int end = check_node(&w, 0, w.bvh.n_aside, 0);
            if (end >= 0 && end != w.bvh.n_prims) {
                CHECK_FAIL(
                    "build_subtree: the tree covers slots %d to %d of %d",
                    w.bvh.n_aside,
                    end,
                    w.bvh.n_prims);
            }
        }
        bvh_free(&w.bvh);
        scene_free(&s);
    }
}

TEST(bvh_intersect_finds_what_brute_force_finds)
{
    struct rng rng = rng_make(5002, 2);
    int reported = 0;
    for (int k = 0; k < 3 && reported == 0; k++) {
        struct scene s;
        CHECK(stagecheck_random_soup(&rng, 100 + 100 * k, &s));
        if (check_current.failed_checks) {
            return;
        }
        struct world brute = world_make(&s);
        struct world tree = brute;
        struct diag err;
        CHECK(bvh_build(&tree.bvh, &tree, &err));
        printf(
            "bvh_intersect: a soup of %d primitives, %d set aside\n",
            tree.n_prims,
            tree.bvh.n_aside);
        uint64_t tests = 0;
        int rays = 0;
        for (int i = 0; i < 3000 && reported == 0; i++) {
            vec3 o = vec3_scale(stagecheck_random_vec3(&rng), (real)(i % 3 == 0 ? 0.5 : 3));
            vec3 d = stagecheck_random_vec3(&rng);
            ray r = {o, d};
            real t_max = i % 2 ? REAL_MAX : (real)(4 * (double)rng_uniform(&rng));
            struct hit want;
            struct hit closest;
            struct hit any_hit;
            struct stats st = {0};
            bool hit_want = world_intersect(&brute, r, t_max, &want, &st);
            struct stats cost = {0};
            bool hit_got = bvh_intersect(&tree, r, t_max, false, &closest, &cost);
            tests += cost.prim_tests;
            rays++;
            bool any = bvh_intersect(&tree, r, t_max, true, &any_hit, &st);
            if (hit_got != hit_want
                || (hit_got && (closest.prim != want.prim || closest.t != want.t))
                || any != hit_want) {
                reported++;
                CHECK_FAIL(
                    "bvh_intersect (%d primitives, %d set aside, ray from (%g %g %g) along (%g %g %g), t_max %g): "
                    "closest hit %s primitive %d at t %.9g, any-hit %s; brute force: %s primitive %d at t %.9g: the "
                    "tree must find exactly the closest hit brute force finds (ties to the lower number)",
                    tree.n_prims,
                    tree.bvh.n_aside,
                    (double)o.x,
                    (double)o.y,
                    (double)o.z,
                    (double)d.x,
                    (double)d.y,
                    (double)d.z,
                    (double)t_max,
                    hit_got ? "on" : "none,",
                    hit_got ? closest.prim : -1,
                    hit_got ? (double)closest.t : 0.0,
                    any ? "blocked" : "clear",
                    hit_want ? "on" : "none,",
                    hit_want ? want.prim : -1,
                    hit_want ? (double)want.t : 0.0);
            }
        }
        /* A tree tests a few dozen primitives a ray; brute force all. */
        double per_ray = (double)tests / (rays > 0 ? rays : 1);
        if (reported == 0 && per_ray > 0.1 * tree.n_prims) {
            reported++;
            CHECK_FAIL(
                "bvh_intersect (%d primitives): %.0f primitive tests a ray on average: traverse the tree, testing "
                "only the leaves whose boxes the ray meets (brute force tests them all)",
                tree.n_prims,
                per_ray);
        }
        bvh_free(&tree.bvh);
        scene_free(&s);
    }
}

TEST_MAIN(
    TEST_ENTRY(build_subtree_splits_at_the_median_of_the_widest_axis),
    TEST_ENTRY(bvh_intersect_finds_what_brute_force_finds))
