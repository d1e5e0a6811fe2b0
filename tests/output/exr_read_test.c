/* exr_read_test.c: cv_exr_read_rgb_any, the reader for images from other
 * renderers (references of convergence and comparison runs): it picks R, G,
 * B by the name after the last dot in either case, prefers plain names to
 * layer-prefixed ones (so "N.Y" never stands in for R), and reads a
 * luminance-only image as grey. Files come from cv_exr_write and, for the
 * shapes it never writes, straight from OpenEXR's C API. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <openexr.h>

#include "base/error.h"
#include "base/mem.h"
#include "output/exr_read.h"
#include "output/exr_write.h"
#include "tests/output/output_helpers.h"
#include "tests/tap.h"

#define W 19
#define H 11

static float rgba[W * H * 4], normal[W * H * 3], lum[W * H], chans[3][W * H];

static void fill(void)
{
    uint32_t rng = 99;
    for (int i = 0; i < W * H * 4; i++) {
        rng = rng * 1664525u + 1013904223u;
        rgba[i] = (float)(rng >> 8) / 65536.0f;
    }
    for (int i = 0; i < W * H; i++) {
        for (int c = 0; c < 3; c++) {
            normal[i * 3 + c] = -1.0f - (float)(i + c);
            chans[c][i] = (float)(100 * c + i) * 0.25f;
        }
        lum[i] = (float)i * 0.5f + 3.0f;
    }
}

/* A float scanline image whose channels are `names`, channel k holding
 * data[k] (W*H floats each). */
static bool write_raw(const char *path, const char *const *names, int n,
                      const float *const *data)
{
    exr_context_t ctxt = NULL;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    if (exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init) != EXR_ERR_SUCCESS)
        return false;
    int part = 0;
    exr_result_t rv = exr_add_part(ctxt, "raw", EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctxt, part, W, H, EXR_COMPRESSION_NONE);
    for (int k = 0; rv == EXR_ERR_SUCCESS && k < n; k++)
        rv = exr_add_channel(ctxt, part, names[k], EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1, 1);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_write_header(ctxt);
    int32_t lines = 1;
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_scanlines_per_chunk(ctxt, part, &lines);
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    bool started = false;
    for (int32_t y = 0; rv == EXR_ERR_SUCCESS && y < H; y += lines) {
        exr_chunk_info_t cinfo;
        rv = exr_write_scanline_chunk_info(ctxt, part, y, &cinfo);
        if (rv == EXR_ERR_SUCCESS)
            rv = started ? exr_encoding_update(ctxt, part, &cinfo, &enc)
                         : exr_encoding_initialize(ctxt, part, &cinfo, &enc);
        for (int16_t c = 0; rv == EXR_ERR_SUCCESS && c < enc.channel_count; c++) {
            exr_coding_channel_info_t *ch = &enc.channels[c];
            int k = 0;
            while (k < n && strcmp(names[k], ch->channel_name) != 0)
                k++;
            ch->user_bytes_per_element = 4;
            ch->user_data_type = EXR_PIXEL_FLOAT;
            ch->user_pixel_stride = 4;
            ch->user_line_stride = 4 * W;
            ch->encode_from_ptr = (const uint8_t *)(data[k] + (size_t)cinfo.start_y * W);
        }
        if (rv == EXR_ERR_SUCCESS && !started) {
            rv = exr_encoding_choose_default_routines(ctxt, part, &enc);
            started = true;
        }
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_encoding_run(ctxt, part, &enc);
    }
    if (started)
        exr_encoding_destroy(ctxt, &enc);
    exr_finish(&ctxt);
    return rv == EXR_ERR_SUCCESS;
}

/* Pixels of rgb (W*H*3) that differ from want(channel c of pixel i). */
static int diff_rgb(const float *rgb, const float *want, int want_stride, const float *grey)
{
    int bad = 0;
    for (int i = 0; i < W * H; i++)
        for (int c = 0; c < 3; c++) {
            float w = grey ? grey[i] : want[i * want_stride + c];
            bad += rgb[i * 3 + c] != w;
        }
    return bad;
}

