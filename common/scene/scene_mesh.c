/*
 * scene_mesh.c - the `mesh` statement: its transform (scale, then rotate,
 * then translate), the file name resolved against the scene's directory, the
 * glTF loader behind gltf.h, and the vertices and triangles appended to the
 * scene's one shared triangle list.  Without a `material` field each
 * primitive keeps its file's material (scene_gltf.c), and the triangles of
 * emissive ones become emitting triangles: area lights of triangle shape.
 */
#include "scene_parser.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "gltf.h"

#define MAX_PATH_CHARS 4096 /* a mesh path: the scene's directory and the file name */
#define DEG_TO_RAD (3.14159265358979323846 / 180.0)

/* A mesh's placement: p' = R (S p) + T, and for normals the inverse
 * transpose of R S, which is R S^-1 since R is a rotation. */
struct transform {
    double scale[3];
    double rotation[3][3];
    double offset[3];
};

/* Rodrigues' formula: counter-clockwise when the axis points at the viewer. */
static void
rotation(const double axis[3], double degrees, double r[3][3])
{
    double len = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    double x = axis[0] / len, y = axis[1] / len, z = axis[2] / len;
    double c = cos(degrees * DEG_TO_RAD), s = sin(degrees * DEG_TO_RAD), t = 1 - c;
    double m[3][3] = {
        {t * x * x + c, t * x * y - s * z, t * x * z + s * y},
        {t * x * y + s * z, t * y * y + c, t * y * z - s * x},
        {t * x * z - s * y, t * y * z + s * x, t * z * z + c},
    };
    memcpy(r, m, sizeof m);
}

static bool
make_transform(struct parser *p, const struct fields *fs, struct transform *xf)
{
    *xf = (struct transform){.scale = {1, 1, 1}, .rotation = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    const struct field_value *scale = scene_get(fs, "scale");
    const struct field_value *rotate = scene_get(fs, "rotate");
    const struct field_value *translate = scene_get(fs, "translate");
    for (int i = 0; i < 3; i++) {
        xf->scale[i] = scale ? scale->num[scale->n == 1 ? 0 : i] : 1;
        xf->offset[i] = translate ? translate->num[i] : 0;
    }
    if (rotate) {
        double axis[3] = {rotate->num[0], rotate->num[1], rotate->num[2]};
        double len = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
        if (!(len > 0) || !isfinite(len)) {
            return scene_fail(p, &rotate->key, "rotate axis must be non-zero");
        }
        rotation(axis, rotate->num[3], xf->rotation);
    }
    return true;
}

/* R v + offset as a vec3; false when a component is not a finite real. */
static bool
rotate_into(const struct transform *xf, const double v[3], const double offset[3], vec3 *out)
{
    double w[3];
    for (int i = 0; i < 3; i++) {
        const double *row = xf->rotation[i];
        w[i] = row[0] * v[0] + row[1] * v[1] + row[2] * v[2] + offset[i];
        if (!(fabs(w[i]) <= REAL_MAX)) {  // false for NaN too
            return false;
        }
    }
    *out = vec3_make((real)w[0], (real)w[1], (real)w[2]);
    return true;
}

static bool
transform_vertex(
    const struct transform *xf,
    const struct gltf_mesh *mesh,
    size_t i,
    vec3 *pos,
    vec3 *normal)
{
    static const double no_offset[3] = {0, 0, 0};
    double v[3], n[3];
    for (int k = 0; k < 3; k++) {
        v[k] = mesh->positions[3 * i + (size_t)k] * xf->scale[k];
        n[k] = mesh->normals ? mesh->normals[3 * i + (size_t)k] / xf->scale[k] : 0;
    }
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3 && len > 0; k++) {
        n[k] /= len;  // a zero normal (none given) stays zero
    }
    return rotate_into(xf, v, xf->offset, pos) && rotate_into(xf, n, no_offset, normal);
}

/* Triangle v0 v1 v2 of the scene's vertices as an emitting triangle: it
 * emits from the side of cross(v1 - v0, v2 - v0), glTF's front face (a
 * mirroring transform swaps two corners to keep it so).  One of zero area
 * emits nothing and is left out. */
