/*
 * embree_bench.c - the same rays through Intel Embree 3, for scale.
 *
 *     embree_bench [BIG.glb [SMALL.glb]]   (from the project root)
 *
 * Loads the models as bvh_bench does (same loader, framing, camera rays and
 * shadow rays, the shadow rays starting from our hits), gives Embree the
 * same triangles (as float, the only precision it takes), and traces the
 * rays with its single-ray API, rtcIntersect1 and rtcOccluded1, on 1 and 2
 * threads, in ROUNDS interleaved rounds.  Prints both builds' times, both
 * throughputs, and ours as a fraction of Embree's: the median of the rounds
 * and its range.  Embree's BVH is a SAH-built 4- or 8-wide tree traversed
 * with SIMD, its triangles tested several at once in float: production's
 * speed, which stage 09 is measured against (stage 05, STAGE=05_bvh, shows
 * a median split's binary tree in double).  Built only where Debian's
 * libembree-dev is installed.
 */
#include <embree3/rtcore.h>
#include <float.h>
#include <stdio.h>

#include "benchlib.h"

#define SPHERE_BANDS 500
#define ROUNDS 3 /* interleaved rounds: odd, for a median */

struct embree {
    RTCDevice device;
    RTCScene scene;
    double seconds_build;
};

/* The model's triangles as one Embree triangle geometry. */
static bool
add_triangles(RTCDevice device, RTCScene scene, const struct scene *s)
{
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *v = rtcSetNewGeometryBuffer(
        geometry,
        RTC_BUFFER_TYPE_VERTEX,
        0,
        RTC_FORMAT_FLOAT3,
        3 * sizeof(float),
        (size_t)s->n_vertices);
    unsigned *index = rtcSetNewGeometryBuffer(
        geometry,
        RTC_BUFFER_TYPE_INDEX,
        0,
        RTC_FORMAT_UINT3,
        3 * sizeof(unsigned),
        (size_t)s->n_triangles);
    if (!v || !index) {
        rtcReleaseGeometry(geometry);
        return false;
    }
    for (int i = 0; i < s->n_vertices; i++) {
        v[3 * i] = (float)s->positions[i].x;
        v[3 * i + 1] = (float)s->positions[i].y;
        v[3 * i + 2] = (float)s->positions[i].z;
    }
    for (int i = 0; i < s->n_triangles; i++) {
        for (int k = 0; k < 3; k++) {
            index[3 * i + k] = (unsigned)s->triangles[i].v[k];
        }
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);
    return true;
}

/* Embree's BVH over the model, on a device limited to `threads` build
 * threads; the build (rtcCommitScene) is timed. */
static bool
embree_build(struct embree *e, const struct scene *s, int threads)
{
    char config[32];
    snprintf(config, sizeof config, "threads=%d", threads);
    e->device = rtcNewDevice(config);
    e->scene = e->device ? rtcNewScene(e->device) : NULL;
    if (!e->scene || !add_triangles(e->device, e->scene, s)) {
        return false;
    }
    double start = stats_clock_seconds();
    rtcCommitScene(e->scene);
    e->seconds_build = stats_clock_seconds() - start;
    return rtcGetDeviceError(e->device) == RTC_ERROR_NONE;
}

static void
embree_free(struct embree *e)
{
    if (e->scene) {
        rtcReleaseScene(e->scene);
    }
    if (e->device) {
        rtcReleaseDevice(e->device);
    }
}

static struct RTCRay
embree_ray(ray r, real t_max)
{
    struct RTCRay er = {
        .org_x = (float)r.o.x,
        .org_y = (float)r.o.y,
        .org_z = (float)r.o.z,
        .tnear = 0,
        .dir_x = (float)r.d.x,
        .dir_y = (float)r.d.y,
        .dir_z = (float)r.d.z,
        .tfar = t_max < FLT_MAX ? (float)t_max : INFINITY,
        .mask = ~0u,
    };
    return er;
}

