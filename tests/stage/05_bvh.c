/*
 * 05_bvh.c - the bounding volume hierarchy: its structure (TESTING.md T15),
 * its answers against testing every primitive (T16), any-hit against
 * closest-hit, its cost growing as log n (T18) and not with the size of a
 * few large primitives (the primitives it sets aside).
 *
 * "Brute force" is the loop of world_intersect without a BVH: every
 * primitive in numbering order, a hit kept when t < the best so far, so the
 * lowest number wins a tie.  The BVH must give the same primitive, the same
 * t, u and v bit for bit, and bvh_intersect(any) must say "hit" exactly when brute
 * force finds one.  Every random choice comes from fixed seeds.
 */
#include <fenv.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "bvh.h"
#include "check.h"
#include "cull.h"
#include "geometry.h"
#include "meshgen.h"
#include "rng.h"

/* Sanitized builds run the same tests on fewer rays. */
#if defined(__SANITIZE_ADDRESS__)
#define RAY_DIVISOR 4
#else
#define RAY_DIVISOR 1
#endif

#define MISMATCHES_SHOWN 5

/* --- scenes built in memory ---------------------------------------------- */

/* realloc or give up: a test without memory cannot say anything. */
static void *
grow(void *p, size_t count, size_t size)
{
    void *q = realloc(p, (count ? count : 1) * size);
    if (!q) {
        printf("out of memory\n");
        exit(2);
    }
    return q;
}

static void
add_mesh(struct scene *s, const struct meshgen_mesh *m)
{
    CHECK(m->n_triangles > 0);
    size_t base = (size_t)s->n_vertices;
    size_t first = (size_t)s->n_triangles;
    s->positions = grow(s->positions, base + m->n_vertices, sizeof *s->positions);
    s->triangles = grow(s->triangles, first + m->n_triangles, sizeof *s->triangles);
    for (size_t i = 0; i < m->n_vertices; i++) {
        const double *p = &m->positions[3 * i];
        s->positions[base + i] = vec3_make((real)p[0], (real)p[1], (real)p[2]);
    }
    for (size_t i = 0; i < m->n_triangles; i++) {
        const unsigned *v = &m->indices[3 * i];
        int b = (int)base;
        s->triangles[first + i] =
            (struct triangle){.v = {b + (int)v[0], b + (int)v[1], b + (int)v[2]}};
    }
    s->n_vertices += (int)m->n_vertices;
    s->n_triangles += (int)m->n_triangles;
}

/* Add a mesh and free it. */
static void
add_mesh_once(struct scene *s, struct meshgen_mesh m)
{
    add_mesh(s, &m);
    meshgen_free(&m);
}

static void
add_sphere(struct scene *s, vec3 center, real radius)
{
    s->spheres = grow(s->spheres, (size_t)s->n_spheres + 1, sizeof *s->spheres);
    s->spheres[s->n_spheres++] = (struct sphere){.center = center, .radius = radius};
}

static void
add_quad(struct scene *s, vec3 corner, vec3 edge1, vec3 edge2)
{
    s->quads = grow(s->quads, (size_t)s->n_quads + 1, sizeof *s->quads);
    s->quads[s->n_quads++] = (struct quad){.corner = corner, .edge1 = edge1, .edge2 = edge2};
}

static void
add_area_light(struct scene *s, vec3 corner, vec3 edge1, vec3 edge2)
{
    s->area_lights = grow(s->area_lights, (size_t)s->n_area_lights + 1, sizeof *s->area_lights);
    s->area_lights[s->n_area_lights++] = (struct area_light){
        .corner = corner,
        .edge1 = edge1,
        .edge2 = edge2,
        .radiance = {1, 1, 1}};
}

/* A random triangle soup (meshgen: a fraction of it degenerate). */
static void
add_soup(struct scene *s, size_t n, uint64_t seed, double box, double edge, double degenerate)
{
    add_mesh_once(s, meshgen_random_triangles(n, seed, box, edge, degenerate));
}

/* --- the reference: every primitive in numbering order ------------------- */

/* Exact bounds of a primitive, in the world's numbering. */
static void
prim_box(const struct world *w, int prim, vec3 *lo, vec3 *hi)
{
    const struct scene *s = w->scene;
    int first_quad = s->n_spheres;
    int first_tri = first_quad + s->n_quads;
    int first_light = first_tri + s->n_triangles;
    vec3 p[4];
    int n = 4;
    if (prim < first_quad) {
        const struct sphere *sp = &s->spheres[prim];
        p[0] = vec3_sub(sp->center, vec3_splat(sp->radius));
        p[1] = vec3_add(sp->center, vec3_splat(sp->radius));
        n = 2;
    } else if (prim < first_tri || prim >= first_light) {
        const struct quad *q = prim < first_tri ? &s->quads[prim - first_quad] : NULL;
        const struct area_light *l = q ? NULL : &s->area_lights[prim - first_light];
        p[0] = q ? q->corner : l->corner;
        p[1] = vec3_add(p[0], q ? q->edge1 : l->edge1);
        p[2] = vec3_add(p[0], q ? q->edge2 : l->edge2);
        p[3] = vec3_add(p[1], q ? q->edge2 : l->edge2);
    } else {
        const struct triangle *t = &s->triangles[prim - first_tri];
        for (n = 0; n < 3; n++) {
            p[n] = s->positions[t->v[n]];
        }
    }
    *lo = *hi = p[0];
    for (int i = 1; i < n; i++) {
        *lo = vec3_min(*lo, p[i]);
        *hi = vec3_max(*hi, p[i]);
    }
}

/* The world and each primitive's ball, for brute force sooner (cull.h):
 * this program took 4.2 processor seconds testing every primitive, 1.2
 * with the balls. */
struct reference {
    const struct world *w;
    struct cull_ball *balls; /* per primitive */
};

static struct reference
reference_make(const struct world *w)
{
    struct reference ref = {w, grow(NULL, (size_t)w->n_prims, sizeof *ref.balls)};
    for (int prim = 0; prim < w->n_prims; prim++) {
        vec3 lo;
        vec3 hi;
        prim_box(w, prim, &lo, &hi);
        ref.balls[prim] = cull_ball_around(lo, hi);
    }
    return ref;
}

static void
reference_free(struct reference *ref)
{
    free(ref->balls);
    ref->balls = NULL;
}

/* Every primitive in numbering order, a hit kept when t < the best so far;
 * with `cull`, only those whose balls the ray's line meets (the same
 * answer but for a degenerate triangle's hit far off it: cull.h). */
static bool
brute_intersect(const struct reference *ref, ray r, real t_max, bool cull, struct hit *out)
{
    bool found = false;
    struct cull_line line = cull_line_make(r.o, r.d);
    for (int prim = 0; prim < ref->w->n_prims; prim++) {
        if ((!cull || cull_line_meets(&ref->balls[prim], &line)) &&
            intersect_prim(ref->w->scene, prim, r, t_max, out)) {
            t_max = out->t;
            found = true;
        }
    }
    return found;
}

