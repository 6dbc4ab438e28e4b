/*
 * camera.h - the pinhole camera of SCENES.md: vertical field of view,
 * pixel (0,0) at the top left, film coordinates in pixels.
 */
#ifndef CAMERA_H
#define CAMERA_H

#include "scene.h"
#include "vec3.h"

struct camera {
    vec3 origin;
    vec3 forward, right, up; /* orthonormal, right-handed: right = forward x up */
    real half_width; /* tan(vfov/2) * width/height: film half-extent at distance 1 */
    real half_height; /* tan(vfov/2) */
    real near; /* rays start on the plane at this depth along forward */
    int width, height; /* pixels */
};

/* Set up a camera for an image of width x height pixels.  desc has been
 * validated by the scene loader (origin != target, up not parallel). */
struct camera camera_make(const struct camera_desc *desc, int width, int height);

/* The ray through film position (film_x, film_y), in pixels from the top-left
 * corner of the image: pixel (px, py) covers [px, px+1) x [py, py+1), and its
 * centre is (px + 0.5, py + 0.5).  The direction is unit length; the
 * origin is where the ray crosses the near plane (the eye when near is 0). */
ray camera_ray(const struct camera *cam, real film_x, real film_y);

#endif /* CAMERA_H */
