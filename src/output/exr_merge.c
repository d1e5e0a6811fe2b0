/* exr_merge.c: see exr_merge.h. The tiles' pixels go through float and
 * back into each channel's own type (half to float to half is exact), so
 * the merge adds no rounding. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <openexr.h>

#include "base/mem.h"
#include "output/exr_merge.h"
#include "output/exr_read.h"
#include "output/exr_write.h"

struct tile {
    const char *path;
    exr_attr_box2i_t display, data;
};

struct channel {
    char *name;
    exr_pixel_type_t type;
    float *pixels;   /* the whole display window */
};

/* The first tile's attributes that Cavalry writes as metadata. */
static void copy_attributes(exr_context_t ctxt, struct cv_metadata *meta)
{
    static const char *const skip[] = {"pixelAspectRatio", "screenWindowWidth", "name", "type",
                                       "cavalry.settingsHash"};
    int32_t n = 0;
    exr_get_attribute_count(ctxt, 0, &n);
    for (int32_t i = 0; i < n; i++) {
        const exr_attribute_t *a = NULL;
        if (exr_get_attribute_by_index(ctxt, 0, EXR_ATTR_LIST_FILE_ORDER, i, &a) !=
            EXR_ERR_SUCCESS)
            continue;
        bool skipped = false;
        for (size_t k = 0; k < sizeof(skip) / sizeof(skip[0]); k++)
            skipped |= strcmp(a->name, skip[k]) == 0;
        if (skipped)
            continue;
        switch (a->type) {
        case EXR_ATTR_STRING: {
            char *s = cv_xmalloc((size_t)a->string->length + 1);
            memcpy(s, a->string->str, (size_t)a->string->length);
            s[a->string->length] = '\0';
            cv_metadata_set_string(meta, a->name, s);
            free(s);
            break;
        }
        case EXR_ATTR_INT: cv_metadata_set_int(meta, a->name, a->i); break;
        case EXR_ATTR_FLOAT: cv_metadata_set_float(meta, a->name, a->f); break;
        case EXR_ATTR_M44F: cv_metadata_set_m44f(meta, a->name, a->m44f->m); break;
        default: break; /* windows, channels, chromaticities: the writer's own */
        }
    }
}

static bool same_box(const exr_attr_box2i_t *a, const exr_attr_box2i_t *b)
{
    return a->min.x == b->min.x && a->min.y == b->min.y && a->max.x == b->max.x &&
           a->max.y == b->max.y;
}

/* Reads a tile's header; the first tile sets channels, compression and
 * metadata, every later one must match it. */
static bool read_header(struct tile *t, bool first, struct channel **chans, size_t *n_chans,
                        exr_compression_t *comp, struct cv_metadata *meta, bool *partial,
                        struct cv_error *err)
{
    exr_context_t ctxt = NULL;
    if (!cv_exr_open_read(t->path, &ctxt, err))
        return false;
    const exr_attr_chlist_t *cl = NULL;
    exr_compression_t c;
    exr_storage_t storage;
    exr_result_t rv = exr_get_storage(ctxt, 0, &storage);
    if (rv == EXR_ERR_SUCCESS && storage != EXR_STORAGE_SCANLINE)
        rv = EXR_ERR_FEATURE_NOT_IMPLEMENTED;
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_display_window(ctxt, 0, &t->display);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_data_window(ctxt, 0, &t->data);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_channels(ctxt, 0, &cl);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_compression(ctxt, 0, &c);
    bool ok = rv == EXR_ERR_SUCCESS ||
              cv_fail(err, "%s: %s", t->path,
                      rv == EXR_ERR_FEATURE_NOT_IMPLEMENTED ? "only scanline images merge"
                                                            : exr_get_default_error_message(rv));
    if (ok && first) {
        *comp = c;
        for (int i = 0; i < cl->num_channels; i++) {
            struct channel ch = {.name = cv_xstrdup(cl->entries[i].name.str),
                                 .type = cl->entries[i].pixel_type};
            if (ch.type == EXR_PIXEL_UINT)
                ok = cv_fail(err, "%s: channel %s: integer channels do not merge", t->path,
                             ch.name);
            (*chans)[(*n_chans)++] = ch;
            if (*n_chans == 64 && i + 1 < cl->num_channels) {
                ok = cv_fail(err, "%s: more than 64 channels", t->path);
                break;
            }
        }
        copy_attributes(ctxt, meta);
    } else if (ok) {
        bool same = (size_t)cl->num_channels == *n_chans;
        for (int i = 0; same && i < cl->num_channels; i++)
            same = strcmp(cl->entries[i].name.str, (*chans)[i].name) == 0 &&
                   cl->entries[i].pixel_type == (*chans)[i].type;
        if (!same)
            ok = cv_fail(err, "%s: channels differ from the first tile's", t->path);
        else if (c != *comp)
            ok = cv_fail(err, "%s: compression differs from the first tile's", t->path);
    }
    int32_t len = 0;
    const char *status = NULL;
    if (ok && exr_attr_get_string(ctxt, 0, "cavalry.status", &len, &status) == EXR_ERR_SUCCESS &&
        !(len == 8 && strncmp(status, "complete", 8) == 0))
        *partial = true;
    exr_finish(&ctxt);
    return ok;
}

