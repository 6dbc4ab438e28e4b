/*
 * warptest.c - chi-square goodness-of-fit tests of sampling routines
 * (warptest.h).
 */
#include "warptest.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "stattest.h"

static const double pi = 3.14159265358979323846;

static bool
warptest_make(struct warptest *w, int rows, int cols, bool directions, bool sphere)
{
    *w = (struct warptest){.rows = rows, .cols = cols, .directions = directions, .sphere = sphere};
    w->counts =
        rows > 0 && cols > 0 ? calloc((size_t)rows * (size_t)cols, sizeof *w->counts) : NULL;
    return w->counts != NULL;
}

bool
warptest_directions(struct warptest *w, int rows, int cols, bool sphere)
{
    return warptest_make(w, rows, cols, true, sphere);
}

bool
warptest_square(struct warptest *w, int rows, int cols)
{
    return warptest_make(w, rows, cols, false, false);
}

void
warptest_free(struct warptest *w)
{
    free(w->counts);
    w->counts = NULL;
}

/* The lowest z of the domain: -1 on the sphere, 0 on the hemisphere. */
static double
z_min(const struct warptest *w)
{
    return w->sphere ? -1 : 0;
}

/* Cell coordinates (0..1 across the grid) of a sample, or false. */
static bool
cell_of(const struct warptest *w, double x, double y, double z, double *a, double *b)
{
    if (w->directions) {
        double len = sqrt(x * x + y * y + z * z);
        if (!(fabs(len - 1) < 1e-6) || z < z_min(w)) {
            return false;
        }
        double phi = atan2(y, x);
        *a = (z - z_min(w)) / (1 - z_min(w)); /* equal-area bands (Archimedes) */
        *b = (phi < 0 ? phi + 2 * pi : phi) / (2 * pi);
    } else {
        if (!(x >= 0 && x < 1 && y >= 0 && y < 1)) {
            return false;
        }
        *a = y;
        *b = x;
    }
    return true;
}

void
warptest_add(struct warptest *w, double x, double y, double z)
{
    double a;
    double b;
    w->n++;
    if (!cell_of(w, x, y, z, &a, &b)) {
        w->outside++;
        return;
    }
    int row = (int)(a * w->rows);
    int col = (int)(b * w->cols);
    row = row < w->rows ? row : w->rows - 1;
    col = col < w->cols ? col : w->cols - 1;
    w->counts[row * w->cols + col]++;
}

/* The density's integral over cell (row, col): a midpoint rule on
 * sub-cells.  Directions: dw = dz dphi over the bands of z. */
/* The uniform density of the domain (warptest_fit's pdf NULL). */
static double
uniform_pdf(const struct warptest *w)
{
    return w->directions ? 1 / ((1 - z_min(w)) * 2 * pi) : 1;
}

static double
cell_integral(const struct warptest *w, int row, int col, warptest_pdf pdf, const void *ctx)
{
    int k = WARPTEST_SUBCELLS;
    double sum = 0;
    for (int i = 0; i < k; i++) {
        for (int j = 0; j < k; j++) {
            double a = (row + (i + 0.5) / k) / w->rows;
            double b = (col + (j + 0.5) / k) / w->cols;
            if (!pdf) {
                sum += uniform_pdf(w);
            } else if (w->directions) {
                double z = z_min(w) + a * (1 - z_min(w));
                double phi = 2 * pi * b;
                double s = sqrt(fmax(0, 1 - z * z));
                sum += pdf(s * cos(phi), s * sin(phi), z, ctx);
            } else {
                sum += pdf(b, a, 0, ctx);
            }
        }
    }
    double cell_measure = w->directions ? (1 - z_min(w)) * 2 * pi / (w->rows * (double)w->cols)
                                        : 1 / (w->rows * (double)w->cols);
    return sum / (k * k) * cell_measure;
}

struct warptest_result
warptest_fit(const struct warptest *w, warptest_pdf pdf, const void *ctx)
{
    struct warptest_result r = {.worst = -1};
    int cells = w->rows * w->cols;
    double pooled_obs = 0;
    double pooled_exp = 0;
    int bins = 0;
    double worst = -1;
    for (int c = 0; c < cells; c++) {
        double integral = cell_integral(w, c / w->cols, c % w->cols, pdf, ctx);
        double e = integral * (double)w->n;
        double o = (double)w->counts[c];
        r.mass += integral;
        if (e < 5) {
            /* Cochran's rule: cells expecting under 5 are pooled. */
            pooled_obs += o;
            pooled_exp += e;
            continue;
        }
        double term = (o - e) * (o - e) / e;
        r.chi2 += term;
        bins++;
        if (term > worst) {
            worst = term;
            r.worst = c;
            r.worst_observed = o;
            r.worst_expected = e;
        }
    }
    if (pooled_exp > 0 || pooled_obs > 0) {
        /* Samples where the density expects (almost) none count in full. */
        double e = fmax(pooled_exp, 1e-9);
        r.chi2 += (pooled_obs - e) * (pooled_obs - e) / e;
        bins++;
    }
    r.dof = bins > 1 ? bins - 1 : 1;
    r.p = w->outside > 0 ? 0 : stattest_chi2_pvalue(r.chi2, r.dof);
    return r;
}

void
warptest_describe(
    const struct warptest *w,
    const struct warptest_result *r,
    char *out,
    unsigned long cap)
{
    int n = snprintf(
        out,
        cap,
        "%ld samples: chi2 %.1f (dof %d, p %.2g), %ld off the domain",
        w->n,
        r->chi2,
        r->dof,
        r->p,
        w->outside);
    if (r->worst < 0 || n < 0 || (unsigned long)n >= cap) {
        return;
    }
    int row = r->worst / w->cols;
    int col = r->worst % w->cols;
    if (w->directions) {
        double z0 = z_min(w) + (1 - z_min(w)) * row / w->rows;
        double z1 = z_min(w) + (1 - z_min(w)) * (row + 1) / w->rows;
        snprintf(
            out + n,
            cap - (unsigned long)n,
            "; most off at theta %.0f-%.0f deg, phi %.0f-%.0f deg: %.0f samples, %.0f expected",
            acos(z1) * 180 / pi,
            acos(z0) * 180 / pi,
            360.0 * col / w->cols,
            360.0 * (col + 1) / w->cols,
            r->worst_observed,
            r->worst_expected);
    } else {
        snprintf(
            out + n,
            cap - (unsigned long)n,
            "; most off at x %.3f-%.3f, y %.3f-%.3f: %.0f samples, %.0f expected",
            (double)col / w->cols,
            (double)(col + 1) / w->cols,
            (double)row / w->rows,
            (double)(row + 1) / w->rows,
            r->worst_observed,
            r->worst_expected);
    }
}
