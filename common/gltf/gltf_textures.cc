/*
 * gltf_textures.cc - a material's base colour and emissive textures, as the
 * stages use them: no stage maps a texture, so each stands as its image's
 * mean colour, times the material's factor (docs/scene-format.md,
 * "Textures").  An image is kept encoded while tinygltf parses the file
 * (keep_image) and decoded only when a base colour or emissive texture
 * names it, after its header's size is checked: a hostile file cannot make
 * the decoder allocate more than GLTF_TEXTURE_MAX_PIXELS texels.
 */
#include "gltf_steps.h"

#include <cmath>

extern "C" {
#include "image.h"  // image_linear_from_srgb: the sRGB transfer function the encoders use
}

// 8192 x 8192: the largest textures in common use; four bytes a texel at 8
// bits, 512 MiB at 16 bits, decoded one at a time.
#define GLTF_TEXTURE_MAX_PIXELS (8192L * 8192L)

// A texel glows when its brightest channel is over this sRGB value of 255:
// dark enough for any visible glow, bright enough to leave a black texel's
// compression noise (a JPEG's +-2) out.
#define GLOW_SRGB8 8

bool
keep_image(
    tinygltf::Image *image,
    const int,
    std::string *,
    std::string *,
    int,
    int,
    const unsigned char *bytes,
    int size,
    void *)
{
    // Encoded, as read: decoded later, only if a material's colour needs it.
    image->image.assign(bytes, bytes + (size > 0 ? size : 0));
    image->width = image->height = -1;
    return true;
}

static uint32_t
read_u32be(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | (uint32_t)p[3];
}

// The width and height a PNG or JPEG header states, without decoding; false
// for another format or a header cut short.
static bool
image_size(const std::vector<unsigned char> &b, long *w, long *h)
{
    static const unsigned char png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    size_t n = b.size();
    if (n >= 24 && std::equal(png, png + 8, b.begin())
        && std::equal(b.begin() + 12, b.begin() + 16, "IHDR")) {
        *w = (long)read_u32be(&b[16]);
        *h = (long)read_u32be(&b[20]);
        return true;
    }
    if (n < 4 || b[0] != 0xff || b[1] != 0xd8) {
        return false;
    }
    // JPEG: segments after the start marker, to the frame header (SOFn).
    size_t i = 2;
    while (i + 4 <= n) {
        if (b[i] != 0xff) {
            return false;
        }
        unsigned marker = b[i + 1];
        if (marker == 0xff) {
            i++;  // fill byte
            continue;
        }
        if (marker == 0x01 || (marker >= 0xd0 && marker <= 0xd8)) {
            i += 2;  // no length
            continue;
        }
        size_t length = (size_t)b[i + 2] << 8 | b[i + 3];
        bool frame =
            marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc;
        if (frame) {
            if (i + 9 > n) {
                return false;
            }
            *h = (long)b[i + 5] << 8 | b[i + 6];
            *w = (long)b[i + 7] << 8 | b[i + 8];
            return true;
        }
        if (length < 2) {
            return false;
        }
        i += 2 + length;
    }
    return false;
}

#ifndef TINYGLTF_NO_STB_IMAGE
// The mean linear colour of a decoded RGBA image of `bits` 8 or 16, and the
// share of its texels that glow.
static void
mean_colour(const tinygltf::Image &img, double mean[3], double *glow)
{
    size_t texels = (size_t)img.width * (size_t)img.height;
    bool wide = img.bits == 16;
    double top = wide ? 65535 : 255;
    std::vector<double> linear(wide ? 0 : 256);
    for (size_t v = 0; v < linear.size(); v++) {
        linear[v] = image_linear_from_srgb((float)v / 255.0f);
    }
    double sum[3] = {0, 0, 0};
    size_t glowing = 0;
    const unsigned char *p = img.image.data();
    for (size_t t = 0; t < texels; t++) {
        unsigned brightest = 0;
        for (int c = 0; c < 3; c++) {
            size_t at = 4 * t + (size_t)c;
            unsigned v = wide ? (unsigned)p[2 * at] | (unsigned)p[2 * at + 1] << 8 : p[at];
            sum[c] += wide ? image_linear_from_srgb((float)(v / top)) : linear[v];
            brightest = v > brightest ? v : brightest;
        }
        glowing += brightest * 255 > GLOW_SRGB8 * (unsigned)top;
    }
    for (int c = 0; c < 3; c++) {
        mean[c] = sum[c] / (double)texels;
    }
    *glow = (double)glowing / (double)texels;
}

