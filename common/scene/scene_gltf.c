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
 * scene_gltf_material.c maps one material; this file gives the scene a
 * file's materials and their notes.  scene_gltf_file.c builds a whole
 * scene from a file with these.
 */
#include "scene_parser.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gltf.h"
#include "scene_gltf_material.h"

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
        return scene_fail(p, at, "too many materials (at most %d)", SCENE_MAX_MATERIALS);
    }
    struct material *a =
        scene_grow(p, at, s->materials, s->n_materials + 1, &p->cap.materials, sizeof *a);
    if (!a) {
        return false;
    }
    s->materials = a;
    struct material *m = &a[s->n_materials];
    *m = map->material;
    m->loc = scene_loc_of(at);
    snprintf(m->name, sizeof m->name, "%.36s (%.24s)", g->name, file);
    if (m->kind == MAT_MIRROR) {
        scene_use_feature(p, FEAT_MIRROR, at);
    } else if (m->kind == MAT_GLASS) {
        scene_use_feature(p, FEAT_GLASS, at);
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
    scene_add_note(p->scene, scene_loc_of(at), "%s: material '%s': %s%s", file, name, why, more);
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
scene_map_file_materials(
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
        scene_fail(p, at, "out of memory for %zu materials", n);
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
        scene_gltf_map_material(g, &map);
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
