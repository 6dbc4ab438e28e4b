/*
 * scene_gltf.c - what a glTF file brings to a scene beyond its triangles
 * (docs/scene-format.md, "Materials from the file"):
 *   - its materials, mapped onto the kinds the renderer models: base colour
 *     to a diffuse albedo, a smooth metal to a mirror, transmission to
 *     glass;
 *   - its emissive primitives, whose triangles become emitting triangles
 *     (area lights of triangle shape, one-sided unless doubleSided);
 *   - one note per kind of thing it asks for that no stage models (a
 *     texture, a rough metal, clearcoat...), naming the file, the first
 *     material concerned and what is used instead; every stage prints the
 *     scene's notes as warnings, and --strict refuses them.
 * scene_gltf_file.c builds a whole scene from a file with these.
 */
#include "scene_parser.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gltf.h"

/* A roughnessFactor at or below this counts as perfectly smooth: a mirror
 * or clear glass (GGX with alpha = roughness^2 = 0.0025 is a highlight a
 * fraction of a degree wide). */
#define SMOOTH_ROUGHNESS 0.05

/* ORDER DROP: the kinds of what a material asks for and no stage models,
 * one note each. */
enum dropped {
    DROP_BASE_COLOR_TEXTURE,
    DROP_METALLIC_ROUGHNESS_TEXTURE,
    DROP_NORMAL_TEXTURE,
    DROP_OCCLUSION_TEXTURE,
    DROP_EMISSIVE_TEXTURE,
    DROP_METALLIC,
    DROP_ROUGHNESS,
    DROP_TRANSMISSION,
    DROP_GLASS_COLOR,
    DROP_EMITTER_COLOR,
    DROP_ALPHA,
    DROP_EXTENSIONS,
    DROP_KINDS,
};

/* One material's mapping: what it becomes, and what each dropped kind
 * says (empty when nothing of that kind was dropped). */
struct mapping {
    struct material material;
    vec3 emission; /* non-zero: its triangles emit this radiance */
    bool two_sided;
    char why[DROP_KINDS][200];
};

static real
clamp01(double x)
{
    return (real)(x < 0 ? 0 : x > 1 ? 1 : x);
}

/* baseColorFactor, times its texture's mean where it was averaged
 * (gltf_textures.cc: no stage maps a texture). */
static vec3
base_color(const struct gltf_material *g)
{
    const double *mean = g->base_color_mean;
    bool textured = g->averaged & GLTF_TEX_BASE_COLOR;
    return vec3_make(
        clamp01(g->base_color[0] * (textured ? mean[0] : 1)),
        clamp01(g->base_color[1] * (textured ? mean[1] : 1)),
        clamp01(g->base_color[2] * (textured ? mean[2] : 1)));
}

/* emissiveFactor x strength, times its texture's mean where it was averaged. */
static vec3
emission(const struct gltf_material *g)
{
    const double *mean = g->emissive_mean;
    bool textured = g->averaged & GLTF_TEX_EMISSIVE;
    return vec3_make(
        (real)(g->emissive[0] * (textured ? mean[0] : 1)),
        (real)(g->emissive[1] * (textured ? mean[1] : 1)),
        (real)(g->emissive[2] * (textured ? mean[2] : 1)));
}

/* Whether the material is a light.  It must emit; with an emissive texture
 * averaged, its glow must also cover at least half of the texture's texels
 * (a car's lamp), or its surface be black.  A glow on less than half is a
 * detail of a surface that reflects (a helmet's lights): no stage models a
 * surface that does both, and the larger part decides. */
static bool
is_emitter(const struct gltf_material *g)
{
    if (vec3_is_zero(emission(g))) {
        return false;
    }
    bool textured = g->averaged & GLTF_TEX_EMISSIVE;
    return !textured || g->emissive_glow >= 0.5 || vec3_is_zero(base_color(g));
}

static const char *
kind_name(enum material_kind kind)
{
    switch (kind) {
    case MAT_MIRROR:
        return "a mirror";
    case MAT_GLASS:
        return "glass";
    default:
        return "diffuse";
    }
}

