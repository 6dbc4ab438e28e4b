/*
 * imgread_exr.c - read OpenEXR files through OpenEXR's C API (OpenEXRCore,
 * OpenEXR >= 3.1), for imgread.c.  Built only with OpenEXR (HAVE_OPENEXR).
 *
 * Reads the first part of a scanline file: channels R, G and B (or Y alone,
 * copied to all three), or those of one layer ("normal.X", "normal.Y",
 * "normal.Z"; one channel alone, "depth.Z", copied to all three), any pixel
 * type, converted to float by the library.
 * The image is the data window; tiled, deep and subsampled files are
 * refused with a message rather than guessed at.
 */
#include <stdbool.h>
#include <string.h>

#include <openexr.h>

#include "diag.h"
#include "image.h"

bool imgread_exr_layer(const char *path, const char *layer, struct image *out, struct diag *err);

/* Library code never prints; errors are reported from the result codes. */
static void
quiet(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    (void)code;
    (void)msg;
}

/* Which of our channels (0 R, 1 G, 2 B) a file channel fills; -1: none.
 * In a layer, "LAYER.C" with C one of R G B or X Y Z (any, for a layer of
 * one channel). */
static int
channel_slot(const char *name, const char *layer, bool grey)
{
    if (layer) {
        size_t n = strlen(layer);
        if (strncmp(name, layer, n) != 0 || name[n] != '.' || !name[n + 1] || name[n + 2]) {
            return -1;
        }
        const char *at = strchr("RGBXYZ", name[n + 1]);
        return grey ? 0 : at ? (int)(at - "RGBXYZ") % 3 : -1;
    }
    if (grey) {
        return strcmp(name, "Y") == 0 ? 0 : -1;
    }
    return strcmp(name, "R") == 0   ? 0
           : strcmp(name, "G") == 0 ? 1
           : strcmp(name, "B") == 0 ? 2
                                    : -1;
}

/* A layer's channels: one (*grey) or three. */
static const char *
find_layer(const exr_attr_chlist_t *list, const char *layer, bool *grey)
{
    int found[3] = {0, 0, 0}, n = 0;
    for (int i = 0; i < list->num_channels; i++) {
        const exr_attr_chlist_entry_t *e = &list->entries[i];
        int slot = channel_slot(e->name.str, layer, false);
        bool in_layer = channel_slot(e->name.str, layer, true) == 0;
        if (in_layer && (e->x_sampling != 1 || e->y_sampling != 1)) {
            return "subsampled channels not supported";
        }
        n += in_layer;
        if (slot >= 0) {
            found[slot] = 1;
        }
    }
    *grey = n == 1;
    return n == 0 ? "no such layer"
           : !*grey && !(found[0] && found[1] && found[2])
               ? "a layer of neither one channel nor three"
               : NULL;
}

/* Whether the part has R, G and B (*grey false) or Y (*grey true). */
static const char *
find_channels(const exr_attr_chlist_t *list, const char *layer, bool *grey)
{
    if (layer) {
        return find_layer(list, layer, grey);
    }
    int found[4] = {0, 0, 0, 0}; /* R G B Y */
    for (int i = 0; i < list->num_channels; i++) {
        const exr_attr_chlist_entry_t *e = &list->entries[i];
        int slot = channel_slot(e->name.str, NULL, false);
        slot = slot >= 0 ? slot : strcmp(e->name.str, "Y") == 0 ? 3 : -1;
        if (slot >= 0 && (e->x_sampling != 1 || e->y_sampling != 1)) {
            return "subsampled channels not supported";
        }
        if (slot >= 0) {
            found[slot] = 1;
        }
    }
    *grey = !(found[0] && found[1] && found[2]);
    return *grey && !found[3] ? "no R, G, B (or Y) channels" : NULL;
}

