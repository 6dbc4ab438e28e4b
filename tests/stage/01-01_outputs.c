/*
 * 01-01_outputs.c - nothing lost (issue 21): every output is checked
 * before any work (distinct from the other outputs and from every input by
 * file identity, its directory there and writable), the outputs of a run
 * appear all together or not at all, and no signal short of SIGKILL leaves
 * a temporary file behind.  The plumbing is common/app/run.c and
 * common/app/run_outputs.c, the same in every stage, so stage 01 tests it.
 */
#include <dirent.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "check.h"
#include "gltf.h"
#include "meshgen.h"
#include "testlib.h"

/* Mostly empty space: a large image renders fast, so a test can make the
 * write (PNG encoding, a large share of the run) long enough to hit. */
static const char sparse_scene[] = "camera origin 0 0 5 target 0 0 0 up 0 1 0 fov 40\n"
                                   "image width 32 height 32\n"
                                   "material white diffuse albedo 0.7 0.7 0.7\n"
                                   "sphere center 0 0 0 radius 0.1 material white\n"
                                   "point_light position 0 2 2 intensity 3 3 3\n";

static const char *
scene_path(void)
{
    const char *path = test_tmp_path("sparse.scene");
    if (!test_file_exists(path)) {
        test_write_file(path, sparse_scene);
    }
    return path;
}

/* A fresh empty directory under the test's temporary directory. */
static const char *
fresh_dir(const char *name)
{
    const char *dir = test_tmp_path(name);
    mkdir(dir, 0777);
    return dir;
}

static const char *
in_dir(const char *dir, const char *name)
{
    static char paths[16][4096];
    static int next;
    char *p = paths[next++ % 16];
    snprintf(p, sizeof paths[0], "%s/%s", dir, name);
    return p;
}

/* Temporary files of the renderer in dir. */
static int
temporaries_in(const char *dir)
{
    return test_count_files(dir, ".stagelight-");
}

/* Remove every file of dir (not recursive) and dir itself. */
static void
remove_dir(const char *dir)
{
    DIR *d = opendir(dir);
    for (struct dirent *e = d ? readdir(d) : NULL; e; e = readdir(d)) {
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0) {
            remove(in_dir(dir, e->d_name));
        }
    }
    if (d) {
        closedir(d);
    }
    rmdir(dir);
}

static int
render_with(const char *const args[], char *log, size_t cap)
{
    return test_render(scene_path(), args, log, cap);
}

TEST(two_outputs_that_are_one_file_are_refused)
{
    const char *dir = fresh_dir("same");
    const char *a = in_dir(dir, "a.png");
    char dotted[4096];
    snprintf(dotted, sizeof dotted, "%s/./a.png", dir);
    const char *args[] = {"-o", a, "--stats", dotted, NULL};
    char log[4096];
    CHECK_MSG(render_with(args, log, sizeof log) == 2, "%s", log);
    CHECK_MSG(strstr(log, "a.png' and --stats") && strstr(log, "same file"), "%s", log);
    CHECK(!test_file_exists(a));
    remove_dir(dir);
}

TEST(an_output_over_the_scene_is_refused_by_identity)
{
    const char *dir = fresh_dir("over-scene");
    const char *scene = in_dir(dir, "my.scene");
    const char *hard = in_dir(dir, "link.json");
    test_write_file(scene, sparse_scene);
    CHECK(link(scene, hard) == 0);
    char dotted[4096];
    snprintf(dotted, sizeof dotted, "%s/../over-scene/my.scene", dir);
    const char *stats_names[] = {scene, dotted, hard};
    for (int i = 0; i < 3; i++) {
        const char *args[] = {"-o", in_dir(dir, "x.png"), "--stats", stats_names[i], NULL};
        char log[4096];
        CHECK_MSG(test_render(scene, args, log, sizeof log) == 2, "%s: %s", stats_names[i], log);
        CHECK_MSG(strstr(log, "my.scene") && strstr(log, "overwrite an input"), "%s", log);
    }
    char *text = test_read_file(scene, NULL);
    CHECK_MSG(text && strcmp(text, sparse_scene) == 0, "the scene file was changed");
    free(text);
    CHECK(!test_file_exists(in_dir(dir, "x.png")));
    remove_dir(dir);
}

