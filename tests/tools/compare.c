/*
 * compare.c - "why is my image wrong?": a render against a reference, in
 * numbers, in words and as an error map.
 *
 *     compare [options] RENDER [RENDER2 ...] REFERENCE
 *
 * Prints relMSE, RMSE, the mean of each channel of both images and the
 * worst block, then tells noise from bias when it can: with two or more
 * renders of different seeds (or one render and --variance), each block of
 * the render is t-tested against the reference (metrics.h, stattest.h), at
 * the family level --alpha Sidak-corrected for the number of tests, and
 * the verdict names the blocks that fail.  Optional outputs: the error map
 * (--map, errmap.h) and a self-contained report page (--html, compare_report.c).
 * Exit status: 0 the images agree, 1 biased, 2 bad input or usage (an
 * image holding NaN or infinite pixels, an output that is an input).
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "compare_report.h"
#include "errmap.h"
#include "estimate.h"
#include "imgread.h"
#include "output_check.h"
#include "pathcheck.h"
#include "stattest.h"

#define MAX_RENDERS 64
#define DEFAULT_BLOCK 16
#define DEFAULT_ALPHA 0.01
#define MAX_LISTED 10 /* failing blocks listed in the text output */

struct args {
    struct comparison c;
    const char *paths[MAX_RENDERS + 1];
    int n_paths;
    const char *map_path;
    const char *html_path;
    double range; /* 0: automatic */
    bool quiet;
    bool ref_se_given;
    bool smooth_mask;
    const char *regions_path; /* --regions: the reference's feature pass */
    struct region_report regions;
};

static const char usage_line[] = "usage: compare [options] RENDER [RENDER2 ...] REFERENCE\n";

static void
usage(FILE *f)
{
    fputs(usage_line, f);
    fputs(
        "\n"
        "Compares a render with a reference image (.pfm, .exr, or .png for a rough\n"
        "look) and says whether they differ by more than the render's noise.\n"
        "\n"
        "Give two or more renders of the same scene and options with different\n"
        "--seed values (their mean is compared; each should have the same spp), or\n"
        "one render and --variance.  Each BLOCKxBLOCK block, each window of 2x2\n"
        "blocks (overlapping: a bias the size of a window is seen nearly whole\n"
        "wherever it lies) and each channel is then t-tested against the reference\n"
        "at the level --alpha, Sidak-corrected for the number of tests: 'consistent\n"
        "with the reference (noise only)' or 'biased', with the failing blocks and\n"
        "windows named.  With one render alone only the numbers are printed: noise\n"
        "cannot be told from bias.\n"
        "\n"
        "  --variance FILE     per-pixel variance of RENDER's pixels (the squared\n"
        "                      standard error), e.g. written by merge --variance\n"
        "  --variance-dof N    its degrees of freedom (merge prints them; default 0:\n"
        "                      taken as exact)\n"
        "  --block N           block size in pixels (default 16)\n"
        "  --alpha A           family significance level (default 0.01)\n"
        "  --ref-rel-se S      the reference's relative standard error per pixel (a\n"
        "                      block's is S / sqrt(its pixels)) and\n"
        "  --ref-dof N         its degrees of freedom (default: from META.json beside\n"
        "                      the reference, else 0 and 0: an exact reference)\n"
        "  --map FILE.png      write the error map: signed relative error, blue\n"
        "                      darker, red brighter, failing blocks and windows\n"
        "                      outlined\n"
        "  --range R           the map's scale is -R..+R (default: automatic)\n"
        "  --html FILE.html    write a self-contained report page\n"
        "  --title TEXT        the report page's title\n"
        "  --max-relmse X      with one render alone: fail when relMSE > X\n"
        "  --mask smooth       with one render alone: compare only the reference's\n"
        "                      smooth pixels (3x3 luminance within 5%, no border):\n"
        "                      for stages without anti-aliasing, whose edges differ\n"
        "  --regions FILE      break the error down by region: FILE is the reference\n"
        "                      scene's feature pass (render --aov feature, docs/aov.md:\n"
        "                      a .pfm, or an .exr holding it as its layer 'feature');\n"
        "                      each region is t-tested as a whole and per block (one\n"
        "                      Sidak-corrected family with the rest), or, with one\n"
        "                      render alone, held against --max-relmse; a line per\n"
        "                      region, with a pixel of it to replay with --pixel\n"
        "  -q, --quiet         print only the verdict, what it can find (the power\n"
        "                      line) and the regions' lines\n"
        "  -h, --help          this text\n"
        "\n"
        "Exit status: 0 the images agree (or, one render alone, were compared),\n"
        "1 biased (or relMSE above --max-relmse, or a region biased or over it),\n"
        "2 bad input: an unreadable image, a NaN or infinite pixel in any image\n"
        "(named, with its file), or --map or --html naming an input or each other.\n",
        f);
}

