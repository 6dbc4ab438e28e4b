/*
 * 01_camera.c - the pinhole camera of SCENES.md: vertical field of view,
 * pixel (0,0) at the top left, no flip, any aspect ratio.
 */
#include "camera.h"
#include "check.h"

static const struct camera_desc cornell = {
    .origin = {0, 1, 3.9},
    .target = {0, 1, 0},
    .up = {0, 1, 0},
    .vfov_deg = 40,
};

/* atan2(|a x b|, a.b): accurate for small angles, unlike acos of a dot. */
static double
angle_between(vec3 a, vec3 b)
{
    return atan2((double)vec3_length(vec3_cross(a, b)), (double)vec3_dot(a, b));
}

TEST(centre_ray_is_forward)
{
    struct camera cam = camera_make(&cornell, 256, 256);
    ray r = camera_ray(&cam, 128, 128);
    CHECK_NEAR(r.d.x, 0, 1e-6);
    CHECK_NEAR(r.d.y, 0, 1e-6);
    CHECK_NEAR(r.d.z, -1, 1e-6);
    CHECK_NEAR(r.o.z, 3.9, 1e-6);
    CHECK_NEAR(vec3_length(r.d), 1, 1e-6);
}

TEST(vertical_fov_at_top_and_bottom_edges)
{
    struct camera cam = camera_make(&cornell, 256, 256);
    vec3 forward = {0, 0, -1};
    ray top = camera_ray(&cam, 128, 0);
    ray bottom = camera_ray(&cam, 128, 256);
    CHECK_NEAR(angle_between(top.d, forward), 20 * acos(-1.0) / 180, 1e-6);
    CHECK_NEAR(angle_between(bottom.d, forward), 20 * acos(-1.0) / 180, 1e-6);
    CHECK(top.d.y > 0); /* row 0 is the top of the picture */
    CHECK(bottom.d.y < 0);
}

TEST(horizontal_extent_follows_aspect_ratio)
{
    /* A 2:1 image: the vertical fov stays 40 degrees, the horizontal
     * half-extent is twice tan(20 degrees). */
    struct camera cam = camera_make(&cornell, 512, 256);
    ray left = camera_ray(&cam, 0, 128);
    ray right = camera_ray(&cam, 512, 128);
    double expected = atan(2 * tan(20 * acos(-1.0) / 180));
    CHECK_NEAR(angle_between(left.d, (vec3){0, 0, -1}), expected, 1e-6);
    CHECK(left.d.x < 0); /* column 0 is the left of the picture (red wall) */
    CHECK(right.d.x > 0);
}

TEST(corner_rays_match_the_pinhole_model)
{
    struct camera cam = camera_make(&cornell, 300, 200);
    double t = tan(20 * acos(-1.0) / 180);
    ray r = camera_ray(&cam, 0, 0); /* top-left corner of the film */
    vec3 expected = vec3_normalize((vec3){-t * 1.5, t, -1});
    CHECK_NEAR(r.d.x, expected.x, 1e-6);
    CHECK_NEAR(r.d.y, expected.y, 1e-6);
    CHECK_NEAR(r.d.z, expected.z, 1e-6);
}

TEST(tilted_camera_keeps_an_orthonormal_frame)
{
    struct camera_desc desc = {
        .origin = {3, 4, 5},
        .target = {-1, 0.5, 2},
        .up = {0.1, 1, 0.2},
        .vfov_deg = 65,
    };
    struct camera cam = camera_make(&desc, 64, 48);
    CHECK_NEAR(vec3_dot(cam.forward, cam.right), 0, 1e-6);
    CHECK_NEAR(vec3_dot(cam.forward, cam.up), 0, 1e-6);
    CHECK_NEAR(vec3_dot(cam.right, cam.up), 0, 1e-6);
    CHECK(cam.up.y > 0);
    ray centre = camera_ray(&cam, 32, 24);
    CHECK_NEAR(angle_between(centre.d, vec3_sub(desc.target, desc.origin)), 0, 1e-6);
}

/* The near plane by hand: a camera at the origin looking down -z with a 90
 * degree field of view on a 2 x 2 image has its film's top-left corner in
 * the direction (-1, 1, -1) (depth 1 along the view); with near 3 the ray
 * through that corner starts where it crosses z = -3, at (-3, 3, -3).  The
 * plane is at a depth along the view, so the centre ray starts at (0, 0, -3)
 * and every ray starts on z = -3.  near 0 (the default) starts at the eye. */
TEST(near_plane_moves_ray_origins_onto_the_plane)
{
    struct camera_desc desc = {
        .origin = {0, 0, 0},
        .target = {0, 0, -1},
        .up = {0, 1, 0},
        .vfov_deg = 90,
        .near = 3,
    };
    struct camera cam = camera_make(&desc, 2, 2);
    ray corner = camera_ray(&cam, 0, 0);
    double inv_sqrt3 = 1 / sqrt(3.0);
    CHECK_NEAR(corner.o.x, -3, 1e-12);
    CHECK_NEAR(corner.o.y, 3, 1e-12);
    CHECK_NEAR(corner.o.z, -3, 1e-12);
    CHECK_NEAR(corner.d.x, -inv_sqrt3, 1e-6);
    CHECK_NEAR(corner.d.y, inv_sqrt3, 1e-6);
    CHECK_NEAR(corner.d.z, -inv_sqrt3, 1e-6);
    ray centre = camera_ray(&cam, 1, 1);
    CHECK_NEAR(centre.o.x, 0, 1e-12);
    CHECK_NEAR(centre.o.y, 0, 1e-12);
    CHECK_NEAR(centre.o.z, -3, 1e-12);
    ray other = camera_ray(&cam, 1.7, 0.2);
    CHECK_NEAR(other.o.z, -3, 1e-12);
    desc.near = 0;
    cam = camera_make(&desc, 2, 2);
    corner = camera_ray(&cam, 0, 0);
    CHECK(corner.o.x == 0 && corner.o.y == 0 && corner.o.z == 0);
}

TEST_MAIN(
    TEST_ENTRY(centre_ray_is_forward),
    TEST_ENTRY(vertical_fov_at_top_and_bottom_edges),
    TEST_ENTRY(horizontal_extent_follows_aspect_ratio),
    TEST_ENTRY(corner_rays_match_the_pinhole_model),
    TEST_ENTRY(tilted_camera_keeps_an_orthonormal_frame),
    TEST_ENTRY(near_plane_moves_ray_origins_onto_the_plane))
