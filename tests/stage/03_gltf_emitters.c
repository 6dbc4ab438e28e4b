/*
 * 03_gltf_emitters.c - an emissive glTF mesh is a light (emitting
 * triangles, docs/scene-format.md), through the stage's binary; from the
 * stage that models area lights on.
 *
 *  - A generated square of two triangles with emissiveFactor (1, 0.5,
 *    0.25) and KHR_materials_emissive_strength 8, facing down, lights a
 *    floor as the `area_light` of the same rectangle and radiance
 *    (8, 4, 2) does: the floor's mean agrees within 2% (both estimates
 *    are noisy: 256 shadow rays per light, or 16 paths of 16 from 06 on), and
 *    the camera sees exactly that radiance on it.
 *  - The same square cut into 100,352 triangles (2,048 before stage 05's
 *    BVH) lights the floor the same,
 *    and a shading point sends no more shadow rays than to one light: the
 *    triangles are picked (light_picker.h), not visited one by one.
 *  - One-sided unless doubleSided: seen from above, the square is black;
 *    with doubleSided it shows its radiance.
 *  - scenes/cornell_blocks.gltf, the library's scene written as glTF
 *    (docs/blender.md), renders from the file alone under --strict: nothing
 *    is dropped, and its light shows its colour (12, 10, 8).
 * The floor is black-free and the light black as a surface, so no light is
 * reflected twice: global illumination (07) changes nothing expected.
 */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "meshgen.h"
#include "stagecheck.h"
#include "testlib.h"

#define HALF 0.3
#define HEIGHT 1.5

/* The square x, z in [-HALF, HALF] at y = HEIGHT, cut into cells x cells
 * squares of two triangles each, wound clockwise seen from above so that
 * its front (glTF's counter-clockwise side) faces down. */
static const char *
write_lamp(const char *name, bool double_sided, int cells)
{
    struct meshgen_mesh m = {0};
    size_t side = (size_t)cells + 1;
    if (!meshgen_alloc(&m, side * side, 2 * (size_t)cells * (size_t)cells, false)) {
        CHECK(false);
        return NULL;
    }
    for (size_t j = 0; j < side; j++) {
        for (size_t i = 0; i < side; i++) {
            double *v = &m.positions[3 * (j * side + i)];
            v[0] = -HALF + 2 * HALF * (double)i / cells;
            v[1] = HEIGHT;
            v[2] = -HALF + 2 * HALF * (double)j / cells;
        }
    }
    unsigned *t = m.indices;
    for (size_t j = 0; j < (size_t)cells; j++) {
        for (size_t i = 0; i < (size_t)cells; i++) {
            unsigned v00 = (unsigned)(j * side + i);
            unsigned v10 = v00 + 1;
            unsigned v01 = v00 + (unsigned)side;
            unsigned v11 = v01 + 1;
            unsigned two[6] = {v00, v10, v11, v00, v11, v01};
            memcpy(t, two, sizeof two);
            t += 6;
        }
    }
    char material[256];
    snprintf(
        material,
        sizeof material,
        "{\"name\":\"lamp\",\"doubleSided\":%s,\"emissiveFactor\":[1,0.5,0.25],"
        "\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1]},\"extensions\":"
        "{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":8}}}",
        double_sided ? "true" : "false");
    struct meshgen_glb_options opts = {.material = material};
    char file[64];
    snprintf(file, sizeof file, "%s.glb", name);
    const char *path = test_tmp_path(file);
    bool ok = meshgen_write_glb(&m, path, &opts);
    meshgen_free(&m);
    CHECK_MSG(ok, "cannot write %s", path);
    return ok ? path : NULL;
}

#define FLOOR \
    "material floor diffuse albedo 0.5 0.5 0.5\n" \
    "quad corner -4 0 -4 edge1 0 0 8 edge2 8 0 0 material floor\n"

