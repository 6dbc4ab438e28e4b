/*
 * test_recorder.c - the pixel trace's recorder and writers (common/inspect/recorder.c,
 * common/inspect/recorder_write.c), without a stage:
 *   - driver_render_pixel_traced gives the pixel the value driver_render_image stores,
 *     bit for bit, NaN passes guarded alike, and records one pass estimate
 *     per pass;
 *   - names: primitives (spheres, quads, triangles, lights) and materials
 *     by the scene file's lines;
 *   - the text form rounds and prints a number that is not one as "n/a",
 *     the JSON form prints it as null and every other number exactly;
 *   - the text form indents a recursive stage's spawned rays (after a
 *     `specular` event) by their depth, under the event that spawned
 *     them, and a decision of the parent's after the branch returned back
 *     at the parent's depth; a trace without `specular`
 *     events (07's loop) is not indented by depth;
 *   - the recorder stops at its limit and says the trace is truncated;
 *   - no recorder, no cost: the inspect_* calls with st->recorder NULL do
 *     nothing.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "driver.h"
#include "recorder.h"
#include "scene.h"
#include "testlib.h"

/* The fields of a stage's struct hit (geometry.h) that inspect_hit reads. */
struct hit {
    real t;
    int prim;
    vec3 p, ng, n;
    bool front_face;
    int material;
};

#include "inspect.h"

static const char scene_text[] = "camera origin 0 0 5 target 0 0 0 up 0 1 0 fov 40\n"
                                 "image width 8 height 6\n"
                                 "material plain diffuse albedo 0.5 0.5 0.5\n"
                                 "material say-hi diffuse albedo 0.5 0.5 0.5\n"
                                 "sphere center 0 0 0 radius 1 material plain\n"
                                 "quad corner -1 -1 -1 edge1 2 0 0 edge2 0 0 2 material plain\n"
                                 "triangle v0 0 0 0 v1 1 0 0 v2 0 1 0 material plain\n"
                                 "point_light position 0 3 0 intensity 1 1 1\n"
                                 "area_light corner 0 2 0 edge1 1 0 0 edge2 0 0 1 radiance 1 1 1\n";

static bool
load(struct scene *s)
{
    struct diag err;
    bool ok = scene_load_string(scene_text, strlen(scene_text), "t.scene", s, &err);
    CHECK_MSG(ok, "%s:%d:%d: %s", err.file, err.line, err.col, err.msg);
    return ok;
}

/* The written form of a trace, in memory. */
static char *
written(const struct recorder *t, bool json)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (json) {
        recorder_write_json(f, t);
    } else {
        recorder_write_text(f, t);
    }
    fclose(f);
    return buf;
}

/* A pixel function that records a sample and a hit, and whose value is
 * its random stream's first number u, or NaN when u < NAN_BELOW. */
#define NAN_BELOW 0.3

static vec3
recording_pixel(int px, int py, struct rng *rng, struct stats *st)
{
    ray r = {{0, 0, 5}, {0, 0, -1}};
    inspect_sample(st, 0, (real)px + (real)0.5, (real)py + (real)0.5, r);
    struct hit h = {.t = 4, .p = {0, 0, 1}, .ng = {0, 0, 1}, .n = {0, 0, 1}, .front_face = true};
    inspect_hit(st, 1, r, &h);
    real zero = 0, u = rng_uniform(rng);
    return u < (real)NAN_BELOW ? vec3_splat(zero / zero) : (vec3){u, (real)px, (real)py};
}

/* Every pass of a traced pixel is the pass of the rendered image: the
 * same value bit for bit, and its NaN passes (which the image drops) named
 * in the trace, as the pixel's random streams predict them. */
TEST(traced_pixel_is_the_rendered_pixel)
{
    struct scene s = {0};
    if (!load(&s)) {
        return;
    }
    const struct test_pixels recording = {recording_pixel};
    struct render_job job = {.width = 8, .height = 6, .threads = 2, .passes = 4, .seed = 7};
    job.tile = test_pixels_tile;
    job.ctx = &recording;
    struct image img = {0};
    struct render_result result;
    struct diag err;
    CHECK(driver_render_image(&job, &img, &result, &err));
    int nan_passes = 0;
    for (int y = 0; y < 6; y += 5) {
        for (int x = 0; x < 8; x += 3) {
            struct recorder *t = recorder_new(&s, x, y);
            float rgb[3];
            struct render_result one;
            driver_render_pixel_traced(&job, x, y, t, rgb, &one);
            CHECK(memcmp(rgb, image_pixel(&img, x, y), sizeof rgb) == 0);
            char *json = written(t, true);
            bool any_nan = false;
            for (int pass = 0; pass < 4 && json; pass++) {
                struct rng r = rng_for_pixel(7, (uint64_t)(y * 8 + x), (uint64_t)pass);
                bool nan = rng_uniform(&r) < (real)NAN_BELOW;
                char expected[64];
                snprintf(
                    expected,
                    sizeof expected,
                    "{\"pass\": %d, \"estimate\": [null, null, null]}",
                    pass);
                bool named = strstr(json, expected) != NULL;
                CHECK_MSG(named == nan, "pixel %d,%d pass %d", x, y, pass);
                any_nan |= nan;
                nan_passes += nan;
            }
            CHECK(one.passes_done == 4 && one.nan_pixels == (uint64_t)any_nan);
            CHECK(json && strstr(json, "{\"pass\": 3, \"estimate\": "));
            free(json);
            recorder_free(t);
        }
    }
    CHECK(nan_passes > 0); /* seed 7 has some: the case is tested */
    image_free(&img);
    scene_free(&s);
}

