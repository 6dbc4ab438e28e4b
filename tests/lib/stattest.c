/*
 * stattest.c - see stattest.h.
 *
 * Sources of the formulas:
 *   Welford, "Note on a method for calculating corrected sums of squares
 *     and products", Technometrics 4(3), 1962; the merge step from Chan,
 *     Golub, LeVeque, "Algorithms for computing the sample variance", 1979.
 *   Incomplete beta: NR 2nd ed. section 6.4, continued fraction eq. 6.4.5,
 *     evaluated with the modified Lentz method of NR section 5.2; the
 *     symmetry I_x(a,b) = 1 - I_{1-x}(b,a) (A&S 26.5.2).
 *   Incomplete gamma: NR section 6.2, series eq. 6.2.5 for x < a + 1 and
 *     continued fraction eq. 6.2.7 (Lentz) otherwise (A&S 6.5.29, 6.5.31).
 *   Student t: A(t|nu) = 1 - I_{nu/(nu+t^2)}(nu/2, 1/2), NR eq. 6.4.9 and
 *     A&S 26.7.1; chi-square: P(chi^2|k) = P(k/2, chi^2/2), NR eq. 6.2.17
 *     and A&S 26.4.19; normal: Phi(z) = erfc(-z/sqrt 2)/2, A&S 26.2.29
 *     (Cephes ndtr.c uses the same identity).
 *   Sidak, "Rectangular confidence regions for the means of multivariate
 *     normal distributions", JASA 62, 1967.
 *   Welch, "The generalization of Student's problem when several different
 *     population variances are involved", Biometrika 34, 1947, with
 *     Satterthwaite's degrees of freedom (Biometrics Bulletin 2, 1946).
 */
#include "stattest.h"

#include <float.h>
#include <math.h>

/* Iteration cap of the series and continued fractions.  They need
 * O(sqrt(max(a, b))) terms (NR 6.2, 6.4), so this covers arguments up to
 * about 1e8, far beyond any test's degrees of freedom. */
#define MAX_ITER 100000

/* Relative accuracy at which a series or continued fraction stops. */
#define EPS 1e-16

/* Stand-in for a zero divisor in Lentz's method (NR 5.2: "FPMIN"). */
#define TINY 1e-300

/* Above this many degrees of freedom Student's t is the normal
 * distribution to better than 1e-7 (the difference falls as 1/dof). */
#define T_NORMAL_DOF 1e7

void
stattest_welford_add(struct stattest_welford *w, double x)
{
    /* Updating the mean first and using both the old and the new deviation
     * keeps m2 free of the cancellation of sum(x^2) - n mean^2. */
    w->n++;
    double delta = x - w->mean;
    w->mean += delta / (double)w->n;
    w->m2 += delta * (x - w->mean);
}

void
stattest_welford_merge(struct stattest_welford *a, const struct stattest_welford *b)
{
    if (b->n == 0) {
        return;
    }
    if (a->n == 0) {
        *a = *b;
        return;
    }
    double na = (double)a->n;
    double nb = (double)b->n;
    double n = na + nb;
    double delta = b->mean - a->mean;
    a->mean += delta * nb / n;
    a->m2 += b->m2 + delta * delta * na * nb / n;
    a->n += b->n;
}

double
stattest_welford_variance(const struct stattest_welford *w)
{
    return w->n < 2 ? NAN : w->m2 / (double)(w->n - 1);
}

double
stattest_welford_var_of_mean(const struct stattest_welford *w)
{
    return stattest_welford_variance(w) / (double)w->n;
}

/* Keep a Lentz denominator away from zero (NR 5.2). */
static double
nonzero(double v)
{
    return fabs(v) < TINY ? TINY : v;
}

/* Continued fraction of I_x(a, b) (NR eq. 6.4.5) by the modified Lentz
 * method; converges fast for x < (a + 1) / (a + b + 2).  NaN when it does not
 * converge. */
static double
beta_fraction(double a, double b, double x)
{
    double d = 1 / nonzero(1 - (a + b) * x / (a + 1));
    double c = 1;
    double h = d;
    for (int m = 1; m <= MAX_ITER; m++) {
        /* Even step d_{2m}, then odd step d_{2m+1} of eq. 6.4.6. */
        double aa = m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m));
        d = 1 / nonzero(1 + aa * d);
        c = nonzero(1 + aa / c);
        h *= d * c;
        aa = -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1));
        d = 1 / nonzero(1 + aa * d);
        c = nonzero(1 + aa / c);
        double step = d * c;
        h *= step;
        if (fabs(step - 1) < EPS) {
            return h;
        }
    }
    return NAN;
}

