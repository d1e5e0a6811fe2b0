#version 450
// glsl/bvh/radix_spine.comp: exclusive prefix sum, in place, of the digit
// counts of one radix sort pass (radix_count.comp), in a single workgroup:
// there are 16 per block and the host keeps the blocks to 2048, so one
// dispatch replaces a multi-level scan. Each invocation sums a run of up to
// RUN4 uvec4 (4 * RUN4 consecutive counts), the runs' totals are scanned
// across the group, and each invocation writes its run's prefixes. The
// run's loads are unrolled so they are all in flight at once (a loop that
// waited on each cost ~25 us per pass on an H100), and they are uvec4
// loads: with one uint per load, each load of a subgroup touched 32 lines
// on this single multiprocessor, and the spine took 26 us per pass at 1 M
// keys (8 passes: 0.21 of the sort's 0.53 ms; 13 us with uvec4).
#include "shared/bindings.h"

layout(local_size_x = 1024) in;

// The count array, 16 * blocks uints: always a whole number of uvec4.
layout(std430, binding = CV_BIND_STAGE0 + 2) buffer Counts { uvec4 counts4[]; };

uniform uint u_count;  // at most 1024 * 4 * RUN4, a multiple of 16

#define RUN4 8

shared uint s_sum[2][1024];

void main()
{
    uint l = gl_LocalInvocationID.x;
    uint n4 = u_count / 4u;
    uint per = (n4 + 1023u) / 1024u;
    uint begin = l * per;
    uvec4 v[RUN4];
    uint total = 0u;
    for (uint k = 0u; k < uint(RUN4); k++) {
        v[k] = k < per && begin + k < n4 ? counts4[begin + k] : uvec4(0u);
        total += v[k].x + v[k].y + v[k].z + v[k].w;
    }
    uint src = 0u;
    s_sum[0][l] = total;
    barrier();
    for (uint off = 1u; off < 1024u; off <<= 1) {
        uint a = s_sum[src][l];
        if (l >= off)
            a += s_sum[src][l - off];
        s_sum[1u - src][l] = a;
        src = 1u - src;
        barrier();
    }
    uint run = s_sum[src][l] - total;
    for (uint k = 0u; k < uint(RUN4); k++) {
        uvec4 x = v[k];
        if (k < per && begin + k < n4)
            counts4[begin + k] = uvec4(run, run + x.x, run + x.x + x.y, run + x.x + x.y + x.z);
        run += x.x + x.y + x.z + x.w;
    }
}
