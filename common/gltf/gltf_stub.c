/*
 * gltf_stub.c - gltf.h for builds without tinygltf.
 *
 * Compiled instead of gltf_load.cc and the gltf_*.cc files beside it when
 * the build does not find tinygltf, so the rest of the project links either
 * way: a scene that names a mesh gets a message saying how to obtain glTF
 * support, never a link error.
 */
#include "gltf.h"

bool
gltf_available(void)
{
    return false;
}

bool
gltf_load(const char *path, struct gltf_mesh *out, struct diag *err)
{
    return gltf_load_limited(path, GLTF_DEFAULT_MAX_BYTES, out, err);
}

bool
gltf_load_limited(const char *path, uint64_t max_bytes, struct gltf_mesh *out, struct diag *err)
{
    (void)max_bytes;
    *out = (struct gltf_mesh){0};
    diag_set(
        err,
        path,
        0,
        0,
        "this build has no glTF support: install libtinygltf-dev and rebuild");
    return false;
}
