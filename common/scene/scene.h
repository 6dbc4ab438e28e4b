/*
 * scene.h - the scene every stage renders, and its text format's loader.
 *
 * The loader accepts the whole format (docs/scene-format.md); what a stage
 * does with each element is the stage's business.  The scene remembers which
 * features it uses and where each first appears, so a stage can say in one
 * line what it does not model (stages/course.h) or, with --strict, refuse.
 *
 * Conventions are those of SCENES.md: right-handed, y up, vertical field of
 * view in degrees, linear RGB, Lambertian BRDF albedo/pi, point-light
 * intensity in W/sr, one-sided quad area lights and emitting spheres with
 * radiance L.
 */
#ifndef SCENE_H
#define SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "diag.h"
#include "vec3.h"

/* Limits that keep a hostile scene file from asking for unbounded memory. */
#define SCENE_MAX_IMAGE_DIM 16384
#define SCENE_MAX_NAME 63
#define SCENE_MAX_MATERIALS 4096
#define SCENE_MAX_NOTES 32

/* The memory a scene's arrays (its elements, a mesh's vertices and
 * triangles) may take unless the caller sets another limit: render's
 * --max-memory (docs/robustness.md).  4 GiB. */
#define SCENE_DEFAULT_MAX_BYTES ((uint64_t)4 << 30)

/* A place in a scene file (1-based line and column; 0,0 = no place). */
struct src_loc {
    int line, col;
};

/* ORDER MAT_KIND: append only (docs and name tables follow this order). */
enum material_kind {
    MAT_DIFFUSE, /* Lambertian: albedo */
    MAT_MIRROR, /* perfect specular reflection: reflectance per channel */
    MAT_GLASS, /* smooth dielectric: ior inside, 1 outside; Fresnel */
    MAT_BLEND, /* classic Whitted surface: albedo (diffuse) + reflectance (mirror) */
    MAT_CHECKER, /* diffuse with a solid 3D checkerboard of albedo / albedo2 */
};

struct material {
    char name[SCENE_MAX_NAME + 1];
    enum material_kind kind;
    vec3 albedo; /* DIFFUSE, BLEND, CHECKER (the first colour) */
    vec3 albedo2; /* CHECKER: the second colour */
    real checker_size; /* CHECKER: edge of one cube of the pattern (scene units) */
    vec3 reflectance; /* MIRROR, BLEND */
    real ior; /* GLASS: index of refraction inside; outside is 1 */
    struct src_loc loc;
};

struct sphere {
    vec3 center;
    real radius;
    int material;
    int line; /* of its statement in the scene file (0: none), for --trace */
};

/* A parallelogram: corner + s*edge1 + t*edge2 for s, t in [0, 1].
 * Two-sided; its geometric normal is normalize(cross(edge1, edge2)). */
struct quad {
    vec3 corner, edge1, edge2;
    int material;
    int line; /* of its statement in the scene file (0: none), for --trace */
};

/* A triangle indexes the scene's shared vertex arrays.  When smooth is true
 * the shading normal interpolates the vertex normals (meshes that carry
 * them); otherwise it is the geometric normal. */
struct triangle {
    int v[3];
    int material;
    bool smooth;
    int line; /* of its `triangle` or `mesh` statement (0: a glTF scene), for --trace */
};

struct point_light {
    vec3 position;
    vec3 intensity; /* W/sr per channel */
    struct src_loc loc;
};

/* A surface emitting radiance L from the side its normal
 * normalize(cross(edge1, edge2)) points to (from both sides when
 * two_sided): the parallelogram corner + s*edge1 + t*edge2 for s, t in
 * [0, 1] (an `area_light` statement), or, when triangle is set, the triangle
 * with corners corner, corner + edge1, corner + edge2 (s + t <= 1: a
 * triangle of an emissive glTF mesh).  As a surface it is black on both
 * sides and blocks light like any other surface. */
struct area_light {
    vec3 corner, edge1, edge2;
    vec3 radiance;
    bool triangle;
    bool two_sided;
    struct src_loc loc;
};

/* A sphere emitting constant radiance L outward from every point of its
 * surface: a spherical area light.  As a surface it is black on both sides
 * and blocks light like any other surface. */
struct sphere_light {
    vec3 center;
    real radius;
    vec3 radiance;
    struct src_loc loc;
};

struct camera_desc {
    vec3 origin, target, up;
    real vfov_deg; /* vertical field of view, degrees, in (0, 180) */
    real near; /* camera rays start on the plane at this depth along the view (>= 0) */
};

/* ORDER FEATURE: append only; stages/course.c describes each. */
enum feature {
    FEAT_POINT_LIGHT,
    FEAT_AREA_LIGHT,
    FEAT_MIRROR,
    FEAT_GLASS,
    FEAT_BLEND,
    FEAT_CHECKER,
    FEAT_AMBIENT, /* a non-zero ambient term */
    FEAT_ENVIRONMENT, /* a non-black background, which lights the scene in 07 */
    FEAT_MESH, /* a triangle mesh loaded from a glTF file */
    FEAT_SPHERE_LIGHT, /* an emitting sphere */
    FEAT_COUNT,
};

#define FEATURE_BIT(f) (1u << (f))

struct scene {
    char path[512]; /* the scene file, as given */
    int width, height; /* image size in pixels */
    struct camera_desc camera;
    vec3 background; /* radiance of rays that leave the scene */
    vec3 ambient; /* ambient radiance term (default 0) */

