/*
 * bvh.c - the median-split bounding volume hierarchy: build and traversal.
 *
 * Build (bvh_build): each primitive is reduced to the centre of its bounding
 * box; a node's primitives are split in two halves of equal count at the
 * median centroid along the axis where the centroids spread most.  The
 * median is found by selection (select.c), not by sorting: O(n) per level,
 * O(n log n) in all.  Splitting by count needs no special case when
 * centroids coincide: they are split anyway, so every leaf holds at most
 * BVH_MAX_LEAF primitives and the tree has about log2(n) levels.  (This is
 * not the surface area heuristic of pbrt or Embree, which cuts where the
 * expected cost of tracing is lowest: slower to build, faster to trace.)
 * Before that, the few primitives that most rays meet (large ones, lights)
 * are set aside, outside the tree (set_aside, below).
 *
 * Traversal (bvh_intersect, bvh_occluded): an explicit stack; at each node
 * both children's boxes are tested, the one on the ray's side of the split
 * plane visited first and the other pushed; the ray-box test is Kay and
 * Kajiya's slabs ("Ray Tracing Complex Scenes", SIGGRAPH 1986) with the
 * precomputed reciprocal direction and sign of Williams et al. ("An
 * Efficient and Robust Ray-Box Intersection Algorithm", JGT 10(1), 2005).
 * Every traversal tests the primitives set aside first, then the tree up to
 * the closest of their hits.  The primitives are tested with the same
 * functions and the same numbers as the brute-force loop of
 * world_intersect, so the answer is the same bit for bit.
 */
#include "bvh.h"

#include <limits.h>
#include <stdlib.h>

#include "geometry.h"
#include "select.h"

static_assert(BVH_MAX_LEAF >= 1 && BVH_MAX_LEAF <= UINT16_MAX, "leaf counts are uint16_t");
static_assert(BVH_MAX_DEPTH >= 33, "an int primitive count needs up to 32 levels");

/*
 * Boxes are widened by this many REAL_EPSILONs of the scene's size (its
 * largest coordinate).  Rounding puts a computed hit off the exact surface,
 * and a computed slab distance off the exact box, by a few epsilons of the
 * distances involved; a box that only just held its primitive could then be
 * missed by a ray that the primitive test reports as a hit, and the BVH
 * would disagree with brute force.  256 epsilons cover rays starting within
 * ~50 scene sizes that are not nearly parallel to the surface they hit, for
 * boxes larger by 2^-44 of the scene in double, 2^-15 in float: no
 * traversal notices.
 */
#define MARGIN_EPSILONS 256

/* "No node": the traversal's answer when the ray misses both children. */
#define NO_NODE UINT32_MAX

/* An axis-aligned box in the working precision. */
struct box {
    vec3 lo, hi;
};

/* LAB 05: BVH build */
/* --- primitive bounds ------------------------------------------------------ */

static struct box
box_empty(void)
{
    return (struct box){vec3_splat(REAL_MAX), vec3_splat(-REAL_MAX)};
}

/* b grown to hold p.  (Comparisons rather than fmin/fmax, which are calls
 * into libm at -O2.) */
static struct box
box_add_point(struct box b, vec3 p)
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
box_union(struct box a, struct box b)
{
    return box_add_point(box_add_point(a, b.lo), b.hi);
}

static struct box
triangle_bounds(vec3 p0, vec3 p1, vec3 p2)
{
    return box_add_point(box_add_point(box_add_point(box_empty(), p0), p1), p2);
}

static struct box
parallelogram_bounds(vec3 corner, vec3 edge1, vec3 edge2)
{
    struct box b = triangle_bounds(corner, vec3_add(corner, edge1), vec3_add(corner, edge2));
    return box_add_point(b, vec3_add(vec3_add(corner, edge1), edge2));
}

static struct box
sphere_bounds(vec3 center, real radius)
{
    vec3 r = vec3_splat(radius);
    return (struct box){vec3_sub(center, r), vec3_add(center, r)};
}

/* Bounds of primitive `prim` in the world's numbering: spheres, quads,
 * triangles, then (when the world counts them) area lights and sphere
 * lights. */
