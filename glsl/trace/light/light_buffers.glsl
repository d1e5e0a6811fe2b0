// glsl/trace/light/light_buffers.glsl: the buffers light sampling reads:
// lights, the light-selection CDF, environment-map distributions, and the
// scene geometry and textures (shared with the BVH and material code: each
// group is declared once under its guard, with the same block names).
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

layout(std430, binding = CV_BIND_LIGHTS) readonly buffer CvLights { CvLight lights[]; };
layout(std430, binding = CV_BIND_LIGHT_CDF) readonly buffer CvLightCdf { float light_cdf[]; };
layout(std430, binding = CV_BIND_ENV_DIST) readonly buffer CvEnvDist { float env_dist[]; };

// Vertices and triangles: light.glsl reads them as CV_LIGHT_VERTS[] and
// CV_LIGHT_TRIS[], whichever declaration came first: ours (or another with
// the same names under CV_SCENE_BUFFERS_DECLARED), or
// glsl/bvh/scene_buffers.glsl's cv_vertices / cv_triangles. Including the
// BVH's file after this one is fine too: SSBO blocks may alias a binding.
#if defined(CV_SCENE_BUFFERS_DECLARED)
#define CV_LIGHT_VERTS vertices
#define CV_LIGHT_TRIS triangles
#elif defined(CV_BVH_SCENE_BUFFERS_GLSL)
#define CV_LIGHT_VERTS cv_vertices
#define CV_LIGHT_TRIS cv_triangles
#else
#define CV_SCENE_BUFFERS_DECLARED
layout(std430, binding = CV_BIND_VERTICES) readonly buffer CvVertices { CvVertex vertices[]; };
layout(std430, binding = CV_BIND_TRIANGLES) readonly buffer CvTriangles { CvTriangle triangles[]; };
#define CV_LIGHT_VERTS vertices
#define CV_LIGHT_TRIS triangles
#endif

#ifndef CV_TEXTURE_BUFFERS_DECLARED
#define CV_TEXTURE_BUFFERS_DECLARED
layout(std430, binding = CV_BIND_TEXTURES) readonly buffer CvTextures { CvTexture textures[]; };
layout(std430, binding = CV_BIND_TEXELS) readonly buffer CvTexels { uvec2 texels[]; };
#endif

#endif
