/* png_write_test.c: PNGs written by cv_png_write decode back with libpng to
 * exactly the quantised input (8 and 16 bit, RGB and RGBA), carry the sRGB
 * chunk (with gAMA and cHRM) when sRGB and the metadata as text; each
 * display encoding gets its cICP, gAMA and cHRM, an unknown one no colour
 * chunk; failures leave nothing behind and keep an older file. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <png.h>

#include "base/error.h"
#include "base/mem.h"
#include "output/atomic_file.h"
#include "output/png_write.h"
#include "tests/output/output_helpers.h"
#include "tests/rng.h"
#include "tests/tap.h"

#define W 29
#define H 17

static uint32_t rng = 777;
static float rnd(void)
{
    return (float)cv_test_lcg32(&rng);
}

/* A decoded PNG: samples as 16-bit values whatever the depth. */
struct decoded {
    uint32_t w, h, channels, depth;
    uint16_t *samples;
    bool srgb, gama, chrm;
    int srgb_intent;
    png_text *text; /* copies of key and text */
    int n_text;
};

static bool decode(const char *path, struct decoded *d)
{
    memset(d, 0, sizeof(*d));
    FILE *f = fopen(path, "rb");
    if (!f)
        return false;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, NULL);
        fclose(f);
        return false;
    }
    png_init_io(png, f);
    png_read_png(png, info, PNG_TRANSFORM_IDENTITY, NULL);
    d->w = png_get_image_width(png, info);
    d->h = png_get_image_height(png, info);
    d->channels = png_get_channels(png, info);
    d->depth = png_get_bit_depth(png, info);
    png_bytepp rows = png_get_rows(png, info);
    d->samples = cv_xmalloc((size_t)d->w * d->h * d->channels * sizeof(uint16_t));
    size_t k = 0;
    for (uint32_t y = 0; y < d->h; y++)
        for (uint32_t x = 0; x < d->w * d->channels; x++)
            d->samples[k++] = d->depth == 16
                                  ? (uint16_t)(rows[y][2 * x] << 8 | rows[y][2 * x + 1])
                                  : rows[y][x];
    d->srgb = png_get_sRGB(png, info, &d->srgb_intent) != 0;
    double g;
    d->gama = png_get_gAMA(png, info, &g) != 0 && fabs(g - 1.0 / 2.2) < 1e-3;
    double wx, wy, rx, ry, gx, gy, bx, by;
    d->chrm = png_get_cHRM(png, info, &wx, &wy, &rx, &ry, &gx, &gy, &bx, &by) != 0
              && fabs(wx - 0.3127) < 1e-4 && fabs(rx - 0.64) < 1e-4 && fabs(by - 0.06) < 1e-4;
    png_textp text;
    int n = png_get_text(png, info, &text, NULL);
    d->text = cv_xcalloc((size_t)n + 1, sizeof(png_text));
    for (int i = 0; i < n; i++) {
        d->text[i].key = cv_xstrdup(text[i].key);
        d->text[i].text = cv_xstrdup(text[i].text);
        d->text[i].compression = text[i].compression;
    }
    d->n_text = n;
    png_destroy_read_struct(&png, &info, NULL);
    fclose(f);
    return true;
}

static const char *text_of(const struct decoded *d, const char *key, int *compression)
{
    for (int i = 0; i < d->n_text; i++) {
        if (strcmp(d->text[i].key, key) == 0) {
            if (compression)
                *compression = d->text[i].compression;
            return d->text[i].text;
        }
    }
    return NULL;
}

static void free_decoded(struct decoded *d)
{
    for (int i = 0; i < d->n_text; i++) {
        free(d->text[i].key);
        free(d->text[i].text);
    }
    free(d->text);
    free(d->samples);
}

