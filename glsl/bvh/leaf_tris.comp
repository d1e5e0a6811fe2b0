#version 450
// glsl/bvh/leaf_tris.comp: last step of the final layout: the positions of
// the triangle in each leaf slot, copied into CvBvhTri slot i (glsl/shared/
// bvh.h), so that traversal reads a leaf's triangles as one contiguous run
// instead of through two levels of indices. Written as raw words, like
// emit.comp: v0.w is an integer that a float path might flush.
//
// Two ways round. By default one invocation per slot gathers triangle
// prims[i] (for trees that tests lay out themselves). With SCATTER, as the
// build runs it, one invocation per reference r reads its own triangle
// (triangle r, or ref_tris[r] after splitting) and writes it to slot
// slot_of[r] (leaf_slots.comp): references come in triangle order, so the
// vertex reads are as coherent as the scene's own order, and only the
// writes land at random. Gathering in leaf order read the vertex buffer at
// random, and random access over more than a few hundred MB collapses on
// NVIDIA (address translation, it seems); scattering into the whole
// output does the same once the output is that large (bench/RESULTS.md,
// "BVH build: wall time"), so the host runs the scatter once per window of
// slots [u_slot_lo, u_slot_hi), each a few hundred MB of output: every pass
// reads all references' slots in order, and only the window's write.
#include "shared/bvh.h"
#include "shared/scene.h"
#include "shared/bindings.h"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"

#include "mesh_buffers.glsl"
#ifdef SCATTER
layout(std430, binding = CV_BIND_BUILD_SLOT_OF) readonly buffer SlotOf { uint slot_of[]; };
layout(std430, binding = CV_BIND_SPLIT_REF_TRIS) readonly buffer RefTris { uint ref_tris[]; };
uniform uint u_split;  // 1: references are split pieces, ref_tris[] names their triangles
uniform uint u_slot_lo, u_slot_hi;
#else
layout(std430, binding = CV_BIND_BVH_PRIMS) readonly buffer Prims { uint prims[]; };
#endif
layout(std430, binding = CV_BIND_BVH_TRIS) writeonly buffer Out { uvec4 out_words[]; };

uniform uint u_n;

void main()
{
    uint i = cv_global_index();
    if (i >= u_n)
        return;
#ifdef SCATTER
    uint slot = slot_of[i];
    if (slot < u_slot_lo || slot >= u_slot_hi || slot >= u_n)
        return;
    uint prim = u_split != 0u ? ref_tris[i] : i;
#else
    uint prim = prims[i];
    uint slot = i;
#endif
    uvec4 a = uvec4(0u), b = uvec4(0u), c = uvec4(0u);
    // Anything out of range stays the all-zero triangle, which no ray hits.
    if (prim < uint(cv_triangles.length())) {
        uvec3 idx = cv_triangles[prim].idx.xyz;
        uint nv = uint(cv_vertices.length());
        if (idx.x < nv && idx.y < nv && idx.z < nv) {
            a = uvec4(floatBitsToUint(cv_vertices[idx.x].pos_u.xyz), prim);
            b = uvec4(floatBitsToUint(cv_vertices[idx.y].pos_u.xyz), 0u);
            c = uvec4(floatBitsToUint(cv_vertices[idx.z].pos_u.xyz), 0u);
        }
    }
    out_words[3u * slot] = a;
    out_words[3u * slot + 1u] = b;
    out_words[3u * slot + 2u] = c;
}