static exr_result_t
read_chunks(exr_context_t ctxt, int y_min, const char *layer, bool grey, struct image *img)
{
    int32_t lines = 0;
    exr_result_t rv = exr_get_scanlines_per_chunk(ctxt, 0, &lines);
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    bool started = false;
    for (int y = 0; y < img->height && rv == EXR_ERR_SUCCESS; y += lines) {
        exr_chunk_info_t chunk;
        rv = exr_read_scanline_chunk_info(ctxt, 0, y_min + y, &chunk);
        if (rv == EXR_ERR_SUCCESS) {
            rv = started ? exr_decoding_update(ctxt, 0, &chunk, &dec)
                         : exr_decoding_initialize(ctxt, 0, &chunk, &dec);
        }
        if (rv != EXR_ERR_SUCCESS) {
            break;
        }
        float *row = image_pixel(img, 0, chunk.start_y - y_min);
        for (int c = 0; c < dec.channel_count; c++) {
            exr_coding_channel_info_t *ch = &dec.channels[c];
            int slot = channel_slot(ch->channel_name, layer, grey);
            ch->decode_to_ptr = slot >= 0 ? (uint8_t *)(row + slot) : NULL;
            ch->user_data_type = EXR_PIXEL_FLOAT;
            ch->user_bytes_per_element = sizeof(float);
            ch->user_pixel_stride = 3 * sizeof(float);
            ch->user_line_stride = img->width * 3 * (int32_t)sizeof(float);
        }
        if (!started) {
            rv = exr_decoding_choose_default_routines(ctxt, 0, &dec);
        }
        started = true;
        if (rv == EXR_ERR_SUCCESS) {
            rv = exr_decoding_run(ctxt, 0, &dec);
        }
    }
    if (started) {
        exr_decoding_destroy(ctxt, &dec);
    }
    return rv;
}

/* Open the first part and check it is something we can read. */
static const char *
check_part(
    exr_context_t ctxt,
    const char *layer,
    exr_attr_box2i_t *window,
    bool *grey,
    exr_result_t *rv)
{
    exr_storage_t storage;
    const exr_attr_chlist_t *list = NULL;
    *rv = exr_get_storage(ctxt, 0, &storage);
    if (*rv == EXR_ERR_SUCCESS && storage != EXR_STORAGE_SCANLINE) {
        return "only scanline OpenEXR files are supported (not tiled or deep)";
    }
    if (*rv == EXR_ERR_SUCCESS) {
        *rv = exr_get_data_window(ctxt, 0, window);
    }
    if (*rv == EXR_ERR_SUCCESS) {
        *rv = exr_get_channels(ctxt, 0, &list);
    }
    return *rv == EXR_ERR_SUCCESS ? find_channels(list, layer, grey) : NULL;
}

bool
imgread_exr_layer(const char *path, const char *layer, struct image *out, struct diag *err)
{
    *out = (struct image){0};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = quiet;
    exr_context_t ctxt = NULL;
    exr_attr_box2i_t window;
    bool grey = false;
    const char *why = NULL;
    exr_result_t rv = exr_start_read(&ctxt, path, &init);
    if (rv == EXR_ERR_SUCCESS) {
        why = check_part(ctxt, layer, &window, &grey, &rv);
    }
    if (!why && rv == EXR_ERR_SUCCESS) {
        int64_t w = (int64_t)window.max.x - window.min.x + 1;
        int64_t h = (int64_t)window.max.y - window.min.y + 1;
        if (w < 1 || h < 1 || w > IMAGE_MAX_DIM || h > IMAGE_MAX_DIM) {
            why = "image size out of range";
        } else if (!image_alloc(out, (int)w, (int)h, err)) {
            why = "out of memory";
        }
    }
    if (!why && rv == EXR_ERR_SUCCESS) {
        rv = read_chunks(ctxt, window.min.y, layer, grey, out);
    }
    exr_finish(&ctxt);
    if (!why && rv != EXR_ERR_SUCCESS) {
        why = exr_get_default_error_message(rv);
    }
    if (why) {
        image_free(out);
        diag_set(
            err,
            path,
            0,
            0,
            "cannot read OpenEXR%s%s: %s",
            layer ? " layer " : "",
            layer ? layer : "",
            why);
        return false;
    }
    if (grey) {
        for (size_t i = 0; i < (size_t)out->width * (size_t)out->height; i++) {
            out->rgb[3 * i + 1] = out->rgb[3 * i + 2] = out->rgb[3 * i];
        }
    }
    return true;
}
