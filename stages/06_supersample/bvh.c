/*
 * bvh.c - the median-split bounding volume hierarchy: each node's primitives split in halves at the
 * median centroid along the axis where the centroids spread most; traversed with Kay and Kajiya's
 * slab test (SIGGRAPH 1986), the nearer child first.
 */
#include "bvh.h"

#include <stdlib.h>
#include <string.h>

#include "geometry.h"

#define MARGIN (256 * REAL_EPSILON) /* of the scene's largest coordinate: boxes widen by it */

static const struct box empty_box = {
    {REAL_MAX, REAL_MAX, REAL_MAX},
    {-REAL_MAX, -REAL_MAX, -REAL_MAX}};

/* b grown to hold p (comparisons: fmin and fmax are calls into libm) */
static struct box
box_add(struct box b, vec3 p)
{
    b.lo.x = p.x < b.lo.x ? p.x : b.lo.x;
    b.lo.y = p.y < b.lo.y ? p.y : b.lo.y;
    b.lo.z = p.z < b.lo.z ? p.z : b.lo.z;
    b.hi.x = p.x > b.hi.x ? p.x : b.hi.x;
    b.hi.y = p.y > b.hi.y ? p.y : b.hi.y;
    b.hi.z = p.z > b.hi.z ? p.z : b.hi.z;
    return b;
}

static struct box
parallelogram_bounds(vec3 corner, vec3 edge1, vec3 edge2)
{
    struct box b = box_add(box_add(empty_box, corner), vec3_add(corner, edge1));
    return box_add(box_add(b, vec3_add(corner, edge2)), vec3_add(vec3_add(corner, edge1), edge2));
}

/* Numbered spheres, quads, triangles, area lights, sphere lights. */
struct box
prim_bounds(const struct world *w, int prim)
{
    const struct scene *s = w->scene;
    int first_triangle = s->n_spheres + s->n_quads;
    int first_light = first_triangle + s->n_triangles;
    int first_sphere_light = first_light + s->n_area_lights;
    if (prim < s->n_spheres || prim >= first_sphere_light) { /* centre +- radius */
        int i = prim - first_sphere_light;
        vec3 c = i >= 0 ? s->sphere_lights[i].center : s->spheres[prim].center;
        vec3 r = vec3_splat(i >= 0 ? s->sphere_lights[i].radius : s->spheres[prim].radius);
        return (struct box){vec3_sub(c, r), vec3_add(c, r)};
    }
    if (prim < first_triangle) {
        const struct quad *q = &s->quads[prim - s->n_spheres];
        return parallelogram_bounds(q->corner, q->edge1, q->edge2);
    }
    if (prim < first_light) {
        const int *v = s->triangles[prim - first_triangle].v;
        struct box b = box_add(box_add(empty_box, s->positions[v[0]]), s->positions[v[1]]);
        return box_add(b, s->positions[v[2]]);
    }
    const struct area_light *light = &s->area_lights[prim - first_light];
    return parallelogram_bounds(light->corner, light->edge1, light->edge2);
}

/* LAB 05: median split */
/* The axis along which the centroids of refs[0, n) spread most (x on ties). */
static int
widest_centroid_axis(const struct build_ref *refs, int n)
{
    struct box b = empty_box;
    for (int i = 0; i < n; i++) {
        b = box_add(b, vec3_make(refs[i].centroid[0], refs[i].centroid[1], refs[i].centroid[2]));
    }
    vec3 e = vec3_sub(b.hi, b.lo);
    return e.z > e.x && e.z > e.y ? 2 : e.y > e.x;
}

/* Move the refs of refs[lo, hi) with a key below the pivot (or equal) to the front, return where
 * the others start: Lomuto's partition, without a branch on the key (random keys mispredict). */
static int
partition(struct build_ref *refs, int lo, int hi, int axis, float pivot, bool or_equal)
{
    int j = lo;
    for (int i = lo; i < hi; i++) {
        float key = refs[i].centroid[axis];
        struct build_ref swap;
        memcpy(&swap, &refs[i], sizeof swap);
        memcpy(&refs[i], &refs[j], sizeof swap);
        memcpy(&refs[j], &swap, sizeof swap);
        j += (key < pivot) | (or_equal & (key == pivot));
    }
    return j;
}

