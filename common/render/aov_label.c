/*
 * aov_label.c - the feature pass's label of a hit (aov.h, aov_label_at):
 * what light reaches it.
 *
 * The label counts, for a diffuse point, how much of the direct light it
 * would receive with nothing in the way (each light's unoccluded
 * irradiance, summed over a fixed grid of points on every light) reaches it
 * unblocked, blocked, or only through glass.  The grid is the same for
 * every pixel, run and stage, and its shadow rays leave a surface as the
 * stage's own do (its spawn_ray_to): the label is a property of the scene,
 * and a reference's label mask is meaningful for any render of it.  A
 * stage that casts no shadow rays (01_raycast) sees nothing in the way.
 */
#include <math.h>

#include "aov.h"

/* Glass surfaces a shadow ray may cross before it counts as blocked. */
#define MAX_CROSSINGS 16

/* The mean of the three channels: how bright a radiance or intensity is,
 * for weighing lights against each other. */
static real
brightness(vec3 c)
{
    return (c.x + c.y + c.z) / 3;
}

/* What a shadow ray from p finds on its way to q. */
enum sight {
    SIGHT_CLEAR,
    SIGHT_BLOCKED,
    SIGHT_THROUGH_GLASS, /* only glass in the way: light reaches p refracted */
};

static bool
is_glass(const struct scene *s, int material)
{
    return material >= 0 && s->materials[material].kind == MAT_GLASS;
}

/* Follow the segment from the hit to q, crossing glass: each ray leaves
 * its surface as the stage's own rays do (its spawn_ray_to).  A stage
 * without it casts no shadow rays: nothing is in the way. */
static enum sight
sight_to(const struct aov_source *src, const struct scene *s, const struct aov_hit *from, vec3 q)
{
    if (!src->spawn_ray_to) {
        return SIGHT_CLEAR;
    }
    struct aov_hit at = *from;
    bool glass = false;
    for (int crossing = 0; crossing <= MAX_CROSSINGS; crossing++) {
        real t_max;
        ray r = src->spawn_ray_to(src->ctx, &at, q, &t_max);
        if (!(t_max > 0) || !src->first_hit(src->ctx, r, t_max, &at)) {
            break;
        }
        if (!is_glass(s, at.material)) {
            return SIGHT_BLOCKED;
        }
        glass = true;
    }
    return glass ? SIGHT_THROUGH_GLASS : SIGHT_CLEAR;
}

/* The unoccluded irradiance at p from each light sample, split by what the
 * shadow ray finds (units: whatever the lights' radiance is in, times sr). */
struct light_tally {
    real total, clear, through_glass;
};

/* A diffuse point being labelled: the stage's hit there, the scene and
 * the stage's ray queries. */
struct receiver {
    const struct aov_source *src;
    const struct scene *scene;
    const struct aov_hit *hit;
};

static void
tally(struct light_tally *t, const struct receiver *at, vec3 q, real weight)
{
    if (!(weight > 0)) {
        return;
    }
    t->total += weight;
    switch (sight_to(at->src, at->scene, at->hit, q)) {
    case SIGHT_CLEAR:
        t->clear += weight;
        break;
    case SIGHT_THROUGH_GLASS:
        t->through_glass += weight;
        break;
    case SIGHT_BLOCKED:
        break;
    }
}

/* cos(theta) / d^2 at p for light arriving from q, 0 from behind. */
static real
receiver_factor(vec3 p, vec3 n, vec3 q, vec3 *dir)
{
    vec3 d = vec3_sub(q, p);
    real d2 = vec3_length2(d);
    *dir = vec3_div(d, sqrt(d2));
    real c = vec3_dot(n, *dir);
    return c > 0 && d2 > 0 ? c / d2 : 0;
}

/* Grid cells per side on each area or sphere light: AOV_GRID, fewer when
 * many lights would take a pixel past AOV_MAX_RAYS. */
static int
grid_side(const struct scene *s)
{
    int lights = s->n_area_lights + s->n_sphere_lights;
    int k = AOV_GRID;
    while (k > 1 && lights * k * k > AOV_MAX_RAYS) {
        k--;
    }
    return k;
}

