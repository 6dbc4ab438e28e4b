/*
 * select.h - selection: the k-th smallest of n keys in O(n), without
 * sorting them.  The BVH build (bvh.c) splits a node's primitives at the
 * median centroid with it.
 */
#ifndef SELECT_H
#define SELECT_H

/* What the build rearranges: a primitive and its centroid, 16 bytes, so the
 * selection moves little memory and reads it in order. */
struct build_ref {
    float centroid[3];
    int prim;
};

/* Rearrange refs[0, n) so that refs[k] (0 <= k < n) is the element a sort by
 * centroid[axis] would put there, none before it greater and none after it
 * smaller.  Keys must not be NaN. */
void select_kth(struct build_ref *refs, int n, int k, int axis);

#endif /* SELECT_H */
