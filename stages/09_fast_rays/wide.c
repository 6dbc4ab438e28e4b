/*
 * wide.c - the binary tree collapsed into one with four children a node (BVH_WIDTH), whose boxes a
 * ray meets or misses together (bvh.c; Wald et al., "Getting rid of packets", 2008; Dammertz et
 * al., "Shallow bounding volume hierarchies", 2008): half the levels, a quarter the nodes, so
 * fewer cache lines a ray, and four box tests for the price of about one.
 */
#include "bvh.h"

#include <stdlib.h>

#include "geometry.h"

/* LAB 09: collapse */
/* The nodes of the binary subtree at id that become a wide node's children, in open[]; returns how
 * many.  The inner one of largest box area is opened (replaced by its two children) until there
 * are BVH_WIDTH or only leaves: the boxes a ray meets most often go first (MacDonald and Booth). */
static int
gather_children(const struct bvh_node *tree, uint32_t id, uint32_t open[BVH_WIDTH])
{
    open[0] = id;
    int n = 1;
    for (bool opened = true; n < BVH_WIDTH && opened;) {
        opened = false;
        int widest = -1;
        real area = -1;
        for (int i = 0; i < n; i++) {
            const struct bvh_node *c = &tree[open[i]];
            struct box b = {
                vec3_make(c->lo[0], c->lo[1], c->lo[2]), vec3_make(c->hi[0], c->hi[1], c->hi[2])};
            if (c->count == 0 && box_area(b) > area) {
                area = box_area(b);
                widest = i;
            }
        }
        if (widest >= 0) {
            uint32_t parent = open[widest];
            open[widest] = parent + 1;
            open[n++] = tree[parent].index;
            opened = true;
        }
    }
    return n;
}
/* END LAB */

/* The binary subtree at id as wide node number *n_wide and the nodes after it, depth first. */
static uint32_t
widen(struct bvh *bvh, const struct bvh_node *tree, uint32_t id, uint32_t *n_wide)
{
    uint32_t at = (*n_wide)++;
    uint32_t open[BVH_WIDTH];
    int n = gather_children(tree, id, open);
    struct bvh_wide node = {.count = {0}};
    for (int i = 0; i < BVH_WIDTH; i++) {
        for (int a = 0; a < 3; a++) {
            node.lo[a][i] = i < n ? tree[open[i]].lo[a] : INFINITY; /* an empty box: never met */
            node.hi[a][i] = i < n ? tree[open[i]].hi[a] : -INFINITY;
        }
    }
    for (int i = 0; i < n; i++) {
        const struct bvh_node *c = &tree[open[i]];
        node.count[i] = c->count;
        node.leaves |= (uint8_t)((c->count > 0) << i);
        node.child[i] = c->count > 0 ? c->index : widen(bvh, tree, open[i], n_wide);
    }
    bvh->wide[at] = node;
    return at;
}

/* Replace the binary nodes by wide ones (at most as many: each holds two or more binary nodes). */
bool
bvh_widen(struct bvh *bvh)
{
    if (bvh->n_nodes == 0) { /* everything set aside, or nothing to hold */
        free(bvh->nodes);
        bvh->nodes = NULL;
        return true;
    }
    bvh->wide = malloc((size_t)bvh->n_nodes * sizeof *bvh->wide);
    if (!bvh->wide) {
        return false;
    }
    uint32_t n_wide = 0;
    widen(bvh, bvh->nodes, 0, &n_wide); /* a root that is a leaf: one node, one child */
    bvh->n_wide = (int)n_wide;
    free(bvh->nodes);
    bvh->nodes = NULL;
    return true;
}
