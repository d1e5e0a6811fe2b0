/* png_write.c: see png_write.h. libpng reports errors by longjmp; the only
 * setjmp is in write_png(), and between it and libpng there are only
 * libpng's frames and our write callback, which holds nothing to free. All
 * allocation happens before the setjmp. */
#include <math.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <png.h>

#include "config.h"
#include "base/log.h"
#include "base/mem.h"
#include "output/atomic_file.h"
#include "output/png_write.h"

uint16_t cv_png_quantize(float v, uint32_t bits)
{
    float maxv = bits == 16 ? 65535.0f : 255.0f;
    if (!(v > 0.0f)) /* NaN too */
        return 0;
    if (v >= 1.0f)
        return (uint16_t)maxv;
    return (uint16_t)floorf(v * maxv + 0.5f);
}

struct png_out {
    struct cv_atomic_file *file;
    struct cv_error io_err;
    bool io_failed;
    char lib_msg[256];
};

static void on_png_error(png_structp png, png_const_charp msg)
{
    struct png_out *o = png_get_error_ptr(png);
    snprintf(o->lib_msg, sizeof(o->lib_msg), "%s", msg);
    png_longjmp(png, 1);
}

static void on_png_warning(png_structp png, png_const_charp msg)
{
    struct png_out *o = png_get_error_ptr(png);
    cv_warn("%s: libpng: %s", cv_atomic_path(o->file), msg);
}

static void on_png_write(png_structp png, png_bytep data, size_t len)
{
    struct png_out *o = png_get_io_ptr(png);
    if (!cv_atomic_write(o->file, data, len, &o->io_err)) {
        o->io_failed = true;
        png_error(png, "write failed");
    }
}

static void on_png_flush(png_structp png)
{
}

static bool is_ascii(const char *s, bool printable_only)
{
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c >= 0x80 || (printable_only && (c < 0x20 || c == 0x7f)))
            return false;
    }
    return true;
}

/* Text chunks, with their strings; built before any setjmp. */
struct texts {
    png_text *t;
    char **owned;
    size_t n;
};

static bool make_texts(const char *path, const struct cv_metadata *meta, struct texts *tx,
                       struct cv_error *err)
{
    size_t n = 1 + (meta ? meta->len : 0);
    tx->t = cv_xcalloc(n, sizeof(*tx->t));
    tx->owned = cv_xcalloc(n, sizeof(*tx->owned));
    tx->n = 0;
    tx->t[0].compression = PNG_TEXT_COMPRESSION_NONE;
    tx->t[0].key = "Software";
    tx->t[0].text = tx->owned[0] = cv_xstrdup(PACKAGE_NAME " " PACKAGE_VERSION);
    tx->n = 1;
    for (size_t i = 0; meta && i < meta->len; i++) {
        const struct cv_meta_entry *e = &meta->entries[i];
        /* the PNG specification's one "Software" keyword: the caller's
         * software entry replaces our default text rather than adding a
         * second chunk */
        if (strcasecmp(e->key, "Software") == 0 && e->type == CV_META_STRING) {
            free(tx->owned[0]);
            tx->t[0].text = tx->owned[0] = cv_xstrdup(e->v.s);
            continue;
        }
        size_t klen = strlen(e->key);
        if (klen < 1 || klen > 79 || !is_ascii(e->key, true) || e->key[0] == ' '
            || e->key[klen - 1] == ' ')
            return cv_fail(err, "%s: metadata key \"%s\" cannot be a PNG text keyword "
                           "(1 to 79 printable ASCII characters)", path, e->key);
        char *value = cv_meta_value_text(e);
        png_text *t = &tx->t[tx->n];
        tx->owned[tx->n++] = value;
        t->key = e->key;
        t->text = value;
        if (is_ascii(value, false)) {
            t->compression = PNG_TEXT_COMPRESSION_NONE;
        } else {
            t->compression = PNG_ITXT_COMPRESSION_NONE;
            t->lang = "";
            t->lang_key = "";
        }
    }
    return true;
}

static void free_texts(struct texts *tx)
{
    for (size_t i = 0; i < tx->n; i++)
        free(tx->owned[i]);
    free(tx->owned);
    free(tx->t);
}

/* The colour chunks of each known encoding: ITU-T H.273 code points for
 * cICP (colour primaries, transfer characteristics; matrix 0 for RGB, full
 * range), which takes precedence over the rest where a reader knows it,
 * then gAMA and cHRM (the encoding's primaries and D65 white, the curve as
 * a power) for readers that know only those. BT.1886 content goes as H.273
 * transfer 1 (BT.709), whose reference display is BT.1886. */
static const struct colour_tag {
    png_byte primaries, transfer;
    double gamma;                   /* gAMA: the encoding exponent */
    double wx, wy, rx, ry, gx, gy, bx, by;
} colour_tags[] = {
    [CV_DISPLAY_SRGB] = {1, 13, 1 / 2.2, 0.3127, 0.3290, 0.64, 0.33, 0.30, 0.60, 0.15, 0.06},
    [CV_DISPLAY_P3] = {12, 13, 1 / 2.2, 0.3127, 0.3290, 0.680, 0.320, 0.265, 0.690, 0.150, 0.060},
    [CV_DISPLAY_BT1886] = {1, 1, 1 / 2.4, 0.3127, 0.3290, 0.64, 0.33, 0.30, 0.60, 0.15, 0.06},
};

