/*
 * wide.c - the binary tree collapsed into one with four children a node, whose four boxes a ray
 * meets or misses together (a loop the compiler turns into vector instructions), traversed with a
 * stack, nearest box first (Wald et al., "Getting rid of packets", 2008; Dammertz et al.,
 * "Shallow bounding volume hierarchies", 2008).  Half the levels, a quarter the nodes: fewer
 * cache lines a ray, and four box tests for the price of about one.
 */
#include "bvh.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "geometry.h"

#define STACK_SIZE 256 /* 3 a level: a tree of < 80 binary levels has < 80 wide ones */

/* The binary subtree at id, gathered into wide node `at` (children numbered later), depth first:
 * the child of largest box area is opened until four (or only leaves) are left. */
static uint32_t
widen(struct bvh *bvh, const struct bvh_node *tree, uint32_t id, uint32_t *n_wide)
{
    uint32_t at = (*n_wide)++;
    uint32_t open[BVH_WIDTH] = {id};
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

/* Replace the binary nodes by wide ones (at most as many: each holds two or more binary nodes),
 * and copy each triangle's corners to its slot: a leaf's triangles are then side by side in memory,
 * not three lookups away (slot, triangle, corner) each. */
bool
bvh_widen(struct bvh *bvh, const struct world *w)
{
    if (bvh->n_nodes == 0) {
        return true;
    }
    const struct scene *s = w->scene;
    bvh->wide = malloc((size_t)bvh->n_nodes * sizeof *bvh->wide);
    bvh->corners = malloc((size_t)bvh->n_prims * sizeof *bvh->corners);
    if (!bvh->wide || !bvh->corners) {
        return false;
    }
    bvh->first_triangle = s->n_spheres + s->n_quads;
    for (int slot = 0; slot < bvh->n_prims; slot++) {
        unsigned t = (unsigned)(bvh->prims[slot] - bvh->first_triangle);
        for (int k = 0; k < 3 && t < (unsigned)s->n_triangles; k++) {
            bvh->corners[slot].p[k] = s->positions[s->triangles[t].v[k]];
        }
    }
    uint32_t n_wide = 0;
    if (bvh->nodes[0].count > 0) { /* a single leaf: one wide node with one child */
        bvh->wide[0] = (struct bvh_wide){
            .count = {bvh->nodes[0].count}, .child = {bvh->nodes[0].index}, .leaves = 1};
        for (int a = 0; a < 3; a++) {
            for (int i = 0; i < BVH_WIDTH; i++) {
                bvh->wide[0].lo[a][i] = i == 0 ? bvh->nodes[0].lo[a] : INFINITY;
                bvh->wide[0].hi[a][i] = i == 0 ? bvh->nodes[0].hi[a] : -INFINITY;
            }
        }
        n_wide = 1;
    } else {
        widen(bvh, bvh->nodes, 0, &n_wide);
    }
    bvh->n_wide = (int)n_wide;
    free(bvh->nodes);
    bvh->nodes = NULL;
    return true;
}

/* LAB 09: wide traversal */
typedef float float4 __attribute__((vector_size(4 * BVH_WIDTH))); /* GCC, Clang: SSE, NEON */
typedef int32_t int4 __attribute__((vector_size(4 * BVH_WIDTH)));

/* A query: the ray, prepared for slab tests in float, and the closest hit so far.  As brute force,
 * ties go to the lowest number: after a hit at t, primitives are tested up to the next real
 * above t. */
struct query {
    const struct world *w;
    ray r;
    float4 o_near[3], o_far[3]; /* the origin rounded so that entries come early, exits late */
    float4 inv_d[3]; /* 1/d within +-FLT_MAX: no 0 * inf */
    int near[3], far[3]; /* where in a node an axis's entering and leaving planes are */
    bool any, found; /* any: stop at the first hit */
    real t_box, t_prim;
    float4 t_box4; /* t_box rounded up, in each lane */
    struct hit *out;
    uint64_t visits, tests;
};

/* Rounding: each of (plane - o) and its product with 1/d is off by at most half an ulp, and 1/d is
 * off by one, so an exit is scaled by 1 + 2 gamma(3) before it is compared (Ize, "Robust BVH ray
 * traversal", JCGT 2013; pbrt-v4's Bounds3::IntersectP); the origin's own rounding is taken up by
 * rounding it towards each plane's far side (o_near, o_far). */
#define EXIT_SCALE (1 + 2 * (3 * FLT_EPSILON / 2) / (1 - 3 * FLT_EPSILON / 2))

/* a where keep is set, else b (vector ?: is C++ only) */
static inline float4
select4(int4 keep, float4 a, float4 b)
{
    return (float4)(((int4)a & keep) | ((int4)b & ~keep));
}

static inline float4
load4(const float *p)
{
    float4 v;
    memcpy(&v, p, sizeof v);
    return v;
}

/* The slab test of a node's four boxes at once: which the ray meets for some t in [0, t_box], and
 * where it enters them (a bit per child, and entry[]). */
static inline unsigned
meet_boxes(const struct query *q, const struct bvh_wide *node, float entry[BVH_WIDTH])
{
    const float *bounds = &node->lo[0][0];
    float4 t_near = {0};
    float4 t_far = q->t_box4;
    for (int a = 0; a < 3; a++) {
        float4 enter = (load4(bounds + q->near[a]) - q->o_near[a]) * q->inv_d[a];
        float4 leave = (load4(bounds + q->far[a]) - q->o_far[a]) * q->inv_d[a];
        t_near = select4(enter > t_near, enter, t_near);
        t_far = select4(leave < t_far, leave, t_far);
    }
    int4 met = t_near <= t_far * EXIT_SCALE;
    memcpy(entry, &t_near, sizeof t_near);
    unsigned mask = 0;
    for (int i = 0; i < BVH_WIDTH; i++) {
        mask |= (unsigned)(met[i] & 1) << i;
    }
    return mask;
}

/* The primitives in slots [first, end): a leaf's, or those set aside. */
static void
test_slots(struct query *q, uint32_t first, uint32_t end)
{
    const struct bvh *bvh = &q->w->bvh;
    struct hit h;
    for (uint32_t slot = first; slot < end && !(q->any && q->found); slot++) {
        q->tests++;
        h.prim = bvh->prims[slot];
        const vec3 *p = bvh->corners[slot].p;
        bool hit = (unsigned)(h.prim - bvh->first_triangle) < (unsigned)q->w->scene->n_triangles
                       ? intersect_triangle(p[0], p[1], p[2], q->r, q->t_prim, &h.t, &h.u, &h.v)
                       : intersect_prim(q->w->scene, h.prim, q->r, q->t_prim, &h);
        if (hit && (!q->found || h.t < q->out->t || h.prim < q->out->prim)) {
            *q->out = h;
            q->found = true;
            q->t_box = h.t;
            q->t_box4 = (float4){0} + float_above(h.t);
            q->t_prim = nextafter(h.t, (real)INFINITY);
        }
    }
}

/* From the root: a node's leaves met are tested, then the nearest inner child met is visited next
 * and the others pushed; a node popped beyond the closest hit is skipped.  The children met are
 * the set bits of a mask, taken lowest first (__builtin_ctz): no branch on each child. */
static void
traverse(struct query *q)
{
    struct {
        uint32_t node;
        float t;
    } stack[STACK_SIZE];
    int top = 0;
    uint32_t id = 0;
    for (;;) {
        const struct bvh_wide *node = &q->w->bvh.wide[id];
        float entry[BVH_WIDTH];
        unsigned mask = meet_boxes(q, node, entry);
        q->visits += BVH_WIDTH;
        for (unsigned leaves = mask & node->leaves; leaves != 0; leaves &= leaves - 1) {
            int i = __builtin_ctz(leaves);
            test_slots(q, node->child[i], node->child[i] + node->count[i]);
        }
        if (q->any && q->found) {
            return;
        }
        unsigned inner = mask & ~node->leaves;
        if (inner == 0) { /* the next node on the stack not beyond the closest hit */
            do {
                if (top == 0) {
                    return;
                }
                top--;
            } while (stack[top].t > q->t_box4[0] * EXIT_SCALE);
            id = stack[top].node;
            continue;
        }
        int nearest = __builtin_ctz(inner);
        for (inner &= inner - 1; inner != 0; inner &= inner - 1) {
            int i = __builtin_ctz(inner);
            int later = entry[i] < entry[nearest] ? nearest : i;
            nearest = entry[i] < entry[nearest] ? i : nearest;
            stack[top].node = node->child[later];
            stack[top++].t = entry[later];
        }
        id = node->child[nearest];
    }
}

bool
bvh_intersect(const struct world *w, ray r, real t_max, bool any, struct hit *out, struct stats *st)
{
    struct query q = {w, r, .any = any, .t_box = t_max, .t_prim = t_max, .out = out};
    q.t_box4 = (float4){0} + float_above(t_max);
    for (int i = 0; i < 3; i++) {
        real d = vec3_axis(r.d, i);
        real o = vec3_axis(r.o, i);
        float inv = fabs(1 / d) <= FLT_MAX ? (float)(1 / d) : copysignf(FLT_MAX, (float)d);
        q.near[i] = BVH_WIDTH * (i + (inv < 0 ? 3 : 0)); /* hi[i] is 3 BVH_WIDTH floats after lo[i] */
        q.far[i] = BVH_WIDTH * (i + (inv < 0 ? 0 : 3));
        float below = float_below(o);
        float above = float_above(o);
        q.inv_d[i] = (float4){0} + inv;
        q.o_near[i] = (float4){0} + (inv < 0 ? below : above);
        q.o_far[i] = (float4){0} + (inv < 0 ? above : below);
    }
    test_slots(&q, 0, (uint32_t)w->bvh.n_aside);
    if (w->bvh.n_wide > 0 && !(any && q.found)) {
        traverse(&q);
    }
    st->node_visits += q.visits;
    st->prim_tests += q.tests;
    return q.found;
}
/* END LAB */
