/*
 * 09_lab_functions.c - lab 09's functions, each on its own (tests/lab/
 * README.md, "Function tests").
 *
 *  - sah_split: on random boxes (spread, clustered, flat, a few large), the
 *    refs are permuted, not changed; those before the count returned lie
 *    on the lower side of one plane across the axis returned; and the
 *    split's cost, area(lower) n(lower) + area(upper) n(upper), is the least
 *    among the planes between SAH_BINS equal bins of the centroids' extent
 *    on each axis (within 1e-3: a centroid on a bin's edge may fall either
 *    way).
 *  - gather_children, through bvh_build (widen): a node has fewer than BVH_WIDTH children
 *    only when all of them are leaves (the collapse opens inner children
 *    while there is room).  05_bvh checks the rest of the wide tree.
 *  - meet_boxes, through bvh_intersect on eight small triangles in four
 *    pairs, which the build puts in one node with four leaves (no stack,
 *    no traversal order): every hit brute force finds, for rays through
 *    the triangles' corners and edges (which lie on the leaves' boxes),
 *    along the axes and not, and far from the origin (1e3, 1e6); a ray
 *    that misses every box, or whose line crosses one only behind its
 *    origin (t < 0), tests no primitive.
 *  - traverse: on random soups of 3,000 and 9,000 primitives, the closest
 *    hit and any-hit answer brute force's; at least the nodes whose boxes
 *    the ray meets before its hit are visited; the nearest child first: a
 *    closest-hit ray visits at most 1.4 times the nodes whose boxes meet it
 *    before its hit (measured 1.08x and 1.11x; the farthest child first
 *    1.74x); an any-hit ray stops at its first hit: on blocked rays it
 *    tests fewer primitives in fewer boxes than the closest-hit query.
 *
 * Deterministic (fixed seeds).  White-box: bvh.h (struct bvh_wide,
 * sah_split, struct build_ref), bvh_build, bvh_intersect, world_intersect.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bvh.h"
#include "check.h"
#include "geometry.h"
#include "rng.h"
#include "stagecheck.h"

/* --- sah_split ------------------------------------------------------------ */

struct dbox {
    double lo[3], hi[3];
    int n;
};

static void
dbox_add(struct dbox *b, const float lo[3], const float hi[3])
{
    for (int a = 0; a < 3; a++) {
        b->lo[a] = b->n == 0 || lo[a] < b->lo[a] ? lo[a] : b->lo[a];
        b->hi[a] = b->n == 0 || hi[a] > b->hi[a] ? hi[a] : b->hi[a];
    }
    b->n++;
}

static double
dbox_cost(const struct dbox *b)
{
    double x = b->hi[0] - b->lo[0];
    double y = b->hi[1] - b->lo[1];
    double z = b->hi[2] - b->lo[2];
    return b->n > 0 ? 2 * (x * y + y * z + z * x) * b->n : 0;
}

/* The least cost among the SAH_BINS - 1 planes of each axis; INFINITY when
 * every centroid falls in one bin on every axis. */
static double
least_cost(const struct build_ref *refs, int n)
{
    double lo[3];
    double hi[3];
    for (int a = 0; a < 3; a++) {
        lo[a] = INFINITY;
        hi[a] = -INFINITY;
        for (int i = 0; i < n; i++) {
            lo[a] = fmin(lo[a], refs[i].centroid[a]);
            hi[a] = fmax(hi[a], refs[i].centroid[a]);
        }
    }
    double best = INFINITY;
    for (int a = 0; a < 3; a++) {
        if (!(hi[a] > lo[a])) {
            continue;
        }
        for (int plane = 1; plane < SAH_BINS; plane++) {
            struct dbox below = {{0}, {0}, 0};
            struct dbox above = {{0}, {0}, 0};
            for (int i = 0; i < n; i++) {
                int k = (int)((refs[i].centroid[a] - lo[a]) / (hi[a] - lo[a]) * SAH_BINS);
                dbox_add(k < plane ? &below : &above, refs[i].lo, refs[i].hi);
            }
            if (below.n > 0 && above.n > 0) {
                best = fmin(best, dbox_cost(&below) + dbox_cost(&above));
            }
        }
    }
    return best;
}

