/*
 * course.h - the course: its stages in order, which of them models which
 * scene feature, and what the stages before it do instead.
 *
 * Each stage declares the features it renders (RENDER_FEATURES in its
 * render.h).  When a scene uses one the stage does not model, main() prints
 * one line naming the stage that adds it and the simplification applied, or
 * refuses the scene under --strict (run_load_scene, common/app/run.h, with
 * course_unmodelled).  The texts live here, once, beside the stages and
 * outside common/ (which knows no stage), so every stage says the same
 * thing.  Every stage links course.c (common/stage.mk).
 */
#ifndef COURSE_H
#define COURSE_H

#include "diag.h"
#include "scene.h"

#define COURSE_STAGES 9

struct course_feature {
    const char *name; /* "area light" */
    int first_stage; /* first stage that models it */
    int last_stage; /* last stage that models it */
    const char *before; /* what stages before first_stage do instead */
    const char *after; /* what stages after last_stage do instead */
};

const struct course_feature *course_feature(enum feature f);

/* "05_bvh" -> 5; 0 when the name does not start with a stage number. */
int course_stage_number(const char *name);

/* 5 -> "05_bvh"; "?" outside 1..COURSE_STAGES. */
const char *course_stage_name(int number);

/* The features a stage models according to the table above. */
unsigned course_features_of_stage(int number);

/* One diagnostic per feature the scene uses and `modelled` lacks, located at
 * the statement that first uses it (at most FEAT_COUNT).  Fills at most max;
 * returns the count.  Each says what is not modelled, then, after its first
 * "; ", what the stage does instead (under --strict, which refuses the
 * scene, that part is left out).  The type of run.h's unmodelled_fn. */
int course_unmodelled(
    const struct scene *s,
    unsigned modelled,
    const char *stage,
    struct diag *notes,
    int max);

#endif /* COURSE_H */
