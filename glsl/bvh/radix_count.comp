#version 450
// glsl/bvh/radix_count.comp: first step of one radix sort pass. Each
// workgroup counts the digits (RADIX_BITS wide) of its block (u_block_tiles
// tiles of 1024 keys) in a shared histogram and writes it digit-major
// (counts[digit * n_blocks + block]), so that a scan of each digit's row
// (radix_spine.comp) and of the digits' totals yields every block's first
// slot per digit, stably. Shared atomics on one counter serialise when many
// keys share a digit, as the high digits of Morton codes do, so each
// invocation adds runs of equal digits among its own keys in one atomic: a
// histogram does not care which keys a run gathers.
#include "shared/bindings.h"

#define THREADS 256
layout(local_size_x = THREADS) in;

layout(std430, binding = CV_BIND_SORT_KEYS) readonly buffer Keys { uint keys[]; };
layout(std430, binding = CV_BIND_SORT_COUNTS) writeonly buffer Counts { uint counts[]; };

uniform uint u_n;
uniform uint u_shift;
uniform uint u_block_tiles;

#include "radix_digits.glsl"

shared uint s_hist[RADIX_BINS];

void main()
{
    uint block = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint block_keys = u_block_tiles * 1024u;
    uint n_blocks = (u_n + block_keys - 1u) / block_keys;
    if (block >= n_blocks)
        return;
    uint l = gl_LocalInvocationID.x;
    for (uint d = l; d < RADIX_BINS; d += uint(THREADS))
        s_hist[d] = 0u;
    barrier();
    uint end = min((block + 1u) * block_keys, u_n);
    uint run_d = 0u, run = 0u;
    for (uint i = block * block_keys + l; i < end; i += uint(THREADS)) {
#ifdef KEY64
        uint d = cv_radix_digit(uvec2(keys[2u * i], keys[2u * i + 1u]), u_shift);
#else
        uint d = cv_radix_digit(keys[i], u_shift);
#endif
        if (d != run_d && run > 0u) {
            atomicAdd(s_hist[run_d], run);
            run = 0u;
        }
        run_d = d;
        run++;
    }
    if (run > 0u)
        atomicAdd(s_hist[run_d], run);
    barrier();
    for (uint d = l; d < RADIX_BINS; d += uint(THREADS))
        counts[d * n_blocks + block] = s_hist[d];
}
