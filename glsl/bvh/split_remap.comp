#version 450
// glsl/bvh/split_remap.comp: after a build over split references, turns
// the leaf slots' reference indices into the triangles they belong to, so
// that leaf_tris.comp and traversal see triangle indices as without
// splitting (src/bvh/split.h).
#include "shared/bindings.h"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_SPLIT_REF_TRIS) readonly buffer RefTris { uint ref_tris[]; };
layout(std430, binding = CV_BIND_BVH_PRIMS) buffer Prims { uint prims[]; };

uniform uint u_n;

void main()
{
    uint i = cv_global_index();
    if (i < u_n)
        prims[i] = ref_tris[prims[i]];
}
