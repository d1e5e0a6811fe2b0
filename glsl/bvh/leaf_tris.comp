#version 450
// glsl/bvh/leaf_tris.comp: last step of the final layout, one invocation per
// leaf slot: copies the positions of triangle prims[i] into CvBvhTri slot i
// (glsl/shared/bvh.h), so that traversal reads a leaf's triangles as one
// contiguous run instead of through two levels of indices. Written as raw
// words, like emit.comp: v0.w is an integer that a float path might flush.
#include "shared/bvh.h"
#include "shared/scene.h"
#include "shared/bindings.h"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_VERTICES) readonly buffer Vertices { CvVertex vertices[]; };
layout(std430, binding = CV_BIND_TRIANGLES) readonly buffer Triangles { CvTriangle triangles[]; };
layout(std430, binding = CV_BIND_BVH_PRIMS) readonly buffer Prims { uint prims[]; };
layout(std430, binding = CV_BIND_BVH_TRIS) writeonly buffer Out { uvec4 out_words[]; };

uniform uint u_n;

void main()
{
    uint i = cv_global_index();
    if (i >= u_n)
        return;
    uint prim = prims[i];
    uvec4 a = uvec4(0u), b = uvec4(0u), c = uvec4(0u);
    // Anything out of range stays the all-zero triangle, which no ray hits.
    if (prim < uint(triangles.length())) {
        uvec3 idx = triangles[prim].idx.xyz;
        uint nv = uint(vertices.length());
        if (idx.x < nv && idx.y < nv && idx.z < nv) {
            a = uvec4(floatBitsToUint(vertices[idx.x].pos_u.xyz), prim);
            b = uvec4(floatBitsToUint(vertices[idx.y].pos_u.xyz), 0u);
            c = uvec4(floatBitsToUint(vertices[idx.z].pos_u.xyz), 0u);
        }
    }
    out_words[3u * i] = a;
    out_words[3u * i + 1u] = b;
    out_words[3u * i + 2u] = c;
}
