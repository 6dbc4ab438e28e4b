/* pathcheck.c - see pathcheck.h. */
#include "pathcheck.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "estimate.h"
#include "stagecheck.h"
#include "stats.h"
#include "stattest.h"
#include "testlib.h"

uint64_t
pathcheck_seed(uint64_t fallback)
{
    static bool printed;
    const char *env = getenv("PATHCHECK_SEED");
    uint64_t seed = fallback;
    if (env && env[0]) {
        seed = strtoull(env, NULL, 10);
    }
    if (!printed) {
        printf("first seed %" PRIu64 "%s\n", seed, env && env[0] ? " (PATHCHECK_SEED)" : "");
        printed = true;
    }
    return seed;
}

bool
pathcheck_render(
    const char *scene,
    const char *const args[],
    uint64_t seed,
    struct image *out,
    const char **stats)
{
    const char *argv[64];
    int n = 0;
    for (int i = 0; args && args[i] && n < 56; i++) {
        argv[n++] = args[i];
    }
    char seed_text[32];
    snprintf(seed_text, sizeof seed_text, "%" PRIu64, seed);
    argv[n++] = "--seed";
    argv[n++] = seed_text;
    argv[n] = NULL;
    return stagecheck_render(scene, argv, out, stats);
}

bool
pathcheck_render_batches(
    const char *scene,
    const char *const args[],
    int k,
    uint64_t seed0,
    struct pathcheck_batches *out)
{
    *out = (struct pathcheck_batches){0};
    out->images = calloc((size_t)k, sizeof *out->images);
    if (!out->images) {
        return false;
    }
    double start = stats_clock_seconds();
    for (int i = 0; i < k; i++) {
        const char *stats = NULL;
        if (!pathcheck_render(scene, args, seed0 + (uint64_t)i, &out->images[i], &stats)) {
            pathcheck_batches_free(out);
            return false;
        }
        out->k = i + 1;
        out->nan_pixels += stagecheck_stat(stats, "nan_pixels");
        out->camera_rays += stagecheck_stat(stats, "rays_camera");
    }
    out->seconds = stats_clock_seconds() - start;
    return true;
}

bool
pathcheck_render_sized(
    const char *scene,
    int size,
    int spp,
    const char *const extra[],
    int k,
    uint64_t seed0,
    struct pathcheck_batches *out)
{
    enum {
        MAX_EXTRA = 8
    };

    char size_text[16];
    char spp_text[16];
    snprintf(size_text, sizeof size_text, "%d", size);
    snprintf(spp_text, sizeof spp_text, "%d", spp);
    const char *args[6 + MAX_EXTRA + 1] = {"-W", size_text, "-H", size_text};
    int n = 4;
    if (spp > 0) {
        args[n++] = "--spp";
        args[n++] = spp_text;
    }
    for (int i = 0; extra && extra[i]; i++) {
        if (i == MAX_EXTRA) {
            printf("pathcheck_render_sized: more than %d extra options\n", MAX_EXTRA);
            return false;
        }
        args[n++] = extra[i];
    }
    if (!pathcheck_render_batches(scene, args, k, seed0, out)) {
        return false;
    }
    if (!(out->nan_pixels == 0)) {
        printf("%s: %.0f NaN pixels in %d renders\n", scene, out->nan_pixels, k);
        pathcheck_batches_free(out);
        return false;
    }
    return true;
}

void
pathcheck_batches_free(struct pathcheck_batches *b)
{
    for (int i = 0; b->images && i < b->k; i++) {
        image_free(&b->images[i]);
    }
    free(b->images);
    *b = (struct pathcheck_batches){0};
}

bool
pathcheck_mean_image(const struct image *images, int k, struct image *out)
{
    struct diag err;
    if (k < 1 || !image_alloc(out, images[0].width, images[0].height, &err)) {
        return false;
    }
    size_t n = (size_t)out->width * (size_t)out->height * 3;
    for (size_t j = 0; j < n; j++) {
        double sum = 0;
        for (int i = 0; i < k; i++) {
            sum += images[i].rgb[j];
        }
        out->rgb[j] = (float)(sum / k);
    }
    return true;
}

