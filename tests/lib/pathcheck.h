/*
 * pathcheck.h - helpers shared by the tests of stages 06 (supersampling)
 * and 07 (path tracing): seeded renders and sets of independent renders
 * that also read nan_pixels, image means and box downsampling, the noise
 * figures of tests/reference/META.json, block t-tests against a reference
 * or between two sets of renders counted against one program-wide Sidak
 * level, and the exact pixel coverage of a straight edge.
 *
 * The statistics follow Nori's and Mitsuba's render tests (TESTING.md T25):
 * K independent renders (different seeds) give K estimates of every block
 * mean; their spread gives the standard error, so no variance formula of
 * the renderer is trusted.  All tests of one program share the family
 * level alpha = 0.01, Sidak-corrected for the number m of tests in the
 * program: alpha' = 1 - (1 - alpha)^(1/m) (stattest_sidak).
 */
#ifndef PATHCHECK_H
#define PATHCHECK_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "image.h"
#include "metrics.h"

/* The family significance level of every statistical test (TESTING.md 5). */
#define PATHCHECK_ALPHA 0.01

/* Whether the test program runs under AddressSanitizer: renders are several
 * times slower there, and the statistical tests scale their work down. */
#if defined(__SANITIZE_ADDRESS__)
#define PATHCHECK_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PATHCHECK_SANITIZED 1
#endif
#endif
#ifndef PATHCHECK_SANITIZED
#define PATHCHECK_SANITIZED 0
#endif

/* The first seed of a program's renders: the environment variable
 * PATHCHECK_SEED when set (to rerun the statistical tests with other seeds
 * and see that they fail about as often as alpha says: TESTING.md,
 * make test-seeds, make calibrate --seed-offsets N), else `fallback`.
 * Printed once. */
uint64_t pathcheck_seed(uint64_t fallback);

/* Render `scene` with `args` (NULL-terminated, may be NULL) plus --seed and
 * --stats; *stats gets the statistics file (valid until the program ends).
 * False, with the binary's output printed, when the run fails. */
bool pathcheck_render(
    const char *scene,
    const char *const args[],
    uint64_t seed,
    struct image *out,
    const char **stats);

/* K renders of one scene with seeds seed0, seed0 + 1, ... */
struct pathcheck_batches {
    int k;
    struct image *images; /* k images */
    double nan_pixels; /* summed over the runs' --stats (NaN if one lacks it) */
    double camera_rays; /* summed likewise */
    double seconds; /* wall-clock time of all runs */
};

bool pathcheck_render_batches(
    const char *scene,
    const char *const args[],
    int k,
    uint64_t seed0,
    struct pathcheck_batches *out);
void pathcheck_batches_free(struct pathcheck_batches *b);

/* pathcheck_render_batches at size x size pixels, with --spp spp (none when
 * spp is 0) and the extra options (NULL-terminated, at most 8; may be
 * NULL).  A render with NaN pixels counts as failed (and says so). */
bool pathcheck_render_sized(
    const char *scene,
    int size,
    int spp,
    const char *const extra[],
    int k,
    uint64_t seed0,
    struct pathcheck_batches *out);

/* The mean of k images of one size (out is allocated). */
bool pathcheck_mean_image(const struct image *images, int k, struct image *out);

/* Box-downsample by an integer factor that divides both sides: each output
 * pixel is the mean of factor x factor input pixels.  For box-filtered
 * pixels this is exact: a pixel of the render at 1/factor the resolution
 * averages radiance over the union of those pixels' footprints. */
bool pathcheck_downsample(const struct image *in, int factor, struct image *out);

/* A number of tests/reference/META.json inside the object of image `name`
 * (e.g. "cornell_diffuse_area_gi", "p90_rel_se_pixel"); false (and a
 * message) when the file, the image or the key is missing. */
bool pathcheck_meta(const char *name, const char *key, double *out);

/* The same in the META.json-style file at path, quietly (compare reads the
 * META.json beside a reference this way). */
bool pathcheck_meta_in(const char *path, const char *name, const char *key, double *out);

/* Outcome of a set of tests at one significance level. */
struct pathcheck_tally {
    size_t tests;
    size_t rejected;
    double min_p; /* 1 before any test */
};

/* A tally with no tests yet. */
struct pathcheck_tally pathcheck_tally_start(void);

/* Count one p-value (NaN counts as a rejection). */
void pathcheck_tally_add(struct pathcheck_tally *t, double p, double level);

/* A Mitsuba reference at the render's resolution, with its noise. */
struct pathcheck_reference {
    struct image image; /* box-downsampled by `factor` */
    int factor; /* reference pixels per render pixel, per side */
    double rel_se_pixel; /* META.json p90_rel_se_pixel: one reference pixel's relative SE */
    double dof; /* META.json batches - 1 */
};

