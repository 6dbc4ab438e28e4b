/*
 * render.h - the extremes battery's black-box machinery, header-only (like
 * expect.h), for the programs that render scenes with the stage's binary
 * (RENDER) and, when it is given, with the same stage built with REAL=float
 * (RENDER_FLOAT; its cases are skipped otherwise): 01_extremes_render.c
 * (every stage), 04-06_extremes_glass.c (glass in the Whitted stages) and
 * 07_extremes_paths.c (interreflection and glass in the path tracer; the
 * glass cases are in glass.h).  Each case is judged
 * against tests/extremes/expect.tsv (expect.h); each program keeps the
 * cases of the stage whose feature they check, so a lab handout's stubs
 * fail only its own stage's files.
 *
 * Here: the image size, the precisions, the command lines of each stage,
 * renders and their comparison (judge_same), the Cornell box transformed
 * (cornell_scene), the case table (RUN_CASES), a pinhole camera for
 * analytic pixel values.  Define TAG (the program's name in the results
 * log) before including it.
 *
 * Images are 32 x 31 pixels (an odd W + H: no pixel centre lies exactly on
 * the diagonal corner edges of the symmetric Cornell box, where the floor
 * and a wall tie and rounding alone decides which is seen).  Stages 06 and
 * 07 take one sample at each pixel centre (--aa grid --spp 1) wherever a
 * per-pixel analytic value is compared; elsewhere their defaults, 07 with
 * 16 samples.  Every render of every case must report nan_pixels 0.
 *
 * "Equals" is relMSE (metrics.h) under 1e-4: a single pixel wholly wrong
 * (acne, a light leak, a hole) is 1e-3 on its own.  Pixels off by more than
 * 10% are counted for the note.
 * Stage 07's paths branch on computed values (Russian roulette, the BSDF
 * lobe), so a rounding difference sends a path elsewhere and the images of
 * a float build differ by noise: for 07 the bound is the relMSE between two
 * seeds of the unit box, with a paired t-test on the mean difference.
 */
#ifndef EXTREMES_RENDER_H
#define EXTREMES_RENDER_H

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "extremes/expect.h"
#include "image.h"
#include "metrics.h"
#include "stagecheck.h"
#include "stattest.h"
#include "testlib.h"

#ifndef TAG
#error "define TAG, the program's name in the extremes log, before including extremes/render.h"
#endif

/* The image size, as numbers and as command-line words. */
#define FRAME_W 32
#define FRAME_H 31
#define PIXELS (FRAME_W * FRAME_H)
#define WORD(x) #x
#define AS_WORD(x) WORD(x)
#define WIDTH AS_WORD(FRAME_W)
#define HEIGHT AS_WORD(FRAME_H)

#define PI_D 3.14159265358979323846

/* relMSE below which two renders are the same image (the issue's bound). */
#define SAME_RELMSE 1e-4

/* A pixel off by more than this (relative, any channel) is an artefact. */
#define ARTEFACT_TOLERANCE 0.1

/* Significance of the paired t-test of stage 07's comparisons, per case
 * (about 20 such cases per precision: a family level of ~2%). */
#define T_TEST_ALPHA 1e-3

/* ---- precisions --------------------------------------------------------- */

struct precision {
    const char *name; /* "double" or "float", as in expect.tsv */
    const char *binary; /* NULL: not available */
    double epsilon; /* REAL_EPSILON of that build */
};

static struct precision precisions[2];

/* RENDER is this build's binary: double, unless the tests themselves are
 * built with REAL=float (then there is no second precision to run). */
static inline void
init_precisions(void)
{
#ifdef REAL_IS_FLOAT
    precisions[0] = (struct precision){"float", test_render_binary(), 0x1p-23};
    precisions[1] = (struct precision){"double", NULL, 0x1p-52};
#else
    precisions[0] = (struct precision){"double", test_render_binary(), 0x1p-52};
    precisions[1] = (struct precision){"float", test_render_float_binary(), 0x1p-23};
#endif
}

/* testlib runs the binary RENDER names: point it at this precision's. */
static inline void
use_precision(const struct precision *p)
{
    setenv("RENDER", p->binary, 1);
}

static inline int
stage(void)
{
    return expect_stage();
}

/* ---- command lines ----------------------------------------------------- */

#define MAX_ARGS 24

