/*
 * aov.c - the render passes (aov.h): the first hit of the pixel-centre ray,
 * and the label of what light reaches it (aov_label.c).
 */
#include "aov.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

const char *const aov_pass_names[AOV_COUNT] = {
    "depth",
    "normal",
    "albedo",
    "id",
    "material",
    "feature",
};

const char *const aov_exr_channels[AOV_COUNT] = {"Z", "XYZ", "RGB", "X", "X", "X"};

const char *const aov_label_names[LABEL_COUNT] = {
    "background",
    "diffuse-lit",
    "penumbra",
    "umbra",
    "mirror",
    "glass",
    "caustic",
    "emitter",
};

bool
aov_parse_list(const char *text, unsigned *passes, struct diag *err)
{
    *passes = 0;
    const char *p = text;
    for (;;) {
        size_t len = strcspn(p, ",");
        int found = -1;
        for (int i = 0; i < AOV_COUNT; i++) {
            if (strlen(aov_pass_names[i]) == len && strncmp(aov_pass_names[i], p, len) == 0) {
                found = i;
            }
        }
        if (found < 0) {
            diag_set(
                err,
                NULL,
                0,
                0,
                "--aov: unknown pass '%.*s'; the passes are depth, normal, albedo, id, "
                "material, feature (comma-separated)",
                (int)len,
                p);
            return false;
        }
        *passes |= 1u << found;
        if (p[len] == '\0') {
            return true;
        }
        p += len + 1;
    }
}

bool
aov_as_layers(const char *image_path)
{
    return image_format_from_path(image_path) == IMAGE_FORMAT_EXR;
}

bool
aov_path(const char *image_path, enum aov_pass pass, char *buf, size_t cap)
{
    const char *slash = strrchr(image_path, '/');
    const char *dot = strrchr(image_path, '.');
    size_t stem = dot && (!slash || dot > slash) ? (size_t)(dot - image_path) : strlen(image_path);
    int n = snprintf(buf, cap, "%.*s.%s.pfm", (int)stem, image_path, aov_pass_names[pass]);
    return n >= 0 && (size_t)n < cap;
}

void
aov_pixel(
    const struct aov_source *src,
    const struct scene *scene,
    unsigned passes,
    int px,
    int py,
    vec3 out[AOV_COUNT])
{
    ray r = src->camera_ray(src->ctx, (real)px + (real)0.5, (real)py + (real)0.5);
    struct aov_hit h;
    if (!src->first_hit(src->ctx, r, REAL_MAX, &h)) {
        out[AOV_DEPTH] = vec3_splat(0);
        out[AOV_NORMAL] = vec3_splat(0);
        out[AOV_ALBEDO] = vec3_splat(0);
        out[AOV_ID] = vec3_splat(-1);
        out[AOV_MATERIAL] = vec3_splat(-1);
        out[AOV_FEATURE] = vec3_splat(LABEL_BACKGROUND);
        return;
    }
    out[AOV_DEPTH] = vec3_splat(vec3_length(vec3_sub(h.p, scene->camera.origin)));
    out[AOV_NORMAL] = h.n;
    out[AOV_ALBEDO] = h.albedo;
    out[AOV_ID] = vec3_splat((real)h.prim);
    out[AOV_MATERIAL] = vec3_splat((real)h.material);
    /* The label alone costs shadow rays: only when asked for. */
    out[AOV_FEATURE] = vec3_splat(0);
    if (passes & (1u << AOV_FEATURE)) {
        out[AOV_FEATURE] = vec3_splat((real)aov_label_at(src, scene, &h));
    }
}

/* What the driver's tile function needs. */
struct aov_job {
    const struct aov_source *src;
    const struct scene *scene;
    unsigned passes;
    struct image *out;
};

/* Every pass of pixel (px, py) into its image (each pixel is written by
 * one thread only). */
static void
aov_job_store(const struct aov_job *job, int px, int py)
{
    vec3 values[AOV_COUNT];
    aov_pixel(job->src, job->scene, job->passes, px, py, values);
    for (int pass = 0; pass < AOV_COUNT; pass++) {
        if (job->passes & (1u << pass)) {
            float *rgb = image_pixel(&job->out[pass], px, py);
            rgb[0] = (float)values[pass].x;
            rgb[1] = (float)values[pass].y;
            rgb[2] = (float)values[pass].z;
        }
    }
}

/* The driver's tile function (driver.h): the passes of each pixel go to
 * their images; the driver's own image is left black. */
static bool
aov_job_tile(const void *ctx, const struct tile *tile, struct stats *st)
{
    (void)st;
    for (int py = tile->y0; py < tile->y1; py++) {
        for (int px = tile->x0; px < tile->x1; px++) {
            if (driver_stop_requested()) {
                return false;
            }
            aov_job_store(ctx, px, py);
            tile_put(tile, px, py, vec3_splat(0));
        }
    }
    return true;
}

static void
free_passes(struct image out[AOV_COUNT])
{
    for (int pass = 0; pass < AOV_COUNT; pass++) {
        image_free(&out[pass]);
    }
}

bool
aov_render(
    const struct aov_source *src,
    const struct scene *scene,
    unsigned passes,
    const struct render_job *like,
    struct image out[AOV_COUNT],
    bool *interrupted,
    struct diag *err)
{
    *interrupted = false;
    for (int pass = 0; pass < AOV_COUNT; pass++) {
        out[pass] = (struct image){0};
    }
    for (int pass = 0; pass < AOV_COUNT; pass++) {
        if ((passes & (1u << pass)) && !image_alloc(&out[pass], like->width, like->height, err)) {
            free_passes(out);
            return false;
        }
    }
    struct aov_job ctx = {src, scene, passes, out};
    struct render_job job = {
        .width = like->width,
        .height = like->height,
        .threads = like->threads,
        .passes = 1,
        .seed = like->seed,
        .progress = like->progress,
        .tile = aov_job_tile,
        .ctx = &ctx,
    };
    struct image unused = {0};
    struct render_result result;
    bool ok = driver_render_image(&job, &unused, &result, err);
    image_free(&unused);
    if (!ok || result.passes_done == 0) {
        *interrupted = ok;
        free_passes(out);
        return false;
    }
    return true;
}
