/*
 * run_load.c - loading the scene for a stage's main() (run.h,
 * run_load_scene): the scene file, its meshes' files, what the stage does
 * not model (a warning each, or --strict's refusal) and the memory the
 * render will need against --max-memory, all before any work.
 */
#include <stdint.h>
#include <string.h>

#include "run.h"

/* A note says what is not modelled and, after its first "; ", what the
 * stage does instead (run.h's unmodelled_fn); under --strict the stage does
 * nothing instead, so that part is replaced by the refusal. */
static void
print_unmodelled(const struct diag *note, bool strict)
{
    if (!strict) {
        diag_print(stderr, note, "warning");
        return;
    }
    struct diag refused = *note;
    char *instead = strstr(refused.msg, "; ");
    size_t at = instead ? (size_t)(instead - refused.msg) : strlen(refused.msg);
    snprintf(refused.msg + at, sizeof refused.msg - at, "; --strict refuses the scene");
    diag_print(stderr, &refused, "error");
}

/* Say, once per feature, what this stage does not model, then what no
 * stage models (the scene's notes); under --strict that is an error.
 * Returns false when the scene is refused. */
static bool
report_unmodelled(const struct run *run, unsigned modelled, unmodelled_fn unmodelled)
{
    const struct scene *s = &run->scene;
    struct diag notes[FEAT_COUNT + SCENE_MAX_NOTES];
    int n = unmodelled(s, modelled, run->stage, notes, FEAT_COUNT);
    for (int i = 0; i < s->n_notes && i < SCENE_MAX_NOTES; i++) {
        notes[n++] = s->notes[i];
    }
    for (int i = 0; i < n; i++) {
        print_unmodelled(&notes[i], run->opt.strict);
    }
    return !(run->opt.strict && n > 0);
}

/* The files the scene read besides itself (meshes, their external buffers
 * and images) are inputs too. */
static bool
check_mesh_files(struct run *run)
{
    const struct scene *s = &run->scene;
    for (int i = 0; i < s->n_input_files; i++) {
        const struct named_file mesh = {"a file the scene reads,", s->input_files[i]};
        if (!run_check_identities(run, &mesh, 1)) {
            return false;
        }
    }
    return true;
}

/* --max-memory in bytes. */
static uint64_t
memory_limit(const struct run *run)
{
    return (uint64_t)run->opt.max_memory_mib << 20;
}

/* What an acceleration structure may take per primitive: the BVH of stages
 * 05-07 holds at most two 32-byte nodes, a 4-byte index and three leaf
 * vertices (vec3) per primitive and builds with a 16-byte record of each,
 * 156 bytes in double; rounded up to a bound with room to spare.  Stages
 * 01-04 hold none: for them it overestimates. */
#define ACCEL_BYTES_PER_PRIMITIVE 256

/* Refuse, before anything is allocated for it, a render whose estimate
 * passes --max-memory: the scene's arrays (loaded within the limit), the
 * acceleration structure, and what the tile driver allocates for the image
 * (docs/robustness.md). */
static bool
check_memory(const struct run *run, struct diag *err)
{
    const struct scene *s = &run->scene;
    struct render_job job = {.threads = cli_thread_count(&run->opt)};
    run_image_size(s, &run->opt, &job.width, &job.height);
    uint64_t primitives = (uint64_t)s->n_spheres + (uint64_t)s->n_quads + (uint64_t)s->n_triangles
                          + (uint64_t)s->n_area_lights;
    uint64_t image = driver_job_bytes(&job);
    /* --aov: an image per pass, and the driver's buffers of their job. */
    uint64_t pixels = (uint64_t)job.width * (uint64_t)job.height;
    for (int pass = 0; pass < AOV_COUNT; pass++) {
        image += run->opt.aov & (1u << pass) ? pixels * 3 * sizeof(float) : 0;
    }
    image += run->opt.aov ? driver_job_bytes(&job) : 0;
    uint64_t accel = primitives * ACCEL_BYTES_PER_PRIMITIVE;
    uint64_t total = scene_bytes(s) + accel + image;
    if (total <= memory_limit(run)) {
        return true;
    }
    diag_set(
        err,
        run->opt.scene_path,
        0,
        0,
        "the render would need about %llu MiB (a %dx%d image: %llu MiB; %llu primitives x %d "
        "bytes: %llu MiB; the scene: %llu MiB), more than the memory limit of %d MiB; raise it "
        "with --max-memory, or ask for a smaller image with -W/-H",
        (unsigned long long)(total >> 20),
        job.width,
        job.height,
        (unsigned long long)(image >> 20),
        (unsigned long long)primitives,
        ACCEL_BYTES_PER_PRIMITIVE,
        (unsigned long long)(accel >> 20),
        (unsigned long long)(scene_bytes(s) >> 20),
        run->opt.max_memory_mib);
    return false;
}

bool
run_load_scene(struct run *run, unsigned modelled, unmodelled_fn unmodelled)
{
    struct diag err;
    const struct scene_options load = {.camera = run->opt.camera, .max_bytes = memory_limit(run)};
    if (!scene_load_with(run->opt.scene_path, &load, &run->scene, &err)) {
        /* Memory the system refused within --max-memory is no fault of the
         * scene's. */
        diag_print(stderr, &err, "error");
        run->status = err.kind == DIAG_NO_MEMORY ? EXIT_RESOURCES : EXIT_INPUT;
        return false;
    }
    run->scene_loaded = true;
    if (!check_mesh_files(run)) {
        run_free(run);
        return false;
    }
    if (!report_unmodelled(run, modelled, unmodelled)) {
        run_free(run);
        run->status = EXIT_INPUT;
        return false;
    }
    if (!check_memory(run, &err)) {
        diag_print(stderr, &err, "error");
        run_free(run);
        run->status = EXIT_INPUT;
        return false;
    }
    run->rep.seconds_load = stats_clock_seconds() - run->start;
    return true;
}
