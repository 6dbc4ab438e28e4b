/*
 * test_gltf.c - glTF loading (gltf.h) and the test mesh generator (meshgen.h).
 *
 * Round trips write meshes with meshgen's own GLB writer and load them back;
 * the models of scenes/models/ are checked against the counts and bounding
 * boxes their credits file (CREDITS.md) and their origin give; hostile files are made by hand here,
 * each refused with a message naming the file.  Run it under AddressSanitizer/UBSan (make
 * SANITIZE=1): "never crashes" is half of what these tests check.  Tests that load files skip in
 * builds without tinygltf, except stub_message, which runs only there.
 */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "gltf.h"
#include "meshgen.h"
#include "rng.h"
#include "testlib.h"

/* float32 storage of coordinates of magnitude <= 10. */
#define FLOAT_TOL 1e-5

/* --- helpers -------------------------------------------------------------- */

/* A .glb of json (padded here) and bin (a multiple of 4 bytes, or NULL). */
static bool
write_glb(const char *path, const char *json, const unsigned char *bin, size_t bin_len)
{
    size_t json_len = (strlen(json) + 3) & ~(size_t)3;
    size_t total = 12 + 8 + json_len + (bin ? 8 + bin_len : 0);
    unsigned char *b = calloc(total, 1);
    if (!b) {
        return false;
    }
    memcpy(b, "glTF", 4);
    test_put_le32(b + 4, 2);
    test_put_le32(b + 8, (uint32_t)total);
    test_put_le32(b + 12, (uint32_t)json_len);
    memcpy(b + 16, "JSON", 4);
    memset(b + 20, ' ', json_len);
    memcpy(b + 20, json, strlen(json));
    if (bin) {
        test_put_le32(b + 20 + json_len, (uint32_t)bin_len);
        memcpy(b + 24 + json_len, "BIN\0", 4);
        memcpy(b + 28 + json_len, bin, bin_len);
    }
    bool ok = test_write_bytes(path, b, total);
    free(b);
    return ok;
}

/* Load path; on failure print the diagnostic. */
static bool
load(const char *path, struct gltf_mesh *m)
{
    struct diag err = {0};
    if (gltf_load(path, m, &err)) {
        return true;
    }
    diag_print(stdout, &err, "error");
    return false;
}

/* Loading path fails, names the file, says something (containing needle
 * unless NULL) and leaves the mesh empty. */
static void
check_refused(const char *path, const char *needle)
{
    struct gltf_mesh m = {0};
    struct diag err = {0};
    bool ok = gltf_load(path, &m, &err);
    CHECK_MSG(!ok, "%s was loaded", path);
    CHECK_MSG(strcmp(err.file, path) == 0, "%s: diag names '%s'", path, err.file);
    CHECK_MSG(err.msg[0] != '\0', "%s: empty message", path);
    if (needle) {
        CHECK_MSG(strstr(err.msg, needle), "%s: '%s' does not mention '%s'", path, err.msg, needle);
    }
    CHECK(m.positions == NULL && m.normals == NULL && m.indices == NULL);
    CHECK(m.n_vertices == 0 && m.n_triangles == 0);
    if (getenv("GLTF_TEST_SHOW")) {
        printf("  %s: %s\n", path, err.msg);
    }
    gltf_free(&m);
}

static void
bbox(const struct gltf_mesh *m, double lo[3], double hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = DBL_MAX;
        hi[k] = -DBL_MAX;
    }
    for (size_t v = 0; v < m->n_vertices; v++) {
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], m->positions[3 * v + k]);
            hi[k] = fmax(hi[k], m->positions[3 * v + k]);
        }
    }
}

