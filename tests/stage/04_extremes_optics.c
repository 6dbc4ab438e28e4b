/*
 * 04_extremes_optics.c - the extremes battery, white-box part for glass
 * (optics.h, from stage 04 on): refraction and the Fresnel reflectance at
 * the indices and angles where they are hardest to compute, each case
 * judged against tests/extremes/expect.tsv (tests/extremes/expect.h).
 * 04_optics.c checks the textbook values at ordinary indices; here:
 *
 *  - critical_angle: leaving glass of index 1.0001, 1.5, 2.42 and 10, at
 *    the critical angle asin(1/n) plus and minus 1e-9 rad (in float, whose
 *    cosines cannot resolve 1e-9 rad there, plus and minus 1000 ulps:
 *    stagecheck_resolvable): just inside, refract succeeds with a unit,
 *    finite direction and F < 1 agrees with a long double reference to
 *    1e-6 (double; F has a square-root singularity there: dF/dtheta is
 *    about 1e4 at 1e-9 rad); just beyond, refract fails and F = 1.
 *  - ior_1_grazing: index exactly 1 is no boundary at all: F = 0 and the
 *    direction unchanged (to 1e-9 in double, 1e-4 in float) at every
 *    incidence, down to cos_i = 1e-15 (double) or 1e-6 (float), rays within
 *    a hair of grazing.
 *  - fresnel_sweep: index 1, 1.0001, 2.42 and 10, entering and leaving,
 *    cos_i from 1 down to 1e-12 and exactly 0: F in [0, 1] and finite;
 *    refract fails only where F = 1 (else the transmitted 1 - F is lost);
 *    where it succeeds with F < 1 the direction is unit and on the far
 *    side, obeys Snell's law, and F is reciprocal (the same F for the
 *    reverse path, Stokes' relations).
 * The figure of each case is the number of violations.
 */
#include <string.h>

#include "check.h"
#include "extremes/expect.h"
#include "optics.h"
#include "stagecheck.h"

#define TAG "optics"

#ifdef REAL_IS_FLOAT
#define TOLERANCE 1e-4
#define SMALLEST_COS 1e-6
#else
#define TOLERANCE 1e-9
#define SMALLEST_COS 1e-15
#endif

static const vec3 normal = {0, 1, 0};

/* The direction travelling into the surface (normal +y) whose cosine of
 * incidence is cos_i, in the x-y plane. */
static vec3
incoming(long double cos_i)
{
    long double sin_i = sqrtl(1 - cos_i * cos_i);
    return vec3_make((real)sin_i, (real)-cos_i, 0);
}

/* The reference reflectance for eta = n_i / n_t, in long double from the
 * amplitudes written with both indices (Born and Wolf 1.5.2). */
static long double
reference_fresnel(long double cos_i, long double n_i, long double n_t)
{
    long double sin_t = n_i / n_t * sqrtl(1 - cos_i * cos_i);
    if (sin_t >= 1) {
        return 1;
    }
    long double cos_t = sqrtl(1 - sin_t * sin_t);
    long double rs = (n_i * cos_i - n_t * cos_t) / (n_i * cos_i + n_t * cos_t);
    long double rp = (n_t * cos_i - n_i * cos_t) / (n_t * cos_i + n_i * cos_t);
    return (rs * rs + rp * rp) / 2;
}

/* Count a violation; the first few go into the note. */
static void
violation(struct outcome *o, const char *what)
{
    if (o->figure < 4) {
        size_t len = strlen(o->note);
        snprintf(o->note + len, sizeof o->note - len, "%s%s", len ? "; " : "", what);
    }
    o->figure++;
}

static void
judge(const char *name, struct outcome *o, const char *what)
{
    o->passed = o->figure == 0;
    size_t len = strlen(o->note);
    snprintf(
        o->note + len,
        sizeof o->note - len,
        "%s%g violations %s",
        len ? "; " : "",
        o->figure,
        what);
    expect_judge(TAG, name, REAL_NAME, o);
}

TEST(critical_angle)
{
    static const double indices[] = {1.0001, 1.5, 2.42, 10};
    struct outcome o = {0};
    double delta = stagecheck_resolvable(1e-9);
    for (size_t i = 0; i < sizeof indices / sizeof indices[0]; i++) {
        long double n = indices[i];
        long double critical = asinl(1 / n);
        for (int side = -1; side <= 1; side += 2) {
            long double cos_i = cosl(critical + side * delta);
            vec3 d = incoming(cos_i);
            real c = -vec3_dot(d, normal); /* the cosine as the stage sees it */
            real f = fresnel_dielectric(c, (real)n);
            vec3 t;
            bool refracted = refract(d, normal, (real)n, &t);
            char what[128];
            if (side > 0 && (refracted || f != 1)) {
                snprintf(
                    what,
                    sizeof what,
                    "n %g beyond: refracted %d, F %g",
                    (double)n,
                    refracted,
                    (double)f);
                violation(&o, what);
            }
            if (side < 0) {
                long double ref = reference_fresnel(c, n, 1);
                bool unit = fabs(vec3_length(t) - 1) < 16 * REAL_EPSILON;
                if (!refracted || !(f < 1) || !vec3_is_finite(t) || !unit) {
                    snprintf(
                        what,
                        sizeof what,
                        "n %g inside: refracted %d, F %g",
                        (double)n,
                        refracted,
                        (double)f);
                    violation(&o, what);
                } else if (!(fabsl(f - ref) <= 1e3 * TOLERANCE)) {
                    snprintf(
                        what,
                        sizeof what,
                        "n %g inside: F %.9g, reference %.9g",
                        (double)n,
                        (double)f,
                        (double)ref);
                    violation(&o, what);
                }
            }
        }
    }
    judge("critical_angle", &o, "at asin(1/n) +- 1e-9 rad (n = 1.0001, 1.5, 2.42, 10)");
}

