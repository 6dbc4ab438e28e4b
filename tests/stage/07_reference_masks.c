/*
 * 07_reference_masks.c - the feature masks stored beside the references
 * (tests/reference/NAME.feature.pfm, by which make grade breaks a lab's
 * error down into regions) are what this stage's `--aov feature` writes
 * for the scenes now: a change to the scenes, the labels (common/render/aov.c) or
 * the geometry that moves a region fails here until `make
 * reference-masks` writes them again.  The masks are written in double;
 * a single-precision build (REAL=float) leaves its shadow rays from its
 * own, coarser offset (the label uses the stage's spawn_ray_to), so there a
 * pixel on a shadow's edge may take the next label (lit, penumbra, umbra):
 * at most 1 pixel in 10,000, none further than the next label.
 *
 * Grading: make grade FULL=1 only (1.1 processor s: it keeps the project's
 * stored masks in step with its scenes and labels; the student's stage
 * draws the labels with given code).
 */
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "testlib.h"

#ifdef REAL_IS_FLOAT
/* The float build's mask against the stored one: the same size, at most 1
 * pixel in 10,000 different, each by one label among lit (1), penumbra (2)
 * and umbra (3). */
static void
check_float_mask(const char *written, const char *stored)
{
    struct image a = {0}, b = {0};
    struct diag err;
    CHECK_MSG(image_read_pfm(written, &a, &err), "%s: %s", written, err.msg);
    CHECK_MSG(image_read_pfm(stored, &b, &err), "%s: %s", stored, err.msg);
    if (a.rgb && b.rgb && a.width == b.width && a.height == b.height) {
        long n = (long)a.width * a.height, differ = 0, far = 0;
        for (long i = 0; i < n; i++) {
            int la = (int)a.rgb[3 * i], lb = (int)b.rgb[3 * i];
            differ += la != lb;
            far += la != lb && !(la >= 1 && la <= 3 && lb >= 1 && lb <= 3 && abs(la - lb) == 1);
        }
        CHECK_MSG(
            differ * 10000 <= n && far == 0,
            "%s: %ld of %ld pixels differ in float, %ld by more than one shadow label",
            stored,
            differ,
            n,
            far);
    } else {
        CHECK_MSG(false, "%s and %s: not two masks of one size", written, stored);
    }
    image_free(&a);
    image_free(&b);
}
#endif

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
#ifdef REAL_IS_FLOAT
        check_float_mask(test_tmp_path(written), test_root_path(stored));
#else
        CHECK_MSG(
            test_same_file(test_tmp_path(written), test_root_path(stored)),
            "%s differs from what this stage writes (make reference-masks)",
            stored);
#endif
    }
}

TEST_MAIN(TEST_ENTRY(stored_feature_masks_are_the_stage_s_feature_pass))
