// glsl/trace/bsdf/alpha.glsl: a material's cut-out ("alpha", a constant or
// a float texture), read by the rays' alpha test (bsdf.glsl:
// cv_material_alpha_pass) and by the light samples of a cut-out emitter
// (light/light.glsl, under CV_ALPHA_EMITTERS).
#ifndef CV_BSDF_ALPHA_GLSL
#define CV_BSDF_ALPHA_GLSL

#include "material_buffers.glsl"
#include "texture.glsl"

float cv_material_alpha(uint material, vec2 uv)
{
    CvMaterial m = materials[material];
    return m.alpha_tex >= 0 ? cv_tex_eval(m.alpha_tex, vec4(m.alpha), uv, 0.0).x : m.alpha;
}

#endif
