/* exr_ref.h: reads the R, G, B channels of a scanline OpenEXR reference
 * image (OpenEXR C API) and box-downsamples it, for the reference
 * comparisons of the renderer tests. */
#ifndef CV_TESTS_TRACE_EXR_REF_H
#define CV_TESTS_TRACE_EXR_REF_H

#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <openexr.h>

static void exr_ref_quiet(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
}

/* *rgb: width*height*3 floats, top row first (free()). */
static inline bool exr_ref_read_rgb(const char *path, float **rgb, uint32_t *width,
                                    uint32_t *height, char *why, size_t why_len)
{
    exr_context_t ctxt = NULL;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = exr_ref_quiet;
    exr_result_t rv = exr_start_read(&ctxt, path, &init);
    exr_attr_box2i_t dw;
    exr_storage_t storage = EXR_STORAGE_SCANLINE;
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_storage(ctxt, 0, &storage);
    if (rv == EXR_ERR_SUCCESS && storage != EXR_STORAGE_SCANLINE)
        rv = EXR_ERR_FEATURE_NOT_IMPLEMENTED;
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_data_window(ctxt, 0, &dw);
    if (rv != EXR_ERR_SUCCESS) {
        snprintf(why, why_len, "%s: %s", path, exr_get_default_error_message(rv));
        exr_finish(&ctxt);
        return false;
    }
    uint32_t w = (uint32_t)(dw.max.x - dw.min.x + 1), h = (uint32_t)(dw.max.y - dw.min.y + 1);
    /* four floats per pixel: a padded stride keeps OpenEXRCore on its
     * generic unpacking path, which handles any channel subset */
    float *tmp = calloc((size_t)w * h * 4, sizeof(float));
    int32_t lines = 1;
    rv = exr_get_scanlines_per_chunk(ctxt, 0, &lines);
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    bool started = false;
    static const char *const names[3] = {"R", "G", "B"};
    for (int32_t y = dw.min.y; rv == EXR_ERR_SUCCESS && y <= dw.max.y; y += lines) {
        exr_chunk_info_t ci;
        rv = exr_read_scanline_chunk_info(ctxt, 0, y, &ci);
        if (rv == EXR_ERR_SUCCESS)
            rv = started ? exr_decoding_update(ctxt, 0, &ci, &dec)
                         : exr_decoding_initialize(ctxt, 0, &ci, &dec);
        if (rv != EXR_ERR_SUCCESS)
            break;
        for (int16_t c = 0; c < dec.channel_count; c++) {
            exr_coding_channel_info_t *ch = &dec.channels[c];
            ch->decode_to_ptr = NULL;
            for (int k = 0; k < 3; k++) {
                if (strcmp(ch->channel_name, names[k]) != 0)
                    continue;
                ch->user_bytes_per_element = 4;
                ch->user_data_type = EXR_PIXEL_FLOAT;
                ch->user_pixel_stride = 4 * sizeof(float);
                ch->user_line_stride = (int32_t)(4 * sizeof(float) * w);
                ch->decode_to_ptr = (uint8_t *)(tmp + (size_t)(ci.start_y - dw.min.y) * w * 4 + k);
            }
        }
        if (!started) {
            rv = exr_decoding_choose_default_routines(ctxt, 0, &dec);
            started = true;
        }
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_decoding_run(ctxt, 0, &dec);
    }
    if (started)
        exr_decoding_destroy(ctxt, &dec);
    exr_finish(&ctxt);
    if (rv != EXR_ERR_SUCCESS) {
        snprintf(why, why_len, "%s: %s", path, exr_get_default_error_message(rv));
        free(tmp);
        return false;
    }
    float *out = malloc((size_t)w * h * 3 * sizeof(float));
    for (size_t i = 0; i < (size_t)w * h; i++)
        memcpy(out + 3 * i, tmp + 4 * i, 3 * sizeof(float));
    free(tmp);
    *rgb = out;
    *width = w;
    *height = h;
    return true;
}

/* Averages factor x factor blocks of an rgb image (w, h multiples of factor). */
static inline float *exr_ref_downsample(const float *rgb, uint32_t w, uint32_t h, uint32_t factor)
{
    uint32_t ow = w / factor, oh = h / factor;
    float *out = calloc((size_t)ow * oh * 3, sizeof(float));
    for (uint32_t y = 0; y < oh * factor; y++)
        for (uint32_t x = 0; x < ow * factor; x++)
            for (int c = 0; c < 3; c++)
                out[((size_t)(y / factor) * ow + x / factor) * 3 + c] +=
                    rgb[((size_t)y * w + x) * 3 + c] / (float)(factor * factor);
    return out;
}

#endif
