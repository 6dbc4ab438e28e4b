/*
 * scene_gltf_material.c - one glTF material mapped onto the kinds the
 * renderer models (docs/scene-format.md, "Materials from the file"): base
 * colour to a diffuse albedo (a texture as its mean colour), a smooth
 * metal to a mirror, transmission to glass, emission to emitting
 * triangles; each kind of thing it asks for that no stage models is said
 * in its mapping's `why`.
 */
#include "scene_gltf_material.h"

#include <stdio.h>
#include <string.h>

/* A roughnessFactor at or below this counts as perfectly smooth: a mirror
 * or clear glass (GGX with alpha = roughness^2 = 0.0025 is a highlight a
 * fraction of a degree wide). */
#define SMOOTH_ROUGHNESS 0.05

static real
clamp01(double x)
{
    return (real)(x < 0 ? 0 : x > 1 ? 1 : x);
}

/* baseColorFactor, times its texture's mean where it was averaged
 * (gltf_textures.cc: no stage maps a texture). */
static vec3
base_color(const struct gltf_material *g)
{
    const double *mean = g->base_color_mean;
    bool textured = g->averaged & GLTF_TEX_BASE_COLOR;
    return vec3_make(
        clamp01(g->base_color[0] * (textured ? mean[0] : 1)),
        clamp01(g->base_color[1] * (textured ? mean[1] : 1)),
        clamp01(g->base_color[2] * (textured ? mean[2] : 1)));
}

/* emissiveFactor x strength, times its texture's mean where it was averaged. */
static vec3
emission(const struct gltf_material *g)
{
    const double *mean = g->emissive_mean;
    bool textured = g->averaged & GLTF_TEX_EMISSIVE;
    return vec3_make(
        (real)(g->emissive[0] * (textured ? mean[0] : 1)),
        (real)(g->emissive[1] * (textured ? mean[1] : 1)),
        (real)(g->emissive[2] * (textured ? mean[2] : 1)));
}

/* Whether the material is a light.  It must emit; with an emissive texture
 * averaged, its glow must also cover at least half of the texture's texels
 * (a car's lamp), or its surface be black.  A glow on less than half is a
 * detail of a surface that reflects (a helmet's lights): no stage models a
 * surface that does both, and the larger part decides. */
static bool
is_emitter(const struct gltf_material *g)
{
    if (vec3_is_zero(emission(g))) {
        return false;
    }
    bool textured = g->averaged & GLTF_TEX_EMISSIVE;
    return !textured || g->emissive_glow >= 0.5 || vec3_is_zero(base_color(g));
}

static const char *
kind_name(enum material_kind kind)
{
    switch (kind) {
    case MAT_MIRROR:
        return "a mirror";
    case MAT_GLASS:
        return "glass";
    default:
        return "diffuse";
    }
}

static void
note_textures(const struct gltf_material *g, struct mapping *out)
{
    vec3 c = base_color(g);
    if ((g->textures & GLTF_TEX_BASE_COLOR) && (g->averaged & GLTF_TEX_BASE_COLOR)) {
        const double *m = g->base_color_mean;
        snprintf(
            out->why[DROP_BASE_COLOR_TEXTURE],
            sizeof out->why[0],
            "baseColorTexture not modelled; using its mean (%.3g, %.3g, %.3g) x baseColorFactor: "
            "(%.3g, %.3g, %.3g)",
            m[0],
            m[1],
            m[2],
            (double)c.x,
            (double)c.y,
            (double)c.z);
    } else if (g->textures & GLTF_TEX_BASE_COLOR) {
        snprintf(
            out->why[DROP_BASE_COLOR_TEXTURE],
            sizeof out->why[0],
            "baseColorTexture not modelled (%s); using baseColorFactor (%g, %g, %g)",
            g->base_color_why,
            (double)c.x,
            (double)c.y,
            (double)c.z);
    }
    if (g->textures & GLTF_TEX_METALLIC_ROUGHNESS) {
        snprintf(
            out->why[DROP_METALLIC_ROUGHNESS_TEXTURE],
            sizeof out->why[0],
            "metallicRoughnessTexture not modelled; using metallicFactor %g and roughnessFactor %g",
            g->metallic,
            g->roughness);
    }
    if (g->textures & GLTF_TEX_NORMAL) {
        snprintf(
            out->why[DROP_NORMAL_TEXTURE],
            sizeof out->why[0],
            "normalTexture not modelled; using the mesh's normals");
    }
    if (g->textures & GLTF_TEX_OCCLUSION) {
        snprintf(
            out->why[DROP_OCCLUSION_TEXTURE],
            sizeof out->why[0],
            "occlusionTexture not modelled; ignored (light is traced, not baked)");
    }
    vec3 e = emission(g);
    if ((g->textures & GLTF_TEX_EMISSIVE) && (g->averaged & GLTF_TEX_EMISSIVE)) {
        snprintf(
            out->why[DROP_EMISSIVE_TEXTURE],
            sizeof out->why[0],
            is_emitter(g) ? "emissiveTexture not modelled; emitting its mean x emissiveFactor x "
                            "strength (%.3g, %.3g, %.3g) (it glows on %.0f%% of its texels)"
                          : "emissiveTexture not modelled; its glow (%.3g, %.3g, %.3g on "
                            "average) is on %.0f%% of its texels: a surface that reflects, the "
                            "glow dropped",
            (double)e.x,
            (double)e.y,
            (double)e.z,
            100 * g->emissive_glow);
    } else if (g->textures & GLTF_TEX_EMISSIVE) {
        snprintf(
            out->why[DROP_EMISSIVE_TEXTURE],
            sizeof out->why[0],
            "emissiveTexture not modelled (%s); using emissiveFactor x strength (%g, %g, %g)",
            g->emissive_why,
            (double)e.x,
            (double)e.y,
            (double)e.z);
    }
}