/* libpng 1.6 before 1.6.45 has no cICP support: it goes as a chunk that
 * libpng passes through, written before PLTE and IDAT as cICP must be. */
static void set_colour(png_structp png, png_infop info, enum cv_display_encoding e,
                       png_unknown_chunk *cicp)
{
    if (e <= CV_DISPLAY_UNKNOWN || e >= sizeof(colour_tags) / sizeof(colour_tags[0]))
        return;
    const struct colour_tag *t = &colour_tags[e];
    if (e == CV_DISPLAY_SRGB) {
        png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    } else {
        png_set_gAMA(png, info, t->gamma);
        png_set_cHRM(png, info, t->wx, t->wy, t->rx, t->ry, t->gx, t->gy, t->bx, t->by);
    }
    memcpy(cicp->name, "cICP", 5);
    cicp->data[0] = t->primaries;
    cicp->data[1] = t->transfer;
    cicp->data[2] = 0;
    cicp->data[3] = 1;
    cicp->size = 4;
    cicp->location = PNG_HAVE_IHDR;
    png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_ALWAYS, (png_const_bytep) "cICP", 1);
    png_set_unknown_chunks(png, info, cicp, 1);
}

/* Everything libpng may longjmp out of. rows holds the whole image,
 * quantised, big-endian at 16 bits as PNG stores it. */
static bool write_png(png_structp png, png_infop info, const struct cv_png_params *p,
                      uint32_t bits, const struct texts *tx, png_bytep *rows)
{
    if (setjmp(png_jmpbuf(png)))
        return false;
    png_set_write_fn(png, png_get_error_ptr(png), on_png_write, on_png_flush);
    png_set_IHDR(png, info, p->width, p->height, (int)bits,
                 p->channels == 4 ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_byte cicp_data[4];
    png_unknown_chunk cicp = {.data = cicp_data};
    set_colour(png, info, p->encoding, &cicp);
    png_set_text(png, info, tx->t, (int)tx->n);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, info);
    return true;
}

static png_bytep quantize_image(const struct cv_png_params *p, uint32_t bits)
{
    size_t bytes = bits / 8;
    size_t n = (size_t)p->width * p->height * p->channels;
    png_bytep buf = cv_xmalloc(n * bytes);
    for (size_t i = 0; i < n; i++) {
        uint16_t q = cv_png_quantize(p->pixels[i], bits);
        if (bytes == 1) {
            buf[i] = (png_byte)q;
        } else {
            buf[2 * i] = (png_byte)(q >> 8);
            buf[2 * i + 1] = (png_byte)(q & 0xff);
        }
    }
    return buf;
}

bool cv_png_write(const char *path, const struct cv_png_params *p, struct cv_error *err)
{
    uint32_t bits = p->bit_depth ? p->bit_depth : 8;
    if (bits != 8 && bits != 16)
        return cv_fail(err, "%s: PNG bit depth must be 8 or 16, not %u", path, bits);
    if (p->channels != 3 && p->channels != 4)
        return cv_fail(err, "%s: PNG needs 3 or 4 channels, not %u", path, p->channels);
    if (!p->pixels || p->width == 0 || p->height == 0)
        return cv_fail(err, "%s: empty image", path);
    if (p->width > PNG_USER_WIDTH_MAX || p->height > PNG_USER_HEIGHT_MAX)
        return cv_fail(err, "%s: image too large for PNG (%ux%u)", path, p->width, p->height);

    struct texts tx = { 0 };
    if (!make_texts(path, p->meta, &tx, err)) {
        free_texts(&tx);
        return false;
    }
    struct png_out out = { 0 };
    if (!cv_atomic_open(path, &out.file, err)) {
        free_texts(&tx);
        return false;
    }
    cv_atomic_set_limit(out.file, p->write_limit);
    png_bytep image = quantize_image(p, bits);
    size_t row_bytes = (size_t)p->width * p->channels * (bits / 8);
    png_bytep *rows = cv_xmalloc(p->height * sizeof(*rows));
    for (uint32_t y = 0; y < p->height; y++)
        rows[y] = image + y * row_bytes;

    bool ok = false;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &out, on_png_error,
                                              on_png_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!png || !info)
        cv_fail(err, "%s: cannot set up libpng", path);
    else if (write_png(png, info, p, bits, &tx, rows))
        ok = true;
    else if (out.io_failed)
        cv_fail(err, "%s", out.io_err.msg); /* the real reason, with errno */
    else
        cv_fail(err, "%s: libpng: %s", path, out.lib_msg);
    png_destroy_write_struct(png ? &png : NULL, info ? &info : NULL);

    if (ok)
        ok = cv_atomic_commit(&out.file, err);
    else
        cv_atomic_abort(&out.file);
    free(rows);
    free(image);
    free_texts(&tx);
    return ok;
}
