// glsl/trace/bsdf/hair.glsl: the hair BSDF of d'Eon et al. 2011 and Chiang
// et al. 2016 as pbrt-v4's HairBxDF has it: per scattering order p (R, TT,
// TRT, and the rest summed in closed form), a longitudinal lobe Mp (the
// v of each order from beta_m, its axis tilted by the cuticle scales'
// alpha), an azimuthal lobe Np (a trimmed logistic of width s from beta_n
// around the order's exit angle) and an attenuation Ap (Fresnel and the
// absorption sigma_a along the path through the fibre).
//
// Local frame: x runs along the fibre, z is the surface normal the ray saw
// and y = z x x; h in [-1, 1] is where across the fibre's width the ray
// hit. theta is measured from the normal plane (sin theta = w.x), phi
// around the fibre from y towards z. f carries no cosine (pbrt-v4 divides
// the lobes' sum by |cos| against the surface normal z).
#ifndef CV_BSDF_HAIR_GLSL
#define CV_BSDF_HAIR_GLSL

#include "../../lib/constants.glsl"
#include "bsdf_sample.glsl"
#include "fresnel.glsl"

#define CV_HAIR_PMAX 3

struct CvHair {
    float h;
    float eta;
    vec3 sigma_a;
    float gamma_o;
    float v[CV_HAIR_PMAX + 1];  // longitudinal variance per order
    float s;                    // azimuthal logistic scale
    vec3 sin2k;                 // sin(2^k alpha), k = 0, 1, 2
    vec3 cos2k;
};

float cv_hair_safe_asin(float x) { return asin(clamp(x, -1.0, 1.0)); }
float cv_hair_safe_sqrt(float x) { return sqrt(max(x, 0.0)); }

// sigma_a from the eumelanin and pheomelanin concentrations (pbrt-v4's
// RGB absorption coefficients of the two pigments).
vec3 cv_hair_sigma_a_from_melanin(float ce, float cp)
{
    return max(ce, 0.0) * vec3(0.419, 0.697, 1.37) + max(cp, 0.0) * vec3(0.187, 0.4, 1.05);
}

// sigma_a that gives about the colour c after many scattering events
// (Chiang et al.'s fit over beta_n).
vec3 cv_hair_sigma_a_from_reflectance(vec3 c, float beta_n)
{
    float b = beta_n, b2 = b * b;
    float d = 5.969 - 0.215 * b + 2.532 * b2 - 10.73 * b2 * b + 5.574 * b2 * b2 + 0.245 * b2 * b2 * b;
    vec3 l = log(clamp(c, 1e-6, 1.0)) / d;
    return l * l;
}

// beta_m, beta_n in (0, 1] (clamped below at 0.01 as pbrt-v4); alpha in degrees.
CvHair cv_hair_make(float h, float eta, vec3 sigma_a, float beta_m, float beta_n, float alpha_deg)
{
    CvHair H;
    H.h = clamp(h, -1.0, 1.0);
    H.eta = eta;
    H.sigma_a = max(sigma_a, vec3(0.0));
    H.gamma_o = cv_hair_safe_asin(H.h);
    float bm = max(beta_m, 0.01), bn = max(beta_n, 0.01);
    float bm2 = bm * bm, bm4 = bm2 * bm2, bm5 = bm4 * bm, bm10 = bm5 * bm5, bm20 = bm10 * bm10;
    float t = 0.726 * bm + 0.812 * bm2 + 3.7 * bm20;
    H.v[0] = t * t;
    H.v[1] = 0.25 * H.v[0];
    H.v[2] = 4.0 * H.v[0];
    H.v[3] = H.v[2];
    float bn2 = bn * bn, bn4 = bn2 * bn2, bn8 = bn4 * bn4, bn16 = bn8 * bn8, bn22 = bn16 * bn4 * bn2;
    H.s = 0.626657069 * (0.265 * bn + 1.194 * bn2 + 5.372 * bn22);  // sqrt(pi / 8)
    float sa = sin(radians(alpha_deg));
    H.sin2k.x = sa;
    H.cos2k.x = cv_hair_safe_sqrt(1.0 - sa * sa);
    H.sin2k.y = 2.0 * H.cos2k.x * H.sin2k.x;
    H.cos2k.y = H.cos2k.x * H.cos2k.x - H.sin2k.x * H.sin2k.x;
    H.sin2k.z = 2.0 * H.cos2k.y * H.sin2k.y;
    H.cos2k.z = H.cos2k.y * H.cos2k.y - H.sin2k.y * H.sin2k.y;
    return H;
}

