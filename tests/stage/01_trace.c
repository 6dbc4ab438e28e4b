/*
 * 01_trace.c - replaying one pixel (render --pixel X,Y --trace FILE,
 * docs/inspect.md), in every stage:
 *   - the traced pixel's value is that pixel of the full render, bit for
 *     bit, for pixels in the corners and the middle, two seeds, 1 and 3
 *     threads;
 *   - the JSON form is valid (python3's json; the value is the mean of the
 *     passes), names the primitive and the material by the scene's lines;
 *   - the text form goes to standard output with --pixel alone;
 *   - --trace-svg is well-formed SVG (01_trace_browser: and renders in
 *     headless Chromium); its camera rays, drawn through the stage's own
 *     camera, land in the traced pixel's square, with camera rays that
 *     start at the eye or on a near plane;
 *   - the usage errors: --trace or --trace-svg without --pixel, a pixel
 *     outside the image (the message gives the range), a trace that is
 *     another output; none writes a file.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "stagecheck.h"
#include "testlib.h"
#include "tracecheck.h"

#define CAP 16384
#define W 16
#define H 12

/* Every kind of surface and light; the lines matter (names_by_line). */
static const char scene_text[] =
    "camera origin 0 1.5 4 target 0 0.5 0 up 0 1 0 fov 40\n"
    "image width 16 height 12\n"
    "material white diffuse albedo 0.8 0.8 0.8\n"
    "material ball diffuse albedo 0.7 0.3 0.2\n"
    "material clear glass ior 1.5\n"
    "material chrome mirror reflectance 0.9 0.9 0.9\n"
    "quad corner -3 0 -3 edge1 0 0 6 edge2 6 0 0 material white\n"
    "sphere center 0 0.5 0 radius 0.5 material ball\n"
    "sphere center -1.1 0.4 0.3 radius 0.4 material clear\n"
    "sphere center 1.1 0.4 0.3 radius 0.4 material chrome\n"
    "point_light position 1 3 2 intensity 6 6 6\n"
    "area_light corner -0.5 2.5 -0.5 edge1 1 0 0 edge2 0 0 1 radiance 4 4 4\n"
    "background color 0.1 0.1 0.2\n";

static const char *
scene_path(void)
{
    return stagecheck_scene("trace.scene", "%s", scene_text);
}

/* The full render with this seed and thread count, as a PFM. */
static bool
full_render(const char *seed, const char *threads, struct image *out)
{
    const char *const args[] = {"-s", "4", "--seed", seed, "-t", threads, NULL};
    return test_render_image(scene_path(), args, out);
}

TEST(pixel_value_is_the_full_renders_bit_for_bit)
{
    static const int pixels[][2] = {{0, 0}, {W - 1, H - 1}, {W / 2, H / 2}, {3, 9}, {12, 2}};
    const char *seeds[] = {"1", "5"};
    for (int s = 0; s < 2; s++) {
        struct image one = {0};
        struct image many = {0};
        if (!full_render(seeds[s], "1", &one) || !full_render(seeds[s], "3", &many)) {
            CHECK(false);
            return;
        }
        for (size_t i = 0; i < sizeof pixels / sizeof pixels[0]; i++) {
            int x = pixels[i][0];
            int y = pixels[i][1];
            const char *const args[] = {"-s", "4", "--seed", seeds[s], NULL};
            const char *trace = tracecheck_pixel(scene_path(), x, y, args);
            float value[3];
            CHECK(trace && tracecheck_value(trace, value));
            if (!trace) {
                continue;
            }
            const float *a = image_pixel(&one, x, y);
            const float *b = image_pixel(&many, x, y);
            CHECK_MSG(
                memcmp(value, a, sizeof value) == 0 && memcmp(value, b, sizeof value) == 0,
                "seed %s pixel (%d, %d): traced (%.9g %.9g %.9g), full render (%.9g %.9g "
                "%.9g) with 1 thread, (%.9g %.9g %.9g) with 3",
                seeds[s],
                x,
                y,
                (double)value[0],
                (double)value[1],
                (double)value[2],
                (double)a[0],
                (double)a[1],
                (double)a[2],
                (double)b[0],
                (double)b[1],
                (double)b[2]);
        }
        image_free(&one);
        image_free(&many);
    }
}

