/*
 * 04_optics.c - reflection, refraction and the dielectric Fresnel
 * reflectance of optics.h against the textbook (TESTING.md T12, T13).
 *
 *  - Fresnel: ((n-1)/(n+1))^2 at normal incidence (glass 1.5: 0.04,
 *    diamond 2.42); 1 beyond the critical angle asin(1/1.5) from inside and
 *    below 1 just before it (+-1e-9 rad); 45 degrees air to glass and 10 degrees glass to
 *    air against Mitsuba's test_fresnel.py values; the exact values Mitsuba
 *    3 computed for the reference images (META.json "bsdf"); R + T = 1 with
 *    T from the transmission amplitudes, computed here independently;
 *    eta = 1 reflects nothing.
 *  - refract: Snell's law sin_t = eta sin_i to 1e-12, in the plane of
 *    incidence, on the far side, unit length; eta = 1 leaves the direction
 *    unchanged; false exactly where Fresnel says total internal reflection.
 *  - reflect: an involution that keeps the angle to the normal and the
 *    plane of incidence.
 *  - A slab of glass: a ray refracted in and out leaves parallel to how it
 *    came, shifted sideways by d = t sin(theta_i - theta_t) / cos(theta_t).
 *
 * Conventions (optics.h): d travels into the surface, n faces d's side,
 * eta = eta_i / eta_t.
 */
#include "check.h"
#include "optics.h"
#include "rng.h"
#include "stagecheck.h"

#ifdef REAL_IS_FLOAT
#define TIGHT 1e-5
#else
#define TIGHT 1e-12
#endif

static const vec3 up = {0, 1, 0};

/* The incoming direction at angle theta (radians) from the normal (0,1,0),
 * travelling down, in the x-y plane. */
static vec3
incoming(double theta)
{
    return vec3_make((real)sin(theta), (real)-cos(theta), 0);
}

/* Fresnel reflectance from the s and p amplitudes (Born and Wolf 1.5.2),
 * written out here with indices n_i, n_t rather than their ratio. */
static double
reflectance_amplitudes(double cos_i, double n_i, double n_t)
{
    double sin_t = n_i / n_t * sqrt(1 - cos_i * cos_i);
    double cos_t = sqrt(1 - sin_t * sin_t);
    double rs = (n_i * cos_i - n_t * cos_t) / (n_i * cos_i + n_t * cos_t);
    double rp = (n_t * cos_i - n_i * cos_t) / (n_t * cos_i + n_i * cos_t);
    return (rs * rs + rp * rp) / 2;
}

/* Transmittance T = (n_t cos_t)/(n_i cos_i) (t_s^2 + t_p^2) / 2 with the
 * transmission amplitudes t_s = 2 n_i cos_i / (n_i cos_i + n_t cos_t),
 * t_p = 2 n_i cos_i / (n_t cos_i + n_i cos_t) (Born and Wolf 1.5.2; Hecht,
 * Optics, 4.6.2): energy conservation R + T = 1 checks R independently. */
static double
transmittance_amplitudes(double cos_i, double n_i, double n_t)
{
    double sin_t = n_i / n_t * sqrt(1 - cos_i * cos_i);
    double cos_t = sqrt(1 - sin_t * sin_t);
    double ts = 2 * n_i * cos_i / (n_i * cos_i + n_t * cos_t);
    double tp = 2 * n_i * cos_i / (n_t * cos_i + n_i * cos_t);
    return n_t * cos_t / (n_i * cos_i) * (ts * ts + tp * tp) / 2;
}

TEST(fresnel_at_normal_incidence)
{
    CHECK_NEAR(fresnel_dielectric(1, 1 / (real)1.5), 0.04, TIGHT);
    CHECK_NEAR(fresnel_dielectric(1, (real)1.5), 0.04, TIGHT); /* same from inside */
    double diamond = (1.42 / 3.42) * (1.42 / 3.42);
    CHECK_NEAR(fresnel_dielectric(1, 1 / (real)2.42), diamond, TIGHT);
    CHECK_NEAR(fresnel_dielectric(1, (real)2.42), diamond, TIGHT);
}