// Modified Bessel function I0 by its series (ten terms), and its log with
// the asymptotic form for large x.
float cv_hair_i0(float x)
{
    float val = 0.0, x2i = 1.0, ifact = 1.0, i4 = 1.0;
    for (int i = 0; i < 10; i++) {
        if (i > 1)
            ifact *= float(i);
        val += x2i / (i4 * ifact * ifact);
        x2i *= x * x;
        i4 *= 4.0;
    }
    return val;
}

float cv_hair_log_i0(float x)
{
    if (x > 12.0)
        return x + 0.5 * (-log(2.0 * CV_PI) + log(1.0 / x) + 1.0 / (8.0 * x));
    return log(cv_hair_i0(x));
}

float cv_hair_mp(float cos_i, float cos_o, float sin_i, float sin_o, float v)
{
    float a = cos_i * cos_o / v, b = sin_i * sin_o / v;
    if (v <= 0.1)
        return exp(cv_hair_log_i0(a) - b - 1.0 / v + 0.6931 + log(1.0 / (2.0 * v)));
    return exp(-b) * cv_hair_i0(a) / (sinh(1.0 / v) * 2.0 * v);
}

// Attenuations of orders 0..PMAX-1 and of all higher orders together, for
// the Fresnel factor at the entry and the transmittance T of one pass.
void cv_hair_ap(float cos_theta_o, float eta, float h, vec3 T, out vec3 ap[CV_HAIR_PMAX + 1])
{
    float cos_gamma_o = cv_hair_safe_sqrt(1.0 - h * h);
    float f = cv_fr_dielectric(cos_theta_o * cos_gamma_o, eta);
    ap[0] = vec3(f);
    ap[1] = (1.0 - f) * (1.0 - f) * T;
    for (int p = 2; p < CV_HAIR_PMAX; p++)
        ap[p] = ap[p - 1] * T * f;
    vec3 den = 1.0 - T * f;
    vec3 num = ap[CV_HAIR_PMAX - 1] * f * T;
    ap[CV_HAIR_PMAX] = vec3(den.x != 0.0 ? num.x / den.x : 0.0, den.y != 0.0 ? num.y / den.y : 0.0,
                            den.z != 0.0 ? num.z / den.z : 0.0);
}

float cv_hair_phi(int p, float gamma_o, float gamma_t)
{
    return 2.0 * float(p) * gamma_t - 2.0 * gamma_o + float(p) * CV_PI;
}

float cv_hair_logistic(float x, float s)
{
    x = abs(x);
    float e = exp(-x / s);
    return e / (s * (1.0 + e) * (1.0 + e));
}

float cv_hair_logistic_cdf(float x, float s) { return 1.0 / (1.0 + exp(-x / s)); }

// The logistic restricted to [-pi, pi] and renormalised.
float cv_hair_trimmed_logistic(float x, float s)
{
    return cv_hair_logistic(x, s) / (cv_hair_logistic_cdf(CV_PI, s) - cv_hair_logistic_cdf(-CV_PI, s));
}

float cv_hair_sample_trimmed_logistic(float u, float s)
{
    float k = cv_hair_logistic_cdf(CV_PI, s) - cv_hair_logistic_cdf(-CV_PI, s);
    float x = -s * log(1.0 / (u * k + cv_hair_logistic_cdf(-CV_PI, s)) - 1.0);
    return clamp(x, -CV_PI, CV_PI);
}

