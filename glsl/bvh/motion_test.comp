#version 450
// glsl/bvh/motion_test.comp: for tests/bvh/motion_test. One ray per
// invocation, (origin, tmin), (dir, tmax), at time u_time, against the
// moving shapes alone, by the query MOTION_QUERY names: 0 closest hit
// through the trees, 1 closest by brute force over every moving triangle,
// 2 and 3 the any-hit forms. One query a program: llvmpipe ends a loop
// after 65535 turns, which the brute-force queries together would pass
// (answers then went missing). Out, one per ray:
// (t, prim, b1, b2), bits as uints, prim 0xffffffff on a miss; the
// any-hit forms (found, -, -, -). With CV_HAS_CURVES, the moving shapes'
// curves too (the curves' buffer bound as the renderer binds it).
// (Included files expand once, where first named, whatever #ifdef is
// around them: curves.glsl's own includes come first, outside it.)
#include "shared/scene.h"
#include "shared/bvh.h"
#include "shared/bindings.h"
#ifdef CV_HAS_CURVES
#include "curves.glsl"
#endif
#include "motion.glsl"

layout(local_size_x = 64) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_PROBE_IN) readonly buffer Rays { vec4 rays[]; };
layout(std430, binding = CV_BIND_PROBE_OUT) writeonly buffer Results { uvec4 results[]; };

uniform uint u_n_rays;
uniform float u_time;

void main()
{
    uint i = cv_global_index();
    if (i >= u_n_rays)
        return;
    cv_trace_time = u_time;
    vec4 a = rays[2 * i], b = rays[2 * i + 1];
    float t = b.w, b1 = 0.0, b2 = 0.0;
    uint prim = 0xffffffffu;
#if MOTION_QUERY == 0
    cv_motion_walk(a.xyz, b.xyz, a.w, false, t, prim, b1, b2);
#elif MOTION_QUERY == 1
    cv_motion_brute(a.xyz, b.xyz, u_time, a.w, false, t, prim, b1, b2);
#elif MOTION_QUERY == 2
    prim = cv_motion_walk(a.xyz, b.xyz, a.w, true, t, prim, b1, b2) ? 1u : 0u;
#else
    prim = cv_motion_brute(a.xyz, b.xyz, u_time, a.w, true, t, prim, b1, b2) ? 1u : 0u;
#endif
    results[i] = uvec4(floatBitsToUint(t), prim, floatBitsToUint(b1), floatBitsToUint(b2));
}
