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
 *   - a scene asking for ten million elements: ten million sphere
 *     statements (a scene file holds at most 64 MiB of text) and a small
 *     .glb whose nodes make ten million triangles: exit 1 before the memory
 *     is spent (the render's peak resident size is checked);
 *   - a glTF accessor of a billion elements: exit 1, the loader names it;
 *   - a .gltf whose JSON, once parsed, would pass --max-memory: exit 1
 *     before it is parsed;
 *   - a .gltf buffer outside the model's directory (absolute, .., a symbolic
 *     link): refused, exit 1;
 *   - --spp, -t, -W, -H, --max-depth, --max-memory at the extremes of their
 *     types: exit 2 with the valid range in the message;
 *   - memory or threads that cannot be had while loading or rendering:
 *     exit 4.
 */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "check.h"
#include "gltf.h"
#include "meshgen.h"
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
 * `words` (NULL-terminated) in the output; and an empty dir on failure.
 * Returns the render's peak resident set size in KiB. */
static long
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
    long peak_kib = -1;
    int got = test_render_peak(scene, argv, log, sizeof log, &peak_kib);
    CHECK_MSG(got == status, "%s: exit %d, expected %d:\n%s", case_name, got, status, log);
    for (int i = 0; words && words[i]; i++) {
        CHECK_MSG(strstr(log, words[i]) != NULL, "%s: no '%s' in:\n%s", case_name, words[i], log);
    }
    if (status != 0) {
        CHECK_MSG(entries(dir) == 0, "%s: files left in %s", case_name, dir);
    } else {
        CHECK_MSG(test_file_exists(out), "%s: no %s", case_name, out);
    }
    return peak_kib;
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

/* Peak resident sizes (KiB) a refused render stays below: the program and
 * its libraries (4 to 6 MiB measured; 12 to 19 under AddressSanitizer),
 * and, reading a scene through a pipe, the 64 MiB of text it may hold
 * (69 MiB measured).  AddressSanitizer's realloc copies, and its quarantine
 * keeps each smaller buffer the text grew through, with shadow memory on
 * top (228 MiB measured): still half the 448 MiB the stream would take. */
#define PEAK_SMALL_KIB (32L << 10)
#if defined(__SANITIZE_ADDRESS__)
#define CAPPED_TEXT_COPIES 4
#else
#define CAPPED_TEXT_COPIES 1
#endif
#define PEAK_OVER_CAPPED_TEXT_KIB \
    (PEAK_SMALL_KIB + (SCENE_FILE_CAP_BYTES >> 10) * CAPPED_TEXT_COPIES)

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

/* Ten million sphere statements: at least 47 bytes each ("sphere center
 * 0 0 -0 radius 0.3 material white"), 470 MB of text or more. */
#define TEN_MILLION 10000000L
#define SPHERE_STATEMENT_MIN_BYTES 47
#define SCENE_FILE_CAP_BYTES (64L << 20)

/* Write the header and the first n sphere statements (i = 0, 1, ...) to fd,
 * a chunk at a time; stop when the reader closes its end.  Returns the
 * bytes the reader took. */
static long long
write_spheres(int fd, long n)
{
    static char chunk[1 << 16];
    size_t used = (size_t)snprintf(chunk, sizeof chunk, "image width 16 height 16\n" SMALL_SCENE);
    long long taken = 0;
    for (long i = 0; i <= n; i++) {
        if (i == n || used > sizeof chunk - 128) {
            for (size_t off = 0; off < used;) {
                ssize_t w = write(fd, chunk + off, used - off);
                if (w < 0 && errno == EINTR) {
                    continue;
                }
                if (w <= 0) {
                    return taken; /* EPIPE: the reader is gone */
                }
                off += (size_t)w;
                taken += w;
            }
            used = 0;
        }
        if (i < n) {
            used += (size_t)snprintf(
                chunk + used,
                sizeof chunk - used,
                "sphere center %ld 0 -%ld radius 0.3 material white\n",
                i % 1000,
                i / 1000);
        }
    }
    return taken;
}

/* Open the FIFO at path for writing once process pid has opened it for
 * reading; -1 if pid ends first or a minute passes. */
static int
open_fifo_for_writing(const char *path, int pid)
{
    for (int tries = 0; tries < 6000; tries++) {
        int fd = open(path, O_WRONLY | O_NONBLOCK);
        if (fd >= 0) {
            fcntl(fd, F_SETFL, 0);
            return fd;
        }
        siginfo_t info = {.si_pid = 0};
        if (errno != ENXIO
            || (waitid(P_PID, (id_t)pid, &info, WEXITED | WNOHANG | WNOWAIT) == 0
                && info.si_pid == pid)) {
            return -1;
        }
        struct timespec pause = {0, 10000000};
        nanosleep(&pause, NULL);
    }
    return -1;
}

