#version 450
// glsl/bvh/bounds.comp: one level of the parallel reduction of the scene's
// centroid bounds. With FROM_TRIANGLES each invocation takes one triangle's
// centroid, with FROM_BOXES the centre of one box (split references,
// src/bvh/split.h); otherwise it takes one (min, max) pair that the previous level
// wrote. Each workgroup writes one pair to u_out; the host repeats until one
// pair is left. Empty inputs reduce to (+big, -big).
#include "shared/scene.h"
#include "shared/bindings.h"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"

#ifdef FROM_TRIANGLES
layout(std430, binding = CV_BIND_VERTICES) readonly buffer Vertices { CvVertex verts[]; };
layout(std430, binding = CV_BIND_TRIANGLES) readonly buffer Triangles { CvTriangle tris[]; };
#elif defined(FROM_BOXES)
layout(std430, binding = CV_BIND_STAGE0 + 3) readonly buffer Boxes { vec4 boxes[]; };
#else
layout(std430, binding = CV_BIND_STAGE0) readonly buffer InBounds { vec4 in_b[]; };
#endif
layout(std430, binding = CV_BIND_STAGE0 + 1) writeonly buffer OutBounds { vec4 out_b[]; };

uniform uint u_n;

shared vec3 s_min[256];
shared vec3 s_max[256];

void main()
{
    uint i = cv_global_index();
    vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
    if (i < u_n) {
#ifdef FROM_TRIANGLES
        uvec4 t = tris[i].idx;
        vec3 c = (verts[t.x].pos_u.xyz + verts[t.y].pos_u.xyz + verts[t.z].pos_u.xyz) * (1.0 / 3.0);
        lo = c;
        hi = c;
#elif defined(FROM_BOXES)
        lo = (boxes[2 * i].xyz + boxes[2 * i + 1].xyz) * 0.5;
        hi = lo;
#else
        lo = in_b[2 * i].xyz;
        hi = in_b[2 * i + 1].xyz;
#endif
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