/* The data windows cover the display window exactly once: each lies
 * inside it, no two overlap, and their areas add up to its area. */
static bool check_cover(const struct tile *t, size_t n, struct cv_error *err)
{
    const exr_attr_box2i_t *d = &t[0].display;
    uint64_t area = 0;
    for (size_t i = 0; i < n; i++) {
        const exr_attr_box2i_t *a = &t[i].data;
        if (!same_box(&t[i].display, d))
            return cv_fail(err, "%s: display window differs from %s's", t[i].path, t[0].path);
        if (a->min.x < d->min.x || a->min.y < d->min.y || a->max.x > d->max.x ||
            a->max.y > d->max.y)
            return cv_fail(err, "%s: data window reaches outside the display window", t[i].path);
        for (size_t j = 0; j < i; j++) {
            const exr_attr_box2i_t *b = &t[j].data;
            if (a->min.x <= b->max.x && b->min.x <= a->max.x && a->min.y <= b->max.y &&
                b->min.y <= a->max.y)
                return cv_fail(err, "%s and %s overlap (pixel %d,%d)", t[j].path, t[i].path,
                               a->min.x > b->min.x ? a->min.x : b->min.x,
                               a->min.y > b->min.y ? a->min.y : b->min.y);
        }
        area += (uint64_t)(a->max.x - a->min.x + 1) * (uint64_t)(a->max.y - a->min.y + 1);
    }
    uint64_t full = (uint64_t)(d->max.x - d->min.x + 1) * (uint64_t)(d->max.y - d->min.y + 1);
    if (area != full)
        return cv_fail(err, "the tiles cover %llu of the display window's %llu pixels",
                       (unsigned long long)area, (unsigned long long)full);
    return true;
}

/* Copies each channel of tile t into the full-window planes. */
static bool place_tile(const struct tile *t, struct channel *chans, size_t n_chans,
                       uint32_t full_w, struct cv_error *err)
{
    for (size_t c = 0; c < n_chans; c++) {
        float *px = NULL;
        uint32_t w, h;
        if (!cv_exr_read_channel(t->path, chans[c].name, &px, &w, &h, err))
            return false;
        uint32_t x0 = (uint32_t)(t->data.min.x - t->display.min.x);
        uint32_t y0 = (uint32_t)(t->data.min.y - t->display.min.y);
        for (uint32_t y = 0; y < h; y++)
            memcpy(chans[c].pixels + (size_t)(y0 + y) * full_w + x0, px + (size_t)y * w,
                   w * sizeof(float));
        free(px);
    }
    return true;
}

static struct channel *find(struct channel *chans, size_t n, const char *name)
{
    for (size_t i = 0; i < n; i++)
        if (strcmp(chans[i].name, name) == 0)
            return &chans[i];
    return NULL;
}