/* Put at refs[k] what a sort by centroid[axis] would (Hoare's FIND, 1961): split the range into
 * keys below, equal to and above its middle one; keep the part holding k. */
static void
select_kth(struct build_ref *refs, int n, int k, int axis)
{
    int lo = 0;
    int hi = n;
    while (hi - lo > 1) {
        float pivot = refs[lo + (hi - lo) / 2].centroid[axis];
        int equal = partition(refs, lo, hi, axis, pivot, false);
        int above = k < equal ? equal : partition(refs, equal, hi, axis, pivot, true);
        if (k >= equal && k < above) {
            return;
        }
        lo = k < equal ? lo : above;
        hi = k < equal ? equal : hi;
    }
}

/* Lay out the subtree over refs[begin, end) as the next nodes, depth first, and return the box
 * around its primitives; the node's is that box widened by the margin, rounded outward to float. */
static struct box
build_subtree(
    struct bvh *bvh,
    const struct world *w,
    struct build_ref *refs,
    int begin,
    int end,
    real margin)
{
    struct bvh_node *node = &bvh->nodes[bvh->n_nodes++];
    struct box b = empty_box;
    if (end - begin <= BVH_MAX_LEAF) {
        *node = (struct bvh_node){.index = (uint32_t)begin, .count = (uint16_t)(end - begin)};
        for (int i = begin; i < end; i++) {
            struct box p = prim_bounds(w, refs[i].prim);
            b = box_add(box_add(b, p.lo), p.hi);
        }
    } else {
        int axis = widest_centroid_axis(refs + begin, end - begin);
        int mid = begin + (end - begin) / 2;
        select_kth(refs + begin, end - begin, mid - begin, axis);
        b = build_subtree(bvh, w, refs, begin, mid, margin); /* the next node */
        *node = (struct bvh_node){.index = (uint32_t)bvh->n_nodes, .axis = (uint8_t)axis};
        struct box second = build_subtree(bvh, w, refs, mid, end, margin);
        b = box_add(box_add(b, second.lo), second.hi);
    }
    for (int i = 0; i < 3; i++) {
        node->lo[i] = float_below(vec3_axis(b.lo, i) - margin);
        node->hi[i] = float_above(vec3_axis(b.hi, i) + margin);
    }
    return b;
}
/* END LAB */

/* The centroids (a NaN one made -infinity by float_below), then the tree. */
bool
bvh_build(struct bvh *bvh, const struct world *w, struct diag *err)
{
    size_t n = (size_t)w->n_prims;
    *bvh = (struct bvh){.n_prims = w->n_prims};
    bool fits = n > 0 && n <= (size_t)1 << 30; /* 2n - 1 nodes at most; n_nodes is an int */
    bvh->nodes = fits ? malloc((2 * n - 1) * sizeof *bvh->nodes) : NULL;
    bvh->prims = fits ? malloc(n * sizeof *bvh->prims) : NULL;
    struct build_ref *refs = fits ? malloc(n * sizeof *refs) : NULL;
    if (n > 0 && (!bvh->nodes || !bvh->prims || !refs)) {
        diag_set(err, NULL, 0, 0, "out of memory building a BVH over %d primitives", w->n_prims);
        free(refs);
        bvh_free(bvh);
        return false;
    }
    struct box all = empty_box;
    for (int p = 0; p < w->n_prims; p++) {
        struct box b = prim_bounds(w, p);
        all = box_add(box_add(all, b.lo), b.hi);
        vec3 c = vec3_scale(vec3_add(b.lo, b.hi), (real)0.5);
        refs[p] = (struct build_ref){{float_below(c.x), float_below(c.y), float_below(c.z)}, p};
    }
    bvh->n_aside = set_aside(w, refs, all);
    real scale = fmax(vec3_max_comp(vec3_abs(all.lo)), vec3_max_comp(vec3_abs(all.hi)));
    if (bvh->n_aside < bvh->n_prims) {
        build_subtree(bvh, w, refs, bvh->n_aside, bvh->n_prims, scale * MARGIN);
    }
    for (int slot = 0; slot < bvh->n_prims; slot++) {
        bvh->prims[slot] = refs[slot].prim;
    }
    free(refs);
    return true;
}