/* A number option's value; false (message printed) when it is not one. */
static bool
parse_number(const char *name, const char *value, double lo, double hi, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(value, &end);
    if (end == value || *end != '\0' || errno == ERANGE || !(v >= lo && v <= hi)) {
        fprintf(
            stderr,
            "compare: error: %s expects a number in [%g, %g], got '%s'\n",
            name,
            lo,
            hi,
            value);
        return false;
    }
    *out = v;
    return true;
}

/* Options that take a value; false on bad usage (message printed). */
static bool
parse_valued(struct args *a, const char *name, const char *value)
{
    struct comparison *c = &a->c;
    double v = 0;
    if (strcmp(name, "--variance") == 0) {
        c->variance_path = value;
    } else if (strcmp(name, "--map") == 0) {
        a->map_path = value;
    } else if (strcmp(name, "--html") == 0) {
        a->html_path = value;
    } else if (strcmp(name, "--title") == 0) {
        c->title = value;
    } else if (strcmp(name, "--mask") == 0) {
        if (strcmp(value, "smooth") != 0) {
            fprintf(stderr, "compare: error: --mask takes 'smooth', got '%s'\n", value);
            return false;
        }
        a->smooth_mask = true;
    } else if (strcmp(name, "--regions") == 0) {
        a->regions_path = value;
    } else if (strcmp(name, "--variance-dof") == 0) {
        return parse_number(name, value, 0, 1e9, &c->pixel_dof);
    } else if (strcmp(name, "--block") == 0) {
        if (!parse_number(name, value, 1, IMAGE_MAX_DIM, &v) || v != floor(v)) {
            fprintf(stderr, "compare: error: --block expects a whole number of pixels\n");
            return false;
        }
        c->block_size = (int)v;
    } else if (strcmp(name, "--alpha") == 0) {
        return parse_number(name, value, 1e-12, 0.5, &c->alpha);
    } else if (strcmp(name, "--ref-rel-se") == 0) {
        a->ref_se_given = true;
        return parse_number(name, value, 0, 1e6, &c->ref_rel_se);
    } else if (strcmp(name, "--ref-dof") == 0) {
        a->ref_se_given = true;
        return parse_number(name, value, 0, 1e12, &c->ref_dof);
    } else if (strcmp(name, "--range") == 0) {
        return parse_number(name, value, 1e-6, 1e6, &a->range);
    } else if (strcmp(name, "--max-relmse") == 0) {
        return parse_number(name, value, 0, 1e30, &c->max_relmse);
    } else {
        fprintf(stderr, "compare: error: unknown option '%s'\n", name);
        return false;
    }
    return true;
}

static bool
takes_value(const char *s)
{
    static const char *const valued[] = {
        "--variance",
        "--variance-dof",
        "--block",
        "--alpha",
        "--ref-rel-se",
        "--ref-dof",
        "--map",
        "--range",
        "--html",
        "--title",
        "--mask",
        "--regions",
        "--max-relmse"};
    for (size_t i = 0; i < sizeof valued / sizeof valued[0]; i++) {
        if (strcmp(s, valued[i]) == 0) {
            return true;
        }
    }
    return false;
}

