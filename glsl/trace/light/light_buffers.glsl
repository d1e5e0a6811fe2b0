// glsl/trace/light/light_buffers.glsl: the buffers light sampling reads:
// lights, the light-selection CDF, environment-map distributions, and the
// scene geometry and textures (declared once, in glsl/bvh/mesh_buffers.glsl
// and glsl/trace/bsdf/texture_buffers.glsl).
//
// The light-selection CDF has one entry per light (cv_light_cdf_at): the
// sum of the selection probabilities of lights 0..i (by power), the last
// entry 1; a buffer texture (shared/bindings.h says why).
// Infinite lights (CV_LIGHT_INFINITE, CV_LIGHT_INFINITE_MAP) must come
// first in lights[]: cv_env_Le / cv_env_pdf stop at the first other light.
// The scene builder orders them so (src/scene/scene.h).
#ifndef CV_LIGHT_BUFFERS_GLSL
#define CV_LIGHT_BUFFERS_GLSL

#include "shared/scene.h"
#include "shared/bindings.h"
#include "shared/envmap.h"
#include "../../bvh/mesh_buffers.glsl"
#include "../bsdf/texture_buffers.glsl"

layout(std430, binding = CV_BIND_LIGHTS) readonly buffer CvLights { CvLight lights[]; };
layout(binding = CV_TEXUNIT_LIGHT_CDF) uniform samplerBuffer cv_light_cdf_tex;
float cv_light_cdf_at(uint i) { return texelFetch(cv_light_cdf_tex, int(i)).x; }
layout(std430, binding = CV_BIND_ENV_DIST) readonly buffer CvEnvDist { float env_dist[]; };

#endif
