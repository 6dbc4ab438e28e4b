/*
 * browser.c - screenshots by headless Chromium (browser.h).
 */
#include "browser.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "imgread.h"
#include "testlib.h"

const char *
browser_path(void)
{
    const char *env = getenv("CHROMIUM");
    if (env && env[0]) {
        return env;
    }
    static const char *const candidates[] = {"/usr/bin/chromium", "/usr/bin/chromium-browser"};
    for (size_t i = 0; i < sizeof candidates / sizeof candidates[0]; i++) {
        if (access(candidates[i], X_OK) == 0) {
            return candidates[i];
        }
    }
    return NULL;
}

bool
browser_screenshot(
    const char *chromium,
    const char *page,
    int width,
    int height,
    const char *shot,
    struct image *out,
    char *log,
    size_t cap)
{
    /* tests/lib/chromium.py drives Chromium: it takes the picture once
     * the page has loaded and is painted (see there why not Chromium's own
     * --screenshot). */
    const char *home = test_tmp_path("chromium-home");
    const char *script = test_root_path("tests/lib/chromium.py");
    char chromium_env[4200], w[32], h[32];
    snprintf(chromium_env, sizeof chromium_env, "CHROMIUM=%s", chromium);
    snprintf(w, sizeof w, "%d", width);
    snprintf(h, sizeof h, "%d", height);
    const char *const mkdir_argv[] = {"/bin/mkdir", "-p", home, NULL};
    if (test_run(mkdir_argv, log, cap) != 0) {
        return false;
    }
    const char *const argv[] = {
        "/usr/bin/env",
        chromium_env,
        "/usr/bin/timeout",
        "300",
        "python3",
        script,
        page,
        w,
        h,
        shot,
        home,
        NULL};
    int status = test_run(argv, log, cap);
    const char *const rm_argv[] = {"/bin/rm", "-rf", home, NULL};
    bool removed = test_run(rm_argv, NULL, 0) == 0 && !test_file_exists(home);
    if (status != 0 || !test_file_exists(shot) || !removed) {
        size_t used = log ? strlen(log) : 0;
        if (log && used + 64 < cap) {
            snprintf(
                log + used,
                cap - used,
                "\n(chromium exit %d%s)",
                status,
                removed ? "" : ", its directory left");
        }
        return false;
    }
    struct diag err = {0};
    if (!imgread(shot, out, &err)) {
        snprintf(log, cap, "%s: %s", err.file, err.msg);
        return false;
    }
    return true;
}
