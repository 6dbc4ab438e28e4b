/*
 * meshgen.c - test meshes and a minimal GLB writer (see meshgen.h).
 *
 * The GLB writer follows the glTF 2.0 specification's "Binary glTF Layout":
 * a 12-byte header, a JSON chunk padded with spaces to 4 bytes and a BIN
 * chunk padded with zeros, all little-endian.  It is written here, not with
 * tinygltf, so tests can make files even in builds without glTF support and
 * so the loader is never checked against itself.
 */
#include "meshgen.h"

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rng.h"

#define MESHGEN_PI 3.14159265358979323846

/* Resolution of the random soup's grid: 2^16 steps per power-of-two box. */
#define SOUP_GRID_STEPS 65536.0

/* Waves summed by the terrain. */
#define TERRAIN_WAVES 6

#define MAX_ICOSPHERE_SUBDIVISIONS 10

/* GLB constants (glTF 2.0, "Binary glTF Layout" and accessor enums). */
#define GLB_MAGIC 0x46546C67u
#define GLB_VERSION 2u
#define GLB_CHUNK_JSON 0x4E4F534Au
#define GLB_CHUNK_BIN 0x004E4942u
#define GLB_HEADER_BYTES 12
#define GLB_CHUNK_HEADER_BYTES 8
#define GLTF_UNSIGNED_SHORT 5123
#define GLTF_UNSIGNED_INT 5125
#define GLTF_FLOAT 5126
#define GLTF_ARRAY_BUFFER 34962
#define GLTF_ELEMENT_ARRAY_BUFFER 34963

bool
meshgen_alloc(struct meshgen_mesh *m, size_t n_vertices, size_t n_triangles, bool with_normals)
{
    *m = (struct meshgen_mesh){0};
    if (n_vertices > SIZE_MAX / (3 * sizeof(double))
        || n_triangles > SIZE_MAX / (3 * sizeof(unsigned))) {
        return false;
    }
    // +1 so that empty arrays are still distinct allocations.
    m->positions = malloc((3 * n_vertices + 1) * sizeof(double));
    m->indices = malloc((3 * n_triangles + 1) * sizeof(unsigned));
    m->normals = with_normals ? malloc((3 * n_vertices + 1) * sizeof(double)) : NULL;
    if (!m->positions || !m->indices || (with_normals && !m->normals)) {
        meshgen_free(m);
        return false;
    }
    m->n_vertices = n_vertices;
    m->n_triangles = n_triangles;
    return true;
}

void
meshgen_free(struct meshgen_mesh *m)
{
    free(m->positions);
    free(m->normals);
    free(m->indices);
    *m = (struct meshgen_mesh){0};
}

static double
uniform(struct rng *r)
{
    return rng_next_u32(r) * 0x1p-32;
}

static void
set3(double *dst, double x, double y, double z)
{
    dst[0] = x;
    dst[1] = y;
    dst[2] = z;
}

static void
set_triangle(unsigned *dst, size_t a, size_t b, size_t c)
{
    dst[0] = (unsigned)a;
    dst[1] = (unsigned)b;
    dst[2] = (unsigned)c;
}

/* --- UV sphere ---------------------------------------------------------------- */

/* Vertex on ring `ring` (1 .. n_theta - 1) at segment `seg` (wrapping). */
static size_t
ring_vertex(int n_phi, int ring, int seg)
{
    return 1 + (size_t)(ring - 1) * (size_t)n_phi + (size_t)(seg % n_phi);
}

/* Unit directions from the centre, stored as the normals: the positions
 * are made from them by place_on_sphere. */
static void
sphere_vertices(struct meshgen_mesh *m, int n_theta, int n_phi)
{
    set3(m->normals, 0, 1, 0);
    for (int ring = 1; ring < n_theta; ring++) {
        double theta = MESHGEN_PI * ring / n_theta;
        for (int seg = 0; seg < n_phi; seg++) {
            double phi = 2 * MESHGEN_PI * seg / n_phi;
            double *n = m->normals + 3 * ring_vertex(n_phi, ring, seg);
            set3(n, sin(theta) * cos(phi), cos(theta), sin(theta) * sin(phi));
        }
    }
    set3(m->normals + 3 * (m->n_vertices - 1), 0, -1, 0);
}

/* Caps fan from the poles; each band between two rings is a strip of quads
 * split in two.  Corners a, b on the upper ring, c, d below them. */
