// glsl/trace/bsdf/coated.glsl: layered materials in closed form, local frame,
// wo and wi on the +z side (bsdf.glsl mirrors both when wo is below: these
// BSDFs are two-sided, as pbrt-v4's LayeredBxDF<..., twoSided = true>).
//
// pbrt-v4 evaluates coateddiffuse / coatedconductor with a stochastic random
// walk between the layers. Cavalry uses a cheaper closed approximation:
//  - the coat reflects like a rough dielectric (pbrt's microfacet reflection
//    lobe with dielectric Fresnel at the microfacet normal);
//  - light entering and leaving the coat is refracted by the macro surface
//    (Fresnel transmittance (1 - F) at each crossing, radiance / eta^2) and
//    attenuated by the coat medium, Tr = exp(-thickness / cos) each way
//    (the medium's scattering albedo and g are ignored: pbrt's default albedo
//    is 0, where this is exact in the single-pass term);
//  - coated diffuse: the base's interreflections with the coat underside are
//    summed as a geometric series with the hemispherical internal
//    reflectance Fdr (Kelemen / Jensen style), R / (1 - R Fdr), which keeps
//    the total at most 1 for R <= 1;
//  - coated conductor: one pass through the coat to the conductor (conductor
//    eta and k divided by the coat eta, as pbrt does) and out; light the coat
//    reflects back down is dropped (except for a smooth coat over a smooth
//    base, where the bounces sum exactly), so rough bases come out darker
//    than pbrt-v4's random walk. Energy is never gained.
// Non-reciprocal in the coat Fresnel weights, which camera paths don't need.
//
// pbrt-v3 plastic is here too: Lambertian Kd + microfacet Ks with pbrt-v3's
// FresnelDielectric(1.5, 1) (eta 1/1.5 in our convention, so grazing
// microfacets reflect fully, as in pbrt-v3), lobes picked with equal
// probability as pbrt-v3's BSDF::Sample_f does.
#ifndef CV_BSDF_COATED_GLSL
#define CV_BSDF_COATED_GLSL

#include "fresnel.glsl"
#include "microfacet.glsl"
#include "conductor.glsl"
#include "diffuse.glsl"
#include "bsdf_sample.glsl"

// Direction just under the coat, pointing up, for w above it (Snell's law
// with relative eta); false under total internal reflection.
bool cv_coat_snell_in(vec3 w, float eta, out vec3 wt)
{
    vec2 xy = w.xy / eta;
    float z2 = 1.0 - dot(xy, xy);
    wt = vec3(xy, cv_safe_sqrt(z2));
    return z2 > 0.0;
}

// Hemispherical (cosine-weighted) reflectance of the coat seen from inside.
float cv_fdr_internal(float eta)
{
    // Jensen et al. 2001's fit for the inside of a medium of relative IOR
    // x >= 1; below 1 the inside sees an external interface of IOR 1/eta,
    // whose reflectance follows from 1 - Fdr_ext(x) = x^2 (1 - Fdr_int(x)).
    float x = eta >= 1.0 ? eta : 1.0 / eta;
    float fint = -1.440 / (x * x) + 0.710 / x + 0.668 + 0.0636 * x;
    fint = clamp(fint, 0.0, 1.0);
    if (eta >= 1.0)
        return fint;
    return clamp(1.0 - x * x * (1.0 - fint), 0.0, 1.0);
}

float cv_coat_tr(float thickness, float cos_t)
{
    return thickness > 0.0 ? exp(-thickness / max(cos_t, 1e-4)) : 1.0;
}

// The coat's own glossy reflection (0 when smooth: then it is a delta lobe).
float cv_coat_spec_f(float eta, vec2 alpha, vec3 wo, vec3 wi)
{
    if (cv_mf_smooth(alpha) || wo.z <= 0.0 || wi.z <= 0.0)
        return 0.0;
    vec3 wm = normalize(wo + wi);
    float F = cv_fr_dielectric(dot(wo, wm), eta);
    return cv_mf_D(alpha, wm) * cv_mf_G(alpha, wo, wi) * F / (4.0 * wo.z * wi.z);
}

float cv_coat_spec_pdf(vec2 alpha, vec3 wo, vec3 wi)
{
    if (cv_mf_smooth(alpha) || wo.z <= 0.0 || wi.z <= 0.0)
        return 0.0;
    vec3 wm = normalize(wo + wi);
    return cv_mf_pdf(alpha, wo, wm) / (4.0 * abs(dot(wo, wm)));
}

