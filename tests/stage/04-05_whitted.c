/*
 * 04-05_whitted.c - Whitted ray tracing through the stage's binary:
 * mirrors, the recursion limit, glass and the checker material.
 *
 *  - A perfect mirror (reflectance 1) in front of the camera shows what a
 *    camera at the mirrored position, looking back, sees without it,
 *    flipped left to right (to 1e-5 away from edges).
 *  - --max-depth N: between two facing mirrors every chain of rays runs to
 *    the limit, so a pixel traces exactly N - 1 secondary rays, and with
 *    blend mirrors (albedo a, reflectance r, ambient 1) its radiance is
 *    a (1 - r^N) / (1 - r).
 *  - Glass of index 1 is invisible (F = 0, rays go straight on); index
 *    1.0001 nearly so.
 *  - The checker floor shows the colour of the cube each pixel's point lies
 *    in, exactly, with no flicker on a floor lying on a cube face, near and
 *    far (1e6) from the origin.
 *
 * Stages 04-05 only: they trace one ray through each pixel centre, which
 * the pixel-exact comparisons rely on (06 jitters camera rays, 07 changes
 * the light transport).
 */
#include "check.h"
#include "metrics.h"
#include "stagecheck.h"
#include "testlib.h"

/* ---- A mirror in front of the camera ---------------------------------------- */

/* Objects behind the camera (z > 0), lit by a point light also behind it;
 * nothing lies between the camera (z = 0) and the mirror plane z = -2. */
#define BEHIND_CAMERA \
    "material white diffuse albedo 0.8 0.8 0.8\n" \
    "material red diffuse albedo 0.7 0.1 0.1\n" \
    "material blue diffuse albedo 0.1 0.2 0.7\n" \
    "quad corner -20 0 0 edge1 0 0 20 edge2 40 0 0 material white\n" \
    "quad corner -20 0 12 edge1 40 0 0 edge2 0 20 0 material white\n" \
    "sphere center 0.5 0.7 3 radius 0.5 material red\n" \
    "sphere center -1 0.4 5 radius 0.4 material blue\n" \
    "point_light position 2 4 2 intensity 20 20 20\n"

TEST(mirror_shows_the_mirrored_view)
{
    const char *with_mirror = stagecheck_scene(
        "mirror.scene",
        "camera origin 0 1 0 target 0 1 -1 up 0 1 0 fov 50\n"
        "image width 48 height 48\n"
        "material glass_mirror mirror reflectance 1 1 1\n"
        "quad corner -20 -20 -2 edge1 40 0 0 edge2 0 40 0 material glass_mirror\n" BEHIND_CAMERA);
    /* The camera reflected in z = -2: origin (0, 1, -4), looking along +z. */
    const char *mirrored = stagecheck_scene(
        "mirrored.scene",
        "camera origin 0 1 -4 target 0 1 -3 up 0 1 0 fov 50\n"
        "image width 48 height 48\n" BEHIND_CAMERA);
    struct image a = {0};
    struct image b = {0};
    if (!stagecheck_render(with_mirror, NULL, &a, NULL)
        || !stagecheck_render(mirrored, NULL, &b, NULL)) {
        CHECK(false);
        image_free(&a);
        return;
    }
    int compared = 0;
    int differ = 0;
    double worst = 0;
    for (int py = 0; py < 48; py++) {
        for (int px = 0; px < 48; px++) {
            /* Its right is our left: pixel px there is 47 - px here. */
            if (!stagecheck_interior(&b, 47 - px, py, 0.5)) {
                continue;
            }
            double d = stagecheck_pixel_reldiff(
                image_pixel(&a, px, py),
                image_pixel(&b, 47 - px, py),
                1e-3);
            worst = fmax(worst, d);
            differ += d > 10 * stagecheck_resolvable(1e-6); /* 1e-5; 1.2e-3 in float */
            compared++;
        }
    }
    printf(
        "%d pixels away from edges compared, %d differ; largest relative difference %.3g\n",
        compared,
        differ,
        worst);
    CHECK(compared > 48 * 48 / 2);
    CHECK(differ == 0);
    image_free(&a);
    image_free(&b);
}

/* ---- The recursion limit ------------------------------------------------------ */

