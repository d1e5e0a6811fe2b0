#version 450
// glsl/bvh/widen_emit.comp: writes the 4-wide tree (src/bvh/widen.c), one
// invocation per wide node: queue[i] is its binary node b, and rank[b],
// the exclusive prefix sum of widen_level.comp's flags, its index. Binary
// preorder restricted to the wide nodes is a preorder of the wide tree
// (each wide subtree lies in one binary subtree), so the nodes come out
// depth-first with each node's first inner child right after it, as the
// binary layout has them (glsl/shared/bvh.h).
#include "shared/bvh.h"
#include "shared/bindings.h"
#include "widen.glsl"

layout(local_size_x = 64) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_WIDEN_INFO) readonly buffer Info { uint info[]; };
layout(std430, binding = CV_BIND_WIDEN_QUEUE) readonly buffer Queue { uint queue[]; };
layout(std430, binding = CV_BIND_WIDEN_FLAGS) readonly buffer Rank { uint rank[]; };
layout(std430, binding = CV_BIND_BVH_NODES) writeonly buffer Wide { CvBvhNode4 wide[]; };

uniform uint u_n;  // wide nodes

void main()
{
    uint i = cv_global_index();
    if (i >= u_n)
        return;
    int n_bin = int(min(info[CV_BVH_INFO_NODES], uint(cv_widen_bin.length())));
    uint b = queue[i];
    if (b >= uint(n_bin) || rank[b] >= uint(wide.length()))
        return;
    CvWideKids k;
    cv_widen_children(int(b), n_bin, k);
    CvBvhNode4 nd;
    nd.lox = nd.loy = nd.loz = vec4(CV_BVH_EMPTY);
    nd.hix = nd.hiy = nd.hiz = vec4(-CV_BVH_EMPTY);
    nd.word = ivec4(0);
    nd.count = ivec4(0);
    for (int c = 0; c < 4; c++) {
        bool leaf = c < k.n && k.count[c] > 0, inner = cv_widen_inner(k, c, n_bin);
        if (!leaf && !inner)
            continue;
        nd.lox[c] = k.lo[c].x;
        nd.loy[c] = k.lo[c].y;
        nd.loz[c] = k.lo[c].z;
        nd.hix[c] = k.hi[c].x;
        nd.hiy[c] = k.hi[c].y;
        nd.hiz[c] = k.hi[c].z;
        nd.word[c] = leaf ? k.word[c] : int(rank[k.word[c]]);
        nd.count[c] = leaf ? k.count[c] : 0;
    }
    wide[rank[b]] = nd;
}