/* 0: parsed; 1: --help; 2: bad usage (message printed). */
static int
parse_args(int argc, char **argv, struct args *a)
{
    a->c.block_size = DEFAULT_BLOCK;
    a->c.alpha = DEFAULT_ALPHA;
    for (int i = 1; i < argc; i++) {
        const char *s = argv[i];
        if (strcmp(s, "-h") == 0 || strcmp(s, "--help") == 0) {
            return 1;
        } else if (strcmp(s, "-q") == 0 || strcmp(s, "--quiet") == 0) {
            a->quiet = true;
        } else if (takes_value(s)) {
            if (i + 1 >= argc) {
                fprintf(stderr, "compare: error: %s needs a value\n", s);
                return 2;
            }
            if (!parse_valued(a, s, argv[++i])) {
                return 2;
            }
        } else if (s[0] == '-' && s[1] != '\0') {
            fprintf(stderr, "compare: error: unknown option '%s'\n", s);
            return 2;
        } else if (a->n_paths <= MAX_RENDERS) {
            a->paths[a->n_paths++] = s;
        } else {
            fprintf(stderr, "compare: error: at most %d renders\n", MAX_RENDERS);
            return 2;
        }
    }
    if (a->n_paths < 2) {
        fprintf(stderr, "compare: error: expected a RENDER and a REFERENCE\n");
        return 2;
    }
    a->c.render_paths = a->paths;
    a->c.k = a->n_paths - 1;
    a->c.reference_path = a->paths[a->n_paths - 1];
    if (a->smooth_mask && (a->c.variance_path || a->c.k > 1)) {
        fprintf(
            stderr,
            "compare: error: --mask goes with one render alone (the block tests use every pixel)\n");
        return 2;
    }
    if (a->c.variance_path && a->c.k > 1) {
        fprintf(stderr, "compare: error: --variance goes with one render, not %d\n", a->c.k);
        return 2;
    }
    return 0;
}

/* The META.json in the directory of the reference at path, into out. */
static void
meta_beside(const char *path, char *out, size_t cap)
{
    const char *slash = strrchr(path, '/');
    snprintf(out, cap, "%.*sMETA.json", (int)(slash ? slash + 1 - path : 0), path);
}

/* The reference's noise from the META.json in its directory (the format of
 * tests/reference/: an object per image name holding "p90_rel_se_pixel" and
 * "batches"), unless given on the command line.  Like the project's tests,
 * the 90th-percentile per-pixel SE stands for every pixel's: an
 * overestimate, which errs towards "consistent". */
static void
reference_noise_from_meta(struct comparison *c)
{
    const char *path = c->reference_path;
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    char name[256], meta[4096];
    snprintf(name, sizeof name, "%.*s", (int)(dot ? dot - base : (long)strlen(base)), base);
    meta_beside(path, meta, sizeof meta);
    double rel_se = 0, batches = 0;
    if (pathcheck_meta_in(meta, name, "p90_rel_se_pixel", &rel_se)
        && pathcheck_meta_in(meta, name, "batches", &batches) && rel_se >= 0 && batches >= 2) {
        c->ref_rel_se = rel_se;
        c->ref_dof = batches - 1;
        c->ref_se_from_meta = true;
    }
}

/* A NaN or infinite pixel has no error to measure, and would turn every
 * mean it enters into NaN: such an input is refused, naming its first one
 * (to replay) and how many there are. */
static bool
check_finite(const struct image *img, const char *path, struct diag *err)
{
    static const char channels[3] = {'R', 'G', 'B'};
    size_t n = (size_t)img->width * (size_t)img->height * 3;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(img->rgb[i])) {
            size_t x = i / 3 % (size_t)img->width, y = i / 3 / (size_t)img->width;
            diag_set(
                err,
                path,
                0,
                0,
                "pixel %zu,%zu is %s in channel %c (NaN or infinite pixels: %zu): compare needs "
                "finite pixels; render --pixel %zu,%zu --trace - replays one",
                x,
                y,
                isnan(img->rgb[i]) ? "NaN" : "infinite",
                channels[i % 3],
                metrics_count_nonfinite(img),
                x,
                y);
            return false;
        }
    }
    return true;
}

/* Read every input; the renders are combined into their mean and its
 * per-pixel variance.  False (diag) on unreadable files or mismatches. */
