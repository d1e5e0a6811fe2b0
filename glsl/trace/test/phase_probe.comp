#version 450
// glsl/trace/test/phase_probe.comp: drives the shipped Henyey-Greenstein
// code (trace/medium/medium.glsl) for tests/trace/medium_phase_test.c:
// mode 0 samples wi for wo = u_wo and g = u_g (xyz: wi, w: pdf); mode 1
// evaluates the density at given directions wi (x: cv_hg_pdf).
layout(local_size_x = 64) in;

#include "lib/index.glsl"
#include "lib/rng.glsl"
#include "lib/constants.glsl"
#include "trace/bsdf/material_buffers.glsl"
#include "trace/medium/medium.glsl"

layout(std430, binding = CV_BIND_PROBE_IN) readonly buffer ProbeIn { vec4 probe_in[]; };
layout(std430, binding = CV_BIND_PROBE_OUT) writeonly buffer ProbeOut { vec4 probe_out[]; };

uniform uint u_mode;
uniform uint u_count;
uniform uint u_seed;
uniform vec3 u_wo;
uniform float u_g;

void main()
{
    uint i = cv_global_index();
    if (i >= u_count)
        return;
    if (u_mode == 0u) {
        CvRng rng = cv_rng_init(u_seed, i);
        float pdf;
        vec3 wi = cv_hg_sample(u_wo, u_g, cv_rng_next2(rng), pdf);
        probe_out[i] = vec4(wi, pdf);
    } else {
        probe_out[i] = vec4(cv_hg_pdf(dot(u_wo, probe_in[i].xyz), u_g));
    }
}