static void
cross_edges(const double *positions, const unsigned *tri, double n[3])
{
    const double *p0 = positions + 3 * tri[0];
    const double *p1 = positions + 3 * tri[1];
    const double *p2 = positions + 3 * tri[2];
    double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
    double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

/* Triangles whose geometric normal disagrees with their vertex normals. */
static size_t
misoriented_triangles(
    const double *positions,
    const double *normals,
    const unsigned *indices,
    size_t n)
{
    size_t bad = 0;
    for (size_t t = 0; t < n; t++) {
        double g[3];
        cross_edges(positions, indices + 3 * t, g);
        double agree = 0;
        for (int c = 0; c < 3; c++) {
            const double *vn = normals + 3 * indices[3 * t + c];
            agree += g[0] * vn[0] + g[1] * vn[1] + g[2] * vn[2];
        }
        bad += agree <= 0;
    }
    return bad;
}

/* Six times the signed volume: positive when the triangles face outward. */
static double
signed_volume6(const double *positions, const unsigned *indices, size_t n)
{
    double sum = 0;
    for (size_t t = 0; t < n; t++) {
        double c[3];
        cross_edges(positions, indices + 3 * t, c);
        const double *p0 = positions + 3 * indices[3 * t];
        sum += p0[0] * c[0] + p0[1] * c[1] + p0[2] * c[2];
    }
    return sum;
}

static bool
same_closed(const struct gltf_mesh *g)
{
    struct meshgen_mesh m = {g->n_vertices, g->positions, g->normals, g->n_triangles, g->indices};
    return meshgen_is_closed(&m);
}

/* The loaded mesh equals m (to float32 precision). */
static void
check_same_mesh(const struct meshgen_mesh *m, const struct gltf_mesh *g, bool with_normals)
{
    CHECK(g->n_vertices == m->n_vertices);
    CHECK(g->n_triangles == m->n_triangles);
    CHECK((g->normals != NULL) == with_normals);
    if (g->n_vertices != m->n_vertices || g->n_triangles != m->n_triangles) {
        return;
    }
    size_t bad = 0;
    for (size_t i = 0; i < 3 * m->n_vertices; i++) {
        bad += !(fabs(g->positions[i] - m->positions[i]) <= FLOAT_TOL);
        bad += with_normals && g->normals && !(fabs(g->normals[i] - m->normals[i]) <= FLOAT_TOL);
    }
    for (size_t i = 0; i < 3 * m->n_triangles; i++) {
        bad += g->indices[i] != m->indices[i];
    }
    CHECK_MSG(bad == 0, "%zu values differ", bad);
}

static struct meshgen_mesh
small_sphere(void)
{
    return meshgen_sphere(12, 16, 2.0, (const double[3]){1, 2, 3}, 0, 0);
}

/* Write m with opts to a temp file, load it back. */
static bool
round_trip(
    const struct meshgen_mesh *m,
    const struct meshgen_glb_options *opts,
    const char *name,
    struct gltf_mesh *out)
{
    const char *path = test_tmp_path(name);
    CHECK(meshgen_write_glb(m, path, opts));
    return load(path, out);
}

/* --- hand-made files: one triangle, parts replaceable --------------------- */

/* Positions (0,0,0), (1,0,0), (0,1,0) as float32, then uint16 indices 0 1 2,
 * then 2 bytes of padding. */
#define TRI_BIN_LEN 44

static void
tri_bin(unsigned char bin[TRI_BIN_LEN])
{
    static const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    memset(bin, 0, TRI_BIN_LEN);
    for (int i = 0; i < 9; i++) {
        uint32_t bits;
        memcpy(&bits, &pos[i], 4);
        test_put_le32(bin + 4 * i, bits);
    }
    for (int i = 0; i < 3; i++) {
        bin[36 + 2 * i] = (unsigned char)i;
    }
}

/* Parts of the document; NULL takes the default. */
struct tri_gltf {
    const char *top; /* members before the rest, each with a trailing comma */
    const char *scene; /* "scene" and "scenes" members, with a trailing comma */
    const char *nodes; /* contents of "nodes" */
    const char *primitive; /* contents of the primitive object */
    const char *accessors; /* contents of "accessors" */
    const char *views; /* contents of "bufferViews" */
    const char *buffer; /* contents of the buffer object */
};

#define TRI_SCENE "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
#define TRI_NODES "{\"mesh\":0}"
#define TRI_PRIMITIVE "\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":4"
#define TRI_POSITIONS "{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}"
#define TRI_INDICES "{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}"
#define TRI_ACCESSORS TRI_POSITIONS "," TRI_INDICES
#define TRI_VIEW_POS "{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36}"
#define TRI_VIEW_IDX "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":6}"
#define TRI_VIEWS TRI_VIEW_POS "," TRI_VIEW_IDX
#define TRI_BUFFER "\"byteLength\":44"

static const char *
or_default(const char *part, const char *fallback)
{
    return part ? part : fallback;
}

#define TRI_FORMAT \
    "{\"asset\":{\"version\":\"2.0\"},%s%s\"nodes\":[%s],\"meshes\":[{\"primitives\":[{%s}]}]," \
    "\"accessors\":[%s],\"bufferViews\":[%s],\"buffers\":[{%s}]}"

/* The document, in a buffer kept until the next call ("" if memory runs
 * out, which the loader then refuses). */
static const char *
tri_json(const struct tri_gltf *g)
{
    static char *json;
    const char *parts[7] = {
        or_default(g->top, ""),
        or_default(g->scene, TRI_SCENE),
        or_default(g->nodes, TRI_NODES),
        or_default(g->primitive, TRI_PRIMITIVE),
        or_default(g->accessors, TRI_ACCESSORS),
        or_default(g->views, TRI_VIEWS),
        or_default(g->buffer, TRI_BUFFER),
    };
    size_t len = sizeof TRI_FORMAT;
    for (int i = 0; i < 7; i++) {
        len += strlen(parts[i]);
    }
    free(json);
    json = malloc(len);
    if (!json) {
        return "";
    }
    snprintf(
        json,
        len,
        TRI_FORMAT,
        parts[0],
        parts[1],
        parts[2],
        parts[3],
        parts[4],
        parts[5],
        parts[6]);
    return json;
}

/* The triangle as tmpdir/name (a .glb with the standard BIN). */
static const char *
tri_glb(const char *name, const struct tri_gltf *g)
{
    unsigned char bin[TRI_BIN_LEN];
    tri_bin(bin);
    const char *path = test_tmp_path(name);
    CHECK(write_glb(path, tri_json(g), bin, sizeof bin));
    return path;
}

/* --- stub and freeing ----------------------------------------------------- */

TEST(stub_message)
{
    if (gltf_available()) {
        SKIP("built with tinygltf: the stub is not compiled");
    }
    struct gltf_mesh m = {0};
    struct diag err = {0};
    CHECK(!gltf_load("scenes/model.glb", &m, &err));
    CHECK(strcmp(err.file, "scenes/model.glb") == 0);
    CHECK(err.line == 0);
    CHECK(
        strcmp(err.msg, "this build has no glTF support: install libtinygltf-dev and rebuild")
        == 0);
    CHECK(m.positions == NULL && m.n_triangles == 0);
}

TEST(free_zero_mesh)
{
    struct gltf_mesh m = {0};
    gltf_free(&m);
    gltf_free(&m);
    CHECK(m.positions == NULL && m.normals == NULL && m.indices == NULL);
}

/* --- meshgen -------------------------------------------------------------- */

TEST(meshgen_sphere_closed)
{
    const double c[3] = {1, 2, 3};
    struct meshgen_mesh m = meshgen_sphere(8, 12, 2.0, c, 0, 0);
    CHECK(m.n_vertices == 2 + 7 * 12);
    CHECK(m.n_triangles == 2 * 12 * 7);
    CHECK(meshgen_is_closed(&m));
    CHECK(misoriented_triangles(m.positions, m.normals, m.indices, m.n_triangles) == 0);
    CHECK(signed_volume6(m.positions, m.indices, m.n_triangles) > 0);
    size_t off = 0;
    for (size_t v = 0; v < m.n_vertices; v++) {
        const double *p = m.positions + 3 * v;
        double r =
            sqrt((p[0] - 1) * (p[0] - 1) + (p[1] - 2) * (p[1] - 2) + (p[2] - 3) * (p[2] - 3));
        off += fabs(r - 2) > 1e-12;
    }
    CHECK(off == 0);
    meshgen_free(&m);
    m = meshgen_sphere(8, 12, 2.0, c, 0.2, 7);
    CHECK(meshgen_is_closed(&m));
    CHECK(misoriented_triangles(m.positions, m.normals, m.indices, m.n_triangles) == 0);
    meshgen_free(&m);
    m = meshgen_sphere(1, 12, 1, c, 0, 0);
    CHECK(m.n_triangles == 0 && m.positions == NULL);
    meshgen_free(&m);
}

TEST(meshgen_sphere_1m)
{
    const double c[3] = {0, 0, 0};
    struct meshgen_mesh m = meshgen_sphere(501, 1000, 1, c, 0.01, 3);
    CHECK(m.n_triangles == 1000000);
    CHECK(meshgen_is_closed(&m));
    meshgen_free(&m);
}

TEST(meshgen_other_closed_meshes)
{
    const double c[3] = {0, 1, 0};
    struct meshgen_mesh m = meshgen_icosphere(3, 1.5, c);
    CHECK(m.n_triangles == 20 * 64);
    CHECK(m.n_vertices == 10 * 64 + 2);
    CHECK(meshgen_is_closed(&m));
    CHECK(misoriented_triangles(m.positions, m.normals, m.indices, m.n_triangles) == 0);
    meshgen_free(&m);
    struct meshgen_mesh box = meshgen_box((const double[3]){-1, 0, 2}, (const double[3]){1, 3, 5});
    CHECK(box.n_vertices == 8 && box.n_triangles == 12);
    CHECK(meshgen_is_closed(&box));
    CHECK_NEAR(signed_volume6(box.positions, box.indices, box.n_triangles), 6 * 2 * 3 * 3, 1e-9);
    meshgen_free(&box);
}

/* Every vertex normal of m has unit length (to float32 precision). */
static size_t
non_unit_normals(const double *normals, size_t n_vertices)
{
    size_t bad = 0;
    for (size_t v = 0; normals && v < n_vertices; v++) {
        const double *n = normals + 3 * v;
        bad += fabs(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1) > 1e-5;
    }
    return bad;
}

TEST(meshgen_subdivide_closed)
{
    // A box twice subdivided: 12 * 16 triangles; Euler V - E + F = 2 with
    // E = 3F/2 gives the vertices; the same closed surface, same volume.
    struct meshgen_mesh box = meshgen_box((const double[3]){-1, 0, 2}, (const double[3]){1, 3, 5});
    struct meshgen_mesh once = {0};
    struct meshgen_mesh twice = {0};
    CHECK(meshgen_subdivide(&box, &once) && meshgen_subdivide(&once, &twice));
    CHECK(twice.n_triangles == 192 && twice.n_vertices == 2 + 192 / 2);
    CHECK(twice.normals == NULL);
    CHECK(meshgen_is_closed(&twice));
    CHECK_NEAR(signed_volume6(twice.positions, twice.indices, twice.n_triangles), 6 * 18, 1e-9);
    // Corners keep their index and position.
    CHECK(memcmp(twice.positions, box.positions, 3 * box.n_vertices * sizeof(double)) == 0);
    meshgen_free(&box);
    meshgen_free(&once);
    meshgen_free(&twice);
}

TEST(meshgen_subdivide_open_with_normals)
{
    // A 3 x 2 terrain: 4 * 3 = 12 vertices; 3 * 3 edges along x, 4 * 2
    // along z and 6 diagonals, 23 edges, each of which gets a midpoint.
    struct meshgen_mesh t = meshgen_terrain(3, 2, 4, 0.25, 1);
    struct meshgen_mesh f = {0};
    CHECK(meshgen_subdivide(&t, &f));
    CHECK(f.n_triangles == 48 && f.n_vertices == 12 + 23);
    CHECK(f.normals != NULL && non_unit_normals(f.normals, f.n_vertices) == 0);
    size_t bad = 0;
    for (size_t tri = 0; f.normals && tri < t.n_triangles; tri++) {
        // Sub-triangle 4t + 1 is (ab, b, bc): ab the midpoint of a and b.
        unsigned a = t.indices[3 * tri];
        unsigned b = t.indices[3 * tri + 1];
        unsigned ab = f.indices[12 * tri + 3];
        double n[3];
        double len = 0;
        for (int k = 0; k < 3; k++) {
            bad += f.positions[3 * ab + k] != (t.positions[3 * a + k] + t.positions[3 * b + k]) / 2;
            n[k] = t.normals[3 * a + k] + t.normals[3 * b + k];
            len += n[k] * n[k];
        }
        for (int k = 0; k < 3; k++) {
            bad += fabs(f.normals[3 * ab + k] - n[k] / sqrt(len)) > 1e-12;
        }
        bad += f.indices[12 * tri + 4] != b;
    }
    CHECK_MSG(bad == 0, "%zu midpoints wrong", bad);
    meshgen_free(&t);
    meshgen_free(&f);
    // Opposite normals at an edge's ends: the lower-indexed end's normal.
    struct meshgen_mesh one = {0};
    CHECK(meshgen_alloc(&one, 3, 1, true));
    memcpy(one.positions, (const double[9]){0, 0, 0, 1, 0, 0, 0, 1, 0}, 9 * sizeof(double));
    memcpy(one.normals, (const double[9]){0, 0, 1, 0, 0, -1, 0, 0, 1}, 9 * sizeof(double));
    memcpy(one.indices, (const unsigned[3]){1, 0, 2}, 3 * sizeof(unsigned));
    CHECK(meshgen_subdivide(&one, &f));
    CHECK(f.n_vertices == 6 && f.n_triangles == 4);
    CHECK(f.n_vertices == 6 && f.normals[3 * 3 + 2] == 1);  // midpoint of 1 and 0
    meshgen_free(&one);
    meshgen_free(&f);
}

TEST(meshgen_terrain_faces_up)
{
    struct meshgen_mesh m = meshgen_terrain(20, 10, 4, 0.25, 1);
    CHECK(m.n_vertices == 21 * 11 && m.n_triangles == 400);
    CHECK(!meshgen_is_closed(&m));
    size_t down = 0;
    for (size_t t = 0; t < m.n_triangles; t++) {
        double n[3];
        cross_edges(m.positions, m.indices + 3 * t, n);
        down += n[1] <= 0;
    }
    CHECK(down == 0);
    for (size_t v = 0; v < m.n_vertices; v++) {
        CHECK(fabs(m.positions[3 * v + 1]) <= 0.25);
    }
    meshgen_free(&m);
}

TEST(meshgen_random_degenerate)
{
    struct meshgen_mesh m = meshgen_random_triangles(2000, 5, 10, 1, 0.25);
    CHECK(m.n_triangles == 2000 && m.n_vertices == 6000);
    size_t degenerate = 0;
    for (size_t t = 0; t < m.n_triangles; t++) {
        double n[3];
        cross_edges(m.positions, m.indices + 3 * t, n);
        degenerate += n[0] == 0 && n[1] == 0 && n[2] == 0;
    }
    // About a quarter, binomial standard deviation about 19.
    CHECK_MSG(degenerate > 400 && degenerate < 600, "%zu degenerate", degenerate);
    struct meshgen_mesh again = meshgen_random_triangles(2000, 5, 10, 1, 0.25);
    CHECK(memcmp(m.positions, again.positions, 9 * 2000 * sizeof(double)) == 0);
    meshgen_free(&m);
    meshgen_free(&again);
}

/* --- round trips ---------------------------------------------------------- */

TEST(round_trip_uint32)
{
    REQUIRE_GLTF();
    struct meshgen_mesh m = small_sphere();
    struct gltf_mesh g = {0};
    CHECK(round_trip(&m, NULL, "rt32.glb", &g));
    check_same_mesh(&m, &g, true);
    CHECK(same_closed(&g));
    gltf_free(&g);
    meshgen_free(&m);
}

TEST(round_trip_uint16_without_normals)
{
    REQUIRE_GLTF();
    struct meshgen_mesh m = small_sphere();
    struct meshgen_glb_options opts = {.index_type = MESHGEN_INDEX_UINT16, .omit_normals = true};
    struct gltf_mesh g = {0};
    CHECK(round_trip(&m, &opts, "rt16.glb", &g));
    check_same_mesh(&m, &g, false);
    gltf_free(&g);
    meshgen_free(&m);
}

TEST(non_indexed)
{
    REQUIRE_GLTF();
    struct meshgen_mesh m = small_sphere();
    struct meshgen_glb_options opts = {.index_type = MESHGEN_INDEX_NONE};
    struct gltf_mesh g = {0};
    CHECK(round_trip(&m, &opts, "flat.glb", &g));
    CHECK(g.n_triangles == m.n_triangles);
    CHECK(g.n_vertices == 3 * m.n_triangles);
    size_t bad = 0;
    for (size_t i = 0; i < g.n_vertices && g.n_vertices == 3 * m.n_triangles; i++) {
        bad += g.indices[i] != i;
        for (int k = 0; k < 3; k++) {
            bad += !(fabs(g.positions[3 * i + k] - m.positions[3 * m.indices[i] + k]) <= FLOAT_TOL);
        }
    }
    CHECK(bad == 0);
    gltf_free(&g);
    meshgen_free(&m);
}

TEST(translate_scale)
{
    REQUIRE_GLTF();
    struct meshgen_mesh m = small_sphere();
    struct meshgen_glb_options opts = {
        .has_translation = true,
        .translation = {1, -2, 3},
        .has_scale = true,
        .scale = {2, 3, 0.5},
    };
    struct gltf_mesh g = {0};
    CHECK(round_trip(&m, &opts, "ts.glb", &g));
    CHECK(g.n_vertices == m.n_vertices && g.normals);
    size_t bad = 0;
    for (size_t v = 0; v < g.n_vertices && g.n_vertices == m.n_vertices && g.normals; v++) {
        double n[3];
        double len = 0;
        for (int k = 0; k < 3; k++) {
            double want = opts.scale[k] * m.positions[3 * v + k] + opts.translation[k];
            bad += !(fabs(g.positions[3 * v + k] - want) <= 4 * FLOAT_TOL);
            n[k] = m.normals[3 * v + k] / opts.scale[k];
            len += n[k] * n[k];
        }
        for (int k = 0; k < 3; k++) {
            bad += !(fabs(g.normals[3 * v + k] - n[k] / sqrt(len)) <= FLOAT_TOL);
        }
    }
    CHECK_MSG(bad == 0, "%zu values differ", bad);
    CHECK(misoriented_triangles(g.positions, g.normals, g.indices, g.n_triangles) == 0);
    gltf_free(&g);
    meshgen_free(&m);
}

TEST(rotation_matches_matrix)
{
    REQUIRE_GLTF();
    struct meshgen_mesh m = small_sphere();
    // A quarter turn about z then a shift: (x, y, z) -> (-y, x, z) + (5, 0, -1).
    struct meshgen_glb_options trs = {
        .has_translation = true,
        .translation = {5, 0, -1},
        .has_rotation = true,
        .rotation = {0, 0, sqrt(0.5), sqrt(0.5)},
    };
    struct meshgen_glb_options mat = {
        .has_matrix = true,
        .matrix = {0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 5, 0, -1, 1},
    };
    struct gltf_mesh a = {0};
    struct gltf_mesh b = {0};
    CHECK(round_trip(&m, &trs, "trs.glb", &a));
    CHECK(round_trip(&m, &mat, "matrix.glb", &b));
    size_t bad = a.n_vertices != m.n_vertices || b.n_vertices != m.n_vertices;
    for (size_t v = 0; !bad && v < m.n_vertices; v++) {
        const double *p = m.positions + 3 * v;
        double want[3] = {-p[1] + 5, p[0], p[2] - 1};
        for (int k = 0; k < 3; k++) {
            bad += !(fabs(a.positions[3 * v + k] - want[k]) <= 4 * FLOAT_TOL);
            bad += !(fabs(b.positions[3 * v + k] - want[k]) <= 4 * FLOAT_TOL);
            bad += !(fabs(a.normals[3 * v + k] - b.normals[3 * v + k]) <= FLOAT_TOL);
        }
    }
    CHECK_MSG(bad == 0, "%zu values differ", bad);
    gltf_free(&a);
    gltf_free(&b);
    meshgen_free(&m);
}

/* The unit normal of a diagonal transform diag(d) applied to n: n / d. */
static size_t
wrong_diagonal_normals(const struct meshgen_mesh *m, const struct gltf_mesh *g, const double d[3])
{
    size_t bad = 0;
    for (size_t v = 0; v < m->n_vertices; v++) {
        double n[3];
        double len = 0;
        for (int k = 0; k < 3; k++) {
            n[k] = m->normals[3 * v + k] / d[k];
            len += n[k] * n[k];
        }
        for (int k = 0; k < 3; k++) {
            bad += !(fabs(g->normals[3 * v + k] - n[k] / sqrt(len)) <= FLOAT_TOL);
        }
    }
    return bad;
}

/* A mirroring node (determinant < 0) must keep triangles facing outward and
 * normals pointing out: the loader swaps two corners of every triangle. */
TEST(mirror_keeps_orientation)
{
    REQUIRE_GLTF();
    struct meshgen_mesh m = small_sphere();
    struct meshgen_glb_options scale = {.has_scale = true, .scale = {-1, 1, 1}};
    struct meshgen_glb_options mat = {
        .has_matrix = true,
        .matrix = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -2, 0, 0, 0, 0, 1},
    };
    const struct meshgen_glb_options *cases[2] = {&scale, &mat};
    const double diagonals[2][3] = {{-1, 1, 1}, {1, 1, -2}};
    for (int i = 0; i < 2; i++) {
        struct gltf_mesh g = {0};
        CHECK(round_trip(&m, cases[i], "mirror.glb", &g));
        CHECK(g.normals && g.n_vertices == m.n_vertices && g.n_triangles == m.n_triangles);
        if (g.normals && g.n_vertices == m.n_vertices) {
            CHECK(wrong_diagonal_normals(&m, &g, diagonals[i]) == 0);
            CHECK(misoriented_triangles(g.positions, g.normals, g.indices, g.n_triangles) == 0);
            CHECK(signed_volume6(g.positions, g.indices, g.n_triangles) > 0);
            CHECK(same_closed(&g));
        }
        gltf_free(&g);
    }
    meshgen_free(&m);
}

