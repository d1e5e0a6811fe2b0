#version 450
// glsl/bvh/widen_next.comp: advances the 4-wide tree's widening by one
// level (src/bvh/widen.c): the wide nodes found by the last level
// (queue[hi .. count)) become the level that widen_level.comp runs next,
// with its indirect dispatch. With u_start it first seeds the root: binary
// node 0 is wide node 0. One invocation.
#include "shared/bvh.h"
#include "shared/bindings.h"
#include "widen.glsl"

layout(local_size_x = 1) in;

layout(std430, binding = CV_BIND_WIDEN_INFO) buffer Info { uint info[]; };
layout(std430, binding = CV_BIND_WIDEN_QUEUE) buffer Queue { uint queue[]; };
layout(std430, binding = CV_BIND_WIDEN_FLAGS) buffer Flags { uint flags[]; };
layout(std430, binding = CV_BIND_WIDEN_NEED) writeonly buffer Need { uint need[]; };

uniform uint u_start;

void main()
{
    if (u_start != 0u) {
        queue[0] = 0u;
        flags[0] = 1u;
        info[CV_BVH_INFO_WIDE] = 1u;
        info[CV_BVH_INFO_LEVEL_HI] = 0u;
        info[CV_BVH_INFO_DEPTH] = 0u;
        info[CV_BVH_INFO_STACK] = 0u;
        need[0] = 0u;
    }
    // Past the queue's end the count only tells the host that it overflowed.
    uint lo = info[CV_BVH_INFO_LEVEL_HI];
    uint hi = min(info[CV_BVH_INFO_WIDE], uint(queue.length()));
    lo = min(lo, hi);
    if (hi > lo)
        info[CV_BVH_INFO_DEPTH]++;
    info[CV_BVH_INFO_LEVEL_LO] = lo;
    info[CV_BVH_INFO_LEVEL_HI] = hi;
    info[CV_BVH_INFO_DISPATCH] = (hi - lo + uint(CV_WIDEN_GROUP) - 1u) / uint(CV_WIDEN_GROUP);
    info[CV_BVH_INFO_DISPATCH + 1] = 1u;
    info[CV_BVH_INFO_DISPATCH + 2] = 1u;
}
