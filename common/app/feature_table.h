/*
 * feature_table.h - which stage models which scene feature, and what the stages
 * before it do instead.
 *
 * Each stage declares the features it renders (RENDER_FEATURES in its
 * render.h).  When a scene uses one the stage does not model, main() prints
 * one line naming the stage that adds it and the simplification applied, or
 * refuses the scene under --strict.  The texts live here, once, so every
 * stage says the same thing.
 */
#ifndef FEATURE_TABLE_H
#define FEATURE_TABLE_H

#include "diag.h"
#include "scene.h"

#define STAGE_COUNT 8

struct feature_info {
    const char *name; /* "area light" */
    int first_stage; /* first stage that models it */
    int last_stage; /* last stage that models it */
    const char *before; /* what stages before first_stage do instead */
    const char *after; /* what stages after last_stage do instead */
};

const struct feature_info *feature_info(enum feature f);

/* "05_bvh" -> 5; 0 when the name does not start with a stage number. */
int feature_table_stage_number(const char *feature_table_stage_name);

/* 5 -> "05_bvh"; "?" outside 1..STAGE_COUNT. */
const char *feature_table_stage_name(int number);

/* The features a stage models according to the table above. */
unsigned feature_table_of_stage(int number);

/* The most diagnostics feature_table_unmodelled gives. */
#define UNMODELLED_MAX (FEAT_COUNT + SCENE_MAX_NOTES)

/* One diagnostic per feature the scene uses and `modelled` lacks, located at
 * the statement that first uses it, then the scene's notes (what no stage
 * models).  Fills at most max; returns the count.  Each says what is not
 * modelled, then, after its first "; ", what the stage does instead (under
 * --strict, which refuses the scene, that part is left out). */
int feature_table_unmodelled(
    const struct scene *s,
    unsigned modelled,
    const char *stage,
    struct diag *notes,
    int max);

#endif /* FEATURE_TABLE_H */
