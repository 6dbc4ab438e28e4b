/*
 * light.h - light arriving directly from the scene's lights.
 */
#ifndef LIGHT_H
#define LIGHT_H

#include "diag.h"
#include "geometry.h"
#include "rng.h"
#include "scene.h"
#include "stats.h"
#include "vec3.h"

/* Irradiance (W/m^2 per channel) that a point source of intensity I at
 * `from` delivers to the surface at h: I cos(theta) / r^2, zero when the
 * light is behind the surface.  Occlusion is the caller's business. */
vec3 point_irradiance(const struct hit *h, vec3 from, vec3 intensity);

/* Where the shadow rays to a rectangle light go (ORDER: the
 * --light-sampling choices). */
enum rect_sampling {
    RECT_BY_AREA, /* uniform over its area */
    RECT_BY_SOLID_ANGLE, /* uniform in the solid angle it subtends (sample_rect_solid_angle()) */
    RECT_BY_SIZE, /* by solid angle where it looks large (RECT_LARGE), else by area */
};

/* How area lights are sampled: `samples` shadow rays per light, or, when
 * adaptive[0] > 0, adaptive[0] probe rays and adaptive[1] more only where
 * the probes disagree (a penumbra).  rect: how rectangles are sampled
 * (enum rect_sampling).
 * bsdf_pdf_cos: for multiple importance sampling, the density per unit
 * solid angle with which the path's bounce at this point draws a direction
 * of cosine cos(theta) to the normal, divided by that cosine (P(diffuse
 * lobe) / pi); each shadow ray's light is then weighted against it by the
 * power heuristic.  0: no MIS (weight 1).
 * lowdisc: with the Sobol sampler (render.c, not with adaptive), shadow ray
 * i of a vertex draws its numbers from point lowdisc_index * samples + i of
 * a 2D sequence of its own per light (seeded by lowdisc_seed and the
 * light's number); otherwise from the pixel's random stream. */
struct shadow_sampling {
    int samples;
    int adaptive[2];
    int rect;
    real bsdf_pdf_cos;
    bool lowdisc; /* the Sobol sampler: the rays' numbers from lowdisc.h */
    uint64_t lowdisc_seed; /* ... from sequences scrambled by this and the light */
    uint32_t lowdisc_index; /* ... at points lowdisc_index * samples + i */
};

/* The extra statistics counter: shading points that took the penumbra path. */
#define STAT_PENUMBRA 0

/*
 * Emitting triangles (the triangles of an emissive glTF mesh, thousands of
 * tiny lights) are sampled as one light: a triangle picked with probability
 * p_i proportional to its power Phi_i = pi A_i lum(L_i) (times 2 when it
 * emits from both sides; lum: the luminance of its radiance), then a point
 * y uniform on it.  y then has the density p_i / A_i per unit area, and,
 * seen from x, p_i / A_i * r^2 / |cos theta'| per unit solid angle
 * (dA = r^2 dw / |cos theta'|, r = |y - x|, theta' between the light's
 * normal and y - x).  Rectangle lights are sampled one by one as before.
 */
struct light_picker {
    int n; /* emitting triangles with non-zero power */
    int *light; /* their indices in the scene's area lights */
    real *cdf; /* cdf[k] = (Phi_0 + ... + Phi_k) / Phi, cdf[n - 1] = 1 */
    real *prob; /* per area light of the scene: p_i, 0 for rectangles */
};

/* Build the picker of the scene's emitting triangles.  False (err says
 * why) when memory runs out. */
bool light_picker_build(struct light_picker *lp, const struct scene *s, struct diag *err);

/* Free; accepts a zero-initialised picker. */
void light_picker_free(struct light_picker *lp);

/* Pick a triangle by power with u0 and a point y uniform on it with (u, v),
 * all three uniform in [0, 1).  Returns its area light's index and sets *y
 * and *pdf_area = p_i / A_i; -1 when there is no emitting triangle. */
int light_picker_sample(
    const struct light_picker *lp,
    const struct scene *s,
    real u0,
    real u,
    real v,
    vec3 *y,
    real *pdf_area);

/* The density per unit solid angle, seen from x, of the point y of area
 * light i as light_picker_sample draws it: p_i / A_i * r^2 / |cos theta'|;
 * 0 for a rectangle light or when y is seen edge-on. */
real light_picker_pdf_solid_angle(
    const struct light_picker *lp,
    const struct scene *s,
    int i,
    vec3 x,
    vec3 y);

/* The point of the light at (u, v) in [0,1)^2: uniform over its area. */
vec3 sample_area_light(const struct area_light *light, real u, real v);

/* A point *y of the rectangle light drawn from (u, v) in [0,1)^2 uniformly
 * in the solid angle it subtends seen from x (Urena, Fajardo and King, "An
 * Area-Preserving Parametrization for Spherical Rectangles", 2013), and
 * *pdf = 1 / that solid angle, per steradian.  False, and nothing set, when
 * the light is no rectangle (a parallelogram, a triangle), when x lies in
 * its plane, or when its solid angle is too small to compute accurately
 * (RECT_SOLID_ANGLE_MIN): the caller samples its area then. */
bool
sample_rect_solid_angle(const struct area_light *light, vec3 x, real u, real v, vec3 *y, real *pdf);

/* The power heuristic of multiple importance sampling (Veach and Guibas,
 * "Optimally Combining Sampling Techniques for Monte Carlo Rendering",
 * 1995, beta = 2): the weight of a sample that technique f drew (n_f
 * samples, density pdf_f) when technique g (n_g samples, density pdf_g)
 * could have drawn it too, (n_f pdf_f)^2 / ((n_f pdf_f)^2 + (n_g pdf_g)^2).
 * The two weights of one point sum to 1; 1 when g cannot draw it. */
real mis_power_heuristic(real n_f, real pdf_f, real n_g, real pdf_g);

/* The density per unit solid angle with which one shadow ray of
 * direct_irradiance() aimed at light number `light` (area lights, then
 * sphere lights: as hit.light) from x draws the direction to its point y;
 * 0 where it never draws it (x inside a sphere light, y seen edge-on). */
real light_pdf(
    const struct scene *s,
    const struct shadow_sampling *sampling,
    const struct light_picker *picker,
    int light,
    vec3 x,
    vec3 y);

/* For --pixel --trace (inspect.h), called only when inspecting: record the
 * shadow ray and, when it is not clear, the nearest surface in its way
 * (found by a second, closest-hit query). */
void inspect_shadow_ray(const struct world *w, ray shadow, real t_max, bool clear, struct stats *st);

/* Whether the segment from the surface at h to the point `to` is clear:
 * one shadow ray, an any-hit query. */
bool visible(const struct world *w, const struct hit *h, vec3 to, struct stats *st);

/* The fraction of light from `to` that reaches h: 1 or 0, glass included
 * (light through glass arrives along the path's own specular bounces). */
vec3 transmittance(const struct world *w, const struct hit *h, vec3 to, struct stats *st);

/* Irradiance at h from every light of the scene that h can see; area
 * lights are sampled with shadow rays as `sampling` says, the emitting
 * triangles together through `picker` (`samples` rays, no adaptive mode). */
vec3 direct_irradiance(
    const struct world *w,
    const struct hit *h,
    const struct shadow_sampling *sampling,
    const struct light_picker *picker,
    struct rng *rng,
    struct stats *st);

#endif /* LIGHT_H */
