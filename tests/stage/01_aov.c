/*
 * 01_aov.c - the render passes (--aov, docs/aov.md) against scenes whose
 * passes can be computed by hand:
 *   - depth: a plane at distance D straight ahead is D / cos(angle) away
 *     along the ray through each pixel centre (camera.h's film mapping);
 *   - normal: on a sphere, the unit vector from its centre to the point
 *     depth along the pixel's ray; 0 where nothing is hit;
 *   - albedo, id, material: the materials and primitive numbers of two
 *     spheres; -1 for the background; the albedo the stage shades with (a
 *     mirror's reflectance before stage 04 models mirrors, none from 04);
 *   - feature: a floor far from a sphere's shadow is diffuse-lit; mirror, glass and (from stage 03, where lights are
 *     surfaces) the light's own pixels are labelled as such; stage 01,
 *     which casts no shadow rays, sees no shadow (the shadows themselves,
 *     which the stage's shadow rays decide: 02_aov_labels.c);
 * and the contract: the files' names, an unknown pass (exit 2, every name
 * listed, nothing written), an output clash, the same passes with 1 and 3
 * threads, and no files without --aov.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "aovcheck.h"
#include "check.h"
#include "imgread.h"
#include "stagecheck.h"
#include "testlib.h"

#define W 40
#define H 30
#define FOV 50.0
#define PI_D 3.14159265358979323846

/* The unit direction of the ray through pixel (px, py)'s centre of a camera
 * at the origin looking down -z with up +y (camera.h, in double). */
static void
pixel_direction(int px, int py, double d[3])
{
    double hh = tan(FOV * PI_D / 360);
    double hw = hh * W / H;
    d[0] = (2 * (px + 0.5) / W - 1) * hw;
    d[1] = (1 - 2 * (py + 0.5) / H) * hh;
    d[2] = -1;
    stagecheck_normalize3(d);
}

static double
tolerance(void)
{
    return stagecheck_resolvable(1e-6) * 100;
}

TEST(depth_of_a_plane_at_a_known_distance)
{
    const double dist = 3.0;
    const char *scene = stagecheck_scene(
        "plane.scene",
        "camera origin 0 0 0 target 0 0 -1 up 0 1 0 fov %g\n"
        "image width %d height %d\n"
        "material grey diffuse albedo 0.5 0.5 0.5\n"
        "quad corner -100 -100 %g edge1 200 0 0 edge2 0 200 0 material grey\n"
        "point_light position 0 0 0 intensity 1 1 1\n",
        FOV,
        W,
        H,
        -dist);
    const char *out = scene ? aovcheck_render(scene, "plane.png", "depth", "2") : NULL;
    struct image depth = {0};
    CHECK(out && aovcheck_read(out, "depth", &depth));
    if (!depth.rgb) {
        return;
    }
    CHECK(depth.width == W && depth.height == H);
    double worst = 0;
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            double d[3];
            pixel_direction(x, y, d);
            double expected = dist / -d[2];
            const float *v = image_pixel(&depth, x, y);
            worst = fmax(worst, fabs(v[0] - expected) / expected);
            CHECK(v[0] == v[1] && v[1] == v[2]);
        }
    }
    CHECK_MSG(worst < tolerance(), "worst relative depth error %g", worst);
    image_free(&depth);
}

/* Two spheres side by side: a red diffuse one (primitive 0, material 1) on
 * the left and a mirror (primitive 1, material 2) on the right. */
static const char *
two_spheres(void)
{
    return stagecheck_scene(
        "spheres.scene",
        "camera origin 0 0 0 target 0 0 -1 up 0 1 0 fov %g\n"
        "image width %d height %d\n"
        "material unused diffuse albedo 0.1 0.2 0.3\n"
        "material red diffuse albedo 0.7 0.1 0.2\n"
        "material chrome mirror reflectance 0.9 0.9 0.9\n"
        "sphere center -0.8 0 -4 radius 0.7 material red\n"
        "sphere center 0.8 0 -4 radius 0.7 material chrome\n"
        "point_light position 0 5 0 intensity 10 10 10\n",
        FOV,
        W,
        H);
}

