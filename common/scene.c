/*
 * scene.c - the loader of the scene text format (docs/scene-format.md).
 *
 * The whole file is read into memory and parsed in one pass.  A small lexer
 * hands out tokens (words, quoted strings, ends of line) with their line and
 * column; a table says which named fields each statement takes, how many
 * values each has and the range they must lie in; one builder per statement
 * checks what the table cannot and appends to the scene.  Every failure goes
 * through fail(), which fills the diagnostic at a token and returns false:
 * the first error stops the load and scene_free() releases what was built.
 */
#include "scene.h"

#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "gltf.h"

/* A scene file is hand-written text; the cap stops a wrong path (a video, a
 * disk image) from being read whole into memory. */
#define MAX_FILE_MIB 64
#define MAX_FILE_BYTES ((size_t)MAX_FILE_MIB << 20)

#define MAX_FIELDS 6 /* the most fields a statement has (mesh: 5) */
#define MAX_VALUES 4 /* the most values a field has (rotate: axis and angle) */
#define MAX_STATEMENTS 16
#define MAX_NUMBER_CHARS 64 /* a longer token is no number anyone writes */
#define MAX_SHOWN 40 /* messages quote at most this many bytes of a token */
#define MAX_LISTED 6 /* material names listed by "unknown material" */
#define MAX_PATH_CHARS 4096 /* a mesh path: the scene's directory and the file name */
#define TAB_WIDTH 8 /* GNU columns: a tab moves to the next multiple of 8, plus 1 */

/* Below this sine of the angle between up and the view direction the
 * camera's basis (built from their cross product) is numerically noise. */
#define MIN_UP_SINE 1e-6

#define DEG_TO_RAD (3.14159265358979323846 / 180.0)
#define STRINGIFY(x) #x
#define TO_STRING(x) STRINGIFY(x)

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
        int materials, spheres, quads, positions, normals, triangles, points, areas;
    } cap;
};

static bool fail(struct parser *p, const struct token *at, const char *fmt, ...) DIAG_PRINTF(3, 4);

static bool
fail(struct parser *p, const struct token *at, const char *fmt, ...)
{
    char msg[sizeof p->err->msg];  // sizeof does not evaluate: p->err may be NULL
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    diag_set(p->err, p->name, at->line, at->col, "%s", msg);
    return false;
}

/* A token as messages quote it: 'text' (cut when long) or "end of line".
 * Returned by value so that show(&t).s can be a fail() argument. */
struct shown {
    char s[MAX_SHOWN + 8];
};

static struct shown
show(const struct token *t)
{
    struct shown out;
    if (t->kind == TOK_EOL || t->kind == TOK_EOF) {
        snprintf(out.s, sizeof out.s, "end of line");
        return out;
    }
    size_t n = t->len;
    const char *more = "";
    if (n > MAX_SHOWN) {
        n = MAX_SHOWN;
        while (n > 0 && ((unsigned char)t->text[n] & 0xc0) == 0x80) {
            n--;  // do not cut a UTF-8 character in two
        }
        more = "...";
    }
    snprintf(out.s, sizeof out.s, "'%.*s%s'", (int)n, t->text, more);
    return out;
}

static bool
token_is(const struct token *t, const char *word)
{
    return t->kind == TOK_WORD && strlen(word) == t->len && memcmp(t->text, word, t->len) == 0;
}

static struct src_loc
loc_of(const struct token *t)
{
    return (struct src_loc){.line = t->line, .col = t->col};
}

/* --- Lexer ---------------------------------------------------------------- */

static struct token
here(const struct parser *p)
{
    return (struct token){.text = p->src + p->pos, .line = p->line, .col = p->col};
}

/* Bytes in the character at p->pos: 1 for a tab or printable ASCII, 2 to 4
 * for valid UTF-8, 0 for anything a text file should not hold. */
static int
char_bytes(const struct parser *p)
{
    const unsigned char *s = (const unsigned char *)p->src + p->pos;
    unsigned c = s[0];
    if (c == '\t' || (c >= 0x20 && c < 0x7f)) {
        return 1;
    }
    int n = c >= 0xf0 ? 4 : c >= 0xe0 ? 3 : 2;
    if (c < 0xc2 || c > 0xf4 || (size_t)n > p->len - p->pos) {
        return 0;
    }
    unsigned cp = c & (0x7fu >> n);
    for (int i = 1; i < n; i++) {
        if ((s[i] & 0xc0) != 0x80) {
            return 0;
        }
        cp = cp << 6 | (s[i] & 0x3fu);
    }
    static const unsigned min_cp[5] = {0, 0, 0x80, 0x800, 0x10000};  // below: overlong
    bool surrogate = cp >= 0xd800 && cp <= 0xdfff;
    return cp < min_cp[n] || cp > 0x10ffff || surrogate ? 0 : n;
}

/* Step over one character; the column counts characters, not bytes. */
static bool
advance(struct parser *p)
{
    int n = char_bytes(p);
    if (n == 0) {
        struct token at = here(p);
        return fail(p, &at, "unexpected byte 0x%02x", (unsigned char)p->src[p->pos]);
    }
    bool tab = p->src[p->pos] == '\t';
    p->col = tab ? ((p->col - 1) / TAB_WIDTH + 1) * TAB_WIDTH + 1 : p->col + 1;
    p->pos += (size_t)n;
    return true;
}

static bool
at_line_end(const struct parser *p)
{
    size_t i = p->pos;
    if (i == p->len) {
        return true;
    }
    return p->src[i] == '\n' || (p->src[i] == '\r' && (i + 1 == p->len || p->src[i + 1] == '\n'));
}

