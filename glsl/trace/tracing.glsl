// glsl/trace/tracing.glsl: ray queries against the BVH for the stages that
// trace (intersect, shadow). Include before geometry.glsl.
#ifndef CV_TRACE_TRACING_GLSL
#define CV_TRACE_TRACING_GLSL

#include "../bvh/scene_buffers.glsl"
// The renderer takes the driver's division in the triangle test: exact
// rounding costs a large share of traversal speed (glsl/bvh/triangle.glsl),
// and a hit distance one ulp apart between drivers changes no image.
// tests/bvh keeps the exact form, where BVH and brute force must agree bit
// for bit across drivers.
#define CV_BVH_FAST_DIV
#include "../bvh/traverse.glsl"

#endif