/* n random boxes: spread over [-1, 1]^3, or in two clusters, or flat in z,
 * and every tenth ten times larger. */
static void
random_refs(struct rng *rng, int n, int kind, struct build_ref *refs)
{
    for (int i = 0; i < n; i++) {
        double size = i % 10 == 9 ? 0.5 : 0.05;
        for (int a = 0; a < 3; a++) {
            double c = 2 * (double)rng_uniform(rng) - 1;
            if (kind == 1) {
                c = (i % 2 ? 0.8 : -0.6) + 0.1 * c;
            }
            if (kind == 2 && a == 2) {
                c = 0.25;
            }
            double half = size * (double)rng_uniform(rng);
            refs[i].lo[a] = float_below(c - half);
            refs[i].hi[a] = float_above(c + half);
            refs[i].centroid[a] = float_below((refs[i].lo[a] + (double)refs[i].hi[a]) / 2);
        }
        refs[i].prim = i;
    }
}

static int
compare_prims(const void *a, const void *b)
{
    return ((const struct build_ref *)a)->prim - ((const struct build_ref *)b)->prim;
}

TEST(sah_split_takes_the_cheapest_plane)
{
    struct rng rng = rng_make(9001, 1);
    static const int sizes[] = {2, 3, 17, 100, 1000};
    struct build_ref *refs = malloc(1000 * sizeof *refs);
    struct build_ref *before = malloc(1000 * sizeof *before);
    CHECK(refs && before);
    for (int c = 0; c < 15 && refs && before && !check_current.failed_checks; c++) {
        int n = sizes[c % 5];
        int kind = c / 5;
        random_refs(&rng, n, kind, refs);
        memcpy(before, refs, (size_t)n * sizeof *refs);
        int axis = -1;
        int j = sah_split(refs, n, &axis);
        double least = least_cost(before, n);
        if (j <= 0 || j >= n || axis < 0 || axis > 2) {
            CHECK_MSG(
                j == 0 && least == INFINITY,
                "sah_split: %d boxes (%s): returned %d below the plane on axis %d; there is a plane with "
                "boxes on both sides (cost %g)",
                n,
                kind == 0 ? "spread" : kind == 1 ? "two clusters" : "flat in z",
                j,
                axis,
                least);
            continue;
        }
        struct dbox below = {{0}, {0}, 0};
        struct dbox above = {{0}, {0}, 0};
        float max_below = -INFINITY;
        float min_above = INFINITY;
        for (int i = 0; i < n; i++) {
            dbox_add(i < j ? &below : &above, refs[i].lo, refs[i].hi);
            float key = refs[i].centroid[axis];
            max_below = i < j && key > max_below ? key : max_below;
            min_above = i >= j && key < min_above ? key : min_above;
        }
        double cost = dbox_cost(&below) + dbox_cost(&above);
        CHECK_MSG(
            max_below <= min_above,
            "sah_split: %d boxes: the first %d are not all below the others on axis %d (a centroid at "
            "%g below, %g above): partition by the plane's bin",
            n,
            j,
            axis,
            (double)max_below,
            (double)min_above);
        CHECK_MSG(
            cost <= least * (1 + 1e-3),
            "sah_split: %d boxes (%s): the split's cost, area x count below plus above, is %g; the plane "
            "of least cost among %d bins an axis costs %g: weigh each side's box area by its count",
            n,
            kind == 0 ? "spread" : kind == 1 ? "two clusters" : "flat in z",
            cost,
            SAH_BINS,
            least);
        qsort(refs, (size_t)n, sizeof *refs, compare_prims);
        bool same = true;
        for (int i = 0; i < n; i++) {
            same = same && memcmp(&refs[i], &before[i], sizeof *refs) == 0;
        }
        CHECK_MSG(same, "sah_split: %d boxes: the refs are not the ones given, reordered", n);
    }
    free(refs);
    free(before);
}

/* --- widen ---------------------------------------------------------------- */

static bool
present(const struct bvh_wide *node, int i)
{
    return node->lo[0][i] <= node->hi[0][i];
}

