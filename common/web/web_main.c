/*
 * web_main.c - the browser build's entry points (make web, common/web/).
 *
 * The page runs a stage's own main() (callMain, with a command line as in a
 * terminal) in each of its Web Workers.  Workers share no memory, so each
 * renders a share of the tiles (render_share, driver.h) from the same
 * per-pixel random streams as the native build; the page adds their images
 * (the tiles of the others are 0 in each) into the whole image.  These
 * functions set that share before main() runs, hand each pass's image to
 * the page, and write the page's whole image as PNG or PFM with the
 * project's writers.  Nothing here renders: the stage and the driver do.
 */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "diag.h"
#include "driver.h"
#include "image.h"

/* The page's function (common/web/stage_lib.js): the mean of the first
 * `passes` passes of this worker's tiles, width x height x 3 floats. */
extern void web_post_pass(const float *rgb, int width, int height, int passes);

static struct render_share web_share;
static struct image web_rendered;

static void
post_pass(void *ctx, const struct image *mean, int passes_done)
{
    (void)ctx;
    web_post_pass(mean->rgb, mean->width, mean->height, passes_done);
}

/* Render the tiles t % parts == part in the runs that follow. */
void web_set_share(int part, int parts);

void
web_set_share(int part, int parts)
{
    image_free(&web_rendered);
    web_share = (struct render_share){.part = part, .parts = parts, .on_pass = post_pass};
    driver_set_share(&web_share);
}

/* The floats of a width x height image the page fills in; the runs that
 * follow take it as the job's image, rendered already (the pixel
 * inspector).  NULL when memory runs out or the size is out of range. */
float *web_use_rendered(int width, int height);

float *
web_use_rendered(int width, int height)
{
    struct diag err;
    image_free(&web_rendered);
    if (!image_alloc(&web_rendered, width, height, &err)) {
        return NULL;
    }
    web_share = (struct render_share){.part = 0, .parts = 1, .rendered = &web_rendered};
    driver_set_share(&web_share);
    return web_rendered.rgb;
}

/* Write width x height x 3 floats (rgb, the page's image) to path, in the
 * format its extension names, with the native build's writers: 0 on
 * success, else 1 (the message on stderr). */
int web_write_image(const float *rgb, int width, int height, const char *path);

int
web_write_image(const float *rgb, int width, int height, const char *path)
{
    struct image img = {width, height, (float *)rgb};
    struct diag err;
    if (!image_write(&img, path, &err)) {
        diag_print(stderr, &err, "error");
        return 1;
    }
    return 0;
}
