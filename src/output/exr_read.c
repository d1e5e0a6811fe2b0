/* exr_read.c: see exr_read.h. */
#include <stdlib.h>
#include <strings.h>
#include <string.h>

#include <openexr.h>

#include "base/mem.h"
#include "output/exr_read.h"

/* OpenEXR prints to stderr by default; the caller gets our message. */
static void quiet(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
}

bool cv_exr_open_read(const char *path, exr_context_t *ctxt, struct cv_error *err)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = quiet;
    exr_result_t rv = exr_start_read(ctxt, path, &init);
    if (rv != EXR_ERR_SUCCESS) {
        exr_finish(ctxt);
        return cv_fail(err, "%s: cannot read as OpenEXR: %s", path,
                       exr_get_default_error_message(rv));
    }
    return true;
}

bool cv_exr_read_attribute_string(const char *path, const char *name, char **value,
                                  struct cv_error *err)
{
    exr_context_t ctxt = NULL;
    if (!cv_exr_open_read(path, &ctxt, err))
        return false;
    int32_t len = 0;
    const char *s = NULL;
    exr_result_t rv = exr_attr_get_string(ctxt, 0, name, &len, &s);
    bool ok = rv == EXR_ERR_SUCCESS;
    if (ok) {
        *value = cv_xmalloc((size_t)len + 1);
        memcpy(*value, s, (size_t)len);
        (*value)[len] = '\0';
    } else if (rv == EXR_ERR_NO_ATTR_BY_NAME) {
        cv_fail(err, "%s: no attribute \"%s\"", path, name);
    } else if (rv == EXR_ERR_ATTR_TYPE_MISMATCH) {
        cv_fail(err, "%s: attribute \"%s\" is not a string", path, name);
    } else {
        cv_fail(err, "%s: attribute \"%s\": %s", path, name, exr_get_default_error_message(rv));
    }
    exr_finish(&ctxt);
    return ok;
}

/* Decodes the named channels into out: pixel i, channel k at
 * out[i*stride + k]. Channels not in the file keep out's values and are
 * reported through *missing (a bit per name). */
