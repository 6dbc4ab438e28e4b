/*
 * stagecheck.h - helpers shared by the tests of stages 02-07 (shadows, soft
 * shadows, Whitted, path tracing): scenes written from a format string,
 * renders that also return their --stats, a render to stop with a signal,
 * the reference images of tests/reference/, and the small image statistics
 * those tests need beyond metrics.h (region means, per-pixel comparisons).
 */
#ifndef STAGECHECK_H
#define STAGECHECK_H

#include <stdbool.h>
#include <stddef.h>

#include "image.h"

struct rng;
struct scene;

/* Load a scene from its text (scene_load_string); on an error, print it
 * (FILE:LINE:COL: error: ...) and return false. */
bool stagecheck_load_text(const char *text, struct scene *out);

/* The unpolarised Fresnel reflectance of a smooth dielectric boundary from
 * the textbook (Hecht, Optics, eq. 4.34): the mean of r_s^2 and r_p^2 for
 * cos_i > 0 on the side the light comes from and eta = eta_i / eta_t; 1
 * past the critical angle.  Computed here, independently of a stage's
 * optics.c. */
double stagecheck_fresnel(double cos_i, double eta);

/* Write a scene file named `name` in the test's temporary directory from a
 * printf format; returns its path (valid until the program ends), or NULL
 * when the text does not fit or cannot be written. */
const char *stagecheck_scene(const char *name, const char *format, ...)
    __attribute__((format(printf, 2, 3)));

/* Render `scene` with the extra arguments `args` (NULL-terminated, may be
 * NULL) and, when stats is not NULL, also --stats into a temporary JSON file
 * whose path is stored in *stats (valid until the program ends).  Returns
 * false, with the binary's output printed, when the run fails. */
bool stagecheck_render(
    const char *scene,
    const char *const args[],
    struct image *out,
    const char **stats);

/* A render that runs until a signal stops it, for the tests that send one
 * (07_progressive.c, 07_signals.c): the stage's render (RENDER), quiet,
 * scenes/cornell_diffuse_area.scene at size x size pixels with --spp
 * 1000000 (hours of passes), its image to out and its --stats to stats. */
struct stagecheck_endless {
    char size[16];
    const char *argv[16]; /* NULL-terminated */
};

/* Fill run->argv; false (and a message) when RENDER is not set. */
bool stagecheck_endless_render(
    struct stagecheck_endless *run,
    int size,
    const char *out,
    const char *stats);

/* A numeric key of a --stats file; NaN (and a message) when it is missing. */
double stagecheck_stat(const char *stats, const char *key);

/* tests/reference/<name>.pfm; false (with a message) when it is missing. */
bool stagecheck_reference(const char *name, struct image *out);

/* relMSE of x against ref over ref's smooth pixels (metrics.h, 3x3 window
 * within METRICS_SMOOTH_TOLERANCE); *n_smooth gets their number.  NaN when
 * the sizes differ, no pixel is smooth or memory runs out. */
double stagecheck_relmse_smooth(const struct image *x, const struct image *ref, size_t *n_smooth);

/* Small vector algebra in double, for expected values computed
 * independently of the stage's vec3. */
double stagecheck_dot3(const double a[3], const double b[3]);
void stagecheck_cross3(const double a[3], const double b[3], double out[3]);
void stagecheck_normalize3(double a[3]);

/* Irradiance at the point x with unit normal n from a polygon of n_corners
 * corners and radiance L, wholly above x's horizon: L times the projected
 * solid angle, which by Lambert's formula (Photometria, 1760; Arvo,
 * "Applications of Irradiance Tensors", SIGGRAPH 1995, eq. 10) is
 *     E = L/2 |sum_i theta_i n . (v_i x v_i+1) / |v_i x v_i+1||
 * with v_i the unit vectors from x to the corners and theta_i the angle
 * between consecutive ones.  The polygon's orientation does not matter. */
double stagecheck_polygon_irradiance(
    double corners[][3],
    int n_corners,
    const double x[3],
    const double n[3],
    double radiance);

/* The solid angle a triangle subtends at x (Van Oosterom and Strackee,
 * "The Solid Angle of a Plane Triangle", IEEE Trans. Biomed. Eng., 1983):
 *     tan(Omega / 2) = |a . (b x c)| / (abc + (a.b) c + (a.c) b + (b.c) a)
 * with a, b, c the vectors from x to the corners and a, b, c also their
 * lengths. */
double stagecheck_triangle_solid_angle(double corners[3][3], const double x[3]);

/* A direction uniform on the unit sphere (Archimedes: z uniform in
 * [-1, 1], the azimuth uniform), from rng.h's generator.  (Plain doubles,
 * so that this header does not bring vec3.h's <tgmath.h> into tests that
 * do not want it.) */
void stagecheck_random_unit(struct rng *rng, double out[3]);

/* A soup of n_each spheres, quads and triangles in [-1, 1]^3, and four
 * quads ten times larger (rng.h before this header); false when the scene
 * does not load. */
struct scene;
bool stagecheck_random_soup(struct rng *rng, int n_each, struct scene *s);

#ifdef VEC3_H
/* The same as a vec3, for white-box tests (which include vec3.h, through
 * rng.h, before this header). */
static inline vec3
stagecheck_random_vec3(struct rng *rng)
{
    double d[3];
    stagecheck_random_unit(rng, d);
    return vec3_make((real)d[0], (real)d[1], (real)d[2]);
}
#endif

/* x, or the smallest relative distance this build's precision (real, see
 * vec3.h) resolves with margin, 1000 REAL_EPSILON, if that is larger:
 * tests that place things 1e-9 apart in double need 1e-4 in float. */
double stagecheck_resolvable(double x);

/* Whether a shape of size `size` placed `offset` from the origin is
 * resolved by this build's precision: REAL_EPSILON * offset <= 1e-4 * size
 * (a float scene 1 across at 1e5 is not). */
bool stagecheck_representable(double size, double offset);

/* Mean of channel c (0..2) over the w x h pixels from (x0, y0). */
double stagecheck_region_mean(const struct image *img, int x0, int y0, int w, int h, int c);

/* Whether pixel (x, y) and its 8 neighbours all lie within `tolerance`
 * (relative, every channel) of one another's centre value: the pixel is
 * not on an edge of img.  Border pixels are never interior. */
bool stagecheck_interior(const struct image *img, int x, int y, double tolerance);

/* The largest relative difference |a - b| / max(|b|, floor) over the
 * channels of one pixel. */
double stagecheck_pixel_reldiff(const float *a, const float *b, double floor);

#endif /* STAGECHECK_H */