#endif

// The mean colour of texture `index`'s image into mean and *glow; false
// with *why (a clause: "its image ...") when it cannot be had.
static bool
texture_mean(
    const tinygltf::Model &model,
    int index,
    double mean[3],
    double *glow,
    std::string *why)
{
    if (index < 0 || (size_t)index >= model.textures.size()) {
        *why = format("texture %d does not exist", index);
        return false;
    }
    int source = model.textures[(size_t)index].source;
    if (source < 0 || (size_t)source >= model.images.size()) {
        *why = "its image is in an extension's format";
        return false;
    }
    const tinygltf::Image &image = model.images[(size_t)source];
    long w = 0;
    long h = 0;
    if (image.image.empty()) {
        *why = format("image %d could not be read", source);
        return false;
    }
    if (!image_size(image.image, &w, &h)) {
        *why = format("image %d is neither PNG nor JPEG", source);
        return false;
    }
    if (w < 1 || h < 1 || w > GLTF_TEXTURE_MAX_PIXELS / h) {
        *why = format(
            "image %d is %ld x %ld, over the %ld texels averaged",
            source,
            w,
            h,
            GLTF_TEXTURE_MAX_PIXELS);
        return false;
    }
#ifdef TINYGLTF_NO_STB_IMAGE
    (void)mean;
    (void)glow;
    *why = "this build decodes no image";
    return false;
#else
    tinygltf::Image img;
    std::string err;
    std::string warn;
    const std::vector<unsigned char> &b = image.image;
    bool ok = tinygltf::LoadImageData(
        &img,
        source,
        &err,
        &warn,
        (int)w,
        (int)h,
        b.data(),
        (int)b.size(),
        nullptr);
    size_t want = (size_t)w * (size_t)h * 4 * (img.bits == 16 ? 2 : 1);
    if (!ok || img.component != 4 || (img.bits != 8 && img.bits != 16)
        || img.image.size() != want) {
        *why = format("image %d could not be decoded", source);
        return false;
    }
    mean_colour(img, mean, glow);
    return true;
#endif
}

// Texture `index`'s mean through the cache of images already averaged (a
// texture is often shared by many materials): true with mean and *glow, or
// false with *why.
static bool
cached_mean(
    const tinygltf::Model &model,
    int index,
    texture_means *cache,
    double mean[3],
    double *glow,
    std::string *why)
{
    auto hit = cache->find(index);
    if (hit == cache->end()) {
        texture_mean_entry e{};
        e.ok = texture_mean(model, index, e.mean, &e.glow, &e.why);
        hit = cache->emplace(index, e).first;
    }
    const texture_mean_entry &e = hit->second;
    std::copy(e.mean, e.mean + 3, mean);
    *glow = e.glow;
    *why = e.why;
    return e.ok;
}

void
average_textures(
    const tinygltf::Model &model,
    const tinygltf::Material &m,
    texture_means *cache,
    gltf_material *out)
{
    std::string why;
    double glow = 0;
    int base = m.pbrMetallicRoughness.baseColorTexture.index;
    if (base >= 0) {
        if (cached_mean(model, base, cache, out->base_color_mean, &glow, &why)) {
            out->averaged |= GLTF_TEX_BASE_COLOR;
        } else {
            snprintf(out->base_color_why, sizeof out->base_color_why, "%s", why.c_str());
        }
    }
    int emissive = m.emissiveTexture.index;
    if (emissive >= 0) {
        if (cached_mean(model, emissive, cache, out->emissive_mean, &out->emissive_glow, &why)) {
            out->averaged |= GLTF_TEX_EMISSIVE;
        } else {
            snprintf(out->emissive_why, sizeof out->emissive_why, "%s", why.c_str());
        }
    }
}
