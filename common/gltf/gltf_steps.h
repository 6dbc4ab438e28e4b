/*
 * gltf_steps.h - what the glTF loader's C++ files share (gltf_load.cc lists
 * them); internal to common/, whose API for meshes is gltf.h.
 *
 * A load goes parse_model -> check_required_extensions -> collect_jobs ->
 * plan_parts -> copy_parts -> copy_materials -> copy_placed; each returns
 * false with *why set on failure, or throws out_of_memory (below) when the
 * system refuses an allocation.
 */
#ifndef GLTF_STEPS_H
#define GLTF_STEPS_H

#include <cstdarg>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <tiny_gltf.h>

extern "C" {
#include "gltf.h"
}

// The model's directory as tinygltf joins it to a URI, the bytes external
// files may still take, why the last one was refused (tinygltf only says
// "File not found"), and the files read.
struct fs_guard {
    std::string prefix;
    size_t budget;
    std::string refused_uri;
    std::string refusal;
    std::vector<std::string> read;  // every file read through the callbacks
};

// A 4x4 matrix, column-major as glTF stores it: m[column * 4 + row].
struct mat4 {
    double m[16];
};

// An accessor whose bytes have been checked: count elements, stride apart.
struct view {
    const unsigned char *data;
    size_t count;
    size_t stride;
    int component_type;
};

// One primitive of one node, checked and ready to copy.
struct part {
    int mesh, primitive;
    size_t job;
    view positions, normals, indices;
    bool has_normals, has_indices;
    size_t n_triangles;
    int material; /* the primitive's material, or -1 */
};

// A node that draws a mesh, with its world transform.
struct job {
    int mesh;
    mat4 world;
};

// A node that holds a camera or a KHR_lights_punctual light (-1: not).
struct placed {
    int node, camera, light;
    mat4 world;
};

// printf into a std::string (messages are short: cut at 511 bytes).  Inline:
// every step uses it, and a helper in gltf_load.cc, which calls the steps,
// would make the files call each other in a circle.
inline std::string format(const char *fmt, ...) DIAG_PRINTF(1, 2);

inline std::string
format(const char *fmt, ...)
{
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    return buf;
}

// An allocation of ours the system refused (tinygltf's and the containers'
// throw std::bad_alloc): gltf_load_limited catches both and marks the
// diagnostic DIAG_NO_MEMORY, so that main() exits 4, not 1.
struct out_of_memory {
    std::string why;
};

static inline uint32_t
read_u32le(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* --- gltf_files.cc: reading files, and tinygltf's filesystem callbacks ---- */

// At most limit bytes of path into *out.
bool
read_file(const std::string &path, size_t limit, std::vector<unsigned char> *out, std::string *why);
// tinygltf::FsCallbacks; user is the fs_guard.
bool guarded_file_exists(const std::string &path, void *user);
std::string unexpanded_path(const std::string &path, void *);
bool guarded_read_file(
    std::vector<unsigned char> *out,
    std::string *err,
    const std::string &path,
    void *user);
bool
refuse_write(std::string *err, const std::string &, const std::vector<unsigned char> &, void *);
/* --- gltf_textures.cc: a texture as its image's mean colour -------------- */

// tinygltf's image loader: an image is kept encoded (decoded only when a
// material's colour needs its mean).
bool keep_image(
    tinygltf::Image *image,
    const int,
    std::string *,
    std::string *,
    int,
    int,
    const unsigned char *bytes,
    int size,
    void *);

// A texture's mean, once taken: the mean linear colour, the share of texels
// that glow, or why it could not be had.
struct texture_mean_entry {
    bool ok;
    double mean[3];
    double glow;
    std::string why;
};

typedef std::map<int, texture_mean_entry> texture_means;  // by texture index
// The means of m's base colour and emissive textures into out (averaged,
// *_mean, emissive_glow, *_why).
void average_textures(
    const tinygltf::Model &model,
    const tinygltf::Material &m,
    texture_means *cache,
    gltf_material *out);

/* --- the steps of a load -------------------------------------------------- */

// gltf_parse.cc
bool parse_model(
    const char *path,
    uint64_t max_bytes,
    tinygltf::Model *model,
    fs_guard *guard,
    std::string *why);
bool check_required_extensions(const tinygltf::Model &model, std::string *why);
// gltf_nodes.cc: the mesh nodes, and the camera and light nodes
bool collect_jobs(
    const tinygltf::Model &model,
    std::vector<job> *jobs,
    std::vector<placed> *cameras_and_lights,
    std::string *why);
// gltf_accessors.cc
bool plan_parts(
    const tinygltf::Model &model,
    const std::vector<job> &jobs,
    std::vector<part> *parts,
    std::string *why);
// gltf_copy.cc
// Refuses, before allocating, arrays that would pass max_bytes.
bool copy_parts(
    const std::vector<job> &jobs,
    const std::vector<part> &parts,
    uint64_t max_bytes,
    struct gltf_mesh *out,
    std::string *why);
// gltf_extras.cc
bool copy_materials(const tinygltf::Model &model, struct gltf_mesh *out, std::string *why);
bool copy_placed(
    const tinygltf::Model &model,
    const std::vector<placed> &cameras_and_lights,
    struct gltf_mesh *out,
    std::string *why);

// gltf_dropped.cc
void copy_dropped(const tinygltf::Model &model, struct gltf_mesh *out);

#endif /* GLTF_STEPS_H */
