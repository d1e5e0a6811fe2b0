// glsl/trace/bsdf/bssrdf.glsl: pbrt-v4's TabulatedBSSRDF of the subsurface
// material, in RGB: the radial profile Sr interpolated from the beam
// diffusion table (glsl/shared/bssrdf.h, computed at load by
// src/scene/bssrdf_table.c) by tensor Catmull-Rom splines over albedo and
// optical radius, its sampling (one colour channel's profile, by inverting
// the spline's integral), the density of a probe segment's exit point
// (three projection axes, MIS over the channels), and the exit lobe Sw
// (pbrt-v4's NormalizedFresnelBxDF). pbrt-v4 is spectral and samples with
// the hero wavelength's profile, weighting by the average density over its
// wavelengths; here a channel is chosen uniformly and the weight is the
// average over the three channels' densities: the same estimator over
// colour channels. The table is a buffer texture (texture unit
// CV_TEXUNIT_BSSRDF, not a storage block: the shade kernels are near
// Mesa's limit of 16). Compiled only with CV_HAS_SUBSURFACE.
#ifndef CV_BSDF_BSSRDF_GLSL
#define CV_BSDF_BSSRDF_GLSL

#include "shared/bindings.h"
#include "shared/bssrdf.h"

layout(binding = CV_TEXUNIT_BSSRDF) uniform samplerBuffer cv_bssrdf_tables;

// Entry i (glsl/shared/bssrdf.h's offsets) of table t.
float cv_bssrdf_at(uint t, int i)
{
    return texelFetch(cv_bssrdf_tables, int(t) * CV_BSSRDF_FLOATS + i).x;
}

