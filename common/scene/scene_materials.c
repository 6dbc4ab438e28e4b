/*
 * scene_materials.c - the `material` statement: the kinds and the fields
 * each takes, the rules for a material's name, and how a shape's `material`
 * field finds its material (and the feature its kind needs).
 */
#include "scene_parser.h"

#include <string.h>

#define MAX_LISTED 6 /* material names listed by "unknown material" */

static int
find_material(const struct scene *s, const struct token *name)
{
    for (int i = 0; i < s->n_materials; i++) {
        if (scene_token_is(name, s->materials[i].name)) {
            return i;
        }
    }
    return -1;
}

static bool
unknown_material(struct parser *p, const struct token *name)
{
    const struct scene *s = p->scene;
    char list[MAX_LISTED * (SCENE_MAX_NAME + 2) + 8] = "";
    size_t used = 0;
    for (int i = 0; i < s->n_materials && i < MAX_LISTED; i++) {
        const char *sep = i ? ", " : "";
        used +=
            (size_t)snprintf(list + used, sizeof list - used, "%s%s", sep, s->materials[i].name);
    }
    if (s->n_materials == 0) {
        return scene_fail(
            p,
            name,
            "unknown material %s (none is defined before it)",
            scene_show(name).s);
    }
    const char *more = s->n_materials > MAX_LISTED ? ", ..." : "";
    return scene_fail(
        p,
        name,
        "unknown material %s (defined materials: %s%s)",
        scene_show(name).s,
        list,
        more);
}

static const struct range range_unit = {.lo = 0, .hi = 1, .text = "in [0, 1]"};

/* What each material kind takes (an unused slot of `fields` ends the list);
 * ORDER MAT_KIND. */
static const struct material_kind_spec {
    const char *name;
    int feature; /* what a shape using it needs; -1: nothing */
    struct field_spec fields[4];
} material_kinds[] = {
    [MAT_DIFFUSE] =
        {.name = "diffuse", .feature = -1, .fields = {NUMBERS("albedo", 3, true, &range_unit)}},
    [MAT_MIRROR] =
        {.name = "mirror",
         .feature = FEAT_MIRROR,
         .fields = {NUMBERS("reflectance", 3, true, &range_unit)}},
    [MAT_GLASS] =
        {.name = "glass",
         .feature = FEAT_GLASS,
         .fields = {NUMBERS("ior", 1, true, &scene_range_positive)}},
    [MAT_BLEND] =
        {.name = "blend",
         .feature = FEAT_BLEND,
         .fields =
             {NUMBERS("albedo", 3, true, &range_unit),
              NUMBERS("reflectance", 3, true, &range_unit)}},
    [MAT_CHECKER] =
        {.name = "checker",
         .feature = FEAT_CHECKER,
         .fields =
             {NUMBERS("albedo", 3, true, &range_unit),
              NUMBERS("albedo2", 3, true, &range_unit),
              NUMBERS("size", 1, true, &scene_range_positive)}},
};

#define N_MATERIAL_KINDS ((int)(sizeof material_kinds / sizeof material_kinds[0]))

/* The shape's `material` field: its index, and the feature its kind needs. */
bool
scene_use_material(struct parser *p, const struct token *kw, const struct fields *fs, int *out)
{
    const struct token *name = &scene_get(fs, "material")->val[0];
    int i = find_material(p->scene, name);
    if (i < 0) {
        return unknown_material(p, name);
    }
    int feature = material_kinds[p->scene->materials[i].kind].feature;
    if (feature >= 0) {
        scene_use_feature(p, (enum feature)feature, kw);
    }
    *out = i;
    return true;
}

static bool
is_name_char(char c, bool first)
{
    bool letter = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
    return letter || (!first && ((c >= '0' && c <= '9') || c == '-'));
}