TEST(gather_children_fills_each_node)
{
    struct rng rng = rng_make(9002, 2);
    static const int sizes[] = {1, 3, 10, 60, 400};
    for (int k = 0; k < 5 && !check_current.failed_checks; k++) {
        struct scene s;
        CHECK(stagecheck_random_soup(&rng, sizes[k], &s));
        struct world w = world_make(&s);
        struct diag err;
        CHECK(bvh_build(&w.bvh, &w, &err));
        int partial = 0;
        for (int id = 0; id < w.bvh.n_wide; id++) {
            const struct bvh_wide *node = &w.bvh.wide[id];
            int children = 0;
            int inner = 0;
            for (int i = 0; i < BVH_WIDTH; i++) {
                children += present(node, i);
                inner += present(node, i) && node->count[i] == 0;
            }
            partial += children < BVH_WIDTH && inner > 0;
        }
        CHECK_MSG(
            partial == 0,
            "gather_children: %d of %d nodes have fewer than %d children and an inner one among them: "
            "open the inner child of largest box until the node is full or only leaves are left",
            partial,
            w.bvh.n_wide,
            BVH_WIDTH);
        bvh_free(&w.bvh);
        scene_free(&s);
    }
}

/* --- meet_boxes ----------------------------------------------------------- */

/* Whether the tree's closest hit and any-hit along r are brute force's. */
static bool
agrees(const struct world *tree, const struct world *brute, ray r, real t_max)
{
    struct hit want;
    struct hit got;
    struct hit any;
    struct stats st = {0};
    bool hit_want = world_intersect(brute, r, t_max, &want, &st);
    bool hit_got = bvh_intersect(tree, r, t_max, false, &got, &st);
    bool blocked = bvh_intersect(tree, r, t_max, true, &any, &st);
    return hit_got == hit_want && blocked == hit_want
           && (!hit_got || (got.prim == want.prim && got.t == want.t));
}

/* 2 BVH_WIDTH triangles in one plane, in BVH_WIDTH pairs near the corners
 * of a square of side 2 around `at` (and, for eight children, of the square
 * 4 to its right): one node, BVH_WIDTH flat leaves of two. */
static bool
one_node_of_leaves(vec3 at, struct scene *s)
{
    char text[4096];
    int n = snprintf(
        text,
        sizeof text,
        "camera origin 0 0 5 target 0 0 0 up 0 1 0 fov 40\nimage width 4 height 4\n"
        "material m diffuse albedo 0.5 0.5 0.5\n");
    for (int i = 0; i < 2 * BVH_WIDTH; i++) {
        int corner = i % BVH_WIDTH;
        double x = (double)at.x + (corner & 1 ? 1 : -1) + 4 * (corner >> 2) + 0.05 * (i / BVH_WIDTH);
        double y = (double)at.y + (corner & 2 ? 1 : -1);
        double z = (double)at.z; /* one plane: the leaves' boxes are flat */
        n += snprintf(
            text + n,
            sizeof text - (size_t)n,
            "triangle v0 %.17g %.17g %.17g v1 %.17g %.17g %.17g v2 %.17g %.17g %.17g material m\n",
            x,
            y,
            z,
            x + 0.25,
            y,
            z,
            x,
            y + 0.25,
            z);
    }
    return stagecheck_load_text(text, s);
}