/* The floor below the light and, at the top of the image, the light. */
#define SIDE_CAMERA \
    "camera origin 0 0.8 2.5 target 0 0.6 0 up 0 1 0 fov 60\nimage width 48 height 48\n"

static double
mean(const struct image *img, int c)
{
    return stagecheck_region_mean(img, 0, 0, img->width, img->height, c);
}

/* The index of the pixel brightest in red: where the light is seen. */
static size_t
brightest_pixel(const struct image *img)
{
    size_t at = 0;
    for (size_t i = 0; i < (size_t)img->width * (size_t)img->height; i++) {
        at = img->rgb[3 * i] > img->rgb[3 * at] ? i : at;
    }
    return at;
}

/* Shadow rays per light at a shading point in render(): 256 where a pixel
 * has one ray, 16 where it has 16 (from stage 06 on). */
static int
shadow_samples(void)
{
    return strcmp(STAGE_NAME, "06_supersample") >= 0 ? 16 : 256;
}

/* Render scene with `shadow` shadow rays per light at a shading point
 * (16 paths a pixel from stage 06 on), its --stats into *stats unless NULL. */
static bool
render(const char *scene, int shadow, struct image *out, const char **stats)
{
    char count[16];
    snprintf(count, sizeof count, "%d", shadow);
    const char *const args[] = {"-s", "16", "--shadow-samples", count, NULL};
    bool samples = strcmp(STAGE_NAME, "06_supersample") >= 0;
    return stagecheck_render(scene, samples ? args : args + 2, out, stats);
}

/* The floor lit by a lamp of cells x cells squares (2 cells^2 emitting
 * triangles) against the `area_light` of the same rectangle and radiance,
 * with `shadow` shadow rays a shading point; the stats of the lamp's render
 * into *stats. */
static void
check_lamp_lights_like_the_area_light(int cells, int shadow, const char **stats)
{
    REQUIRE_GLTF();
    if (!write_lamp("lamp", false, cells)) {
        return;
    }
    const char *mesh = stagecheck_scene("mesh.scene", SIDE_CAMERA FLOOR "mesh file lamp.glb\n");
    const char *rect = stagecheck_scene(
        "rect.scene",
        SIDE_CAMERA FLOOR "area_light corner %g %g %g edge1 %g 0 0 edge2 0 0 %g radiance 8 4 2\n",
        -HALF,
        HEIGHT,
        -HALF,
        2 * HALF,
        2 * HALF);
    struct image a = {0};
    struct image b = {0};
    if (!mesh || !rect || !render(mesh, shadow, &a, stats) || !render(rect, shadow, &b, NULL)) {
        CHECK(false);
        image_free(&a);
        return;
    }
    for (int c = 0; c < 3; c++) {
        double ma = mean(&a, c);
        double mb = mean(&b, c);
        printf(
            "%d triangles, channel %d: emissive mesh %.6g, area light %.6g\n",
            2 * cells * cells,
            c,
            ma,
            mb);
        CHECK_MSG(fabs(ma - mb) < 0.02 * mb, "channel %d: %g vs %g", c, ma, mb);
    }
    /* The light's radiance where the camera sees it. */
    size_t at = brightest_pixel(&a);
    CHECK_NEAR(a.rgb[3 * at], 8, 1e-5);
    CHECK_NEAR(a.rgb[3 * at + 1], 4, 1e-5);
    CHECK_NEAR(a.rgb[3 * at + 2], 2, 1e-5);
    image_free(&a);
    image_free(&b);
}

TEST(emissive_square_lights_like_the_area_light)
{
    check_lamp_lights_like_the_area_light(1, shadow_samples(), NULL);
}

/* 18,432 emitting triangles (a glTF car's lamps have 88,837; 100,352 here
 * cost 0.3 processor s more a grade and count the same): each shadow ray
 * of a shading point goes to one of them, picked (light_picker.h), so a
 * vertex costs what one light costs whatever their number, and the floor
 * is lit as by the one rectangle they tile.  Before stage 05 every ray
 * tests every triangle (no BVH), so stages 03-04 have 2,048 of them: the
 * shadow rays' count is the picker's all the same.
 * 16 shadow rays a point (not 256): lab 05's untouched handout traverses
 * by brute force. */