/* --- the real assets ------------------------------------------------------ */

/* Load a model of scenes/models/ (they are part of the repository, so a
 * missing one is a failure, not a skip). */
static bool
load_model(const char *name, struct gltf_mesh *m)
{
    char rel[256];
    snprintf(rel, sizeof rel, "scenes/models/%s", name);
    return load(test_root_path(rel), m);
}

static void
check_bbox(const struct gltf_mesh *m, const double lo[3], const double hi[3], double tol)
{
    double got_lo[3];
    double got_hi[3];
    bbox(m, got_lo, got_hi);
    for (int k = 0; k < 3; k++) {
        CHECK_NEAR(got_lo[k], lo[k], tol);
        CHECK_NEAR(got_hi[k], hi[k], tol);
    }
}

/* A Stanford model: its counts and its bounding box as Stanford's PLY file
 * has them (CREDITS.md), with a unit normal at every vertex. */
static void
check_stanford_model(
    const char *name,
    size_t n_triangles,
    size_t n_vertices,
    const double lo[3],
    const double hi[3])
{
    struct gltf_mesh m = {0};
    CHECK(load_model(name, &m));
    CHECK(m.n_triangles == n_triangles);
    CHECK(m.n_vertices == n_vertices);
    CHECK(m.normals != NULL && non_unit_normals(m.normals, m.n_vertices) == 0);
    check_bbox(&m, lo, hi, 1e-6);
    gltf_free(&m);
}

TEST(asset_bunny)
{
    REQUIRE_GLTF();
    check_stanford_model(
        "bunny.glb",
        69451,
        35947,
        (const double[3]){-0.094690, 0.032987, -0.061874},
        (const double[3]){0.061009, 0.187321, 0.058800});
}

TEST(asset_dragon)
{
    REQUIRE_GLTF();
    check_stanford_model(
        "dragon_res2.glb",
        202520,
        100250,
        (const double[3]){-0.108188, 0.052739, -0.050345},
        (const double[3]){0.096406, 0.197139, 0.041137});
}

TEST(asset_buddha)
{
    REQUIRE_GLTF();
    check_stanford_model(
        "happy_res3.glb",
        67240,
        32328,
        (const double[3]){-0.046097, 0.049849, -0.047376},
        (const double[3]){0.035197, 0.247673, 0.033971});
}

/* The 1.08M-triangle Buddha `make models` generates: happy_res3 with its
 * triangles split into four twice, its corners where they were, the Stanford
 * credit in the file. */