/* A word ends at a space, a tab, a comment or the end of the line. */
static bool
at_word_end(const struct parser *p)
{
    return at_line_end(p) || p->src[p->pos] == ' ' || p->src[p->pos] == '\t'
           || p->src[p->pos] == '#';
}

static bool
lex_string(struct parser *p, struct token *tok)
{
    tok->kind = TOK_STRING;
    advance(p);
    for (;;) {
        if (at_line_end(p)) {
            return fail(p, tok, "unterminated quoted string");
        }
        const char *c = p->src + p->pos;
        if (c[0] == '"') {
            break;
        }
        bool escape = c[0] == '\\' && p->pos + 1 < p->len && (c[1] == '"' || c[1] == '\\');
        if ((escape && !advance(p)) || !advance(p)) {
            return false;
        }
    }
    advance(p);
    tok->len = (size_t)(p->src + p->pos - tok->text);
    struct token after = here(p);
    return at_word_end(p) || fail(p, &after, "expected a space after the closing quote");
}

static bool
lex_word(struct parser *p, struct token *tok)
{
    tok->kind = TOK_WORD;
    while (!at_word_end(p)) {
        if (p->src[p->pos] == '"') {
            struct token at = here(p);
            return fail(p, &at, "unexpected '\"' inside a word (quote the whole file name)");
        }
        if (!advance(p)) {
            return false;
        }
    }
    tok->len = (size_t)(p->src + p->pos - tok->text);
    return true;
}

/* The next token: comments are skipped, each line ends with a TOK_EOL and
 * the text with a TOK_EOF (returned again by every later call). */
static bool
next_token(struct parser *p, struct token *tok)
{
    while (p->pos < p->len && (p->src[p->pos] == ' ' || p->src[p->pos] == '\t')) {
        advance(p);
    }
    while (p->pos < p->len && p->src[p->pos] == '#' && !at_line_end(p)) {
        do {
            if (!advance(p)) {  // a comment, too, must be text
                return false;
            }
        } while (!at_line_end(p));
    }
    *tok = here(p);
    if (p->pos == p->len) {
        tok->kind = TOK_EOF;
        return true;
    }
    if (at_line_end(p)) {
        tok->kind = TOK_EOL;
        p->pos += p->src[p->pos] == '\r' ? 1 : 0;
        p->pos += p->pos < p->len ? 1 : 0;
        p->line++;
        p->col = 1;
        return true;
    }
    return p->src[p->pos] == '"' ? lex_string(p, tok) : lex_word(p, tok);
}

static bool
peek_token(struct parser *p, struct token *tok)
{
    size_t pos = p->pos;
    int line = p->line;
    int col = p->col;
    bool ok = next_token(p, tok);
    p->pos = pos;
    p->line = line;
    p->col = col;
    return ok;
}

/* --- Values --------------------------------------------------------------- */

enum number_status {
    NUMBER_OK,
    NUMBER_BAD,
    NUMBER_NOT_FINITE,
    NUMBER_OUT_OF_RANGE,
};

static bool
equals_nocase(const char *s, size_t n, const char *lower)
{
    size_t i = 0;
    while (i < n && lower[i]
           && (s[i] >= 'A' && s[i] <= 'Z' ? s[i] - 'A' + 'a' : s[i]) == lower[i]) {
        i++;
    }
    return i == n && !lower[i];
}

/* nan, inf, infinity, nan(...), any case, signed or not. */
static bool
names_non_finite(const struct token *t)
{
    size_t sign = t->len > 0 && (t->text[0] == '+' || t->text[0] == '-');
    const char *s = t->text + sign;
    size_t n = t->len - sign;
    bool nan_payload = n > 4 && equals_nocase(s, 4, "nan(") && s[n - 1] == ')';
    return equals_nocase(s, n, "inf") || equals_nocase(s, n, "infinity")
           || equals_nocase(s, n, "nan") || nan_payload;
}

/* strtod, decimal only (alone it would take hex floats, nan and inf), the
 * whole token consumed and the value representable as a real. */
static enum number_status
to_number(const struct token *t, real *out)
{
    char buf[MAX_NUMBER_CHARS + 1];
    if (t->kind != TOK_WORD) {
        return NUMBER_BAD;
    }
    if (names_non_finite(t)) {
        return NUMBER_NOT_FINITE;
    }
    if (t->len > MAX_NUMBER_CHARS) {
        return NUMBER_BAD;
    }
    memcpy(buf, t->text, t->len);
    buf[t->len] = '\0';
    char *end;
    errno = 0;
    double d = strtod(buf, &end);
    if (strspn(buf, "0123456789+-.eE") != t->len || end != buf + t->len) {
        return NUMBER_BAD;
    }
    // Checked before the conversion: a double beyond float's range is UB there.
    if (errno == ERANGE || fabs(d) > REAL_MAX || (d != 0 && (real)d == 0)) {
        return NUMBER_OUT_OF_RANGE;
    }
    *out = (real)d;
    return NUMBER_OK;
}

static enum number_status
to_integer(const struct token *t, long *out)
{
    char buf[MAX_NUMBER_CHARS + 1];
    size_t sign = t->len > 0 && (t->text[0] == '+' || t->text[0] == '-');
    if (t->kind != TOK_WORD || t->len == sign || t->len > MAX_NUMBER_CHARS) {
        return NUMBER_BAD;
    }
    memcpy(buf, t->text, t->len);
    buf[t->len] = '\0';
    if (strspn(buf + sign, "0123456789") != t->len - sign) {
        return NUMBER_BAD;
    }
    errno = 0;
    *out = strtol(buf, NULL, 10);
    return errno == ERANGE ? NUMBER_OUT_OF_RANGE : NUMBER_OK;
}

