/* aovcheck.c - the render passes in the stage tests (aovcheck.h). */
#include "aovcheck.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "stagecheck.h"
#include "testlib.h"

#define STRIP_FOV 30.0
#define PI_D 3.14159265358979323846

const char *
aovcheck_render(const char *scene, const char *name, const char *passes, const char *threads)
{
    const char *out = test_tmp_path(name);
    const char *args[] = {"--aov", passes, "-t", threads, "-o", out, NULL};
    char log[4096];
    int status = test_render(scene, args, log, sizeof log);
    if (status != 0) {
        printf("render --aov %s failed (status %d):\n%s\n", passes, status, log);
        return NULL;
    }
    return out;
}

bool
aovcheck_read(const char *image, const char *pass, struct image *out)
{
    char path[1024];
    snprintf(path, sizeof path, "%.*s.%s.pfm", (int)(strrchr(image, '.') - image), image, pass);
    struct diag err;
    if (!image_read_pfm(path, out, &err)) {
        printf("cannot read %s: %s\n", path, err.msg);
        return false;
    }
    return true;
}

bool
aovcheck_strip(const char *ball, const char *name, struct image *feature)
{
    char scene_name[64], image_name[64];
    snprintf(scene_name, sizeof scene_name, "%s.scene", name);
    snprintf(image_name, sizeof image_name, "%s.png", name);
    const char *scene = stagecheck_scene(
        scene_name,
        "camera origin 0 %g 0 target 0 0 0 up 0 0 -1 fov %g\n"
        "image width %d height %d\n"
        "material grey diffuse albedo 0.5 0.5 0.5\n"
        "material ball %s\n"
        "quad corner -50 0 -50 edge1 0 0 100 edge2 100 0 0 material grey\n"
        "sphere center 0 1 0 radius 0.8 material ball\n"
        "area_light corner 2.6 3 -0.4 edge1 0.8 0 0 edge2 0 0 0.8 radiance 4 4 4\n",
        AOVCHECK_STRIP_CAMERA,
        STRIP_FOV,
        AOVCHECK_STRIP_W,
        AOVCHECK_STRIP_H,
        ball);
    const char *out = scene ? aovcheck_render(scene, image_name, "feature", "2") : NULL;
    return out && aovcheck_read(out, "feature", feature);
}

int
aovcheck_strip_column(double x)
{
    double half_width = tan(STRIP_FOV * PI_D / 360) * AOVCHECK_STRIP_W / AOVCHECK_STRIP_H;
    return (int)floor((x / AOVCHECK_STRIP_CAMERA / half_width + 1) * AOVCHECK_STRIP_W / 2);
}

int
aovcheck_strip_label(const struct image *feature, double x)
{
    return (int)image_pixel(feature, aovcheck_strip_column(x), AOVCHECK_STRIP_H / 2)[0];
}
