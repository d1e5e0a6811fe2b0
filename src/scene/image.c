/* image.c: reading the image formats pbrt scenes use. */
#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <stb/stb_image.h>

#include "base/file.h"
#include "base/mem.h"
#include "scene/exr_image.h"
#include "scene/hdr_check.h"
#include "scene/image.h"

#define MAX_DIM 65536
#define MAX_PIXELS (1L << 28) /* 4 GiB of float RGBA: refuse more */

uint16_t cv_float_to_half(float f)
{
    union { float f; uint32_t u; } v = {f};
    uint32_t sign = (v.u >> 16) & 0x8000u;
    uint32_t exp = (v.u >> 23) & 0xffu, mant = v.u & 0x7fffffu;
    if (exp == 0xff) /* inf, nan */
        return (uint16_t)(sign | 0x7c00u | (mant ? 0x200u : 0));
    int e = (int)exp - 127 + 15;
    if (e >= 31)
        return (uint16_t)(sign | 0x7c00u);
    if (e <= 0) {
        if (e < -10)
            return (uint16_t)sign;
        mant |= 0x800000u;
        int shift = 14 - e;
        uint32_t h = mant >> shift;
        uint32_t rem = mant & ((1u << shift) - 1), half = 1u << (shift - 1);
        if (rem > half || (rem == half && (h & 1)))
            h++;
        return (uint16_t)(sign | h);
    }
    uint32_t h = ((uint32_t)e << 10) | (mant >> 13);
    uint32_t rem = mant & 0x1fffu;
    if (rem > 0x1000u || (rem == 0x1000u && (h & 1)))
        h++; /* may carry into the exponent: still correct */
    return (uint16_t)(sign | h);
}

float cv_half_to_float(uint16_t h)
{
    uint32_t sign = (uint32_t)(h & 0x8000u) << 16, e = (h >> 10) & 0x1fu, m = h & 0x3ffu;
    union { uint32_t u; float f; } v;
    if (e == 0) {
        float f = ldexpf((float)m, -24);
        return sign ? -f : f;
    }
    if (e == 31)
        v.u = sign | 0x7f800000u | (m << 13);
    else
        v.u = sign | ((e + 112) << 23) | (m << 13);
    return v.f;
}

static float srgb_to_linear(float c)
{
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

static const char *ext_of(const char *path)
{
    const char *dot = strrchr(path, '.');
    return dot ? dot + 1 : "";
}

static bool ext_is(const char *path, const char *e)
{
    const char *x = ext_of(path);
    return strcasecmp(x, e) == 0;
}

/* The colour type of a PNG's header (6: RGBA), or -1. */
static int png_color_type(const char *path)
{
    unsigned char h[26];
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    size_t n = fread(h, 1, sizeof(h), f);
    fclose(f);
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (n < sizeof(h) || memcmp(h, sig, 8) != 0 || memcmp(h + 12, "IHDR", 4) != 0)
        return -1;
    return h[25];
}

/* Whether img's alpha is below 1 anywhere. */
static bool alpha_used(const struct cv_image *img)
{
    for (size_t i = 0; i < (size_t)img->width * img->height; i++)
        if (img->rgba[4 * i + 3] != 1.0f)
            return true;
    return false;
}

static bool load_pfm(const char *path, struct cv_image *img, struct cv_error *err)
{
    char *data;
    size_t len;
    if (!cv_read_file(path, &data, &len, err))
        return false;
    char type[3] = {0};
    int w = 0, h = 0, n = 0;
    double scale = 0;
    if (sscanf(data, "%2s %d %d %lf%n", type, &w, &h, &scale, &n) != 4 ||
        (strcmp(type, "PF") != 0 && strcmp(type, "Pf") != 0) || w <= 0 || h <= 0 ||
        w > MAX_DIM || h > MAX_DIM || (long)w * h > MAX_PIXELS || scale == 0) {
        free(data);
        return cv_fail(err, "%s: not a valid PFM header", path);
    }
    size_t off = (size_t)n + 1; /* one whitespace character after the scale */
    int ch = type[1] == 'F' ? 3 : 1;
    size_t need = (size_t)w * h * ch * 4;
    if (off > len || len - off < need) {
        free(data);
        return cv_fail(err, "%s: PFM data truncated", path);
    }
    bool swap = (scale > 0) != 0; /* positive scale: big endian */
    const unsigned char *p = (const unsigned char *)data + off;
    img->width = w;
    img->height = h;
    img->is_float = true;
    img->rgba = cv_xmalloc((size_t)w * h * 4 * sizeof(float));
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            /* PFM rows go bottom to top */
            float *o = &img->rgba[((size_t)(h - 1 - y) * w + x) * 4];
            for (int c = 0; c < ch; c++) {
                unsigned char b[4];
                memcpy(b, p + (((size_t)y * w + x) * ch + c) * 4, 4);
                if (swap) {
                    unsigned char t = b[0]; b[0] = b[3]; b[3] = t;
                    t = b[1]; b[1] = b[2]; b[2] = t;
                }
                float f;
                memcpy(&f, b, 4);
                o[c] = f * (float)fabs(scale);
            }
            if (ch == 1)
                o[1] = o[2] = o[0];
            o[3] = 1;
        }
    free(data);
    return true;
}

