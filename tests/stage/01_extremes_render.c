/*
 * 01_extremes_render.c - the extremes battery, black-box part: scenes at
 * the edges of floating point rendered by the stage's binary (RENDER) and,
 * when it is given, by the same stage built with REAL=float (RENDER_FLOAT;
 * its cases are skipped otherwise), each case judged against
 * tests/extremes/expect.tsv (tests/extremes/expect.h).  docs/extremes.md
 * describes every case and shows the table of the last run.
 *
 * Images are 32 x 31 pixels (an odd W + H: no pixel centre lies exactly on
 * the diagonal corner edges of the symmetric Cornell box, where the floor
 * and a wall tie and rounding alone decides which is seen).  Stages 06 and
 * 07 take one sample at each pixel centre (--aa grid --spp 1) wherever a
 * per-pixel analytic value is compared; elsewhere their defaults, 07 with
 * 16 samples.  Every render of every case must report nan_pixels 0.
 *
 * The families (one test each):
 *  - scale: the area-light Cornell box scaled by 1e-6 .. 1e6 equals the
 *    unit box (radiance does not depend on units);
 *  - far: the same box translated by 1e1 .. 1e7 along (1, 1, 1);
 *  - acne: a tilted plane under a point light 1 and 0.01 degrees above it,
 *    pixel by pixel against the analytic radiance;
 *  - inside: a camera inside a sphere with a point light at its centre sees
 *    a uniform radiance albedo I / (pi R^2);
 *  - thin glass: a glass slab 1e-5 thick before an area light, pixel by
 *    pixel against the Fresnel transmittance;
 *  - watertight: a closed mesh whose vertices lie on pixel-centre rays, so
 *    every pixel centre is aimed exactly at a vertex or an edge;
 *  - degenerate: zero-area triangles and quads crossed by whole rows of
 *    pixel rays, a zero and a tiny sphere, a zero-area light, lights on a
 *    surface, cameras with the target at (or next to) the origin and with a
 *    huge or tiny up vector;
 *  - optics: a glass sphere of index 1, 1.0001, 2.42 and 10 in a white
 *    furnace, pixel by pixel against the Fresnel series;
 *  - radiance: light radiance 1e-20 and 1e20, albedo 0 and 1.
 *
 * "Equals" is relMSE (metrics.h) under 1e-4: a single pixel wholly wrong
 * (acne, a light leak, a hole) is 1e-3 on its own.  Pixels off by more than
 * 10% are counted for the note.
 * Stage 07's paths branch on computed values (Russian roulette, the BSDF
 * lobe), so a rounding difference sends a path elsewhere and the images of
 * a float build differ by noise: for 07 the bound is the relMSE between two
 * seeds of the unit box, with a paired t-test on the mean difference.
 */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "extremes/expect.h"
#include "image.h"
#include "meshgen.h"
#include "metrics.h"
#include "stagecheck.h"
#include "stattest.h"
#include "testlib.h"

#define TAG "render"

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
static void
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
static void
use_precision(const struct precision *p)
{
    setenv("RENDER", p->binary, 1);
}

static int
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

static void
args_add(struct args *a, const char *const *list)
{
    for (int i = 0; list && list[i] && a->n < MAX_ARGS - 1; i++) {
        a->v[a->n++] = list[i];
    }
    a->v[a->n] = NULL;
}

/* The image size, plus what the stage needs to take one ray through each
 * pixel centre (centre) or its usual samples (not centre). */
static struct args
base_args(bool centre)
{
    static const char *const size[] = {"-W", WIDTH, "-H", HEIGHT, NULL};
    static const char *const one_centre_sample[] = {"--aa", "grid", "--spp", "1", NULL};
    static const char *const path_samples[] = {"--spp", "16", NULL};
    struct args a = {.n = 0};
    args_add(&a, size);
    if (stage() >= 6 && centre) {
        args_add(&a, one_centre_sample);
    } else if (stage() >= 7) {
        args_add(&a, path_samples);
    }
    return a;
}

/* Stage 07 with direct light only (camera ray plus one shadow ray): the
 * analytic scenes below count only that. */
static struct args
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
static void
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
static bool
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
static int
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
static int
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
static double
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
static void
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

static bool
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
static void
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
static const char *
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
static const char *
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
static bool
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
static double
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
static void
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
static void
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

/* ---- scale and translation ----------------------------------------------- */

static void
run_scale(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    struct edit e = {c->param, 0, 1, -1, NULL, {NULL}};
    compare_with_unit(c->name, &e, p, o);
}

static void
run_far(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    struct edit e = {1, c->param, 1, -1, NULL, {NULL}};
    compare_with_unit(c->name, &e, p, o);
}

TEST(scale)
{
    static const struct render_case cases[] = {
        {"scale_1e-6", run_scale, 1e-6, 0},
        {"scale_1e-3", run_scale, 1e-3, 0},
        {"scale_1e3", run_scale, 1e3, 0},
        {"scale_1e6", run_scale, 1e6, 0},
    };
    RUN_CASES(cases);
}

TEST(far_from_origin)
{
    static const struct render_case cases[] = {
        {"far_1e1", run_far, 1e1, 0},
        {"far_1e2", run_far, 1e2, 0},
        {"far_1e3", run_far, 1e3, 0},
        {"far_1e4", run_far, 1e4, 0},
        {"far_1e5", run_far, 1e5, 0},
        {"far_1e6", run_far, 1e6, 0},
        {"far_1e7", run_far, 1e7, 0},
    };
    RUN_CASES(cases);
}

/* ---- a pinhole camera, for analytic pixel values ------------------------- */

/* The camera of docs/scene-format.md (camera.h): pixel (px, py)'s centre
 * ray, in double from the scene's numbers. */
struct pinhole {
    double origin[3], forward[3], right[3], up[3];
    double half_w, half_h;
    int w, h;
};

static struct pinhole
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
static void
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
static double
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
static double
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

/* ---- acne: grazing light on a tilted plane -------------------------------- */

/* A square plane 2 units across, its normal tilted off the axes, centred
 * c->offset (1, 1, 1) from the origin; a point light 20 units away,
 * c->param degrees above the plane; the camera 3 units above it at 45
 * degrees.  Expected: albedo/pi I cos / r^2 at each pixel's hit point. */
