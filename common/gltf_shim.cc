/*
 * gltf_shim.cc - gltf.h implemented with tinygltf: the project's only C++.
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
 *   - images are never decoded (Duck.glb has a texture; we need none);
 *   - sizes and offsets are checked in size_t with overflow guards before
 *     anything is read, and totals before anything is allocated;
 *   - no exception leaves this file: gltf_load catches everything.
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
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include <fcntl.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include <tiny_gltf.h>

extern "C" {
#include "gltf.h"
}

// Most bytes read from the model file, and from all its external files
// together: far above any mesh this renderer can trace, small enough to
// refuse a hostile size before reading it.
#define GLTF_MAX_FILE_BYTES ((size_t)1 << 30)

// The scene indexes vertices and triangle corners with int.
#define GLTF_MAX_VERTICES ((size_t)INT_MAX / 3)
#define GLTF_MAX_TRIANGLES ((size_t)INT_MAX / 3)

// Deeper node trees are refused rather than risk the stack.
#define GLTF_MAX_NODE_DEPTH 256

// GLB layout (glTF 2.0 specification, "Binary glTF Layout").
#define GLB_HEADER_BYTES 12
#define GLB_CHUNK_HEADER_BYTES 8
#define GLB_VERSION 2
#define GLB_CHUNK_JSON 0x4E4F534Au
#define GLB_CHUNK_BIN 0x004E4942u

// JSON nested deeper is refused (see the top); glTF's own structure is less
// than 10 levels deep.
#define GLTF_MAX_JSON_DEPTH 128

// A node matrix's last row must be (0 0 0 1) to within this.
#define AFFINE_TOLERANCE 1e-6

// The model's directory as tinygltf joins it to a URI, the bytes external
// files may still take, and why the last one was refused (tinygltf only
// says "File not found").
struct fs_guard {
    std::string prefix;
    size_t budget;
    std::string refused_uri;
    std::string refusal;
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
};

// A node that draws a mesh, with its world transform.
struct job {
    int mesh;
    mat4 world;
};

static std::string format(const char *fmt, ...) DIAG_PRINTF(1, 2);

static std::string
format(const char *fmt, ...)
{
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    return buf;
}

/* --- reading files ------------------------------------------------------- */

static bool
read_open_file(int fd, size_t limit, std::vector<unsigned char> *out, std::string *why)
{
    struct stat st;
    if (fstat(fd, &st) != 0) {
        *why = format("cannot stat: %s", strerror(errno));
        return false;
    }
    if (!S_ISREG(st.st_mode)) {
        *why = "not a regular file";
        return false;
    }
    if ((uintmax_t)st.st_size > limit) {
        *why = format("%jd bytes is more than the %zu bytes allowed", (intmax_t)st.st_size, limit);
        return false;
    }
    size_t size = (size_t)st.st_size;
    out->resize(size);
    size_t done = 0;
    while (done < size) {
        ssize_t n = read(fd, out->data() + done, size - done);
        if (n < 0 && errno == EINTR) {
            continue;
        }
        if (n <= 0) {
            *why = n < 0 ? format("read error: %s", strerror(errno)) : "file shrank while read";
            return false;
        }
        done += (size_t)n;
    }
    return true;
}

// A whole regular file of at most limit bytes.
static bool
read_file(const std::string &path, size_t limit, std::vector<unsigned char> *out, std::string *why)
{
    // O_NONBLOCK: opening a FIFO must not wait for a writer.
    int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        *why = format("cannot open: %s", strerror(errno));
        return false;
    }
    bool ok = read_open_file(fd, limit, out, why);
    close(fd);
    return ok;
}

/* --- filesystem callbacks: external files stay below the model ---------- */

