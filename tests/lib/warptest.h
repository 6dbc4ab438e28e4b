/*
 * warptest.h - goodness-of-fit tests of sampling routines against their own
 * densities, for the labs' function tests (tests/stage/NN_lab_functions.c).
 *
 * After Nori's warptest and pbrt-v4's sampling tests: draw N samples,
 * count them in the cells of a grid over the domain, integrate the claimed
 * density over each cell for the expected counts, and apply Pearson's
 * chi-square test, pooling cells whose expected count is below 5 (Cochran's
 * rule) into one.  A routine whose samples do not follow its density gives
 * a small p-value; the test rejects below the level the caller gives.
 *
 * Two domains: directions (the cells are equal-area bands of z = cos(theta)
 * times sectors of phi, on the hemisphere z > 0 or the whole sphere) and
 * points of the unit square.  The density is integrated numerically over
 * each cell (a midpoint rule on WARPTEST_SUBCELLS^2 sub-cells), so any
 * density the caller can evaluate works, discontinuous ones included.
 */
#ifndef WARPTEST_H
#define WARPTEST_H

#include <stdbool.h>

#define WARPTEST_SUBCELLS 8

/* A histogram of samples over a grid of rows x cols cells. */
struct warptest {
    int rows, cols;
    bool sphere; /* directions: the whole sphere (else the hemisphere z > 0) */
    bool directions; /* directions (else points of [0,1)^2) */
    long n; /* samples added */
    long outside; /* samples off the domain (or not finite): each one fails the test */
    long *counts; /* rows * cols */
};

/* A grid for directions: rows bands of z, cols sectors of phi. */
bool warptest_directions(struct warptest *w, int rows, int cols, bool sphere);

/* A grid for points of [0,1)^2: rows in y, cols in x. */
bool warptest_square(struct warptest *w, int rows, int cols);

void warptest_free(struct warptest *w);

/* Count one sample: a direction (x, y, z), unit length within 1e-6, or a
 * point (x, y) of [0,1)^2 (z ignored). */
void warptest_add(struct warptest *w, double x, double y, double z);

/* A density over the domain: per steradian for directions, per unit area
 * for the square, at direction (x, y, z) or point (x, y). */
typedef double (*warptest_pdf)(double x, double y, double z, const void *ctx);

struct warptest_result {
    double chi2;
    int dof;
    double p; /* the chi-square p-value; 0 when any sample was off the domain */
    double mass; /* the density's integral over the domain (1 for a density) */
    int worst; /* the cell with the largest (observed - expected)^2 / expected */
    double worst_observed, worst_expected;
};

/* Pearson's test of the counts against pdf (NULL: uniform over the domain). */
struct warptest_result warptest_fit(const struct warptest *w, warptest_pdf pdf, const void *ctx);

/* One line that says where the samples disagree with the density most:
 * "N samples: chi2 X (dof D, p P); most off in theta A-B deg, phi C-D deg:
 * O samples, E expected" (or the cell of the square). */
void warptest_describe(
    const struct warptest *w,
    const struct warptest_result *r,
    char *out,
    unsigned long cap);

#endif /* WARPTEST_H */
