// glsl/trace/shading.glsl: where the trace stages get materials and lights
// from (one place to switch between the BSDF stage's GLSL and the stand-ins).
#ifndef CV_TRACE_SHADING_GLSL
#define CV_TRACE_SHADING_GLSL

#include "geometry.glsl"
#include "fallback/bsdf_basic.glsl"
#include "fallback/light_basic.glsl"

#endif