/* Load tests/reference/<name>.pfm, downsampled by factor, and its noise
 * figures. */
bool pathcheck_reference_load(const char *name, int factor, struct pathcheck_reference *out);
void pathcheck_reference_free(struct pathcheck_reference *ref);

/* Block t-tests (metrics.h) of k >= 2 renders against the reference, as
 * compare makes them: their mean and the per-pixel variance of that mean
 * (estimate.h, k - 1 degrees of freedom per pixel), each block's variance
 * at least its neighbourhood's (metrics_block_stats_variance); each block
 * and channel counted in *t at `level`.  The reference's standard
 * error of a block mean is taken as rel_se_pixel * |block mean| /
 * sqrt(reference pixels in the block): its pixels' noise is independent
 * (Mitsuba's independent sampler), and the 90th percentile of the per-pixel
 * relative SE errs on the side of accepting.  The statistics are returned
 * in *stats (free with metrics_block_stats_free) when stats is not NULL. */
bool pathcheck_reference_test(
    const struct image *renders,
    int k,
    const struct pathcheck_reference *ref,
    int block_size,
    double level,
    struct pathcheck_tally *t,
    struct metrics_block_stats *stats);

/* Two-sample block tests: per block and channel, Welch's t-test of the ka
 * block means of renders a against the kb of renders b (all one size). */
bool pathcheck_block_welch(
    const struct image *a,
    int ka,
    const struct image *b,
    int kb,
    int block_size,
    double level,
    struct pathcheck_tally *t);

/* Two sets of renders of one scene (all one size) said to agree:
 * pathcheck_block_welch over blocks of block_size and over the whole image,
 * both at `level`.  Prints one line, "<what>: N block tests, min p, R
 * rejected; image mean: min p, R rejected (level)", and returns whether
 * nothing was rejected (false also when the sizes differ). */
bool pathcheck_sets_agree(
    const char *what,
    const struct pathcheck_batches *a,
    const struct pathcheck_batches *b,
    int block_size,
    double level);

/* How many p-values one pathcheck_sets_agree makes on width x height
 * images: every block and the whole image, 3 channels each (for the Sidak
 * correction of a program's level). */
double pathcheck_sets_agree_tests(int width, int height, int block_size);

/* The size of the stage-07 tests that compare two sets of renders of a
 * small scene: images PATHCHECK_SETS_SIZE pixels a side (also as the
 * string PATHCHECK_SETS_SIZE_ARG for a command line), PATHCHECK_SETS_K
 * renders per set, blocks of PATHCHECK_SETS_BLOCK.  Under AddressSanitizer
 * renders are several times slower: smaller sets (valid, less power). */
#if PATHCHECK_SANITIZED
#define PATHCHECK_SETS_SIZE 32
#define PATHCHECK_SETS_SIZE_ARG "32"
#define PATHCHECK_SETS_K 6
#else
#define PATHCHECK_SETS_SIZE 64
#define PATHCHECK_SETS_SIZE_ARG "64"
#define PATHCHECK_SETS_K 8
#endif
#define PATHCHECK_SETS_BLOCK 16

/* relMSE (metrics.h) of each render against ref, averaged over the k
 * renders; NaN when sizes differ. */
double pathcheck_mean_relmse(const struct image *renders, int k, const struct image *ref);

/* ---- A straight edge on the film ----------------------------------------
 *
 * The half-plane of film points (x, y) (pixel units, (0,0) the top-left
 * corner of the film, y down) with nx (x - x0) + ny (y - y0) > 0.  The
 * scene pathcheck_edge_scene writes shows exactly that half-plane as an
 * area light of radiance 1 against a black background: a pinhole camera
 * with a 90 degree field of view looking straight at a plane at distance
 * size/2 maps the film one to one (one unit per pixel) onto that plane,
 * where the light's long edge lies along the line.  A box-filtered pixel's
 * value is therefore exactly its covered area. */
struct pathcheck_edge {
    int size; /* the image is size x size pixels */
    double x0, y0; /* a film point on the edge */
    double angle; /* direction (radians) of the normal (nx, ny) = (cos, sin), into the light */
};

/* Write the edge's scene into the test's temporary directory as `name`;
 * returns its path, or NULL. */
const char *pathcheck_edge_scene(const char *name, const struct pathcheck_edge *e);

/* Area of pixel (px, py)'s unit square inside the half-plane, in [0, 1]. */
double pathcheck_edge_coverage(const struct pathcheck_edge *e, int px, int py);

/* Whether film point (x, y) lies strictly inside the half-plane. */
bool pathcheck_edge_inside(const struct pathcheck_edge *e, double x, double y);

#endif /* PATHCHECK_H */