float cv_hair_np(float phi, int p, float s, float gamma_o, float gamma_t)
{
    float dphi = phi - cv_hair_phi(p, gamma_o, gamma_t);
    // into [-pi, pi]: a remainder, not a loop (p pi reaches 3 pi)
    dphi -= 2.0 * CV_PI * floor((dphi + CV_PI) / (2.0 * CV_PI));
    return cv_hair_trimmed_logistic(dphi, s);
}

// theta_o of order p, tilted by the scales: R by -2 alpha, TT by +alpha,
// TRT by +4 alpha (as sin and cos).
vec2 cv_hair_tilt(CvHair H, int p, float sin_o, float cos_o)
{
    vec2 r;
    if (p == 0)
        r = vec2(sin_o * H.cos2k.y - cos_o * H.sin2k.y, cos_o * H.cos2k.y + sin_o * H.sin2k.y);
    else if (p == 1)
        r = vec2(sin_o * H.cos2k.x + cos_o * H.sin2k.x, cos_o * H.cos2k.x - sin_o * H.sin2k.x);
    else if (p == 2)
        r = vec2(sin_o * H.cos2k.z + cos_o * H.sin2k.z, cos_o * H.cos2k.z - sin_o * H.sin2k.z);
    else
        r = vec2(sin_o, cos_o);
    return vec2(r.x, abs(r.y));
}

// Transmittance of one pass through the fibre and gamma_t, for wo.
vec3 cv_hair_transmittance(CvHair H, float sin_o, float cos_o, out float gamma_t)
{
    float sin_t = sin_o / H.eta;
    float cos_t = cv_hair_safe_sqrt(1.0 - sin_t * sin_t);
    float etap = cv_hair_safe_sqrt(H.eta * H.eta - sin_o * sin_o) / cos_o;
    float sin_gt = H.h / etap;
    float cos_gt = cv_hair_safe_sqrt(1.0 - sin_gt * sin_gt);
    gamma_t = cv_hair_safe_asin(sin_gt);
    return exp(-H.sigma_a * (2.0 * cos_gt / cos_t));
}

vec3 cv_hair_f(CvHair H, vec3 wo, vec3 wi)
{
    float sin_o = wo.x, cos_o = cv_hair_safe_sqrt(1.0 - sin_o * sin_o);
    float phi_o = atan(wo.z, wo.y);
    float sin_i = wi.x, cos_i = cv_hair_safe_sqrt(1.0 - sin_i * sin_i);
    float phi_i = atan(wi.z, wi.y);
    float gamma_t;
    vec3 T = cv_hair_transmittance(H, sin_o, cos_o, gamma_t);
    vec3 ap[CV_HAIR_PMAX + 1];
    cv_hair_ap(cos_o, H.eta, H.h, T, ap);
    float phi = phi_i - phi_o;
    vec3 sum = vec3(0.0);
    for (int p = 0; p < CV_HAIR_PMAX; p++) {
        vec2 t = cv_hair_tilt(H, p, sin_o, cos_o);
        sum += cv_hair_mp(cos_i, t.y, sin_i, t.x, H.v[p]) * ap[p] * cv_hair_np(phi, p, H.s, H.gamma_o, gamma_t);
    }
    sum += cv_hair_mp(cos_i, cos_o, sin_i, sin_o, H.v[CV_HAIR_PMAX]) * ap[CV_HAIR_PMAX] * CV_INV_2PI;
    if (abs(wi.z) > 0.0)
        sum /= abs(wi.z);
    return sum;
}

// Probability of sampling each order: its attenuation's channel average
// over the sum of them.
void cv_hair_ap_pdf(CvHair H, float sin_o, float cos_o, out float pdf[CV_HAIR_PMAX + 1])
{
    float gamma_t;
    vec3 T = cv_hair_transmittance(H, sin_o, cos_o, gamma_t);
    vec3 ap[CV_HAIR_PMAX + 1];
    cv_hair_ap(cos_o, H.eta, H.h, T, ap);
    float sum = 0.0;
    for (int p = 0; p <= CV_HAIR_PMAX; p++) {
        pdf[p] = (ap[p].x + ap[p].y + ap[p].z) / 3.0;
        sum += pdf[p];
    }
    for (int p = 0; p <= CV_HAIR_PMAX; p++)
        pdf[p] = sum > 0.0 ? pdf[p] / sum : 0.0;
}