void
bvh_free(struct bvh *bvh)
{
    free(bvh->nodes);
    free(bvh->prims);
    *bvh = (struct bvh){.nodes = NULL};
}

/* LAB 05: BVH traversal */
/* A query: the ray, prepared for slab tests, and the closest hit so far.  As brute force, ties go
 * to the lowest number: after a hit at t, primitives are tested up to the next real above t. */
struct query {
    const struct world *w;
    ray r;
    real o[3];
    real inv_d[3]; /* 1/d within +-REAL_MAX: no 0 * inf (docs/stages/05_bvh.md, "Numerics") */
    bool enters_hi[3]; /* d < 0: the ray enters a slab through hi */
    bool any, found; /* any: stop at the first hit */
    real t_box, t_prim;
    struct hit *out;
    uint64_t visits, tests;
};

/* The slab test: whether the ray is, for some t in [0, t_box], in each axis's slab lo <= x <= hi
 * of node id's box (between (lo - o) / d and (hi - o) / d), and where it enters the box. */
static inline bool
meets_box(const struct query *q, uint32_t id, real *entry)
{
    const struct bvh_node *node = &q->w->bvh.nodes[id];
    real t_near = 0;
    real t_far = q->t_box;
    for (int i = 0; i < 3; i++) {
        real t_enter = ((q->enters_hi[i] ? node->hi[i] : node->lo[i]) - q->o[i]) * q->inv_d[i];
        real t_leave = ((q->enters_hi[i] ? node->lo[i] : node->hi[i]) - q->o[i]) * q->inv_d[i];
        t_near = t_enter > t_near ? t_enter : t_near;
        t_far = t_leave < t_far ? t_leave : t_far;
    }
    *entry = t_near;
    return t_near <= t_far;
}

/* The primitives in slots [first, end): a leaf's, or those set aside. */
static void
test_slots(struct query *q, uint32_t first, uint32_t end)
{
    struct hit h;
    for (uint32_t slot = first; slot < end && !(q->any && q->found); slot++) {
        q->tests++;
        bool hit = intersect_prim(q->w->scene, q->w->bvh.prims[slot], q->r, q->t_prim, &h);
        if (hit && (!q->found || h.t < q->out->t || h.prim < q->out->prim)) {
            *q->out = h;
            q->found = true;
            q->t_box = h.t;
            q->t_prim = nextafter(h.t, (real)INFINITY);
        }
    }
}

/* A leaf's primitives, or the children whose boxes the ray meets, the one on the side of the split
 * it comes from first (the first holds the lower centroids), the other (kept on the call stack)
 * unless it starts beyond a hit. */
static void
visit(struct query *q, uint32_t id)
{
    const struct bvh_node *node = &q->w->bvh.nodes[id];
    if (node->count > 0) {
        test_slots(q, node->index, node->index + node->count);
        return;
    }
    bool second_first = q->enters_hi[node->axis];
    uint32_t child[2] = {second_first ? node->index : id + 1, second_first ? id + 1 : node->index};
    real t[2];
    bool hit[2] = {meets_box(q, child[0], &t[0]), meets_box(q, child[1], &t[1])};
    q->visits += 2;
    for (int i = 0; i < 2 && !(q->any && q->found); i++) {
        if (hit[i] && t[i] <= q->t_box) {
            visit(q, child[i]);
        }
    }
}

bool
bvh_intersect(const struct world *w, ray r, real t_max, bool any, struct hit *out, struct stats *st)
{
    struct query q = {w, r, .any = any, .t_box = t_max, .t_prim = t_max, .out = out};
    for (int i = 0; i < 3; i++) {
        real d = vec3_axis(r.d, i);
        q.o[i] = vec3_axis(r.o, i);
        q.inv_d[i] = fabs(1 / d) <= REAL_MAX ? 1 / d : copysign(REAL_MAX, d);
        q.enters_hi[i] = q.inv_d[i] < 0;
    }
    test_slots(&q, 0, (uint32_t)w->bvh.n_aside);
    real t_root;
    q.visits = w->bvh.n_nodes > 0 && !(any && q.found);
    if (q.visits > 0 && meets_box(&q, 0, &t_root)) {
        visit(&q, 0);
    }
    st->node_visits += q.visits;
    st->prim_tests += q.tests;
    return q.found;
}
/* END LAB */
