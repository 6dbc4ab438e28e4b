/*
 * fuzz_pfm.c - the PFM reader (image_read_pfm), colour and greyscale, either
 * byte order.  A success must give a size in range and pixels that can all
 * be read; a failure must say why and leave the image empty.
 */
#include "fuzz.h"
#include "image.h"

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct image img = {0};
    struct diag err = {0};
    if (image_read_pfm(fuzz_write("image.pfm", data, size), &img, &err)) {
        if (img.width < 1 || img.width > IMAGE_MAX_DIM || img.height < 1
            || img.height > IMAGE_MAX_DIM || !img.rgb) {
            fuzz_fail("image %dx%d (pixels %p)", img.width, img.height, (void *)img.rgb);
        }
        volatile float sum = 0;
        for (size_t i = 0; i < (size_t)img.width * (size_t)img.height * 3; i++) {
            sum += img.rgb[i];
        }
        (void)sum;
    } else {
        fuzz_require_message(&err, "image_read_pfm");
        if (img.rgb) {
            fuzz_fail("a failed read left pixels");
        }
    }
    image_free(&img);
    return 0;
}