/* bvh_intersect through the tree bvh over w's primitives (w itself holds
 * none: world_intersect and brute_intersect test every primitive). */
static bool
tree_intersect(
    const struct bvh *bvh,
    const struct world *w,
    ray r,
    real t_max,
    bool any,
    struct hit *out,
    struct stats *st)
{
    struct world with_tree = *w;
    with_tree.bvh = *bvh;
    return bvh_intersect(&with_tree, r, t_max, any, out, st);
}

/* --- the structure (T15) -------------------------------------------------- */

/* The box around every primitive. */
static void
scene_box(const struct world *w, vec3 *lo, vec3 *hi)
{
    prim_box(w, 0, lo, hi);
    for (int prim = 1; prim < w->n_prims; prim++) {
        vec3 a;
        vec3 b;
        prim_box(w, prim, &a, &b);
        *lo = vec3_min(*lo, a);
        *hi = vec3_max(*hi, b);
    }
}

/* What a walk of the tree found wrong, counted by kind. */
struct walk {
    int next_id; /* nodes are numbered in depth-first order */
    int next_slot; /* leaves cover prims[n_aside, n_prims) in order, without gaps */
    int depth, leaves, max_leaf;
    int bad_order, bad_leaf, bad_box, bad_child, bad_prim;
    int *seen; /* per primitive: how many leaves hold it */
};

#ifndef BVH_WIDTH /* the binary tree: stages 05 to 08 */
static bool
box_holds(const struct bvh_node *outer, vec3 lo, vec3 hi)
{
    for (int i = 0; i < 3; i++) {
        if (!((real)outer->lo[i] <= vec3_axis(lo, i) && vec3_axis(hi, i) <= (real)outer->hi[i])) {
            return false;
        }
    }
    return true;
}

static bool
node_holds(const struct bvh_node *outer, const struct bvh_node *inner)
{
    vec3 lo = vec3_make(inner->lo[0], inner->lo[1], inner->lo[2]);
    vec3 hi = vec3_make(inner->hi[0], inner->hi[1], inner->hi[2]);
    return box_holds(outer, lo, hi);
}


static void
walk_leaf(const struct bvh *bvh, const struct world *w, const struct bvh_node *node, struct walk *k)
{
    k->leaves++;
    k->max_leaf = node->count > k->max_leaf ? node->count : k->max_leaf;
    k->bad_leaf += node->count < 1 || node->count > BVH_MAX_LEAF
                   || node->index != (uint32_t)k->next_slot
                   || node->index + node->count > (uint32_t)bvh->n_prims;
    for (uint32_t slot = node->index;
         slot < node->index + node->count && slot < (uint32_t)bvh->n_prims;
         slot++) {
        int prim = bvh->prims[slot];
        if (prim < 0 || prim >= w->n_prims) {
            k->bad_prim++;
            continue;
        }
        k->seen[prim]++;
        vec3 lo;
        vec3 hi;
        prim_box(w, prim, &lo, &hi);
        k->bad_box += !box_holds(node, lo, hi);
    }
    k->next_slot += node->count;
}

static void
walk_interior(const struct bvh *bvh, uint32_t id, struct walk *k)
{
    const struct bvh_node *node = &bvh->nodes[id];
    uint32_t second = node->index;
    if (second <= id + 1 || second >= (uint32_t)bvh->n_nodes || node->axis > 2) {
        k->bad_child++;
        return;
    }
    k->bad_box += !node_holds(node, &bvh->nodes[id + 1]) || !node_holds(node, &bvh->nodes[second]);
}

/* Depth-first walk from the root, checking each node as it is met (a
 * median split of fewer than 2^31 primitives is under 32 levels deep). */
static void
walk_tree(const struct bvh *bvh, const struct world *w, struct walk *k)
{
    uint32_t stack[64];
    int depth_of[64];
    int top = 0;
    stack[top] = 0;
    depth_of[top++] = 1;
    while (top > 0 && k->bad_child == 0 && top < 64 - 2) {
        uint32_t id = stack[--top];
        int depth = depth_of[top];
        k->bad_order += id != (uint32_t)k->next_id++;
        k->depth = depth > k->depth ? depth : k->depth;
        const struct bvh_node *node = &bvh->nodes[id];
        if (node->count > 0) {
            walk_leaf(bvh, w, node, k);
            continue;
        }
        walk_interior(bvh, id, k);
        stack[top] = node->index;
        depth_of[top++] = depth + 1;
        stack[top] = id + 1;
        depth_of[top++] = depth + 1;
    }
}

#endif

/* The primitives set aside: at most BVH_MAX_ASIDE, valid numbers; counted
 * in k->seen. */
static void
check_aside(const struct bvh *bvh, const struct world *w, struct walk *k)
{
    CHECK_MSG(
        bvh->n_aside >= 0 && bvh->n_aside <= BVH_MAX_ASIDE && bvh->n_aside <= w->n_prims,
        "%d primitives set aside",
        bvh->n_aside);
    for (int slot = 0; slot < bvh->n_aside && slot < w->n_prims; slot++) {
        int prim = bvh->prims[slot];
        bool valid = prim >= 0 && prim < w->n_prims;
        k->bad_prim += !valid;
        k->seen[valid ? prim : 0] += valid;
    }
    k->next_slot = bvh->n_aside;
}

#ifndef BVH_WIDTH
/* Levels a median split of n primitives makes: halving until a leaf. */
static int
median_split_depth(int n)
{
    return n <= BVH_MAX_LEAF ? 1 : 1 + median_split_depth(n - n / 2);
}

/* T15: every primitive in exactly one leaf or set aside; leaves of
 * 1..BVH_MAX_LEAF primitives covering the rest of prims[] in order;
 * depth-first numbering; every box holding its children and its
 * primitives; the summary fields true; the median split's depth. */
static void
check_structure(const struct bvh *bvh, const struct world *w)
{
    CHECK(bvh->n_prims == w->n_prims);
    if (w->n_prims == 0) {
        CHECK(bvh->n_nodes == 0 && bvh->n_aside == 0);
        return;
    }
    int in_tree = w->n_prims - bvh->n_aside;
    if (in_tree > 0 && (bvh->n_nodes < 1 || !bvh->nodes)) {
        CHECK_MSG(false, "no nodes for %d primitives: bvh_build built no tree", in_tree);
        return;
    }
    struct walk k = {.seen = calloc((size_t)w->n_prims, sizeof(int))};
    CHECK(k.seen != NULL && bvh->n_nodes <= 2 * in_tree - 1 + (in_tree == 0));
    check_aside(bvh, w, &k);
    if (in_tree > 0) {
        walk_tree(bvh, w, &k);
    }
    int not_once = 0;
    for (int prim = 0; prim < w->n_prims; prim++) {
        not_once += k.seen[prim] != 1;
    }
    free(k.seen);
    CHECK_MSG(not_once == 0, "%d primitives not in exactly one leaf or set aside", not_once);
    CHECK_MSG(
        k.bad_order == 0 && k.bad_child == 0,
        "%d nodes out of depth-first order, %d bad children",
        k.bad_order,
        k.bad_child);
    CHECK_MSG(
        k.bad_leaf == 0 && k.bad_prim == 0,
        "%d bad leaves, %d bad numbers",
        k.bad_leaf,
        k.bad_prim);
    CHECK_MSG(k.bad_box == 0, "%d boxes not holding their contents", k.bad_box);
    CHECK(k.next_id == bvh->n_nodes && k.next_slot == w->n_prims);
    CHECK(k.depth == (in_tree == 0 ? 0 : median_split_depth(in_tree)));
    CHECK(k.max_leaf <= BVH_MAX_LEAF);
}
#endif