static void
sphere_triangles(struct meshgen_mesh *m, int n_theta, int n_phi)
{
    unsigned *t = m->indices;
    size_t south = m->n_vertices - 1;
    for (int seg = 0; seg < n_phi; seg++) {
        set_triangle(t, 0, ring_vertex(n_phi, 1, seg + 1), ring_vertex(n_phi, 1, seg));
        t += 3;
    }
    for (int ring = 1; ring + 1 < n_theta; ring++) {
        for (int seg = 0; seg < n_phi; seg++) {
            size_t a = ring_vertex(n_phi, ring, seg);
            size_t b = ring_vertex(n_phi, ring, seg + 1);
            size_t c = ring_vertex(n_phi, ring + 1, seg);
            size_t d = ring_vertex(n_phi, ring + 1, seg + 1);
            set_triangle(t, a, b, d);
            set_triangle(t + 3, a, d, c);
            t += 6;
        }
    }
    for (int seg = 0; seg < n_phi; seg++) {
        set_triangle(
            t,
            south,
            ring_vertex(n_phi, n_theta - 1, seg),
            ring_vertex(n_phi, n_theta - 1, seg + 1));
        t += 3;
    }
}

/* Positions = center + r * unit normal, r jittered per vertex. */
static void
place_on_sphere(
    struct meshgen_mesh *m,
    double radius,
    const double center[3],
    double jitter,
    uint64_t seed)
{
    struct rng r = rng_make(seed, 0);
    for (size_t v = 0; v < m->n_vertices; v++) {
        double scale = radius;
        if (jitter > 0) {
            scale *= 1 + jitter * (2 * uniform(&r) - 1);
        }
        for (int k = 0; k < 3; k++) {
            m->positions[3 * v + k] = center[k] + scale * m->normals[3 * v + k];
        }
    }
}

struct meshgen_mesh
meshgen_sphere(
    int n_theta,
    int n_phi,
    double radius,
    const double center[3],
    double jitter,
    uint64_t seed)
{
    struct meshgen_mesh m = {0};
    if (n_theta < 2 || n_phi < 3 || (double)n_theta * n_phi > 1e9) {
        return m;
    }
    size_t n_vertices = 2 + (size_t)(n_theta - 1) * (size_t)n_phi;
    size_t n_triangles = 2 * (size_t)n_phi * (size_t)(n_theta - 1);
    if (!meshgen_alloc(&m, n_vertices, n_triangles, true)) {
        return m;
    }
    sphere_vertices(&m, n_theta, n_phi);
    sphere_triangles(&m, n_theta, n_phi);
    place_on_sphere(&m, radius, center, jitter, seed);
    if (jitter > 0 && !meshgen_compute_normals(&m)) {
        meshgen_free(&m);
    }
    return m;
}

/* --- icosphere ------------------------------------------------------------ */

/* Make m's triangles face away from the point `inside`. */
static void
orient_outward(struct meshgen_mesh *m, const double inside[3])
{
    for (size_t t = 0; t < m->n_triangles; t++) {
        unsigned *tri = m->indices + 3 * t;
        const double *p0 = m->positions + 3 * tri[0];
        const double *p1 = m->positions + 3 * tri[1];
        const double *p2 = m->positions + 3 * tri[2];
        double e1[3];
        double e2[3];
        for (int k = 0; k < 3; k++) {
            e1[k] = p1[k] - p0[k];
            e2[k] = p2[k] - p0[k];
        }
        double n[3] = {
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0]};
        double out = 0;
        for (int k = 0; k < 3; k++) {
            out += n[k] * (p0[k] - inside[k]);
        }
        if (out < 0) {
            unsigned swap = tri[1];
            tri[1] = tri[2];
            tri[2] = swap;
        }
    }
}

/* Vertices i and j of the icosahedron below are joined by an edge. */
static bool
is_edge(const struct meshgen_mesh *m, size_t i, size_t j)
{
    const double *a = m->positions + 3 * i;
    const double *b = m->positions + 3 * j;
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return fabs(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - 4) < 1e-9;
}

/* The icosahedron with vertices (0, +-1, +-g), (+-1, +-g, 0), (+-g, 0, +-1),
 * g the golden ratio: its edges have length 2 and its faces are the triples
 * of vertices joined pairwise by edges. */
static bool
icosahedron(struct meshgen_mesh *m)
{
    const double g = (1 + sqrt(5.0)) / 2;
    if (!meshgen_alloc(m, 12, 20, false)) {
        return false;
    }
    for (int i = 0; i < 4; i++) {
        double a = i & 1 ? -1 : 1;
        double b = i & 2 ? -g : g;
        set3(m->positions + 3 * i, 0, a, b);
        set3(m->positions + 3 * (4 + i), a, b, 0);
        set3(m->positions + 3 * (8 + i), b, 0, a);
    }
    size_t n = 0;
    for (size_t i = 0; i < 12; i++) {
        for (size_t j = i + 1; j < 12; j++) {
            if (!is_edge(m, i, j)) {
                continue;
            }
            for (size_t k = j + 1; k < 12; k++) {
                if (is_edge(m, i, k) && is_edge(m, j, k) && n < 20) {
                    set_triangle(m->indices + 3 * n++, i, j, k);
                }
            }
        }
    }
    orient_outward(m, (double[3]){0, 0, 0});
    return n == 20;
}

