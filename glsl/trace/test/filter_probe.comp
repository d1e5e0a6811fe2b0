#version 450
// glsl/trace/test/filter_probe.comp: cv_filter_sample (trace/filter.glsl)
// for n independent uniform 2D samples, for tests/trace/filter_sample_test:
// out[i] = (offset x, offset y, weight, 0).
layout(local_size_x = 64) in;
#include "shared/trace.h"
#include "../../lib/index.glsl"
layout(std140, binding = CV_UBO_PASS) uniform CvPassBlock { CvPassParams u_pass; };
#include "../sampler.glsl"
#include "../filter.glsl"

layout(std430, binding = CV_BIND_PROBE_OUT) writeonly buffer Out { vec4 samples[]; };
uniform uint u_n;
uniform uvec2 u_seed;

void main()
{
    uint i = cv_global_index();
    if (i >= u_n)
        return;
    float w;
    vec2 p = cv_filter_sample(cv_sample_2d(i, 0u, 0u, u_seed, 1u), w);
    samples[i] = vec4(p, w, 0.0);
}
