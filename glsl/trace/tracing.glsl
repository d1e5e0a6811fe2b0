// glsl/trace/tracing.glsl: ray queries against the BVH for the stages that
// trace (intersect, shadow). Include before geometry.glsl.
#ifndef CV_TRACE_TRACING_GLSL
#define CV_TRACE_TRACING_GLSL

#include "../bvh/scene_buffers.glsl"
#include "../bvh/traverse.glsl"

#endif