static void
run_acne(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    (void)p;
    double offset = c->offset;
    double n[3] = {0.3, 1, 0.2};
    double t1[3] = {1, -0.3, 0};
    double t2[3];
    stagecheck_normalize3(n);
    stagecheck_cross3(t1, n, t2); /* t1 is not yet orthogonal to n: fix it */
    stagecheck_normalize3(t2);
    stagecheck_cross3(n, t2, t1);
    double center[3] = {offset, offset, offset};
    double corner[3], e1[3], e2[3], light[3], eye[3], target[3];
    double el = c->param * PI_D / 180;
    for (int i = 0; i < 3; i++) {
        corner[i] = center[i] - t1[i] - t2[i];
        e1[i] = 2 * t1[i];
        e2[i] = 2 * t2[i];
        light[i] = center[i] + 20 * (cos(el) * t1[i] + sin(el) * n[i]);
        eye[i] = center[i] + 3 * (n[i] - t1[i]) / sqrt(2.0);
        target[i] = center[i];
    }
    const double intensity = 400;
    const double albedo = 0.5;
    const char *scene = stagecheck_scene(
        "acne.scene",
        "camera origin %.17g %.17g %.17g target %.17g %.17g %.17g up %.17g %.17g %.17g fov 40\n"
        "image width " WIDTH " height " HEIGHT "\n"
        "material m diffuse albedo %g %g %g\n"
        "quad corner %.17g %.17g %.17g edge1 %.17g %.17g %.17g edge2 %.17g %.17g %.17g "
        "material m\n"
        "point_light position %.17g %.17g %.17g intensity %g %g %g\n",
        eye[0],
        eye[1],
        eye[2],
        target[0],
        target[1],
        target[2],
        n[0],
        n[1],
        n[2],
        albedo,
        albedo,
        albedo,
        corner[0],
        corner[1],
        corner[2],
        e1[0],
        e1[1],
        e1[2],
        e2[0],
        e2[1],
        e2[2],
        light[0],
        light[1],
        light[2],
        intensity,
        intensity,
        intensity);
    struct pinhole cam = pinhole_make(eye, target, n, 40);
    double expected[PIXELS];
    for (int py = 0; py < cam.h; py++) {
        for (int px = 0; px < cam.w; px++) {
            double d[3], q[3], l[3];
            pinhole_ray(&cam, px, py, d);
            double to_plane[3] = {center[0] - eye[0], center[1] - eye[1], center[2] - eye[2]};
            double t = stagecheck_dot3(to_plane, n) / stagecheck_dot3(d, n);
            for (int i = 0; i < 3; i++) {
                q[i] = eye[i] + t * d[i];
                l[i] = light[i] - q[i];
            }
            double r2 = stagecheck_dot3(l, l);
            double cos_l = stagecheck_dot3(l, n) / sqrt(r2);
            double qc[3] = {q[0] - center[0], q[1] - center[1], q[2] - center[2]};
            bool inside =
                fabs(stagecheck_dot3(qc, t1)) < 0.98 && fabs(stagecheck_dot3(qc, t2)) < 0.98;
            expected[py * cam.w + px] = inside ? albedo / PI_D * intensity * cos_l / r2 : -1;
        }
    }
    struct image img;
    double nan = 0;
    struct args a = direct_args();
    if (!render(scene, &a, &img, &nan)) {
        o->figure = INFINITY;
        return;
    }
    int n_bad;
    double worst = worst_pixel_error(&img, expected, 0.25, &n_bad);
    o->figure = n_bad;
    o->passed = n_bad == 0 && nan == 0;
    snprintf(
        o->note,
        sizeof o->note,
        "pixels of the plane off by > 25%% (acne): %d; worst relative error %.3g; nan_pixels %g",
        n_bad,
        worst,
        nan);
    image_free(&img);
}

TEST(acne)
{
    static const struct render_case cases[] = {
        {"acne_grazing_1deg", run_acne, 1, 0},
        {"acne_grazing_0.01deg", run_acne, 0.01, 0},
        {"acne_grazing_far", run_acne, 1, 1e4},
    };
    RUN_CASES(cases);
}

/* ---- a sphere seen from inside ---------------------------------------- */

/* The camera inside a diffuse sphere of radius R, a point light of
 * intensity I at its centre: every wall point gets I / R^2 at normal
 * incidence, so every pixel is albedo I / (pi R^2).  R is the case's
 * parameter; the sphere is centred R (1, -2, 3) from the origin, the camera
 * halfway to the wall. */
static void
run_inside(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    (void)p;
    double r = c->param;
    double center[3] = {r, -2 * r, 3 * r};
    const double albedo = 0.5;
    double intensity = r * r; /* so that the expected radiance is 1 / (2 pi) */
    const char *scene = stagecheck_scene(
        "inside.scene",
        "camera origin %.17g %.17g %.17g target %.17g %.17g %.17g up 0 1 0 fov 60\n"
        "image width " WIDTH " height " HEIGHT "\n"
        "material m diffuse albedo %g %g %g\n"
        "sphere center %.17g %.17g %.17g radius %.17g material m\n"
        "point_light position %.17g %.17g %.17g intensity %.17g %.17g %.17g\n",
        center[0] + 0.5 * r,
        center[1],
        center[2],
        center[0] + r,
        center[1] + 0.3 * r,
        center[2] - 0.2 * r,
        albedo,
        albedo,
        albedo,
        center[0],
        center[1],
        center[2],
        r,
        center[0],
        center[1],
        center[2],
        intensity,
        intensity,
        intensity);
    double expected[PIXELS];
    for (int i = 0; i < PIXELS; i++) {
        expected[i] = albedo * intensity / (PI_D * r * r);
    }
    struct image img;
    double nan = 0;
    struct args a = direct_args();
    if (!render(scene, &a, &img, &nan)) {
        o->figure = INFINITY;
        return;
    }
    int n_bad;
    o->figure = worst_pixel_error(&img, expected, 1e-3, &n_bad);
    o->passed = n_bad == 0 && nan == 0;
    snprintf(
        o->note,
        sizeof o->note,
        "worst relative error %.3g; pixels off by > 1e-3: %d; nan_pixels %g",
        o->figure,
        n_bad,
        nan);
    image_free(&img);
}

