/*
 * fuzz_gltf.c - JSON glTF (.gltf) through the glTF loader, with its buffers.
 *
 * The input is the JSON text, optionally followed by a NUL byte and the bytes
 * of an external buffer: the harness writes model.gltf and, after the NUL,
 * buffer.bin beside it, so both a buffer named by "uri": "buffer.bin" and
 * data: URIs inside the JSON are fuzzed.  (JSON text never holds a raw NUL,
 * so the split loses nothing.)
 */
#include <string.h>

#include "fuzz.h"
#include "fuzz_gltf_check.h"

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const uint8_t *nul = memchr(data, '\0', size);
    size_t json_len = nul ? (size_t)(nul - data) : size;
    if (nul) {
        fuzz_write("buffer.bin", nul + 1, size - json_len - 1);
    } else {
        fuzz_remove("buffer.bin");
    }
    fuzz_gltf_load(fuzz_write("model.gltf", data, json_len));
    return 0;
}
