/*
 * recorder_write.c - a recorded trace (recorder_events.h) written as an indented
 * text tree or as JSON (recorder.h), and the names every writer, SVG too,
 * prints for a primitive or a light: each field in the order the
 * recorder (recorder.c) added it.
 */
#include "recorder_events.h"

#include <math.h>
#include <string.h>

/* --- names -------------------------------------------------------------- */

void
recorder_prim_name(const struct scene *s, int prim, struct recorder_name *out)
{
    int shapes[] = {s->n_spheres, s->n_quads, s->n_triangles, s->n_area_lights, s->n_sphere_lights};
    static const char *const kinds[] = {"sphere", "quad", "triangle", "area_light", "sphere_light"};
    int index = prim;
    int k = 0;
    while (k < 4 && index >= shapes[k]) {
        index -= shapes[k];
        k++;
    }
    *out = (struct recorder_name){.kind = kinds[k], .index = index};
    switch (k) {
    case 0:
        out->line = index < s->n_spheres ? s->spheres[index].line : 0;
        break;
    case 1:
        out->line = s->quads[index].line;
        break;
    case 2:
        out->line = s->triangles[index].line;
        break;
    case 3:
        out->line = s->area_lights[index].loc.line;
        break;
    default:
        out->line = index < s->n_sphere_lights ? s->sphere_lights[index].loc.line : 0;
        break;
    }
}

void
recorder_light_name(const struct scene *s, long long code, struct recorder_name *out)
{
    int kind = (int)(code >> 32);
    int index = (int)(code & 0xffffffff);
    static const char *const kinds[] = {"point_light", "area_light", "sphere_light"};
    *out = (struct recorder_name){.kind = kinds[kind], .index = index};
    if (kind == RECORDER_POINT_LIGHT) {
        out->line = s->point_lights[index].loc.line;
    } else if (kind == RECORDER_AREA_LIGHT) {
        out->line = s->area_lights[index].loc.line;
    } else {
        out->line = s->sphere_lights[index].loc.line;
    }
}

/* --- text ----------------------------------------------------------------- */

static void
text_vec(FILE *f, const double x[3], int dims)
{
    if (dims == 2) {
        fprintf(f, "(%.4g %.4g)", x[0], x[1]);
    } else {
        fprintf(f, "(%.4g %.4g %.4g)", x[0], x[1], x[2]);
    }
}

static void
text_field(FILE *f, const struct recorder *t, const struct recorder_field *field)
{
    struct recorder_name name;
    fprintf(f, "  %s ", field->key);
    switch (field->kind) {
    case FIELD_NUM:
        if (isnan(field->x[0])) {
            fprintf(f, "n/a");
        } else {
            fprintf(f, "%.4g", field->x[0]);
        }
        break;
    case FIELD_VEC:
        text_vec(f, field->x, field->dims);
        break;
    case FIELD_INT:
        fprintf(f, "%lld", field->i);
        break;
    case FIELD_TEXT:
        fprintf(f, "%s", field->text);
        break;
    case FIELD_PRIM:
        recorder_prim_name(t->scene, (int)field->i, &name);
        fprintf(f, "%s #%d (line %d)", name.kind, name.index, name.line);
        break;
    case FIELD_MATERIAL:
        if (field->i < 0) {
            fprintf(f, "none");
        } else {
            const struct material *m = &t->scene->materials[field->i];
            fprintf(f, "'%s' (line %d)", m->name, m->loc.line);
        }
        break;
    case FIELD_LIGHT:
        recorder_light_name(t->scene, field->i, &name);
        fprintf(f, "%s #%d (line %d)", name.kind, name.index, name.line);
        break;
    }
}

/* Whether the stage recursed: in 04-06 a `specular` event spawns the rays
 * that follow it (07 loops along one path and records `bounce`s). */
static bool
is_recursive(const struct recorder *t)
{
    for (int i = 0; i < t->n_events; i++) {
        if (strcmp(t->events[i].type, "specular") == 0) {
            return true;
        }
    }
    return false;
}

/* How many recursions deep the events from e on are: the depth - 1 of
 * e's ray when e is a hit, a miss or a specular decision (which follows
 * the branch it spawned off, once that has returned), 0 at a new sample,
 * else as before. */
static int
recursion_depth(const struct recorder_event *e, int before)
{
    if (e->level == 0) {
        return 0;
    }
    for (int k = 0; k < e->n_fields; k++) {
        if (strcmp(e->fields[k].key, "depth") == 0) {
            return e->fields[k].i > 1 ? (int)e->fields[k].i - 1 : 0;
        }
    }
    return before;
}

