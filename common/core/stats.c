/* stats.c - the end-of-run report and its JSON form (see stats.h). */
#include "stats.h"

#include <math.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include "atomic_file.h"

void
stats_report_set(struct report *r, const char *key, double value, bool integer)
{
    for (int i = 0; i < r->n_values; i++) {
        if (strcmp(r->values[i].key, key) == 0) {
            r->values[i].value = value;
            r->values[i].integer = integer;
            return;
        }
    }
    if (r->n_values < REPORT_MAX_VALUES) {
        struct report_value *v = &r->values[r->n_values++];
        snprintf(v->key, sizeof v->key, "%s", key);
        v->value = value;
        v->integer = integer;
    }
}

static uint64_t
total_rays(const struct stats *c)
{
    return c->rays_camera + c->rays_shadow + c->rays_secondary;
}

static double
per_second(double count, double seconds)
{
    return seconds > 0 ? count / seconds : 0;
}

void
stats_report_print(FILE *f, const struct report *r)
{
    const struct stats *c = &r->counts;
    double rays = (double)total_rays(c);
    fprintf(
        f,
        "%s: %s, %dx%d, %d spp, %d thread%s\n",
        r->stage,
        r->scene,
        r->width,
        r->height,
        r->spp,
        r->threads,
        r->threads == 1 ? "" : "s");
    fprintf(
        f,
        "  time     %.3f s total: load %.3f s, build %.3f s, render %.3f s (%.3f s CPU)\n",
        r->seconds_total,
        r->seconds_load,
        r->seconds_build,
        r->seconds_render,
        r->seconds_render_cpu);
    fprintf(
        f,
        "  rays     %.4g camera, %.4g shadow, %.4g secondary: %.3f Mrays/s\n",
        (double)c->rays_camera,
        (double)c->rays_shadow,
        (double)c->rays_secondary,
        per_second(rays, r->seconds_render) * 1e-6);
    if (rays > 0) {
        fprintf(
            f,
            "  per ray  %.2f primitive tests, %.2f node visits\n",
            (double)c->prim_tests / rays,
            (double)c->node_visits / rays);
    }
    for (int i = 0; i < STATS_MAX_EXTRA; i++) {
        if (r->extra_names[i]) {
            fprintf(f, "  %-8s %llu\n", r->extra_names[i], (unsigned long long)c->extra[i]);
        }
    }
    for (int i = 0; i < r->n_values; i++) {
        fprintf(f, "  %-8s %.6g\n", r->values[i].key, r->values[i].value);
    }
    if (r->nan_pixels > 0) {
        fprintf(
            f,
            "  WARNING  %llu pixels were NaN or Inf (set to 0 in the image)\n",
            (unsigned long long)r->nan_pixels);
    }
}

/* JSON strings: escape what JSON requires (the scene path is user text). */
static void
json_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (; s && *s; s++) {
        unsigned char ch = (unsigned char)*s;
        if (ch == '"' || ch == '\\') {
            fprintf(f, "\\%c", ch);
        } else if (ch < 0x20) {
            fprintf(f, "\\u%04x", ch);
        } else {
            fputc(ch, f);
        }
    }
    fputc('"', f);
}

static void
json_u64(FILE *f, const char *key, uint64_t v)
{
    fprintf(f, ",\n  \"%s\": %llu", key, (unsigned long long)v);
}

static void
json_real(FILE *f, const char *key, double v)
{
    /* %.17g round-trips a double; JSON has no NaN or Inf. */
    fprintf(f, ",\n  \"%s\": %.17g", key, isfinite(v) ? v : 0.0);
}

void
stats_report_write_json_to(FILE *f, const struct report *r)
{
    const struct stats *c = &r->counts;
    fprintf(f, "{\n  \"stage\": ");
    json_string(f, r->stage);
    fprintf(f, ",\n  \"scene\": ");
    json_string(f, r->scene);
    json_u64(f, "width", (uint64_t)r->width);
    json_u64(f, "height", (uint64_t)r->height);
    json_u64(f, "spp", (uint64_t)r->spp);
    json_u64(f, "threads", (uint64_t)r->threads);
    json_u64(f, "seed", r->seed);
    json_real(f, "seconds_total", r->seconds_total);
    json_real(f, "seconds_load", r->seconds_load);
    json_real(f, "seconds_build", r->seconds_build);
    json_real(f, "seconds_render", r->seconds_render);
    json_real(f, "seconds_render_cpu", r->seconds_render_cpu);
    json_u64(f, "rays_camera", c->rays_camera);
    json_u64(f, "rays_shadow", c->rays_shadow);
    json_u64(f, "rays_secondary", c->rays_secondary);
    json_u64(f, "prim_tests", c->prim_tests);
    json_u64(f, "node_visits", c->node_visits);
    json_u64(f, "nan_pixels", r->nan_pixels);
    json_u64(f, "peak_rss_bytes", r->peak_rss_bytes);
    json_real(f, "rays_per_second", per_second((double)total_rays(c), r->seconds_render));
    for (int i = 0; i < STATS_MAX_EXTRA; i++) {
        if (r->extra_names[i]) {
            json_u64(f, r->extra_names[i], c->extra[i]);
        }
    }
    for (int i = 0; i < r->n_values; i++) {
        if (r->values[i].integer) {
            json_u64(f, r->values[i].key, (uint64_t)r->values[i].value);
        } else {
            json_real(f, r->values[i].key, r->values[i].value);
        }
    }
    fprintf(f, "\n}\n");
}

bool
stats_report_write_json(const struct report *r, const char *path, struct diag *err)
{
    struct atomic_file af;
    if (!atomic_file_open(&af, path, err)) {
        return false;
    }
    stats_report_write_json_to(af.f, r);
    return atomic_file_commit(&af, err);
}

double
stats_clock_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

uint64_t
stats_peak_rss_bytes(void)
{
    struct rusage usage;
    if (getrusage(RUSAGE_SELF, &usage) != 0) {
        return 0;
    }
#ifdef __APPLE__
    return (uint64_t)usage.ru_maxrss; /* macOS reports bytes */
#else
    return (uint64_t)usage.ru_maxrss * 1024u; /* Linux and the BSDs report kilobytes */
#endif
}
