/*
 * test_report_browser.c - compare's report page (compare --html) rendered
 * by a real browser: headless Chromium takes screenshots of the page at a
 * desktop and at a phone width, and the test reads their pixels.
 *
 * The inputs are flat colours nothing else on the page uses: renders of
 * green (linear 0.1, 0.6, 0.1) against a magenta reference (0.6, 0.1,
 * 0.6), so the render is brighter everywhere and the verdict is "biased".
 * In the screenshot the test finds the render's green and the reference's
 * magenta (the embedded images decoded and shown), the error map's red,
 * the red verdict box; side by side on the desktop and one above the other
 * on the phone; and the render over the reference, cut by the slider.
 * The page's script is driven as a user would: the slider moved (its
 * input event) moves the cut, and the flip button shows one image whole,
 * then the other.
 *
 * Chromium: browser.h; skipped with a message when there is none.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "browser.h"
#include "check.h"
#include "image.h"
#include "testlib.h"

#define W 64
#define H 48
#define CAP 16384

/* A flat image of linear colour rgb, with noise of relative size 0.002
 * from `seed` so that two renders differ. */
static bool
write_flat(const char *name, const float rgb[3], unsigned seed)
{
    struct image img = {0};
    struct diag err = {0};
    bool ok = image_alloc(&img, W, H, &err);
    uint32_t s = seed * 2654435761u + 1;
    for (int i = 0; ok && i < W * H * 3; i++) {
        s = s * 1664525u + 1013904223u; /* Numerical Recipes' LCG: test noise */
        double u = (s >> 8) / 16777216.0 - 0.5;
        img.rgb[i] = (float)(rgb[i % 3] * (1 + (seed ? 0.004 * u : 0)));
    }
    ok = ok && image_write(&img, test_tmp_path(name), &err);
    image_free(&img);
    return ok;
}

static bool
near(const int *p, int r, int g, int b, int tol)
{
    return abs(p[0] - r) <= tol && abs(p[1] - g) <= tol && abs(p[2] - b) <= tol;
}

enum colour_class {
    OTHER,
    GREEN,
    MAGENTA,
    MAP_RED,
    VERDICT
};

static enum colour_class
classify(const float *q)
{
    int p[3] = {image_srgb_encode8(q[0]), image_srgb_encode8(q[1]), image_srgb_encode8(q[2])};
    if (near(p, 89, 203, 89, 12)) { /* sRGB of linear 0.1, 0.6, 0.1 */
        return GREEN;
    }
    if (near(p, 203, 89, 203, 12)) {
        return MAGENTA;
    }
    if (near(p, 0xf8, 0xc8, 0xc0, 4)) { /* the biased verdict's background */
        return VERDICT;
    }
    if (p[0] > 150 && p[1] < 110 && p[2] < 110 && p[0] - p[1] > 90) { /* RdBu's reds */
        return MAP_RED;
    }
    return OTHER;
}

/* The first row holding `k`, or -1. */
static int
first_row(const struct image *shot, enum colour_class k)
{
    for (int y = 0; y < shot->height; y++) {
        for (int x = 0; x < shot->width; x++) {
            if (classify(image_pixel(shot, x, y)) == k) {
                return y;
            }
        }
    }
    return -1;
}

/* Pixels of class k above row `below`. */
static long
count_above(const struct image *shot, enum colour_class k, int below)
{
    long n = 0;
    for (int y = 0; y < below && y < shot->height; y++) {
        for (int x = 0; x < shot->width; x++) {
            n += classify(image_pixel(shot, x, y)) == k;
        }
    }
    return n;
}

/* The classes met along row y from left to right, each run of at least
 * min_run pixels once, as a string: "GMRRRR" for green, magenta and four
 * runs of map red. */
static void
row_runs(const struct image *shot, int y, int min_run, char *out, size_t cap)
{
    static const char letters[] = ".GMRV";
    size_t n = 0;
    int run = 0;
    enum colour_class current = OTHER;
    for (int x = 0; x <= shot->width; x++) {
        enum colour_class k = x < shot->width ? classify(image_pixel(shot, x, y)) : OTHER;
        if (k == current) {
            run++;
            continue;
        }
        if (current != OTHER && run >= min_run && n + 1 < cap) {
            out[n++] = letters[current];
        }
        current = k;
        run = 1;
    }
    out[n] = '\0';
}

