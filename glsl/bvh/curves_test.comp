#version 450
// glsl/bvh/curves_test.comp: for tests/bvh/curves_test. One ray per
// invocation, (origin, tmin), (dir, tmax), against the curves alone: the
// closest hit through the curve tree and by brute force over every curve,
// both any-hit forms, and the frame of the closest hit. Out, 4 per ray:
// (t, prim, u, v) of the tree walk, the same of the brute force, (any
// walk, any brute, -, -) and (normal, p_err) of the walk's hit (bits as
// uints; prim 0xffffffff on a miss).
#include "curves.glsl"

layout(local_size_x = 64) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_PROBE_IN) readonly buffer Rays { vec4 rays[]; };
layout(std430, binding = CV_BIND_PROBE_OUT) writeonly buffer Results { uvec4 results[]; };

uniform uint u_n_rays;

void main()
{
    uint i = cv_global_index();
    if (i >= u_n_rays)
        return;
    vec4 a = rays[2 * i], b = rays[2 * i + 1];
    float t0 = b.w, u0 = 0.0, v0 = 0.0, t1 = b.w, u1 = 0.0, v1 = 0.0, t2 = b.w, u2 = 0.0, v2 = 0.0,
          t3 = b.w, u3 = 0.0, v3 = 0.0;
    uint p0 = 0xffffffffu, p1 = 0xffffffffu, p2 = 0xffffffffu, p3 = 0xffffffffu;
    cv_curves_walk(a.xyz, b.xyz, a.w, false, t0, p0, u0, v0);
    cv_curves_brute(a.xyz, b.xyz, a.w, false, t1, p1, u1, v1);
    bool any_walk = cv_curves_walk(a.xyz, b.xyz, a.w, true, t2, p2, u2, v2);
    bool any_brute = cv_curves_brute(a.xyz, b.xyz, a.w, true, t3, p3, u3, v3);
    vec3 n = vec3(0.0), dpdu;
    float p_err = 0.0;
    uint word;
    if (p0 != 0xffffffffu)
        cv_curve_frame(p0 & ~CV_PRIM_CURVE, u0, v0, b.xyz, dpdu, n, p_err, word);
    results[4u * i] = uvec4(floatBitsToUint(t0), p0, floatBitsToUint(u0), floatBitsToUint(v0));
    results[4u * i + 1u] = uvec4(floatBitsToUint(t1), p1, floatBitsToUint(u1), floatBitsToUint(v1));
    results[4u * i + 2u] = uvec4(any_walk ? 1u : 0u, any_brute ? 1u : 0u, 0u, 0u);
    results[4u * i + 3u] = floatBitsToUint(vec4(n, p_err));
}
