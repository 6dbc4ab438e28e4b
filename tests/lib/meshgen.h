/*
 * meshgen.h - triangle meshes made in memory, for tests and benchmarks, and
 * a minimal writer of binary glTF (.glb) files holding one of them.
 *
 * Conventions shared by every generator:
 *   - y is up; triangles are counter-clockwise seen from outside (glTF's
 *     front faces), so cross(p1 - p0, p2 - p0) points out of a closed mesh;
 *   - vertices are shared between the triangles that meet at them;
 *   - a generator returns the mesh by value; on bad parameters or when
 *     memory runs out it returns an empty mesh (all zero): check
 *     n_triangles > 0;
 *   - everything is deterministic: the same arguments give the same bytes.
 *
 * Free every mesh with meshgen_free (a zero-initialised one too).
 *
 * Sizes: meshgen_sphere(501, 1000, ...) makes 1,000,000 triangles in well
 * under a second; every generator is linear in its output.
 */
#ifndef MESHGEN_H
#define MESHGEN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct meshgen_mesh {
    size_t n_vertices;
    double *positions; /* 3 * n_vertices */
    double *normals; /* 3 * n_vertices, unit; NULL when the mesh has none */
    size_t n_triangles;
    unsigned *indices; /* 3 * n_triangles, each < n_vertices */
};

/* Allocate arrays for n_vertices and n_triangles (contents unset; normals
 * only when with_normals).  False (and m left empty) when memory runs out. */
bool
meshgen_alloc(struct meshgen_mesh *m, size_t n_vertices, size_t n_triangles, bool with_normals);

/* Free the arrays and zero the struct; accepts a zero-initialised mesh. */
void meshgen_free(struct meshgen_mesh *m);

/* A closed UV sphere.  n_theta >= 2 bands from pole to pole (polar angle),
 * n_phi >= 3 segments around the y axis (azimuth).  Each pole is a single
 * vertex and the seam at azimuth 0 is closed, so every edge is shared by
 * exactly two triangles.  Vertices: 2 + (n_theta - 1) * n_phi; triangles:
 * 2 * n_phi * (n_theta - 1).  jitter >= 0 moves every vertex radially by a
 * factor uniform in [1 - jitter, 1 + jitter] (seeded by seed); the mesh stays
 * closed.  Normals: exact sphere normals when jitter is 0, otherwise
 * area-weighted. */
struct meshgen_mesh meshgen_sphere(
    int n_theta,
    int n_phi,
    double radius,
    const double center[3],
    double jitter,
    uint64_t seed);

/* A closed icosphere: the regular icosahedron, each triangle split into four
 * `subdivisions` times (0..10) with midpoints shared, pushed onto the sphere.
 * 20 * 4^subdivisions triangles, no poles; exact sphere normals. */
struct meshgen_mesh meshgen_icosphere(int subdivisions, double radius, const double center[3]);

/* Split every triangle of `from` into four at its edge midpoints, each
 * midpoint made once and shared by the triangles of its edge (the mesh need
 * not be closed), into `to` (its arrays are new; `from` is unchanged).
 * Corners keep their index.  Normals, when `from` has them, carry over; a
 * midpoint's is the normalised mean of its edge's ends' (the lower-indexed
 * end's when they cancel), so the smooth shading stays that of `from`.  False
 * (and `to` empty) when memory runs out or the result would not fit
 * unsigned indices.  Triangles: 4 * n; vertices: n_vertices + edges. */
bool meshgen_subdivide(const struct meshgen_mesh *from, struct meshgen_mesh *to);

/* The closed axis-aligned box [lo, hi] (lo < hi on every axis): 8 shared
 * vertices, 12 triangles, no normals (it is meant to be flat-shaded). */
struct meshgen_mesh meshgen_box(const double lo[3], const double hi[3]);

/* A bumpy height field over [-size/2, size/2] in x and z: (nx + 1) * (nz + 1)
 * vertices, 2 * nx * nz triangles facing +y, heights within +-amplitude made
 * of a few random waves (seeded by seed).  Area-weighted normals.  Open: its
 * border edges belong to one triangle. */
struct meshgen_mesh meshgen_terrain(int nx, int nz, double size, double amplitude, uint64_t seed);

