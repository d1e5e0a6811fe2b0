#version 450
// glsl/bvh/emit.comp: writes the final CvBvhNode of every live inner node
// at its scanned index; children that are leaves or collapsed subtrees
// become leaf references into the primitive order. The invocation of the
// last inner node also stores the final node count in info[0].
#include "shared/bvh.h"
#include "shared/bindings.h"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_STAGE0 + 1) readonly buffer Nodes { CvBvhBuildNode nodes[]; };
layout(std430, binding = CV_BIND_STAGE0 + 2) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = CV_BIND_STAGE0 + 3) readonly buffer Index { uint index[]; };
layout(std430, binding = CV_BIND_STAGE0 + 4) writeonly buffer Info { uint info[]; };
layout(std430, binding = CV_BIND_BVH_NODES) writeonly buffer Out { CvBvhNode out_nodes[]; };

uniform uint u_n;

bool is_live(int node)
{
    return node < int(u_n) - 1 && (offsets[node] & 0x80000000u) == 0u &&
           (nodes[node].link.w & CV_BVH_COLLAPSE) == 0;
}

void child_words(int c, out int word, out int count)
{
    if (is_live(c)) {
        word = int(index[c]);
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
    bool live = is_live(node);
    if (i + 2u == u_n)
        info[0] = index[node] + (live ? 1u : 0u);
    if (!live)
        return;
    ivec4 link = nodes[node].link;
    int lw, lc, rw, rc;
    child_words(link.x, lw, lc);
    child_words(link.y, rw, rc);
    CvBvhNode o;
    o.lmin = vec4(nodes[link.x].bmin.xyz, intBitsToFloat(lw));
    o.lmax = vec4(nodes[link.x].bmax.xyz, intBitsToFloat(lc));
    o.rmin = vec4(nodes[link.y].bmin.xyz, intBitsToFloat(rw));
    o.rmax = vec4(nodes[link.y].bmax.xyz, intBitsToFloat(rc));
    out_nodes[index[node]] = o;
}
