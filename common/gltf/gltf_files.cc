/*
 * gltf_files.cc - how the glTF loader reads files: the model file itself,
 * and tinygltf's filesystem callbacks, which confine external buffers to
 * relative URIs below the model's directory (no "..", no scheme, no
 * absolute path, no symbolic link leading out of it), within one byte
 * budget, and never decode images.
 */
#include "gltf_steps.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

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
bool
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

// Whether path, every symbolic link in it followed, is inside the directory
// prefix names (itself resolved the same way): a link in the model's
// directory may lead to another of its files, never out of it.
static bool
resolves_inside(const std::string &path, const std::string &prefix)
{
    char *file = realpath(path.c_str(), nullptr);
    char *dir = realpath(prefix.c_str(), nullptr);
    bool inside = false;
    if (file && dir) {
        size_t n = strlen(dir);
        bool root = n == 1 && dir[0] == '/';
        inside = strncmp(file, dir, n) == 0 && (root || file[n] == '/');
    }
    free(file);
    free(dir);
    return inside;
}

bool
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
    if (!resolves_inside(path, guard->prefix)) {
        refuse(guard, uri, "is refused: a symbolic link leads it outside the model's directory");
        return false;
    }
    return true;
}

// No ~ or $VAR expansion: a URI is data, not a shell word.
std::string
unexpanded_path(const std::string &path, void *)
{
    return path;
}

bool
guarded_read_file(
    std::vector<unsigned char> *out,
    std::string *err,
    const std::string &path,
    void *user)
{
    fs_guard *guard = static_cast<fs_guard *>(user);
    std::string uri;
    std::string why;
    if (!uri_of(guard, path, &uri) || !unsafe_uri_reason(uri).empty()
        || !resolves_inside(path, guard->prefix)) {
        uri = path;
        why = "it is outside the model's directory";
    } else if (read_file(path, guard->budget, out, &why)) {
        guard->budget -= out->size();
        guard->read.push_back(path);
        return true;
    }
    refuse(guard, uri, "cannot be read: " + why);
    *err += why;
    return false;
}

bool
refuse_write(std::string *err, const std::string &, const std::vector<unsigned char> &, void *)
{
    *err += "writing is not supported";
    return false;
}