static bool
read_number(struct parser *p, struct field_value *v)
{
    struct token t;
    real x = 0;
    if (!next_token(p, &t)) {
        return false;
    }
    enum number_status status = to_number(&t, &x);
    if (status == NUMBER_OUT_OF_RANGE) {
        return fail(p, &t, "number %s is out of range", show(&t).s);
    }
    if (status != NUMBER_OK) {
        // "a number", "3 finite numbers", "1 or 3 numbers" (the first value of scale)
        static const char *const counts[] = {"1 or 3", "a", "2", "3", "4"};
        int n = v->spec->kind != VAL_SCALE ? v->spec->arity : v->n == 0 ? 0 : 3;
        const char *finite = status == NUMBER_NOT_FINITE ? " finite" : "";
        return fail(
            p,
            &t,
            "expected %s%s number%s after '%s', got %s",
            counts[n],
            finite,
            n == 1 ? "" : "s",
            v->spec->name,
            show(&t).s);
    }
    v->val[v->n] = t;
    v->num[v->n++] = x;
    return true;
}

/* `scale S` or `scale SX SY SZ`: whether a number-like token follows decides. */
static bool
read_scale(struct parser *p, struct field_value *v)
{
    struct token next;
    real ignored;
    if (!read_number(p, v) || !peek_token(p, &next)) {
        return false;
    }
    if (to_number(&next, &ignored) == NUMBER_BAD) {
        return true;
    }
    return read_number(p, v) && read_number(p, v);
}

static bool
read_integer(struct parser *p, struct field_value *v)
{
    struct token t;
    if (!next_token(p, &t)) {
        return false;
    }
    enum number_status status = to_integer(&t, &v->integer);
    if (status == NUMBER_BAD) {
        return fail(p, &t, "expected an integer after '%s', got %s", v->spec->name, show(&t).s);
    }
    if (status == NUMBER_OUT_OF_RANGE) {
        v->integer = t.text[0] == '-' ? LONG_MIN : LONG_MAX;  // fails the range check
    }
    v->val[v->n++] = t;
    return true;
}

static bool
read_word(struct parser *p, struct field_value *v)
{
    struct token t;
    if (!next_token(p, &t)) {
        return false;
    }
    bool is_path = v->spec->kind == VAL_PATH;
    if (t.kind != TOK_WORD && !(is_path && t.kind == TOK_STRING)) {
        const char *want = is_path ? "a file name" : "a material name";
        return fail(p, &t, "expected %s after '%s', got %s", want, v->spec->name, show(&t).s);
    }
    v->val[v->n++] = t;
    return true;
}

static bool
read_values(struct parser *p, struct field_value *v)
{
    switch (v->spec->kind) {
    case VAL_NUMBERS:
        for (int i = 0; i < v->spec->arity; i++) {
            if (!read_number(p, v)) {
                return false;
            }
        }
        return true;
    case VAL_SCALE:
        return read_scale(p, v);
    case VAL_INT:
        return read_integer(p, v);
    case VAL_NAME:
    case VAL_PATH:
        return read_word(p, v);
    }
    return false;
}

static bool
check_range(struct parser *p, const struct field_value *v)
{
    const struct range *r = v->spec->range;
    for (int i = 0; r && i < v->n; i++) {
        double x = v->spec->kind == VAL_INT ? (double)v->integer : (double)v->num[i];
        bool above = r->lo_open ? x > r->lo : x >= r->lo;
        bool below = r->hi_open ? x < r->hi : x <= r->hi;
        if (!above || !below || (r->not_zero && x == 0)) {
            const struct token *t = &v->val[i];
            const char *each = v->n > 1 ? " per component" : "";
            const char *name = v->spec->name;
            int len = (int)t->len;
            return fail(p, t, "%s must be %s%s, got %.*s", name, r->text, each, len, t->text);
        }
    }
    return true;
}

/* --- Fields --------------------------------------------------------------- */

static bool
unknown_field(
    struct parser *p,
    const struct fields *fs,
    const struct token *t,
    const struct field_value *last)
{
    real ignored;
    bool numeric = last && last->spec->kind != VAL_NAME && last->spec->kind != VAL_PATH;
    if (numeric && to_number(t, &ignored) != NUMBER_BAD) {
        char count[16] = "1 or 3";
        if (last->spec->kind != VAL_SCALE) {
            snprintf(count, sizeof count, "%d", last->spec->arity);
        }
        return fail(p, t, "too many numbers after '%s', expected %s", last->spec->name, count);
    }
    char list[160] = "";  // "center, radius or material"
    size_t used = 0;
    for (int i = 0; fs->spec[i].name && used < sizeof list; i++) {
        const char *sep = i == 0 ? "" : fs->spec[i + 1].name ? ", " : " or ";
        used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", sep, fs->spec[i].name);
    }
    return fail(p, t, "unknown field %s in %s (expected %s)", show(t).s, fs->context, list);
}

/* Named fields up to the end of the line, each at most once and its values
 * in range; then every required field must have been given. */