TEST(meet_boxes_keeps_every_hit)
{
    struct rng rng = rng_make(9003, 3);
    static const double offsets[] = {0, 1e3, 1e6};
    for (int k = 0; k < 3 && !check_current.failed_checks; k++) {
        vec3 at = vec3_splat((real)offsets[k]);
        struct scene s;
        CHECK(one_node_of_leaves(at, &s));
        struct world brute = world_make(&s);
        struct world tree = brute;
        struct diag err;
        CHECK(bvh_build(&tree.bvh, &tree, &err));
        if (tree.bvh.n_wide != 1 || tree.bvh.wide[0].leaves != (1u << BVH_WIDTH) - 1) {
            CHECK_FAIL(
                "the build did not put %d triangles in one node of %d leaves (%d nodes): "
                "check gather_children and sah_split first",
                2 * BVH_WIDTH,
                BVH_WIDTH,
                tree.bvh.n_wide);
            bvh_free(&tree.bvh);
            scene_free(&s);
            continue;
        }
        int rays = 0;
        int wrong = 0;
        for (int t = 0; t < s.n_triangles; t++) { /* at each corner and edge's midpoint */
            const int *v = s.triangles[t].v;
            for (int c = 0; c < 6; c++) {
                vec3 p = s.positions[v[c % 3]];
                p = c < 3 ? p : vec3_scale(vec3_add(p, s.positions[v[(c + 1) % 3]]), (real)0.5);
                for (int m = 0; m < 14; m++) {
                    vec3 d = stagecheck_random_vec3(&rng);
                    if (m < 6) { /* along the axes: in the boxes' faces and edges */
                        d = vec3_make(m / 2 == 0, m / 2 == 1, m / 2 == 2);
                        d = m % 2 ? vec3_neg(d) : d;
                    }
                    ray r = {vec3_sub(p, vec3_scale(d, 3)), d};
                    rays++;
                    wrong += !agrees(&tree, &brute, r, REAL_MAX);
                }
            }
        }
        int tested = 0; /* rays above the plane, rising: they meet no box */
        for (int m = 0; m < 64; m++) {
            vec3 d = stagecheck_random_vec3(&rng);
            d.z = 0;
            /* Above the boxes' margin: 256 ulps of the coordinates (30 units at 1e6 in float). */
            double above = 1 + 1e-4 * offsets[k] + 0.01 * m;
            vec3 o = vec3_add(at, vec3_make(0, 0, (real)above));
            vec3 up = vec3_make(0, 0, 1);
            if (m % 2 == 0) { /* nearly level (not parallel to a box): the line misses them */
                d = vec3_normalize(vec3_add(d, vec3_scale(up, (real)1e-3)));
            } else { /* up from above a leaf: the line crosses its box, behind the origin */
                real x = m & 2 ? (real)1.1 : (real)-0.9;
                real y = m & 4 ? (real)1.1 : (real)-0.9;
                o = vec3_add(o, vec3_make(x, y, 0));
                d = vec3_normalize(vec3_add(vec3_scale(d, (real)(0.05 / above)), up));
            }
            ray r = {o, d};
            struct hit h;
            struct stats st = {0};
            wrong += bvh_intersect(&tree, r, REAL_MAX, false, &h, &st);
            tested += (int)st.prim_tests;
        }
        CHECK_MSG(
            tested == 0,
            "meet_boxes: 64 rays above four flat leaves %g from the origin, which meet none of their "
            "boxes for t >= 0, tested %d primitives: a box the ray misses, or meets only behind its "
            "origin (t < 0), is not met",
            offsets[k],
            tested);
        CHECK_MSG(
            wrong == 0,
            "meet_boxes: %d of %d rays through the corners and edges of eight triangles in four leaves, "
            "%g from the origin, lose or change their hit (brute force): round the origin towards each plane's far "
            "side, scale the exit by 1 + 2 gamma(3), and keep all four lanes",
            wrong,
            rays,
            offsets[k]);
        bvh_free(&tree.bvh);
        scene_free(&s);
    }
}

/* --- traverse ------------------------------------------------------------- */

/* Nodes of the subtree at id whose boxes (as their parents hold them) r
 * meets for t in [0, t], counting id itself. */
static int
nodes_met(const struct bvh *bvh, uint32_t id, ray r, double t)
{
    const struct bvh_wide *node = &bvh->wide[id];
    int n = 1;
    for (int i = 0; i < BVH_WIDTH; i++) {
        if (!present(node, i) || node->count[i] > 0) {
            continue;
        }
        double t0 = 0;
        double t1 = t * (1 + 1e-9);
        for (int a = 0; a < 3; a++) {
            double o = vec3_axis(r.o, a);
            double d = vec3_axis(r.d, a);
            double lo = node->lo[a][i];
            double hi = node->hi[a][i];
            if (d == 0) {
                t1 = o < lo || o > hi ? -1 : t1;
                continue;
            }
            double ta = (lo - o) / d;
            double tb = (hi - o) / d;
            t0 = fmax(t0, fmin(ta, tb) * (1 - 1e-9));
            t1 = fmin(t1, fmax(ta, tb) * (1 + 1e-9));
        }
        n += t0 <= t1 ? nodes_met(bvh, node->child[i], r, t) : 0;
    }
    return n;
}