struct args {
    const char *v[MAX_ARGS];
    int n;
};

static inline void
args_add(struct args *a, const char *const *list)
{
    for (int i = 0; list && list[i] && a->n < MAX_ARGS - 1; i++) {
        a->v[a->n++] = list[i];
    }
    a->v[a->n] = NULL;
}

/* The image size, plus what the stage needs to take one ray through each
 * pixel centre (centre) or its usual samples (not centre). */
static inline struct args
base_args(bool centre)
{
    static const char *const size[] = {"-W", WIDTH, "-H", HEIGHT, NULL};
    static const char *const one_centre_sample[] = {"--aa", "grid", "--spp", "1", NULL};
    /* The independent sampler, not 08's default Sobol: after two renders
     * of one seed part at a rounding, the Sobol sampler still gives both
     * the same numbers (drawn per depth and use, not from a stream), so
     * the pair stays correlated and the paired t-test below finds
     * differences far below the noise bound it is meant to judge against
     * (a 1e-6 shift of a light in a plane: p 1e-21 at relMSE 2e-4). */
    static const char *const path_samples[] =
        {"--spp", "16", "--sampler", "independent", "--aa", "jitter", NULL};
    static const char *const path_samples_07[] = {"--spp", "16", NULL};
    struct args a = {.n = 0};
    args_add(&a, size);
    if (stage() >= 6 && centre) {
        args_add(&a, one_centre_sample);
    } else if (stage() >= 8) {
        args_add(&a, path_samples);
    } else if (stage() >= 7) {
        args_add(&a, path_samples_07);
    }
    return a;
}

/* Stage 07 with direct light only (camera ray plus one shadow ray): the
 * analytic scenes below count only that. */
static inline struct args
direct_args(void)
{
    static const char *const direct[] = {"--max-depth", "2", NULL};
    struct args a = base_args(true);
    if (stage() >= 7) {
        args_add(&a, direct);
    }
    return a;
}

/* ---- renders ------------------------------------------------------------ */

/* The case and precision running, for keep_scene. */
static const char *current_case = "";
static const char *current_precision = "";

/* With EXTREMES_SCENES set to a directory, every scene rendered is copied
 * there as CASE-PRECISION-NAME.scene (tests/extremes/images.sh renders the
 * documentation's images from them). */
static inline void
keep_scene(const char *scene)
{
    const char *dir = getenv("EXTREMES_SCENES");
    if (!dir || !dir[0] || !scene) {
        return;
    }
    char *text = test_read_file(scene, NULL);
    const char *base = strrchr(scene, '/');
    char path[1024];
    snprintf(
        path,
        sizeof path,
        "%s/%s-%s-%s",
        dir,
        current_case,
        current_precision,
        base ? base + 1 : scene);
    if (!text || !test_write_file(path, text)) {
        printf("cannot keep %s as %s\n", scene, path);
    }
    free(text);
}

/* One render; false (with the output printed) when it fails.  *nan gets its
 * nan_pixels. */
static inline bool
render(const char *scene, const struct args *a, struct image *img, double *nan)
{
    const char *stats = NULL;
    *img = (struct image){0};
    keep_scene(scene);
    if (!scene || !stagecheck_render(scene, a->v, img, &stats)) {
        return false;
    }
    *nan = stagecheck_stat(stats, "nan_pixels");
    return true;
}

/* Run the binary on a scene that may be refused or crash (with the small
 * image size); returns the exit status and leaves the output in `out`. */
static inline int
run_scene(const char *scene, char *out, size_t cap)
{
    keep_scene(scene);
    struct args a = base_args(true);
    const char *const output[] = {"-o", test_tmp_path("run.pfm"), NULL};
    args_add(&a, output);
    return test_render(scene, a.v, out, cap);
}

/* Pixels of mask (NULL: all) where some channel of x is off from ref by
 * more than ARTEFACT_TOLERANCE relative (with a floor of 1e-3 of ref's
 * brightest). */