TEST(fresnel_known_angles)
{
    double deg = acos(-1.0) / 180;
    /* Mitsuba's test_fresnel.py: 45 degrees air to glass (theta_t =
     * 28.1255 deg), 10 degrees glass to air (theta_t = 15.0981 deg). */
    double f45 = 0.5 * (0.0920134 * 0.0920134 + 0.3033370 * 0.3033370);
    CHECK_NEAR(fresnel_dielectric((real)cos(45 * deg), 1 / (real)1.5), f45, 1e-6);
    double f10 = 0.5 * (0.1904680 * 0.1904680 + 0.2094943 * 0.2094943);
    CHECK_NEAR(fresnel_dielectric((real)cos(10 * deg), (real)1.5), f10, 1e-6);
    /* Mitsuba 3 for the reference images (META.json checks.bsdf, 6
     * digits): cos_i > 0 enters the glass, < 0 leaves it. */
    static const double table[][2] =
        {{0.8, 0.043895}, {0.5, 0.089187}, {0.2, 0.338894}, {-0.8, 0.114141}, {-0.7, 1.0}};
    for (int i = 0; i < 5; i++) {
        double c = table[i][0];
        real eta = c > 0 ? 1 / (real)1.5 : (real)1.5;
        CHECK_NEAR(fresnel_dielectric((real)fabs(c), eta), table[i][1], 1e-6);
    }
}

TEST(total_internal_reflection_beyond_the_critical_angle)
{
    /* 1e-9 rad either side (1000 REAL_EPSILON in a float build).  Below
     * the critical angle F = 1 - O(sqrt(delta)): 0.99973 at 1e-9. */
    double critical = asin(1 / 1.5);
    double delta = stagecheck_resolvable(1e-9);
    CHECK(fresnel_dielectric((real)cos(critical + delta), (real)1.5) == 1);
    double below = fresnel_dielectric((real)cos(critical - delta), (real)1.5);
    printf("F at the critical angle - %g rad: %.9f\n", delta, below);
    CHECK(below < 1 && below > 1 - 30 * sqrt(delta));
    vec3 t;
    CHECK(!refract(incoming(critical + delta), up, (real)1.5, &t));
    CHECK(refract(incoming(critical - delta), up, (real)1.5, &t));
    /* Grazing from inside, and every angle past the critical one. */
    for (int i = 1; i <= 100; i++) {
        double theta = critical + (acos(-1.0) / 2 - critical) * i / 100.0;
        CHECK(fresnel_dielectric((real)cos(theta), (real)1.5) == 1);
        CHECK(!refract(incoming(theta), up, (real)1.5, &t));
    }
}

TEST(reflected_plus_transmitted_is_one)
{
    static const double indices[] = {1.33, 1.5, 2.42};
    for (int k = 0; k < 3; k++) {
        double n = indices[k];
        for (int i = 0; i <= 200; i++) {
            double cos_i = 0.005 + 0.995 * i / 200.0;
            /* Entering (always transmits) and leaving (below critical). */
            double r_in = fresnel_dielectric((real)cos_i, (real)(1 / n));
            CHECK_NEAR(r_in, reflectance_amplitudes(cos_i, 1, n), TIGHT);
            CHECK_NEAR(r_in + transmittance_amplitudes(cos_i, 1, n), 1, TIGHT);
            if (sqrt(1 - cos_i * cos_i) * n < 1 - 1e-6) {
                double r_out = fresnel_dielectric((real)cos_i, (real)n);
                CHECK_NEAR(r_out + transmittance_amplitudes(cos_i, n, 1), 1, TIGHT);
            }
        }
    }
}

TEST(index_one_is_invisible)
{
    for (int i = 0; i < 90; i++) {
        double theta = i * acos(-1.0) / 180;
        CHECK_NEAR(fresnel_dielectric((real)cos(theta), 1), 0, TIGHT);
        vec3 d = incoming(theta);
        vec3 t;
        CHECK(refract(d, up, 1, &t));
        CHECK(vec3_length(vec3_sub(t, d)) < TIGHT);
    }
}

