#version 450
// glsl/bvh/layout.comp: first step of the final layout, one invocation per
// build node. Climbing to the root gives the node's first slot in the leaf
// primitive order (a left-first depth-first order, so every subtree, and so
// every collapsed leaf, owns a contiguous range) and whether an ancestor was
// collapsed (the node is then inside a leaf: "dead"). Leaves write their
// triangle into the primitive order.
//
// The final inner nodes are numbered in the same left-first depth-first
// (pre)order, so that a parent's left child is its next node and every
// subtree is one contiguous run of memory. In a tree where every inner node
// has two children, the inner nodes before X in preorder are its ancestors
// plus, for each ancestor whose right subtree holds X, the inner nodes of
// its left subtree (one fewer than that subtree's final leaves). So
//   index(X) = (final leaves whose first slot is below X's)
//            + (ancestors whose left subtree holds X),
// the first term from a prefix sum over `starts` (1 at the first slot of
// every final leaf: a build leaf or collapsed node that is not dead), the
// second counted here on the climb and kept in `lefts`; emit.comp adds
// them. Ancestors of a live node are live, so the climb's count is exact.
#include "shared/bvh.h"
#include "shared/bindings.h"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_BUILD_VALS) readonly buffer Vals { uint vals[]; };
layout(std430, binding = CV_BIND_BUILD_NODES) readonly buffer Nodes { CvBvhBuildNode nodes[]; };
layout(std430, binding = CV_BIND_BUILD_OFFSETS) writeonly buffer Offsets { uint offsets[]; };
layout(std430, binding = CV_BIND_BUILD_LEFTS) writeonly buffer Lefts { uint lefts[]; };
// Zeroed by the host; one word per leaf slot.
layout(std430, binding = CV_BIND_BUILD_STARTS) writeonly buffer Starts { uint starts[]; };
layout(std430, binding = CV_BIND_BVH_PRIMS) writeonly buffer Prims { uint prims[]; };

uniform uint u_n;

void main()
{
    uint i = cv_global_index();
    int n_inner = int(u_n) - 1;
    if (i >= 2u * u_n - 1u)
        return;
    int node = int(i);
    uint off = 0u, left = 0u;
    bool dead = false;
    int c = node, p = nodes[node].link.z;
    while (p >= 0) {
        ivec4 link = nodes[p].link;
        dead = dead || (link.w & CV_BVH_COLLAPSE) != 0;
        if (link.y == c)
            off += uint(nodes[link.x].link.w & CV_BVH_COUNT_MASK);
        else
            left++;
        c = p;
        p = link.z;
    }
    offsets[node] = off | (dead ? 0x80000000u : 0u);
    bool leaf = node >= n_inner;
    if (leaf)
        prims[off] = vals[node - n_inner];
    else
        lefts[node] = left;
    if (!dead && (leaf || (nodes[node].link.w & CV_BVH_COLLAPSE) != 0))
        starts[off] = 1u;
}
