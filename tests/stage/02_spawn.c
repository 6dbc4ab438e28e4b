/*
 * 02_spawn.c - rays that leave a surface never find it again (TESTING.md
 * T7, after Mitsuba's test_ray_offset.py and pbrt's Reintersect tests).
 *
 * For a sphere, a parallelogram and a triangle, each at scales 1e-3, 1 and
 * 1e3 and at distances 0 and 1e4 from the origin: rays from 3 or 1e4 sizes
 * away hit the shape at random points; from each hit a ray is spawned
 * (spawn_ray) in a random direction of the hemisphere it was hit from (and,
 * for the flat shapes, of the other one too), and a shadow ray
 * (spawn_ray_to) goes to a point off the surface.  In a world holding only
 * that shape:
 *   - no spawned ray hits the shape again (world_intersect, world_occluded),
 *     in particular not at t < 1e-3 * size, the acne a fixed epsilon gives;
 *   - the computed hit point lies within its error bound of the true
 *     surface (measured in long double), so the bound is a bound;
 *   - the bound is > 0 and < 1e-6 (|p| + size): proportional to the
 *     magnitudes involved, not a large constant that would pass the test
 *     above by hiding every nearby surface.
 *
 * White-box: world_make, world_intersect, world_occluded, spawn_ray,
 * spawn_ray_to and struct hit, which every later stage keeps.
 */
#include <stdint.h>
#include <string.h>

#include "check.h"
#include "geometry.h"
#include "rng.h"
#include "scene.h"
#include "stagecheck.h"

#define RAYS_PER_CASE 4096

#ifdef REAL_IS_FLOAT
#define BOUND_FACTOR 1e-3
#else
#define BOUND_FACTOR 1e-6
#endif

enum shape {
    SHAPE_SPHERE,
    SHAPE_QUAD,
    SHAPE_TRIANGLE
};

static const char *const shape_names[] = {"sphere", "quad", "triangle"};

/* What went wrong in one case (shape, scale, offset). */
struct tally {
    int missed; /* a ray aimed at the shape did not hit it */
    int self_hits; /* a spawned ray hit the shape again */
    int near_hits; /* ... at t < 1e-3 * size */
    int occluded; /* a shadow ray off the surface was blocked */
    int outside_bound; /* the hit point is farther from the surface than its bound */
    int bad_bound; /* bound <= 0, or >= BOUND_FACTOR * (|p| + size) */
    double worst_ratio; /* largest (distance to the surface) / bound */
};

/* Uniform over the hemisphere around n. */
static vec3
random_in_hemisphere(struct rng *rng, vec3 n)
{
    vec3 d = stagecheck_random_vec3(rng);
    return vec3_dot(d, n) < 0 ? vec3_neg(d) : d;
}

static real
max_abs(vec3 a)
{
    return fmax(fabs(a.x), fmax(fabs(a.y), fabs(a.z)));
}

/* The flat shape's corner and its two edges (a quad's as given, a
 * triangle's from its first corner). */
static void
flat_frame(const struct scene *s, enum shape shape, vec3 *o, vec3 *e1, vec3 *e2)
{
    if (shape == SHAPE_QUAD) {
        *o = s->quads[0].corner;
        *e1 = s->quads[0].edge1;
        *e2 = s->quads[0].edge2;
        return;
    }
    *o = s->positions[0];
    *e1 = vec3_sub(s->positions[1], *o);
    *e2 = vec3_sub(s->positions[2], *o);
}

/* Distance from p to the shape's true surface (the sphere, or the plane of
 * the flat shape), in long double so that it is exact enough to judge an
 * error bound of a few ulps. */
static long double
surface_distance(const struct scene *s, enum shape shape, vec3 p)
{
    long double px = p.x, py = p.y, pz = p.z;
    if (shape == SHAPE_SPHERE) {
        const struct sphere *sp = &s->spheres[0];
        long double dx = px - sp->center.x, dy = py - sp->center.y, dz = pz - sp->center.z;
        return fabsl(sqrtl(dx * dx + dy * dy + dz * dz) - (long double)sp->radius);
    }
    vec3 o;
    vec3 e1;
    vec3 e2;
    flat_frame(s, shape, &o, &e1, &e2);
    long double nx = (long double)e1.y * e2.z - (long double)e1.z * e2.y;
    long double ny = (long double)e1.z * e2.x - (long double)e1.x * e2.z;
    long double nz = (long double)e1.x * e2.y - (long double)e1.y * e2.x;
    long double len = sqrtl(nx * nx + ny * ny + nz * nz);
    return fabsl((px - o.x) * nx + (py - o.y) * ny + (pz - o.z) * nz) / len;
}