TEST(max_depth_bounds_every_chain_of_rays)
{
    /* Blend mirrors at z = -1 and z = +1, 40 wide, the camera between them
     * looking at one with a 10 degree view: every reflected ray hits the
     * other mirror (it drifts sideways by 2 tan(5 deg) = 0.17 per bounce).
     * Ambient 1 and no light: each surface point adds its albedo a, each
     * reflection scales by r. */
    const char *scene = stagecheck_scene(
        "two_mirrors.scene",
        "camera origin 0 0 0 target 0 0 -1 up 0 1 0 fov 10\n"
        "image width 16 height 16\n"
        "ambient color 1 1 1\n"
        "material half blend albedo 0.5 0.5 0.5 reflectance 0.5 0.5 0.5\n"
        "quad corner -20 -20 -1 edge1 40 0 0 edge2 0 40 0 material half\n"
        "quad corner -20 -20 1 edge1 40 0 0 edge2 0 40 0 material half\n");
    static const int depths[] = {1, 2, 3, 5};
    for (int i = 0; i < 4; i++) {
        char depth[16];
        snprintf(depth, sizeof depth, "%d", depths[i]);
        const char *const args[] = {"--max-depth", depth, NULL};
        struct image img = {0};
        const char *stats = NULL;
        if (!stagecheck_render(scene, args, &img, &stats)) {
            CHECK(false);
            continue;
        }
        double expected = 0.5 * (1 - pow(0.5, depths[i])) / (1 - 0.5);
        int wrong = 0;
        for (int p = 0; p < 16 * 16; p++) {
            wrong += fabs(img.rgb[3 * p] - expected) > 1e-6;
        }
        double secondary = stagecheck_stat(stats, "rays_secondary");
        double camera = stagecheck_stat(stats, "rays_camera");
        printf(
            "max depth %d: radiance %.9g (expected %.9g), %d pixels off; rays_secondary %.0f "
            "(expected %d = pixels x (depth - 1))\n",
            depths[i],
            img.rgb[0],
            expected,
            wrong,
            secondary,
            256 * (depths[i] - 1));
        CHECK(wrong == 0);
        CHECK(camera == 256);
        CHECK_MSG(
            secondary == 256 * (depths[i] - 1),
            "max depth %d: %.0f secondary rays",
            depths[i],
            secondary);
        image_free(&img);
    }
}

/* ---- Glass of index 1 ---------------------------------------------------------- */

/* A floor, a wall, a diffuse sphere and a point light, with an optional
 * glass sphere in front of the diffuse one covering half of it. */
static bool
render_with_glass(const char *glass, struct image *img)
{
    const char *scene = stagecheck_scene(
        "glass_index.scene",
        "camera origin 0 1 4 target 0 0.6 0 up 0 1 0 fov 40\n"
        "image width 48 height 48\n"
        "material white diffuse albedo 0.8 0.8 0.8\n"
        "material red diffuse albedo 0.7 0.1 0.1\n"
        "%s"
        "quad corner -5 0 -5 edge1 0 0 10 edge2 10 0 0 material white\n"
        "quad corner -5 0 -2 edge1 10 0 0 edge2 0 5 0 material white\n"
        "sphere center 0 0.5 0 radius 0.5 material red\n"
        "point_light position 1 3 2 intensity 10 10 10\n",
        glass);
    return stagecheck_render(scene, NULL, img, NULL);
}

TEST(glass_of_index_one_is_invisible)
{
    struct image plain = {0};
    struct image clear = {0};
    struct image nearly = {0};
    if (!render_with_glass("", &plain)
        || !render_with_glass(
            "material g glass ior 1\n"
            "sphere center 0.35 0.7 1.2 radius 0.45 material g\n",
            &clear)
        || !render_with_glass(
            "material g glass ior 1.0001\n"
            "sphere center 0.35 0.7 1.2 radius 0.45 material g\n",
            &nearly)) {
        CHECK(false);
    } else {
        int differ = 0;
        double worst = 0;
        for (int py = 0; py < 48; py++) {
            for (int px = 0; px < 48; px++) {
                double d = stagecheck_pixel_reldiff(
                    image_pixel(&clear, px, py),
                    image_pixel(&plain, px, py),
                    1e-3);
                worst = fmax(worst, d);
                differ += d > 1e-5;
            }
        }
        double relmse_nearly = metrics_relmse(&nearly, &plain, NULL);
        printf(
            "index 1: %d pixels differ by more than 1e-5 (largest %.3g); "
            "index 1.0001: relMSE %.3g\n",
            differ,
            worst,
            relmse_nearly);
        CHECK(differ == 0);
        CHECK(relmse_nearly < 1e-5);
    }
    image_free(&plain);
    image_free(&clear);
    image_free(&nearly);
}

/* ---- The checker material ------------------------------------------------------ */

/* A checker floor (size 1, albedo 0.9 / albedo2 (0.1, 0.2, 0.3)) at height
 * floor_y under ambient light 1, so a pixel's value is its albedo exactly,
 * seen straight down from 10 above (cx, floor_y, cz) with a field of view
 * 6 cells across, 64x64.  Pixel (px, py)'s centre ray meets the floor at
 * (cx + 10 X, floor_y, cz - 10 Y), X and Y its film coordinates at
 * distance 1 (camera right = +x, up = -z).  Returns the number of pixels
 * deep inside a cell (x and z at least 0.15 from a cell boundary) and, in
 * *matches[0] and [1], how many show the colour cell parity (i + j + k)
 * predicts under each assignment (even -> albedo, or even -> albedo2). */
