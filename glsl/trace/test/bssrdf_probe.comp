#version 450
// glsl/trace/test/bssrdf_probe.comp: drives the shipped BSSRDF profile code
// (trace/bsdf/bssrdf.glsl) for tests/trace/bssrdf_sample_test.c, on table
// u_table of the bound tables with albedo u_rho and extinction u_sigma_t:
// mode 0 samples a radius per invocation (x: cv_bssrdf_sample_sr, < 0 for
// none); mode 1 evaluates the profile at given radii (x: Sr, y: its
// sampling density per unit area, pdf_Sr); mode 2 inverts effective
// albedos (x: cv_bssrdf_invert).
layout(local_size_x = 64) in;

#include "lib/index.glsl"
#include "lib/rng.glsl"
#include "lib/constants.glsl"
#include "lib/frame.glsl"
#include "trace/bsdf/material_buffers.glsl"
#include "trace/bsdf/bssrdf.glsl"

layout(std430, binding = CV_BIND_PROBE_IN) readonly buffer ProbeIn { vec4 probe_in[]; };
layout(std430, binding = CV_BIND_PROBE_OUT) writeonly buffer ProbeOut { vec4 probe_out[]; };

uniform uint u_mode;
uniform uint u_count;
uniform uint u_seed;
uniform uint u_table;
uniform float u_rho;
uniform float u_sigma_t;

void main()
{
    uint i = cv_global_index();
    if (i >= u_count)
        return;
    if (u_mode == 0u) {
        CvRng rng = cv_rng_init(u_seed, i);
        probe_out[i] = vec4(cv_bssrdf_sample_sr(u_table, u_rho, u_sigma_t, cv_rng_next2(rng).x));
    } else if (u_mode == 1u) {
        probe_out[i] = vec4(cv_bssrdf_sr(u_table, u_rho, u_sigma_t, probe_in[i].x), 0.0, 0.0);
    } else {
        probe_out[i] = vec4(cv_bssrdf_invert(u_table, probe_in[i].x));
    }
}
