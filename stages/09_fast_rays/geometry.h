/*
 * geometry.h - where a ray meets the scene.
 *
 * The scene's shapes are numbered as one list of primitives: spheres first,
 * then quads, then triangles, then the area lights and the sphere lights
 * (surfaces too: they are seen and they cast shadows).  Intersection routines compute only the ray
 * parameter t (and the surface coordinates u, v); hit_finish() computes the
 * point and normals once, for the closest hit.
 */
#ifndef GEOMETRY_H
#define GEOMETRY_H

#include <stdbool.h>

#include "bvh.h"
#include "scene.h"
#include "stats.h"
#include "vec3.h"

struct hit {
    real t; /* distance along the (unit) ray direction */
    real u, v; /* surface coordinates: barycentric for triangles, edge fractions for quads */
    int prim; /* index in the primitive list */
    vec3 p; /* the hit point */
    vec3 ng; /* geometric normal, unit, facing the ray's origin */
    vec3 n; /* shading normal, unit, on the same side as ng */
    bool front_face; /* the ray arrived on the side the outward normal points to */
    int material;
    real error; /* bound on |computed p - true surface point| (scene units) */
    int light; /* the light hit (area lights, then sphere lights: light_radiance), or -1 */
};

/* The shapes a ray can hit: the scene's, numbered as one list. */
struct world {
    const struct scene *scene;
    int n_prims;
    struct bvh bvh; /* none (n_prims 0): test every primitive, the reference */
};

struct world world_make(const struct scene *s);

/* Nearest intersection with t in (0, t_max); the direction must be unit. */
bool intersect_sphere(const struct sphere *sphere, ray r, real t_max, real *t);
bool intersect_quad(const struct quad *quad, ray r, real t_max, real *t, real *u, real *v);
bool intersect_triangle(vec3 p0, vec3 p1, vec3 p2, ray r, real t_max, real *t, real *u, real *v);

/* Intersect primitive `prim`; on a hit with t < t_max, fill t, u, v, prim. */
bool intersect_prim(const struct scene *s, int prim, ray r, real t_max, struct hit *out);

/* Point, normals, side and material of a hit found by intersect_prim. */
void hit_finish(const struct scene *s, ray r, struct hit *h);

/* The closest hit along r with t in (0, t_max), finished; false on a miss. */
bool world_intersect(const struct world *w, ray r, real t_max, struct hit *out, struct stats *st);

/* Whether anything blocks r for t in (0, t_max): stops at the first hit. */
bool world_occluded(const struct world *w, ray r, real t_max, struct stats *st);

/* A ray leaving the surface at h in unit direction d, its origin pushed off
 * the surface, to the side d points to, by the hit point's error bound. */
ray spawn_ray(const struct hit *h, vec3 d);

/* A ray from the surface at h towards the point `to`, and in *t_max the
 * distance it may travel before reaching `to` (less the rounding error of
 * `to` itself, so a surface that `to` lies on does not count). */
ray spawn_ray_to(const struct hit *h, vec3 to, real *t_max);

#endif /* GEOMETRY_H */