bool
pathcheck_downsample(const struct image *in, int factor, struct image *out)
{
    struct diag err;
    if (factor < 1 || in->width % factor || in->height % factor
        || !image_alloc(out, in->width / factor, in->height / factor, &err)) {
        printf("cannot downsample a %dx%d image by %d\n", in->width, in->height, factor);
        return false;
    }
    for (int y = 0; y < out->height; y++) {
        for (int x = 0; x < out->width; x++) {
            for (int c = 0; c < 3; c++) {
                double sum = 0;
                for (int dy = 0; dy < factor; dy++) {
                    for (int dx = 0; dx < factor; dx++) {
                        sum += image_pixel(in, x * factor + dx, y * factor + dy)[c];
                    }
                }
                image_pixel(out, x, y)[c] = (float)(sum / (factor * factor));
            }
        }
    }
    return true;
}

/* The end of the JSON object that starts at `open` (a '{'), or NULL.  No
 * string of META.json holds a brace, so counting them is enough. */
static const char *
object_end(const char *open)
{
    int depth = 0;
    for (const char *p = open; *p; p++) {
        depth += *p == '{';
        depth -= *p == '}';
        if (depth == 0) {
            return p;
        }
    }
    return NULL;
}

bool
pathcheck_meta(const char *name, const char *key, double *out)
{
    const char *path = test_root_path("tests/reference/META.json");
    bool ok = pathcheck_meta_in(path, name, key, out);
    if (!ok) {
        printf("%s: no number \"%s\" for image \"%s\"\n", path, key, name);
    }
    return ok;
}

bool
pathcheck_meta_in(const char *path, const char *name, const char *key, double *out)
{
    char *text = test_read_file(path, NULL);
    char pattern[160];
    snprintf(pattern, sizeof pattern, "\"%s\"", name);
    const char *at = text ? strstr(text, pattern) : NULL;
    const char *open = at ? strchr(at, '{') : NULL;
    const char *end = open ? object_end(open) : NULL;
    bool ok = false;
    if (end) {
        snprintf(pattern, sizeof pattern, "\"%s\"", key);
        const char *k = strstr(open, pattern);
        if (k && k < end) {
            k += strlen(pattern);
            while (*k == ' ' || *k == ':') {
                k++;
            }
            char *stop;
            *out = strtod(k, &stop);
            ok = stop != k;
        }
    }
    free(text);
    return ok;
}

struct pathcheck_tally
pathcheck_tally_start(void)
{
    return (struct pathcheck_tally){.tests = 0, .rejected = 0, .min_p = 1};
}

void
pathcheck_tally_add(struct pathcheck_tally *t, double p, double level)
{
    t->tests++;
    t->rejected += !(p >= level);
    t->min_p = isnan(p) ? 0 : fmin(t->min_p, p);
}

bool
pathcheck_reference_load(const char *name, int factor, struct pathcheck_reference *out)
{
    *out = (struct pathcheck_reference){.factor = factor};
    struct image full = {0};
    double batches = 0;
    if (!stagecheck_reference(name, &full) || !pathcheck_meta(name, "batches", &batches)
        || !pathcheck_meta(name, "p90_rel_se_pixel", &out->rel_se_pixel)) {
        image_free(&full);
        return false;
    }
    out->dof = batches - 1;
    bool ok = pathcheck_downsample(&full, factor, &out->image);
    image_free(&full);
    return ok;
}

void
pathcheck_reference_free(struct pathcheck_reference *ref)
{
    image_free(&ref->image);
}

/* Blocks across and down for a given block size, as metrics.h cuts them. */
static int
blocks_along(int pixels, int block_size)
{
    return (pixels + block_size - 1) / block_size;
}

