/* test_vec3.c - vector identities, the orthonormal basis, safe_sqrt. */
#include "check.h"
#include "rng.h"
#include "vec3.h"

#ifdef REAL_IS_FLOAT
#define TOL 1e-5
#else
#define TOL 1e-12
#endif

static vec3
random_vec3(struct rng *r)
{
    return (vec3){rng_uniform(r) * 2 - 1, rng_uniform(r) * 2 - 1, rng_uniform(r) * 2 - 1};
}

TEST(algebra_identities)
{
    struct rng r = rng_make(42, 0);
    for (int i = 0; i < 1000; i++) {
        vec3 a = random_vec3(&r);
        vec3 b = random_vec3(&r);
        vec3 c = random_vec3(&r);
        vec3 axb = vec3_cross(a, b);
        CHECK_NEAR(vec3_dot(axb, a), 0, TOL);
        CHECK_NEAR(vec3_dot(axb, b), 0, TOL);
        /* Lagrange: |a x b|^2 = |a|^2 |b|^2 - (a.b)^2 */
        real lhs = vec3_length2(axb);
        real rhs = vec3_length2(a) * vec3_length2(b) - vec3_dot(a, b) * vec3_dot(a, b);
        CHECK_NEAR(lhs, rhs, TOL * 10);
        /* triple product is cyclic */
        CHECK_NEAR(vec3_dot(a, vec3_cross(b, c)), vec3_dot(b, vec3_cross(c, a)), TOL * 10);
        vec3 sum = vec3_sub(vec3_add(a, b), b);
        CHECK_NEAR(sum.x, a.x, TOL);
        CHECK_NEAR(vec3_length(vec3_normalize(a)), 1, TOL);
        vec3 m = vec3_madd(a, b, 2);
        CHECK_NEAR(m.y, a.y + 2 * b.y, TOL);
    }
}

TEST(component_helpers)
{
    vec3 a = {1, -2, 3};
    vec3 b = {-4, 5, -6};
    CHECK(vec3_axis(a, 0) == 1 && vec3_axis(a, 1) == -2 && vec3_axis(a, 2) == 3);
    CHECK(vec3_max_comp(a) == 3);
    vec3 mn = vec3_min(a, b);
    vec3 mx = vec3_max(a, b);
    CHECK(mn.x == -4 && mn.y == -2 && mn.z == -6);
    CHECK(mx.x == 1 && mx.y == 5 && mx.z == 3);
    vec3 p = vec3_mul(a, b);
    CHECK(p.x == -4 && p.y == -10 && p.z == -18);
    CHECK(vec3_is_zero(vec3_splat(0)) && !vec3_is_zero(a));
    CHECK(vec3_is_finite(a));
    CHECK(!vec3_is_finite((vec3){0, NAN, 0}) && !vec3_is_finite((vec3){INFINITY, 0, 0}));
    ray r = {{1, 2, 3}, {0, 0, 1}};
    CHECK(ray_at(r, 2).z == 5);
}

TEST(orthonormal_basis_for_any_normal)
{
    struct rng r = rng_make(7, 1);
    vec3 special[] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, 1, 0}, {0, -1e-9, -1}};
    for (int i = 0; i < 1005; i++) {
        vec3 n = i < 5 ? vec3_normalize(special[i]) : vec3_normalize(random_vec3(&r));
        struct onb b = onb_from_normal(n);
        CHECK_NEAR(vec3_length(b.s), 1, TOL * 10);
        CHECK_NEAR(vec3_length(b.t), 1, TOL * 10);
        CHECK_NEAR(vec3_dot(b.s, b.t), 0, TOL * 10);
        CHECK_NEAR(vec3_dot(b.s, n), 0, TOL * 10);
        CHECK_NEAR(vec3_dot(b.t, n), 0, TOL * 10);
        /* right-handed: s x t = n */
        vec3 st = vec3_cross(b.s, b.t);
        CHECK_NEAR(vec3_dot(st, n), 1, TOL * 10);
        vec3 w = onb_to_world(b, (vec3){0, 0, 1});
        CHECK_NEAR(w.z, n.z, TOL);
    }
}

TEST(safe_sqrt_clamps_round_off)
{
    CHECK(safe_sqrt(-1e-17) == 0);
    CHECK(safe_sqrt(4) == 2);
}

TEST_MAIN(
    TEST_ENTRY(algebra_identities),
    TEST_ENTRY(component_helpers),
    TEST_ENTRY(orthonormal_basis_for_any_normal),
    TEST_ENTRY(safe_sqrt_clamps_round_off))