TEST(names_by_line)
{
    struct scene s = {0};
    if (!load(&s)) {
        return;
    }
    struct recorder *t = recorder_new(&s, 1, 2);
    struct stats st = {.recorder = t};
    ray r = {{0, 0, 5}, {0, 0, -1}};
    vec3 n = {0, 0, 1};
    recorder_pass_begin(t, 0);
    inspect_sample(&st, 0, 1.25, 2.75, r);
    /* Primitives: sphere 0, quad 1, triangle 2, area light 3. */
    for (int prim = 0; prim < 4; prim++) {
        struct hit h = {1, prim, n, n, n, prim != 1, prim == 2 ? 1 : 0};
        inspect_hit(&st, 1 + prim, r, &h);
    }
    inspect_light(&st, RECORDER_POINT_LIGHT, 0);
    inspect_specular(&st, 1, "mirror", NAN, vec3_splat(0.5));
    recorder_pass_end(t, vec3_splat(1));
    char *json = written(t, true);
    char *text = written(t, false);
    CHECK(json && strstr(json, "\"primitive\": {\"kind\": \"sphere\", \"index\": 0, \"line\": 5}"));
    CHECK(json && strstr(json, "\"primitive\": {\"kind\": \"quad\", \"index\": 0, \"line\": 6}"));
    CHECK(
        json && strstr(json, "\"primitive\": {\"kind\": \"triangle\", \"index\": 0, \"line\": 7}"));
    CHECK(
        json
        && strstr(json, "\"primitive\": {\"kind\": \"area_light\", \"index\": 0, \"line\": 9}"));
    CHECK(
        json && strstr(json, "\"source\": {\"kind\": \"point_light\", \"index\": 0, \"line\": 8}"));
    CHECK(json && strstr(json, "\"material\": {\"name\": \"say-hi\", \"line\": 4}"));
    CHECK(json && strstr(json, "\"subpixel\": [0.25, 0.75]"));
    CHECK(json && strstr(json, "\"fresnel\": null"));
    CHECK(json && strstr(json, "\"side\": \"back\""));
    CHECK(text && strstr(text, "primitive sphere #0 (line 5)  material 'plain' (line 3)"));
    CHECK(text && strstr(text, "fresnel n/a"));
    CHECK(text && strstr(text, "subpixel (0.25 0.75)"));
    free(json);
    free(text);
    recorder_free(t);
    scene_free(&s);
}

TEST(offsets_are_measured_from_the_spawning_hit)
{
    struct scene s = {0};
    if (!load(&s)) {
        return;
    }
    struct recorder *t = recorder_new(&s, 0, 0);
    struct stats st = {.recorder = t};
    vec3 n = {0, 1, 0};
    recorder_pass_begin(t, 0);
    inspect_sample(&st, 0, 0.5, 0.5, (ray){{0, 0, 5}, {0, 0, -1}});
    struct hit floor = {.t = 5, .prim = 1, .p = {0, 0, 0}, .ng = n, .n = n, .front_face = true};
    inspect_hit(&st, 1, (ray){{0, 0, 5}, {0, 0, -1}}, &floor);
    inspect_shadow(&st, (ray){{0, 0.25, 0}, {0, 1, 0}}, 2, -1, 0);
    struct hit above = {.t = 1, .prim = 0, .p = {0, 1.5, 0}, .ng = n, .n = n, .front_face = true};
    inspect_hit(&st, 2, (ray){{0, 0.5, 0}, {0, 1, 0}}, &above);
    recorder_pass_end(t, vec3_splat(0));
    char *json = written(t, true);
    CHECK(json && strstr(json, "\"t_max\": 2") && strstr(json, "\"offset\": 0.25"));
    CHECK(json && strstr(json, "\"depth\": 2") && strstr(json, "\"offset\": 0.5"));
    free(json);
    recorder_free(t);
    scene_free(&s);
}

/* The indentation of the first line from *from on that begins, past its
 * spaces, with `what`; *from moves past that line.  -1 if none. */
