// glsl/trace/bsdf/fresnel.glsl: Fresnel reflectance (dielectric and
// conductor) and refraction, in pbrt-v4's conventions: eta is the relative
// IOR eta_t / eta_i with the normal on the incident side when cos_i > 0.
#ifndef CV_BSDF_FRESNEL_GLSL
#define CV_BSDF_FRESNEL_GLSL

#include "../../lib/constants.glsl"

// Unpolarized reflectance of a dielectric interface; cos_i < 0 means the
// direction is on the inside, so the interface is seen with 1/eta.
float cv_fr_dielectric(float cos_i, float eta)
{
    cos_i = clamp(cos_i, -1.0, 1.0);
    if (cos_i < 0.0) {
        eta = 1.0 / eta;
        cos_i = -cos_i;
    }
    float sin2_i = 1.0 - cos_i * cos_i;
    float sin2_t = sin2_i / (eta * eta);
    if (sin2_t >= 1.0)
        return 1.0;
    float cos_t = cv_safe_sqrt(1.0 - sin2_t);
    float r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5 * (r_parl * r_parl + r_perp * r_perp);
}

// Complex arithmetic on vec2 (re, im).
vec2 cv_cmul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
vec2 cv_cdiv(vec2 a, vec2 b)
{
    float s = 1.0 / dot(b, b);
    return vec2(a.x * b.x + a.y * b.y, a.y * b.x - a.x * b.y) * s;
}
float cv_cnorm(vec2 a) { return dot(a, a); }
vec2 cv_csqrt(vec2 z)
{
    float n = length(z);
    if (n == 0.0)
        return vec2(0.0);
    float t1 = sqrt(0.5 * (n + abs(z.x)));
    float t2 = 0.5 * z.y / t1;
    if (z.x >= 0.0)
        return vec2(t1, t2);
    return vec2(abs(t2), z.y >= 0.0 ? t1 : -t1);
}

// Conductor reflectance for complex IOR eta + i k, one channel.
float cv_fr_complex1(float cos_i, float eta_re, float k)
{
    vec2 eta = vec2(eta_re, k);
    cos_i = clamp(cos_i, 0.0, 1.0);
    float sin2_i = 1.0 - cos_i * cos_i;
    vec2 sin2_t = cv_cdiv(vec2(sin2_i, 0.0), cv_cmul(eta, eta));
    vec2 cos_t = cv_csqrt(vec2(1.0, 0.0) - sin2_t);
    vec2 ci = vec2(cos_i, 0.0);
    vec2 r_parl = cv_cdiv(cv_cmul(eta, ci) - cos_t, cv_cmul(eta, ci) + cos_t);
    vec2 r_perp = cv_cdiv(ci - cv_cmul(eta, cos_t), ci + cv_cmul(eta, cos_t));
    return 0.5 * (cv_cnorm(r_parl) + cv_cnorm(r_perp));
}

#ifdef CV_CONDUCTOR_TABLES
// The Fresnel tables of conductors given by spectra (glsl/shared/
// conductor_fresnel.h): a buffer texture, not a storage block.
#include "shared/bindings.h"
#include "shared/conductor_fresnel.h"
layout(binding = CV_TEXUNIT_CONDUCTOR_FRESNEL) uniform samplerBuffer cv_conductor_fresnel;

vec3 cv_fr_table(float cos_i, int t)
{
    float x = clamp(cos_i, 0.0, 1.0) * float(CV_CONDUCTOR_FRESNEL_N - 1);
    int i = min(int(x), CV_CONDUCTOR_FRESNEL_N - 2);
    int at = t * CV_CONDUCTOR_FRESNEL_N + i;
    return mix(texelFetch(cv_conductor_fresnel, at).rgb, texelFetch(cv_conductor_fresnel, at + 1).rgb,
               x - float(i));
}
#endif

// eta.x < 0 (CV_CONDUCTOR_TABLES only): a conductor given by spectra, k.x
// its table (cv_material_conductor).
vec3 cv_fr_complex(float cos_i, vec3 eta, vec3 k)
{
#ifdef CV_CONDUCTOR_TABLES
    if (eta.x < 0.0)
        return cv_fr_table(cos_i, int(k.x));
#endif
    return vec3(cv_fr_complex1(cos_i, eta.x, k.x), cv_fr_complex1(cos_i, eta.y, k.y),
                cv_fr_complex1(cos_i, eta.z, k.z));
}

// Refracts wi about n (same side as wi) with relative eta; false on total
// internal reflection. etap receives the eta actually used.
bool cv_refract(vec3 wi, vec3 n, float eta, out float etap, out vec3 wt)
{
    float cos_i = dot(n, wi);
    if (cos_i < 0.0) {
        eta = 1.0 / eta;
        cos_i = -cos_i;
        n = -n;
    }
    etap = eta;
    float sin2_i = max(0.0, 1.0 - cos_i * cos_i);
    float sin2_t = sin2_i / (eta * eta);
    wt = vec3(0.0);
    if (sin2_t >= 1.0)
        return false;
    float cos_t = cv_safe_sqrt(1.0 - sin2_t);
    wt = -wi / eta + (cos_i / eta - cos_t) * n;
    return true;
}

#endif
