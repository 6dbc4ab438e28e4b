/*
 * 07_reference_masks.c - the feature masks stored beside the references
 * (tests/reference/NAME.feature.pfm, by which make grade breaks a lab's
 * error down into regions) are what this stage's `--aov feature` writes
 * for the scenes now: a change to the scenes, the labels (common/render/aov.c) or
 * the geometry that moves a region fails here until `make
 * reference-masks` writes them again.
 */
#include <stdio.h>

#include "check.h"
#include "testlib.h"

TEST(stored_feature_masks_are_the_stage_s_feature_pass)
{
    static const char *const scenes[] = {
        "cornell_diffuse_point",
        "cornell_diffuse_area",
        "cornell_specular_area",
    };
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++) {
        char scene[256], out[256], written[256], stored[256];
        snprintf(scene, sizeof scene, "scenes/%s.scene", scenes[i]);
        snprintf(out, sizeof out, "%s.pfm", scenes[i]);
        snprintf(written, sizeof written, "%s.feature.pfm", scenes[i]);
        snprintf(stored, sizeof stored, "tests/reference/%s.feature.pfm", scenes[i]);
        const char *args[] = {"-s", "1", "--aov", "feature", "-o", test_tmp_path(out), NULL};
        char log[2048];
        int status = test_render(test_root_path(scene), args, log, sizeof log);
        CHECK_MSG(status == 0, "%s: status %d: %s", scene, status, log);
        CHECK_MSG(
            test_same_file(test_tmp_path(written), test_root_path(stored)),
            "%s differs from what this stage writes (make reference-masks)",
            stored);
    }
}

TEST_MAIN(TEST_ENTRY(stored_feature_masks_are_the_stage_s_feature_pass))
