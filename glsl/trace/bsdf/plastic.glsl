// glsl/trace/bsdf/plastic.glsl: pbrt-v3 plastic, local frame, wo and wi on
// the +z side (bsdf.glsl mirrors both when wo is below): Lambertian Kd +
// microfacet Ks with pbrt-v3's FresnelDielectric(1.5, 1) (eta 1/1.5 in our
// convention, so grazing microfacets reflect fully, as in pbrt-v3), lobes
// picked with equal probability as pbrt-v3's BSDF::Sample_f does.
#ifndef CV_BSDF_PLASTIC_GLSL
#define CV_BSDF_PLASTIC_GLSL

#include "fresnel.glsl"
#include "microfacet.glsl"
#include "diffuse.glsl"
#include "bsdf_sample.glsl"

#define CV_PLASTIC_ETA (1.0 / 1.5)

// The glossy lobe's pdf (visible normals, reflection about wm).
float cv_plastic_spec_pdf(vec2 alpha, vec3 wo, vec3 wi)
{
    if (cv_mf_smooth(alpha) || wo.z <= 0.0 || wi.z <= 0.0)
        return 0.0;
    vec3 wm = normalize(wo + wi);
    return cv_mf_pdf(alpha, wo, wm) / (4.0 * abs(dot(wo, wm)));
}


float cv_plastic_spec_f(vec2 alpha, vec3 wo, vec3 wi)
{
    if (cv_mf_smooth(alpha) || wo.z <= 0.0 || wi.z <= 0.0)
        return 0.0;
    vec3 wm = normalize(wo + wi);
    return cv_mf_D(alpha, wm) * cv_mf_G(alpha, wo, wi) * cv_fr_dielectric(dot(wi, wm), CV_PLASTIC_ETA) /
           (4.0 * wo.z * wi.z);
}

vec3 cv_plastic_f(vec3 kd, vec3 ks, vec2 alpha, vec3 wo, vec3 wi)
{
    if (wo.z <= 0.0 || wi.z <= 0.0)
        return vec3(0.0);
    return kd * CV_INV_PI + ks * cv_plastic_spec_f(alpha, wo, wi);
}

float cv_plastic_ps(vec3 kd, vec3 ks)
{
    bool d = cv_max3(kd) > 0.0, sp = cv_max3(ks) > 0.0;
    return d && sp ? 0.5 : (sp ? 1.0 : 0.0);
}

float cv_plastic_pdf(vec3 kd, vec3 ks, vec2 alpha, vec3 wo, vec3 wi)
{
    if (wo.z <= 0.0 || wi.z <= 0.0)
        return 0.0;
    float ps = cv_plastic_ps(kd, ks);
    return ps * cv_plastic_spec_pdf(alpha, wo, wi) + (1.0 - ps) * cv_cosine_hemisphere_pdf(wi.z);
}

bool cv_plastic_sample(vec3 kd, vec3 ks, vec2 alpha, vec3 wo, float uc, vec2 u, out CvBsdfSample s)
{
    s = CvBsdfSample(vec3(0.0), vec3(0.0), 0.0, 0u);
    float ps = cv_plastic_ps(kd, ks);
    if (wo.z <= 0.0 || (cv_max3(kd) <= 0.0 && cv_max3(ks) <= 0.0))
        return false;
    vec3 wi;
    if (uc < ps) {
        if (cv_mf_smooth(alpha)) {
            wi = vec3(-wo.x, -wo.y, wo.z);
            s = CvBsdfSample(wi, ks * (cv_fr_dielectric(wo.z, CV_PLASTIC_ETA) / wi.z), ps,
                             CV_BSDF_REFLECTION | CV_BSDF_SPECULAR);
            return true;
        }
        wi = reflect(-wo, cv_mf_sample_wm(alpha, wo, u));
    } else {
        wi = cv_sample_cosine_hemisphere(u);
    }
    if (wi.z <= 0.0)
        return false;
    float pdf = cv_plastic_pdf(kd, ks, alpha, wo, wi);
    s = CvBsdfSample(wi, cv_plastic_f(kd, ks, alpha, wo, wi), pdf, CV_BSDF_REFLECTION);
    return pdf > 0.0;
}

#endif
