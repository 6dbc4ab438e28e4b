/*
 * 01_features.c - the features a stage declares (RENDER_FEATURES) are the
 * ones the shared table says it models, so the one-line notes are true.
 */
#include "check.h"
#include "course.h"
#include "render.h"

TEST(render_features_agree_with_the_feature_table)
{
    CHECK(RENDER_FEATURES == course_features_of_stage(course_stage_number(STAGE_NAME)));
}

TEST(every_feature_names_the_stage_that_adds_it)
{
    for (int f = 0; f < FEAT_COUNT; f++) {
        const struct course_feature *info = course_feature(f);
        CHECK(info->name != NULL);
        CHECK(info->first_stage >= 1 && info->first_stage <= info->last_stage);
        CHECK(info->last_stage <= COURSE_STAGES);
        CHECK_MSG(info->first_stage == 1 || info->before, "%s", info->name);
        CHECK_MSG(info->last_stage == COURSE_STAGES || info->after, "%s", info->name);
    }
}

TEST_MAIN(
    TEST_ENTRY(render_features_agree_with_the_feature_table),
    TEST_ENTRY(every_feature_names_the_stage_that_adds_it))