TEST(sphere_from_inside)
{
    static const struct render_case cases[] = {
        {"inside_sphere_1", run_inside, 1, 0},
        {"inside_sphere_1e-4", run_inside, 1e-4, 0},
        {"inside_sphere_1e4", run_inside, 1e4, 0},
    };
    RUN_CASES(cases);
}

/* ---- glass: exact Fresnel values --------------------------------------- */

/* Fresnel reflectance of unpolarised light at a smooth boundary, from the
 * cosine of incidence and the ratio n = n_t / n_i, written from Snell's
 * law and the amplitude coefficients (Born and Wolf 1.5.2), independently
 * of the stage's optics.c; 1 under total internal reflection. */
static double
fresnel(double cos_i, double n)
{
    double sin_t2 = (1 - cos_i * cos_i) / (n * n);
    if (sin_t2 >= 1) {
        return 1;
    }
    double cos_t = sqrt(1 - sin_t2);
    double rs = (cos_i - n * cos_t) / (cos_i + n * cos_t);
    double rp = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    return (rs * rs + rp * rp) / 2;
}

/* The Whitted depth limit of stages 04-06 (their default --max-depth). */
#define WHITTED_DEPTH 8

/* The glass scenes' command line: one ray through each pixel centre, or,
 * for stage 07, `spp` samples on the pixel-centre grid without Russian
 * roulette, so that a path through glass keeps the weight 1 until it leaves
 * (bsdf.c picks reflection with probability F). */
static struct args
glass_args(const char *spp)
{
    if (stage() < 7) {
        return base_args(true);
    }
    const char *const path[] =
        {"-W", WIDTH, "-H", HEIGHT, "--aa", "grid", "--no-rr", "--spp", spp, NULL};
    struct args a = {.n = 0};
    args_add(&a, path);
    return a;
}

/* ---- a glass sphere in a white furnace ------------------------------------ */

/* A glass sphere of index ior under a uniform background of radiance 1, no
 * lights.  Whitted (04-06): a camera ray meeting the sphere at cos_i gives
 * F + (1 - F)^2 (1 + F + ... + F^(D-3)) for depth limit D (the ray inside
 * a sphere meets it again at the refracted angle, where the reflectance is
 * the same F); 07: exactly 1 (nothing absorbs, every path leaves).  Stages
 * 01-03 shade glass as white diffuse: the sphere is black there. */
static void
run_furnace(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    double eye[3] = {0.3, 0.5, 4};
    double target[3] = {0, 0, 0};
    double up[3] = {0, 1, 0};
    double center[3] = {0, 0, 0};
    const char *scene = stagecheck_scene(
        "furnace.scene",
        "camera origin %g %g %g target 0 0 0 up 0 1 0 fov 35\n"
        "image width " WIDTH " height " HEIGHT "\n"
        "background color 1 1 1\n"
        "material glass glass ior %.17g\n"
        "sphere center 0 0 0 radius 1 material glass\n",
        eye[0],
        eye[1],
        eye[2],
        c->param);
    struct pinhole cam = pinhole_make(eye, target, up, 35);
    double expected[PIXELS];
    int sphere_pixels = 0;
    for (int py = 0; py < cam.h; py++) {
        for (int px = 0; px < cam.w; px++) {
            double d[3];
            pinhole_ray(&cam, px, py, d);
            double t = sphere_t(eye, d, center, 1);
            double value = 1;
            if (t > 0 && stage() < 7) {
                double nrm[3] = {eye[0] + t * d[0], eye[1] + t * d[1], eye[2] + t * d[2]};
                double f = fresnel(-stagecheck_dot3(d, nrm), c->param);
                double series = 0;
                for (int k = 0; k <= WHITTED_DEPTH - 3; k++) {
                    series += pow(f, k);
                }
                value = f + (1 - f) * (1 - f) * series;
            }
            sphere_pixels += t > 0;
            expected[py * cam.w + px] = value;
        }
    }
    struct image img;
    double nan = 0;
    struct args a = glass_args("4");
    if (!render(scene, &a, &img, &nan)) {
        o->figure = INFINITY;
        return;
    }
    /* Near the silhouette F changes as 1/cos_i: float's rounding of the
     * hit point (~1e-7 of the scene) moves it by up to ~1e-3 there. */
    double tolerance = p->epsilon > 1e-10 ? 1e-2 : 1e-4;
    int n_bad;
    o->figure = worst_pixel_error(&img, expected, tolerance, &n_bad);
    o->passed = n_bad == 0 && nan == 0;
    snprintf(
        o->note,
        sizeof o->note,
        "worst relative error %.3g (%d sphere pixels); pixels off by > %g: %d; nan_pixels %g",
        o->figure,
        sphere_pixels,
        tolerance,
        n_bad,
        nan);
    image_free(&img);
}

TEST(optics_glass_furnace)
{
    static const struct render_case cases[] = {
        {"ior_1", run_furnace, 1, 0},
        {"ior_1.0001", run_furnace, 1.0001, 0},
        {"ior_2.42", run_furnace, 2.42, 0},
        {"ior_10", run_furnace, 10, 0},
    };
    RUN_CASES(cases);
}

/* ---- a thin glass slab ---------------------------------------------------- */

/* A slab of glass (index 1.5) of thickness w (the case's parameter, the
 * scene being ~2 units across), tilted off the axes, its two faces' normals
 * cross(edge1, edge2) pointing out of the glass (glass needs to know its
 * inside: hit_finish's front_face), before an area light
 * of radiance 1 that fills the view.  Through the slab, Whitted (04-06)
 * gives (1 - F)^2 (1 + F^2 + ... ) with the terms the depth limit allows
 * (light leaving at ray depth 3, 5, 7 for D = 8), F at the camera ray's
 * incidence (the same at both faces); 07 on average (1 - F) / (1 + F), the
 * whole series.  Beside the slab: 1.  A refracted ray spawned beyond the
 * back face (an offset larger than w) misses it and gives 1 - F instead. */