static void test_quantize(void)
{
    /* The rule, by hand: clamp, then round v*max to nearest, halves up. */
    TAP_EQ_INT(cv_png_quantize(0.0f, 8), 0, "0 -> 0");
    TAP_EQ_INT(cv_png_quantize(1.0f, 8), 255, "1 -> 255");
    TAP_EQ_INT(cv_png_quantize(0.5f, 8), 128, "0.5 -> 128 (127.5 rounds up)");
    TAP_EQ_INT(cv_png_quantize(0.25f, 8), 64, "0.25 -> 64 (63.75)");
    TAP_EQ_INT(cv_png_quantize(1.0f / 255.0f * 0.49f, 8), 0, "0.49 step -> 0");
    TAP_EQ_INT(cv_png_quantize(1.0f / 255.0f * 0.51f, 8), 1, "0.51 step -> 1");
    TAP_EQ_INT(cv_png_quantize(-0.3f, 8), 0, "negative clamps to 0");
    TAP_EQ_INT(cv_png_quantize(7.0f, 8), 255, "above 1 clamps to 255");
    TAP_EQ_INT(cv_png_quantize(NAN, 8), 0, "NaN -> 0");
    TAP_EQ_INT(cv_png_quantize(INFINITY, 16), 65535, "inf -> 65535");
    TAP_EQ_INT(cv_png_quantize(0.5f, 16), 32768, "0.5 -> 32768 at 16 bits");
    TAP_EQ_INT(cv_png_quantize(0.1f, 16), 6554, "0.1 -> 6554 (6553.5)");
}

/* The colour chunks of a PNG file, read by walking its chunks. */
struct colour_chunks {
    bool cicp, srgb, gama, chrm, iccp, cicp_before_idat;
    unsigned char cicp_data[4];
    uint32_t gama_value;      /* gAMA: gamma * 100000 */
    uint32_t chrm_value[8];   /* wx wy rx ry gx gy bx by, * 100000 */
};

static uint32_t be32(const unsigned char *b)
{
    return (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3];
}

static bool read_colour_chunks(const char *path, struct colour_chunks *c)
{
    memset(c, 0, sizeof(*c));
    FILE *f = fopen(path, "rb");
    if (!f)
        return false;
    unsigned char sig[8], head[8];
    bool idat = false, ok = fread(sig, 1, 8, f) == 8;
    while (ok && fread(head, 1, 8, f) == 8) {
        uint32_t len = be32(head);
        unsigned char *data = cv_xmalloc(len + 4);
        ok = fread(data, 1, len + 4, f) == len + 4;
        if (ok && memcmp(head + 4, "cICP", 4) == 0 && len == 4) {
            c->cicp = true;
            c->cicp_before_idat = !idat;
            memcpy(c->cicp_data, data, 4);
        } else if (memcmp(head + 4, "sRGB", 4) == 0) {
            c->srgb = true;
        } else if (memcmp(head + 4, "iCCP", 4) == 0) {
            c->iccp = true;
        } else if (ok && memcmp(head + 4, "gAMA", 4) == 0 && len == 4) {
            c->gama = true;
            c->gama_value = be32(data);
        } else if (ok && memcmp(head + 4, "cHRM", 4) == 0 && len == 32) {
            c->chrm = true;
            for (int i = 0; i < 8; i++)
                c->chrm_value[i] = be32(data + 4 * i);
        } else if (memcmp(head + 4, "IDAT", 4) == 0) {
            idat = true;
        }
        free(data);
    }
    fclose(f);
    return ok;
}

/* Each display encoding's tags: cICP (H.273 primaries, transfer, matrix 0,
 * full range) before IDAT, gAMA and cHRM for the encoding, the sRGB chunk
 * for sRGB only, and nothing for an unknown encoding. */