/* Kinds of degenerate triangle meshgen_random_triangles makes. */
enum meshgen_degenerate {
    MESHGEN_DEGENERATE_COLLINEAR, /* three distinct collinear points */
    MESHGEN_DEGENERATE_COINCIDENT, /* two corners at the same position */
    MESHGEN_DEGENERATE_POINT, /* all three corners at one position */
    MESHGEN_DEGENERATE_REPEATED_INDEX, /* the same vertex index twice */
    MESHGEN_DEGENERATE_KINDS,
};

/* A triangle soup of n triangles, vertices not shared (3 * n vertices, some
 * unused by REPEATED_INDEX triangles), no normals.  The first corner of each
 * triangle is uniform in the cube [-box_size/2, box_size/2]^3; the others lie
 * within max_edge of it on each axis, or anywhere in the cube when max_edge
 * <= 0.  A fraction degenerate_fraction (0..1) of the triangles is degenerate,
 * of a kind chosen at random.  Every coordinate is a multiple of a power of
 * two (box_size rounded up to a power of two, / 2^16), so degenerate
 * triangles are exactly degenerate: their cross product computes to exactly
 * zero in double (and the coordinates are exact in float32). */
struct meshgen_mesh meshgen_random_triangles(
    size_t n,
    uint64_t seed,
    double box_size,
    double max_edge,
    double degenerate_fraction);

/* Replace (or add) normals: area-weighted vertex normals, (0,0,0) for a
 * vertex no triangle of non-zero area uses.  False when memory runs out. */
bool meshgen_compute_normals(struct meshgen_mesh *m);

/* True when every edge is shared by exactly two triangles that traverse it
 * in opposite directions (closed, consistently oriented, no repeated
 * indices).  False also when memory runs out. */
bool meshgen_is_closed(const struct meshgen_mesh *m);

enum meshgen_index_type {
    MESHGEN_INDEX_UINT32, /* the default */
    MESHGEN_INDEX_UINT16, /* needs n_vertices < 65535 (0xffff is reserved) */
    MESHGEN_INDEX_NONE, /* non-indexed: three vertices written per triangle */
};

/* How meshgen_write_glb writes the mesh; zero-initialised means uint32
 * indices, normals when the mesh has them, an identity node. */
struct meshgen_glb_options {
    enum meshgen_index_type index_type;
    bool omit_normals;
    /* The node's transform: the matrix (column-major, as in glTF) when
     * has_matrix, otherwise whichever of translation, rotation (unit
     * quaternion x, y, z, w) and scale are set.  Values must be finite. */
    bool has_matrix;
    double matrix[16];
    bool has_translation;
    double translation[3];
    bool has_rotation;
    double rotation[4];
    bool has_scale;
    double scale[3];
    /* asset.copyright (UTF-8; quotes, backslashes and control characters
     * are escaped), or NULL for none. */
    const char *copyright;
    /* JSON spliced in as written, for files that say more than geometry
     * (each NULL when unused): `material` is the primitive's material, an
     * object such as {"pbrMetallicRoughness":{"baseColorFactor":[1,0,0,1]}};
     * `nodes` holds n_nodes more node objects, comma-separated, each a root
     * of the scene after the mesh's node (cameras, lights); `members` more
     * members of the top-level object, e.g. "cameras":[...]; `meshes` more
     * mesh objects after the mesh (mesh 1 on, placed by `nodes`), which
     * may share its accessors: POSITION 0, NORMAL 1, the indices 2;
     * `material` may hold several, comma-separated (the mesh's is 0). */
    const char *material;
    const char *nodes;
    int n_nodes;
    const char *members;
    const char *meshes;
    /* NULL: a .glb.  Else a .gltf: the JSON as text, its buffer in an
     * external file at this URI relative to the .gltf's directory (a
     * relative path, written into the JSON as given), which is written
     * too. */
    const char *bin_uri;
};

/* Write m as a .glb (or a .gltf and its buffer: bin_uri): one scene, one
 * node (with the options' transform), one mesh of one TRIANGLES primitive;
 * float32 POSITION with min/max (left out when a coordinate is not finite),
 * float32 NORMAL, and the indices.  opts may be NULL.  False when a file
 * cannot be written, memory runs out, the mesh does not fit the index type
 * or the file would exceed 4 GiB. */
bool meshgen_write_glb(
    const struct meshgen_mesh *m,
    const char *path,
    const struct meshgen_glb_options *opts);

#endif /* MESHGEN_H */