TEST(traverse_visits_the_nearest_child_first)
{
    struct rng rng = rng_make(9004, 4);
    for (int k = 0; k < 2 && !check_current.failed_checks; k++) {
        struct scene s;
        CHECK(stagecheck_random_soup(&rng, 1000 + 2000 * k, &s));
        struct world brute = world_make(&s);
        struct world tree = brute;
        struct diag err;
        CHECK(bvh_build(&tree.bvh, &tree, &err));
        int wrong = 0;
        double visited = 0;
        double needed = 0;
        double tests_any = 0;
        double tests_closest = 0;
        double visits_any = 0;
        double visits_closest = 0;
        int blocked = 0;
        for (int i = 0; i < 2000; i++) {
            vec3 o = vec3_scale(stagecheck_random_vec3(&rng), (real)(i % 3 == 0 ? 0.5 : 3));
            ray r = {o, stagecheck_random_vec3(&rng)};
            real t_max = i % 2 ? REAL_MAX : (real)(4 * (double)rng_uniform(&rng));
            wrong += !agrees(&tree, &brute, r, t_max);
            struct hit h;
            struct hit first;
            struct stats closest = {0};
            struct stats any = {0};
            bool hit = bvh_intersect(&tree, r, t_max, false, &h, &closest);
            bvh_intersect(&tree, r, t_max, true, &first, &any);
            visited += (double)closest.node_visits / BVH_WIDTH;
            needed += tree.bvh.n_wide > 0 ? nodes_met(&tree.bvh, 0, r, hit ? (double)h.t : (double)t_max) : 0;
            blocked += hit;
            tests_any += hit ? (double)any.prim_tests : 0;
            tests_closest += hit ? (double)closest.prim_tests : 0;
            visits_any += hit ? (double)any.node_visits : 0;
            visits_closest += hit ? (double)closest.node_visits : 0;
        }
        printf(
            "traverse: %d primitives: %.2f nodes visited a ray, %.2f met before the hit; on %d blocked "
            "rays %.2f primitive tests any-hit, %.2f closest\n",
            tree.n_prims,
            visited / 2000,
            needed / 2000,
            blocked,
            tests_any / (blocked > 0 ? blocked : 1),
            tests_closest / (blocked > 0 ? blocked : 1));
        CHECK_MSG(
            wrong == 0,
            "traverse: %d of 2000 rays in a soup of %d primitives lose or change their hit (brute force): "
            "every child whose box the ray meets before the closest hit must be visited",
            wrong,
            tree.n_prims);
        CHECK_MSG(
            visited >= 0.99 * needed,
            "traverse: %.2f nodes visited a ray where %.2f boxes meet it before its hit: descend into "
            "the tree (every child whose box the ray meets before the closest hit)",
            visited / 2000,
            needed / 2000);
        CHECK_MSG(
            visited <= 1.4 * needed,
            "traverse: %.2f nodes visited a ray where %.2f boxes meet it before its hit: visit the "
            "nearest child first, push the others, and skip a popped node beyond the closest hit",
            visited / 2000,
            needed / 2000);
        CHECK_MSG(
            tests_any < tests_closest && visits_any < visits_closest,
            "traverse: on %d blocked rays an any-hit query tests %.0f primitives in %.0f boxes, a "
            "closest-hit one %.0f in %.0f: an any-hit query stops at its first hit",
            blocked,
            tests_any,
            visits_any,
            tests_closest,
            visits_closest);
        bvh_free(&tree.bvh);
        scene_free(&s);
    }
}

TEST_MAIN(
    TEST_ENTRY(sah_split_takes_the_cheapest_plane),
    TEST_ENTRY(gather_children_fills_each_node),
    TEST_ENTRY(meet_boxes_keeps_every_hit),
    TEST_ENTRY(traverse_visits_the_nearest_child_first))