void
recorder_write_text(FILE *f, const struct recorder *t)
{
    fprintf(f, "pixel (%d, %d) of %s\n", t->px, t->py, t->scene->path);
    fprintf(f, "value (%.6g %.6g %.6g)", t->value[0], t->value[1], t->value[2]);
    fprintf(f, "  the mean of %d pass estimates:", t->n_passes);
    for (int i = 0; i < t->n_passes && i < 8; i++) {
        fprintf(f, " ");
        text_vec(f, t->passes[i].estimate, 3);
    }
    fprintf(f, "%s\n", t->n_passes > 8 ? " ..." : "");
    int pass = -1;
    bool nest = is_recursive(t);
    int depth = 0;
    for (int i = 0; i < t->n_events; i++) {
        const struct recorder_event *e = &t->events[i];
        if (e->pass != pass) {
            pass = e->pass;
            fprintf(f, "pass %d\n", pass);
        }
        /* A recursive stage's spawned ray sits one step under the
         * `specular` event (level 2) that spawned it. */
        depth = nest ? recursion_depth(e, depth) : 0;
        fprintf(f, "%*s%s", 2 + 2 * e->level + 4 * depth, "", e->type);
        for (int k = 0; k < e->n_fields; k++) {
            text_field(f, t, &e->fields[k]);
        }
        fprintf(f, "\n");
    }
    if (t->truncated) {
        fprintf(f, "(truncated: only the first %d events were kept)\n", t->n_events);
    }
}

/* --- JSON ----------------------------------------------------------------- */

/* A number as JSON has them: non-finite values are null. */
static void
json_number(FILE *f, double x)
{
    if (isfinite(x)) {
        fprintf(f, "%.17g", x);
    } else {
        fprintf(f, "null");
    }
}

static void
json_vec(FILE *f, const double x[3], int dims)
{
    fprintf(f, "[");
    for (int i = 0; i < dims; i++) {
        fprintf(f, i ? ", " : "");
        json_number(f, x[i]);
    }
    fprintf(f, "]");
}

/* A string of the scene (a material's name) with JSON's escapes. */
static void
json_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\') {
            fprintf(f, "\\%c", c);
        } else if (c < 0x20) {
            fprintf(f, "\\u%04x", c);
        } else {
            fputc(c, f);
        }
    }
    fputc('"', f);
}

static void
json_name(FILE *f, const struct recorder_name *name)
{
    fprintf(
        f,
        "{\"kind\": \"%s\", \"index\": %d, \"line\": %d}",
        name->kind,
        name->index,
        name->line);
}

static void
json_field(FILE *f, const struct recorder *t, const struct recorder_field *field)
{
    struct recorder_name name;
    fprintf(f, ", \"%s\": ", field->key);
    switch (field->kind) {
    case FIELD_NUM:
        json_number(f, field->x[0]);
        break;
    case FIELD_VEC:
        json_vec(f, field->x, field->dims);
        break;
    case FIELD_INT:
        fprintf(f, "%lld", field->i);
        break;
    case FIELD_TEXT:
        json_string(f, field->text);
        break;
    case FIELD_PRIM:
        recorder_prim_name(t->scene, (int)field->i, &name);
        json_name(f, &name);
        break;
    case FIELD_MATERIAL:
        if (field->i < 0) {
            fprintf(f, "null");
        } else {
            const struct material *m = &t->scene->materials[field->i];
            fprintf(f, "{\"name\": ");
            json_string(f, m->name);
            fprintf(f, ", \"line\": %d}", m->loc.line);
        }
        break;
    case FIELD_LIGHT:
        recorder_light_name(t->scene, field->i, &name);
        json_name(f, &name);
        break;
    }
}

static void
json_event(FILE *f, const struct recorder *t, const struct recorder_event *e)
{
    fprintf(f, "{\"type\": \"%s\", \"level\": %d", e->type, e->level);
    for (int k = 0; k < e->n_fields; k++) {
        json_field(f, t, &e->fields[k]);
    }
    fprintf(f, "}");
}

void
recorder_write_json(FILE *f, const struct recorder *t)
{
    double value[3] = {t->value[0], t->value[1], t->value[2]};
    fprintf(f, "{\n  \"scene\": ");
    json_string(f, t->scene->path);
    fprintf(f, ",\n  \"pixel\": [%d, %d],\n  \"value\": ", t->px, t->py);
    json_vec(f, value, 3);
    fprintf(f, ",\n  \"passes\": [");
    for (int i = 0; i < t->n_passes; i++) {
        fprintf(f, "%s{\"pass\": %d, \"estimate\": ", i ? ", " : "", t->passes[i].pass);
        json_vec(f, t->passes[i].estimate, 3);
        fprintf(f, "}");
    }
    fprintf(f, "],\n  \"truncated\": %s,\n  \"samples\": [", t->truncated ? "true" : "false");
    bool first_sample = true;
    for (int i = 0; i < t->n_events;) {
        const struct recorder_event *s = &t->events[i];
        fprintf(f, "%s\n    {\"pass\": %d", first_sample ? "" : ",", s->pass);
        first_sample = false;
        for (int k = 0; k < s->n_fields; k++) {
            json_field(f, t, &s->fields[k]);
        }
        fprintf(f, ", \"events\": [");
        int j = i + 1;
        for (; j < t->n_events && t->events[j].level > 0; j++) {
            fprintf(f, "%s\n      ", j > i + 1 ? "," : "");
            json_event(f, t, &t->events[j]);
        }
        fprintf(f, "]}");
        i = j;
    }
    fprintf(f, "\n  ]\n}\n");
}
