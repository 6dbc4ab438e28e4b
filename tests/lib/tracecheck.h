/*
 * tracecheck.h - helpers of the tests of `render --pixel X,Y --trace FILE`
 * (tests/stage/NN_trace.c): replay a pixel into a JSON trace, read the
 * pixel's value back, validate the JSON's structure with python3, and count
 * the events of a kind.
 */
#ifndef TRACECHECK_H
#define TRACECHECK_H

#include <stdbool.h>
#include <stddef.h>

/* Render only pixel (x, y) of scene with the extra arguments args
 * (NULL-terminated, may be NULL) into a JSON trace in the temporary
 * directory; returns its path (valid until the program ends), or NULL, with
 * the binary's output printed, when the run fails. */
const char *tracecheck_pixel(const char *scene, int x, int y, const char *const args[]);

/* The scene of the shadow traces (tests/stage/02_trace.c, 03_trace.c): a
 * ball of radius 0.3 floating at height 1 over the origin of an 8 x 8
 * floor, seen from (0, 4, 4) at 21 x 21 pixels (the middle pixel, 10, 10,
 * sees the floor at the origin), with the statement `light` on line 5 (the
 * ball on line 4); written as NAME in the temporary directory.  Its path,
 * or NULL. */
const char *tracecheck_ball_scene(const char *name, const char *light);

/* Trace pixel (x, y) of scene with one camera ray through its centre (--aa
 * grid from stage 06 on) and, from stage 07 on, shadow rays at its first
 * vertex only (--max-depth 2); option and value (may be NULL) are added.
 * The trace's path, or NULL (the output printed) when the run fails. */
const char *
tracecheck_one_vertex(const char *scene, int x, int y, const char *option, const char *value);

/* The "value" of a JSON trace, as the float the image stores; false when
 * the file or the key is missing. */
bool tracecheck_value(const char *path, float value[3]);

/* How many times `text` occurs in the file (0 when it cannot be read). */
int tracecheck_count(const char *path, const char *text);

/* The numbers that follow each occurrence of `key` (e.g. "\"fresnel\": ")
 * in the file, in order, into out[0 .. max); returns how many there are
 * (more than max are counted, not stored). */
int tracecheck_numbers(const char *path, const char *key, double *out, int max);

/* Validate a JSON trace with python3's json module: an object with
 * "pixel" (two integers), "value" (three numbers), "passes" and a
 * non-empty "samples" list whose items hold "events", each an object with
 * a string "type"; the value is the float mean of the passes' estimates.
 * 1: valid, 0: invalid (why in `why`), -1: no python3 to ask. */
int tracecheck_json_valid(const char *path, char *why, size_t cap);

/* Whether the file is well-formed XML whose root is an <svg> element
 * holding an embedded PNG image (python3's xml.etree); -1 without python3. */
int tracecheck_svg_valid(const char *path, char *why, size_t cap);

#endif /* TRACECHECK_H */
