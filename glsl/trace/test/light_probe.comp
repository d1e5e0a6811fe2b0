#version 450
// glsl/trace/test/light_probe.comp: drives the shipped light-sampling code
// for tests/trace/light_*: mode 0 samples lights from the point u_p; mode 1
// evaluates cv_env_Le / cv_env_pdf at given directions; mode 2 evaluates
// cv_light_pdf_area for given light points (xyz) of light u_light, with the
// normal u_n_light.
layout(local_size_x = 64) in;

#include "lib/index.glsl"
#include "lib/rng.glsl"
#include "trace/light/light_buffers.glsl"
#include "trace/light/light.glsl"

layout(std430, binding = CV_BIND_PROBE_IN) readonly buffer ProbeIn { vec4 probe_in[]; };
layout(std430, binding = CV_BIND_PROBE_OUT) writeonly buffer ProbeOut { vec4 probe_out[]; };

uniform uint u_mode;
uniform uint u_count;
uniform uint u_seed;
uniform uint u_light;
uniform vec3 u_p;
uniform vec3 u_n_light;

void main()
{
    uint i = cv_global_index();
    if (i >= u_count)
        return;
    if (u_mode == 0u) {
        CvRng rng = cv_rng_init(u_seed, i);
        vec3 u3 = vec3(cv_rng_next(rng), cv_rng_next2(rng));
        CvLightSample s;
        bool ok = cv_light_sample(u_p, vec3(0.0, 0.0, 1.0), u3, s);
        if (!ok && s.pdf > 0.0 && !s.delta) {
            // a direction was sampled but carries no radiance: it still
            // belongs in the histogram
            probe_out[2u * i] = vec4(s.wi, s.pdf);
            probe_out[2u * i + 1u] = vec4(0.0, 0.0, 0.0, s.dist);
            return;
        }
        if (!ok) {
            probe_out[2u * i] = vec4(0.0, 0.0, 0.0, -1.0);
            probe_out[2u * i + 1u] = vec4(0.0);
            return;
        }
        probe_out[2u * i] = vec4(s.wi, s.pdf);
        probe_out[2u * i + 1u] = vec4(s.L, s.delta ? -s.dist : s.dist);
    } else if (u_mode == 1u) {
        vec3 d = probe_in[i].xyz;
        probe_out[i] = vec4(cv_env_Le(d), cv_env_pdf(d));
    } else {
        probe_out[i] = vec4(cv_light_pdf_area(u_light, u_p, probe_in[i].xyz, u_n_light));
    }
}
