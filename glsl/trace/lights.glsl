// glsl/trace/lights.glsl: where the trace stages get light sampling and
// emission from. Include after geometry.glsl.
#ifndef CV_TRACE_LIGHTS_GLSL
#define CV_TRACE_LIGHTS_GLSL

#include "scene_buffers.glsl"
#include "light/light_buffers.glsl"
#include "light/light.glsl"

#endif
