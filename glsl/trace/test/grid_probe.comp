#version 450
// glsl/trace/test/grid_probe.comp: drives the shipped grid-medium code
// (trace/medium/grid.glsl) for tests/trace/medium_grid_test.c, on medium
// u_medium of the bound scene. Mode 0: at render-space points probe_in[i]
// writes sigma_a (xyz) and the majorant of the point's cell (w), sigma_s,
// Le, and the point in the grid's unit cube (4 vec4 per point). Mode 1:
// for rays probe_in[2i] (origin, w: t1), probe_in[2i+1] (unit direction),
// the integral of the majorant over [0, t1] by the DDA walk (x) and the
// number of cells it visited (y).
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
