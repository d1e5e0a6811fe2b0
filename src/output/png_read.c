/* png_read.c: see png_read.h. libpng reports errors by longjmp; the jump
 * lands in the one function that owns the libpng structures and holds
 * nothing else to free. */
#include <errno.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <png.h>

#include "base/mem.h"
#include "output/png_read.h"

struct read_state {
    char message[256];
};

static void on_error(png_structp png, png_const_charp msg)
{
    struct read_state *st = png_get_error_ptr(png);
    snprintf(st->message, sizeof(st->message), "%s", msg);
    png_longjmp(png, 1);
}

static void on_warning(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg;
}

/* Returns the text (malloc'd) or NULL; the state's message says why. */
static char *find_text(FILE *f, const char *key, struct read_state *st)
{
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, st, on_error, on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    char *volatile found = NULL;
    if (!png || !info) {
        snprintf(st->message, sizeof(st->message), "out of memory in libpng");
    } else if (setjmp(png_jmpbuf(png)) == 0) {
        png_init_io(png, f);
        png_read_info(png, info);
        png_textp text = NULL;
        int n = 0;
        png_get_text(png, info, &text, &n);
        for (int i = 0; i < n && !found; i++)
            if (strcmp(text[i].key, key) == 0)
                found = cv_xstrdup(text[i].text ? text[i].text : "");
        if (!found)
            snprintf(st->message, sizeof(st->message), "no text chunk \"%s\"", key);
    }
    png_destroy_read_struct(png ? &png : NULL, info ? &info : NULL, NULL);
    return found;
}

bool cv_png_read_text(const char *path, const char *key, char **value, struct cv_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return cv_fail(err, "%s: %s", path, strerror(errno));
    unsigned char sig[8];
    if (fread(sig, 1, sizeof(sig), f) != sizeof(sig) || png_sig_cmp(sig, 0, sizeof(sig)) != 0) {
        fclose(f);
        return cv_fail(err, "%s: not a PNG file", path);
    }
    rewind(f);
    struct read_state st = {{0}};
    char *text = find_text(f, key, &st);
    fclose(f);
    if (!text)
        return cv_fail(err, "%s: %s", path, st.message);
    *value = text;
    return true;
}

/* Decodes every row, then reads to IEND: zlib checks its Adler-32, libpng
 * every chunk's CRC (ancillary chunks too, here). */
static bool decode_all(FILE *f, struct read_state *st)
{
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, st, on_error, on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    unsigned char *volatile row = NULL;
    volatile bool ok = false;
    if (!png || !info) {
        snprintf(st->message, sizeof(st->message), "out of memory in libpng");
    } else if (setjmp(png_jmpbuf(png)) == 0) {
        png_set_crc_action(png, PNG_CRC_ERROR_QUIT, PNG_CRC_ERROR_QUIT);
        png_init_io(png, f);
        png_read_info(png, info);
        int passes = png_set_interlace_handling(png);
        png_read_update_info(png, info);
        row = cv_xmalloc(png_get_rowbytes(png, info) + 1);
        png_uint_32 h = png_get_image_height(png, info);
        for (int pass = 0; pass < passes; pass++)
            for (png_uint_32 y = 0; y < h; y++)
                png_read_row(png, row, NULL);
        png_read_end(png, NULL);
        ok = true;
    }
    free(row);
    png_destroy_read_struct(png ? &png : NULL, info ? &info : NULL, NULL);
    return ok;
}

bool cv_png_check(const char *path, struct cv_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return cv_fail(err, "%s: %s", path, strerror(errno));
    struct read_state st = {{0}};
    bool ok = decode_all(f, &st);
    fclose(f);
    return ok || cv_fail(err, "%s: %s", path, st.message);
}