// Probability of sampling the coat lobe rather than the base.
float cv_coat_prob(float eta, vec3 wo, vec3 base_albedo)
{
    float F = cv_fr_dielectric(wo.z, eta);
    float w = F + (1.0 - F) * cv_max3(base_albedo);
    return w > 0.0 ? clamp(F / w, 0.1, 0.9) : 0.5;
}

// ---- coated diffuse ----------------------------------------------------

vec3 cv_coated_diffuse_base_f(vec3 r, float eta, float thickness, vec3 wo, vec3 wi)
{
    vec3 wot, wit;
    if (!cv_coat_snell_in(wo, eta, wot) || !cv_coat_snell_in(wi, eta, wit))
        return vec3(0.0);
    float to = (1.0 - cv_fr_dielectric(wo.z, eta)) * cv_coat_tr(thickness, wot.z);
    float ti = (1.0 - cv_fr_dielectric(wi.z, eta)) * cv_coat_tr(thickness, wit.z);
    float fdr = cv_fdr_internal(eta);
    return to * ti * r / (CV_PI * eta * eta * (vec3(1.0) - r * fdr));
}

vec3 cv_coated_diffuse_f(vec3 r, float eta, vec2 alpha, float thickness, vec3 wo, vec3 wi)
{
    if (wo.z <= 0.0 || wi.z <= 0.0)
        return vec3(0.0);
    return vec3(cv_coat_spec_f(eta, alpha, wo, wi)) + cv_coated_diffuse_base_f(r, eta, thickness, wo, wi);
}

float cv_coated_diffuse_pdf(vec3 r, float eta, vec2 alpha, vec3 wo, vec3 wi)
{
    if (wo.z <= 0.0 || wi.z <= 0.0)
        return 0.0;
    float ps = cv_coat_prob(eta, wo, r);
    return ps * cv_coat_spec_pdf(alpha, wo, wi) + (1.0 - ps) * cv_cosine_hemisphere_pdf(wi.z);
}

bool cv_coated_diffuse_sample(vec3 r, float eta, vec2 alpha, float thickness, vec3 wo, float uc, vec2 u,
                              out CvBsdfSample s)
{
    s = CvBsdfSample(vec3(0.0), vec3(0.0), 0.0, 0u);
    if (wo.z <= 0.0)
        return false;
    float ps = cv_coat_prob(eta, wo, r);
    vec3 wi;
    if (uc < ps) {
        if (cv_mf_smooth(alpha)) {
            wi = vec3(-wo.x, -wo.y, wo.z);
            s = CvBsdfSample(wi, vec3(cv_fr_dielectric(wo.z, eta) / wi.z), ps,
                             CV_BSDF_REFLECTION | CV_BSDF_SPECULAR);
            return true;
        }
        wi = reflect(-wo, cv_mf_sample_wm(alpha, wo, u));
    } else {
        wi = cv_sample_cosine_hemisphere(u);
    }
    if (wi.z <= 0.0)
        return false;
    float pdf = cv_coated_diffuse_pdf(r, eta, alpha, wo, wi);
    s = CvBsdfSample(wi, cv_coated_diffuse_f(r, eta, alpha, thickness, wo, wi), pdf, CV_BSDF_REFLECTION);
    return pdf > 0.0;
}

// ---- coated conductor --------------------------------------------------
// ceta, ck: conductor eta and k already divided by the coat's eta.

vec3 cv_coated_conductor_base_f(float eta, float thickness, vec2 alpha2, vec3 ceta, vec3 ck, vec3 wo, vec3 wi)
{
    vec3 wot, wit;
    if (cv_mf_smooth(alpha2) || !cv_coat_snell_in(wo, eta, wot) || !cv_coat_snell_in(wi, eta, wit))
        return vec3(0.0);
    float to = (1.0 - cv_fr_dielectric(wo.z, eta)) * cv_coat_tr(thickness, wot.z);
    float ti = (1.0 - cv_fr_dielectric(wi.z, eta)) * cv_coat_tr(thickness, wit.z);
    return to * ti * cv_conductor_f(alpha2, ceta, ck, wot, wit) / (eta * eta);
}

float cv_coated_conductor_base_pdf(float eta, vec2 alpha2, vec3 wo, vec3 wi)
{
    vec3 wot, wit;
    if (cv_mf_smooth(alpha2) || !cv_coat_snell_in(wo, eta, wot) || !cv_coat_snell_in(wi, eta, wit))
        return 0.0;
    // d(omega_t) / d(omega) = cos / (eta^2 cos_t)
    return cv_conductor_pdf(alpha2, wot, wit) * wi.z / (eta * eta * wit.z);
}

