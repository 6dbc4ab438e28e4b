/*
 * gltf_extras.cc - what a glTF file holds beyond triangles, copied out as
 * the file gives it (gltf.h): its materials (factors, the extensions the
 * renderer reads, which textures and other extensions are used), and the
 * cameras and KHR_lights_punctual lights of the nodes reached, in world
 * space.  Deciding what becomes of them is the scene loader's business.
 *
 * Every number is checked: a non-finite or out-of-range factor refuses the
 * file, as a broken accessor does.
 */
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "gltf_steps.h"

// Copy a name of the file into a fixed buffer: cut, control bytes as '?'.
static void
copy_name(char *dst, size_t cap, const std::string &src)
{
    size_t n = src.size() < cap - 1 ? src.size() : cap - 1;
    for (size_t i = 0; i < n; i++) {
        unsigned char c = (unsigned char)src[i];
        dst[i] = c < ' ' || c == 0x7f ? '?' : (char)c;
    }
    dst[n] = '\0';
}

// A number of an extension object, or fallback when it is absent.
static bool
ext_number(
    const tinygltf::Value &ext,
    const char *key,
    double fallback,
    double *out,
    const std::string &ctx,
    std::string *why)
{
    *out = fallback;
    if (!ext.IsObject() || !ext.Has(key)) {
        return true;
    }
    const tinygltf::Value &v = ext.Get(key);
    if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble())) {
        *why = format("%s: %s is not a finite number", ctx.c_str(), key);
        return false;
    }
    *out = v.GetNumberAsDouble();
    return true;
}

// Each value finite and in [lo, hi].
static bool
check_factors(
    const std::vector<double> &v,
    size_t n,
    double lo,
    double hi,
    const std::string &what,
    std::string *why)
{
    if (!v.empty() && v.size() != n) {
        *why = format("%s has %zu numbers, expected %zu", what.c_str(), v.size(), n);
        return false;
    }
    for (double x : v) {
        if (!(x >= lo && x <= hi)) {
            *why = format("%s: %g is not in [%g, %g]", what.c_str(), x, lo, hi);
            return false;
        }
    }
    return true;
}

// The extension names of the material that the renderer does not read.
static void
other_extensions(const tinygltf::Material &m, bool transmission_texture, gltf_material *out)
{
    std::string list;
    for (const auto &ext : m.extensions) {
        const std::string &name = ext.first;
        if (name == "KHR_materials_emissive_strength" || name == "KHR_materials_ior"
            || name == "KHR_materials_transmission") {
            continue;
        }
        list += (list.empty() ? "" : ", ") + name;
    }
    if (transmission_texture) {
        list += std::string(list.empty() ? "" : ", ") + "transmissionTexture";
    }
    copy_name(out->other_extensions, sizeof out->other_extensions, list);
}

static bool
copy_extensions(
    const tinygltf::Material &m,
    const std::string &ctx,
    gltf_material *out,
    std::string *why)
{
    const tinygltf::Value none;
    auto find = [&](const char *name) -> const tinygltf::Value & {
        auto it = m.extensions.find(name);
        return it == m.extensions.end() ? none : it->second;
    };
    const tinygltf::Value &strength = find("KHR_materials_emissive_strength");
    const tinygltf::Value &transmission = find("KHR_materials_transmission");
    const tinygltf::Value &ior = find("KHR_materials_ior");
    double s = 1;
    out->has_transmission = transmission.IsObject();
    if (!ext_number(strength, "emissiveStrength", 1, &s, ctx, why)
        || !ext_number(transmission, "transmissionFactor", 0, &out->transmission, ctx, why)
        || !ext_number(ior, "ior", 1.5, &out->ior, ctx, why)) {
        return false;
    }
    if (!(s >= 0) || !(out->transmission >= 0 && out->transmission <= 1) || !(out->ior >= 0)) {
        *why = format(
            "%s: emissiveStrength %g, transmissionFactor %g or ior %g is out of range",
            ctx.c_str(),
            s,
            out->transmission,
            out->ior);
        return false;
    }
    for (int k = 0; k < 3; k++) {
        out->emissive[k] *= s;
    }
    bool transmission_texture = transmission.IsObject() && transmission.Has("transmissionTexture");
    other_extensions(m, transmission_texture, out);
    return true;
}

static bool
copy_material(const tinygltf::Material &m, size_t index, gltf_material *out, std::string *why)
{
    std::string ctx = format("material %zu", index);
    const tinygltf::PbrMetallicRoughness &pbr = m.pbrMetallicRoughness;
    if (!check_factors(pbr.baseColorFactor, 4, 0, 1, ctx + " baseColorFactor", why)
        || !check_factors(m.emissiveFactor, 3, 0, 1, ctx + " emissiveFactor", why)
        || !check_factors({pbr.metallicFactor, pbr.roughnessFactor}, 2, 0, 1, ctx, why)) {
        return false;
    }
    if (m.name.empty()) {
        copy_name(out->name, sizeof out->name, format("#%zu", index));
    } else {
        copy_name(out->name, sizeof out->name, m.name);
    }
    for (int k = 0; k < 4; k++) {
        out->base_color[k] = pbr.baseColorFactor.empty() ? 1 : pbr.baseColorFactor[(size_t)k];
    }
    for (int k = 0; k < 3; k++) {
        out->emissive[k] = m.emissiveFactor.empty() ? 0 : m.emissiveFactor[(size_t)k];
    }
    out->metallic = pbr.metallicFactor;
    out->roughness = pbr.roughnessFactor;
    out->double_sided = m.doubleSided;
    out->alpha_mode = m.alphaMode == "BLEND"  ? GLTF_ALPHA_BLEND
                      : m.alphaMode == "MASK" ? GLTF_ALPHA_MASK
                                              : GLTF_ALPHA_OPAQUE;
    out->textures =
        (pbr.baseColorTexture.index >= 0 ? (unsigned)GLTF_TEX_BASE_COLOR : 0u)
        | (pbr.metallicRoughnessTexture.index >= 0 ? (unsigned)GLTF_TEX_METALLIC_ROUGHNESS : 0u)
        | (m.normalTexture.index >= 0 ? (unsigned)GLTF_TEX_NORMAL : 0u)
        | (m.occlusionTexture.index >= 0 ? (unsigned)GLTF_TEX_OCCLUSION : 0u)
        | (m.emissiveTexture.index >= 0 ? (unsigned)GLTF_TEX_EMISSIVE : 0u);
    return copy_extensions(m, ctx, out, why);
}