static void
run_thin_glass(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    (void)p;
    double w = c->param;
    double n[3] = {0.2, 0.1, 1};
    double a1[3] = {1, 0, -0.2};
    double a2[3];
    stagecheck_normalize3(n);
    stagecheck_cross3(n, a1, a2);
    stagecheck_normalize3(a2);
    stagecheck_cross3(a2, n, a1);
    double front[3], back[3], e1[3], e2[3];
    for (int i = 0; i < 3; i++) {
        front[i] = -0.6 * a1[i] - 0.6 * a2[i];
        back[i] = front[i] - w * n[i];
        e1[i] = 1.2 * a1[i];
        e2[i] = 1.2 * a2[i];
    }
    double eye[3] = {0.1, 0.2, 4};
    double target[3] = {0, 0, 0};
    double up[3] = {0, 1, 0};
    /* The light: a 6 x 6 square at z = -2 emitting towards +z. */
    const char *scene = stagecheck_scene(
        "thin_glass.scene",
        "camera origin %g %g %g target 0 0 0 up 0 1 0 fov 30\n"
        "image width " WIDTH " height " HEIGHT "\n"
        "material glass glass ior 1.5\n"
        "quad corner %.17g %.17g %.17g edge1 %.17g %.17g %.17g edge2 %.17g %.17g %.17g "
        "material glass\n"
        "quad corner %.17g %.17g %.17g edge1 %.17g %.17g %.17g edge2 %.17g %.17g %.17g "
        "material glass\n"
        "area_light corner -3 -3 -2 edge1 6 0 0 edge2 0 6 0 radiance 1 1 1\n",
        eye[0],
        eye[1],
        eye[2],
        front[0],
        front[1],
        front[2],
        e1[0],
        e1[1],
        e1[2],
        e2[0],
        e2[1],
        e2[2],
        back[0],
        back[1],
        back[2],
        e2[0],
        e2[1],
        e2[2],
        e1[0],
        e1[1],
        e1[2]);
    struct pinhole cam = pinhole_make(eye, target, up, 30);
    double expected[PIXELS];
    int slab_pixels = 0;
    for (int py = 0; py < cam.h; py++) {
        for (int px = 0; px < cam.w; px++) {
            double d[3];
            pinhole_ray(&cam, px, py, d);
            double to_front[3] = {front[0] - eye[0], front[1] - eye[1], front[2] - eye[2]};
            double t = stagecheck_dot3(to_front, n) / stagecheck_dot3(d, n);
            double q[3] = {
                eye[0] + t * d[0] - front[0],
                eye[1] + t * d[1] - front[1],
                eye[2] + t * d[2] - front[2]};
            double u = stagecheck_dot3(q, e1) / 1.44;
            double v = stagecheck_dot3(q, e2) / 1.44;
            bool on_slab = u > 0 && u < 1 && v > 0 && v < 1;
            bool near_edge = fmin(fmin(u, 1 - u), fmin(v, 1 - v)) > -0.02
                             && fmin(fmin(u, 1 - u), fmin(v, 1 - v)) < 0.02;
            double f = fresnel(fabs(stagecheck_dot3(d, n)), 1.5);
            double value = 1;
            if (on_slab) {
                value = stage() >= 7 ? (1 - f) / (1 + f)
                                     : (1 - f) * (1 - f) * (1 + f * f + f * f * f * f);
            }
            slab_pixels += on_slab && !near_edge;
            expected[py * cam.w + px] = near_edge ? -1 : value;
        }
    }
    struct image img;
    double nan = 0;
    struct args a = glass_args("256");
    if (!render(scene, &a, &img, &nan)) {
        o->figure = INFINITY;
        return;
    }
    int n_bad;
    o->figure = worst_pixel_error(&img, expected, 1e-4, &n_bad);
    o->passed = n_bad == 0 && nan == 0;
    snprintf(
        o->note,
        sizeof o->note,
        "worst relative error %.3g (%d slab pixels); pixels off by > 1e-4: %d; nan_pixels %g",
        o->figure,
        slab_pixels,
        n_bad,
        nan);
    if (stage() >= 7) {
        /* 256 paths per pixel, each 1 or 0: a t-test of the mean of
         * rendered / expected over the pixels against 1; the figure is
         * the mean's relative bias. */
        struct stattest_welford ratio = {0};
        for (int i = 0; i < img.width * img.height; i++) {
            if (expected[i] > 0 && expected[i] < 1) { /* the slab's pixels */
                stattest_welford_add(&ratio, img.rgb[3 * i] / expected[i]);
            }
        }
        double p_value = stattest_t_test_welford_one_sample(&ratio, 1).p;
        o->figure = fabs(ratio.mean - 1);
        o->passed = p_value >= T_TEST_ALPHA && nan == 0;
        snprintf(
            o->note,
            sizeof o->note,
            "mean of rendered / expected %.4f over %d pixels (t-test against 1: p %.3g); "
            "nan_pixels %g",
            ratio.mean,
            (int)ratio.n,
            p_value,
            nan);
    }
    image_free(&img);
}

TEST(thin_glass)
{
    static const struct render_case cases[] = {
        {"thin_glass_1e-5", run_thin_glass, 1e-5, 0},
    };
    RUN_CASES(cases);
}

/* ---- the looking-down-z camera ----------------------------------------- */

/* The camera at the origin looking down -z with y up, as the stage computes
 * it: forward (0, 0, -1), right (1, 0, 0) and up (0, 1, 0) come out exact,
 * so the unnormalised ray through the centre of pixel (px, py) is exactly
 * (x, y, -1) with x and y rounded as below (camera.c's expressions, in
 * double): every point s (x, y, -1) lies on that ray, and every point
 * (X, y D, -D) on the plane of the pixel row py. */
#define AXIS_CAMERA \
    "camera origin 0 0 0 target 0 0 -1 up 0 1 0 fov 40\nimage width " WIDTH " height " HEIGHT "\n"

static double
axis_x(int px)
{
    double half_h = tan(40 * PI_D / 360);
    double half_w = half_h * FRAME_W / FRAME_H;
    return (2 * (px + 0.5) / FRAME_W - 1) * half_w;
}

static double
axis_y(int py)
{
    double half_h = tan(40 * PI_D / 360);
    return (1 - 2 * (py + 0.5) / FRAME_H) * half_h;
}

/* Append a formatted statement to a growing scene text. */
static void append(char *buf, size_t cap, const char *format, ...)
    __attribute__((format(printf, 3, 4)));

static void
append(char *buf, size_t cap, const char *format, ...)
{
    size_t len = strlen(buf);
    va_list ap;
    va_start(ap, format);
    vsnprintf(buf + len, cap - len, format, ap);
    va_end(ap);
}

