/*
 * gen_meshes.c - write the generated test meshes as .glb files.
 *
 *     gen_meshes OUTDIR
 *
 * writes into OUTDIR (which must exist):
 *     sphere_1k.glb    UV sphere, radius 1 at the origin, 1,000 triangles
 *                      (20 bands x 25 segments), smooth normals, closed
 *     terrain_10k.glb  height field 4 x 4 units, bumps within +-0.25,
 *                      10,000 triangles (100 x 50 cells), normals, open
 *     closed_mesh.glb  icosphere, radius 1 at the origin, 1,280 triangles
 *                      (3 subdivisions), smooth normals, closed
 *     lamps_100k.glb   a lamp of 100,352 emitting triangles (a car's lamps
 *                      from Blender have 88,837): a bumpy height field 1 x 1
 *                      unit (224 x 224 cells, bumps within +-0.02) turned
 *                      to face down and raised to y = 2, emissive (4, 4, 4)
 *                      from its lower side (make bench's many emitters)
 * The same bytes every run (fixed seeds).  Exit status 0, 1 when a file
 * cannot be written, 2 on a usage error.
 */
#include <stdio.h>

#include "meshgen.h"

/* Generator parameters: see the table above. */
#define SPHERE_BANDS 21 /* 20 rings of quads between the poles */
#define SPHERE_SEGMENTS 25
#define TERRAIN_NX 100
#define TERRAIN_NZ 50
#define TERRAIN_SIZE 4.0
#define TERRAIN_AMPLITUDE 0.25
#define TERRAIN_SEED 1
#define ICOSPHERE_LEVELS 3
#define LAMPS_CELLS 224
#define LAMPS_AMPLITUDE 0.02
#define LAMPS_HEIGHT 2.0

static int
write_mesh_with(
    const char *dir,
    const char *name,
    struct meshgen_mesh mesh,
    const struct meshgen_glb_options *opts)
{
    char path[4096];
    int n = snprintf(path, sizeof path, "%s/%s", dir, name);
    bool ok = n > 0 && (size_t)n < sizeof path && mesh.n_triangles > 0
              && meshgen_write_glb(&mesh, path, opts);
    if (!ok) {
        fprintf(stderr, "gen_meshes: %s: cannot write %s\n", dir, name);
    }
    meshgen_free(&mesh);
    return ok ? 0 : 1;
}

static int
write_mesh(const char *dir, const char *name, struct meshgen_mesh mesh)
{
    return write_mesh_with(dir, name, mesh, NULL);
}

int
main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: gen_meshes OUTDIR\n");
        return 2;
    }
    const char *dir = argv[1];
    const double origin[3] = {0, 0, 0};
    int failures = 0;
    failures += write_mesh(
        dir,
        "sphere_1k.glb",
        meshgen_sphere(SPHERE_BANDS, SPHERE_SEGMENTS, 1, origin, 0, 0));
    failures += write_mesh(
        dir,
        "terrain_10k.glb",
        meshgen_terrain(TERRAIN_NX, TERRAIN_NZ, TERRAIN_SIZE, TERRAIN_AMPLITUDE, TERRAIN_SEED));
    failures += write_mesh(dir, "closed_mesh.glb", meshgen_icosphere(ICOSPHERE_LEVELS, 1, origin));
    /* Half a turn about x: the field's upper side, its front, faces down. */
    struct meshgen_glb_options lamps = {
        .has_rotation = true,
        .rotation = {1, 0, 0, 0},
        .has_translation = true,
        .translation = {0, LAMPS_HEIGHT, 0},
        .material = "{\"name\":\"lamps\",\"emissiveFactor\":[1,1,1],\"extensions\":"
                    "{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":4}},"
                    "\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1]}}",
    };
    failures += write_mesh_with(
        dir,
        "lamps_100k.glb",
        meshgen_terrain(LAMPS_CELLS, LAMPS_CELLS, 1, LAMPS_AMPLITUDE, TERRAIN_SEED),
        &lamps);
    return failures ? 1 : 0;
}
