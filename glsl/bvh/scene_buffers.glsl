// glsl/bvh/scene_buffers.glsl: the read-only buffers that traversal reads:
// scene vertices and triangles (mesh_buffers.glsl) and the BVH nodes,
// primitive order and leaf-ordered triangles (glsl/shared/bvh.h), at their
// fixed bindings. Include it once per shader, before glsl/bvh/traverse.glsl.
#ifndef CV_BVH_SCENE_BUFFERS_GLSL
#define CV_BVH_SCENE_BUFFERS_GLSL

#include "shared/bvh.h"
#include "shared/bindings.h"
#include "mesh_buffers.glsl"

layout(std430, binding = CV_BIND_BVH_NODES) readonly buffer CvBvhNodeBuffer { CvBvhNode4 cv_bvh_nodes[]; };
layout(std430, binding = CV_BIND_BVH_PRIMS) readonly buffer CvBvhPrimBuffer { uint cv_bvh_prims[]; };
layout(std430, binding = CV_BIND_BVH_TRIS) readonly buffer CvBvhTriBuffer { CvBvhTri cv_bvh_tris[]; };

#endif
