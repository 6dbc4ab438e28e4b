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
 *   - feature: under a sphere lit by a square light, the shadow's centre is
 *     umbra, far away is diffuse-lit, and between them penumbra, in that
 *     order along a line; under a glass sphere the shadow is a caustic;
 *     mirror, glass and (from stage 03, where lights are surfaces) the
 *     light's own pixels are labelled as such; stage 01, which casts no
 *     shadow rays, sees no shadow: the floor is lit everywhere;
 * and the contract: the files' names, an unknown pass (exit 2, every name
 * listed, nothing written), an output clash, the same passes with 1 and 3
 * threads, and no files without --aov.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "imgread.h"
#include "stagecheck.h"
#include "testlib.h"

#define W 40
#define H 30
#define FOV 50.0
#define PI_D 3.14159265358979323846

/* A pass written beside `image` (aov.h's naming: the stem, the pass,
 * .pfm); false with a message when it cannot be read. */
static bool
read_pass(const char *image, const char *pass, struct image *out)
{
    char path[1024];
    snprintf(path, sizeof path, "%.*s.%s.pfm", (int)(strrchr(image, '.') - image), image, pass);
    struct diag err;
    if (!image_read_pfm(path, out, &err)) {
        printf("cannot read %s: %s\n", path, err.msg);
        return false;
    }
    return true;
}

/* Render scene with --aov passes into a PNG named `name` in the temporary
 * directory; its path, or NULL (with the output printed) on failure. */
static const char *
render_passes(const char *scene, const char *name, const char *passes, const char *threads)
{
    const char *out = test_tmp_path(name);
    const char *args[] = {"--aov", passes, "-t", threads, "-o", out, NULL};
    char log[4096];
    int status = test_render(scene, args, log, sizeof log);
    if (status != 0) {
        printf("render --aov %s failed (status %d):\n%s\n", passes, status, log);
        return NULL;
    }
    return out;
}

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
    const char *out = scene ? render_passes(scene, "plane.png", "depth", "2") : NULL;
    struct image depth = {0};
    CHECK(out && read_pass(out, "depth", &depth));
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
        scene ? render_passes(scene, "spheres.png", "normal,depth,albedo,id,material", "2") : NULL;
    struct image depth = {0}, normal = {0}, albedo = {0}, id = {0}, material = {0};
    CHECK(
        out && read_pass(out, "depth", &depth) && read_pass(out, "normal", &normal)
        && read_pass(out, "albedo", &albedo) && read_pass(out, "id", &id)
        && read_pass(out, "material", &material));
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

/* A floor (y = 0) seen from straight above, under a sphere of material
 * `ball` (centre (0, 1, 0), radius 0.8) and a 0.8 x 0.8 light at height 3
 * centred at x = 3, facing down: the sphere's shadow is centred at
 * x = -1.5 (the line from the light's centre through the sphere's).  The
 * image is a strip along the x axis; returns the feature pass. */
#define STRIP_W 160
#define STRIP_H 20
#define STRIP_FOV 30.0
#define CAMERA_HEIGHT 8.0

static bool
strip_labels(const char *ball, const char *name, struct image *feature)
{
    char scene_name[64], image_name[64];
    snprintf(scene_name, sizeof scene_name, "%s.scene", name);
    snprintf(image_name, sizeof image_name, "%s.png", name);
    const char *scene = stagecheck_scene(
        scene_name,
        "camera origin 0 %g 0 target 0 0 0 up 0 0 -1 fov %g\n"
        "image width %d height %d\n"
        "material grey diffuse albedo 0.5 0.5 0.5\n"
        "material ball %s\n"
        "quad corner -50 0 -50 edge1 0 0 100 edge2 100 0 0 material grey\n"
        "sphere center 0 1 0 radius 0.8 material ball\n"
        "area_light corner 2.6 3 -0.4 edge1 0.8 0 0 edge2 0 0 0.8 radiance 4 4 4\n",
        CAMERA_HEIGHT,
        STRIP_FOV,
        STRIP_W,
        STRIP_H,
        ball);
    const char *out = scene ? render_passes(scene, image_name, "feature", "2") : NULL;
    return out && read_pass(out, "feature", feature);
}

/* The column of the strip's image where the floor's point at x is seen. */
static int
strip_column(double x)
{
    double half_width = tan(STRIP_FOV * PI_D / 360) * STRIP_W / STRIP_H;
    return (int)floor((x / CAMERA_HEIGHT / half_width + 1) * STRIP_W / 2);
}

static int
strip_label(const struct image *f, double x)
{
    return (int)image_pixel(f, strip_column(x), STRIP_H / 2)[0];
}

/* enum aov_label's numbers (docs/aov.md). */
enum {
    BACKGROUND,
    LIT,
    PENUMBRA,
    UMBRA,
    MIRROR,
    GLASS,
    CAUSTIC,
    EMITTER
};

