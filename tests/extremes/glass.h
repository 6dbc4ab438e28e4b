/*
 * glass.h - the glass cases of the extremes battery, header-only (like
 * render.h, which it needs): a glass sphere in a white furnace and a thin
 * glass slab, each pixel by pixel against the analytic radiance.  Whitted's
 * recursion (stages 04-06) and the path tracer (07) give different values,
 * and are different labs' work: 04-06_extremes_glass.c runs the cases in
 * 04-06, 07_extremes_paths.c in 07, with the same tables and names.
 */
#ifndef EXTREMES_GLASS_H
#define EXTREMES_GLASS_H

#include <math.h>

#include "extremes/render.h"

/* ---- glass: exact Fresnel values --------------------------------------- */

/* Fresnel reflectance of unpolarised light at a smooth boundary, from the
 * cosine of incidence and the ratio n = n_t / n_i, written from Snell's
 * law and the amplitude coefficients (Born and Wolf 1.5.2), independently
 * of the stage's optics.c; 1 under total internal reflection. */
static inline double
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
static inline struct args
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
static inline void
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
    /* Near the silhouette F changes as 1/cos_i: float's rounding of the
     * hit point (~1e-7 of the scene) moves it by up to ~1e-3 there. */
    double tolerance = p->epsilon > 1e-10 ? 1e-2 : 1e-4;
    char counted[64];
    snprintf(counted, sizeof counted, "%d sphere pixels", sphere_pixels);
    struct image img;
    double nan = 0;
    struct args a = glass_args("4");
    if (render_judged(scene, &a, expected, tolerance, counted, o, &img, &nan)) {
        image_free(&img);
    }
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
static inline void
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
    char counted[64];
    snprintf(counted, sizeof counted, "%d slab pixels", slab_pixels);
    struct image img;
    double nan = 0;
    struct args a = glass_args("256");
    if (!render_judged(scene, &a, expected, 1e-4, counted, o, &img, &nan)) {
        return;
    }
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

/* The cases, by the names expect.tsv gives them. */
static const struct render_case glass_furnace_cases[] = {
    {"ior_1", run_furnace, 1, 0},
    {"ior_1.0001", run_furnace, 1.0001, 0},
    {"ior_2.42", run_furnace, 2.42, 0},
    {"ior_10", run_furnace, 10, 0},
};

static const struct render_case thin_glass_cases[] = {
    {"thin_glass_1e-5", run_thin_glass, 1e-5, 0},
};

#endif /* EXTREMES_GLASS_H */
