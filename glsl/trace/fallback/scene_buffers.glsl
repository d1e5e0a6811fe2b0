// glsl/trace/fallback/scene_buffers.glsl: the scene SSBOs at their fixed
// bindings (glsl/shared/bindings.h), for the pipeline's stand-in traversal
// and materials used until the BVH and BSDF stages provide theirs.
#ifndef CV_TRACE_FALLBACK_SCENE_BUFFERS_GLSL
#define CV_TRACE_FALLBACK_SCENE_BUFFERS_GLSL

#include "shared/scene.h"
#include "shared/bindings.h"

layout(std430, binding = CV_BIND_VERTICES) readonly buffer CvVertexBlock { CvVertex cv_vertices[]; };
layout(std430, binding = CV_BIND_TRIANGLES) readonly buffer CvTriangleBlock { CvTriangle cv_triangles[]; };
layout(std430, binding = CV_BIND_TRI_LIGHT) readonly buffer CvTriLightBlock { int cv_tri_light[]; };
layout(std430, binding = CV_BIND_MATERIALS) readonly buffer CvMaterialBlock { CvMaterial cv_materials[]; };
layout(std430, binding = CV_BIND_LIGHTS) readonly buffer CvLightBlock { CvLight cv_lights[]; };
layout(std430, binding = CV_BIND_LIGHT_CDF) readonly buffer CvLightCdfBlock { float cv_light_cdf[]; };

#endif
