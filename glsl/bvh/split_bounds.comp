#version 450
// glsl/bvh/split_bounds.comp: first level of the reduction of the scene
// box (the union of the triangles' boxes, not of their centroids) that
// triangle splitting places its grid in; bounds.comp reduces the workgroups'
// pairs further. Empty inputs reduce to (+big, -big).
#include "shared/scene.h"
#include "shared/bindings.h"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_VERTICES) readonly buffer Vertices { CvVertex verts[]; };
layout(std430, binding = CV_BIND_TRIANGLES) readonly buffer Triangles { CvTriangle tris[]; };
layout(std430, binding = CV_BIND_STAGE0 + 1) writeonly buffer OutBounds { vec4 out_b[]; };

uniform uint u_n;

shared vec3 s_min[256];
shared vec3 s_max[256];

void main()
{
    uint i = cv_global_index();
    vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
    if (i < u_n) {
        uvec4 t = tris[i].idx;
        vec3 a = verts[t.x].pos_u.xyz, b = verts[t.y].pos_u.xyz, c = verts[t.z].pos_u.xyz;
        lo = min(a, min(b, c));
        hi = max(a, max(b, c));
    }
    uint l = gl_LocalInvocationID.x;
    s_min[l] = lo;
    s_max[l] = hi;
    barrier();
    for (uint s = 128; s > 0; s >>= 1) {
        if (l < s) {
            s_min[l] = min(s_min[l], s_min[l + s]);
            s_max[l] = max(s_max[l], s_max[l + s]);
        }
        barrier();
    }
    if (l == 0) {
        uint g = i / 256u;
        out_b[2 * g] = vec4(s_min[0], 0.0);
        out_b[2 * g + 1] = vec4(s_max[0], 0.0);
    }
}
