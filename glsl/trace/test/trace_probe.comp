#version 450
// glsl/trace/test/trace_probe.comp: for bench/rt_probe, which times it. One
// query per ray through tracing.glsl, the traversal as intersect.comp and
// shadow.comp compile it, in their group size: closest hit, or with
// CV_PROBE_ANY_HIT any hit. Rays: (origin, tmin), (dir, tmax). Result:
// (t bits, prim); prim 0xffffffff on a miss; an any-hit query that finds
// an occluder reports prim 0 and t = tmax.
#include "shared/trace.h"
layout(local_size_x = CV_TRACE_GROUP) in;
#include "trace/tracing.glsl"
#include "lib/index.glsl"

layout(std430, binding = CV_BIND_PROBE_IN) readonly buffer Rays { vec4 rays[]; };
layout(std430, binding = CV_BIND_PROBE_OUT) writeonly buffer Results { uvec2 results[]; };

uniform uint u_n_rays;

void main()
{
    uint i = cv_global_index();
    if (i >= u_n_rays)
        return;
    vec4 a = rays[2 * i], b = rays[2 * i + 1];
#ifdef CV_PROBE_ANY_HIT
    bool occluded = cv_trace_any(a.xyz, b.xyz, a.w, b.w);
    results[i] = uvec2(floatBitsToUint(b.w), occluded ? 0u : 0xffffffffu);
#else
    CvHit hit;
    cv_trace_closest(a.xyz, b.xyz, a.w, b.w, hit);
    results[i] = uvec2(floatBitsToUint(hit.t), hit.prim);
#endif
}
