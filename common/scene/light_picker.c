/*
 * light_picker.c - the emitting triangles as one light (light_picker.h).
 */
#include "light_picker.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

/* A light's weight, finite: an overflow (a vast bright triangle) counts as the largest double. */
static double
finite_weight(light_weight_fn weight, const struct area_light *light)
{
    double w = weight(light);
    return w > DBL_MAX ? DBL_MAX : w;
}

double
light_weight_area(const struct area_light *light)
{
    return (double)area_light_area(light);
}

void
light_picker_free(struct light_picker *p)
{
    free(p->own);
    free(p->cdf);
    *p = (struct light_picker){0};
}

bool
light_picker_build(
    const struct scene *s,
    light_weight_fn weight,
    struct light_picker *p,
    struct diag *err)
{
    int n = s->n_area_lights;
    *p = (struct light_picker){.n = n};
    p->own = malloc((size_t)(n + 1) * sizeof *p->own);
    p->cdf = malloc((size_t)(n + 1) * sizeof *p->cdf);
    if (!p->own || !p->cdf) {
        light_picker_free(p);
        diag_set(err, NULL, 0, 0, "out of memory for the picker of %d lights", n);
        return false;
    }
    /* Weights over the largest: a sum of at most n terms <= 1 cannot overflow. */
    double largest = 0;
    for (int i = 0; i < n; i++) {
        const struct area_light *l = &s->area_lights[i];
        largest = l->triangle ? fmax(largest, finite_weight(weight, l)) : largest;
    }
    double total = 0;
    for (int i = 0; i < n; i++) {
        const struct area_light *l = &s->area_lights[i];
        if (!l->triangle) {
            p->own[p->n_own++] = i;
        } else if (largest > 0) {
            total += finite_weight(weight, l) / largest;
        }
        p->cdf[i] = total;
    }
    for (int i = 0; i < n; i++) {
        /* The last bins end at 1 exactly: every u < 1 finds a light. */
        p->cdf[i] = p->cdf[i] == total ? 1 : p->cdf[i] / total;
    }
    if (!(total > 0)) {
        free(p->cdf); /* no emitting triangle: nothing to pick */
        p->cdf = NULL;
    }
    return true;
}

int
light_pick(const struct light_picker *p, double u)
{
    /* A stratified u = (k + v) / n may round up to 1 (in float, about once
     * in a million picks): it stands for the last bin, as u just below 1. */
    if (!(u < 1)) {
        u = nextafter(1.0, 0.0);
    }
    /* The first bin ending past u (binary search). */
    int lo = 0;
    int hi = p->n - 1;
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (p->cdf[mid] > u) {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    return lo;
}

double
light_pick_probability(const struct scene *s, const struct light_picker *p, int light)
{
    if (!p || !p->cdf || !s->area_lights[light].triangle) {
        return 1;
    }
    return p->cdf[light] - (light > 0 ? p->cdf[light - 1] : 0);
}