static bool
read_fields(struct parser *p, const struct token *kw, struct fields *fs)
{
    const struct field_value *last = NULL;
    struct token t;
    while (next_token(p, &t)) {
        if (t.kind == TOK_EOL || t.kind == TOK_EOF) {
            for (const struct field_spec *f = fs->spec; f->name; f++) {
                if (f->required && !fs->v[f - fs->spec].spec) {
                    return fail(p, kw, "missing field '%s' in %s", f->name, fs->context);
                }
            }
            return true;
        }
        int i = 0;
        while (fs->spec[i].name && !token_is(&t, fs->spec[i].name)) {
            i++;
        }
        if (!fs->spec[i].name) {
            return unknown_field(p, fs, &t, last);
        }
        struct field_value *v = &fs->v[i];
        if (v->spec) {
            return fail(p, &t, "duplicate field %s in %s", show(&t).s, fs->context);
        }
        *v = (struct field_value){.spec = &fs->spec[i], .key = t};
        if (!read_values(p, v) || !check_range(p, v)) {
            return false;
        }
        last = v;
    }
    return false;
}

static const struct field_value *
get(const struct fields *fs, const char *name)
{
    for (int i = 0; fs->spec[i].name; i++) {
        if (strcmp(fs->spec[i].name, name) == 0) {
            return fs->v[i].spec ? &fs->v[i] : NULL;
        }
    }
    return NULL;
}

static vec3
vec_of(const struct fields *fs, const char *name)
{
    const struct field_value *v = get(fs, name);
    return vec3_make(v->num[0], v->num[1], v->num[2]);
}

/* --- Scene building ------------------------------------------------------- */

static void
use_feature(struct parser *p, enum feature f, const struct token *kw)
{
    if (!(p->scene->features & FEATURE_BIT(f))) {
        p->scene->features |= FEATURE_BIT(f);
        p->scene->feature_loc[f] = loc_of(kw);
    }
}

/* Room for `need` items in an array of capacity *cap: the (possibly moved)
 * array, or NULL with the diag set (the old array is still owned by the
 * scene).  A statement adds one item, and a 64 MiB file holds far fewer
 * than INT_MAX statements; meshes check their counts before they come. */
static void *
grow(struct parser *p, const struct token *at, void *items, int need, int *cap, size_t size)
{
    if (need <= *cap) {
        return items;
    }
    int new_cap = *cap < 16 ? 16 : *cap;
    while (new_cap < need) {
        new_cap = new_cap > INT_MAX / 2 ? INT_MAX : new_cap * 2;
    }
    void *grown = NULL;
    if ((size_t)new_cap <= SIZE_MAX / size) {
        grown = realloc(items, (size_t)new_cap * size);
    }
    if (!grown) {
        fail(p, at, "out of memory");
        return NULL;
    }
    *cap = new_cap;
    return grown;
}

static int
find_material(const struct scene *s, const struct token *name)
{
    for (int i = 0; i < s->n_materials; i++) {
        if (token_is(name, s->materials[i].name)) {
            return i;
        }
    }
    return -1;
}

static bool
unknown_material(struct parser *p, const struct token *name)
{
    const struct scene *s = p->scene;
    char list[MAX_LISTED * (SCENE_MAX_NAME + 2) + 8] = "";
    size_t used = 0;
    for (int i = 0; i < s->n_materials && i < MAX_LISTED; i++) {
        const char *sep = i ? ", " : "";
        used +=
            (size_t)snprintf(list + used, sizeof list - used, "%s%s", sep, s->materials[i].name);
    }
    if (s->n_materials == 0) {
        return fail(p, name, "unknown material %s (none is defined before it)", show(name).s);
    }
    const char *more = s->n_materials > MAX_LISTED ? ", ..." : "";
    return fail(p, name, "unknown material %s (defined materials: %s%s)", show(name).s, list, more);
}

#define NUMBERS(n, count, req, limits) \
    { \
        .name = n, .kind = VAL_NUMBERS, .arity = count, .required = req, .range = limits \
    }

static const struct range range_positive =
    {.lo = 0, .hi = REAL_MAX, .lo_open = true, .text = "> 0"};
static const struct range range_nonnegative = {.lo = 0, .hi = REAL_MAX, .text = ">= 0"};
static const struct range range_unit = {.lo = 0, .hi = 1, .text = "in [0, 1]"};

/* What each material kind takes (an unused slot of `fields` ends the list);
 * ORDER MAT_KIND. */
static const struct material_kind_spec {
    const char *name;
    int feature; /* what a shape using it needs; -1: nothing */
    struct field_spec fields[4];
} material_kinds[] = {
    [MAT_DIFFUSE] =
        {.name = "diffuse", .feature = -1, .fields = {NUMBERS("albedo", 3, true, &range_unit)}},
    [MAT_MIRROR] =
        {.name = "mirror",
         .feature = FEAT_MIRROR,
         .fields = {NUMBERS("reflectance", 3, true, &range_unit)}},
    [MAT_GLASS] =
        {.name = "glass",
         .feature = FEAT_GLASS,
         .fields = {NUMBERS("ior", 1, true, &range_positive)}},
    [MAT_BLEND] =
        {.name = "blend",
         .feature = FEAT_BLEND,
         .fields =
             {NUMBERS("albedo", 3, true, &range_unit),
              NUMBERS("reflectance", 3, true, &range_unit)}},
    [MAT_CHECKER] =
        {.name = "checker",
         .feature = FEAT_CHECKER,
         .fields =
             {NUMBERS("albedo", 3, true, &range_unit),
              NUMBERS("albedo2", 3, true, &range_unit),
              NUMBERS("size", 1, true, &range_positive)}},
};

