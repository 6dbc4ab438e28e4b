/*
 * test_stattest.c - the statistics machinery of tests/lib/stattest.c against
 * closed forms (t with 1 and 2 degrees of freedom, chi-square with 2) and
 * tabulated values.  Values marked "mpmath" were computed with mpmath at 30
 * digits (betainc, gammainc, ncdf); quantiles are the usual table entries.
 */
#include <math.h>

#include "check.h"
#include "rng.h"
#include "stattest.h"

#define PI_D 3.14159265358979323846

TEST(welford_matches_two_pass)
{
    static const double xs[] = {1e9 + 4, 1e9 + 7, 1e9 + 13, 1e9 + 16};
    struct stattest_welford w = {0};
    for (int i = 0; i < 4; i++) {
        stattest_welford_add(&w, xs[i]);
    }
    /* Shifted data: the naive sum-of-squares formula loses every digit. */
    CHECK(w.n == 4);
    CHECK_NEAR(w.mean, 1e9 + 10, 1e-6);
    CHECK_NEAR(stattest_welford_variance(&w), 30.0, 1e-6);
    CHECK_NEAR(stattest_welford_var_of_mean(&w), 7.5, 1e-6);

    struct stattest_welford one = {0};
    stattest_welford_add(&one, 3.0);
    CHECK(isnan(stattest_welford_variance(&one)));
}

TEST(welford_merge_equals_sequential)
{
    struct rng r = rng_make(7, 1);
    struct stattest_welford all = {0}, a = {0}, b = {0}, empty = {0};
    for (int i = 0; i < 1000; i++) {
        double x = 5 + 3 * (double)rng_uniform(&r);
        stattest_welford_add(&all, x);
        stattest_welford_add(i < 300 ? &a : &b, x);
    }
    stattest_welford_merge(&a, &b);
    stattest_welford_merge(&a, &empty);
    CHECK(a.n == all.n);
    CHECK_NEAR(a.mean, all.mean, 1e-12);
    CHECK_NEAR(stattest_welford_variance(&a), stattest_welford_variance(&all), 1e-12);
    stattest_welford_merge(&empty, &all);
    CHECK(empty.n == all.n && empty.mean == all.mean);
}

TEST(incbeta_closed_forms_and_tables)
{
    /* I_x(a, 1) = x^a, I_x(1, b) = 1 - (1-x)^b, I_{1/2}(a, a) = 1/2. */
    CHECK_REL(stattest_incbeta(3.5, 1, 0.3), pow(0.3, 3.5), 1e-13);
    CHECK_REL(stattest_incbeta(1, 4.25, 0.6), 1 - pow(0.4, 4.25), 1e-13);
    CHECK_NEAR(stattest_incbeta(17, 17, 0.5), 0.5, 1e-14);
    CHECK_REL(stattest_incbeta(2.5, 3.5, 0.3), 0.2967529892956663986, 1e-12); /* mpmath */
    CHECK_REL(stattest_incbeta(50, 60, 0.4), 0.1247068583431002620, 1e-10); /* mpmath */
    CHECK(stattest_incbeta(2, 3, 0) == 0);
    CHECK(stattest_incbeta(2, 3, 1) == 1);
    CHECK(isnan(stattest_incbeta(-1, 3, 0.5)));
    CHECK(isnan(stattest_incbeta(2, 3, 1.5)));
}

TEST(t_distribution_closed_forms)
{
    /* dof 1 is Cauchy: F(t) = 1/2 + atan(t)/pi; dof 2: F(t) = 1/2 + t/(2 sqrt(2 + t^2)). */
    static const double ts[] = {-30, -2.5, -0.3, 0, 0.7, 1, 4, 100};
    for (int i = 0; i < 8; i++) {
        double t = ts[i];
        CHECK_NEAR(stattest_t_cdf(t, 1), 0.5 + atan(t) / PI_D, 1e-13);
        CHECK_NEAR(stattest_t_cdf(t, 2), 0.5 + t / (2 * sqrt(2 + t * t)), 1e-13);
    }
    /* Far tail of dof 1: 1 - F(t) = atan(1/t)/pi keeps relative precision. */
    CHECK_REL(stattest_t_cdf(-1e6, 1), atan(1e-6) / PI_D, 1e-10);
}

