/*
 * 02_aov_labels.c - the feature pass's shadows (--aov feature, docs/aov.md),
 * from stage 02 on, where the stage's own shadow rays (its spawn_ray_to,
 * stages/NN_name/passes.c) decide them.  On the strip of aovcheck.h (a
 * floor seen from above, a sphere over it, a square light beside):
 *   - under a diffuse sphere the shadow's centre is umbra, far away is
 *     diffuse-lit, and between them penumbra, in that order along a line,
 *     with at least two penumbra pixels; the sphere's top, which faces the
 *     light, is lit;
 *   - under a glass sphere the shadow is a caustic; under a mirror, umbra.
 * A shadow ray that starts on its own curved surface (no offset off it,
 * LAB 02's spawn_ray) can find that surface in its way: the sphere's top
 * is then in its own shadow.
 */
#include "aovcheck.h"
#include "check.h"

TEST(feature_labels_along_a_shadow)
{
    struct image f = {0};
    CHECK(aovcheck_strip("diffuse albedo 0.5 0.5 0.5", "shadow", &f));
    if (!f.rgb) {
        return;
    }
    int centre = aovcheck_strip_label(&f, -1.5);
    CHECK_MSG(centre == AOVCHECK_UMBRA, "shadow centre: %d", centre);
    CHECK_MSG(
        aovcheck_strip_label(&f, -6) == AOVCHECK_LIT,
        "far floor: %d",
        aovcheck_strip_label(&f, -6));
    /* Leftwards from the shadow's centre: umbra, then penumbra, then lit,
     * never back. */
    const int order[] = {AOVCHECK_UMBRA, AOVCHECK_PENUMBRA, AOVCHECK_LIT};
    int at = 0, penumbra = 0;
    for (int x = aovcheck_strip_column(-1.5); x >= 0; x--) {
        int label = (int)image_pixel(&f, x, AOVCHECK_STRIP_H / 2)[0];
        penumbra += label == AOVCHECK_PENUMBRA;
        while (at < 3 && label != order[at]) {
            at++;
        }
        CHECK_MSG(at < 3, "column %d: label %d out of the order umbra, penumbra, lit", x, label);
        if (at == 3) {
            break;
        }
    }
    CHECK_MSG(penumbra >= 2, "%d penumbra pixels between umbra and lit", penumbra);
    int top = aovcheck_strip_label(&f, 0);
    CHECK_MSG(top == AOVCHECK_LIT, "the sphere's top, facing the light: %d", top);
    image_free(&f);
}

TEST(glass_casts_a_caustic_and_a_mirror_a_shadow)
{
    struct image glass = {0}, mirror = {0};
    CHECK(aovcheck_strip("glass ior 1.5", "glass", &glass));
    CHECK(aovcheck_strip("mirror reflectance 0.9 0.9 0.9", "mirror", &mirror));
    if (glass.rgb && mirror.rgb) {
        int under_glass = aovcheck_strip_label(&glass, -1.5);
        int under_mirror = aovcheck_strip_label(&mirror, -1.5);
        CHECK_MSG(under_glass == AOVCHECK_CAUSTIC, "under glass: %d", under_glass);
        CHECK_MSG(under_mirror == AOVCHECK_UMBRA, "under the mirror: %d", under_mirror);
    }
    image_free(&glass);
    image_free(&mirror);
}

TEST_MAIN(
    TEST_ENTRY(feature_labels_along_a_shadow),
    TEST_ENTRY(glass_casts_a_caustic_and_a_mirror_a_shadow))
