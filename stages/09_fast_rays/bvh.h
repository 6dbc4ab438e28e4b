/*
 * bvh.h - the bounding volume hierarchy (bvh.c, wide.c): world_intersect's answer from ~log4(n) nodes.
 */
#ifndef BVH_H
#define BVH_H

#include <stdbool.h>
#include <stdint.h>

#include "diag.h"
#include "stats.h"
#include "vec3.h"

#ifndef BVH_MAX_LEAF
#define BVH_MAX_LEAF 2 /* most primitives in a leaf (tests/bench measures others) */
#endif
#define SAH_BINS 16 /* planes per axis: SAH_BINS - 1 (Wald 2007: 16 lose little to every plane) */
#ifndef BVH_MAX_ASIDE
#define BVH_MAX_ASIDE 8 /* most primitives set aside (aside.c) */
#endif

struct world; /* geometry.h */
struct hit;

/* 32 bytes, two to a cache line, in depth-first order: an interior node's first child is next. */
struct bvh_node {
    float lo[3], hi[3]; /* bounds, rounded outward: they contain the primitives exactly */
    uint32_t index; /* interior: the second child; leaf: the first slot of prims */
    uint16_t count; /* primitives in a leaf; 0 for an interior node */
    uint8_t axis; /* interior: the split axis (0 x, 1 y, 2 z) */
};

/* 128 bytes, two cache lines: four children's boxes, by axis then child, so that one vector holds
 * an axis's four lower (or upper) bounds. */
#if !defined BVH_WIDTH && defined __AVX2__ /* 8 floats a register (NATIVE=1 on most x86-64) */
#define BVH_WIDTH 8
#elif !defined BVH_WIDTH
#define BVH_WIDTH 4 /* children a node: 4 or 8 */
#endif
struct bvh_wide {
    float lo[3][BVH_WIDTH], hi[3][BVH_WIDTH]; /* an absent child's box is empty: lo +inf, hi -inf */
    uint32_t child[BVH_WIDTH]; /* inner child: its node; leaf: the first slot of prims */
    uint16_t count[BVH_WIDTH]; /* primitives of a leaf child; 0 for an inner child */
    uint8_t leaves; /* bit i: child i is a leaf */
};

struct bvh {
    struct bvh_node *nodes; /* the binary tree as built, nodes[0] the root; freed once widened */
    int n_nodes;
    struct bvh_wide *wide; /* wide.c: the tree traversed, wide[0] the root */
    int n_wide;
    int *prims; /* primitive numbers: those set aside, then the tree's in leaf order */
    int n_prims; /* 0: no BVH, world_intersect tests every primitive */
    int n_aside; /* prims[0, n_aside): tested by every ray, before the tree */
};

bool bvh_build(struct bvh *bvh, const struct world *w, struct diag *err);

void bvh_free(struct bvh *bvh);

/* wide.c: replace the binary nodes by wide ones; false when out of memory. */
bool bvh_widen(struct bvh *bvh);

/* The closest hit along r with t in (0, t_max), or (any) whether there is
 * one: t, u, v and prim, as intersect_prim fills them. */
bool bvh_intersect(
    const struct world *w,
    ray r,
    real t_max,
    bool any,
    struct hit *out,
    struct stats *st);

struct box {
    vec3 lo, hi;
};
struct build_ref { /* what the build sorts */
    float centroid[3];
    int prim;
    float lo[3], hi[3]; /* the primitive's bounds, rounded outward */
};

struct box prim_bounds(const struct world *w, int prim);

/* aside.c: the surface area of b (0 for an empty or flat-less box). */
real box_area(struct box b);

/* bvh.c: split refs[0, n) by the surface area heuristic, the refs below the plane first; returns
 * how many, and the plane's axis in *axis (0 when every centroid falls in one bin). */
int sah_split(struct build_ref *refs, int n, int *axis);

/* aside.c: move the primitives set aside to refs[0, n) and return n. */
int set_aside(const struct world *w, struct build_ref *refs, struct box scene);

#endif /* BVH_H */
