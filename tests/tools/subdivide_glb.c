/*
 * subdivide_glb.c - a glTF model with every triangle split into four at its
 * edge midpoints, LEVELS times, written as a .glb.
 *
 *     subdivide_glb IN LEVELS OUT [COPYRIGHT]
 *
 * The make rule `models` uses it to make the 1,075,840-triangle Happy Buddha
 * (build/models/happy_res3_subdiv16.glb) from scenes/models/happy_res3.glb
 * with LEVELS 2: the same surface, 16 times as many triangles, so that the
 * BVH has the workload of Stanford's full-resolution scan without 25 MB of it
 * in the repository.  Positions of the new vertices are edge midpoints, so
 * the surface (silhouette, shadows) is exactly the input's; normals are
 * carried over (meshgen_subdivide), so is the smooth shading.  IN is read
 * with the stages' own loader (gltf.h: node transforms applied), OUT is
 * written with meshgen's writer: float32 positions and normals, uint32
 * indices, COPYRIGHT as its asset.copyright.  The same input gives the same
 * bytes.  Exit status 0, 1 when IN cannot be read or OUT written, 2 on a
 * usage error.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

#include "diag.h"
#include "gltf.h"
#include "meshgen.h"

/* 4^6 = 4096 times the triangles is far beyond any model that fits in
 * memory; the bound keeps a typo from trying. */
#define MAX_LEVELS 6

/* The loaded model as a meshgen mesh (the arrays are moved, not copied). */
static struct meshgen_mesh
as_meshgen(struct gltf_mesh *g)
{
    struct meshgen_mesh m = {
        .n_vertices = g->n_vertices,
        .positions = g->positions,
        .normals = g->normals,
        .n_triangles = g->n_triangles,
        .indices = g->indices,
    };
    *g = (struct gltf_mesh){0};
    return m;
}

static bool
parse_levels(const char *text, int *levels)
{
    char *end;
    errno = 0;
    long v = strtol(text, &end, 10);
    *levels = (int)v;
    return errno == 0 && end != text && *end == '\0' && v >= 0 && v <= MAX_LEVELS;
}

int
main(int argc, char **argv)
{
    int levels;
    if ((argc != 4 && argc != 5) || !parse_levels(argv[2], &levels)) {
        fprintf(stderr, "usage: subdivide_glb IN LEVELS(0..%d) OUT [COPYRIGHT]\n", MAX_LEVELS);
        return 2;
    }
    struct gltf_mesh loaded = {0};
    struct diag err;
    if (!gltf_load(argv[1], &loaded, &err)) {
        diag_print(stderr, &err, "error");
        return 1;
    }
    struct meshgen_mesh m = as_meshgen(&loaded);
    bool ok = true;
    for (int level = 0; level < levels && ok; level++) {
        struct meshgen_mesh finer;
        ok = meshgen_subdivide(&m, &finer);
        meshgen_free(&m);
        m = finer;
    }
    if (!ok) {
        fprintf(stderr, "subdivide_glb: %s: out of memory\n", argv[1]);
        return 1;
    }
    const struct meshgen_glb_options opts = {.copyright = argc == 5 ? argv[4] : NULL};
    ok = meshgen_write_glb(&m, argv[3], &opts);
    if (ok) {
        printf(
            "%s subdivided %d times: %zu triangles, %zu vertices\n",
            argv[1],
            levels,
            m.n_triangles,
            m.n_vertices);
    } else {
        fprintf(stderr, "subdivide_glb: cannot write %s\n", argv[3]);
    }
    meshgen_free(&m);
    return ok ? 0 : 1;
}