bool
pathcheck_reference_test(
    const struct image *renders,
    int k,
    const struct pathcheck_reference *ref,
    int block_size,
    double level,
    struct pathcheck_tally *t,
    struct metrics_block_stats *stats)
{
    const struct image *r = &ref->image;
    int bx = blocks_along(r->width, block_size);
    int n_blocks = bx * blocks_along(r->height, block_size);
    double *se = calloc((size_t)n_blocks * 3, sizeof *se);
    if (!se) {
        return false;
    }
    /* SE of a block mean of n independent pixels of relative SE s and
     * similar values m: s m / sqrt(n); n counts reference pixels. */
    for (int b = 0; b < n_blocks; b++) {
        int x0 = (b % bx) * block_size;
        int y0 = (b / bx) * block_size;
        int w = r->width - x0 < block_size ? r->width - x0 : block_size;
        int h = r->height - y0 < block_size ? r->height - y0 : block_size;
        double n = (double)w * h * ref->factor * ref->factor;
        for (int c = 0; c < 3; c++) {
            double m = stagecheck_region_mean(r, x0, y0, w, h, c);
            se[3 * b + c] = ref->rel_se_pixel * fabs(m) / sqrt(n);
        }
    }
    struct metrics_block_params params = {
        .block_size = block_size,
        .ref_se = se,
        .ref_dof = ref->dof,
    };
    /* The per-pixel variances of the renders' mean, each block's at least
     * its neighbourhood's, as compare tests them: where light comes by rare
     * paths (a sliver of penumbra lit only by BSDF samples that hit the
     * lamp), all k renders can miss a block's paths at once, and the
     * spread of their block means is then 0 (calibrated:
     * docs/calibration/README.md). */
    struct metrics_block_stats s;
    struct diag err = {0};
    struct image mean = {0}, variance = {0};
    bool ok = estimate_combine(renders, NULL, k, &mean, &variance, &err)
              && metrics_block_stats_variance(&mean, &variance, k - 1, r, &params, &s, &err);
    free(se);
    image_free(&mean);
    image_free(&variance);
    if (!ok) {
        diag_print(stdout, &err, "error");
        return false;
    }
    for (int b = 0; b < s.n_blocks; b++) {
        for (int c = 0; c < 3; c++) {
            pathcheck_tally_add(t, s.blocks[b].p[c], level);
        }
    }
    if (stats) {
        *stats = s;
    } else {
        metrics_block_stats_free(&s);
    }
    return true;
}

bool
pathcheck_block_welch(
    const struct image *a,
    int ka,
    const struct image *b,
    int kb,
    int block_size,
    double level,
    struct pathcheck_tally *t)
{
    int width = a[0].width;
    int height = a[0].height;
    for (int i = 0; i < kb; i++) {
        if (b[i].width != width || b[i].height != height) {
            printf(
                "two-sample test: %dx%d against %dx%d\n",
                width,
                height,
                b[i].width,
                b[i].height);
            return false;
        }
    }
    for (int y0 = 0; y0 < height; y0 += block_size) {
        for (int x0 = 0; x0 < width; x0 += block_size) {
            int w = width - x0 < block_size ? width - x0 : block_size;
            int h = height - y0 < block_size ? height - y0 : block_size;
            for (int c = 0; c < 3; c++) {
                struct stattest_welford wa = {0};
                struct stattest_welford wb = {0};
                for (int i = 0; i < ka; i++) {
                    stattest_welford_add(&wa, stagecheck_region_mean(&a[i], x0, y0, w, h, c));
                }
                for (int i = 0; i < kb; i++) {
                    stattest_welford_add(&wb, stagecheck_region_mean(&b[i], x0, y0, w, h, c));
                }
                struct stattest_result r = stattest_t_test_welford_welch(&wa, &wb);
                pathcheck_tally_add(t, r.p, level);
            }
        }
    }
    return true;
}

