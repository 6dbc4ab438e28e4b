/*
 * image_exr.c - write OpenEXR files through OpenEXR's C API (OpenEXRCore,
 * OpenEXR >= 3.1).  Built only when the library is found; see image_exr.h.
 *
 * The image goes out as one scanline part holding 32-bit float channels R, G
 * and B (and the channels of its layers, "depth.Z"...) with lossless ZIP
 * compression: linear radiance, unclamped, as the
 * renderer computed it.  OpenEXR writes through our callback into the
 * temporary file image_write() opened, so the temporary-file-and-rename
 * scheme is the same for every format.
 */
#include "image_exr.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>

#include <openexr.h>

struct exr_sink {
    int fd;
    int error; /* errno of the first failed write, 0 while all is well */
};

/* OpenEXR's write callback, with pwrite()'s semantics (the library says
 * where each piece goes, and fills in the chunk offset table last). */
static int64_t
write_at(
    exr_const_context_t ctxt,
    void *userdata,
    const void *buffer,
    uint64_t size,
    uint64_t offset,
    exr_stream_error_func_ptr_t error_cb)
{
    (void)ctxt;
    (void)error_cb;
    struct exr_sink *sink = userdata;
    const uint8_t *bytes = buffer;
    uint64_t done = 0;
    while (done < size) {
        ssize_t n = pwrite(sink->fd, bytes + done, (size_t)(size - done), (off_t)(offset + done));
        if (n < 0 && errno == EINTR) {
            continue;
        }
        if (n <= 0) {
            if (!sink->error) {
                sink->error = n < 0 ? errno : EIO;
            }
            return -1;
        }
        done += (uint64_t)n;
    }
    return (int64_t)done;
}

/* Library code never prints, and OpenEXR's default handler prints to stderr;
 * failures are reported from the result codes instead. */
static void
ignore_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    (void)code;
    (void)msg;
}

/* Where each channel of the file comes from: an image and one of its
 * three interleaved channels.  R, G and B are the image's; a layer adds
 * "NAME.C" for each letter C of its channels. */
#define MAX_CHANNELS 32

struct channel_source {
    char name[64];
    const struct image *img;
    int offset;
};

struct channel_table {
    struct channel_source ch[MAX_CHANNELS];
    int n;
};

static bool
add_source(struct channel_table *t, const char *layer, char c, const struct image *img, int offset)
{
    if (t->n == MAX_CHANNELS) {
        return false;
    }
    struct channel_source *ch = &t->ch[t->n++];
    int n = layer ? snprintf(ch->name, sizeof ch->name, "%s.%c", layer, c)
                  : snprintf(ch->name, sizeof ch->name, "%c", c);
    ch->img = img;
    ch->offset = offset;
    return n > 0 && (size_t)n < sizeof ch->name;
}

static bool
build_table(
    const struct image *img,
    const struct image_layer *layers,
    int n_layers,
    struct channel_table *t)
{
    bool ok = add_source(t, NULL, 'R', img, 0) && add_source(t, NULL, 'G', img, 1)
              && add_source(t, NULL, 'B', img, 2);
    for (int i = 0; ok && i < n_layers; i++) {
        const struct image_layer *l = &layers[i];
        ok = l->img->width == img->width && l->img->height == img->height;
        for (int c = 0; ok && c < 3 && l->channels[c]; c++) {
            ok = add_source(t, l->name, l->channels[c], l->img, c);
        }
    }
    return ok;
}

static exr_result_t
define_part(exr_context_t ctxt, const struct image *img, const struct channel_table *t)
{
    int part = 0;
    exr_result_t rv = exr_add_part(ctxt, NULL, EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS) {
        rv = exr_initialize_required_attr_simple(
            ctxt,
            part,
            img->width,
            img->height,
            EXR_COMPRESSION_ZIP);
    }
    // The library keeps the channel list sorted by name, as the format wants.
    for (int c = 0; c < t->n && rv == EXR_ERR_SUCCESS; c++) {
        // Colour channels are "perceptually logarithmic" (pLinear 0).
        rv = exr_add_channel(
            ctxt,
            part,
            t->ch[c].name,
            EXR_PIXEL_FLOAT,
            EXR_PERCEPTUALLY_LOGARITHMIC,
            1,
            1);
    }
    return rv;
}

