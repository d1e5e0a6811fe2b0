#version 450
// glsl/bvh/radix_count.comp: first step of one 4-bit radix sort pass. Each
// workgroup counts the digits of its block (u_block_tiles tiles of 1024
// keys) and writes the 16 counts digit-major (counts[digit * n_blocks +
// block]), so that one exclusive scan of the whole array (radix_spine.comp)
// yields every block's first slot per digit, stably. Counts are kept per
// invocation, 16 bits per digit, and summed over the group in shared memory:
// shared atomics on 16 counters serialise when a tile's keys share a digit,
// as the high digits of Morton codes mostly do. 128 invocations keep that
// sum to 4 KiB of shared memory, which bounds the groups per
// multiprocessor (see treelet.comp).
// With KEY64 a key is two words (low, high) and u_shift runs over 0..63.
#include "shared/bindings.h"

#define THREADS 128
layout(local_size_x = THREADS) in;

layout(std430, binding = CV_BIND_STAGE0) readonly buffer Keys { uint keys[]; };
layout(std430, binding = CV_BIND_STAGE0 + 2) writeonly buffer Counts { uint counts[]; };

uniform uint u_n;
uniform uint u_shift;
uniform uint u_block_tiles;  // at most 63, so a block's counts fit 16 bits

shared uvec4 s_lo[THREADS], s_hi[THREADS];

#include "radix_digits.glsl"

void main()
{
    uint block = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint block_keys = u_block_tiles * 1024u;
    uint n_blocks = (u_n + block_keys - 1u) / block_keys;
    if (block >= n_blocks)
        return;
    uint l = gl_LocalInvocationID.x;
    uint end = min((block + 1u) * block_keys, u_n);
    uvec4 lo = uvec4(0u), hi = uvec4(0u);
    for (uint i = block * block_keys + l; i < end; i += uint(THREADS)) {
#ifdef KEY64
        uint w = keys[2u * i + (u_shift >> 5)];
#else
        uint w = keys[i];
#endif
        cv_radix_count((w >> (u_shift & 31u)) & 15u, lo, hi);
    }
    s_lo[l] = lo;
    s_hi[l] = hi;
    barrier();
    for (uint half_n = uint(THREADS) / 2u; half_n > 0u; half_n >>= 1) {
        if (l < half_n) {
            s_lo[l] += s_lo[l + half_n];
            s_hi[l] += s_hi[l + half_n];
        }
        barrier();
    }
    if (l < 16u)
        counts[l * n_blocks + block] = cv_radix_field(l < 8u ? s_lo[0] : s_hi[0], l);
}
