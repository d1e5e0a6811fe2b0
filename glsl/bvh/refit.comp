#version 450
// glsl/bvh/refit.comp: bottom-up bounds, primitive counts and SAH costs.
// One invocation per leaf climbs towards the root; at each inner node the
// first arrival stops (atomic counter) and the second, which knows both
// children are final, computes the node and climbs on. The host may run it
// in several passes, each for the leaves of one window of triangle indices
// (REFIT_WINDOW in src/bvh/bvh.c); the counters carry over between them.
// A node's parent (link.z, from hierarchy.comp) does not change here.
#include "shared/scene.h"
#include "shared/bvh.h"
#include "shared/bindings.h"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_BUILD_VALS) readonly buffer Vals { uint vals[]; };
// each triangle's box in input order, from morton.comp
layout(std430, binding = CV_BIND_LEAF_BOXES) readonly buffer LeafBoxes { vec4 leaf_boxes[]; };
layout(std430, binding = CV_BIND_BUILD_NODES) coherent buffer Nodes { CvBvhBuildNode nodes[]; };
layout(std430, binding = CV_BIND_BUILD_COUNTERS) coherent buffer Counters { uint counters[]; };

uniform uint u_n;
// This pass's window of triangle indices, [u_tri_lo, u_tri_hi).
uniform uint u_tri_lo;
uniform uint u_tri_hi;

#include "sah.glsl"

void main()
{
    uint i = cv_global_index();
    if (i >= u_n)
        return;
    int node = int(u_n) - 1 + int(i);
    uint tri = vals[i];
    if (tri < u_tri_lo || tri >= u_tri_hi)
        return;
    vec3 lo = leaf_boxes[2u * tri].xyz, hi = leaf_boxes[2u * tri + 1u].xyz;
    // The climb carries the node it comes from in registers and reads only
    // its sibling: half the loads of cv_bvh_update_node.
    vec4 bmin = vec4(lo, float(CV_BVH_COST_TRI) * cv_half_area(lo, hi));
    int w = 1;
    nodes[node].bmin = bmin;
    nodes[node].bmax = vec4(hi, 0.0);
    nodes[node].link.w = w;
    memoryBarrierBuffer();
    int p = nodes[node].link.z;
    while (p >= 0) {
        if (atomicAdd(counters[p], 1u) == 0u)
            return;
        memoryBarrierBuffer();
        ivec4 link = nodes[p].link;
        bool left = link.x == node;
        int sib = left ? link.y : link.x;
        vec4 smin = nodes[sib].bmin;
        vec3 shi = nodes[sib].bmax.xyz;
        int sw = nodes[sib].link.w;
        // Left before right, as cv_bvh_update_node adds the costs.
        if (left)
            bmin = cv_bvh_combine(p, bmin, hi, w, smin, shi, sw, hi, w);
        else
            bmin = cv_bvh_combine(p, smin, shi, sw, bmin, hi, w, hi, w);
        memoryBarrierBuffer();
        node = p;
        p = link.z;
    }
}