/* Point the encoder's channels at the chunk's rows of their images, each
 * channel by name (the library orders them by name). */
static void
point_channels(exr_encode_pipeline_t *enc, const struct channel_table *t, int y)
{
    for (int c = 0; c < enc->channel_count; c++) {
        exr_coding_channel_info_t *ch = &enc->channels[c];
        const struct channel_source *src = &t->ch[0];
        for (int i = 0; i < t->n; i++) {
            if (strcmp(t->ch[i].name, ch->channel_name) == 0) {
                src = &t->ch[i];
            }
        }
        ch->user_data_type = EXR_PIXEL_FLOAT;
        ch->user_bytes_per_element = sizeof(float);
        ch->user_pixel_stride = 3 * sizeof(float);
        ch->user_line_stride = src->img->width * 3 * (int32_t)sizeof(float);
        ch->encode_from_ptr = (const uint8_t *)(image_pixel(src->img, 0, y) + src->offset);
    }
}

static exr_result_t
write_chunks(exr_context_t ctxt, const struct image *img, const struct channel_table *t)
{
    int32_t lines = 0;
    exr_result_t rv = exr_get_scanlines_per_chunk(ctxt, 0, &lines);
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    bool started = false;
    for (int y = 0; y < img->height && rv == EXR_ERR_SUCCESS; y += lines) {
        exr_chunk_info_t chunk;
        rv = exr_write_scanline_chunk_info(ctxt, 0, y, &chunk);
        if (rv == EXR_ERR_SUCCESS) {
            rv = started ? exr_encoding_update(ctxt, 0, &chunk, &enc)
                         : exr_encoding_initialize(ctxt, 0, &chunk, &enc);
        }
        if (rv == EXR_ERR_SUCCESS) {
            point_channels(&enc, t, y);
            if (!started) {
                rv = exr_encoding_choose_default_routines(ctxt, 0, &enc);
            }
            started = true;
        }
        if (rv == EXR_ERR_SUCCESS) {
            rv = exr_encoding_run(ctxt, 0, &enc);
        }
    }
    if (started) {
        exr_encoding_destroy(ctxt, &enc);
    }
    return rv;
}

bool
image_exr_write(const struct image *img, int fd, const char *path, struct diag *err)
{
    return image_exr_write_layers(img, NULL, 0, fd, path, err);
}

bool
image_exr_write_layers(
    const struct image *img,
    const struct image_layer *layers,
    int n_layers,
    int fd,
    const char *path,
    struct diag *err)
{
    struct channel_table table = {.n = 0};
    if (!build_table(img, layers, n_layers, &table)) {
        diag_set(err, path, 0, 0, "cannot write OpenEXR: bad layers (too many, or another size)");
        return false;
    }
    struct exr_sink sink = {.fd = fd};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = ignore_error;
    init.user_data = &sink;
    init.write_fn = write_at;
    exr_context_t ctxt = NULL;
    // With our own write function the name is only for OpenEXR's messages.
    exr_result_t rv = exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS) {
        rv = define_part(ctxt, img, &table);
    }
    if (rv == EXR_ERR_SUCCESS) {
        rv = exr_write_header(ctxt);
    }
    if (rv == EXR_ERR_SUCCESS) {
        rv = write_chunks(ctxt, img, &table);
    }
    // exr_finish() writes the chunk offset table, so it can fail too.
    exr_result_t finished = exr_finish(&ctxt);
    if (rv == EXR_ERR_SUCCESS) {
        rv = finished;
    }
    if (sink.error) {
        diag_set(err, path, 0, 0, "cannot write: %s", strerror(sink.error));
        return false;
    }
    if (rv != EXR_ERR_SUCCESS) {
        diag_set(err, path, 0, 0, "cannot write OpenEXR: %s", exr_get_default_error_message(rv));
        return false;
    }
    return true;
}
