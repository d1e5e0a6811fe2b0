// glsl/trace/bsdf/texture_buffers.glsl: the scene's texture table and
// texels (half RGBA pairs), read-only at their fixed bindings: the one
// declaration of these buffers, for the material code (texture.glsl) and
// the environment map (light/envmap.glsl).
#ifndef CV_BSDF_TEXTURE_BUFFERS_GLSL
#define CV_BSDF_TEXTURE_BUFFERS_GLSL

#include "shared/scene.h"
#include "shared/bindings.h"

layout(std430, binding = CV_BIND_TEXTURES) readonly buffer CvTextures { CvTexture textures[]; };
layout(std430, binding = CV_BIND_TEXELS) readonly buffer CvTexels { uvec2 texels[]; };

#endif