bool
copy_materials(const tinygltf::Model &model, struct gltf_mesh *out, std::string *why)
{
    size_t n = model.materials.size();
    out->materials = (gltf_material *)calloc(n + 1, sizeof *out->materials);
    if (!out->materials) {
        throw out_of_memory{format("out of memory for %zu materials", n)};
    }
    out->n_materials = n;
    texture_means cache;
    for (size_t i = 0; i < n; i++) {
        if (!copy_material(model.materials[i], i, &out->materials[i], why)) {
            return false;
        }
        average_textures(model, model.materials[i], &cache, &out->materials[i]);
    }
    return true;
}

/* --- cameras and lights ---------------------------------------------------- */

// Column c of the world matrix (0: x axis, 1: y, 2: z, 3: the origin),
// scaled by sign; unit when unit is set.  False when it cannot be made
// unit (a degenerate transform).
static bool
world_column(const mat4 &w, int c, double sign, bool unit, double out[3])
{
    for (int r = 0; r < 3; r++) {
        out[r] = sign * w.m[c * 4 + r];
    }
    if (!unit) {
        return std::isfinite(out[0] + out[1] + out[2]);
    }
    double len = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
    if (!(len > 0) || !std::isfinite(len)) {
        return false;
    }
    for (int r = 0; r < 3; r++) {
        out[r] /= len;
    }
    return true;
}

static bool
copy_camera(const tinygltf::Model &model, const placed &at, gltf_camera *out, std::string *why)
{
    const tinygltf::Camera &c = model.cameras[(size_t)at.camera];
    std::string name = c.name.empty() ? model.nodes[(size_t)at.node].name : c.name;
    copy_name(out->name, sizeof out->name, name.empty() ? format("#%d", at.camera) : name);
    out->perspective = c.type != "orthographic";
    out->yfov = c.perspective.yfov;
    out->aspect = c.perspective.aspectRatio;
    bool ok = std::isfinite(out->yfov) && std::isfinite(out->aspect) && out->aspect >= 0
              && world_column(at.world, 3, 1, false, out->origin)
              && world_column(at.world, 2, -1, true, out->forward)
              && world_column(at.world, 1, 1, true, out->up);
    if (!ok) {
        *why = format(
            "node %d: camera %d has a degenerate transform or a bad field",
            at.node,
            at.camera);
    }
    return ok;
}

static bool
copy_light(const tinygltf::Model &model, const placed &at, gltf_light *out, std::string *why)
{
    const tinygltf::Light &l = model.lights[(size_t)at.light];
    copy_name(
        out->name,
        sizeof out->name,
        l.name.empty() ? model.nodes[(size_t)at.node].name : l.name);
    out->type = l.type == "spot"          ? GLTF_LIGHT_SPOT
                : l.type == "directional" ? GLTF_LIGHT_DIRECTIONAL
                                          : GLTF_LIGHT_POINT;
    std::string ctx = format("light %d", at.light);
    if (!check_factors(l.color, 3, 0, 1, ctx + " color", why)) {
        return false;
    }
    for (int k = 0; k < 3; k++) {
        out->color[k] = l.color.empty() ? 1 : l.color[(size_t)k];
    }
    out->intensity = l.intensity;
    out->range = l.range;
    bool ok = l.intensity >= 0 && std::isfinite(l.intensity) && l.range >= 0
              && std::isfinite(l.range) && world_column(at.world, 3, 1, false, out->position)
              && world_column(at.world, 2, -1, true, out->direction);
    if (!ok) {
        *why = format(
            "node %d: %s has a negative or non-finite intensity or range, or a "
            "degenerate transform",
            at.node,
            ctx.c_str());
    }
    return ok;
}

bool
copy_placed(
    const tinygltf::Model &model,
    const std::vector<placed> &cameras_and_lights,
    struct gltf_mesh *out,
    std::string *why)
{
    size_t n = cameras_and_lights.size();
    out->cameras = (gltf_camera *)calloc(n + 1, sizeof *out->cameras);
    out->lights = (gltf_light *)calloc(n + 1, sizeof *out->lights);
    if (!out->cameras || !out->lights) {
        throw out_of_memory{format("out of memory for %zu cameras and lights", n)};
    }
    for (const placed &at : cameras_and_lights) {
        if (at.camera >= 0 && !copy_camera(model, at, &out->cameras[out->n_cameras++], why)) {
            return false;
        }
        if (at.light >= 0 && !copy_light(model, at, &out->lights[out->n_lights++], why)) {
            return false;
        }
    }
    return true;
}
