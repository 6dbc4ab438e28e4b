/* course.c - the stages of the course and the scene features each models (course.h). */
#include "course.h"

/* ORDER FEATURE */
static const struct course_feature table[FEAT_COUNT] = {
    [FEAT_POINT_LIGHT] = {.name = "point light", .first_stage = 1, .last_stage = COURSE_STAGES},
    [FEAT_AREA_LIGHT] =
        {
            .name = "area light",
            .first_stage = 3,
            .last_stage = COURSE_STAGES,
            .before = "lit as a point light at its centre with intensity L*A*cos(angle to its "
                      "normal), and not seen by the camera",
        },
    [FEAT_MIRROR] =
        {
            .name = "mirror material",
            .first_stage = 4,
            .last_stage = COURSE_STAGES,
            .before = "shaded as a diffuse surface with its reflectance as albedo",
        },
    [FEAT_GLASS] =
        {
            .name = "glass material",
            .first_stage = 4,
            .last_stage = COURSE_STAGES,
            .before = "shaded as a white diffuse surface",
        },
    [FEAT_BLEND] =
        {
            .name = "blend material",
            .first_stage = 4,
            .last_stage = COURSE_STAGES,
            .before = "only its diffuse part is shaded",
        },
    [FEAT_CHECKER] =
        {
            .name = "checker material",
            .first_stage = 4,
            .last_stage = COURSE_STAGES,
            .before = "shaded as diffuse with the mean of its two colours",
        },
    [FEAT_AMBIENT] =
        {
            .name = "ambient term",
            .first_stage = 1,
            .last_stage = 6,
            .after = "ignored: path tracing computes the indirect light it stands in for",
        },
    [FEAT_ENVIRONMENT] =
        {
            .name = "non-black background",
            .first_stage = 7,
            .last_stage = COURSE_STAGES,
            .before = "seen by rays that miss, but it lights nothing",
        },
    [FEAT_MESH] = {.name = "glTF mesh", .first_stage = 1, .last_stage = COURSE_STAGES},
    [FEAT_SPHERE_LIGHT] =
        {
            .name = "sphere light",
            .first_stage = 3,
            .last_stage = COURSE_STAGES,
            .before = "lit as a point light at its centre with intensity L*pi*r^2 (the same "
                      "irradiance where the whole sphere is above the horizon), and not seen by "
                      "the camera",
        },
};

static const char *const stage_names[COURSE_STAGES + 1] = {
    "?",
    "01_raycast",
    "02_shadows",
    "03_soft_shadows",
    "04_reflect_refract",
    "05_bvh",
    "06_supersample",
    "07_pathtrace",
    "08_variance_reduction",
    "09_fast_rays",
};

const struct course_feature *
course_feature(enum feature f)
{
    return &table[f];
}

int
course_stage_number(const char *name)
{
    if (!name || name[0] < '0' || name[0] > '9' || name[1] < '0' || name[1] > '9') {
        return 0;
    }
    return (name[0] - '0') * 10 + (name[1] - '0');
}

const char *
course_stage_name(int number)
{
    return number >= 1 && number <= COURSE_STAGES ? stage_names[number] : stage_names[0];
}

unsigned
course_features_of_stage(int number)
{
    unsigned mask = 0;
    for (int f = 0; f < FEAT_COUNT; f++) {
        if (number >= table[f].first_stage && number <= table[f].last_stage) {
            mask |= FEATURE_BIT(f);
        }
    }
    return mask;
}

int
course_unmodelled(
    const struct scene *s,
    unsigned modelled,
    const char *stage,
    struct diag *notes,
    int max)
{
    int n = 0;
    int here = course_stage_number(stage);
    for (int f = 0; f < FEAT_COUNT && n < max; f++) {
        if (!(s->features & FEATURE_BIT(f)) || (modelled & FEATURE_BIT(f))) {
            continue;
        }
        const struct course_feature *info = &table[f];
        struct src_loc at = s->feature_loc[f];
        if (here < info->first_stage) {
            diag_set(
                &notes[n++],
                s->path,
                at.line,
                at.col,
                "%s: not modelled by %s (%s adds it); %s",
                info->name,
                stage,
                course_stage_name(info->first_stage),
                info->before);
        } else {
            diag_set(
                &notes[n++],
                s->path,
                at.line,
                at.col,
                "%s: not modelled by %s; %s",
                info->name,
                stage,
                info->after ? info->after : "ignored");
        }
    }
    return n;
}
