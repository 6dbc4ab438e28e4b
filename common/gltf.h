/*
 * gltf.h - triangle meshes from glTF 2.0 files (.gltf or .glb).
 *
 * The only C++ in the project lives behind this C API: gltf_shim.cc (and the
 * gltf_*.cc files it lists) wraps tinygltf (Debian's libtinygltf-dev) when
 * the build finds it, and gltf_stub.c, compiled otherwise, returns a clear
 * error instead.
 *
 * gltf_load flattens every TRIANGLES primitive of the default scene (or of
 * scene 0 when none is marked default) into one world-space triangle list:
 * each node's transform (matrix or TRS, composed down the node tree) applied
 * to positions, its inverse transpose to normals.  Indices are 8, 16 or 32
 * bit; non-indexed primitives are taken three vertices at a time.
 *
 * The file is untrusted input: external buffer URIs must be relative and stay
 * inside the model's directory, every accessor is bounds-checked against its
 * buffer view and buffer before it is read, every index against the vertex
 * count, and sizes are checked before anything is allocated.  A broken file
 * gives false and a message, never a crash.
 */
#ifndef GLTF_H
#define GLTF_H

#include <stdbool.h>
#include <stddef.h>

#include "diag.h"

struct gltf_mesh {
    size_t n_vertices;
    double *positions; /* 3 * n_vertices, world space */
    double *normals; /* 3 * n_vertices, unit; NULL when no primitive had normals;
                        (0,0,0) for the vertices of primitives without them */
    size_t n_triangles;
    unsigned *indices; /* 3 * n_triangles, each < n_vertices */
};

/* True when built with tinygltf. */
bool gltf_available(void);

/* Load path into out (zero-initialised by the caller).  On failure out is
 * left empty and err names the file and the problem. */
bool gltf_load(const char *path, struct gltf_mesh *out, struct diag *err);

/* Free; accepts a zero-initialised mesh. */
void gltf_free(struct gltf_mesh *mesh);

#endif /* GLTF_H */
