/*
 * 01_resources.c - hostile inputs against every stage's binary: what a scene
 * or a command line asks for is bounded (docs/robustness.md).  Each case
 * checks the exit status, the message, and that no file was written (each
 * case writes into a directory of its own that must stay empty).
 *
 *   - a 16384x16384 image, or one that passes --max-memory: refused before
 *     any work, exit 1; --max-memory raises the limit;
 *   - more elements than --max-memory allows: refused by the loader at the
 *     statement that passes it, or before the acceleration structure and
 *     the image are allocated, exit 1;
 *   - a glTF accessor of a billion elements: exit 1, the loader names it;
 *   - a .gltf buffer outside the model's directory (absolute, .., a symbolic
 *     link): refused, exit 1;
 *   - --spp, -t, -W, -H, --max-depth, --max-memory at the extremes of their
 *     types: exit 2 with the valid range in the message;
 *   - memory or threads that cannot be had while rendering: exit 4.
 */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "gltf.h"
#include "testlib.h"

#define EXIT_INPUT 1
#define EXIT_USAGE 2
#define EXIT_RESOURCES 4

#define SMALL_SCENE \
    "camera origin 0 1 3.9 target 0 1 0 up 0 1 0 fov 40\n" \
    "material white diffuse albedo 0.73 0.73 0.73\n" \
    "sphere center 0 0.4 0 radius 0.4 material white\n" \
    "point_light position 0 1.9 0 intensity 3 2.5 2\n"

/* A scene file of the small scene with the image statement given. */
static const char *
small_scene(const char *name, int width, int height)
{
    char text[1024];
    snprintf(text, sizeof text, "image width %d height %d\n" SMALL_SCENE, width, height);
    const char *path = test_tmp_path(name);
    test_write_file(path, text);
    return path;
}

/* A fresh, empty directory for one case's output; returns it. */
static const char *
out_dir(const char *name)
{
    const char *dir = test_tmp_path(name);
    mkdir(dir, 0700);
    return dir;
}

/* The names in dir (not . and ..): 0 when the case left nothing behind. */
static int
entries(const char *dir)
{
    DIR *d = opendir(dir);
    int n = 0;
    struct dirent *e;
    while (d && (e = readdir(d)) != NULL) {
        n += strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0;
    }
    if (d) {
        closedir(d);
    }
    return d ? n : -1;
}

/* Render scene with args into dir/out.png; expect status and every word of
 * `words` (NULL-terminated) in the output; and an empty dir on failure. */
static void
expect_run(
    const char *case_name,
    const char *scene,
    const char *const args[],
    int status,
    const char *const words[])
{
    const char *dir = out_dir(case_name);
    char out[1200];
    snprintf(out, sizeof out, "%s/out.png", dir);
    const char *argv[40];
    int n = 0;
    argv[n++] = "-o";
    argv[n++] = out;
    for (int i = 0; args[i] && n < 38; i++) {
        argv[n++] = args[i];
    }
    argv[n] = NULL;
    char log[8192];
    int got = test_render(scene, argv, log, sizeof log);
    CHECK_MSG(got == status, "%s: exit %d, expected %d:\n%s", case_name, got, status, log);
    for (int i = 0; words && words[i]; i++) {
        CHECK_MSG(strstr(log, words[i]) != NULL, "%s: no '%s' in:\n%s", case_name, words[i], log);
    }
    if (status != 0) {
        CHECK_MSG(entries(dir) == 0, "%s: files left in %s", case_name, dir);
    } else {
        CHECK_MSG(test_file_exists(out), "%s: no %s", case_name, out);
    }
}

TEST(huge_image_refused)
{
    const char *scene = small_scene("huge.scene", 16384, 16384);
    const char *none[] = {NULL};
    const char *words[] = {"16384x16384", "memory limit of 4096 MiB", "--max-memory", NULL};
    expect_run("huge_scene", scene, none, EXIT_INPUT, words);
    const char *args[] = {"-W", "16384", "-H", "16384", NULL};
    expect_run("huge_options", small_scene("small.scene", 48, 32), args, EXIT_INPUT, words);
}

/* 768x768 pixels take more than 16 MiB (3 floats and two vec3 each, in
 * double or float) and less than 256 MiB: the limit decides, both ways. */
TEST(max_memory_is_the_limit)
{
    const char *scene = small_scene("mega.scene", 768, 768);
    const char *low[] = {"--max-memory", "16", "--spp", "1", NULL};
    const char *words[] = {"768x768", "memory limit of 16 MiB", NULL};
    expect_run("max_memory_low", scene, low, EXIT_INPUT, words);
    const char *high[] = {"--max-memory", "256", "--spp", "1", NULL};
    expect_run("max_memory_high", scene, high, 0, NULL);
}

