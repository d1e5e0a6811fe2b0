// glsl/trace/bsdf/sss_exit.glsl: the lobe through which light leaves a
// subsurface material at a BSSRDF probe's exit point, pbrt-v4's
// NormalizedFresnelBxDF: diffuse, weighted by the Fresnel transmittance
// and normalised by the first Fresnel moment, times eta^2 for radiance;
// cosine-sampled. Reflection only, on the side of the local z.
#ifndef CV_BSDF_SSS_EXIT_GLSL
#define CV_BSDF_SSS_EXIT_GLSL

// The first moment of the Fresnel reflectance (d'Eon and Irving's fit,
// as pbrt-v4: src/scene/bssrdf_table.c has the same for the table).
float cv_fresnel_moment1(float e)
{
    float e2 = e * e, e3 = e2 * e, e4 = e3 * e, e5 = e4 * e;
    if (e < 1.0)
        return 0.45966 - 1.73965 * e + 3.37668 * e2 - 3.904945 * e3 + 2.49277 * e4 - 0.68441 * e5;
    return -4.61686 + 11.1136 * e - 10.4646 * e2 + 5.11455 * e3 - 1.27198 * e4 + 0.12746 * e5;
}

vec3 cv_sss_exit_f(float eta, vec3 wo, vec3 wi)
{
    if (!cv_same_hemisphere(wo, wi))
        return vec3(0.0);
    float c = 1.0 - 2.0 * cv_fresnel_moment1(1.0 / eta);
    return vec3((1.0 - cv_fr_dielectric(wi.z, eta)) / (c * CV_PI) * eta * eta);
}

float cv_sss_exit_pdf(vec3 wo, vec3 wi)
{
    return cv_same_hemisphere(wo, wi) ? abs(wi.z) * CV_INV_PI : 0.0;
}

bool cv_sss_exit_sample(float eta, vec3 wo, vec2 u, out CvBsdfSample s)
{
    vec3 wi = cv_sample_cosine_hemisphere(u);
    if (wo.z < 0.0)
        wi.z = -wi.z;
    s = CvBsdfSample(wi, cv_sss_exit_f(eta, wo, wi), cv_sss_exit_pdf(wo, wi), CV_BSDF_REFLECTION);
    return s.pdf > 0.0;
}

#endif
