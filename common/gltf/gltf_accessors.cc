/*
 * gltf_accessors.cc - every primitive's accessors checked against the bytes
 * that were actually loaded (type, component type, buffer view bounds and
 * stride, all in size_t with overflow guards) and planned into parts ready
 * to copy, with the totals checked before anything is allocated.
 */
#include "gltf_steps.h"

#include <climits>

// The scene indexes vertices and triangle corners with int.
#define GLTF_MAX_VERTICES ((size_t)INT_MAX / 3)
#define GLTF_MAX_TRIANGLES ((size_t)INT_MAX / 3)

/* --- checking accessors --------------------------------------------------- */

static const char *
type_name(int type)
{
    switch (type) {
    case TINYGLTF_TYPE_SCALAR:
        return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
        return "VEC2";
    case TINYGLTF_TYPE_VEC3:
        return "VEC3";
    case TINYGLTF_TYPE_VEC4:
        return "VEC4";
    default:
        return "a matrix";
    }
}

// Bytes per component of the types we read; 0 for the others.
static size_t
component_bytes(int component_type, bool is_index)
{
    switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return is_index ? 1 : 0;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return is_index ? 2 : 0;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        return is_index ? 4 : 0;
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return is_index ? 0 : 4;
    default:
        return 0;
    }
}

// The buffer view's bytes within the data actually loaded for its buffer.
static bool
view_bytes(
    const tinygltf::Model &model,
    int index,
    const std::string &ctx,
    const tinygltf::BufferView **out,
    std::string *why)
{
    if (index < 0 || (size_t)index >= model.bufferViews.size()) {
        *why = format("%s: buffer view %d does not exist", ctx.c_str(), index);
        return false;
    }
    const tinygltf::BufferView &bv = model.bufferViews[(size_t)index];
    if (bv.buffer < 0 || (size_t)bv.buffer >= model.buffers.size()) {
        *why =
            format("%s: buffer view %d: buffer %d does not exist", ctx.c_str(), index, bv.buffer);
        return false;
    }
    size_t loaded = model.buffers[(size_t)bv.buffer].data.size();
    if (bv.byteOffset > loaded || bv.byteLength > loaded - bv.byteOffset) {
        *why = format(
            "%s: buffer view %d runs past the end of buffer %d (%zu bytes)",
            ctx.c_str(),
            index,
            bv.buffer,
            loaded);
        return false;
    }
    *out = &bv;
    return true;
}

// The accessor holds what we read (float VEC3, or unsigned SCALAR indices)
// in a buffer view; *elem gets the size of one element in bytes.
static bool
check_accessor_type(
    const tinygltf::Accessor &a,
    int index,
    const char *ctx,
    bool is_index,
    size_t *elem,
    std::string *why)
{
    if (a.sparse.isSparse) {
        *why = format("%s: accessor %d: sparse accessors are not supported", ctx, index);
        return false;
    }
    int want_type = is_index ? TINYGLTF_TYPE_SCALAR : TINYGLTF_TYPE_VEC3;
    size_t comp = component_bytes(a.componentType, is_index);
    if (a.type != want_type || comp == 0) {
        *why = format(
            "%s: accessor %d must be %s (it is %s of componentType %d)",
            ctx,
            index,
            is_index ? "unsigned byte, short or int SCALAR" : "float VEC3",
            type_name(a.type),
            a.componentType);
        return false;
    }
    if (a.bufferView < 0) {
        *why = format("%s: accessor %d has no buffer view", ctx, index);
        return false;
    }
    *elem = comp * (is_index ? 1 : 3);
    return true;
}

// The accessor's elements all lie inside its buffer view, itself inside the
// bytes loaded for its buffer.
static bool
check_accessor(
    const tinygltf::Model &model,
    int index,
    const std::string &ctx,
    bool is_index,
    view *out,
    std::string *why)
{
    const char *c = ctx.c_str();
    if (index < 0 || (size_t)index >= model.accessors.size()) {
        *why = format("%s: accessor %d does not exist", c, index);
        return false;
    }
    const tinygltf::Accessor &a = model.accessors[(size_t)index];
    size_t elem = 0;
    const tinygltf::BufferView *bv = nullptr;
    if (!check_accessor_type(a, index, c, is_index, &elem, why)
        || !view_bytes(model, a.bufferView, ctx, &bv, why)) {
        return false;
    }
    size_t stride = bv->byteStride ? bv->byteStride : elem;
    if (stride < elem) {
        *why = format(
            "%s: buffer view %d: byteStride %zu is less than the %zu-byte elements of accessor %d",
            c,
            a.bufferView,
            stride,
            elem,
            index);
        return false;
    }
    // The last element ends at byteOffset + (count - 1) * stride + elem.
    bool fits = a.count == 0
                || (a.count - 1 <= (SIZE_MAX - elem) / stride && a.byteOffset <= bv->byteLength
                    && (a.count - 1) * stride + elem <= bv->byteLength - a.byteOffset);
    if (!fits) {
        *why =
            format("%s: accessor %d reads past the end of buffer view %d", c, index, a.bufferView);
        return false;
    }
    const unsigned char *base = model.buffers[(size_t)bv->buffer].data.data();
    const unsigned char *first = a.count ? base + bv->byteOffset + a.byteOffset : nullptr;
    *out = view{first, a.count, stride, a.componentType};
    return true;
}

