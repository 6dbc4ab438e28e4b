/*
 * browser.h - pages and pictures rendered by a real browser: headless
 * Chromium takes a screenshot of a file (an HTML page, an SVG), which the
 * test then reads like any image (imgread.h).
 *
 * Chromium: $CHROMIUM, else /usr/bin/chromium (Debian's package) or
 * /usr/bin/chromium-browser; tests skip with a message when there is none.
 * tests/lib/chromium.py drives it (python3) and takes the picture once the
 * page has loaded and is painted.  It runs with a fresh profile, HOME and
 * TMPDIR in a directory of its own under the test's temporary directory,
 * removed afterwards.
 */
#ifndef BROWSER_H
#define BROWSER_H

#include <stdbool.h>
#include <stddef.h>

#include "image.h"

/* The message a test skips with when there is no Chromium. */
#define BROWSER_MISSING \
    "no Chromium: apt-get install chromium (or set CHROMIUM) to test in a browser"

/* The Chromium to run, or NULL when there is none. */
const char *browser_path(void);

/* Screenshot of the file `page` at width x height pixels into shot (a PNG
 * path), read back into *out.  False, with Chromium's output or the
 * reader's message in log (cap bytes), when either step fails; the
 * browser's private directory is gone in both cases. */
bool browser_screenshot(
    const char *chromium,
    const char *page,
    int width,
    int height,
    const char *shot,
    struct image *out,
    char *log,
    size_t cap);

#endif /* BROWSER_H */