TEST(normal_albedo_id_and_material_of_two_spheres)
{
    const char *scene = two_spheres();
    const char *out =
        scene ? aovcheck_render(scene, "spheres.png", "normal,depth,albedo,id,material", "2")
              : NULL;
    struct image depth = {0}, normal = {0}, albedo = {0}, id = {0}, material = {0};
    CHECK(
        out && aovcheck_read(out, "depth", &depth) && aovcheck_read(out, "normal", &normal)
        && aovcheck_read(out, "albedo", &albedo) && aovcheck_read(out, "id", &id)
        && aovcheck_read(out, "material", &material));
    if (!material.rgb) {
        return;
    }
    const double centres[2][3] = {{-0.8, 0, -4}, {0.8, 0, -4}};
    /* The second sphere is a mirror: stages before 04 shade it as a
     * diffuse surface of its reflectance (stages/course.c), and the pass
     * shows the albedo the stage shades with. */
    double mirror = atoi(STAGE_NAME) >= 4 ? 0 : 0.9;
    const double albedos[2][3] = {{0.7, 0.1, 0.2}, {mirror, mirror, mirror}};
    int seen[2] = {0, 0};
    int background = 0;
    double worst_normal = 0;
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            const float *i = image_pixel(&id, x, y);
            const float *m = image_pixel(&material, x, y);
            const float *n = image_pixel(&normal, x, y);
            const float *a = image_pixel(&albedo, x, y);
            float t = image_pixel(&depth, x, y)[0];
            if (i[0] < 0) {
                background++;
                CHECK(i[0] == -1 && m[0] == -1 && t == 0);
                CHECK(n[0] == 0 && n[1] == 0 && n[2] == 0 && a[0] == 0);
                continue;
            }
            int s = (int)i[0];
            CHECK_MSG(s == 0 || s == 1, "id %g at (%d, %d)", i[0], x, y);
            if (s != 0 && s != 1) {
                continue;
            }
            seen[s]++;
            CHECK(m[0] == s + 1 && m[1] == m[0] && m[2] == m[0]);
            for (int c = 0; c < 3; c++) {
                CHECK_NEAR(a[c], albedos[s][c], 1e-6);
            }
            double d[3], expected[3];
            pixel_direction(x, y, d);
            for (int c = 0; c < 3; c++) {
                expected[c] = (t * d[c] - centres[s][c]) / 0.7;
            }
            for (int c = 0; c < 3; c++) {
                worst_normal = fmax(worst_normal, fabs(n[c] - expected[c]));
            }
        }
    }
    CHECK(seen[0] > 20 && seen[1] > 20 && background > 20);
    CHECK_MSG(worst_normal < 1e-3, "worst normal error %g", worst_normal);
    image_free(&depth);
    image_free(&normal);
    image_free(&albedo);
    image_free(&id);
    image_free(&material);
}

/* The feature label of what no shadow ray decides (the strip of
 * aovcheck.h): the far floor is diffuse-lit, glass and mirror are named, and the light's back is an emitter where the
 * stages make lights surfaces (from 03), else the floor under it, lit.
 * Stage 01 casts no shadow rays: the floor under the sphere is lit too.
 * (Shadows, penumbrae and caustics: 02_aov_labels.c.) */
TEST(feature_labels_name_surfaces_and_lights)
{
    struct image diffuse = {0}, glass = {0}, mirror = {0};
    CHECK(aovcheck_strip("diffuse albedo 0.5 0.5 0.5", "diffuse", &diffuse));
    CHECK(aovcheck_strip("glass ior 1.5", "glass", &glass));
    CHECK(aovcheck_strip("mirror reflectance 0.9 0.9 0.9", "mirror", &mirror));
    if (diffuse.rgb && glass.rgb && mirror.rgb) {
        CHECK(aovcheck_strip_label(&diffuse, -6) == AOVCHECK_LIT);
        CHECK(aovcheck_strip_label(&glass, 0) == AOVCHECK_GLASS);
        CHECK(aovcheck_strip_label(&mirror, 0) == AOVCHECK_MIRROR);
        /* The light (centre x = 3, 5 below the camera) over the floor's
         * x = 3 * 8 / 5. */
        int light = aovcheck_strip_label(&diffuse, 3 * AOVCHECK_STRIP_CAMERA / 5);
        int expected = atoi(STAGE_NAME) >= 3 ? AOVCHECK_EMITTER : AOVCHECK_LIT;
        CHECK_MSG(light == expected, "light: %d, not %d", light, expected);
        if (atoi(STAGE_NAME) == 1) {
            int under = aovcheck_strip_label(&diffuse, -1.5);
            CHECK_MSG(under == AOVCHECK_LIT, "stage 01 sees no shadow: %d", under);
        }
    }
    image_free(&diffuse);
    image_free(&glass);
    image_free(&mirror);
}

TEST(an_unknown_pass_is_refused_with_the_list_of_passes)
{
    const char *scene = two_spheres();
    const char *out = test_tmp_path("refused.png");
    const char *args[] = {"--aov", "depth,zdepth", "-o", out, NULL};
    char log[4096];
    CHECK(scene && test_render(scene, args, log, sizeof log) == 2);
    CHECK_MSG(
        strstr(log, "'zdepth'") && strstr(log, "depth, normal, albedo, id, material, feature"),
        "%s",
        log);
    const char *empty[] = {"--aov", "", "-o", out, NULL};
    CHECK(test_render(scene, empty, log, sizeof log) == 2);
    CHECK(!test_file_exists(out) && !test_file_exists(test_tmp_path("refused.depth.pfm")));
}