static const char *
mode_name(int mode)
{
    static const char *const names[] = {
        "POINTS",
        "LINES",
        "LINE_LOOP",
        "LINE_STRIP",
        "TRIANGLES",
        "TRIANGLE_STRIP",
        "TRIANGLE_FAN",
    };
    return mode >= 0 && mode < 7 ? names[mode] : "unknown";
}

static bool
plan_attributes(
    const tinygltf::Model &model,
    const tinygltf::Primitive &p,
    const std::string &ctx,
    part *out,
    std::string *why)
{
    auto pos = p.attributes.find("POSITION");
    if (pos == p.attributes.end()) {
        *why = ctx + " has no POSITION attribute";
        return false;
    }
    if (!check_accessor(model, pos->second, ctx + " POSITION", false, &out->positions, why)) {
        return false;
    }
    auto nrm = p.attributes.find("NORMAL");
    out->has_normals = nrm != p.attributes.end();
    if (!out->has_normals) {
        return true;
    }
    if (!check_accessor(model, nrm->second, ctx + " NORMAL", false, &out->normals, why)) {
        return false;
    }
    if (out->normals.count != out->positions.count) {
        *why = format(
            "%s: NORMAL has %zu elements but POSITION has %zu",
            ctx.c_str(),
            out->normals.count,
            out->positions.count);
        return false;
    }
    return true;
}

static bool
plan_primitive(
    const tinygltf::Model &model,
    size_t job_index,
    int mesh,
    int prim,
    part *out,
    std::string *why)
{
    const tinygltf::Primitive &p = model.meshes[(size_t)mesh].primitives[(size_t)prim];
    std::string ctx = format("mesh %d primitive %d", mesh, prim);
    *out = part{};
    out->mesh = mesh;
    out->primitive = prim;
    out->material = p.material;
    if (p.material < -1 || p.material >= (int)model.materials.size()) {
        *why = format("%s: material %d does not exist", ctx.c_str(), p.material);
        return false;
    }
    out->job = job_index;
    if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != -1) {
        *why = format(
            "%s: mode %d (%s) is not supported: only triangles (mode 4) are",
            ctx.c_str(),
            p.mode,
            mode_name(p.mode));
        return false;
    }
    if (!plan_attributes(model, p, ctx, out, why)) {
        return false;
    }
    out->has_indices = p.indices != -1;
    if (out->has_indices
        && !check_accessor(model, p.indices, ctx + " indices", true, &out->indices, why)) {
        return false;
    }
    size_t corners = out->has_indices ? out->indices.count : out->positions.count;
    if (corners % 3 != 0) {
        const char *what = out->has_indices ? "indices" : "vertices without indices";
        *why = format("%s: %zu %s is not a multiple of 3", ctx.c_str(), corners, what);
        return false;
    }
    out->n_triangles = corners / 3;
    return true;
}

// Every primitive of every job, with totals checked against the limits.
bool
plan_parts(
    const tinygltf::Model &model,
    const std::vector<job> &jobs,
    std::vector<part> *parts,
    std::string *why)
{
    size_t n_vertices = 0;
    size_t n_triangles = 0;
    for (size_t j = 0; j < jobs.size(); j++) {
        const tinygltf::Mesh &mesh = model.meshes[(size_t)jobs[j].mesh];
        for (size_t k = 0; k < mesh.primitives.size(); k++) {
            part p;
            if (!plan_primitive(model, j, jobs[j].mesh, (int)k, &p, why)) {
                return false;
            }
            if (p.positions.count > GLTF_MAX_VERTICES - n_vertices
                || p.n_triangles > GLTF_MAX_TRIANGLES - n_triangles) {
                *why =
                    format("the scene has more than %zu vertices or triangles", GLTF_MAX_VERTICES);
                return false;
            }
            n_vertices += p.positions.count;
            n_triangles += p.n_triangles;
            parts->push_back(p);
        }
    }
    if (n_triangles == 0) {
        *why = "the scene has no triangles";
        return false;
    }
    return true;
}