static inline int
artefact_pixels(const struct image *x, const struct image *ref, const unsigned char *mask)
{
    float peak = 0;
    for (int i = 0; i < ref->width * ref->height * 3; i++) {
        peak = fmaxf(peak, ref->rgb[i]);
    }
    int n = 0;
    for (int y = 0; y < ref->height; y++) {
        for (int px = 0; px < ref->width; px++) {
            double d = stagecheck_pixel_reldiff(
                image_pixel(x, px, y),
                image_pixel(ref, px, y),
                1e-3 * peak);
            n += (!mask || mask[y * ref->width + px]) && !(d <= ARTEFACT_TOLERANCE);
        }
    }
    return n;
}

/* Paired t-test of the per-pixel differences x - ref (mean over channels)
 * on the pixels of mask (NULL: all):
 * the p-value of "the images have the same mean". */
static inline double
paired_p(const struct image *x, const struct image *ref, const unsigned char *mask)
{
    struct stattest_welford w = {0};
    for (int i = 0; i < ref->width * ref->height; i++) {
        if (mask && !mask[i]) {
            continue;
        }
        const float *a = &x->rgb[3 * i];
        const float *b = &ref->rgb[3 * i];
        stattest_welford_add(&w, ((double)a[0] + a[1] + a[2] - b[0] - b[1] - b[2]) / 3);
    }
    return stattest_t_test_welford_one_sample(&w, 0).p;
}

/* Compare a render with the image it must equal, on the pixels of mask
 * (NULL: all): relMSE (the figure; one pixel wholly wrong in 992 is 1e-3,
 * so a single acne or hole pixel fails), the artefact pixels for the note,
 * and for stage 07 the noise bound and the t-test. */
static inline void
judge_same(
    const struct image *x,
    const struct image *ref,
    const unsigned char *mask,
    double noise,
    double nan,
    struct outcome *o)
{
    o->figure = metrics_relmse(x, ref, mask);
    int artefacts = artefact_pixels(x, ref, mask);
    if (stage() >= 7 && o->figure > SAME_RELMSE) {
        /* Paths that went elsewhere: no worse than a second seed, and no
         * difference in the mean (the t-test is only asked here: two
         * images equal to 1e-12 differ "significantly" by rounding). */
        double p = paired_p(x, ref, mask);
        double limit = fmax(SAME_RELMSE, noise);
        o->passed = o->figure <= limit && p >= T_TEST_ALPHA && nan == 0;
        snprintf(
            o->note,
            sizeof o->note,
            "relMSE %.3g (limit %.3g: two seeds' noise %.3g), paired t-test p %.3g, "
            "pixels off by > 10%%: %d, nan_pixels %g",
            o->figure,
            limit,
            noise,
            p,
            artefacts,
            nan);
        return;
    }
    o->passed = o->figure <= SAME_RELMSE && nan == 0;
    snprintf(
        o->note,
        sizeof o->note,
        "relMSE %.3g, pixels off by > 10%%: %d, nan_pixels %g",
        o->figure,
        artefacts,
        nan);
}

/* ---- the Cornell box, transformed ---------------------------------------- */

/* How to change a Cornell box (scenes/cornell_diffuse_area.scene unless
 * `source` names another): every point p becomes scale p + translate
 * (1, 1, 1), every length is scaled, radiances are multiplied, albedos
 * replaced when albedo >= 0, and a statement whose keyword starts one of
 * the `replace` lines is replaced by that line (untransformed). */
struct edit {
    double scale;
    double translate;
    double radiance;
    double albedo;
    const char *source;
    const char *replace[3];
};

static const struct edit unit_box = {1, 0, 1, -1, NULL, {NULL}};

static inline bool
is_word(const char *w, const char *const *list)
{
    for (int i = 0; list[i]; i++) {
        if (strcmp(w, list[i]) == 0) {
            return true;
        }
    }
    return false;
}

/* Append to buf what `word` followed by its numbers becomes; *p points
 * past the word in the line and is advanced past the numbers used. */
static inline void
edit_field(const char *word, char **p, const struct edit *e, char *buf, size_t cap)
{
    static const char *const points[] =
        {"origin", "target", "center", "corner", "position", "v0", "v1", "v2", NULL};
    static const char *const vectors[] = {"edge1", "edge2", NULL};
    static const char *const lengths[] = {"radius", "size", NULL};
    int count = is_word(word, points) || is_word(word, vectors) || strcmp(word, "radiance") == 0
                        || strcmp(word, "albedo") == 0
                    ? 3
                : is_word(word, lengths) ? 1
                                         : 0;
    for (int k = 0; k < count; k++) {
        double v = strtod(*p, p);
        if (is_word(word, points)) {
            v = e->scale * v + e->translate;
        } else if (is_word(word, vectors) || is_word(word, lengths)) {
            v *= e->scale;
        } else if (strcmp(word, "radiance") == 0) {
            v *= e->radiance;
        } else if (e->albedo >= 0) {
            v = e->albedo;
        }
        size_t len = strlen(buf);
        snprintf(buf + len, cap - len, " %.17g", v);
    }
}