/* ---- watertight: every pixel centre on an edge or a vertex ----------------- */

#define GRID_FIRST 4 /* pixel of the first vertex, both axes */
#define GRID_COLS 13 /* vertices at px = 4, 6, ..., 28 */
#define GRID_ROWS 12 /* and at py = 4, 6, ..., 26 */

/* The front of a sphere (centre (0, 0, -4), radius 1.6) tessellated so that
 * vertex (i, j) lies on the centre ray of pixel (4 + 2i, 4 + 2j), closed at
 * the back by a fan to an apex: every pixel centre from (4, 4) to (28, 26)
 * lies on a vertex (both coordinates even), a horizontal or vertical edge
 * (one odd) or a diagonal (both odd; the diagonals run from (i, j) to
 * (i + 1, j + 1)), since a straight edge projects to the straight segment
 * between its ends' pixels.  Returns the mesh (positions and indices). */
static struct meshgen_mesh
pixel_aligned_mesh(void)
{
    struct meshgen_mesh m;
    size_t n_front = 2 * (GRID_COLS - 1) * (GRID_ROWS - 1);
    size_t n_border = 2 * (GRID_COLS - 1) + 2 * (GRID_ROWS - 1);
    if (!meshgen_alloc(&m, GRID_COLS * GRID_ROWS + 1, n_front + n_border, false)) {
        return m;
    }
    for (int j = 0; j < GRID_ROWS; j++) {
        for (int i = 0; i < GRID_COLS; i++) {
            long double d[3] = {axis_x(GRID_FIRST + 2 * i), axis_y(GRID_FIRST + 2 * j), -1};
            /* s d on the sphere |p - (0, 0, -4)| = 1.6: the nearer root. */
            long double a = d[0] * d[0] + d[1] * d[1] + 1;
            long double b = -4; /* d . (0, 0, -4) */
            long double s = (-b - sqrtl(b * b - a * (16 - 2.56L))) / a;
            double *v = &m.positions[3 * (j * GRID_COLS + i)];
            for (int k = 0; k < 3; k++) {
                v[k] = (double)(s * d[k]);
            }
        }
    }
    double *apex = &m.positions[3 * GRID_COLS * GRID_ROWS];
    apex[0] = 0;
    apex[1] = 0;
    apex[2] = -12;
    size_t t = 0;
    for (int j = 0; j + 1 < GRID_ROWS; j++) {
        for (int i = 0; i + 1 < GRID_COLS; i++) {
            unsigned a = (unsigned)(j * GRID_COLS + i);
            unsigned b = a + 1;
            unsigned c = a + GRID_COLS;
            unsigned d = c + 1;
            unsigned quad[6] = {a, c, d, a, d, b}; /* counter-clockwise seen from the camera */
            memcpy(&m.indices[3 * t], quad, sizeof quad);
            t += 2;
        }
    }
    /* The fan: each border edge (p, q) of a front triangle, reversed, with
     * the apex, so that every edge is shared by two triangles. */
    unsigned apex_index = GRID_COLS * GRID_ROWS;
    size_t front = t;
    for (size_t k = 0; k < front; k++) {
        for (int e = 0; e < 3; e++) {
            unsigned p = m.indices[3 * k + e];
            unsigned q = m.indices[3 * k + (e + 1) % 3];
            bool shared = false;
            for (size_t l = 0; l < front && !shared; l++) {
                for (int f = 0; f < 3; f++) {
                    shared |= m.indices[3 * l + f] == q && m.indices[3 * l + (f + 1) % 3] == p;
                }
            }
            if (!shared && t < m.n_triangles) {
                unsigned fan[3] = {apex_index, q, p};
                memcpy(&m.indices[3 * t++], fan, sizeof fan);
            }
        }
    }
    m.n_triangles = t;
    return m;
}

static void
run_watertight(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    (void)c;
    (void)p;
    struct meshgen_mesh m = pixel_aligned_mesh();
    CHECK(m.n_triangles > 0 && meshgen_is_closed(&m));
    static char text[1 << 16];
    snprintf(
        text,
        sizeof text,
        AXIS_CAMERA "material front diffuse albedo 0.8 0.8 0.8\n"
                    "material back diffuse albedo 0.8 0 0\n"
                    "point_light position 0 0 0 intensity 16 16 16\n");
    size_t n_front = 2 * (GRID_COLS - 1) * (GRID_ROWS - 1);
    for (size_t t = 0; t < m.n_triangles; t++) {
        append(text, sizeof text, "triangle");
        for (int k = 0; k < 3; k++) {
            const double *v = &m.positions[3 * m.indices[3 * t + k]];
            append(text, sizeof text, " v%d %.17g %.17g %.17g", k, v[0], v[1], v[2]);
        }
        append(text, sizeof text, " material %s\n", t < n_front ? "front" : "back");
    }
    const char *scene = test_tmp_path("watertight.scene");
    CHECK(test_write_file(scene, text));
    struct image img;
    double nan = 0;
    struct args a = direct_args();
    if (!render(scene, &a, &img, &nan)) {
        o->figure = INFINITY;
        meshgen_free(&m);
        return;
    }
    /* The grid's border pixels are aimed at edges the front shares with
     * the fan: either may be seen there.  Inside the border every edge
     * and vertex belongs to the front alone. */
    int leaks = 0;
    int aimed = 0;
    for (int py = GRID_FIRST + 1; py < GRID_FIRST + 2 * (GRID_ROWS - 1); py++) {
        for (int px = GRID_FIRST + 1; px < GRID_FIRST + 2 * (GRID_COLS - 1); px++) {
            /* The front is grey; a ray through it sees the red back (in
             * shadow from 02 on) or the black background. */
            leaks += image_pixel(&img, px, py)[1] == 0;
            aimed++;
        }
    }
    o->figure = leaks;
    o->passed = leaks == 0 && nan == 0;
    snprintf(
        o->note,
        sizeof o->note,
        "%zu triangles; of %d pixels whose centre ray is aimed at a vertex or an edge of the "
        "front, %d see through it; nan_pixels %g",
        m.n_triangles,
        aimed,
        leaks,
        nan);
    image_free(&img);
    meshgen_free(&m);
}

TEST(watertight_mesh)
{
    static const struct render_case cases[] = {
        {"watertight_render", run_watertight, 0, 0},
    };
    RUN_CASES(cases);
}