/* Midpoints shared between the two triangles of an edge: an open-addressing
 * table from the edge (lo, hi) to the vertex made at its middle. */
struct midpoints {
    uint64_t *keys; /* (lo << 32 | hi) + 1; 0 marks an empty slot */
    unsigned *vertex;
    size_t mask;
};

/* The normal at the middle of edge (a, b): the normalised mean of its ends'
 * normals, which is what interpolation across the old triangle gave there
 * up to length; a's when the two cancel. */
static void
midpoint_normal(double *normals, size_t v, unsigned a, unsigned b)
{
    double n[3];
    for (int k = 0; k < 3; k++) {
        n[k] = normals[3 * a + k] + normals[3 * b + k];
    }
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++) {
        normals[3 * v + k] = len > 0 ? n[k] / len : normals[3 * a + k];
    }
}

static unsigned
midpoint(struct midpoints *table, struct meshgen_mesh *m, unsigned a, unsigned b)
{
    unsigned lo = a < b ? a : b;
    unsigned hi = a < b ? b : a;
    uint64_t key = ((uint64_t)lo << 32 | hi) + 1;
    size_t slot = (size_t)(rng_mix64(key) & table->mask);
    while (table->keys[slot] != 0 && table->keys[slot] != key) {
        slot = (slot + 1) & table->mask;
    }
    if (table->keys[slot] == 0) {
        size_t v = m->n_vertices++;
        for (int k = 0; k < 3; k++) {
            m->positions[3 * v + k] = (m->positions[3 * a + k] + m->positions[3 * b + k]) / 2;
        }
        if (m->normals) {
            midpoint_normal(m->normals, v, lo, hi);
        }
        table->keys[slot] = key;
        table->vertex[slot] = (unsigned)v;
    }
    return table->vertex[slot];
}

bool
meshgen_subdivide(const struct meshgen_mesh *from, struct meshgen_mesh *to)
{
    // At most three new vertices a triangle (fewer where triangles share
    // edges); the result must stay indexable by unsigned.
    size_t max_edges = 3 * from->n_triangles;
    if (from->n_triangles > SIZE_MAX / 12 || from->n_vertices + max_edges > UINT_MAX) {
        *to = (struct meshgen_mesh){0};
        return false;
    }
    size_t slots = 1;
    while (slots < 2 * max_edges) {
        slots *= 2;
    }
    struct midpoints table = {
        calloc(slots, sizeof(uint64_t)),
        malloc(slots * sizeof(unsigned)),
        slots - 1};
    bool ok = table.keys && table.vertex
              && meshgen_alloc(
                  to,
                  from->n_vertices + max_edges,
                  4 * from->n_triangles,
                  from->normals != NULL);
    if (ok) {
        memcpy(to->positions, from->positions, 3 * from->n_vertices * sizeof(double));
        if (from->normals) {
            memcpy(to->normals, from->normals, 3 * from->n_vertices * sizeof(double));
        }
        to->n_vertices = from->n_vertices;
        for (size_t t = 0; t < from->n_triangles; t++) {
            const unsigned *c = from->indices + 3 * t;
            unsigned ab = midpoint(&table, to, c[0], c[1]);
            unsigned bc = midpoint(&table, to, c[1], c[2]);
            unsigned ca = midpoint(&table, to, c[2], c[0]);
            unsigned *dst = to->indices + 12 * t;
            set_triangle(dst, c[0], ab, ca);
            set_triangle(dst + 3, ab, c[1], bc);
            set_triangle(dst + 6, ca, bc, c[2]);
            set_triangle(dst + 9, ab, bc, ca);
        }
    }
    free(table.keys);
    free(table.vertex);
    return ok;
}

struct meshgen_mesh
meshgen_icosphere(int subdivisions, double radius, const double center[3])
{
    struct meshgen_mesh m = {0};
    if (subdivisions < 0 || subdivisions > MAX_ICOSPHERE_SUBDIVISIONS || !icosahedron(&m)) {
        meshgen_free(&m);
        return m;
    }
    for (int level = 0; level < subdivisions; level++) {
        struct meshgen_mesh finer = {0};
        bool ok = meshgen_subdivide(&m, &finer);
        meshgen_free(&m);
        if (!ok) {
            meshgen_free(&finer);
            return m;
        }
        m = finer;
    }
    m.normals = malloc((3 * m.n_vertices + 1) * sizeof(double));
    if (!m.normals) {
        meshgen_free(&m);
        return m;
    }
    for (size_t v = 0; v < m.n_vertices; v++) {
        double *p = m.positions + 3 * v;
        double len = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        set3(m.normals + 3 * v, p[0] / len, p[1] / len, p[2] / len);
    }
    place_on_sphere(&m, radius, center, 0, 0);
    return m;
}

