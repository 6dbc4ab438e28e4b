/*
 * 01-05_lambert.c - direct light against the analytic formula
 * L = albedo/pi * I cos(theta) / r^2 at chosen (unshadowed) pixels of the
 * point-light Cornell scene, computed here independently of the renderer,
 * and the ambient term.  Stages 01-05 trace one ray through each pixel
 * centre, which is what the formula evaluates.
 */
#include "check.h"
#include "testlib.h"

#ifdef REAL_IS_FLOAT
#define REL_TOL 2e-4
#else
#define REL_TOL 1e-5
#endif

static const double eye[3] = {0, 1, 3.9};

/* The film position of a world point, from SCENES.md's pinhole model
 * (camera looking down -z, vertical fov 40, 256x256). */
static void
project(const double p[3], double *fx, double *fy)
{
    double t = tan(20 * acos(-1.0) / 180);
    double dz = eye[2] - p[2];
    *fx = 128 * (1 + (p[0] - eye[0]) / dz / t);
    *fy = 128 * (1 - (p[1] - eye[1]) / dz / t);
}

/* Radiance at pixel (px, py) whose centre ray meets the plane
 * coordinate[axis] = level with the given normal: Lambert with one point
 * light, no occlusion. */
static double
expected_radiance(
    int px,
    int py,
    int axis,
    double level,
    const double normal[3],
    double albedo,
    double intensity)
{
    double t = tan(20 * acos(-1.0) / 180);
    double d[3] = {((px + 0.5) / 128 - 1) * t, (1 - (py + 0.5) / 128) * t, -1};
    double s = (level - eye[axis]) / d[axis];
    double q[3] = {eye[0] + s * d[0], eye[1] + s * d[1], eye[2] + s * d[2]};
    double l[3] = {0 - q[0], 1.9 - q[1], 0 - q[2]};
    double r2 = l[0] * l[0] + l[1] * l[1] + l[2] * l[2];
    double cosine = (l[0] * normal[0] + l[1] * normal[1] + l[2] * normal[2]) / sqrt(r2);
    return albedo / acos(-1.0) * intensity * cosine / r2;
}

static void
check_pixel(const struct image *img, int px, int py, double expected_red)
{
    double got = image_pixel(img, px, py)[0];
    CHECK_MSG(
        fabs(got - expected_red) <= REL_TOL * expected_red,
        "pixel (%d, %d): %.9g, expected %.9g",
        px,
        py,
        got,
        expected_red);
}

TEST(floor_and_ceiling_pixels_match_lambert)
{
    struct image img = {0};
    const char *scene = test_root_path("scenes/cornell_diffuse_point.scene");
    if (!test_render_image(scene, NULL, &img)) {
        CHECK(false);
        return;
    }
    static const double floor_points[][3] = {{0, 0, 0}, {-0.5, 0, 0.7}, {0.6, 0, 0.8}, {0, 0, 0.9}};
    static const double up[3] = {0, 1, 0};
    for (int i = 0; i < 4; i++) {
        double fx;
        double fy;
        project(floor_points[i], &fx, &fy);
        int px = (int)fx;
        int py = (int)fy;
        check_pixel(&img, px, py, expected_radiance(px, py, 1, 0, up, 0.73, 3.0));
    }
    static const double down[3] = {0, -1, 0};
    static const double ceiling[3] = {0.3, 2, 0.5};
    double fx;
    double fy;
    project(ceiling, &fx, &fy);
    check_pixel(&img, (int)fx, (int)fy, expected_radiance((int)fx, (int)fy, 1, 2, down, 0.73, 3.0));
    image_free(&img);
}

TEST(ambient_term_alone)
{
    static const char text[] = "camera origin 0 0 5 target 0 0 0 up 0 1 0 fov 30\n"
                               "image width 9 height 9\n"
                               "ambient color 0.2 0.4 0.8\n"
                               "material grey diffuse albedo 0.5 0.25 1\n"
                               "sphere center 0 0 0 radius 1 material grey\n";
    const char *scene = test_tmp_path("ambient.scene");
    test_write_file(scene, text);
    struct image img = {0};
    if (!test_render_image(scene, NULL, &img)) {
        CHECK(false);
        return;
    }
    float *centre = image_pixel(&img, 4, 4);
    float *corner = image_pixel(&img, 0, 0);
    CHECK_NEAR(centre[0], 0.1, 1e-7);
    CHECK_NEAR(centre[1], 0.1, 1e-7);
    CHECK_NEAR(centre[2], 0.8, 1e-7);
    CHECK_NEAR(corner[0], 0, 0);
    image_free(&img);
}

TEST_MAIN(TEST_ENTRY(floor_and_ceiling_pixels_match_lambert), TEST_ENTRY(ambient_term_alone))
