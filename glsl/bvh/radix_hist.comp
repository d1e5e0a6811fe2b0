#version 450
// glsl/bvh/radix_hist.comp: first step of one 4-bit radix sort pass. Each
// workgroup counts the digits of its tile of 1024 keys and writes the counts
// digit-major (hist[digit * n_tiles + tile]) so that one exclusive scan of
// the whole array yields every tile's scatter base, stably. With KEY64 a
// key is two words (low, high) and u_shift runs over 0..63.
#include "shared/bindings.h"

layout(local_size_x = 256) in;

layout(std430, binding = CV_BIND_STAGE0) readonly buffer Keys { uint keys[]; };
layout(std430, binding = CV_BIND_STAGE0 + 2) writeonly buffer Hist { uint hist[]; };

uniform uint u_n;
uniform uint u_shift;

shared uint s_count[16];

void main()
{
    uint tile = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint n_tiles = (u_n + 1023u) / 1024u;
    if (tile >= n_tiles)
        return;
    uint l = gl_LocalInvocationID.x;
    if (l < 16)
        s_count[l] = 0;
    barrier();
    for (uint k = 0; k < 4; k++) {
        uint i = tile * 1024u + k * 256u + l;
        if (i < u_n) {
#ifdef KEY64
            uint w = keys[2u * i + (u_shift >> 5)];
#else
            uint w = keys[i];
#endif
            atomicAdd(s_count[(w >> (u_shift & 31u)) & 15u], 1u);
        }
    }
    barrier();
    if (l < 16)
        hist[l * n_tiles + tile] = s_count[l];
}
