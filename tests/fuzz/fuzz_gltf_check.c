/*
 * fuzz_gltf_check.c - see fuzz_gltf_check.h.
 */
#include "fuzz_gltf_check.h"

#include "fuzz.h"
#include "gltf.h"

void
fuzz_gltf_load(const char *path)
{
    struct gltf_mesh mesh = {0};
    struct diag err = {0};
    if (gltf_load(path, &mesh, &err)) {
        if (mesh.n_triangles > 0 && (!mesh.indices || !mesh.positions)) {
            fuzz_fail("%zu triangles without arrays", mesh.n_triangles);
        }
        for (size_t i = 0; i < 3 * mesh.n_triangles; i++) {
            if (mesh.indices[i] >= mesh.n_vertices) {
                fuzz_fail("index %u of %zu vertices", mesh.indices[i], mesh.n_vertices);
            }
        }
        /* Touch every coordinate: an array shorter than its count is an
         * AddressSanitizer error here. */
        volatile double sum = 0;
        for (size_t i = 0; i < 3 * mesh.n_vertices; i++) {
            sum += mesh.positions[i] + (mesh.normals ? mesh.normals[i] : 0);
        }
        (void)sum;
    } else {
        fuzz_require_message(&err, "gltf_load");
        if (mesh.n_vertices || mesh.n_triangles || mesh.positions || mesh.indices) {
            fuzz_fail("a failed gltf_load left a non-empty mesh");
        }
    }
    gltf_free(&mesh);
}
