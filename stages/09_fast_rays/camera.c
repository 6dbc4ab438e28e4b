/* camera.c - pinhole camera: film position to primary ray. */
#include "camera.h"

/*
 * v / |v| for any finite non-zero v.  vec3_normalize squares the
 * components: for a target 1e-200 from the origin, or an up vector 1e-200
 * long, the squared length underflows to 0; for an up vector 1e200 long it
 * overflows, and every ray would go to the image centre.  Such a v is first
 * divided by its largest component, which brings the squared length into
 * [1, 3]; an ordinary v is normalised exactly as before.
 */
static vec3
unit_vector(vec3 v)
{
    if (isnormal(vec3_length2(v))) {
        return vec3_normalize(v);
    }
    real largest = vec3_max_comp(vec3_abs(v));
    return vec3_normalize(vec3_div(v, largest));
}

struct camera
camera_make(const struct camera_desc *desc, int width, int height)
{
    struct camera cam;
    cam.origin = desc->origin;
    vec3 view = vec3_sub(desc->target, desc->origin);
    if (!vec3_is_finite(view)) {
        /* Origin and target near the largest number: halves cannot overflow. */
        view = vec3_sub(vec3_scale(desc->target, (real)0.5), vec3_scale(desc->origin, (real)0.5));
    }
    cam.forward = unit_vector(view);
    cam.right = unit_vector(vec3_cross(cam.forward, desc->up));
    cam.up = vec3_cross(cam.right, cam.forward);
    cam.half_height = tan(desc->vfov_deg * PI / 360);
    cam.half_width = cam.half_height * (real)width / (real)height;
    cam.near = desc->near;
    cam.width = width;
    cam.height = height;
    return cam;
}

ray
camera_ray(const struct camera *cam, real film_x, real film_y)
{
    /* LAB 01: camera ray */
    /* Film to the image plane at distance 1: x from -half_width (left) to
     * +half_width (right), y from +half_height (top) to -half_height. */
    real x = (2 * film_x / (real)cam->width - 1) * cam->half_width;
    real y = (1 - 2 * film_y / (real)cam->height) * cam->half_height;
    vec3 d = vec3_madd(vec3_madd(cam->forward, cam->right, x), cam->up, y);
    /* d reaches depth 1 along forward (right and up are perpendicular to
     * it), so origin + near d is where the ray crosses the near plane. */
    return (ray){vec3_madd(cam->origin, d, cam->near), vec3_normalize(d)};
    /* END LAB */
}
