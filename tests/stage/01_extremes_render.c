/*
 * 01_extremes_render.c - the extremes battery, black-box part: scenes at
 * the edges of floating point rendered by the stage's binary (RENDER) and,
 * when it is given, by the same stage built with REAL=float (RENDER_FLOAT;
 * its cases are skipped otherwise), each case judged against
 * tests/extremes/expect.tsv (tests/extremes/expect.h).  docs/extremes.md
 * describes every case and shows the table of the last run.  The image
 * size, the command lines, the comparisons and the case table are in
 * tests/extremes/render.h, shared with the cases of later stages' features
 * (04-06_extremes_glass.c, 07_extremes_paths.c).
 *
 * The families (one test each), what every stage must survive:
 *  - scale: the area-light Cornell box scaled by 1e-6 .. 1e6 equals the
 *    unit box (radiance does not depend on units);
 *  - far: the same box translated by 1e1 .. 1e7 along (1, 1, 1);
 *  - acne: a tilted plane under a point light 1 and 0.01 degrees above it,
 *    pixel by pixel against the analytic radiance;
 *  - inside: a camera inside a sphere with a point light at its centre sees
 *    a uniform radiance albedo I / (pi R^2);
 *  - watertight: a closed mesh whose vertices lie on pixel-centre rays, so
 *    every pixel centre is aimed exactly at a vertex or an edge;
 *  - degenerate: zero-area triangles and quads crossed by whole rows of
 *    pixel rays, a zero and a tiny sphere, a zero-area light, lights on a
 *    surface, cameras with the target at (or next to) the origin and with a
 *    huge or tiny up vector;
 *  - radiance: light radiance 1e-20 and 1e20, albedo 0 and 1 (direct
 *    light).
 */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TAG "render"

#include "extremes/render.h"
#include "meshgen.h"

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
    if (render_judged(scene, &a, expected, 1e-3, "every pixel", o, &img, &nan)) {
        image_free(&img);
    }
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

/* The area light of run_light_on_surface and the camera it is seen with
 * (the box's own camera, written out so that the test knows it). */
#define SURFACE_LIGHT_CAMERA "camera origin 0 1 3.9 target 0 1 0 up 0 1 0 fov 40"
static const double surface_light_corner[3] = {-0.25, 2, -0.25};
static const double surface_light_edges[2][3] = {{0.5, 0, 0}, {0, 0, 0.5}};

/* The pixels that the light (surface_light_corner + s edge 1 + t edge 2,
 * s and t in [0, 1]) covers even in part, in the image of
 * SURFACE_LIGHT_CAMERA: the bounding box of its corners' projections, a rectangle of pixels,
 * widened by one pixel for rounding.  Computed from the geometry, not from
 * a render, so that it does not depend on where a stage puts its samples
 * (06's adaptive sampling places them by the image's content). */
static void
light_mask(unsigned char *covered)
{
    const double origin[3] = {0, 1, 3.9};
    const double target[3] = {0, 1, 0};
    const double up[3] = {0, 1, 0};
    struct pinhole cam = pinhole_make(origin, target, up, 40);
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (int k = 0; k < 4; k++) {
        double d[3];
        for (int i = 0; i < 3; i++) {
            d[i] = surface_light_corner[i] + (k & 1) * surface_light_edges[0][i]
                   + (k >> 1) * surface_light_edges[1][i] - origin[i];
        }
        double z = stagecheck_dot3(d, cam.forward);
        /* Continuous pixel coordinates: pixel px spans [px, px + 1). */
        double x = (stagecheck_dot3(d, cam.right) / z / cam.half_w + 1) * cam.w / 2;
        double y = (1 - stagecheck_dot3(d, cam.up) / z / cam.half_h) * cam.h / 2;
        x0 = fmin(x0, x);
        x1 = fmax(x1, x);
        y0 = fmin(y0, y);
        y1 = fmax(y1, y);
    }
    for (int py = 0; py < cam.h; py++) {
        for (int px = 0; px < cam.w; px++) {
            covered[py * cam.w + px] =
                px + 1 >= x0 - 1 && px <= x1 + 1 && py + 1 >= y0 - 1 && py <= y1 + 1;
        }
    }
}

