/*
 * bvh.c - the bounding volume hierarchy, split by the surface area heuristic: each node's
 * primitives go to the side of the plane, among a few per axis, that makes the expected cost of a
 * ray's visit least (MacDonald and Booth 1990; binned, Wald 2007); then collapsed into a tree of
 * four children a node (wide.c).
 */
#include "bvh.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "geometry.h"

#define MARGIN (256 * REAL_EPSILON) /* of the scene's largest coordinate: boxes widen by it */
#define SAH_MAX_DEPTH 48 /* deeper nodes split at the median: the tree has < 48 + 31 levels */
#define STACK_SIZE 256 /* 3 a level: a tree of < 80 binary levels has < 80 wide ones */

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

/* END LAB */

/* LAB 09: SAH split */
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
int
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

/* END LAB */

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
        int axis = 0;
        int mid = depth < SAH_MAX_DEPTH ? begin + sah_split(refs + begin, end - begin, &axis) : begin;
        if (mid == begin) { /* one bin, or deep: the median along the widest spread */
            axis = widest_centroid_axis(refs + begin, end - begin);
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
    if (!bvh_widen(bvh)) {
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
    free(bvh->prims);
    *bvh = (struct bvh){.nodes = NULL};
}

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

/* Bit i set where lane i of m is (all ones): lane i's bit kept, then the lanes OR-ed together in
 * halves (a loop over the lanes compiles to one instruction a lane and a bit). */
static inline unsigned
lane_bits(int4 m)
{
#if BVH_WIDTH == 8
    m &= (int4){1, 2, 4, 8, 16, 32, 64, 128};
    m |= __builtin_shufflevector(m, m, 4, 5, 6, 7, 0, 1, 2, 3);
    m |= __builtin_shufflevector(m, m, 2, 3, 0, 1, 6, 7, 4, 5);
    m |= __builtin_shufflevector(m, m, 1, 0, 3, 2, 5, 4, 7, 6);
#else
    m &= (int4){1, 2, 4, 8};
    m |= __builtin_shufflevector(m, m, 2, 3, 0, 1);
    m |= __builtin_shufflevector(m, m, 1, 0, 3, 2);
#endif
    return (unsigned)m[0];
}

/* LAB 09: four boxes at once */
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
    memcpy(entry, &t_near, sizeof t_near);
    return lane_bits(t_near <= t_far * EXIT_SCALE);
}

/* END LAB */

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
            q->t_box4 = (float4){0} + float_above(h.t);
            q->t_prim = nextafter(h.t, (real)INFINITY);
        }
    }
}

/* LAB 09: wide traversal */
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

/* END LAB */

bool
bvh_intersect(const struct world *w, ray r, real t_max, bool any, struct hit *out, struct stats *st)
{
    struct query q; /* every member set below: an initializer would clear its 300 bytes first */
    q.w = w;
    q.r = r;
    q.any = any;
    q.found = false;
    q.t_box = t_max;
    q.t_prim = t_max;
    q.t_box4 = (float4){0} + float_above(t_max);
    q.out = out;
    q.visits = 0;
    q.tests = 0;
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