/* A run that writes option's output over input, one of the files a scene
 * reads, is refused before any work (exit 2, naming both paths), and input
 * is left as it was. */
static void
check_refused_over_input(const char *scene, const char *option, const char *input, const char *dir)
{
    size_t len = 0;
    char *before = test_read_file(input, &len);
    const char *image = strcmp(option, "-o") == 0 ? input : in_dir(dir, "x.png");
    const char *args[] =
        {"-o", image, "--stats", strcmp(option, "-o") == 0 ? in_dir(dir, "x.json") : input, NULL};
    char log[4096];
    CHECK_MSG(test_render(scene, args, log, sizeof log) == 2, "%s %s: %s", option, input, log);
    char quoted[4200];
    snprintf(quoted, sizeof quoted, "%s '%s' is a file the scene reads, '", option, input);
    const char *name = strrchr(input, '/') ? strrchr(input, '/') + 1 : input;
    const char *said = strstr(log, quoted);
    CHECK_MSG(said && strstr(said + strlen(quoted), name), "%s", log);
    size_t after_len = 0;
    char *after = test_read_file(input, &after_len);
    CHECK_MSG(
        before && after && after_len == len && memcmp(before, after, len) == 0,
        "%s was changed",
        input);
    free(before);
    free(after);
}

/* The files a scene reads are inputs too: a mesh, and every file its glTF
 * load reads besides (external buffers, images, read though not decoded). */
TEST(an_output_over_a_file_the_scene_reads_is_refused)
{
    REQUIRE_GLTF();
    const char *dir = fresh_dir("over-mesh");
    const char *scene = in_dir(dir, "m.scene");
    size_t len = 0;
    char *glb = test_read_file(test_root_path("scenes/models/Box.glb"), &len);
    CHECK(glb && test_write_bytes(in_dir(dir, "box.glb"), glb, len));
    free(glb);
    struct meshgen_mesh box = meshgen_box((double[3]){-1, -1, -1}, (double[3]){1, 1, 1});
    /* With a camera, to be a whole scene too. */
    const struct meshgen_glb_options external = {
        .bin_uri = "model.bin",
        .nodes = "{\"camera\":0,\"translation\":[0,0,5]}",
        .n_nodes = 1,
        .members =
            "\"images\":[{\"uri\":\"texture.png\"}],"
            "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.7,\"znear\":0.1}}]",
    };
    CHECK(meshgen_write_glb(&box, in_dir(dir, "model.gltf"), &external));
    meshgen_free(&box);
    CHECK(test_write_file(in_dir(dir, "texture.png"), "a texture, never decoded"));
    test_write_file(
        scene,
        "camera origin 0 0 5 target 0 0 0 up 0 1 0 fov 40\n"
        "image width 8 height 8\n"
        "material white diffuse albedo 0.7 0.7 0.7\n"
        "mesh file box.glb material white\n"
        "mesh file model.gltf material white\n");
    check_refused_over_input(scene, "--stats", in_dir(dir, "box.glb"), dir);
    check_refused_over_input(scene, "--stats", in_dir(dir, "model.gltf"), dir);
    check_refused_over_input(scene, "-o", in_dir(dir, "texture.png"), dir);
    check_refused_over_input(scene, "--stats", in_dir(dir, "model.bin"), dir);
    /* The glTF file as the whole scene: its buffer is an input. */
    char gltf_scene[4096];
    snprintf(gltf_scene, sizeof gltf_scene, "%s", in_dir(dir, "model.gltf"));
    check_refused_over_input(gltf_scene, "--stats", in_dir(dir, "model.bin"), dir);
    CHECK(!test_file_exists(in_dir(dir, "x.png")) && !test_file_exists(in_dir(dir, "x.json")));
    remove_dir(dir);
}

/* A missing directory is found before the render: this one would take
 * minutes, so an answer within seconds means nothing was rendered. */