/* Grid point (i, j) of k x k on light number `light` (the area lights,
 * then the sphere lights): its position q, the unit normal there on the
 * emitting side, the area of its cell and the light's brightness. */
static void
grid_point(
    const struct scene *s,
    int light,
    int i,
    int j,
    int k,
    vec3 *q,
    vec3 *nq,
    real *cell_area,
    real *radiance)
{
    real u = ((real)i + (real)0.5) / (real)k;
    real v = ((real)j + (real)0.5) / (real)k;
    if (light < s->n_area_lights) {
        const struct area_light *a = &s->area_lights[light];
        if (a->triangle) {
            /* The square onto the triangle, area-preserving (Shirley:
             * barycentrics 1 - sqrt(u), sqrt(u) v). */
            real su = sqrt(u);
            u = su * (1 - v);
            v = su * v;
        }
        *q = vec3_madd(vec3_madd(a->corner, a->edge1, u), a->edge2, v);
        *nq = area_light_normal(a);
        *cell_area = area_light_area(a) / (real)(k * k);
        *radiance = brightness(a->radiance);
        return;
    }
    const struct sphere_light *b = &s->sphere_lights[light - s->n_area_lights];
    /* Equal-area cells of the sphere: z uniform in [-1, 1] (Archimedes),
     * the azimuth uniform. */
    real z = 1 - 2 * u;
    real phi = 2 * PI * v;
    real ring = safe_sqrt(1 - z * z);
    *nq = vec3_make(ring * cos(phi), ring * sin(phi), z);
    *q = vec3_madd(b->center, *nq, b->radius);
    *cell_area = 4 * PI * b->radius * b->radius / (real)(k * k);
    *radiance = brightness(b->radiance);
}

/* Whether light number `light` sends light from its point q with normal nq
 * in direction d (an area light: from its emitting side; a sphere light:
 * outward). */
static real
emitting_cos(const struct scene *s, int light, vec3 nq, vec3 d)
{
    if (light < s->n_area_lights) {
        return area_light_cos(&s->area_lights[light], nq, d);
    }
    return vec3_dot(nq, d);
}

static void
tally_light(struct light_tally *t, const struct receiver *at, int light, int k)
{
    for (int j = 0; j < k; j++) {
        for (int i = 0; i < k; i++) {
            vec3 q, nq, dir;
            real cell_area, radiance;
            grid_point(at->scene, light, i, j, k, &q, &nq, &cell_area, &radiance);
            real g = receiver_factor(at->hit->p, at->hit->n, q, &dir);
            real cos_light = emitting_cos(at->scene, light, nq, vec3_neg(dir));
            tally(t, at, q, cos_light > 0 ? radiance * g * cos_light * cell_area : 0);
        }
    }
}

/* The label of a diffuse point: how much of its unoccluded direct light
 * reaches it. */
static enum aov_label
diffuse_label(const struct aov_source *src, const struct scene *s, const struct aov_hit *h)
{
    const struct receiver at = {src, s, h};
    struct light_tally t = {0};
    for (int i = 0; i < s->n_point_lights; i++) {
        const struct point_light *light = &s->point_lights[i];
        vec3 dir;
        real g = receiver_factor(h->p, h->n, light->position, &dir);
        tally(&t, &at, light->position, brightness(light->intensity) * g);
    }
    int k = grid_side(s);
    for (int light = 0; light < s->n_area_lights + s->n_sphere_lights; light++) {
        tally_light(&t, &at, light, k);
    }
    if (t.through_glass > 0) {
        return LABEL_CAUSTIC;
    }
    if (t.clear <= 0) {
        return LABEL_UMBRA;
    }
    return t.clear < t.total ? LABEL_PENUMBRA : LABEL_LIT;
}

enum aov_label
aov_label_at(const struct aov_source *src, const struct scene *scene, const struct aov_hit *h)
{
    if (h->material < 0) {
        return LABEL_EMITTER;
    }
    switch (scene->materials[h->material].kind) {
    case MAT_MIRROR:
        return LABEL_MIRROR;
    case MAT_GLASS:
        return LABEL_GLASS;
    case MAT_DIFFUSE:
    case MAT_BLEND:
    case MAT_CHECKER:
        break;
    }
    return diffuse_label(src, scene, h);
}
