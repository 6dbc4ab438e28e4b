/*
 * bsdf.h - how light scatters at each material, as a path tracer needs it:
 * a sampled direction to continue the path in, and the weight f cos / pdf
 * that keeps the estimate unbiased.
 */
#ifndef BSDF_H
#define BSDF_H

#include <stdbool.h>

#include "geometry.h"
#include "scene.h"
#include "vec3.h"

struct bsdf_sample {
    vec3 d; /* the new direction, unit */
    vec3 weight; /* f(d) |cos| / pdf(d), per channel */
    bool specular; /* a mirror or glass bounce: next-event estimation cannot find its light */
    const char *lobe; /* which lobe d was drawn from, for --trace: "diffuse", "mirror", ... */
    real pdf; /* d's density per steradian (diffuse), or its lobe's probability (specular) */
};

/* A cosine-weighted direction around +z (pdf cos(theta) / pi), from (u, v)
 * in [0,1)^2: a uniform point on the unit disk lifted to the hemisphere
 * (Malley's method; pbrt 4ed, A.5.3). */
vec3 sample_cosine_hemisphere(real u, real v);

/* Continue a path that arrived along d at h, where the material's diffuse
 * part has the given albedo: pick a lobe (diffuse, mirror, or glass
 * reflection or refraction) in proportion to what it reflects, by u[0],
 * then a direction, by u[1] and u[2] (three uniform numbers in [0, 1)).
 * False when the path ends here (nothing is reflected, or the direction
 * would pass through the surface). */
bool sample_bsdf(
    const struct material *m,
    vec3 albedo,
    const struct hit *h,
    vec3 d,
    const real u[3],
    struct bsdf_sample *out);

#endif /* BSDF_H */