TEST(a_missing_directory_is_refused_at_once_and_nothing_is_written)
{
    const char *dir = fresh_dir("missing");
    const char *image = in_dir(dir, "st.png");
    const char *big[] = {"-W", "16384", "-H", "16384", "-o", image, "--stats"};
    const char *stats_missing[] =
        {big[0], big[1], big[2], big[3], big[4], big[5], big[6], "/nonexistent/s.json", NULL};
    const char *image_missing[] =
        {big[0], big[1], big[2], big[3], "-o", in_dir(dir, "nodir/x.png"), NULL};
    const char *const *cases[] = {stats_missing, image_missing};
    for (int i = 0; i < 2; i++) {
        char log[4096];
        double start = (double)time(NULL);
        CHECK_MSG(render_with(cases[i], log, sizeof log) == 3, "%s", log);
        CHECK_MSG((double)time(NULL) - start < 10, "took %.0f s", (double)time(NULL) - start);
        CHECK_MSG(strstr(log, "does not exist"), "%s", log);
    }
    CHECK(!test_file_exists(image));
    CHECK(temporaries_in(dir) == 0);
    remove_dir(dir);
}

/* -W alone scales the height by the scene's aspect ratio; past the limit
 * of a side that is refused before any memory is asked for. */
TEST(a_derived_image_size_past_the_limit_is_refused)
{
    const char *scene = test_tmp_path("tall.scene");
    test_write_file(
        scene,
        "camera origin 0 0 5 target 0 0 0 up 0 1 0 fov 40\n"
        "image width 1 height 4096\n"
        "point_light position 0 2 2 intensity 3 3 3\n");
    const char *out = test_tmp_path("tall.png");
    const char *args[] = {"-W", "8", "-o", out, NULL};
    char log[4096];
    CHECK_MSG(test_render(scene, args, log, sizeof log) == 2, "%s", log);
    CHECK_MSG(strstr(log, "8x32768"), "%s", log);
    CHECK(!test_file_exists(out));
}

/* An output that cannot be written when the image is done (its directory
 * removed during the render) takes the other outputs with it. */
TEST(when_one_output_fails_none_is_left)
{
    const char *dir = fresh_dir("one-fails");
    const char *stats_dir = fresh_dir("one-fails-stats");
    const char *image = in_dir(dir, "st.png");
    const char *argv[] = {
        test_render_binary(),
        "-q",
        "-W",
        "2048",
        "-H",
        "2048",
        "-o",
        image,
        "--stats",
        in_dir(stats_dir, "s.json"),
        scene_path(),
        NULL};
    int pid = test_spawn(argv, test_tmp_path("one-fails.log"));
    struct timespec pause = {0, 100 * 1000 * 1000};
    nanosleep(&pause, NULL); /* past the checks; the render takes longer */
    rmdir(stats_dir);
    int status = test_wait(pid);
    char *log = test_read_file(test_tmp_path("one-fails.log"), NULL);
    CHECK_MSG(status == 3, "exit %d: %s", status, log ? log : "");
    CHECK_MSG(!test_file_exists(image), "the image was left: %s", log ? log : "");
    CHECK(temporaries_in(dir) == 0);
    free(log);
    remove_dir(dir);
}

/* The temporary name is short: a 255-byte output name (the usual limit of
 * one file name) still works. */
TEST(the_longest_file_name_is_written)
{
    const char *dir = fresh_dir("long");
    char name[256];
    memset(name, 'a', 251);
    memcpy(name + 251, ".png", 5);
    const char *out = in_dir(dir, name);
    const char *args[] = {"-o", out, NULL};
    char log[4096];
    CHECK_MSG(render_with(args, log, sizeof log) == 0, "%s", log);
    CHECK(test_file_exists(out));
    CHECK(temporaries_in(dir) == 0);
    remove_dir(dir);
}

TEST(stats_dash_goes_to_standard_output)
{
    const char *dir = fresh_dir("dash");
    bool dash_before = test_file_exists("-"); /* in the working directory */
    const char *args[] = {"-o", in_dir(dir, "x.png"), "--stats", "-", NULL};
    char log[8192];
    CHECK_MSG(render_with(args, log, sizeof log) == 0, "%s", log);
    CHECK_MSG(strstr(log, "\"stage\": \"" STAGE_NAME "\""), "%s", log);
    CHECK(test_file_exists("-") == dash_before);
    CHECK(test_file_exists(in_dir(dir, "x.png")));
    remove_dir(dir);
}

/* Whether path is a complete PNG: it ends with the IEND chunk. */
static bool
complete_png(const char *path)
{
    size_t len = 0;
    char *data = test_read_file(path, &len);
    bool ok = data && len > 20 && memcmp(data + len - 8, "IEND", 4) == 0;
    free(data);
    return ok;
}

