/*
 * scene.c - the loader of the scene text format (docs/scene-format.md): the
 * table of statements, the loop that reads them, and the public API.
 *
 * The whole file is read into memory and parsed in one pass.  A small lexer
 * hands out tokens (words, quoted strings, ends of line) with their line and
 * column; a table says which named fields each statement takes, how many
 * values each has and the range they must lie in; one builder per statement
 * checks what the table cannot and appends to the scene.  Every failure goes
 * through scene_fail(), which fills the diagnostic at a token and returns false:
 * the first error stops the load and scene_free() releases what was built.
 *
 * The loader's files, all sharing the parser state of scene_parser.h, in
 * layers: each calls only those listed before it (tests/common/layers.sh
 * checks that no file calls back up).
 *   scene_lexer.c      errors (fail, scene_show) and tokens
 *   scene_fields.c     values and named fields, checked against the table
 *   scene_store.c      the scene's arrays: growth, lights, features, scene_free()
 *   scene_materials.c  the material statement and shapes' material names
 *   scene_build.c      camera, image, colours, shapes and lights
 *   scene_gltf.c       glTF materials mapped, emitters, notes of what is dropped
 *   scene_mesh.c       mesh files: transforms and glTF meshes
 *   scene_gltf_file.c  a glTF file as the whole scene: camera, lights
 *   scene.c            (this file) statements, scene_load(): the dispatch
 */
#include "scene.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "scene_parser.h"

/* A scene file is hand-written text; the cap stops a wrong path (a video, a
 * disk image) from being read whole into memory. */
#define MAX_FILE_MIB 64
#define MAX_FILE_BYTES ((size_t)MAX_FILE_MIB << 20)

#define STRINGIFY(x) #x
#define TO_STRING(x) STRINGIFY(x)

/* --- Statements ----------------------------------------------------------- */

static const struct range range_nonnegative = {.lo = 0, .hi = REAL_MAX, .text = ">= 0"};
static const struct range range_fov =
    {.lo = 0, .hi = 180, .lo_open = true, .hi_open = true, .text = "in (0, 180) degrees"};
static const struct range range_not_zero =
    {.lo = -REAL_MAX, .hi = REAL_MAX, .not_zero = true, .text = "non-zero"};
static const struct range range_image = {
    .lo = 1,
    .hi = SCENE_MAX_IMAGE_DIM,
    .text = "in [1, " TO_STRING(SCENE_MAX_IMAGE_DIM) "] pixels"};

#define MATERIAL_REF \
    { \
        .name = "material", .kind = VAL_NAME, .arity = 1, .required = true \
    }

