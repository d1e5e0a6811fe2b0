#version 450
// glsl/bvh/widen_level.comp: one level of the 4-wide tree's widening
// (src/bvh/widen.c), one invocation per wide node of the level
// (queue[lo .. hi), each a binary node). Each opens its children
// (widen.glsl) and appends the binary nodes of its inner children to the
// queue as the next level, flagging them: the flags' prefix sum later
// numbers the wide nodes in the binary tree's preorder (widen_emit.comp).
// Only the discovery order within a level depends on the atomics; the
// tree written does not.
// need[] (by queue entry) holds the stack entries a query may have pushed
// on its way down to the node: traversal pushes all entered inner children
// of a node but the nearest (glsl/bvh/traverse.glsl), so at most k - 1 for
// k inner children. The largest sum goes to info[CV_BVH_INFO_STACK].
#include "shared/bvh.h"
#include "shared/bindings.h"
#include "widen.glsl"

layout(local_size_x = CV_WIDEN_GROUP) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_WIDEN_INFO) coherent buffer Info { uint info[]; };
layout(std430, binding = CV_BIND_WIDEN_QUEUE) buffer Queue { uint queue[]; };
layout(std430, binding = CV_BIND_WIDEN_FLAGS) writeonly buffer Flags { uint flags[]; };
layout(std430, binding = CV_BIND_WIDEN_NEED) buffer Need { uint need[]; };

// The group's inner children and deepest stack need are gathered here
// first, so that the level's nodes, which all add to the same counters, do
// so once per group rather than twice per node: contended global atomics
// were a large share of widening's time (bench/RESULTS.md, "The 4-wide
// tree, built on the GPU").
shared uint s_count, s_base, s_need;

void main()
{
    if (gl_LocalInvocationIndex == 0u) {
        s_count = 0u;
        s_need = 0u;
    }
    barrier();
    uint i = info[CV_BVH_INFO_LEVEL_LO] + cv_global_index();
    bool live = i < info[CV_BVH_INFO_LEVEL_HI];
    int n_bin = int(min(info[CV_BVH_INFO_NODES], uint(cv_widen_bin.length())));
    CvWideKids k;
    k.n = 0;
    if (live)
        cv_widen_children(int(queue[i]), n_bin, k);
    uint n_inner = 0u;
    for (int c = 0; c < 4; c++)
        n_inner += cv_widen_inner(k, c, n_bin) ? 1u : 0u;
    uint below = n_inner > 0u ? need[i] + n_inner - 1u : 0u;
    uint at = n_inner > 0u ? atomicAdd(s_count, n_inner) : 0u;
    if (n_inner > 1u)
        atomicMax(s_need, below);
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        s_base = s_count > 0u ? atomicAdd(info[CV_BVH_INFO_WIDE], s_count) : 0u;
        if (s_need > 0u)
            atomicMax(info[CV_BVH_INFO_STACK], s_need);
    }
    barrier();
    at += s_base;
    for (int c = 0; c < 4; c++) {
        if (!cv_widen_inner(k, c, n_bin))
            continue;
        if (at < uint(queue.length()) && at < uint(need.length())) {
            queue[at] = uint(k.word[c]);
            need[at] = below;
        }
        flags[k.word[c]] = 1u;
        at++;
    }
}