static void test_tags(const char *dir)
{
    static const struct {
        enum cv_display_encoding e;
        unsigned char primaries, transfer;
        uint32_t gama, rx, gy;
        bool srgb;
    } cases[] = {
        {CV_DISPLAY_SRGB, 1, 13, 45455, 64000, 60000, true},
        {CV_DISPLAY_P3, 12, 13, 45455, 68000, 69000, false},
        {CV_DISPLAY_BT1886, 1, 1, 41667, 64000, 60000, false},
    };
    float px[3 * 4 * 2] = {0.25f, 0.5f, 0.75f};
    struct cv_error err = {{0}};
    for (size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
        const char *name = cv_display_encoding_name(cases[i].e);
        char *path = cv_xasprintf("%s/tag-%zu.png", dir, i);
        struct cv_png_params p = {.pixels = px, .width = 4, .height = 2, .channels = 3,
                                  .encoding = cases[i].e};
        struct colour_chunks c = {0};
        struct decoded d;
        bool ok = cv_png_write(path, &p, &err) && read_colour_chunks(path, &c);
        tap_ok(ok && decode(path, &d) && d.w == 4 && d.samples[0] == cv_png_quantize(0.25f, 8),
               "%s: libpng decodes it", name);
        if (ok)
            free_decoded(&d);
        tap_ok(ok && c.cicp && c.cicp_before_idat && c.cicp_data[0] == cases[i].primaries &&
                   c.cicp_data[1] == cases[i].transfer && c.cicp_data[2] == 0 &&
                   c.cicp_data[3] == 1,
               "%s: cICP %u/%u/%u/%u before IDAT %s", name, c.cicp_data[0], c.cicp_data[1],
               c.cicp_data[2], c.cicp_data[3], err.msg);
        tap_ok(ok && c.gama && c.gama_value == cases[i].gama && c.chrm &&
                   c.chrm_value[0] == 31270 && c.chrm_value[2] == cases[i].rx &&
                   c.chrm_value[5] == cases[i].gy,
               "%s: gAMA %u, cHRM white %u red x %u green y %u", name, c.gama_value,
               c.chrm_value[0], c.chrm_value[2], c.chrm_value[5]);
        tap_ok(ok && c.srgb == cases[i].srgb && !c.iccp, "%s: %s sRGB chunk", name,
               cases[i].srgb ? "an" : "no");
        free(path);
    }
    char *path = cv_xasprintf("%s/tag-unknown.png", dir);
    struct cv_png_params p = {.pixels = px, .width = 4, .height = 2, .channels = 3};
    struct colour_chunks c = {0};
    bool ok = cv_png_write(path, &p, &err) && read_colour_chunks(path, &c);
    tap_ok(ok && !c.cicp && !c.srgb && !c.gama && !c.chrm && !c.iccp,
           "unknown encoding: no colour chunk at all %s", err.msg);
    free(path);
}

static void test_roundtrip(const char *dir, uint32_t channels, uint32_t depth)
{
    size_t n = (size_t)W * H * channels;
    float *px = cv_xmalloc(n * sizeof(float));
    for (size_t i = 0; i < n; i++)
        px[i] = rnd() * 1.2f - 0.1f; /* some out of [0,1], to clamp */
    px[0] = NAN;
    px[1] = 0.5f;
    char *path = cv_xasprintf("%s/rt-%u-%u.png", dir, channels, depth);
    struct cv_metadata *meta = cv_metadata_new();
    cv_metadata_set_string(meta, "scene", "scenes/cornell.pbrt");
    cv_metadata_set_int(meta, "spp", 1024);
    cv_metadata_set_float(meta, "renderTime", 3.5);
    cv_metadata_set_bool(meta, "partial", true);
    cv_metadata_set_string(meta, "job", "plan\xc3\xa8te"); /* UTF-8: needs iTXt */
    struct cv_png_params p = {
        .pixels = px, .width = W, .height = H, .channels = channels, .bit_depth = depth,
        .encoding = CV_DISPLAY_SRGB, .meta = meta,
    };
    struct cv_error err = { { 0 } };
    if (!tap_ok(cv_png_write(path, &p, &err), "write %u-bit %s", depth,
                channels == 4 ? "RGBA" : "RGB"))
        tap_diag("%s", err.msg);
    struct decoded d;
    tap_ok(decode(path, &d), "libpng decodes it");
    tap_ok(d.w == W && d.h == H && d.channels == channels && d.depth == depth,
           "size %ux%u, %u channels, %u bits", d.w, d.h, d.channels, d.depth);
    int bad = 0;
    for (size_t i = 0; d.samples && i < n; i++)
        if (d.samples[i] != cv_png_quantize(px[i], depth))
            bad++;
    TAP_EQ_INT(bad, 0, "every sample equals the quantised input");
    tap_ok(d.samples && d.samples[0] == 0
               && d.samples[1] == (depth == 8 ? 128 : 32768),
           "NaN and 0.5 as the rule says");
    tap_ok(d.srgb && d.srgb_intent == PNG_sRGB_INTENT_PERCEPTUAL, "sRGB chunk, perceptual");
    tap_ok(d.gama && d.chrm, "gAMA 1/2.2 and cHRM Rec.709/D65 alongside");
    const char *sw = text_of(&d, "Software", NULL);
    tap_ok(sw && strncmp(sw, "cavalry ", 8) == 0, "Software text: %s", sw ? sw : "(none)");
    const char *t = text_of(&d, "scene", NULL);
    tap_ok(t && strcmp(t, "scenes/cornell.pbrt") == 0, "scene text");
    t = text_of(&d, "spp", NULL);
    tap_ok(t && strcmp(t, "1024") == 0, "spp text");
    t = text_of(&d, "renderTime", NULL);
    tap_ok(t && strcmp(t, "3.5") == 0, "renderTime text");
    t = text_of(&d, "partial", NULL);
    tap_ok(t && strcmp(t, "1") == 0, "partial text");
    int comp = -99;
    t = text_of(&d, "job", &comp);
    tap_ok(t && strcmp(t, "plan\xc3\xa8te") == 0 && comp == PNG_ITXT_COMPRESSION_NONE,
           "non-ASCII value as iTXt, UTF-8 intact");
    free_decoded(&d);
    cv_metadata_destroy(&meta);
    unlink(path);
    free(path);
    free(px);
}

