/* benchlib.c - see benchlib.h. */
#include "benchlib.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "meshgen.h"

#define CHUNK 1024 /* rays a thread takes at a time */
#define FOV_DEG 30 /* the framing camera's vertical field of view */
#define OFFSET_FRACTION 1e-6 /* shadow-ray offset, as a fraction of the model's size */

/* --- models ------------------------------------------------------------- */

/* Look at the model from +z, a little above, from the distance at which
 * the larger of its width and height fills the image; put the light up,
 * right and in front. */
static void
frame(struct bench_model *m)
{
    const struct scene *s = &m->scene;
    vec3 lo = vec3_splat(REAL_MAX);
    vec3 hi = vec3_splat(-REAL_MAX);
    for (int i = 0; i < s->n_vertices; i++) {
        lo = vec3_min(lo, s->positions[i]);
        hi = vec3_max(hi, s->positions[i]);
    }
    vec3 center = vec3_scale(vec3_add(lo, hi), (real)0.5);
    vec3 extent = vec3_sub(hi, lo);
    real half = fmax(extent.x, extent.y) / 2 * (real)1.05;
    real distance = half / tan(FOV_DEG * PI / 360) + extent.z / 2;
    vec3 view = vec3_normalize(vec3_make(0, (real)0.2, 1));
    m->scene.camera = (struct camera_desc){
        .origin = vec3_madd(center, view, distance),
        .target = center,
        .up = vec3_make(0, 1, 0),
        .vfov_deg = FOV_DEG,
    };
    m->camera = camera_make(&m->scene.camera, BENCH_WIDTH, BENCH_HEIGHT);
    real radius = vec3_length(extent) / 2;
    m->light = vec3_add(center, vec3_scale(vec3_make(2, 3, 4), radius));
    m->offset = (real)OFFSET_FRACTION * radius;
    m->world = world_make(&m->scene);
}

bool
bench_load(struct bench_model *m, const char *path, struct diag *err)
{
    *m = (struct bench_model){.seconds_load = 0};
    const char *slash = strrchr(path, '/');
    snprintf(m->name, sizeof m->name, "%s", slash ? slash + 1 : path);
    char text[4608];
    /* A scene in the working directory: a relative path is taken from there,
     * as the command line gave it. */
    int len = snprintf(
        text,
        sizeof text,
        "camera origin 0 0 1 target 0 0 0 up 0 1 0 fov %d\n"
        "image width %d height %d\n"
        "material white diffuse albedo 0.8 0.8 0.8\n"
        "mesh file \"%s\" material white\n",
        FOV_DEG,
        BENCH_WIDTH,
        BENCH_HEIGHT,
        path);
    if (len < 0 || (size_t)len >= sizeof text) {
        diag_set(err, path, 0, 0, "path too long");
        return false;
    }
    double start = stats_clock_seconds();
    if (!scene_load_string(text, (size_t)len, "bench.scene", &m->scene, err)) {
        return false;
    }
    m->seconds_load = stats_clock_seconds() - start;
    frame(m);
    return true;
}

/* Copy a meshgen mesh into m's scene as triangles of material 0. */
static bool
scene_from_mesh(struct scene *s, const struct meshgen_mesh *mesh)
{
    static const struct material white = {
        .name = "white",
        .kind = MAT_DIFFUSE,
        .albedo = {0.8, 0.8, 0.8}};
    s->materials = malloc(sizeof *s->materials);
    s->positions = malloc(mesh->n_vertices * sizeof *s->positions);
    s->normals = calloc(mesh->n_vertices, sizeof *s->normals);
    s->triangles = malloc(mesh->n_triangles * sizeof *s->triangles);
    if (!s->materials || !s->positions || !s->normals || !s->triangles) {
        return false;
    }
    s->materials[0] = white;
    s->n_materials = 1;
    for (size_t i = 0; i < mesh->n_vertices; i++) {
        const double *p = &mesh->positions[3 * i];
        s->positions[i] = vec3_make((real)p[0], (real)p[1], (real)p[2]);
    }
    for (size_t i = 0; i < mesh->n_triangles; i++) {
        const unsigned *v = &mesh->indices[3 * i];
        s->triangles[i] = (struct triangle){.v = {(int)v[0], (int)v[1], (int)v[2]}};
    }
    s->n_vertices = (int)mesh->n_vertices;
    s->n_triangles = (int)mesh->n_triangles;
    s->width = BENCH_WIDTH;
    s->height = BENCH_HEIGHT;
    return true;
}