TEST(t_distribution_tables)
{
    /* The brief's example: t = 2, dof 10 -> two-sided p 0.07339. */
    CHECK_NEAR(stattest_t_pvalue(2.0, 10), 0.07339, 5e-6);
    CHECK_REL(stattest_t_pvalue(2.0, 10), 0.07338803477074036562, 1e-12); /* mpmath */
    CHECK_REL(stattest_t_pvalue(-2.0, 10), 0.07338803477074036562, 1e-12);
    /* Table quantiles: t_{0.975, 10} = 2.228138852, t_{0.995, 30} = 2.749995652. */
    CHECK_NEAR(stattest_t_pvalue(2.228138852, 10), 0.05, 1e-9);
    CHECK_NEAR(stattest_t_cdf(2.749995652, 30), 0.995, 1e-9);
    CHECK_REL(stattest_t_pvalue(0.5, 3), 0.6514479648481509944, 1e-12); /* mpmath */
    CHECK_REL(stattest_t_pvalue(10, 5), 1.709475757429635907e-4, 1e-10); /* mpmath */
    CHECK_REL(stattest_t_pvalue(50, 4), 9.574453656969698410e-7, 1e-9); /* mpmath */
    CHECK_REL(stattest_t_pvalue(1.5, 2.5), 0.2478364530862962611, 1e-12); /* mpmath */
    CHECK_REL(stattest_t_pvalue(3, 1000), 2.766709044238192464e-3, 1e-9); /* mpmath */
    CHECK(stattest_t_pvalue(0, 7) == 1);
    CHECK(stattest_t_pvalue(INFINITY, 7) == 0);
    CHECK(isnan(stattest_t_pvalue(1, 0)));
    CHECK(isnan(stattest_t_cdf(NAN, 5)));
    /* Very many degrees of freedom: the normal distribution. */
    CHECK_NEAR(stattest_t_pvalue(1.959963984540054, INFINITY), 0.05, 1e-12);
    CHECK_NEAR(stattest_t_pvalue(1.959963984540054, 1e6), 0.05, 1e-6);
}

TEST(t_critical_inverts_the_p_value)
{
    /* The table quantiles above, read backwards. */
    CHECK_NEAR(stattest_t_critical(0.05, 10), 2.228138852, 1e-8);
    CHECK_NEAR(stattest_t_critical(0.01, 30), 2.749995652, 1e-8);
    CHECK_NEAR(stattest_t_critical(0.05, INFINITY), 1.959963984540054, 1e-12);
    /* One-sided: the normal's 90% quantile. */
    CHECK_NEAR(stattest_t_critical(0.2, INFINITY), 1.2815515655446004, 1e-12);
    /* dof 1 (Cauchy): p = 1 - (2/pi) atan t, so t = cot(pi p / 2), far out. */
    CHECK_REL(stattest_t_critical(1e-7, 1), 1 / tan(PI_D * 1e-7 / 2), 1e-9);
    /* Round trips at a compare-sized level. */
    for (double dof = 1.5; dof < 1e5; dof *= 7) {
        double t = stattest_t_critical(1.3e-6, dof);
        CHECK_REL(stattest_t_pvalue(t, dof), 1.3e-6, 1e-9);
    }
    CHECK(stattest_t_critical(1, 5) < 1e-12);
    CHECK(isnan(stattest_t_critical(0, 5)));
    CHECK(isnan(stattest_t_critical(1.5, 5)));
    CHECK(isnan(stattest_t_critical(0.05, 0)));
    CHECK(isnan(stattest_t_critical(NAN, 5)));
}