static bool
load_inputs(struct comparison *c, struct diag *err)
{
    struct image renders[MAX_RENDERS] = {{0}};
    bool ok = imgread(c->reference_path, &c->reference, err)
              && check_finite(&c->reference, c->reference_path, err);
    for (int j = 0; ok && j < c->k; j++) {
        ok = imgread(c->render_paths[j], &renders[j], err)
             && check_finite(&renders[j], c->render_paths[j], err);
        if (ok
            && (renders[j].width != c->reference.width
                || renders[j].height != c->reference.height)) {
            diag_set(
                err,
                c->render_paths[j],
                0,
                0,
                "the render is %dx%d but the reference %s is %dx%d",
                renders[j].width,
                renders[j].height,
                c->reference_path,
                c->reference.width,
                c->reference.height);
            ok = false;
        }
    }
    ok = ok
         && estimate_combine(
             renders,
             NULL,
             c->k,
             &c->render,
             c->k >= 2 ? &c->variance : NULL,
             err);
    c->noise = c->k >= 2 ? NOISE_RENDERS : NOISE_NONE;
    c->pixel_dof = c->k >= 2 ? c->k - 1 : c->pixel_dof;
    c->renders_identical = ok && c->k >= 2;
    for (int j = 1; c->renders_identical && j < c->k; j++) {
        size_t bytes = (size_t)renders[0].width * (size_t)renders[0].height * 3 * sizeof(float);
        c->renders_identical = memcmp(renders[0].rgb, renders[j].rgb, bytes) == 0;
    }
    for (int j = 0; j < c->k; j++) {
        image_free(&renders[j]);
    }
    if (ok && c->variance_path) {
        ok = imgread(c->variance_path, &c->variance, err);
        if (ok
            && (c->variance.width != c->render.width || c->variance.height != c->render.height)) {
            diag_set(
                err,
                c->variance_path,
                0,
                0,
                "the variance image is %dx%d but the render is %dx%d",
                c->variance.width,
                c->variance.height,
                c->render.width,
                c->render.height);
            ok = false;
        }
        size_t n = (size_t)c->variance.width * (size_t)c->variance.height * 3;
        for (size_t i = 0; ok && i < n; i++) {
            if (!(c->variance.rgb[i] >= 0) || !isfinite(c->variance.rgb[i])) {
                diag_set(
                    err,
                    c->variance_path,
                    0,
                    0,
                    "a variance must be finite and >= 0, found %g at pixel %zu",
                    c->variance.rgb[i],
                    i / 3);
                ok = false;
            }
        }
        c->noise = NOISE_VARIANCE;
    }
    return ok;
}

int
compare_block_channel(const struct metrics_block *b)
{
    int best = 0;
    for (int ch = 1; ch < 3; ch++) {
        if (b->p[ch] < b->p[best]) {
            best = ch;
        }
    }
    return best;
}

void
compare_describe_block(char *buf, size_t cap, const struct metrics_block *b)
{
    int n = snprintf(
        buf,
        cap,
        "the %s at x %d-%d, y %d-%d is ",
        b->window ? "window" : "block",
        b->x0,
        b->x0 + b->w - 1,
        b->y0,
        b->y0 + b->h - 1);
    if (n >= 0 && (size_t)n < cap) {
        regions_describe_difference(
            buf + n,
            cap - (size_t)n,
            b->mean,
            b->ref_mean,
            b->t,
            b->p,
            true);
    }
}

static double
block_min_p(const struct metrics_block *b)
{
    return fmin(b->p[0], fmin(b->p[1], b->p[2]));
}

/* Sort failing blocks and windows by their smallest p (most significant
 * first). */
static const struct metrics_block_stats *sort_blocks;

static int
by_significance(const void *a, const void *b)
{
    double pa = block_min_p(metrics_block_test(sort_blocks, *(const int *)a));
    double pb = block_min_p(metrics_block_test(sort_blocks, *(const int *)b));
    return (pa > pb) - (pa < pb);
}

/* The block and window tests and the list of those failing; other_tests
 * more tests (the regions') share the family level alpha with them. */
