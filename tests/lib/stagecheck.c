/* stagecheck.c - see stagecheck.h. */
#include "stagecheck.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "metrics.h"
#include "rng.h"
#include "scene.h"
#include "testlib.h"

const char *
stagecheck_scene(const char *name, const char *format, ...)
{
    static char text[16384];
    va_list ap;
    va_start(ap, format);
    int n = vsnprintf(text, sizeof text, format, ap);
    va_end(ap);
    if (n < 0 || (size_t)n >= sizeof text) {
        printf("stagecheck_scene: scene %s does not fit in %zu bytes\n", name, sizeof text);
        return NULL;
    }
    const char *path = test_tmp_path(name);
    if (!test_write_file(path, text)) {
        printf("stagecheck_scene: cannot write %s\n", path);
        return NULL;
    }
    return path;
}

bool
stagecheck_render(
    const char *scene,
    const char *const args[],
    struct image *out,
    const char **stats)
{
    static int counter;
    const char *argv[64];
    int n = 0;
    for (int i = 0; args && args[i] && n < 60; i++) {
        argv[n++] = args[i];
    }
    if (stats) {
        char name[64];
        snprintf(name, sizeof name, "stats-%d.json", counter++);
        *stats = test_tmp_path(name);
        argv[n++] = "--stats";
        argv[n++] = *stats;
    }
    argv[n] = NULL;
    if (!scene) {
        printf("stagecheck_render: no scene\n");
        return false;
    }
    return test_render_image(scene, argv, out);
}

bool
stagecheck_endless_render(
    struct stagecheck_endless *run,
    int size,
    const char *out,
    const char *stats)
{
    const char *render = test_render_binary();
    if (!render) {
        printf("stagecheck_endless_render: RENDER is not set\n");
        return false;
    }
    snprintf(run->size, sizeof run->size, "%d", size);
    const char *argv[] = {
        render,
        "-q",
        "-W",
        run->size,
        "-H",
        run->size,
        "--spp",
        "1000000",
        "-o",
        out,
        "--stats",
        stats,
        test_root_path("scenes/cornell_diffuse_area.scene"),
        NULL};
    _Static_assert(sizeof argv <= sizeof run->argv, "stagecheck_endless.argv is too small");
    memcpy(run->argv, argv, sizeof argv);
    return true;
}

double
stagecheck_stat(const char *stats, const char *key)
{
    double value;
    if (!stats || !test_json_number(stats, key, &value)) {
        printf("statistics %s: no key \"%s\"\n", stats ? stats : "(none)", key);
        return NAN;
    }
    return value;
}

bool
stagecheck_reference(const char *name, struct image *out)
{
    char relative[256];
    snprintf(relative, sizeof relative, "tests/reference/%s.pfm", name);
    struct diag err;
    if (!image_read_pfm(test_root_path(relative), out, &err)) {
        diag_print(stdout, &err, "error");
        return false;
    }
    return true;
}

double
stagecheck_relmse_smooth(const struct image *x, const struct image *ref, size_t *n_smooth)
{
    struct diag err;
    *n_smooth = 0;
    unsigned char *mask = metrics_smooth_mask(ref, METRICS_SMOOTH_TOLERANCE, n_smooth, &err);
    if (!mask) {
        diag_print(stdout, &err, "error");
        return NAN;
    }
    double relmse = metrics_relmse(x, ref, mask);
    free(mask);
    return relmse;
}

double
stagecheck_region_mean(const struct image *img, int x0, int y0, int w, int h, int c)
{
    double sum = 0;
    for (int y = y0; y < y0 + h; y++) {
        for (int x = x0; x < x0 + w; x++) {
            sum += image_pixel(img, x, y)[c];
        }
    }
    return sum / ((double)w * (double)h);
}

double
stagecheck_pixel_reldiff(const float *a, const float *b, double floor)
{
    double worst = 0;
    for (int c = 0; c < 3; c++) {
        double d = fabs((double)a[c] - (double)b[c]) / fmax(fabs((double)b[c]), floor);
        worst = isnan(d) ? INFINITY : fmax(worst, d);
    }
    return worst;
}

bool
stagecheck_interior(const struct image *img, int x, int y, double tolerance)
{
    if (x < 1 || y < 1 || x >= img->width - 1 || y >= img->height - 1) {
        return false;
    }
    const float *centre = image_pixel(img, x, y);
    for (int dy = -1; dy <= 1; dy++) {
        for (int dx = -1; dx <= 1; dx++) {
            if (stagecheck_pixel_reldiff(image_pixel(img, x + dx, y + dy), centre, 1e-6)
                > tolerance) {
                return false;
            }
        }
    }
    return true;
}

double
stagecheck_resolvable(double x)
{
    return fmax(x, 1000 * (double)REAL_EPSILON);
}

bool
stagecheck_representable(double size, double offset)
{
    return (double)REAL_EPSILON * offset <= 1e-4 * size;
}

double
stagecheck_dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void
stagecheck_cross3(const double a[3], const double b[3], double out[3])
{
    double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    out[0] = c[0];
    out[1] = c[1];
    out[2] = c[2];
}

