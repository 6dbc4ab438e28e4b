/*
 * boxdown.c - box-filter downsampling (see boxdown.h).
 */
#include "boxdown.h"

bool
box_downsample(const struct image *in, int f, struct image *out, struct diag *err)
{
    *out = (struct image){0};
    if (f < 1 || in->width % f != 0 || in->height % f != 0) {
        diag_set(
            err,
            NULL,
            0,
            0,
            "factor %d does not divide the image size %dx%d",
            f,
            in->width,
            in->height);
        return false;
    }
    if (!image_alloc(out, in->width / f, in->height / f, err)) {
        return false;
    }
    double scale = 1.0 / ((double)f * (double)f);
    for (int y = 0; y < out->height; y++) {
        for (int x = 0; x < out->width; x++) {
            double sum[3] = {0, 0, 0};
            for (int j = 0; j < f; j++) {
                for (int i = 0; i < f; i++) {
                    const float *p = image_pixel(in, f * x + i, f * y + j);
                    sum[0] += p[0];
                    sum[1] += p[1];
                    sum[2] += p[2];
                }
            }
            float *q = image_pixel(out, x, y);
            for (int c = 0; c < 3; c++) {
                q[c] = (float)(sum[c] * scale);
            }
        }
    }
    return true;
}
