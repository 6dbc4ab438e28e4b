/*
 * 01_trace_browser.c - the pixel's trace as a picture (render --pixel X,Y
 * --trace-svg FILE, docs/inspect.md) renders in headless Chromium, in
 * every stage: the legend's swatches of the camera ray and the bounce are
 * on the screenshot.
 *
 * Grading: make grade FULL=1 only (1.5 processor s, Chromium's start: it
 * tests common/'s SVG writer in a browser, not the student's stage, whose
 * traces 01_trace checks).
 */
#include <stdio.h>
#include <string.h>

#include "browser.h"
#include "check.h"
#include "stagecheck.h"
#include "testlib.h"

#define CAP 16384

TEST(svg_renders_in_chromium)
{
    const char *scene = stagecheck_scene(
        "browser.scene",
        "camera origin 0 1 4 target 0 0.5 0 up 0 1 0 fov 40\n"
        "image width 16 height 12\n"
        "material white diffuse albedo 0.8 0.8 0.8\n"
        "quad corner -3 0 -3 edge1 0 0 6 edge2 6 0 0 material white\n"
        "sphere center 0 0.5 0 radius 0.5 material white\n"
        "point_light position 1 3 2 intensity 6 6 6\n");
    const char *svg = test_tmp_path("trace.svg");
    const char *const args[] = {"--pixel", "8,6", "--trace-svg", svg, NULL};
    char out[CAP];
    int status = scene ? test_render(scene, args, out, sizeof out) : -1;
    CHECK_MSG(status == 0 && test_file_exists(svg), "exit %d\n%s", status, out);
    const char *chromium = browser_path();
    if (!chromium) {
        SKIP(BROWSER_MISSING);
    }
    struct image shot = {0};
    bool ok = browser_screenshot(
        chromium,
        svg,
        800,
        600,
        test_tmp_path("shot.png"),
        &shot,
        out,
        sizeof out);
    CHECK_MSG(ok, "%s", out);
    /* The legend's swatches (24 x 8 each): the camera ray's yellow and the
     * bounce's orange are drawn whatever the stage. */
    int yellow = 0;
    int orange = 0;
    for (int y = 0; ok && y < shot.height; y++) {
        for (int x = 0; x < shot.width; x++) {
            const float *p = image_pixel(&shot, x, y);
            int r = image_srgb_encode8(p[0]);
            int g = image_srgb_encode8(p[1]);
            int b = image_srgb_encode8(p[2]);
            yellow += r > 240 && g > 200 && g < 225 && b < 20;
            orange += r > 240 && g > 115 && g < 140 && b < 30;
        }
    }
    CHECK_MSG(yellow >= 150 && orange >= 150, "yellow %d, orange %d pixels", yellow, orange);
    image_free(&shot);
}

TEST_MAIN(TEST_ENTRY(svg_renders_in_chromium))
