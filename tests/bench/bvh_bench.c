/*
 * bvh_bench.c - how fast the stage's BVH builds and traces.
 *
 *     bvh_bench [BIG.glb [SMALL.glb]]      (from the project root)
 *
 * For the Happy Buddha subdivided to 1.08M triangles and for the Stanford
 * bunny (69k), loaded through the scene loader and framed in a 600x600
 * image: load and build time; camera rays (closest hit) and shadow rays to
 * one point light (any hit) per second on 1 and 2 threads; BVH nodes visited
 * and primitives tested per ray; and, on the bunny, the speed-up over
 * testing every triangle (brute force timed on every BRUTE_STRIDE-th camera
 * ray only, and said so).  A missing model is skipped with a message; the
 * large one is then replaced by a generated sphere of 1M triangles.
 * Exit status 0, 1 when something could not be built.
 */
#include <stdio.h>
#include <string.h>

#include "benchlib.h"

#define SPHERE_BANDS 500 /* the stand-in: 4 * 500^2 = 1M triangles */
#define BRUTE_STRIDE 1024 /* brute force traces every 1024th camera ray */

#ifndef BVH_WIDTH
/* Levels of the subtree at node id (nodes in depth-first order, bvh.h). */
static int
tree_depth(const struct bvh *bvh, uint32_t id)
{
    const struct bvh_node *node = &bvh->nodes[id];
    if (node->count > 0) {
        return 1;
    }
    int first = tree_depth(bvh, id + 1);
    int second = tree_depth(bvh, node->index);
    return 1 + (first > second ? first : second);
}
#endif

static void
print_model(const struct bench_model *m)
{
    const struct bvh *b = &m->world.bvh;
#ifdef BVH_WIDTH /* stage 09 on: the binary tree is widened, its nodes freed */
    printf(
        "\n%s: %d triangles, load %.3f s, build %.3f s (1 thread), %d nodes of %d children "
        "(from %d binary), %.1f MiB\n",
        m->name,
        m->scene.n_triangles,
        m->seconds_load,
        m->seconds_build,
        b->n_wide,
        BVH_WIDTH,
        b->n_nodes,
        (double)((size_t)b->n_wide * sizeof *b->wide + (size_t)b->n_prims * sizeof *b->prims)
            / (1 << 20));
#else
    printf(
        "\n%s: %d triangles, load %.3f s, build %.3f s (1 thread), %d nodes, depth %d, "
        "%.1f MiB\n",
        m->name,
        m->scene.n_triangles,
        m->seconds_load,
        m->seconds_build,
        b->n_nodes,
        b->n_nodes > 0 ? tree_depth(b, 0) : 0,
        (double)((size_t)b->n_nodes * sizeof *b->nodes + (size_t)b->n_prims * sizeof *b->prims)
            / (1 << 20));
#endif
    printf(
        "  %-8s %8s %8s %12s %12s %10s %10s\n",
        "rays",
        "count",
        "hits",
        "Mrays/s 1t",
        "Mrays/s 2t",
        "nodes/ray",
        "prims/ray");
}

static void
print_row(const char *what, const struct bench_result *one, const struct bench_result *two)
{
    double n = one->rays ? (double)one->rays : 1;
    printf(
        "  %-8s %8zu %8llu %12.2f %12.2f %10.1f %10.1f\n",
        what,
        one->rays,
        (unsigned long long)one->hits,
        bench_mrays(one),
        bench_mrays(two),
        (double)one->counts.node_visits / n,
        (double)one->counts.prim_tests / n);
}

/* Camera and shadow rays through the BVH on 1 and 2 threads; fills
 * camera_1t (the brute-force comparison needs it). */
static bool
trace_model(
    struct bench_model *m,
    const struct ray_batch *camera,
    const struct ray_batch *shadow,
    struct bench_result *camera_1t)
{
    struct bench_result r2;
    struct bench_result s1;
    struct bench_result s2;
    bool ok = bench_time(camera, 1, 1, BENCH_RUNS, bench_bvh_closest, m, camera_1t)
              && bench_time(camera, 1, 2, BENCH_RUNS, bench_bvh_closest, m, &r2)
              && bench_time(shadow, 1, 1, BENCH_RUNS, bench_bvh_any, m, &s1)
              && bench_time(shadow, 1, 2, BENCH_RUNS, bench_bvh_any, m, &s2);
    if (ok) {
        print_row("camera", camera_1t, &r2);
        print_row("shadow", &s1, &s2);
    }
    return ok;
}

/* Brute force on a subset of the camera rays, extrapolated to rays/s. */
static bool
compare_brute(struct bench_model *m, const struct ray_batch *camera, const struct bench_result *bvh)
{
    struct bench_result brute;
    if (!bench_time(camera, BRUTE_STRIDE, 1, 1, bench_brute_closest, m, &brute)) {
        return false;
    }
    double rays_per_s = (double)brute.rays / brute.seconds;
    printf(
        "  brute force, 1 thread, on every %dth camera ray only (%zu rays, %.2f s): "
        "%.0f rays/s,\n  extrapolated to all camera rays: the BVH is %.0fx faster\n",
        BRUTE_STRIDE,
        brute.rays,
        brute.seconds,
        rays_per_s,
        bench_mrays(bvh) * 1e6 / rays_per_s);
    return true;
}

/* Build, make the rays, trace; brute force too when asked. */
static bool
bench_model(struct bench_model *m, bool with_brute)
{
    struct diag err;
    struct ray_batch camera = {.n = 0};
    struct ray_batch shadow = {.n = 0};
    struct bench_result camera_1t;
    bool ok = bench_build(m, &err);
    if (!ok) {
        diag_print(stderr, &err, "error");
    }
    ok = ok && bench_camera_rays(m, &camera) && bench_shadow_rays(m, &camera, &shadow);
    if (ok) {
        print_model(m);
        ok = trace_model(m, &camera, &shadow, &camera_1t);
    }
    ok = ok && (!with_brute || compare_brute(m, &camera, &camera_1t));
    ray_batch_free(&camera);
    ray_batch_free(&shadow);
    return ok;
}

int
main(int argc, char **argv)
{
    const char *big = argc > 1 ? argv[1] : BENCH_BIG_MODEL;
    const char *small = argc > 2 ? argv[2] : BENCH_SMALL_MODEL;
    printf(
        "BVH benchmark of %s: %s precision, built for %s, BVH_MAX_LEAF %d, %dx%d camera rays, "
        "1 point light, best of %d runs\n",
        STAGE_NAME,
        REAL_NAME,
        BENCH_ISA,
        BVH_MAX_LEAF,
        BENCH_WIDTH,
        BENCH_HEIGHT,
        BENCH_RUNS);
    struct diag err;
    struct bench_model m;
    bool ok = true;
    if (bench_load(&m, big, &err)) {
        ok = bench_model(&m, false);
    } else {
        printf("skipping %s: %s\n", big, err.msg);
        bench_model_free(&m);
        ok = bench_generate_sphere(&m, SPHERE_BANDS, &err) && bench_model(&m, false);
    }
    bench_model_free(&m);
    if (bench_load(&m, small, &err)) {
        ok = bench_model(&m, true) && ok;
    } else {
        printf("skipping %s: %s\n", small, err.msg);
    }
    bench_model_free(&m);
    return ok ? 0 : 1;
}