// Why uri may not be read, or empty when it may.
static std::string
unsafe_uri_reason(const std::string &uri)
{
    if (uri.empty()) {
        return "it is empty";
    }
    if (uri.find('\0') != std::string::npos) {
        return "it contains a NUL byte";
    }
    if (uri[0] == '/' || uri[0] == '\\') {
        return "absolute paths are not allowed";
    }
    if (uri.compare(0, 5, "data:") == 0) {
        return "only base64 data: URIs of binary data are supported";
    }
    if (uri.find(':') != std::string::npos) {
        return "no URI scheme other than data: is allowed";
    }
    if (uri.find('\\') != std::string::npos) {
        return "backslashes are not allowed";
    }
    size_t start = 0;
    while (start <= uri.size()) {
        size_t end = uri.find('/', start);
        if (end == std::string::npos) {
            end = uri.size();
        }
        if (uri.compare(start, end - start, "..") == 0) {
            return "'..' is not allowed: files must stay in the model's directory";
        }
        start = end + 1;
    }
    return "";
}

static void
refuse(fs_guard *guard, const std::string &uri, const std::string &reason)
{
    guard->refused_uri = uri;
    guard->refusal = format("external file '%.200s' %s", uri.c_str(), reason.c_str());
}

// The URI part of a path tinygltf built as prefix + uri; false for the other
// places tinygltf looks (the working directory), which are never allowed.
static bool
uri_of(const fs_guard *guard, const std::string &path, std::string *uri)
{
    if (path.compare(0, guard->prefix.size(), guard->prefix) != 0) {
        return false;
    }
    *uri = path.substr(guard->prefix.size());
    return true;
}

static bool
guarded_file_exists(const std::string &path, void *user)
{
    fs_guard *guard = static_cast<fs_guard *>(user);
    std::string uri;
    if (!uri_of(guard, path, &uri)) {
        return false;
    }
    std::string reason = unsafe_uri_reason(uri);
    if (!reason.empty()) {
        refuse(guard, uri, "is refused: " + reason);
        return false;
    }
    struct stat st;
    if (stat(path.c_str(), &st) != 0) {
        refuse(guard, uri, format("cannot be opened: %s", strerror(errno)));
        return false;
    }
    return true;
}

// No ~ or $VAR expansion: a URI is data, not a shell word.
static std::string
unexpanded_path(const std::string &path, void *)
{
    return path;
}

static bool
guarded_read_file(
    std::vector<unsigned char> *out,
    std::string *err,
    const std::string &path,
    void *user)
{
    fs_guard *guard = static_cast<fs_guard *>(user);
    std::string uri;
    std::string why;
    if (!uri_of(guard, path, &uri) || !unsafe_uri_reason(uri).empty()) {
        uri = path;
        why = "it is outside the model's directory";
    } else if (read_file(path, guard->budget, out, &why)) {
        guard->budget -= out->size();
        return true;
    }
    refuse(guard, uri, "cannot be read: " + why);
    *err += why;
    return false;
}

static bool
refuse_write(std::string *err, const std::string &, const std::vector<unsigned char> &, void *)
{
    *err += "writing is not supported";
    return false;
}

// Images are accepted unread: texture decoding is attack surface we need not.
static bool
skip_image(
    tinygltf::Image *,
    const int,
    std::string *,
    std::string *,
    int,
    int,
    const unsigned char *,
    int,
    void *)
{
    return true;
}

/* --- loading the model ---------------------------------------------------- */