#ifdef BVH_WIDTH
/*
 * Stage 09 on: the binary tree is widened (bvh.h's struct bvh_wide) and its
 * nodes freed.  The same invariants, for BVH_WIDTH children a node: every
 * primitive in exactly one leaf or set aside; leaves of 1..BVH_MAX_LEAF
 * primitives, together covering each slot of prims[n_aside, n_prims) once;
 * the nodes numbered depth first; child i's box holding its primitives, or
 * its own children's boxes; an absent child's box empty and never a leaf;
 * at most 80 levels (the build splits by the SAH to depth 48, then at the
 * median: the traversal's stack holds 3 a level).
 */
static bool
wide_holds(const struct bvh_wide *node, int i, vec3 lo, vec3 hi)
{
    for (int a = 0; a < 3; a++) {
        if (!((real)node->lo[a][i] <= vec3_axis(lo, a) && vec3_axis(hi, a) <= (real)node->hi[a][i])) {
            return false;
        }
    }
    return true;
}

static void
walk_wide(const struct bvh *bvh, const struct world *w, uint32_t id, int depth, struct walk *k, int *slots)
{
    k->bad_order += id != (uint32_t)k->next_id++;
    k->depth = depth > k->depth ? depth : k->depth;
    const struct bvh_wide *node = &bvh->wide[id];
    for (int i = 0; i < BVH_WIDTH && k->bad_child == 0 && depth <= 80; i++) {
        bool leaf = node->leaves >> i & 1;
        if (!(node->lo[0][i] <= node->hi[0][i])) { /* absent */
            k->bad_child += leaf || node->count[i] != 0 || node->lo[0][i] != INFINITY;
            continue;
        }
        if (leaf != (node->count[i] > 0)) {
            k->bad_child++;
            continue;
        }
        if (leaf) {
            k->leaves++;
            k->max_leaf = node->count[i] > k->max_leaf ? node->count[i] : k->max_leaf;
            uint32_t first = node->child[i];
            if (first < (uint32_t)bvh->n_aside || first + node->count[i] > (uint32_t)bvh->n_prims) {
                k->bad_leaf++;
                continue;
            }
            for (uint32_t slot = first; slot < first + node->count[i]; slot++) {
                int prim = bvh->prims[slot];
                slots[slot]++;
                if (prim < 0 || prim >= w->n_prims) {
                    k->bad_prim++;
                    continue;
                }
                k->seen[prim]++;
                vec3 lo;
                vec3 hi;
                prim_box(w, prim, &lo, &hi);
                k->bad_box += !wide_holds(node, i, lo, hi);
            }
            continue;
        }
        uint32_t c = node->child[i];
        if (c <= id || c >= (uint32_t)bvh->n_wide) {
            k->bad_child++;
            continue;
        }
        const struct bvh_wide *child = &bvh->wide[c];
        for (int j = 0; j < BVH_WIDTH; j++) {
            if (child->lo[0][j] <= child->hi[0][j]) {
                vec3 lo = vec3_make(child->lo[0][j], child->lo[1][j], child->lo[2][j]);
                vec3 hi = vec3_make(child->hi[0][j], child->hi[1][j], child->hi[2][j]);
                k->bad_box += !wide_holds(node, i, lo, hi);
            }
        }
        walk_wide(bvh, w, c, depth + 1, k, slots);
    }
}

static void
check_structure(const struct bvh *bvh, const struct world *w)
{
    CHECK(bvh->n_prims == w->n_prims);
    if (w->n_prims == 0) {
        CHECK(bvh->n_wide == 0 && bvh->n_aside == 0);
        return;
    }
    int in_tree = w->n_prims - bvh->n_aside;
    if (in_tree > 0 && (bvh->n_wide < 1 || !bvh->wide)) {
        CHECK_MSG(false, "no nodes for %d primitives: bvh_build built no tree", in_tree);
        return;
    }
    CHECK_MSG(bvh->nodes == NULL, "the binary nodes are kept after widening");
    struct walk k = {.seen = calloc((size_t)w->n_prims, sizeof(int))};
    int *slots = calloc((size_t)w->n_prims, sizeof(int));
    CHECK(k.seen != NULL && slots != NULL && bvh->n_wide <= 2 * in_tree - 1 + (in_tree == 0));
    if (!k.seen || !slots) {
        free(k.seen);
        free(slots);
        return;
    }
    check_aside(bvh, w, &k);
    if (in_tree > 0) {
        walk_wide(bvh, w, 0, 1, &k, slots);
    }
    int not_once = 0;
    int slots_not_once = 0;
    for (int prim = 0; prim < w->n_prims; prim++) {
        not_once += k.seen[prim] != 1;
        slots_not_once += prim >= bvh->n_aside && slots[prim] != 1;
    }
    free(k.seen);
    free(slots);
    CHECK_MSG(not_once == 0, "%d primitives not in exactly one leaf or set aside", not_once);
    CHECK_MSG(slots_not_once == 0, "%d slots not in exactly one leaf", slots_not_once);
    CHECK_MSG(
        k.bad_order == 0 && k.bad_child == 0,
        "%d nodes out of depth-first order, %d bad children",
        k.bad_order,
        k.bad_child);
    CHECK_MSG(k.bad_leaf == 0 && k.bad_prim == 0, "%d bad leaves, %d bad numbers", k.bad_leaf, k.bad_prim);
    CHECK_MSG(k.bad_box == 0, "%d boxes not holding their contents", k.bad_box);
    CHECK(in_tree == 0 || k.next_id == bvh->n_wide);
    CHECK_MSG(k.depth <= 80, "%d levels", k.depth);
    CHECK(k.max_leaf <= BVH_MAX_LEAF);
}
#endif

/* Build over s, check the structure, and keep the BVH in *bvh. */
static void
build_checked(const struct world *w, struct bvh *bvh)
{
    struct diag err;
    CHECK(bvh_build(bvh, w, &err));
    check_structure(bvh, w);
}

TEST(structure_of_random_soups)
{
    CHECK(sizeof(struct bvh_node) == 32); /* two nodes to a 64-byte cache line */
    const size_t sizes[] = {1, 2, 3, 4, 5, 7, 17, 100, 1000, 4097};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        struct scene s = {0};
        add_soup(&s, sizes[i], 100 + i, 10, 1, 0.1);
        struct world w = world_make(&s);
        struct bvh bvh;
        build_checked(&w, &bvh);
        bvh_free(&bvh);
        scene_free(&s);
    }
}

