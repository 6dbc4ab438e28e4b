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
    const char *home = test_tmp_path("chromium-home");
    char profile[4200], tmp[4200], home_env[4200], size[64], out_arg[4200], url[4200];
    snprintf(profile, sizeof profile, "--user-data-dir=%s/profile", home);
    snprintf(tmp, sizeof tmp, "TMPDIR=%s", home);
    snprintf(home_env, sizeof home_env, "HOME=%s", home);
    snprintf(size, sizeof size, "--window-size=%d,%d", width, height);
    snprintf(out_arg, sizeof out_arg, "--screenshot=%s", shot);
    snprintf(url, sizeof url, "file://%s", page);
    const char *const mkdir_argv[] = {"/bin/mkdir", "-p", home, NULL};
    if (test_run(mkdir_argv, log, cap) != 0) {
        return false;
    }
    const char *const argv[] = {
        "/usr/bin/env",
        tmp,
        home_env,
        "/usr/bin/timeout",
        "120",
        chromium,
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--hide-scrollbars",
        /* Let the page's tasks (decoding its data-URI images, its script)
         * finish before the shot: on a busy machine it was once taken
         * with an image not yet painted. */
        "--virtual-time-budget=5000",
        profile,
        size,
        out_arg,
        url,
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
