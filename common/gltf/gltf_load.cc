/*
 * gltf_load.cc - gltf.h implemented with tinygltf (the project's only C++).
 * This file holds the C API (gltf_free, the same without tinygltf, is in
 * gltf_mesh.c); the loader's steps are in gltf_files.cc (reading
 * files, confined), gltf_parse.cc (GLB and JSON checks, tinygltf),
 * gltf_nodes.cc (transforms), gltf_accessors.cc (checks), gltf_copy.cc,
 * gltf_extras.cc (materials, cameras, lights), gltf_textures.cc (a
 * texture's mean colour) and gltf_dropped.cc (what no stage models), which
 * share gltf_steps.h.
 *
 * tinygltf parses the JSON and gathers the buffers; everything after that is
 * ours: choosing the nodes, checking every accessor against the bytes that
 * were actually loaded, and copying the triangles out in world space.
 *
 * The file is untrusted:
 *   - the model is read here, at most GLTF_MAX_FILE_BYTES, and a .glb's
 *     chunk layout is checked before tinygltf sees it (tinygltf 2.7.0 lets
 *     a BIN chunk run 8 bytes past the end of the file);
 *   - a scan of the JSON text refuses nesting deeper than
 *     GLTF_MAX_JSON_DEPTH (tinygltf copies "extras" recursively and a few
 *     megabytes of '[' overflow the stack) and, in a .glb, more than one
 *     buffer without a uri (tinygltf copies the BIN chunk for each);
 *   - every external file goes through our filesystem callbacks, which
 *     accept only relative paths below the model's directory, without a
 *     ".." component or a URI scheme (data: URIs never reach them: tinygltf
 *     decodes those itself), and read at most GLTF_MAX_FILE_BYTES in all;
 *   - an image is decoded only when a material's base colour or emissive
 *     texture names it, after its header's size is checked
 *     (gltf_textures.cc: a texture stands as its mean colour);
 *   - sizes and offsets are checked in size_t with overflow guards before
 *     anything is read, and totals before anything is allocated;
 *   - no exception leaves this file: gltf_load catches everything, and an
 *     allocation the system refuses (std::bad_alloc, out_of_memory) is
 *     reported as such (DIAG_NO_MEMORY), not as an invalid file.
 * Symbolic links inside the model's directory are followed: the threat is a
 * hostile model file, not a hostile directory.
 *
 * Decisions:
 *   - the default scene, else scene 0; a file without scenes contributes
 *     every root node (a node that is nobody's child);
 *   - only TRIANGLES primitives; any other mode refuses the file (silently
 *     dropping lines or points would be a surprise);
 *   - sparse accessors, morph-target deformation and skinning are not
 *     applied: sparse accessors refuse the file, targets and skins are
 *     ignored (the mesh is taken in its rest pose);
 *   - a scene that yields no triangle is an error.
 */
#include "gltf_steps.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <new>

// The files the load read, each once, into out->files (malloc'd: the C
// side frees them).
static void
copy_file_names(const std::vector<std::string> &read, struct gltf_mesh *out)
{
    std::vector<std::string> names;
    for (const std::string &name : read) {
        if (std::find(names.begin(), names.end(), name) == names.end()) {
            names.push_back(name);
        }
    }
    if (names.empty()) {
        return;
    }
    out->files = static_cast<char **>(calloc(names.size(), sizeof *out->files));
    if (!out->files) {
        throw out_of_memory{format("out of memory for the names of %zu files", names.size())};
    }
    for (const std::string &name : names) {
        char *copy = static_cast<char *>(malloc(name.size() + 1));
        if (!copy) {
            throw out_of_memory{format("out of memory for the names of %zu files", names.size())};
        }
        memcpy(copy, name.c_str(), name.size() + 1);
        out->files[out->n_files++] = copy;
    }
}

static bool
load(const char *path, uint64_t max_bytes, struct gltf_mesh *out, std::string *why)
{
    tinygltf::Model model;
    fs_guard guard;
    std::vector<job> jobs;
    std::vector<placed> cameras_and_lights;
    std::vector<part> parts;
    bool ok =
        parse_model(path, max_bytes, &model, &guard, why) && check_required_extensions(model, why)
        && collect_jobs(model, &jobs, &cameras_and_lights, why)
        && plan_parts(model, jobs, &parts, why) && copy_parts(jobs, parts, max_bytes, out, why)
        && copy_materials(model, out, why) && copy_placed(model, cameras_and_lights, out, why);
    if (ok) {
        copy_file_names(guard.read, out);
        copy_dropped(model, out);
    }
    return ok;
}

// Messages may quote the file's own strings: keep control bytes out of them.
static void
sanitise(char *msg)
{
    for (char *c = msg; *c; c++) {
        if ((unsigned char)*c < ' ' || *c == 0x7f) {
            *c = '?';
        }
    }
}

/* --- the C API ------------------------------------------------------------ */

extern "C" bool
gltf_available(void)
{
    return true;
}

extern "C" bool
gltf_load(const char *path, struct gltf_mesh *out, struct diag *err)
{
    return gltf_load_limited(path, GLTF_DEFAULT_MAX_BYTES, out, err);
}

extern "C" bool
gltf_load_limited(const char *path, uint64_t max_bytes, struct gltf_mesh *out, struct diag *err)
{
    *out = gltf_mesh{};
    if (!path) {
        diag_set(err, NULL, 0, 0, "no glTF file named");
        return false;
    }
    try {
        std::string why;
        if (load(path, max_bytes, out, &why)) {
            return true;
        }
        diag_set(err, path, 0, 0, "%s", why.c_str());
    } catch (const out_of_memory &e) {
        diag_set(err, path, 0, 0, "%s", e.why.c_str());
        diag_mark_no_memory(err);
    } catch (const std::bad_alloc &) {
        diag_set(err, path, 0, 0, "out of memory: the system refused memory to the glTF parser");
        diag_mark_no_memory(err);
    } catch (const std::exception &e) {
        diag_set(err, path, 0, 0, "unexpected error in the glTF loader: %s", e.what());
    } catch (...) {
        diag_set(err, path, 0, 0, "unexpected error in the glTF loader");
    }
    if (err) {
        sanitise(err->msg);
    }
    gltf_free(out);
    return false;
}