/* One primitive is as large as the scene: it is set aside, and there is no
 * tree. */
TEST(single_primitive_is_set_aside)
{
    for (int kind = 0; kind < 3; kind++) {
        struct scene s = {0};
        if (kind == 0) {
            add_sphere(&s, vec3_make(1, 2, 3), 0.5);
        } else if (kind == 1) {
            add_quad(&s, vec3_make(0, 0, 0), vec3_make(1, 0, 0), vec3_make(0, 1, 0));
        } else {
            add_soup(&s, 1, 7, 4, 1, 0);
        }
        struct world w = world_make(&s);
        struct bvh bvh;
        build_checked(&w, &bvh);
        CHECK(bvh.n_nodes == 0 && bvh.n_aside == 1 && bvh.prims[0] == 0);
        bvh_free(&bvh);
        scene_free(&s);
    }
}

TEST(empty_world)
{
    struct scene s = {0};
    struct world w = world_make(&s);
    struct bvh bvh;
    struct diag err;
    struct stats st = {0};
    struct hit h;
    CHECK(bvh_build(&bvh, &w, &err));
    CHECK(bvh.n_nodes == 0 && bvh.n_prims == 0);
    ray r = {vec3_make(0, 0, 0), vec3_make(0, 0, 1)};
    CHECK(!tree_intersect(&bvh, &w, r, REAL_MAX, false, &h, &st));
    CHECK(!tree_intersect(&bvh, &w, r, REAL_MAX, true, &h, &st));
    bvh_free(&bvh);
    bvh_free(&bvh); /* freeing twice, or a zeroed bvh, is allowed */
}

/* Copies of one triangle (2,000: every centroid the same), then with
 * spheres of many radii and the triangle mirrored through the same centre
 * added.  Splitting by count must still end, with leaves no larger than
 * BVH_MAX_LEAF and the depth of a median split. */
TEST(coincident_centroids_terminate)
{
    struct scene s = {0};
    struct meshgen_mesh one = meshgen_random_triangles(1, 3, 2, 1, 0);
    for (int i = 0; i < 2000; i++) {
        add_mesh(&s, &one);
    }
    struct world w = world_make(&s);
    struct bvh bvh;
    build_checked(&w, &bvh);
    bvh_free(&bvh);
    vec3 lo;
    vec3 hi;
    prim_box(&w, 0, &lo, &hi);
    vec3 c = vec3_scale(vec3_add(lo, hi), 0.5);
    for (size_t i = 0; i < 3 * one.n_vertices; i++) {
        one.positions[i] = 2 * vec3_axis(c, (int)(i % 3)) - one.positions[i];
    }
    for (int i = 0; i < 300; i++) {
        add_mesh(&s, &one);
        add_sphere(&s, c, (real)(1 + i));
    }
    meshgen_free(&one);
    w = world_make(&s);
    build_checked(&w, &bvh);
    bvh_free(&bvh);
    scene_free(&s);
}

/* A flat (coplanar) scene: the boxes have zero thickness but for the
 * margin, and every centroid has the same y. */
TEST(flat_scene)
{
    struct scene s = {0};
    add_mesh_once(&s, meshgen_terrain(40, 30, 4, 0, 1));
    for (int i = 0; i < 10; i++) {
        add_quad(&s, vec3_make(i - 5, 0, 3), vec3_make(1, 0, 0), vec3_make(0, 0, 1));
    }
    struct world w = world_make(&s);
    struct bvh bvh;
    build_checked(&w, &bvh);
    bvh_free(&bvh);
    scene_free(&s);
}

/* --- against brute force (T16) -------------------------------------------- */

struct agreement {
    int rays, hits, mismatches;
    int off_surface; /* brute force's hit is nowhere near its primitive */
};

static void
show_mismatch(
    ray r,
    real t_max,
    bool e,
    const struct hit *expect,
    bool g,
    const struct hit *got,
    bool any)
{
    printf(
        "  ray o (%a %a %a) d (%a %a %a) t_max %a:\n",
        (double)r.o.x,
        (double)r.o.y,
        (double)r.o.z,
        (double)r.d.x,
        (double)r.d.y,
        (double)r.d.z,
        (double)t_max);
    printf(
        "    brute %s prim %d t %a; bvh %s prim %d t %a; occluded %d\n",
        e ? "hit" : "miss",
        e ? expect->prim : -1,
        e ? (double)expect->t : 0.0,
        g ? "hit" : "miss",
        g ? got->prim : -1,
        g ? (double)got->t : 0.0,
        any);
}

/*
 * Whether a hit lies far outside its primitive's bounds.  Moller-Trumbore
 * on a degenerate (collinear) triangle can compute a determinant of pure
 * rounding noise instead of 0 and report a "hit" anywhere along the ray.
 * No bounding box can hold such hits, so no BVH can agree with brute force
 * there; compare_ray counts these rays apart and reports them.  (Example,
 * soup seed 1018, triangle 154: corners (-60.1875, 492.328, -295.328),
 * (175.656, 148.562, -341.5), (-296.031, 836.094, -249.156), exactly
 * collinear; det = -0x1.8p-38, u = v = -0, t = 1365.33 from a ray passing
 * nowhere near it.  intersect_triangle could reject zero-area triangles.)
 */
static bool
hit_off_surface(const struct world *w, ray r, const struct hit *h)
{
    vec3 lo;
    vec3 hi;
    prim_box(w, h->prim, &lo, &hi);
    vec3 p = ray_at(r, h->t);
    real slack = (real)1e-4 * (vec3_max_comp(vec3_abs(lo)) + vec3_max_comp(vec3_abs(hi)) + h->t);
    for (int i = 0; i < 3; i++) {
        real x = vec3_axis(p, i);
        if (x < vec3_axis(lo, i) - slack || x > vec3_axis(hi, i) + slack) {
            return true;
        }
    }
    return false;
}

/* Brute force's hit (e, expect) and the tree's closest (g, got) and any (any). */
static bool
answers_agree(bool e, const struct hit *expect, bool g, const struct hit *got, bool any)
{
    if (e != g || any != e) {
        return false;
    }
    return !e || (got->prim == expect->prim && got->t == expect->t && got->u == expect->u &&
                  got->v == expect->v);
}

