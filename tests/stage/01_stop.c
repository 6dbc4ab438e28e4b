/*
 * 01_stop.c - a stop comes within a second (CONTRACT.md: SIGINT, SIGTERM
 * and SIGHUP stop a render), whatever the scene: the driver looks for it
 * after every pixel, not after every 16x16 tile, which on a heavy scene
 * takes many seconds.
 *
 * The heavy scene: a sphere of 1,280 emitting triangles (a glTF file, as
 * a car's emissive lamps arrive from Blender) over a floor.  Stages 01-02
 * light the floor from each triangle (a shadow ray to each at each shaded
 * point, every one tested against every triangle: no BVH); from 03 on,
 * each shadow ray goes to one triangle, picked (light_picker.h), so the
 * test asks for the most shadow rays a shading point may have, 65,536 a
 * point.  Either way a pixel costs milliseconds (a fifth of a second
 * where a lab's handout traverses by brute force) and a 16x16 tile
 * seconds: before the check per pixel, SIGTERM took 23 s (stage 03) to
 * 56 s (stage 07) to end its render.
 */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "meshgen.h"
#include "stagecheck.h"
#include "testlib.h"

static double
now_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

TEST(sigterm_ends_a_heavy_render_within_a_second)
{
    static const double centre[3] = {0, 1, 0};
    struct meshgen_mesh m = meshgen_icosphere(3, 0.5, centre);
    struct meshgen_glb_options opts = {
        .material = "{\"name\":\"lamps\",\"emissiveFactor\":[1,1,1],\"pbrMetallicRoughness\":"
                    "{\"baseColorFactor\":[0,0,0,1]}}",
    };
    bool written =
        m.n_triangles >= 1280 && meshgen_write_glb(&m, test_tmp_path("lamps.glb"), &opts);
    meshgen_free(&m);
    if (!written) {
        CHECK_MSG(false, "cannot write lamps.glb");
        return;
    }
    const char *scene = stagecheck_scene(
        "heavy.scene",
        "camera origin 0 1 4 target 0 0.5 0 up 0 1 0 fov 50\n"
        "image width 64 height 64\n"
        "material floor diffuse albedo 0.5 0.5 0.5\n"
        "quad corner -4 0 -4 edge1 0 0 8 edge2 8 0 0 material floor\n"
        "mesh file lamps.glb\n");
    const char *out = test_tmp_path("heavy.pfm");
    bool picks = atoi(STAGE_NAME) >= 3;
    const char *argv[] = {
        test_render_binary(),
        "-q",
        "-t",
        "1",
        "-o",
        out,
        scene,
        picks ? "--shadow-samples" : NULL,
        "65536",
        NULL};
    if (!scene || !argv[0]) {
        CHECK_MSG(false, "no scene or RENDER");
        return;
    }
    int pid = test_spawn(argv, test_tmp_path("heavy.log"));
    /* Past loading (a tenth of a second): the render is in its tiles.  One
     * thread: the test's cost is its wait. */
    struct timespec wait = {0, 500 * 1000 * 1000};
    nanosleep(&wait, NULL);
    double sent = now_seconds();
    kill(pid, SIGTERM);
    int status = test_wait(pid);
    double took = now_seconds() - sent;
    char *log = test_read_file(test_tmp_path("heavy.log"), NULL);
    printf("SIGTERM after 0.5 s: exit %d %.3f s later\n", status, took);
    CHECK_MSG(took < 1.0, "the render ended %.2f s after SIGTERM: %s", took, log ? log : "");
    /* A progressive stage writes the passes it completed (exit 0), the
     * others nothing. */
    CHECK_MSG(
        test_file_exists(out) == (status == 0),
        "exit %d, image %d",
        status,
        test_file_exists(out));
    CHECK(test_count_files(test_tmpdir(), ".stagelight-") == 0);
    free(log);
}

TEST_MAIN(TEST_ENTRY(sigterm_ends_a_heavy_render_within_a_second))
