/*
 * 07_sphere_light.c - the path tracer's direct light from a sphere light
 * agrees with stage 03's.  Direct light only (--max-depth 2: the camera
 * ray and one segment to the light), a floor lit by a sphere light past a
 * wall that shadows part of it, everything the camera sees smooth (no
 * edges on the film, so stage 03's one ray through each pixel centre and
 * 07's samples over the pixel have the same expectation).
 *
 * Two independent estimators of the same image: stage 03 samples the
 * sphere by the cone of directions it subtends (shadow rays, 16 per
 * point), 07 with --no-nee finds the light only by the directions its
 * diffuse bounces sample (cosine-weighted), counting its radiance where a
 * bounce hits it.  A wrong cone, a wrong solid angle or a wrong visibility
 * test in either shows as a difference.  Per 16 x 16 block and channel and
 * for the whole image: Welch's t-test of the block means of K renders of
 * each (pathcheck_block_welch), at alpha = 0.01 Sidak-corrected for all of
 * them.  07 with next-event estimation (the same cone sampling, through its
 * own light.c) is compared with both.  Where stage 03 is not built (a lab
 * handout holds one stage), 07 with next-event estimation stands in for it,
 * and the test says so.
 */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "pathcheck.h"
#include "stagecheck.h"
#include "stattest.h"
#include "testlib.h"

/* Three comparisons of two sets of renders. */
#define N_STAT_TESTS \
    (3 * pathcheck_sets_agree_tests(PATHCHECK_SETS_SIZE, PATHCHECK_SETS_SIZE, PATHCHECK_SETS_BLOCK))

/* The camera looks straight down at the floor from height 3 (the floor
 * fills the view); the sphere light (radius 0.5, radiance 20) and the wall
 * (x = 1.3, from height 1 to 2.2, z <= 0) are outside the view. */
static const char scene_text[] = "camera origin 0 3 0 target 0 0 0 up 0 0 -1 fov 60\n"
                                 "image width 64 height 64\n"
                                 "material floor diffuse albedo 0.5 0.5 0.5\n"
                                 "material black diffuse albedo 0 0 0\n"
                                 "quad corner -20 0 -20 edge1 0 0 40 edge2 40 0 0 material floor\n"
                                 "quad corner 1.3 1 -3 edge1 0 0 3 edge2 0 1.2 0 material black\n"
                                 "sphere_light center 1.8 1.6 -0.4 radius 0.5 radiance 20 20 20\n";

/* Stage 03's binary beside this stage's (RENDER), or NULL. */
static const char *
stage03_binary(void)
{
    static char path[4096];
    const char *render = test_render_binary();
    const char *at = render ? strstr(render, "07_pathtrace/render") : NULL;
    if (!at) {
        return NULL;
    }
    snprintf(path, sizeof path, "%.*s03_soft_shadows/render", (int)(at - render), render);
    return test_file_exists(path) ? path : NULL;
}

/* K renders with `binary` (NULL: this stage's), spp samples per pixel (0:
 * the binary's own sampling, for stage 03) and the extra arguments. */
static bool
render_with(
    const char *binary,
    const char *scene,
    int spp,
    const char *const args[],
    uint64_t seed,
    struct pathcheck_batches *out)
{
    char *saved = strdup(test_render_binary());
    if (binary) {
        setenv("RENDER", binary, 1);
    }
    bool ok = saved
              && pathcheck_render_sized(
                  scene,
                  PATHCHECK_SETS_SIZE,
                  spp,
                  args,
                  PATHCHECK_SETS_K,
                  seed,
                  out);
    if (saved) {
        setenv("RENDER", saved, 1);
    }
    free(saved);
    CHECK_MSG(ok, "renders failed or have NaN pixels");
    return ok;
}

static void
compare(const char *what, const struct pathcheck_batches *a, const struct pathcheck_batches *b)
{
    double level = stattest_sidak(PATHCHECK_ALPHA, N_STAT_TESTS);
    CHECK_MSG(pathcheck_sets_agree(what, a, b, PATHCHECK_SETS_BLOCK, level), "%s differ", what);
}

TEST(direct_light_agrees_with_stage_03)
{
    const char *scene = test_tmp_path("sphere_lit.scene");
    test_write_file(scene, scene_text);
    uint64_t seed = pathcheck_seed(7300);
    static const char *const nee[] = {"--max-depth", "2", NULL};
    static const char *const no_nee[] = {"--max-depth", "2", "--no-nee", NULL};
    const char *binary03 = stage03_binary();
    struct pathcheck_batches with_nee = {0};
    struct pathcheck_batches without_nee = {0};
    struct pathcheck_batches direct03 = {0};
    bool ok = render_with(NULL, scene, 16, nee, seed, &with_nee)
              && render_with(NULL, scene, 16, no_nee, seed + 100, &without_nee);
    if (ok && binary03) {
        ok = render_with(binary03, scene, 0, NULL, seed + 200, &direct03);
    } else if (ok) {
        printf("stage 03 is not built here: 07 with next-event estimation stands in for it\n");
    }
    if (ok) {
        const struct pathcheck_batches *reference = binary03 ? &direct03 : &with_nee;
        compare("07 --no-nee vs 03", &without_nee, reference);
        compare("07 (NEE) vs 03", &with_nee, reference);
        compare("07 (NEE) vs 07 --no-nee", &with_nee, &without_nee);
    }
    pathcheck_batches_free(&with_nee);
    pathcheck_batches_free(&without_nee);
    pathcheck_batches_free(&direct03);
}

TEST_MAIN(TEST_ENTRY(direct_light_agrees_with_stage_03))