static bool
test_blocks(struct comparison *c, int other_tests, struct diag *err)
{
    /* A block mean of n independent pixels has 1/sqrt(n) of their relative
     * SE (taken for a whole block; edge blocks are smaller). */
    struct metrics_block_params params = {
        .block_size = c->block_size,
        .ref_rel_se = c->ref_rel_se / c->block_size,
        .ref_dof = c->ref_dof,
        .windows = true,
    };
    if (!metrics_block_stats_variance(
            &c->render,
            &c->variance,
            c->pixel_dof,
            &c->reference,
            &params,
            &c->blocks,
            err)) {
        return false;
    }
    int n = c->blocks.n_blocks + c->blocks.n_windows;
    c->level = stattest_sidak(c->alpha, 3.0 * n + other_tests);
    if (!metrics_block_power(
            &c->blocks, c->level, COMPARE_POWER, COMPARE_TARGET_BIAS, &c->power, err)) {
        return false;
    }
    c->failing = malloc((size_t)n * sizeof *c->failing);
    if (!c->failing) {
        diag_set(err, NULL, 0, 0, "out of memory");
        return false;
    }
    for (int i = 0; i < n; i++) {
        const struct metrics_block *b = metrics_block_test(&c->blocks, i);
        if (!(block_min_p(b) >= c->level)) {
            c->failing[c->n_failing++] = i;
            c->n_failing_windows += b->window;
        }
    }
    sort_blocks = &c->blocks;
    qsort(c->failing, (size_t)c->n_failing, sizeof *c->failing, by_significance);
    return true;
}

/* The block whose mean luminance is furthest from the reference's, as the
 * error map measures it (errmap.h); blocks cut as the tests cut them. */
static void
find_worst(struct comparison *c)
{
    int bs = c->block_size;
    int bx = (c->render.width + bs - 1) / bs, by = (c->render.height + bs - 1) / bs;
    c->worst = -1;
    c->worst_error = 0;
    for (int i = 0; i < bx * by; i++) {
        int x0 = (i % bx) * bs, y0 = (i / bx) * bs;
        double sx = 0, sr = 0, n = 0;
        for (int y = y0; y < y0 + bs && y < c->render.height; y++) {
            for (int x = x0; x < x0 + bs && x < c->render.width; x++) {
                if (!c->mask || c->mask[(size_t)y * (size_t)c->render.width + (size_t)x]) {
                    sx += metrics_luminance(image_pixel(&c->render, x, y));
                    sr += metrics_luminance(image_pixel(&c->reference, x, y));
                    n++;
                }
            }
        }
        double e = (sx / n - sr / n) / sqrt(sr / n * (sr / n) + METRICS_RELMSE_EPS);
        if (n > 0 && (c->worst < 0 || !(fabs(e) <= fabs(c->worst_error)))) {
            c->worst = i;
            c->worst_error = e;
        }
    }
}

static void
decide(struct comparison *c)
{
    const struct metrics *m = &c->m;
    if (c->noise == NOISE_NONE) {
        bool over = c->max_relmse > 0 && !(m->relmse <= c->max_relmse);
        c->status = over ? COMPARE_BIASED : COMPARE_AGREE;
        if (over) {
            snprintf(
                c->verdict,
                sizeof c->verdict,
                "too far: relMSE %.3g is above the limit %.3g",
                m->relmse,
                c->max_relmse);
        } else if (c->max_relmse > 0) {
            snprintf(
                c->verdict,
                sizeof c->verdict,
                "within the limit: relMSE %.3g is at most %.3g (one render: noise not told from bias)",
                m->relmse,
                c->max_relmse);
        } else {
            snprintf(
                c->verdict,
                sizeof c->verdict,
                "not tested for bias: give a second render with another --seed, or --variance");
        }
        return;
    }
    c->status = c->n_failing ? COMPARE_BIASED : COMPARE_AGREE;
    if (c->n_failing) {
        snprintf(
            c->verdict,
            sizeof c->verdict,
            "biased: %d of %d blocks and %d of %d windows differ from the reference by more than "
            "noise",
            c->n_failing - c->n_failing_windows,
            c->blocks.n_blocks,
            c->n_failing_windows,
            c->blocks.n_windows);
    } else {
        snprintf(
            c->verdict,
            sizeof c->verdict,
            "consistent with the reference (noise only): none of %d blocks and %d windows differs by "
            "more than noise",
            c->blocks.n_blocks,
            c->blocks.n_windows);
    }
}

