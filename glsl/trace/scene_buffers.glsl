// glsl/trace/scene_buffers.glsl: the scene SSBOs the trace stages read
// beside those of glsl/bvh/scene_buffers.glsl (vertices, triangles, BVH), at
// their fixed bindings (glsl/shared/bindings.h).
#ifndef CV_TRACE_SCENE_BUFFERS_GLSL
#define CV_TRACE_SCENE_BUFFERS_GLSL

#include "shared/scene.h"
#include "shared/bindings.h"

layout(std430, binding = CV_BIND_TRI_LIGHT) readonly buffer CvTriLightBlock { int cv_tri_light[]; };
layout(std430, binding = CV_BIND_MATERIALS) readonly buffer CvMaterialBlock { CvMaterial cv_materials[]; };
layout(std430, binding = CV_BIND_LIGHTS) readonly buffer CvLightBlock { CvLight cv_lights[]; };
layout(std430, binding = CV_BIND_LIGHT_CDF) readonly buffer CvLightCdfBlock { float cv_light_cdf[]; };

#endif