// The segment i with nodes[i] <= x < nodes[i + 1] of the n nodes from
// entry `base`, clamped to 0..n-2 (pbrt-v4's FindInterval).
int cv_bssrdf_interval(uint t, int base, int n, float x)
{
    int lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (cv_bssrdf_at(t, base + mid) <= x)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

// Catmull-Rom weights of x over the n nodes from `base` (pbrt-v4's
// CatmullRomWeights): false outside them.
bool cv_bssrdf_weights(uint t, int base, int n, float x, out int offset, out vec4 w)
{
    offset = 0;
    w = vec4(0.0);
    if (!(x >= cv_bssrdf_at(t, base) && x <= cv_bssrdf_at(t, base + n - 1)))
        return false;
    int i = cv_bssrdf_interval(t, base, n, x);
    offset = i - 1;
    float x0 = cv_bssrdf_at(t, base + i), x1 = cv_bssrdf_at(t, base + i + 1);
    float s = (x - x0) / (x1 - x0), s2 = s * s, s3 = s2 * s;
    w.y = 2.0 * s3 - 3.0 * s2 + 1.0;
    w.z = -2.0 * s3 + 3.0 * s2;
    if (i > 0) {
        float w0 = (s3 - 2.0 * s2 + s) * (x1 - x0) / (x1 - cv_bssrdf_at(t, base + i - 1));
        w.x = -w0;
        w.z += w0;
    } else {
        float w0 = s3 - 2.0 * s2 + s;
        w.y -= w0;
        w.z += w0;
    }
    if (i + 2 < n) {
        float w3 = (s3 - s2) * (x1 - x0) / (cv_bssrdf_at(t, base + i + 2) - x0);
        w.y -= w3;
        w.w = w3;
    } else {
        float w3 = s3 - s2;
        w.y -= w3;
        w.z += w3;
    }
    return true;
}

// Sr (x) and its sampling density (y) at radius r for one channel of
// albedo rho and extinction sigma_t: pbrt-v4's Sr and PDF_Sr.
vec2 cv_bssrdf_sr(uint t, float rho, float sigma_t, float r)
{
    float ro = r * sigma_t;
    int oi, oj;
    vec4 wi, wj;
    if (!cv_bssrdf_weights(t, CV_BSSRDF_RHO, CV_BSSRDF_N_RHO, rho, oi, wi) ||
        !cv_bssrdf_weights(t, CV_BSSRDF_RADIUS, CV_BSSRDF_N_RADIUS, ro, oj, wj))
        return vec2(0.0);
    float sr = 0.0, rho_eff = 0.0;
    for (int j = 0; j < 4; j++) {
        if (wi[j] == 0.0)
            continue;
        rho_eff += wi[j] * cv_bssrdf_at(t, CV_BSSRDF_RHO_EFF + oi + j);
        for (int k = 0; k < 4; k++)
            if (wj[k] != 0.0)
                sr += wi[j] * wj[k] * cv_bssrdf_at(t, CV_BSSRDF_PROFILE + (oi + j) * CV_BSSRDF_N_RADIUS + oj + k);
    }
    if (ro != 0.0)
        sr /= 2.0 * CV_PI * ro;  // the table holds 2 pi r Sr
    sr *= sigma_t * sigma_t;
    return max(vec2(sr, rho_eff > 0.0 ? sr / rho_eff : 0.0), vec2(0.0));
}

// The profile's spline of albedo weights (oi, wi) at radius node k: of
// the profile (cdf false) or its running integral (cdf true).
float cv_bssrdf_lerp(uint t, int oi, vec4 wi, int k, bool cdf)
{
    int base = cdf ? CV_BSSRDF_CDF : CV_BSSRDF_PROFILE;
    float v = 0.0;
    for (int j = 0; j < 4; j++)
        if (wi[j] != 0.0)
            v += wi[j] * cv_bssrdf_at(t, base + (oi + j) * CV_BSSRDF_N_RADIUS + k);
    return v;
}

// A radius drawn from one channel's profile (pbrt-v4's SampleSr: the
// inverse of the spline's integral, SampleCatmullRom2D), < 0 when the
// channel does not scatter.
float cv_bssrdf_sample_sr(uint t, float rho, float sigma_t, float u)
{
    int oi;
    vec4 wi;
    if (!(sigma_t > 0.0) || !cv_bssrdf_weights(t, CV_BSSRDF_RHO, CV_BSSRDF_N_RHO, rho, oi, wi))
        return -1.0;
    const int n = CV_BSSRDF_N_RADIUS;
    float maximum = cv_bssrdf_lerp(t, oi, wi, n - 1, true);
    if (!(maximum > 0.0))
        return -1.0;
    u *= maximum;
    // the interval whose interpolated CDF brackets u
    int lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (cv_bssrdf_lerp(t, oi, wi, mid, true) <= u)
            lo = mid;
        else
            hi = mid;
    }
    int i = lo;
    float f0 = cv_bssrdf_lerp(t, oi, wi, i, false), f1 = cv_bssrdf_lerp(t, oi, wi, i + 1, false);
    float x0 = cv_bssrdf_at(t, CV_BSSRDF_RADIUS + i), x1 = cv_bssrdf_at(t, CV_BSSRDF_RADIUS + i + 1);
    float width = x1 - x0;
    u = (u - cv_bssrdf_lerp(t, oi, wi, i, true)) / width;
    float d0 = i > 0 ? width * (f1 - cv_bssrdf_lerp(t, oi, wi, i - 1, false)) /
                           (x1 - cv_bssrdf_at(t, CV_BSSRDF_RADIUS + i - 1))
                     : f1 - f0;
    float d1 = i + 2 < n ? width * (cv_bssrdf_lerp(t, oi, wi, i + 2, false) - f0) /
                               (cv_bssrdf_at(t, CV_BSSRDF_RADIUS + i + 2) - x0)
                         : f1 - f0;
    // Newton-bisection on the segment's integral F(s) = u (pbrt-v4's
    // NewtonBisection with its tolerances)
    float a = 0.0, b = 1.0;
    float c1 = 0.5 * d0, c2 = (1.0 / 3.0) * (-2.0 * d0 - d1) + f1 - f0,
          c3 = 0.25 * (d0 + d1) + 0.5 * (f0 - f1);
    float Fa = -u, Fb = f0 + c1 + c2 + c3 - u;
    if (abs(Fa) < 1e-6)
        return x0 / sigma_t;
    if (abs(Fb) < 1e-6)
        return x1 / sigma_t;
    bool neg = Fa < 0.0;
    float s = -Fa / (Fb - Fa);
    for (int it = 0; it < 64; it++) {
        if (!(s > a && s < b))
            s = 0.5 * (a + b);
        float F = s * (f0 + s * (c1 + s * (c2 + s * c3))) - u;
        float f = f0 + s * (d0 + s * ((-2.0 * d0 - d1 + 3.0 * (f1 - f0)) + s * (d0 + d1 + 2.0 * (f0 - f1))));
        if (neg == (F < 0.0))
            a = s;
        else
            b = s;
        if (b - a < 1e-6 || abs(F) < 1e-6)
            break;
        s -= F / f;
    }
    return (x0 + width * s) / sigma_t;
}