/* text after label, wrapped at 80 columns, continuation lines indented. */
static void
print_wrapped(const char *label, const char *text)
{
    size_t indent = strlen(label), column = indent;
    fputs(label, stdout);
    while (*text) {
        size_t word = strcspn(text, " ");
        if (column > indent && column + 1 + word > 80) {
            printf("\n%*s", (int)indent, "");
            column = indent;
        } else if (column > indent) {
            putchar(' ');
            column++;
        }
        printf("%.*s", (int)word, text);
        column += word;
        text += word;
        text += strspn(text, " ");
    }
    putchar('\n');
}

static void
print_text(const struct comparison *c)
{
    const struct metrics *m = &c->m;
    printf("render     %s", c->render_paths[0]);
    if (c->k > 1) {
        printf(" and %d more (their mean)", c->k - 1);
    }
    printf("\nreference  %s", c->reference_path);
    if (c->ref_rel_se > 0) {
        char se[64];
        metrics_format_plain(se, sizeof se, c->ref_rel_se);
        printf(
            " (relative SE %s per pixel, %g dof%s)",
            se,
            c->ref_dof,
            c->ref_se_from_meta ? ", from its META.json" : "");
    }
    printf("\nsize       %dx%d\n", c->render.width, c->render.height);
    if (c->mask) {
        printf(
            "compared   %zu of %d pixels: the reference's smooth ones (--mask smooth)\n",
            c->n_masked,
            c->render.width * c->render.height);
    }
    printf("relMSE     %.4g\n", m->relmse);
    printf("RMSE       %.4g\n", m->rmse);
    char means[160];
    compare_format_means(means, sizeof means, m, ", ");
    printf("mean R G B %s\n", means);
    if (c->worst >= 0) {
        int bs = c->block_size, bx = (c->render.width + bs - 1) / bs;
        int x0 = (c->worst % bx) * bs, y0 = (c->worst / bx) * bs;
        printf(
            "worst      the block at x %d-%d, y %d-%d: ",
            x0,
            (x0 + bs < c->render.width ? x0 + bs : c->render.width) - 1,
            y0,
            (y0 + bs < c->render.height ? y0 + bs : c->render.height) - 1);
        char size[64];
        metrics_format_plain(size, sizeof size, fabs(100 * c->worst_error));
        printf("luminance %s%% %s\n", size, c->worst_error < 0 ? "darker" : "brighter");
    }
    if (c->noise != NOISE_NONE) {
        printf(
            "noise      %s\n",
            c->noise == NOISE_RENDERS ? "from the spread of the renders"
                                      : "from the variance image");
        if (c->renders_identical) {
            printf(
                "note       the renders are identical (a deterministic stage, or one seed twice):\n"
                "           no noise, so any difference beyond the reference's own noise counts\n");
        }
        char tests[256];
        snprintf(
            tests,
            sizeof tests,
            "%d blocks of %dx%d and %d windows of %dx%d (2x2 blocks, overlapping) x 3 channels, "
            "each at %.2g (alpha %g, Sidak-corrected)",
            c->blocks.n_blocks,
            c->block_size,
            c->block_size,
            c->blocks.n_windows,
            2 * c->block_size,
            2 * c->block_size,
            c->level,
            c->alpha);
        print_wrapped("tests      ", tests);
    }
    printf("verdict    %s\n", c->verdict);
    for (int i = 0; i < c->n_failing && i < MAX_LISTED; i++) {
        char line[256];
        compare_describe_block(line, sizeof line, metrics_block_test(&c->blocks, c->failing[i]));
        printf("           %s\n", line);
    }
    if (c->n_failing > MAX_LISTED) {
        printf("           ... and %d more (see the error map)\n", c->n_failing - MAX_LISTED);
    }
    if (compare_bias_hint_applies(c)) {
        print_wrapped("hint       ", compare_bias_hint);
    }
    char alarms[1024];
    compare_format_alarms(alarms, sizeof alarms, c);
    if (alarms[0]) {
        print_wrapped("alarms     ", alarms);
    }
    char power[512];
    compare_format_power(power, sizeof power, c);
    if (power[0]) {
        print_wrapped("power      ", power);
    }
}