TEST(chi_square)
{
    /* k = 2: F(x) = 1 - exp(-x/2); k = 1: F(x) = erf(sqrt(x/2)). */
    static const double xs[] = {0.01, 0.5, 1, 3, 10, 40};
    for (int i = 0; i < 6; i++) {
        CHECK_NEAR(stattest_chi2_cdf(xs[i], 2), -expm1(-xs[i] / 2), 1e-13);
        CHECK_REL(stattest_chi2_pvalue(xs[i], 2), exp(-xs[i] / 2), 1e-12);
        CHECK_NEAR(stattest_chi2_cdf(xs[i], 1), erf(sqrt(xs[i] / 2)), 1e-13);
    }
    /* Table quantiles: chi2_{0.95}(10) = 18.30703805, chi2_{0.95}(3) = 7.814727903. */
    CHECK_NEAR(stattest_chi2_cdf(18.30703805, 10), 0.95, 1e-9);
    CHECK_NEAR(stattest_chi2_cdf(7.814727903, 3), 0.95, 1e-9);
    CHECK_REL(stattest_chi2_pvalue(103.4, 63), 1.009227091461469612e-3, 1e-10); /* mpmath */
    CHECK_REL(stattest_chi2_pvalue(200, 100), 1.178450072097942245e-8, 1e-9); /* mpmath */
    CHECK_REL(stattest_chi2_cdf(0.5, 4), 2.649902116074391469e-2, 1e-12); /* mpmath */
    CHECK_REL(stattest_chi2_pvalue(1000, 10), 1.870290720915949696e-208, 1e-9); /* mpmath */
    /* A 101 x 101 histogram test has about 10^4 degrees of freedom. */
    CHECK_REL(stattest_chi2_pvalue(10300, 10200), 0.2411747175865113636, 1e-8); /* mpmath */
    CHECK_REL(stattest_chi2_cdf(10300, 10200), 0.7588252824134886364, 1e-8); /* mpmath */
    CHECK(stattest_chi2_cdf(0, 3) == 0 && stattest_chi2_pvalue(0, 3) == 1);
    CHECK_REL(stattest_gamma_p(3, 2), 0.3233235838169365405, 1e-13); /* mpmath */
    CHECK_REL(stattest_gamma_q(0.5, 30), 9.485737571073848388e-15, 1e-10); /* mpmath */
    CHECK(isnan(stattest_gamma_p(0, 1)) && isnan(stattest_gamma_q(1, -1)));
}

TEST(normal_distribution)
{
    CHECK_NEAR(stattest_normal_cdf(0), 0.5, 1e-16);
    CHECK_NEAR(stattest_normal_cdf(-1), 0.1586552539314570514, 1e-15);
    CHECK_NEAR(stattest_normal_cdf(1.959963984540054), 0.975, 1e-15);
    CHECK_REL(stattest_normal_cdf(-8), 6.220960574271784124e-16, 1e-12); /* mpmath */
    CHECK_NEAR(stattest_normal_pvalue(-1.959963984540054), 0.05, 1e-14);
}

TEST(sidak_correction)
{
    CHECK_NEAR(stattest_sidak(0.01, 1), 0.01, 1e-17);
    /* 1 - 0.99^(1/10) = 1.00451...e-3 */
    CHECK_REL(stattest_sidak(0.01, 10), 1 - pow(0.99, 0.1), 1e-12);
    /* m tests at alpha' reject with overall probability alpha. */
    double a = stattest_sidak(0.01, 196608);
    CHECK_REL(1 - pow(1 - a, 196608), 0.01, 1e-9);
    CHECK(a < 0.01 / 196608 * 1.01 && a > 0.01 / 196608);
    CHECK(isnan(stattest_sidak(0.01, 0.5)));
}

/* Mean and variance of n draws of a + (b - a) * u. */
static struct stattest_welford
uniform_samples(uint64_t seed, int n, double a, double b)
{
    struct rng r = rng_make(seed, 3);
    struct stattest_welford w = {0};
    for (int i = 0; i < n; i++) {
        stattest_welford_add(&w, a + (b - a) * (double)rng_uniform(&r));
    }
    return w;
}