/* The line of e->replace that replaces a statement starting with `word`. */
static inline const char *
replacement(const struct edit *e, const char *word)
{
    for (int i = 0; i < 3 && e->replace[i]; i++) {
        size_t n = strlen(word);
        if (strncmp(e->replace[i], word, n) == 0 && e->replace[i][n] == ' ') {
            return e->replace[i];
        }
    }
    return NULL;
}

/* The edited box as a scene file called `name`. */
static inline const char *
cornell_scene(const char *name, const struct edit *e)
{
    const char *source = e->source ? e->source : "scenes/cornell_diffuse_area.scene";
    char *text = test_read_file(test_root_path(source), NULL);
    static char out[16384];
    out[0] = '\0';
    for (char *line = text ? strtok(text, "\n") : NULL; line; line = strtok(NULL, "\n")) {
        line[strcspn(line, "#")] = '\0';
        char *p = line;
        char word[64];
        int used;
        size_t len = strlen(out);
        if (sscanf(p, " %63s", word) == 1 && replacement(e, word)) {
            snprintf(out + len, sizeof out - len, "%s\n", replacement(e, word));
            continue;
        }
        while (sscanf(p, " %63s%n", word, &used) == 1) {
            p += used;
            len = strlen(out);
            snprintf(
                out + len,
                sizeof out - len,
                "%s%s",
                len && out[len - 1] != '\n' ? " " : "",
                word);
            edit_field(word, &p, e, out, sizeof out);
        }
        len = strlen(out);
        snprintf(out + len, sizeof out - len, "\n");
    }
    free(text);
    return text ? stagecheck_scene(name, "%s", out) : NULL;
}

/* The unit box of this precision, and for stage 07 the relMSE between two
 * seeds of it (the noise); rendered once per precision. */
static inline bool
unit_reference(const struct precision *p, struct image *out, double *noise)
{
    static struct image cache[2];
    static double noise_cache[2];
    int k = p == &precisions[0] ? 0 : 1;
    if (!cache[k].rgb) {
        struct args a = base_args(false);
        double nan = 0;
        const char *scene = cornell_scene("unit.scene", &unit_box);
        if (!render(scene, &a, &cache[k], &nan) || nan != 0) {
            image_free(&cache[k]);
            return false;
        }
        noise_cache[k] = 0;
        if (stage() >= 7) {
            static const char *const seed2[] = {"--seed", "2", NULL};
            struct image other;
            args_add(&a, seed2);
            if (render(scene, &a, &other, &nan)) {
                noise_cache[k] = metrics_relmse(&other, &cache[k], NULL);
                image_free(&other);
            }
        }
    }
    *out = cache[k];
    *noise = noise_cache[k];
    return true;
}

/* The noise bound of stage 07's comparisons in this precision (0 before
 * 07; infinite when the unit box cannot be rendered: the case then fails
 * on its own render). */
static inline double
noise_of(const struct precision *p)
{
    struct image unit;
    double noise = 0;
    if (stage() >= 7 && !unit_reference(p, &unit, &noise)) {
        noise = INFINITY;
    }
    return noise;
}

/* Render the edited box and compare it with the unit box, after dividing
 * by the radiance factor. */
static inline void
compare_with_unit(
    const char *case_name,
    const struct edit *e,
    const struct precision *p,
    struct outcome *o)
{
    struct image ref;
    struct image x;
    double noise;
    double nan = 0;
    char name[128];
    snprintf(name, sizeof name, "%s.scene", case_name);
    struct args a = base_args(false);
    if (!unit_reference(p, &ref, &noise) || !render(cornell_scene(name, e), &a, &x, &nan)) {
        o->figure = INFINITY;
        snprintf(o->note, sizeof o->note, "render failed");
        return;
    }
    for (int i = 0; i < x.width * x.height * 3; i++) {
        x.rgb[i] = (float)((double)x.rgb[i] / e->radiance);
    }
    judge_same(&x, &ref, NULL, noise, nan, o);
    image_free(&x);
}