/* Every statement and its fields (an unused slot of `fields` ends the list). */
static const struct statement {
    const char *keyword;
    bool once; /* at most once per scene */
    bool required; /* at least once per scene */
    bool (*build)(struct parser *p, const struct token *kw, struct fields *fs);
    struct field_spec fields[MAX_FIELDS]; /* none: the statement reads its own (material) */
} statements[] = {
    {.keyword = "camera",
     .once = true,
     .required = true,
     .build = scene_build_camera,
     .fields =
         {NUMBERS("origin", 3, true, NULL),
          NUMBERS("target", 3, true, NULL),
          NUMBERS("up", 3, true, NULL),
          NUMBERS("fov", 1, true, &range_fov),
          NUMBERS("near", 1, false, &range_nonnegative)}},
    {.keyword = "image",
     .once = true,
     .required = true,
     .build = scene_build_image,
     .fields =
         {{.name = "width", .kind = VAL_INT, .arity = 1, .required = true, .range = &range_image},
          {.name = "height",
           .kind = VAL_INT,
           .arity = 1,
           .required = true,
           .range = &range_image}}},
    {.keyword = "background",
     .once = true,
     .build = scene_build_color,
     .fields = {NUMBERS("color", 3, true, &range_nonnegative)}},
    {.keyword = "ambient",
     .once = true,
     .build = scene_build_color,
     .fields = {NUMBERS("color", 3, true, &range_nonnegative)}},
    {.keyword = "material", .build = scene_parse_material},
    {.keyword = "sphere",
     .build = scene_build_sphere,
     .fields =
         {NUMBERS("center", 3, true, NULL),
          NUMBERS("radius", 1, true, &scene_range_positive),
          MATERIAL_REF}},
    {.keyword = "quad",
     .build = scene_build_quad,
     .fields =
         {NUMBERS("corner", 3, true, NULL),
          NUMBERS("edge1", 3, true, NULL),
          NUMBERS("edge2", 3, true, NULL),
          MATERIAL_REF}},
    {.keyword = "triangle",
     .build = scene_build_triangle,
     .fields =
         {NUMBERS("v0", 3, true, NULL),
          NUMBERS("v1", 3, true, NULL),
          NUMBERS("v2", 3, true, NULL),
          MATERIAL_REF}},
    {.keyword = "mesh",
     .build = scene_build_mesh,
     .fields =
         {{.name = "file", .kind = VAL_PATH, .arity = 1, .required = true},
          {.name = "material", .kind = VAL_NAME, .arity = 1},
          {.name = "scale", .kind = VAL_SCALE, .arity = 3, .range = &range_not_zero},
          NUMBERS("rotate", 4, false, NULL),
          NUMBERS("translate", 3, false, NULL)}},
    {.keyword = "point_light",
     .build = scene_build_point_light,
     .fields =
         {NUMBERS("position", 3, true, NULL), NUMBERS("intensity", 3, true, &range_nonnegative)}},
    {.keyword = "area_light",
     .build = scene_build_area_light,
     .fields =
         {NUMBERS("corner", 3, true, NULL),
          NUMBERS("edge1", 3, true, NULL),
          NUMBERS("edge2", 3, true, NULL),
          NUMBERS("radiance", 3, true, &range_nonnegative)}},
    {.keyword = "sphere_light",
     .build = scene_build_sphere_light,
     .fields =
         {NUMBERS("center", 3, true, NULL),
          NUMBERS("radius", 1, true, &scene_range_positive),
          NUMBERS("radiance", 3, true, &range_nonnegative)}},
};

#define N_STATEMENTS ((int)(sizeof statements / sizeof statements[0]))
_Static_assert(N_STATEMENTS <= MAX_STATEMENTS, "parser.seen is too small");

static bool
parse_statement(struct parser *p, const struct token *kw)
{
    int i = 0;
    while (i < N_STATEMENTS && !scene_token_is(kw, statements[i].keyword)) {
        i++;
    }
    if (i == N_STATEMENTS) {
        return scene_fail(p, kw, "unknown keyword %s", scene_show(kw).s);
    }
    const struct statement *st = &statements[i];
    if (st->once && p->seen[i].line) {
        int first = p->seen[i].line;
        return scene_fail(p, kw, "duplicate '%s' statement (first on line %d)", st->keyword, first);
    }
    p->seen[i] = p->seen[i].line ? p->seen[i] : scene_loc_of(kw);
    struct fields fs = {.spec = st->fields};
    snprintf(fs.context, sizeof fs.context, "'%s'", st->keyword);
    if (st->fields[0].name && !scene_read_fields(p, kw, &fs)) {
        return false;
    }
    return st->build(p, kw, &fs);
}

static bool
parse_scene(struct parser *p)
{
    struct token tok;
    do {
        if (!scene_next_token(p, &tok)) {
            return false;
        }
        if (tok.kind == TOK_WORD || tok.kind == TOK_STRING) {
            if (!parse_statement(p, &tok)) {
                return false;
            }
        }
    } while (tok.kind != TOK_EOF);
    for (int i = 0; i < N_STATEMENTS; i++) {
        if (statements[i].required && !p->seen[i].line) {
            return scene_fail(p, &tok, "missing '%s' statement", statements[i].keyword);
        }
    }
    return true;
}

/* --- Public --------------------------------------------------------------- */

/* The whole file, up to MAX_FILE_BYTES, into *out (free it).  A regular
 * file is refused by its size before any of it is read; a pipe or a device
 * is read up to one byte past the cap. */
