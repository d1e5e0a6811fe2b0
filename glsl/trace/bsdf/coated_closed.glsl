// glsl/trace/bsdf/coated_closed.glsl: coated diffuse in closed form: the
// expected value of pbrt-v4's layered estimator (layered.glsl) for a
// dielectric coat over a Lambertian base of reflectance r, across a slab
// that absorbs (unit extinction, given thickness) and does not scatter
// (albedo 0). Used where the coat is smooth or nearly so (alpha up to
// CV_COAT_CLOSED_ALPHA) and the host allowed it (CV_MATF_COAT_CLOSED:
// src/scene/coat_closed.c computes r_in and t_out).
//
// With wo, wi above, mu their cosines, mu' the refracted ones, F Fresnel's
// reflectance and t(mu) = (1 - F(mu)) exp(-thickness / mu'):
//   f = top reflection + t(mu_o) t(mu_i) r / (pi eta^2) * sum_{k<K} (r r_in)^k
// The walk refracts in (radiance / eta^2), reaches the base, where it
// connects to wi through the coat (r / pi, t(mu_i)), and reflects with
// cosine density (weight r); each further visit costs one internal
// reflection with the slab's transmittance up and down (r_in, its cosine
// average). pbrt-v4 counts events: K = ceil(max_depth / 2) visits for f.
// (Its sampling walk exits after at most floor(max_depth / 2) visits: for
// an odd max_depth the two differ by one term; here both use f's K.)
// Russian roulette in the walk is unbiased and does not enter.
//
// The top reflection: a delta lobe of weight F(mu_o) for a smooth coat;
// for a nearly smooth one pbrt-v4's microfacet reflection, which is exact
// in both (its estimator adds it as is); the transmitted part then takes
// the smooth coat's transmission, which the rough coat's differs from by
// far less than noise up to CV_COAT_CLOSED_ALPHA (bsdf_coat_closed_test).
//
// Sampling: the reflection with probability F / (F + the diffuse part's
// albedo, averaged over channels), a function of wo alone; else cosine
// sampling. Local frame, wo and wi on +z (bsdf.glsl mirrors both). Cost
// class: O(1), a few transcendentals; the random walk is O(n_samples *
// max_depth) per call.
#ifndef CV_BSDF_COATED_CLOSED_GLSL
#define CV_BSDF_COATED_CLOSED_GLSL

#include "../../lib/constants.glsl"
#include "../../lib/sampling.glsl"
#include "fresnel.glsl"
#include "microfacet.glsl"
#include "bsdf_sample.glsl"

// (Coats up to CV_COAT_CLOSED_ALPHA, glsl/shared/scene.h, take it.)

struct CvCoatClosed {
    float eta;        // coat IOR (outside 1)
    vec2 alpha;       // coat roughness (cv_mf_smooth: delta reflection)
    vec3 r;           // base reflectance [0, 1]
    float thickness;  // slab thickness (> 0)
    int max_depth;    // pbrt-v4's maxdepth
    float r_in;       // host: cosine-averaged internal reflectance, slab round trip included
    float t_out;      // host: the base's escape through the coat, over pi (coat_closed.h)
};

// One way through the coat and the slab at outer cosine mu.
float cv_cc_t(CvCoatClosed C, float mu)
{
    float s2 = (1.0 - mu * mu) / (C.eta * C.eta);
    if (s2 >= 1.0)
        return 0.0;
    float F = C.eta == 1.0 ? 0.0 : cv_fr_dielectric(mu, C.eta);
    return (1.0 - F) * exp(-C.thickness / sqrt(1.0 - s2));
}

// r times the sum over the K visits of the base.
vec3 cv_cc_bounces(CvCoatClosed C)
{
    int K = max(C.max_depth + 1, 0) / 2;
    if (K == 0)
        return vec3(0.0);
    vec3 x = C.r * C.r_in;
    vec3 s = (1.0 - pow(x, vec3(float(K)))) / max(1.0 - x, vec3(1e-7));
    return C.r * mix(s, vec3(float(K)), lessThan(1.0 - x, vec3(1e-5)));
}

