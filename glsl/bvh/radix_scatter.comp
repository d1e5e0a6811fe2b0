#version 450
// glsl/bvh/radix_scatter.comp: last step of one 4-bit radix sort pass. Each
// workgroup walks its block's tiles of 1024 keys in order, carrying the
// block's next slot per digit (from the scanned counts of radix_count.comp
// and radix_spine.comp). In a tile, each invocation owns KEYS consecutive
// keys and counts their digits, 16 bits per digit packed into two uvec4;
// a scan of those counts across the group gives every key its stable rank
// among equal digits, and so its slot.
// The keys go straight to their slots. Staging the sorted tile in shared
// memory to write whole lines took 28 KiB of it, which (as treelet.comp
// found) leaves room for one group per multiprocessor on an H100: 0.39 ms
// for the 8 passes over 1 M keys, against 0.30 ms for direct writes from
// 256 invocations of 4 keys (16 KiB; 128 of 8 keys, 8 KiB: 0.34 ms; 64 of
// 16: 0.36 ms).
// With KEY64 a key is two words (low, high) and u_shift runs over 0..63.
#include "shared/bindings.h"

#define THREADS 256
#define KEYS (1024 / THREADS)
layout(local_size_x = THREADS) in;

layout(std430, binding = CV_BIND_STAGE0) readonly buffer Keys { uint keys[]; };
layout(std430, binding = CV_BIND_STAGE0 + 1) readonly buffer Vals { uint vals[]; };
layout(std430, binding = CV_BIND_STAGE0 + 2) readonly buffer Counts { uint counts[]; };
layout(std430, binding = CV_BIND_STAGE0 + 3) writeonly buffer KeysOut { uint keys_out[]; };
layout(std430, binding = CV_BIND_STAGE0 + 4) writeonly buffer ValsOut { uint vals_out[]; };

uniform uint u_n;
uniform uint u_shift;
uniform uint u_block_tiles;

shared uvec4 s_lo[2][THREADS], s_hi[2][THREADS];
// Per digit: the block's next output slot, and the current tile's count.
shared uint s_base[16], s_count[16];

#include "radix_digits.glsl"

void main()
{
    uint block = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint block_keys = u_block_tiles * 1024u;
    uint n_blocks = (u_n + block_keys - 1u) / block_keys;
    if (block >= n_blocks)
        return;
    uint l = gl_LocalInvocationID.x;
    if (l < 16u)
        s_base[l] = counts[l * n_blocks + block];
    for (uint tile = block * u_block_tiles; tile < (block + 1u) * u_block_tiles; tile++) {
        uint first = tile * 1024u;
        if (first >= u_n)
            break;
#ifdef KEY64
        uvec2 key[KEYS];
#else
        uint key[KEYS];
#endif
        // dig is 16 (no key) or the digit | the key's rank among this
        // invocation's keys of that digit << 8.
        uint val[KEYS], dig[KEYS];
        uvec4 lo = uvec4(0u), hi = uvec4(0u);
        for (uint k = 0u; k < uint(KEYS); k++) {
            uint i = first + l * uint(KEYS) + k;
            dig[k] = 16u;
            if (i < u_n) {
#ifdef KEY64
                key[k] = uvec2(keys[2u * i], keys[2u * i + 1u]);
                uint d = (key[k][u_shift >> 5] >> (u_shift & 31u)) & 15u;
#else
                key[k] = keys[i];
                uint d = (key[k] >> u_shift) & 15u;
#endif
                val[k] = vals[i];
                dig[k] = d | (cv_radix_field(d < 8u ? lo : hi, d) << 8);
                cv_radix_count(d, lo, hi);
            }
        }
        // Inclusive Hillis-Steele scan of the packed counts, ping-ponging.
        uint src = 0u;
        s_lo[0][l] = lo;
        s_hi[0][l] = hi;
        barrier();
        for (uint off = 1u; off < uint(THREADS); off <<= 1) {
            uvec4 a = s_lo[src][l], b = s_hi[src][l];
            if (l >= off) {
                a += s_lo[src][l - off];
                b += s_hi[src][l - off];
            }
            s_lo[1u - src][l] = a;
            s_hi[1u - src][l] = b;
            src = 1u - src;
            barrier();
        }
        if (l < 16u)
            s_count[l] = cv_radix_field(l < 8u ? s_lo[src][THREADS - 1] : s_hi[src][THREADS - 1], l);
        // Exclusive prefix of this invocation = inclusive minus its own.
        uvec4 plo = s_lo[src][l] - lo, phi = s_hi[src][l] - hi;
        for (uint k = 0u; k < uint(KEYS); k++) {
            uint d = dig[k] & 0xffu;
            if (d >= 16u)
                continue;
            uint dst = s_base[d] + cv_radix_field(d < 8u ? plo : phi, d) + (dig[k] >> 8);
#ifdef KEY64
            keys_out[2u * dst] = key[k].x;
            keys_out[2u * dst + 1u] = key[k].y;
#else
            keys_out[dst] = key[k];
#endif
            vals_out[dst] = val[k];
        }
        barrier();
        // The next tile's barriers order this update before its use.
        if (l < 16u)
            s_base[l] += s_count[l];
    }
}
