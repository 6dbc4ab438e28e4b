/*
 * scene_gltf_file.c - a glTF file (.glb, or .gltf with its buffers) as the
 * whole scene (docs/scene-format.md, "A glTF file as the scene"): its
 * camera, its KHR_lights_punctual point lights, its meshes with their
 * materials and emitters (scene_gltf.c).  Nothing else is assumed: a file
 * without a camera is refused, one without lights gets a headlight, noted.
 */
#include "scene_parser.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "gltf.h"

/* Without -W, the image is this wide; the height follows the camera's
 * aspect ratio, or this one when the file gives none. */
#define DEFAULT_WIDTH 640
#define DEFAULT_ASPECT (4.0 / 3.0)

/* KHR_lights_punctual gives point and spot lights in candela (lm/sr), a
 * photometric unit; the scene format's intensities are W/sr per channel.
 * Blender's exporter turns W into candela with 683 lm/W (the luminous
 * efficacy of 555 nm light, the definition of the candela), and we undo
 * exactly that: I [W/sr] = I_v [cd] / 683. */
#define LUMENS_PER_WATT 683.0

#define RAD_TO_DEG (180.0 / 3.14159265358979323846)

bool
scene_path_is_gltf(const char *path)
{
    size_t n = strlen(path);
    return (n >= 4 && strcasecmp(path + n - 4, ".glb") == 0)
           || (n >= 5 && strcasecmp(path + n - 5, ".gltf") == 0);
}

static vec3
vec_from(const double v[3])
{
    return vec3_make((real)v[0], (real)v[1], (real)v[2]);
}

/* The camera named `name`, or the first; NULL (err set) when there is none. */
static const struct gltf_camera *
choose_camera(struct parser *p, const struct token *at, const struct gltf_mesh *m, const char *name)
{
    if (m->n_cameras == 0) {
        scene_fail(
            p,
            at,
            "the file has no camera: add one (in Blender: Add > Camera, then export with "
            "Include > Cameras ticked), or write a .scene file whose 'mesh' statement loads it");
        return NULL;
    }
    if (!name) {
        return &m->cameras[0];
    }
    char list[256] = "";
    size_t used = 0;
    for (size_t i = 0; i < m->n_cameras; i++) {
        if (strcmp(m->cameras[i].name, name) == 0) {
            return &m->cameras[i];
        }
        used += (size_t)snprintf(
            list + used,
            used < sizeof list ? sizeof list - used : 0,
            "%s'%s'",
            i ? ", " : "",
            m->cameras[i].name);
        used = used < sizeof list ? used : sizeof list;
    }
    scene_fail(p, at, "no camera named '%s' in the file (its cameras: %s)", name, list);
    return NULL;
}

static bool
set_camera(struct parser *p, const struct token *at, const struct gltf_camera *c)
{
    struct scene *s = p->scene;
    if (!c->perspective) {
        return scene_fail(
            p,
            at,
            "camera '%s' is orthographic: only perspective cameras are supported",
            c->name);
    }
    double fov = c->yfov * RAD_TO_DEG;
    if (!(fov > 0 && fov < 180)) {
        return scene_fail(
            p,
            at,
            "camera '%s': yfov must be in (0, pi) radians, got %g",
            c->name,
            c->yfov);
    }
    s->camera = (struct camera_desc){
        .origin = vec_from(c->origin),
        .target = vec3_add(vec_from(c->origin), vec_from(c->forward)),
        .up = vec_from(c->up),
        .vfov_deg = (real)fov,
    };
    /* -W and -H rescale this keeping the aspect ratio (render's image_size). */
    double aspect = c->aspect > 0 ? c->aspect : DEFAULT_ASPECT;
    double h = DEFAULT_WIDTH / aspect + 0.5;
    s->width = DEFAULT_WIDTH;
    s->height = h < 1 ? 1 : h > SCENE_MAX_IMAGE_DIM ? SCENE_MAX_IMAGE_DIM : (int)h;
    return true;
}

static const char *const light_type_names[] = {"point", "spot", "directional"};

/* Point lights in W/sr; spot and directional lights and a point light's
 * range are noted, one line per kind. */