// The delta part when the base is smooth: mirror direction, value per |cos|.
// With a smooth base every internal bounce stays on the mirror direction,
// so when the coat is smooth too the bounces between coat and base sum
// exactly: (1-F)^2 Tr^2 Fc / (1 - F Tr^2 Fc) (the coat reflects F from
// inside at the refracted angle, as from outside).
vec3 cv_coated_conductor_base_delta(float eta, float thickness, vec3 ceta, vec3 ck, vec3 wo, bool coat_smooth)
{
    vec3 wot;
    if (!cv_coat_snell_in(wo, eta, wot))
        return vec3(0.0);
    float F = cv_fr_dielectric(wo.z, eta), tr = cv_coat_tr(thickness, wot.z);
    vec3 fc = cv_fr_complex(wot.z, ceta, ck);
    vec3 once = cv_sqr((1.0 - F) * tr) * fc;
    return coat_smooth ? once / (vec3(1.0) - F * tr * tr * fc) : once;
}

vec3 cv_coated_conductor_f(float eta, vec2 alpha, float thickness, vec2 alpha2, vec3 ceta, vec3 ck,
                           vec3 wo, vec3 wi)
{
    if (wo.z <= 0.0 || wi.z <= 0.0)
        return vec3(0.0);
    return vec3(cv_coat_spec_f(eta, alpha, wo, wi)) +
           cv_coated_conductor_base_f(eta, thickness, alpha2, ceta, ck, wo, wi);
}

float cv_coated_conductor_ps(float eta, vec3 ceta, vec3 ck, vec3 wo)
{
    return cv_coat_prob(eta, wo, cv_fr_complex(1.0, ceta, ck));
}

float cv_coated_conductor_pdf(float eta, vec2 alpha, vec2 alpha2, vec3 ceta, vec3 ck, vec3 wo, vec3 wi)
{
    if (wo.z <= 0.0 || wi.z <= 0.0)
        return 0.0;
    float ps = cv_coated_conductor_ps(eta, ceta, ck, wo);
    return ps * cv_coat_spec_pdf(alpha, wo, wi) + (1.0 - ps) * cv_coated_conductor_base_pdf(eta, alpha2, wo, wi);
}

bool cv_coated_conductor_sample(float eta, vec2 alpha, float thickness, vec2 alpha2, vec3 ceta, vec3 ck,
                                vec3 wo, float uc, vec2 u, out CvBsdfSample s)
{
    s = CvBsdfSample(vec3(0.0), vec3(0.0), 0.0, 0u);
    if (wo.z <= 0.0)
        return false;
    float ps = cv_coated_conductor_ps(eta, ceta, ck, wo);
    bool coat_delta = cv_mf_smooth(alpha), base_delta = cv_mf_smooth(alpha2);
    bool pick_coat = uc < ps;
    vec3 mirror = vec3(-wo.x, -wo.y, wo.z);
    if ((pick_coat && coat_delta) || (!pick_coat && base_delta)) {
        // Both delta lobes, if both are, share the mirror direction.
        vec3 f = vec3(0.0);
        float pdf = 0.0;
        if (coat_delta) {
            f += vec3(cv_fr_dielectric(wo.z, eta));
            pdf += ps;
        }
        if (base_delta) {
            f += cv_coated_conductor_base_delta(eta, thickness, ceta, ck, wo, coat_delta);
            pdf += 1.0 - ps;
        }
        s = CvBsdfSample(mirror, f / mirror.z, pdf, CV_BSDF_REFLECTION | CV_BSDF_SPECULAR);
        return true;
    }
    vec3 wi;
    if (pick_coat) {
        wi = reflect(-wo, cv_mf_sample_wm(alpha, wo, u));
    } else {
        vec3 wot;
        if (!cv_coat_snell_in(wo, eta, wot))
            return false;
        vec3 wit = reflect(-wot, cv_mf_sample_wm(alpha2, wot, u));
        if (wit.z <= 0.0)
            return false;
        vec2 xy = wit.xy * eta;
        float z2 = 1.0 - dot(xy, xy);
        if (z2 <= 0.0)
            return false;
        wi = vec3(xy, sqrt(z2));
    }
    if (wi.z <= 0.0)
        return false;
    float pdf = cv_coated_conductor_pdf(eta, alpha, alpha2, ceta, ck, wo, wi);
    s = CvBsdfSample(wi, cv_coated_conductor_f(eta, alpha, thickness, alpha2, ceta, ck, wo, wi), pdf,
                     CV_BSDF_REFLECTION);
    return pdf > 0.0;
}

// ---- pbrt-v3 plastic ---------------------------------------------------

#define CV_PLASTIC_ETA (1.0 / 1.5)

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
    return ps * cv_coat_spec_pdf(alpha, wo, wi) + (1.0 - ps) * cv_cosine_hemisphere_pdf(wi.z);
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