/* Write the page; false (and skip) without Chromium. */
static const char *
write_page(void)
{
    static const float green[3] = {0.1f, 0.6f, 0.1f};
    static const float magenta[3] = {0.6f, 0.1f, 0.6f};
    CHECK(
        write_flat("a.pfm", green, 1) && write_flat("b.pfm", green, 2)
        && write_flat("ref.pfm", magenta, 0));
    const char *page = test_tmp_path("page.html");
    const char *const args[] = {
        test_tmp_path("a.pfm"),
        test_tmp_path("b.pfm"),
        test_tmp_path("ref.pfm"),
        "--html",
        page,
        NULL};
    char out[CAP];
    int status = test_run_tool("compare", args, out, sizeof out);
    CHECK_MSG(status == 1, "compare: exit %d\n%s", status, out);
    return page;
}

/* The page in Chromium at width x height, read back into shot. */
static bool
page_screenshot(const char *chromium, int width, int height, const char *name, struct image *shot)
{
    const char *page = write_page();
    char log[CAP];
    bool ok = browser_screenshot(
        chromium,
        page,
        width,
        height,
        test_tmp_path(name),
        shot,
        log,
        sizeof log);
    CHECK_MSG(ok, "%s", log);
    return ok;
}

/* Where the images start (the render's first row), the colour runs along
 * a row 20 pixels below that (runs of at least min_run), and the verdict
 * box's pixels above it. */
struct layout {
    int top;
    char runs[32];
    long verdict;
};

static struct layout
page_layout(const struct image *shot, int min_run, const char *what)
{
    struct layout l = {.top = first_row(shot, GREEN)};
    if (l.top >= 0) {
        row_runs(shot, l.top + 20, min_run, l.runs, sizeof l.runs);
    }
    l.verdict = count_above(shot, VERDICT, l.top);
    printf(
        "%s: images from row %d; along row %d: %s; verdict box %ld pixels above\n",
        what,
        l.top,
        l.top + 20,
        l.runs,
        l.verdict);
    return l;
}

TEST(report_page_in_chromium_on_a_desktop)
{
    const char *chromium = browser_path();
    if (!chromium) {
        SKIP(BROWSER_MISSING);
    }
    struct image shot = {0};
    if (!page_screenshot(chromium, 1200, 900, "desktop.png", &shot)) {
        return;
    }
    CHECK(shot.width == 1200);
    /* Render, reference and error map side by side, each about a third of
     * the width: along a row through their tops, green then magenta then
     * the map's red (cut into runs of ~90 by its outlines); the red verdict
     * box above them. */
    struct layout l = page_layout(&shot, 60, "desktop");
    CHECK(strncmp(l.runs, "GMR", 3) == 0 && strspn(l.runs + 2, "R") == strlen(l.runs + 2));
    CHECK(l.verdict > 10000);
    /* Below them the render over the reference, cut by the slider at half
     * its width: the bottom row of the screenshot crosses it. */
    char slider[32] = "";
    row_runs(&shot, shot.height - 10, 100, slider, sizeof slider);
    printf("desktop: along row %d: %s\n", shot.height - 10, slider);
    CHECK(strcmp(slider, "GM") == 0);
    image_free(&shot);
}

TEST(report_page_in_chromium_on_a_phone)
{
    const char *chromium = browser_path();
    if (!chromium) {
        SKIP(BROWSER_MISSING);
    }
    struct image shot = {0};
    if (!page_screenshot(chromium, 390, 1400, "phone.png", &shot)) {
        return;
    }
    /* One column: the render alone across the width, the reference below
     * it, the verdict above. */
    struct layout l = page_layout(&shot, 300, "phone");
    int magenta = first_row(&shot, MAGENTA);
    printf("phone: reference from row %d\n", magenta);
    CHECK(strcmp(l.runs, "G") == 0);
    CHECK(magenta > l.top + 250);
    CHECK(l.verdict > 5000);
    image_free(&shot);
}

/* The page with `action` (script) run after the page's own script, as a
 * user's drag or click would: its screenshot at the desktop's size. */
static bool
page_after(const char *chromium, const char *name, const char *action, struct image *shot)
{
    char *html = test_read_file(write_page(), NULL);
    const char *end = html ? strstr(html, "</body>") : NULL;
    CHECK(end != NULL);
    if (!end) {
        free(html);
        return false;
    }
    size_t cap = strlen(html) + strlen(action) + 64;
    char *page = malloc(cap), path[64], png[64], log[CAP];
    snprintf(page, cap, "%.*s<script>%s</script>\n%s", (int)(end - html), html, action, end);
    snprintf(path, sizeof path, "%s.html", name);
    snprintf(png, sizeof png, "%s.png", name);
    bool ok = test_write_file(test_tmp_path(path), page);
    ok = ok
         && browser_screenshot(
             chromium,
             test_tmp_path(path),
             1200,
             900,
             test_tmp_path(png),
             shot,
             log,
             sizeof log);
    CHECK_MSG(ok, "%s", log);
    free(page);
    free(html);
    return ok;
}

