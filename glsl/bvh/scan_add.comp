#version 450
// glsl/bvh/scan_add.comp: adds each tile's scanned total back to the tile's
// elements, finishing a multi-level exclusive scan (see scan_block.comp).
#include "shared/bindings.h"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_SCAN_DATA) buffer Data { uint data[]; };
layout(std430, binding = CV_BIND_SCAN_SUMS) readonly buffer Sums { uint sums[]; };

uniform uint u_n;

void main()
{
    uint i = cv_global_index();
    if (i < u_n)
        data[i] += sums[i / 1024u];
}
