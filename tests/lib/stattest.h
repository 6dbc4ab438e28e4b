/*
 * stattest.h - the statistics behind the project's hypothesis tests: running
 * mean and variance, the Student-t, chi-square and normal distributions,
 * Sidak's correction, and t-tests that return p-values.
 *
 * Every function is written from the formulas in the literature (cited at
 * each definition in stattest.c): Numerical Recipes in C, 2nd ed. (NR),
 * Abramowitz & Stegun, Handbook of Mathematical Functions (A&S), and the
 * Cephes library's documentation.  Pure functions: no state, no I/O.
 *
 * How the tests use them (TESTING.md sections 4 and 5): a test computes a
 * p-value and rejects when p < alpha', where alpha' is the family alpha
 * (0.01) Sidak-corrected for the number m of tests in the stage.
 */
#ifndef STATTEST_H
#define STATTEST_H

#include <stdint.h>

/* Welford's running mean and variance.  Start from a zero-initialised
 * struct: struct stattest_welford w = {0}; */
struct stattest_welford {
    int64_t n;
    double mean;
    double m2; /* sum of squared deviations from the running mean */
};

void stattest_welford_add(struct stattest_welford *w, double x);

/* Fold b into a (Chan, Golub, LeVeque's pairwise update), e.g. to combine
 * per-thread accumulators. */
void stattest_welford_merge(struct stattest_welford *a, const struct stattest_welford *b);

/* Sample variance (divisor n - 1); NaN when n < 2. */
double stattest_welford_variance(const struct stattest_welford *w);

/* Squared standard error of the mean, variance / n; NaN when n < 2. */
double stattest_welford_var_of_mean(const struct stattest_welford *w);

/* Regularized incomplete beta function I_x(a, b), a, b > 0, x in [0, 1].
 * NaN for arguments outside the domain or if the continued fraction fails
 * to converge (it converges for every a, b below about 1e8). */
double stattest_incbeta(double a, double b, double x);

/* Regularized incomplete gamma functions P(a, x) (lower) and
 * Q(a, x) = 1 - P(a, x) (upper), a > 0, x >= 0; each computed directly, so a
 * tiny tail keeps its relative precision.  NaN outside the domain. */
double stattest_gamma_p(double a, double x);
double stattest_gamma_q(double a, double x);

/* Student's t distribution with dof > 0 degrees of freedom (dof need not be
 * an integer: Welch's test gives fractional ones).  dof = INFINITY (or above
 * 1e7, where t and normal differ by under 1e-7) uses the normal distribution. */
double stattest_t_cdf(double t, double dof);

/* P(|T| >= |t|): the two-sided p-value of a t statistic. */
double stattest_t_pvalue(double t, double dof);

/* The critical value of a two-sided t-test: the t >= 0 with
 * stattest_t_pvalue(t, dof) = p, for 0 < p <= 1 (NaN otherwise).  Also a
 * one-sided quantile: P(T >= t) = p / 2. */
double stattest_t_critical(double p, double dof);

/* Chi-square distribution with k > 0 degrees of freedom: P(X <= x) and the
 * upper tail P(X > x), the p-value of a chi-square statistic. */
double stattest_chi2_cdf(double x, double k);
double stattest_chi2_pvalue(double x, double k);

/* Standard normal distribution: Phi(z) and the two-sided p-value
 * P(|Z| >= |z|). */
double stattest_normal_cdf(double z);
double stattest_normal_pvalue(double z);

/* Sidak's per-test significance level: alpha' = 1 - (1 - alpha)^(1/m), so
 * that m independent tests at alpha' reject a true hypothesis with overall
 * probability alpha.  m >= 1. */
double stattest_sidak(double alpha, double m);

/* Outcome of a t-test.  p is two-sided.  A zero standard error gives t = 0
 * and p = 1 for equal estimates, t = +-INFINITY and p = 0 otherwise.  Too
 * little data (n < 2) gives NaN everywhere; treat NaN as a rejection. */
struct stattest_result {
    double t;
    double dof;
    double p;
};

/* Compare two estimates a and b whose squared standard errors are var_a and
 * var_b with dof_a and dof_b degrees of freedom (INFINITY, or 0, for an exact
 * variance).  t = (a - b) / sqrt(var_a + var_b); the degrees of freedom are
 * Welch-Satterthwaite's.  The building block of the two tests below and of
 * a render-against-reference test, where the reference has its own SE. */
struct stattest_result stattest_t_test_estimates(
    double a,
    double var_a,
    double dof_a,
    double b,
    double var_b,
    double dof_b);

/* One-sample t-test: is the mean of n samples (sample variance `variance`)
 * equal to mu0? */
struct stattest_result
stattest_t_test_one_sample(double mean, double variance, int64_t n, double mu0);

/* Welch's two-sample t-test (unequal variances): are the means equal? */
struct stattest_result stattest_t_test_welch(
    double mean1,
    double variance1,
    int64_t n1,
    double mean2,
    double variance2,
    int64_t n2);

/* The same tests straight from two running accumulators. */
struct stattest_result
stattest_t_test_welford_one_sample(const struct stattest_welford *w, double mu0);
struct stattest_result
stattest_t_test_welford_welch(const struct stattest_welford *w1, const struct stattest_welford *w2);

#endif /* STATTEST_H */