TEST(generated_buddha)
{
    REQUIRE_GLTF();
    const char *path = test_root_path("build/models/happy_res3_subdiv16.glb");
    struct gltf_mesh big = {0};
    struct gltf_mesh small = {0};
    CHECK_MSG(load(path, &big), "%s: run `make models` first", path);
    CHECK(load_model("happy_res3.glb", &small));
    CHECK(big.n_triangles == 16 * small.n_triangles && big.n_triangles == 1075840);
    CHECK(big.n_vertices == 522933);
    bool corners_kept =
        big.n_vertices >= small.n_vertices && small.n_vertices > 0
        && memcmp(big.positions, small.positions, 3 * small.n_vertices * sizeof(double)) == 0;
    CHECK(corners_kept);
    CHECK(big.normals != NULL && non_unit_normals(big.normals, big.n_vertices) == 0);
    size_t len = 0;
    char *bytes = test_read_file(path, &len);
    // The JSON chunk starts 20 bytes in; the credit is in asset.copyright.
    size_t json_len = bytes && len >= 20 ? test_get_le32((unsigned char *)bytes + 12) : 0;
    bool credited = false;
    if (json_len > 0 && 20 + json_len <= len) {
        bytes[20 + json_len - 1] = '\0';  // the last byte is padding
        credited = strstr(bytes + 20, "\"copyright\":\"Stanford 3D Scanning Repository") != NULL;
    }
    CHECK(credited);
    free(bytes);
    gltf_free(&big);
    gltf_free(&small);
}

/* Box.glb's root matrix maps (x, y, z) to (x, z, -y) (z up to y up).  Its
 * POSITION accessor starts 288 bytes into the BIN chunk (see its JSON). */
static bool
box_matrix_applied(const char *path, const struct gltf_mesh *m)
{
    size_t len;
    unsigned char *bytes = (unsigned char *)test_read_file(path, &len);
    size_t start = bytes ? 20 + test_get_le32(bytes + 12) + 8 + 288 : 0;
    bool ok = bytes && m->n_vertices == 24 && start + 24 * 12 <= len;
    for (size_t v = 0; ok && v < 24; v++) {
        float raw[3];
        for (int k = 0; k < 3; k++) {
            uint32_t bits = test_get_le32(bytes + start + 12 * v + 4 * (size_t)k);
            memcpy(&raw[k], &bits, 4);
        }
        const double *p = m->positions + 3 * v;
        ok = p[0] == raw[0] && p[1] == raw[2] && p[2] == -raw[1];
    }
    free(bytes);
    return ok;
}

TEST(asset_box)
{
    REQUIRE_GLTF();
    struct gltf_mesh m = {0};
    CHECK(load_model("Box.glb", &m));
    CHECK(m.n_triangles == 12 && m.n_vertices == 24);
    check_bbox(&m, (const double[3]){-0.5, -0.5, -0.5}, (const double[3]){0.5, 0.5, 0.5}, 1e-6);
    CHECK(box_matrix_applied(test_root_path("scenes/models/Box.glb"), &m));
    if (m.normals) {
        CHECK(misoriented_triangles(m.positions, m.normals, m.indices, m.n_triangles) == 0);
    }
    CHECK(signed_volume6(m.positions, m.indices, m.n_triangles) > 0);
    gltf_free(&m);
}

TEST(asset_duck)
{
    REQUIRE_GLTF();
    struct gltf_mesh m = {0};
    CHECK(load_model("Duck.glb", &m));
    CHECK(m.n_triangles == 4212 && m.n_vertices == 2399);
    check_bbox(
        &m,
        (const double[3]){-0.693, 0.099, -0.613},
        (const double[3]){0.962, 1.640, 0.539},
        1e-3);
    gltf_free(&m);
}

TEST(asset_cornell_box)
{
    REQUIRE_GLTF();
    struct gltf_mesh m = {0};
    CHECK(load_model("cornell_box.glb", &m));
    CHECK(m.n_triangles == 12 && m.n_vertices == 24);
    check_bbox(&m, (const double[3]){-1, 0, -1}, (const double[3]){1, 2, 1}, 1e-6);
    gltf_free(&m);
}

/* --- hostile and broken files --------------------------------------------- */

TEST(hand_made_triangle_loads)
{
    REQUIRE_GLTF();
    struct gltf_mesh m = {0};
    CHECK(load(tri_glb("tri.glb", &(struct tri_gltf){0}), &m));
    CHECK(m.n_triangles == 1 && m.n_vertices == 3 && m.normals == NULL);
    if (m.n_vertices == 3) {
        CHECK(m.positions[3] == 1 && m.positions[7] == 1);
        CHECK(m.indices[0] == 0 && m.indices[1] == 1 && m.indices[2] == 2);
    }
    gltf_free(&m);
}

TEST(uint8_indices)
{
    REQUIRE_GLTF();
    unsigned char bin[TRI_BIN_LEN];
    tri_bin(bin);
    bin[36] = 2;  // indices 2 0 1 as bytes
    bin[37] = 0;
    bin[38] = 1;
    struct tri_gltf g = {
        .accessors = TRI_POSITIONS
        ",{\"bufferView\":1,\"componentType\":5121,\"count\":3,\"type\":\"SCALAR\"}",
        .views = TRI_VIEW_POS ",{\"buffer\":0,\"byteOffset\":36,\"byteLength\":3}",
    };
    const char *path = test_tmp_path("u8.glb");
    CHECK(write_glb(path, tri_json(&g), bin, sizeof bin));
    struct gltf_mesh m = {0};
    CHECK(load(path, &m));
    CHECK(m.n_triangles == 1);
    if (m.n_triangles == 1) {
        CHECK(m.indices[0] == 2 && m.indices[1] == 0 && m.indices[2] == 1);
    }
    gltf_free(&m);
}

TEST(empty_and_garbage)
{
    REQUIRE_GLTF();
    const char *empty = test_tmp_path("empty.glb");
    CHECK(test_write_bytes(empty, "", 0));
    check_refused(empty, "empty");
    struct rng r = rng_make(11, 0);
    unsigned char junk[4096];
    for (int i = 0; i < 60; i++) {
        size_t len = 1 + rng_next_u32(&r) % sizeof junk;
        for (size_t k = 0; k < len; k++) {
            junk[k] = (unsigned char)rng_next_u32(&r);
        }
        if (i % 3 == 2 && len >= 4) {
            memcpy(junk, "glTF", 4);
        }
        const char *path = test_tmp_path(i % 2 ? "junk.glb" : "junk.gltf");
        CHECK(test_write_bytes(path, junk, len));
        check_refused(path, NULL);
    }
    check_refused(test_tmp_path("does-not-exist.glb"), "cannot open");
    check_refused(test_tmpdir(), NULL);
}

TEST(wrong_magic)
{
    REQUIRE_GLTF();
    size_t len;
    char *bytes = test_read_file(tri_glb("magic.glb", &(struct tri_gltf){0}), &len);
    CHECK(bytes != NULL);
    if (!bytes) {
        return;
    }
    bytes[1] = 'L';
    const char *path = test_tmp_path("magic.glb");
    CHECK(test_write_bytes(path, bytes, len));
    check_refused(path, "glTF");
    path = test_tmp_path("magic.gltf");
    CHECK(test_write_bytes(path, bytes, len));
    check_refused(path, NULL);
    memcpy(bytes, "glTF", 4);
    test_put_le32((unsigned char *)bytes + 4, 1);
    path = test_tmp_path("version.glb");
    CHECK(test_write_bytes(path, bytes, len));
    check_refused(path, "version");
    free(bytes);
}

/* Cut a valid file at many offsets; also patch the header's length so only
 * the chunk lengths give the truncation away. */
TEST(truncated_glb)
{
    REQUIRE_GLTF();
    struct meshgen_mesh m = small_sphere();
    const char *full = test_tmp_path("full.glb");
    CHECK(meshgen_write_glb(&m, full, NULL));
    meshgen_free(&m);
    size_t len;
    unsigned char *bytes = (unsigned char *)test_read_file(full, &len);
    CHECK(bytes && len > 100);
    if (!bytes || len <= 100) {
        free(bytes);
        return;
    }
    size_t json_end = 20 + test_get_le32(bytes + 12);
    size_t cuts[] = {
        1,
        4,
        11,
        12,
        19,
        20,
        21,
        json_end / 2,
        json_end - 1,
        json_end,
        json_end + 4,
        json_end + 8,
        json_end + 100,
        len - 4,
        len - 1};
    const char *path = test_tmp_path("cut.glb");
    for (size_t i = 0; i < sizeof cuts / sizeof cuts[0]; i++) {
        CHECK(test_write_bytes(path, bytes, cuts[i]));
        check_refused(path, NULL);
        if (cuts[i] >= 12) {
            test_put_le32(bytes + 8, (uint32_t)cuts[i]);
            CHECK(test_write_bytes(path, bytes, cuts[i]));
            check_refused(path, NULL);
            test_put_le32(bytes + 8, (uint32_t)len);
        }
    }
    free(bytes);
}

TEST(chunk_lengths_past_end)
{
    REQUIRE_GLTF();
    size_t len;
    unsigned char *bytes =
        (unsigned char *)test_read_file(tri_glb("chunks.glb", &(struct tri_gltf){0}), &len);
    CHECK(bytes != NULL);
    if (!bytes) {
        return;
    }
    const char *path = test_tmp_path("chunks.glb");
    uint32_t json_len = test_get_le32(bytes + 12);
    test_put_le32(bytes + 12, (uint32_t)len);
    CHECK(test_write_bytes(path, bytes, len));
    check_refused(path, "JSON chunk");
    test_put_le32(bytes + 12, 0xfffffff0u);
    CHECK(test_write_bytes(path, bytes, len));
    check_refused(path, "JSON chunk");
    test_put_le32(bytes + 12, json_len);
    // tinygltf 2.7.0 alone would accept a BIN chunk 8 bytes too long.
    unsigned char *bin_header = bytes + 20 + json_len;
    test_put_le32(bin_header, test_get_le32(bin_header) + 8);
    CHECK(test_write_bytes(path, bytes, len));
    check_refused(path, "BIN chunk");
    free(bytes);
}

