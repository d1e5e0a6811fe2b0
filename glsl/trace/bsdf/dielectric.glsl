// glsl/trace/bsdf/dielectric.glsl: smooth and rough (Trowbridge-Reitz)
// dielectric interfaces after pbrt-v4's DielectricBxDF, and the thin
// dielectric slab (ThinDielectricBxDF), local frame. eta = eta_inside /
// eta_outside with the outside on +z. Transmitted radiance is divided by
// etap^2 (camera paths carry radiance). kr/kt scale the reflected and
// transmitted parts (pbrt-v3 glass Kr/Kt; 1 for pbrt-v4).
#ifndef CV_BSDF_DIELECTRIC_GLSL
#define CV_BSDF_DIELECTRIC_GLSL

#include "fresnel.glsl"
#include "microfacet.glsl"
#include "bsdf_sample.glsl"

bool cv_dielectric_is_delta(float eta, vec2 alpha) { return eta == 1.0 || cv_mf_smooth(alpha); }

// The generalized half vector of (wo, wi), facing +z; false when the pair
// has no valid microfacet (grazing or backfacing).
bool cv_dielectric_half(float eta, vec3 wo, vec3 wi, out vec3 wm, out float etap, out bool refl)
{
    float co = wo.z, ci = wi.z;
    refl = ci * co > 0.0;
    etap = 1.0;
    if (!refl)
        etap = co > 0.0 ? eta : 1.0 / eta;
    wm = wi * etap + wo;
    if (ci == 0.0 || co == 0.0 || dot(wm, wm) == 0.0)
        return false;
    wm = normalize(wm);
    if (wm.z < 0.0)
        wm = -wm;
    if (dot(wm, wi) * ci < 0.0 || dot(wm, wo) * co < 0.0)
        return false;
    return true;
}

vec3 cv_dielectric_f(float eta, vec2 alpha, vec3 kr, vec3 kt, vec3 wo, vec3 wi)
{
    if (cv_dielectric_is_delta(eta, alpha))
        return vec3(0.0);
    vec3 wm;
    float etap;
    bool refl;
    if (!cv_dielectric_half(eta, wo, wi, wm, etap, refl))
        return vec3(0.0);
    float F = cv_fr_dielectric(dot(wo, wm), eta);
    if (refl)
        return kr * (cv_mf_D(alpha, wm) * cv_mf_G(alpha, wo, wi) * F / abs(4.0 * wi.z * wo.z));
    float denom = cv_sqr(dot(wi, wm) + dot(wo, wm) / etap) * wi.z * wo.z;
    float ft = cv_mf_D(alpha, wm) * (1.0 - F) * cv_mf_G(alpha, wo, wi) *
               abs(dot(wi, wm) * dot(wo, wm) / denom);
    return kt * (ft / (etap * etap));
}

float cv_dielectric_pdf(float eta, vec2 alpha, vec3 wo, vec3 wi)
{
    if (cv_dielectric_is_delta(eta, alpha))
        return 0.0;
    vec3 wm;
    float etap;
    bool refl;
    if (!cv_dielectric_half(eta, wo, wi, wm, etap, refl))
        return 0.0;
    float R = cv_fr_dielectric(dot(wo, wm), eta), T = 1.0 - R;
    if (refl)
        return cv_mf_pdf(alpha, wo, wm) / (4.0 * abs(dot(wo, wm))) * R / (R + T);
    float denom = cv_sqr(dot(wi, wm) + dot(wo, wm) / etap);
    return cv_mf_pdf(alpha, wo, wm) * abs(dot(wi, wm)) / denom * T / (R + T);
}

bool cv_dielectric_sample(float eta, vec2 alpha, vec3 kr, vec3 kt, vec3 wo, float uc, vec2 u,
                          out CvBsdfSample s)
{
    s = CvBsdfSample(vec3(0.0), vec3(0.0), 0.0, 0u);
    if (wo.z == 0.0)
        return false;
    if (cv_dielectric_is_delta(eta, alpha)) {
        float R = cv_fr_dielectric(wo.z, eta), T = 1.0 - R;
        if (uc < R / (R + T)) {
            vec3 wi = vec3(-wo.x, -wo.y, wo.z);
            s = CvBsdfSample(wi, kr * (R / abs(wi.z)), R / (R + T), CV_BSDF_REFLECTION | CV_BSDF_SPECULAR);
            return true;
        }
        vec3 wi;
        float etap;
        if (!cv_refract(wo, vec3(0.0, 0.0, 1.0), eta, etap, wi) || wi.z == 0.0)
            return false;
        s = CvBsdfSample(wi, kt * (T / abs(wi.z) / (etap * etap)), T / (R + T),
                         CV_BSDF_TRANSMISSION | CV_BSDF_SPECULAR);
        return true;
    }
    vec3 wm = cv_mf_sample_wm(alpha, wo, u);
    float R = cv_fr_dielectric(dot(wo, wm), eta), T = 1.0 - R;
    if (uc < R / (R + T)) {
        vec3 wi = reflect(-wo, wm);
        if (!cv_same_hemisphere(wo, wi))
            return false;
        float pdf = cv_mf_pdf(alpha, wo, wm) / (4.0 * abs(dot(wo, wm))) * R / (R + T);
        vec3 f = kr * (cv_mf_D(alpha, wm) * cv_mf_G(alpha, wo, wi) * R / abs(4.0 * wi.z * wo.z));
        s = CvBsdfSample(wi, f, pdf, CV_BSDF_REFLECTION);
        return pdf > 0.0;
    }
    vec3 wi;
    float etap;
    if (!cv_refract(wo, wm, eta, etap, wi) || cv_same_hemisphere(wo, wi) || wi.z == 0.0)
        return false;
    float denom = cv_sqr(dot(wi, wm) + dot(wo, wm) / etap);
    float pdf = cv_mf_pdf(alpha, wo, wm) * abs(dot(wi, wm)) / denom * T / (R + T);
    float ft = T * cv_mf_D(alpha, wm) * cv_mf_G(alpha, wo, wi) *
               abs(dot(wi, wm) * dot(wo, wm) / (wi.z * wo.z * denom));
    s = CvBsdfSample(wi, kt * (ft / (etap * etap)), pdf, CV_BSDF_TRANSMISSION);
    return pdf > 0.0;
}

// Thin slab: internal reflections summed in closed form, transmission
// straight through (no bending, no radiance scaling).
vec2 cv_thin_dielectric_RT(float eta, vec3 wo)
{
    float R = cv_fr_dielectric(abs(wo.z), eta), T = 1.0 - R;
    if (R < 1.0) {
        R += T * T * R / (1.0 - R * R);
        T = 1.0 - R;
    }
    return vec2(R, T);
}

bool cv_thin_dielectric_sample(float eta, vec3 wo, float uc, out CvBsdfSample s)
{
    s = CvBsdfSample(vec3(0.0), vec3(0.0), 0.0, 0u);
    if (wo.z == 0.0)
        return false;
    vec2 rt = cv_thin_dielectric_RT(eta, wo);
    float pr = rt.x / (rt.x + rt.y);
    if (uc < pr) {
        vec3 wi = vec3(-wo.x, -wo.y, wo.z);
        s = CvBsdfSample(wi, vec3(rt.x / abs(wi.z)), pr, CV_BSDF_REFLECTION | CV_BSDF_SPECULAR);
    } else {
        vec3 wi = -wo;
        s = CvBsdfSample(wi, vec3(rt.y / abs(wi.z)), 1.0 - pr, CV_BSDF_TRANSMISSION | CV_BSDF_SPECULAR);
    }
    return s.pdf > 0.0;
}

#endif