/* --- box ------------------------------------------------------------------ */

struct meshgen_mesh
meshgen_box(const double lo[3], const double hi[3])
{
    // Corner i has x from bit 0, y from bit 1, z from bit 2 (0 = lo, 1 = hi);
    // each face is two triangles on the four corners sharing one bit.
    static const unsigned faces[6][4] = {
        {0, 2, 6, 4},
        {1, 3, 7, 5},
        {0, 1, 5, 4},
        {2, 3, 7, 6},
        {0, 1, 3, 2},
        {4, 5, 7, 6},
    };
    struct meshgen_mesh m = {0};
    if (!(lo[0] < hi[0] && lo[1] < hi[1] && lo[2] < hi[2]) || !meshgen_alloc(&m, 8, 12, false)) {
        return m;
    }
    for (int i = 0; i < 8; i++) {
        set3(
            m.positions + 3 * i,
            i & 1 ? hi[0] : lo[0],
            i & 2 ? hi[1] : lo[1],
            i & 4 ? hi[2] : lo[2]);
    }
    for (int f = 0; f < 6; f++) {
        const unsigned *q = faces[f];
        set_triangle(m.indices + 6 * f, q[0], q[1], q[2]);
        set_triangle(m.indices + 6 * f + 3, q[0], q[2], q[3]);
    }
    double middle[3] = {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
    orient_outward(&m, middle);
    return m;
}

/* --- terrain -------------------------------------------------------------- */

struct wave {
    double kx, kz, phase, weight;
};

static double
terrain_height(const struct wave *waves, double x, double z)
{
    double h = 0;
    for (int i = 0; i < TERRAIN_WAVES; i++) {
        h += waves[i].weight * sin(waves[i].kx * x + waves[i].kz * z + waves[i].phase);
    }
    return h;
}

/* Waves of 1 to 4 periods across the terrain, weights summing to 1. */
static void
make_waves(struct wave *waves, double size, uint64_t seed)
{
    struct rng r = rng_make(seed, 1);
    double total = 0;
    for (int i = 0; i < TERRAIN_WAVES; i++) {
        double angle = 2 * MESHGEN_PI * uniform(&r);
        double k = 2 * MESHGEN_PI * (1 + 3 * uniform(&r)) / size;
        waves[i] = (struct wave){
            k * cos(angle),
            k * sin(angle),
            2 * MESHGEN_PI * uniform(&r),
            0.2 + uniform(&r)};
        total += waves[i].weight;
    }
    for (int i = 0; i < TERRAIN_WAVES; i++) {
        waves[i].weight /= total;
    }
}

struct meshgen_mesh
meshgen_terrain(int nx, int nz, double size, double amplitude, uint64_t seed)
{
    struct meshgen_mesh m = {0};
    if (nx < 1 || nz < 1 || (double)nx * nz > 1e9 || !(size > 0)) {
        return m;
    }
    size_t row = (size_t)nx + 1;
    if (!meshgen_alloc(&m, row * ((size_t)nz + 1), 2 * (size_t)nx * (size_t)nz, false)) {
        return m;
    }
    struct wave waves[TERRAIN_WAVES];
    make_waves(waves, size, seed);
    for (int j = 0; j <= nz; j++) {
        for (int i = 0; i <= nx; i++) {
            double x = size * ((double)i / nx - 0.5);
            double z = size * ((double)j / nz - 0.5);
            set3(
                m.positions + 3 * ((size_t)j * row + (size_t)i),
                x,
                amplitude * terrain_height(waves, x, z),
                z);
        }
    }
    unsigned *t = m.indices;
    for (size_t j = 0; j < (size_t)nz; j++) {
        for (size_t i = 0; i < (size_t)nx; i++) {
            size_t v00 = j * row + i;
            set_triangle(t, v00, v00 + row, v00 + row + 1);
            set_triangle(t + 3, v00, v00 + row + 1, v00 + 1);
            t += 6;
        }
    }
    if (!meshgen_compute_normals(&m)) {
        meshgen_free(&m);
    }
    return m;
}

/* --- random triangle soup ------------------------------------------------- */

struct soup {
    struct rng rng;
    double step; /* grid spacing: every coordinate is a multiple */
    double half_steps; /* half the cube's side, in steps */
    double edge_steps; /* largest offset of the second and third corners */
};

/* A multiple of the step in [-steps, steps]. */
static double
soup_coord(struct soup *s, double steps)
{
    return s->step * floor((2 * uniform(&s->rng) - 1) * steps + 0.5);
}

static void
soup_point(struct soup *s, const double *near, double *out)
{
    for (int k = 0; k < 3; k++) {
        out[k] = near ? near[k] + soup_coord(s, s->edge_steps) : soup_coord(s, s->half_steps);
    }
}

static void
soup_degenerate(struct soup *s, double *p, unsigned *tri)
{
    enum meshgen_degenerate kind =
        (enum meshgen_degenerate)(rng_next_u32(&s->rng) % MESHGEN_DEGENERATE_KINDS);
    switch (kind) {
    case MESHGEN_DEGENERATE_COLLINEAR:
        // p0 in the middle of p1 and p2 = p0 - (p1 - p0): exact on the grid.
        for (int k = 0; k < 3; k++) {
            p[6 + k] = 2 * p[k] - p[3 + k];
        }
        break;
    case MESHGEN_DEGENERATE_COINCIDENT:
        memcpy(p + 3, p, 3 * sizeof(double));
        break;
    case MESHGEN_DEGENERATE_POINT:
        memcpy(p + 3, p, 3 * sizeof(double));
        memcpy(p + 6, p, 3 * sizeof(double));
        break;
    default:
        tri[1] = tri[0];
        break;
    }
}

struct meshgen_mesh
meshgen_random_triangles(
    size_t n,
    uint64_t seed,
    double box_size,
    double max_edge,
    double degenerate_fraction)
{
    struct meshgen_mesh m = {0};
    if (n == 0 || n > SIZE_MAX / 9 || !(box_size > 0) || !meshgen_alloc(&m, 3 * n, n, false)) {
        return m;
    }
    double cube = 1;
    while (cube < box_size) {
        cube *= 2;
    }
    struct soup s = {rng_make(seed, 2), cube / SOUP_GRID_STEPS, 0, 0};
    s.half_steps = box_size / 2 / s.step;
    s.edge_steps = max_edge > 0 ? max_edge / s.step : 0;
    for (size_t t = 0; t < n; t++) {
        double *p = m.positions + 9 * t;
        unsigned *tri = m.indices + 3 * t;
        set_triangle(tri, 3 * t, 3 * t + 1, 3 * t + 2);
        soup_point(&s, NULL, p);
        soup_point(&s, max_edge > 0 ? p : NULL, p + 3);
        soup_point(&s, max_edge > 0 ? p : NULL, p + 6);
        if (uniform(&s.rng) < degenerate_fraction) {
            soup_degenerate(&s, p, tri);
        }
    }
    return m;
}

/* --- mesh checks ---------------------------------------------------------- */

bool
meshgen_compute_normals(struct meshgen_mesh *m)
{
    if (!m->normals) {
        m->normals = malloc((3 * m->n_vertices + 1) * sizeof(double));
        if (!m->normals) {
            return false;
        }
    }
    memset(m->normals, 0, 3 * m->n_vertices * sizeof(double));
    for (size_t t = 0; t < m->n_triangles; t++) {
        const unsigned *c = m->indices + 3 * t;
        const double *p0 = m->positions + 3 * c[0];
        const double *p1 = m->positions + 3 * c[1];
        const double *p2 = m->positions + 3 * c[2];
        double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        // The unnormalised cross product weights each face by its area.
        double n[3] = {
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0]};
        for (int i = 0; i < 3; i++) {
            for (int k = 0; k < 3; k++) {
                m->normals[3 * c[i] + k] += n[k];
            }
        }
    }
    for (size_t v = 0; v < m->n_vertices; v++) {
        double *n = m->normals + 3 * v;
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double inv = len > 0 ? 1 / len : 0;
        set3(n, n[0] * inv, n[1] * inv, n[2] * inv);
    }
    return true;
}