/* Start a render of a 1536x1536 PNG and its statistics into dir (the
 * -O3 build writes it in about 0.2 s; 1024x1024 took 0.1 s, and under
 * load too few signals arrived during the write); once its
 * first temporary file exists (the write has begun), wait `delay` seconds
 * and send the signals (sig2 too unless 0).  Returns the exit status. */
static int
signal_during_write(const char *dir, int sig1, int sig2, double delay)
{
    const char *argv[] = {
        test_render_binary(),
        "-q",
        "-W",
        "1536",
        "-H",
        "1536",
        "-o",
        in_dir(dir, "out.png"),
        "--stats",
        in_dir(dir, "out.json"),
        scene_path(),
        NULL};
    int pid = test_spawn(argv, test_tmp_path("signal.log"));
    struct timespec poll = {0, 200 * 1000};
    /* At most about 60 s: the write begins long before on any machine. */
    for (int i = 0; i < 300000 && temporaries_in(dir) == 0; i++) {
        nanosleep(&poll, NULL);
    }
    struct timespec wait = {(time_t)delay, (long)((delay - (double)(time_t)delay) * 1e9)};
    nanosleep(&wait, NULL);
    kill(pid, sig1);
    if (sig2) {
        kill(pid, sig2);
    }
    return test_wait(pid);
}

/* After any signal the directory holds no temporary file, and the image
 * and the statistics are there together, complete, or not at all. */
TEST(no_signal_leaves_a_temporary_file)
{
    struct {
        int sig1, sig2;
        bool completes; /* a first SIGINT, SIGTERM or SIGHUP lets the write finish */
    } cases[] = {
        {SIGTERM, 0, true},
        {SIGHUP, 0, true},
        {SIGINT, 0, true},
        {SIGTERM, SIGTERM, false},
        {SIGINT, SIGHUP, false},
        {SIGQUIT, 0, false},
        {SIGUSR1, 0, false},
        {SIGPIPE, 0, false},
        {SIGALRM, 0, false},
    };

    const double delays[] = {0, 0.03};
    int hits = 0;
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        for (size_t d = 0; d < sizeof delays / sizeof delays[0]; d++) {
            const char *dir = fresh_dir("signals");
            int status = signal_during_write(dir, cases[c].sig1, cases[c].sig2, delays[d]);
            bool image = test_file_exists(in_dir(dir, "out.png"));
            bool stats = test_file_exists(in_dir(dir, "out.json"));
            CHECK_MSG(
                temporaries_in(dir) == 0,
                "signal %d then %d after %.2f s: a temporary file is left",
                cases[c].sig1,
                cases[c].sig2,
                delays[d]);
            CHECK_MSG(
                image == stats,
                "signal %d: image %d, statistics %d",
                cases[c].sig1,
                image,
                stats);
            CHECK_MSG(!image || complete_png(in_dir(dir, "out.png")), "a partial image");
            if (cases[c].completes) {
                CHECK_MSG(status == 0 && image, "signal %d: exit %d", cases[c].sig1, status);
            } else if (status != 0) {
                hits++;
                CHECK_MSG(
                    !image,
                    "signal %d killed it (exit %d) yet left outputs",
                    cases[c].sig1,
                    status);
            }
            remove_dir(dir);
        }
    }
    /* The write is long enough that most signals arrive during it. */
    CHECK_MSG(hits >= 6, "only %d of 12 fatal signals arrived during the write", hits);
}

TEST_MAIN(
    TEST_ENTRY(two_outputs_that_are_one_file_are_refused),
    TEST_ENTRY(an_output_over_the_scene_is_refused_by_identity),
    TEST_ENTRY(an_output_over_a_file_the_scene_reads_is_refused),
    TEST_ENTRY(a_missing_directory_is_refused_at_once_and_nothing_is_written),
    TEST_ENTRY(a_derived_image_size_past_the_limit_is_refused),
    TEST_ENTRY(when_one_output_fails_none_is_left),
    TEST_ENTRY(the_longest_file_name_is_written),
    TEST_ENTRY(stats_dash_goes_to_standard_output),
    TEST_ENTRY(no_signal_leaves_a_temporary_file))
