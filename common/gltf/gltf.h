/*
 * gltf.h - triangle meshes from glTF 2.0 files (.gltf or .glb).
 *
 * The only C++ in the project lives behind this C API: gltf_load.cc (and the
 * gltf_*.cc files it lists) wraps tinygltf (Debian's libtinygltf-dev) when
 * the build finds it, and gltf_stub.c, compiled otherwise, returns a clear
 * error instead.
 *
 * gltf_load flattens every TRIANGLES primitive of the default scene (or of
 * scene 0 when none is marked default) into one world-space triangle list:
 * each node's transform (matrix or TRS, composed down the node tree) applied
 * to positions, its inverse transpose to normals.  Indices are 8, 16 or 32
 * bit; non-indexed primitives are taken three vertices at a time.
 *
 * Each triangle keeps the index of its primitive's glTF material, and the
 * materials are returned as the file gives them (gltf_material: factors,
 * extensions, which textures are used); what the renderer makes of them is
 * the scene loader's business (scene_gltf.c).  The cameras and the
 * KHR_lights_punctual lights of the nodes reached are returned in world
 * space, for a file rendered as the whole scene.
 *
 * The file is untrusted input: external buffer URIs must be relative and stay
 * inside the model's directory, every accessor is bounds-checked against its
 * buffer view and buffer before it is read, every index against the vertex
 * count, and sizes are checked before anything is allocated.  A broken file
 * gives false and a message, never a crash.
 */
#ifndef GLTF_H
#define GLTF_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "diag.h"

#define GLTF_MAX_NAME 63 /* longer names are cut; control bytes become '?' */

/* The texture slots of a material that name a texture (bits). */
enum gltf_texture {
    GLTF_TEX_BASE_COLOR = 1,
    GLTF_TEX_METALLIC_ROUGHNESS = 2,
    GLTF_TEX_NORMAL = 4,
    GLTF_TEX_OCCLUSION = 8,
    GLTF_TEX_EMISSIVE = 16,
};

enum gltf_alpha_mode {
    GLTF_ALPHA_OPAQUE,
    GLTF_ALPHA_MASK,
    GLTF_ALPHA_BLEND
};

/* A glTF material as written, defaults filled in (glTF 2.0, "Materials"). */
struct gltf_material {
    char name[GLTF_MAX_NAME + 1]; /* "" when the file gives none */
    double base_color[4]; /* baseColorFactor: linear RGB and alpha; default 1 */
    double metallic, roughness; /* metallicFactor, roughnessFactor; default 1 */
    double emissive[3]; /* emissiveFactor times KHR_materials_emissive_strength */
    bool has_transmission; /* KHR_materials_transmission present */
    double transmission; /* its transmissionFactor (default 0) */
    double ior; /* KHR_materials_ior's ior, 1.5 without it */
    bool double_sided;
    enum gltf_alpha_mode alpha_mode;
    unsigned textures; /* enum gltf_texture bits */
    /* No stage maps a texture: the base colour and emissive textures stand
     * as their images' mean linear colour (decoded from sRGB), for the
     * slots in `averaged`; the share of the emissive image's texels that
     * glow; why a slot named in `textures` was not averaged ("" if it was). */
    unsigned averaged; /* enum gltf_texture bits */
    double base_color_mean[3];
    double emissive_mean[3];
    double emissive_glow; /* 0..1 */
    char base_color_why[64];
    char emissive_why[64];
    /* Extensions of the material that are none of the above, their names
     * separated by ", " (cut to fit; "" when none). */
    char other_extensions[160];
};

/* A camera node: a pinhole at origin looking along forward (the node's -z),
 * up its +y, both unit, in world space. */
struct gltf_camera {
    char name[GLTF_MAX_NAME + 1]; /* the camera's name, else its node's, else "" */
    bool perspective; /* false: orthographic */
    double yfov; /* vertical field of view, radians (perspective) */
    double aspect; /* width / height; 0 when the file gives none */
    double origin[3], forward[3], up[3];
};

enum gltf_light_type {
    GLTF_LIGHT_POINT,
    GLTF_LIGHT_SPOT,
    GLTF_LIGHT_DIRECTIONAL
};

/* A KHR_lights_punctual light node, in world space. */
struct gltf_light {
    char name[GLTF_MAX_NAME + 1];
    enum gltf_light_type type;
    double color[3]; /* linear RGB, default 1 */
    double intensity; /* candela (point, spot) or lux (directional) */
    double range; /* 0: unlimited */
    double position[3], direction[3]; /* direction: the node's -z, unit */
};

#define GLTF_MAX_DROPPED 8

struct gltf_mesh {
    size_t n_vertices;
    double *positions; /* 3 * n_vertices, world space */
    double *normals; /* 3 * n_vertices, unit; NULL when no primitive had normals;
                        (0,0,0) for the vertices of primitives without them */
    size_t n_triangles;
    unsigned *indices; /* 3 * n_triangles, each < n_vertices */
    int *triangle_material; /* n_triangles: index into materials, or -1 for a
                               primitive without one (glTF's default material) */
    struct gltf_material *materials;
    size_t n_materials;
    struct gltf_camera *cameras; /* in the order the node tree is walked */
    size_t n_cameras;
    struct gltf_light *lights;
    size_t n_lights;
    /* What of the file no stage models, beside its materials (those are
     * noted by the scene loader): skins, animations, morph targets,
     * instancing, other extensions; one line each, "what not modelled;
     * what is used instead". */
    char dropped[GLTF_MAX_DROPPED][200];
    int n_dropped;
    /* The other files the load read (external buffers, and images, read
     * though never decoded), each once, as opened: the model's directory
     * joined to the URI.  They are inputs of a render as the model is. */
    char **files;
    size_t n_files;
};

/* True when built with tinygltf. */
bool gltf_available(void);

/* Load path into out (zero-initialised by the caller).  On failure out is
 * left empty and err names the file and the problem.  The mesh's arrays may
 * take at most GLTF_DEFAULT_MAX_BYTES. */
bool gltf_load(const char *path, struct gltf_mesh *out, struct diag *err);

/* 4 GiB, the default limit of a scene's arrays too (scene.h). */
#define GLTF_DEFAULT_MAX_BYTES ((uint64_t)4 << 30)

/* Same, with the mesh's arrays limited to max_bytes, checked once the
 * vertices and triangles are counted (each node that instances a mesh
 * counts it again) and before anything is allocated for them. */
bool
gltf_load_limited(const char *path, uint64_t max_bytes, struct gltf_mesh *out, struct diag *err);

/* Free; accepts a zero-initialised mesh. */
void gltf_free(struct gltf_mesh *mesh);

#endif /* GLTF_H */