#define N_MATERIAL_KINDS ((int)(sizeof material_kinds / sizeof material_kinds[0]))

/* The shape's `material` field: its index, and the feature its kind needs. */
static bool
use_material(struct parser *p, const struct token *kw, const struct fields *fs, int *out)
{
    const struct token *name = &get(fs, "material")->val[0];
    int i = find_material(p->scene, name);
    if (i < 0) {
        return unknown_material(p, name);
    }
    int feature = material_kinds[p->scene->materials[i].kind].feature;
    if (feature >= 0) {
        use_feature(p, (enum feature)feature, kw);
    }
    *out = i;
    return true;
}

static bool
is_name_char(char c, bool first)
{
    bool letter = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
    return letter || (!first && ((c >= '0' && c <= '9') || c == '-'));
}

static bool
check_material_name(struct parser *p, const struct token *t)
{
    const char *rule = "expected a letter or '_', then letters, digits, '_' or '-'";
    if (t->kind != TOK_WORD) {
        return fail(p, t, "expected a material name after 'material', got %s", show(t).s);
    }
    for (size_t i = 0; i < t->len; i++) {
        if (!is_name_char(t->text[i], i == 0)) {
            return fail(p, t, "invalid material name %s (%s)", show(t).s, rule);
        }
    }
    if (t->len > SCENE_MAX_NAME) {
        return fail(p, t, "material name %s is longer than %d", show(t).s, SCENE_MAX_NAME);
    }
    int first = find_material(p->scene, t);
    if (first >= 0) {
        int line = p->scene->materials[first].loc.line;
        return fail(p, t, "duplicate material %s (first defined on line %d)", show(t).s, line);
    }
    return true;
}

/* Whitted's blend reflects albedo diffusely and reflectance specularly: the
 * two together must not reflect more than arrives. */
static bool
check_blend(struct parser *p, const struct fields *fs)
{
    const struct field_value *albedo = get(fs, "albedo");
    const struct field_value *refl = get(fs, "reflectance");
    for (int i = 0; i < 3; i++) {
        double sum = (double)albedo->num[i] + (double)refl->num[i];
        if (sum > 1) {
            return fail(
                p,
                &refl->val[i],
                "albedo + reflectance must be <= 1 per component, got %g",
                sum);
        }
    }
    return true;
}

static bool
add_material(
    struct parser *p,
    const struct token *kw,
    const struct token *name,
    int kind,
    const struct fields *fs)
{
    struct scene *s = p->scene;
    if (s->n_materials >= SCENE_MAX_MATERIALS) {
        return fail(p, kw, "too many materials (at most %d)", SCENE_MAX_MATERIALS);
    }
    if (kind == MAT_BLEND && !check_blend(p, fs)) {
        return false;
    }
    struct material *a =
        grow(p, kw, s->materials, s->n_materials + 1, &p->cap.materials, sizeof *a);
    if (!a) {
        return false;
    }
    s->materials = a;
    struct material *m = &a[s->n_materials++];
    *m = (struct material){.kind = (enum material_kind)kind, .loc = loc_of(kw)};
    snprintf(m->name, sizeof m->name, "%.*s", (int)name->len, name->text);
    m->albedo = get(fs, "albedo") ? vec_of(fs, "albedo") : vec3_splat(0);
    m->albedo2 = get(fs, "albedo2") ? vec_of(fs, "albedo2") : vec3_splat(0);
    m->reflectance = get(fs, "reflectance") ? vec_of(fs, "reflectance") : vec3_splat(0);
    m->checker_size = get(fs, "size") ? get(fs, "size")->num[0] : 0;
    m->ior = get(fs, "ior") ? get(fs, "ior")->num[0] : 0;
    return true;
}

/* material NAME KIND fields...: the kind decides which fields follow. */
static bool
parse_material(struct parser *p, const struct token *kw, struct fields *fs)
{
    struct token name, kind;
    if (!next_token(p, &name) || !check_material_name(p, &name) || !next_token(p, &kind)) {
        return false;
    }
    int k = 0;
    while (k < N_MATERIAL_KINDS && !token_is(&kind, material_kinds[k].name)) {
        k++;
    }
    if (k == N_MATERIAL_KINDS) {
        const char *kinds = "diffuse, mirror, glass, blend or checker";
        return fail(
            p,
            &kind,
            "expected a material kind (%s) after %s, got %s",
            kinds,
            show(&name).s,
            show(&kind).s);
    }
    fs->spec = material_kinds[k].fields;
    const char *kind_name = material_kinds[k].name;
    snprintf(fs->context, sizeof fs->context, "%s material %s", kind_name, show(&name).s);
    return read_fields(p, kw, fs) && add_material(p, kw, &name, k, fs);
}

/* Sine of the angle between non-zero a and b, each first divided by its
 * largest component so that no product overflows; NaN if one is infinite. */
static double
sine_between(const double a_in[3], const double b_in[3])
{
    double a[3], b[3];
    double ma = fmax(fabs(a_in[0]), fmax(fabs(a_in[1]), fabs(a_in[2])));
    double mb = fmax(fabs(b_in[0]), fmax(fabs(b_in[1]), fabs(b_in[2])));
    for (int i = 0; i < 3; i++) {
        a[i] = a_in[i] / ma;
        b[i] = b_in[i] / mb;
    }
    double cx = a[1] * b[2] - a[2] * b[1];
    double cy = a[2] * b[0] - a[0] * b[2];
    double cz = a[0] * b[1] - a[1] * b[0];
    double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    double lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    return sqrt(cx * cx + cy * cy + cz * cz) / (la * lb);
}

