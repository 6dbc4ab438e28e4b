/*
 * gltf_mesh.c - gltf_free (gltf.h), the same with or without tinygltf, so
 * that gltf_load.cc and gltf_stub.c need no copy of it.
 */
#include "gltf.h"

#include <stdlib.h>

void
gltf_free(struct gltf_mesh *mesh)
{
    free(mesh->positions);
    free(mesh->normals);
    free(mesh->indices);
    free(mesh->triangle_material);
    free(mesh->materials);
    free(mesh->cameras);
    free(mesh->lights);
    for (size_t i = 0; i < mesh->n_files; i++) {
        free(mesh->files[i]);
    }
    free(mesh->files);
    *mesh = (struct gltf_mesh){0};
}