static void
note_textures(const struct gltf_material *g, struct mapping *out)
{
    vec3 c = base_color(g);
    if ((g->textures & GLTF_TEX_BASE_COLOR) && (g->averaged & GLTF_TEX_BASE_COLOR)) {
        const double *m = g->base_color_mean;
        snprintf(
            out->why[DROP_BASE_COLOR_TEXTURE],
            sizeof out->why[0],
            "baseColorTexture not modelled; using its mean (%.3g, %.3g, %.3g) x baseColorFactor: "
            "(%.3g, %.3g, %.3g)",
            m[0],
            m[1],
            m[2],
            (double)c.x,
            (double)c.y,
            (double)c.z);
    } else if (g->textures & GLTF_TEX_BASE_COLOR) {
        snprintf(
            out->why[DROP_BASE_COLOR_TEXTURE],
            sizeof out->why[0],
            "baseColorTexture not modelled (%s); using baseColorFactor (%g, %g, %g)",
            g->base_color_why,
            (double)c.x,
            (double)c.y,
            (double)c.z);
    }
    if (g->textures & GLTF_TEX_METALLIC_ROUGHNESS) {
        snprintf(
            out->why[DROP_METALLIC_ROUGHNESS_TEXTURE],
            sizeof out->why[0],
            "metallicRoughnessTexture not modelled; using metallicFactor %g and roughnessFactor %g",
            g->metallic,
            g->roughness);
    }
    if (g->textures & GLTF_TEX_NORMAL) {
        snprintf(
            out->why[DROP_NORMAL_TEXTURE],
            sizeof out->why[0],
            "normalTexture not modelled; using the mesh's normals");
    }
    if (g->textures & GLTF_TEX_OCCLUSION) {
        snprintf(
            out->why[DROP_OCCLUSION_TEXTURE],
            sizeof out->why[0],
            "occlusionTexture not modelled; ignored (light is traced, not baked)");
    }
    vec3 e = emission(g);
    if ((g->textures & GLTF_TEX_EMISSIVE) && (g->averaged & GLTF_TEX_EMISSIVE)) {
        snprintf(
            out->why[DROP_EMISSIVE_TEXTURE],
            sizeof out->why[0],
            is_emitter(g) ? "emissiveTexture not modelled; emitting its mean x emissiveFactor x "
                            "strength (%.3g, %.3g, %.3g) (it glows on %.0f%% of its texels)"
                          : "emissiveTexture not modelled; its glow (%.3g, %.3g, %.3g on "
                            "average) is on %.0f%% of its texels: a surface that reflects, the "
                            "glow dropped",
            (double)e.x,
            (double)e.y,
            (double)e.z,
            100 * g->emissive_glow);
    } else if (g->textures & GLTF_TEX_EMISSIVE) {
        snprintf(
            out->why[DROP_EMISSIVE_TEXTURE],
            sizeof out->why[0],
            "emissiveTexture not modelled (%s); using emissiveFactor x strength (%g, %g, %g)",
            g->emissive_why,
            (double)e.x,
            (double)e.y,
            (double)e.z);
    }
}

static void
note_alpha_and_extensions(const struct gltf_material *g, struct mapping *out)
{
    static const char *const modes[] = {"OPAQUE", "MASK", "BLEND"};
    if (g->alpha_mode != GLTF_ALPHA_OPAQUE) {
        snprintf(
            out->why[DROP_ALPHA],
            sizeof out->why[0],
            "alphaMode %s (alpha %g) not modelled; opaque",
            modes[g->alpha_mode],
            g->base_color[3]);
    }
    if (g->other_extensions[0]) {
        snprintf(
            out->why[DROP_EXTENSIONS],
            sizeof out->why[0],
            "%s not modelled; ignored",
            g->other_extensions);
    }
}

/* An emissive material: its triangles emit; as surfaces they are black,
 * as every light is (SCENES.md). */
static void
map_emitter(const struct gltf_material *g, struct mapping *out)
{
    out->emission = emission(g);
    out->two_sided = g->double_sided;
    out->material.kind = MAT_DIFFUSE;
    vec3 c = base_color(g);
    if (!vec3_is_zero(c)) {
        snprintf(
            out->why[DROP_EMITTER_COLOR],
            sizeof out->why[0],
            "baseColorFactor (%g, %g, %g) of an emissive material not modelled; emitting "
            "surfaces reflect nothing",
            (double)c.x,
            (double)c.y,
            (double)c.z);
    }
}

/* KHR_materials_transmission: smooth clear glass of KHR_materials_ior's
 * index. */
static void
map_glass(const struct gltf_material *g, struct mapping *out)
{
    out->material.kind = MAT_GLASS;
    out->material.ior = (real)(g->ior > 0 ? g->ior : 1.5);
    vec3 c = base_color(g);
    if (g->transmission < 1) {
        snprintf(
            out->why[DROP_TRANSMISSION],
            sizeof out->why[0],
            "transmissionFactor %g not modelled; glass transmits all it does not reflect",
            g->transmission);
    }
    if (c.x < 1 || c.y < 1 || c.z < 1) {
        snprintf(
            out->why[DROP_GLASS_COLOR],
            sizeof out->why[0],
            "baseColorFactor (%g, %g, %g) of a transmissive material not modelled; clear glass",
            (double)c.x,
            (double)c.y,
            (double)c.z);
    }
    if (g->roughness > SMOOTH_ROUGHNESS) {
        snprintf(
            out->why[DROP_ROUGHNESS],
            sizeof out->why[0],
            "roughnessFactor %g of a transmissive material not modelled; smooth glass",
            g->roughness);
    }
}

