/* texture.c: pbrt textures into CvTexture records, and image files into the
 * shared texel buffer with a box-filtered mip chain: half floats for 8-bit
 * images, 32-bit floats for images of high dynamic range (glsl/shared/
 * scene.h says why). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/file.h"
#include "base/mem.h"
#include "scene/builder.h"
#include "scene/image.h"

static void tex_init(CvTexture *t, uint32_t type)
{
    memset(t, 0, sizeof(*t));
    t->type = type;
    t->tex_a = t->tex_b = t->amount_tex = -1;
    t->uv_map = (cv_vec4){1, 1, 0, 0};
    t->scale = 1;
    t->amount = 0.5f;
}

/* Texels of an image of w x h and its mip levels down to 1 x 1; levels
 * (may be NULL) gets their count. */
static uint64_t mip_texels(int w, int h, uint32_t *levels)
{
    uint64_t total = 0;
    uint32_t nl = 0;
    for (int lw = w, lh = h;; lw = lw > 1 ? lw / 2 : 1, lh = lh > 1 ? lh / 2 : 1) {
        total += (uint64_t)lw * lh;
        nl++;
        if (lw == 1 && lh == 1)
            break;
    }
    if (levels)
        *levels = nl;
    return total;
}

/* Room for `slots` more texel slots at the texel buffer's end; false with
 * err set where the buffer would pass its 2^32 slots. */
static bool reserve_texels(struct cv_builder *b, uint64_t slots, struct cv_error *err)
{
    struct cv_scene *s = b->s;
    if (s->n_texels + slots > 0xffffffffu)
        return cv_fail(err, "texel buffer exceeds 2^32 slots of 8 bytes");
    s->texels = cv_xgrow(s->texels, &b->cap_texel, (size_t)(s->n_texels + slots) * 2, sizeof(uint32_t));
    return true;
}

/* Appends levels of img to the texel buffer, in float where `flags` has
 * CV_TEXF_RGBA32F, else in half; returns the first slot. */
static uint32_t add_texels(struct cv_builder *b, const struct cv_image *img, uint32_t flags,
                           uint32_t *levels, struct cv_error *err, bool *ok)
{
    struct cv_scene *s = b->s;
    int w = img->width, h = img->height;
    uint32_t slots = CV_TEX_SLOTS(flags);
    uint32_t nl;
    uint64_t total = mip_texels(w, h, &nl) * slots;
    *ok = reserve_texels(b, total, err);
    if (!*ok)
        return 0;
    uint32_t offset = (uint32_t)s->n_texels;
    float *cur = cv_xmalloc((size_t)w * h * 4 * sizeof(float));
    memcpy(cur, img->rgba, (size_t)w * h * 4 * sizeof(float));
    uint32_t *out = s->texels + s->n_texels * 2;
    for (int lw = w, lh = h;;) {
        for (size_t i = 0; i < (size_t)lw * lh; i++) {
            const float *c = &cur[i * 4];
            if (slots == 2) {
                memcpy(&out[4 * i], c, 4 * sizeof(float));
                continue;
            }
            out[2 * i] = cv_float_to_half(c[0]) | ((uint32_t)cv_float_to_half(c[1]) << 16);
            out[2 * i + 1] = cv_float_to_half(c[2]) | ((uint32_t)cv_float_to_half(c[3]) << 16);
        }
        out += (size_t)lw * lh * 2 * slots;
        if (lw == 1 && lh == 1)
            break;
        int nw = lw > 1 ? lw / 2 : 1, nh = lh > 1 ? lh / 2 : 1;
        float *next = cv_xmalloc((size_t)nw * nh * 4 * sizeof(float));
        for (int y = 0; y < nh; y++)
            for (int x = 0; x < nw; x++)
                for (int c = 0; c < 4; c++) {
                    /* box filter over the 2x2 (or odd edge 3) footprint */
                    int x0 = x * 2, y0 = y * 2;
                    int x1 = (x == nw - 1) ? lw - 1 : x0 + 1, y1 = (y == nh - 1) ? lh - 1 : y0 + 1;
                    double sum = 0;
                    int cnt = 0;
                    for (int yy = y0; yy <= y1; yy++)
                        for (int xx = x0; xx <= x1; xx++) {
                            sum += cur[((size_t)yy * lw + xx) * 4 + c];
                            cnt++;
                        }
                    next[((size_t)y * nw + x) * 4 + c] = (float)(sum / cnt);
                }
        free(cur);
        cur = next;
        lw = nw;
        lh = nh;
    }
    free(cur);
    s->n_texels += total;
    *levels = nl;
    return offset;
}

