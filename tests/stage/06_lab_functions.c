/*
 * 06_lab_functions.c - lab 06's functions, each on its own (tests/lab/
 * README.md, "Function tests").
 *
 *  - sample_position, grid: sample i of n lies at the centre of a cell of a
 *    k x m grid over the pixel (k = strata_columns(n), either way round),
 *    one sample per cell, for n = 1 to 16.
 *  - sample_position, jitter: one sample per cell, every one in [0,1)^2,
 *    and within its cell a uniform point: a chi-square test of the
 *    offsets in their cells (16 x 16 bins, 102,400 samples of n = 1, 4, 8,
 *    9, 12) and of the positions over the whole pixel.
 *  - adaptive_pixel: on a pixel the light covers whole, its AA_PROBES
 *    probes agree: it traces just those and returns the light's radiance
 *    exactly; on a pixel an edge of the light crosses, it traces all spp
 *    samples, counts the pixel as refined, and its mean over 64 seeds is
 *    the covered fraction (from a 64 x 64 grid of the same pixel) within
 *    5 standard errors; with spp below AA_PROBES, spp samples.
 *
 * The two chi-square tests and the mean of the edge pixel share alpha 0.01
 * (Sidak); seeds from pathcheck_seed().  White-box: includes the stage's
 * render.c for its static sample_position() and adaptive_pixel().
 */
#include "render.c"

#include <stdio.h>
#include <string.h>

#include "check.h"
#include "pathcheck.h"
#include "stagecheck.h"
#include "stattest.h"
#include "warptest.h"

#define N_STAT_TESTS 3

static double
level(void)
{
    return stattest_sidak(PATHCHECK_ALPHA, N_STAT_TESTS);
}

/* Cell of (dx, dy) in a cols x rows grid, or -1 outside [0,1)^2. */
static int
cell_in(real dx, real dy, int cols, int rows)
{
    if (!(dx >= 0 && dx < 1 && dy >= 0 && dy < 1)) {
        return -1;
    }
    return (int)(dy * (real)rows) * cols + (int)(dx * (real)cols);
}

/* Whether the n positions put one sample in each cell of a cols x rows
 * grid (and, for the grid pattern, each at its cell's centre). */
static bool
one_per_cell(const real *dx, const real *dy, int n, int cols, int rows, bool centres)
{
    bool seen[64] = {false};
    for (int i = 0; i < n; i++) {
        int c = cell_in(dx[i], dy[i], cols, rows);
        if (c < 0 || seen[c]) {
            return false;
        }
        seen[c] = true;
        if (centres) {
            double cx = (c % cols + 0.5) / cols;
            double cy = (c / cols + 0.5) / rows;
            if (fabs((double)dx[i] - cx) > 1e-6 || fabs((double)dy[i] - cy) > 1e-6) {
                return false;
            }
        }
    }
    return true;
}

/* The positions of sample_position for i = 0 .. n-1. */
static void
positions(int pattern, int n, struct rng *rng, real *dx, real *dy)
{
    for (int i = 0; i < n; i++) {
        sample_position(pattern, i, n, rng, &dx[i], &dy[i]);
    }
}

static void
describe(int n, const real *dx, const real *dy, char *out, size_t cap)
{
    int len = snprintf(out, cap, "n = %d:", n);
    for (int i = 0; i < n && len > 0 && (size_t)len < cap; i++) {
        len +=
            snprintf(out + len, cap - (size_t)len, " (%.3f, %.3f)", (double)dx[i], (double)dy[i]);
    }
}

TEST(sample_position_grid_puts_one_sample_at_each_cell_centre)
{
    struct rng rng = rng_make(6001, 1);
    for (int n = 1; n <= 16; n++) {
        real dx[16];
        real dy[16];
        positions(AA_GRID, n, &rng, dx, dy);
        int k = strata_columns(n);
        if (!one_per_cell(dx, dy, n, k, n / k, true) && !one_per_cell(dx, dy, n, n / k, k, true)) {
            char where[700];
            describe(n, dx, dy, where, sizeof where);
            CHECK_FAIL(
                "sample_position (grid): the %d samples are not the centres of the cells of a %d x %d "
                "grid over the pixel, one each: %s",
                n,
                k,
                n / k,
                where);
            return;
        }
    }
}