float cv_hair_pdf(CvHair H, vec3 wo, vec3 wi)
{
    float sin_o = wo.x, cos_o = cv_hair_safe_sqrt(1.0 - sin_o * sin_o);
    float phi_o = atan(wo.z, wo.y);
    float sin_i = wi.x, cos_i = cv_hair_safe_sqrt(1.0 - sin_i * sin_i);
    float phi_i = atan(wi.z, wi.y);
    float gamma_t;
    cv_hair_transmittance(H, sin_o, cos_o, gamma_t);
    float ap_pdf[CV_HAIR_PMAX + 1];
    cv_hair_ap_pdf(H, sin_o, cos_o, ap_pdf);
    float phi = phi_i - phi_o;
    float pdf = 0.0;
    for (int p = 0; p < CV_HAIR_PMAX; p++) {
        vec2 t = cv_hair_tilt(H, p, sin_o, cos_o);
        pdf += cv_hair_mp(cos_i, t.y, sin_i, t.x, H.v[p]) * ap_pdf[p] *
               cv_hair_np(phi, p, H.s, H.gamma_o, gamma_t);
    }
    pdf += cv_hair_mp(cos_i, cos_o, sin_i, sin_o, H.v[CV_HAIR_PMAX]) * ap_pdf[CV_HAIR_PMAX] * CV_INV_2PI;
    return pdf;
}

// uc picks the order (and, rescaled, places phi), u places theta.
bool cv_hair_sample(CvHair H, vec3 wo, float uc, vec2 u, out CvBsdfSample s)
{
    s = CvBsdfSample(vec3(0.0), vec3(0.0), 0.0, 0u);
    float sin_o = wo.x, cos_o = cv_hair_safe_sqrt(1.0 - sin_o * sin_o);
    float phi_o = atan(wo.z, wo.y);
    float ap_pdf[CV_HAIR_PMAX + 1];
    cv_hair_ap_pdf(H, sin_o, cos_o, ap_pdf);
    int p = 0;
    for (; p < CV_HAIR_PMAX; p++) {
        if (uc < ap_pdf[p])
            break;
        uc -= ap_pdf[p];
    }
    if (!(ap_pdf[p] > 0.0))
        return false;
    uc = min(uc / ap_pdf[p], CV_ONE_MINUS_EPS);

    vec2 t = cv_hair_tilt(H, p, sin_o, cos_o);
    float u0 = max(u.x, 1e-5);
    float vp = H.v[p];
    float cos_theta = 1.0 + vp * log(u0 + (1.0 - u0) * exp(-2.0 / vp));
    float sin_theta = cv_hair_safe_sqrt(1.0 - cos_theta * cos_theta);
    float cos_phi = cos(2.0 * CV_PI * u.y);
    float sin_i = -cos_theta * t.x + sin_theta * cos_phi * t.y;
    float cos_i = cv_hair_safe_sqrt(1.0 - sin_i * sin_i);

    float gamma_t;
    cv_hair_transmittance(H, sin_o, cos_o, gamma_t);
    float dphi = p < CV_HAIR_PMAX ? cv_hair_phi(p, H.gamma_o, gamma_t) + cv_hair_sample_trimmed_logistic(uc, H.s)
                                  : 2.0 * CV_PI * uc;
    float phi_i = phi_o + dphi;
    vec3 wi = vec3(sin_i, cos_i * cos(phi_i), cos_i * sin(phi_i));

    s.wi = wi;
    s.pdf = cv_hair_pdf(H, wo, wi);
    s.f = cv_hair_f(H, wo, wi);
    s.flags = CV_BSDF_REFLECTION;
    return s.pdf > 0.0;
}

#endif