static bool write_merged(const char *out_path, struct channel *chans, size_t n_chans,
                         uint32_t w, uint32_t h, exr_compression_t comp,
                         const struct cv_metadata *meta, struct cv_error *err)
{
    static const char *const rgba_names[4] = {"R", "G", "B", "A"};
    struct channel *rgba_ch[4];
    for (int k = 0; k < 4; k++) {
        rgba_ch[k] = find(chans, n_chans, rgba_names[k]);
        if (!rgba_ch[k])
            return cv_fail(err, "tiles have no %s channel (Cavalry's EXRs have R, G, B, A)",
                           rgba_names[k]);
        if (rgba_ch[k]->type != rgba_ch[0]->type)
            return cv_fail(err, "tiles mix half and float in R, G, B, A");
    }
    size_t n = (size_t)w * h;
    float *rgba = cv_xmalloc(n * 4 * sizeof(float));
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 4; k++)
            rgba[4 * i + (size_t)k] = rgba_ch[k]->pixels[i];
    struct cv_image_layer *layers = cv_xcalloc(n_chans, sizeof(*layers));
    size_t n_layers = 0;
    for (size_t c = 0; c < n_chans; c++) {
        if (strlen(chans[c].name) == 1 && strchr("RGBA", chans[c].name[0]))
            continue;
        /* one layer per channel, named in full ("albedo.R"): same names out */
        layers[n_layers++] = (struct cv_image_layer){
            .name = NULL, .n_channels = 1, .channels = {chans[c].name},
            .data = chans[c].pixels,
            .pixel = chans[c].type == EXR_PIXEL_FLOAT ? CV_EXR_PIXEL_FLOAT : CV_EXR_PIXEL_HALF};
    }
    bool ok = cv_exr_write(out_path, &(struct cv_exr_params){
                                         .rgba = rgba,
                                         .width = w,
                                         .height = h,
                                         .use_float = rgba_ch[0]->type == EXR_PIXEL_FLOAT,
                                         .compression = cv_exr_compression_of(comp),
                                         .layers = layers,
                                         .n_layers = n_layers,
                                         .meta = meta,
                                     },
                           err);
    free(layers);
    free(rgba);
    return ok;
}

bool cv_exr_merge(const char *out_path, const char *const *paths, size_t n_tiles,
                  struct cv_error *err)
{
    if (n_tiles == 0)
        return cv_fail(err, "--merge: no tiles given");
    struct tile *tiles = cv_xcalloc(n_tiles, sizeof(*tiles));
    struct channel *chans = cv_xcalloc(64, sizeof(*chans));
    size_t n_chans = 0;
    exr_compression_t comp = EXR_COMPRESSION_ZIP;
    struct cv_metadata *meta = cv_metadata_new();
    bool partial = false, ok = true;
    for (size_t i = 0; ok && i < n_tiles; i++) {
        tiles[i].path = paths[i];
        ok = read_header(&tiles[i], i == 0, &chans, &n_chans, &comp, meta, &partial, err);
    }
    ok = ok && check_cover(tiles, n_tiles, err);
    uint32_t w = 0, h = 0;
    if (ok) {
        w = (uint32_t)(tiles[0].display.max.x - tiles[0].display.min.x + 1);
        h = (uint32_t)(tiles[0].display.max.y - tiles[0].display.min.y + 1);
        if ((uint64_t)w * h > (1u << 28))
            ok = cv_fail(err, "a merged image of %ux%u pixels is too large", w, h);
    }
    for (size_t c = 0; ok && c < n_chans; c++)
        chans[c].pixels = cv_xcalloc((size_t)w * h, sizeof(float));
    for (size_t i = 0; ok && i < n_tiles; i++)
        ok = place_tile(&tiles[i], chans, n_chans, w, err);
    if (ok && partial)
        cv_metadata_set_string(meta, "cavalry.status", "partial");
    ok = ok && write_merged(out_path, chans, n_chans, w, h, comp, meta, err);
    for (size_t c = 0; c < n_chans; c++) {
        free(chans[c].name);
        free(chans[c].pixels);
    }
    free(chans);
    free(tiles);
    cv_metadata_destroy(&meta);
    return ok;
}
