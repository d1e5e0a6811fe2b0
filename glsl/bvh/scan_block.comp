#version 450
// glsl/bvh/scan_block.comp: exclusive prefix sum of uints, in place, over
// tiles of 1024 (256 threads x 4); each tile's total goes to sums[tile] so
// the host can scan the totals and add them back (scan_add.comp).
#include "shared/bindings.h"

layout(local_size_x = 256) in;

layout(std430, binding = CV_BIND_SCAN_DATA) buffer Data { uint data[]; };
layout(std430, binding = CV_BIND_SCAN_SUMS) writeonly buffer Sums { uint sums[]; };

uniform uint u_n;

shared uint s[2][256];

void main()
{
    uint tile = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    if (tile >= (u_n + 1023u) / 1024u)
        return;
    uint l = gl_LocalInvocationID.x;
    uint base = tile * 1024u + l * 4u;
    uint v[4];
    uint total = 0;
    for (uint k = 0; k < 4; k++) {
        v[k] = base + k < u_n ? data[base + k] : 0u;
        total += v[k];
    }
    uint src = 0;
    s[0][l] = total;
    barrier();
    for (uint off = 1; off < 256; off <<= 1) {
        uint a = s[src][l];
        if (l >= off)
            a += s[src][l - off];
        s[1 - src][l] = a;
        src = 1 - src;
        barrier();
    }
    uint run = s[src][l] - total;
    for (uint k = 0; k < 4; k++) {
        if (base + k < u_n)
            data[base + k] = run;
        run += v[k];
    }
    if (l == 255)
        sums[tile] = s[src][255];
}
