#version 450
// glsl/bvh/radix_spine.comp: exclusive prefix sum, in place, of the digit
// counts of one radix sort pass (radix_count.comp), in a single workgroup:
// there are 16 per block and the host keeps the blocks to RUN * 64, so one
// dispatch replaces a multi-level scan. Each invocation sums a run of up to
// RUN consecutive counts, the runs' totals are scanned across the group, and
// each invocation writes its run's prefixes. The run's loads are unrolled so
// they are all in flight at once: a loop that waited on each cost ~25 us per
// pass on an H100.
#include "shared/bindings.h"

layout(local_size_x = 1024) in;

layout(std430, binding = CV_BIND_STAGE0 + 2) buffer Counts { uint counts[]; };

uniform uint u_count;  // at most 1024 * RUN

#define RUN 32

shared uint s_sum[2][1024];

void main()
{
    uint l = gl_LocalInvocationID.x;
    uint per = (u_count + 1023u) / 1024u;
    uint begin = l * per;
    uint v[RUN];
    uint total = 0u;
    for (uint k = 0u; k < uint(RUN); k++) {
        v[k] = k < per && begin + k < u_count ? counts[begin + k] : 0u;
        total += v[k];
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
    for (uint k = 0u; k < uint(RUN); k++) {
        if (k < per && begin + k < u_count)
            counts[begin + k] = run;
        run += v[k];
    }
}
