/*
 * 01-02_area_point.c - before stage 03 an area light is lit as a point
 * light at its centre with intensity L * A * cos(angle to its normal).
 * Straight below a light of radiance L and area A at height h, that gives
 * irradiance E = L A / h^2 and radiance albedo/pi * E.  A sphere light is
 * lit as a point at its centre of intensity L pi r^2, and not seen.
 */
#include "check.h"
#include "testlib.h"

TEST(area_light_as_point_light_at_its_centre)
{
    /* A 1x1 camera looking straight down at (0,0,0) from below the light. */
    static const char text[] =
        "camera origin 0 1 0 target 0 0 0 up 0 0 -1 fov 1\n"
        "image width 1 height 1\n"
        "material white diffuse albedo 0.5 0.5 0.5\n"
        "quad corner -10 0 -10 edge1 20 0 0 edge2 0 0 20 material white\n"
        "area_light corner -0.1 2 -0.1 edge1 0.2 0 0 edge2 0 0 0.2 radiance 5 5 5\n";
    const char *scene = test_tmp_path("area.scene");
    test_write_file(scene, text);
    struct image img = {0};
    if (!test_render_image(scene, NULL, &img)) {
        CHECK(false);
        return;
    }
    double expected = 0.5 / acos(-1.0) * 5 * 0.04 / 4;
    CHECK_NEAR(img.rgb[0], expected, 1e-6 * expected);
    image_free(&img);
}

TEST(area_light_lights_nothing_behind_it)
{
    static const char text[] =
        "camera origin 0 2.5 0 target 0 3 0 up 0 0 -1 fov 1\n"
        "image width 1 height 1\n"
        "material white diffuse albedo 0.5 0.5 0.5\n"
        "quad corner -10 3 -10 edge1 20 0 0 edge2 0 0 20 material white\n"
        "area_light corner -0.1 2 -0.1 edge1 0.2 0 0 edge2 0 0 0.2 radiance 5 5 5\n";
    const char *scene = test_tmp_path("behind.scene");
    test_write_file(scene, text);
    struct image img = {0};
    if (!test_render_image(scene, NULL, &img)) {
        CHECK(false);
        return;
    }
    CHECK(img.rgb[0] == 0);
    image_free(&img);
}

/* A floor point at the origin lit by a sphere light of radiance 5 and
 * radius 0.5 at (0.3, 2, 0): E = I cos(theta) / d^2 with I = 5 pi 0.25,
 * d^2 = 4.09, cos(theta) = 2 / d; the camera, below the sphere, looks down
 * at the point.  Looked at, the sphere itself is not drawn. */
TEST(sphere_light_as_point_light_at_its_centre)
{
    static const char text[] = "camera origin 0 1 0 target 0 0 0 up 0 0 -1 fov 1\n"
                               "image width 1 height 1\n"
                               "material white diffuse albedo 0.5 0.5 0.5\n"
                               "quad corner -10 0 -10 edge1 20 0 0 edge2 0 0 20 material white\n"
                               "sphere_light center 0.3 2 0 radius 0.5 radiance 5 5 5\n";
    const char *scene = test_tmp_path("sphere.scene");
    test_write_file(scene, text);
    struct image img = {0};
    if (!test_render_image(scene, NULL, &img)) {
        CHECK(false);
        return;
    }
    double pi = acos(-1.0);
    double d2 = 0.3 * 0.3 + 2 * 2;
    double expected = 0.5 / pi * (5 * pi * 0.25) * (2 / sqrt(d2)) / d2;
    CHECK_NEAR(img.rgb[0], expected, 1e-6 * expected);
    image_free(&img);
    // Seen straight on, the sphere is not drawn: the floor behind it is.
    static const char seen[] = "camera origin 0.3 2 3 target 0.3 2 0 up 0 1 0 fov 1\n"
                               "image width 1 height 1\n"
                               "sphere_light center 0.3 2 0 radius 0.5 radiance 5 5 5\n";
    scene = test_tmp_path("seen.scene");
    test_write_file(scene, seen);
    if (test_render_image(scene, NULL, &img)) {
        CHECK(img.rgb[0] == 0);
        image_free(&img);
    } else {
        CHECK(false);
    }
}

TEST_MAIN(
    TEST_ENTRY(area_light_as_point_light_at_its_centre),
    TEST_ENTRY(sphere_light_as_point_light_at_its_centre),
    TEST_ENTRY(area_light_lights_nothing_behind_it))