bool
bench_generate_sphere(struct bench_model *m, int n_bands, struct diag *err)
{
    *m = (struct bench_model){.seconds_load = 0};
    snprintf(m->name, sizeof m->name, "sphere (generated)");
    const double center[3] = {0, 0, 0};
    double start = stats_clock_seconds();
    struct meshgen_mesh mesh = meshgen_sphere(n_bands + 1, 2 * n_bands, 1, center, 0, 1);
    bool ok = mesh.n_triangles > 0 && scene_from_mesh(&m->scene, &mesh);
    meshgen_free(&mesh);
    if (!ok) {
        diag_set(err, NULL, 0, 0, "out of memory making a sphere of %d bands", n_bands);
        scene_free(&m->scene);
        return false;
    }
    m->seconds_load = stats_clock_seconds() - start;
    frame(m);
    return true;
}

bool
bench_build(struct bench_model *m, struct diag *err)
{
    m->seconds_build = 0;
    for (int run = 0; run < BENCH_RUNS; run++) {
        bvh_free(&m->world.bvh);
        double start = stats_clock_seconds();
        if (!bvh_build(&m->world.bvh, &m->world, err)) {
            return false;
        }
        double seconds = stats_clock_seconds() - start;
        if (run == 0 || seconds < m->seconds_build) {
            m->seconds_build = seconds;
        }
    }
    return true;
}

void
bench_model_free(struct bench_model *m)
{
    bvh_free(&m->world.bvh);
    scene_free(&m->scene);
}

/* --- rays --------------------------------------------------------------- */

static bool
batch_alloc(struct ray_batch *b, size_t n)
{
    b->rays = malloc((n ? n : 1) * sizeof *b->rays);
    b->t_max = malloc((n ? n : 1) * sizeof *b->t_max);
    b->n = 0;
    return b->rays && b->t_max;
}

void
ray_batch_free(struct ray_batch *b)
{
    free(b->rays);
    free(b->t_max);
    *b = (struct ray_batch){.n = 0};
}

bool
bench_camera_rays(const struct bench_model *m, struct ray_batch *out)
{
    if (!batch_alloc(out, (size_t)BENCH_WIDTH * BENCH_HEIGHT)) {
        ray_batch_free(out);
        return false;
    }
    for (int py = 0; py < BENCH_HEIGHT; py++) {
        for (int px = 0; px < BENCH_WIDTH; px++) {
            real x = (real)px + (real)0.5;
            real y = (real)py + (real)0.5;
            out->rays[out->n] = camera_ray(&m->camera, x, y);
            out->t_max[out->n++] = REAL_MAX;
        }
    }
    return true;
}

/* The shadow ray from the hit of camera ray r, if the light is on the side
 * the camera sees; false otherwise. */
static bool
shadow_ray(const struct bench_model *m, ray r, struct hit *h, ray *out, real *t_max)
{
    hit_finish(&m->scene, r, h);
    vec3 origin = vec3_madd(h->p, h->ng, m->offset);
    vec3 to_light = vec3_sub(m->light, origin);
    real distance = vec3_length(to_light);
    if (!(vec3_dot(to_light, h->ng) > 0 && distance > 0)) {
        return false;
    }
    *out = (ray){origin, vec3_scale(to_light, 1 / distance)};
    *t_max = distance;
    return true;
}

bool
bench_shadow_rays(
    const struct bench_model *m,
    const struct ray_batch *camera,
    struct ray_batch *out)
{
    if (!batch_alloc(out, camera->n)) {
        ray_batch_free(out);
        return false;
    }
    struct stats st = {0};
    for (size_t i = 0; i < camera->n; i++) {
        struct hit h;
        ray r = camera->rays[i];
        if (bvh_intersect(&m->world, r, camera->t_max[i], false, &h, &st)
            && shadow_ray(m, r, &h, &out->rays[out->n], &out->t_max[out->n])) {
            out->n++;
        }
    }
    return true;
}

