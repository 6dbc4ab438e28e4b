/*
 * 04_lab_functions.c - lab 04's optics, each function on its own
 * (tests/lab/README.md, "Function tests"), against formulas computed here
 * (reflection and refraction in long double); the glass shading of stages 04-06 is
 * 04-06_lab_functions.c.  Conventions (optics.h): d travels into the
 * surface, n faces d's side, eta = eta_i / eta_t.
 *
 *  - reflect: d - 2 (d.n) n for random d and n.
 *  - refract: where Snell's law has a solution, true and the unit direction
 *    eta d + (eta cos_i - cos_t) n (in the plane of incidence, on the far
 *    side, sin_t = eta sin_i); false exactly past the critical angle; for
 *    eta from 1/2.42 to 2.42.
 *  - fresnel_dielectric: the unpolarised reflectance (r_s^2 + r_p^2) / 2
 *    of the Fresnel equations (stagecheck_fresnel: Hecht, Optics, 4.34), 1
 *    past the critical angle, for random angles and the same indices.
 *
 * Deterministic (fixed seeds).  White-box: optics.h, which every later
 * stage keeps.
 */
#include <stdio.h>

#include "check.h"
#include "optics.h"
#include "rng.h"
#include "stagecheck.h"

#define TOL (sizeof(real) == sizeof(float) ? 1e-4 : 1e-9)

static const double etas[] = {1 / 2.42, 1 / 1.5, 1 / 1.33, 1.33, 1.5, 2.42};

/* A random unit n and a unit d with d.n < 0 (travelling into the surface). */
static void
random_pair(struct rng *rng, vec3 *d, vec3 *n)
{
    *n = stagecheck_random_vec3(rng);
    *d = stagecheck_random_vec3(rng);
    if (vec3_dot(*d, *n) > 0) {
        *d = vec3_neg(*d);
    }
}

TEST(reflect_mirrors_d_about_n)
{
    struct rng rng = rng_make(4001, 1);
    for (int i = 0; i < 1000; i++) {
        vec3 d;
        vec3 n;
        random_pair(&rng, &d, &n);
        long double dn = (long double)d.x * n.x + (long double)d.y * n.y + (long double)d.z * n.z;
        long double want[3] = {d.x - 2 * dn * n.x, d.y - 2 * dn * n.y, d.z - 2 * dn * n.z};
        vec3 got = reflect(d, n);
        if (fabsl(got.x - want[0]) + fabsl(got.y - want[1]) + fabsl(got.z - want[2]) > 10 * TOL) {
            CHECK_FAIL(
                "reflect (d (%g %g %g), n (%g %g %g)): (%g %g %g), expected d - 2 (d.n) n = (%Lg %Lg %Lg)",
                (double)d.x,
                (double)d.y,
                (double)d.z,
                (double)n.x,
                (double)n.y,
                (double)n.z,
                (double)got.x,
                (double)got.y,
                (double)got.z,
                want[0],
                want[1],
                want[2]);
            return;
        }
    }
}

TEST(refract_obeys_snell_and_fails_only_past_the_critical_angle)
{
    struct rng rng = rng_make(4002, 2);
    for (int i = 0; i < 3000; i++) {
        vec3 d;
        vec3 n;
        random_pair(&rng, &d, &n);
        long double eta = etas[i % 6];
        long double cos_i =
            -((long double)d.x * n.x + (long double)d.y * n.y + (long double)d.z * n.z);
        long double sin2_t = eta * eta * (1 - cos_i * cos_i);
        if (fabsl(sin2_t - 1) < 1e-6L) {
            continue; /* at the critical angle: either answer */
        }
        bool expect = sin2_t < 1;
        vec3 got = {0, 0, 0};
        bool ok = refract(d, n, (real)eta, &got);
        long double want[3] = {0, 0, 0};
        if (expect) {
            long double cos_t = sqrtl(1 - sin2_t);
            long double k = eta * cos_i - cos_t;
            want[0] = eta * d.x + k * n.x;
            want[1] = eta * d.y + k * n.y;
            want[2] = eta * d.z + k * n.z;
        }
        long double err = fabsl(got.x - want[0]) + fabsl(got.y - want[1]) + fabsl(got.z - want[2]);
        if (ok != expect || (expect && err > 100 * TOL)) {
            CHECK_FAIL(
                "refract (eta %.4Lg, angle of incidence %.2Lf deg): %s (%g %g %g); expected %s (%.6Lg %.6Lg %.6Lg): "
                "Snell's law sin_t = eta sin_i, t = eta d + (eta cos_i - cos_t) n, unit; false only past the "
                "critical angle (total internal reflection)",
                eta,
                acosl(cos_i) * 180 / 3.14159265358979323846L,
                ok ? "true," : "false,",
                (double)got.x,
                (double)got.y,
                (double)got.z,
                expect ? "true," : "false",
                want[0],
                want[1],
                want[2]);
            return;
        }
    }
}

TEST(fresnel_dielectric_matches_the_fresnel_equations)
{
    struct rng rng = rng_make(4003, 3);
    for (int i = 0; i < 3000; i++) {
        double eta = etas[i % 6];
        double cos_i = i < 6 ? 1 : (double)rng_uniform(&rng);
        if (fabs(eta * eta * (1 - cos_i * cos_i) - 1) < 1e-6) {
            continue; /* at the critical angle: either answer */
        }
        double want = stagecheck_fresnel(cos_i, eta);
        real got = fresnel_dielectric((real)cos_i, (real)eta);
        if (fabs((double)got - want) > 100 * TOL) {
            CHECK_FAIL(
                "fresnel_dielectric (cos_i %.6g, eta %.4g): %.8g, expected %.8g: the mean of r_s^2 and r_p^2, "
                "r_s = (eta cos_i - cos_t) / (eta cos_i + cos_t), r_p = (cos_i - eta cos_t) / (cos_i + eta "
                "cos_t); 1 past the critical angle",
                cos_i,
                eta,
                (double)got,
                want);
            return;
        }
    }
}

TEST_MAIN(
    TEST_ENTRY(reflect_mirrors_d_about_n),
    TEST_ENTRY(refract_obeys_snell_and_fails_only_past_the_critical_angle),
    TEST_ENTRY(fresnel_dielectric_matches_the_fresnel_equations))
