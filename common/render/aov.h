/*
 * aov.h - render passes (arbitrary output variables, `--aov LIST`): beside
 * the image, what each pixel shows, as data: how far the first surface is,
 * which way it faces, its colour, which primitive and material it is, and a
 * label of what kind of light reaches it (docs/aov.md).
 *
 * A pass's value is that of the ray through the pixel's centre, whatever
 * the stage's sampling: the passes have no noise.  Every ray is the
 * stage's own (struct aov_source: its camera ray, its first-hit query with
 * the albedo it shades with, its ray off a surface); what is here is the
 * bookkeeping, so the passes describe the scene, not the stage's
 * approximation of its light: the `feature` label counts shadow rays from
 * a fixed grid of points on every light, and does not depend on the
 * stage's shadow sampling.
 */
#ifndef AOV_H
#define AOV_H

#include <stdbool.h>

#include "diag.h"
#include "driver.h"
#include "image.h"
#include "scene.h"
#include "vec3.h"

/* ORDER AOV_PASS: the passes, in the order aov_pass_names lists them. */
enum aov_pass {
    AOV_DEPTH, /* distance from the eye to the first hit (0: nothing hit) */
    AOV_NORMAL, /* its shading normal, unit, world space, turned to the camera */
    AOV_ALBEDO, /* its diffuse colour (0 for mirror, glass and lights) */
    AOV_ID, /* its primitive's index in the stage's list (-1: nothing hit) */
    AOV_MATERIAL, /* its material's index in the scene file (-1: none) */
    AOV_FEATURE, /* enum aov_label */
    AOV_COUNT,
};

/* The pass names of --aov, indexed by enum aov_pass. */
extern const char *const aov_pass_names[AOV_COUNT];

/* The channels of each pass as a layer of an OpenEXR image ("depth.Z",
 * "normal.X"..., "albedo.R"..., "id.X", "material.X", "feature.X"). */
extern const char *const aov_exr_channels[AOV_COUNT];

/* ORDER AOV_LABEL: what a pixel of the feature pass shows (its value is the
 * number); append only, the references' masks store these numbers. */
enum aov_label {
    LABEL_BACKGROUND, /* nothing hit */
    LABEL_LIT, /* a diffuse surface every light sample of which is visible */
    LABEL_PENUMBRA, /* ... some of its light samples visible, some blocked */
    LABEL_UMBRA, /* ... none visible (blocked, or all behind the surface) */
    LABEL_MIRROR, /* a mirror */
    LABEL_GLASS, /* glass */
    LABEL_CAUSTIC, /* a diffuse surface some of whose light comes through glass */
    LABEL_EMITTER, /* a light's surface */
    LABEL_COUNT,
};

/* The label names (docs/aov.md), indexed by enum aov_label. */
extern const char *const aov_label_names[LABEL_COUNT];

/* The first surface along a ray, as the passes need it. */
struct aov_hit {
    real t; /* distance along the unit direction */
    vec3 p; /* the point */
    vec3 n; /* shading normal, unit, on the side the ray came from */
    int prim; /* index in the stage's primitive list */
    int material; /* index in scene->materials; -1 for a light's surface */
    vec3 albedo; /* the diffuse albedo the stage shades the point with */
    vec3 ng; /* the stage's geometric normal, and its bound on p's */
    real error; /* rounding error: what its spawn_ray_to needs */
};

/* What a stage supplies: the ray through a film position in pixels
 * (camera.h's camera_ray), the closest hit along a ray with t in
 * (0, t_max) (geometry.h's world_intersect, the albedo from render.c), and
 * the ray from a hit towards a point (geometry.h's spawn_ray_to: the
 * stage's own offset off the surface, and t_max short of the point); NULL
 * in a stage without shadow rays, whose feature pass then sees nothing in
 * the way of any light, as the stage does (01_raycast). */
struct aov_source {
    const void *ctx;
    ray (*camera_ray)(const void *ctx, real film_x, real film_y);
    bool (*first_hit)(const void *ctx, ray r, real t_max, struct aov_hit *out);
    ray (*spawn_ray_to)(const void *ctx, const struct aov_hit *from, vec3 to, real *t_max);
};

/* Parse a comma-separated list of pass names into a bit set (bit
 * 1u << pass).  An unknown or empty name is an error naming every pass. */
bool aov_parse_list(const char *text, unsigned *passes, struct diag *err);

/* Whether the passes of an image written to image_path are layers of it
 * (an .exr image) rather than files beside it. */
bool aov_as_layers(const char *image_path);

/* The file a pass goes to when it is not a layer of an EXR image: the
 * image's path without its extension, then ".PASS.pfm" (out.png gives
 * out.depth.pfm).  False when it does not fit in cap. */
bool aov_path(const char *image_path, enum aov_pass pass, char *buf, size_t cap);

/* Shadow rays per light the feature label takes, at most (a grid of
 * AOV_GRID x AOV_GRID on each area or sphere light, fewer per light when
 * there are many lights so that a pixel takes at most AOV_MAX_RAYS). */
#define AOV_GRID 8
#define AOV_MAX_RAYS 256

/* The passes of one pixel, from the ray through its centre (px + 0.5,
 * py + 0.5): out[pass] receives the value of each pass in the bit set
 * `passes` (one number in all three channels for depth, id, material and
 * feature). */
void aov_pixel(
    const struct aov_source *src,
    const struct scene *scene,
    unsigned passes,
    int px,
    int py,
    vec3 out[AOV_COUNT]);

/* Every pixel of the passes in the bit set `passes`, each into its image
 * out[pass] (allocated here at the job's size), on the job's threads with
 * its progress bar.  False when memory or threads could not be had (err
 * says which) or when the run was interrupted (*interrupted; nothing is
 * allocated then). */
bool aov_render(
    const struct aov_source *src,
    const struct scene *scene,
    unsigned passes,
    const struct render_job *like,
    struct image out[AOV_COUNT],
    bool *interrupted,
    struct diag *err);

/* The label of a surface point (exposed for tests). */
enum aov_label
aov_label_at(const struct aov_source *src, const struct scene *scene, const struct aov_hit *h);

#endif /* AOV_H */