void cv_scene_texel(const struct cv_scene *s, const CvTexture *t, uint64_t i, float rgba[4])
{
    const uint32_t *w = s->texels + ((uint64_t)t->offset + i * CV_TEX_SLOTS(t->flags)) * 2;
    if (t->flags & CV_TEXF_RGBA32F) {
        memcpy(rgba, w, 4 * sizeof(float));
        return;
    }
    for (int c = 0; c < 4; c++)
        rgba[c] = cv_half_to_float((uint16_t)(w[c / 2] >> (16 * (c % 2))));
}

void cv_scene_texture_average(const struct cv_scene *s, const CvTexture *t, float rgba[4])
{
    uint64_t last = 0;
    for (uint32_t w = t->width, h = t->height; w > 1 || h > 1;) {
        last += (uint64_t)w * h;
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
    }
    cv_scene_texel(s, t, last, rgba);
}

double cv_scene_texture_luminance(const struct cv_scene *s, const CvTexture *t)
{
    float rgba[4];
    cv_scene_texture_average(s, t, rgba);
    return CV_LUMA(rgba[0], rgba[1], rgba[2]);
}

int cv_b_image_texture(struct cv_builder *b, const char *file, const char *dir, bool srgb,
                       const struct cv_loc *loc, struct cv_error *err)
{
    char *path = cv_b_resolve(b, dir, file, err);
    if (!path) {
        cv_error_prefix(err, "%s:%d:%d: image \"%s\"", loc->file, loc->line, loc->col, file);
        return -1;
    }
    char *key = cv_xasprintf("%s|%d", path, srgb);
    int idx = cv_b_lookup(b->images, b->n_images, key);
    if (idx >= 0) {
        free(path);
        free(key);
        return idx;
    }
    struct cv_image img;
    if (!cv_image_load(path, srgb, &img, err)) {
        cv_error_prefix(err, "%s:%d:%d: image \"%s\"", loc->file, loc->line, loc->col, file);
        free(path);
        free(key);
        return -1;
    }
    CvTexture t;
    tex_init(&t, CV_TEX_IMAGE);
    if (img.is_float)
        t.flags |= CV_TEXF_RGBA32F;
    bool ok;
    t.offset = add_texels(b, &img, t.flags, &t.levels, err, &ok);
    t.width = (uint32_t)img.width;
    t.height = (uint32_t)img.height;
    if (srgb && !img.is_float)
        t.flags |= CV_TEXF_SRGB;
    if (img.alpha)
        t.flags |= CV_TEXF_ALPHA;
    cv_image_free(&img);
    free(path);
    if (!ok) {
        cv_error_prefix(err, "%s:%d:%d: image \"%s\"", loc->file, loc->line, loc->col, file);
        free(key);
        return -1;
    }
    idx = cv_b_add_texture(b, &t);
    cv_b_set_named(&b->images, &b->n_images, &b->cap_images, key, idx);
    free(key);
    return idx;
}

/* The image texture that a "float" imagemap of image texture idx reads
 * (texture.glsl's float lookup: the average of r, g, b): idx itself, or
 * for an image marked CV_TEXF_ALPHA a copy of its texels with the alpha in
 * r, g and b, made once: a select of the alpha in the shaders' lookup,
 * inlined by every textured shade kernel, slowed textured scenes
 * (bench/RESULTS.md, "A float texture's alpha in the shaders"). -1 with
 * err set where the texel buffer is full. */
