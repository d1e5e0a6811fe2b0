#version 450
// glsl/bvh/morton.comp: Morton code of each triangle's centroid inside the
// centroid bounds: 30 bits (1024 cells per axis), or with KEY64 60 bits
// (2^20 cells per axis) stored as two words, low first. Writes the key and
// the triangle index as the value for the radix sort, and the triangle's
// box for refit.comp: written here in input order, one coalesced pass,
// because gathering triangles and vertices in sorted order from refit
// reads at random over large buffers, which falls off a cliff on NVIDIA
// past a few hundred MB (bench/RESULTS.md, "Figures behind the code").
// With FROM_BOXES the elements are split references (src/bvh/split.h) whose
// boxes are already there: the key is of the box's centre.
#include "shared/scene.h"
#include "shared/bindings.h"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"

#include "mesh_buffers.glsl"
layout(std430, binding = CV_BIND_BUILD_BOUNDS) readonly buffer Bounds { vec4 bounds[]; };
layout(std430, binding = CV_BIND_MORTON_KEYS) writeonly buffer Keys { uint keys[]; };
layout(std430, binding = CV_BIND_MORTON_VALS) writeonly buffer Vals { uint vals[]; };
#ifdef FROM_BOXES
layout(std430, binding = CV_BIND_LEAF_BOXES) readonly buffer LeafBoxes { vec4 leaf_boxes[]; };
#else
layout(std430, binding = CV_BIND_LEAF_BOXES) writeonly buffer LeafBoxes { vec4 leaf_boxes[]; };
#endif

uniform uint u_n;

uint spread10(uint x)
{
    x &= 0x3ffu;
    x = (x | (x << 16)) & 0x030000ffu;
    x = (x | (x << 8)) & 0x0300f00fu;
    x = (x | (x << 4)) & 0x030c30c3u;
    x = (x | (x << 2)) & 0x09249249u;
    return x;
}

void main()
{
    uint i = cv_global_index();
    if (i >= u_n)
        return;
#ifdef FROM_BOXES
    vec3 c = (leaf_boxes[2u * i].xyz + leaf_boxes[2u * i + 1u].xyz) * 0.5;
#else
    uvec4 t = cv_triangles[i].idx;
    vec3 a = cv_vertices[t.x].pos_u.xyz, b = cv_vertices[t.y].pos_u.xyz, c3 = cv_vertices[t.z].pos_u.xyz;
    leaf_boxes[2u * i] = vec4(min(a, min(b, c3)), 0.0);
    leaf_boxes[2u * i + 1u] = vec4(max(a, max(b, c3)), 0.0);
    vec3 c = (a + b + c3) * (1.0 / 3.0);
#endif
    vec3 lo = bounds[0].xyz, ext = bounds[1].xyz - lo;
    // A flat axis (all centroids equal there) maps to cell 0.
    vec3 inv = vec3(ext.x > 0.0 ? 1.0 / ext.x : 0.0, ext.y > 0.0 ? 1.0 / ext.y : 0.0,
                    ext.z > 0.0 ? 1.0 / ext.z : 0.0);
#ifdef KEY64
    // Interleaving is bitwise, so the high 10 bits of each axis make the
    // high 30 bits of the code.
    uvec3 q = uvec3(clamp((c - lo) * inv * 1048576.0, vec3(0.0), vec3(1048575.0)));
    uint low = (spread10(q.x) << 2) | (spread10(q.y) << 1) | spread10(q.z);
    uvec3 h = q >> 10;
    uint high = (spread10(h.x) << 2) | (spread10(h.y) << 1) | spread10(h.z);
    keys[2u * i] = low | (high << 30);
    keys[2u * i + 1u] = high >> 2;
#else
    uvec3 q = uvec3(clamp((c - lo) * inv * 1024.0, vec3(0.0), vec3(1023.0)));
    keys[i] = (spread10(q.x) << 2) | (spread10(q.y) << 1) | spread10(q.z);
#endif
    vals[i] = i;
}
