/*
 * light_picker.h - the emitting triangles of a scene as one light.  An
 * emissive glTF material makes each of its mesh's triangles a light,
 * thousands of them (a car's lamps: 88,837); shadow rays to every one at
 * every shading point would cost in proportion to their number.  Instead
 * each shadow ray goes to one triangle i, picked with probability p_i, and
 * what it brings is divided by p_i: the expected value
 * is the sum over all the triangles (unbiased), the cost one binary search
 * (Shirley, Wang and Zimmerman, "Monte Carlo Techniques for Direct Lighting
 * Calculations", 1996).  Stages 03-07 pick in proportion to area (a pick
 * and a uniform point on the triangle are then a uniform point on the whole
 * emitting surface); stage 08 by power (its picker.c).
 */
#ifndef LIGHT_PICKER_H
#define LIGHT_PICKER_H

#include <stdbool.h>

#include "diag.h"
#include "scene.h"

/* The area lights as the shadow rays see them: each of own[0..n_own)
 * (`area_light` statements) on its own, and the emitting triangles as one
 * light, of which each shading point picks one by the cumulative shares
 * cdf[0..n) (NULL: no emitting triangle; a light on its own has an empty
 * share). */
struct light_picker {
    int *own;
    int n_own;
    double *cdf;
    int n;
};

/* A triangle light's share of the picks (> 0, finite). */
typedef double (*light_weight_fn)(const struct area_light *light);

/* The share stages 03-07 give a triangle: its area. */
double light_weight_area(const struct area_light *light);

/* The picker of s's area lights with triangles weighted by `weight`;
 * false (err set) when out of memory. */
bool light_picker_build(
    const struct scene *s,
    light_weight_fn weight,
    struct light_picker *p,
    struct diag *err);
void light_picker_free(struct light_picker *p);

/* The area light u in [0,1] picks (p->cdf must not be NULL); u = 1 picks
 * as u just below 1 does. */
int light_pick(const struct light_picker *p, double u);

/* The probability that area light `light` is picked: 1 for a light sampled
 * on its own, or without a picker (p NULL). */
double light_pick_probability(const struct scene *s, const struct light_picker *p, int light);

#endif /* LIGHT_PICKER_H */
