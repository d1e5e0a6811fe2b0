#version 450
// glsl/bvh/split_sum.comp: one level of the sum of the splitting
// priorities: each workgroup adds 256 of the previous level's sums; the host
// repeats until one is left (src/bvh/split.c).
#include "shared/bindings.h"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_SPLIT_SUM_IN) readonly buffer In { float in_s[]; };
layout(std430, binding = CV_BIND_SPLIT_SUM_OUT) writeonly buffer Out { float out_s[]; };

uniform uint u_n;

shared float s_sum[256];

void main()
{
    uint i = cv_global_index();
    uint l = gl_LocalInvocationID.x;
    s_sum[l] = i < u_n ? in_s[i] : 0.0;
    barrier();
    for (uint s = 128; s > 0; s >>= 1) {
        if (l < s)
            s_sum[l] += s_sum[l + s];
        barrier();
    }
    if (l == 0)
        out_s[i / 256u] = s_sum[0];
}