TEST(sample_position_jitter_puts_one_uniform_point_in_each_cell)
{
    static const int ns[] = {1, 4, 8, 9, 12};
    struct warptest in_cell;
    struct warptest whole;
    CHECK(warptest_square(&in_cell, 16, 16) && warptest_square(&whole, 16, 16));
    struct rng rng = rng_make(pathcheck_seed(6002), 2);
    int reported = 0;
    for (int rep = 0; rep < 2560; rep++) {
        for (int j = 0; j < 5; j++) {
            int n = ns[j];
            int k = strata_columns(n);
            int m = n / k;
            real dx[16];
            real dy[16];
            positions(AA_JITTER, n, &rng, dx, dy);
            bool k_by_m = one_per_cell(dx, dy, n, k, m, false);
            if (!k_by_m && !one_per_cell(dx, dy, n, m, k, false) && reported++ == 0) {
                char where[700];
                describe(n, dx, dy, where, sizeof where);
                CHECK_FAIL(
                    "sample_position (jitter): the %d samples are not one in each cell of a %d x %d grid "
                    "over the pixel (stratified): %s",
                    n,
                    k,
                    m,
                    where);
            }
            int cols = k_by_m ? k : m;
            int rows = n / cols;
            for (int i = 0; i < n; i++) {
                double fx = (double)dx[i] * cols;
                double fy = (double)dy[i] * rows;
                warptest_add(&in_cell, fx - floor(fx), fy - floor(fy), 0);
                warptest_add(&whole, (double)dx[i], (double)dy[i], 0);
            }
        }
    }
    const struct warptest *tests[] = {&in_cell, &whole};
    const char *what[] = {"within its cell", "over the pixel"};
    for (int t = 0; t < 2; t++) {
        struct warptest_result fit = warptest_fit(tests[t], NULL, NULL);
        char why[300];
        warptest_describe(tests[t], &fit, why, sizeof why);
        printf("sample_position (jitter) %s: %s\n", what[t], why);
        if (fit.p < level()) {
            CHECK_FAIL(
                "sample_position (jitter): a sample is not uniform %s (p %.2g < %.3g): %s; use two "
                "independent uniform numbers, one for x and one for y",
                what[t],
                fit.p,
                level(),
                why);
        }
        warptest_free((struct warptest *)tests[t]);
    }
}

/* A camera looking at an area light of radiance 1 that covers the image
 * left of x = edge_x (world units at the light's plane z = 0); the
 * background is black.  8 x 8 pixels. */
struct edge_scene {
    struct scene scene;
    struct renderer renderer;
};

static bool
edge_scene_make(struct edge_scene *e, double edge_x, int spp)
{
    char text[512];
    snprintf(
        text,
        sizeof text,
        "camera origin 0 0 5 target 0 0 0 up 0 1 0 fov 20\n"
        "image width 8 height 8\n"
        "area_light corner -10 -10 0 edge1 %.17g 0 0 edge2 0 20 0 radiance 1 1 1\n",
        edge_x + 10);
    memset(e, 0, sizeof *e);
    if (!stagecheck_load_text(text, &e->scene)) {
        return false;
    }
    e->renderer.scene = &e->scene;
    e->renderer.world = world_make(&e->scene);
    e->renderer.camera = camera_make(&e->scene.camera, 8, 8);
    e->renderer.max_depth = 1;
    e->renderer.spp = spp;
    e->renderer.aa = AA_ADAPTIVE;
    e->renderer.aa_threshold = (real)0.05;
    return true;
}

/* The scene whose light's edge runs down the middle of pixel column 4
 * (film x = 4.5, found with the stage's camera): the left cells of those
 * pixels are lit, the right ones dark, so any probes disagree. */
static bool
edge_scene_halving_column_4(struct edge_scene *e, int spp)
{
    if (!edge_scene_make(e, 0, spp)) {
        return false;
    }
    ray r = camera_ray(&e->renderer.camera, (real)4.5, 4);
    double x = (double)r.o.x - (double)r.o.z / (double)r.d.z * (double)r.d.x;
    scene_free(&e->scene);
    return edge_scene_make(e, x, spp);
}

/* The radiance along a camera ray r, by the stage's trace (08 adds its
 * sampler's sample number). */
static vec3
trace_sample(const struct renderer *renderer, ray r, struct rng *rng, struct stats *st)
{
#ifdef SAMPLER_H
    struct sample_id id = {renderer->sampler, 0, 0};
    return trace(renderer, r, 1, id, rng, st);
#else
    return trace(renderer, r, 1, rng, st);
#endif
}

