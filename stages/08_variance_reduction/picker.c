/*
 * picker.c - the light picker: of the emitting triangles (of a glTF mesh,
 * thousands of them), the shadow rays of a path vertex go to one, picked in
 * proportion to its power (Shirley, Wang and Zimmerman, "Monte Carlo
 * Techniques for Direct Lighting Calculations", 1996), not to every one;
 * dividing by the pick's probability keeps the estimate unbiased.
 */
#include "light.h"

#include <stdlib.h>

/* A triangle light's power over pi (area x luminance, x 2 two-sided); 0 for the others. */
static real
light_power(const struct area_light *light)
{
    vec3 l = light->radiance;
    real luminance = (real)0.2126 * l.x + (real)0.7152 * l.y + (real)0.0722 * l.z;
    return light->triangle ? area_light_area(light) * luminance * (light->two_sided ? 2 : 1) : 0;
}

bool
light_picker_build(const struct scene *s, real **cdf, struct diag *err)
{
    int n = s->n_area_lights;
    *cdf = malloc((size_t)(n + 1) * sizeof **cdf);
    if (!*cdf) {
        diag_set(err, NULL, 0, 0, "out of memory for the picker of %d lights", n);
        return false;
    }
    real total = 0;
    for (int i = 0; i < n; i++) {
        total += light_power(&s->area_lights[i]);
        (*cdf)[i] = total;
    }
    for (int i = 0; i < n; i++) {
        /* The last bins end at 1 exactly: every u < 1 finds a light. */
        (*cdf)[i] = (*cdf)[i] == total ? 1 : (*cdf)[i] / total;
    }
    if (!(total > 0)) {
        free(*cdf); /* no emitting triangle: nothing to pick */
        *cdf = NULL;
    }
    return true;
}

real
light_pick_probability(
    const struct scene *s,
    const struct shadow_sampling *sampling,
    const struct area_light *light)
{
    const real *cdf = sampling->pick_cdf;
    int i = (int)(light - s->area_lights);
    return !cdf || !light->triangle ? 1 : cdf[i] - (i > 0 ? cdf[i - 1] : 0);
}

const struct area_light *
light_pick(const struct scene *s, const real *cdf, real u)
{
    /* The first bin ending past u (binary search; the others' are empty). */
    int lo = 0;
    int hi = s->n_area_lights - 1;
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (cdf[mid] > u) {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    return &s->area_lights[lo];
}
