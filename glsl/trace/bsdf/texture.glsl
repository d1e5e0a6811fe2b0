// glsl/trace/bsdf/texture.glsl: texture evaluation over the scene's texture
// table (needs textures[] and texels[]: see material_buffers.glsl).
//
// Image textures: texel (0,0) is the image's top-left; lookups use
// (s, t) = (u', 1 - v') with u' = su*u + du, v' = sv*v + dv (pbrt's
// convention that v = 0 is the bottom of the image). Filtering is bilinear
// within a mip level and linear between levels (trilinear) for a given
// level of detail `lod` (0 = full resolution); CV_TEXF_BILERP pins lod to 0.
// GLSL has no recursion: composite textures (scale, mix, checkerboard) may
// nest CV_TEX_MAX_NESTING (two) deep; deeper operands read as their
// constant value (the importer warns).
#ifndef CV_BSDF_TEXTURE_GLSL
#define CV_BSDF_TEXTURE_GLSL

#include "../../lib/constants.glsl"

vec4 cv_texel_fetch(uint base, uint w, uint h, ivec2 xy, uint flags)
{
    if ((flags & CV_TEXF_WRAP_BLACK) != 0u && (xy.x < 0 || xy.y < 0 || xy.x >= int(w) || xy.y >= int(h)))
        return vec4(0.0);
    if ((flags & CV_TEXF_WRAP_OCTAHEDRAL) != 0u) {
        // pbrt-v4's octahedral sphere wrap: the point just across an edge
        // of the equal-area square is the one mirrored about that edge's
        // midpoint (a bilinear lookup reaches one texel out at most)
        if (xy.x < 0 || xy.x >= int(w)) {
            xy.x = xy.x < 0 ? -1 - xy.x : 2 * int(w) - 1 - xy.x;
            xy.y = int(h) - 1 - xy.y;
        }
        if (xy.y < 0 || xy.y >= int(h)) {
            xy.y = xy.y < 0 ? -1 - xy.y : 2 * int(h) - 1 - xy.y;
            xy.x = int(w) - 1 - xy.x;
        }
        xy = clamp(xy, ivec2(0), ivec2(int(w) - 1, int(h) - 1));
    } else if ((flags & CV_TEXF_WRAP_LATLONG) != 0u) {
        xy.x = int(uint(xy.x % int(w) + int(w)) % w);
        xy.y = clamp(xy.y, 0, int(h) - 1);
    } else if ((flags & (CV_TEXF_WRAP_CLAMP | CV_TEXF_WRAP_BLACK)) != 0u) {
        xy = clamp(xy, ivec2(0), ivec2(int(w) - 1, int(h) - 1));
    } else {
        xy.x = int(uint(xy.x % int(w) + int(w)) % w);
        xy.y = int(uint(xy.y % int(h) + int(h)) % h);
    }
    uint at = base + (uint(xy.y) * w + uint(xy.x)) * CV_TEX_SLOTS(flags);
    uvec2 t = texels[at];
    if ((flags & CV_TEXF_RGBA32F) != 0u)
        return vec4(uintBitsToFloat(t), uintBitsToFloat(texels[at + 1u]));
    return vec4(unpackHalf2x16(t.x), unpackHalf2x16(t.y));
}

// Bilinear lookups at (s, t) in [0,1]^2 (t = 0: top row) in up to two mip
// levels, blended by the fraction of lod. Written as loops so that the
// fetch is compiled once.
vec4 cv_image_lookup(CvTexture tx, vec2 st, float lod)
{
    bool mip = (tx.flags & CV_TEXF_BILERP) == 0u && tx.levels > 1u && lod > 0.0;
    lod = mip ? min(lod, float(tx.levels - 1u)) : 0.0;
    uint l0 = uint(floor(lod));
    float lf = lod - float(l0);
    int n_levels = lf > 0.0 ? 2 : 1;
    uint base = tx.offset, w = max(tx.width, 1u), h = max(tx.height, 1u);
    for (uint l = 0u; l < l0; l++) {
        base += w * h * CV_TEX_SLOTS(tx.flags);
        w = max(w / 2u, 1u);
        h = max(h / 2u, 1u);
    }
    vec4 result = vec4(0.0);
    for (int level = 0; level < n_levels; level++) {
        vec2 p = st * vec2(w, h) - 0.5;
        vec2 f = p - floor(p);
        ivec2 i = ivec2(floor(p));
        vec4 sum = vec4(0.0);
        for (int c = 0; c < 4; c++) {
            ivec2 o = ivec2(c & 1, c >> 1);
            vec2 wt = mix(1.0 - f, f, vec2(o));
            sum += wt.x * wt.y * cv_texel_fetch(base, w, h, i + o, tx.flags);
        }
        result += (level == 0 ? 1.0 - lf : lf) * sum;
        base += w * h * CV_TEX_SLOTS(tx.flags);
        w = max(w / 2u, 1u);
        h = max(h / 2u, 1u);
    }
    return result;
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

bool cv_tex_is_leaf(uint type) { return type == CV_TEX_IMAGE || type == CV_TEX_CONSTANT; }

vec4 cv_tex_leaf(CvTexture tx, vec2 uv, float lod)
{
    if (tx.type == CV_TEX_IMAGE)
        return cv_tex_finish(tx, cv_image_lookup(tx, cv_tex_st(tx, uv), lod));
    return cv_tex_finish(tx, tx.value_a);
}

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
    return a;
}