/* The metallic-roughness model's two ends that a stage models: a smooth
 * metal is a mirror reflecting its base colour, a non-metal of roughness 1
 * is diffuse (its 4% specular layer neglected).  In between, the nearest
 * end: metallic >= 0.5 is a metal, and a metal of roughness >= 0.5 is
 * closer to diffuse than to a mirror. */
static void
map_surface(const struct gltf_material *g, struct mapping *out)
{
    bool metal = g->metallic >= 0.5;
    bool mirror = metal && g->roughness < 0.5;
    struct material *m = &out->material;
    m->kind = mirror ? MAT_MIRROR : MAT_DIFFUSE;
    m->reflectance = mirror ? base_color(g) : vec3_splat(0);
    m->albedo = mirror ? vec3_splat(0) : base_color(g);
    const char *as = kind_name(m->kind);
    if (g->metallic > 0 && g->metallic < 1) {
        snprintf(
            out->why[DROP_METALLIC],
            sizeof out->why[0],
            "metallicFactor %g not modelled (only 0 and 1); shaded as %s",
            g->metallic,
            as);
    }
    bool exact = mirror ? g->roughness <= SMOOTH_ROUGHNESS : !metal && g->roughness >= 1;
    if (!exact) {
        snprintf(
            out->why[DROP_ROUGHNESS],
            sizeof out->why[0],
            "roughnessFactor %g of a %s not modelled (a smooth metal is a mirror, a non-metal "
            "of roughness 1 diffuse); shaded as %s",
            g->roughness,
            metal ? "metal" : "non-metal",
            as);
    }
}

static void
map_material(const struct gltf_material *g, struct mapping *out)
{
    memset(out, 0, sizeof *out);
    if (is_emitter(g)) {
        map_emitter(g, out);
    } else if (g->has_transmission && g->transmission > 0) {
        map_glass(g, out);
    } else {
        map_surface(g, out);
    }
    note_textures(g, out);
    note_alpha_and_extensions(g, out);
}

/* glTF's default material, for primitives without one: white, metallic 1,
 * roughness 1 (glTF 2.0, "Default Material").  A file without materials
 * asked for none of that: it is shaded as white diffuse, the nearest
 * surface the stages model (map_surface), with no note to blame a metal on
 * (docs/blender.md). */
static const struct gltf_material default_material = {
    .name = "(default)",
    .base_color = {1, 1, 1, 1},
    .metallic = 1,
    .roughness = 1,
    .ior = 1.5,
};

/* --- Notes ---------------------------------------------------------------- */

void
scene_add_note(struct scene *s, struct src_loc at, const char *fmt, ...)
{
    if (s->n_notes >= SCENE_MAX_NOTES) {
        return;
    }
    char msg[sizeof s->notes[0].msg];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (s->n_notes == SCENE_MAX_NOTES - 1) {
        snprintf(
            msg,
            sizeof msg,
            "more that is not modelled (only %d notes are kept)",
            SCENE_MAX_NOTES - 1);
    }
    diag_set(&s->notes[s->n_notes++], s->path, at.line, at.col, "%s", msg);
}

/* --- The file's materials in the scene ------------------------------------- */

/* A scene material for a mapped glTF material, named "NAME (FILE)": a name
 * no scene token can spell (it has a space), so the file's materials never
 * clash with the scene's. */
static bool
add_file_material(
    struct parser *p,
    const struct token *at,
    const char *file,
    const struct gltf_material *g,
    const struct mapping *map,
    int *out)
{
    struct scene *s = p->scene;
    if (s->n_materials >= SCENE_MAX_MATERIALS) {
        return fail(p, at, "too many materials (at most %d)", SCENE_MAX_MATERIALS);
    }
    struct material *a =
        grow(p, at, s->materials, s->n_materials + 1, &p->cap.materials, sizeof *a);
    if (!a) {
        return false;
    }
    s->materials = a;
    struct material *m = &a[s->n_materials];
    *m = map->material;
    m->loc = loc_of(at);
    snprintf(m->name, sizeof m->name, "%.36s (%.24s)", g->name, file);
    if (m->kind == MAT_MIRROR) {
        use_feature(p, FEAT_MIRROR, at);
    } else if (m->kind == MAT_GLASS) {
        use_feature(p, FEAT_GLASS, at);
    }
    *out = s->n_materials++;
    return true;
}