TEST(refraction_obeys_snell_in_the_plane_of_incidence)
{
    struct rng rng = rng_make(12, 3);
    static const real etas[] = {1 / (real)1.5, (real)1.5, 1 / (real)2.42, (real)1.33};
    int refracted = 0;
    for (int i = 0; i < 20000; i++) {
        vec3 d = stagecheck_random_vec3(&rng);
        vec3 n = stagecheck_random_vec3(&rng);
        if (vec3_dot(d, n) > 0) {
            n = vec3_neg(n);
        }
        real eta = etas[i % 4];
        real cos_i = -vec3_dot(d, n);
        if (cos_i < (real)1e-3) {
            continue; /* grazing: sin_i is ill-conditioned */
        }
        vec3 t;
        bool ok = refract(d, n, eta, &t);
        bool tir = fresnel_dielectric(cos_i, eta) == 1;
        CHECK(ok != tir);
        if (!ok) {
            continue;
        }
        refracted++;
        double sin_i = vec3_length(vec3_cross(d, n));
        double sin_t = vec3_length(vec3_cross(t, n));
        CHECK_NEAR(sin_t, eta * sin_i, TIGHT);
        CHECK_NEAR(vec3_length(t), 1, TIGHT);
        CHECK(vec3_dot(t, n) < 0); /* on the far side */
        /* In the plane of d and n: perpendicular to their cross product. */
        CHECK(fabs(vec3_dot(t, vec3_cross(d, n))) < TIGHT);
    }
    /* Both branches exercised: about 13,000 refract, the rest reflect
     * totally (cos_i below 0.745 at eta 1.5, below 0.66 at 1.33). */
    printf("%d of 20000 refracted\n", refracted);
    CHECK(refracted > 10000 && refracted < 16000);
}

TEST(reflection_is_an_involution_keeping_the_angle)
{
    struct rng rng = rng_make(13, 5);
    for (int i = 0; i < 20000; i++) {
        vec3 d = stagecheck_random_vec3(&rng);
        vec3 n = stagecheck_random_vec3(&rng);
        if (vec3_dot(d, n) > 0) {
            n = vec3_neg(n);
        }
        vec3 r = reflect(d, n);
        CHECK_NEAR(vec3_dot(r, n), -vec3_dot(d, n), TIGHT);
        CHECK_NEAR(vec3_length(r), 1, TIGHT);
        CHECK(fabs(vec3_dot(r, vec3_cross(d, n))) < TIGHT);
        /* reflect(r, -n): r leaves on n's side, so -n faces it. */
        vec3 back = reflect(r, vec3_neg(n));
        CHECK(vec3_length(vec3_sub(back, d)) < TIGHT);
        CHECK(vec3_length(vec3_sub(reflect(r, n), d)) < TIGHT);
    }
}

TEST(glass_slab_shifts_a_ray_sideways)
{
    /* A slab between y = 0 and y = -thickness, index 1.5, in air.  The ray
     * enters at the origin at angle theta_i, crosses to the bottom face
     * and leaves; the exit direction equals the entry one and the exit line
     * lies d = t sin(theta_i - theta_t) / cos(theta_t) from the entry line
     * (e.g. Hecht, Optics, 5.2). */
    const double thickness = 0.7;
    for (int i = 1; i < 89; i += 4) {
        double theta_i = i * acos(-1.0) / 180;
        vec3 d = incoming(theta_i);
        vec3 inside;
        vec3 out;
        if (!refract(d, up, 1 / (real)1.5, &inside)) {
            CHECK(false);
            continue;
        }
        /* At the bottom face the normal facing the ray is (0, 1, 0) too. */
        vec3 exit_point = vec3_scale(inside, (real)(thickness / -inside.y));
        if (!refract(inside, up, (real)1.5, &out)) {
            CHECK(false);
            continue;
        }
        CHECK(vec3_length(vec3_sub(out, d)) < 10 * TIGHT);
        /* Distance of exit_point from the entry line through 0 along d. */
        double shift = vec3_length(vec3_cross(exit_point, d));
        double theta_t = asin(sin(theta_i) / 1.5);
        double expected = thickness * sin(theta_i - theta_t) / cos(theta_t);
        CHECK_NEAR(shift, expected, 10 * TIGHT);
    }
}

TEST_MAIN(
    TEST_ENTRY(fresnel_at_normal_incidence),
    TEST_ENTRY(fresnel_known_angles),
    TEST_ENTRY(total_internal_reflection_beyond_the_critical_angle),
    TEST_ENTRY(reflected_plus_transmitted_is_one),
    TEST_ENTRY(index_one_is_invisible),
    TEST_ENTRY(refraction_obeys_snell_in_the_plane_of_incidence),
    TEST_ENTRY(reflection_is_an_involution_keeping_the_angle),
    TEST_ENTRY(glass_slab_shifts_a_ray_sideways))
