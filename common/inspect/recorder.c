/*
 * recorder.c - the recorder of one pixel's rays (recorder.h): the events the
 * stage's inspect_* calls (inspect.h) record.  Its written forms are
 * recorder_write.c (text, JSON) and recorder_svg.c (SVG).
 *
 * An event is a type, a level in the tree and a list of named fields
 * (numbers, vectors, names of what the scene holds); the writers print the
 * fields in the order they were recorded, so adding a number to an event is
 * one line in its recorder_log_* function.
 */
#include "recorder_events.h"

#include <stdlib.h>
#include <string.h>

struct recorder *
recorder_new(const struct scene *scene, int px, int py)
{
    struct recorder *t = calloc(1, sizeof *t);
    if (!t) {
        return NULL;
    }
    t->scene = scene;
    t->px = px;
    t->py = py;
    t->pass = -1;
    return t;
}

void
recorder_free(struct recorder *t)
{
    if (t) {
        free(t->events);
        free(t->passes);
        free(t);
    }
}

/* A new event of this type at this level; NULL (and the trace marked
 * truncated) past RECORDER_MAX_EVENTS or when memory runs out. */
static struct recorder_event *
add_event(struct recorder *t, const char *type, int level, enum recorder_segment segment)
{
    if (t->n_events == t->cap_events) {
        int cap = t->cap_events ? 2 * t->cap_events : 256;
        struct recorder_event *grown = t->n_events < RECORDER_MAX_EVENTS
                                           ? realloc(t->events, (size_t)cap * sizeof *grown)
                                           : NULL;
        if (!grown) {
            t->truncated = true;
            return NULL;
        }
        t->events = grown;
        t->cap_events = cap;
    }
    struct recorder_event *e = &t->events[t->n_events++];
    *e = (struct recorder_event){.type = type, .level = level, .segment = segment, .pass = t->pass};
    return e;
}

static struct recorder_field *
add_field(struct recorder_event *e, const char *key, enum recorder_field_kind kind)
{
    if (!e || e->n_fields == RECORDER_MAX_FIELDS) {
        return NULL;
    }
    struct recorder_field *f = &e->fields[e->n_fields++];
    *f = (struct recorder_field){.key = key, .kind = kind};
    return f;
}

static void
put_num(struct recorder_event *e, const char *key, real x)
{
    struct recorder_field *f = add_field(e, key, FIELD_NUM);
    if (f) {
        f->x[0] = (double)x;
    }
}

static void
put_vec(struct recorder_event *e, const char *key, vec3 v)
{
    struct recorder_field *f = add_field(e, key, FIELD_VEC);
    if (f) {
        f->dims = 3;
        f->x[0] = (double)v.x;
        f->x[1] = (double)v.y;
        f->x[2] = (double)v.z;
    }
}

/* A position in the pixel, (0,0) its top-left corner. */
static void
put_vec2(struct recorder_event *e, const char *key, real x, real y)
{
    struct recorder_field *f = add_field(e, key, FIELD_VEC);
    if (f) {
        f->dims = 2;
        f->x[0] = (double)x;
        f->x[1] = (double)y;
    }
}

static void
put_int(struct recorder_event *e, const char *key, enum recorder_field_kind kind, long long i)
{
    struct recorder_field *f = add_field(e, key, kind);
    if (f) {
        f->i = i;
    }
}

static void
put_text(struct recorder_event *e, const char *key, const char *text)
{
    struct recorder_field *f = add_field(e, key, FIELD_TEXT);
    if (f) {
        f->text = text;
    }
}

static void
set_segment(struct recorder_event *e, vec3 from, vec3 to)
{
    if (e) {
        e->from[0] = (double)from.x;
        e->from[1] = (double)from.y;
        e->from[2] = (double)from.z;
        e->to[0] = (double)to.x;
        e->to[1] = (double)to.y;
        e->to[2] = (double)to.z;
    }
}

void
recorder_pass_begin(struct recorder *t, int pass)
{
    t->pass = pass;
}

