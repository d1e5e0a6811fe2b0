// glsl/trace/bsdf/diffuse.glsl: Lambertian reflection and diffuse
// transmission (pbrt-v4 DiffuseBxDF, DiffuseTransmissionBxDF), local frame.
// Reflection is two-sided: wi is sampled on wo's side of the surface.
#ifndef CV_BSDF_DIFFUSE_GLSL
#define CV_BSDF_DIFFUSE_GLSL

#include "../../lib/constants.glsl"
#include "../../lib/frame.glsl"
#include "../../lib/sampling.glsl"
#include "bsdf_sample.glsl"

vec3 cv_diffuse_f(vec3 r, vec3 wo, vec3 wi)
{
    return cv_same_hemisphere(wo, wi) ? r * CV_INV_PI : vec3(0.0);
}

float cv_diffuse_pdf(vec3 wo, vec3 wi)
{
    return cv_same_hemisphere(wo, wi) ? cv_cosine_hemisphere_pdf(abs(wi.z)) : 0.0;
}

bool cv_diffuse_sample(vec3 r, vec3 wo, vec2 u, out CvBsdfSample s)
{
    s = CvBsdfSample(vec3(0.0), vec3(0.0), 0.0, 0u);
    if (wo.z == 0.0 || cv_max3(r) <= 0.0)
        return false;
    vec3 wi = cv_sample_cosine_hemisphere(u);
    if (wo.z < 0.0)
        wi.z = -wi.z;
    s = CvBsdfSample(wi, r * CV_INV_PI, cv_cosine_hemisphere_pdf(abs(wi.z)), CV_BSDF_REFLECTION);
    return s.pdf > 0.0;
}

// Reflection r on wo's side, transmission t on the other; lobes picked in
// proportion to their largest channel.
vec3 cv_difftrans_f(vec3 r, vec3 t, vec3 wo, vec3 wi)
{
    return (cv_same_hemisphere(wo, wi) ? r : t) * CV_INV_PI;
}

float cv_difftrans_pdf(vec3 r, vec3 t, vec3 wo, vec3 wi)
{
    float pr = cv_max3(r), pt = cv_max3(t);
    if (pr + pt <= 0.0)
        return 0.0;
    float c = cv_cosine_hemisphere_pdf(abs(wi.z));
    return (cv_same_hemisphere(wo, wi) ? pr : pt) / (pr + pt) * c;
}

bool cv_difftrans_sample(vec3 r, vec3 t, vec3 wo, float uc, vec2 u, out CvBsdfSample s)
{
    s = CvBsdfSample(vec3(0.0), vec3(0.0), 0.0, 0u);
    float pr = cv_max3(r), pt = cv_max3(t);
    if (pr + pt <= 0.0 || wo.z == 0.0)
        return false;
    vec3 wi = cv_sample_cosine_hemisphere(u);
    float c = cv_cosine_hemisphere_pdf(wi.z);
    if (uc < pr / (pr + pt)) {
        if (wo.z < 0.0)
            wi.z = -wi.z;
        s = CvBsdfSample(wi, r * CV_INV_PI, c * pr / (pr + pt), CV_BSDF_REFLECTION);
    } else {
        if (wo.z > 0.0)
            wi.z = -wi.z;
        s = CvBsdfSample(wi, t * CV_INV_PI, c * pt / (pr + pt), CV_BSDF_TRANSMISSION);
    }
    return s.pdf > 0.0;
}

#endif