static bool
build_camera(struct parser *p, const struct token *kw, struct fields *fs)
{
    (void)kw;
    vec3 o = vec_of(fs, "origin");
    vec3 t = vec_of(fs, "target");
    vec3 up = vec_of(fs, "up");
    if (o.x == t.x && o.y == t.y && o.z == t.z) {
        return fail(p, &get(fs, "target")->key, "target must differ from origin");
    }
    if (vec3_is_zero(up)) {
        return fail(p, &get(fs, "up")->key, "up must be non-zero");
    }
    // In double, where the difference of two reals cannot overflow.
    double view[3] = {(double)t.x - o.x, (double)t.y - o.y, (double)t.z - o.z};
    double up_d[3] = {up.x, up.y, up.z};
    if (!(sine_between(view, up_d) >= MIN_UP_SINE)) {
        const char *msg = "up must not be parallel to the view direction (target - origin)";
        return fail(p, &get(fs, "up")->key, "%s", msg);
    }
    real fov = get(fs, "fov")->num[0];
    p->scene->camera = (struct camera_desc){.origin = o, .target = t, .up = up, .vfov_deg = fov};
    return true;
}

static bool
build_image(struct parser *p, const struct token *kw, struct fields *fs)
{
    (void)kw;
    p->scene->width = (int)get(fs, "width")->integer;
    p->scene->height = (int)get(fs, "height")->integer;
    return true;
}

/* background and ambient: a colour, and a feature when it is not black. */
static bool
build_color(struct parser *p, const struct token *kw, struct fields *fs)
{
    bool background = token_is(kw, "background");
    vec3 color = vec_of(fs, "color");
    *(background ? &p->scene->background : &p->scene->ambient) = color;
    if (!vec3_is_zero(color)) {
        use_feature(p, background ? FEAT_ENVIRONMENT : FEAT_AMBIENT, kw);
    }
    return true;
}

static bool
build_sphere(struct parser *p, const struct token *kw, struct fields *fs)
{
    struct scene *s = p->scene;
    int material;
    if (!use_material(p, kw, fs, &material)) {
        return false;
    }
    struct sphere *a = grow(p, kw, s->spheres, s->n_spheres + 1, &p->cap.spheres, sizeof *a);
    if (!a) {
        return false;
    }
    s->spheres = a;
    real radius = get(fs, "radius")->num[0];
    a[s->n_spheres++] =
        (struct sphere){.center = vec_of(fs, "center"), .radius = radius, .material = material};
    return true;
}

/* A quad of zero area is allowed: it is never hit. */
static bool
build_quad(struct parser *p, const struct token *kw, struct fields *fs)
{
    struct scene *s = p->scene;
    int material;
    if (!use_material(p, kw, fs, &material)) {
        return false;
    }
    struct quad *a = grow(p, kw, s->quads, s->n_quads + 1, &p->cap.quads, sizeof *a);
    if (!a) {
        return false;
    }
    s->quads = a;
    struct quad *q = &a[s->n_quads++];
    *q = (struct quad){.corner = vec_of(fs, "corner"), .material = material};
    q->edge1 = vec_of(fs, "edge1");
    q->edge2 = vec_of(fs, "edge2");
    return true;
}

/* Room for n more vertices and m more triangles. */
static bool
room_for_mesh(struct parser *p, const struct token *at, size_t n, size_t m)
{
    struct scene *s = p->scene;
    if (n > (size_t)(INT_MAX - s->n_vertices) || m > (size_t)(INT_MAX - s->n_triangles)) {
        return fail(p, at, "too many vertices or triangles in the scene (at most %d)", INT_MAX);
    }
    vec3 *pos = grow(p, at, s->positions, s->n_vertices + (int)n, &p->cap.positions, sizeof *pos);
    if (!pos) {
        return false;
    }
    s->positions = pos;
    vec3 *nrm = grow(p, at, s->normals, s->n_vertices + (int)n, &p->cap.normals, sizeof *nrm);
    if (!nrm) {
        return false;
    }
    s->normals = nrm;
    int triangles = s->n_triangles + (int)m;
    struct triangle *tri = grow(p, at, s->triangles, triangles, &p->cap.triangles, sizeof *tri);
    if (!tri) {
        return false;
    }
    s->triangles = tri;
    return true;
}