/* One ray through the BVH and through brute force: the same answer? */
static void
compare_ray(
    const struct reference *ref,
    const struct bvh *bvh,
    ray r,
    real t_max,
    struct agreement *a)
{
    const struct world *w = ref->w;
    struct hit expect;
    struct hit got;
    struct stats st = {0};
    bool g = tree_intersect(bvh, w, r, t_max, false, &got, &st);
    struct hit scratch;
    bool any = tree_intersect(bvh, w, r, t_max, true, &scratch, &st);
    bool e = brute_intersect(ref, r, t_max, true, &expect);
    bool same = answers_agree(e, &expect, g, &got, any);
    if (!same) {
        e = brute_intersect(ref, r, t_max, false, &expect);
        same = answers_agree(e, &expect, g, &got, any);
    }
    if (!same && e && hit_off_surface(w, r, &expect)) {
        a->off_surface++;
    } else if (!same && a->mismatches++ < MISMATCHES_SHOWN) {
        show_mismatch(r, t_max, e, &expect, g, &got, any);
    }
    a->rays++;
    a->hits += e;
}

static void
check_agreement(const char *what, const struct agreement *a, double min_hit_fraction)
{
    printf("  %s: %d rays, %d hits, %d mismatches", what, a->rays, a->hits, a->mismatches);
    if (a->off_surface) {
        printf(
            "; left out: %d where brute force hits a degenerate triangle far off it",
            a->off_surface);
    }
    printf("\n");
    CHECK_MSG(
        a->mismatches == 0,
        "%s: %d of %d rays differ from brute force",
        what,
        a->mismatches,
        a->rays);
    CHECK_MSG(
        a->hits >= min_hit_fraction * a->rays,
        "%s: only %d hits in %d rays",
        what,
        a->hits,
        a->rays);
}

static vec3
uniform_direction(struct rng *g)
{
    real z = 1 - 2 * rng_uniform(g);
    real phi = 2 * PI * rng_uniform(g);
    real s = safe_sqrt(1 - z * z);
    return vec3_make(s * cos(phi), s * sin(phi), z);
}

/* Axis-aligned (with signed zeros), almost axis-aligned (a component
 * 1e-310, whose reciprocal overflows) or uniform directions. */
static vec3
test_direction(struct rng *g)
{
    real u = rng_uniform(g);
    if (u < (real)0.8) {
        return uniform_direction(g);
    }
    int axis = (int)(rng_uniform(g) * 3) % 3;
    real sign = rng_uniform(g) < (real)0.5 ? -1 : 1;
    real zero = rng_uniform(g) < (real)0.5 ? (real)-0.0 : (real)0.0;
    vec3 d = vec3_splat(zero);
    if (u < (real)0.9) {
        d = vec3_make(zero, (real)1e-310 * sign, (real)-1e-310); /* 0 in float builds */
    }
    return axis == 0   ? vec3_make(sign, d.y, d.z)
           : axis == 1 ? vec3_make(d.y, sign, d.z)
                       : vec3_make(d.y, d.z, sign);
}

/* A random point on a random primitive, to aim at: most rays then hit. */
static vec3
point_on_prim(const struct world *w, struct rng *g)
{
    const struct scene *s = w->scene;
    int prim = (int)(rng_uniform(g) * w->n_prims) % w->n_prims;
    int first_quad = s->n_spheres;
    int first_tri = first_quad + s->n_quads;
    int first_light = first_tri + s->n_triangles;
    real u = rng_uniform(g);
    real v = rng_uniform(g);
    if (prim < first_quad) {
        const struct sphere *sp = &s->spheres[prim];
        return vec3_madd(sp->center, uniform_direction(g), sp->radius * (real)0.99);
    }
    if (prim < first_tri) {
        const struct quad *q = &s->quads[prim - first_quad];
        return vec3_madd(vec3_madd(q->corner, q->edge1, u), q->edge2, v);
    }
    if (prim >= first_light) {
        const struct area_light *l = &s->area_lights[prim - first_light];
        return vec3_madd(vec3_madd(l->corner, l->edge1, u), l->edge2, v);
    }
    const struct triangle *t = &s->triangles[prim - first_tri];
    if (u + v > 1) {
        u = 1 - u;
        v = 1 - v;
    }
    vec3 p0 = s->positions[t->v[0]];
    vec3 e1 = vec3_sub(s->positions[t->v[1]], p0);
    vec3 e2 = vec3_sub(s->positions[t->v[2]], p0);
    return vec3_madd(vec3_madd(p0, e1, u), e2, v);
}

/* n rays: origins inside the scene's bounds widened by `spread` (so many
 * start inside boxes), half aimed at a primitive, half in test directions;
 * t_max mostly unlimited, sometimes random. */
static void
compare_random_rays(
    const struct reference *ref,
    const struct bvh *bvh,
    int n,
    uint64_t seed,
    struct agreement *a)
{
    const struct world *w = ref->w;
    struct rng g = rng_make(seed, 5);
    vec3 lo;
    vec3 hi;
    scene_box(w, &lo, &hi);
    vec3 size = vec3_sub(hi, lo);
    for (int i = 0; i < n; i++) {
        vec3 f = vec3_make(rng_uniform(&g), rng_uniform(&g), rng_uniform(&g));
        vec3 o = vec3_add(vec3_sub(lo, vec3_scale(size, 0.25)), vec3_mul(f, vec3_scale(size, 1.5)));
        vec3 d = test_direction(&g);
        if (i % 2 == 0) {
            vec3 to = vec3_sub(point_on_prim(w, &g), o);
            d = vec3_length2(to) > 0 ? vec3_normalize(to) : d;
        }
        real t_max = rng_uniform(&g) < (real)0.8 ? REAL_MAX : rng_uniform(&g) * vec3_length(size);
        compare_ray(ref, bvh, (ray){o, d}, t_max, a);
    }
}

/* Build over s and compare n random rays. */
static void
check_scene_rays(const struct scene *s, int n, uint64_t seed, const char *what, double min_hits)
{
    struct world w = world_make(s);
    struct bvh bvh;
    build_checked(&w, &bvh);
    struct reference ref = reference_make(&w);
    struct agreement a = {0};
    compare_random_rays(&ref, &bvh, n / RAY_DIVISOR, seed, &a);
    check_agreement(what, &a, min_hits);
    reference_free(&ref);
    bvh_free(&bvh);
}

/* 40 soups of 200..2,150 triangles, small and large, 10% degenerate:
 * 25,000 rays (TESTING.md's T16: 500 rays a mesh). */
TEST(agrees_on_random_soups)
{
    for (int i = 0; i < 40; i++) {
        struct scene s = {0};
        size_t n = 200 + 50 * (size_t)i;
        add_soup(&s, n, 1000 + (uint64_t)i, i % 2 ? 1 : 1000, i % 3 ? 0.1 : 0, 0.1);
        char what[64];
        snprintf(what, sizeof what, "soup %d (%zu triangles)", i, n);
        check_scene_rays(&s, 625, 2000 + (uint64_t)i, what, 0.08);
        scene_free(&s);
    }
}

/* Degenerate meshes only: zero-area, collinear, repeated vertices and
 * indices, aimed at (some are hit along their edges, most never are). */
TEST(agrees_on_degenerate_meshes)
{
    struct scene s = {0};
    add_soup(&s, 1500, 31, 8, 1, 1.0);
    add_soup(&s, 500, 32, 8, 0.5, 0.5);
    check_scene_rays(&s, 10000, 33, "degenerate soup", 0.05);
    scene_free(&s);
}