static bool
embree_closest(const void *ctx, ray r, real t_max, struct stats *st)
{
    const struct embree *e = ctx;
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    struct RTCRayHit rh = {.ray = embree_ray(r, t_max)};
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(e->scene, &context, &rh);
    (void)st;
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

static bool
embree_any(const void *ctx, ray r, real t_max, struct stats *st)
{
    const struct embree *e = ctx;
    struct RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    struct RTCRay er = embree_ray(r, t_max);
    rtcOccluded1(e->scene, &context, &er);
    (void)st;
    return er.tfar < 0; /* Embree marks an occluded ray with tfar = -inf */
}

/* The median of v[0, n) (n odd), and its least and greatest. */
static void
median_range(const double *v, int n, double *median, double *least, double *most)
{
    double sorted[ROUNDS];
    for (int i = 0; i < n; i++) { /* insertion sort: n is ROUNDS */
        int j = i;
        for (; j > 0 && sorted[j - 1] > v[i]; j--) {
            sorted[j] = sorted[j - 1];
        }
        sorted[j] = v[i];
    }
    *median = sorted[n / 2];
    *least = sorted[0];
    *most = sorted[n - 1];
}

/* ROUNDS rounds, each timing ours then Embree on 1 and on 2 threads; a row: the medians of the
 * Mrays/s, and the median of the rounds' ratios with their range (a ratio is taken within one
 * round: the machine's load drifts between rounds more than within one). */
static bool
compare(
    const char *what,
    const struct ray_batch *b,
    bench_trace_fn ours,
    const void *model,
    bench_trace_fn theirs,
    const struct embree *e)
{
    double mrays[2][2][ROUNDS]; /* [threads - 1][0 ours, 1 Embree][round] */
    double ratio[2][ROUNDS];
    uint64_t hits[2] = {0, 0};
    for (int round = 0; round < ROUNDS; round++) {
        for (int t = 0; t < 2; t++) {
            struct bench_result r[2];
            if (!bench_time(b, 1, t + 1, BENCH_RUNS, ours, model, &r[0])
                || !bench_time(b, 1, t + 1, BENCH_RUNS, theirs, e, &r[1])) {
                return false;
            }
            for (int k = 0; k < 2; k++) {
                mrays[t][k][round] = bench_mrays(&r[k]);
                hits[k] = r[k].hits;
            }
            ratio[t][round] = mrays[t][0][round] / mrays[t][1][round];
        }
    }
    printf(
        "  %-7s %7zu %8llu %8llu",
        what,
        b->n,
        (unsigned long long)hits[0],
        (unsigned long long)hits[1]);
    for (int t = 0; t < 2; t++) {
        double m[3];
        double lo;
        double hi;
        median_range(mrays[t][0], ROUNDS, &m[0], &lo, &hi);
        median_range(mrays[t][1], ROUNDS, &m[1], &lo, &hi);
        median_range(ratio[t], ROUNDS, &m[2], &lo, &hi);
        printf(" %9.2f %9.2f %6.0f%% (%2.0f-%2.0f%%)", m[0], m[1], 100 * m[2], 100 * lo, 100 * hi);
    }
    printf("\n");
    return true;
}

static bool
bench_against_embree(struct bench_model *m)
{
    struct diag err;
    struct embree one = {0};
    struct embree two = {0};
    struct ray_batch camera = {.n = 0};
    struct ray_batch shadow = {.n = 0};
    bool ok = bench_build(m, &err) && embree_build(&one, &m->scene, 1)
              && embree_build(&two, &m->scene, 2) && bench_camera_rays(m, &camera)
              && bench_shadow_rays(m, &camera, &shadow);
    if (ok) {
        printf(
            "\n%s: %d triangles; build: ours %.3f s (1 thread), Embree %.3f s (1 thread), "
            "%.3f s (2 threads)\n",
            m->name,
            m->scene.n_triangles,
            m->seconds_build,
            one.seconds_build,
            two.seconds_build);
        printf(
            "  %-7s %7s %8s %8s %9s %9s %17s %9s %9s %17s\n",
            "rays",
            "count",
            "hits",
            "Embree",
            "ours 1t",
            "Embree",
            "ours/E 1t",
            "ours 2t",
            "Embree",
            "ours/E 2t");
        ok = compare("camera", &camera, bench_bvh_closest, m, embree_closest, &one)
             && compare("shadow", &shadow, bench_bvh_any, m, embree_any, &one);
    } else {
        printf("%s: could not build (%s)\n", m->name, err.msg);
    }
    ray_batch_free(&camera);
    ray_batch_free(&shadow);
    embree_free(&one);
    embree_free(&two);
    return ok;
}

int
main(int argc, char **argv)
{
    const char *big = argc > 1 ? argv[1] : BENCH_BIG_MODEL;
    const char *small = argc > 2 ? argv[2] : BENCH_SMALL_MODEL;
    printf(
        "Embree 3 against %s's BVH: same models and rays, %s precision for ours (built for %s), "
        "float for Embree.\nMrays/s: the median of %d interleaved rounds, each the best of %d "
        "runs; ours/E: the median of the rounds' ratios (their range)\n",
        STAGE_NAME,
        REAL_NAME,
        BENCH_ISA,
        ROUNDS,
        BENCH_RUNS);
    struct diag err;
    struct bench_model m;
    bool ok = true;
    if (bench_load(&m, big, &err)) {
        ok = bench_against_embree(&m);
    } else {
        printf("skipping %s: %s\n", big, err.msg);
        bench_model_free(&m);
        ok = bench_generate_sphere(&m, SPHERE_BANDS, &err) && bench_against_embree(&m);
    }
    bench_model_free(&m);
    if (bench_load(&m, small, &err)) {
        ok = bench_against_embree(&m) && ok;
    } else {
        printf("skipping %s: %s\n", small, err.msg);
    }
    bench_model_free(&m);
    return ok ? 0 : 1;
}