TEST(json_is_valid_and_names_by_line)
{
    const char *trace = tracecheck_pixel(scene_path(), W / 2, H / 2, NULL);
    if (!trace) {
        CHECK(false);
        return;
    }
    char why[CAP];
    int valid = tracecheck_json_valid(trace, why, sizeof why);
    if (valid < 0) {
        printf("no python3: the JSON's structure is not checked\n");
    } else {
        CHECK_MSG(valid == 1, "%s: %s", trace, why);
    }
    /* The middle pixel sees the ball: the sphere of line 8, of the
     * material of line 4. */
    CHECK(tracecheck_count(trace, "\"type\": \"sample\"") == 0);
    CHECK(tracecheck_count(trace, "\"type\": \"hit\"") >= 1);
    CHECK(
        tracecheck_count(trace, "\"primitive\": {\"kind\": \"sphere\", \"index\": 0, \"line\": 8}")
        >= 1);
    CHECK(tracecheck_count(trace, "\"material\": {\"name\": \"ball\", \"line\": 4}") >= 1);
    CHECK(
        tracecheck_count(trace, "\"type\": \"shade\"")
            + tracecheck_count(trace, "\"type\": \"nee\"")
        >= 1);
}

TEST(text_trace_on_standard_output)
{
    const char *const args[] = {"--pixel", "8,6", NULL};
    char out[CAP];
    int status = test_render(scene_path(), args, out, sizeof out);
    CHECK_MSG(status == 0, "exit %d\n%s", status, out);
    CHECK_MSG(strstr(out, "pixel (8, 6) of ") != NULL, "%s", out);
    CHECK_MSG(strstr(out, "\n  sample  index 0") != NULL, "%s", out);
    CHECK_MSG(strstr(out, "\n    hit  depth 1") != NULL, "%s", out);
    CHECK_MSG(strstr(out, "sphere #0 (line 8)") != NULL, "%s", out);
    CHECK(!test_file_exists(test_tmp_path("trace.png")));
}

TEST(svg_is_valid)
{
    const char *svg = test_tmp_path("trace.svg");
    const char *const args[] = {"--pixel", "8,6", "--trace-svg", svg, NULL};
    char out[CAP];
    int status = test_render(scene_path(), args, out, sizeof out);
    CHECK_MSG(status == 0 && test_file_exists(svg), "exit %d\n%s", status, out);
    CHECK_MSG(strstr(out, "differs") == NULL, "%s", out);
    int valid = tracecheck_svg_valid(svg, out, sizeof out);
    if (valid < 0) {
        SKIP("no python3: the SVG's structure is not checked");
    }
    CHECK_MSG(valid == 1, "%s: %s", svg, out);
}

/* How many of the camera-ray lines (yellow, style_of in recorder_svg.c) of
 * the SVG's film panel (the part before the top view) have an end outside
 * pixel (px, py)'s square of `scale` units (plus half a unit for the
 * printed rounding); *n_lines counts them all. */
static int
camera_lines_outside(char *svg, int px, int py, double scale, int *n_lines)
{
    int outside = 0;
    *n_lines = 0;
    char *top_view = strstr(svg, "id=\"top-view\"");
    if (top_view) {
        *top_view = '\0';
    }
    for (const char *at = strstr(svg, "<line "); at; at = strstr(at + 1, "<line ")) {
        const char *end = strchr(at, '>');
        const char *yellow = strstr(at, "stroke=\"#ffd400\"");
        double x[2];
        double y[2];
        if (!end || !yellow || yellow > end
            || sscanf(
                   at,
                   "<line x1=\"%lf\" y1=\"%lf\" x2=\"%lf\" y2=\"%lf\"",
                   &x[0],
                   &y[0],
                   &x[1],
                   &y[1])
                   != 4) {
            continue;
        }
        (*n_lines)++;
        for (int i = 0; i < 2; i++) {
            bool in_x = x[i] >= px * scale - 0.5 && x[i] <= (px + 1) * scale + 0.5;
            bool in_y = y[i] >= py * scale - 0.5 && y[i] <= (py + 1) * scale + 0.5;
            outside += !(in_x && in_y);
        }
    }
    return outside;
}

/* The camera rays of the picture are projected through the stage's own
 * camera: each lands in the traced pixel's square (30 SVG units a pixel:
 * the 480-unit panel over 16 pixels), for rays from the eye and for rays
 * that start on a near plane (the projection must find the eye behind
 * them, not take their origins for it). */