// Evaluates texture `id` at uv; `fallback` (the material's constant) when
// id < 0. Float textures return their value in every channel. The host
// defines CV_NO_TEXTURES for a scene without textures, so that the stage
// kernels carry none of this code (every id is -1 there).
// The tree (the root, its operands a/b/amount, their operands) is walked in
// post-order by one loop of at most 13 steps, so the leaf lookup is compiled
// once (llvmpipe's compile time grows fast with inlined copies). Step k < 12
// is operand j = k % 4 of the root's operand c = k / 4 (j = 3: that operand
// itself); step 12 is the root. Values live in named variables written by
// selects, never in an array indexed by the step: a dynamically indexed
// array is placed in local memory, which costs every shade kernel occupancy.
vec4 cv_tex_eval(int id, vec4 fallback, vec2 uv, float lod)
{
#ifdef CV_NO_TEXTURES
    return fallback;
#else
    if (id < 0)
        return fallback;
    CvTexture root = textures[id];
    // operands of the root (ca, cb, camt) and of the operand being walked
    // (ga, gb, gamt); kid: the operand being walked
    vec4 ca = root.value_a, cb = root.value_b, camt = vec4(root.amount);
    vec4 ga = vec4(0.0), gb = vec4(0.0), gamt = vec4(0.0);
    CvTexture kid = root;
    int kid_id = -1;
    vec4 result = fallback;
    for (int k = cv_tex_is_leaf(root.type) ? 12 : 0; k < 13; k++) {
        int c = k >> 2, j = k & 3;
        int t;
        vec4 v;
        if (k == 12) {
            t = id;
            v = fallback;
        } else if (j == 0) {
            // a new operand of the root: its own operands come first
            kid_id = c == 0 ? root.tex_a : (c == 1 ? root.tex_b : root.amount_tex);
            if (kid_id >= 0)
                kid = textures[kid_id];
            if (kid_id < 0 || cv_tex_is_leaf(kid.type)) {
                k += 2;  // no operands of its own: on to the operand itself
                continue;
            }
            t = kid.tex_a;
            v = kid.value_a;
        } else if (j == 3) {
            t = kid_id;
            v = c == 0 ? root.value_a : (c == 1 ? root.value_b : vec4(root.amount));
        } else {
            t = j == 1 ? kid.tex_b : kid.amount_tex;
            v = j == 1 ? kid.value_b : vec4(kid.amount);
        }
        if (t >= 0) {
            CvTexture tx = textures[t];
            bool depth2 = k != 12 && j != 3;  // an operand's operand
            if (cv_tex_is_leaf(tx.type))
                v = cv_tex_leaf(tx, uv, lod);
            else if (depth2)
                v = tx.value_a;  // nested deeper than two composites
            else
                v = cv_tex_combine(tx, k == 12 ? ca : ga, k == 12 ? cb : gb, k == 12 ? camt.x : gamt.x, uv);
        }
        if (k == 12)
            result = v;
        else if (j == 3) {
            if (c == 0)
                ca = v;
            else if (c == 1)
                cb = v;
            else
                camt = v;
        } else if (j == 0)
            ga = v;
        else if (j == 1)
            gb = v;
        else
            gamt = v;
    }
    return result;
#endif
}

#endif
