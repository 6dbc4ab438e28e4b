/*
 * aovcheck.h - rendering the render passes (--aov, docs/aov.md) in the
 * stage tests and reading them back: tests/stage/01_aov.c (the passes of
 * every stage) and 02_aov_labels.c (the feature label's shadows, which the
 * stages' shadow rays decide from stage 02 on).
 */
#ifndef AOVCHECK_H
#define AOVCHECK_H

#include <stdbool.h>

#include "image.h"

/* enum aov_label's numbers (docs/aov.md), written out: the tests fix them. */
enum {
    AOVCHECK_BACKGROUND,
    AOVCHECK_LIT,
    AOVCHECK_PENUMBRA,
    AOVCHECK_UMBRA,
    AOVCHECK_MIRROR,
    AOVCHECK_GLASS,
    AOVCHECK_CAUSTIC,
    AOVCHECK_EMITTER,
};

/* Render scene with --aov passes (and -t threads) into a PNG named `name`
 * in the temporary directory; its path, or NULL (with the output printed)
 * on failure. */
const char *
aovcheck_render(const char *scene, const char *name, const char *passes, const char *threads);

/* The pass written beside `image` (aov.h's naming: the stem, the pass,
 * .pfm); false with a message when it cannot be read. */
bool aovcheck_read(const char *image, const char *pass, struct image *out);

/* The strip: a floor (y = 0) seen from straight above, from height
 * AOVCHECK_STRIP_CAMERA, under a sphere of material `ball` (centre
 * (0, 1, 0), radius 0.8) and a 0.8 x 0.8 light at height 3 centred at
 * x = 3, facing down: the sphere's shadow is centred at x = -1.5 (the line
 * from the light's centre through the sphere's).  The image is a strip
 * along the x axis, AOVCHECK_STRIP_W x AOVCHECK_STRIP_H; its feature pass
 * into *feature (`name` names the files). */
#define AOVCHECK_STRIP_W 160
#define AOVCHECK_STRIP_H 20
#define AOVCHECK_STRIP_CAMERA 8.0
bool aovcheck_strip(const char *ball, const char *name, struct image *feature);

/* The column of the strip's image where the floor's point at x is seen,
 * and the label there (on the middle row). */
int aovcheck_strip_column(double x);
int aovcheck_strip_label(const struct image *feature, double x);

#endif /* AOVCHECK_H */
