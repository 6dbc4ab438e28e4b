/*
 * image_srgb.c - linear radiance to sRGB (IEC 61966-2-1) and back, and the
 * 8-bit encoding of a row that the PNG and PPM writers share.
 */
#include "image.h"

#include "image_codec.h"

#include <math.h>

/* ---- sRGB (IEC 61966-2-1) ---------------------------------------------- */

float
image_srgb_from_linear(float linear)
{
    // The linear segment near black meets the power curve at 0.0031308.
    if (linear <= 0.0031308f) {
        return 12.92f * linear;
    }
    return (float)(1.055 * pow(linear, 1.0 / 2.4) - 0.055);
}

float
image_linear_from_srgb(float encoded)
{
    if (encoded <= 0.04045f) {
        return encoded / 12.92f;
    }
    return (float)pow((encoded + 0.055) / 1.055, 2.4);
}

uint8_t
image_srgb_encode8(float linear)
{
    // Written so that NaN takes the first branch: !(NaN > 0) is true.
    if (!(linear > 0.0f)) {
        return 0;
    }
    if (linear >= 1.0f) {
        return 255;
    }
    return (uint8_t)(image_srgb_from_linear(linear) * 255.0f + 0.5f);
}

void
image_encode_row(const struct image *img, int y, uint8_t *out)
{
    const float *p = image_pixel(img, 0, y);
    for (size_t i = 0; i < (size_t)img->width * 3; i++) {
        out[i] = image_srgb_encode8(p[i]);
    }
}