/* A light on a surface.  Point light: on the floor of the point-light box
 * (its irradiance there is exactly 0: cos = 0), compared with the same
 * light 1e-6 above the floor.  Area light: in the ceiling's plane, compared
 * with it 1e-6 below, over the pixels the light does not cover even in
 * part (light_mask): where the two coincident surfaces tie, the one whose
 * t rounds lower is seen, so a pixel the light covers, wholly or (with
 * several samples per pixel, 06's and 07's) in part, differs by the
 * light's radiance, which says nothing of the light on the surface; the
 * note says how many of those pixels show the light (brighter than
 * anything it lights, radiance 12). */
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
              : "point_light position 0.1 0 -0.5 intensity 3 2.5 2",
         area ? SURFACE_LIGHT_CAMERA : NULL}};
    const struct edit off = {
        1,
        0,
        1,
        -1,
        on.source,
        {area
             ? "area_light corner -0.25 1.999999 -0.25 edge1 0.5 0 0 edge2 0 0 0.5 radiance 12 10 8"
             : "point_light position 0.1 0.000001 -0.5 intensity 3 2.5 2",
         area ? SURFACE_LIGHT_CAMERA : NULL}};
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
    unsigned char covered[PIXELS] = {0};
    if (area) {
        light_mask(covered);
    }
    unsigned char mask[PIXELS];
    int n_covered = 0;
    int light_pixels = 0;
    int light_seen = 0;
    for (int i = 0; i < PIXELS; i++) {
        mask[i] = !covered[i];
        n_covered += covered[i];
        light_pixels += covered[i] && ref.rgb[3 * i] > 2;
        light_seen += covered[i] && x.rgb[3 * i] > 2;
    }
    judge_same(&x, &ref, mask, noise_of(p), nan + nan_ref, o);
    size_t len = strlen(o->note);
    snprintf(
        o->note + len,
        sizeof o->note - len,
        "; outside the %d pixels the light covers; the light shows in %d of the %d where it "
        "shows 1e-6 lower",
        n_covered,
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
 * exactly twice the second.  Stage 07's interreflection makes it more than
 * twice: 07_extremes_paths.c. */
static void
run_albedo_1(const struct render_case *c, const struct precision *p, struct outcome *o)
{
    (void)c;
    (void)p;
    struct albedo_pair pair;
    if (!render_albedo_pair(&pair, o)) {
        return;
    }
    o->figure = metrics_relmse(&pair.one, &pair.twice_half, NULL);
    o->passed = o->figure <= SAME_RELMSE && pair.finite && pair.nan == 0;
    snprintf(
        o->note,
        sizeof o->note,
        "relMSE of albedo 1 against 2 x albedo 0.5 (light excluded): %.3g; nan_pixels %g",
        o->figure,
        pair.nan);
    albedo_pair_free(&pair);
}

TEST(radiance_range)
{
    static const struct render_case cases[] = {
        {"radiance_1e-20", run_radiance, 1e-20, 0},
        {"radiance_1e20", run_radiance, 1e20, 0},
        {"albedo_0", run_albedo_0, 0, 0},
        {"albedo_1_direct", run_albedo_1, 0, 0},
    };
    RUN_CASES(cases);
}

TEST(second_precision_given)
{
    SKIP_WITHOUT_SECOND_PRECISION();
}

TEST_MAIN(
    TEST_ENTRY(second_precision_given),
    TEST_ENTRY(scale),
    TEST_ENTRY(far_from_origin),
    TEST_ENTRY(acne),
    TEST_ENTRY(sphere_from_inside),
    TEST_ENTRY(watertight_mesh),
    TEST_ENTRY(degenerate_input),
    TEST_ENTRY(radiance_range))
