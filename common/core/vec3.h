/*
 * vec3.h - the numbers every stage computes with.
 *
 * One scalar type, `real` (double unless built with `make REAL=float`), one
 * 3-vector type used for points, directions, normals and colours alike, and a
 * ray.  Everything is passed and returned by value; after inlining at -O2 the
 * cost is nil and call sites read like the maths they compute.
 *
 * <tgmath.h> makes sqrt, fabs, fmin, ... pick the float or double version from
 * their argument, so this file (and every stage) compiles in both precisions.
 */
#ifndef VEC3_H
#define VEC3_H

#include <assert.h>
#include <float.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>
#include <tgmath.h>

#ifdef REAL_IS_FLOAT
typedef float real;
#define REAL_EPSILON 0x1p-23f /* FLT_EPSILON: spacing of reals just above 1 */
#define REAL_MAX 0x1.fffffep+127f
#define REAL_NAME "float"
#else
typedef double real;
#define REAL_EPSILON 0x1p-52 /* DBL_EPSILON */
#define REAL_MAX 0x1.fffffffffffffp+1023
#define REAL_NAME "double"
#endif

/* M_PI is POSIX, not ISO C. */
#define PI ((real)3.14159265358979323846)
#define INV_PI ((real)0.31830988618379067154)

typedef struct vec3 {
    real x, y, z;
} vec3;

/* A ray: origin o and direction d.  Directions are unit length wherever a
 * ray is traced, so the ray parameter t is a distance (scene units). */
typedef struct ray {
    vec3 o, d;
} ray;

static inline vec3
vec3_make(real x, real y, real z)
{
    return (vec3){x, y, z};
}

static inline vec3
vec3_splat(real s)
{
    return (vec3){s, s, s};
}

static inline vec3
vec3_add(vec3 a, vec3 b)
{
    return (vec3){a.x + b.x, a.y + b.y, a.z + b.z};
}

static inline vec3
vec3_sub(vec3 a, vec3 b)
{
    return (vec3){a.x - b.x, a.y - b.y, a.z - b.z};
}

/* Component-wise product: colour times colour (albedo times radiance). */
static inline vec3
vec3_mul(vec3 a, vec3 b)
{
    return (vec3){a.x * b.x, a.y * b.y, a.z * b.z};
}

static inline vec3
vec3_scale(vec3 a, real s)
{
    return (vec3){a.x * s, a.y * s, a.z * s};
}

static inline vec3
vec3_div(vec3 a, real s)
{
    return vec3_scale(a, 1 / s);
}

static inline vec3
vec3_neg(vec3 a)
{
    return (vec3){-a.x, -a.y, -a.z};
}

/* a + b*s, the most common shape: a point moved along a direction. */
static inline vec3
vec3_madd(vec3 a, vec3 b, real s)
{
    return (vec3){a.x + b.x * s, a.y + b.y * s, a.z + b.z * s};
}

static inline real
vec3_dot(vec3 a, vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

static inline vec3
vec3_cross(vec3 a, vec3 b)
{
    return (vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

static inline real
vec3_length2(vec3 a)
{
    return vec3_dot(a, a);
}

static inline real
vec3_length(vec3 a)
{
    return sqrt(vec3_dot(a, a));
}

/* Precondition: a is not the zero vector (asserted in test builds). */
static inline vec3
vec3_normalize(vec3 a)
{
    real len = vec3_length(a);
    assert(len > 0);
    return vec3_scale(a, 1 / len);
}

static inline vec3
vec3_lerp(vec3 a, vec3 b, real t)
{
    return vec3_add(vec3_scale(a, 1 - t), vec3_scale(b, t));
}

static inline vec3
vec3_min(vec3 a, vec3 b)
{
    return (vec3){fmin(a.x, b.x), fmin(a.y, b.y), fmin(a.z, b.z)};
}

static inline vec3
vec3_max(vec3 a, vec3 b)
{
    return (vec3){fmax(a.x, b.x), fmax(a.y, b.y), fmax(a.z, b.z)};
}

static inline vec3
vec3_abs(vec3 a)
{
    return (vec3){fabs(a.x), fabs(a.y), fabs(a.z)};
}

/* fmax(a, b) without a call into the maths library (which is what fmax
 * compiles to unless NaNs are ruled out): the larger of a and b, the
 * other one when one is a NaN, and b when they compare equal (as glibc's
 * fmax on x86-64, signed zeros included).  Hot: the error bound of every
 * hit takes three. */
static inline real
real_max(real a, real b)
{
    return a > b || isnan(b) ? a : b;
}

static inline real
vec3_max_comp(vec3 a)
{
    return real_max(a.x, real_max(a.y, a.z));
}

/* Axis access without pointer arithmetic over struct members. */
static inline real
vec3_axis(vec3 a, int axis)
{
    return axis == 0 ? a.x : axis == 1 ? a.y : a.z;
}

static inline bool
vec3_is_zero(vec3 a)
{
    return a.x == 0 && a.y == 0 && a.z == 0;
}

static inline bool
vec3_is_finite(vec3 a)
{
    return isfinite(a.x) && isfinite(a.y) && isfinite(a.z);
}

static inline vec3
ray_at(ray r, real t)
{
    return vec3_madd(r.o, r.d, t);
}

/* sqrt that treats tiny negative round-off as zero (pbrt's SafeSqrt). */
static inline real
safe_sqrt(real x)
{
    return sqrt(real_max((real)0, x));
}

/*
 * An orthonormal basis (s, t, n) around a unit vector n, branch-free:
 * Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017.
 * Used to turn a direction sampled around +z into one around n.
 */
struct onb {
    vec3 s, t, n;
};

static inline struct onb
onb_from_normal(vec3 n)
{
    real sign = copysign((real)1, n.z);
    real a = -1 / (sign + n.z);
    real b = n.x * n.y * a;
    struct onb basis;
    basis.s = (vec3){1 + sign * n.x * n.x * a, sign * b, -sign * n.x};
    basis.t = (vec3){b, sign + n.y * n.y * a, -n.y};
    basis.n = n;
    return basis;
}

/* Local coordinates (x along s, y along t, z along n) to world. */
static inline vec3
onb_to_world(struct onb basis, vec3 local)
{
    vec3 w = vec3_scale(basis.s, local.x);
    w = vec3_madd(w, basis.t, local.y);
    return vec3_madd(w, basis.n, local.z);
}

/* The largest float <= x (-infinity for NaN): rounding outward, so that a
 * box stored in float (the BVH's, from stage 05 on) still contains the
 * real-valued one. */
static inline float
float_below(real x)
{
    if (!(x > -FLT_MAX)) {
        return -INFINITY;
    }
    if (x >= FLT_MAX) {
        return FLT_MAX;
    }
    float f = (float)x;
    if (!((real)f > x)) {
        return f;
    }
    /* The float just below f, f > -FLT_MAX here: its bit pattern one step
     * towards -infinity (as nextafterf, without the call: a ray's set-up in
     * stage 09 rounds six of these). */
    if (f == 0) {
        return -FLT_TRUE_MIN;
    }
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    bits = f > 0 ? bits - 1 : bits + 1;
    memcpy(&f, &bits, sizeof f);
    return f;
}

/* The smallest float >= x. */
static inline float
float_above(real x)
{
    return -float_below(-x);
}

#endif /* VEC3_H */
