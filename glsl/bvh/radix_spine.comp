#version 450
// glsl/bvh/radix_spine.comp: middle step of one radix sort pass. Workgroup
// d scans row d of the digit-major block counts (radix_count.comp) in
// place, exclusively, and writes the row's total after the rows
// (counts[RADIX_BINS * n_blocks + d]); radix_scatter.comp scans those
// totals itself. One group per digit instead of one group for all rows:
// with 256 digits that is up to half a million counts. Each invocation
// sums a run of up to RUN consecutive counts, the runs' totals are scanned
// across the group, and each invocation writes its run's prefixes; the
// run's loads are unrolled so they are all in flight at once.
#include "shared/bindings.h"

#define THREADS 256
layout(local_size_x = THREADS) in;

layout(std430, binding = CV_BIND_SORT_COUNTS) buffer Counts { uint counts[]; };

uniform uint u_blocks;  // at most THREADS * RUN

#include "radix_digits.glsl"

#define RUN 8

shared uint s_sum[2][THREADS];

void main()
{
    uint d = gl_WorkGroupID.x;
    uint l = gl_LocalInvocationID.x;
    uint row = d * u_blocks;
    uint per = (u_blocks + uint(THREADS) - 1u) / uint(THREADS);
    uint begin = l * per;
    uint v[RUN];
    uint total = 0u;
    for (uint k = 0u; k < uint(RUN); k++) {
        v[k] = k < per && begin + k < u_blocks ? counts[row + begin + k] : 0u;
        total += v[k];
    }
    uint src = 0u;
    s_sum[0][l] = total;
    barrier();
    for (uint off = 1u; off < uint(THREADS); off <<= 1) {
        uint a = s_sum[src][l];
        if (l >= off)
            a += s_sum[src][l - off];
        s_sum[1u - src][l] = a;
        src = 1u - src;
        barrier();
    }
    uint run = s_sum[src][l] - total;
    for (uint k = 0u; k < uint(RUN); k++) {
        if (k < per && begin + k < u_blocks)
            counts[row + begin + k] = run;
        run += v[k];
    }
    if (l == uint(THREADS) - 1u)
        counts[RADIX_BINS * u_blocks + d] = s_sum[src][l];
}
