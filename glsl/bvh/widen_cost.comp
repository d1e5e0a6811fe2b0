#version 450
// glsl/bvh/widen_cost.comp: every binary node's cv_widen_cost, bottom-up
// (widen.glsl says what they are; src/bvh/widen.c runs it after
// widen_up.comp). One invocation per binary node; those with no inner
// child start and climb towards the root. At a node with two inner
// children the first arrival stops (bit 31 of its up word, set
// atomically) and the second, which knows both children's costs are
// final, computes the node and climbs on; a node with one inner child is
// computed by the one climb that reaches it.
#define CV_WIDEN_COST_ACCESS coherent
#include "shared/bvh.h"
#include "shared/bindings.h"
#include "widen.glsl"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_WIDEN_INFO) readonly buffer Info { uint info[]; };
layout(std430, binding = CV_BIND_WIDEN_UP) coherent buffer Up { uint up[]; };

uniform uint u_n;  // binary nodes at most

#define ARRIVED 0x80000000u

bool both_inner(CvBvhNode nd, int n_bin)
{
    return cv_widen_is_inner(floatBitsToInt(nd.lmin.w), floatBitsToInt(nd.lmax.w), n_bin) &&
           cv_widen_is_inner(floatBitsToInt(nd.rmin.w), floatBitsToInt(nd.rmax.w), n_bin);
}

void main()
{
    uint i = cv_global_index();
    int n_bin = int(min(min(info[CV_BVH_INFO_NODES], u_n),
                        min(uint(cv_widen_bin.length()), uint(up.length()))));
    if (i >= uint(n_bin) || i >= uint(cv_widen_cost.length()))
        return;
    CvBvhNode nd = cv_widen_bin[i];
    if (cv_widen_is_inner(floatBitsToInt(nd.lmin.w), floatBitsToInt(nd.lmax.w), n_bin) ||
        cv_widen_is_inner(floatBitsToInt(nd.rmin.w), floatBitsToInt(nd.rmax.w), n_bin))
        return;
    cv_widen_cost[i] = cv_widen_node_cost(nd, n_bin);
    memoryBarrierBuffer();
    uint p = up[i] & ~ARRIVED;
    // A valid tree's climb ends at the root within n_bin steps; the bound
    // only keeps a bad one from running away.
    for (int steps = 0; p < uint(n_bin) && steps < n_bin; steps++) {
        nd = cv_widen_bin[p];
        uint above;
        if (both_inner(nd, n_bin)) {
            uint old = atomicOr(up[p], ARRIVED);
            if ((old & ARRIVED) == 0u)
                return;
            above = old & ~ARRIVED;
        } else {
            above = up[p] & ~ARRIVED;
        }
        memoryBarrierBuffer();
        cv_widen_cost[p] = cv_widen_node_cost(nd, n_bin);
        memoryBarrierBuffer();
        p = above;
    }
}