static int
compare_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a;
    uint64_t y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

bool
meshgen_is_closed(const struct meshgen_mesh *m)
{
    size_t n = 3 * m->n_triangles;
    uint64_t *edges = malloc((n + 1) * sizeof(uint64_t));
    if (!edges || n == 0) {
        free(edges);
        return false;
    }
    for (size_t t = 0; t < m->n_triangles; t++) {
        for (int k = 0; k < 3; k++) {
            uint64_t from = m->indices[3 * t + (size_t)k];
            uint64_t to = m->indices[3 * t + (size_t)(k + 1) % 3];
            edges[3 * t + (size_t)k] = from << 32 | to;
        }
    }
    qsort(edges, n, sizeof(uint64_t), compare_u64);
    // Each directed edge once, and its reverse present: every edge is then
    // shared by exactly two triangles traversing it in opposite directions.
    bool closed = true;
    for (size_t i = 0; i < n && closed; i++) {
        uint64_t reverse = edges[i] << 32 | edges[i] >> 32;
        bool repeated = (i + 1 < n && edges[i + 1] == edges[i]) || edges[i] == reverse;
        closed = !repeated && bsearch(&reverse, edges, n, sizeof(uint64_t), compare_u64) != NULL;
    }
    free(edges);
    return closed;
}