bool
pathcheck_sets_agree(
    const char *what,
    const struct pathcheck_batches *a,
    const struct pathcheck_batches *b,
    int block_size,
    double level)
{
    int width = a->images[0].width;
    int height = a->images[0].height;
    int whole_size = width > height ? width : height;
    struct pathcheck_tally blocks = pathcheck_tally_start();
    struct pathcheck_tally whole = pathcheck_tally_start();
    if (!pathcheck_block_welch(a->images, a->k, b->images, b->k, block_size, level, &blocks)
        || !pathcheck_block_welch(a->images, a->k, b->images, b->k, whole_size, level, &whole)) {
        return false;
    }
    printf(
        "%s: %zu block tests, min p %.3g, %zu rejected; image mean: min p %.3g, %zu rejected "
        "(level %.3g)\n",
        what,
        blocks.tests,
        blocks.min_p,
        blocks.rejected,
        whole.min_p,
        whole.rejected,
        level);
    return blocks.rejected == 0 && whole.rejected == 0;
}

double
pathcheck_sets_agree_tests(int width, int height, int block_size)
{
    double across = (width + block_size - 1) / block_size;
    double down = (height + block_size - 1) / block_size;
    return 3 * (across * down + 1);
}

double
pathcheck_mean_relmse(const struct image *renders, int k, const struct image *ref)
{
    double sum = 0;
    for (int i = 0; i < k; i++) {
        sum += metrics_relmse(&renders[i], ref, NULL);
    }
    return sum / k;
}

/* ---- the edge ------------------------------------------------------------ */

static double
edge_side(const struct pathcheck_edge *e, double x, double y)
{
    return cos(e->angle) * (x - e->x0) + sin(e->angle) * (y - e->y0);
}

bool
pathcheck_edge_inside(const struct pathcheck_edge *e, double x, double y)
{
    return edge_side(e, x, y) > 0;
}

const char *
pathcheck_edge_scene(const char *name, const struct pathcheck_edge *e)
{
    /* Film (x, y) lies at world (x - d, d - y, -d), d = size / 2: the film's
     * y axis points down, the world's up.  In the world the edge runs along
     * t = (-sin, -cos, 0) and the light lies towards n = (cos, -sin, 0);
     * cross(t, n) = (0, 0, 1) faces the camera, so the light's front side
     * is the one seen. */
    double d = e->size / 2.0;
    double c = cos(e->angle);
    double s = sin(e->angle);
    double big = 4.0 * e->size; /* the other three edges lie far outside the view */
    double p0[3] = {e->x0 - d, d - e->y0, -d};
    double t[3] = {-s, -c, 0};
    double n[3] = {c, -s, 0};
    return stagecheck_scene(
        name,
        "camera origin 0 0 0 target 0 0 -1 up 0 1 0 fov 90\n"
        "image width %d height %d\n"
        "area_light corner %.17g %.17g %.17g edge1 %.17g %.17g %.17g edge2 %.17g %.17g %.17g "
        "radiance 1 1 1\n",
        e->size,
        e->size,
        p0[0] - big * t[0],
        p0[1] - big * t[1],
        p0[2],
        2 * big * t[0],
        2 * big * t[1],
        0.0,
        big * n[0],
        big * n[1],
        0.0);
}

double
pathcheck_edge_coverage(const struct pathcheck_edge *e, int px, int py)
{
    /* Clip the pixel's square to the half-plane (Sutherland and Hodgman,
     * "Reentrant polygon clipping", CACM 1974) and take the area of what is
     * left by the shoelace formula. */
    double sx[4] = {px, px + 1.0, px + 1.0, px};
    double sy[4] = {py, py, py + 1.0, py + 1.0};
    double cx[8];
    double cy[8];
    int n = 0;
    for (int i = 0; i < 4; i++) {
        int j = (i + 1) % 4;
        double fi = edge_side(e, sx[i], sy[i]);
        double fj = edge_side(e, sx[j], sy[j]);
        if (fi > 0) {
            cx[n] = sx[i];
            cy[n++] = sy[i];
        }
        if ((fi > 0) != (fj > 0)) {
            double u = fi / (fi - fj);
            cx[n] = sx[i] + u * (sx[j] - sx[i]);
            cy[n++] = sy[i] + u * (sy[j] - sy[i]);
        }
    }
    double area = 0;
    for (int i = 0; i < n; i++) {
        int j = (i + 1) % n;
        area += cx[i] * cy[j] - cx[j] * cy[i];
    }
    return fabs(area) / 2;
}
