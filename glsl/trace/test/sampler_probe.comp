#version 450
// glsl/trace/test/sampler_probe.comp: writes cv_sample_2d for a range of
// pixels, sample indices and dimension pairs, for tests/trace/sampler_test.
layout(local_size_x = 64) in;
#include "shared/bindings.h"
#include "../../lib/index.glsl"
#include "../sampler.glsl"

layout(std430, binding = CV_BIND_PROBE_OUT) writeonly buffer Out { vec2 samples[]; };
uniform uint u_n_samples;   // per (pixel, pair)
uniform uint u_n_pairs;
uniform uint u_n_pixels;
uniform uvec2 u_seed;
uniform uint u_sampler;
uniform uint u_first;       // first sample index

void main()
{
    uint i = cv_global_index();
    if (i >= u_n_samples * u_n_pairs * u_n_pixels)
        return;
    uint s = i % u_n_samples, pair = (i / u_n_samples) % u_n_pairs,
         pixel = i / (u_n_samples * u_n_pairs);
    samples[i] = cv_sample_2d(pixel, u_first + s, pair, u_seed, u_sampler);
}