/* ---- the cases' table ---------------------------------------------------- */

struct render_case {
    const char *name;
    void (*run)(const struct render_case *c, const struct precision *p, struct outcome *o);
    double param; /* the case's number: a scale, an angle, an index ... */
    double offset; /* and, for some, a distance from the origin */
};

/* Run each case for each precision the table does not skip. */
static inline void
run_cases(const struct render_case *cases, size_t n)
{
    if (!precisions[0].name) {
        init_precisions();
    }
    for (size_t i = 0; i < n; i++) {
        for (int k = 0; k < 2; k++) {
            const struct precision *p = &precisions[k];
            struct expectation e;
            expect_lookup(cases[i].name, p->name, &e);
            if (e.kind == EXPECT_SKIP) {
                expect_log_skip(TAG, cases[i].name, p->name, e.reason);
                continue;
            }
            if (!p->binary) {
                expect_log_skip(TAG, cases[i].name, p->name, "no such build given (RENDER_FLOAT)");
                continue;
            }
            use_precision(p);
            current_case = cases[i].name;
            current_precision = p->name;
            struct outcome o = {.figure = NAN};
            cases[i].run(&cases[i], p, &o);
            expect_judge(TAG, cases[i].name, p->name, &o);
        }
    }
    use_precision(&precisions[0]);
}

#define RUN_CASES(table) run_cases(table, sizeof table / sizeof table[0])

/* ---- a pinhole camera, for analytic pixel values ------------------------- */

/* The camera of docs/scene-format.md (camera.h): pixel (px, py)'s centre
 * ray, in double from the scene's numbers. */
struct pinhole {
    double origin[3], forward[3], right[3], up[3];
    double half_w, half_h;
    int w, h;
};

static inline struct pinhole
pinhole_make(const double origin[3], const double target[3], const double up[3], double fov)
{
    struct pinhole c = {.w = FRAME_W, .h = FRAME_H};
    for (int i = 0; i < 3; i++) {
        c.origin[i] = origin[i];
        c.forward[i] = target[i] - origin[i];
    }
    stagecheck_normalize3(c.forward);
    stagecheck_cross3(c.forward, up, c.right);
    stagecheck_normalize3(c.right);
    stagecheck_cross3(c.right, c.forward, c.up);
    c.half_h = tan(fov * PI_D / 360);
    c.half_w = c.half_h * c.w / c.h;
    return c;
}

/* Unit direction of the ray through pixel (px, py)'s centre. */
static inline void
pinhole_ray(const struct pinhole *c, int px, int py, double d[3])
{
    double x = (2 * (px + 0.5) / c->w - 1) * c->half_w;
    double y = (1 - 2 * (py + 0.5) / c->h) * c->half_h;
    for (int i = 0; i < 3; i++) {
        d[i] = c->forward[i] + x * c->right[i] + y * c->up[i];
    }
    stagecheck_normalize3(d);
}

/* Where o + t d meets the sphere (centre, radius) first with t > 0; -1 on a
 * miss.  Plain double: the expected values need not be exact to 1e-16. */
static inline double
sphere_t(const double o[3], const double d[3], const double center[3], double radius)
{
    double f[3] = {o[0] - center[0], o[1] - center[1], o[2] - center[2]};
    double b = stagecheck_dot3(f, d);
    double c = stagecheck_dot3(f, f) - radius * radius;
    double disc = b * b - c;
    if (disc < 0) {
        return -1;
    }
    double t0 = -b - sqrt(disc);
    double t1 = -b + sqrt(disc);
    return t0 > 0 ? t0 : t1 > 0 ? t1 : -1;
}

/* Largest relative error of the image against the expected radiance per
 * pixel (expected[] holds one value per pixel and channel 0; pixels with a
 * negative expected value are not compared), and how many pixels are off
 * by more than `bad` relative. */