/* The scene holding one shape of the given size, `offset` from the origin
 * (along a direction with no zero component), in a general orientation. */
static bool
make_scene(enum shape shape, double size, double offset, struct scene *s)
{
    double c[3] = {offset + 0.1 * size, -0.6 * offset + 0.2 * size, 0.8 * offset - 0.3 * size};
    char text[2048];
    int n = snprintf(
        text,
        sizeof text,
        "camera origin 0 0 10 target 0 0 0 up 0 1 0 fov 40\n"
        "image width 1 height 1\n"
        "material m diffuse albedo 0.5 0.5 0.5\n");
    if (shape == SHAPE_SPHERE) {
        snprintf(
            text + n,
            sizeof text - (size_t)n,
            "sphere center %.17g %.17g %.17g radius %.17g material m\n",
            c[0],
            c[1],
            c[2],
            size);
    } else if (shape == SHAPE_QUAD) {
        snprintf(
            text + n,
            sizeof text - (size_t)n,
            "quad corner %.17g %.17g %.17g edge1 %.17g %.17g %.17g edge2 %.17g %.17g %.17g "
            "material m\n",
            c[0],
            c[1],
            c[2],
            size,
            0.3 * size,
            -0.2 * size,
            -0.25 * size,
            0.8 * size,
            0.5 * size);
    } else {
        snprintf(
            text + n,
            sizeof text - (size_t)n,
            "triangle v0 %.17g %.17g %.17g v1 %.17g %.17g %.17g v2 %.17g %.17g %.17g "
            "material m\n",
            c[0],
            c[1],
            c[2],
            c[0] + size,
            c[1] + 0.3 * size,
            c[2] - 0.2 * size,
            c[0] - 0.25 * size,
            c[1] + 0.8 * size,
            c[2] + 0.5 * size);
    }
    struct diag err;
    if (!scene_load_string(text, strlen(text), "spawn.scene", s, &err)) {
        diag_print(stdout, &err, "error");
        return false;
    }
    return true;
}

/* A random point of the shape's surface and its outward (geometric) normal;
 * flat shapes keep away from their edges by 1% so a ray aimed at the point
 * hits the shape whatever its rounding. */
static vec3
random_surface_point(const struct scene *s, enum shape shape, struct rng *rng, vec3 *normal)
{
    if (shape == SHAPE_SPHERE) {
        vec3 n = stagecheck_random_vec3(rng);
        *normal = n;
        return vec3_madd(s->spheres[0].center, n, s->spheres[0].radius);
    }
    real u = (real)0.01 + (real)0.98 * rng_uniform(rng);
    real v = (real)0.01 + (real)0.98 * rng_uniform(rng);
    vec3 o;
    vec3 e1;
    vec3 e2;
    flat_frame(s, shape, &o, &e1, &e2);
    if (shape == SHAPE_TRIANGLE) {
        if (u + v > 1) { /* fold into the triangle ... */
            u = 1 - u;
            v = 1 - v;
        }
        /* ... and keep 1% from its long edge too (u + v <= 0.99). */
        u = (real)0.01 + (real)0.97 * u;
        v = (real)0.01 + (real)0.97 * v;
    }
    *normal = vec3_normalize(vec3_cross(e1, e2));
    return vec3_madd(vec3_madd(o, e1, u), e2, v);
}

/* One spawned ray from h in direction d: count a hit on the shape. */
static void
check_spawned(const struct world *w, const struct hit *h, vec3 d, double size, struct tally *t)
{
    struct stats st = {0};
    struct hit again;
    ray r = spawn_ray(h, d);
    if (world_intersect(w, r, REAL_MAX, &again, &st)) {
        t->self_hits++;
        t->near_hits += again.t < 1e-3 * size;
    } else if (world_occluded(w, r, REAL_MAX, &st)) {
        t->self_hits++; /* the any-hit query must agree with the closest hit */
    }
    /* A shadow ray to a point 2 sizes off the surface along d. */
    real t_max;
    ray shadow = spawn_ray_to(h, vec3_madd(h->p, d, (real)(2 * size)), &t_max);
    t->occluded += world_occluded(w, shadow, t_max, &st);
}