static int float_image(struct cv_builder *b, int idx, struct cv_error *err)
{
    struct cv_scene *s = b->s;
    CvTexture t = s->textures[idx];
    if (!(t.flags & CV_TEXF_ALPHA))
        return idx;
    char key[32];
    snprintf(key, sizeof(key), "|alpha|%d", idx);   /* no path's key ("path|srgb") */
    int c = cv_b_lookup(b->images, b->n_images, key);
    if (c >= 0)
        return c;
    uint32_t slots = CV_TEX_SLOTS(t.flags);
    uint64_t n = mip_texels((int)t.width, (int)t.height, NULL), total = n * slots;
    if (!reserve_texels(b, total, err))
        return -1;
    const uint32_t *from = s->texels + (size_t)t.offset * 2;
    uint32_t *to = s->texels + s->n_texels * 2;
    for (uint64_t i = 0; i < n; i++) {
        if (slots == 2) {   /* float r, g, b, a */
            for (int k = 0; k < 4; k++)
                to[4 * i + k] = from[4 * i + 3];
        } else {            /* half (r, g), (b, a) */
            uint32_t a = from[2 * i + 1] >> 16;
            to[2 * i] = to[2 * i + 1] = a | (a << 16);
        }
    }
    t.offset = (uint32_t)s->n_texels;
    t.flags &= ~CV_TEXF_ALPHA;   /* the copy's r, g, b are that alpha */
    s->n_texels += total;
    int i = cv_b_add_texture(b, &t);
    cv_b_set_named(&b->images, &b->n_images, &b->cap_images, key, i);
    return i;
}

int cv_b_image_texture_v4(struct cv_builder *b, const char *file, const char *dir, bool srgb,
                          const char *what, const struct cv_loc *loc, struct cv_error *err)
{
    if (!srgb && cv_image_always_srgb(file)) {
        if (!cv_b_warn(b, err, loc, "%s \"%s\": pbrt-v4 decodes 8-bit images other than PNG "
                       "from sRGB whatever encoding is asked; decoded so", what, file))
            return -1;
        srgb = true;
    }
    return cv_b_image_texture(b, file, dir, srgb, loc, err);
}

int cv_b_texture_times(struct cv_builder *b, int id, const double rgb[3])
{
    CvTexture t = b->s->textures[id];
    if (rgb[0] == rgb[1] && rgb[1] == rgb[2] && !(t.flags & CV_TEXF_INVERT)) {
        t.scale *= (float)rgb[0];
        return cv_b_add_texture(b, &t);
    }
    tex_init(&t, CV_TEX_SCALE);
    t.tex_a = id;
    t.value_b = (cv_vec4){(float)rgb[0], (float)rgb[1], (float)rgb[2], 1};
    return cv_b_add_texture(b, &t);
}

/* How deep composites nest in texture t of s (a leaf: 0). */
static int nesting(const struct cv_scene *s, const CvTexture *t)
{
    if (t->type == CV_TEX_IMAGE || t->type == CV_TEX_CONSTANT)
        return 0;
    int d = 0, ops[3] = {t->tex_a, t->tex_b, t->amount_tex};
    for (int i = 0; i < 3; i++)
        if (ops[i] >= 0) {
            int k = nesting(s, &s->textures[ops[i]]);
            d = k > d ? k : d;
        }
    return d + 1;
}

