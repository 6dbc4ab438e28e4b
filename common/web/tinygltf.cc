// tinygltf.cc - tinygltf's implementation, for the browser build only
// (make web): natively the project links Debian's libtinygltf, which has no
// WebAssembly build.  Images are never decoded (gltf_parse.cc's loader skips
// them), so stb_image is left out (-DTINYGLTF_NO_STB_IMAGE in the Makefile,
// for every file that includes tiny_gltf.h).
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