void
stagecheck_normalize3(double a[3])
{
    double len = sqrt(stagecheck_dot3(a, a));
    a[0] /= len;
    a[1] /= len;
    a[2] /= len;
}

double
stagecheck_polygon_irradiance(
    double corners[][3],
    int n_corners,
    const double x[3],
    const double n[3],
    double radiance)
{
    double sum = 0;
    for (int i = 0; i < n_corners; i++) {
        const double *a = corners[i];
        const double *b = corners[(i + 1) % n_corners];
        double va[3] = {a[0] - x[0], a[1] - x[1], a[2] - x[2]};
        double vb[3] = {b[0] - x[0], b[1] - x[1], b[2] - x[2]};
        stagecheck_normalize3(va);
        stagecheck_normalize3(vb);
        double c[3];
        stagecheck_cross3(va, vb, c);
        double theta = atan2(sqrt(stagecheck_dot3(c, c)), stagecheck_dot3(va, vb));
        sum += theta * stagecheck_dot3(n, c) / sqrt(stagecheck_dot3(c, c));
    }
    return radiance / 2 * fabs(sum);
}

double
stagecheck_triangle_solid_angle(double corners[3][3], const double x[3])
{
    double v[3][3];
    double len[3];
    for (int k = 0; k < 3; k++) {
        for (int j = 0; j < 3; j++) {
            v[k][j] = corners[k][j] - x[j];
        }
        len[k] = sqrt(stagecheck_dot3(v[k], v[k]));
    }
    double bc[3];
    stagecheck_cross3(v[1], v[2], bc);
    double triple = fabs(stagecheck_dot3(v[0], bc));
    double denom = len[0] * len[1] * len[2] + stagecheck_dot3(v[0], v[1]) * len[2]
                   + stagecheck_dot3(v[0], v[2]) * len[1] + stagecheck_dot3(v[1], v[2]) * len[0];
    return 2 * atan2(triple, denom);
}

void
stagecheck_random_unit(struct rng *rng, double out[3])
{
    double z = 1 - 2 * (double)rng_uniform(rng);
    double phi = 2 * PI * (double)rng_uniform(rng);
    double s = sqrt(fmax(0.0, 1 - z * z));
    out[0] = s * cos(phi);
    out[1] = s * sin(phi);
    out[2] = z;
}

bool
stagecheck_load_text(const char *text, struct scene *out)
{
    struct diag err;
    if (!scene_load_string(text, strlen(text), "test.scene", out, &err)) {
        diag_print(stdout, &err, "error");
        return false;
    }
    return true;
}

double
stagecheck_fresnel(double cos_i, double eta)
{
    double sin2_t = eta * eta * (1 - cos_i * cos_i);
    if (sin2_t >= 1) {
        return 1;
    }
    double cos_t = sqrt(1 - sin2_t);
    double rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    double rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return (rs * rs + rp * rp) / 2;
}

/* A soup of n_each spheres, quads and triangles in [-1, 1]^3, and four
 * quads ten times larger. */
bool
stagecheck_random_soup(struct rng *rng, int n_each, struct scene *s)
{
    size_t cap = (size_t)n_each * 400 + 2048;
    char *text = malloc(cap);
    if (!text) {
        return false;
    }
    int n = snprintf(
        text,
        cap,
        "camera origin 0 0 5 target 0 0 0 up 0 1 0 fov 40\nimage width 4 height 4\n"
        "material m diffuse albedo 0.5 0.5 0.5\n");
    for (int i = 0; i < n_each + 4; i++) {
        double c[3];
        double e1[3];
        double e2[3];
        double size = i < n_each ? 0.2 : 3;
        for (int k = 0; k < 3; k++) {
            c[k] = 2 * (double)rng_uniform(rng) - 1;
            e1[k] = size * (2 * (double)rng_uniform(rng) - 1);
            e2[k] = size * (2 * (double)rng_uniform(rng) - 1);
        }
        n += snprintf(
            text + n,
            cap - (size_t)n,
            "quad corner %.9g %.9g %.9g edge1 %.9g %.9g %.9g edge2 %.9g %.9g %.9g material m\n",
            c[0],
            c[1],
            c[2],
            e1[0],
            e1[1],
            e1[2],
            e2[0],
            e2[1],
            e2[2]);
        if (i >= n_each) {
            continue;
        }
        n += snprintf(
            text + n,
            cap - (size_t)n,
            "sphere center %.9g %.9g %.9g radius %.9g material m\n"
            "triangle v0 %.9g %.9g %.9g v1 %.9g %.9g %.9g v2 %.9g %.9g %.9g material m\n",
            c[1],
            c[2],
            c[0],
            0.02 + 0.08 * (double)rng_uniform(rng),
            c[2],
            c[0],
            c[1],
            c[2] + e1[0],
            c[0] + e1[1],
            c[1] + e1[2],
            c[2] + e2[0],
            c[0] + e2[1],
            c[1] + e2[2]);
    }
    bool ok = stagecheck_load_text(text, s);
    free(text);
    return ok;
}