/* The share of the render (green) among the render and the reference
 * (magenta) along the bottom row, which crosses the render over the
 * reference; -1 when neither is there. */
static double
render_share(const struct image *shot, const char *what)
{
    long green = 0, magenta = 0;
    int y = shot->height - 10;
    for (int x = 0; x < shot->width; x++) {
        enum colour_class k = classify(image_pixel(shot, x, y));
        green += k == GREEN;
        magenta += k == MAGENTA;
    }
    double share = green + magenta ? (double)green / (double)(green + magenta) : -1;
    printf(
        "%s: along row %d, %ld render and %ld reference pixels (%.2f)\n",
        what,
        y,
        green,
        magenta,
        share);
    return share;
}

/* The slider at 20: the render's edge moves to a fifth of the width (it
 * starts at half). */
TEST(report_page_slider_moves_the_edge)
{
    const char *chromium = browser_path();
    if (!chromium) {
        SKIP(BROWSER_MISSING);
    }
    struct image shot = {0};
    const char drag[] =
        "var s=document.getElementById('slide');s.value=20;s.dispatchEvent(new Event('input'));";
    if (page_after(chromium, "slid", drag, &shot)) {
        double share = render_share(&shot, "slider at 20");
        CHECK(share > 0.15 && share < 0.25);
    }
    image_free(&shot);
}

/* flip shows the render whole, and again the reference whole. */
TEST(report_page_flip_toggles)
{
    const char *chromium = browser_path();
    if (!chromium) {
        SKIP(BROWSER_MISSING);
    }
    const char once[] = "document.getElementById('flip').click();";
    const char twice[] =
        "document.getElementById('flip').click();document.getElementById('flip').click();";
    struct image shot = {0};
    if (page_after(chromium, "flip1", once, &shot)) {
        CHECK(render_share(&shot, "flipped once") > 0.99);
    }
    image_free(&shot);
    if (page_after(chromium, "flip2", twice, &shot)) {
        double share = render_share(&shot, "flipped twice");
        CHECK(share >= 0 && share < 0.01);
    }
    image_free(&shot);
}

/* Chromium's Unix sockets live in its TMPDIR, and a socket's path must
 * stay under 108 bytes: a home deep in a long TMPDIR (a folder under /tmp
 * of 26 characters was enough, macOS's is longer) closed Chromium's pipe.
 * chromium.py replaces a long home by a short one; here the home's path is
 * over 100 characters, and the screenshot is still taken. */
TEST(a_long_temporary_directory_still_gets_a_screenshot)
{
    const char *chromium = browser_path();
    if (!chromium) {
        SKIP(BROWSER_MISSING);
    }
    const char *page = write_page();
    char home[512];
    snprintf(
        home,
        sizeof home,
        "%s",
        test_tmp_path("a-temporary-directory-as-deep-as-a-course-server-or-macos-makes-it-"
                      "to-be-long/chromium-home"));
    CHECK(strlen(home) > 100);
    const char *const mkdir_argv[] = {"/bin/mkdir", "-p", home, NULL};
    char log[CAP];
    CHECK(test_run(mkdir_argv, log, sizeof log) == 0);
    char chromium_env[4200];
    snprintf(chromium_env, sizeof chromium_env, "CHROMIUM=%s", chromium);
    const char *shot = test_tmp_path("long-home.png");
    const char *const argv[] = {
        "/usr/bin/env",
        chromium_env,
        "python3",
        test_root_path("tests/lib/chromium.py"),
        page,
        "320",
        "240",
        shot,
        home,
        NULL};
    int status = test_run(argv, log, sizeof log);
    CHECK_MSG(status == 0 && test_file_exists(shot), "chromium.py: exit %d\n%s", status, log);
}

TEST_MAIN(
    TEST_ENTRY(a_long_temporary_directory_still_gets_a_screenshot),
    TEST_ENTRY(report_page_in_chromium_on_a_desktop),
    TEST_ENTRY(report_page_in_chromium_on_a_phone),
    TEST_ENTRY(report_page_slider_moves_the_edge),
    TEST_ENTRY(report_page_flip_toggles))
