/*
 * fuzz_gltf_check.h - load a glTF file and check what gltf.h promises; shared
 * by the .glb and .gltf harnesses.
 */
#ifndef FUZZ_GLTF_CHECK_H
#define FUZZ_GLTF_CHECK_H

/* gltf_load(path): on success every index is below n_vertices and the arrays
 * exist for the counts given; on failure the mesh is empty and err says why. */
void fuzz_gltf_load(const char *path);

#endif /* FUZZ_GLTF_CHECK_H */
