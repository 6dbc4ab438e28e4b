/*
 * fuzz_scene.c - the scene text format (scene_load_string).
 *
 * The input is a scene file.  Its name places it in tests/fuzz/seeds/glb, so
 * a `mesh file tri.glb` statement reaches the glTF loader through the scene's
 * placement code with a real model.  A success must give a scene whose every
 * index is in range; a failure must say why.
 */
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"
#include "scene.h"

#define SCENE_NAME PROJECT_ROOT "/tests/fuzz/seeds/glb/fuzz.scene"

static void
check_scene(const struct scene *s)
{
    if (s->width < 1 || s->width > SCENE_MAX_IMAGE_DIM || s->height < 1
        || s->height > SCENE_MAX_IMAGE_DIM) {
        fuzz_fail("image size %dx%d out of range", s->width, s->height);
    }
    if (s->n_materials < 0 || s->n_spheres < 0 || s->n_quads < 0 || s->n_vertices < 0
        || s->n_triangles < 0 || s->n_point_lights < 0 || s->n_area_lights < 0) {
        fuzz_fail("negative count");
    }
    for (int i = 0; i < s->n_spheres; i++) {
        if (s->spheres[i].material < 0 || s->spheres[i].material >= s->n_materials) {
            fuzz_fail("sphere %d: material %d of %d", i, s->spheres[i].material, s->n_materials);
        }
    }
    for (int i = 0; i < s->n_quads; i++) {
        if (s->quads[i].material < 0 || s->quads[i].material >= s->n_materials) {
            fuzz_fail("quad %d: material %d of %d", i, s->quads[i].material, s->n_materials);
        }
    }
    for (int i = 0; i < s->n_triangles; i++) {
        const struct triangle *t = &s->triangles[i];
        if (t->material < 0 || t->material >= s->n_materials) {
            fuzz_fail("triangle %d: material %d of %d", i, t->material, s->n_materials);
        }
        for (int k = 0; k < 3; k++) {
            if (t->v[k] < 0 || t->v[k] >= s->n_vertices) {
                fuzz_fail("triangle %d: vertex %d of %d", i, t->v[k], s->n_vertices);
            }
        }
    }
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* An exact-size copy: reading past the text is an AddressSanitizer error. */
    char *text = malloc(size ? size : 1);
    if (!text) {
        return 0;
    }
    memcpy(text, data, size);
    struct scene scene = {0};
    struct diag err = {0};
    if (scene_load_string(text, size, SCENE_NAME, &scene, &err)) {
        check_scene(&scene);
    } else {
        fuzz_require_message(&err, "scene_load_string");
    }
    scene_free(&scene);
    free(text);
    return 0;
}
