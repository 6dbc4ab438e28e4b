/*
 * tinygltf_impl.cc - tinygltf's implementation, compiled into the fuzz build
 * only.  Debian's libtinygltf is built without instrumentation: linked as
 * is, the fuzzer would see none of tinygltf's branches and AddressSanitizer
 * none of its memory accesses.  Compiled here from the same header (and
 * nlohmann-json's, nlohmann-json3-dev), the glTF harnesses fuzz the JSON
 * parser and tinygltf's own checks too.  Images are never decoded (the loader
 * skips them), so stb_image is left out.
 */
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

namespace tinygltf
{
// The shim's translation units see the header without TINYGLTF_NO_STB_IMAGE,
// so their TinyGLTF objects start out pointing at these two; the loader sets
// its own image loader (which skips images) and never writes.
bool
LoadImageData(
    Image *,
    const int,
    std::string *err,
    std::string *,
    int,
    int,
    const unsigned char *,
    int,
    void *)
{
    if (err) {
        *err += "images are not decoded";
    }
    return false;
}

bool
WriteImageData(const std::string *, const std::string *, const Image *, bool, std::string *, void *)
{
    return false;
}
}  // namespace tinygltf
