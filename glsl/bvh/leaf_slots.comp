#version 450
// glsl/bvh/leaf_slots.comp: the inverse of the leaf order, for
// leaf_tris.comp's scattering pass: slot_of[r] is the leaf slot that holds
// reference r (prims[] holds references here, before split_remap.comp
// turns them into triangles). The writes land in a buffer of 4 bytes per
// reference, small enough that their scatter costs little.
#include "shared/bindings.h"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_BVH_PRIMS) readonly buffer Prims { uint prims[]; };
layout(std430, binding = CV_BIND_BUILD_SLOT_OF) writeonly buffer SlotOf { uint slot_of[]; };

uniform uint u_n;

void main()
{
    uint i = cv_global_index();
    if (i < u_n && prims[i] < u_n)
        slot_of[prims[i]] = i;
}
