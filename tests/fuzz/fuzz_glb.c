/*
 * fuzz_glb.c - binary glTF (.glb) through the glTF loader (gltf_load).
 *
 * The input is the whole .glb file: header, JSON chunk, BIN chunk.  A success
 * must give indices below the vertex count; a failure must say why.
 */
#include "fuzz.h"
#include "fuzz_gltf_check.h"

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_gltf_load(fuzz_write("model.glb", data, size));
    return 0;
}
