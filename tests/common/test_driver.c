/*
 * test_driver.c - the tile renderer: every pixel computed once per pass,
 * images independent of the thread count, passes averaged, NaN pixels
 * counted and guarded, statistics summed over threads; shares of the
 * tiles (render_share, the browser build's workers) that add up to the
 * whole image bit for bit.  (How stage 07 splits spp into passes:
 * tests/stage/07_progressive.c.)
 */
#include <string.h>

#include "check.h"
#include "driver.h"
#include "testlib.h"

/* A pixel function whose value depends on the pixel and its random stream. */
static vec3
noisy_pixel(int px, int py, struct rng *rng, struct stats *st)
{
    st->rays_camera++;
    return (vec3){(real)px, (real)py, rng_uniform(rng)};
}

static vec3
nan_pixel(int px, int py, struct rng *rng, struct stats *st)
{
    (void)rng;
    (void)st;
    real zero = 0;
    return (px == 3 && py == 5) ? (vec3){zero / zero, 1, 1} : (vec3){1, 1, 1};
}

static const struct test_pixels noisy = {noisy_pixel};
static const struct test_pixels nan_at_3_5 = {nan_pixel};

static struct render_job
job_for(const struct test_pixels *pixels, int threads, int passes)
{
    return (struct render_job){
        .width = 37,
        .height = 21,
        .threads = threads,
        .passes = passes,
        .seed = 3,
        .tile = test_pixels_tile,
        .ctx = pixels,
    };
}

TEST(every_pixel_once_and_thread_independent)
{
    struct image one = {0};
    struct image four = {0};
    struct render_result r1;
    struct render_result r4;
    struct diag err;
    struct render_job j1 = job_for(&noisy, 1, 3);
    struct render_job j4 = job_for(&noisy, 4, 3);
    CHECK(driver_render_image(&j1, &one, &r1, &err));
    CHECK(driver_render_image(&j4, &four, &r4, &err));
    CHECK(memcmp(one.rgb, four.rgb, sizeof(float) * 3 * 37 * 21) == 0);
    CHECK(r1.passes_done == 3 && r4.passes_done == 3);
    CHECK(r1.counts.rays_camera == 3 * 37 * 21 && r4.counts.rays_camera == 3 * 37 * 21);
    /* the mean of three passes of (px, py, u) */
    CHECK(image_pixel(&one, 36, 20)[0] == 36 && image_pixel(&one, 36, 20)[1] == 20);
    float u = image_pixel(&one, 5, 5)[2];
    CHECK(u > 0 && u < 1);
    image_free(&one);
    image_free(&four);
}

TEST(nan_pixels_are_counted_and_zeroed)
{
    struct image img = {0};
    struct render_result r;
    struct diag err;
    struct render_job j = job_for(&nan_at_3_5, 2, 2);
    CHECK(driver_render_image(&j, &img, &r, &err));
    CHECK(r.nan_pixels == 1);
    CHECK(image_pixel(&img, 3, 5)[0] == 0);
    CHECK(image_pixel(&img, 3, 5)[1] == 0); /* the whole estimate is dropped */
    CHECK(image_pixel(&img, 4, 5)[0] == 1);
    image_free(&img);
}

TEST(seed_changes_the_image)
{
    struct image a = {0};
    struct image b = {0};
    struct render_result r;
    struct diag err;
    struct render_job j = job_for(&noisy, 2, 1);
    CHECK(driver_render_image(&j, &a, &r, &err));
    j.seed = 4;
    CHECK(driver_render_image(&j, &b, &r, &err));
    CHECK(memcmp(a.rgb, b.rgb, sizeof(float) * 3 * 37 * 21) != 0);
    image_free(&a);
    image_free(&b);
}

/* What on_pass saw: how often it was called and the last pass count. */
struct pass_log {
    int calls, last;
};

static void
log_pass(void *ctx, const struct image *mean, int passes_done)
{
    struct pass_log *log = ctx;
    (void)mean;
    log->calls++;
    log->last = passes_done;
}

TEST(shares_add_up_to_the_image)
{
    enum {
        PARTS = 3,
        FLOATS = 3 * 37 * 21
    };
    struct image whole = {0};
    struct render_result r;
    struct diag err;
    struct render_job j = job_for(&noisy, 2, 4);
    CHECK(driver_render_image(&j, &whole, &r, &err));
    static float sum[FLOATS];
    uint64_t rays = 0;
    for (int part = 0; part < PARTS; part++) {
        struct pass_log log = {0};
        struct render_share share =
            {.part = part, .parts = PARTS, .on_pass = log_pass, .ctx = &log};
        struct image img = {0};
        driver_set_share(&share);
        CHECK(driver_render_image(&j, &img, &r, &err));
        CHECK(log.calls == 4 && log.last == 4);
        rays += r.counts.rays_camera;
        for (int i = 0; i < FLOATS; i++) {
            sum[i] += img.rgb[i];
        }
        image_free(&img);
    }
    driver_set_share(NULL);
    CHECK(rays == 4 * 37 * 21); /* every pixel rendered by one share */
    CHECK(memcmp(sum, whole.rgb, sizeof sum) == 0);
    /* An image rendered already is returned as it is. */
    struct render_share given = {.part = 0, .parts = 1, .rendered = &whole};
    struct image copy = {0};
    driver_set_share(&given);
    CHECK(driver_render_image(&j, &copy, &r, &err));
    driver_set_share(NULL);
    CHECK(r.passes_done == 4 && memcmp(copy.rgb, whole.rgb, sizeof sum) == 0);
    image_free(&copy);
    image_free(&whole);
}

TEST_MAIN(
    TEST_ENTRY(every_pixel_once_and_thread_independent),
    TEST_ENTRY(nan_pixels_are_counted_and_zeroed),
    TEST_ENTRY(seed_changes_the_image),
    TEST_ENTRY(shares_add_up_to_the_image))