/* --- timing ------------------------------------------------------------- */

struct timing {
    const struct ray_batch *batch;
    size_t stride, n; /* rays batch->rays[k * stride] for k < n */
    bench_trace_fn trace;
    const void *ctx;
    atomic_size_t next_chunk;
};

struct worker {
    struct timing *timing;
    uint64_t hits;
    struct stats counts;
    pthread_t thread;
};

static void *
work(void *arg)
{
    struct worker *w = arg;
    struct timing *t = w->timing;
    for (;;) {
        size_t begin = atomic_fetch_add(&t->next_chunk, 1) * CHUNK;
        if (begin >= t->n) {
            return NULL;
        }
        size_t end = begin + CHUNK < t->n ? begin + CHUNK : t->n;
        for (size_t k = begin; k < end; k++) {
            size_t i = k * t->stride;
            w->hits += t->trace(t->ctx, t->batch->rays[i], t->batch->t_max[i], &w->counts);
        }
    }
}

/* One run on `threads` threads (the calling one among them). */
static bool
run_once(struct timing *t, struct worker *workers, int threads, struct bench_result *out)
{
    atomic_store(&t->next_chunk, 0);
    int started = 1;
    double start = stats_clock_seconds();
    for (int i = 0; i < threads; i++) {
        workers[i] = (struct worker){.timing = t};
    }
    for (; started < threads; started++) {
        if (pthread_create(&workers[started].thread, NULL, work, &workers[started]) != 0) {
            break;
        }
    }
    work(&workers[0]);
    for (int i = 1; i < started; i++) {
        pthread_join(workers[i].thread, NULL);
    }
    *out = (struct bench_result){.seconds = stats_clock_seconds() - start, .rays = t->n};
    for (int i = 0; i < threads; i++) {
        out->hits += workers[i].hits;
        stats_add(&out->counts, &workers[i].counts);
    }
    return started == threads;
}

bool
bench_time(
    const struct ray_batch *b,
    size_t stride,
    int threads,
    int runs,
    bench_trace_fn trace,
    const void *ctx,
    struct bench_result *out)
{
    struct timing t = {.batch = b, .stride = stride, .trace = trace, .ctx = ctx};
    t.n = b->n ? (b->n - 1) / stride + 1 : 0;
    struct worker *workers = calloc((size_t)threads, sizeof *workers);
    bool ok = workers != NULL;
    for (int run = 0; ok && run < runs; run++) {
        struct bench_result r;
        ok = run_once(&t, workers, threads, &r);
        if (run == 0 || r.seconds < out->seconds) {
            *out = r;
        }
    }
    free(workers);
    return ok;
}

double
bench_mrays(const struct bench_result *r)
{
    return r->seconds > 0 ? (double)r->rays / r->seconds * 1e-6 : 0;
}

/* --- what is traced ----------------------------------------------------- */

bool
bench_bvh_closest(const void *ctx, ray r, real t_max, struct stats *st)
{
    const struct bench_model *m = ctx;
    struct hit h;
    return bvh_intersect(&m->world, r, t_max, false, &h, st);
}

bool
bench_bvh_any(const void *ctx, ray r, real t_max, struct stats *st)
{
    const struct bench_model *m = ctx;
    struct hit h;
    return bvh_intersect(&m->world, r, t_max, true, &h, st);
}

bool
bench_brute_closest(const void *ctx, ray r, real t_max, struct stats *st)
{
    const struct bench_model *m = ctx;
    struct hit h;
    bool found = false;
    for (int prim = 0; prim < m->world.n_prims; prim++) {
        if (intersect_prim(&m->scene, prim, r, t_max, &h)) {
            t_max = h.t;
            found = true;
        }
    }
    st->prim_tests += (uint64_t)m->world.n_prims;
    return found;
}