TEST(accessor_out_of_bounds)
{
    REQUIRE_GLTF();

    struct {
        const char *accessors;
        const char *views;
        const char *needle;
    } cases[] = {
        // count too large for its view
        {"{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"}," TRI_INDICES,
         NULL,
         "reads past the end of buffer view 0"},
        // accessor byteOffset past the view
        {"{\"bufferView\":0,\"byteOffset\":40,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}," TRI_INDICES,
         NULL,
         "reads past"},
        {"{\"bufferView\":0,\"byteOffset\":4,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}," TRI_INDICES,
         NULL,
         "reads past"},
        // view byteOffset / byteLength past the buffer
        {NULL,
         "{\"buffer\":0,\"byteOffset\":1000,\"byteLength\":36}," TRI_VIEW_IDX,
         "past the end of buffer 0"},
        {NULL,
         "{\"buffer\":0,\"byteOffset\":0,\"byteLength\":100}," TRI_VIEW_IDX,
         "past the end of buffer 0"},
        {NULL,
         "{\"buffer\":0,\"byteOffset\":40,\"byteLength\":6}," TRI_VIEW_IDX,
         "past the end of buffer 0"},
        // indices reading past their view
        {TRI_POSITIONS ",{\"bufferView\":1,\"componentType\":5125,\"count\":3,\"type\":\"SCALAR\"}",
         NULL,
         "reads past"},
        // missing buffer, view, accessor
        {NULL, "{\"buffer\":3,\"byteLength\":36}," TRI_VIEW_IDX, "buffer 3 does not exist"},
        {"{\"bufferView\":7,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}," TRI_INDICES,
         NULL,
         "buffer view 7 does not exist"},
        {TRI_POSITIONS, NULL, "accessor"},
        {"{\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}," TRI_INDICES,
         NULL,
         "no buffer view"},
        // stride smaller than an element
        {NULL, "{\"buffer\":0,\"byteLength\":36,\"byteStride\":4}," TRI_VIEW_IDX, "byteStride 4"},
        {NULL, "{\"buffer\":0,\"byteLength\":36,\"byteStride\":14}," TRI_VIEW_IDX, NULL},
        // wrong types
        {"{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC2\"}," TRI_INDICES,
         NULL,
         "float VEC3"},
        {"{\"bufferView\":0,\"componentType\":5123,\"count\":3,\"type\":\"VEC3\"}," TRI_INDICES,
         NULL,
         "float VEC3"},
        {TRI_POSITIONS ",{\"bufferView\":1,\"componentType\":5126,\"count\":1,\"type\":\"SCALAR\"}",
         NULL,
         "unsigned"},
        {TRI_POSITIONS ",{\"bufferView\":1,\"componentType\":5122,\"count\":3,\"type\":\"SCALAR\"}",
         NULL,
         "unsigned"},
    };

    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct tri_gltf g = {.accessors = cases[i].accessors, .views = cases[i].views};
        check_refused(tri_glb("bounds.glb", &g), cases[i].needle);
    }
}

/* Counts whose byte size overflows or dwarfs the buffer. */
TEST(huge_counts)
{
    REQUIRE_GLTF();
    const char *counts[] = {
        "2147483648",
        "4294967296",
        "6148914691236517206",
        "9223372036854775807",
        "18446744073709551615"};
    for (size_t i = 0; i < sizeof counts / sizeof counts[0]; i++) {
        char accessors[512];
        snprintf(
            accessors,
            sizeof accessors,
            "{\"bufferView\":0,\"componentType\":5126,\"count\":%s,\"type\":\"VEC3\"}," TRI_INDICES,
            counts[i]);
        check_refused(tri_glb("huge.glb", &(struct tri_gltf){.accessors = accessors}), NULL);
        snprintf(
            accessors,
            sizeof accessors,
            TRI_POSITIONS
            ",{\"bufferView\":1,\"componentType\":5123,\"count\":%s,\"type\":\"SCALAR\"}",
            counts[i]);
        check_refused(tri_glb("huge.glb", &(struct tri_gltf){.accessors = accessors}), NULL);
    }
}

TEST(bad_indices)
{
    REQUIRE_GLTF();
    unsigned char bin[TRI_BIN_LEN];
    tri_bin(bin);
    bin[40] = 3;  // the third index: only 3 vertices
    const char *path = test_tmp_path("index.glb");
    CHECK(write_glb(path, tri_json(&(struct tri_gltf){0}), bin, sizeof bin));
    check_refused(path, "out of range");
    tri_bin(bin);
    bin[41] = 0xff;
    CHECK(write_glb(path, tri_json(&(struct tri_gltf){0}), bin, sizeof bin));
    check_refused(path, "out of range");
    struct tri_gltf two = {
        .accessors = TRI_POSITIONS
        ",{\"bufferView\":1,\"componentType\":5123,\"count\":2,\"type\":\"SCALAR\"}"};
    check_refused(tri_glb("two.glb", &two), "multiple of 3");
    struct tri_gltf flat = {
        .primitive = "\"attributes\":{\"POSITION\":0}",
        .accessors = "{\"bufferView\":0,\"componentType\":5126,\"count\":2,\"type\":\"VEC3\"}",
    };
    check_refused(tri_glb("flat2.glb", &flat), "multiple of 3");
}

TEST(non_finite_positions)
{
    REQUIRE_GLTF();
    const uint32_t bad_bits[] = {0x7fc00000u, 0x7f800000u, 0xff800000u};  // NaN, +inf, -inf
    const char *path = test_tmp_path("nan.glb");
    for (int i = 0; i < 3; i++) {
        unsigned char bin[TRI_BIN_LEN];
        tri_bin(bin);
        test_put_le32(bin + 16, bad_bits[i]);
        CHECK(write_glb(path, tri_json(&(struct tri_gltf){0}), bin, sizeof bin));
        check_refused(path, "non-finite");
    }
    // Finite in the file, infinite once a node scales it.
    struct tri_gltf scaled = {.nodes = "{\"mesh\":0,\"scale\":[1e300,1e300,1e300]}"};
    unsigned char bin[TRI_BIN_LEN];
    tri_bin(bin);
    test_put_le32(bin + 12, 0x7f7fffffu);  // FLT_MAX
    CHECK(write_glb(path, tri_json(&scaled), bin, sizeof bin));
    check_refused(path, "non-finite");
}

