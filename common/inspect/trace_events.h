/*
 * trace_events.h - what the trace recorder (trace.c) holds, shared by its
 * text and JSON writers (trace_write.c) and its SVG writer (trace_svg.c).
 */
#ifndef TRACE_EVENTS_H
#define TRACE_EVENTS_H

#include "trace.h"

/* The most events one trace keeps (about 600 bytes each): a pixel of
 * --spp 64 in a closed room takes a few thousand.  Past it the trace says
 * it is truncated; the pixel's value is still the full render's. */
#define TRACE_MAX_EVENTS (1 << 17)

/* Deeper rays than this have their offset measured from the last hit. */
#define TRACE_MAX_DEPTH 64

/* The most numbers one event carries. */
#define TRACE_MAX_FIELDS 12

enum trace_field_kind {
    FIELD_NUM,
    FIELD_VEC,
    FIELD_INT,
    FIELD_TEXT, /* a string literal of the code */
    FIELD_PRIM, /* a primitive's number (its kind, index and line are printed) */
    FIELD_MATERIAL, /* a material's number; -1: none */
    FIELD_LIGHT, /* (enum trace_light_kind << 32) | index */
};

struct trace_field {
    const char *key;
    enum trace_field_kind kind;
    double x[3]; /* NUM (x[0]), VEC */
    int dims; /* VEC: 3, or 2 for a position in the pixel */
    long long i; /* INT, PRIM, MATERIAL, LIGHT */
    const char *text; /* TEXT */
};

struct trace_event {
    const char *type;
    int level; /* 0 sample, 1 hit or miss, 2 what was done there, 3 a light's rays */
    int pass;
    enum trace_segment segment; /* what the SVG draws from `from` to `to` */
    double from[3], to[3];
    int n_fields;
    struct trace_field fields[TRACE_MAX_FIELDS];
};

struct trace_pass {
    int pass;
    double estimate[3];
};

struct trace {
    const struct scene *scene;
    int px, py;
    struct trace_event *events;
    int n_events, cap_events;
    struct trace_pass *passes;
    int n_passes, cap_passes;
    bool truncated;
    float value[3];
    bool has_value;
    /* While recording: */
    int pass;
    vec3 last_point; /* the last hit point: shadow rays' offsets are from it */
    bool have_point;
    vec3 vertex[TRACE_MAX_DEPTH]; /* the hit point of each depth: a ray of depth d
                                     is spawned at vertex[d - 1] */
};

/* What the writers print for a primitive or a light: its statement's
 * keyword, its index among those and its line in the scene file
 * (trace_write.c). */
struct trace_name {
    const char *kind;
    int index;
    int line;
};

void trace_prim_name(const struct scene *s, int prim, struct trace_name *out);
void trace_light_name(const struct scene *s, long long code, struct trace_name *out);

#endif /* TRACE_EVENTS_H */