    struct material *materials;
    int n_materials;
    struct sphere *spheres;
    int n_spheres;
    struct quad *quads;
    int n_quads;
    vec3 *positions; /* shared vertex arrays for triangles */
    vec3 *normals; /* unit vertex normals; (0,0,0) where a vertex has none */
    int n_vertices;
    struct triangle *triangles;
    int n_triangles;
    struct point_light *point_lights;
    int n_point_lights;
    struct area_light *area_lights;
    int n_area_lights;
    struct sphere_light *sphere_lights;
    int n_sphere_lights;

    char **input_files; /* files read besides the scene (meshes, buffers, images) */
    int n_input_files;

    unsigned features; /* FEATURE_BIT(f) for each feature used */
    struct src_loc feature_loc[FEAT_COUNT]; /* statement where each is first used */

    /* What the scene asks for that no stage models, beyond the features
     * (a glTF texture, a rough metal, a spot light...): one line per kind,
     * with the statement (or the glTF file) it comes from: what is not
     * modelled, "; ", what is done instead (stages/course.h).  Every stage
     * prints them as warnings; --strict refuses the scene. */
    struct diag notes[SCENE_MAX_NOTES];
    int n_notes;
};

/* Load a scene file.  On failure returns false, frees what was built and
 * fills err with FILE:LINE:COL and what was expected, what was found.
 * A path ending in .glb or .gltf (any case) is a glTF file taken as the
 * whole scene: its first camera, its lights, its meshes and materials
 * (docs/scene-format.md, "A glTF file as the scene").  The scene's arrays
 * may take at most SCENE_DEFAULT_MAX_BYTES. */
bool scene_load(const char *path, struct scene *out, struct diag *err);

/* Choices for loading a scene. */
struct scene_options {
    const char *camera; /* a glTF scene's camera by name; NULL: the file's first */
    uint64_t max_bytes; /* the scene's arrays may take at most this; 0: SCENE_DEFAULT_MAX_BYTES.
                           A statement that would need more is an error at that
                           statement, before anything is allocated for it. */
};

/* scene_load with options (opt may be NULL); a camera named for a scene
 * that is not a glTF file is an error. */
bool scene_load_with(
    const char *path,
    const struct scene_options *opt,
    struct scene *out,
    struct diag *err);

/* scene_load with the scene's arrays limited to max_bytes. */
bool scene_load_limited(const char *path, uint64_t max_bytes, struct scene *out, struct diag *err);

/* Same, from text in memory; `name` is the file name used in diagnostics and
 * the directory mesh files are found relative to. */
bool scene_load_string(
    const char *text,
    size_t len,
    const char *name,
    struct scene *out,
    struct diag *err);

/* Bytes held by the scene's arrays (counts times sizes). */
uint64_t scene_bytes(const struct scene *s);

/* Free everything; accepts a zero-initialised or half-built scene. */
void scene_free(struct scene *s);

/* The radiance an area light sends towards a ray that hit its front
 * (front_face: the side its normal points to) or its back. */
static inline vec3
area_light_emitted(const struct area_light *light, bool front_face)
{
    return front_face || light->two_sided ? light->radiance : vec3_splat(0);
}

/* The geometric normal of an area light (unit, the emitting side). */
static inline vec3
area_light_normal(const struct area_light *light)
{
    return vec3_normalize(vec3_cross(light->edge1, light->edge2));
}

/* |cross(edge1, edge2)| is the parallelogram's area, twice the triangle's. */
static inline real
area_light_area(const struct area_light *light)
{
    real parallelogram = vec3_length(vec3_cross(light->edge1, light->edge2));
    return light->triangle ? parallelogram / 2 : parallelogram;
}

/* The centroid: corner + (edge1 + edge2) / 2 for a parallelogram, / 3 for
 * a triangle. */
static inline vec3
area_light_center(const struct area_light *light)
{
    real f = light->triangle ? (real)1 / 3 : (real)0.5;
    return vec3_add(light->corner, vec3_scale(vec3_add(light->edge1, light->edge2), f));
}

/* The cosine of the angle between the light's normal n and the unit
 * direction d in which it sends light; negative values (the back) count
 * as |cos| for a two-sided light. */
static inline real
area_light_cos(const struct area_light *light, vec3 n, vec3 d)
{
    real c = vec3_dot(n, d);
    return light->two_sided ? fabs(c) : c;
}

/* The intensity (W/sr) of a point at a sphere light's centre that gives the
 * same irradiance as the sphere wherever all of it is above the horizon:
 * from outside, a sphere of radiance L and radius r subtends the solid angle
 * of a disc of area pi r^2 facing the viewer, so it acts as I = L pi r^2
 * (its irradiance at distance d is L pi (r/d)^2 cos(theta) = I cos / d^2). */
static inline vec3
sphere_light_intensity(const struct sphere_light *light)
{
    return vec3_scale(light->radiance, PI * light->radius * light->radius);
}

/* The radiance light number `light` sends towards a ray that hit its front
 * or its back: the area lights are numbered first, then the sphere lights
 * (which emit outward only: their front is the outside). */
static inline vec3
light_emitted(const struct scene *s, int light, bool front_face)
{
    if (light < s->n_area_lights) {
        return area_light_emitted(&s->area_lights[light], front_face);
    }
    return front_face ? s->sphere_lights[light - s->n_area_lights].radiance : vec3_splat(0);
}

#endif /* SCENE_H */