static int
checker_pixels(double cx, double cz, double floor_y, const char *winding, int matches[2])
{
    double half = 0.3; /* tan(fov / 2): 3 cells each side at distance 10 */
    const char *scene = stagecheck_scene(
        "checker.scene",
        "camera origin %.17g %.17g %.17g target %.17g %.17g %.17g up 0 0 -1 fov %.17g\n"
        "image width 64 height 64\n"
        "ambient color 1 1 1\n"
        "material ch checker albedo 0.9 0.9 0.9 albedo2 0.1 0.2 0.3 size 1\n"
        "quad corner %.17g %.17g %.17g %s material ch\n",
        cx,
        floor_y + 10,
        cz,
        cx,
        floor_y,
        cz,
        2 * atan(half) * 180 / 3.14159265358979323846,
        cx - 10,
        floor_y,
        cz - 10,
        winding);
    struct image img = {0};
    matches[0] = matches[1] = 0;
    if (!stagecheck_render(scene, NULL, &img, NULL)) {
        return -1;
    }
    int deep = 0;
    for (int py = 0; py < 64; py++) {
        for (int px = 0; px < 64; px++) {
            double x = cx + 10 * (2 * (px + 0.5) / 64 - 1) * half;
            double z = cz - 10 * (1 - 2 * (py + 0.5) / 64) * half;
            double fx = x - floor(x);
            double fz = z - floor(z);
            if (fx < 0.15 || fx > 0.85 || fz < 0.15 || fz > 0.85) {
                continue;
            }
            deep++;
            long parity = ((long)floor(x) + (long)floor(floor_y) + (long)floor(z)) & 1;
            const float *p = image_pixel(&img, px, py);
            bool first = p[0] == 0.9f && p[1] == 0.9f && p[2] == 0.9f;
            bool second = p[0] == 0.1f && p[1] == 0.2f && p[2] == 0.3f;
            matches[0] += parity == 0 ? first : second;
            matches[1] += parity == 0 ? second : first;
        }
    }
    image_free(&img);
    return deep;
}

#define EDGES_UP "edge1 0 0 20 edge2 20 0 0" /* normal +y */
#define EDGES_DOWN "edge1 20 0 0 edge2 0 0 20" /* normal -y */

TEST(checker_shows_the_cell_each_point_lies_in)
{
    /* The floor mid-way through the layer of cubes 0 <= y < 1: cell
     * (floor(x), 0, floor(z)), albedo where the sum is even (the stage's
     * convention), whichever way the quad is wound. */
    static const char *const windings[] = {EDGES_UP, EDGES_DOWN};
    for (int i = 0; i < 2; i++) {
        int matches[2];
        int deep = checker_pixels(0.3, 0.2, 0.5, windings[i], matches);
        printf(
            "floor at y = 0.5 (%s): %d of %d pixels deep in cells match\n",
            windings[i],
            matches[0],
            deep);
        CHECK(deep > 1000);
        CHECK_MSG(matches[0] == deep, "%d of %d", matches[0], deep);
    }
}

TEST(checker_floor_on_a_cube_face_does_not_flicker)
{
    /* y = 0 is the face between two layers of cubes; which layer a point
     * rounds into must not change from pixel to pixel: every pixel deep in
     * a cell must follow one of the two parities, the same one throughout
     * the image.  Near the origin and 1e6 away from it.  (Which layer is
     * the stage's choice; 04 takes the one behind the quad's outward
     * normal, so swapping edge1 and edge2 swaps the colours.) */
    static const double centres[][2] = {{0.3, 0.2}, {1e6 + 0.3, -1e6 + 0.2}};
    for (int i = 0; i < 2; i++) {
        int matches[2];
        int deep = checker_pixels(centres[i][0], centres[i][1], 0, EDGES_UP, matches);
        printf(
            "floor at y = 0 around x = %g: %d pixels deep in cells, parity matches %d / %d\n",
            centres[i][0],
            deep,
            matches[0],
            matches[1]);
        CHECK(deep > 1000);
        CHECK_MSG(
            matches[0] == deep || matches[1] == deep,
            "mixed: %d / %d of %d",
            matches[0],
            matches[1],
            deep);
    }
}

TEST_MAIN(
    TEST_ENTRY(mirror_shows_the_mirrored_view),
    TEST_ENTRY(max_depth_bounds_every_chain_of_rays),
    TEST_ENTRY(glass_of_index_one_is_invisible),
    TEST_ENTRY(checker_shows_the_cell_each_point_lies_in),
    TEST_ENTRY(checker_floor_on_a_cube_face_does_not_flicker))