/* The fraction of pixel (px, py) the light covers: a 64 x 64 grid of its
 * points, through the stage's own camera and trace. */
static double
coverage(const struct renderer *renderer, int px, int py)
{
    struct rng rng = rng_make(1, 1);
    struct stats st = {0};
    double sum = 0;
    for (int j = 0; j < 64; j++) {
        for (int i = 0; i < 64; i++) {
            ray r = camera_ray(
                &renderer->camera,
                (real)px + (real)((i + 0.5) / 64),
                (real)py + (real)((j + 0.5) / 64));
            sum += (double)luminance(trace_sample(renderer, r, &rng, &st));
        }
    }
    return sum / 4096;
}

TEST(adaptive_pixel_refines_only_where_the_probes_disagree)
{
    struct edge_scene e;
    CHECK(edge_scene_halving_column_4(&e, 64));
    if (check_current.failed_checks) {
        return;
    }
    /* Pixel 1 is wholly lit; the edge halves pixel 4. */
    int lit = 1;
    int edge = 4;
    double edge_cover = coverage(&e.renderer, edge, 4);
    CHECK_MSG(
        coverage(&e.renderer, lit, 4) == 1 && fabs(edge_cover - 0.5) < 0.02,
        "the test's scene: pixel 1 is not lit whole, or pixel 4 not half (%.4f)",
        edge_cover);
    if (check_current.failed_checks) {
        return;
    }
    struct rng rng = rng_make(6003, 3);
    struct stats st = {0};
    vec3 l = adaptive_pixel(&e.renderer, lit, 4, &rng, &st);
    if (!(st.rays_camera == AA_PROBES && l.x == 1 && l.y == 1 && l.z == 1
          && st.extra[STAT_AA_REFINED] == 0)) {
        CHECK_FAIL(
            "adaptive_pixel (spp 64, a pixel the light covers whole): traced %ld camera rays and "
            "returned (%g %g %g), refined %ld: where the %d probes agree, trace only them and return "
            "their mean (1 1 1)",
            (long)st.rays_camera,
            (double)l.x,
            (double)l.y,
            (double)l.z,
            (long)st.extra[STAT_AA_REFINED],
            AA_PROBES);
    }
    struct stattest_welford w = {0};
    uint64_t seed = pathcheck_seed(6004);
    bool refined_all = true;
    long rays = 0;
    for (int s = 0; s < 64; s++) {
        struct rng r = rng_make(seed + (uint64_t)s, 4);
        struct stats es = {0};
        vec3 v = adaptive_pixel(&e.renderer, edge, 4, &r, &es);
        refined_all &= es.rays_camera == 64 && es.extra[STAT_AA_REFINED] == 1;
        rays = (long)es.rays_camera;
        stattest_welford_add(&w, (double)luminance(v));
    }
    if (!refined_all) {
        CHECK_FAIL(
            "adaptive_pixel (spp 64, a pixel the light's edge crosses, %.0f%% covered): traced %ld camera "
            "rays (or did not count the pixel as refined): where the probes disagree, trace all spp "
            "samples",
            100 * edge_cover,
            rays);
    }
    /* The halved pixel's stratified samples may all agree with the edge
     * (no variance): then the mean must be the coverage itself. */
    struct stattest_result t = stattest_t_test_welford_one_sample(&w, edge_cover);
    bool biased = w.m2 > 0 ? t.p < level() : fabs(w.mean - edge_cover) > 1e-6;
    if (biased) {
        CHECK_FAIL(
            "adaptive_pixel (spp 64, an edge pixel %.4f covered): its mean over 64 seeds is %.4f (p %.2g): "
            "a refined pixel is the mean of all its samples, the probes included",
            edge_cover,
            w.mean,
            t.p);
    }
    /* Fewer samples than probes: spp of them. */
    e.renderer.spp = 2;
    struct stats few = {0};
    (void)adaptive_pixel(&e.renderer, edge, 4, &rng, &few);
    if (few.rays_camera != 2) {
        CHECK_FAIL("adaptive_pixel (spp 2): traced %ld camera rays, not 2", (long)few.rays_camera);
    }
    scene_free(&e.scene);
}

TEST_MAIN(
    TEST_ENTRY(sample_position_grid_puts_one_sample_at_each_cell_centre),
    TEST_ENTRY(sample_position_jitter_puts_one_uniform_point_in_each_cell),
    TEST_ENTRY(adaptive_pixel_refines_only_where_the_probes_disagree))
