// glsl/bvh/mesh_buffers.glsl: the scene's vertices and triangles
// (glsl/shared/scene.h), read-only at their fixed bindings: the one
// declaration of these buffers for every shader that reads them (the BVH
// build and traversal, and the trace stages' geometry and lights).
#ifndef CV_BVH_MESH_BUFFERS_GLSL
#define CV_BVH_MESH_BUFFERS_GLSL

#include "shared/scene.h"
#include "shared/bindings.h"

layout(std430, binding = CV_BIND_VERTICES) readonly buffer CvVertexBuffer { CvVertex cv_vertices[]; };
layout(std430, binding = CV_BIND_TRIANGLES) readonly buffer CvTriangleBuffer { CvTriangle cv_triangles[]; };

#endif