static inline double
worst_pixel_error(const struct image *img, const double *expected, double bad, int *n_bad)
{
    double worst = 0;
    *n_bad = 0;
    for (int y = 0; y < img->height; y++) {
        for (int x = 0; x < img->width; x++) {
            double e = expected[y * img->width + x];
            if (e < 0) {
                continue;
            }
            double v = image_pixel(img, x, y)[0];
            double err = fabs(v - e) / fmax(e, 1e-30);
            worst = isnan(err) ? INFINITY : fmax(worst, err);
            *n_bad += !(err <= bad);
        }
    }
    return worst;
}

/* Render `scene` with `a` into *img and judge it against expected[] (as
 * worst_pixel_error, `bad` the tolerance): o->figure the worst relative
 * error, passed when no pixel is off by more than `bad` and none is NaN,
 * the note naming the `counted` pixels (e.g. "412 sphere pixels"); *nan
 * the image's NaN pixels.  False when the render failed (o->figure
 * infinite, nothing to free); otherwise the caller frees *img. */
static inline bool
render_judged(
    const char *scene,
    const struct args *a,
    const double *expected,
    double bad,
    const char *counted,
    struct outcome *o,
    struct image *img,
    double *nan)
{
    if (!render(scene, a, img, nan)) {
        o->figure = INFINITY;
        return false;
    }
    int n_bad;
    o->figure = worst_pixel_error(img, expected, bad, &n_bad);
    o->passed = n_bad == 0 && *nan == 0;
    snprintf(
        o->note,
        sizeof o->note,
        "worst relative error %.3g (%s); pixels off by > %g: %d; nan_pixels %g",
        o->figure,
        counted,
        bad,
        n_bad,
        *nan);
    return true;
}

/* ---- the albedo extremes --------------------------------------------------- */

/* The box with every albedo set to `albedo`, one ray per pixel centre. */
static inline bool
render_albedo(double albedo, struct image *img, double *nan)
{
    char name[64];
    snprintf(name, sizeof name, "albedo_%g.scene", albedo);
    struct edit e = {1, 0, 1, albedo, NULL, {NULL}};
    struct args a = base_args(true);
    return render(cornell_scene(name, &e), &a, img, nan);
}

/* The box at albedo 1 and at albedo 0.5, each less the box at albedo 0 (the
 * light's own pixels), the second doubled; nan: the three renders'
 * nan_pixels; finite: whether `one` is finite everywhere. */
struct albedo_pair {
    struct image one, twice_half;
    double nan;
    bool finite;
};

/* Render the pair; false, with o's figure infinite and nothing to free,
 * when a render fails. */
static inline bool
render_albedo_pair(struct albedo_pair *pair, struct outcome *o)
{
    struct image zero;
    double nans[3] = {0, 0, 0};
    *pair = (struct albedo_pair){.finite = true};
    if (!render_albedo(1, &pair->one, &nans[0]) || !render_albedo(0.5, &pair->twice_half, &nans[1])
        || !render_albedo(0, &zero, &nans[2])) {
        image_free(&pair->one);
        image_free(&pair->twice_half);
        o->figure = INFINITY;
        return false;
    }
    for (int i = 0; i < 3 * pair->one.width * pair->one.height; i++) {
        pair->one.rgb[i] -= zero.rgb[i];
        pair->twice_half.rgb[i] = 2 * (pair->twice_half.rgb[i] - zero.rgb[i]);
        pair->finite = pair->finite && isfinite(pair->one.rgb[i]);
    }
    pair->nan = nans[0] + nans[1] + nans[2];
    image_free(&zero);
    return true;
}

static inline void
albedo_pair_free(struct albedo_pair *pair)
{
    image_free(&pair->one);
    image_free(&pair->twice_half);
}

/* Why the second precision is not run, or NULL. */
static inline const char *
second_precision_missing(void)
{
    init_precisions();
#ifdef REAL_IS_FLOAT
    return "tests built with REAL=float: the double cases run in the double build";
#else
    return precisions[1].binary ? NULL
                                : "RENDER_FLOAT unset or missing: the float cases are skipped "
                                  "(make REAL=float)";
#endif
}

/* The body of every black-box program's first test,
 * second_precision_given: it is skipped (SKIP returns from the test) when
 * the second precision is not run, so that the program's closing line
 * shows that half of its cases did not run. */
#define SKIP_WITHOUT_SECOND_PRECISION() \
    do { \
        const char *why_ = second_precision_missing(); \
        if (why_) { \
            SKIP(why_); \
        } \
    } while (0)

#endif /* EXTREMES_RENDER_H */