static int
indent_of(const char **from, const char *what)
{
    for (const char *line = *from; *line;) {
        int n = (int)strspn(line, " ");
        const char *end = strchr(line, '\n');
        if (strncmp(line + n, what, strlen(what)) == 0) {
            *from = end ? end + 1 : line + strlen(line);
            return n;
        }
        if (!end) {
            break;
        }
        line = end + 1;
    }
    return -1;
}

/* A glass hit whose reflected ray (depth 2) reflects again (depth 3), then
 * the refracted ray of the first hit (depth 2 again); with `specular`
 * events when `recursive`, else with 07's `bounce`s. */
static char *
nested_text(const struct scene *s, bool recursive)
{
    struct recorder *t = recorder_new(s, 0, 0);
    struct stats st = {.recorder = t};
    vec3 n = {0, 1, 0};
    ray r = {{0, 0, 5}, {0, 0, -1}};
    recorder_pass_begin(t, 0);
    inspect_sample(&st, 0, 0.5, 0.5, r);
    int depths[] = {1, 2, 3, 2};
    for (int i = 0; i < 4; i++) {
        inspect_hit(&st, depths[i], r, &(struct hit){.t = 1, .ng = n, .n = n, .front_face = true});
        if (recursive) {
            inspect_specular(&st, depths[i], "reflect", 0.04, vec3_splat(0.04));
        } else {
            inspect_bounce(&st, "diffuse", n, 0.3, vec3_splat(1), vec3_splat(0.5));
        }
    }
    if (recursive) {
        /* Back at the first hit, after its reflected branch: refraction. */
        inspect_specular(&st, 1, "refract", 0.04, vec3_splat(0.96));
    }
    recorder_pass_end(t, vec3_splat(0));
    char *text = written(t, false);
    recorder_free(t);
    return text;
}

TEST(text_indents_by_recursion_depth)
{
    struct scene s = {0};
    if (!load(&s)) {
        return;
    }
    char *text = nested_text(&s, true);
    const char *at = text ? text : "";
    int hit1 = indent_of(&at, "hit  depth 1");
    int spec1 = indent_of(&at, "specular");
    int hit2 = indent_of(&at, "hit  depth 2");
    int spec2 = indent_of(&at, "specular");
    int hit3 = indent_of(&at, "hit  depth 3");
    int hit2b = indent_of(&at, "hit  depth 2");
    int refract = indent_of(&at, "specular  depth 1  event refract");
    CHECK_MSG(
        hit1 == 4 && spec1 == 6 && hit2 == 8 && spec2 == 10 && hit3 == 12 && hit2b == 8
            && refract == 6,
        "indents %d %d %d %d %d %d %d\n%s",
        hit1,
        spec1,
        hit2,
        spec2,
        hit3,
        hit2b,
        refract,
        text ? text : "");
    free(text);
    text = nested_text(&s, false);
    at = text ? text : "";
    int flat1 = indent_of(&at, "hit  depth 1");
    int flat3 = indent_of(&at, "hit  depth 3");
    CHECK_MSG(flat1 == 4 && flat3 == 4, "a loop's path is not nested: %d %d", flat1, flat3);
    free(text);
    scene_free(&s);
}

TEST(truncated_at_the_limit)
{
    struct scene s = {0};
    if (!load(&s)) {
        return;
    }
    struct recorder *t = recorder_new(&s, 0, 0);
    struct stats st = {.recorder = t};
    recorder_pass_begin(t, 0);
    inspect_sample(&st, 0, 0.5, 0.5, (ray){{0, 0, 5}, {0, 0, -1}});
    for (int i = 0; i < 200000; i++) {
        inspect_end(&st, "again");
    }
    recorder_pass_end(t, vec3_splat(0));
    char *json = written(t, true);
    char *text = written(t, false);
    CHECK(json && strstr(json, "\"truncated\": true"));
    CHECK(text && strstr(text, "(truncated: only the first 131072 events were kept)"));
    free(json);
    free(text);
    recorder_free(t);
    scene_free(&s);
}

TEST(no_recorder_no_events)
{
    struct stats st = {0};
    ray r = {{0, 0, 0}, {0, 0, 1}};
    CHECK(!inspecting(&st));
    inspect_sample(&st, 0, 0, 0, r);
    inspect_miss(&st, 1, r, vec3_splat(1));
    inspect_end(&st, "nothing");
    CHECK(st.recorder == NULL && st.rays_camera == 0);
}

TEST_MAIN(
    TEST_ENTRY(traced_pixel_is_the_rendered_pixel),
    TEST_ENTRY(names_by_line),
    TEST_ENTRY(offsets_are_measured_from_the_spawning_hit),
    TEST_ENTRY(text_indents_by_recursion_depth),
    TEST_ENTRY(truncated_at_the_limit),
    TEST_ENTRY(no_recorder_no_events))