static void test_failures(const char *dir)
{
    float px[W * H * 3];
    for (size_t i = 0; i < CV_ARRAY_SIZE(px); i++)
        px[i] = rnd();
    char *path = cv_xasprintf("%s/shot.png", dir);
    struct cv_png_params p = { .pixels = px, .width = W, .height = H, .channels = 3 };
    struct cv_error err = { { 0 } };
    put_file(path, "old image");

    long long cuts[] = { 0, 8, 40, 200 };
    for (size_t i = 0; i < CV_ARRAY_SIZE(cuts); i++) {
        p.write_limit = &(struct cv_write_limit){cuts[i], ENOSPC};
        bool ok = cv_png_write(path, &p, &err);
        p.write_limit = NULL;
        tap_ok(!ok && strstr(err.msg, path) && strstr(err.msg, strerror(ENOSPC)),
               "disk full after %lld bytes: %s", cuts[i], err.msg);
        tap_ok(file_is(path, "old image") && count_entries(dir) == 1,
               "old file untouched, no temporary");
    }

    p.bit_depth = 12;
    tap_ok(!cv_png_write(path, &p, &err) && strstr(err.msg, "8 or 16"), "bad depth: %s",
           err.msg);
    p.bit_depth = 8;
    p.channels = 2;
    tap_ok(!cv_png_write(path, &p, &err) && strstr(err.msg, "3 or 4"), "bad channels: %s",
           err.msg);
    p.channels = 3;
    struct cv_metadata *meta = cv_metadata_new();
    cv_metadata_set_string(meta, "a key that is far too long to be a PNG keyword because "
                                 "they stop at seventy-nine", "x");
    p.meta = meta;
    tap_ok(!cv_png_write(path, &p, &err) && strstr(err.msg, "keyword"), "long key: %s",
           err.msg);
    cv_metadata_destroy(&meta);
    p.meta = NULL;
    tap_ok(file_is(path, "old image") && count_entries(dir) == 1,
           "old file untouched, no temporary");

    char *under = cv_xasprintf("%s/x.png", path); /* a file where a folder should be */
    tap_ok(!cv_png_write(under, &p, &err) && strstr(err.msg, under)
               && strstr(err.msg, strerror(ENOTDIR)),
           "unwritable place: %s", err.msg);
    free(under);
    tap_ok(!cv_png_write("/proc/cavalry-test.png", &p, &err)
               && strstr(err.msg, "/proc/cavalry-test.png"),
           "/proc: %s", err.msg);

    tap_ok(cv_png_write(path, &p, &err), "a good write then replaces the old file");
    struct decoded d;
    tap_ok(decode(path, &d) && d.w == W && count_entries(dir) == 1, "the new file is a PNG");
    free_decoded(&d);
    unlink(path);
    free(path);
}

int main(void)
{
    test_quantize();
    char *dir = scratch_dir("png");
    test_roundtrip(dir, 3, 8);
    test_roundtrip(dir, 4, 8);
    test_roundtrip(dir, 3, 16);
    test_roundtrip(dir, 4, 16);
    test_failures(dir);
    remove_scratch(dir);
    dir = scratch_dir("png-tags");
    test_tags(dir);
    remove_scratch(dir);
    return tap_done();
}