TEST(unsupported_features)
{
    REQUIRE_GLTF();
    struct tri_gltf points = {
        .primitive = "\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":0"};
    check_refused(tri_glb("points.glb", &points), "mode 0 (POINTS)");
    struct tri_gltf strip = {.primitive = "\"attributes\":{\"POSITION\":0},\"mode\":5"};
    check_refused(tri_glb("strip.glb", &strip), "TRIANGLE_STRIP");
    struct tri_gltf sparse = {
        .accessors =
            "{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
            "\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":1,\"componentType\":5123},"
            "\"values\":{\"bufferView\":0}}}," TRI_INDICES,
    };
    check_refused(tri_glb("sparse.glb", &sparse), "sparse accessors are not supported");
    struct tri_gltf draco = {.top = "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],"};
    check_refused(tri_glb("draco.glb", &draco), "KHR_draco_mesh_compression");
    /* As Draco files are: accessors without a bufferView (the mesh is in the
     * extension's compressed view), which tinygltf refuses first ("accessor[0]
     * invalid bufferView") unless the required extension is read before it. */
    struct tri_gltf real_draco = {
        .top = "\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],"
               "\"extensionsRequired\":[\"KHR_materials_unlit\",\"KHR_draco_mesh_compression\"],",
        .primitive = "\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":4,\"extensions\":"
                     "{\"KHR_draco_mesh_compression\":{\"bufferView\":0,\"attributes\":"
                     "{\"POSITION\":0}}}",
        .accessors = "{\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                     "{\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}",
    };
    check_refused(
        tri_glb("real-draco.glb", &real_draco),
        "requires extension 'KHR_draco_mesh_compression', which is not supported");
    struct tri_gltf no_position = {.primitive = "\"attributes\":{\"NORMAL\":0},\"indices\":1"};
    check_refused(tri_glb("nopos.glb", &no_position), "POSITION");
    struct tri_gltf normals = {
        .primitive = "\"attributes\":{\"POSITION\":0,\"NORMAL\":2},\"indices\":1",
        .accessors = TRI_ACCESSORS
        ",{\"bufferView\":0,\"componentType\":5126,\"count\":2,\"type\":\"VEC3\"}"};
    check_refused(tri_glb("normals.glb", &normals), "NORMAL has 2");
    struct tri_gltf empty = {
        .accessors = "{\"bufferView\":0,\"componentType\":5126,\"count\":0,\"type\":\"VEC3\"}",
        .primitive = "\"attributes\":{\"POSITION\":0}"};
    check_refused(tri_glb("none.glb", &empty), "no triangles");
}

TEST(bad_nodes)
{
    REQUIRE_GLTF();
    struct tri_gltf cycle = {.nodes = "{\"mesh\":0,\"children\":[0]}"};
    check_refused(tri_glb("cycle.glb", &cycle), "reached twice");
    struct tri_gltf loop = {.nodes = "{\"children\":[1]},{\"children\":[0],\"mesh\":0}"};
    check_refused(tri_glb("loop.glb", &loop), "reached twice");
    struct tri_gltf shared = {
        .scene = "\"scene\":0,\"scenes\":[{\"nodes\":[0,1]}],",
        .nodes = "{\"children\":[2]},{\"children\":[2]},{\"mesh\":0}",
    };
    check_refused(tri_glb("shared.glb", &shared), "reached twice");
    struct tri_gltf child = {.nodes = "{\"mesh\":0,\"children\":[5]}"};
    check_refused(tri_glb("child.glb", &child), "child node 5 does not exist");
    struct tri_gltf root = {.scene = "\"scenes\":[{\"nodes\":[-1]}],"};
    check_refused(tri_glb("root.glb", &root), "node -1");
    struct tri_gltf scene = {.scene = "\"scene\":3,\"scenes\":[{\"nodes\":[0]}],"};
    check_refused(tri_glb("scene.glb", &scene), "scene 3 does not exist");
    struct tri_gltf mesh = {.nodes = "{\"mesh\":4}"};
    check_refused(tri_glb("mesh.glb", &mesh), "mesh 4 does not exist");
    struct tri_gltf matrix = {
        .nodes = "{\"mesh\":0,\"matrix\":[1,0,0,0, 0,1,0,0, 0,0,1,0.5, 0,0,0,1]}"};
    check_refused(tri_glb("proj.glb", &matrix), "not affine");
    struct tri_gltf short_matrix = {.nodes = "{\"mesh\":0,\"matrix\":[1,0,0]}"};
    check_refused(tri_glb("short.glb", &short_matrix), "wrong length");
    struct tri_gltf zero_q = {.nodes = "{\"mesh\":0,\"rotation\":[0,0,0,0]}"};
    check_refused(tri_glb("zeroq.glb", &zero_q), "zero quaternion");
}

/* A chain of n nodes, the last holding the mesh, each shifting by +1 in x. */
static const char *
chain_glb(int n)
{
    static char nodes[65536];
    size_t len = 0;
    for (int i = 0; i < n && len < sizeof nodes - 64; i++) {
        const char *sep = i ? "," : "";
        if (i + 1 < n) {
            len += (size_t)snprintf(
                nodes + len,
                sizeof nodes - len,
                "%s{\"translation\":[1,0,0],\"children\":[%d]}",
                sep,
                i + 1);
        } else {
            len += (size_t)snprintf(
                nodes + len,
                sizeof nodes - len,
                "%s{\"translation\":[1,0,0],\"mesh\":0}",
                sep);
        }
    }
    return tri_glb("chain.glb", &(struct tri_gltf){.nodes = nodes});
}

TEST(deep_node_tree)
{
    REQUIRE_GLTF();
    struct gltf_mesh m = {0};
    CHECK(load(chain_glb(100), &m));
    CHECK(m.n_vertices == 3 && m.positions[0] == 100);
    gltf_free(&m);
    check_refused(chain_glb(1000), "deeper than");
}

TEST(no_scenes_uses_root_nodes)
{
    REQUIRE_GLTF();
    struct tri_gltf g = {
        .scene = "",
        .nodes =
            "{\"translation\":[0,0,5],\"children\":[1]},{\"mesh\":0},{\"mesh\":0,\"scale\":[2,2,2]}",
    };
    struct gltf_mesh m = {0};
    CHECK(load(tri_glb("noscene.glb", &g), &m));
    CHECK(m.n_triangles == 2 && m.n_vertices == 6);
    if (m.n_vertices == 6) {
        CHECK(m.positions[2] == 5);  // node 1 under node 0
        CHECK(m.positions[12] == 2);  // node 2, a root of its own
    }
    gltf_free(&m);
}

TEST(interleaved_attributes)
{
    REQUIRE_GLTF();
    // Three vertices of (position, normal), byteStride 24, then indices.
    static const float data[18] = {0, 0, 0, 0, 0, 2, 1, 0, 0, 0, 0, 2, 0, 1, 0, 0, 0, 2};
    unsigned char bin[80] = {0};
    for (int i = 0; i < 18; i++) {
        uint32_t bits;
        memcpy(&bits, &data[i], 4);
        test_put_le32(bin + 4 * i, bits);
    }
    bin[74] = 1;
    bin[76] = 2;
    struct tri_gltf g = {
        .primitive = "\"attributes\":{\"POSITION\":0,\"NORMAL\":2},\"indices\":1",
        .accessors = TRI_POSITIONS
        ",{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"},"
        "{\"bufferView\":0,\"byteOffset\":12,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}",
        .views =
            "{\"buffer\":0,\"byteLength\":72,\"byteStride\":24},{\"buffer\":0,\"byteOffset\":72,\"byteLength\":6}",
        .buffer = "\"byteLength\":80",
    };
    const char *path = test_tmp_path("interleaved.glb");
    CHECK(write_glb(path, tri_json(&g), bin, sizeof bin));
    struct gltf_mesh m = {0};
    CHECK(load(path, &m));
    CHECK(m.n_vertices == 3 && m.normals);
    if (m.n_vertices == 3 && m.normals) {
        CHECK(m.positions[3] == 1 && m.positions[7] == 1);
        for (int v = 0; v < 3; v++) {
            CHECK(m.normals[3 * v] == 0 && m.normals[3 * v + 1] == 0 && m.normals[3 * v + 2] == 1);
        }
    }
    gltf_free(&m);
}

/* Base64 (RFC 4648) of n bytes into out (4 * ceil(n / 3) + 1 bytes). */
static void
base64(const unsigned char *in, size_t n, char *out)
{
    static const char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (size_t i = 0; i < n; i += 3) {
        size_t left = n - i;  // bytes in this group, 3 unless the last
        uint32_t v = (uint32_t)in[i] << 16;
        v |= left > 1 ? (uint32_t)in[i + 1] << 8 : 0;
        v |= left > 2 ? (uint32_t)in[i + 2] : 0;
        for (size_t k = 0; k < 4; k++) {
            // A group of b bytes gives b + 1 digits, then '=' padding.
            *out++ = k <= left ? digits[(v >> (18 - 6 * k)) & 63] : '=';
        }
    }
    *out = '\0';
}

/* Brackets nested n deep inside "extras" (tinygltf copies extras
 * recursively: without a depth limit a long run of '[' overflows the stack). */
static char *
nested_extras(size_t n)
{
    char *extras = malloc(2 * n + 16);
    if (extras) {
        memset(extras, '[', n);
        memset(extras + n, ']', n);
        extras[2 * n] = '\0';
    }
    return extras;
}

TEST(deeply_nested_json)
{
    REQUIRE_GLTF();
    const size_t depths[] = {100, 1000000};
    for (int i = 0; i < 2; i++) {
        char *extras = nested_extras(depths[i]);
        char *nodes = extras ? malloc(2 * depths[i] + 64) : NULL;
        CHECK(nodes != NULL);
        if (!nodes) {
            free(extras);
            return;
        }
        sprintf(nodes, "{\"mesh\":0,\"extras\":%s}", extras);
        struct tri_gltf g = {.nodes = nodes};
        unsigned char bin[TRI_BIN_LEN];
        tri_bin(bin);
        const char *path = test_tmp_path("nested.glb");
        CHECK(write_glb(path, tri_json(&g), bin, sizeof bin));
        if (i == 0) {
            struct gltf_mesh m = {0};
            CHECK(load(path, &m));
            gltf_free(&m);
        } else {
            check_refused(path, "nests deeper");
        }
        free(extras);
        free(nodes);
    }
}

/* tinygltf copies the BIN chunk once per buffer without a uri: only the
 * first buffer may be one (as the specification says). */
TEST(bin_chunk_shared_once)
{
    REQUIRE_GLTF();
    struct tri_gltf two = {.top = "\"buffers\":[{\"byteLength\":44},{\"byteLength\":44}],"};
    // tri_json adds its own "buffers" member after .top: both count.
    check_refused(tri_glb("twobuffers.glb", &two), "3 buffers have no uri");
    struct tri_gltf escaped = {.top = "\"buf\\u0066ers\":[{\"byteLength\":44}],"};
    check_refused(tri_glb("escaped.glb", &escaped), "buffers have no uri");
    unsigned char bin[TRI_BIN_LEN];
    tri_bin(bin);
    char b64[64];
    base64(bin, sizeof bin, b64);
    char buffers[256];
    snprintf(
        buffers,
        sizeof buffers,
        "\"byteLength\":44},{\"uri\":\"data:application/octet-stream;base64,%s\",\"byteLength\":44",
        b64);
    struct gltf_mesh m = {0};
    CHECK(load(tri_glb("bin-and-data.glb", &(struct tri_gltf){.buffer = buffers}), &m));
    CHECK(m.n_triangles == 1);
    gltf_free(&m);
}

/* 716 instances of a mesh of 1,000,000 (degenerate) triangles: more than
 * the scene's int indices allow, refused before anything is allocated. */
TEST(instancing_total_limit)
{
    REQUIRE_GLTF();

    enum {
        TRIANGLES = 1000000,
        INSTANCES = 716
    };

    size_t bin_len = 36 + 3 * TRIANGLES;  // 3 positions, uint8 indices all 0
    unsigned char *bin = calloc(bin_len, 1);
    char *json = malloc(INSTANCES * 16 + 1024);
    CHECK(bin && json);
    if (!bin || !json) {
        free(bin);
        free(json);
        return;
    }
    size_t len = (size_t)sprintf(json, "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[");
    for (int i = 0; i < INSTANCES; i++) {
        len += (size_t)sprintf(json + len, "%s%d", i ? "," : "", i);
    }
    len += (size_t)sprintf(json + len, "]}],\"nodes\":[");
    for (int i = 0; i < INSTANCES; i++) {
        len += (size_t)sprintf(json + len, "%s{\"mesh\":0}", i ? "," : "");
    }
    sprintf(
        json + len,
        "],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
        "\"accessors\":[" TRI_POSITIONS
        ",{\"bufferView\":1,\"componentType\":5121,\"count\":%d,\"type\":\"SCALAR\"}],"
        "\"bufferViews\":[" TRI_VIEW_POS ",{\"buffer\":0,\"byteOffset\":36,\"byteLength\":%d}],"
        "\"buffers\":[{\"byteLength\":%zu}]}",
        3 * TRIANGLES,
        3 * TRIANGLES,
        bin_len);
    const char *path = test_tmp_path("instances.glb");
    CHECK(write_glb(path, json, bin, bin_len));
    check_refused(path, "more than");
    remove(path);
    free(bin);
    free(json);
}

/* --- external files ------------------------------------------------------- */

/* tmpdir/models/model.gltf whose buffer is uri, returning its path. */
static const char *
gltf_with_uri(const char *uri)
{
    char buffer[1024];
    snprintf(buffer, sizeof buffer, "\"uri\":\"%s\",\"byteLength\":44", uri);
    mkdir(test_tmp_path("models"), 0755);
    const char *path = test_tmp_path("models/model.gltf");
    CHECK(test_write_file(path, tri_json(&(struct tri_gltf){.buffer = buffer})));
    return path;
}