/* A scene of n spheres on a small image. */
static const char *
spheres_scene(const char *name, int n)
{
    size_t cap = (size_t)n * 64 + 1024;
    char *text = malloc(cap);
    size_t used = (size_t)snprintf(text, cap, "image width 16 height 16\n" SMALL_SCENE);
    for (int i = 0; i < n; i++) {
        used += (size_t)snprintf(
            text + used,
            cap - used,
            "sphere center %d 0 -%d radius 0.3 material white\n",
            i % 1000,
            i / 1000);
    }
    const char *path = test_tmp_path(name);
    test_write_file(path, text);
    free(text);
    return path;
}

/* 200,000 spheres take 4 to 8 MB in the scene (float or double): over a
 * 1 MiB limit the loader stops at the sphere that passes it; under 12 MiB
 * the scene loads but the acceleration structure it would need does not
 * fit. */
TEST(too_many_elements_refused)
{
    const char *scene = spheres_scene("spheres.scene", 200000);
    const char *tiny[] = {"--max-memory", "1", NULL};
    const char *in_loader[] = {"spheres.scene:", "memory limit of 1 MiB", "--max-memory", NULL};
    expect_run("elements_loader", scene, tiny, EXIT_INPUT, in_loader);
    const char *small[] = {"--max-memory", "12", NULL};
    const char *in_check[] = {"200001 primitives", "memory limit of 12 MiB", NULL};
    expect_run("elements_render", scene, small, EXIT_INPUT, in_check);
}

/* A .gltf whose one buffer is 36 bytes of a data: URI, read by an accessor
 * that declares `count` VEC3 floats. */
static const char *
gltf_with_count(const char *name, const char *count, const char *uri)
{
    char text[2048];
    snprintf(
        text,
        sizeof text,
        "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%s,"
        "\"type\":\"VEC3\"}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
        "\"buffers\":[{\"byteLength\":36,\"uri\":\"%s\"}]}",
        count,
        uri);
    const char *path = test_tmp_path(name);
    test_write_file(path, text);
    return path;
}

#define DATA_36 "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAA"

/* A scene of one mesh file. */
static const char *
mesh_scene(const char *name, const char *mesh)
{
    char text[4096];
    snprintf(
        text,
        sizeof text,
        "image width 16 height 16\n" SMALL_SCENE "mesh file \"%s\" material white\n",
        mesh);
    const char *path = test_tmp_path(name);
    test_write_file(path, text);
    return path;
}

TEST(billion_element_accessor)
{
    if (!gltf_available()) {
        SKIP("built without tinygltf");
    }
    gltf_with_count("billion.gltf", "1000000000", DATA_36);
    const char *none[] = {NULL};
    const char *words[] = {"billion.gltf", "accessor 0", "buffer view 0", NULL};
    expect_run("billion", mesh_scene("billion.scene", "billion.gltf"), none, EXIT_INPUT, words);
}

TEST(buffer_outside_the_model_refused)
{
    if (!gltf_available()) {
        SKIP("built without tinygltf");
    }
    /* The 36 bytes, outside the models' directory and inside it. */
    static const unsigned char zeros[36];
    const char *outside = test_tmp_path("outside.bin");
    FILE *f = fopen(outside, "wb");
    CHECK(f && fwrite(zeros, 1, sizeof zeros, f) == sizeof zeros);
    if (f) {
        fclose(f);
    }
    mkdir(test_tmp_path("models"), 0700);
    const char *link = test_tmp_path("models/link.bin");
    unlink(link);
    CHECK(symlink(outside, link) == 0);

    const char *none[] = {NULL};
    gltf_with_count("models/absolute.gltf", "3", outside);
    const char *absolute[] = {"absolute paths are not allowed", NULL};
    expect_run(
        "uri_absolute",
        mesh_scene("absolute.scene", "models/absolute.gltf"),
        none,
        EXIT_INPUT,
        absolute);
    gltf_with_count("models/dotdot.gltf", "3", "../outside.bin");
    const char *dotdot[] = {"'..' is not allowed", NULL};
    expect_run(
        "uri_dotdot",
        mesh_scene("dotdot.scene", "models/dotdot.gltf"),
        none,
        EXIT_INPUT,
        dotdot);
    gltf_with_count("models/link.gltf", "3", "link.bin");
    const char *symlinked[] = {"link.bin", "outside the model's directory", NULL};
    expect_run(
        "uri_symlink",
        mesh_scene("link.scene", "models/link.gltf"),
        none,
        EXIT_INPUT,
        symlinked);
    /* The same buffer as a file of the directory is read. */
    const char *inside = test_tmp_path("models/inside.bin");
    f = fopen(inside, "wb");
    CHECK(f && fwrite(zeros, 1, sizeof zeros, f) == sizeof zeros);
    if (f) {
        fclose(f);
    }
    gltf_with_count("models/inside.gltf", "3", "inside.bin");
    expect_run("uri_inside", mesh_scene("inside.scene", "models/inside.gltf"), none, 0, NULL);
}