/* ---- degenerate input ------------------------------------------------------ */

/* A camera in general position, and the stage's own arithmetic for it
 * (camera.c, in double, operation for operation), so that points can be
 * put on the plane of a pixel row as the stage's rays see it. */
#define TILTED_CAMERA "camera origin 0.1 0.2 0.3 target 0.4 0.05 -0.7 up 0.1 1 0.05 fov 40\n"

struct stage_camera {
    double origin[3], forward[3], right[3], up[3];
    double half_w, half_h;
};

static void
normalize_as_stage(double a[3])
{
    double inv = 1 / sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int i = 0; i < 3; i++) {
        a[i] *= inv;
    }
}

static struct stage_camera
tilted_camera(void)
{
    static const double origin[3] = {0.1, 0.2, 0.3};
    static const double target[3] = {0.4, 0.05, -0.7};
    static const double up[3] = {0.1, 1, 0.05};
    struct stage_camera c;
    for (int i = 0; i < 3; i++) {
        c.origin[i] = origin[i];
        c.forward[i] = target[i] - origin[i];
    }
    normalize_as_stage(c.forward);
    stagecheck_cross3(c.forward, up, c.right);
    normalize_as_stage(c.right);
    stagecheck_cross3(c.right, c.forward, c.up);
    c.half_h = tan(40 * PI_D / 360);
    c.half_w = c.half_h * FRAME_W / FRAME_H;
    return c;
}

/* The point `s` along the (unnormalised) centre ray of pixel (px, py). */
static void
on_pixel_ray(const struct stage_camera *c, int px, int py, double s, double out[3])
{
    double x = (2 * (px + 0.5) / FRAME_W - 1) * c->half_w;
    double y = (1 - 2 * (py + 0.5) / FRAME_H) * c->half_h;
    for (int i = 0; i < 3; i++) {
        double d = c->forward[i] + c->right[i] * x;
        d = d + c->up[i] * y;
        out[i] = (double)((long double)c->origin[i] + (long double)s * d);
    }
}

/* The scene of the degenerate shapes: a white backdrop lit by a point light
 * at the eye, and `shapes` (red) before it. */
static const char *
backdrop_scene(const char *name, const char *shapes)
{
    static char text[1 << 14];
    snprintf(
        text,
        sizeof text,
        TILTED_CAMERA "image width " WIDTH " height " HEIGHT "\n"
                      "material white diffuse albedo 0.8 0.8 0.8\n"
                      "material red diffuse albedo 0.9 0.1 0.1\n"
                      "quad corner -8 -8 -16 edge1 16 0 0 edge2 0 16 0 material white\n"
                      "point_light position 0.1 0.2 0.3 intensity 256 256 256\n%s",
        shapes);
    const char *path = test_tmp_path(name);
    return test_write_file(path, text) ? path : NULL;
}

/* Pixels that differ at all between two renders. */
static int
differing_pixels(const struct image *x, const struct image *ref)
{
    int n = 0;
    for (int i = 0; i < ref->width * ref->height; i++) {
        n += memcmp(&x->rgb[3 * i], &ref->rgb[3 * i], 3 * sizeof(float)) != 0;
    }
    return n;
}

/* Render the backdrop with `shapes` and without: the figure is the number
 * of pixels that differ (a shape that is never hit changes none). */
static void
compare_backdrop(const char *shapes, struct outcome *o)
{
    struct image clean;
    struct image x;
    double nan_clean = 0;
    double nan = 0;
    struct args a = direct_args();
    if (!render(backdrop_scene("clean.scene", ""), &a, &clean, &nan_clean)
        || !render(backdrop_scene("shapes.scene", shapes), &a, &x, &nan)) {
        o->figure = INFINITY;
        image_free(&clean);
        return;
    }
    o->figure = differing_pixels(&x, &clean);
    o->passed = o->figure == 0 && nan == 0 && nan_clean == 0;
    snprintf(
        o->note,
        sizeof o->note,
        "pixels changed by the shapes: %g; nan_pixels %g",
        o->figure,
        nan);
    image_free(&clean);
    image_free(&x);
}

/* Degenerate shapes on the planes of the pixel rows 5, 9, ..., 25, each
 * from A (4 units along the ray of pixel 6 of the row) to B (8 units along
 * that of pixel 25): every ray of the row between them (and every shadow
 * ray from the backdrop it sees to the light at the eye) passes through
 * the shape's line, to the rounding of A and B.  kind: 'r' a triangle with
 * a repeated vertex (A, B, B), 'p' one with three equal vertices, 'q' a
 * quad with edge2 = edge1 / 2; each has a zero cross product of its
 * edges. */
static void
run_degenerate(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    (void)p;
    struct stage_camera cam = tilted_camera();
    char shapes[8192] = "";
    for (int py = 5; py <= 25; py += 4) {
        double a[3];
        double b[3];
        on_pixel_ray(&cam, 6, py, 4, a);
        on_pixel_ray(&cam, 25, py, 8, b);
        double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        if (c->param == 'r') {
            append(
                shapes,
                sizeof shapes,
                "triangle v0 %.17g %.17g %.17g v1 %.17g %.17g %.17g v2 %.17g %.17g %.17g "
                "material red\n",
                a[0],
                a[1],
                a[2],
                b[0],
                b[1],
                b[2],
                b[0],
                b[1],
                b[2]);
        } else if (c->param == 'p') {
            append(
                shapes,
                sizeof shapes,
                "triangle v0 %.17g %.17g %.17g v1 %.17g %.17g %.17g v2 %.17g %.17g %.17g "
                "material red\n",
                a[0],
                a[1],
                a[2],
                a[0],
                a[1],
                a[2],
                a[0],
                a[1],
                a[2]);
        } else {
            append(
                shapes,
                sizeof shapes,
                "quad corner %.17g %.17g %.17g edge1 %.17g %.17g %.17g edge2 %.17g %.17g %.17g "
                "material red\n",
                a[0],
                a[1],
                a[2],
                e[0],
                e[1],
                e[2],
                e[0] / 2,
                e[1] / 2,
                e[2] / 2);
        }
    }
    compare_backdrop(shapes, o);
}

/* A sphere whose radius squared underflows (1e-200 in double, 1e-30 in
 * float) before the backdrop: invisible, and no NaN. */
