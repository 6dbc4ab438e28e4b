/*
 * 07_trace.c - what a traced path says (docs/inspect.md), stage 07:
 *   - every path ends once, and the trace says how: Russian roulette
 *     ("stops"), an emitter hit, a ray leaving the scene, or an `end` event
 *     (--max-depth, nothing reflects); so those events number the samples,
 *     at every seed, and no roulette follows an ending;
 *   - Russian roulette: q in (0, 1], and the path stops exactly when the
 *     number drawn is u >= q; 1 before --rr-depth;
 *   - each diffuse bounce multiplies the throughput by the albedo (the
 *     weight f cos / pdf of a cosine-weighted direction), and its pdf is a
 *     density cos(theta) / pi <= 1 / pi;
 *   - a diffuse bounce that hits the light adds nothing (its `emission`
 *     radiance is 0): next-event estimation counted that light;
 *   - at the rim of a bubble (ior 0.6) the sampled lobe is total internal
 *     reflection, with probability 1;
 *   - --pixel with --time is refused (a replay needs a fixed number of
 *     samples).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "pathcheck.h"
#include "stagecheck.h"
#include "testlib.h"
#include "tracecheck.h"
#include "vec3.h"

#define CAP 4096
#define MAX_EVENTS 4096

/* A closed grey room with an opening, lit from the ceiling by a square
 * light of side 2 * half centred under it, of radiance L. */
static const char *
lit_room_scene(const char *name, double half, double radiance)
{
    return stagecheck_scene(
        name,
        "camera origin 0 1 3.5 target 0 1 0 up 0 1 0 fov 45\n"
        "image width 16 height 16\n"
        "material grey diffuse albedo 0.5 0.5 0.5\n"
        "quad corner -1 0 -1 edge1 0 0 2 edge2 2 0 0 material grey\n"
        "quad corner -1 2 -1 edge1 2 0 0 edge2 0 0 2 material grey\n"
        "quad corner -1 0 -1 edge1 2 0 0 edge2 0 2 0 material grey\n"
        "quad corner -1 0 -1 edge1 0 2 0 edge2 0 0 2 material grey\n"
        "quad corner 1 0 -1 edge1 0 0 2 edge2 0 2 0 material grey\n"
        "area_light corner %g 1.98 %g edge1 %g 0 0 edge2 0 0 %g radiance %g %g %g\n",
        -half,
        -half,
        2 * half,
        2 * half,
        radiance,
        radiance,
        radiance);
}

/* The room with a small bright light. */
static const char *
room_scene(void)
{
    return lit_room_scene("room.scene", 0.3, 10);
}

/* Whether, in the JSON trace `json`, an event of type `ending` is ever
 * followed by a roulette event (the next "type" after it): a path that
 * ended draws no roulette number. */
static bool
roulette_after(const char *json, const char *ending)
{
    char key[64];
    snprintf(key, sizeof key, "\"type\": \"%s\"", ending);
    for (const char *p = strstr(json, key); p; p = strstr(p + 1, key)) {
        const char *next = strstr(p + strlen(key), "\"type\": ");
        if (next && strncmp(next, "\"type\": \"roulette\"", 18) == 0) {
            return true;
        }
    }
    return false;
}

/* Pixel (8, 10)'s 16 samples in the room at one seed. */
static void
check_path_endings(uint64_t seed)
{
    char seed_text[32];
    snprintf(seed_text, sizeof seed_text, "%llu", (unsigned long long)seed);
    const char *const args[] = {"-s", "16", "--seed", seed_text, NULL};
    const char *trace = tracecheck_pixel(room_scene(), 8, 10, args);
    if (!trace) {
        CHECK(false);
        return;
    }
    int samples = tracecheck_count(trace, "\"type\": \"radiance\"");
    int stops = tracecheck_count(trace, "\"outcome\": \"stops\"");
    int ends = tracecheck_count(trace, "\"type\": \"end\"");
    int emitters = tracecheck_count(trace, "\"type\": \"emission\"");
    int misses = tracecheck_count(trace, "\"type\": \"miss\"");
    CHECK_MSG(
        samples == 16 && stops + ends + emitters + misses == samples,
        "seed %s: %d samples; %d roulette stops, %d ends, %d emitter hits, %d misses",
        seed_text,
        samples,
        stops,
        ends,
        emitters,
        misses);
    char *json = test_read_file(trace, NULL);
    CHECK_MSG(
        json && !roulette_after(json, "emission") && !roulette_after(json, "end"),
        "seed %s: a roulette record after a path ended (an emitter hit or an end)",
        seed_text);
    free(json);
    static double q[MAX_EVENTS], u[MAX_EVENTS];
    int n = tracecheck_numbers(trace, "\"q\": ", q, MAX_EVENTS);
    CHECK(n == tracecheck_numbers(trace, "\"u\": ", u, MAX_EVENTS) && n > 0 && n <= MAX_EVENTS);
    int stopped = 0;
    for (int i = 0; i < n && i < MAX_EVENTS; i++) {
        CHECK(q[i] > 0 && q[i] <= 1 && u[i] >= 0 && u[i] < 1);
        stopped += u[i] >= q[i];
    }
    CHECK(stopped == stops);
    /* Diffuse bounces: beta_after = beta_before x 0.5, pdf <= 1 / pi. */
    static double before[MAX_EVENTS], after[MAX_EVENTS], pdf[MAX_EVENTS];
    int b = tracecheck_numbers(trace, "\"beta_before\": [", before, MAX_EVENTS);
    CHECK(b == tracecheck_numbers(trace, "\"beta_after\": [", after, MAX_EVENTS) && b > 0);
    CHECK(b == tracecheck_numbers(trace, "\"pdf\": ", pdf, MAX_EVENTS));
    for (int i = 0; i < b && i < MAX_EVENTS; i++) {
        CHECK_NEAR(after[i], 0.5 * before[i], 1e-6 * before[i]);
        CHECK(pdf[i] > 0 && pdf[i] <= 0.31830988618379070 + 1e-9 /* 1 / pi */);
    }
}