/* Whether the stage casts shadow rays (from 02): stage 01 sees nothing in
 * the way of a light, and its feature pass says so (aov_label.c). */
static bool
casts_shadow_rays(void)
{
    return atoi(STAGE_NAME) >= 2;
}

TEST(feature_labels_along_a_shadow)
{
    struct image f = {0};
    CHECK(strip_labels("diffuse albedo 0.5 0.5 0.5", "shadow", &f));
    if (!f.rgb) {
        return;
    }
    if (!casts_shadow_rays()) {
        CHECK_MSG(strip_label(&f, -1.5) == LIT, "no shadow: %d", strip_label(&f, -1.5));
        CHECK(strip_label(&f, -6) == LIT && strip_label(&f, 0) == LIT);
        image_free(&f);
        return;
    }
    CHECK_MSG(strip_label(&f, -1.5) == UMBRA, "shadow centre: %d", strip_label(&f, -1.5));
    CHECK_MSG(strip_label(&f, -6) == LIT, "far floor: %d", strip_label(&f, -6));
    /* Leftwards from the shadow's centre: umbra, then penumbra, then lit,
     * never back. */
    int order[] = {UMBRA, PENUMBRA, LIT};
    int at = 0, penumbra = 0;
    for (int x = strip_column(-1.5); x >= 0; x--) {
        int label = (int)image_pixel(&f, x, STRIP_H / 2)[0];
        penumbra += label == PENUMBRA;
        while (at < 3 && label != order[at]) {
            at++;
        }
        CHECK_MSG(at < 3, "column %d: label %d out of the order umbra, penumbra, lit", x, label);
        if (at == 3) {
            break;
        }
    }
    CHECK_MSG(penumbra >= 2, "%d penumbra pixels between umbra and lit", penumbra);
    /* The sphere's top faces the light: lit. */
    CHECK(strip_label(&f, 0) == LIT);
    /* The light's back (centre x = 3, 5 below the camera) is seen where
     * stages make it a surface (from 03), over the floor's x = 3 * 8 / 5. */
    int light = strip_label(&f, 3 * CAMERA_HEIGHT / 5);
    CHECK_MSG(atoi(STAGE_NAME) >= 3 ? light == EMITTER : light == LIT, "light: %d", light);
    image_free(&f);
}

TEST(glass_casts_a_caustic_and_specular_surfaces_are_named)
{
    struct image glass = {0}, mirror = {0};
    CHECK(strip_labels("glass ior 1.5", "glass", &glass));
    CHECK(strip_labels("mirror reflectance 0.9 0.9 0.9", "mirror", &mirror));
    if (!glass.rgb || !mirror.rgb) {
        image_free(&glass);
        return;
    }
    int under_glass = casts_shadow_rays() ? CAUSTIC : LIT;
    int under_mirror = casts_shadow_rays() ? UMBRA : LIT;
    CHECK_MSG(
        strip_label(&glass, -1.5) == under_glass,
        "under glass: %d",
        strip_label(&glass, -1.5));
    CHECK(strip_label(&glass, 0) == GLASS);
    CHECK(strip_label(&glass, -6) == LIT);
    CHECK_MSG(
        strip_label(&mirror, -1.5) == under_mirror,
        "under the mirror: %d",
        strip_label(&mirror, -1.5));
    CHECK(strip_label(&mirror, 0) == MIRROR);
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
    const char *one = scene ? render_passes(scene, "one.png", "feature,normal", "1") : NULL;
    const char *three = scene ? render_passes(scene, "three.png", "feature,normal", "3") : NULL;
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
        scene ? render_passes(scene, "layers.png", "depth,normal,feature", "2") : NULL;
    const char *exr =
        scene ? render_passes(scene, "layers.exr", "depth,normal,feature", "2") : NULL;
    CHECK(png && exr);
    if (!png || !exr) {
        return;
    }
    CHECK(test_count_files(test_tmpdir(), "layers.") == 5); /* layers.exr, layers.png, 3 .pfm */
    const char *passes[] = {"depth", "normal", "feature"};
    for (int i = 0; i < 3; i++) {
        struct image file = {0}, layer = {0};
        struct diag err;
        CHECK(read_pass(png, passes[i], &file));
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
    TEST_ENTRY(feature_labels_along_a_shadow),
    TEST_ENTRY(glass_casts_a_caustic_and_specular_surfaces_are_named),
    TEST_ENTRY(an_unknown_pass_is_refused_with_the_list_of_passes),
    TEST_ENTRY(a_pass_that_would_overwrite_another_output_is_refused),
    TEST_ENTRY(passes_do_not_depend_on_the_thread_count_and_cost_nothing_unasked),
    TEST_ENTRY(an_exr_image_holds_the_passes_as_layers),
    TEST_ENTRY(the_memory_estimate_counts_the_passes))
