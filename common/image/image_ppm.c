/*
 * image_ppm.c - the binary PPM writer (P6, maxval 255): 8-bit sRGB, rows top
 * to bottom.
 */
#include "image.h"

#include "image_codec.h"

#include <errno.h>
#include <stdlib.h>

void
image_write_ppm(struct sink *s, const struct image *img)
{
    errno = 0;
    if (fprintf(s->f, "P6\n%d %d\n255\n", img->width, img->height) < 0) {
        s->error = errno ? errno : EIO;
    }
    size_t n = (size_t)img->width * 3;
    uint8_t *row = malloc(n);
    if (!row) {
        s->error = ENOMEM;
        return;
    }
    for (int y = 0; y < img->height; y++) {
        image_encode_row(img, y, row);
        image_sink_put(s, row, n);
    }
    free(row);
}