static bool
write_tri_bin(const char *path)
{
    unsigned char bin[TRI_BIN_LEN];
    tri_bin(bin);
    return test_write_bytes(path, bin, sizeof bin);
}

TEST(external_buffers_inside)
{
    REQUIRE_GLTF();
    mkdir(test_tmp_path("models"), 0755);
    mkdir(test_tmp_path("models/sub"), 0755);
    CHECK(write_tri_bin(test_tmp_path("models/tri.bin")));
    CHECK(write_tri_bin(test_tmp_path("models/sub/tri 2.bin")));
    const char *uris[] = {"tri.bin", "./tri.bin", "sub/tri 2.bin", "sub/tri%202.bin"};
    for (size_t i = 0; i < sizeof uris / sizeof uris[0]; i++) {
        struct gltf_mesh m = {0};
        CHECK_MSG(load(gltf_with_uri(uris[i]), &m), "uri %s", uris[i]);
        CHECK(m.n_triangles == 1);
        // The buffer is named among the files read (an input of a render).
        const char *bin = strstr(uris[i], "sub/") ? "/sub/tri 2.bin" : "tri.bin";
        CHECK_MSG(m.n_files == 1 && strstr(m.files[0], bin), "uri %s", uris[i]);
        gltf_free(&m);
    }
    // A bare file name: the model's directory is the working directory.
    char cwd[4096];
    CHECK(getcwd(cwd, sizeof cwd) != NULL);
    gltf_with_uri("tri.bin");
    if (chdir(test_tmp_path("models")) == 0) {
        struct gltf_mesh m = {0};
        CHECK(load("model.gltf", &m));
        CHECK(m.n_triangles == 1);
        gltf_free(&m);
        CHECK(chdir(cwd) == 0);
    }
}

TEST(external_buffers_outside)
{
    REQUIRE_GLTF();
    // A perfectly good buffer next to the model's directory: only the guard
    // stops the loader from using it.
    CHECK(write_tri_bin(test_tmp_path("secret.bin")));
    const char *uris[] = {
        "../secret.bin",
        "sub/../../secret.bin",
        "sub/../tri.bin",
        "%2e%2e/secret.bin",
        "..",
        "/etc/passwd",
        "file:///etc/passwd",
        "C:\\\\secret.bin",
        "..\\\\secret.bin",
    };
    for (size_t i = 0; i < sizeof uris / sizeof uris[0]; i++) {
        check_refused(gltf_with_uri(uris[i]), "refused");
    }
    char abs_uri[1024];
    snprintf(abs_uri, sizeof abs_uri, "%s", test_tmp_path("secret.bin"));
    check_refused(gltf_with_uri(abs_uri), "absolute");
    check_refused(gltf_with_uri("missing.bin"), "missing.bin");
    mkdir(test_tmp_path("models/dir.bin"), 0755);
    check_refused(gltf_with_uri("dir.bin"), "dir.bin");
}

/* Symbolic links in the model's directory: to one of its files, read; out
 * of it (a file link, a directory link), refused. */
TEST(external_buffers_symlinks)
{
    REQUIRE_GLTF();
    mkdir(test_tmp_path("models"), 0755);
    CHECK(write_tri_bin(test_tmp_path("models/tri.bin")));
    CHECK(write_tri_bin(test_tmp_path("secret.bin")));
    const char *links[][2] = {
        {"tri.bin", "models/link_in.bin"},
        {test_tmp_path("secret.bin"), "models/link_out.bin"},
        {"..", "models/up"},
    };
    for (size_t i = 0; i < sizeof links / sizeof links[0]; i++) {
        const char *at = test_tmp_path(links[i][1]);
        unlink(at);
        CHECK(symlink(links[i][0], at) == 0);
    }
    struct gltf_mesh m = {0};
    CHECK(load(gltf_with_uri("link_in.bin"), &m));
    CHECK(m.n_triangles == 1);
    gltf_free(&m);
    check_refused(gltf_with_uri("link_out.bin"), "symbolic link");
    check_refused(gltf_with_uri("up/secret.bin"), "symbolic link");
}

/* Ten nodes instancing a mesh of 1,000 triangles (3,000 vertices, no
 * normals, not indexed) need 10 x (3,000 vertices x 3 doubles + 3,000
 * indices) = 840,000 bytes: refused under that, loaded at it.  (The JSON's
 * own estimate, a few tens of KB, is far below.) */
#define SOUP_VERTICES 3000
#define SOUP_BIN_BYTES (SOUP_VERTICES * 12)

static const char *
write_instanced_soup(const char *name)
{
    char json[4096];
    size_t len = (size_t)sprintf(
        json,
        "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0,1,2,3,4,5,6,7,8,9]}],"
        "\"nodes\":[");
    for (int i = 0; i < 10; i++) {
        len += (size_t)sprintf(json + len, "%s{\"mesh\":0}", i ? "," : "");
    }
    sprintf(
        json + len,
        "],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%d,"
        "\"type\":\"VEC3\"}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":%d}],"
        "\"buffers\":[{\"byteLength\":%d}]}",
        SOUP_VERTICES,
        SOUP_BIN_BYTES,
        SOUP_BIN_BYTES);
    static unsigned char bin[SOUP_BIN_BYTES];
    const char *path = test_tmp_path(name);
    CHECK(write_glb(path, json, bin, sizeof bin));
    return path;
}

TEST(memory_limit)
{
    REQUIRE_GLTF();
    const char *path = write_instanced_soup("instanced.glb");
    uint64_t need = 10 * SOUP_VERTICES * (3 * sizeof(double) + sizeof(unsigned));
    struct gltf_mesh m = {0};
    struct diag err = {0};
    CHECK(!gltf_load_limited(path, need - 1, &m, &err));
    CHECK_MSG(strstr(err.msg, "30000 vertices and 10000 triangles") != NULL, "%s", err.msg);
    CHECK_MSG(strstr(err.msg, "--max-memory") != NULL, "%s", err.msg);
    CHECK(m.positions == NULL && m.n_vertices == 0);
    CHECK(err.kind == DIAG_INVALID);
    CHECK_MSG(gltf_load_limited(path, need, &m, &err), "%s", err.msg);
    CHECK(m.n_triangles == 10000);
    gltf_free(&m);
}

/* The JSON is refused before it is parsed when its estimate (256 bytes per
 * value, counted at ',', ':', '[' and '{', and 4 per byte of text) passes
 * the limit: the same file's 10 nodes and accessors under 16 KiB. */
TEST(json_memory_limit)
{
    REQUIRE_GLTF();
    const char *path = write_instanced_soup("instanced_json.glb");
    struct gltf_mesh m = {0};
    struct diag err = {0};
    CHECK(!gltf_load_limited(path, 16 << 10, &m, &err));
    CHECK_MSG(strstr(err.msg, "the JSON text (") != NULL, "%s", err.msg);
    CHECK_MSG(strstr(err.msg, "once parsed") != NULL, "%s", err.msg);
    CHECK_MSG(strstr(err.msg, "--max-memory") != NULL, "%s", err.msg);
    CHECK(m.positions == NULL && m.n_vertices == 0);
}

TEST(data_uri)
{
    REQUIRE_GLTF();
    unsigned char bin[TRI_BIN_LEN];
    tri_bin(bin);
    char b64[64];
    base64(bin, sizeof bin, b64);
    char uri[128];
    snprintf(uri, sizeof uri, "data:application/octet-stream;base64,%s", b64);
    struct gltf_mesh m = {0};
    CHECK(load(gltf_with_uri(uri), &m));
    CHECK(m.n_triangles == 1 && m.n_vertices == 3);
    gltf_free(&m);
    check_refused(gltf_with_uri("data:text/html,<script>"), NULL);
}

/* Files over the limit are refused from their size alone (sparse files: no
 * disk is used). */
TEST(size_limit)
{
    REQUIRE_GLTF();
    const off_t too_big = ((off_t)1 << 30) + 1;
    mkdir(test_tmp_path("models"), 0755);
    const char *big_bin = test_tmp_path("models/big.bin");
    CHECK(write_tri_bin(big_bin));
    if (truncate(big_bin, too_big) != 0) {
        SKIP("cannot make a sparse file here");
    }
    check_refused(gltf_with_uri("big.bin"), "allowed");
    const char *big_glb = test_tmp_path("big.glb");
    CHECK(test_write_bytes(big_glb, "glTF", 4));
    CHECK(truncate(big_glb, too_big) == 0);
    check_refused(big_glb, "allowed");
    remove(big_bin);
    remove(big_glb);
}

/* --- fuzzing --------------------------------------------------------------- */

/* A loaded mesh keeps the API's promises. */
static void
check_invariants(const struct gltf_mesh *m)
{
    size_t bad = 0;
    for (size_t i = 0; i < 3 * m->n_triangles; i++) {
        bad += m->indices[i] >= m->n_vertices;
    }
    for (size_t i = 0; i < 3 * m->n_vertices; i++) {
        bad += !isfinite(m->positions[i]);
    }
    CHECK(bad == 0);
}

/* Offsets of the JSON chunk's digits, in a static array; their count. */
static size_t
json_digits(const unsigned char *glb, size_t len, size_t **out)
{
    static size_t at[65536];
    size_t n = 0;
    size_t end = 20 + test_get_le32(glb + 12);
    for (size_t i = 20; i < end && i < len && n < 65536; i++) {
        if (glb[i] >= '0' && glb[i] <= '9') {
            at[n++] = i;
        }
    }
    *out = at;
    return n;
}

/* Load a mutated file: it fails cleanly or gives a mesh that keeps the
 * API's promises. */
