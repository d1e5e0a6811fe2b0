#version 450
// glsl/bvh/rays_test.comp: for tests and the benchmark. Traces one ray per
// invocation either through the BVH (traverse.glsl) or, with BRUTE_FORCE,
// against every triangle with the same watertight routine and the same
// tie rule (lowest t, then lowest index). Rays: (origin, tmin), (dir, tmax).
// Result: (t bits, prim, any-hit, nodes visited by both traversals, 0 for
// the brute force); prim = 0xffffffff on a miss. The brute force's any-hit
// uses the any-hit triangle test, so with CV_BVH_FAST_DIV defined (the
// renderer's form, glsl/trace/tracing.glsl) both sides still run the same
// arithmetic and must agree exactly.
#define CV_BVH_COUNT_STEPS
#include "scene_buffers.glsl"
#include "traverse.glsl"

layout(local_size_x = 64) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_PROBE_IN) readonly buffer Rays { vec4 rays[]; };
layout(std430, binding = CV_BIND_PROBE_OUT) writeonly buffer Results { uvec4 results[]; };

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
        if (cv_bvh_tri(r, p, t, b1, b2) && t > a.w && t < b.w &&
            (t < hit.t || (t == hit.t && p < hit.prim)))
            hit = CvHit(t, p, b1, b2);
        uvec4 idx = cv_triangles[p].idx;
        any = any || cv_ray_tri_any(r, cv_vertices[idx.x].pos_u.xyz, cv_vertices[idx.y].pos_u.xyz,
                                    cv_vertices[idx.z].pos_u.xyz, a.w, b.w);
    }
#else
    cv_trace_closest(a.xyz, b.xyz, a.w, b.w, hit);
    any = cv_trace_any(a.xyz, b.xyz, a.w, b.w);
#endif
    #ifdef BRUTE_FORCE
    uint steps = 0u;
#else
    uint steps = cv_bvh_steps;
#endif
    results[i] = uvec4(floatBitsToUint(hit.t), hit.prim, any ? 1u : 0u, steps);
}
