/*
 * scene_parser.h - the scene loader's internal state, shared by its files
 * (scene.c lists them); not part of the core's API, which is scene.h.
 *
 * A parser walks one scene text; tokens point into that text.  Each
 * statement's named fields are described by field_spec tables (the
 * statements' in scene.c, the material kinds' in scene_materials.c), read
 * into a struct fields, then handed to the statement's builder.  Every
 * function that can fail returns false after scene_fail() has filled the diag.
 */
#ifndef SCENE_PARSER_H
#define SCENE_PARSER_H

#include "scene.h"

#define MAX_FIELDS 6 /* the most fields a statement has (mesh: 5) */
#define MAX_VALUES 4 /* the most values a field has (rotate: axis and angle) */
#define MAX_STATEMENTS 16
#define MAX_SHOWN 40 /* messages quote at most this many bytes of a token */

enum token_kind {
    TOK_WORD,
    TOK_STRING, /* "quoted": file names with spaces */
    TOK_EOL,
    TOK_EOF,
};

struct token {
    enum token_kind kind;
    const char *text; /* in the source; a string's text includes its quotes */
    size_t len;
    int line, col;
};

enum value_kind {
    VAL_NUMBERS, /* `arity` real numbers */
    VAL_SCALE, /* 1 or 3 real numbers */
    VAL_INT, /* one integer */
    VAL_NAME, /* one word: a material's name */
    VAL_PATH, /* one word or quoted string: a file name */
};

/* Each value must lie in [lo, hi] (an end excluded when open) and, with
 * not_zero, differ from 0; `text` says so in messages. */
struct range {
    double lo, hi;
    bool lo_open, hi_open, not_zero;
    const char *text;
};

struct field_spec {
    const char *name;
    enum value_kind kind;
    int arity;
    bool required;
    const struct range *range; /* NULL: any finite value */
};

/* A field as written: its name token, its value tokens and their values. */
struct field_value {
    const struct field_spec *spec; /* NULL: not given */
    struct token key;
    struct token val[MAX_VALUES];
    real num[MAX_VALUES];
    long integer; /* VAL_INT */
    int n;
};

struct fields {
    const struct field_spec *spec; /* ends with a NULL name */
    char context[96]; /* "'sphere'", "diffuse material 'white'" */
    struct field_value v[MAX_FIELDS];
};

struct parser {
    const char *src;
    size_t len, pos;
    int line, col;
    const char *name; /* file name in diagnostics; meshes are relative to it */
    struct scene *scene;
    struct diag *err;
    struct src_loc seen[MAX_STATEMENTS]; /* first use of each statement */

    struct {
        int materials, spheres, quads, positions, normals, triangles, points, areas, sphere_lights;
    } cap;

    uint64_t bytes; /* held by the scene's arrays (their capacities) */
    uint64_t max_bytes; /* the most they may hold (scene_load_limited) */
};

/* --- Errors and tokens (scene_lexer.c) ------------------------------------ */

bool scene_fail(struct parser *p, const struct token *at, const char *fmt, ...) DIAG_PRINTF(3, 4);

/* A token as messages quote it: 'text' (cut when long) or "end of line".
 * Returned by value so that scene_show(&t).s can be a scene_fail() argument. */
struct shown {
    char s[MAX_SHOWN + 8];
};

struct shown scene_show(const struct token *t);
bool scene_token_is(const struct token *t, const char *word);
struct src_loc scene_loc_of(const struct token *t);

/* The next token: comments are skipped, each line ends with a TOK_EOL and
 * the text with a TOK_EOF (returned again by every later call). */
bool scene_next_token(struct parser *p, struct token *tok);
/* The next token, leaving the parser where it was. */
bool scene_peek_token(struct parser *p, struct token *tok);

/* --- Fields (scene_fields.c) ---------------------------------------------- */

#define NUMBERS(n, count, req, limits) \
    { \
        .name = n, .kind = VAL_NUMBERS, .arity = count, .required = req, .range = limits \
    }

extern const struct range scene_range_positive; /* > 0 */

/* Named fields up to the end of the line, each at most once and its values
 * in range; then every required field must have been given. */