/* --- GLB writer ----------------------------------------------------------- */

/* A growing text buffer; `failed` sticks once memory runs out. */
struct text {
    char *buf;
    size_t len, cap;
    bool failed;
};

#ifdef __GNUC__
#define MESHGEN_PRINTF(fmt_index, first_arg) __attribute__((format(printf, fmt_index, first_arg)))
#else
#define MESHGEN_PRINTF(fmt_index, first_arg)
#endif

static void text_printf(struct text *t, const char *fmt, ...) MESHGEN_PRINTF(2, 3);

static void
text_printf(struct text *t, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = t->failed ? -1 : vsnprintf(t->buf + t->len, t->cap - t->len, fmt, ap);
    va_end(ap);
    if (n >= 0 && (size_t)n >= t->cap - t->len) {
        size_t cap = 2 * t->cap + (size_t)n;
        char *grown = realloc(t->buf, cap);
        if (grown) {
            t->buf = grown;
            t->cap = cap;
            va_start(ap, fmt);
            vsnprintf(t->buf + t->len, t->cap - t->len, fmt, ap);
            va_end(ap);
        }
        n = grown ? n : -1;
    }
    t->failed = t->failed || n < 0;
    t->len += t->failed ? 0 : (size_t)n;
}

/* Bytes of one section of the BIN chunk. */
struct section {
    size_t offset, length;
};

/* What goes in the file: the vertices as written (expanded for a
 * non-indexed mesh) and the layout of the BIN chunk. */
struct glb_plan {
    const struct meshgen_mesh *mesh;
    const struct meshgen_glb_options *opts;
    size_t n_vertices;
    bool normals;
    size_t index_bytes; /* 0 when non-indexed */
    struct section pos, nrm, idx;
    size_t bin_length; /* padded to 4 */
};

/* The mesh vertex written as vertex v of the file. */
static size_t
source_vertex(const struct glb_plan *plan, size_t v)
{
    return plan->index_bytes ? v : plan->mesh->indices[v];
}

static void
put_u32(unsigned char *p, uint32_t v)
{
    for (int i = 0; i < 4; i++) {
        p[i] = (unsigned char)(v >> (8 * i));
    }
}

static void
put_vec3(unsigned char *dst, const double *src)
{
    for (int k = 0; k < 3; k++) {
        float f = (float)src[k];
        uint32_t bits;
        memcpy(&bits, &f, sizeof bits);
        put_u32(dst + 4 * k, bits);
    }
}

static void
fill_bin(const struct glb_plan *plan, unsigned char *bin)
{
    const struct meshgen_mesh *m = plan->mesh;
    memset(bin, 0, plan->bin_length);
    for (size_t v = 0; v < plan->n_vertices; v++) {
        size_t src = source_vertex(plan, v);
        put_vec3(bin + plan->pos.offset + 12 * v, m->positions + 3 * src);
        if (plan->normals) {
            put_vec3(bin + plan->nrm.offset + 12 * v, m->normals + 3 * src);
        }
    }
    for (size_t i = 0; plan->index_bytes && i < 3 * m->n_triangles; i++) {
        unsigned char *dst = bin + plan->idx.offset + plan->index_bytes * i;
        if (plan->index_bytes == 4) {
            put_u32(dst, m->indices[i]);
        } else {
            dst[0] = (unsigned char)m->indices[i];
            dst[1] = (unsigned char)(m->indices[i] >> 8);
        }
    }
}

static bool
make_plan(
    const struct meshgen_mesh *m,
    const struct meshgen_glb_options *opts,
    struct glb_plan *plan)
{
    *plan = (struct glb_plan){.mesh = m, .opts = opts};
    bool indexed = opts->index_type != MESHGEN_INDEX_NONE;
    plan->n_vertices = indexed ? m->n_vertices : 3 * m->n_triangles;
    plan->normals = m->normals && !opts->omit_normals;
    plan->index_bytes = !indexed ? 0 : opts->index_type == MESHGEN_INDEX_UINT16 ? 2 : 4;
    if (opts->index_type == MESHGEN_INDEX_UINT16 && m->n_vertices >= 0xffff) {
        return false;
    }
    // Keep everything well inside the 32-bit lengths of the format.
    if (plan->n_vertices > UINT32_MAX / 32 || m->n_triangles > UINT32_MAX / 16) {
        return false;
    }
    plan->pos = (struct section){0, 12 * plan->n_vertices};
    plan->nrm = (struct section){plan->pos.length, plan->normals ? 12 * plan->n_vertices : 0};
    plan->idx = (struct section){
        plan->nrm.offset + plan->nrm.length,
        3 * m->n_triangles * plan->index_bytes};
    plan->bin_length = (plan->idx.offset + plan->idx.length + 3) & ~(size_t)3;
    return true;
}