static void
load_mutant(const char *path, const unsigned char *bytes, size_t len)
{
    CHECK(test_write_bytes(path, bytes, len));
    struct gltf_mesh m = {0};
    struct diag err = {0};
    if (gltf_load(path, &m, &err)) {
        check_invariants(&m);
    } else {
        CHECK(strcmp(err.file, path) == 0 && err.msg[0]);
    }
    gltf_free(&m);
}

/* Mutate a valid file: random bytes anywhere, and digits of the JSON for
 * other digits (valid JSON, wrong numbers: counts, offsets, indices). */
TEST(mutation_fuzz)
{
    REQUIRE_GLTF();
    struct meshgen_mesh mesh = meshgen_sphere(4, 5, 1, (const double[3]){0, 0, 0}, 0, 0);
    const char *orig = test_tmp_path("fuzz-orig.glb");
    struct meshgen_glb_options opts = {.index_type = MESHGEN_INDEX_UINT16};
    CHECK(meshgen_write_glb(&mesh, orig, &opts));
    meshgen_free(&mesh);
    size_t len;
    unsigned char *clean = (unsigned char *)test_read_file(orig, &len);
    unsigned char *bytes = malloc(len + 1);
    CHECK(clean && bytes);
    if (!clean || !bytes) {
        free(clean);
        free(bytes);
        return;
    }
    size_t *digits;
    size_t n_digits = json_digits(clean, len, &digits);
    struct rng r = rng_make(2024, 0);
    const char *path = test_tmp_path("fuzz.glb");
    for (int round = 0; round < 600; round++) {
        memcpy(bytes, clean, len);
        int edits = 1 + (int)(rng_next_u32(&r) % 3);
        for (int e = 0; e < edits; e++) {
            if (round % 2 == 0) {
                bytes[rng_next_u32(&r) % len] = (unsigned char)rng_next_u32(&r);
            } else {
                bytes[digits[rng_next_u32(&r) % n_digits]] =
                    (unsigned char)('0' + rng_next_u32(&r) % 10);
            }
        }
        load_mutant(path, bytes, len);
    }
    free(clean);
    free(bytes);
}

/* --- textures as their mean colour (gltf_textures.cc) --------------------- */

/* A triangle .glb whose material 0 is `material`, with images and textures
 * as `members` says. */
static const char *
textured_glb(const char *name, const char *material, const char *members)
{
    struct meshgen_mesh m = {0};
    static const double corners[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const unsigned tri[3] = {0, 1, 2};
    if (!meshgen_alloc(&m, 3, 1, false)) {
        return NULL;
    }
    memcpy(m.positions, corners, sizeof corners);
    memcpy(m.indices, tri, sizeof tri);
    struct meshgen_glb_options opts = {.material = material, .members = members};
    const char *path = test_tmp_path(name);
    bool ok = meshgen_write_glb(&m, path, &opts);
    meshgen_free(&m);
    return ok ? path : NULL;
}

#define TEXTURES(uri) "\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"" uri "\"}]"

TEST(base_colour_and_emissive_textures_are_their_mean)
{
    REQUIRE_GLTF();
    CHECK(test_write_texture("half.png", 4) && test_write_texture("quarter.png", 2));
    const char *both = textured_glb(
        "both.glb",
        "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}},"
        "\"emissiveTexture\":{\"index\":0},\"emissiveFactor\":[1,1,1]}",
        TEXTURES("half.png"));
    const char *quarter = textured_glb(
        "quarter.glb",
        "{\"emissiveTexture\":{\"index\":0},\"emissiveFactor\":[1,1,1]}",
        TEXTURES("quarter.png"));
    struct gltf_mesh m = {0};
    if (!both || !quarter || !load(both, &m)) {
        CHECK(false);
        return;
    }
    static const int codes[3] = {204, 102, 51};
    const struct gltf_material *g = &m.materials[0];
    CHECK(g->averaged == (GLTF_TEX_BASE_COLOR | GLTF_TEX_EMISSIVE));
    for (int c = 0; c < 3; c++) {
        /* Half the texels at the code's linear value: the mean is half of
         * it, not half of the code (an sRGB mean would be 2.2x too bright). */
        double want = test_srgb8_linear(codes[c]) / 2;
        CHECK_NEAR(g->base_color_mean[c], want, 1e-12);
        CHECK_NEAR(g->emissive_mean[c], want, 1e-12);
    }
    CHECK_NEAR(g->emissive_glow, 0.5, 0);
    CHECK(g->base_color_why[0] == 0 && g->emissive_why[0] == 0);
    gltf_free(&m);
    if (load(quarter, &m)) {
        CHECK_NEAR(m.materials[0].emissive_glow, 0.25, 0);
        CHECK_NEAR(m.materials[0].emissive_mean[0], test_srgb8_linear(204) / 4, 1e-12);
    }
    gltf_free(&m);
}

/* Bytes of a PNG's signature and header chunk stating width x height, and
 * nothing after it: the size is read, the image is never decoded. */
static bool
write_png_header(const char *name, uint32_t width, uint32_t height)
{
    unsigned char b[33] =
        {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R'};
    for (int i = 0; i < 4; i++) {
        b[16 + i] = (unsigned char)(width >> (24 - 8 * i));
        b[20 + i] = (unsigned char)(height >> (24 - 8 * i));
    }
    b[24] = 8; /* bit depth; colour type 0 and the rest 0; no CRC check is reached */
    return test_write_bytes(test_tmp_path(name), b, sizeof b);
}

TEST(textures_that_cannot_be_averaged_say_why)
{
    REQUIRE_GLTF();
    /* A JPEG's start, an APP0 segment and a frame header of 65535 x 65535. */
    static const unsigned char jpeg[] =
        {0xff, 0xd8, 0xff, 0xe0, 0, 4, 'J', 'F', 0xff, 0xc0, 0, 11, 8, 0xff, 0xff, 0xff, 0xff, 3};
    CHECK(write_png_header("huge.png", 100000, 100000));
    CHECK(test_write_bytes(test_tmp_path("huge.jpg"), jpeg, sizeof jpeg));
    CHECK(test_write_bytes(test_tmp_path("odd.gif"), "GIF89a", 6));
    CHECK(write_png_header("broken.png", 4, 4));

    static const struct {
        const char *uri, *why;
    } cases[] = {
        {"huge.png", "image 0 is 100000 x 100000, over the 67108864 texels averaged"},
        {"huge.jpg", "image 0 is 65535 x 65535, over the 67108864 texels averaged"},
        {"odd.gif", "image 0 is neither PNG nor JPEG"},
        {"broken.png", "image 0 could not be decoded"},
    };

    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char members[256];
        snprintf(members, sizeof members, TEXTURES("%s"), cases[i].uri);
        const char *path = textured_glb(
            "bad.glb",
            "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}",
            members);
        struct gltf_mesh m = {0};
        if (!path || !load(path, &m)) {
            CHECK_MSG(false, "%s", cases[i].uri);
            continue;
        }
        CHECK_MSG(
            m.materials[0].averaged == 0
                && strcmp(m.materials[0].base_color_why, cases[i].why) == 0,
            "%s: '%s'",
            cases[i].uri,
            m.materials[0].base_color_why);
        gltf_free(&m);
    }
}

TEST_MAIN(
    TEST_ENTRY(stub_message),
    TEST_ENTRY(free_zero_mesh),
    TEST_ENTRY(meshgen_sphere_closed),
    TEST_ENTRY(meshgen_sphere_1m),
    TEST_ENTRY(meshgen_other_closed_meshes),
    TEST_ENTRY(meshgen_subdivide_closed),
    TEST_ENTRY(meshgen_subdivide_open_with_normals),
    TEST_ENTRY(meshgen_terrain_faces_up),
    TEST_ENTRY(meshgen_random_degenerate),
    TEST_ENTRY(round_trip_uint32),
    TEST_ENTRY(round_trip_uint16_without_normals),
    TEST_ENTRY(non_indexed),
    TEST_ENTRY(translate_scale),
    TEST_ENTRY(rotation_matches_matrix),
    TEST_ENTRY(mirror_keeps_orientation),
    TEST_ENTRY(asset_bunny),
    TEST_ENTRY(asset_dragon),
    TEST_ENTRY(asset_buddha),
    TEST_ENTRY(generated_buddha),
    TEST_ENTRY(asset_box),
    TEST_ENTRY(asset_duck),
    TEST_ENTRY(asset_cornell_box),
    TEST_ENTRY(hand_made_triangle_loads),
    TEST_ENTRY(uint8_indices),
    TEST_ENTRY(empty_and_garbage),
    TEST_ENTRY(wrong_magic),
    TEST_ENTRY(truncated_glb),
    TEST_ENTRY(chunk_lengths_past_end),
    TEST_ENTRY(accessor_out_of_bounds),
    TEST_ENTRY(huge_counts),
    TEST_ENTRY(bad_indices),
    TEST_ENTRY(non_finite_positions),
    TEST_ENTRY(unsupported_features),
    TEST_ENTRY(bad_nodes),
    TEST_ENTRY(deep_node_tree),
    TEST_ENTRY(no_scenes_uses_root_nodes),
    TEST_ENTRY(interleaved_attributes),
    TEST_ENTRY(deeply_nested_json),
    TEST_ENTRY(bin_chunk_shared_once),
    TEST_ENTRY(instancing_total_limit),
    TEST_ENTRY(base_colour_and_emissive_textures_are_their_mean),
    TEST_ENTRY(textures_that_cannot_be_averaged_say_why),
    TEST_ENTRY(external_buffers_inside),
    TEST_ENTRY(external_buffers_outside),
    TEST_ENTRY(external_buffers_symlinks),
    TEST_ENTRY(memory_limit),
    TEST_ENTRY(json_memory_limit),
    TEST_ENTRY(data_uri),
    TEST_ENTRY(size_limit),
    TEST_ENTRY(mutation_fuzz))