vec3 cv_cc_diffuse_f(CvCoatClosed C, vec3 wo, vec3 wi)
{
    return cv_cc_t(C, wo.z) * cv_cc_t(C, wi.z) * (CV_INV_PI / (C.eta * C.eta)) * cv_cc_bounces(C);
}

float cv_cc_fresnel(CvCoatClosed C, float c) { return C.eta == 1.0 ? 0.0 : cv_fr_dielectric(c, C.eta); }

// Probability of sampling the top reflection from wo.
float cv_coat_closed_spec_prob(CvCoatClosed C, vec3 wo)
{
    float F = cv_cc_fresnel(C, wo.z);
    if (!(F > 0.0))
        return 0.0;
    vec3 d = cv_cc_t(C, wo.z) * C.t_out * cv_cc_bounces(C);
    return F / (F + cv_mean3(d));
}

// The nearly smooth coat's microfacet reflection and its sampling density.
float cv_cc_refl_f(CvCoatClosed C, vec3 wo, vec3 wi)
{
    vec3 wm = normalize(wo + wi);
    return cv_mf_D(C.alpha, wm) * cv_mf_G(C.alpha, wo, wi) * cv_cc_fresnel(C, dot(wo, wm)) / (4.0 * wo.z * wi.z);
}

float cv_cc_refl_pdf(CvCoatClosed C, vec3 wo, vec3 wi)
{
    vec3 wm = normalize(wo + wi);
    return cv_mf_pdf(C.alpha, wo, wm) / (4.0 * abs(dot(wo, wm)));
}

vec3 cv_coat_closed_f(CvCoatClosed C, vec3 wo, vec3 wi)
{
    if (!(wo.z > 0.0) || !(wi.z > 0.0))
        return vec3(0.0);
    vec3 f = cv_cc_diffuse_f(C, wo, wi);
    if (!cv_mf_smooth(C.alpha))
        f += vec3(cv_cc_refl_f(C, wo, wi));
    return f;
}

// Density of the non-delta samples.
float cv_coat_closed_pdf(CvCoatClosed C, vec3 wo, vec3 wi)
{
    if (!(wo.z > 0.0) || !(wi.z > 0.0))
        return 0.0;
    float ps = cv_coat_closed_spec_prob(C, wo);
    float p = (1.0 - ps) * cv_cosine_hemisphere_pdf(wi.z);
    if (!cv_mf_smooth(C.alpha))
        p += ps * cv_cc_refl_pdf(C, wo, wi);
    return p;
}

bool cv_coat_closed_sample(CvCoatClosed C, vec3 wo, float uc, vec2 u, out CvBsdfSample s)
{
    s = CvBsdfSample(vec3(0.0), vec3(0.0), 0.0, 0u);
    if (!(wo.z > 0.0))
        return false;
    float ps = cv_coat_closed_spec_prob(C, wo);
    vec3 wi;
    if (uc < ps) {
        if (cv_mf_smooth(C.alpha)) {
            wi = vec3(-wo.xy, wo.z);
            s = CvBsdfSample(wi, vec3(cv_cc_fresnel(C, wo.z) / wi.z), ps, CV_BSDF_REFLECTION | CV_BSDF_SPECULAR);
            return true;
        }
        wi = reflect(-wo, cv_mf_sample_wm(C.alpha, wo, u));
    } else {
        wi = cv_sample_cosine_hemisphere(u);
    }
    if (!(wi.z > 0.0))
        return false;
    float pdf = cv_coat_closed_pdf(C, wo, wi);
    s = CvBsdfSample(wi, cv_coat_closed_f(C, wo, wi), pdf, CV_BSDF_REFLECTION);
    return pdf > 0.0;
}

#endif