/* min and max of the float32 positions as written; false if not finite. */
static bool
position_bounds(const struct glb_plan *plan, float lo[3], float hi[3])
{
    for (size_t v = 0; v < plan->n_vertices; v++) {
        const double *p = plan->mesh->positions + 3 * source_vertex(plan, v);
        for (int k = 0; k < 3; k++) {
            float f = (float)p[k];
            if (!isfinite(f)) {
                return false;
            }
            lo[k] = v == 0 || f < lo[k] ? f : lo[k];
            hi[k] = v == 0 || f > hi[k] ? f : hi[k];
        }
    }
    return plan->n_vertices > 0;
}

static void
json_numbers(struct text *t, const char *name, const double *v, int n)
{
    text_printf(t, ",\"%s\":[", name);
    for (int i = 0; i < n; i++) {
        text_printf(t, "%s%.17g", i ? "," : "", v[i]);
    }
    text_printf(t, "]");
}

static void
json_node(struct text *t, const struct meshgen_glb_options *o)
{
    text_printf(t, "\"nodes\":[{\"mesh\":0");
    if (o->has_matrix) {
        json_numbers(t, "matrix", o->matrix, 16);
    } else {
        if (o->has_translation) {
            json_numbers(t, "translation", o->translation, 3);
        }
        if (o->has_rotation) {
            json_numbers(t, "rotation", o->rotation, 4);
        }
        if (o->has_scale) {
            json_numbers(t, "scale", o->scale, 3);
        }
    }
    text_printf(t, "}%s%s],", o->nodes ? "," : "", o->nodes ? o->nodes : "");
}

static void
json_view(struct text *t, struct section s, int target, bool last)
{
    text_printf(
        t,
        "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":%d}%s",
        s.offset,
        s.length,
        target,
        last ? "" : ",");
}

/* Accessor `view` (its buffer view has the same number) of count elements. */
static void
json_accessor(struct text *t, int view, int component_type, size_t count, const char *type)
{
    text_printf(
        t,
        "%s{\"bufferView\":%d,\"componentType\":%d,\"count\":%zu,\"type\":\"%s\"",
        view ? "," : "",
        view,
        component_type,
        count,
        type);
}

/* Accessors and buffer views in the order POSITION, NORMAL, indices. */
static void
json_accessors(struct text *t, const struct glb_plan *plan)
{
    float lo[3];
    float hi[3];
    text_printf(t, "\"accessors\":[");
    json_accessor(t, 0, GLTF_FLOAT, plan->n_vertices, "VEC3");
    if (position_bounds(plan, lo, hi)) {
        text_printf(t, ",\"min\":[%.9g,%.9g,%.9g]", lo[0], lo[1], lo[2]);
        text_printf(t, ",\"max\":[%.9g,%.9g,%.9g]", hi[0], hi[1], hi[2]);
    }
    text_printf(t, "}");
    int view = 1;
    if (plan->normals) {
        json_accessor(t, view++, GLTF_FLOAT, plan->n_vertices, "VEC3");
        text_printf(t, "}");
    }
    if (plan->index_bytes) {
        int type = plan->index_bytes == 2 ? GLTF_UNSIGNED_SHORT : GLTF_UNSIGNED_INT;
        json_accessor(t, view, type, 3 * plan->mesh->n_triangles, "SCALAR");
        text_printf(t, "}");
    }
    text_printf(t, "],\"bufferViews\":[");
    json_view(t, plan->pos, GLTF_ARRAY_BUFFER, !plan->normals && !plan->index_bytes);
    if (plan->normals) {
        json_view(t, plan->nrm, GLTF_ARRAY_BUFFER, !plan->index_bytes);
    }
    if (plan->index_bytes) {
        json_view(t, plan->idx, GLTF_ELEMENT_ARRAY_BUFFER, true);
    }
    text_printf(t, "],");
}

/* s as the contents of a JSON string. */
static void
json_string_contents(struct text *t, const char *s)
{
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\') {
            text_printf(t, "\\%c", c);
        } else if (c < 0x20) {
            text_printf(t, "\\u%04x", c);
        } else {
            text_printf(t, "%c", c);
        }
    }
}

