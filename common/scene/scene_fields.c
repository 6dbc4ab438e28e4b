/*
 * scene_fields.c - a statement's named fields and their values: numbers
 * (decimal only, finite, representable as a real), integers, names and file
 * names; each field at most once, its values within the range the statement
 * table gives, and the required ones present.  scene_get() and scene_vec_of() hand the
 * values to the builders.
 */
#include "scene_parser.h"

#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#define MAX_NUMBER_CHARS 64 /* a longer token is no number anyone writes */

/* The range most sizes share (radii, an index of refraction, ...). */
const struct range scene_range_positive = {.lo = 0, .hi = REAL_MAX, .lo_open = true, .text = "> 0"};

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
    if (!scene_next_token(p, &t)) {
        return false;
    }
    enum number_status status = to_number(&t, &x);
    if (status == NUMBER_OUT_OF_RANGE) {
        return scene_fail(p, &t, "number %s is out of range", scene_show(&t).s);
    }
    if (status != NUMBER_OK) {
        // "a number", "3 finite numbers", "1 or 3 numbers" (the first value of scale)
        static const char *const counts[] = {"1 or 3", "a", "2", "3", "4"};
        int n = v->spec->kind != VAL_SCALE ? v->spec->arity : v->n == 0 ? 0 : 3;
        const char *finite = status == NUMBER_NOT_FINITE ? " finite" : "";
        return scene_fail(
            p,
            &t,
            "expected %s%s number%s after '%s', got %s",
            counts[n],
            finite,
            n == 1 ? "" : "s",
            v->spec->name,
            scene_show(&t).s);
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
    if (!read_number(p, v) || !scene_peek_token(p, &next)) {
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
    if (!scene_next_token(p, &t)) {
        return false;
    }
    enum number_status status = to_integer(&t, &v->integer);
    if (status == NUMBER_BAD) {
        return scene_fail(
            p,
            &t,
            "expected an integer after '%s', got %s",
            v->spec->name,
            scene_show(&t).s);
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
    if (!scene_next_token(p, &t)) {
        return false;
    }
    bool is_path = v->spec->kind == VAL_PATH;
    if (t.kind != TOK_WORD && !(is_path && t.kind == TOK_STRING)) {
        const char *want = is_path ? "a file name" : "a material name";
        return scene_fail(
            p,
            &t,
            "expected %s after '%s', got %s",
            want,
            v->spec->name,
            scene_show(&t).s);
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
            return scene_fail(p, t, "%s must be %s%s, got %.*s", name, r->text, each, len, t->text);
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
        return scene_fail(
            p,
            t,
            "too many numbers after '%s', expected %s",
            last->spec->name,
            count);
    }
    char list[160] = "";  // "center, radius or material"
    size_t used = 0;
    for (int i = 0; fs->spec[i].name && used < sizeof list; i++) {
        const char *sep = i == 0 ? "" : fs->spec[i + 1].name ? ", " : " or ";
        used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", sep, fs->spec[i].name);
    }
    return scene_fail(
        p,
        t,
        "unknown field %s in %s (expected %s)",
        scene_show(t).s,
        fs->context,
        list);
}

/* Named fields up to the end of the line, each at most once and its values
 * in range; then every required field must have been given. */
bool
scene_read_fields(struct parser *p, const struct token *kw, struct fields *fs)
{
    const struct field_value *last = NULL;
    struct token t;
    while (scene_next_token(p, &t)) {
        if (t.kind == TOK_EOL || t.kind == TOK_EOF) {
            for (const struct field_spec *f = fs->spec; f->name; f++) {
                if (f->required && !fs->v[f - fs->spec].spec) {
                    return scene_fail(p, kw, "missing field '%s' in %s", f->name, fs->context);
                }
            }
            return true;
        }
        int i = 0;
        while (fs->spec[i].name && !scene_token_is(&t, fs->spec[i].name)) {
            i++;
        }
        if (!fs->spec[i].name) {
            return unknown_field(p, fs, &t, last);
        }
        struct field_value *v = &fs->v[i];
        if (v->spec) {
            return scene_fail(p, &t, "duplicate field %s in %s", scene_show(&t).s, fs->context);
        }
        *v = (struct field_value){.spec = &fs->spec[i], .key = t};
        if (!read_values(p, v) || !check_range(p, v)) {
            return false;
        }
        last = v;
    }
    return false;
}

const struct field_value *
scene_get(const struct fields *fs, const char *name)
{
    for (int i = 0; fs->spec[i].name; i++) {
        if (strcmp(fs->spec[i].name, name) == 0) {
            return fs->v[i].spec ? &fs->v[i] : NULL;
        }
    }
    return NULL;
}

vec3
scene_vec_of(const struct fields *fs, const char *name)
{
    const struct field_value *v = scene_get(fs, name);
    return vec3_make(v->num[0], v->num[1], v->num[2]);
}