static bool load_exr(const char *path, struct cv_image *img, struct cv_error *err)
{
    if (!cv_exr_image_load(path, MAX_DIM, MAX_PIXELS, &img->rgba, &img->width, &img->height, err))
        return false;
    img->is_float = true;
    img->alpha = alpha_used(img);
    return true;
}

static bool load_stb(const char *path, bool srgb, struct cv_image *img, struct cv_error *err)
{
    int w, h, n;
    if (stbi_is_hdr(path)) {
        char *data;
        size_t len;
        if (!cv_read_file(path, &data, &len, err))
            return false;
        const unsigned char *u = (const unsigned char *)data;
        if (len > INT_MAX || !cv_hdr_check(path, u, len, err)) {
            if (len > INT_MAX)
                cv_fail(err, "%s: image too large", path);
            free(data);
            return false;
        }
        float *f = stbi_loadf_from_memory(u, (int)len, &w, &h, &n, 4);
        free(data);
        if (!f)
            return cv_fail(err, "%s: %s", path, stbi_failure_reason());
        img->width = w;
        img->height = h;
        img->is_float = true;
        img->rgba = cv_xmalloc((size_t)w * h * 4 * sizeof(float));
        memcpy(img->rgba, f, (size_t)w * h * 4 * sizeof(float));
        stbi_image_free(f);
        return true;
    }
    bool is16 = stbi_is_16_bit(path);
    void *d = is16 ? (void *)stbi_load_16(path, &w, &h, &n, 4) : (void *)stbi_load(path, &w, &h, &n, 4);
    if (!d)
        return cv_fail(err, "%s: %s", path, stbi_failure_reason());
    if (w <= 0 || h <= 0 || w > MAX_DIM || h > MAX_DIM || (long)w * h > MAX_PIXELS) {
        stbi_image_free(d);
        return cv_fail(err, "%s: image too large", path);
    }
    img->width = w;
    img->height = h;
    img->is_float = false;
    size_t count = (size_t)w * h * 4;
    img->rgba = cv_xmalloc(count * sizeof(float));
    float lut[256];
    for (int i = 0; i < 256; i++)
        lut[i] = srgb ? srgb_to_linear(i / 255.0f) : i / 255.0f;
    /* pbrt-v4 keeps the alpha of an RGBA PNG alone (its other formats and
     * PNG types come without), decoded by the encoding as the colour is */
    bool keep = ext_is(path, "png") && png_color_type(path) == 6;
    for (size_t i = 0; i < count; i++) {
        bool alpha = (i & 3) == 3 && !keep;
        if (is16) {
            float v = ((const uint16_t *)d)[i] / 65535.0f;
            img->rgba[i] = srgb && !alpha ? srgb_to_linear(v) : v;
        } else {
            uint8_t v = ((const uint8_t *)d)[i];
            img->rgba[i] = alpha ? v / 255.0f : lut[v];
        }
    }
    stbi_image_free(d);
    img->alpha = keep && alpha_used(img);
    return true;
}

bool cv_image_load(const char *path, bool srgb, struct cv_image *img, struct cv_error *err)
{
    memset(img, 0, sizeof(*img));
    if (!cv_input_check(path, err))
        return false;
    if (ext_is(path, "pfm"))
        return load_pfm(path, img, err);
    if (ext_is(path, "exr"))
        return load_exr(path, img, err);
    return load_stb(path, srgb, img, err);
}

bool cv_image_always_srgb(const char *path)
{
    static const char *const own[] = {"png", "exr", "pfm", "hdr", "qoi"};
    for (size_t i = 0; i < CV_ARRAY_SIZE(own); i++)
        if (ext_is(path, own[i]))
            return false;
    return true;
}

void cv_image_free(struct cv_image *img)
{
    free(img->rgba);
    memset(img, 0, sizeof(*img));
}