static struct box
prim_bounds(const struct world *w, int prim)
{
    const struct scene *s = w->scene;
    int first_quad = s->n_spheres;
    int first_triangle = first_quad + s->n_quads;
    int first_light = first_triangle + s->n_triangles;
    int first_sphere_light = first_light + s->n_area_lights;
    if (prim < first_quad) {
        return sphere_bounds(s->spheres[prim].center, s->spheres[prim].radius);
    }
    if (prim < first_triangle) {
        const struct quad *q = &s->quads[prim - first_quad];
        return parallelogram_bounds(q->corner, q->edge1, q->edge2);
    }
    if (prim < first_light) {
        const struct triangle *tri = &s->triangles[prim - first_triangle];
        const vec3 *p = s->positions;
        return triangle_bounds(p[tri->v[0]], p[tri->v[1]], p[tri->v[2]]);
    }
    if (prim >= first_sphere_light) {
        const struct sphere_light *sphere = &s->sphere_lights[prim - first_sphere_light];
        return sphere_bounds(sphere->center, sphere->radius);
    }
    const struct area_light *light = &s->area_lights[prim - first_light];
    return parallelogram_bounds(light->corner, light->edge1, light->edge2);
}

/* --- primitives set aside ------------------------------------------------ */

/*
 * A median split places a primitive by its centroid alone, so a primitive
 * that many rays meet can end up in a leaf with neighbours far from it: a
 * wall of a room beside a few triangles of the statue in it, a light on
 * the ceiling beside the statue's top.  That leaf's box and every
 * ancestor's then span the gap, and a ray crossing it tests two boxes per
 * level all the way down the chain.  A few such primitives are kept out of
 * the tree instead, in prims[0, n_aside), and every ray tests them first.
 *
 * Which: those that a ray meets with a chance p of at least
 * 1/BVH_ASIDE_DIVISOR.  In the tree such a primitive costs a ray p times
 * two box tests per level of its chain, 2 x 17 levels for 10^5
 * primitives: over 2 box tests at p = 1/16.  Set aside, it costs every ray
 * one primitive test, about 1.5 box tests (callgrind on the bunny box:
 * some 100 instructions per quad test, 70 per box with its share of the
 * traversal).  The chance is estimated two ways, the larger counting:
 * - for rays from everywhere, the ratio of the primitive's box's surface
 *   area to the scene box's (for convex bodies, the argument of the surface
 *   area heuristic: MacDonald and Booth 1990): the large primitives;
 * - for shadow rays, 1 / (number of lights) for a light: next-event
 *   estimation aims a shadow ray at one light from every point it shades.
 * At most BVH_MAX_ASIDE primitives are set aside, the most likely ones
 * (ties to the lowest number), so that a ray tests at most that many
 * outside the tree, whatever the scene.  docs/stages/05_bvh.md, "Primitives
 * of very different sizes", has the measurements.
 */

