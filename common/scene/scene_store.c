/*
 * scene_store.c - the scene's arrays as the loader fills them: room for
 * more elements within the memory limit, lights appended, features
 * recorded, and what scene_bytes() and scene_free() (scene.h) report and
 * release.  The lowest layer of the loader above the lexer: the builders
 * (scene_build.c, scene_materials.c, scene_mesh.c, scene_gltf*.c) call it,
 * it calls none of them.
 */
#include "scene_parser.h"

#include <limits.h>
#include <stdint.h>
#include <stdlib.h>

void
scene_use_feature(struct parser *p, enum feature f, const struct token *kw)
{
    if (!(p->scene->features & FEATURE_BIT(f))) {
        p->scene->features |= FEATURE_BIT(f);
        p->scene->feature_loc[f] = scene_loc_of(kw);
    }
}

/* Room for `need` items in an array of capacity *cap: the (possibly moved)
 * array, or NULL with the diag set (the old array is still owned by the
 * scene).  A statement adds one item, and a 64 MiB file holds far fewer
 * than INT_MAX statements; meshes check their counts before they come.
 * Every array counts against the parser's memory limit (p->max_bytes): the
 * items needed must fit in it, and the doubled capacity is cut to what
 * fits, so the limit is never passed, not even by the last doubling. */
void *
scene_grow(struct parser *p, const struct token *at, void *items, int need, int *cap, size_t size)
{
    if (need <= *cap) {
        return items;
    }
    uint64_t others = p->bytes - (uint64_t)*cap * size;
    uint64_t room = p->max_bytes > others ? (p->max_bytes - others) / size : 0;
    if ((uint64_t)need > room) {
        scene_fail(
            p,
            at,
            "the scene needs more than the memory limit of %llu MiB for its elements "
            "(%d spheres, %d quads, %d triangles, %d vertices so far); raise it with --max-memory",
            (unsigned long long)(p->max_bytes >> 20),
            p->scene->n_spheres,
            p->scene->n_quads,
            p->scene->n_triangles,
            p->scene->n_vertices);
        return NULL;
    }
    int new_cap = *cap < 16 ? 16 : *cap;
    while (new_cap < need) {
        new_cap = new_cap > INT_MAX / 2 ? INT_MAX : new_cap * 2;
    }
    new_cap = (uint64_t)new_cap > room ? (int)room : new_cap;
    void *grown = NULL;
    if ((size_t)new_cap <= SIZE_MAX / size) {
        grown = realloc(items, (size_t)new_cap * size);
    }
    if (!grown) {
        scene_fail(
            p,
            at,
            "out of memory: the system refused %llu MiB for the scene's elements (within the "
            "memory limit of %llu MiB)",
            (unsigned long long)(((uint64_t)new_cap * size) >> 20),
            (unsigned long long)(p->max_bytes >> 20));
        diag_mark_no_memory(p->err);
        return NULL;
    }
    p->bytes = others + (uint64_t)new_cap * size;
    *cap = new_cap;
    return grown;
}

/* Room for n more vertices and m more triangles. */
bool
scene_room_for_mesh(struct parser *p, const struct token *at, size_t n, size_t m)
{
    struct scene *s = p->scene;
    if (n > (size_t)(INT_MAX - s->n_vertices) || m > (size_t)(INT_MAX - s->n_triangles)) {
        return scene_fail(
            p,
            at,
            "too many vertices or triangles in the scene (at most %d)",
            INT_MAX);
    }
    vec3 *pos =
        scene_grow(p, at, s->positions, s->n_vertices + (int)n, &p->cap.positions, sizeof *pos);
    if (!pos) {
        return false;
    }
    s->positions = pos;
    vec3 *nrm = scene_grow(p, at, s->normals, s->n_vertices + (int)n, &p->cap.normals, sizeof *nrm);
    if (!nrm) {
        return false;
    }
    s->normals = nrm;
    int triangles = s->n_triangles + (int)m;
    struct triangle *tri =
        scene_grow(p, at, s->triangles, triangles, &p->cap.triangles, sizeof *tri);
    if (!tri) {
        return false;
    }
    s->triangles = tri;
    return true;
}

bool
scene_add_point_light(struct parser *p, const struct token *kw, struct point_light light)
{
    struct scene *s = p->scene;
    int n = s->n_point_lights;
    struct point_light *a = scene_grow(p, kw, s->point_lights, n + 1, &p->cap.points, sizeof *a);
    if (!a) {
        return false;
    }
    s->point_lights = a;
    a[s->n_point_lights++] = light;
    scene_use_feature(p, FEAT_POINT_LIGHT, kw);
    return true;
}

bool
scene_add_area_light(struct parser *p, const struct token *kw, struct area_light light)
{
    struct scene *s = p->scene;
    int n = s->n_area_lights;
    struct area_light *a = scene_grow(p, kw, s->area_lights, n + 1, &p->cap.areas, sizeof *a);
    if (!a) {
        return false;
    }
    s->area_lights = a;
    a[s->n_area_lights++] = light;
    scene_use_feature(p, FEAT_AREA_LIGHT, kw);
    return true;
}

uint64_t
scene_bytes(const struct scene *s)
{
    return (uint64_t)s->n_materials * sizeof *s->materials
           + (uint64_t)s->n_spheres * sizeof *s->spheres + (uint64_t)s->n_quads * sizeof *s->quads
           + (uint64_t)s->n_vertices * (sizeof *s->positions + sizeof *s->normals)
           + (uint64_t)s->n_triangles * sizeof *s->triangles
           + (uint64_t)s->n_point_lights * sizeof *s->point_lights
           + (uint64_t)s->n_area_lights * sizeof *s->area_lights;
}

void
scene_free(struct scene *s)
{
    free(s->materials);
    free(s->spheres);
    free(s->quads);
    free(s->positions);
    free(s->normals);
    free(s->triangles);
    free(s->point_lights);
    free(s->area_lights);
    for (int i = 0; i < s->n_input_files; i++) {
        free(s->input_files[i]);
    }
    free(s->input_files);
    free(s->sphere_lights);
    *s = (struct scene){.width = 0};
}
