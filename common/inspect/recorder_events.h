/*
 * recorder_events.h - what the trace recorder (recorder.c) holds, shared by its
 * text and JSON writers (recorder_write.c) and its SVG writer (recorder_svg.c).
 */
#ifndef RECORDER_EVENTS_H
#define RECORDER_EVENTS_H

#include "recorder.h"

/* The most events one trace keeps (about 600 bytes each): a pixel of
 * --spp 64 in a closed room takes a few thousand.  Past it the trace says
 * it is truncated; the pixel's value is still the full render's. */
#define RECORDER_MAX_EVENTS (1 << 17)

/* Deeper rays than this have their offset measured from the last hit. */
#define RECORDER_MAX_DEPTH 64

/* The most numbers one event carries. */
#define RECORDER_MAX_FIELDS 12

enum recorder_field_kind {
    FIELD_NUM,
    FIELD_VEC,
    FIELD_INT,
    FIELD_TEXT, /* a string literal of the code */
    FIELD_PRIM, /* a primitive's number (its kind, index and line are printed) */
    FIELD_MATERIAL, /* a material's number; -1: none */
    FIELD_LIGHT, /* (enum recorder_light_kind << 32) | index */
};

struct recorder_field {
    const char *key;
    enum recorder_field_kind kind;
    double x[3]; /* NUM (x[0]), VEC */
    int dims; /* VEC: 3, or 2 for a position in the pixel */
    long long i; /* INT, PRIM, MATERIAL, LIGHT */
    const char *text; /* TEXT */
};

struct recorder_event {
    const char *type;
    int level; /* 0 sample, 1 hit or miss, 2 what was done there, 3 a light's rays */
    int pass;
    enum recorder_segment segment; /* what the SVG draws from `from` to `to` */
    double from[3], to[3];
    int n_fields;
    struct recorder_field fields[RECORDER_MAX_FIELDS];
};

struct recorder_pass {
    int pass;
    double estimate[3];
};

struct recorder {
    const struct scene *scene;
    int px, py;
    struct recorder_event *events;
    int n_events, cap_events;
    struct recorder_pass *passes;
    int n_passes, cap_passes;
    bool truncated;
    float value[3];
    bool has_value;
    /* While recording: */
    int pass;
    vec3 last_point; /* the last hit point: shadow rays' offsets are from it */
    bool have_point;
    vec3 vertex[RECORDER_MAX_DEPTH]; /* the hit point of each depth: a ray of depth d
                                     is spawned at vertex[d - 1] */
};

/* What the writers print for a primitive or a light: its statement's
 * keyword, its index among those and its line in the scene file
 * (recorder_write.c). */
struct recorder_name {
    const char *kind;
    int index;
    int line;
};

void recorder_prim_name(const struct scene *s, int prim, struct recorder_name *out);
void recorder_light_name(const struct scene *s, long long code, struct recorder_name *out);

#endif /* RECORDER_EVENTS_H */
