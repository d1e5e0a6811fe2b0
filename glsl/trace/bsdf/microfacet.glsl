// glsl/trace/bsdf/microfacet.glsl: the anisotropic Trowbridge-Reitz (GGX)
// distribution in the local shading frame, with Smith masking and
// visible-normal sampling (Heitz 2018), following pbrt-v4's
// TrowbridgeReitzDistribution.
#ifndef CV_BSDF_MICROFACET_GLSL
#define CV_BSDF_MICROFACET_GLSL

#include "../../lib/constants.glsl"
#include "../../lib/frame.glsl"
#include "../../lib/sampling.glsl"

// Below this alpha a lobe is treated as perfectly specular (pbrt-v4: 1e-3).
#define CV_SMOOTH_ALPHA 1e-3

bool cv_mf_smooth(vec2 alpha) { return max(alpha.x, alpha.y) < CV_SMOOTH_ALPHA; }

float cv_mf_D(vec2 alpha, vec3 wm)
{
    float c2 = cv_cos2_theta(wm);
    float t2 = cv_tan2_theta(wm);
    if (isinf(t2) || c2 <= 0.0)
        return 0.0;
    float c4 = c2 * c2;
    float cp = cv_cos_phi(wm), sp = cv_sin_phi(wm);
    float e = t2 * (cp * cp / (alpha.x * alpha.x) + sp * sp / (alpha.y * alpha.y));
    return 1.0 / (CV_PI * alpha.x * alpha.y * c4 * (1.0 + e) * (1.0 + e));
}

float cv_mf_lambda(vec2 alpha, vec3 w)
{
    float t2 = cv_tan2_theta(w);
    if (isinf(t2) || isnan(t2))
        return 0.0;
    float cp = cv_cos_phi(w), sp = cv_sin_phi(w);
    float a2 = cp * cp * alpha.x * alpha.x + sp * sp * alpha.y * alpha.y;
    return (sqrt(1.0 + a2 * t2) - 1.0) / 2.0;
}

float cv_mf_G1(vec2 alpha, vec3 w) { return 1.0 / (1.0 + cv_mf_lambda(alpha, w)); }
float cv_mf_G(vec2 alpha, vec3 wo, vec3 wi)
{
    return 1.0 / (1.0 + cv_mf_lambda(alpha, wo) + cv_mf_lambda(alpha, wi));
}

// Distribution of normals visible from w: G1(w) / |cos w| * D(wm) * |w.wm|.
float cv_mf_D_visible(vec2 alpha, vec3 w, vec3 wm)
{
    return cv_mf_G1(alpha, w) / cv_abs_cos_theta(w) * cv_mf_D(alpha, wm) * abs(dot(w, wm));
}

float cv_mf_pdf(vec2 alpha, vec3 w, vec3 wm) { return cv_mf_D_visible(alpha, w, wm); }

// Samples a visible normal for w (either hemisphere: mirrored to +z).
vec3 cv_mf_sample_wm(vec2 alpha, vec3 w, vec2 u)
{
    vec3 wh = normalize(vec3(alpha.x * w.x, alpha.y * w.y, w.z));
    if (wh.z < 0.0)
        wh = -wh;
    vec3 t1 = wh.z < 0.99999 ? normalize(cross(vec3(0.0, 0.0, 1.0), wh)) : vec3(1.0, 0.0, 0.0);
    vec3 t2 = cross(wh, t1);
    vec2 p = cv_sample_disk_concentric(u);
    float h = sqrt(max(0.0, 1.0 - p.x * p.x));
    p.y = mix(h, p.y, (1.0 + wh.z) / 2.0);
    float pz = sqrt(max(0.0, 1.0 - dot(p, p)));
    vec3 nh = p.x * t1 + p.y * t2 + pz * wh;
    return normalize(vec3(alpha.x * nh.x, alpha.y * nh.y, max(1e-6, nh.z)));
}

#endif