/* A closed tessellated sphere, seen from outside and from inside. */
TEST(agrees_on_closed_sphere)
{
    struct scene s = {0};
    const double center[3] = {0.25, -0.5, 1};
    add_mesh_once(&s, meshgen_sphere(40, 60, 2, center, 0.05, 9));
    check_scene_rays(&s, 10000, 41, "closed sphere", 0.5);
    scene_free(&s);
}

/* Spheres, quads, triangles and area lights together (the lights are
 * primitives when the stage's world counts them). */
TEST(agrees_on_mixed_scene)
{
    struct scene s = {0};
    struct rng g = rng_make(51, 1);
    for (int i = 0; i < 60; i++) {
        vec3 c =
            vec3_make(rng_uniform(&g) * 8 - 4, rng_uniform(&g) * 8 - 4, rng_uniform(&g) * 8 - 4);
        add_sphere(&s, c, (real)0.05 + rng_uniform(&g) * (real)0.5);
        add_quad(
            &s,
            c,
            vec3_scale(uniform_direction(&g), 1),
            vec3_scale(uniform_direction(&g), 0.5));
        add_area_light(&s, vec3_add(c, vec3_splat(1)), vec3_make(0.3, 0, 0), vec3_make(0, 0, 0.3));
    }
    add_soup(&s, 800, 52, 8, 0.5, 0.1);
    struct world w = world_make(&s);
    CHECK(w.n_prims >= s.n_spheres + s.n_quads + s.n_triangles);
    check_scene_rays(&s, 10000, 53, "mixed scene", 0.3);
    scene_free(&s);
}

/* Copies of one triangle and of one quad are hit at exactly the same t:
 * brute force keeps the lowest number, and so must the BVH, though the
 * copies end up in different leaves. */
TEST(ties_go_to_the_lowest_number)
{
    struct scene s = {0};
    for (int i = 0; i < 64; i++) {
        add_quad(&s, vec3_make(-1, -1, -2.5), vec3_make(2, 0, 0), vec3_make(0, 2, 0));
    }
    struct meshgen_mesh one = meshgen_random_triangles(1, 61, 2, 0, 0);
    for (int i = 0; i < 64; i++) {
        add_mesh(&s, &one);
    }
    meshgen_free(&one);
    add_soup(&s, 300, 62, 4, 0.5, 0);
    check_scene_rays(&s, 4000, 63, "duplicates", 0.3);
    struct world w = world_make(&s);
    struct bvh bvh;
    build_checked(&w, &bvh);
    struct hit h;
    struct stats st = {0};
    ray r = {vec3_make(0.125, 0.25, -3), vec3_make(0, 0, 1)};
    CHECK(tree_intersect(&bvh, &w, r, REAL_MAX, false, &h, &st) && h.prim == 0);
    bvh_free(&bvh);
    scene_free(&s);
}

/* --- axis-aligned rays in faces and along edges (TESTING.md 3.4) ---------- */

/* A row of unit cubes along x at z in [2, 3] (triangles; neighbours share a
 * face, so each shared face is there twice), a cube of quads [0, 1]^3 and a
 * cube of triangles [1, 2] x [0, 1] x [0, 1] beside it. */
static void
make_cubes(struct scene *s)
{
    for (int i = 0; i < 4; i++) {
        const double lo[3] = {i, 0, 2};
        const double hi[3] = {i + 1, 1, 3};
        add_mesh_once(s, meshgen_box(lo, hi));
    }
    vec3 o = vec3_make(0, 0, 0);
    vec3 x = vec3_make(1, 0, 0);
    vec3 y = vec3_make(0, 1, 0);
    vec3 z = vec3_make(0, 0, 1);
    add_quad(s, o, x, y);
    add_quad(s, o, y, z);
    add_quad(s, o, z, x);
    add_quad(s, vec3_add(o, z), x, y);
    add_quad(s, vec3_add(o, x), y, z);
    add_quad(s, vec3_add(o, y), z, x);
    const double lo[3] = {1, 0, 0};
    const double hi[3] = {2, 1, 1};
    add_mesh_once(s, meshgen_box(lo, hi));
}

static vec3
on_axes(int axis, real along, real a, real b)
{
    return axis == 0   ? vec3_make(along, a, b)
           : axis == 1 ? vec3_make(b, along, a)
                       : vec3_make(a, b, along);
}

/* Rays along each axis, both ways, with +0 and -0 in the other components,
 * from outside and from inside the cubes, on a grid of lines that includes
 * every face plane (0, 1, 2, 3, 4) and every edge where two of them meet. */
static void
compare_axis_rays(const struct reference *ref, const struct bvh *bvh, struct agreement *a)
{
    static const real grid[] = {-0.5, 0, 0.25, 0.5, 1, 1.5, 2, 2.5, 3, 4, 4.5};
    static const real starts[] = {-10, 0.5, 1, 2.5}; /* -10: from outside */
    const int n = (int)(sizeof grid / sizeof grid[0]);
    for (int axis = 0; axis < 3; axis++) {
        for (int k = 0; k < 4 * 4; k++) {
            real sign = k & 1 ? -1 : 1;
            real zero = k & 2 ? (real)-0.0 : (real)0.0;
            real start = k / 4 == 0 ? -10 * sign : starts[k / 4];
            vec3 d = on_axes(axis, sign, zero, zero);
            for (int i = 0; i < n * n; i++) {
                vec3 o = on_axes(axis, start, grid[i / n], grid[i % n]);
                compare_ray(ref, bvh, (ray){o, d}, REAL_MAX, a);
            }
        }
    }
}

/* Diagonal rays from grid points through edges and corners of the cubes. */
static void
compare_diagonal_rays(const struct reference *ref, const struct bvh *bvh, struct agreement *a)
{
    for (int i = 0; i < 5 * 5 * 5; i++) {
        vec3 o = vec3_make(i % 5 - 0.5, i / 5 % 5 - 1, i / 25 - 0.5);
        for (int j = 0; j < 5 * 4 * 4; j++) {
            vec3 to = vec3_make(j % 5, j / 5 % 4 * 0.5, j / 20 % 4);
            vec3 d = vec3_sub(to, o);
            if (vec3_length2(d) > 0) {
                compare_ray(ref, bvh, (ray){o, vec3_normalize(d)}, REAL_MAX, a);
            }
        }
    }
}

TEST(agrees_on_rays_in_faces_and_edges)
{
    struct scene s = {0};
    make_cubes(&s);
    struct world w = world_make(&s);
    struct bvh bvh;
    build_checked(&w, &bvh);
    struct reference ref = reference_make(&w);
    struct agreement a = {0};
    compare_axis_rays(&ref, &bvh, &a);
    check_agreement("axis-aligned rays", &a, 0.1);
    a = (struct agreement){0};
    compare_diagonal_rays(&ref, &bvh, &a);
    check_agreement("rays through edges and corners", &a, 0.3);
    reference_free(&ref);
    bvh_free(&bvh);
    scene_free(&s);
}

