// glsl/trace/materials.glsl: where the trace stages get materials (BSDFs,
// alpha cut-outs) from: the BSDF stage's GLSL, or bsdf_basic.glsl when the
// host defines CV_BSDF_BASIC (the include stays inside the #if: includes are
// expanded in place).
#ifndef CV_TRACE_MATERIALS_GLSL
#define CV_TRACE_MATERIALS_GLSL

#include "bsdf/material_buffers.glsl"
// outside the #if: the loader includes a file once, and light.glsl needs it
#include "../lib/constants.glsl"
// likewise for medium/medium.glsl (volpath's phase sampling)
#include "../lib/frame.glsl"
#include "bsdf/texture.glsl"
// both BSDF interfaces answer the same query
#include "bsdf/bsdf_query.glsl"
#ifdef CV_BSDF_BASIC
#include "bsdf_basic.glsl"
#else
#include "bsdf/bsdf.glsl"
#endif

#endif