/* A value-or-texture slot of a texture: float or spectrum per `is_float`. */
static bool slot(struct cv_builder *b, struct cv_params *ps, const char *name, bool is_float,
                 double def, const char *dir, cv_vec4 *val, int *tex, struct cv_error *err)
{
    if (is_float) {
        double v = def;
        if (!cv_b_float_tex(b, ps, name, &v, tex, err))
            return false;
        *val = (cv_vec4){(float)v, (float)v, (float)v, 1};
        return true;
    }
    double rgb[3] = {def, def, def};
    if (!cv_b_color_tex(b, ps, name, CV_SPEC_REFLECTANCE, dir, rgb, tex, err))
        return false;
    *val = (cv_vec4){(float)rgb[0], (float)rgb[1], (float)rgb[2], 1};
    return true;
}

static bool uv_mapping(struct cv_builder *b, struct cv_params *ps, CvTexture *t,
                       const struct cv_loc *loc, struct cv_error *err)
{
    const char *mapping = cv_params_string(ps, "mapping", "uv");
    if (strcmp(mapping, "uv") != 0 &&
        !cv_b_warn(b, err, loc, "texture mapping \"%s\" is not supported; uv used", mapping))
        return false;
    t->uv_map = (cv_vec4){(float)cv_params_float(ps, "uscale", 1), (float)cv_params_float(ps, "vscale", 1),
                          (float)cv_params_float(ps, "udelta", 0), (float)cv_params_float(ps, "vdelta", 0)};
    return true;
}

