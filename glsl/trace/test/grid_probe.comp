#version 450
// glsl/trace/test/grid_probe.comp: drives the shipped grid-medium code
// (trace/medium/grid.glsl) for tests/trace/medium_grid_test.c, on medium
// u_medium of the bound scene. Mode 0: at render-space points probe_in[i]
// writes sigma_a (xyz) and the majorant of the point's cell (w), sigma_s,
// Le, and the point in the grid's unit cube (4 vec4 per point). Mode 1:
// for rays probe_in[2i] (origin, w: t1), probe_in[2i+1] (unit direction),
// the integral of the majorant over [0, t1] by the DDA walk (x) and the
// number of cells it visited (y). Modes 2 and 3 take the same rays, u_count
// = rays x u_samples invocations, each one estimate of sample j of ray
// i / u_samples (two vec4): mode 2, ratio tracking's transmittance; mode 3,
// delta tracking from r = 1 with hero channel j % 3: the weight if the walk
// passes t1 (an estimate of the transmittance), else 0; then the weight
// times sigma_t at the collision if it collides (of 1 minus it), else 0.
// Mode 4 (compiled with CV_MEDIUM_CLOUDS, tests/trace/medium_cloud_test.c):
// at points probe_in[i], the noise (x), its differences (yzw), and the
// density of cloud medium u_medium there in its medium space (two vec4).
#define CV_MEDIUM_GRIDS 1
layout(local_size_x = 64) in;

#include "lib/index.glsl"
#include "lib/constants.glsl"
#include "trace/bsdf/material_buffers.glsl"
#include "trace/sampler.glsl"
#include "trace/medium/medium.glsl"

layout(std430, binding = CV_BIND_PROBE_IN) readonly buffer ProbeIn { vec4 probe_in[]; };
layout(std430, binding = CV_BIND_PROBE_OUT) writeonly buffer ProbeOut { vec4 probe_out[]; };

uniform uint u_mode;
uniform uint u_count;
uniform uint u_medium;
uniform uint u_samples;

void main()
{
    uint i = cv_global_index();
    if (i >= u_count)
        return;
    uint m = u_medium;
    if (u_mode == 0u) {
        vec3 g = cv_grid_space(m, vec4(probe_in[i].xyz, 1.0));
        vec3 sa, ss, Le;
        cv_grid_point(m, g, sa, ss, Le);
        ivec3 c = clamp(ivec3(g * float(CV_MAJORANT_RES)), ivec3(0), ivec3(CV_MAJORANT_RES - 1u));
        probe_out[4u * i] = vec4(sa, cv_grid_majorant(m, c));
        probe_out[4u * i + 1u] = vec4(ss, 0.0);
        probe_out[4u * i + 2u] = vec4(Le, 0.0);
        probe_out[4u * i + 3u] = vec4(g, 0.0);
#ifdef CV_MEDIUM_CLOUDS
    } else if (u_mode == 4u) {
        vec3 p = probe_in[i].xyz;
        uint k = cv_media(m).grids.x;
        probe_out[2u * i] = vec4(cv_noise(p), cv_dnoise(p));
        probe_out[2u * i + 1u] = vec4(cv_cloud_density(p, cv_grid_float(k), cv_grid_float(k + 1u),
                                                       cv_grid_float(k + 2u)), 0.0, 0.0, 0.0);
#endif
    } else if (u_mode == 2u || u_mode == 3u) {
        // one estimate per invocation (llvmpipe cuts long loops short)
        uint ray = i / u_samples, j = i % u_samples;
        vec4 o = probe_in[2u * ray];
        vec3 d = probe_in[2u * ray + 1u].xyz;
        vec3 a = vec3(0.0), b = vec3(0.0);
        uvec3 key = uvec3(ray, j, 0x9e3779b9u * (u_mode + 1u));
        if (u_mode == 2u) {
            a = cv_grid_transmittance(m, o.xyz, d, 0.0, o.w, key);
        } else {
            uint n = 0u;
            vec3 r = vec3(1.0), w;
            float t;
            if (cv_grid_sample_distance(m, o.xyz, d, 0.0, o.w, j % 3u, key, n, r, t, w)) {
                vec3 sa, ss, Le;
                cv_grid_point(m, cv_grid_space(m, vec4(o.xyz + t * d, 1.0)), sa, ss, Le);
                b = w * (sa + ss);
            } else {
                a = w;
            }
        }
        probe_out[2u * i] = vec4(a, 0.0);
        probe_out[2u * i + 1u] = vec4(b, 0.0);
    } else {
        vec4 o = probe_in[2u * i];
        vec3 d = probe_in[2u * i + 1u].xyz;
        CvGridWalk w;
        float sum = 0.0, cells = 0.0;
        if (cv_grid_walk_start(m, o.xyz, d, 0.0, o.w, w)) {
            float ta, tb, maj;
            while (cv_grid_walk_next(m, w, ta, tb, maj) && cells < 1000.0) {
                sum += maj * (tb - ta);
                cells += 1.0;
            }
        }
        probe_out[i] = vec4(sum, cells, 0.0, 0.0);
    }
}
