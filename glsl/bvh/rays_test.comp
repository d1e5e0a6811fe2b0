#version 450
// glsl/bvh/rays_test.comp: for tests and the benchmark. Traces one ray per
// invocation either through the BVH (traverse.glsl) or, with BRUTE_FORCE,
// against every triangle with the same watertight routine and the same
// tie rule (lowest t, then lowest index). Rays: (origin, tmin), (dir, tmax).
// Result: (t bits, prim, any-hit, 0); prim = 0xffffffff on a miss.
#include "scene_buffers.glsl"
#include "traverse.glsl"

layout(local_size_x = 64) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_STAGE0) readonly buffer Rays { vec4 rays[]; };
layout(std430, binding = CV_BIND_STAGE0 + 1) writeonly buffer Results { uvec4 results[]; };

uniform uint u_n_rays;
uniform uint u_n_tris;

void main()
{
    uint i = cv_global_index();
    if (i >= u_n_rays)
        return;
    vec4 a = rays[2 * i], b = rays[2 * i + 1];
    CvHit hit;
    bool any;
#ifdef BRUTE_FORCE
    CvRayTri r = cv_ray_tri_setup(a.xyz, b.xyz);
    hit = CvHit(b.w, 0xffffffffu, 0.0, 0.0);
    any = false;
    for (uint p = 0; p < u_n_tris; p++) {
        float t, b1, b2;
        if (cv_bvh_tri(r, p, t, b1, b2) && t > a.w && t < b.w) {
            any = true;
            if (t < hit.t || (t == hit.t && p < hit.prim))
                hit = CvHit(t, p, b1, b2);
        }
    }
#else
    cv_trace_closest(a.xyz, b.xyz, a.w, b.w, hit);
    any = cv_trace_any(a.xyz, b.xyz, a.w, b.w);
#endif
    results[i] = uvec4(floatBitsToUint(hit.t), hit.prim, any ? 1u : 0u, 0u);
}
