// gltf_dropped.cc - what of a glTF file no stage models, beside its
// materials, named one line each (gltf.h, gltf_mesh.dropped): the scene
// loader turns each into a note, and --strict refuses the scene.
#include <string>

#include "gltf_steps.h"

static void
add(struct gltf_mesh *out, const std::string &line)
{
    if (out->n_dropped < GLTF_MAX_DROPPED) {
        snprintf(out->dropped[out->n_dropped++], sizeof out->dropped[0], "%s", line.c_str());
    }
}

static bool
has_morph_targets(const tinygltf::Model &model)
{
    for (const tinygltf::Mesh &mesh : model.meshes) {
        for (const tinygltf::Primitive &prim : mesh.primitives) {
            if (!prim.targets.empty()) {
                return true;
            }
        }
    }
    return false;
}

static size_t
instanced_nodes(const tinygltf::Model &model)
{
    size_t n = 0;
    for (const tinygltf::Node &node : model.nodes) {
        n += node.extensions.count("EXT_mesh_gpu_instancing") > 0;
    }
    return n;
}

// Extensions read, refused or named elsewhere: materials' (named by the
// scene loader, material by material), lights, the ones a load refuses
// (check_required_extensions: a file that requires them never gets here)
// and instancing (named above).
static bool
named_elsewhere(const std::string &name)
{
    return (name.compare(0, 14, "KHR_materials_") == 0 && name != "KHR_materials_variants")
           || name == "KHR_lights_punctual" || name == "EXT_mesh_gpu_instancing"
           || name == "KHR_draco_mesh_compression" || name == "KHR_mesh_quantization";
}

void
copy_dropped(const tinygltf::Model &model, struct gltf_mesh *out)
{
    if (!model.skins.empty()) {
        add(out,
            format(
                "%zu skin(s) not modelled; the skinned meshes as stored, in their bind pose",
                model.skins.size()));
    }
    if (!model.animations.empty()) {
        add(out,
            format(
                "%zu animation(s) not modelled; the nodes' own transforms, no frame of an animation",
                model.animations.size()));
    }
    if (has_morph_targets(model)) {
        add(out, "morph targets not modelled; the base meshes, the targets' weights ignored");
    }
    size_t instanced = instanced_nodes(model);
    if (instanced > 0) {
        add(out,
            format(
                "EXT_mesh_gpu_instancing (%zu node(s)) not modelled; one instance each, at its "
                "node's own transform",
                instanced));
    }
    for (const std::string &name : model.extensionsUsed) {
        if (!named_elsewhere(name)) {
            add(out, format("extension '%.100s' not modelled; ignored", name.c_str()));
        }
    }
}