/* The error map of c (failing blocks outlined) into map. */
static bool
draw_map(const struct comparison *c, double range, struct image *map, struct diag *err)
{
    struct errmap_box *boxes = malloc((size_t)(c->n_failing ? c->n_failing : 1) * sizeof *boxes);
    if (!boxes) {
        diag_set(err, NULL, 0, 0, "out of memory");
        return false;
    }
    for (int i = 0; i < c->n_failing; i++) {
        const struct metrics_block *b = metrics_block_test(&c->blocks, c->failing[i]);
        boxes[i] = (struct errmap_box){b->x0, b->y0, b->w, b->h};
    }
    bool ok = errmap_draw(&c->render, &c->reference, range, c->mask, boxes, c->n_failing, map, err);
    free(boxes);
    return ok;
}

/* --regions: the error of each region of the feature pass; its tests are
 * one family with the block tests, whose number they are told. */
static bool
compare_regions(struct args *a, struct diag *err)
{
    struct comparison *c = &a->c;
    int block_tests = c->noise == NOISE_NONE
                          ? 0
                          : 3 * metrics_block_test_count(
                                    c->render.width,
                                    c->render.height,
                                    c->block_size,
                                    true);
    struct image labels = {0};
    /* An EXR written with --aov holds the pass as its layer "feature". */
    bool layered = image_format_from_path(a->regions_path) == IMAGE_FORMAT_EXR;
    if (!(layered ? imgread_layer(a->regions_path, "feature", &labels, err)
                  : imgread(a->regions_path, &labels, err))) {
        return false;
    }
    const struct region_inputs in = {
        .render = &c->render,
        .variance = &c->variance,
        .pixel_dof = c->pixel_dof,
        .reference = &c->reference,
        .ref_rel_se = c->ref_rel_se,
        .ref_dof = c->ref_dof,
        .labels = &labels,
        .mask = c->mask,
        .block_size = c->block_size,
        .alpha = c->alpha,
        .other_tests = block_tests,
        .max_relmse = c->max_relmse,
    };
    bool ok = regions_compare(&in, &a->regions, err);
    regions_sort(&a->regions);
    c->regions = ok ? &a->regions : NULL;
    if (!ok) {
        char why[sizeof err->msg];
        snprintf(why, sizeof why, "%s", err->msg);
        diag_set(err, a->regions_path, 0, 0, "--regions: %s", why);
    }
    image_free(&labels);
    return ok;
}

/* One line per region, the biased ones first (most significant first),
 * each with a pixel to replay. */
static void
print_regions(const struct args *a)
{
    const struct region_report *rep = &a->regions;
    int biased = 0;
    for (int i = 0; i < rep->n_regions; i++) {
        biased += rep->regions[i].biased;
    }
    if (rep->noise) {
        printf(
            "regions    %d of %d biased, by the reference's feature pass %s (t-tests of each "
            "region and of its part in each block)\n",
            biased,
            rep->n_regions,
            a->regions_path);
    } else if (rep->max_relmse > 0) {
        printf(
            "regions    %d of %d over the limit, by the reference's feature pass %s (relMSE per "
            "region; one render: noise not told from bias)\n",
            biased,
            rep->n_regions,
            a->regions_path);
    } else {
        printf(
            "regions    %d, by the reference's feature pass %s (relMSE per region; one render: "
            "noise not told from bias)\n",
            rep->n_regions,
            a->regions_path);
    }
    for (int i = 0; i < rep->n_regions; i++) {
        const struct region_result *r = &rep->regions[i];
        char name[32], line[512];
        regions_describe(line, sizeof line, r, rep);
        printf(
            "  %-12s %7zu px: %s\n",
            regions_label_name(r->label, name, sizeof name),
            r->n_pixels,
            line);
        if (r->biased && r->pixel_x >= 0) {
            printf(
                "  %-12s replay pixel %d,%d: render --pixel %d,%d --trace - SCENE\n",
                "",
                r->pixel_x,
                r->pixel_y,
                r->pixel_x,
                r->pixel_y);
        }
    }
}