static uint32_t
read_u32le(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

// The 12-byte header: magic, version, and a length equal to the file's.
static bool
check_glb_header(const std::vector<unsigned char> &bytes, std::string *why)
{
    size_t size = bytes.size();
    if (size < 4 || memcmp(bytes.data(), "glTF", 4) != 0) {
        *why = "not a binary glTF file: it does not start with 'glTF'";
        return false;
    }
    if (size < GLB_HEADER_BYTES + GLB_CHUNK_HEADER_BYTES) {
        *why = format("truncated: %zu bytes is too short for a GLB header", size);
        return false;
    }
    const unsigned char *b = bytes.data();
    if (read_u32le(b + 4) != GLB_VERSION) {
        *why = format("GLB version %u is not supported (only 2)", (unsigned)read_u32le(b + 4));
        return false;
    }
    if (read_u32le(b + 8) != size) {
        *why = format(
            "the GLB header gives a length of %u bytes but the file has %zu (truncated?)",
            (unsigned)read_u32le(b + 8),
            size);
        return false;
    }
    return true;
}

// The header, then a JSON chunk and an optional BIN chunk that fit the file.
static bool
check_glb_layout(const std::vector<unsigned char> &bytes, std::string *why)
{
    if (!check_glb_header(bytes, why)) {
        return false;
    }
    const unsigned char *b = bytes.data();
    size_t size = bytes.size();
    size_t json_len = read_u32le(b + GLB_HEADER_BYTES);
    size_t at = GLB_HEADER_BYTES + GLB_CHUNK_HEADER_BYTES;
    if (read_u32le(b + GLB_HEADER_BYTES + 4) != GLB_CHUNK_JSON) {
        *why = "the first GLB chunk is not JSON";
        return false;
    }
    if (json_len > size - at) {
        *why = format("the JSON chunk (%zu bytes) runs past the end of the file", json_len);
        return false;
    }
    at += json_len;
    if (at == size) {
        return true;
    }
    if (size - at < GLB_CHUNK_HEADER_BYTES) {
        *why = "truncated: the file ends inside a chunk header";
        return false;
    }
    size_t bin_len = read_u32le(b + at);
    if (read_u32le(b + at + 4) != GLB_CHUNK_BIN) {
        *why = "the second GLB chunk is not BIN";
        return false;
    }
    if (bin_len > size - at - GLB_CHUNK_HEADER_BYTES) {
        *why = format("the BIN chunk (%zu bytes) runs past the end of the file", bin_len);
        return false;
    }
    return true;
}

// The JSON pre-scan follows strings and brackets only (the parser judges
// the rest): how deep arrays and objects nest, and which members of the
// top-level "buffers" array have a "uri".
struct json_scan {
    const unsigned char *text;
    int depth;
    size_t last_start, last_len;  // the last string read, raw
    bool key_is_buffers;  // the root member being read is "buffers"
    bool in_buffers;  // inside that member's array
    bool has_uri;  // the buffer object being read has a "uri"
    size_t without_uri;  // buffer objects without one
};

static bool
last_string_is(const json_scan *s, const char *word)
{
    size_t n = strlen(word);
    return s->last_len == n && memcmp(s->text + s->last_start, word, n) == 0;
}

// A string followed by ':' names a member.
static void
scan_colon(json_scan *s)
{
    if (s->depth == 1) {
        // A name with escapes might spell "buffers": take it as if it did.
        bool escaped = memchr(s->text + s->last_start, '\\', s->last_len) != nullptr;
        s->key_is_buffers = escaped || last_string_is(s, "buffers");
    } else if (s->depth == 3 && s->in_buffers && last_string_is(s, "uri")) {
        s->has_uri = true;
    }
}

static void
scan_open(json_scan *s, unsigned char c)
{
    s->depth++;
    if (s->depth == 2) {
        s->in_buffers = c == '[' && s->key_is_buffers;
    } else if (s->depth == 3 && s->in_buffers) {
        s->has_uri = false;
    }
}

static void
scan_close(json_scan *s)
{
    if (s->depth == 3 && s->in_buffers) {
        s->without_uri += !s->has_uri;
    }
    s->depth--;
}

// Checks the nesting depth; counts the buffers without a uri.
static bool
scan_json(const unsigned char *text, size_t len, size_t *without_uri, std::string *why)
{
    json_scan s = {};
    s.text = text;
    for (size_t i = 0; i < len; i++) {
        unsigned char c = text[i];
        if (c == '"') {
            size_t end = i + 1;
            while (end < len && text[end] != '"') {
                end += text[end] == '\\' ? 2 : 1;  // an escaped '"' does not end it
            }
            s.last_start = i + 1;
            s.last_len = (end < len ? end : len) - s.last_start;
            i = end;
        } else if (c == ':') {
            scan_colon(&s);
        } else if (c == '[' || c == '{') {
            scan_open(&s, c);
        } else if (c == ']' || c == '}') {
            scan_close(&s);
        }
        if (s.depth > GLTF_MAX_JSON_DEPTH) {
            *why = format("the JSON nests deeper than %d levels", GLTF_MAX_JSON_DEPTH);
            return false;
        }
    }
    *without_uri = s.without_uri;
    return true;
}

static bool
looks_binary(const char *path, const std::vector<unsigned char> &bytes)
{
    if (bytes.size() >= 4 && memcmp(bytes.data(), "glTF", 4) == 0) {
        return true;
    }
    size_t len = strlen(path);
    return len >= 4 && strcasecmp(path + len - 4, ".glb") == 0;
}

// The directory tinygltf resolves URIs against; "." for a bare file name.
static std::string
model_directory(const char *path)
{
    std::string p(path);
    size_t slash = p.find_last_of('/');
    if (slash == std::string::npos) {
        return ".";
    }
    return slash == 0 ? "/" : p.substr(0, slash);
}

// The first line of a tinygltf message, in our style: lower case, no period.
static std::string
tidy_message(const std::string &text)
{
    size_t start = text.find_first_not_of(" \t\r\n");
    if (start == std::string::npos) {
        return "";
    }
    std::string line = text.substr(start, text.find_first_of("\r\n", start) - start);
    while (!line.empty() && (line.back() == '.' || line.back() == ' ')) {
        line.pop_back();
    }
    bool is_word = line.size() > 1 && islower((unsigned char)line[1]);
    if (is_word && isupper((unsigned char)line[0])) {
        line[0] = (char)tolower((unsigned char)line[0]);
    }
    return line;
}

// What tinygltf is not trusted with: a .glb's chunk layout, the JSON's
// nesting, and buffers that would each copy the BIN chunk.
static bool
check_before_parsing(const std::vector<unsigned char> &bytes, bool binary, std::string *why)
{
    if (binary && !check_glb_layout(bytes, why)) {
        return false;
    }
    const unsigned char *json =
        bytes.data() + (binary ? GLB_HEADER_BYTES + GLB_CHUNK_HEADER_BYTES : 0);
    size_t json_len = binary ? read_u32le(bytes.data() + GLB_HEADER_BYTES) : bytes.size();
    size_t without_uri = 0;
    if (!scan_json(json, json_len, &without_uri, why)) {
        return false;
    }
    // The specification lets only the first buffer use the BIN chunk.
    if (binary && without_uri > 1) {
        *why = format("%zu buffers have no uri: only the first may use the BIN chunk", without_uri);
        return false;
    }
    return true;
}

// tinygltf on the checked bytes, with our filesystem and image callbacks.
static bool
run_tinygltf(
    const std::vector<unsigned char> &bytes,
    bool binary,
    const std::string &dir,
    tinygltf::Model *model,
    fs_guard *guard,
    std::string *why)
{
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(skip_image, nullptr);
    tinygltf::FsCallbacks fs =
        {guarded_file_exists, unexpanded_path, guarded_read_file, refuse_write, guard};
    loader.SetFsCallbacks(fs);
    std::string err;
    std::string warn;
    unsigned size = (unsigned)bytes.size();
    const char *text = (const char *)bytes.data();
    bool ok = binary ? loader.LoadBinaryFromMemory(model, &err, &warn, bytes.data(), size, dir)
                     : loader.LoadASCIIFromString(model, &err, &warn, text, size, dir);
    if (!ok) {
        bool refused = !guard->refusal.empty() && err.find(guard->refused_uri) != err.npos;
        *why = refused ? guard->refusal : tidy_message(err);
        if (why->empty()) {
            *why = "tinygltf could not load the file";
        }
    }
    return ok;
}

static bool
parse_model(const char *path, tinygltf::Model *model, fs_guard *guard, std::string *why)
{
    std::vector<unsigned char> bytes;
    if (!read_file(path, GLTF_MAX_FILE_BYTES, &bytes, why)) {
        return false;
    }
    if (bytes.empty()) {
        *why = "the file is empty";
        return false;
    }
    bool binary = looks_binary(path, bytes);
    if (!check_before_parsing(bytes, binary, why)) {
        return false;
    }
    std::string dir = model_directory(path);
    guard->prefix = dir.back() == '/' ? dir : dir + "/";
    guard->budget = GLTF_MAX_FILE_BYTES;
    return run_tinygltf(bytes, binary, dir, model, guard, why);
}

// Extensions that only change appearance, which we ignore anyway.
static bool
check_required_extensions(const tinygltf::Model &model, std::string *why)
{
    for (const std::string &name : model.extensionsRequired) {
        if (name.compare(0, 14, "KHR_materials_") == 0
            || name.compare(0, 12, "KHR_texture_") == 0) {
            continue;
        }
        *why = format("the file requires extension '%.100s', which is not supported", name.c_str());
        return false;
    }
    return true;
}

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
};

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