bool cv_b_texture(struct cv_builder *b, const char *name, const char *kind, const char *cls,
                  struct cv_params *ps, const struct cv_loc *loc, const char *dir,
                  struct cv_error *err)
{
    bool is_float;
    if (strcmp(kind, "float") == 0)
        is_float = true;
    else if (strcmp(kind, "spectrum") == 0 || strcmp(kind, "color") == 0 || strcmp(kind, "rgb") == 0)
        is_float = false;
    else
        return cv_fail(err, "%s:%d:%d: texture \"%s\": type must be \"float\" or \"spectrum\", not \"%s\"",
                       loc->file, loc->line, loc->col, name, kind);
    CvTexture t;
    tex_init(&t, CV_TEX_CONSTANT);
    if (strcmp(cls, "imagemap") == 0) {
        const char *file = cv_params_string(ps, "filename", NULL);
        if (!file)
            return cv_fail(err, "%s:%d:%d: imagemap \"%s\" has no filename", loc->file, loc->line,
                           loc->col, name);
        /* v4 "encoding" (sRGB default for 8-bit), v3 "gamma" (bool) */
        bool srgb = true, v4 = false;
        const char *enc = cv_params_string(ps, "encoding", NULL);
        if (enc) {
            v4 = true;
            if (strcmp(enc, "linear") == 0)
                srgb = false;
            else if (strcmp(enc, "sRGB") != 0 &&
                     !cv_b_warn(b, err, loc, "encoding \"%s\" read as sRGB", enc))
                return false;
        } else {
            struct cv_param *g = cv_params_find(ps, "gamma");
            if (g && g->type == CV_PARAM_BOOL)
                srgb = g->nums[0] != 0;
            else if (g)
                g->used = false;
            /* pbrt-v3 decodes 8-bit PNG/TGA as sRGB unless gamma is false */
        }
        int img = v4 ? cv_b_image_texture_v4(b, file, dir, srgb, "encoding \"linear\" of", loc, err)
                     : cv_b_image_texture(b, file, dir, srgb, loc, err);
        if (img >= 0 && is_float && (img = float_image(b, img, err)) < 0)
            cv_error_prefix(err, "%s:%d:%d: image \"%s\"", loc->file, loc->line, loc->col, file);
        if (img < 0)
            return false;
        t = b->s->textures[img];
        double sc = cv_params_float(ps, "scale", 1);
        t.scale = (float)sc;
        if (cv_params_bool(ps, "invert", false))
            t.flags |= CV_TEXF_INVERT;
        const char *wrap = cv_params_string(ps, "wrap", "repeat");
        if (strcmp(wrap, "clamp") == 0)
            t.flags |= CV_TEXF_WRAP_CLAMP;
        else if (strcmp(wrap, "black") == 0)
            t.flags |= CV_TEXF_WRAP_BLACK;
        else if (strcmp(wrap, "repeat") != 0 &&
                 !cv_b_warn(b, err, loc, "wrap mode \"%s\" unknown; repeat used", wrap))
            return false;
        const char *filter = cv_params_string(ps, "filter", "bilinear");
        bool trilinear = cv_params_bool(ps, "trilinear", false);
        if ((strcmp(filter, "bilinear") == 0 || strcmp(filter, "point") == 0) && !trilinear &&
            cv_params_find(ps, "filter"))
            t.flags |= CV_TEXF_BILERP;
        cv_params_float(ps, "maxanisotropy", 8);
        if (!uv_mapping(b, ps, &t, loc, err))
            return false;
    } else if (strcmp(cls, "constant") == 0) {
        if (!slot(b, ps, "value", is_float, 1, dir, &t.value_a, &t.tex_a, err))
            return false;
    } else if (strcmp(cls, "scale") == 0) {
        t.type = CV_TEX_SCALE;
        if (cv_params_find(ps, "tex1") || cv_params_find(ps, "tex2")) { /* v3 */
            if (!slot(b, ps, "tex1", is_float, 1, dir, &t.value_a, &t.tex_a, err) ||
                !slot(b, ps, "tex2", is_float, 1, dir, &t.value_b, &t.tex_b, err))
                return false;
        } else {
            if (!slot(b, ps, "tex", is_float, 1, dir, &t.value_a, &t.tex_a, err) ||
                !slot(b, ps, "scale", true, 1, dir, &t.value_b, &t.tex_b, err))
                return false;
        }
    } else if (strcmp(cls, "mix") == 0) {
        t.type = CV_TEX_MIX;
        double amount = 0.5;
        if (!slot(b, ps, "tex1", is_float, 0, dir, &t.value_a, &t.tex_a, err) ||
            !slot(b, ps, "tex2", is_float, 1, dir, &t.value_b, &t.tex_b, err) ||
            !cv_b_float_tex(b, ps, "amount", &amount, &t.amount_tex, err))
            return false;
        t.amount = (float)amount;
    } else if (strcmp(cls, "checkerboard") == 0) {
        t.type = CV_TEX_CHECKERBOARD;
        if (!slot(b, ps, "tex1", is_float, 1, dir, &t.value_a, &t.tex_a, err) ||
            !slot(b, ps, "tex2", is_float, 0, dir, &t.value_b, &t.tex_b, err))
            return false;
        if (cv_params_int(ps, "dimension", 2) != 2 &&
            !cv_b_warn(b, err, loc, "3D checkerboard is not supported; 2D used"))
            return false;
        cv_params_string(ps, "aamode", NULL);
        if (!uv_mapping(b, ps, &t, loc, err))
            return false;
    } else {
        if (!cv_b_warn(b, err, loc, "texture class \"%s\" is not supported; constant 0.5 used", cls))
            return false;
        for (size_t i = 0; i < ps->n; i++)
            ps->v[i].used = true;
        t.value_a = (cv_vec4){0.5f, 0.5f, 0.5f, 1};
    }
    if (is_float)
        t.flags |= CV_TEXF_FLOAT;
    int depth = nesting(b->s, &t);
    if (depth > CV_TEX_MAX_NESTING &&
        !cv_b_warn(b, err, loc, "texture \"%s\" nests composite textures %d deep: the renderer "
                   "evaluates %d, and a composite operand deeper reads as its constant value",
                   name, depth, CV_TEX_MAX_NESTING))
        return false;
    int idx = cv_b_add_texture(b, &t);
    if (is_float)
        cv_b_set_named(&b->float_tex, &b->n_float_tex, &b->cap_float_tex, name, idx);
    else
        cv_b_set_named(&b->spec_tex, &b->n_spec_tex, &b->cap_spec_tex, name, idx);
    return true;
}