/* Each numeric option at the extremes of int, long long and beyond: exit 2,
 * the option and its valid range in the message. */
TEST(option_extremes)
{
    static const char *const values[] = {
        "0",
        "-1",
        "2147483647",
        "2147483648",
        "-2147483648",
        "-2147483649",
        "4294967296",
        "9223372036854775807",
        "9223372036854775808",
        "-9223372036854775809",
        "99999999999999999999999",
        "1e9",
        "",
    };
    struct {
        const char *option, *name, *range;
        int first_stage;
    } options[] = {
        {"--spp", "spp", "[1, 16777216]", 1},
        {"-t", "threads", "[1, 1024]", 1},
        {"-W", "width", "[1, 16384]", 1},
        {"-H", "height", "[1, 16384]", 1},
        {"--max-memory", "max-memory", "[1, 1073741824]", 1},
        {"--max-depth", "max-depth", "[1, 65536]", 4},
    };
    const char *scene = small_scene("small.scene", 48, 32);
    int stage = atoi(STAGE_NAME);
    for (size_t i = 0; i < sizeof options / sizeof options[0]; i++) {
        if (stage < options[i].first_stage) {
            continue;
        }
        for (size_t k = 0; k < sizeof values / sizeof values[0]; k++) {
            char case_name[64];
            snprintf(case_name, sizeof case_name, "extreme_%s_%zu", options[i].name, k);
            const char *args[] = {options[i].option, values[k], NULL};
            const char *words[] = {options[i].name, options[i].range, NULL};
            expect_run(case_name, scene, args, EXIT_USAGE, words);
        }
    }
}

/* The largest values that are valid are accepted (on a tiny image). */
TEST(option_maxima_accepted)
{
    const char *scene = small_scene("tiny.scene", 4, 4);
    const char *args[] = {"-t", "1024", "--max-memory", "1073741824", NULL};
    expect_run("maxima", scene, args, 0, NULL);
    if (atoi(STAGE_NAME) >= 4) {
        const char *depth[] = {"--max-depth", "65536", NULL};
        expect_run("max_depth", scene, depth, 0, NULL);
    }
}

/* Under a 400 MB address-space limit (ulimit -v) the render cannot have a
 * 4096x4096 image (about 1 GB, within --max-memory) nor the stacks of 64
 * threads: exit 4 with a message, no file.  Sanitizer builds reserve far
 * more address space than that at start, so they skip. */
static void
expect_starved(const char *case_name, const char *extra, const char *word)
{
    const char *dir = out_dir(case_name);
    char cmd[4096];
    snprintf(
        cmd,
        sizeof cmd,
        "ulimit -v 400000 && exec '%s' -q -o '%s/out.png' %s '%s'",
        test_render_binary(),
        dir,
        extra,
        small_scene("starved.scene", 48, 32));
    const char *argv[] = {"/bin/sh", "-c", cmd, NULL};
    char log[4096];
    int got = test_run(argv, log, sizeof log);
    CHECK_MSG(got == EXIT_RESOURCES, "%s: exit %d, expected 4:\n%s", case_name, got, log);
    CHECK_MSG(strstr(log, word) != NULL, "%s: no '%s' in:\n%s", case_name, word, log);
    CHECK_MSG(entries(dir) == 0, "%s: files left in %s", case_name, dir);
}

TEST(out_of_memory_or_threads)
{
#if defined(__SANITIZE_ADDRESS__)
    SKIP("AddressSanitizer needs more address space than the limit tested");
#else
    expect_starved("starved_memory", "-t 1 -W 4096 -H 4096 --spp 1", "out of memory");
    expect_starved("starved_threads", "-t 64", "cannot start 64 threads");
#endif
}

TEST_MAIN(
    TEST_ENTRY(huge_image_refused),
    TEST_ENTRY(max_memory_is_the_limit),
    TEST_ENTRY(too_many_elements_refused),
    TEST_ENTRY(billion_element_accessor),
    TEST_ENTRY(buffer_outside_the_model_refused),
    TEST_ENTRY(option_extremes),
    TEST_ENTRY(option_maxima_accepted),
    TEST_ENTRY(out_of_memory_or_threads))
