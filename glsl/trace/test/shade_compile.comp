#version 450
// glsl/trace/test/shade_compile.comp: everything a shade kernel takes from
// the BSDF and light code, in one shader (material and light buffers
// together), one next-event estimation step with MIS; built by
// tests/trace/light_sampling_test to check that the interfaces combine.
layout(local_size_x = 64) in;

#include "lib/index.glsl"
#include "lib/rng.glsl"
#include "trace/bsdf/material_buffers.glsl"
#include "trace/light/light_buffers.glsl"
#include "trace/bsdf/bsdf.glsl"
#include "trace/light/light.glsl"

layout(std430, binding = CV_BIND_PROBE_OUT) writeonly buffer ShadeOut { vec4 shade_out[]; };

uniform uint u_count;

void main()
{
    uint i = cv_global_index();
    if (i >= u_count)
        return;
    CvRng rng = cv_rng_init(1u, i);
    vec3 wo = vec3(0.0, 0.0, 1.0);
    CvShadingPoint sp = CvShadingPoint(vec3(0.0), vec3(0.0, 0.0, 1.0), vec3(0.0, 0.0, 1.0),
                                       vec3(1.0, 0.0, 0.0), vec2(0.5), true);
    uint mat = cv_triangles[0].idx.w & CV_TRI_MATERIAL_MASK;
    if (cv_material_alpha_pass(mat, sp.uv, cv_rng_next(rng)))
        return;
    CvBsdf b = cv_bsdf_at(mat, sp, cv_rng_next(rng));
    cv_bsdf_set_stream(b, cv_rng_next2(rng), cv_rng_next2(rng));
    vec3 L = vec3(0.0);
    CvLightSample ls;
    if (cv_light_sample(sp.p, sp.ns, vec3(cv_rng_next(rng), cv_rng_next2(rng)), ls)) {
        vec3 f = cv_bsdf_f(b, wo, ls.wi) * abs(dot(ls.wi, sp.ns));
        float w = ls.delta ? 1.0 : cv_power_heuristic(ls.pdf, cv_bsdf_pdf(b, wo, ls.wi));
        L += f * ls.L * w / ls.pdf;
    }
    CvBsdfSample bs;
    if (cv_bsdf_sample(b, wo, cv_rng_next(rng), cv_rng_next2(rng), bs)) {
        float w = (bs.flags & CV_BSDF_SPECULAR) != 0u ? 1.0 : cv_power_heuristic(bs.pdf, cv_env_pdf(bs.wi));
        L += bs.f * abs(dot(bs.wi, sp.ns)) / bs.pdf * cv_env_Le(bs.wi) * w;
        L += cv_light_Le_area(0u, -bs.wi, sp.uv, true, sp.p) * cv_light_pdf_area(0u, sp.p, bs.wi, sp.ng);
    }
    shade_out[i] = vec4(L, cv_bsdf_is_delta(b) ? 1.0 : 0.0) + vec4(cv_bsdf_albedo(b), 0.0);
}