static void
run_tiny_sphere(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    (void)c;
    char shape[256];
    snprintf(
        shape,
        sizeof shape,
        "sphere center 0.41 0.05 -0.7 radius %s material red\n",
        p->epsilon > 1e-10 ? "1e-30" : "1e-200");
    compare_backdrop(shape, o);
}

/* The exit status and the first message of the binary's output, without
 * the temporary directory (the note goes to docs/extremes.md). */
static void
note_exit(struct outcome *o, int status, const char *out)
{
    const char *message = strstr(out, "error:");
    const char *assertion = strstr(out, "Assertion");
    const char *shown = message ? message : assertion ? assertion : out;
    snprintf(o->note, sizeof o->note, "exit %d: %.300s", status, shown);
    o->note[strcspn(o->note, "\n")] = '\0';
}

/* A scene the loader must refuse: exit status 1 and the message of
 * docs/scene-format.md.  The figure is the exit status. */
static void
expect_refusal(const char *scene, const char *message, struct outcome *o)
{
    char out[4096];
    int status = scene ? run_scene(scene, out, sizeof out) : -1;
    o->figure = status;
    o->passed = status == 1 && strstr(out, message) != NULL;
    note_exit(o, status, out);
}

static void
run_zero_sphere(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    (void)c;
    (void)p;
    expect_refusal(
        backdrop_scene("zero_sphere.scene", "sphere center 0.4 0.05 -0.7 radius 0 material red\n"),
        "radius must be > 0, got 0",
        o);
}

static void
run_zero_light(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    (void)c;
    (void)p;
    expect_refusal(
        backdrop_scene(
            "zero_light.scene",
            "area_light corner -1 -1 -4 edge1 2 0 0 edge2 4 0 0 radiance 1 1 1\n"),
        "area_light has zero area",
        o);
}

static void
run_target_is_origin(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    (void)c;
    (void)p;
    const struct edit e =
        {1, 0, 1, -1, NULL, {"camera origin 0 1 3.9 target 0 1 3.9 up 0 1 0 fov 40"}};
    expect_refusal(
        cornell_scene("target_is_origin.scene", &e),
        "target must differ from origin",
        o);
}

/* Render the box with camera line `camera` and compare with `reference`'s:
 * the same view must give the same image.  The figure is the relMSE, or
 * infinity when the render fails (a crash: exit status in the note). */
static void
compare_cameras(
    const char *camera,
    const char *reference,
    const struct precision *p,
    struct outcome *o)
{
    const struct edit e_ref = {1, 0, 1, -1, NULL, {reference}};
    const struct edit e = {1, 0, 1, -1, NULL, {camera}};
    struct image ref;
    struct image x;
    double nan_ref = 0;
    double nan = 0;
    struct args a = base_args(false);
    if (!render(cornell_scene("camera_ref.scene", &e_ref), &a, &ref, &nan_ref)) {
        o->figure = INFINITY;
        return;
    }
    char out[4096];
    const char *scene = cornell_scene("camera.scene", &e);
    int status = run_scene(scene, out, sizeof out);
    if (status != 0 || !render(scene, &a, &x, &nan)) {
        o->figure = INFINITY;
        note_exit(o, status, out);
        image_free(&ref);
        return;
    }
    judge_same(&x, &ref, NULL, noise_of(p), nan, o);
    image_free(&ref);
    image_free(&x);
}

/* Tiny and huge numbers for the camera: what this precision can read
 * whose square underflows or overflows. */
static const char *
tiny(const struct precision *p)
{
    return p->epsilon > 1e-10 ? "1e-30" : "1e-200";
}

static const char *
huge(const struct precision *p)
{
    return p->epsilon > 1e-10 ? "1e30" : "1e200";
}

/* The target a tiny distance from the origin, across the view of the box
 * from its middle towards the green wall. */
static void
run_target_near_origin(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    (void)c;
    char camera[256];
    snprintf(camera, sizeof camera, "camera origin 0 1 0 target %s 1 0 up 0 1 0 fov 60", tiny(p));
    compare_cameras(camera, "camera origin 0 1 0 target 1 1 0 up 0 1 0 fov 60", p, o);
}

static void
run_up(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    char camera[256];
    snprintf(
        camera,
        sizeof camera,
        "camera origin 0 1 3.9 target 0 1 0 up 0 %s 0 fov 40",
        c->param > 1 ? huge(p) : tiny(p));
    compare_cameras(camera, "camera origin 0 1 3.9 target 0 1 0 up 0 1 0 fov 40", p, o);
}

/* A light on a surface.  Point light: on the floor of the point-light box
 * (its irradiance there is exactly 0: cos = 0), compared with the same
 * light 1e-6 above the floor.  Area light: in the ceiling's plane, compared
 * with it 1e-6 below, over the pixels that do not see the light itself
 * (brighter than 2: where the two coincident surfaces tie, and the one
 * whose t rounds lower is seen); the note says how many show the light. */
static void
run_light_on_surface(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    bool area = c->param > 0;
    const struct edit on = {
        1,
        0,
        1,
        -1,
        area ? NULL : "scenes/cornell_diffuse_point.scene",
        {area ? "area_light corner -0.25 2 -0.25 edge1 0.5 0 0 edge2 0 0 0.5 radiance 12 10 8"
              : "point_light position 0.1 0 -0.5 intensity 3 2.5 2"}};
    const struct edit off = {
        1,
        0,
        1,
        -1,
        on.source,
        {area
             ? "area_light corner -0.25 1.999999 -0.25 edge1 0.5 0 0 edge2 0 0 0.5 radiance 12 10 8"
             : "point_light position 0.1 0.000001 -0.5 intensity 3 2.5 2"}};
    struct image ref;
    struct image x;
    double nan_ref = 0;
    double nan = 0;
    struct args a = base_args(false);
    if (!render(cornell_scene("light_off.scene", &off), &a, &ref, &nan_ref)
        || !render(cornell_scene("light_on.scene", &on), &a, &x, &nan)) {
        o->figure = INFINITY;
        image_free(&ref);
        return;
    }
    /* The light's pixels: brighter than anything it lights (radiance 12). */
    unsigned char mask[PIXELS];
    int light_pixels = 0;
    int light_seen = 0;
    for (int i = 0; i < ref.width * ref.height; i++) {
        bool is_light = area && ref.rgb[3 * i] > 2;
        mask[i] = !is_light;
        light_pixels += is_light;
        light_seen += is_light && x.rgb[3 * i] > 2;
    }
    judge_same(&x, &ref, mask, noise_of(p), nan + nan_ref, o);
    size_t len = strlen(o->note);
    snprintf(
        o->note + len,
        sizeof o->note - len,
        "; outside the light's pixels; the light shows in %d of its %d pixels",
        light_seen,
        light_pixels);
    image_free(&ref);
    image_free(&x);
}

