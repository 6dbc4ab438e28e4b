/*
 * bvh.h - a bounding volume hierarchy over the world's primitives, so that a
 * ray tests about log2(n) boxes and a few primitives instead of all n.
 *
 * The tree is built by median split: a node's primitives are cut in two
 * halves of equal count along the longest axis of their centroids' bounds,
 * until at most BVH_MAX_LEAF remain.  The answer is exactly the brute-force
 * answer of world_intersect: the same primitive and the same t, bit for bit,
 * ties going to the lowest primitive number.  (Provided the primitive tests
 * report hits on their primitives: a test that reports a "hit" far off its
 * primitive, as Moller-Trumbore can on an exactly degenerate triangle whose
 * determinant comes out as rounding noise, finds it in no box.)
 *
 * A few primitives that most rays meet (the walls of a room around a
 * statue, a ground quad under a mesh, the light that shadow rays aim at)
 * are set aside: kept out of the tree and tested by every ray before it
 * (bvh.c, "primitives set aside").  In a median-split tree such a primitive
 * would share a leaf with neighbours far from it, widening that leaf's box
 * and every ancestor's over the gap, and most rays would enter that whole
 * chain of nodes.
 *
 * Memory layout: prims[0, n_aside) are the primitives set aside, in
 * numbering order; the tree's leaves hold the rest.  The nodes are one
 * array in depth-first order.  An interior node's first child is the next
 * node; its second child is nodes[index].  A leaf holds prims[index ..
 * index + count), primitive numbers in the world's numbering (spheres,
 * quads, triangles, then area lights).
 */
#ifndef BVH_H
#define BVH_H

#include <assert.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "diag.h"
#include "stats.h"
#include "vec3.h"

/* Most primitives in a leaf (another may be chosen with -DBVH_MAX_LEAF=N).
 * Measured on the 1.08M-triangle Buddha and the bunny (tests/bench): 1
 * traces as fast as 2 with twice the nodes; 4 is 2-10% slower, 8 15-20%. */
#ifndef BVH_MAX_LEAF
#define BVH_MAX_LEAF 2
#endif

/* Primitives are set aside (kept out of the tree, tested by every ray)
 * when a ray meets them with an estimated chance of at least
 * 1/BVH_ASIDE_DIVISOR: large ones, by their box's surface area against the
 * scene's, and lights, which shadow rays aim at.  At most BVH_MAX_ASIDE
 * (the likeliest), so that a ray tests no more than that outside the tree.
 * bvh.c, "primitives set aside", says why; -DBVH_MAX_ASIDE=0 builds the
 * plain tree. */
#ifndef BVH_ASIDE_DIVISOR
#define BVH_ASIDE_DIVISOR 16
#endif
#ifndef BVH_MAX_ASIDE
#define BVH_MAX_ASIDE 8
#endif

/* Deepest tree the traversal stack holds.  A median split halves the count
 * at every level, so n primitives need about log2(n) levels: 32 for 2^31. */
#define BVH_MAX_DEPTH 64

struct world; /* geometry.h */
struct hit;

struct bvh_node {
    float lo[3], hi[3]; /* bounds, rounded outward: they contain the primitives exactly */
    uint32_t index; /* interior: the second child; leaf: the first slot of prims */
    uint16_t count; /* primitives in a leaf; 0 for an interior node */
    uint8_t axis; /* interior: the split axis (0 x, 1 y, 2 z) */
    uint8_t flags; /* unused, 0 */
};

static_assert(sizeof(struct bvh_node) == 32, "two nodes per 64-byte cache line");

struct bvh {
    struct bvh_node *nodes; /* nodes[0] is the root */
    int n_nodes;
    int *prims; /* primitive numbers: those set aside, then the rest in leaf order */
    int n_prims;
    int n_aside; /* prims[0, n_aside): set aside, tested by every ray; 0 to BVH_MAX_ASIDE */
    int depth; /* levels, the root being level 1; 0 without a tree */
    int max_leaf; /* most primitives in one leaf */
    double mean_leaf; /* mean primitives per leaf (0 without a tree) */
    int n_leaves;
    size_t bytes; /* memory held by the structure */
    /* Triangles' corners copied in leaf order (3 per slot of prims; unused
     * for other primitives), so a leaf's triangles are read from one place
     * instead of through three index arrays.  NULL when there are none. */
    vec3 *leaf_vertices;
    int tri_begin, tri_end; /* the triangles' primitive numbers */
};

/* Build the hierarchy over w's primitives (zero primitives is allowed), the
 * large ones set aside.  Fills bvh (without nodes when there are no
 * primitives or all are set aside); false with err set when memory runs
 * out (bvh is left empty). */
bool bvh_build(struct bvh *bvh, const struct world *w, struct diag *err);

/* Free; accepts a zero-initialised or freed bvh. */
void bvh_free(struct bvh *bvh);

/* The closest hit along r with t in (0, t_max), ties to the lowest primitive
 * number: t, u, v and prim filled as intersect_prim does; not finished
 * (hit_finish does that).  False on a miss.  Adds the boxes tested to
 * st->node_visits and the primitives tested to st->prim_tests. */
bool bvh_intersect(
    const struct bvh *bvh,
    const struct world *w,
    ray r,
    real t_max,
    struct hit *out,
    struct stats *st);

/* True when any primitive is hit with t in (0, t_max); stops at the first.
 * Counts as bvh_intersect does. */
bool
bvh_occluded(const struct bvh *bvh, const struct world *w, ray r, real t_max, struct stats *st);

#endif /* BVH_H */