/* I_x(a, b) given both x and y = 1 - x: a caller that can form 1 - x
 * without rounding (the t distribution can) passes it exactly. */
static double
incbeta_xy(double a, double b, double x, double y)
{
    if (!(a > 0 && b > 0 && x >= 0 && y >= 0)) {
        return NAN;
    }
    if (x == 0 || y == 0) {
        return x == 0 ? 0 : 1;
    }
    /* x^a y^b / B(a, b), the front factor of eq. 6.4.5, in logarithms. */
    double log_front = a * log(x) + b * log(y) + lgamma(a + b) - lgamma(a) - lgamma(b);
    double front = exp(log_front);
    if (x < (a + 1) / (a + b + 2)) {
        return front * beta_fraction(a, b, x) / a;
    }
    return 1 - front * beta_fraction(b, a, y) / b;
}

double
stattest_incbeta(double a, double b, double x)
{
    if (!(x >= 0 && x <= 1)) {
        return NAN;
    }
    return incbeta_xy(a, b, x, 1 - x);
}

/* x^a e^-x / Gamma(a), the common factor of NR eqs. 6.2.5 and 6.2.7. */
static double
gamma_front(double a, double x)
{
    return exp(a * log(x) - x - lgamma(a));
}

/* P(a, x) by its series (NR eq. 6.2.5); for x < a + 1. */
static double
gamma_series(double a, double x)
{
    double term = 1 / a;
    double sum = term;
    for (int n = 1; n <= MAX_ITER; n++) {
        term *= x / (a + n);
        sum += term;
        if (fabs(term) < fabs(sum) * EPS) {
            return sum * gamma_front(a, x);
        }
    }
    return NAN;
}

/* Q(a, x) by its continued fraction (NR eq. 6.2.7, modified Lentz); for
 * x >= a + 1. */
static double
gamma_fraction(double a, double x)
{
    double b = x + 1 - a;
    double c = 1 / TINY;
    double d = 1 / b;
    double h = d;
    for (int i = 1; i <= MAX_ITER; i++) {
        double an = -i * (i - a);
        b += 2;
        d = 1 / nonzero(an * d + b);
        c = nonzero(b + an / c);
        double step = d * c;
        h *= step;
        if (fabs(step - 1) < EPS) {
            return h * gamma_front(a, x);
        }
    }
    return NAN;
}

double
stattest_gamma_p(double a, double x)
{
    if (!(a > 0 && x >= 0)) {
        return NAN;
    }
    if (x == 0 || isinf(x)) {
        return x == 0 ? 0 : 1;
    }
    return x < a + 1 ? gamma_series(a, x) : 1 - gamma_fraction(a, x);
}

double
stattest_gamma_q(double a, double x)
{
    if (!(a > 0 && x >= 0)) {
        return NAN;
    }
    if (x == 0 || isinf(x)) {
        return x == 0 ? 1 : 0;
    }
    return x < a + 1 ? 1 - gamma_series(a, x) : gamma_fraction(a, x);
}

double
stattest_normal_cdf(double z)
{
    /* erfc keeps the lower tail's relative precision, where 1 + erf would
     * cancel (A&S 26.2.29, Cephes ndtr). */
    return 0.5 * erfc(-z / sqrt(2.0));
}

double
stattest_normal_pvalue(double z)
{
    return erfc(fabs(z) / sqrt(2.0));
}

/* P(|T| >= |t|) = I_x(dof/2, 1/2) with x = dof / (dof + t^2) (NR 6.4.9);
 * x and 1 - x = t^2 / (dof + t^2) are each formed directly. */
static double
t_two_sided(double t, double dof)
{
    double t2 = t * t;
    if (isinf(t2)) {
        return 0;
    }
    return incbeta_xy(0.5 * dof, 0.5, dof / (dof + t2), t2 / (dof + t2));
}

double
stattest_t_cdf(double t, double dof)
{
    if (isnan(t) || !(dof > 0)) {
        return NAN;
    }
    if (dof > T_NORMAL_DOF) {
        return stattest_normal_cdf(t);
    }
    double tail = 0.5 * t_two_sided(t, dof);
    return t > 0 ? 1 - tail : tail;
}

double
stattest_t_pvalue(double t, double dof)
{
    if (isnan(t) || !(dof > 0)) {
        return NAN;
    }
    if (dof > T_NORMAL_DOF) {
        return stattest_normal_pvalue(t);
    }
    return t_two_sided(t, dof);
}

