/*
 * gltf_nodes.cc - which nodes draw, and where: each node's matrix or TRS
 * transform, composed down the node tree of the default scene (else scene
 * 0, else every root node) into one world transform per mesh drawn.
 */
#include "gltf_steps.h"

#include <cmath>

// Deeper node trees are refused rather than risk the stack.
#define GLTF_MAX_NODE_DEPTH 256

// A node matrix's last row must be (0 0 0 1) to within this.
#define AFFINE_TOLERANCE 1e-6

/* --- node transforms ------------------------------------------------------ */

static mat4
mat4_identity(void)
{
    mat4 r = {};
    for (int i = 0; i < 4; i++) {
        r.m[i * 4 + i] = 1;
    }
    return r;
}

static mat4
mat4_mul(const mat4 &a, const mat4 &b)
{
    mat4 r = {};
    for (int col = 0; col < 4; col++) {
        for (int row = 0; row < 4; row++) {
            double sum = 0;
            for (int k = 0; k < 4; k++) {
                sum += a.m[k * 4 + row] * b.m[col * 4 + k];
            }
            r.m[col * 4 + row] = sum;
        }
    }
    return r;
}

static bool
all_finite(const std::vector<double> &values)
{
    for (double v : values) {
        if (!std::isfinite(v)) {
            return false;
        }
    }
    return true;
}

// T * R * S from a node's translation, rotation (x, y, z, w) and scale.
static mat4
trs_matrix(const std::vector<double> &t, const std::vector<double> &q, const std::vector<double> &s)
{
    double x = q.empty() ? 0 : q[0];
    double y = q.empty() ? 0 : q[1];
    double z = q.empty() ? 0 : q[2];
    double w = q.empty() ? 1 : q[3];
    double len = std::sqrt(x * x + y * y + z * z + w * w);
    x /= len;
    y /= len;
    z /= len;
    w /= len;
    double rot[9] = {
        1 - 2 * (y * y + z * z),
        2 * (x * y + z * w),
        2 * (x * z - y * w),
        2 * (x * y - z * w),
        1 - 2 * (x * x + z * z),
        2 * (y * z + x * w),
        2 * (x * z + y * w),
        2 * (y * z - x * w),
        1 - 2 * (x * x + y * y),
    };
    mat4 r = mat4_identity();
    for (int col = 0; col < 3; col++) {
        double scale = s.empty() ? 1 : s[(size_t)col];
        for (int row = 0; row < 3; row++) {
            r.m[col * 4 + row] = rot[col * 3 + row] * scale;
        }
        r.m[12 + col] = t.empty() ? 0 : t[(size_t)col];
    }
    return r;
}

static bool
node_transform(const tinygltf::Node &node, int index, mat4 *out, std::string *why)
{
    const std::vector<double> &m = node.matrix;
    bool sizes_ok = (m.empty() || m.size() == 16)
                    && (node.translation.empty() || node.translation.size() == 3)
                    && (node.rotation.empty() || node.rotation.size() == 4)
                    && (node.scale.empty() || node.scale.size() == 3);
    if (!sizes_ok) {
        *why =
            format("node %d: matrix, translation, rotation or scale has the wrong length", index);
        return false;
    }
    if (!all_finite(m) || !all_finite(node.translation) || !all_finite(node.rotation)
        || !all_finite(node.scale)) {
        *why = format("node %d: its transform has a non-finite number", index);
        return false;
    }
    if (m.empty()) {
        const std::vector<double> &q = node.rotation;
        if (!q.empty() && q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0) {
            *why = format("node %d: rotation is the zero quaternion", index);
            return false;
        }
        *out = trs_matrix(node.translation, q, node.scale);
        return true;
    }
    if (std::fabs(m[3]) > AFFINE_TOLERANCE || std::fabs(m[7]) > AFFINE_TOLERANCE
        || std::fabs(m[11]) > AFFINE_TOLERANCE || std::fabs(m[15] - 1) > AFFINE_TOLERANCE) {
        *why = format("node %d: matrix is not affine (its last row is not 0 0 0 1)", index);
        return false;
    }
    for (int i = 0; i < 16; i++) {
        out->m[i] = m[(size_t)i];
    }
    return true;
}

/* --- choosing the nodes --------------------------------------------------- */