/* --map and --html: two files, neither one of the inputs (output_check.h,
 * as render checks its outputs: by file identity, before any work). */
static bool
check_outputs(const struct args *a, struct diag *err)
{
    struct named_file outputs[2], inputs[MAX_RENDERS + 4];
    char meta[4096];
    int n_out = 0, n_in = 0;
    if (a->map_path) {
        outputs[n_out++] = (struct named_file){"--map", a->map_path};
    }
    if (a->html_path) {
        outputs[n_out++] = (struct named_file){"--html", a->html_path};
    }
    for (int j = 0; j < a->c.k; j++) {
        inputs[n_in++] = (struct named_file){"the render", a->c.render_paths[j]};
    }
    inputs[n_in++] = (struct named_file){"the reference", a->c.reference_path};
    meta_beside(a->c.reference_path, meta, sizeof meta);
    inputs[n_in++] = (struct named_file){"the reference's META.json", meta};
    if (a->c.variance_path) {
        inputs[n_in++] = (struct named_file){"--variance", a->c.variance_path};
    }
    if (a->regions_path) {
        inputs[n_in++] = (struct named_file){"--regions", a->regions_path};
    }
    return output_check(outputs, n_out, inputs, n_in, err) == OUTPUTS_OK;
}

static bool
run(struct args *a, struct diag *err)
{
    struct comparison *c = &a->c;
    if (!check_outputs(a, err)) {
        return false;
    }
    if (!a->ref_se_given) {
        reference_noise_from_meta(c);
    }
    if (!load_inputs(c, err)) {
        return false;
    }
    if (a->smooth_mask) {
        c->mask = metrics_smooth_mask(&c->reference, METRICS_SMOOTH_TOLERANCE, &c->n_masked, err);
        if (!c->mask) {
            return false;
        }
    }
    if (!metrics_compare(&c->render, &c->reference, c->mask, &c->m, err)) {
        return false;
    }
    if (a->regions_path && !compare_regions(a, err)) {
        return false;
    }
    if (c->noise != NOISE_NONE && !test_blocks(c, a->regions_path ? a->regions.n_tests : 0, err)) {
        return false;
    }
    find_worst(c);
    decide(c);
    c->map_range = a->range > 0 ? a->range : errmap_auto_range(&c->render, &c->reference);
    struct image map = {0};
    bool ok = true;
    if (a->map_path || a->html_path) {
        ok = draw_map(c, c->map_range, &map, err);
    }
    ok = ok && (!a->map_path || image_write(&map, a->map_path, err));
    ok = ok && (!a->html_path || compare_write_html(c, &map, a->html_path, err));
    image_free(&map);
    return ok;
}

static void
release(struct comparison *c)
{
    image_free(&c->render);
    image_free(&c->reference);
    image_free(&c->variance);
    metrics_block_stats_free(&c->blocks);
    free(c->failing);
    free(c->mask);
}

int
main(int argc, char **argv)
{
    static struct args a;
    int status = parse_args(argc, argv, &a);
    if (status == 1) {
        usage(stdout);
        return 0;
    }
    if (status == 2) {
        fputs(usage_line, stderr);
        return COMPARE_BAD_INPUT;
    }
    struct diag err = {0};
    if (!run(&a, &err)) {
        diag_print(stderr, &err, "error");
        release(&a.c);
        return COMPARE_BAD_INPUT;
    }
    if (a.quiet) {
        char power[512];
        compare_format_power(power, sizeof power, &a.c);
        printf("%s\n%s%s%s", a.c.verdict, power[0] ? "power: " : "", power, power[0] ? "\n" : "");
    } else {
        print_text(&a.c);
    }
    status = a.c.status;
    if (a.regions_path) {
        print_regions(&a);
        for (int i = 0; i < a.regions.n_regions; i++) {
            status = a.regions.regions[i].biased ? COMPARE_BIASED : status;
        }
    }
    release(&a.c);
    return fflush(stdout) == 0 && !ferror(stdout) ? status : COMPARE_BAD_INPUT;
}