double
stattest_t_critical(double p, double dof)
{
    if (!(p > 0 && p <= 1) || !(dof > 0)) {
        return NAN;
    }
    /* The p-value falls as |t| grows: bracket p between lo and hi = 2 lo,
     * then bisect until the bracket is a few ulps of t wide. */
    double lo = 0, hi = 1;
    while (stattest_t_pvalue(hi, dof) > p && hi < 1e300) {
        lo = hi;
        hi *= 2;
    }
    for (int i = 0; i < 200 && hi - lo > 4 * DBL_EPSILON * hi; i++) {
        double mid = 0.5 * (lo + hi);
        if (stattest_t_pvalue(mid, dof) > p) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return 0.5 * (lo + hi);
}

double
stattest_chi2_cdf(double x, double k)
{
    if (!(k > 0) || isnan(x)) {
        return NAN;
    }
    return x <= 0 ? 0 : stattest_gamma_p(0.5 * k, 0.5 * x);
}

double
stattest_chi2_pvalue(double x, double k)
{
    if (!(k > 0) || isnan(x)) {
        return NAN;
    }
    return x <= 0 ? 1 : stattest_gamma_q(0.5 * k, 0.5 * x);
}

double
stattest_sidak(double alpha, double m)
{
    /* 1 - (1 - alpha)^(1/m) through log1p/expm1: for small alpha and large
     * m the direct form loses most of its digits to cancellation. */
    if (!(alpha >= 0 && alpha <= 1 && m >= 1)) {
        return NAN;
    }
    return -expm1(log1p(-alpha) / m);
}

/* Welch-Satterthwaite degrees of freedom of var_a + var_b, written with the
 * fractions f = var / (var_a + var_b) in [0, 1] so nothing over- or
 * underflows.  An exact variance (dof 0 or infinite) adds no term. */
static double
satterthwaite(double var_a, double dof_a, double var_b, double dof_b)
{
    double v = var_a + var_b;
    double fa = var_a / v;
    double fb = var_b / v;
    double den = 0;
    if (dof_a > 0 && isfinite(dof_a)) {
        den += fa * fa / dof_a;
    }
    if (dof_b > 0 && isfinite(dof_b)) {
        den += fb * fb / dof_b;
    }
    return den > 0 ? 1 / den : INFINITY;
}

static struct stattest_result
no_result(void)
{
    return (struct stattest_result){NAN, NAN, NAN};
}

struct stattest_result
stattest_t_test_estimates(
    double a,
    double var_a,
    double dof_a,
    double b,
    double var_b,
    double dof_b)
{
    double v = var_a + var_b;
    if (!(isfinite(a) && isfinite(b) && var_a >= 0 && var_b >= 0 && isfinite(v))) {
        return no_result();
    }
    double diff = a - b;
    struct stattest_result r;
    if (v == 0) {
        /* No uncertainty at all: the estimates agree or they do not. */
        r.dof = INFINITY;
        r.t = diff == 0 ? 0 : copysign(INFINITY, diff);
        r.p = diff == 0 ? 1 : 0;
        return r;
    }
    r.dof = satterthwaite(var_a, dof_a, var_b, dof_b);
    r.t = diff / sqrt(v);
    r.p = stattest_t_pvalue(r.t, r.dof);
    return r;
}

struct stattest_result
stattest_t_test_one_sample(double mean, double variance, int64_t n, double mu0)
{
    if (n < 2) {
        return no_result();
    }
    double dn = (double)n;
    return stattest_t_test_estimates(mean, variance / dn, dn - 1, mu0, 0, INFINITY);
}

struct stattest_result
stattest_t_test_welch(
    double mean1,
    double variance1,
    int64_t n1,
    double mean2,
    double variance2,
    int64_t n2)
{
    if (n1 < 2 || n2 < 2) {
        return no_result();
    }
    double d1 = (double)n1;
    double d2 = (double)n2;
    return stattest_t_test_estimates(mean1, variance1 / d1, d1 - 1, mean2, variance2 / d2, d2 - 1);
}

struct stattest_result
stattest_t_test_welford_one_sample(const struct stattest_welford *w, double mu0)
{
    return stattest_t_test_one_sample(w->mean, stattest_welford_variance(w), w->n, mu0);
}

struct stattest_result
stattest_t_test_welford_welch(const struct stattest_welford *w1, const struct stattest_welford *w2)
{
    return stattest_t_test_welch(
        w1->mean,
        stattest_welford_variance(w1),
        w1->n,
        w2->mean,
        stattest_welford_variance(w2),
        w2->n);
}