static void
json_document(struct text *t, const struct glb_plan *plan)
{
    text_printf(t, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"stagelight meshgen\"");
    if (plan->opts->copyright) {
        text_printf(t, ",\"copyright\":\"");
        json_string_contents(t, plan->opts->copyright);
        text_printf(t, "\"");
    }
    text_printf(t, "},");
    const struct meshgen_glb_options *o = plan->opts;
    text_printf(t, "\"scene\":0,\"scenes\":[{\"nodes\":[0");
    for (int i = 1; o->nodes && i <= o->n_nodes; i++) {
        text_printf(t, ",%d", i);
    }
    text_printf(t, "]}],");
    json_node(t, o);
    if (o->material) {
        text_printf(t, "\"materials\":[%s],", o->material);
    }
    if (o->members) {
        text_printf(t, "%s,", o->members);
    }
    text_printf(t, "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0");
    if (plan->normals) {
        text_printf(t, ",\"NORMAL\":1");
    }
    text_printf(t, "}");
    if (plan->index_bytes) {
        text_printf(t, ",\"indices\":%d", plan->normals ? 2 : 1);
    }
    text_printf(t, ",\"mode\":4%s}]}", o->material ? ",\"material\":0" : "");
    if (o->meshes) {
        text_printf(t, ",%s", o->meshes);
    }
    text_printf(t, "],");
    json_accessors(t, plan);
    text_printf(t, "\"buffers\":[{");
    if (o->bin_uri) {
        text_printf(t, "\"uri\":\"%s\",", o->bin_uri);
    }
    text_printf(t, "\"byteLength\":%zu}]}", plan->bin_length);
    // Pad the JSON chunk with spaces to a multiple of 4 bytes.
    while (!t->failed && t->len % 4 != 0) {
        text_printf(t, " ");
    }
}

static bool
write_glb_file(
    const char *path,
    const struct text *json,
    const unsigned char *bin,
    size_t bin_length)
{
    size_t total = GLB_HEADER_BYTES + 2 * GLB_CHUNK_HEADER_BYTES + json->len + bin_length;
    if (total > UINT32_MAX) {
        return false;
    }
    unsigned char header[GLB_HEADER_BYTES + GLB_CHUNK_HEADER_BYTES];
    put_u32(header, GLB_MAGIC);
    put_u32(header + 4, GLB_VERSION);
    put_u32(header + 8, (uint32_t)total);
    put_u32(header + 12, (uint32_t)json->len);
    put_u32(header + 16, GLB_CHUNK_JSON);
    unsigned char bin_header[GLB_CHUNK_HEADER_BYTES];
    put_u32(bin_header, (uint32_t)bin_length);
    put_u32(bin_header + 4, GLB_CHUNK_BIN);
    FILE *f = fopen(path, "wb");
    if (!f) {
        return false;
    }
    bool ok = fwrite(header, 1, sizeof header, f) == sizeof header
              && fwrite(json->buf, 1, json->len, f) == json->len
              && fwrite(bin_header, 1, sizeof bin_header, f) == sizeof bin_header
              && fwrite(bin, 1, bin_length, f) == bin_length;
    return fclose(f) == 0 && ok;
}

/* A .gltf at path and its buffer at uri, relative to path's directory. */
static bool
write_gltf_files(
    const char *path,
    const char *uri,
    const struct text *json,
    const unsigned char *bin,
    size_t bin_length)
{
    const char *slash = strrchr(path, '/');
    size_t dir = slash ? (size_t)(slash - path + 1) : 0;
    char *bin_path = malloc(dir + strlen(uri) + 1);
    bool ok = bin_path != NULL;
    if (ok) {
        memcpy(bin_path, path, dir);
        memcpy(bin_path + dir, uri, strlen(uri) + 1);
        FILE *f = fopen(bin_path, "wb");
        ok = f && fwrite(bin, 1, bin_length, f) == bin_length;
        ok = f && fclose(f) == 0 && ok;
        f = ok ? fopen(path, "wb") : NULL;
        ok = f && fwrite(json->buf, 1, json->len, f) == json->len;
        ok = f && fclose(f) == 0 && ok;
    }
    free(bin_path);
    return ok;
}

bool
meshgen_write_glb(
    const struct meshgen_mesh *m,
    const char *path,
    const struct meshgen_glb_options *opts)
{
    static const struct meshgen_glb_options defaults = {0};
    struct glb_plan plan;
    if (!make_plan(m, opts ? opts : &defaults, &plan)) {
        return false;
    }
    struct text json = {malloc(4096), 0, 4096, false};
    unsigned char *bin = malloc(plan.bin_length + 1);
    json.failed = !json.buf;
    bool ok = false;
    if (bin && !json.failed) {
        json_document(&json, &plan);
        fill_bin(&plan, bin);
        const char *uri = plan.opts->bin_uri;
        ok = !json.failed
             && (uri ? write_gltf_files(path, uri, &json, bin, plan.bin_length)
                     : write_glb_file(path, &json, bin, plan.bin_length));
    }
    free(json.buf);
    free(bin);
    return ok;
}
