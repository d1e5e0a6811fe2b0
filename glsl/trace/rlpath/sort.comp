#version 450
// glsl/trace/rlpath/sort.comp: puts the iteration's hits in the order of
// their table keys for the rlpath shade and update stages (grouping threads
// by cell, as Dahm and Keller do, so that a work group reads and updates a
// few keys' CDFs and bins instead of one per invocation). intersect.comp
// (CV_HIT_KEYS) has counted every hit's sort bin and kept the bin and the
// hit's rank in it (pad0, pad1); layout in shared/rlpath.h.
// SORT_MODE 0: one work group turns the counts into exclusive offsets and
// clears the counts for the next iteration (a fixed number of bins, so the
// dispatch is direct); SORT_MODE 1, over the hit queue (indirect): hit i goes
// to order[offset of its bin + its rank]. The order within a bin follows
// the atomics' order, which changes nothing a pixel adds up (one path per
// pixel in flight).
#include "shared/trace.h"
#include "shared/rlpath.h"
#if SORT_MODE == 0
layout(local_size_x = CV_RL_SORT_GROUP) in;
#else
layout(local_size_x = CV_TRACE_GROUP) in;
#endif
#include "../common.glsl"

layout(std430, binding = CV_BIND_RL_SORT) coherent buffer CvRlSort { uint rl_sort[]; };
layout(std430, binding = CV_BIND_RL_ORDER) writeonly buffer CvRlOrder { uint rl_order[]; };

#if SORT_MODE == 0
const uint PER = CV_RL_SORT_BINS / uint(CV_RL_SORT_GROUP);
shared uint s_sum[CV_RL_SORT_GROUP];

void main()
{
    uint t = gl_LocalInvocationID.x, b0 = t * PER;
    uint c[PER];
    uint sum = 0u;
    for (uint k = 0u; k < PER; k++) {
        c[k] = rl_sort[b0 + k];
        sum += c[k];
    }
    s_sum[t] = sum;
    barrier();
    // inclusive scan of the invocations' sums (Hillis and Steele)
    for (uint d = 1u; d < uint(CV_RL_SORT_GROUP); d <<= 1u) {
        uint v = t >= d ? s_sum[t - d] : 0u;
        barrier();
        s_sum[t] += v;
        barrier();
    }
    uint run = s_sum[t] - sum;
    for (uint k = 0u; k < PER; k++) {
        rl_sort[CV_RL_SORT_BINS + b0 + k] = run;
        rl_sort[b0 + k] = 0u;
        run += c[k];
    }
}
#else
void main()
{
    uint i = cv_global_index();
    if (i >= cv_hit_count())
        return;
    CvHitItem h = hits[i];
    rl_order[rl_sort[CV_RL_SORT_BINS + h.pad0] + h.pad1] = i;
}
#endif
