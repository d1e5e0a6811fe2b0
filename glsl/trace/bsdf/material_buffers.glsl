// glsl/trace/bsdf/material_buffers.glsl: the scene's material and texture
// tables as the BSDF code reads them (read-only). Include once per shader,
// before bsdf.glsl.
#ifndef CV_BSDF_MATERIAL_BUFFERS_GLSL
#define CV_BSDF_MATERIAL_BUFFERS_GLSL

#include "shared/scene.h"
#include "shared/bindings.h"

layout(std430, binding = CV_BIND_MATERIALS) readonly buffer CvMaterials { CvMaterial materials[]; };
#ifndef CV_TEXTURE_BUFFERS_DECLARED
#define CV_TEXTURE_BUFFERS_DECLARED
layout(std430, binding = CV_BIND_TEXTURES) readonly buffer CvTextures { CvTexture textures[]; };
layout(std430, binding = CV_BIND_TEXELS) readonly buffer CvTexels { uvec2 texels[]; };
#endif

#endif
