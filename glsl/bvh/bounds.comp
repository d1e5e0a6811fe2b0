#version 450
// glsl/bvh/bounds.comp: the scene's centroid bounds in one dispatch. Each
// workgroup reduces a grid-strided share of the triangles' centroids (K per
// invocation and step, their loads issued together) and writes its (min,
// max) pair to bounds[2 + 2 * group]; the last group to finish, told by an
// atomic counter that src/bvh/bounds.c clears, reduces those pairs into
// bounds[0..1]. One dispatch instead of one level per factor of 256: the
// levels' dispatches and barriers cost more than the reduction from a few
// million triangles on (bench/RESULTS.md, "Figures behind the code").
// With FROM_BOXES the centroids are the centres of split references' boxes
// (src/bvh/split.h) instead of the triangles'; with SCENE_BOX the result is
// the union of the triangles' boxes, in which splitting lays its grid.
// src/bvh/bounds.h dispatches it. Empty inputs reduce to (+big, -big).
#include "shared/scene.h"
#include "shared/bindings.h"

#define THREADS 256
#define K 4  // src/bvh/bounds.c counts on THREADS * K = 1024
layout(local_size_x = THREADS) in;

#ifdef FROM_BOXES
layout(std430, binding = CV_BIND_LEAF_BOXES) readonly buffer Boxes { vec4 boxes[]; };
#else
#include "mesh_buffers.glsl"
#endif
// The result at [0..1], each group's pair after it; read by morton.comp.
layout(std430, binding = CV_BIND_BOUNDS_OUT) coherent buffer Bounds { vec4 bounds[]; };
// [0]: groups finished; zero when the dispatch starts.
layout(std430, binding = CV_BIND_BOUNDS_DONE) coherent buffer Done { uint done[]; };

uniform uint u_n;

shared vec3 s_min[THREADS];
shared vec3 s_max[THREADS];
shared bool s_last;

// Leaves the group's (min, max) of lo, hi in s_min[0], s_max[0].
void group_reduce(uint l, vec3 lo, vec3 hi)
{
    s_min[l] = lo;
    s_max[l] = hi;
    barrier();
    for (uint s = uint(THREADS) / 2u; s > 0u; s >>= 1) {
        if (l < s) {
            s_min[l] = min(s_min[l], s_min[l + s]);
            s_max[l] = max(s_max[l], s_max[l + s]);
        }
        barrier();
    }
}

void main()
{
    uint l = gl_LocalInvocationID.x, g = gl_WorkGroupID.x, groups = gl_NumWorkGroups.x;
    vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
    uint stride = groups * uint(THREADS * K);
    for (uint base = g * uint(THREADS * K) + l; base < u_n; base += stride) {
#ifdef FROM_BOXES
        for (uint k = 0u; k < uint(K); k++) {
            uint i = base + k * uint(THREADS);
            if (i < u_n) {
                vec3 c = (boxes[2u * i].xyz + boxes[2u * i + 1u].xyz) * 0.5;
                lo = min(lo, c);
                hi = max(hi, c);
            }
        }
#else
        uvec4 t[K];
        for (uint k = 0u; k < uint(K); k++) {
            uint i = base + k * uint(THREADS);
            t[k] = i < u_n ? cv_triangles[i].idx : uvec4(0u);
        }
        for (uint k = 0u; k < uint(K); k++) {
            if (base + k * uint(THREADS) < u_n) {
                vec3 a = cv_vertices[t[k].x].pos_u.xyz, b = cv_vertices[t[k].y].pos_u.xyz,
                     c = cv_vertices[t[k].z].pos_u.xyz;
#ifdef SCENE_BOX
                lo = min(lo, min(a, min(b, c)));
                hi = max(hi, max(a, max(b, c)));
#else
                vec3 m = (a + b + c) * (1.0 / 3.0);
                lo = min(lo, m);
                hi = max(hi, m);
#endif
            }
        }
#endif
    }
    group_reduce(l, lo, hi);
    if (l == 0u) {
        bounds[2u + 2u * g] = vec4(s_min[0], 0.0);
        bounds[3u + 2u * g] = vec4(s_max[0], 0.0);
        // Our pair is visible before the count says so.
        memoryBarrierBuffer();
        s_last = atomicAdd(done[0], 1u) == groups - 1u;
    }
    barrier();
    if (!s_last)
        return;
    memoryBarrierBuffer();
    lo = vec3(3.0e38);
    hi = vec3(-3.0e38);
    for (uint j = l; j < groups; j += uint(THREADS)) {
        lo = min(lo, bounds[2u + 2u * j].xyz);
        hi = max(hi, bounds[3u + 2u * j].xyz);
    }
    group_reduce(l, lo, hi);
    if (l == 0u) {
        bounds[0] = vec4(s_min[0], 0.0);
        bounds[1] = vec4(s_max[0], 0.0);
    }
}
