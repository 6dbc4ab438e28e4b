/*
 * scene_gltf_material.h - one glTF material mapped onto the kinds the
 * renderer models (scene_gltf_material.c), and what it drops, kind by
 * kind, for scene_gltf.c's notes.
 */
#ifndef SCENE_GLTF_MATERIAL_H
#define SCENE_GLTF_MATERIAL_H

#include "gltf.h"
#include "scene.h"

/* ORDER DROP: the kinds of what a material asks for and no stage models,
 * one note each. */
enum dropped {
    DROP_BASE_COLOR_TEXTURE,
    DROP_METALLIC_ROUGHNESS_TEXTURE,
    DROP_NORMAL_TEXTURE,
    DROP_OCCLUSION_TEXTURE,
    DROP_EMISSIVE_TEXTURE,
    DROP_METALLIC,
    DROP_ROUGHNESS,
    DROP_TRANSMISSION,
    DROP_GLASS_COLOR,
    DROP_EMITTER_COLOR,
    DROP_ALPHA,
    DROP_EXTENSIONS,
    DROP_KINDS,
};

/* One material's mapping: what it becomes, and what each dropped kind
 * says (empty when nothing of that kind was dropped). */
struct mapping {
    struct material material;
    vec3 emission; /* non-zero: its triangles emit this radiance */
    bool two_sided;
    char why[DROP_KINDS][200];
};

/* g mapped onto a material the stages model, with what it drops. */
void scene_gltf_map_material(const struct gltf_material *g, struct mapping *out);

#endif