static bool
read_file(const char *path, char **out, size_t *len, struct diag *err)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        diag_set(err, path, 0, 0, "cannot open: %s", strerror(errno));
        return false;
    }
    struct stat st;
    if (fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode)
        && (uint64_t)st.st_size > MAX_FILE_BYTES) {
        diag_set(
            err,
            path,
            0,
            0,
            "too large for a scene file (%llu MiB, over %d MiB)",
            (unsigned long long)(st.st_size >> 20),
            MAX_FILE_MIB);
        fclose(f);
        return false;
    }
    size_t cap = (size_t)1 << 16;
    size_t n = 0;
    char *text = NULL;
    for (;;) {  // up to one byte past the cap, to see that the cap is passed
        char *grown = realloc(text, cap);
        if (!grown) {
            diag_set(
                err,
                path,
                0,
                0,
                "out of memory: the system refused %zu bytes for the text",
                cap);
            diag_mark_no_memory(err);
            goto fail;
        }
        text = grown;
        n += fread(text + n, 1, cap - n, f);
        if (n < cap || cap > MAX_FILE_BYTES) {
            break;
        }
        cap = cap * 2 > MAX_FILE_BYTES ? MAX_FILE_BYTES + 1 : cap * 2;
    }
    if (ferror(f)) {
        diag_set(err, path, 0, 0, "cannot read: %s", strerror(errno));
        goto fail;
    }
    if (n > MAX_FILE_BYTES) {
        diag_set(err, path, 0, 0, "too large for a scene file (over %d MiB)", MAX_FILE_MIB);
        goto fail;
    }
    fclose(f);
    *out = text;
    *len = n;
    return true;
fail:
    free(text);
    fclose(f);
    return false;
}

/* The text of a scene, parsed with its arrays limited to max_bytes. */
static bool
load_text(
    const char *text,
    size_t len,
    const char *name,
    uint64_t max_bytes,
    struct scene *out,
    struct diag *err)
{
    *out = (struct scene){.width = 0};
    name = name ? name : "<string>";
    snprintf(out->path, sizeof out->path, "%s", name);
    struct parser p = {.src = text ? text : "", .len = text ? len : 0, .line = 1, .col = 1};
    /* The UTF-8 byte-order mark some editors put at the start of a file is
     * no part of the scene, and no column. */
    if (p.len >= 3 && memcmp(p.src, "\xEF\xBB\xBF", 3) == 0) {
        p.pos = 3;
    }
    p.name = name;
    p.scene = out;
    p.err = err;
    p.max_bytes = max_bytes;
    if (!parse_scene(&p)) {
        scene_free(out);
        return false;
    }
    return true;
}

bool
scene_load_with(
    const char *path,
    const struct scene_options *opt,
    struct scene *out,
    struct diag *err)
{
    const char *camera = opt ? opt->camera : NULL;
    uint64_t max_bytes = opt && opt->max_bytes ? opt->max_bytes : SCENE_DEFAULT_MAX_BYTES;
    if (scene_path_is_gltf(path)) {
        return scene_load_gltf(path, camera, max_bytes, out, err);
    }
    *out = (struct scene){.width = 0};
    if (camera) {
        diag_set(err, path, 0, 0, "--camera chooses a camera of a glTF scene (.glb, .gltf)");
        return false;
    }
    char *text = NULL;
    size_t len = 0;
    if (!read_file(path, &text, &len, err)) {
        return false;
    }
    bool ok = load_text(text, len, path, max_bytes, out, err);
    free(text);
    return ok;
}

bool
scene_load_limited(const char *path, uint64_t max_bytes, struct scene *out, struct diag *err)
{
    const struct scene_options opt = {.max_bytes = max_bytes};
    return scene_load_with(path, &opt, out, err);
}

bool
scene_load(const char *path, struct scene *out, struct diag *err)
{
    return scene_load_with(path, NULL, out, err);
}

bool
scene_load_string(
    const char *text,
    size_t len,
    const char *name,
    struct scene *out,
    struct diag *err)
{
    return load_text(text, len, name, SCENE_DEFAULT_MAX_BYTES, out, err);
}