static bool decode(exr_context_t ctxt, const char *path, const char *const *names, int n,
                   float *out, uint32_t stride, const exr_attr_box2i_t *dw, unsigned *missing,
                   struct cv_error *err)
{
    uint32_t width = (uint32_t)(dw->max.x - dw->min.x + 1);
    int32_t lines = 1;
    exr_result_t rv = exr_get_scanlines_per_chunk(ctxt, 0, &lines);
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    bool started = false;
    *missing = (1u << n) - 1;
    for (int32_t y = dw->min.y; rv == EXR_ERR_SUCCESS && y <= dw->max.y; y += lines) {
        exr_chunk_info_t cinfo;
        rv = exr_read_scanline_chunk_info(ctxt, 0, y, &cinfo);
        if (rv == EXR_ERR_SUCCESS)
            rv = started ? exr_decoding_update(ctxt, 0, &cinfo, &dec)
                         : exr_decoding_initialize(ctxt, 0, &cinfo, &dec);
        if (rv != EXR_ERR_SUCCESS)
            break;
        for (int16_t c = 0; c < dec.channel_count; c++) {
            exr_coding_channel_info_t *ch = &dec.channels[c];
            ch->decode_to_ptr = NULL;
            for (int k = 0; k < n; k++) {
                if (strcmp(ch->channel_name, names[k]) != 0)
                    continue;
                *missing &= ~(1u << k);
                ch->user_bytes_per_element = 4;
                ch->user_data_type = EXR_PIXEL_FLOAT;
                ch->user_pixel_stride = (int32_t)(stride * sizeof(float));
                ch->user_line_stride = (int32_t)(stride * sizeof(float) * width);
                ch->decode_to_ptr =
                    (uint8_t *)(out + (size_t)(cinfo.start_y - dw->min.y) * width * stride + k);
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
    if (rv != EXR_ERR_SUCCESS)
        return cv_fail(err, "%s: cannot decode pixels: %s", path,
                       exr_get_default_error_message(rv));
    return true;
}

/* Opens path and checks it is something decode() handles. */
static bool open_image(const char *path, exr_context_t *ctxt, exr_attr_box2i_t *dw,
                       struct cv_error *err)
{
    if (!cv_exr_open_read(path, ctxt, err))
        return false;
    exr_storage_t storage;
    exr_result_t rv = exr_get_storage(*ctxt, 0, &storage);
    if (rv == EXR_ERR_SUCCESS && storage != EXR_STORAGE_SCANLINE) {
        exr_finish(ctxt);
        return cv_fail(err, "%s: only scanline images are supported", path);
    }
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_data_window(*ctxt, 0, dw);
    if (rv != EXR_ERR_SUCCESS) {
        exr_finish(ctxt);
        return cv_fail(err, "%s: %s", path, exr_get_default_error_message(rv));
    }
    return true;
}

/* Decodes the named channels of the open image (data window dw) into a new
 * array of n floats per pixel; the first `required` names must exist, the
 * others read as fill. */
static bool read_open(exr_context_t ctxt, const exr_attr_box2i_t *dw, const char *path,
                      const char *const *names, int n, int required, const float *fill,
                      float **data, uint32_t *width, uint32_t *height, struct cv_error *err)
{
    uint32_t w = (uint32_t)(dw->max.x - dw->min.x + 1), h = (uint32_t)(dw->max.y - dw->min.y + 1);
    /* One spare float per pixel: OpenEXRCore 3.1 picks "fast" half-to-float
     * routines for tightly interleaved or planar output that write wrong
     * values or crash when some channels are skipped; a padded stride
     * keeps it on its generic, correct path. */
    size_t pad = (size_t)n + 1, npix = (size_t)w * h;
    float *tmp = cv_xmalloc(npix * pad * sizeof(float));
    for (size_t i = 0; i < npix; i++)
        for (int k = 0; k < n; k++)
            tmp[i * pad + (size_t)k] = fill[k];
    unsigned missing = 0;
    bool ok = decode(ctxt, path, names, n, tmp, (uint32_t)pad, dw, &missing, err);
    float *out = cv_xmalloc(npix * (size_t)n * sizeof(float));
    for (size_t i = 0; i < npix; i++)
        memcpy(out + i * (size_t)n, tmp + i * pad, (size_t)n * sizeof(float));
    free(tmp);
    for (int k = 0; ok && k < required; k++)
        if (missing & (1u << k))
            ok = cv_fail(err, "%s: no channel \"%s\"", path, names[k]);
    if (!ok) {
        free(out);
        return false;
    }
    *data = out;
    *width = w;
    *height = h;
    return true;
}

static bool read_interleaved(const char *path, const char *const *names, int n, int required,
                             const float *fill, float **data, uint32_t *width, uint32_t *height,
                             struct cv_error *err)
{
    exr_context_t ctxt = NULL;
    exr_attr_box2i_t dw;
    if (!open_image(path, &ctxt, &dw, err))
        return false;
    bool ok = read_open(ctxt, &dw, path, names, n, required, fill, data, width, height, err);
    exr_finish(&ctxt);
    return ok;
}

bool cv_exr_read_channel(const char *path, const char *channel, float **data,
                         uint32_t *width, uint32_t *height, struct cv_error *err)
{
    const float zero = 0.0f;
    return read_interleaved(path, &channel, 1, 1, &zero, data, width, height, err);
}

bool cv_exr_read_rgba(const char *path, float **rgba, uint32_t *width, uint32_t *height,
                      struct cv_error *err)
{
    static const char *const names[4] = { "R", "G", "B", "A" };
    static const float fill[4] = { 0.0f, 0.0f, 0.0f, 1.0f };
    return read_interleaved(path, names, 4, 3, fill, rgba, width, height, err);
}

/* How well channel `name` serves slot (0 R, 1 G, 2 B): lower is better, -1
 * not at all. A layer prefix ranks below the plain name, Y below R. */
static int channel_rank(const char *name, int slot)
{
    static const char *const letters[3] = { "R", "G", "B" };
    const char *dot = strrchr(name, '.');
    const char *base = dot ? dot + 1 : name;
    int prefixed = dot ? 1 : 0;
    if (!strcasecmp(base, letters[slot]))
        return prefixed;
    if (slot == 0 && !strcmp(base, "Y"))
        return 2 + prefixed;
    return -1;
}

bool cv_exr_read_rgb_any(const char *path, float **rgb, uint32_t *width, uint32_t *height,
                         struct cv_error *err)
{
    exr_context_t ctxt = NULL;
    exr_attr_box2i_t dw;
    if (!open_image(path, &ctxt, &dw, err))
        return false;
    const exr_attr_chlist_t *chl = NULL;
    exr_result_t rv = exr_get_channels(ctxt, 0, &chl);
    if (rv != EXR_ERR_SUCCESS) {
        exr_finish(&ctxt);
        return cv_fail(err, "%s: %s", path, exr_get_default_error_message(rv));
    }
    const char *chosen[3] = { NULL, NULL, NULL };
    int best[3] = { -1, -1, -1 };
    for (int i = 0; i < chl->num_channels; i++) {
        const char *name = chl->entries[i].name.str;
        for (int slot = 0; slot < 3; slot++) {
            int r = channel_rank(name, slot);
            if (r >= 0 && (best[slot] < 0 || r < best[slot])) {
                best[slot] = r;
                chosen[slot] = name;
            }
        }
    }
    if (best[0] < 0) {
        exr_finish(&ctxt);
        return cv_fail(err, "%s: no R or Y channel", path);
    }
    const char *names[3];
    int slot_of[3], n = 0;
    for (int slot = 0; slot < 3; slot++)
        if (best[slot] >= 0) {
            names[n] = chosen[slot];
            slot_of[n++] = slot;
        }
    static const float zero[3] = { 0.0f, 0.0f, 0.0f };
    float *tmp = NULL;
    uint32_t w = 0, h = 0;
    /* The names belong to the context: decode before closing it. */
    bool ok = read_open(ctxt, &dw, path, names, n, n, zero, &tmp, &w, &h, err);
    exr_finish(&ctxt);
    if (!ok)
        return false;
    size_t npix = (size_t)w * h;
    float *out = cv_xmalloc(npix * 3 * sizeof(float));
    for (size_t i = 0; i < npix; i++) {
        float px[3];
        px[0] = px[1] = px[2] = tmp[i * (size_t)n];
        for (int k = 0; k < n; k++)
            px[slot_of[k]] = tmp[i * (size_t)n + (size_t)k];
        memcpy(out + i * 3, px, sizeof px);
    }
    free(tmp);
    *rgb = out;
    *width = w;
    *height = h;
    return true;
}