static void
note_alpha_and_extensions(const struct gltf_material *g, struct mapping *out)
{
    static const char *const modes[] = {"OPAQUE", "MASK", "BLEND"};
    if (g->alpha_mode != GLTF_ALPHA_OPAQUE) {
        snprintf(
            out->why[DROP_ALPHA],
            sizeof out->why[0],
            "alphaMode %s (alpha %g) not modelled; opaque",
            modes[g->alpha_mode],
            g->base_color[3]);
    }
    if (g->other_extensions[0]) {
        snprintf(
            out->why[DROP_EXTENSIONS],
            sizeof out->why[0],
            "%s not modelled; ignored",
            g->other_extensions);
    }
}

/* An emissive material: its triangles emit; as surfaces they are black,
 * as every light is (SCENES.md). */
static void
map_emitter(const struct gltf_material *g, struct mapping *out)
{
    out->emission = emission(g);
    out->two_sided = g->double_sided;
    out->material.kind = MAT_DIFFUSE;
    vec3 c = base_color(g);
    if (!vec3_is_zero(c)) {
        snprintf(
            out->why[DROP_EMITTER_COLOR],
            sizeof out->why[0],
            "baseColorFactor (%g, %g, %g) of an emissive material not modelled; emitting "
            "surfaces reflect nothing",
            (double)c.x,
            (double)c.y,
            (double)c.z);
    }
}

/* KHR_materials_transmission: smooth clear glass of KHR_materials_ior's
 * index. */
static void
map_glass(const struct gltf_material *g, struct mapping *out)
{
    out->material.kind = MAT_GLASS;
    out->material.ior = (real)(g->ior > 0 ? g->ior : 1.5);
    vec3 c = base_color(g);
    if (g->transmission < 1) {
        snprintf(
            out->why[DROP_TRANSMISSION],
            sizeof out->why[0],
            "transmissionFactor %g not modelled; glass transmits all it does not reflect",
            g->transmission);
    }
    if (c.x < 1 || c.y < 1 || c.z < 1) {
        snprintf(
            out->why[DROP_GLASS_COLOR],
            sizeof out->why[0],
            "baseColorFactor (%g, %g, %g) of a transmissive material not modelled; clear glass",
            (double)c.x,
            (double)c.y,
            (double)c.z);
    }
    if (g->roughness > SMOOTH_ROUGHNESS) {
        snprintf(
            out->why[DROP_ROUGHNESS],
            sizeof out->why[0],
            "roughnessFactor %g of a transmissive material not modelled; smooth glass",
            g->roughness);
    }
}

/* The metallic-roughness model's two ends that a stage models: a smooth
 * metal is a mirror reflecting its base colour, a non-metal of roughness 1
 * is diffuse (its 4% specular layer neglected).  In between, the nearest
 * end: metallic >= 0.5 is a metal, and a metal of roughness >= 0.5 is
 * closer to diffuse than to a mirror. */
static void
map_surface(const struct gltf_material *g, struct mapping *out)
{
    bool metal = g->metallic >= 0.5;
    bool mirror = metal && g->roughness < 0.5;
    struct material *m = &out->material;
    m->kind = mirror ? MAT_MIRROR : MAT_DIFFUSE;
    m->reflectance = mirror ? base_color(g) : vec3_splat(0);
    m->albedo = mirror ? vec3_splat(0) : base_color(g);
    const char *as = kind_name(m->kind);
    if (g->metallic > 0 && g->metallic < 1) {
        snprintf(
            out->why[DROP_METALLIC],
            sizeof out->why[0],
            "metallicFactor %g not modelled (only 0 and 1); shaded as %s",
            g->metallic,
            as);
    }
    bool exact = mirror ? g->roughness <= SMOOTH_ROUGHNESS : !metal && g->roughness >= 1;
    if (!exact) {
        snprintf(
            out->why[DROP_ROUGHNESS],
            sizeof out->why[0],
            "roughnessFactor %g of a %s not modelled (a smooth metal is a mirror, a non-metal "
            "of roughness 1 diffuse); shaded as %s",
            g->roughness,
            metal ? "metal" : "non-metal",
            as);
    }
}

void
scene_gltf_map_material(const struct gltf_material *g, struct mapping *out)
{
    memset(out, 0, sizeof *out);
    if (is_emitter(g)) {
        map_emitter(g, out);
    } else if (g->has_transmission && g->transmission > 0) {
        map_glass(g, out);
    } else {
        map_surface(g, out);
    }
    note_textures(g, out);
    note_alpha_and_extensions(g, out);
}
