// glsl/trace/bsdf/conductor.glsl: Trowbridge-Reitz conductor with complex
// Fresnel (pbrt-v4 ConductorBxDF), local frame; perfectly specular below
// CV_SMOOTH_ALPHA. Symmetric in the sign of z, hence two-sided.
#ifndef CV_BSDF_CONDUCTOR_GLSL
#define CV_BSDF_CONDUCTOR_GLSL

#include "fresnel.glsl"
#include "microfacet.glsl"
#include "bsdf_sample.glsl"

vec3 cv_conductor_f(vec2 alpha, vec3 eta, vec3 k, vec3 wo, vec3 wi)
{
    if (!cv_same_hemisphere(wo, wi) || cv_mf_smooth(alpha))
        return vec3(0.0);
    float co = abs(wo.z), ci = abs(wi.z);
    if (ci == 0.0 || co == 0.0)
        return vec3(0.0);
    vec3 wm = wi + wo;
    if (dot(wm, wm) == 0.0)
        return vec3(0.0);
    wm = normalize(wm);
    vec3 F = cv_fr_complex(abs(dot(wo, wm)), eta, k);
    return cv_mf_D(alpha, wm) * F * cv_mf_G(alpha, wo, wi) / (4.0 * ci * co);
}

float cv_conductor_pdf(vec2 alpha, vec3 wo, vec3 wi)
{
    if (!cv_same_hemisphere(wo, wi) || cv_mf_smooth(alpha))
        return 0.0;
    vec3 wm = wo + wi;
    if (dot(wm, wm) == 0.0)
        return 0.0;
    wm = normalize(wm);
    if (wm.z < 0.0)
        wm = -wm;
    return cv_mf_pdf(alpha, wo, wm) / (4.0 * abs(dot(wo, wm)));
}

bool cv_conductor_sample(vec2 alpha, vec3 eta, vec3 k, vec3 wo, vec2 u, out CvBsdfSample s)
{
    s = CvBsdfSample(vec3(0.0), vec3(0.0), 0.0, 0u);
    if (wo.z == 0.0)
        return false;
    if (cv_mf_smooth(alpha)) {
        vec3 wi = vec3(-wo.x, -wo.y, wo.z);
        s = CvBsdfSample(wi, cv_fr_complex(abs(wi.z), eta, k) / abs(wi.z), 1.0,
                         CV_BSDF_REFLECTION | CV_BSDF_SPECULAR);
        return true;
    }
    vec3 wm = cv_mf_sample_wm(alpha, wo, u);
    vec3 wi = reflect(-wo, wm);
    if (!cv_same_hemisphere(wo, wi))
        return false;
    float pdf = cv_mf_pdf(alpha, wo, wm) / (4.0 * abs(dot(wo, wm)));
    float co = abs(wo.z), ci = abs(wi.z);
    if (ci == 0.0 || !(pdf > 0.0))
        return false;
    vec3 F = cv_fr_complex(abs(dot(wo, wm)), eta, k);
    vec3 f = cv_mf_D(alpha, wm) * F * cv_mf_G(alpha, wo, wi) / (4.0 * ci * co);
    s = CvBsdfSample(wi, f, pdf, CV_BSDF_REFLECTION);
    return true;
}

#endif
