/* camera.c - pinhole camera: film position to primary ray. */
#include "camera.h"

struct camera
camera_make(const struct camera_desc *desc, int width, int height)
{
    struct camera cam;
    cam.origin = desc->origin;
    cam.forward = vec3_normalize(vec3_sub(desc->target, desc->origin));
    cam.right = vec3_normalize(vec3_cross(cam.forward, desc->up));
    cam.up = vec3_cross(cam.right, cam.forward);
    cam.half_height = tan(desc->vfov_deg * PI / 360);
    cam.half_width = cam.half_height * (real)width / (real)height;
    cam.width = width;
    cam.height = height;
    return cam;
}

ray
camera_ray(const struct camera *cam, real film_x, real film_y)
{
    /* LAB 01: the ray through film position (film_x, film_y): map the film to the image
     * plane at distance 1 using half_width and half_height (docs/stages/01_raycast.md#lab)
     * stub: (void)film_x;
     * (void)film_y;
     * return (ray){cam->origin, cam->forward}; */
    /* Film to the image plane at distance 1: x from -half_width (left) to
     * +half_width (right), y from +half_height (top) to -half_height. */
    real x = (2 * film_x / (real)cam->width - 1) * cam->half_width;
    real y = (1 - 2 * film_y / (real)cam->height) * cam->half_height;
    vec3 d = vec3_madd(vec3_madd(cam->forward, cam->right, x), cam->up, y);
    return (ray){cam->origin, vec3_normalize(d)};
    /* END LAB */
}
