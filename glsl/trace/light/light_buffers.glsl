// glsl/trace/light/light_buffers.glsl: the buffers light sampling reads:
// lights, the light-selection CDF, environment-map distributions, and the
// scene geometry and textures (declared once, in glsl/bvh/mesh_buffers.glsl
// and glsl/trace/bsdf/texture_buffers.glsl).
//
// light_cdf has one entry per light: light_cdf[i] = sum of the selection
// probabilities of lights 0..i (by power), the last entry 1.
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
layout(std430, binding = CV_BIND_LIGHT_CDF) readonly buffer CvLightCdf { float light_cdf[]; };
layout(std430, binding = CV_BIND_ENV_DIST) readonly buffer CvEnvDist { float env_dist[]; };

#endif