/* The slab test handles parallel rays without 0 * infinity: tracing rays
 * that run exactly in box faces raises no invalid-operation flag. */
TEST(traversal_raises_no_invalid_operation)
{
    struct scene s = {0};
    make_cubes(&s);
    struct world w = world_make(&s);
    struct bvh bvh;
    build_checked(&w, &bvh);
    struct reference ref = reference_make(&w);
    struct agreement a = {0};
    feclearexcept(FE_ALL_EXCEPT);
    compare_axis_rays(&ref, &bvh, &a);
    CHECK(!fetestexcept(FE_INVALID));
    reference_free(&ref);
    bvh_free(&bvh);
    scene_free(&s);
}

/* t_max exactly at, just below and just above a hit, and half of it: the
 * BVH's limits are brute force's (hits count only when t < t_max). */
TEST(agrees_at_t_max_limits)
{
    struct scene s = {0};
    add_soup(&s, 2000, 71, 10, 1, 0.05);
    add_sphere(&s, vec3_make(0, 0, 0), 1);
    struct world w = world_make(&s);
    struct bvh bvh;
    build_checked(&w, &bvh);
    struct reference ref = reference_make(&w);
    struct rng g = rng_make(72, 1);
    struct agreement a = {0};
    for (int i = 0; i < 4000 / RAY_DIVISOR; i++) {
        ray r = {vec3_scale(uniform_direction(&g), 8), uniform_direction(&g)};
        r.d = vec3_normalize(vec3_sub(point_on_prim(&w, &g), r.o));
        struct hit h;
        if (!brute_intersect(&ref, r, REAL_MAX, true, &h)) {
            continue;
        }
        const real limits[] =
            {h.t, nextafter(h.t, (real)0), nextafter(h.t, (real)INFINITY), h.t / 2};
        for (int k = 0; k < 4; k++) {
            compare_ray(&ref, &bvh, r, limits[k], &a);
        }
    }
    check_agreement("t_max limits", &a, 0.2);
    reference_free(&ref);
    bvh_free(&bvh);
    scene_free(&s);
}

/* Shadow rays: between two random points of a terrain, t_max the distance
 * between them; any-hit queries agree with brute-force closest hit. */
TEST(any_hit_agrees_with_closest_hit)
{
    struct scene s = {0};
    add_mesh_once(&s, meshgen_terrain(60, 60, 4, 0.8, 81));
    struct world w = world_make(&s);
    struct bvh bvh;
    build_checked(&w, &bvh);
    struct reference ref = reference_make(&w);
    struct rng g = rng_make(82, 1);
    struct agreement a = {0};
    int blocked = 0;
    for (int i = 0; i < 10000 / RAY_DIVISOR; i++) {
        vec3 from = vec3_add(point_on_prim(&w, &g), vec3_make(0, 0.05, 0));
        vec3 to = vec3_add(point_on_prim(&w, &g), vec3_make(0, 0.05, 0));
        real distance = vec3_length(vec3_sub(to, from));
        if (distance > 0) {
            ray r = {from, vec3_scale(vec3_sub(to, from), 1 / distance)};
            struct stats st = {0};
            struct hit h;
            blocked += tree_intersect(&bvh, &w, r, distance, true, &h, &st);
            compare_ray(&ref, &bvh, r, distance, &a);
        }
    }
    printf("  %d of %d shadow rays blocked\n", blocked, a.rays);
    check_agreement("shadow rays", &a, 0.05);
    reference_free(&ref);
    bvh_free(&bvh);
    scene_free(&s);
}

/* --- cost (T18) ----------------------------------------------------------- */

/* Mean box tests and primitive tests per ray for a 64 x 64 grid of camera
 * rays from (0, 0, 3) towards a unit sphere at the origin. */
static void
cost_per_ray(const struct scene *s, double *visits, double *tests, int *hits)
{
    struct world w = world_make(s);
    struct bvh bvh;
    struct diag err;
    CHECK(bvh_build(&bvh, &w, &err));
    struct stats st = {0};
    *hits = 0;
    for (int i = 0; i < 64 * 64; i++) {
        vec3 film = vec3_make(
            (i % 64 + (real)0.5) / 64 - (real)0.5,
            (i / 64 + (real)0.5) / 64 - (real)0.5,
            -1);
        ray r = {vec3_make(0, 0, 3), vec3_normalize(film)};
        struct hit h;
        *hits += tree_intersect(&bvh, &w, r, REAL_MAX, false, &h, &st);
    }
    *visits = (double)st.node_visits / (64 * 64);
    *tests = (double)st.prim_tests / (64 * 64);
    bvh_free(&bvh);
}

/* The same sphere tessellated into 1,000 and 100,000 triangles: 100 times
 * the triangles may cost no more than 3 times the work per ray (log2 grows
 * by 1.67x from 1k to 100k; brute force by 100x), and far less than brute
 * force. */
TEST(cost_grows_as_log_n)
{
    const double center[3] = {0, 0, 0};
    double visits[2];
    double tests[2];
    int hits[2];
    const int bands[2] = {20, 200}; /* 20 x 25 x 2 = 1,000; 200 x 250 x 2 = 100,000 */
    const int segments[2] = {25, 250};
    for (int k = 0; k < 2; k++) {
        struct scene s = {0};
        add_mesh_once(&s, meshgen_sphere(bands[k] + 1, segments[k], 1, center, 0, 1));
        cost_per_ray(&s, &visits[k], &tests[k], &hits[k]);
        printf(
            "  sphere of %d triangles: %.1f boxes and %.2f triangles tested per ray, %d hits\n",
            s.n_triangles,
            visits[k],
            tests[k],
            hits[k]);
        bool bounded = tests[k] < s.n_triangles / 20.0;
        CHECK_MSG(
            bounded,
            "%.1f triangles tested per ray, not under 1/20 of the %d",
            tests[k],
            s.n_triangles);
        scene_free(&s);
        if (!bounded) {
            /* Over the bound at 1k already (brute force, a handout's stub,
             * tests them all): at 100k the same traversal would test up to
             * 4096 x 1e5 triangles (many seconds) and fail the same bound. */
            printf("  the 100k sphere is not rendered: the 1k one already fails\n");
            return;
        }
    }
    printf("  ratio of boxes tested, 100k / 1k triangles: %.2f\n", visits[1] / visits[0]);
    CHECK(hits[0] > 1000 && hits[1] > 1000);
    CHECK(visits[1] / visits[0] < 3);
}

/* --- primitives set aside ------------------------------------------------ */

/* A floor quad 100 x 100 one unit under the unit sphere of cost_per_ray,
 * and a small light two units above it: what a median split alone would
 * put in leaves beside the sphere's triangles. */