int main(void)
{
    fill();
    char *dir = scratch_dir("exr-read");
    struct cv_error err = { { 0 } };
    float *rgb = NULL;
    uint32_t w = 0, h = 0;

    /* Beauty plus an N layer whose Y must not be taken for R. */
    char *ours = cv_xasprintf("%s/ours.exr", dir);
    struct cv_image_layer layers[] = {
        { .name = "N", .n_channels = 3, .channels = { "X", "Y", "Z" }, .data = normal,
          .pixel = CV_EXR_PIXEL_FLOAT },
    };
    struct cv_exr_params p = { .rgba = rgba, .width = W, .height = H, .use_float = true,
                               .compression = CV_EXR_ZIP, .layers = layers, .n_layers = 1 };
    tap_ok(cv_exr_write(ours, &p, &err), "write RGBA with an N layer");
    tap_ok(cv_exr_read_rgb_any(ours, &rgb, &w, &h, &err) && w == W && h == H,
           "read our own image");
    TAP_EQ_INT(rgb ? diff_rgb(rgb, rgba, 4, NULL) : -1, 0, "R, G, B of the beauty, not N.Y");
    free(rgb);
    rgb = NULL;

    /* Lower case and layer-prefixed names, in an order other than RGB. */
    char *prefixed = cv_xasprintf("%s/prefixed.exr", dir);
    const char *const pnames[] = { "beauty.b", "beauty.g", "beauty.r" };
    const float *const pdata[] = { chans[2], chans[1], chans[0] };
    tap_ok(write_raw(prefixed, pnames, 3, pdata), "write beauty.b, beauty.g, beauty.r");
    tap_ok(cv_exr_read_rgb_any(prefixed, &rgb, &w, &h, &err), "read it");
    int bad = 0;
    for (int i = 0; rgb && i < W * H; i++)
        for (int c = 0; c < 3; c++)
            bad += rgb[i * 3 + c] != chans[c][i];
    TAP_EQ_INT(rgb ? bad : -1, 0, "channels land in R, G, B by name");
    free(rgb);
    rgb = NULL;

    /* Luminance only. */
    char *grey = cv_xasprintf("%s/grey.exr", dir);
    const char *const gnames[] = { "Y" };
    const float *const gdata[] = { lum };
    tap_ok(write_raw(grey, gnames, 1, gdata), "write a Y-only image");
    tap_ok(cv_exr_read_rgb_any(grey, &rgb, &w, &h, &err), "read it");
    TAP_EQ_INT(rgb ? diff_rgb(rgb, NULL, 0, lum) : -1, 0, "Y read as grey");
    free(rgb);
    rgb = NULL;

    /* Nothing usable, and not an image at all. */
    char *none = cv_xasprintf("%s/none.exr", dir);
    const char *const nnames[] = { "Z" };
    tap_ok(write_raw(none, nnames, 1, gdata), "write a Z-only image");
    tap_ok(!cv_exr_read_rgb_any(none, &rgb, &w, &h, &err) && strstr(err.msg, none)
               && strstr(err.msg, "no R or Y"),
           "no colour channel is an error: %s", err.msg);
    char *junk = cv_xasprintf("%s/junk.exr", dir);
    FILE *f = fopen(junk, "w");
    if (f) {
        fputs("not an image", f);
        fclose(f);
    }
    tap_ok(!cv_exr_read_rgb_any(junk, &rgb, &w, &h, &err) && strstr(err.msg, junk),
           "a file that is not EXR: %s", err.msg);

    const char *paths[] = { ours, prefixed, grey, none, junk };
    for (size_t i = 0; i < CV_ARRAY_SIZE(paths); i++) {
        unlink(paths[i]);
        free((char *)paths[i]);
    }
    remove_scratch(dir);
    return tap_done();
}
