/*
 * scene_build.c - the builders of the statements that add one element: the
 * camera, the image size, background and ambient, spheres, quads, single
 * triangles and the lights (point, area and sphere lights).  Each checks
 * what the field table cannot (a camera's up not along its view, a light of
 * non-zero area), appends to the scene through scene_grow() (scene_store.c) and
 * records the features the element uses.
 */
#include "scene_parser.h"

/* Below this sine of the angle between up and the view direction the
 * camera's basis (built from their cross product) is numerically noise. */
#define MIN_UP_SINE 1e-6

/* Sine of the angle between non-zero a and b, each first divided by its
 * largest component so that no product overflows; NaN if one is infinite. */
static double
sine_between(const double a_in[3], const double b_in[3])
{
    double a[3], b[3];
    double ma = fmax(fabs(a_in[0]), fmax(fabs(a_in[1]), fabs(a_in[2])));
    double mb = fmax(fabs(b_in[0]), fmax(fabs(b_in[1]), fabs(b_in[2])));
    for (int i = 0; i < 3; i++) {
        a[i] = a_in[i] / ma;
        b[i] = b_in[i] / mb;
    }
    double cx = a[1] * b[2] - a[2] * b[1];
    double cy = a[2] * b[0] - a[0] * b[2];
    double cz = a[0] * b[1] - a[1] * b[0];
    double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    double lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    return sqrt(cx * cx + cy * cy + cz * cz) / (la * lb);
}

bool
scene_build_camera(struct parser *p, const struct token *kw, struct fields *fs)
{
    (void)kw;
    vec3 o = scene_vec_of(fs, "origin");
    vec3 t = scene_vec_of(fs, "target");
    vec3 up = scene_vec_of(fs, "up");
    if (o.x == t.x && o.y == t.y && o.z == t.z) {
        return scene_fail(p, &scene_get(fs, "target")->key, "target must differ from origin");
    }
    if (vec3_is_zero(up)) {
        return scene_fail(p, &scene_get(fs, "up")->key, "up must be non-zero");
    }
    // In double, where the difference of two reals cannot overflow.
    double view[3] = {(double)t.x - o.x, (double)t.y - o.y, (double)t.z - o.z};
    double up_d[3] = {up.x, up.y, up.z};
    if (!(sine_between(view, up_d) >= MIN_UP_SINE)) {
        const char *msg = "up must not be parallel to the view direction (target - origin)";
        return scene_fail(p, &scene_get(fs, "up")->key, "%s", msg);
    }
    real fov = scene_get(fs, "fov")->num[0];
    const struct field_value *near = scene_get(fs, "near");
    p->scene->camera = (struct camera_desc){
        .origin = o,
        .target = t,
        .up = up,
        .vfov_deg = fov,
        .near = near ? near->num[0] : 0};
    return true;
}

bool
scene_build_image(struct parser *p, const struct token *kw, struct fields *fs)
{
    (void)kw;
    p->scene->width = (int)scene_get(fs, "width")->integer;
    p->scene->height = (int)scene_get(fs, "height")->integer;
    return true;
}

/* background and ambient: a colour, and a feature when it is not black. */
bool
scene_build_color(struct parser *p, const struct token *kw, struct fields *fs)
{
    bool background = scene_token_is(kw, "background");
    vec3 color = scene_vec_of(fs, "color");
    *(background ? &p->scene->background : &p->scene->ambient) = color;
    if (!vec3_is_zero(color)) {
        scene_use_feature(p, background ? FEAT_ENVIRONMENT : FEAT_AMBIENT, kw);
    }
    return true;
}

bool
scene_build_sphere(struct parser *p, const struct token *kw, struct fields *fs)
{
    struct scene *s = p->scene;
    int material;
    if (!scene_use_material(p, kw, fs, &material)) {
        return false;
    }
    struct sphere *a = scene_grow(p, kw, s->spheres, s->n_spheres + 1, &p->cap.spheres, sizeof *a);
    if (!a) {
        return false;
    }
    s->spheres = a;
    real radius = scene_get(fs, "radius")->num[0];
    a[s->n_spheres++] = (struct sphere){
        .center = scene_vec_of(fs, "center"),
        .radius = radius,
        .material = material,
        .line = kw->line};
    return true;
}

/* A quad of zero area is allowed: it is never hit. */
bool
scene_build_quad(struct parser *p, const struct token *kw, struct fields *fs)
{
    struct scene *s = p->scene;
    int material;
    if (!scene_use_material(p, kw, fs, &material)) {
        return false;
    }
    struct quad *a = scene_grow(p, kw, s->quads, s->n_quads + 1, &p->cap.quads, sizeof *a);
    if (!a) {
        return false;
    }
    s->quads = a;
    struct quad *q = &a[s->n_quads++];
    *q =
        (struct quad){.corner = scene_vec_of(fs, "corner"), .material = material, .line = kw->line};
    q->edge1 = scene_vec_of(fs, "edge1");
    q->edge2 = scene_vec_of(fs, "edge2");
    return true;
}

/* A triangle of zero area is allowed, as in meshes: it is never hit. */
bool
scene_build_triangle(struct parser *p, const struct token *kw, struct fields *fs)
{
    struct scene *s = p->scene;
    int material;
    if (!scene_use_material(p, kw, fs, &material) || !scene_room_for_mesh(p, kw, 3, 1)) {
        return false;
    }
    static const char *const corners[] = {"v0", "v1", "v2"};
    struct triangle tri = {.material = material, .smooth = false, .line = kw->line};
    for (int i = 0; i < 3; i++) {
        tri.v[i] = s->n_vertices;
        s->positions[s->n_vertices] = scene_vec_of(fs, corners[i]);
        s->normals[s->n_vertices++] = vec3_splat(0);
    }
    s->triangles[s->n_triangles++] = tri;
    return true;
}

bool
scene_build_point_light(struct parser *p, const struct token *kw, struct fields *fs)
{
    struct point_light light = {
        .position = scene_vec_of(fs, "position"),
        .intensity = scene_vec_of(fs, "intensity"),
        .loc = scene_loc_of(kw)};
    return scene_add_point_light(p, kw, light);
}

bool
scene_build_area_light(struct parser *p, const struct token *kw, struct fields *fs)
{
    struct area_light light = {.corner = scene_vec_of(fs, "corner"), .loc = scene_loc_of(kw)};
    light.edge1 = scene_vec_of(fs, "edge1");
    light.edge2 = scene_vec_of(fs, "edge2");
    light.radiance = scene_vec_of(fs, "radiance");
    real area = area_light_area(&light);
    if (!isfinite(area)) {
        return scene_fail(p, kw, "area_light is too large (its area is not a finite number)");
    }
    if (!(area > 0)) {
        return scene_fail(p, kw, "area_light has zero area (edge1 and edge2 are parallel or zero)");
    }
    return scene_add_area_light(p, kw, light);
}

bool
scene_build_sphere_light(struct parser *p, const struct token *kw, struct fields *fs)
{
    struct scene *s = p->scene;
    int n = s->n_sphere_lights;
    struct sphere_light *a =
        scene_grow(p, kw, s->sphere_lights, n + 1, &p->cap.sphere_lights, sizeof *a);
    if (!a) {
        return false;
    }
    s->sphere_lights = a;
    a[s->n_sphere_lights++] = (struct sphere_light){
        .center = scene_vec_of(fs, "center"),
        .radius = scene_get(fs, "radius")->num[0],
        .radiance = scene_vec_of(fs, "radiance"),
        .loc = scene_loc_of(kw)};
    scene_use_feature(p, FEAT_SPHERE_LIGHT, kw);
    return true;
}
