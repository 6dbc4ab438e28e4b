/*
 * 07_signals.c - SIGTERM (kill, timeout, a batch scheduler's time limit)
 * and SIGHUP (a closed terminal) stop a progressive render as Ctrl-C does:
 * the complete passes are written, with their statistics, and the run
 * exits 0 (CONTRACT.md).  07_progressive.c covers SIGINT.
 *
 * Grading: make grade FULL=1 only (its renders stop after 1.5 s, so whether
 * a pass is complete by then depends on the machine's load: a score must
 * not; and it tests the given driver, not the lab's functions).
 */
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "stagecheck.h"
#include "testlib.h"

TEST(sigterm_and_sighup_write_the_complete_passes)
{
    const int signals[] = {SIGTERM, SIGHUP};
    const char *names[] = {"SIGTERM", "SIGHUP"};
    for (int i = 0; i < 2; i++) {
        char out[64], stats[64];
        snprintf(out, sizeof out, "%s.pfm", names[i]);
        snprintf(stats, sizeof stats, "%s.json", names[i]);
        struct stagecheck_endless run;
        if (!stagecheck_endless_render(&run, 64, test_tmp_path(out), test_tmp_path(stats))) {
            CHECK_MSG(false, "RENDER is not set");
            return;
        }
        int pid = test_spawn(run.argv, test_tmp_path("signals.log"));
        /* Long past loading the scene on a busy machine; the render would
         * take hours. */
        struct timespec wait = {1, 500 * 1000 * 1000};
        nanosleep(&wait, NULL);
        kill(pid, signals[i]);
        int status = test_wait(pid);
        char *log = test_read_file(test_tmp_path("signals.log"), NULL);
        CHECK_MSG(status == 0, "%s: exit %d: %s", names[i], status, log ? log : "");
        CHECK_MSG(log && strstr(log, "complete passes"), "%s: %s", names[i], log ? log : "");
        double spp = 0;
        CHECK_MSG(test_json_number(test_tmp_path(stats), "spp", &spp) && spp >= 1, "spp %g", spp);
        struct image img = {0};
        struct diag err;
        CHECK_MSG(image_read_pfm(test_tmp_path(out), &img, &err), "%s: no image", names[i]);
        image_free(&img);
        free(log);
    }
    CHECK(test_count_files(test_tmpdir(), ".stagelight-") == 0);
}

TEST_MAIN(TEST_ENTRY(sigterm_and_sighup_write_the_complete_passes))
