/*
 * test_docs.c - the file names in docs/architecture.md exist.
 *
 * The map of the code names files; when a file moves, the map must move
 * with it.  Every `code` span that looks like a file name, and every link
 * target, must name a file or directory of the project:
 *   - with a '/', relative to the project root (`common/scene/scene.c`), or for a
 *     link, relative to docs/ (`stages/05_bvh.md`); NN_name stands for any
 *     stage (`stages/NN_name/render.c`: at least one stage has it);
 *   - without one (`render.c`), in common/, in some stage or at the root.
 * Function names (`scene_load()`), options and commands are not file names:
 * only spans of letters, digits and "_./-" that hold a '/' or end in a
 * source or document extension are checked; fenced blocks are skipped.
 */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "testlib.h"

#define MAX_NAME 512

static const char *const extensions[] = {
    ".c",
    ".h",
    ".cc",
    ".md",
    ".sh",
    ".mk",
    ".awk",
    ".in",
    ".stubs",
    ".scene",
    ".glb",
};

static bool
ends_with(const char *s, const char *end)
{
    size_t n = strlen(s);
    size_t m = strlen(end);
    return n >= m && strcmp(s + n - m, end) == 0;
}

static bool
looks_like_file(const char *s)
{
    if (s[0] == '\0'
        || strspn(s, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_./-")
               != strlen(s)) {
        return false;
    }
    if (strchr(s, '/') || strcmp(s, "Makefile") == 0) {
        return true;
    }
    for (size_t i = 0; i < sizeof extensions / sizeof extensions[0]; i++) {
        if (ends_with(s, extensions[i])) {
            return true;
        }
    }
    return false;
}

/* dir/name relative to the root (dir may be ""), trailing '/' allowed. */
static bool
exists_in(const char *dir, const char *name)
{
    char path[2 * MAX_NAME + 2];
    int w = snprintf(path, sizeof path, "%s%s%s", dir, dir[0] ? "/" : "", name);
    if (w < 0 || (size_t)w >= sizeof path) {
        return false; /* longer than any name the docs can hold */
    }
    size_t n = strlen(path);
    if (n > 1 && path[n - 1] == '/') {
        path[n - 1] = '\0';
    }
    return test_file_exists(test_root_path(path));
}

/* name with each stage directory in turn for "NN_name" (or for the dir
 * itself when the name has no placeholder): true when one exists. */
static bool
exists_in_some_stage(const char *name, bool bare)
{
    DIR *d = opendir(test_root_path("stages"));
    bool found = false;
    const char *nn = strstr(name, "NN_name");
    struct dirent *e;
    while (d && !found && (e = readdir(d)) != NULL) {
        if (e->d_name[0] < '0' || e->d_name[0] > '9') {
            continue;
        }
        char path[2 * MAX_NAME];
        if (bare) {
            snprintf(path, sizeof path, "stages/%s", e->d_name);
            found = exists_in(path, name);
        } else if (nn) {
            snprintf(
                path,
                sizeof path,
                "%.*s%s%s",
                (int)(nn - name),
                name,
                e->d_name,
                nn + strlen("NN_name"));
            found = exists_in("", path);
        }
    }
    if (d) {
        closedir(d);
    }
    return found;
}

/* A bare name of common/: in one of its layer folders (common/core/, ...). */
static bool
exists_in_common(const char *name)
{
    DIR *d = opendir(test_root_path("common"));
    bool found = false;
    struct dirent *e;
    while (d && !found && (e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.') {
            continue;
        }
        char dir[MAX_NAME];
        snprintf(dir, sizeof dir, "common/%s", e->d_name);
        found = exists_in(dir, name);
    }
    if (d) {
        closedir(d);
    }
    return found;
}

static bool
file_exists(const char *name, const char *link_dir)
{
    if (link_dir) {
        return strstr(name, "NN_name") ? false : exists_in(link_dir, name);
    }
    if (strstr(name, "NN_name")) {
        return exists_in_some_stage(name, false);
    }
    if (strchr(name, '/')) {
        return exists_in("", name);
    }
    return exists_in("common", name) || exists_in_common(name) || exists_in("", name)
           || exists_in_some_stage(name, true);
}

/* Checks one candidate; counts it in *checked and returns 1 when missing. */
static int
check_name(const char *start, size_t len, const char *link_dir, const char *doc, int *checked)
{
    char name[MAX_NAME];
    if (len == 0 || len >= sizeof name) {
        return 0;
    }
    memcpy(name, start, len);
    name[len] = '\0';
    if (link_dir) {
        char *anchor = strchr(name, '#');
        if (anchor) {
            *anchor = '\0';
        }
        if (name[0] == '\0' || strstr(name, "://") || strncmp(name, "mailto:", 7) == 0) {
            return 0;
        }
    } else if (!looks_like_file(name)) {
        return 0;
    }
    (*checked)++;
    if (file_exists(name, link_dir)) {
        return 0;
    }
    printf("%s: names '%s', which does not exist\n", doc, name);
    return 1;
}

/* The missing file names of text (a Markdown page in docs/): code spans
 * and link targets; *checked counts the names looked at. */
static int
missing_names(const char *text, const char *doc, int *checked)
{
    int missing = 0;
    *checked = 0;
    for (const char *p = text; *p; p++) {
        if (strncmp(p, "```", 3) == 0 && (p == text || p[-1] == '\n')) {
            const char *end = strstr(p + 3, "\n```");  // a fenced block: not names
            if (!end) {
                break;
            }
            p = end + 3;
        } else if (p[0] == '`') {
            const char *end = strchr(p + 1, '`');
            if (!end) {
                break;
            }
            missing += check_name(p + 1, (size_t)(end - p - 1), NULL, doc, checked);
            p = end;
        } else if (p[0] == ']' && p[1] == '(') {
            const char *end = strpbrk(p + 2, ") \n");
            if (!end) {
                break;
            }
            missing += check_name(p + 2, (size_t)(end - p - 2), "docs", doc, checked);
            p = end;
        }
    }
    return missing;
}

TEST(architecture_names_only_existing_files)
{
    const char *doc = "docs/architecture.md";
    char *text = test_read_file(test_root_path(doc), NULL);
    CHECK_MSG(text != NULL, "cannot read %s", doc);
    if (!text) {
        return;
    }
    int checked = 0;
    int missing = missing_names(text, doc, &checked);
    CHECK_MSG(missing == 0, "%d of %d file names in %s do not exist", missing, checked, doc);
    // A map of the code names its files: far fewer means the scan broke.
    CHECK_MSG(checked >= 30, "only %d file names found in %s", checked, doc);
    free(text);
}

TEST(a_missing_name_is_found)
{
    const char *text = "```\n`common/in_a_fence.c`\n```\n"
                       "`common/scene/scene.c` and `scene_load()` and `common/no_such_file.c`,\n"
                       "`render.c`, `not_a_stage_file.c`, `stages/NN_name/render.c`,\n"
                       "`stages/NN_name/nothing.c`, [the BVH](stages/05_bvh.md#lab) and\n"
                       "[gone](stages/99_none.md), [site](https://example.org/x.md).\n";
    int checked = 0;
    int missing = missing_names(text, "(test text)", &checked);
    CHECK(checked == 8);
    CHECK(missing == 4);
}

TEST_MAIN(TEST_ENTRY(architecture_names_only_existing_files), TEST_ENTRY(a_missing_name_is_found))
