/*
 * gltf_copy.cc - the checked parts copied out into one world-space triangle
 * list: positions by the node's matrix, normals by its inverse transpose,
 * indices offset (and their winding flipped under a mirroring transform).
 */
#include "gltf_steps.h"

#include <cmath>
#include <cstdlib>
#include <cstring>

/* --- copying the triangles out -------------------------------------------- */

static double
read_f32(const unsigned char *p)
{
    uint32_t bits = read_u32le(p);
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

static size_t
read_index(const view &v, size_t i)
{
    const unsigned char *p = v.data + i * v.stride;
    switch (v.component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return (size_t)p[0] | (size_t)p[1] << 8;
    default:
        return read_u32le(p);
    }
}

// The transform of normals: the inverse transpose of the upper 3x3, as its
// cofactor matrix times the sign of the determinant (the length does not
// matter: normals are renormalised).  Returns the determinant.
static double
normal_matrix(const mat4 &world, double out[9])
{
    const double *m = world.m;
    // Column j of the upper 3x3 is (m[4j], m[4j+1], m[4j+2]); the cofactor
    // matrix's columns are cross products of the other two columns.
    const double *c0 = m;
    const double *c1 = m + 4;
    const double *c2 = m + 8;
    const double *cols[3][2] = {{c1, c2}, {c2, c0}, {c0, c1}};
    for (int j = 0; j < 3; j++) {
        const double *a = cols[j][0];
        const double *b = cols[j][1];
        out[j * 3 + 0] = a[1] * b[2] - a[2] * b[1];
        out[j * 3 + 1] = a[2] * b[0] - a[0] * b[2];
        out[j * 3 + 2] = a[0] * b[1] - a[1] * b[0];
    }
    double det = c0[0] * out[0] + c0[1] * out[1] + c0[2] * out[2];
    if (det < 0) {
        for (int i = 0; i < 9; i++) {
            out[i] = -out[i];
        }
    }
    return det;
}

static bool
copy_positions(const part &p, const mat4 &world, double *out, std::string *why)
{
    const double *m = world.m;
    for (size_t i = 0; i < p.positions.count; i++) {
        const unsigned char *src = p.positions.data + i * p.positions.stride;
        double x = read_f32(src);
        double y = read_f32(src + 4);
        double z = read_f32(src + 8);
        double *dst = out + 3 * i;
        for (int r = 0; r < 3; r++) {
            dst[r] = m[r] * x + m[4 + r] * y + m[8 + r] * z + m[12 + r];
        }
        if (!std::isfinite(dst[0]) || !std::isfinite(dst[1]) || !std::isfinite(dst[2])) {
            *why = format(
                "mesh %d primitive %d: vertex %zu has a non-finite position%s",
                p.mesh,
                p.primitive,
                i,
                std::isfinite(x + y + z) ? " after its node transform" : "");
            return false;
        }
    }
    return true;
}

static bool
copy_normals(const part &p, const double nm[9], double *out, std::string *why)
{
    for (size_t i = 0; i < p.normals.count; i++) {
        const unsigned char *src = p.normals.data + i * p.normals.stride;
        double n[3] = {read_f32(src), read_f32(src + 4), read_f32(src + 8)};
        if (!std::isfinite(n[0]) || !std::isfinite(n[1]) || !std::isfinite(n[2])) {
            *why = format(
                "mesh %d primitive %d: vertex %zu has a non-finite normal",
                p.mesh,
                p.primitive,
                i);
            return false;
        }
        double *dst = out + 3 * i;
        for (int r = 0; r < 3; r++) {
            dst[r] = nm[r] * n[0] + nm[3 + r] * n[1] + nm[6 + r] * n[2];
        }
        double len = std::sqrt(dst[0] * dst[0] + dst[1] * dst[1] + dst[2] * dst[2]);
        for (int r = 0; r < 3; r++) {
            dst[r] = len > 0 && std::isfinite(len) ? dst[r] / len : 0;
        }
    }
    return true;
}

// Indices offset by the part's first vertex; a mirroring transform swaps two
// corners so the winding still agrees with the normals.
static bool
copy_indices(const part &p, size_t first_vertex, bool mirrored, unsigned *out, std::string *why)
{
    for (size_t t = 0; t < p.n_triangles; t++) {
        size_t corner[3];
        for (size_t k = 0; k < 3; k++) {
            size_t at = 3 * t + k;
            corner[k] = p.has_indices ? read_index(p.indices, at) : at;
            if (corner[k] >= p.positions.count) {
                *why = format(
                    "mesh %d primitive %d: index %zu (number %zu) is out of range: "
                    "POSITION has %zu vertices",
                    p.mesh,
                    p.primitive,
                    corner[k],
                    at,
                    p.positions.count);
                return false;
            }
        }
        unsigned *dst = out + 3 * t;
        dst[0] = (unsigned)(first_vertex + corner[0]);
        dst[1] = (unsigned)(first_vertex + corner[mirrored ? 2 : 1]);
        dst[2] = (unsigned)(first_vertex + corner[mirrored ? 1 : 2]);
    }
    return true;
}

static bool
allocate_mesh(
    const std::vector<part> &parts,
    uint64_t max_bytes,
    struct gltf_mesh *out,
    std::string *why)
{
    size_t n_vertices = 0;
    size_t n_triangles = 0;
    bool any_normals = false;
    for (const part &p : parts) {
        n_vertices += p.positions.count;
        n_triangles += p.n_triangles;
        any_normals = any_normals || p.has_normals;
    }
    // plan_parts keeps the counts below INT_MAX: no product overflows.
    uint64_t per_vertex = (any_normals ? 6 : 3) * sizeof(double);
    uint64_t bytes = n_vertices * per_vertex + 3 * n_triangles * sizeof(unsigned);
    if (bytes > max_bytes) {
        *why = format(
            "%zu vertices and %zu triangles (a mesh counts once per node that uses it) need "
            "%llu MiB, more than the memory limit of %llu MiB left for them; raise it with "
            "--max-memory",
            n_vertices,
            n_triangles,
            (unsigned long long)((bytes + (1 << 20) - 1) >> 20),
            (unsigned long long)(max_bytes >> 20));
        return false;
    }
    out->n_triangles = n_triangles;
    // The limits keep these products far from overflow; +1 avoids malloc(0).
    out->positions = (double *)malloc((3 * n_vertices + 1) * sizeof(double));
    out->indices = (unsigned *)malloc((3 * out->n_triangles + 1) * sizeof(unsigned));
    out->triangle_material = (int *)malloc((out->n_triangles + 1) * sizeof(int));
    if (any_normals) {
        out->normals = (double *)calloc(3 * n_vertices + 1, sizeof(double));
    }
    out->n_vertices = n_vertices;
    if (!out->positions || !out->indices || !out->triangle_material
        || (any_normals && !out->normals)) {
        throw out_of_memory{format(
            "out of memory: the system refused %llu MiB for %zu vertices and %zu triangles",
            (unsigned long long)((bytes + (1 << 20) - 1) >> 20),
            n_vertices,
            n_triangles)};
    }
    return true;
}

bool
copy_parts(
    const std::vector<job> &jobs,
    const std::vector<part> &parts,
    uint64_t max_bytes,
    struct gltf_mesh *out,
    std::string *why)
{
    if (!allocate_mesh(parts, max_bytes, out, why)) {
        return false;
    }
    size_t first_vertex = 0;
    size_t first_triangle = 0;
    for (const part &p : parts) {
        const mat4 &world = jobs[p.job].world;
        double nm[9];
        double det = normal_matrix(world, nm);
        if (!copy_positions(p, world, out->positions + 3 * first_vertex, why)) {
            return false;
        }
        if (p.has_normals && !copy_normals(p, nm, out->normals + 3 * first_vertex, why)) {
            return false;
        }
        unsigned *dst = out->indices + 3 * first_triangle;
        if (!copy_indices(p, first_vertex, det < 0, dst, why)) {
            return false;
        }
        for (size_t t = 0; t < p.n_triangles; t++) {
            out->triangle_material[first_triangle + t] = p.material;
        }
        first_vertex += p.positions.count;
        first_triangle += p.n_triangles;
    }
    return true;
}
