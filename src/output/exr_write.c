/* exr_write.c: see exr_write.h. OpenEXR writes through our own write
 * function into an atomic file, so the same code as for PNG decides what is
 * left on disk after a failure, and write errors keep their errno. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <openexr.h>

#include "config.h"
#include "base/mem.h"
#include "output/atomic_file.h"
#include "output/exr_write.h"

/* OpenEXR's value of each of our compressions (names: manifest/enums.c). */
static const exr_compression_t to_openexr[CV_EXR_COMPRESSION_COUNT] = {
    [CV_EXR_ZIP] = EXR_COMPRESSION_ZIP,   [CV_EXR_NONE] = EXR_COMPRESSION_NONE,
    [CV_EXR_ZIPS] = EXR_COMPRESSION_ZIPS, [CV_EXR_PIZ] = EXR_COMPRESSION_PIZ,
    [CV_EXR_RLE] = EXR_COMPRESSION_RLE,   [CV_EXR_DWAA] = EXR_COMPRESSION_DWAA,
    [CV_EXR_DWAB] = EXR_COMPRESSION_DWAB,
};

/* OpenEXRCore 3.1 (Debian 12) reads and writes every method but DWAA/DWAB
 * ("not yet implemented in C"); its C encoder for them came with 3.2. */
bool cv_exr_compression_supported(enum cv_exr_compression c)
{
    if (c != CV_EXR_DWAA && c != CV_EXR_DWAB)
        return true;
    int maj = 0, min = 0, patch = 0;
    const char *extra = NULL;
    exr_get_library_version(&maj, &min, &patch, &extra);
    return maj > 3 || (maj == 3 && min >= 2);
}

enum cv_exr_compression cv_exr_compression_of(int openexr_value)
{
    for (int i = 0; i < CV_EXR_COMPRESSION_COUNT; i++)
        if ((int)to_openexr[i] == openexr_value)
            return (enum cv_exr_compression)i;
    return CV_EXR_ZIP;
}

bool cv_exr_compression_parse(const char *name, enum cv_exr_compression *out,
                              struct cv_error *err)
{
    const struct cv_names *t = &cv_exr_compression_names;
    int i = cv_name_find(t, name);
    if (i < 0) {
        char list[128] = "";
        for (size_t k = 0; k < t->count; k++)
            snprintf(list + strlen(list), sizeof(list) - strlen(list), "%s%s", k ? ", " : "",
                     t->names[k]);
        return cv_fail(err, "unknown EXR compression \"%s\" (%s)", name, list);
    }
    if (!cv_exr_compression_supported((enum cv_exr_compression)i)) {
        int maj = 0, min = 0, patch = 0;
        const char *extra = NULL;
        exr_get_library_version(&maj, &min, &patch, &extra);
        return cv_fail(err, "EXR compression \"%s\" needs OpenEXR 3.2 or later "
                       "(this is %d.%d.%d); use zip or piz", name, maj, min, patch);
    }
    *out = (enum cv_exr_compression)i;
    return true;
}

/* Where one EXR channel's floats come from. */
struct source {
    char *name;
    const float *base; /* first float of this channel in the top row */
    uint32_t stride;   /* floats from one pixel to the next */
};

struct writer {
    struct cv_atomic_file *file;
    struct cv_error io_err; /* the first write failure, with its errno */
    bool io_failed;
    char lib_msg[512];      /* OpenEXR's last complaint */
    struct source *sources;
    size_t n_sources, cap_sources;
};

/* The writer being run on this thread. OpenEXR holds the context's lock
 * while it reports an error, so the handler cannot ask the context for its
 * user data (exr_get_user_data would deadlock). */
static _Thread_local struct writer *current_writer;

static void on_exr_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    struct writer *w = current_writer;
    if (w)
        snprintf(w->lib_msg, sizeof(w->lib_msg), "%s",
                 msg ? msg : exr_get_default_error_message(code));
}