TEST(svg_camera_rays_land_in_their_pixel)
{
    static const char *const nears[] = {"0", "2.5"};
    for (int k = 0; k < 2; k++) {
        char name[32];
        snprintf(name, sizeof name, "near%d.scene", k);
        const char *scene = stagecheck_scene(
            name,
            "camera origin 0 1.5 4 target 0 0.5 0 up 0 1 0 fov 40 near %s\n%s",
            nears[k],
            strchr(scene_text, '\n') + 1);
        const char *svg = test_tmp_path("near.svg");
        const char *const args[] = {"--pixel", "3,9", "-s", "4", "--trace-svg", svg, NULL};
        char out[CAP];
        int status = test_render(scene, args, out, sizeof out);
        CHECK_MSG(status == 0, "near %s: exit %d\n%s", nears[k], status, out);
        char *text = test_read_file(svg, NULL);
        CHECK_MSG(text != NULL, "near %s: no SVG", nears[k]);
        if (text) {
            int n_lines;
            int outside = camera_lines_outside(text, 3, 9, 30, &n_lines);
            CHECK_MSG(n_lines > 0, "near %s: no camera ray drawn", nears[k]);
            CHECK_MSG(
                outside == 0,
                "near %s: %d camera-ray ends outside pixel (3, 9)",
                nears[k],
                outside);
            free(text);
        }
    }
}

/* A command line that is refused with exit 2, a message holding `says`,
 * and no file written. */
static void
check_refused(const char *const args[], const char *says)
{
    char out[CAP];
    int status = test_render(scene_path(), args, out, sizeof out);
    CHECK_MSG(
        status == 2 && strstr(out, says),
        "exit %d, expected 2 and '%s':\n%s",
        status,
        says,
        out);
    CHECK(!test_file_exists(test_tmp_path("refused.json")));
    CHECK(!test_file_exists(test_tmp_path("refused.png")));
    CHECK(test_count_files(test_tmpdir(), ".stagelight-") == 0);
}

TEST(usage_errors)
{
    const char *json = test_tmp_path("refused.json");
    const char *png = test_tmp_path("refused.png");
    const char *const no_pixel[] = {"--trace", json, "-o", png, NULL};
    check_refused(no_pixel, "--trace needs --pixel");
    const char *const svg_no_pixel[] = {"--trace-svg", json, "-o", png, NULL};
    check_refused(svg_no_pixel, "--trace-svg needs --pixel");
    const char *const outside[] = {"--pixel", "16,3", "--trace", json, NULL};
    check_refused(outside, "X in [0, 15], Y in [0, 11]");
    const char *const below[] = {"--pixel", "3,12", "--trace", json, NULL};
    check_refused(below, "outside the 16x12 image");
    const char *const negative[] = {"--pixel", "-1,3", "--trace", json, NULL};
    check_refused(negative, "--pixel");
    const char *const same[] = {"--pixel", "1,1", "--trace", png, "-o", png, NULL};
    check_refused(same, "--trace");
    const char *const two_stdout[] = {"--pixel", "1,1", "--trace", "-", "--stats", "-", NULL};
    check_refused(two_stdout, "standard output");
}

TEST(image_only_when_asked)
{
    const char *png = test_tmp_path("asked.png");
    const char *json = test_tmp_path("asked.json");
    const char *const args[] = {"--pixel", "2,2", "--trace", json, "-o", png, NULL};
    char out[CAP];
    int status = test_render(scene_path(), args, out, sizeof out);
    CHECK_MSG(status == 0, "exit %d\n%s", status, out);
    CHECK(test_file_exists(png) && test_file_exists(json));
    CHECK_MSG(strstr(out, "differs") == NULL, "%s", out);
}

TEST_MAIN(
    TEST_ENTRY(pixel_value_is_the_full_renders_bit_for_bit),
    TEST_ENTRY(json_is_valid_and_names_by_line),
    TEST_ENTRY(text_trace_on_standard_output),
    TEST_ENTRY(svg_is_valid),
    TEST_ENTRY(svg_camera_rays_land_in_their_pixel),
    TEST_ENTRY(usage_errors),
    TEST_ENTRY(image_only_when_asked))