static bool
check_material_name(struct parser *p, const struct token *t)
{
    const char *rule = "expected a letter or '_', then letters, digits, '_' or '-'";
    if (t->kind != TOK_WORD) {
        return scene_fail(
            p,
            t,
            "expected a material name after 'material', got %s",
            scene_show(t).s);
    }
    for (size_t i = 0; i < t->len; i++) {
        if (!is_name_char(t->text[i], i == 0)) {
            return scene_fail(p, t, "invalid material name %s (%s)", scene_show(t).s, rule);
        }
    }
    if (t->len > SCENE_MAX_NAME) {
        return scene_fail(
            p,
            t,
            "material name %s is longer than %d",
            scene_show(t).s,
            SCENE_MAX_NAME);
    }
    int first = find_material(p->scene, t);
    if (first >= 0) {
        int line = p->scene->materials[first].loc.line;
        return scene_fail(
            p,
            t,
            "duplicate material %s (first defined on line %d)",
            scene_show(t).s,
            line);
    }
    return true;
}

/* Whitted's blend reflects albedo diffusely and reflectance specularly: the
 * two together must not reflect more than arrives. */
static bool
check_blend(struct parser *p, const struct fields *fs)
{
    const struct field_value *albedo = scene_get(fs, "albedo");
    const struct field_value *refl = scene_get(fs, "reflectance");
    for (int i = 0; i < 3; i++) {
        double sum = (double)albedo->num[i] + (double)refl->num[i];
        if (sum > 1) {
            return scene_fail(
                p,
                &refl->val[i],
                "albedo + reflectance must be <= 1 per component, got %g",
                sum);
        }
    }
    return true;
}

static bool
add_material(
    struct parser *p,
    const struct token *kw,
    const struct token *name,
    int kind,
    const struct fields *fs)
{
    struct scene *s = p->scene;
    if (s->n_materials >= SCENE_MAX_MATERIALS) {
        return scene_fail(p, kw, "too many materials (at most %d)", SCENE_MAX_MATERIALS);
    }
    if (kind == MAT_BLEND && !check_blend(p, fs)) {
        return false;
    }
    struct material *a =
        scene_grow(p, kw, s->materials, s->n_materials + 1, &p->cap.materials, sizeof *a);
    if (!a) {
        return false;
    }
    s->materials = a;
    struct material *m = &a[s->n_materials++];
    *m = (struct material){.kind = (enum material_kind)kind, .loc = scene_loc_of(kw)};
    snprintf(m->name, sizeof m->name, "%.*s", (int)name->len, name->text);
    m->albedo = scene_get(fs, "albedo") ? scene_vec_of(fs, "albedo") : vec3_splat(0);
    m->albedo2 = scene_get(fs, "albedo2") ? scene_vec_of(fs, "albedo2") : vec3_splat(0);
    m->reflectance = scene_get(fs, "reflectance") ? scene_vec_of(fs, "reflectance") : vec3_splat(0);
    m->checker_size = scene_get(fs, "size") ? scene_get(fs, "size")->num[0] : 0;
    m->ior = scene_get(fs, "ior") ? scene_get(fs, "ior")->num[0] : 0;
    return true;
}

/* material NAME KIND fields...: the kind decides which fields follow. */
bool
scene_parse_material(struct parser *p, const struct token *kw, struct fields *fs)
{
    struct token name, kind;
    if (!scene_next_token(p, &name) || !check_material_name(p, &name)
        || !scene_next_token(p, &kind)) {
        return false;
    }
    int k = 0;
    while (k < N_MATERIAL_KINDS && !scene_token_is(&kind, material_kinds[k].name)) {
        k++;
    }
    if (k == N_MATERIAL_KINDS) {
        const char *kinds = "diffuse, mirror, glass, blend or checker";
        return scene_fail(
            p,
            &kind,
            "expected a material kind (%s) after %s, got %s",
            kinds,
            scene_show(&name).s,
            scene_show(&kind).s);
    }
    fs->spec = material_kinds[k].fields;
    const char *kind_name = material_kinds[k].name;
    snprintf(fs->context, sizeof fs->context, "%s material %s", kind_name, scene_show(&name).s);
    return scene_read_fields(p, kw, fs) && add_material(p, kw, &name, k, fs);
}
