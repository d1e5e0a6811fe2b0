#version 450
// glsl/bvh/emit.comp: writes the final CvBvhNode of every live inner node
// at its depth-first index (layout.comp says how that index is formed);
// children that are leaves or collapsed subtrees become leaf references
// into the primitive order. The parent of the last leaf (whose range ends
// at slot n) stores the final node count, one fewer than the final leaves,
// in info[CV_BVH_INFO_NODES].
#include "shared/bvh.h"
#include "shared/bindings.h"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_BUILD_NODES) readonly buffer Nodes { CvBvhBuildNode nodes[]; };
layout(std430, binding = CV_BIND_BUILD_OFFSETS) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = CV_BIND_BUILD_LEFTS) readonly buffer Lefts { uint lefts[]; };
layout(std430, binding = CV_BIND_EMIT_INFO) writeonly buffer Info { uint info[]; };
// Exclusive prefix sum of layout.comp's final-leaf starts, per leaf slot.
layout(std430, binding = CV_BIND_EMIT_LEAVES) readonly buffer Leaves { uint leaves_before[]; };
// Written as raw words: the .w fields are integers, and small ones are
// float denormals that no float path should get a chance to flush.
layout(std430, binding = CV_BIND_BVH_NODES) writeonly buffer Out { uvec4 out_words[]; };

uniform uint u_n;

bool is_live(int node)
{
    return node < int(u_n) - 1 && (offsets[node] & 0x80000000u) == 0u &&
           (nodes[node].link.w & CV_BVH_COLLAPSE) == 0;
}

uint final_index(int node)
{
    return leaves_before[offsets[node] & 0x7fffffffu] + lefts[node];
}

void child_words(int c, out int word, out int count)
{
    if (is_live(c)) {
        word = int(final_index(c));
        count = 0;
    } else {
        word = int(offsets[c] & 0x7fffffffu);
        count = nodes[c].link.w & CV_BVH_COUNT_MASK;
    }
}

void main()
{
    uint i = cv_global_index();
    if (i + 1u >= u_n)
        return;
    int node = int(i);
    if (!is_live(node))
        return;
    ivec4 link = nodes[node].link;
    int lw, lc, rw, rc;
    child_words(link.x, lw, lc);
    child_words(link.y, rw, rc);
    if (rc > 0 && uint(rw + rc) == u_n)
        info[CV_BVH_INFO_NODES] = leaves_before[rw];
    uint o = 4u * final_index(node);
    out_words[o] = uvec4(floatBitsToUint(nodes[link.x].bmin.xyz), uint(lw));
    out_words[o + 1u] = uvec4(floatBitsToUint(nodes[link.x].bmax.xyz), uint(lc));
    out_words[o + 2u] = uvec4(floatBitsToUint(nodes[link.y].bmin.xyz), uint(rw));
    out_words[o + 3u] = uvec4(floatBitsToUint(nodes[link.y].bmax.xyz), uint(rc));
}
