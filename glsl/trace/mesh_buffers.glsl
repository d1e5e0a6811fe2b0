// glsl/trace/mesh_buffers.glsl: the scene's vertices and triangles for
// stages that do not trace. Their blocks match glsl/bvh/scene_buffers.glsl,
// which declares them with the BVH's own buffers where a stage traces; the
// BVH buffers are left out here because Mesa counts every declared storage
// block against its 16.
#ifndef CV_TRACE_MESH_BUFFERS_GLSL
#define CV_TRACE_MESH_BUFFERS_GLSL
#ifndef CV_BVH_SCENE_BUFFERS_GLSL

#include "shared/scene.h"
#include "shared/bindings.h"

layout(std430, binding = CV_BIND_VERTICES) readonly buffer CvVertexBuffer { CvVertex cv_vertices[]; };
layout(std430, binding = CV_BIND_TRIANGLES) readonly buffer CvTriangleBuffer { CvTriangle cv_triangles[]; };
// same names as the BVH's declaration: later code (light_buffers.glsl)
// takes them as that one (tracing stages include tracing.glsl first)
#define CV_BVH_SCENE_BUFFERS_GLSL

#endif
#endif