// The albedo rho of table t whose effective albedo is u (pbrt-v4's
// InvertCatmullRom of the effective albedos: Newton-bisection on the
// spline segment that brackets u).
float cv_bssrdf_invert(uint t, float u)
{
    const int n = CV_BSSRDF_N_RHO;
    float f_lo = cv_bssrdf_at(t, CV_BSSRDF_RHO_EFF), f_hi = cv_bssrdf_at(t, CV_BSSRDF_RHO_EFF + n - 1);
    if (!(u > f_lo))
        return cv_bssrdf_at(t, CV_BSSRDF_RHO);
    if (!(u < f_hi))
        return cv_bssrdf_at(t, CV_BSSRDF_RHO + n - 1);
    int i = cv_bssrdf_interval(t, CV_BSSRDF_RHO_EFF, n, u);
    float x0 = cv_bssrdf_at(t, CV_BSSRDF_RHO + i), x1 = cv_bssrdf_at(t, CV_BSSRDF_RHO + i + 1);
    float f0 = cv_bssrdf_at(t, CV_BSSRDF_RHO_EFF + i), f1 = cv_bssrdf_at(t, CV_BSSRDF_RHO_EFF + i + 1);
    float w = x1 - x0;
    float d0 = i > 0 ? w * (f1 - cv_bssrdf_at(t, CV_BSSRDF_RHO_EFF + i - 1)) / (x1 - cv_bssrdf_at(t, CV_BSSRDF_RHO + i - 1))
                     : f1 - f0;
    float d1 = i + 2 < n ? w * (cv_bssrdf_at(t, CV_BSSRDF_RHO_EFF + i + 2) - f0) /
                               (cv_bssrdf_at(t, CV_BSSRDF_RHO + i + 2) - x0)
                         : f1 - f0;
    float a = 0.0, b = 1.0, s = (u - f0) / (f1 - f0);
    for (int it = 0; it < 64; it++) {
        if (!(s > a && s < b))
            s = 0.5 * (a + b);
        float s2 = s * s, s3 = s2 * s;
        float F = (2.0 * s3 - 3.0 * s2 + 1.0) * f0 + (-2.0 * s3 + 3.0 * s2) * f1 + (s3 - 2.0 * s2 + s) * d0 +
                  (s3 - s2) * d1 - u;
        float dF = (6.0 * s2 - 6.0 * s) * f0 + (-6.0 * s2 + 6.0 * s) * f1 + (3.0 * s2 - 4.0 * s + 1.0) * d0 +
                   (3.0 * s2 - 2.0 * s) * d1;
        if (F < 0.0)
            a = s;
        else
            b = s;
        if (b - a < 1e-6 || abs(F) < 1e-6)
            break;
        s -= F / dF;
    }
    return x0 + s * w;
}

// A subsurface material's scattering: per-channel albedo and extinction,
// its table and eta (glsl/shared/scene.h's CV_MAT_SUBSURFACE).
struct CvBssrdf { vec3 rho; vec3 sigma_t; uint table; float eta; };

CvBssrdf cv_bssrdf_make(vec3 sigma_a, vec3 sigma_s, uint table, float eta)
{
    vec3 st = sigma_a + sigma_s;
    vec3 rho = mix(vec3(0.0), sigma_s / max(st, vec3(1e-30)), greaterThan(st, vec3(0.0)));
    return CvBssrdf(rho, st, table, eta);
}