void
recorder_pass_end(struct recorder *t, vec3 estimate)
{
    if (t->n_passes == t->cap_passes) {
        int cap = t->cap_passes ? 2 * t->cap_passes : 16;
        struct recorder_pass *grown = realloc(t->passes, (size_t)cap * sizeof *grown);
        if (!grown) {
            t->truncated = true;
            return;
        }
        t->passes = grown;
        t->cap_passes = cap;
    }
    t->passes[t->n_passes++] = (struct recorder_pass){
        .pass = t->pass,
        .estimate = {(double)estimate.x, (double)estimate.y, (double)estimate.z}};
}

void
recorder_set_value(struct recorder *t, const float rgb[3])
{
    memcpy(t->value, rgb, sizeof t->value);
    t->has_value = true;
}

void
recorder_log_sample(struct recorder *t, int index, real film_x, real film_y, ray r)
{
    struct recorder_event *e = add_event(t, "sample", 0, SEG_NONE);
    put_int(e, "index", FIELD_INT, index);
    put_vec2(e, "subpixel", film_x - (real)t->px, film_y - (real)t->py);
    put_vec(e, "origin", r.o);
    put_vec(e, "direction", r.d);
    t->have_point = false;
}

void
recorder_log_sample_done(struct recorder *t, vec3 radiance)
{
    struct recorder_event *e = add_event(t, "radiance", 1, SEG_NONE);
    put_vec(e, "value", radiance);
}

/* How far the origin of a ray spawned at a hit lies from the hit point:
 * the offset that keeps it from hitting its own surface. */
static void
put_offset(struct recorder_event *e, vec3 origin, vec3 from)
{
    put_num(e, "offset", vec3_length(vec3_sub(origin, from)));
}

/* A ray of this depth (> 1) starts at the hit point of the depth before. */
static void
put_spawn_offset(struct recorder *t, struct recorder_event *e, int depth, ray r)
{
    if (depth > 1 && t->have_point) {
        put_offset(e, r.o, depth - 1 <= RECORDER_MAX_DEPTH ? t->vertex[depth - 2] : t->last_point);
    }
}

/* Remember hit point p of a ray of this depth. */
static void
remember_vertex(struct recorder *t, int depth, vec3 p)
{
    if (depth >= 1 && depth <= RECORDER_MAX_DEPTH) {
        t->vertex[depth - 1] = p;
    }
    t->last_point = p;
    t->have_point = true;
}

void
recorder_log_hit(
    struct recorder *t,
    int depth,
    ray r,
    real dist,
    vec3 p,
    int prim,
    int material,
    vec3 ng,
    vec3 n,
    bool front_face)
{
    enum recorder_segment segment = depth <= 1 ? SEG_CAMERA : SEG_BOUNCE;
    struct recorder_event *e = add_event(t, "hit", 1, segment);
    put_int(e, "depth", FIELD_INT, depth);
    put_vec(e, "origin", r.o);
    put_vec(e, "direction", r.d);
    put_spawn_offset(t, e, depth, r);
    put_num(e, "t", dist);
    put_int(e, "primitive", FIELD_PRIM, prim);
    put_int(e, "material", FIELD_MATERIAL, material);
    put_vec(e, "point", p);
    put_vec(e, "ng", ng);
    put_vec(e, "n", n);
    put_text(e, "side", front_face ? "front" : "back");
    set_segment(e, r.o, p);
    remember_vertex(t, depth, p);
}

void
recorder_log_miss(struct recorder *t, int depth, ray r, vec3 radiance)
{
    struct recorder_event *e = add_event(t, "miss", 1, SEG_MISS);
    put_int(e, "depth", FIELD_INT, depth);
    put_vec(e, "origin", r.o);
    put_vec(e, "direction", r.d);
    put_spawn_offset(t, e, depth, r);
    put_vec(e, "radiance", radiance);
    set_segment(e, r.o, r.d); /* "to" is the direction: the SVG draws it a short way */
}

void
recorder_log_light(struct recorder *t, enum recorder_light_kind kind, int index)
{
    struct recorder_event *e = add_event(t, "light", 2, SEG_NONE);
    put_int(e, "source", FIELD_LIGHT, (long long)kind << 32 | (unsigned)index);
}