/* Surface area of a box (0 for an empty one). */
static real
box_area(struct box b)
{
    vec3 e = vec3_max(vec3_sub(b.hi, b.lo), vec3_splat(0));
    return 2 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

/* The chance that a ray meets primitive `prim`, estimated as above, for a
 * scene box of surface area scene_area > 0. */
static real
chance_of_meeting(const struct world *w, int prim, real scene_area)
{
    const struct scene *s = w->scene;
    int first_light = s->n_spheres + s->n_quads + s->n_triangles;
    real chance = box_area(prim_bounds(w, prim)) / scene_area;
    if (prim >= first_light) {
        real aimed_at = (real)1 / (s->n_area_lights + s->n_sphere_lights);
        chance = aimed_at > chance ? aimed_at : chance;
    }
    return chance;
}

struct aside {
    real chance;
    int prim;
};

/* Add `a` to list[0, n), kept in decreasing chance (an equal chance after
 * the earlier primitive) and to at most BVH_MAX_ASIDE; returns the new n. */
static int
keep_likeliest(struct aside *list, int n, struct aside a)
{
    int at = n;
    while (at > 0 && list[at - 1].chance < a.chance) {
        at--;
    }
    if (at >= BVH_MAX_ASIDE) {
        return n;
    }
    n = n < BVH_MAX_ASIDE ? n + 1 : n;
    for (int i = n - 1; i > at; i--) {
        list[i] = list[i - 1];
    }
    list[at] = a;
    return n;
}

/* Sort list[0, n) by primitive number (n is at most BVH_MAX_ASIDE). */
static void
sort_by_prim(struct aside *list, int n)
{
    for (int i = 1; i < n; i++) {
        struct aside a = list[i];
        int j = i;
        for (; j > 0 && list[j - 1].prim > a.prim; j--) {
            list[j] = list[j - 1];
        }
        list[j] = a;
    }
}

/*
 * Choose the primitives to set aside and move them to refs[0, n_aside), in
 * numbering order; return n_aside.  refs must be in numbering order
 * (refs[p].prim == p, as make_refs leaves them): then the k-th chosen,
 * primitive p_k >= k, is swapped with refs[k], and no later swap touches
 * it.  A scene box of zero or infinite area sets nothing aside.
 */
static int
set_aside(const struct world *w, struct build_ref *refs, struct box all)
{
    struct aside list[BVH_MAX_ASIDE + 1];
    int n = 0;
    real scene_area = box_area(all);
    if (!(scene_area > 0 && scene_area <= REAL_MAX)) {
        return 0;
    }
    for (int prim = 0; prim < w->n_prims && BVH_MAX_ASIDE > 0; prim++) {
        real chance = chance_of_meeting(w, prim, scene_area);
        if (chance >= (real)1 / BVH_ASIDE_DIVISOR) {
            n = keep_likeliest(list, n, (struct aside){chance, prim});
        }
    }
    sort_by_prim(list, n);
    for (int k = 0; k < n; k++) {
        struct build_ref chosen = refs[list[k].prim];
        refs[list[k].prim] = refs[k];
        refs[k] = chosen;
    }
    return n;
}

/* --- the split axis ------------------------------------------------------- */

/* The axis along which the centroids of refs[0, n) spread most (x on ties,
 * including when they all coincide). */
static int
widest_centroid_axis(const struct build_ref *refs, int n)
{
    float lo_x = INFINITY, lo_y = INFINITY, lo_z = INFINITY;
    float hi_x = -INFINITY, hi_y = -INFINITY, hi_z = -INFINITY;
    for (int i = 0; i < n; i++) {
        const float *c = refs[i].centroid;
        lo_x = c[0] < lo_x ? c[0] : lo_x;
        lo_y = c[1] < lo_y ? c[1] : lo_y;
        lo_z = c[2] < lo_z ? c[2] : lo_z;
        hi_x = c[0] > hi_x ? c[0] : hi_x;
        hi_y = c[1] > hi_y ? c[1] : hi_y;
        hi_z = c[2] > hi_z ? c[2] : hi_z;
    }
    float extent[3] = {hi_x - lo_x, hi_y - lo_y, hi_z - lo_z};
    int axis = extent[1] > extent[0] ? 1 : 0;
    return extent[2] > extent[axis] ? 2 : axis;
}

/* --- building ------------------------------------------------------------- */

/* Every primitive's centroid, in numbering order; returns the box around
 * all primitives.  (float_below turns the NaN centre of an infinite box
 * into -infinity: every key compares.) */
static struct box
make_refs(const struct world *w, struct build_ref *refs)
{
    struct box all = box_empty();
    for (int prim = 0; prim < w->n_prims; prim++) {
        struct box b = prim_bounds(w, prim);
        all = box_union(all, b);
        vec3 c = vec3_scale(vec3_add(b.lo, b.hi), (real)0.5);
        refs[prim] =
            (struct build_ref){{float_below(c.x), float_below(c.y), float_below(c.z)}, prim};
    }
    return all;
}

/*
 * Lay out the subtree over refs[begin, end) as the next nodes of bvh, depth
 * first, and return its root's index.  Only the topology: set_boxes fills
 * in the boxes afterwards.  The recursion is as deep as the tree: the count
 * halves at each level.
 */
static uint32_t
build_subtree(struct bvh *bvh, struct build_ref *refs, int begin, int end, int depth)
{
    uint32_t id = (uint32_t)bvh->n_nodes++;
    bvh->depth = depth > bvh->depth ? depth : bvh->depth;
    if (end - begin <= BVH_MAX_LEAF) {
        uint16_t count = (uint16_t)(end - begin);
        bvh->nodes[id] = (struct bvh_node){.index = (uint32_t)begin, .count = count};
        return id;
    }
    int axis = widest_centroid_axis(refs + begin, end - begin);
    int mid = begin + (end - begin) / 2;
    select_kth(refs + begin, end - begin, mid - begin, axis);
    build_subtree(bvh, refs, begin, mid, depth + 1); /* the first child: node id + 1 */
    uint32_t second = build_subtree(bvh, refs, mid, end, depth + 1);
    bvh->nodes[id] = (struct bvh_node){.index = second, .axis = (uint8_t)axis};
    return id;
}

/* Primitive numbers in leaf order, and the triangles' corners beside them.
 * One pass in slot order: the reads are scattered over the scene's arrays
 * but independent of each other, so the processor overlaps their cache
 * misses. */
static void
set_leaf_order(struct bvh *bvh, const struct world *w, const struct build_ref *refs)
{
    const struct scene *s = w->scene;
    for (int slot = 0; slot < bvh->n_prims; slot++) {
        int prim = refs[slot].prim;
        bvh->prims[slot] = prim;
        if (prim >= bvh->tri_begin && prim < bvh->tri_end) {
            const struct triangle *tri = &s->triangles[prim - bvh->tri_begin];
            vec3 *corners = &bvh->leaf_vertices[3 * (size_t)slot];
            for (int k = 0; k < 3; k++) {
                corners[k] = s->positions[tri->v[k]];
            }
        }
    }
}

/* Bounds of the primitive in leaf slot `slot`. */
static struct box
slot_bounds(const struct bvh *bvh, const struct world *w, uint32_t slot)
{
    int prim = bvh->prims[slot];
    if (prim < bvh->tri_begin || prim >= bvh->tri_end) {
        return prim_bounds(w, prim);
    }
    const vec3 *p = &bvh->leaf_vertices[3 * (size_t)slot];
    return triangle_bounds(p[0], p[1], p[2]);
}

/* A leaf's box: its primitives' bounds widened by the margin and rounded
 * outward to float. */
static void
set_leaf_box(struct bvh_node *leaf, const struct bvh *bvh, const struct world *w, real margin)
{
    struct box b = box_empty();
    for (uint32_t slot = leaf->index; slot < leaf->index + leaf->count; slot++) {
        b = box_union(b, slot_bounds(bvh, w, slot));
    }
    for (int i = 0; i < 3; i++) {
        leaf->lo[i] = float_below(vec3_axis(b.lo, i) - margin);
        leaf->hi[i] = float_above(vec3_axis(b.hi, i) + margin);
    }
}

/* Every node's box, children before parents: in depth-first order both
 * children come after their parent, so one backward pass does it. */
static void
set_boxes(struct bvh *bvh, const struct world *w, real margin)
{
    for (int id = bvh->n_nodes - 1; id >= 0; id--) {
        struct bvh_node *node = &bvh->nodes[id];
        if (node->count > 0) {
            set_leaf_box(node, bvh, w, margin);
            continue;
        }
        const struct bvh_node *a = &bvh->nodes[id + 1];
        const struct bvh_node *b = &bvh->nodes[node->index];
        for (int i = 0; i < 3; i++) {
            node->lo[i] = a->lo[i] < b->lo[i] ? a->lo[i] : b->lo[i];
            node->hi[i] = a->hi[i] > b->hi[i] ? a->hi[i] : b->hi[i];
        }
    }
}

static real
margin_for(struct box all)
{
    real scale = fmax(vec3_max_comp(vec3_abs(all.lo)), vec3_max_comp(vec3_abs(all.hi)));
    return scale * (MARGIN_EPSILONS * REAL_EPSILON);
}

/* malloc(count * size), or NULL when that overflows. */
static void *
alloc_array(size_t count, size_t size)
{
    return count > SIZE_MAX / size ? NULL : malloc(count * size);
}

/* A median split of n >= 1 primitives makes at most 2n - 1 nodes (fewer
 * with leaves of more than one, or primitives set aside: summarize gives
 * the rest back). */
static bool
allocate(struct bvh *bvh, int n, struct build_ref **refs)
{
    size_t count = (size_t)n;
    bvh->nodes = alloc_array(2 * count - 1, sizeof *bvh->nodes);
    bvh->prims = alloc_array(count, sizeof *bvh->prims);
    *refs = alloc_array(count, sizeof **refs);
    bool ok = bvh->nodes && bvh->prims && *refs;
    if (bvh->tri_end > bvh->tri_begin) {
        bvh->leaf_vertices = alloc_array(3 * count, sizeof *bvh->leaf_vertices);
        ok = ok && bvh->leaf_vertices;
    }
    return ok;
}

/* Give back the unused part of the node array; record the leaf sizes and
 * the memory held. */
static void
summarize(struct bvh *bvh)
{
    size_t count = (size_t)bvh->n_nodes;
    struct bvh_node *nodes = count > 0 ? realloc(bvh->nodes, count * sizeof *nodes) : NULL;
    bvh->nodes = nodes ? nodes : bvh->nodes;
    for (int id = 0; id < bvh->n_nodes; id++) {
        int n = bvh->nodes[id].count;
        bvh->n_leaves += n > 0;
        bvh->max_leaf = n > bvh->max_leaf ? n : bvh->max_leaf;
    }
    int in_tree = bvh->n_prims - bvh->n_aside;
    bvh->mean_leaf = bvh->n_leaves > 0 ? (double)in_tree / bvh->n_leaves : 0;
    bvh->bytes = count * sizeof *bvh->nodes + (size_t)bvh->n_prims * sizeof *bvh->prims;
    if (bvh->leaf_vertices) {
        bvh->bytes += 3 * (size_t)bvh->n_prims * sizeof *bvh->leaf_vertices;
    }
}

bool
bvh_build(struct bvh *bvh, const struct world *w, struct diag *err)
{
    const struct scene *s = w->scene;
    int tri_begin = s->n_spheres + s->n_quads;
    *bvh = (struct bvh){.tri_begin = tri_begin, .tri_end = tri_begin + s->n_triangles};
    if (w->n_prims <= 0) {
        return true;
    }
    struct build_ref *refs = NULL;
    /* n_nodes (an int) reaches 2n - 1. */
    if (w->n_prims > INT_MAX / 2 || !allocate(bvh, w->n_prims, &refs)) {
        diag_set(err, NULL, 0, 0, "out of memory building a BVH over %d primitives", w->n_prims);
        free(refs);
        bvh_free(bvh);
        return false;
    }
    bvh->n_prims = w->n_prims;
    struct box all = make_refs(w, refs);
    real margin = margin_for(all);
    bvh->n_aside = set_aside(w, refs, all);
    if (bvh->n_aside < bvh->n_prims) {
        build_subtree(bvh, refs, bvh->n_aside, bvh->n_prims, 1);
    }
    assert(bvh->depth <= BVH_MAX_DEPTH);
    set_leaf_order(bvh, w, refs);
    free(refs);
    set_boxes(bvh, w, margin);
    summarize(bvh);
    return true;
}

/* END LAB */

void
bvh_free(struct bvh *bvh)
{
    free(bvh->nodes);
    free(bvh->prims);
    free(bvh->leaf_vertices);
    *bvh = (struct bvh){.nodes = NULL};
}

/* LAB 05: BVH traversal */
/* --- traversal ------------------------------------------------------------ */

/* A ray prepared for slab tests. */
struct slab_ray {
    real o[3];
    real inv_d[3]; /* 1/d, held within +-REAL_MAX (d = 0: +-REAL_MAX, by d's sign) */
    bool enters_hi[3]; /* inv_d < 0: the ray enters a slab through hi */
};

static struct slab_ray
slab_ray_make(ray r)
{
    struct slab_ray sr;
    for (int i = 0; i < 3; i++) {
        real d = vec3_axis(r.d, i);
        real inv = 1 / d;
        sr.o[i] = vec3_axis(r.o, i);
        sr.inv_d[i] = fabs(inv) <= REAL_MAX ? inv : copysign(REAL_MAX, d);
        sr.enters_hi[i] = sr.inv_d[i] < 0;
    }
    return sr;
}

/*
 * Narrow [*t_near, *t_far] to the t where the ray is inside the slab
 * lo <= x <= hi of axis i: between (lo - o) / d and (hi - o) / d, the
 * plane the ray crosses first chosen by the sign of d.  Williams et al.
 * let 1/d be infinite for a ray parallel to the slab; then an origin
 * exactly on the slab's plane gives 0 * infinity = NaN.  Here 1/d is held
 * to +-REAL_MAX instead, which keeps every product a number (the bounds
 * are finite or infinite, never NaN, and 1/d is never 0) and gives a
 * parallel ray the right answer without a branch: inside the slab, the
 * two distances have opposite signs (or one is 0, on a face: the box is
 * closed) and the interval keeps t = 0 .. t_far; outside, both have the
 * same sign and the interval is empty, or starts so far away (over 1e8
 * scene units even for a gap of one float) that at worst a box is entered
 * that holds nothing the ray can reach - a wasted test, never a missed
 * hit.
 */
static inline void
clip_slab(real lo, real hi, const struct slab_ray *sr, int i, real *t_near, real *t_far)
{
    real t_enter = ((sr->enters_hi[i] ? hi : lo) - sr->o[i]) * sr->inv_d[i];
    real t_leave = ((sr->enters_hi[i] ? lo : hi) - sr->o[i]) * sr->inv_d[i];
    *t_near = t_enter > *t_near ? t_enter : *t_near;
    *t_far = t_leave < *t_far ? t_leave : *t_far;
}

/* Whether the ray meets the node's box at some t in [0, t_limit], and
 * where it enters: the three slabs' intervals intersected. */
static inline bool
ray_box_entry(const struct bvh_node *node, const struct slab_ray *sr, real t_limit, real *entry)
{
    real t_near = 0;
    real t_far = t_limit;
    clip_slab(node->lo[0], node->hi[0], sr, 0, &t_near, &t_far);
    clip_slab(node->lo[1], node->hi[1], sr, 1, &t_near, &t_far);
    clip_slab(node->lo[2], node->hi[2], sr, 2, &t_near, &t_far);
    *entry = t_near;
    return t_near <= t_far;
}

/* Intersect the primitive in leaf slot `slot`, exactly as intersect_prim
 * would: triangles from the leaf-ordered copy of their corners (the same
 * numbers, so the same result), anything else through intersect_prim. */
static inline bool
intersect_slot(
    const struct bvh *bvh,
    const struct world *w,
    uint32_t slot,
    ray r,
    real t_max,
    struct hit *out)
{
    int prim = bvh->prims[slot];
    if (prim < bvh->tri_begin || prim >= bvh->tri_end) {
        return intersect_prim(w->scene, prim, r, t_max, out);
    }
    const vec3 *p = &bvh->leaf_vertices[3 * (size_t)slot];
    real t = 0;
    real u = 0;
    real v = 0;
    if (!intersect_triangle(p[0], p[1], p[2], r, t_max, &t, &u, &v)) {
        return false;
    }
    out->t = t;
    out->u = u;
    out->v = v;
    out->prim = prim;
    return true;
}

/*
 * A traversal in progress: the nodes still to visit, each with the t where
 * the ray enters it, and the counts for struct stats (node_visits counts
 * box tests).  The stack holds at most one node per level: the other child
 * of each node on the path to the current one.
 */
struct pending {
    uint32_t id;
    real t_entry;
};

struct traversal {
    struct slab_ray sr;
    struct pending stack[BVH_MAX_DEPTH];
    int top;
    uint64_t visits, tests;
};

/* A traversal of r before its first node (the stack is not cleared: it
 * is read only below top). */
static void
traversal_begin(struct traversal *tr, ray r)
{
    tr->sr = slab_ray_make(r);
    tr->top = 0;
    tr->visits = 0;
    tr->tests = 0;
}

/* The root, if the ray meets its box by t_limit; NO_NODE otherwise. */
static uint32_t
start(const struct bvh *bvh, struct traversal *tr, real t_limit)
{
    real t_entry;
    if (bvh->n_nodes == 0) {
        return NO_NODE;
    }
    tr->visits++;
    return ray_box_entry(&bvh->nodes[0], &tr->sr, t_limit, &t_entry) ? 0 : NO_NODE;
}

/*
 * Test the children of interior node `id` against the ray (up to t_limit)
 * and return the one to visit next, pushing the other when both are hit, or
 * return NO_NODE when both are missed.  The near child is the one on the
 * side of the split plane the ray comes from: along the split axis, the
 * first child holds the lower centroids.
 */
static inline uint32_t
descend(const struct bvh *bvh, uint32_t id, real t_limit, struct traversal *tr)
{
    const struct bvh_node *node = &bvh->nodes[id];
    bool second_first = tr->sr.enters_hi[node->axis];
    uint32_t near = second_first ? node->index : id + 1;
    uint32_t far = second_first ? id + 1 : node->index;
    real t_near_child;
    real t_far_child;
    bool hit_near = ray_box_entry(&bvh->nodes[near], &tr->sr, t_limit, &t_near_child);
    bool hit_far = ray_box_entry(&bvh->nodes[far], &tr->sr, t_limit, &t_far_child);
    tr->visits += 2;
    if (hit_near && hit_far) {
        tr->stack[tr->top].id = far;
        tr->stack[tr->top++].t_entry = t_far_child;
    }
    return hit_near ? near : hit_far ? far : NO_NODE;
}

/* The next node from the stack that the ray enters no later than t_limit
 * (the limit may have shrunk since it was pushed), or NO_NODE. */
static inline uint32_t
pop(struct traversal *tr, real t_limit)
{
    while (tr->top > 0) {
        tr->top--;
        if (tr->stack[tr->top].t_entry <= t_limit) {
            return tr->stack[tr->top].id;
        }
    }
    return NO_NODE;
}

/*
 * The closest hit so far.  Brute force keeps the first of equal t in
 * numbering order; the BVH meets primitives in another order, so after a hit
 * at t it tests primitives up to just above t (t_prim = the next real after
 * t) and lets an equal t replace the best when its primitive number is
 * lower.  Boxes are entered up to t itself (t_box): a box entered after it
 * holds nothing as close, one entered at t may hold a tie.
 */
struct closest {
    struct hit *out;
    bool found;
    real t_box;
    real t_prim;
};

/* The primitives in slots [first, end): a leaf's, or those set aside. */
static void
closest_in_slots(
    const struct bvh *bvh,
    const struct world *w,
    uint32_t first,
    uint32_t end,
    ray r,
    struct closest *c)
{
    struct hit h;
    for (uint32_t slot = first; slot < end; slot++) {
        if (!intersect_slot(bvh, w, slot, r, c->t_prim, &h)) {
            continue;
        }
        if (!c->found || h.t < c->out->t || h.prim < c->out->prim) {
            c->out->t = h.t;
            c->out->u = h.u;
            c->out->v = h.v;
            c->out->prim = h.prim;
            c->found = true;
            c->t_box = h.t;
            c->t_prim = nextafter(h.t, (real)INFINITY);
        }
    }
}

bool
bvh_intersect(
    const struct bvh *bvh,
    const struct world *w,
    ray r,
    real t_max,
    struct hit *out,
    struct stats *st)
{
    struct closest c = {.out = out, .t_box = t_max, .t_prim = t_max};
    struct traversal tr;
    traversal_begin(&tr, r);
    closest_in_slots(bvh, w, 0, (uint32_t)bvh->n_aside, r, &c);
    tr.tests += (uint64_t)bvh->n_aside;
    uint32_t id = start(bvh, &tr, c.t_box);
    while (id != NO_NODE) {
        const struct bvh_node *node = &bvh->nodes[id];
        if (node->count == 0) {
            id = descend(bvh, id, c.t_box, &tr);
            id = id != NO_NODE ? id : pop(&tr, c.t_box);
            continue;
        }
        closest_in_slots(bvh, w, node->index, node->index + node->count, r, &c);
        tr.tests += node->count;
        id = pop(&tr, c.t_box);
    }
    st->node_visits += tr.visits;
    st->prim_tests += tr.tests;
    return c.found;
}

/* Whether a primitive in slots [first, end) is hit before t_max. */
static bool
any_in_slots(
    const struct bvh *bvh,
    const struct world *w,
    uint32_t first,
    uint32_t end,
    ray r,
    real t_max,
    struct traversal *tr)
{
    struct hit h;
    for (uint32_t slot = first; slot < end; slot++) {
        tr->tests++;
        if (intersect_slot(bvh, w, slot, r, t_max, &h)) {
            return true;
        }
    }
    return false;
}

bool
bvh_occluded(const struct bvh *bvh, const struct world *w, ray r, real t_max, struct stats *st)
{
    struct traversal tr;
    traversal_begin(&tr, r);
    bool hit = any_in_slots(bvh, w, 0, (uint32_t)bvh->n_aside, r, t_max, &tr);
    uint32_t id = hit ? NO_NODE : start(bvh, &tr, t_max);
    while (id != NO_NODE && !hit) {
        const struct bvh_node *node = &bvh->nodes[id];
        if (node->count == 0) {
            id = descend(bvh, id, t_max, &tr);
            id = id != NO_NODE ? id : pop(&tr, t_max);
            continue;
        }
        hit = any_in_slots(bvh, w, node->index, node->index + node->count, r, t_max, &tr);
        id = pop(&tr, t_max);
    }
    st->node_visits += tr.visits;
    st->prim_tests += tr.tests;
    return hit;
}

/* END LAB */
