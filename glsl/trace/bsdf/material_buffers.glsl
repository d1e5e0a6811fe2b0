// glsl/trace/bsdf/material_buffers.glsl: the scene's material table and
// the textures materials read, as the BSDF code reads them (read-only).
// Include before bsdf.glsl.
#ifndef CV_BSDF_MATERIAL_BUFFERS_GLSL
#define CV_BSDF_MATERIAL_BUFFERS_GLSL

#include "shared/scene.h"
#include "shared/bindings.h"
#include "texture_buffers.glsl"

layout(std430, binding = CV_BIND_MATERIALS) readonly buffer CvMaterials { CvMaterial materials[]; };
#ifndef CV_NO_MEASURED
// the measured BRDFs' tables (glsl/shared/measured.h, bsdf/measured.glsl),
// a buffer texture: no storage block (a kernel may bind only 16)
layout(binding = CV_TEXUNIT_MEASURED) uniform usamplerBuffer cv_measured_tex;
uint cv_measured(uint i) { return texelFetch(cv_measured_tex, int(i)).r; }
#endif

#endif