static struct tally
run_case(enum shape shape, double size, double offset, uint64_t seed)
{
    struct tally t = {0};
    struct scene s = {0};
    if (!make_scene(shape, size, offset, &s)) {
        t.missed = RAYS_PER_CASE;
        return t;
    }
    struct world w = world_make(&s);
    struct rng rng = rng_make(seed, 1);
    for (int i = 0; i < RAYS_PER_CASE; i++) {
        vec3 normal;
        vec3 target = random_surface_point(&s, shape, &rng, &normal);
        /* From outside a sphere; from either side of a flat shape; never
         * closer than 3 degrees to grazing so the aimed ray surely hits. */
        vec3 side = shape == SHAPE_SPHERE || (i & 1) ? normal : vec3_neg(normal);
        vec3 from = random_in_hemisphere(&rng, side);
        if (vec3_dot(from, side) < (real)0.05) {
            from = vec3_normalize(vec3_madd(from, side, (real)0.1));
        }
        real dist = (real)size * ((i & 2) ? (real)1e4 : (real)3);
        vec3 origin = vec3_madd(target, from, dist);
        ray r = {origin, vec3_normalize(vec3_sub(target, origin))};
        struct hit h;
        struct stats st = {0};
        if (!world_intersect(&w, r, REAL_MAX, &h, &st)) {
            t.missed++;
            continue;
        }
        double dist_to_surface = (double)surface_distance(&s, shape, h.p);
        t.outside_bound += !(dist_to_surface <= h.error);
        t.worst_ratio = fmax(t.worst_ratio, dist_to_surface / h.error);
        t.bad_bound += !(h.error > 0 && h.error < BOUND_FACTOR * (max_abs(h.p) + size));
        /* Leave on the side it was hit from (reflection) ... */
        check_spawned(&w, &h, random_in_hemisphere(&rng, h.ng), size, &t);
        /* ... and, through a flat shape, from the other side (refraction). */
        if (shape != SHAPE_SPHERE) {
            check_spawned(&w, &h, random_in_hemisphere(&rng, vec3_neg(h.ng)), size, &t);
        }
    }
    scene_free(&s);
    return t;
}

static void
check_shape(enum shape shape)
{
    static const double sizes[] = {1e-3, 1, 1e3};
    static const double offsets[] = {0, 1e4};
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 2; j++) {
            /* In float, a shape 1e-3 across 1e4 from the origin is below the
             * precision of its own coordinates: not a meaningful case. */
            if (!stagecheck_representable(sizes[i], offsets[j])) {
                continue;
            }
            struct tally t = run_case(shape, sizes[i], offsets[j], (uint64_t)(7 + 3 * i + j));
            printf(
                "%-8s size %-6g offset %-6g: missed %d, self-hits %d (%d at t < 1e-3 size), "
                "false occlusions %d, outside bound %d, bad bound %d; "
                "worst distance/bound %.3g\n",
                shape_names[shape],
                sizes[i],
                offsets[j],
                t.missed,
                t.self_hits,
                t.near_hits,
                t.occluded,
                t.outside_bound,
                t.bad_bound,
                t.worst_ratio);
            CHECK(t.missed == 0);
            CHECK(t.self_hits == 0);
            CHECK(t.near_hits == 0);
            CHECK(t.occluded == 0);
            CHECK(t.outside_bound == 0);
            CHECK(t.bad_bound == 0);
        }
    }
}

TEST(sphere_spawned_rays_never_hit_it_again)
{
    check_shape(SHAPE_SPHERE);
}

TEST(quad_spawned_rays_never_hit_it_again)
{
    check_shape(SHAPE_QUAD);
}

TEST(triangle_spawned_rays_never_hit_it_again)
{
    check_shape(SHAPE_TRIANGLE);
}

TEST_MAIN(
    TEST_ENTRY(sphere_spawned_rays_never_hit_it_again),
    TEST_ENTRY(quad_spawned_rays_never_hit_it_again),
    TEST_ENTRY(triangle_spawned_rays_never_hit_it_again))