static bool
append_emitter(
    struct parser *p,
    const struct token *at,
    const int v[3],
    bool mirrored,
    const struct file_surface *surface)
{
    struct scene *s = p->scene;
    vec3 p0 = s->positions[v[0]];
    vec3 e1 = vec3_sub(s->positions[v[mirrored ? 2 : 1]], p0);
    vec3 e2 = vec3_sub(s->positions[v[mirrored ? 1 : 2]], p0);
    struct area_light light = {
        .corner = p0,
        .edge1 = e1,
        .edge2 = e2,
        .radiance = surface->emission,
        .triangle = true,
        .two_sided = surface->two_sided,
        .loc = scene_loc_of(at),
    };
    real area = area_light_area(&light);
    return !(area > 0) || !isfinite(area) || scene_add_area_light(p, at, light);
}

/* The file's vertices, transformed, and its triangles: of `material`, or
 * (material < 0) of their own surfaces. */
static bool
append_mesh(
    struct parser *p,
    const struct token *at,
    const struct gltf_mesh *mesh,
    const struct transform *xf,
    int material,
    const struct file_surface *surfaces)
{
    struct scene *s = p->scene;
    if (!scene_room_for_mesh(p, at, mesh->n_vertices, mesh->n_triangles)) {
        return false;
    }
    bool mirrored = xf->scale[0] * xf->scale[1] * xf->scale[2] < 0;
    int n_triangles = s->n_triangles;
    for (size_t i = 0; i < mesh->n_vertices; i++) {
        size_t v = (size_t)s->n_vertices + i;
        if (!transform_vertex(xf, mesh, i, &s->positions[v], &s->normals[v])) {
            return scene_fail(p, at, "mesh vertex %zu is not finite once transformed", i);
        }
    }
    for (size_t i = 0; i < mesh->n_triangles; i++) {
        const struct file_surface *surface = NULL;
        if (material < 0) {
            int m = mesh->triangle_material[i];
            surface = &surfaces[m >= 0 ? (size_t)m : mesh->n_materials];
        }
        struct triangle tri = {
            .material = surface ? surface->material : material,
            .smooth = mesh->normals != NULL,
            .line = at->line,
        };
        for (int k = 0; k < 3; k++) {
            unsigned index = mesh->indices[3 * i + (size_t)k];
            if (index >= mesh->n_vertices) {
                return scene_fail(
                    p,
                    at,
                    "mesh triangle %zu uses vertex %u of %zu",
                    i,
                    index,
                    mesh->n_vertices);
            }
            tri.v[k] = s->n_vertices + (int)index;
            // Interpolating a missing (zero) vertex normal would give no normal.
            tri.smooth = tri.smooth && !vec3_is_zero(s->normals[tri.v[k]]);
        }
        if (tri.material >= 0) {
            s->triangles[n_triangles++] = tri;
        } else if (!append_emitter(p, at, tri.v, mirrored, surface)) {
            return false;
        }
    }
    s->n_vertices += (int)mesh->n_vertices;
    s->n_triangles = n_triangles;
    return true;
}

/* append_mesh with the file's own materials. */
static bool
append_with_surfaces(
    struct parser *p,
    const struct token *at,
    const char *file,
    const struct gltf_mesh *mesh,
    const struct transform *xf)
{
    struct file_surface *surfaces = NULL;
    if (!scene_map_file_materials(p, at, file, mesh, &surfaces)) {
        return false;
    }
    bool ok = append_mesh(p, at, mesh, xf, -1, surfaces);
    free(surfaces);
    return ok;
}

bool
scene_append_file_mesh(
    struct parser *p,
    const struct token *at,
    const char *file,
    const struct gltf_mesh *mesh)
{
    static const struct transform identity = {
        .scale = {1, 1, 1},
        .rotation = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
    };
    bool ok = append_with_surfaces(p, at, file, mesh, &identity);
    if (ok) {
        scene_use_feature(p, FEAT_MESH, at);
    }
    return ok;
}

/* The file token's text (quotes and escapes removed) into name, and the
 * path to open (relative to the scene file's directory) into path. */
static bool
mesh_path(struct parser *p, const struct token *t, char *name, char *path)
{
    size_t n = 0;
    size_t quoted = t->kind == TOK_STRING;
    for (size_t i = quoted; i < t->len - quoted && n < MAX_PATH_CHARS - 1; i++) {
        bool escape = quoted && t->text[i] == '\\';
        i += escape && (t->text[i + 1] == '"' || t->text[i + 1] == '\\');
        name[n++] = t->text[i];
    }
    name[n] = '\0';
    if (n == 0) {
        return scene_fail(p, t, "expected a file name after 'file', got an empty string");
    }
    const char *slash = strrchr(p->name, '/');
    int dir = name[0] == '/' || !slash ? 0 : (int)(slash - p->name + 1);
    if (n >= MAX_PATH_CHARS - 1 || (size_t)dir + n >= MAX_PATH_CHARS) {
        return scene_fail(p, t, "mesh path too long (at most %d bytes)", MAX_PATH_CHARS - 1);
    }
    memcpy(path, p->name, (size_t)dir);
    memcpy(path + dir, name, n + 1);
    return true;
}