TEST(t_tests_on_known_distributions)
{
    /* U(0, 1): mean 1/2.  Fixed seeds, so the outcome is deterministic. */
    struct stattest_welford w1 = uniform_samples(11, 5000, 0, 1);
    struct stattest_welford w2 = uniform_samples(12, 800, -0.5, 1.5); /* also mean 1/2 */
    double alpha = stattest_sidak(0.01, 4);
    CHECK(stattest_t_test_welford_one_sample(&w1, 0.5).p >= alpha);
    CHECK(stattest_t_test_welford_welch(&w1, &w2).p >= alpha);
    /* A mean shifted by 0.05 (about 3.5 standard errors of the 800-sample
     * mean at variance 1/3) must be detected in both tests. */
    struct stattest_welford w3 = uniform_samples(13, 800, -0.45, 1.55);
    CHECK(stattest_t_test_welford_one_sample(&w1, 0.55).p < alpha);
    CHECK(stattest_t_test_welford_welch(&w1, &w3).p < 0.05);
    /* Welch-Satterthwaite dof lies between min(n) - 1 and n1 + n2 - 2. */
    struct stattest_result r = stattest_t_test_welford_welch(&w1, &w2);
    CHECK(r.dof >= 799 && r.dof <= 5798);
}

TEST(t_test_hand_computed)
{
    /* Welch: means 10, 12; variances 4, 9; n 10, 12.
     * se^2 = 0.4 + 0.75 = 1.15; t = -2/sqrt(1.15);
     * dof = 1.15^2 / (0.4^2/9 + 0.75^2/11) = 19.8347... */
    struct stattest_result r = stattest_t_test_welch(10, 4, 10, 12, 9, 12);
    CHECK_NEAR(r.t, -2 / sqrt(1.15), 1e-14);
    CHECK_NEAR(r.dof, 1.3225 / (0.16 / 9 + 0.5625 / 11), 1e-10);
    CHECK_NEAR(r.p, stattest_t_pvalue(r.t, r.dof), 0);
    /* One sample: mean 5.2, variance 1, n 25 -> t = 1, dof 24. */
    r = stattest_t_test_one_sample(5.2, 1, 25, 5);
    CHECK_NEAR(r.t, 1, 1e-12);
    CHECK(r.dof == 24);
    /* Estimates with a reference that has its own (exact-dof) SE. */
    r = stattest_t_test_estimates(1.0, 0.0009, 7, 1.1, 0.0016, INFINITY);
    CHECK_NEAR(r.t, -0.1 / 0.05, 1e-12);
    CHECK_NEAR(r.dof, 7 / (0.36 * 0.36), 1e-9);
    /* Degenerate inputs. */
    r = stattest_t_test_estimates(2, 0, 3, 2, 0, 3);
    CHECK(r.t == 0 && r.p == 1);
    r = stattest_t_test_estimates(2, 0, 3, 2.5, 0, 3);
    CHECK(isinf(r.t) && r.t < 0 && r.p == 0);
    CHECK(isnan(stattest_t_test_one_sample(1, 1, 1, 0).p));
    CHECK(isnan(stattest_t_test_estimates(NAN, 1, 3, 0, 1, 3).p));
}

TEST_MAIN(
    TEST_ENTRY(welford_matches_two_pass),
    TEST_ENTRY(welford_merge_equals_sequential),
    TEST_ENTRY(incbeta_closed_forms_and_tables),
    TEST_ENTRY(t_distribution_closed_forms),
    TEST_ENTRY(t_distribution_tables),
    TEST_ENTRY(t_critical_inverts_the_p_value),
    TEST_ENTRY(chi_square),
    TEST_ENTRY(normal_distribution),
    TEST_ENTRY(sidak_correction),
    TEST_ENTRY(t_tests_on_known_distributions),
    TEST_ENTRY(t_test_hand_computed))