bool scene_read_fields(struct parser *p, const struct token *kw, struct fields *fs);
/* The field called name as given, or NULL when it was not. */
const struct field_value *scene_get(const struct fields *fs, const char *name);
/* A given field of three numbers as a vec3. */
vec3 scene_vec_of(const struct fields *fs, const char *name);

/* --- The scene's arrays (scene_store.c) ---------------------------------- */

/* Record that the scene uses feature f, first at kw. */
void scene_use_feature(struct parser *p, enum feature f, const struct token *kw);
/* Room for `need` items in an array of capacity *cap: the (possibly moved)
 * array, or NULL with the diag set (the old array is still owned by the
 * scene). */
void *
scene_grow(struct parser *p, const struct token *at, void *items, int need, int *cap, size_t size);
/* Room for n more vertices and m more triangles. */
bool scene_room_for_mesh(struct parser *p, const struct token *at, size_t n, size_t m);
/* Append a light and record its feature. */
bool scene_add_point_light(struct parser *p, const struct token *kw, struct point_light light);
bool scene_add_area_light(struct parser *p, const struct token *kw, struct area_light light);

/* --- Building the scene (scene_build.c, scene_materials.c, scene_mesh.c) -- */

/* The shape's `material` field: its index, and the feature its kind needs. */
bool
scene_use_material(struct parser *p, const struct token *kw, const struct fields *fs, int *out);

/* The statements' builders: kw is the keyword, fs the fields read for it
 * (scene_parse_material reads its own, since its kind decides which follow). */
bool scene_parse_material(struct parser *p, const struct token *kw, struct fields *fs);
bool scene_build_camera(struct parser *p, const struct token *kw, struct fields *fs);
bool scene_build_image(struct parser *p, const struct token *kw, struct fields *fs);
bool scene_build_color(struct parser *p, const struct token *kw, struct fields *fs);
bool scene_build_sphere(struct parser *p, const struct token *kw, struct fields *fs);
bool scene_build_quad(struct parser *p, const struct token *kw, struct fields *fs);
bool scene_build_triangle(struct parser *p, const struct token *kw, struct fields *fs);
bool scene_build_mesh(struct parser *p, const struct token *kw, struct fields *fs);
bool scene_build_point_light(struct parser *p, const struct token *kw, struct fields *fs);
bool scene_build_area_light(struct parser *p, const struct token *kw, struct fields *fs);
bool scene_build_sphere_light(struct parser *p, const struct token *kw, struct fields *fs);

/* --- glTF files (scene_gltf.c, scene_mesh.c, scene_gltf_file.c) ----------- */

struct gltf_mesh;

/* What a material of a glTF file became in the scene. */
struct file_surface {
    int material; /* the scene material; -1 for an emitter */
    vec3 emission; /* an emitter's radiance */
    bool two_sided; /* an emitter's doubleSided */
};

/* Add a note to the scene (at most SCENE_MAX_NOTES; the last says more
 * were left out). */
void scene_add_note(struct scene *s, struct src_loc at, const char *fmt, ...) DIAG_PRINTF(3, 4);

/* Map the materials the mesh's triangles use onto scene materials and
 * emitters, and note what they drop (one note per kind).  *out gets one
 * entry per glTF material and one more, last, for glTF's default material
 * (free it). */
bool scene_map_file_materials(
    struct parser *p,
    const struct token *at,
    const char *file,
    const struct gltf_mesh *mesh,
    struct file_surface **out);

/* Load the glTF file at path (named `name` in messages: "cannot load mesh
 * 'NAME': ..."; NULL when the file is the scene itself, which the message's
 * location already names) into *out; the files the load read besides it
 * (external buffers, images) join the scene's input_files. */
bool scene_load_gltf_file(
    struct parser *p,
    const struct token *at,
    const char *name,
    const char *path,
    struct gltf_mesh *out);

/* Append a loaded file as it stands (no transform) with its own
 * materials and emitters. */
bool scene_append_file_mesh(
    struct parser *p,
    const struct token *at,
    const char *file,
    const struct gltf_mesh *mesh);

/* A glTF file as the whole scene (scene_gltf_file.c). */
bool scene_path_is_gltf(const char *path);
bool scene_load_gltf(
    const char *path,
    const char *camera,
    uint64_t max_bytes,
    struct scene *out,
    struct diag *err);

#endif /* SCENE_PARSER_H */