/* "A scene of ten million spheres": as text, 470 MB or more, over the 64 MiB
 * a scene file may hold.  Streamed through a FIFO (nothing on disk), the
 * loader must stop reading at the cap and refuse, holding no more than the
 * capped text; a regular file of that size is refused by its size before a
 * byte of it is read. */
TEST(ten_million_spheres_text)
{
    const char *fifo = test_tmp_path("ten_million.scene");
    unlink(fifo);
    CHECK(mkfifo(fifo, 0600) == 0);
    const char *dir = out_dir("ten_million_fifo");
    char out[1200];
    snprintf(out, sizeof out, "%s/out.png", dir);
    const char *argv[] = {test_render_binary(), "-q", "-o", out, fifo, NULL};
    const char *capture = test_tmp_path("ten_million.log");
    int pid = test_spawn(argv, capture);
    void (*was)(int) = signal(SIGPIPE, SIG_IGN);
    int fd = open_fifo_for_writing(fifo, pid);
    long long taken = fd >= 0 ? write_spheres(fd, TEN_MILLION) : -1;
    if (fd >= 0) {
        close(fd);
    }
    signal(SIGPIPE, was);
    long peak_kib = -1;
    int got = test_wait_peak(pid, &peak_kib);
    size_t len = 0;
    char *log = test_read_file(capture, &len);
    const char *text = log ? log : "";
    CHECK_MSG(got == EXIT_INPUT, "fifo: exit %d, expected 1:\n%s", got, text);
    CHECK_MSG(strstr(text, "too large for a scene file (over 64 MiB)") != NULL, "fifo: %s", text);
    CHECK_MSG(entries(dir) == 0, "fifo: files left in %s", dir);
    /* It read the cap and a byte more, and the pipe held at most 1 MiB. */
    CHECK_MSG(
        taken > SCENE_FILE_CAP_BYTES && taken <= SCENE_FILE_CAP_BYTES + (1L << 20) + 65536,
        "the render took %lld bytes of the %ld-byte stream",
        taken,
        TEN_MILLION * SPHERE_STATEMENT_MIN_BYTES);
    CHECK_MSG(
        peak_kib > 0 && peak_kib < PEAK_OVER_CAPPED_TEXT_KIB,
        "peak resident size %ld KiB reading a capped scene",
        peak_kib);
    printf("    fifo: took %lld bytes, peak resident size %ld KiB\n", taken, peak_kib);
    free(log);
    remove(capture);
    unlink(fifo);

    /* The same size as a regular file: the statements' start, then a hole. */
    const char *big = test_tmp_path("ten_million_file.scene");
    int file = open(big, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    CHECK(file >= 0 && write_spheres(file, 1000) > 0);
    CHECK(file >= 0 && ftruncate(file, (off_t)TEN_MILLION * SPHERE_STATEMENT_MIN_BYTES) == 0);
    if (file >= 0) {
        close(file);
    }
    const char *none[] = {NULL};
    const char *words[] = {"too large for a scene file (448 MiB, over 64 MiB)", NULL};
    long file_kib = expect_run("ten_million_file", big, none, EXIT_INPUT, words);
    CHECK_MSG(file_kib > 0 && file_kib < PEAK_SMALL_KIB, "peak resident size %ld KiB", file_kib);
    remove(big);
}

/* A .gltf whose one buffer is 36 bytes of a data: URI, read by an accessor
 * that declares `count` VEC3 floats; `members` (JSON, may be empty) are
 * more members of the top-level object. */
static const char *
gltf_with_members(const char *name, const char *count, const char *uri, const char *members)
{
    size_t cap = strlen(members) + 2048;
    char *text = malloc(cap);
    snprintf(
        text,
        cap,
        "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%s,"
        "\"type\":\"VEC3\"}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
        "\"buffers\":[{\"byteLength\":36,\"uri\":\"%s\"}]%s%s}",
        count,
        uri,
        members[0] ? "," : "",
        members);
    const char *path = test_tmp_path(name);
    test_write_file(path, text);
    free(text);
    return path;
}

static const char *
gltf_with_count(const char *name, const char *count, const char *uri)
{
    return gltf_with_members(name, count, uri, "");
}

#define DATA_36 \
    "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAA"

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
    REQUIRE_GLTF();
    gltf_with_count("billion.gltf", "1000000000", DATA_36);
    const char *none[] = {NULL};
    const char *words[] = {"billion.gltf", "accessor 0", "buffer view 0", NULL};
    expect_run("billion", mesh_scene("billion.scene", "billion.gltf"), none, EXIT_INPUT, words);
}

/* A small .glb whose nodes make more than ten million triangles: one
 * icosphere of 5,120 triangles (2,562 vertices), used by 1,955 nodes. */
#define ICOSPHERE_TRIANGLES 5120
#define INSTANCES 1955