/* A triangle of zero area is allowed, as in meshes: it is never hit. */
static bool
build_triangle(struct parser *p, const struct token *kw, struct fields *fs)
{
    struct scene *s = p->scene;
    int material;
    if (!use_material(p, kw, fs, &material) || !room_for_mesh(p, kw, 3, 1)) {
        return false;
    }
    static const char *const corners[] = {"v0", "v1", "v2"};
    struct triangle tri = {.material = material, .smooth = false};
    for (int i = 0; i < 3; i++) {
        tri.v[i] = s->n_vertices;
        s->positions[s->n_vertices] = vec_of(fs, corners[i]);
        s->normals[s->n_vertices++] = vec3_splat(0);
    }
    s->triangles[s->n_triangles++] = tri;
    return true;
}

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
    const struct field_value *scale = get(fs, "scale");
    const struct field_value *rotate = get(fs, "rotate");
    const struct field_value *translate = get(fs, "translate");
    for (int i = 0; i < 3; i++) {
        xf->scale[i] = scale ? scale->num[scale->n == 1 ? 0 : i] : 1;
        xf->offset[i] = translate ? translate->num[i] : 0;
    }
    if (rotate) {
        double axis[3] = {rotate->num[0], rotate->num[1], rotate->num[2]};
        double len = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
        if (!(len > 0) || !isfinite(len)) {
            return fail(p, &rotate->key, "rotate axis must be non-zero");
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

static bool
append_mesh(
    struct parser *p,
    const struct token *at,
    const struct gltf_mesh *mesh,
    const struct transform *xf,
    int material)
{
    struct scene *s = p->scene;
    if (!room_for_mesh(p, at, mesh->n_vertices, mesh->n_triangles)) {
        return false;
    }
    for (size_t i = 0; i < mesh->n_vertices; i++) {
        size_t v = (size_t)s->n_vertices + i;
        if (!transform_vertex(xf, mesh, i, &s->positions[v], &s->normals[v])) {
            return fail(p, at, "mesh vertex %zu is not finite once transformed", i);
        }
    }
    for (size_t i = 0; i < mesh->n_triangles; i++) {
        struct triangle tri = {.material = material, .smooth = mesh->normals != NULL};
        for (int k = 0; k < 3; k++) {
            unsigned index = mesh->indices[3 * i + (size_t)k];
            if (index >= mesh->n_vertices) {
                return fail(
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
        s->triangles[s->n_triangles + (int)i] = tri;
    }
    s->n_vertices += (int)mesh->n_vertices;
    s->n_triangles += (int)mesh->n_triangles;
    return true;
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
        return fail(p, t, "expected a file name after 'file', got an empty string");
    }
    const char *slash = strrchr(p->name, '/');
    int dir = name[0] == '/' || !slash ? 0 : (int)(slash - p->name + 1);
    if (n >= MAX_PATH_CHARS - 1 || (size_t)dir + n >= MAX_PATH_CHARS) {
        return fail(p, t, "mesh path too long (at most %d bytes)", MAX_PATH_CHARS - 1);
    }
    memcpy(path, p->name, (size_t)dir);
    memcpy(path + dir, name, n + 1);
    return true;
}

static bool
load_mesh(
    struct parser *p,
    const struct token *t,
    const char *name,
    const char *path,
    struct gltf_mesh *out)
{
    // Opened here first, so that a missing file reads the same with or without glTF.
    FILE *f = fopen(path, "rb");
    if (!f) {
        return fail(p, t, "cannot load mesh '%s': cannot open: %s", name, strerror(errno));
    }
    fclose(f);
    if (!gltf_available()) {
        const char *how = "this build has no glTF support: install libtinygltf-dev and rebuild";
        return fail(p, t, "cannot load mesh '%s': %s", name, how);
    }
    struct diag gerr = {.line = 0};
    if (!gltf_load(path, out, &gerr)) {
        return fail(p, t, "cannot load mesh '%s': %s", name, gerr.msg);
    }
    return true;
}

static bool
build_mesh(struct parser *p, const struct token *kw, struct fields *fs)
{
    int material;
    struct transform xf;
    if (!use_material(p, kw, fs, &material) || !make_transform(p, fs, &xf)) {
        return false;
    }
    const struct token *file = &get(fs, "file")->val[0];
    char name[MAX_PATH_CHARS], path[MAX_PATH_CHARS];
    struct gltf_mesh mesh = {.n_vertices = 0};
    if (!mesh_path(p, file, name, path) || !load_mesh(p, file, name, path, &mesh)) {
        return false;
    }
    bool ok = append_mesh(p, file, &mesh, &xf, material);
    gltf_free(&mesh);
    if (ok) {
        use_feature(p, FEAT_MESH, kw);
    }
    return ok;
}

static bool
build_point_light(struct parser *p, const struct token *kw, struct fields *fs)
{
    struct scene *s = p->scene;
    int n = s->n_point_lights;
    struct point_light *a = grow(p, kw, s->point_lights, n + 1, &p->cap.points, sizeof *a);
    if (!a) {
        return false;
    }
    s->point_lights = a;
    a[s->n_point_lights++] = (struct point_light){
        .position = vec_of(fs, "position"),
        .intensity = vec_of(fs, "intensity")};
    use_feature(p, FEAT_POINT_LIGHT, kw);
    return true;
}

static bool
build_area_light(struct parser *p, const struct token *kw, struct fields *fs)
{
    struct scene *s = p->scene;
    struct area_light light = {.corner = vec_of(fs, "corner"), .loc = loc_of(kw)};
    light.edge1 = vec_of(fs, "edge1");
    light.edge2 = vec_of(fs, "edge2");
    light.radiance = vec_of(fs, "radiance");
    real area = area_light_area(&light);
    if (!isfinite(area)) {
        return fail(p, kw, "area_light is too large (its area is not a finite number)");
    }
    if (!(area > 0)) {
        return fail(p, kw, "area_light has zero area (edge1 and edge2 are parallel or zero)");
    }
    int n = s->n_area_lights;
    struct area_light *a = grow(p, kw, s->area_lights, n + 1, &p->cap.areas, sizeof *a);
    if (!a) {
        return false;
    }
    s->area_lights = a;
    a[s->n_area_lights++] = light;
    use_feature(p, FEAT_AREA_LIGHT, kw);
    return true;
}

/* --- Statements ----------------------------------------------------------- */

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
     .build = build_camera,
     .fields =
         {NUMBERS("origin", 3, true, NULL),
          NUMBERS("target", 3, true, NULL),
          NUMBERS("up", 3, true, NULL),
          NUMBERS("fov", 1, true, &range_fov)}},
    {.keyword = "image",
     .once = true,
     .required = true,
     .build = build_image,
     .fields =
         {{.name = "width", .kind = VAL_INT, .arity = 1, .required = true, .range = &range_image},
          {.name = "height",
           .kind = VAL_INT,
           .arity = 1,
           .required = true,
           .range = &range_image}}},
    {.keyword = "background",
     .once = true,
     .build = build_color,
     .fields = {NUMBERS("color", 3, true, &range_nonnegative)}},
    {.keyword = "ambient",
     .once = true,
     .build = build_color,
     .fields = {NUMBERS("color", 3, true, &range_nonnegative)}},
    {.keyword = "material", .build = parse_material},
    {.keyword = "sphere",
     .build = build_sphere,
     .fields =
         {NUMBERS("center", 3, true, NULL),
          NUMBERS("radius", 1, true, &range_positive),
          MATERIAL_REF}},
    {.keyword = "quad",
     .build = build_quad,
     .fields =
         {NUMBERS("corner", 3, true, NULL),
          NUMBERS("edge1", 3, true, NULL),
          NUMBERS("edge2", 3, true, NULL),
          MATERIAL_REF}},
    {.keyword = "triangle",
     .build = build_triangle,
     .fields =
         {NUMBERS("v0", 3, true, NULL),
          NUMBERS("v1", 3, true, NULL),
          NUMBERS("v2", 3, true, NULL),
          MATERIAL_REF}},
    {.keyword = "mesh",
     .build = build_mesh,
     .fields =
         {{.name = "file", .kind = VAL_PATH, .arity = 1, .required = true},
          MATERIAL_REF,
          {.name = "scale", .kind = VAL_SCALE, .arity = 3, .range = &range_not_zero},
          NUMBERS("rotate", 4, false, NULL),
          NUMBERS("translate", 3, false, NULL)}},
    {.keyword = "point_light",
     .build = build_point_light,
     .fields =
         {NUMBERS("position", 3, true, NULL), NUMBERS("intensity", 3, true, &range_nonnegative)}},
    {.keyword = "area_light",
     .build = build_area_light,
     .fields =
         {NUMBERS("corner", 3, true, NULL),
          NUMBERS("edge1", 3, true, NULL),
          NUMBERS("edge2", 3, true, NULL),
          NUMBERS("radiance", 3, true, &range_nonnegative)}},
};

#define N_STATEMENTS ((int)(sizeof statements / sizeof statements[0]))
_Static_assert(N_STATEMENTS <= MAX_STATEMENTS, "parser.seen is too small");

static bool
parse_statement(struct parser *p, const struct token *kw)
{
    int i = 0;
    while (i < N_STATEMENTS && !token_is(kw, statements[i].keyword)) {
        i++;
    }
    if (i == N_STATEMENTS) {
        return fail(p, kw, "unknown keyword %s", show(kw).s);
    }
    const struct statement *st = &statements[i];
    if (st->once && p->seen[i].line) {
        int first = p->seen[i].line;
        return fail(p, kw, "duplicate '%s' statement (first on line %d)", st->keyword, first);
    }
    p->seen[i] = p->seen[i].line ? p->seen[i] : loc_of(kw);
    struct fields fs = {.spec = st->fields};
    snprintf(fs.context, sizeof fs.context, "'%s'", st->keyword);
    if (st->fields[0].name && !read_fields(p, kw, &fs)) {
        return false;
    }
    return st->build(p, kw, &fs);
}

static bool
parse_scene(struct parser *p)
{
    struct token tok;
    do {
        if (!next_token(p, &tok)) {
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
            return fail(p, &tok, "missing '%s' statement", statements[i].keyword);
        }
    }
    return true;
}

/* --- Public --------------------------------------------------------------- */

/* The whole file, up to MAX_FILE_BYTES, into *out (free it). */
static bool
read_file(const char *path, char **out, size_t *len, struct diag *err)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        diag_set(err, path, 0, 0, "cannot open: %s", strerror(errno));
        return false;
    }
    size_t cap = (size_t)1 << 16;
    size_t n = 0;
    char *text = NULL;
    for (;;) {  // up to one byte past the cap, to see that the cap is passed
        char *grown = realloc(text, cap);
        if (!grown) {
            diag_set(err, path, 0, 0, "out of memory");
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

bool
scene_load(const char *path, struct scene *out, struct diag *err)
{
    *out = (struct scene){.width = 0};
    char *text = NULL;
    size_t len = 0;
    if (!read_file(path, &text, &len, err)) {
        return false;
    }
    bool ok = scene_load_string(text, len, path, out, err);
    free(text);
    return ok;
}

bool
scene_load_string(
    const char *text,
    size_t len,
    const char *name,
    struct scene *out,
    struct diag *err)
{
    *out = (struct scene){.width = 0};
    name = name ? name : "<string>";
    snprintf(out->path, sizeof out->path, "%s", name);
    struct parser p = {.src = text ? text : "", .len = text ? len : 0, .line = 1, .col = 1};
    p.name = name;
    p.scene = out;
    p.err = err;
    if (!parse_scene(&p)) {
        scene_free(out);
        return false;
    }
    return true;
}

void
scene_free(struct scene *s)
{
    free(s->materials);
    free(s->spheres);
    free(s->quads);
    free(s->positions);
    free(s->normals);
    free(s->triangles);
    free(s->point_lights);
    free(s->area_lights);
    *s = (struct scene){.width = 0};
}