/* Remember a file the scene read, so that the run can refuse to write
 * over it (output_check.h). */
static bool
note_input_file(struct parser *p, const struct token *t, const char *path)
{
    struct scene *s = p->scene;
    char **grown = realloc(s->input_files, (size_t)(s->n_input_files + 1) * sizeof *grown);
    char *copy = malloc(strlen(path) + 1);
    if (grown) {
        s->input_files = grown;
    }
    if (!grown || !copy) {
        free(copy);
        scene_fail(p, t, "out of memory for the name of '%s'", path);
        diag_mark_no_memory(p->err);
        return false;
    }
    memcpy(copy, path, strlen(path) + 1);
    s->input_files[s->n_input_files++] = copy;
    return true;
}

bool
scene_load_gltf_file(
    struct parser *p,
    const struct token *t,
    const char *name,
    const char *path,
    struct gltf_mesh *out)
{
    char lead[300] = "";
    if (name) {
        snprintf(lead, sizeof lead, "cannot load mesh '%.256s': ", name);
    }
    // Opened here first, so that a missing file reads the same with or without glTF.
    FILE *f = fopen(path, "rb");
    if (!f) {
        return scene_fail(p, t, "%scannot open: %s", lead, strerror(errno));
    }
    fclose(f);
    if (!gltf_available()) {
        const char *how = "this build has no glTF support: install libtinygltf-dev and rebuild";
        return scene_fail(p, t, "%s%s", lead, how);
    }
    struct diag gerr = {.line = 0};
    /* The mesh's own arrays count against what the scene has left; the
     * scene's copy of them is counted again by scene_grow(). */
    uint64_t left = p->max_bytes > p->bytes ? p->max_bytes - p->bytes : 0;
    if (!gltf_load_limited(path, left, out, &gerr)) {
        scene_fail(p, t, "%s%s", lead, gerr.msg);
        if (gerr.kind == DIAG_NO_MEMORY) {
            diag_mark_no_memory(p->err);
        }
        return false;
    }
    /* Its external buffers (and images) are inputs as the file is. */
    for (size_t i = 0; i < out->n_files; i++) {
        if (!note_input_file(p, t, out->files[i])) {
            gltf_free(out);
            return false;
        }
    }
    /* What of it no stage models (skins, animations, ...), a note each. */
    const char *slash = strrchr(path, '/');
    for (int i = 0; i < out->n_dropped; i++) {
        scene_add_note(
            p->scene,
            scene_loc_of(t),
            "%s: %s",
            name    ? name
            : slash ? slash + 1
                    : path,
            out->dropped[i]);
    }
    return true;
}

bool
scene_build_mesh(struct parser *p, const struct token *kw, struct fields *fs)
{
    int material = -1;
    struct transform xf;
    bool own_materials = !scene_get(fs, "material");
    if ((!own_materials && !scene_use_material(p, kw, fs, &material))
        || !make_transform(p, fs, &xf)) {
        return false;
    }
    const struct token *file = &scene_get(fs, "file")->val[0];
    char name[MAX_PATH_CHARS], path[MAX_PATH_CHARS];
    struct gltf_mesh mesh = {.n_vertices = 0};
    if (!mesh_path(p, file, name, path) || !scene_load_gltf_file(p, file, name, path, &mesh)) {
        return false;
    }
    if (mesh.n_lights > 0) {
        /* A scene's lights are its own statements; a file loaded as the
         * scene (render FILE.glb) is lit by them. */
        scene_add_note(
            p->scene,
            scene_loc_of(file),
            "%s: %zu KHR_lights_punctual light(s) not placed by a mesh line; ignored (render the "
            "file as the scene to light it by them)",
            name,
            mesh.n_lights);
    }
    bool ok = (own_materials ? append_with_surfaces(p, kw, name, &mesh, &xf)
                             : append_mesh(p, file, &mesh, &xf, material, NULL))
              && note_input_file(p, file, path);
    gltf_free(&mesh);
    if (ok) {
        scene_use_feature(p, FEAT_MESH, kw);
    }
    return ok;
}
