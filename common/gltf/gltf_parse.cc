/*
 * gltf_parse.cc - from the model file's bytes to a tinygltf::Model: a .glb's
 * container (header and chunk layout) and the JSON text are checked before
 * tinygltf parses them, tinygltf runs with our filesystem callbacks, and
 * extensions the file requires but the loader lacks refuse it.
 */
#include "gltf_steps.h"

#include <cctype>
#include <cstring>

#include <strings.h>

// Most bytes read from the model file, and from all its external files
// together: far above any mesh this renderer can trace, small enough to
// refuse a hostile size before reading it.
#define GLTF_MAX_FILE_BYTES ((size_t)1 << 30)

// GLB layout (glTF 2.0 specification, "Binary glTF Layout").
#define GLB_HEADER_BYTES 12
#define GLB_CHUNK_HEADER_BYTES 8
#define GLB_VERSION 2
#define GLB_CHUNK_JSON 0x4E4F534Au
#define GLB_CHUNK_BIN 0x004E4942u

// JSON nested deeper is refused (see gltf_load.cc); glTF's own structure is
// less than 10 levels deep.
#define GLTF_MAX_JSON_DEPTH 128

// What the JSON text becomes in memory once parsed, counted against the
// memory limit before tinygltf sees it: nlohmann-json's document and
// tinygltf's model (its "extras" copied into tinygltf::Value) are held at
// once.  Peak RSS of a render loading 40 MB of one kind of value, over the
// values counted (docs/robustness.md, "Bounded resources"): 200 bytes per
// value for numbers, 242 for empty strings, 197 for objects of one member
// (the member's ':' counted), 37 for empty arrays; and 3.4 bytes per byte
// of text for a model whose buffer is a data: URI (the string, its copy,
// the decoded buffer).  A value is counted at each ',', ':', '[' and '{'
// outside strings.
#define GLTF_JSON_BYTES_PER_VALUE 256
#define GLTF_JSON_BYTES_PER_TEXT_BYTE 4

/* --- loading the model ---------------------------------------------------- */

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
    uint64_t values;  // ',', ':', '[' and '{' outside strings: the values, about
    bool key_is_required;  // the root member being read is "extensionsRequired"
    bool in_required;  // inside that member's array
    size_t unsupported_start, unsupported_len;  // its first name no stage reads; len 0: none
};

static bool extension_supported(const char *name, size_t len);

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
        s->key_is_required = last_string_is(s, "extensionsRequired");
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
        s->in_required = c == '[' && s->key_is_required;
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

// Checks the nesting depth; counts the buffers without a uri and the values.
static bool
scan_json(const unsigned char *text, size_t len, json_scan *out, std::string *why)
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
            // An element of extensionsRequired (an array holds no names).
            if (s.in_required && s.depth == 2 && s.unsupported_len == 0
                && !extension_supported((const char *)text + s.last_start, s.last_len)) {
                s.unsupported_start = s.last_start;
                s.unsupported_len = s.last_len;
            }
        } else if (c == ':') {
            s.values++;
            scan_colon(&s);
        } else if (c == ',') {
            s.values++;
        } else if (c == '[' || c == '{') {
            s.values++;
            scan_open(&s, c);
        } else if (c == ']' || c == '}') {
            scan_close(&s);
        }
        if (s.depth > GLTF_MAX_JSON_DEPTH) {
            *why = format("the JSON nests deeper than %d levels", GLTF_MAX_JSON_DEPTH);
            return false;
        }
    }
    *out = s;
    return true;
}

// Refuse JSON whose parsed form would pass the memory limit (max_bytes: what
// the scene has left), before it is parsed.
static bool
check_json_memory(const json_scan &s, size_t len, uint64_t max_bytes, std::string *why)
{
    uint64_t bytes =
        s.values * GLTF_JSON_BYTES_PER_VALUE + (uint64_t)len * GLTF_JSON_BYTES_PER_TEXT_BYTE;
    if (bytes <= max_bytes) {
        return true;
    }
    *why = format(
        "the JSON text (%zu bytes, about %llu values) would take about %llu MiB once parsed, "
        "more than the memory limit of %llu MiB left for it; raise it with --max-memory",
        len,
        (unsigned long long)s.values,
        (unsigned long long)((bytes + (1 << 20) - 1) >> 20),
        (unsigned long long)(max_bytes >> 20));
    return false;
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
// nesting and size once parsed, and buffers that would each copy the BIN
// chunk.
static bool
check_before_parsing(
    const std::vector<unsigned char> &bytes,
    bool binary,
    uint64_t max_bytes,
    std::string *why)
{
    if (binary && !check_glb_layout(bytes, why)) {
        return false;
    }
    const unsigned char *json =
        bytes.data() + (binary ? GLB_HEADER_BYTES + GLB_CHUNK_HEADER_BYTES : 0);
    size_t json_len = binary ? read_u32le(bytes.data() + GLB_HEADER_BYTES) : bytes.size();
    json_scan scan;
    if (!scan_json(json, json_len, &scan, why)
        || !check_json_memory(scan, json_len, max_bytes, why)) {
        return false;
    }
    // Before tinygltf, whose errors for a compressed or quantized file
    // speak of accessors (a Draco mesh: "accessor[0] invalid bufferView").
    if (scan.unsupported_len > 0) {
        *why = format(
            "the file requires extension '%.*s', which is not supported",
            (int)(scan.unsupported_len < 100 ? scan.unsupported_len : 100),
            (const char *)json + scan.unsupported_start);
        return false;
    }
    // The specification lets only the first buffer use the BIN chunk.
    if (binary && scan.without_uri > 1) {
        *why = format(
            "%zu buffers have no uri: only the first may use the BIN chunk",
            scan.without_uri);
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
    loader.SetImageLoader(keep_image, nullptr);
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

bool
parse_model(
    const char *path,
    uint64_t max_bytes,
    tinygltf::Model *model,
    fs_guard *guard,
    std::string *why)
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
    if (!check_before_parsing(bytes, binary, max_bytes, why)) {
        return false;
    }
    std::string dir = model_directory(path);
    guard->prefix = dir.back() == '/' ? dir : dir + "/";
    guard->budget = GLTF_MAX_FILE_BYTES;
    return run_tinygltf(bytes, binary, dir, model, guard, why);
}

// Extensions the renderer reads or can do without: materials and textures
// (mapped or noted by the scene loader) and punctual lights.  The name is
// len bytes, raw (an escaped name is never one of these).
static bool
extension_supported(const char *name, size_t len)
{
    std::string n(name, len);
    return n.compare(0, 14, "KHR_materials_") == 0 || n.compare(0, 12, "KHR_texture_") == 0
           || n == "KHR_lights_punctual";
}

bool
check_required_extensions(const tinygltf::Model &model, std::string *why)
{
    for (const std::string &name : model.extensionsRequired) {
        if (extension_supported(name.data(), name.size())) {
            continue;
        }
        *why = format("the file requires extension '%.100s', which is not supported", name.c_str());
        return false;
    }
    return true;
}