TEST(many_emitting_triangles_cost_what_one_light_costs)
{
    const char *stats = NULL;
    check_lamp_lights_like_the_area_light(atoi(STAGE_NAME) >= 5 ? 96 : 32, 16, &stats);
    if (!stats) {
        return;
    }
    double shadow = stagecheck_stat(stats, "rays_shadow");
    double vertices =
        stagecheck_stat(stats, "rays_camera") + stagecheck_stat(stats, "rays_secondary");
    printf("%.0f shadow rays from %.0f rays' hits\n", shadow, vertices);
    CHECK_MSG(
        shadow <= 16 * vertices,
        "%.0f shadow rays for %.0f rays: more than 16 a hit",
        shadow,
        vertices);
}

/* The camera above the light, looking down at its back. */
#define TOP_CAMERA "camera origin 0 3 0 target 0 0 0 up 0 0 -1 fov 10\nimage width 8 height 8\n"

TEST(one_sided_unless_double_sided)
{
    REQUIRE_GLTF();
    if (!write_lamp("one", false, 1) || !write_lamp("two", true, 1)) {
        return;
    }
    const char *one = stagecheck_scene("one.scene", TOP_CAMERA FLOOR "mesh file one.glb\n");
    const char *two = stagecheck_scene("two.scene", TOP_CAMERA FLOOR "mesh file two.glb\n");
    struct image a = {0};
    struct image b = {0};
    if (!one || !two || !render(one, shadow_samples(), &a, NULL)
        || !render(two, shadow_samples(), &b, NULL)) {
        CHECK(false);
        image_free(&a);
        return;
    }
    /* The whole view is the light's back. */
    for (int c = 0; c < 3; c++) {
        CHECK_NEAR(mean(&a, c), 0, 0);
        CHECK_NEAR(mean(&b, c), c == 0 ? 8 : c == 1 ? 4 : 2, 1e-5);
    }
    image_free(&a);
    image_free(&b);
}

TEST(library_scene_written_as_gltf_renders_strict)
{
    REQUIRE_GLTF();
    const char *scene = test_root_path("scenes/cornell_blocks.gltf");
    const char *const args[] = {"--strict", "-W", "32", NULL};
    const char *const to_file[] = {"--strict", "-W", "32", "-o", test_tmp_path("blocks.pfm"), NULL};
    static char text[4096];
    CHECK_MSG(test_render(scene, to_file, text, sizeof text) == 0, "%s", text);
    CHECK_MSG(strstr(text, "warning") == NULL, "%s", text);
    struct image img = {0};
    if (!test_render_image(scene, args, &img)) {
        CHECK(false);
        return;
    }
    CHECK(img.width == 32 && img.height == 32);
    size_t at = brightest_pixel(&img);
    /* The light, seen at a grazing angle, covers part of its pixels (a
     * supersampled pixel averages it with the dim ceiling): at most its
     * radiance, in about its proportions 12 : 10 : 8. */
    const float *l = &img.rgb[3 * at];
    CHECK_MSG(l[0] > 1 && l[0] <= 12 * (1 + 1e-5), "%g", l[0]);
    CHECK_NEAR(l[1] / l[0], 10.0 / 12, 0.03);
    CHECK_NEAR(l[2] / l[0], 8.0 / 12, 0.03);
    CHECK(mean(&img, 1) > 0.01);
    image_free(&img);
}

TEST_MAIN(
    TEST_ENTRY(emissive_square_lights_like_the_area_light),
    TEST_ENTRY(many_emitting_triangles_cost_what_one_light_costs),
    TEST_ENTRY(one_sided_unless_double_sided),
    TEST_ENTRY(library_scene_written_as_gltf_renders_strict))