// The coefficients of material `material` at a point where its
// coefficients (or their textures) read c_a and c_s: sigma_a and sigma_s
// (per scene unit), as pbrt-v4's SubsurfaceMaterial::GetBSSRDF.
void cv_bssrdf_sigma(uint material, vec3 c_a, vec3 c_s, out vec3 sigma_a, out vec3 sigma_s)
{
    CvMaterial m = materials[material];
    sigma_a = m.reflectance.rgb;
    sigma_s = m.specular.rgb;
    if ((m.flags & CV_MATF_SSS_POINT) == 0u)
        return;  // constants, scaled (and inverted) at load
    float scale = m.k.y;
    if ((m.flags & CV_MATF_SSS_DIFFUSE) != 0u) {
        vec3 mfree = max(scale * c_s, vec3(1e-30));
        for (int c = 0; c < 3; c++) {
            float rho = cv_bssrdf_invert(uint(m.k.x), clamp(c_a[c], 0.0, 1.0));
            sigma_s[c] = rho / mfree[c];
            sigma_a[c] = (1.0 - rho) / mfree[c];
        }
    } else {
        sigma_a = max(scale * c_a, vec3(0.0));
        sigma_s = max(scale * c_s, vec3(0.0));
    }
}

// The three projection axes of a probe at a point with normal ns, as one
// frame: x, y tangents (probability 1/4 each), z the normal (1/2).
CvFrame cv_bssrdf_axes(vec3 ns) { return cv_frame_from_z(ns); }

// A probe segment at po (normal ns): start p0 and the vector to its end,
// from u1 (axis, then channel) and u2 (radius, angle); false when the
// sampled radius lies beyond the channel's profile (pbrt-v4's SampleSp).
bool cv_bssrdf_probe(CvBssrdf s, vec3 po, vec3 ns, float u1, vec2 u2, out vec3 p0, out vec3 seg)
{
    p0 = po;
    seg = vec3(0.0);
    CvFrame f = cv_bssrdf_axes(ns);
    vec3 axis, a1, a2;
    float v;  // u1 rescaled within the axis' range, for the channel
    if (u1 < 0.25) {
        axis = f.x; a1 = f.y; a2 = f.z;
        v = u1 * 4.0;
    } else if (u1 < 0.5) {
        axis = f.y; a1 = f.z; a2 = f.x;
        v = (u1 - 0.25) * 4.0;
    } else {
        axis = f.z; a1 = f.x; a2 = f.y;
        v = (u1 - 0.5) * 2.0;
    }
    int c = min(int(v * 3.0), 2);
    float r = cv_bssrdf_sample_sr(s.table, s.rho[c], s.sigma_t[c], u2.x);
    if (r < 0.0)
        return false;
    float r_max = cv_bssrdf_sample_sr(s.table, s.rho[c], s.sigma_t[c], 0.999);
    if (!(r < r_max))
        return false;
    float l = 2.0 * sqrt(r_max * r_max - r * r);
    float phi = 2.0 * CV_PI * u2.y;
    p0 = po + r * (cos(phi) * a1 + sin(phi) * a2) - 0.5 * l * axis;
    seg = l * axis;
    return true;
}

// Sp at exit point pi and the density (per area, channels averaged) of
// having probed it from po (normal ns), with geometric normal ni there
// (pbrt-v4's Sp and PDF_Sp).
vec3 cv_bssrdf_sp(CvBssrdf s, vec3 po, vec3 ns, vec3 pi, vec3 ni, out float pdf)
{
    CvFrame f = cv_bssrdf_axes(ns);
    vec3 d = cv_to_local(f, pi - po), n = cv_to_local(f, ni);
    vec3 r_proj = sqrt(vec3(d.y * d.y + d.z * d.z, d.z * d.z + d.x * d.x, d.x * d.x + d.y * d.y));
    vec3 axis_prob = vec3(0.25, 0.25, 0.5);
    float dist = length(pi - po);
    vec3 sp = vec3(0.0);
    pdf = 0.0;
    for (int c = 0; c < 3; c++) {
        sp[c] = cv_bssrdf_sr(s.table, s.rho[c], s.sigma_t[c], dist).x;
        for (int a = 0; a < 3; a++)
            pdf += cv_bssrdf_sr(s.table, s.rho[c], s.sigma_t[c], r_proj[a]).y * abs(n[a]) * axis_prob[a];
    }
    pdf /= 3.0;
    return sp;
}

#endif
