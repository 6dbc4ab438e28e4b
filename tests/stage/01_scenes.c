/*
 * 01_scenes.c - every scene of scenes/ renders in this stage: exit status 0,
 * a finite, non-negative image (black is allowed: smallpt's light is hidden
 * from stage 02's point-light stand-in by the ceiling), and exactly one line
 * for each feature the scene uses that the stage does not model (naming the
 * scene and the stage); with --strict, the stage refuses exactly the scenes
 * that have such a line.  Rendered 8 pixels wide with one sample per pixel,
 * so that the stages without a BVH get through the million-triangle Buddha
 * in about a second.
 */
#include <dirent.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "course.h"
#include "gltf.h"
#include "render.h"
#include "scene.h"
#include "testlib.h"

#define MAX_SCENES 256
#define WIDTH "8"

static int
compare_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The scene files of scenes/ (paths from the project root), sorted. */
static int
list_scene_files(char **names, int max)
{
    DIR *dir = opendir(test_root_path("scenes"));
    int n = 0;
    for (struct dirent *e; dir && (e = readdir(dir)) != NULL && n < max;) {
        size_t len = strlen(e->d_name);
        if (len > 6 && strcmp(e->d_name + len - 6, ".scene") == 0) {
            names[n] = malloc(len + 8);
            snprintf(names[n++], len + 8, "scenes/%s", e->d_name);
        }
    }
    if (dir) {
        closedir(dir);
    }
    qsort(names, (size_t)n, sizeof *names, compare_names);
    return n;
}

static int
count_lines_with(const char *text, const char *needle)
{
    int n = 0;
    for (const char *line = text; *line;) {
        const char *end = strchr(line, '\n');
        size_t len = end ? (size_t)(end - line) : strlen(line);
        char buf[1024];
        snprintf(buf, sizeof buf, "%.*s", (int)(len < sizeof buf ? len : sizeof buf - 1), line);
        n += strstr(buf, needle) != NULL;
        line += len + (end != NULL);
    }
    return n;
}

/* The features the scene uses that this stage does not model. */
static int
unmodelled_features(const char *path, bool *loaded)
{
    struct scene s;
    struct diag err;
    *loaded = scene_load(path, &s, &err);
    if (!*loaded) {
        diag_print(stdout, &err, "error");
        return -1;
    }
    unsigned missing = s.features & ~(unsigned)RENDER_FEATURES;
    scene_free(&s);
    int n = 0;
    for (int f = 0; f < FEAT_COUNT; f++) {
        n += (missing & FEATURE_BIT(f)) != 0;
    }
    return n;
}

static bool
finite_and_non_negative(const struct image *im)
{
    bool ok = true;
    for (size_t i = 0; i < 3 * (size_t)im->width * (size_t)im->height; i++) {
        ok = ok && isfinite(im->rgb[i]) && im->rgb[i] >= 0;
    }
    return ok;
}

static void
check_scene(const char *name)
{
    const char *path = test_root_path(name);
    bool loaded;
    int notes = unmodelled_features(path, &loaded);
    if (!loaded && !gltf_available()) {
        printf("note: %s: not rendered, this build has no glTF support\n", name);
        return;
    }
    CHECK_MSG(loaded, "%s", name);
    const char *out = test_tmp_path("scene.pfm");
    const char *args[] = {"-W", WIDTH, "-s", "1", "-t", "2", "-o", out, NULL};
    char log[16384];
    int status = test_render(path, args, log, sizeof log);
    CHECK_MSG(status == 0, "%s: exit status %d:\n%s", name, status, log);
    struct image im = {0};
    struct diag err;
    bool read = status == 0 && image_read_pfm(out, &im, &err);
    CHECK_MSG(read && finite_and_non_negative(&im), "%s: no image, or not finite", name);
    if (read) {
        image_free(&im);
    }
    remove(out);
    // One line per unmodelled feature, each naming the scene and the stage.
    char said[600];
    snprintf(said, sizeof said, "not modelled by %s", STAGE_NAME);
    CHECK_MSG(
        count_lines_with(log, said) == notes && count_lines_with(log, "warning:") == notes
            && (notes == 0 || count_lines_with(log, name) == notes),
        "%s: expected %d notes:\n%s",
        name,
        notes,
        log);
    if (notes > 0) {
        const char *strict[] = {"-W", WIDTH, "--strict", "-o", out, NULL};
        CHECK_MSG(test_render(path, strict, log, sizeof log) == 1, "%s: --strict:\n%s", name, log);
        CHECK(!test_file_exists(out));
    }
}

TEST(every_scene_renders)
{
    char *names[MAX_SCENES];
    int n = list_scene_files(names, MAX_SCENES);
    CHECK(n >= 10);
    for (int i = 0; i < n; i++) {
        check_scene(names[i]);
        free(names[i]);
    }
}

TEST_MAIN(TEST_ENTRY(every_scene_renders))