/* An identity, not an estimate: it holds at every seed, so four are tried
 * (from pathcheck_seed(), so that other seeds can be tried too). */
TEST(every_path_ends_once_and_says_why)
{
    uint64_t first = pathcheck_seed(1);
    for (uint64_t seed = first; seed < first + 4; seed++) {
        check_path_endings(seed);
    }
}

/* The room with a light large enough for bounces to hit it often. */
static const char *
big_light_scene(void)
{
    return lit_room_scene("big_light.scene", 0.8, 2);
}

/* Of pixel (8, 10)'s 64 samples in the big-light room with args, the
 * emissions found by a diffuse bounce (-1: no trace) and, in *lit, how
 * many of them add light. */
static int
diffuse_bounce_emissions(const char *const args[], int *lit)
{
    const char *trace = tracecheck_pixel(big_light_scene(), 8, 10, args);
    size_t len;
    char *json = trace ? test_read_file(trace, &len) : NULL;
    if (!json) {
        return -1;
    }
    int found = 0;
    *lit = 0;
    for (const char *p = strstr(json, "\"type\": \"emission\""); p;
         p = strstr(p + 1, "\"type\": \"emission\"")) {
        const char *next = strstr(p + 1, "\"type\": ");
        const char *f = strstr(p, "\"found_by\": \"diffuse bounce\"");
        if (!f || (next && f > next)) {
            continue; /* found by the camera or a specular bounce */
        }
        const char *r = strstr(p, "\"radiance\": [");
        double c[3] = {-1, -1, -1};
        CHECK(r && sscanf(r, "\"radiance\": [%lf, %lf, %lf]", &c[0], &c[1], &c[2]) == 3);
        *lit += c[0] != 0 || c[1] != 0 || c[2] != 0;
        found++;
    }
    free(json);
    return found;
}

/* The shadow rays of the vertex the bounce left counted that light; from
 * stage 08 on, with MIS, the bounce counts it too, weighted. */
TEST(bounce_hitting_the_light_adds_nothing_under_nee)
{
    const char *const plain[] = {"-s", "64", "--shadow-samples", "1", NULL};
    const char *const no_mis[] = {"-s", "64", "--shadow-samples", "1", "--no-mis", NULL};
    bool mis_stage = atoi(STAGE_NAME) >= 8;
    int lit;
    int found = diffuse_bounce_emissions(mis_stage ? no_mis : plain, &lit);
    CHECK_MSG(found >= 1, "no diffuse bounce hit the light in 64 samples");
    CHECK_MSG(lit == 0, "%d of %d emissions counted twice", lit, found);
    if (mis_stage) {
        found = diffuse_bounce_emissions(plain, &lit);
        CHECK_MSG(found >= 1 && lit >= 1, "MIS: %d of %d emissions weighed in", lit, found);
    }
}

TEST(max_depth_ends_paths)
{
    const char *const args[] = {"-s", "4", "--no-rr", "--max-depth", "3", NULL};
    const char *trace = tracecheck_pixel(room_scene(), 8, 10, args);
    CHECK(trace && tracecheck_count(trace, "\"type\": \"roulette\"") == 0);
    int ends = trace ? tracecheck_count(trace, "max-depth") : 0;
    int others = trace ? tracecheck_count(trace, "\"type\": \"emission\"")
                             + tracecheck_count(trace, "\"type\": \"miss\"")
                       : 0;
    CHECK_MSG(ends >= 1 && ends + others == 4, "%d max-depth ends, %d other ends", ends, others);
    CHECK(trace && tracecheck_count(trace, "\"depth\": 4") == 0);
}

TEST(bubble_rim_samples_total_internal_reflection)
{
    const char *scene = stagecheck_scene(
        "bubble.scene",
        "camera origin 0 0 5 target 0 0 0 up 0 1 0 fov 30\n"
        "image width 31 height 31\n"
        "background color 0.5 0.5 0.5\n"
        "material bubble glass ior 0.6\n"
        "sphere center 0 0 0 radius 1 material bubble\n");
    const char *const args[] = {"-s", "1", "--aa", "grid", NULL};
    const char *trace = tracecheck_pixel(scene, 26, 15, args);
    CHECK(trace && tracecheck_count(trace, "\"lobe\": \"total internal reflection\"") >= 1);
    double pdf[1];
    CHECK(trace && tracecheck_numbers(trace, "\"pdf\": ", pdf, 1) >= 1);
    CHECK_NEAR(pdf[0], 1.0, 0.0);
}

TEST(time_limit_is_refused)
{
    const char *const args[] = {"--pixel", "1,1", "--time", "1", NULL};
    char out[CAP];
    int status = test_render(room_scene(), args, out, sizeof out);
    CHECK_MSG(status == 2 && strstr(out, "--time"), "exit %d\n%s", status, out);
}

TEST_MAIN(
    TEST_ENTRY(every_path_ends_once_and_says_why),
    TEST_ENTRY(bounce_hitting_the_light_adds_nothing_under_nee),
    TEST_ENTRY(max_depth_ends_paths),
    TEST_ENTRY(bubble_rim_samples_total_internal_reflection),
    TEST_ENTRY(time_limit_is_refused))
