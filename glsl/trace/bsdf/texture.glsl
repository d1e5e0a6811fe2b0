// glsl/trace/bsdf/texture.glsl: texture evaluation over the scene's texture
// table (needs textures[] and texels[]: see material_buffers.glsl).
//
// Image textures: texel (0,0) is the image's top-left; lookups use
// (s, t) = (u', 1 - v') with u' = su*u + du, v' = sv*v + dv (pbrt's
// convention that v = 0 is the bottom of the image). Filtering is bilinear
// within a mip level and linear between levels (trilinear) for a given
// level of detail `lod` (0 = full resolution); CV_TEXF_BILERP pins lod to 0.
// GLSL has no recursion: composite textures (scale, mix, checkerboard) may
// nest two deep; deeper operands read as their constant value.
#ifndef CV_BSDF_TEXTURE_GLSL
#define CV_BSDF_TEXTURE_GLSL

#include "../../lib/constants.glsl"

vec4 cv_texel_fetch(uint base, uint w, uint h, ivec2 xy, uint flags)
{
    if ((flags & CV_TEXF_WRAP_BLACK) != 0u && (xy.x < 0 || xy.y < 0 || xy.x >= int(w) || xy.y >= int(h)))
        return vec4(0.0);
    if ((flags & (CV_TEXF_WRAP_CLAMP | CV_TEXF_WRAP_BLACK)) != 0u) {
        xy = clamp(xy, ivec2(0), ivec2(int(w) - 1, int(h) - 1));
    } else {
        xy.x = int(uint(xy.x % int(w) + int(w)) % w);
        xy.y = int(uint(xy.y % int(h) + int(h)) % h);
    }
    uvec2 t = texels[base + uint(xy.y) * w + uint(xy.x)];
    return vec4(unpackHalf2x16(t.x), unpackHalf2x16(t.y));
}

// Bilinear lookup at (s, t) in [0,1]^2 (t = 0: top row) of one mip level.
vec4 cv_image_level(CvTexture tx, uint level, vec2 st)
{
    uint base = tx.offset, w = max(tx.width, 1u), h = max(tx.height, 1u);
    for (uint l = 0u; l < level; l++) {
        base += w * h;
        w = max(w / 2u, 1u);
        h = max(h / 2u, 1u);
    }
    vec2 p = st * vec2(w, h) - 0.5;
    vec2 f = p - floor(p);
    ivec2 i = ivec2(floor(p));
    vec4 a = cv_texel_fetch(base, w, h, i, tx.flags);
    vec4 b = cv_texel_fetch(base, w, h, i + ivec2(1, 0), tx.flags);
    vec4 c = cv_texel_fetch(base, w, h, i + ivec2(0, 1), tx.flags);
    vec4 d = cv_texel_fetch(base, w, h, i + ivec2(1, 1), tx.flags);
    return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}

vec4 cv_image_lookup(CvTexture tx, vec2 st, float lod)
{
    if ((tx.flags & CV_TEXF_BILERP) != 0u || tx.levels <= 1u || !(lod > 0.0))
        return cv_image_level(tx, 0u, st);
    lod = min(lod, float(tx.levels - 1u));
    uint l0 = uint(floor(lod));
    float f = lod - float(l0);
    vec4 a = cv_image_level(tx, l0, st);
    return f > 0.0 ? mix(a, cv_image_level(tx, min(l0 + 1u, tx.levels - 1u), st), f) : a;
}

vec2 cv_tex_st(CvTexture tx, vec2 uv)
{
    vec2 m = tx.uv_map.xy * uv + tx.uv_map.zw;
    return vec2(m.x, 1.0 - m.y);
}

vec4 cv_tex_finish(CvTexture tx, vec4 v)
{
    if ((tx.flags & CV_TEXF_FLOAT) != 0u && tx.type == CV_TEX_IMAGE)
        v = vec4((v.r + v.g + v.b) / 3.0);
    v *= tx.scale;
    if ((tx.flags & CV_TEXF_INVERT) != 0u)
        v = vec4(1.0) - v;
    return v;
}

// Constants and images only.
vec4 cv_tex_leaf(int id, vec4 fallback, vec2 uv, float lod)
{
    if (id < 0)
        return fallback;
    CvTexture tx = textures[id];
    if (tx.type == CV_TEX_IMAGE)
        return cv_tex_finish(tx, cv_image_lookup(tx, cv_tex_st(tx, uv), lod));
    if (tx.type == CV_TEX_CONSTANT)
        return cv_tex_finish(tx, tx.value_a);
    return fallback;
}

// One composite level whose operands are leaves. `kind` selects how the
// operand a/b values are combined.
vec4 cv_tex_combine(CvTexture tx, vec4 a, vec4 b, float amount, vec2 uv)
{
    if (tx.type == CV_TEX_SCALE)
        return cv_tex_finish(tx, a * b);
    if (tx.type == CV_TEX_MIX)
        return cv_tex_finish(tx, mix(a, b, amount));
    if (tx.type == CV_TEX_CHECKERBOARD) {
        vec2 m = tx.uv_map.xy * uv + tx.uv_map.zw;
        int c = int(floor(m.x)) + int(floor(m.y));
        return cv_tex_finish(tx, (c & 1) == 0 ? a : b);
    }
    if (tx.type == CV_TEX_CONSTANT)
        return cv_tex_finish(tx, tx.value_a);
    return a;
}

vec4 cv_tex_level1(int id, vec4 fallback, vec2 uv, float lod)
{
    if (id < 0)
        return fallback;
    CvTexture tx = textures[id];
    if (tx.type == CV_TEX_IMAGE || tx.type == CV_TEX_CONSTANT)
        return cv_tex_leaf(id, fallback, uv, lod);
    vec4 a = cv_tex_leaf(tx.tex_a, tx.value_a, uv, lod);
    vec4 b = cv_tex_leaf(tx.tex_b, tx.value_b, uv, lod);
    float amt = cv_tex_leaf(tx.amount_tex, vec4(tx.amount), uv, lod).x;
    return cv_tex_combine(tx, a, b, amt, uv);
}

// Evaluates texture `id` at uv; `fallback` (the material's constant) when
// id < 0. Float textures return their value in every channel.
vec4 cv_tex_eval(int id, vec4 fallback, vec2 uv, float lod)
{
    if (id < 0)
        return fallback;
#ifdef CV_TEX_DISABLE
    return fallback;
#endif
    CvTexture tx = textures[id];
    if (tx.type == CV_TEX_IMAGE || tx.type == CV_TEX_CONSTANT)
        return cv_tex_leaf(id, fallback, uv, lod);
    vec4 a = cv_tex_level1(tx.tex_a, tx.value_a, uv, lod);
    vec4 b = cv_tex_level1(tx.tex_b, tx.value_b, uv, lod);
    float amt = cv_tex_level1(tx.amount_tex, vec4(tx.amount), uv, lod).x;
    return cv_tex_combine(tx, a, b, amt, uv);
}

#endif
