/*
 * replay.c - every input that ever broke a harness, and the seeds, run
 * through the harnesses in the ordinary build (no clang, no libFuzzer).
 *
 * Each harness's entry point is compiled under its own name
 * (fuzz_NAME_input, see fuzz.h); test NAME feeds it every file of
 * tests/fuzz/regressions/NAME and tests/fuzz/seeds/NAME.  A harness that
 * crashes, aborts on a broken promise, or (under make sanitize) trips a
 * sanitizer takes the program down, which the runner counts as a failure.
 *
 *     replay                      every test
 *     replay NAME ...             the named tests
 *     replay --run NAME FILE...   one harness on the given files (a reproducer)
 */
#include <dirent.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

int fuzz_scene_input(const uint8_t *data, size_t size);
int fuzz_glb_input(const uint8_t *data, size_t size);
int fuzz_gltf_input(const uint8_t *data, size_t size);
int fuzz_pfm_input(const uint8_t *data, size_t size);
int fuzz_cli_input(const uint8_t *data, size_t size);

typedef int (*fuzz_fn)(const uint8_t *data, size_t size);

struct harness {
    const char *name;
    fuzz_fn fn;
};

static const struct harness harnesses[] = {
    {"scene", fuzz_scene_input},
    {"glb", fuzz_glb_input},
    {"gltf", fuzz_gltf_input},
    {"pfm", fuzz_pfm_input},
    {"cli", fuzz_cli_input},
};

#define N_HARNESSES (sizeof harnesses / sizeof harnesses[0])

/* Run fn on the file at path; false when it cannot be read. */
static bool
replay_file(fuzz_fn fn, const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        return false;
    }
    uint8_t *data = NULL;
    size_t size = 0, cap = 0;
    bool ok = true;
    for (;;) {
        if (size == cap) {
            cap = cap ? 2 * cap : 4096;
            uint8_t *bigger = realloc(data, cap);
            if (!bigger) {
                ok = false;
                break;
            }
            data = bigger;
        }
        size_t got = fread(data + size, 1, cap - size, f);
        size += got;
        if (got == 0) {
            ok = !ferror(f);
            break;
        }
    }
    fclose(f);
    if (ok) {
        /* The exact size, as libFuzzer gives it: overreads stay detectable. */
        uint8_t *exact = malloc(size ? size : 1);
        ok = exact != NULL;
        if (ok) {
            memcpy(exact, data, size);
            fflush(stdout);
            fn(exact, size);
            free(exact);
        }
    }
    free(data);
    return ok;
}

static int
by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Replay every regular file of dir (sorted); returns how many, -1 when the
 * directory cannot be listed. */
static int
replay_dir(fuzz_fn fn, const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) {
        return -1;
    }
    char *names[4096];
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL && n < 4096) {
        if (e->d_name[0] != '.' && strcmp(e->d_name, "README.md") != 0) {
            names[n++] = strdup(e->d_name);
        }
    }
    closedir(d);
    qsort(names, (size_t)n, sizeof names[0], by_name);
    int done = 0;
    for (int i = 0; i < n; i++) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        CHECK_MSG(names[i] && replay_file(fn, path), "cannot read %s", path);
        done++;
        free(names[i]);
    }
    return done;
}

static void
replay_harness(const char *name)
{
    const struct harness *h = NULL;
    for (size_t i = 0; i < N_HARNESSES; i++) {
        if (strcmp(harnesses[i].name, name) == 0) {
            h = &harnesses[i];
        }
    }
    char dir[4096];
    snprintf(dir, sizeof dir, "%s/tests/fuzz/regressions/%s", PROJECT_ROOT, name);
    int regressions = replay_dir(h->fn, dir);
    CHECK_MSG(regressions >= 0, "cannot list %s", dir);
    snprintf(dir, sizeof dir, "%s/tests/fuzz/seeds/%s", PROJECT_ROOT, name);
    int seeds = replay_dir(h->fn, dir);
    CHECK_MSG(seeds > 0, "no seeds in %s", dir);
    printf("%s: replayed %d regression inputs and %d seeds\n", name, regressions, seeds);
}

TEST(scene)
{
    replay_harness("scene");
}

TEST(glb)
{
    replay_harness("glb");
}

TEST(gltf)
{
    replay_harness("gltf");
}

TEST(pfm)
{
    replay_harness("pfm");
}

TEST(cli)
{
    replay_harness("cli");
}

int
main(int argc, char **argv)
{
    if (argc >= 3 && strcmp(argv[1], "--run") == 0) {
        for (size_t i = 0; i < N_HARNESSES; i++) {
            if (strcmp(harnesses[i].name, argv[2]) != 0) {
                continue;
            }
            for (int k = 3; k < argc; k++) {
                printf("%s: %s\n", argv[2], argv[k]);
                if (!replay_file(harnesses[i].fn, argv[k])) {
                    perror(argv[k]);
                    return 1;
                }
            }
            printf("no crash\n");
            return 0;
        }
        fprintf(stderr, "replay: no harness '%s'\n", argv[2]);
        return 2;
    }
    static const struct check_test tests[] = {
        TEST_ENTRY(scene),
        TEST_ENTRY(glb),
        TEST_ENTRY(gltf),
        TEST_ENTRY(pfm),
        TEST_ENTRY(cli),
    };
    return check_run(tests, sizeof tests / sizeof tests[0], argc, argv);
}
