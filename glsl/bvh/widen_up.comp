#version 450
// glsl/bvh/widen_up.comp: each binary node's parent, for widen_cost.comp's
// climb (src/bvh/widen.c), one invocation per binary node: up[c] = b for
// each inner child c of b, and the root's up word CV_WIDEN_ROOT. Bit 31
// stays clear for widen_cost.comp's arrivals.
#include "shared/bvh.h"
#include "shared/bindings.h"
#include "widen.glsl"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_WIDEN_INFO) readonly buffer Info { uint info[]; };
layout(std430, binding = CV_BIND_WIDEN_UP) writeonly buffer Up { uint up[]; };

uniform uint u_n;  // binary nodes at most

void main()
{
    uint i = cv_global_index();
    int n_bin = int(min(min(info[CV_BVH_INFO_NODES], u_n), uint(cv_widen_bin.length())));
    if (i >= uint(n_bin) || i >= uint(up.length()))
        return;
    if (i == 0u)
        up[0] = CV_WIDEN_ROOT;
    CvBvhNode nd = cv_widen_bin[i];
    int lw = floatBitsToInt(nd.lmin.w), rw = floatBitsToInt(nd.rmin.w);
    if (cv_widen_is_inner(lw, floatBitsToInt(nd.lmax.w), n_bin) && lw < up.length())
        up[lw] = i;
    if (cv_widen_is_inner(rw, floatBitsToInt(nd.rmax.w), n_bin) && rw < up.length())
        up[rw] = i;
}