/* The material extensions noted one by one: each different list of them
 * gets its own note (a file of clearcoat and sheen names both). */
#define DROP_EXTENSION_LISTS 8

/* What was dropped, by kind: how many materials and the first of them; for
 * the extensions, by each different list of them. */
struct drop_tally {
    int count[DROP_KINDS];
    const char *first_name[DROP_KINDS];
    char first_why[DROP_KINDS][200];
    int n_lists;
    int list_count[DROP_EXTENSION_LISTS];
    const char *list_name[DROP_EXTENSION_LISTS];
    char list_why[DROP_EXTENSION_LISTS][200];
};

static void
tally_extensions(struct drop_tally *t, const struct gltf_material *g, const char *why)
{
    for (int i = 0; i < t->n_lists; i++) {
        if (strcmp(t->list_why[i], why) == 0) {
            t->list_count[i]++;
            return;
        }
    }
    /* Past the last slot, the rest count with it (its note says "more"). */
    int i = t->n_lists < DROP_EXTENSION_LISTS ? t->n_lists++ : DROP_EXTENSION_LISTS - 1;
    if (t->list_count[i]++ == 0) {
        t->list_name[i] = g->name;
        snprintf(t->list_why[i], sizeof t->list_why[i], "%s", why);
    }
}

static void
tally(struct drop_tally *t, const struct gltf_material *g, const struct mapping *map)
{
    for (int k = 0; k < DROP_KINDS; k++) {
        if (k == DROP_EXTENSIONS && map->why[k][0]) {
            tally_extensions(t, g, map->why[k]);
        } else if (map->why[k][0] && t->count[k]++ == 0) {
            t->first_name[k] = g->name;
            memcpy(t->first_why[k], map->why[k], sizeof t->first_why[k]);
        }
    }
}

static void
note_one(
    struct parser *p,
    const struct token *at,
    const char *file,
    const char *name,
    const char *why,
    int count)
{
    char more[48] = "";
    if (count > 1) {
        snprintf(more, sizeof more, " (and %d more materials)", count - 1);
    }
    scene_add_note(p->scene, loc_of(at), "%s: material '%s': %s%s", file, name, why, more);
}

/* One note per dropped kind: the first material that dropped it, and how
 * many more did; the extensions, one note per different list of them. */
static void
note_dropped(struct parser *p, const struct token *at, const char *file, const struct drop_tally *t)
{
    for (int k = 0; k < DROP_KINDS; k++) {
        if (t->count[k] > 0) {
            note_one(p, at, file, t->first_name[k], t->first_why[k], t->count[k]);
        }
    }
    for (int i = 0; i < t->n_lists; i++) {
        note_one(p, at, file, t->list_name[i], t->list_why[i], t->list_count[i]);
    }
}

bool
map_file_materials(
    struct parser *p,
    const struct token *at,
    const char *file,
    const struct gltf_mesh *mesh,
    struct file_surface **out)
{
    size_t n = mesh->n_materials;
    struct file_surface *surf = calloc(n + 1, sizeof *surf);
    char *used = calloc(n + 1, 1);
    struct drop_tally *t = calloc(1, sizeof *t);
    bool ok = surf && used && t;
    if (!ok) {
        fail(p, at, "out of memory for %zu materials", n);
        diag_mark_no_memory(p->err);
    }
    for (size_t i = 0; ok && i < mesh->n_triangles; i++) {
        int m = mesh->triangle_material[i];
        used[m >= 0 && (size_t)m < n ? (size_t)m : n] = 1;
    }
    for (size_t i = 0; ok && i <= n; i++) {
        if (!used[i]) {
            continue;
        }
        const struct gltf_material *g = i < n ? &mesh->materials[i] : &default_material;
        struct mapping map;
        map_material(g, &map);
        if (g == &default_material) {
            memset(map.why, 0, sizeof map.why);
        }
        tally(t, g, &map);
        surf[i].emission = map.emission;
        surf[i].two_sided = map.two_sided;
        surf[i].material = -1;
        if (vec3_is_zero(map.emission)) {
            ok = add_file_material(p, at, file, g, &map, &surf[i].material);
        }
    }
    if (ok) {
        note_dropped(p, at, file, t);
    }
    free(used);
    free(t);
    if (!ok) {
        free(surf);
        surf = NULL;
    }
    *out = surf;
    return ok;
}
