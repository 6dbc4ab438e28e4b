/*
 * bvh.c - the bounding volume hierarchy, split by the surface area heuristic: each node's
 * primitives go to the side of the plane, among a few per axis, that makes the expected cost of a
 * ray's visit least (MacDonald and Booth 1990; binned, Wald 2007); then collapsed into a tree of
 * four children a node (wide.c).
 */
#include "bvh.h"

#include <stdlib.h>
#include <string.h>

#include "geometry.h"

#define MARGIN (256 * REAL_EPSILON) /* of the scene's largest coordinate: boxes widen by it */
#define SAH_BINS 16 /* planes per axis: SAH_BINS - 1 (Wald 2007: 16 lose little to every plane) */
#define SAH_MAX_DEPTH 48 /* deeper nodes split at the median: the tree has < 48 + 31 levels */

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

/* The bin, of SAH_BINS equal ones from lo on (scale: SAH_BINS over their extent), of centroid c. */
static int
bin_of(float c, float lo, float scale)
{
    int k = (int)((c - lo) * scale);
    return k < 0 ? 0 : k < SAH_BINS ? k : SAH_BINS - 1;
}

struct bin { /* in float, as the refs' bounds: exact, and half the memory traffic */
    float lo[3], hi[3];
    int n;
};

static void
bin_add(struct bin *b, const float lo[3], const float hi[3], int n)
{
    for (int a = 0; a < 3; a++) {
        b->lo[a] = lo[a] < b->lo[a] ? lo[a] : b->lo[a];
        b->hi[a] = hi[a] > b->hi[a] ? hi[a] : b->hi[a];
    }
    b->n += n;
}

/* The surface area of the bin's box (0 for an empty bin). */
static real
bin_area(const struct bin *b)
{
    real x = (real)b->hi[0] - b->lo[0];
    real y = (real)b->hi[1] - b->lo[1];
    real z = (real)b->hi[2] - b->lo[2];
    return b->n > 0 ? 2 * (x * y + y * z + z * x) : 0;
}

/* Split refs[0, n) at the plane of least cost, the primitives of the bins below it first, and
 * return how many they are, and the plane's axis; 0 when every centroid falls in one bin.  A ray
 * that meets a box meets a child with the chance of its area over the box's, so the expected cost
 * of testing both children's primitives is proportional to area(below) n(below) + area(above)
 * n(above).  One pass over the refs fills the bins of all three axes. */
static int
sah_split(struct build_ref *refs, int n, int *axis_out)
{
    const struct bin empty = {{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}, 0};
    struct bin c = empty;
    for (int i = 0; i < n; i++) {
        bin_add(&c, refs[i].centroid, refs[i].centroid, 0);
    }
    float scale[3];
    struct bin bins[3][SAH_BINS];
    for (int a = 0; a < 3; a++) {
        scale[a] = c.hi[a] > c.lo[a] ? SAH_BINS / (c.hi[a] - c.lo[a]) : 0;
        for (int k = 0; k < SAH_BINS; k++) {
            bins[a][k] = empty;
        }
    }
    for (int i = 0; i < n; i++) {
        for (int a = 0; a < 3; a++) {
            bin_add(&bins[a][bin_of(refs[i].centroid[a], c.lo[a], scale[a])], refs[i].lo, refs[i].hi, 1);
        }
    }
    real best = REAL_MAX;
    int best_axis = -1;
    int best_plane = 0;
    for (int a = 0; a < 3; a++) {
        real above[SAH_BINS]; /* area(above plane k) n(above plane k) */
        struct bin b = empty;
        for (int k = SAH_BINS - 1; k > 0; k--) {
            bin_add(&b, bins[a][k].lo, bins[a][k].hi, bins[a][k].n);
            above[k] = bin_area(&b) * b.n;
        }
        b = empty;
        for (int k = 1; k < SAH_BINS && scale[a] > 0; k++) {
            bin_add(&b, bins[a][k - 1].lo, bins[a][k - 1].hi, bins[a][k - 1].n);
            real cost = bin_area(&b) * b.n + above[k];
            if (b.n > 0 && b.n < n && cost < best) {
                best = cost;
                best_axis = a;
                best_plane = k;
            }
        }
    }
    if (best_axis < 0) {
        return 0;
    }
    *axis_out = best_axis;
    int j = 0;
    for (int i = 0; i < n; i++) {
        if (bin_of(refs[i].centroid[best_axis], c.lo[best_axis], scale[best_axis]) < best_plane) {
            struct build_ref swap = refs[i];
            refs[i] = refs[j];
            refs[j++] = swap;
        }
    }
    return j;
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
    real margin,
    int depth)
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
        int mid = depth < SAH_MAX_DEPTH ? begin + sah_split(refs + begin, end - begin, &axis) : begin;
        if (mid == begin) { /* one bin, or deep: the median along the widest spread */
            mid = begin + (end - begin) / 2;
            select_kth(refs + begin, end - begin, mid - begin, axis);
        }
        b = build_subtree(bvh, w, refs, begin, mid, margin, depth + 1); /* the next node */
        *node = (struct bvh_node){.index = (uint32_t)bvh->n_nodes, .axis = (uint8_t)axis};
        struct box second = build_subtree(bvh, w, refs, mid, end, margin, depth + 1);
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
        refs[p] = (struct build_ref){
            {float_below(c.x), float_below(c.y), float_below(c.z)},
            p,
            {float_below(b.lo.x), float_below(b.lo.y), float_below(b.lo.z)},
            {float_above(b.hi.x), float_above(b.hi.y), float_above(b.hi.z)}};
    }
    bvh->n_aside = set_aside(w, refs, all);
    real scale = fmax(vec3_max_comp(vec3_abs(all.lo)), vec3_max_comp(vec3_abs(all.hi)));
    if (bvh->n_aside < bvh->n_prims) {
        build_subtree(bvh, w, refs, bvh->n_aside, bvh->n_prims, scale * MARGIN, 0);
    }
    for (int slot = 0; slot < bvh->n_prims; slot++) {
        bvh->prims[slot] = refs[slot].prim;
    }
    free(refs);
    if (!bvh_widen(bvh, w)) {
        diag_set(err, NULL, 0, 0, "out of memory building a BVH over %d primitives", w->n_prims);
        bvh_free(bvh);
        return false;
    }
    return true;
}

void
bvh_free(struct bvh *bvh)
{
    free(bvh->nodes);
    free(bvh->wide);
    free(bvh->corners);
    free(bvh->prims);
    *bvh = (struct bvh){.nodes = NULL};
}