TEST(ior_1_grazing)
{
    struct outcome o = {0};
    for (double cos_i = 1; cos_i >= SMALLEST_COS; cos_i /= 10) {
        vec3 d = incoming(cos_i);
        real c = -vec3_dot(d, normal);
        real f = fresnel_dielectric(c, 1);
        vec3 t;
        bool refracted = refract(d, normal, 1, &t);
        double turn = refracted ? vec3_length(vec3_sub(t, d)) : 1;
        if (!(f <= TOLERANCE) || !(turn <= TOLERANCE)) {
            char what[128];
            snprintf(
                what,
                sizeof what,
                "cos_i %g: F %g, direction turned by %g",
                cos_i,
                (double)f,
                turn);
            violation(&o, what);
        }
    }
    judge("ior_1_grazing", &o, "of F = 0 and an unchanged direction for index 1");
}

/* One incidence of the sweep: every property of the file's comment. */
static void
check_incidence(long double cos_i, real eta, struct outcome *o)
{
    vec3 d = incoming(cos_i);
    real c = -vec3_dot(d, normal);
    real f = fresnel_dielectric(c, eta);
    vec3 t;
    bool refracted = refract(d, normal, eta, &t);
    char what[160];
    snprintf(
        what,
        sizeof what,
        "cos_i %.3Lg eta %g: F %g, refracted %d",
        cos_i,
        (double)eta,
        (double)f,
        refracted);
    /* Refraction may fail only under total internal reflection (F = 1),
     * or the 1 - F it should carry is lost.  The converse is allowed: at
     * (or, in rounding, near) grazing incidence F is 1 and a refracted ray
     * carries nothing. */
    bool consistent = refracted || f == 1;
    if (!(f >= 0 && f <= 1) || !consistent) {
        violation(o, what);
        return;
    }
    if (!refracted || f == 1) {
        return;
    }
    double sin_i = sqrt(fmax(0.0, 1 - (double)c * c));
    double sin_t = sqrt((double)t.x * t.x + (double)t.z * t.z);
    bool unit = fabs(vec3_length(t) - 1) < 16 * REAL_EPSILON;
    bool far_side = vec3_dot(t, normal) <= 0;
    bool snell = fabs(sin_t - eta * sin_i) <= TOLERANCE;
    /* Reciprocity: the reverse path, from inside at the transmitted angle
     * with the inverse ratio, reflects the same fraction (away from
     * grazing, where F's slope amplifies the rounding of cos_t). */
    real back = fresnel_dielectric(-vec3_dot(t, normal), 1 / eta);
    bool reciprocal = fabs((double)back - f) <= 1e3 * TOLERANCE || c < 1e-6;
    if (!unit || !far_side || !snell || !reciprocal || !vec3_is_finite(t)) {
        size_t len = strlen(what);
        snprintf(
            what + len,
            sizeof what - len,
            ": unit %d, far side %d, Snell %d, reciprocal %d",
            unit,
            far_side,
            snell,
            reciprocal);
        violation(o, what);
    }
}

TEST(fresnel_sweep)
{
    static const double indices[] = {1, 1.0001, 2.42, 10};
    struct outcome o = {0};
    int n = 0;
    for (size_t i = 0; i < sizeof indices / sizeof indices[0]; i++) {
        for (int leaving = 0; leaving < 2; leaving++) {
            real eta = (real)(leaving ? indices[i] : 1 / indices[i]);
            check_incidence(0, eta, &o);
            n++;
            for (long double cos_i = 1; cos_i >= 1e-12L; cos_i /= 1.5L) {
                check_incidence(cos_i, eta, &o);
                n++;
            }
        }
    }
    char what[96];
    snprintf(what, sizeof what, "in %d incidences (index 1 .. 10, both ways, cos_i 1 .. 0)", n);
    judge("fresnel_sweep", &o, what);
}

TEST_MAIN(TEST_ENTRY(critical_angle), TEST_ENTRY(ior_1_grazing), TEST_ENTRY(fresnel_sweep))