void
recorder_log_shadow(struct recorder *t, ray r, real t_max, int blocker, real blocker_dist)
{
    enum recorder_segment segment = blocker < 0 ? SEG_SHADOW_CLEAR : SEG_SHADOW_BLOCKED;
    struct recorder_event *e = add_event(t, "shadow", 3, segment);
    put_vec(e, "origin", r.o);
    put_vec(e, "direction", r.d);
    if (t->have_point) {
        put_offset(e, r.o, t->last_point);
    }
    put_num(e, "t_max", t_max);
    if (blocker < 0) {
        put_text(e, "result", "clear");
        set_segment(e, r.o, ray_at(r, t_max));
        return;
    }
    put_text(e, "result", "blocked");
    put_int(e, "blocker", FIELD_PRIM, blocker);
    put_num(e, "blocker_t", blocker_dist);
    set_segment(e, r.o, ray_at(r, blocker_dist));
}

void
recorder_log_light_sample(
    struct recorder *t,
    vec3 y,
    real pdf_area,
    real pdf_solid_angle,
    vec3 irradiance)
{
    struct recorder_event *e = add_event(t, "light_sample", 3, SEG_NONE);
    put_vec(e, "point", y);
    put_num(e, "pdf_area", pdf_area);
    put_num(e, "pdf_solid_angle", pdf_solid_angle);
    put_vec(e, "irradiance", irradiance);
}

void
recorder_log_adaptive(struct recorder *t, int probes, int blocked, int more)
{
    struct recorder_event *e = add_event(t, "adaptive", 3, SEG_NONE);
    put_int(e, "probes", FIELD_INT, probes);
    put_int(e, "blocked", FIELD_INT, blocked);
    put_int(e, "more_samples", FIELD_INT, more);
    const char *verdict = more > 0            ? "penumbra: more samples"
                          : blocked == 0      ? "all probes clear: the exact unoccluded irradiance"
                          : blocked == probes ? "all probes blocked: umbra"
                                              : "the probes' mean";
    put_text(e, "decision", verdict);
}

void
recorder_log_shade(struct recorder *t, vec3 albedo, vec3 irradiance, vec3 ambient, vec3 radiance)
{
    struct recorder_event *e = add_event(t, "shade", 2, SEG_NONE);
    put_vec(e, "albedo", albedo);
    put_vec(e, "irradiance", irradiance);
    put_vec(e, "ambient", ambient);
    put_vec(e, "radiance", radiance);
}

void
recorder_log_specular(struct recorder *t, int depth, const char *event, real fresnel, vec3 weight)
{
    struct recorder_event *e = add_event(t, "specular", 2, SEG_NONE);
    put_int(e, "depth", FIELD_INT, depth);
    put_text(e, "event", event);
    put_num(e, "fresnel", fresnel);
    put_vec(e, "weight", weight);
}

void
recorder_log_bounce(
    struct recorder *t,
    const char *lobe,
    vec3 d,
    real pdf,
    vec3 beta_before,
    vec3 beta_after)
{
    struct recorder_event *e = add_event(t, "bounce", 2, SEG_NONE);
    put_text(e, "lobe", lobe ? lobe : "?");
    put_vec(e, "direction", d);
    put_num(e, "pdf", pdf);
    put_vec(e, "beta_before", beta_before);
    put_vec(e, "beta_after", beta_after);
}

void
recorder_log_nee(struct recorder *t, vec3 radiance)
{
    struct recorder_event *e = add_event(t, "nee", 2, SEG_NONE);
    put_vec(e, "radiance", radiance);
}

void
recorder_log_emission(struct recorder *t, vec3 radiance, bool after_specular)
{
    struct recorder_event *e = add_event(t, "emission", 2, SEG_NONE);
    put_vec(e, "radiance", radiance);
    put_text(e, "found_by", after_specular ? "camera or specular ray" : "diffuse bounce");
}

void
recorder_log_roulette(struct recorder *t, real q, real u, bool survived)
{
    if (!(q > 0)) {
        return; /* the path had already ended (its throughput is 0) */
    }
    struct recorder_event *e = add_event(t, "roulette", 2, SEG_NONE);
    put_num(e, "q", q);
    put_num(e, "u", u);
    put_text(e, "outcome", survived ? "survives (throughput / q)" : "stops");
}

void
recorder_log_end(struct recorder *t, const char *why)
{
    struct recorder_event *e = add_event(t, "end", 2, SEG_NONE);
    put_text(e, "why", why);
}