static const char *
ten_million_triangles_glb(const char *name)
{
    const double center[3] = {0, 0.4, 0};
    struct meshgen_mesh mesh = meshgen_icosphere(4, 0.4, center);
    CHECK(mesh.n_triangles == ICOSPHERE_TRIANGLES);
    static const char node[] = "{\"mesh\":0}";
    char *nodes = malloc((INSTANCES - 1) * sizeof node);
    size_t used = 0;
    for (int i = 1; i < INSTANCES; i++) {
        used += (size_t)sprintf(nodes + used, "%s%s", i > 1 ? "," : "", node);
    }
    const struct meshgen_glb_options opts = {.nodes = nodes, .n_nodes = INSTANCES - 1};
    const char *path = test_tmp_path(name);
    CHECK(meshgen_write_glb(&mesh, path, &opts));
    free(nodes);
    meshgen_free(&mesh);
    return path;
}

/* Ten million triangles from a file of 150 KB, against --max-memory: the
 * loader counts every node's triangles before allocating any (refused at
 * 256 MiB with the counts in the message, the peak resident size small);
 * what the system refuses within the limit is exit 4 (below). */
TEST(ten_million_triangles_glb)
{
    REQUIRE_GLTF();
    const char *glb = ten_million_triangles_glb("ten_million.glb");
    struct stat st;
    CHECK(stat(glb, &st) == 0 && st.st_size < 256 * 1024);
    const char *scene = mesh_scene("ten_million_glb.scene", "ten_million.glb");
    const char *limit[] = {"--max-memory", "256", NULL};
    char count[64];
    snprintf(count, sizeof count, "%d triangles", ICOSPHERE_TRIANGLES * INSTANCES);
    const char *words[] =
        {"ten_million.glb", count, "memory limit of 255 MiB", "--max-memory", NULL};
    long peak_kib = expect_run("ten_million_glb", scene, limit, EXIT_INPUT, words);
    CHECK_MSG(peak_kib > 0 && peak_kib < PEAK_SMALL_KIB, "peak resident size %ld KiB", peak_kib);
}

/* A .gltf of 300,000 JSON values (600 KB: an "extras" array of zeros), 76
 * MiB by the loader's estimate once parsed (61 MiB measured): refused
 * before parsing under a 64 MiB limit, loaded under 512 MiB; the refused
 * run never builds the document (its peak is 32 MiB smaller at least). */
TEST(gltf_json_bounded)
{
    REQUIRE_GLTF();
    const long n_values = 300000;
    char *extras = malloc((size_t)n_values * 2 + 16);
    size_t used = (size_t)sprintf(extras, "\"extras\":[0");
    for (long i = 1; i < n_values; i++) {
        extras[used++] = ',';
        extras[used++] = '0';
    }
    sprintf(extras + used, "]");
    gltf_with_members("json.gltf", "3", DATA_36, extras);
    free(extras);
    const char *scene = mesh_scene("json.scene", "json.gltf");
    const char *low[] = {"--max-memory", "64", NULL};
    const char *words[] = {"json.gltf", "the JSON text", "once parsed", "--max-memory", NULL};
    long refused_kib = expect_run("json_refused", scene, low, EXIT_INPUT, words);
    const char *high[] = {"--max-memory", "512", NULL};
    long loaded_kib = expect_run("json_loaded", scene, high, 0, NULL);
    CHECK_MSG(
        refused_kib > 0 && loaded_kib - refused_kib > (32L << 10),
        "peak resident size %ld KiB refused, %ld KiB loaded",
        refused_kib,
        loaded_kib);
}

TEST(buffer_outside_the_model_refused)
{
    REQUIRE_GLTF();
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
 * threads, and the loader cannot have the 400 MB of the ten million
 * triangles' arrays (within the default 4096 MiB): exit 4 with a message,
 * no file.  Sanitizer builds reserve far more address space than that at
 * start, so they skip. */
static void
expect_starved(const char *case_name, const char *extra, const char *scene, const char *word)
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
        scene);
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
    const char *scene = small_scene("starved.scene", 48, 32);
    expect_starved("starved_memory", "-t 1 -W 4096 -H 4096 --spp 1", scene, "out of memory");
    expect_starved("starved_threads", "-t 64", scene, "cannot start 64 threads");
    if (gltf_available()) {
        ten_million_triangles_glb("starved.glb");
        const char *mesh = mesh_scene("starved_glb.scene", "starved.glb");
        expect_starved("starved_loader", "-t 1", mesh, "out of memory: the system refused");
    }
#endif
}

TEST_MAIN(
    TEST_ENTRY(huge_image_refused),
    TEST_ENTRY(max_memory_is_the_limit),
    TEST_ENTRY(too_many_elements_refused),
    TEST_ENTRY(ten_million_spheres_text),
    TEST_ENTRY(billion_element_accessor),
    TEST_ENTRY(ten_million_triangles_glb),
    TEST_ENTRY(gltf_json_bounded),
    TEST_ENTRY(buffer_outside_the_model_refused),
    TEST_ENTRY(option_extremes),
    TEST_ENTRY(option_maxima_accepted),
    TEST_ENTRY(out_of_memory_or_threads))