static bool
add_lights(struct parser *p, const struct token *at, const char *file, const struct gltf_mesh *m)
{
    int skipped[3] = {0, 0, 0};
    const char *first[3] = {NULL, NULL, NULL};
    int ranged = 0;
    const struct gltf_light *first_ranged = NULL;
    for (size_t i = 0; i < m->n_lights; i++) {
        const struct gltf_light *l = &m->lights[i];
        if (l->type != GLTF_LIGHT_POINT) {
            first[l->type] = skipped[l->type]++ ? first[l->type] : l->name;
            continue;
        }
        first_ranged = l->range > 0 && ranged++ == 0 ? l : first_ranged;
        vec3 intensity = vec3_scale(vec_from(l->color), (real)(l->intensity / LUMENS_PER_WATT));
        if (!scene_add_point_light(
                p,
                at,
                (struct point_light){.position = vec_from(l->position), .intensity = intensity})) {
            return false;
        }
    }
    for (int t = GLTF_LIGHT_SPOT; t <= GLTF_LIGHT_DIRECTIONAL; t++) {
        if (skipped[t]) {
            scene_add_note(
                p->scene,
                scene_loc_of(at),
                "%s: %s light '%s' not modelled; ignored%s",
                file,
                light_type_names[t],
                first[t],
                skipped[t] > 1 ? " (and the file's other ones)" : "");
        }
    }
    if (first_ranged) {
        scene_add_note(
            p->scene,
            scene_loc_of(at),
            "%s: point light '%s': range %g not modelled; it lights every distance",
            file,
            first_ranged->name,
            first_ranged->range);
    }
    return true;
}

/* A file that brings no light of its own gets one at the camera, so that
 * it renders at all: intensity pi d^2, d the distance from the camera to
 * the centre of the model's bounding box, which makes a white diffuse
 * surface facing the camera at that distance about as bright as 1. */
static bool
add_headlight(struct parser *p, const struct token *at, const char *file)
{
    struct scene *s = p->scene;
    vec3 lo = vec3_splat(REAL_MAX);
    vec3 hi = vec3_splat(-REAL_MAX);
    for (int i = 0; i < s->n_vertices; i++) {
        lo = vec3_min(lo, s->positions[i]);
        hi = vec3_max(hi, s->positions[i]);
    }
    vec3 centre = vec3_scale(vec3_add(lo, hi), (real)0.5);
    real d = s->n_vertices > 0 ? vec3_length(vec3_sub(centre, s->camera.origin)) : 1;
    d = d > 0 && isfinite(d) ? d : 1;
    real intensity = PI * d * d;
    scene_add_note(
        s,
        scene_loc_of(at),
        "%s has no lights; lit by a headlight, a point light of %g W/sr at the camera (add "
        "lights to the file to light it yourself)",
        file,
        (double)intensity);
    return scene_add_point_light(
        p,
        at,
        (struct point_light){.position = s->camera.origin, .intensity = vec3_splat(intensity)});
}

bool
scene_load_gltf(
    const char *path,
    const char *camera,
    uint64_t max_bytes,
    struct scene *out,
    struct diag *err)
{
    *out = (struct scene){.width = 0};
    snprintf(out->path, sizeof out->path, "%s", path);
    struct parser p = {
        .src = "",
        .line = 1,
        .col = 1,
        .name = path,
        .scene = out,
        .err = err,
        .max_bytes = max_bytes,
    };
    /* Diagnostics about the file as a whole: no line, no column. */
    const struct token at = {.kind = TOK_EOF, .text = "", .line = 0, .col = 0};
    const char *slash = strrchr(path, '/');
    const char *file = slash ? slash + 1 : path;
    struct gltf_mesh mesh = {.n_vertices = 0};
    const struct gltf_camera *cam = NULL;
    bool ok = scene_load_gltf_file(&p, &at, NULL, path, &mesh)
              && (cam = choose_camera(&p, &at, &mesh, camera)) != NULL && set_camera(&p, &at, cam)
              && scene_append_file_mesh(&p, &at, file, &mesh) && add_lights(&p, &at, file, &mesh);
    if (ok && out->n_point_lights == 0 && out->n_area_lights == 0) {
        ok = add_headlight(&p, &at, file);
    }
    gltf_free(&mesh);
    if (!ok) {
        scene_free(out);
    }
    return ok;
}
