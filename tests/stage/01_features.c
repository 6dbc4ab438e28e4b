/*
 * 01_features.c - the features a stage declares (RENDER_FEATURES) are the
 * ones the shared table says it models, so the one-line notes are true.
 */
#include "check.h"
#include "feature_table.h"
#include "render.h"

TEST(render_features_agree_with_the_feature_table)
{
    CHECK(RENDER_FEATURES == feature_table_of_stage(feature_table_stage_number(STAGE_NAME)));
}

TEST(every_feature_names_the_stage_that_adds_it)
{
    for (int f = 0; f < FEAT_COUNT; f++) {
        const struct feature_info *info = feature_info(f);
        CHECK(info->name != NULL);
        CHECK(info->first_stage >= 1 && info->first_stage <= info->last_stage);
        CHECK(info->last_stage <= STAGE_COUNT);
        CHECK_MSG(info->first_stage == 1 || info->before, "%s", info->name);
        CHECK_MSG(info->last_stage == STAGE_COUNT || info->after, "%s", info->name);
    }
}

TEST_MAIN(
    TEST_ENTRY(render_features_agree_with_the_feature_table),
    TEST_ENTRY(every_feature_names_the_stage_that_adds_it))