static bool
collect_jobs(const tinygltf::Model &model, std::vector<job> *jobs, std::string *why)
{
    std::vector<int> roots;
    if (!root_nodes(model, &roots, why)) {
        return false;
    }
    walker w = {&model, std::vector<char>(model.nodes.size(), 0), {}};
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
    return true;
}

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
static bool
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

/* --- copying the triangles out -------------------------------------------- */

static double
read_f32(const unsigned char *p)
{
    uint32_t bits = read_u32le(p);
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

static size_t
read_index(const view &v, size_t i)
{
    const unsigned char *p = v.data + i * v.stride;
    switch (v.component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return (size_t)p[0] | (size_t)p[1] << 8;
    default:
        return read_u32le(p);
    }
}

// The transform of normals: the inverse transpose of the upper 3x3, as its
// cofactor matrix times the sign of the determinant (the length does not
// matter: normals are renormalised).  Returns the determinant.
static double
normal_matrix(const mat4 &world, double out[9])
{
    const double *m = world.m;
    // Column j of the upper 3x3 is (m[4j], m[4j+1], m[4j+2]); the cofactor
    // matrix's columns are cross products of the other two columns.
    const double *c0 = m;
    const double *c1 = m + 4;
    const double *c2 = m + 8;
    const double *cols[3][2] = {{c1, c2}, {c2, c0}, {c0, c1}};
    for (int j = 0; j < 3; j++) {
        const double *a = cols[j][0];
        const double *b = cols[j][1];
        out[j * 3 + 0] = a[1] * b[2] - a[2] * b[1];
        out[j * 3 + 1] = a[2] * b[0] - a[0] * b[2];
        out[j * 3 + 2] = a[0] * b[1] - a[1] * b[0];
    }
    double det = c0[0] * out[0] + c0[1] * out[1] + c0[2] * out[2];
    if (det < 0) {
        for (int i = 0; i < 9; i++) {
            out[i] = -out[i];
        }
    }
    return det;
}

static bool
copy_positions(const part &p, const mat4 &world, double *out, std::string *why)
{
    const double *m = world.m;
    for (size_t i = 0; i < p.positions.count; i++) {
        const unsigned char *src = p.positions.data + i * p.positions.stride;
        double x = read_f32(src);
        double y = read_f32(src + 4);
        double z = read_f32(src + 8);
        double *dst = out + 3 * i;
        for (int r = 0; r < 3; r++) {
            dst[r] = m[r] * x + m[4 + r] * y + m[8 + r] * z + m[12 + r];
        }
        if (!std::isfinite(dst[0]) || !std::isfinite(dst[1]) || !std::isfinite(dst[2])) {
            *why = format(
                "mesh %d primitive %d: vertex %zu has a non-finite position%s",
                p.mesh,
                p.primitive,
                i,
                std::isfinite(x + y + z) ? " after its node transform" : "");
            return false;
        }
    }
    return true;
}

static bool
copy_normals(const part &p, const double nm[9], double *out, std::string *why)
{
    for (size_t i = 0; i < p.normals.count; i++) {
        const unsigned char *src = p.normals.data + i * p.normals.stride;
        double n[3] = {read_f32(src), read_f32(src + 4), read_f32(src + 8)};
        if (!std::isfinite(n[0]) || !std::isfinite(n[1]) || !std::isfinite(n[2])) {
            *why = format(
                "mesh %d primitive %d: vertex %zu has a non-finite normal",
                p.mesh,
                p.primitive,
                i);
            return false;
        }
        double *dst = out + 3 * i;
        for (int r = 0; r < 3; r++) {
            dst[r] = nm[r] * n[0] + nm[3 + r] * n[1] + nm[6 + r] * n[2];
        }
        double len = std::sqrt(dst[0] * dst[0] + dst[1] * dst[1] + dst[2] * dst[2]);
        for (int r = 0; r < 3; r++) {
            dst[r] = len > 0 && std::isfinite(len) ? dst[r] / len : 0;
        }
    }
    return true;
}

// Indices offset by the part's first vertex; a mirroring transform swaps two
// corners so the winding still agrees with the normals.
static bool
copy_indices(const part &p, size_t first_vertex, bool mirrored, unsigned *out, std::string *why)
{
    for (size_t t = 0; t < p.n_triangles; t++) {
        size_t corner[3];
        for (size_t k = 0; k < 3; k++) {
            size_t at = 3 * t + k;
            corner[k] = p.has_indices ? read_index(p.indices, at) : at;
            if (corner[k] >= p.positions.count) {
                *why = format(
                    "mesh %d primitive %d: index %zu (number %zu) is out of range: "
                    "POSITION has %zu vertices",
                    p.mesh,
                    p.primitive,
                    corner[k],
                    at,
                    p.positions.count);
                return false;
            }
        }
        unsigned *dst = out + 3 * t;
        dst[0] = (unsigned)(first_vertex + corner[0]);
        dst[1] = (unsigned)(first_vertex + corner[mirrored ? 2 : 1]);
        dst[2] = (unsigned)(first_vertex + corner[mirrored ? 1 : 2]);
    }
    return true;
}

static bool
allocate_mesh(const std::vector<part> &parts, struct gltf_mesh *out, std::string *why)
{
    size_t n_vertices = 0;
    bool any_normals = false;
    for (const part &p : parts) {
        n_vertices += p.positions.count;
        out->n_triangles += p.n_triangles;
        any_normals = any_normals || p.has_normals;
    }
    // The limits keep these products far from overflow; +1 avoids malloc(0).
    out->positions = (double *)malloc((3 * n_vertices + 1) * sizeof(double));
    out->indices = (unsigned *)malloc((3 * out->n_triangles + 1) * sizeof(unsigned));
    if (any_normals) {
        out->normals = (double *)calloc(3 * n_vertices + 1, sizeof(double));
    }
    out->n_vertices = n_vertices;
    if (!out->positions || !out->indices || (any_normals && !out->normals)) {
        *why = format("out of memory for %zu vertices", n_vertices);
        return false;
    }
    return true;
}

static bool
copy_parts(
    const std::vector<job> &jobs,
    const std::vector<part> &parts,
    struct gltf_mesh *out,
    std::string *why)
{
    if (!allocate_mesh(parts, out, why)) {
        return false;
    }
    size_t first_vertex = 0;
    size_t first_triangle = 0;
    for (const part &p : parts) {
        const mat4 &world = jobs[p.job].world;
        double nm[9];
        double det = normal_matrix(world, nm);
        if (!copy_positions(p, world, out->positions + 3 * first_vertex, why)) {
            return false;
        }
        if (p.has_normals && !copy_normals(p, nm, out->normals + 3 * first_vertex, why)) {
            return false;
        }
        unsigned *dst = out->indices + 3 * first_triangle;
        if (!copy_indices(p, first_vertex, det < 0, dst, why)) {
            return false;
        }
        first_vertex += p.positions.count;
        first_triangle += p.n_triangles;
    }
    return true;
}

static bool
load(const char *path, struct gltf_mesh *out, std::string *why)
{
    tinygltf::Model model;
    fs_guard guard;
    std::vector<job> jobs;
    std::vector<part> parts;
    return parse_model(path, &model, &guard, why) && check_required_extensions(model, why)
           && collect_jobs(model, &jobs, why) && plan_parts(model, jobs, &parts, why)
           && copy_parts(jobs, parts, out, why);
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
    *out = gltf_mesh{};
    if (!path) {
        diag_set(err, NULL, 0, 0, "no glTF file named");
        return false;
    }
    try {
        std::string why;
        if (load(path, out, &why)) {
            return true;
        }
        diag_set(err, path, 0, 0, "%s", why.c_str());
    } catch (const std::bad_alloc &) {
        diag_set(err, path, 0, 0, "out of memory");
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

extern "C" void
gltf_free(struct gltf_mesh *mesh)
{
    free(mesh->positions);
    free(mesh->normals);
    free(mesh->indices);
    *mesh = gltf_mesh{};
}
