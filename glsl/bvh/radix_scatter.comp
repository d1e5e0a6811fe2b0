#version 450
// glsl/bvh/radix_scatter.comp: second step of one 4-bit radix sort pass.
// Each thread owns 4 consecutive keys of the tile; per-digit counts are
// packed 16 bits each into two uvec4 (a tile holds at most 1024 keys, so no
// field overflows) and scanned across the workgroup, which gives every key
// its stable rank among equal digits. Destination = scanned tile base + rank.
// With KEY64 a key is two words (low, high) and u_shift runs over 0..63.
#include "shared/bindings.h"

layout(local_size_x = 256) in;

layout(std430, binding = CV_BIND_STAGE0) readonly buffer Keys { uint keys[]; };
layout(std430, binding = CV_BIND_STAGE0 + 1) readonly buffer Vals { uint vals[]; };
layout(std430, binding = CV_BIND_STAGE0 + 2) readonly buffer Hist { uint hist[]; };
layout(std430, binding = CV_BIND_STAGE0 + 3) writeonly buffer KeysOut { uint keys_out[]; };
layout(std430, binding = CV_BIND_STAGE0 + 4) writeonly buffer ValsOut { uint vals_out[]; };

uniform uint u_n;
uniform uint u_shift;

shared uvec4 s_lo[2][256];
shared uvec4 s_hi[2][256];
shared uint s_base[16];

uvec4 one_hot(uint d)
{
    // 16-bit field d&7 of a uvec4 (two fields per component).
    uvec4 v = uvec4(0);
    v[(d & 7u) >> 1] = 1u << (16u * (d & 1u));
    return v;
}

uint field(uvec4 v, uint d)
{
    return (v[(d & 7u) >> 1] >> (16u * (d & 1u))) & 0xffffu;
}

void main()
{
    uint tile = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint n_tiles = (u_n + 1023u) / 1024u;
    if (tile >= n_tiles)
        return;
    uint l = gl_LocalInvocationID.x;
#ifdef KEY64
    uvec2 key[4];
#else
    uint key[4];
#endif
    uint val[4], dig[4];
    uvec4 lo = uvec4(0), hi = uvec4(0);
    for (uint k = 0; k < 4; k++) {
        uint i = tile * 1024u + l * 4u + k;
        dig[k] = 16u;
        val[k] = 0u;
#ifdef KEY64
        key[k] = uvec2(0u);
        if (i < u_n) {
            key[k] = uvec2(keys[2u * i], keys[2u * i + 1u]);
            dig[k] = (key[k][u_shift >> 5] >> (u_shift & 31u)) & 15u;
#else
        key[k] = 0u;
        if (i < u_n) {
            key[k] = keys[i];
            dig[k] = (key[k] >> u_shift) & 15u;
#endif
            val[k] = vals[i];
            if (dig[k] < 8u)
                lo += one_hot(dig[k]);
            else
                hi += one_hot(dig[k]);
        }
    }
    if (l < 16)
        s_base[l] = hist[l * n_tiles + tile];
    // Inclusive Hillis-Steele scan of the packed counts, ping-ponging.
    uint src = 0;
    s_lo[0][l] = lo;
    s_hi[0][l] = hi;
    barrier();
    for (uint off = 1; off < 256; off <<= 1) {
        uvec4 a = s_lo[src][l], b = s_hi[src][l];
        if (l >= off) {
            a += s_lo[src][l - off];
            b += s_hi[src][l - off];
        }
        s_lo[1 - src][l] = a;
        s_hi[1 - src][l] = b;
        src = 1 - src;
        barrier();
    }
    // Exclusive prefix of this thread = inclusive minus own.
    uvec4 plo = s_lo[src][l] - lo, phi = s_hi[src][l] - hi;
    uint seen[4] = uint[4](0u, 0u, 0u, 0u);
    for (uint k = 0; k < 4; k++) {
        uint d = dig[k];
        if (d >= 16u)
            continue;
        uint before = 0;
        for (uint j = 0; j < k; j++)
            before += dig[j] == d ? 1u : 0u;
        uint rank = (d < 8u ? field(plo, d) : field(phi, d)) + before;
        uint dst = s_base[d] + rank;
#ifdef KEY64
        keys_out[2u * dst] = key[k].x;
        keys_out[2u * dst + 1u] = key[k].y;
#else
        keys_out[dst] = key[k];
#endif
        vals_out[dst] = val[k];
    }
}