static void
add_floor_and_light(struct scene *s)
{
    add_quad(s, vec3_make(-50, -1, -50), vec3_make(0, 0, 100), vec3_make(100, 0, 0));
    add_area_light(s, vec3_make(-0.25, 3, -0.25), vec3_make(0.5, 0, 0), vec3_make(0, 0, 0.5));
}

/* The sphere of 20,000 triangles costs a ray about as many box tests on
 * the floor, under the light, as alone: the two are set aside, and each
 * costs every ray one primitive test.  (Left in the tree, they make every
 * ray descend their leaves' chains of scene-sized boxes.) */
TEST(large_primitives_add_no_box_tests)
{
    const double center[3] = {0, 0, 0};
    struct scene s = {0};
    add_mesh_once(&s, meshgen_sphere(101, 100, 1, center, 0, 1));
    double visits[2];
    double tests[2];
    int hits[2];
    cost_per_ray(&s, &visits[0], &tests[0], &hits[0]);
    if (!(tests[0] < s.n_triangles / 20.0)) {
        CHECK_MSG(false, "%.1f triangles tested per ray: no tree", tests[0]);
        scene_free(&s);
        return;
    }
    add_floor_and_light(&s);
    cost_per_ray(&s, &visits[1], &tests[1], &hits[1]);
    printf(
        "  per ray, sphere alone: %.2f boxes, %.2f primitives; on the floor under the light: "
        "%.2f boxes, %.2f primitives\n",
        visits[0],
        tests[0],
        visits[1],
        tests[1]);
    CHECK(hits[1] > hits[0] && hits[0] > 1000);
    CHECK_MSG(
        tests[1] <= tests[0] + 2.5,
        "%.2f primitives tested per ray, %.2f without the floor and light",
        tests[1],
        tests[0]);
    CHECK_MSG(
        visits[1] <= 1.1 * visits[0],
        "%.2f boxes tested per ray, %.2f without the floor and light",
        visits[1],
        visits[0]);
    check_scene_rays(&s, 2500, 92, "sphere on a floor under a light", 0.5);
    scene_free(&s);
}

/* A Cornell box in memory: five walls 2 x 2, two spheres and a light, all
 * large against the box: every one set aside, no tree. */
TEST(every_primitive_large)
{
    struct scene s = {0};
    vec3 o = vec3_make(-1, 0, -1);
    add_quad(&s, o, vec3_make(0, 0, 2), vec3_make(2, 0, 0));
    add_quad(&s, vec3_make(-1, 2, -1), vec3_make(2, 0, 0), vec3_make(0, 0, 2));
    add_quad(&s, o, vec3_make(2, 0, 0), vec3_make(0, 2, 0));
    add_quad(&s, o, vec3_make(0, 2, 0), vec3_make(0, 0, 2));
    add_quad(&s, vec3_make(1, 0, -1), vec3_make(0, 0, 2), vec3_make(0, 2, 0));
    add_sphere(&s, vec3_make(-0.45, 0.4, -0.3), 0.4);
    add_sphere(&s, vec3_make(0.45, 0.3, 0.3), 0.3);
    add_area_light(&s, vec3_make(-0.25, 1.98, -0.25), vec3_make(0.5, 0, 0), vec3_make(0, 0, 0.5));
    struct world w = world_make(&s);
    struct bvh bvh;
    build_checked(&w, &bvh);
    int expect = w.n_prims < BVH_MAX_ASIDE ? w.n_prims : BVH_MAX_ASIDE;
    CHECK_MSG(bvh.n_aside == expect, "%d of %d set aside", bvh.n_aside, w.n_prims);
    CHECK(w.n_prims > BVH_MAX_ASIDE || bvh.n_nodes == 0);
    bvh_free(&bvh);
    check_scene_rays(&s, 10000, 93, "Cornell box", 0.5);
    scene_free(&s);
}

/* 30 quads through the origin, growing in size, every one large: only the
 * BVH_MAX_ASIDE largest are set aside, largest first, the others go into
 * the tree. */
TEST(at_most_the_cap_set_aside)
{
    struct scene s = {0};
    const int n = 30;
    for (int i = 0; i < n; i++) {
        real size = 1 + (real)i / 10;
        vec3 e1 = vec3_make(size, 0, 0);
        vec3 e2 = vec3_make(0, size, size / 2);
        add_quad(&s, vec3_scale(vec3_add(e1, e2), -0.5), e1, e2);
    }
    struct world w = world_make(&s);
    struct bvh bvh;
    build_checked(&w, &bvh);
    CHECK_MSG(bvh.n_aside == BVH_MAX_ASIDE, "%d set aside", bvh.n_aside);
    int not_largest = 0;
    for (int k = 0; k < bvh.n_aside; k++) {
        not_largest += bvh.prims[k] != n - 1 - k;
    }
    CHECK_MSG(not_largest == 0, "%d set aside are not the largest", not_largest);
    bvh_free(&bvh);
    check_scene_rays(&s, 10000, 94, "large quads", 0.5);
    scene_free(&s);
}

/* Primitives of similar sizes (a closed sphere, a terrain, a soup): nothing
 * is set aside. */
TEST(similar_sizes_set_nothing_aside)
{
    const double center[3] = {0.25, -0.5, 1};
    for (int i = 0; i < 3; i++) {
        struct scene s = {0};
        if (i == 0) {
            add_mesh_once(&s, meshgen_sphere(40, 60, 2, center, 0.05, 9));
        } else if (i == 1) {
            add_mesh_once(&s, meshgen_terrain(60, 60, 4, 0.8, 81));
        } else {
            add_soup(&s, 2000, 95, 10, 1, 0.1);
        }
        struct world w = world_make(&s);
        struct bvh bvh;
        build_checked(&w, &bvh);
        CHECK_MSG(bvh.n_aside == 0, "scene %d: %d set aside", i, bvh.n_aside);
        bvh_free(&bvh);
        scene_free(&s);
    }
}

TEST_MAIN(
    TEST_ENTRY(structure_of_random_soups),
    TEST_ENTRY(single_primitive_is_set_aside),
    TEST_ENTRY(empty_world),
    TEST_ENTRY(coincident_centroids_terminate),
    TEST_ENTRY(flat_scene),
    TEST_ENTRY(agrees_on_random_soups),
    TEST_ENTRY(agrees_on_degenerate_meshes),
    TEST_ENTRY(agrees_on_closed_sphere),
    TEST_ENTRY(agrees_on_mixed_scene),
    TEST_ENTRY(ties_go_to_the_lowest_number),
    TEST_ENTRY(agrees_on_rays_in_faces_and_edges),
    TEST_ENTRY(traversal_raises_no_invalid_operation),
    TEST_ENTRY(agrees_at_t_max_limits),
    TEST_ENTRY(any_hit_agrees_with_closest_hit),
    TEST_ENTRY(cost_grows_as_log_n),
    TEST_ENTRY(large_primitives_add_no_box_tests),
    TEST_ENTRY(every_primitive_large),
    TEST_ENTRY(at_most_the_cap_set_aside),
    TEST_ENTRY(similar_sizes_set_nothing_aside))
