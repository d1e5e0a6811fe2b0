#version 450
// glsl/gpu/selftest.comp: the smallest real workload: out[i] = f(in[i], i).
// Used by the context tests (every backend) and --list-gpus --check.
layout(local_size_x = 64) in;

#include "shared/bindings.h"
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_CHECK_IN) readonly buffer In { uint values_in[]; };
layout(std430, binding = CV_BIND_CHECK_OUT) writeonly buffer Out { uint values_out[]; };

uniform uint u_count;

void main()
{
    uint i = cv_global_index();
    if (i >= u_count)
        return;
    values_out[i] = values_in[i] * SELFTEST_MUL + i;
}