TEST(a_pass_that_would_overwrite_another_output_is_refused)
{
    const char *scene = two_spheres();
    const char *out = test_tmp_path("clash.png");
    const char *stats = test_tmp_path("clash.depth.pfm");
    const char *args[] = {"--aov", "depth", "--stats", stats, "-o", out, NULL};
    char log[4096];
    CHECK(scene && test_render(scene, args, log, sizeof log) == 2);
    CHECK_MSG(strstr(log, "--aov") != NULL, "%s", log);
    CHECK(!test_file_exists(out) && !test_file_exists(stats));
}

TEST(passes_do_not_depend_on_the_thread_count_and_cost_nothing_unasked)
{
    const char *scene = two_spheres();
    const char *one = scene ? aovcheck_render(scene, "one.png", "feature,normal", "1") : NULL;
    const char *three = scene ? aovcheck_render(scene, "three.png", "feature,normal", "3") : NULL;
    CHECK(one && three);
    if (one && three) {
        CHECK(test_same_file(test_tmp_path("one.feature.pfm"), test_tmp_path("three.feature.pfm")));
        CHECK(test_same_file(test_tmp_path("one.normal.pfm"), test_tmp_path("three.normal.pfm")));
        CHECK(test_same_file(one, three));
    }
    const char *plain = test_tmp_path("plain.png");
    const char *args[] = {"-o", plain, NULL};
    CHECK(scene && test_render(scene, args, NULL, 0) == 0);
    CHECK(test_count_files(test_tmpdir(), "plain.") == 1);
    CHECK(test_count_files(test_tmpdir(), ".stagelight-") == 0);
}

/* The memory estimate of --max-memory counts the passes: a refused
 * 2000x2000 render says it needs at least the six passes' 12 bytes per
 * pixel more with --aov than without. */
static double
estimated_mib(const char *scene, const char *aov)
{
    const char *args[] = {
        "-W",
        "2000",
        "-H",
        "2000",
        "--max-memory",
        "1",
        "-o",
        test_tmp_path("big.png"),
        aov ? "--aov" : NULL,
        aov,
        NULL};
    char log[4096];
    double mib = -1;
    const char *about =
        test_render(scene, args, log, sizeof log) == 1 ? strstr(log, "about ") : NULL;
    return about && sscanf(about, "about %lf MiB", &mib) == 1 ? mib : -1;
}

TEST(the_memory_estimate_counts_the_passes)
{
    const char *scene = two_spheres();
    double plain = scene ? estimated_mib(scene, NULL) : -1;
    double with = scene ? estimated_mib(scene, "depth,normal,albedo,id,material,feature") : -1;
    CHECK_MSG(
        plain > 0 && with - plain >= 6 * 12 * 4e6 / (1 << 20) - 1,
        "%g MiB, %g MiB with --aov",
        plain,
        with);
    CHECK(!test_file_exists(test_tmp_path("big.png")));
}

/* An .exr image holds the passes as its layers (depth.Z, normal.X/Y/Z,
 * feature.X), the same numbers as the .pfm files beside a .png, and no
 * file is written beside it. */
TEST(an_exr_image_holds_the_passes_as_layers)
{
    if (!image_exr_available()) {
        SKIP("built without OpenEXR");
    }
    const char *scene = two_spheres();
    const char *png =
        scene ? aovcheck_render(scene, "layers.png", "depth,normal,feature", "2") : NULL;
    const char *exr =
        scene ? aovcheck_render(scene, "layers.exr", "depth,normal,feature", "2") : NULL;
    CHECK(png && exr);
    if (!png || !exr) {
        return;
    }
    CHECK(test_count_files(test_tmpdir(), "layers.") == 5); /* layers.exr, layers.png, 3 .pfm */
    const char *passes[] = {"depth", "normal", "feature"};
    for (int i = 0; i < 3; i++) {
        struct image file = {0}, layer = {0};
        struct diag err;
        CHECK(aovcheck_read(png, passes[i], &file));
        CHECK_MSG(imgread_layer(exr, passes[i], &layer, &err), "%s", err.msg);
        size_t n = (size_t)W * H * 3;
        CHECK(
            file.rgb && layer.rgb && layer.width == W && layer.height == H
            && memcmp(file.rgb, layer.rgb, n * sizeof(float)) == 0);
        image_free(&file);
        image_free(&layer);
    }
    struct image none = {0};
    struct diag err;
    CHECK(!imgread_layer(exr, "albedo", &none, &err));
}

TEST_MAIN(
    TEST_ENTRY(depth_of_a_plane_at_a_known_distance),
    TEST_ENTRY(normal_albedo_id_and_material_of_two_spheres),
    TEST_ENTRY(feature_labels_name_surfaces_and_lights),
    TEST_ENTRY(an_unknown_pass_is_refused_with_the_list_of_passes),
    TEST_ENTRY(a_pass_that_would_overwrite_another_output_is_refused),
    TEST_ENTRY(passes_do_not_depend_on_the_thread_count_and_cost_nothing_unasked),
    TEST_ENTRY(an_exr_image_holds_the_passes_as_layers),
    TEST_ENTRY(the_memory_estimate_counts_the_passes))