struct walker {
    const tinygltf::Model *model;
    std::vector<char> seen;
    std::vector<job> jobs;
    std::vector<placed> cameras_and_lights;
};

// The light index of a node's KHR_lights_punctual extension, or -1.
static bool
node_light(
    const tinygltf::Model &model,
    const tinygltf::Node &node,
    int index,
    int *light,
    std::string *why)
{
    *light = -1;
    auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end()) {
        return true;
    }
    const tinygltf::Value &v = ext->second;
    bool is_int = v.IsObject() && v.Has("light") && v.Get("light").IsInt();
    *light = is_int ? v.Get("light").Get<int>() : -2;
    if (*light < 0 || (size_t)*light >= model.lights.size()) {
        *why = format("node %d: its KHR_lights_punctual light does not exist", index);
        return false;
    }
    return true;
}

static bool
walk_node(walker *w, int index, const mat4 &parent, int depth, std::string *why)
{
    if (depth > GLTF_MAX_NODE_DEPTH) {
        *why = format("the node tree is deeper than %d levels", GLTF_MAX_NODE_DEPTH);
        return false;
    }
    if (w->seen[(size_t)index]) {
        *why =
            format("node %d is reached twice: the node tree has a cycle or a shared child", index);
        return false;
    }
    w->seen[(size_t)index] = 1;
    const tinygltf::Node &node = w->model->nodes[(size_t)index];
    mat4 local;
    if (!node_transform(node, index, &local, why)) {
        return false;
    }
    mat4 world = mat4_mul(parent, local);
    if (node.mesh < -1 || node.mesh >= (int)w->model->meshes.size()) {
        *why = format("node %d: mesh %d does not exist", index, node.mesh);
        return false;
    }
    if (node.mesh >= 0) {
        w->jobs.push_back(job{node.mesh, world});
    }
    int light;
    if (node.camera < -1 || node.camera >= (int)w->model->cameras.size()) {
        *why = format("node %d: camera %d does not exist", index, node.camera);
        return false;
    }
    if (!node_light(*w->model, node, index, &light, why)) {
        return false;
    }
    if (node.camera >= 0 || light >= 0) {
        w->cameras_and_lights.push_back(placed{index, node.camera, light, world});
    }
    for (int child : node.children) {
        if (child < 0 || (size_t)child >= w->model->nodes.size()) {
            *why = format("node %d: child node %d does not exist", index, child);
            return false;
        }
        if (!walk_node(w, child, world, depth + 1, why)) {
            return false;
        }
    }
    return true;
}

// The nodes the scene starts from (see the decisions at the top).
static bool
root_nodes(const tinygltf::Model &model, std::vector<int> *roots, std::string *why)
{
    int scene = model.defaultScene;
    if (scene != -1 && (scene < 0 || (size_t)scene >= model.scenes.size())) {
        *why = format("the default scene %d does not exist", scene);
        return false;
    }
    if (scene == -1 && !model.scenes.empty()) {
        scene = 0;
    }
    if (scene >= 0) {
        *roots = model.scenes[(size_t)scene].nodes;
        return true;
    }
    std::vector<char> is_child(model.nodes.size(), 0);
    for (const tinygltf::Node &node : model.nodes) {
        for (int child : node.children) {
            if (child >= 0 && (size_t)child < model.nodes.size()) {
                is_child[(size_t)child] = 1;
            }
        }
    }
    for (size_t i = 0; i < model.nodes.size(); i++) {
        if (!is_child[i]) {
            roots->push_back((int)i);
        }
    }
    return true;
}

bool
collect_jobs(
    const tinygltf::Model &model,
    std::vector<job> *jobs,
    std::vector<placed> *cameras_and_lights,
    std::string *why)
{
    std::vector<int> roots;
    if (!root_nodes(model, &roots, why)) {
        return false;
    }
    walker w = {&model, std::vector<char>(model.nodes.size(), 0), {}, {}};
    for (int root : roots) {
        if (root < 0 || (size_t)root >= model.nodes.size()) {
            *why = format("the scene lists node %d, which does not exist", root);
            return false;
        }
        if (!walk_node(&w, root, mat4_identity(), 0, why)) {
            return false;
        }
    }
    jobs->swap(w.jobs);
    cameras_and_lights->swap(w.cameras_and_lights);
    return true;
}
