/*
 * picker.c - the light picker.  An emissive glTF material makes each of its
 * mesh's triangles a light, thousands of them; shadow rays to every one at
 * every shading point would cost in proportion to their number.  So the
 * emitting triangles are one light: a shading point sends its shadow rays
 * to one triangle i, picked with probability p_i, and divides what they
 * bring by p_i.  The expected value is the sum over all the triangles
 * (unbiased); the cost, one binary search.  p_i is in proportion to the
 * triangle's area, so a point drawn this way is uniform over the whole
 * emitting surface (Shirley, Wang and Zimmerman, "Monte Carlo Techniques
 * for Direct Lighting Calculations", 1996; stage 08 picks by power).
 */
#include "light.h"

#include <stdlib.h>

/* A light's share of the picks: a triangle's area; 0 for a light sampled on its own. */
static double
light_weight(const struct area_light *light)
{
    return light->triangle ? (double)area_light_area(light) : 0;
}

void
light_picker_free(struct light_picker *p)
{
    free(p->own);
    free(p->cdf);
    *p = (struct light_picker){0};
}

bool
light_picker_build(const struct scene *s, struct light_picker *p, struct diag *err)
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
        largest = fmax(largest, light_weight(&s->area_lights[i]));
    }
    double total = 0;
    for (int i = 0; i < n; i++) {
        if (!s->area_lights[i].triangle) {
            p->own[p->n_own++] = i;
        }
        total += largest > 0 ? light_weight(&s->area_lights[i]) / largest : 0;
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
light_pick(const struct light_picker *p, real u)
{
    /* The first bin ending past u (binary search; a light on its own has an empty one). */
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

real
light_pick_probability(const struct scene *s, const struct light_picker *p, int light)
{
    if (!p || !p->cdf || !s->area_lights[light].triangle) {
        return 1;
    }
    return (real)(p->cdf[light] - (light > 0 ? p->cdf[light - 1] : 0));
}
