/* exr_read.c: reads a scanline OpenEXR image (the reference of a
 * convergence run) into linear RGB floats through the OpenEXR C API. A
 * missing G or B channel copies R (luminance-only references). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <openexr.h>

#include "base/mem.h"
#include "bench/bench.h"

static int channel_slot(const char *name)
{
    const char *dot = strrchr(name, '.');
    const char *base = dot ? dot + 1 : name;
    if (!strcmp(base, "R") || !strcmp(base, "r") || !strcmp(base, "Y"))
        return 0;
    if (!strcmp(base, "G") || !strcmp(base, "g"))
        return 1;
    if (!strcmp(base, "B") || !strcmp(base, "b"))
        return 2;
    return -1;
}

bool bench_read_exr(const char *path, float **rgb, unsigned *w, unsigned *h,
                    struct cv_error *err)
{
    exr_context_t ctx = NULL;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_result_t rv = exr_start_read(&ctx, path, &init);
    if (rv != EXR_ERR_SUCCESS)
        return cv_fail(err, "%s: %s", path, exr_get_error_code_as_string(rv));
    exr_storage_t storage;
    exr_attr_box2i_t dw;
    int32_t lines = 0;
    if ((rv = exr_get_storage(ctx, 0, &storage)) || (rv = exr_get_data_window(ctx, 0, &dw)) ||
        (rv = exr_get_scanlines_per_chunk(ctx, 0, &lines))) {
        exr_finish(&ctx);
        return cv_fail(err, "%s: %s", path, exr_get_error_code_as_string(rv));
    }
    if (storage != EXR_STORAGE_SCANLINE) {
        exr_finish(&ctx);
        return cv_fail(err, "%s: only scanline EXR images are read", path);
    }
    unsigned W = (unsigned)(dw.max.x - dw.min.x + 1), H = (unsigned)(dw.max.y - dw.min.y + 1);
    float *img = cv_xcalloc((size_t)W * H * 3, sizeof(float));
    bool seen[3] = {false, false, false};
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    bool inited = false;
    for (int y = dw.min.y; y <= dw.max.y && rv == EXR_ERR_SUCCESS; y += lines) {
        exr_chunk_info_t ci;
        if ((rv = exr_read_scanline_chunk_info(ctx, 0, y, &ci)))
            break;
        rv = inited ? exr_decoding_update(ctx, 0, &ci, &dec)
                    : exr_decoding_initialize(ctx, 0, &ci, &dec);
        if (rv)
            break;
        for (int c = 0; c < dec.channel_count; c++) {
            exr_coding_channel_info_t *ch = &dec.channels[c];
            int slot = channel_slot(ch->channel_name);
            if (slot < 0 || ch->height == 0) {
                ch->decode_to_ptr = NULL;
                continue;
            }
            seen[slot] = true;
            ch->user_data_type = EXR_PIXEL_FLOAT;
            ch->user_bytes_per_element = 4;
            ch->user_pixel_stride = 12;
            ch->user_line_stride = (int32_t)(12 * W);
            ch->decode_to_ptr = (uint8_t *)(img + ((size_t)(ci.start_y - dw.min.y) * W) * 3 + slot);
        }
        if (!inited && (rv = exr_decoding_choose_default_routines(ctx, 0, &dec)))
            break;
        inited = true;
        rv = exr_decoding_run(ctx, 0, &dec);
    }
    if (inited)
        exr_decoding_destroy(ctx, &dec);
    exr_finish(&ctx);
    if (rv != EXR_ERR_SUCCESS) {
        free(img);
        return cv_fail(err, "%s: decoding: %s", path, exr_get_error_code_as_string(rv));
    }
    if (!seen[0]) {
        free(img);
        return cv_fail(err, "%s: no R or Y channel", path);
    }
    for (size_t i = 0; i < (size_t)W * H; i++)
        for (int c = 1; c < 3; c++)
            if (!seen[c])
                img[3 * i + c] = img[3 * i];
    *rgb = img;
    *w = W;
    *h = H;
    return true;
}