TEST(degenerate_input)
{
    static const struct render_case cases[] = {
        {"degenerate_repeated_vertex", run_degenerate, 'r', 0},
        {"degenerate_one_point", run_degenerate, 'p', 0},
        {"degenerate_zero_area_quad", run_degenerate, 'q', 0},
        {"zero_size_sphere", run_zero_sphere, 0, 0},
        {"tiny_sphere", run_tiny_sphere, 0, 0},
        {"zero_area_light", run_zero_light, 0, 0},
        {"light_on_surface_point", run_light_on_surface, 0, 0},
        {"light_on_surface_area", run_light_on_surface, 1, 0},
        {"camera_target_is_origin", run_target_is_origin, 0, 0},
        {"camera_target_near_origin", run_target_near_origin, 0, 0},
        {"camera_up_huge", run_up, 2, 0},
        {"camera_up_tiny", run_up, 0, 0},
    };
    RUN_CASES(cases);
}

/* ---- radiance range ---------------------------------------------------------- */

static void
run_radiance(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    struct edit e = {1, 0, c->param, -1, NULL, {NULL}};
    compare_with_unit(c->name, &e, p, o);
}

/* The box with every albedo set to `albedo`, one ray per pixel centre. */
static bool
render_albedo(double albedo, struct image *img, double *nan)
{
    char name[64];
    snprintf(name, sizeof name, "albedo_%g.scene", albedo);
    struct edit e = {1, 0, 1, albedo, NULL, {NULL}};
    struct args a = base_args(true);
    return render(cornell_scene(name, &e), &a, img, nan);
}

/* Albedo 0: every pixel is black or shows the light's radiance (12, 10, 8)
 * itself; the figure is the number of other pixels. */
static void
run_albedo_0(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    (void)c;
    (void)p;
    struct image img;
    double nan = 0;
    if (!render_albedo(0, &img, &nan)) {
        o->figure = INFINITY;
        return;
    }
    int other = 0;
    for (int i = 0; i < img.width * img.height; i++) {
        const float *v = &img.rgb[3 * i];
        bool black = v[0] == 0 && v[1] == 0 && v[2] == 0;
        bool light = v[0] == 12 && v[1] == 10 && v[2] == 8;
        other += !black && !light;
    }
    o->figure = other;
    o->passed = other == 0 && nan == 0;
    snprintf(
        o->note,
        sizeof o->note,
        "pixels neither black nor the light: %d; nan_pixels %g",
        other,
        nan);
    image_free(&img);
}

/* Albedo 1 against albedo 0.5, with the light's own pixels (albedo 0)
 * subtracted: direct light is linear in the albedo (01-06), so the first is
 * exactly twice the second; with interreflection (07) more than twice. */
static void
run_albedo_1(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    (void)p;
    struct image one, half, zero;
    double nan[3] = {0, 0, 0};
    if (!render_albedo(1, &one, &nan[0]) || !render_albedo(0.5, &half, &nan[1])
        || !render_albedo(0, &zero, &nan[2])) {
        o->figure = INFINITY;
        return;
    }
    double sum_one = 0;
    double sum_half = 0;
    bool finite = true;
    for (int i = 0; i < 3 * one.width * one.height; i++) {
        one.rgb[i] -= zero.rgb[i];
        half.rgb[i] = 2 * (half.rgb[i] - zero.rgb[i]);
        sum_one += one.rgb[i];
        sum_half += half.rgb[i];
        finite = finite && isfinite(one.rgb[i]);
    }
    bool nans = nan[0] + nan[1] + nan[2] > 0;
    if (c->param > 0) { /* interreflection: the ratio of the means */
        o->figure = sum_one / sum_half;
        o->passed = o->figure > 1 && finite && !nans;
        snprintf(
            o->note,
            sizeof o->note,
            "mean radiance (light excluded), albedo 1 / (2 x albedo 0.5): %.4g; nan_pixels %g",
            o->figure,
            nan[0] + nan[1] + nan[2]);
    } else {
        o->figure = metrics_relmse(&one, &half, NULL);
        o->passed = o->figure <= SAME_RELMSE && finite && !nans;
        snprintf(
            o->note,
            sizeof o->note,
            "relMSE of albedo 1 against 2 x albedo 0.5 (light excluded): %.3g; nan_pixels %g",
            o->figure,
            nan[0] + nan[1] + nan[2]);
    }
    image_free(&one);
    image_free(&half);
    image_free(&zero);
}

TEST(radiance_range)
{
    static const struct render_case cases[] = {
        {"radiance_1e-20", run_radiance, 1e-20, 0},
        {"radiance_1e20", run_radiance, 1e20, 0},
        {"albedo_0", run_albedo_0, 0, 0},
        {"albedo_1_direct", run_albedo_1, 0, 0},
        {"albedo_1_interreflection", run_albedo_1, 1, 0},
    };
    RUN_CASES(cases);
}

/* Counted as skipped when the second precision is not run, so the closing
 * line shows that half of the battery did not run. */
TEST(second_precision_given)
{
    init_precisions();
#ifdef REAL_IS_FLOAT
    SKIP("tests built with REAL=float: the double cases run in the double build");
#else
    if (!precisions[1].binary) {
        SKIP("RENDER_FLOAT unset or missing: the float cases are skipped (make REAL=float)");
    }
#endif
}

TEST_MAIN(
    TEST_ENTRY(second_precision_given),
    TEST_ENTRY(scale),
    TEST_ENTRY(far_from_origin),
    TEST_ENTRY(acne),
    TEST_ENTRY(sphere_from_inside),
    TEST_ENTRY(optics_glass_furnace),
    TEST_ENTRY(thin_glass),
    TEST_ENTRY(watertight_mesh),
    TEST_ENTRY(degenerate_input),
    TEST_ENTRY(radiance_range))
