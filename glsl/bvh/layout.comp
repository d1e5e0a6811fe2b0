#version 450
// glsl/bvh/layout.comp: first step of the final layout, one invocation per
// build node. Climbing to the root gives the node's first slot in the leaf
// primitive order (a left-first depth-first order, so every subtree, and so
// every collapsed leaf, owns a contiguous range) and whether an ancestor was
// collapsed (the node is then inside a leaf: "dead"). Leaves write their
// triangle into the primitive order; inner nodes write 1 to `live` when
// they stay inner nodes of the final tree, to be scanned into final indices.
#include "shared/bvh.h"
#include "shared/bindings.h"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_STAGE0) readonly buffer Vals { uint vals[]; };
layout(std430, binding = CV_BIND_STAGE0 + 1) readonly buffer Nodes { CvBvhBuildNode nodes[]; };
layout(std430, binding = CV_BIND_STAGE0 + 2) writeonly buffer Offsets { uint offsets[]; };
layout(std430, binding = CV_BIND_STAGE0 + 3) writeonly buffer Live { uint live[]; };
layout(std430, binding = CV_BIND_BVH_PRIMS) writeonly buffer Prims { uint prims[]; };

uniform uint u_n;

void main()
{
    uint i = cv_global_index();
    int n_inner = int(u_n) - 1;
    if (i >= 2u * u_n - 1u)
        return;
    int node = int(i);
    uint off = 0u;
    bool dead = false;
    int c = node, p = nodes[node].link.z;
    while (p >= 0) {
        ivec4 link = nodes[p].link;
        dead = dead || (link.w & CV_BVH_COLLAPSE) != 0;
        if (link.y == c)
            off += uint(nodes[link.x].link.w & CV_BVH_COUNT_MASK);
        c = p;
        p = link.z;
    }
    offsets[node] = off | (dead ? 0x80000000u : 0u);
    if (node >= n_inner)
        prims[off] = vals[node - n_inner];
    else
        live[node] = !dead && (nodes[node].link.w & CV_BVH_COLLAPSE) == 0 ? 1u : 0u;
}