static int64_t on_exr_write(exr_const_context_t ctxt, void *ud, const void *buf, uint64_t sz,
                            uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    struct writer *w = ud;
    struct cv_error e;
    if (!cv_atomic_write_at(w->file, buf, (size_t)sz, offset, &e)) {
        if (!w->io_failed)
            w->io_err = e;
        w->io_failed = true;
        error_cb(ctxt, EXR_ERR_WRITE_IO, "%s", e.msg);
        return -1;
    }
    return (int64_t)sz;
}

/* The best message for a failed call: our own write error first, since it
 * carries the real reason (errno), then what OpenEXR said. */
static bool fail_exr(struct writer *w, const char *path, const char *what, exr_result_t rv,
                     struct cv_error *err)
{
    if (w->io_failed)
        return cv_fail(err, "%s", w->io_err.msg);
    return cv_fail(err, "%s: %s: %s", path, what,
                   w->lib_msg[0] ? w->lib_msg : exr_get_default_error_message(rv));
}

static bool add_channel(exr_context_t ctxt, struct writer *w, const char *name,
                        exr_pixel_type_t type, const float *base, uint32_t stride,
                        const char *path, struct cv_error *err)
{
    exr_result_t rv = exr_add_channel(ctxt, 0, name, type, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (rv != EXR_ERR_SUCCESS)
        return fail_exr(w, path, "adding a channel", rv, err);
    struct source s = { .name = cv_xstrdup(name), .base = base, .stride = stride };
    CV_PUSH(w->sources, w->n_sources, w->cap_sources, s);
    return true;
}

static bool add_channels(exr_context_t ctxt, struct writer *w, const struct cv_exr_params *p,
                         const char *path, struct cv_error *err)
{
    exr_pixel_type_t image_type = p->use_float ? EXR_PIXEL_FLOAT : EXR_PIXEL_HALF;
    static const char *const rgba[4] = { "R", "G", "B", "A" };
    for (int c = 0; c < 4; c++)
        if (!add_channel(ctxt, w, rgba[c], image_type, p->rgba + c, 4, path, err))
            return false;
    for (size_t l = 0; l < p->n_layers; l++) {
        const struct cv_image_layer *layer = &p->layers[l];
        if (layer->n_channels < 1 || layer->n_channels > 4 || !layer->data)
            return cv_fail(err, "%s: layer %s: needs 1 to 4 channels and data", path,
                           layer->name ? layer->name : "(unnamed)");
        exr_pixel_type_t type = layer->pixel == CV_EXR_PIXEL_HALF    ? EXR_PIXEL_HALF
                                : layer->pixel == CV_EXR_PIXEL_FLOAT ? EXR_PIXEL_FLOAT
                                                                     : image_type;
        for (uint32_t c = 0; c < layer->n_channels; c++) {
            const char *ch = layer->channels[c];
            if (!ch || !*ch)
                return cv_fail(err, "%s: layer %s: channel %u has no name", path,
                               layer->name ? layer->name : "(unnamed)", c);
            char *name = layer->name && *layer->name ? cv_xasprintf("%s.%s", layer->name, ch)
                                                     : cv_xstrdup(ch);
            bool ok = add_channel(ctxt, w, name, type, layer->data + c, layer->n_channels,
                                  path, err);
            if (!ok)
                cv_error_prefix(err, "channel \"%s\": ", name);
            free(name);
            if (!ok)
                return false;
        }
    }
    return true;
}

static bool set_attributes(exr_context_t ctxt, struct writer *w, const struct cv_exr_params *p,
                           const char *path, struct cv_error *err)
{
    /* Rec.709 / sRGB primaries and D65: the renderer's working space. */
    static const exr_attr_chromaticities_t rec709 = {
        0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f,
    };
    exr_result_t rv = exr_attr_set_chromaticities(ctxt, 0, "chromaticities", &rec709);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_attr_set_string(ctxt, 0, "software", PACKAGE_NAME " " PACKAGE_VERSION);
    if (rv != EXR_ERR_SUCCESS)
        return fail_exr(w, path, "setting attributes", rv, err);
    size_t n_meta = p->meta ? p->meta->len : 0, n_exr = p->meta_exr ? p->meta_exr->len : 0;
    for (size_t i = 0; i < n_meta + n_exr; i++) {
        const struct cv_meta_entry *e =
            i < n_meta ? &p->meta->entries[i] : &p->meta_exr->entries[i - n_meta];
        switch (e->type) {
        case CV_META_STRING:
            rv = exr_attr_set_string(ctxt, 0, e->key, e->v.s);
            break;
        case CV_META_INT:
            if (e->v.i >= INT32_MIN && e->v.i <= INT32_MAX)
                rv = exr_attr_set_int(ctxt, 0, e->key, (int32_t)e->v.i);
            else
                rv = exr_attr_set_double(ctxt, 0, e->key, (double)e->v.i);
            break;
        case CV_META_FLOAT:
            rv = exr_attr_set_float(ctxt, 0, e->key, (float)e->v.f);
            break;
        case CV_META_M44F: {
            exr_attr_m44f_t m;
            memcpy(m.m, e->v.m, sizeof(m.m));
            rv = exr_attr_set_m44f(ctxt, 0, e->key, &m);
            break;
        }
        }
        if (rv != EXR_ERR_SUCCESS) {
            char *what = cv_xasprintf("attribute \"%s\"", e->key);
            fail_exr(w, path, what, rv, err);
            free(what);
            return false;
        }
    }
    return true;
}

static const struct source *find_source(const struct writer *w, const char *name)
{
    for (size_t i = 0; i < w->n_sources; i++)
        if (strcmp(w->sources[i].name, name) == 0)
            return &w->sources[i];
    return NULL;
}

static bool write_pixels(exr_context_t ctxt, struct writer *w, const struct cv_exr_params *p,
                         const char *path, struct cv_error *err)
{
    int32_t lines = 1;
    exr_result_t rv = exr_get_scanlines_per_chunk(ctxt, 0, &lines);
    if (rv != EXR_ERR_SUCCESS)
        return fail_exr(w, path, "chunk layout", rv, err);
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    bool started = false, ok = true;
    /* chunks are addressed by the data window's y; rows by y - y0 */
    int32_t y0 = p->full_width ? (int32_t)p->y0 : 0;
    for (int32_t y = 0; ok && y < (int32_t)p->height; y += lines) {
        exr_chunk_info_t cinfo;
        rv = exr_write_scanline_chunk_info(ctxt, 0, y0 + y, &cinfo);
        if (rv == EXR_ERR_SUCCESS)
            rv = started ? exr_encoding_update(ctxt, 0, &cinfo, &enc)
                         : exr_encoding_initialize(ctxt, 0, &cinfo, &enc);
        if (rv != EXR_ERR_SUCCESS) {
            ok = fail_exr(w, path, "encoding", rv, err);
            break;
        }
        for (int16_t c = 0; c < enc.channel_count; c++) {
            exr_coding_channel_info_t *ch = &enc.channels[c];
            const struct source *s = find_source(w, ch->channel_name);
            if (!s) {
                ok = cv_fail(err, "%s: channel %s has no data", path, ch->channel_name);
                break;
            }
            ch->user_bytes_per_element = 4;
            ch->user_data_type = EXR_PIXEL_FLOAT;
            ch->user_pixel_stride = (int32_t)(s->stride * sizeof(float));
            ch->user_line_stride = (int32_t)(s->stride * sizeof(float) * p->width);
            ch->encode_from_ptr =
                (const uint8_t *)(s->base + (size_t)(cinfo.start_y - y0) * p->width * s->stride);
        }
        if (!ok)
            break;
        if (!started) {
            rv = exr_encoding_choose_default_routines(ctxt, 0, &enc);
            started = true;
        }
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_encoding_run(ctxt, 0, &enc);
        if (rv != EXR_ERR_SUCCESS)
            ok = fail_exr(w, path, "writing pixels", rv, err);
    }
    if (started)
        exr_encoding_destroy(ctxt, &enc);
    return ok;
}

static bool check_params(const char *path, const struct cv_exr_params *p, struct cv_error *err)
{
    if (!p->rgba || p->width == 0 || p->height == 0)
        return cv_fail(err, "%s: empty image", path);
    if (p->width > INT32_MAX / 2 || p->height > INT32_MAX / 2)
        return cv_fail(err, "%s: image too large (%ux%u)", path, p->width, p->height);
    if (p->full_width && ((uint64_t)p->x0 + p->width > p->full_width ||
                          (uint64_t)p->y0 + p->height > p->full_height))
        return cv_fail(err, "%s: data window %ux%u at (%u, %u) outside the %ux%u display window",
                       path, p->width, p->height, p->x0, p->y0, p->full_width, p->full_height);
    if (p->full_width > INT32_MAX / 2 || p->full_height > INT32_MAX / 2)
        return cv_fail(err, "%s: image too large (%ux%u)", path, p->full_width, p->full_height);
    if ((unsigned)p->compression >= CV_EXR_COMPRESSION_COUNT)
        return cv_fail(err, "%s: invalid EXR compression %d", path, (int)p->compression);
    if (!cv_exr_compression_supported(p->compression))
        return cv_fail(err, "%s: EXR compression %s needs OpenEXR 3.2 or later", path,
                       cv_exr_compression_name(p->compression));
    return true;
}

static exr_compression_t to_exr(enum cv_exr_compression c)
{
    return (unsigned)c < CV_EXR_COMPRESSION_COUNT ? to_openexr[c] : EXR_COMPRESSION_ZIP;
}

bool cv_exr_write(const char *path, const struct cv_exr_params *p, struct cv_error *err)
{
    if (!check_params(path, p, err))
        return false;
    struct writer w = { 0 };
    if (!cv_atomic_open(path, &w.file, err))
        return false;
    cv_atomic_set_limit(w.file, p->write_limit);
    current_writer = &w;

    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = on_exr_error;
    init.write_fn = on_exr_write;
    init.user_data = &w;
    exr_context_t ctxt = NULL;
    int part = 0;
    bool ok = true;
    exr_result_t rv = exr_start_write(&ctxt, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_add_part(ctxt, "rgba", EXR_STORAGE_SCANLINE, &part);
    uint32_t fw = p->full_width ? p->full_width : p->width;
    uint32_t fh = p->full_width ? p->full_height : p->height;
    int32_t x0 = p->full_width ? (int32_t)p->x0 : 0, y0 = p->full_width ? (int32_t)p->y0 : 0;
    exr_attr_box2i_t display = {.min = {.x = 0, .y = 0},
                                .max = {.x = (int32_t)fw - 1, .y = (int32_t)fh - 1}};
    exr_attr_box2i_t data = {.min = {.x = x0, .y = y0},
                             .max = {.x = x0 + (int32_t)p->width - 1,
                                     .y = y0 + (int32_t)p->height - 1}};
    exr_attr_v2f_t center = {.x = 0.0f, .y = 0.0f};
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr(ctxt, part, &display, &data, 1.0f, &center, 1.0f,
                                          EXR_LINEORDER_INCREASING_Y, to_exr(p->compression));
    if (rv != EXR_ERR_SUCCESS)
        ok = fail_exr(&w, path, "starting the file", rv, err);
    ok = ok && add_channels(ctxt, &w, p, path, err);
    ok = ok && set_attributes(ctxt, &w, p, path, err);
    if (ok && (rv = exr_write_header(ctxt)) != EXR_ERR_SUCCESS)
        ok = fail_exr(&w, path, "writing the header", rv, err);
    ok = ok && write_pixels(ctxt, &w, p, path, err);
    /* finish writes the chunk offset table, so its result matters. */
    if (ctxt && (rv = exr_finish(&ctxt)) != EXR_ERR_SUCCESS && ok)
        ok = fail_exr(&w, path, "finishing the file", rv, err);
    current_writer = NULL;
    if (ok && w.io_failed)
        ok = cv_fail(err, "%s", w.io_err.msg);
    if (ok)
        ok = cv_atomic_commit(&w.file, err);
    else
        cv_atomic_abort(&w.file);
    for (size_t i = 0; i < w.n_sources; i++)
        free(w.sources[i].name);
    free(w.sources);
    return ok;
}
