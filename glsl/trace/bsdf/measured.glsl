// glsl/trace/bsdf/measured.glsl: pbrt-v4's MeasuredBxDF, the measured BRDFs
// of the RGL database (Dupuy & Jakob 2018, "An Adaptive Parameterization
// for Efficient Material Acquisition and Rendering"), on the tables of
// glsl/shared/measured.h. Angles map to the unit square as pbrt-v4 does:
// u(theta) = sqrt(theta / (pi/2)), u(phi) = phi / (2 pi) + 1/2, phi of the
// half vector taken relative to phi of wo for isotropic BRDFs.
//
// f(wo, wi) = rgb(R^-1(u(wm))) D(u(wm)) / (4 sigma(u(wo)) cos(wi)), with
// R the visible-normal warp of wo's slice and rgb the file's spectra in
// Rec.709. Sampling warps u by the luminance table, then by the
// visible-normal warp, into the half vector, and reflects wo about it.
// Reflection only; the callers mirror wo onto +z (cv_bsdf_mirrored).
//
// The including shader declares the tables (material_buffers.glsl, read
// by cv_measured(i)). Each lookup reads the buffer texture; a shading
// point reads a few dozen words (three warps, two binary searches each when sampling).
#ifndef CV_BSDF_MEASURED_GLSL
#define CV_BSDF_MEASURED_GLSL

#include "../../lib/constants.glsl"
#include "shared/measured.h"
#include "bsdf_sample.glsl"

float cv_meas_word(uint i) { return uintBitsToFloat(cv_measured(i)); }

// One table: its grid, arrays (absolute word offsets) and value scale.
struct CvMeasTable { uint nx; uint ny; uint data; uint marg; uint cond; float scale; };

CvMeasTable cv_meas_table(uint base, uint k)
{
    uint h = base + CV_MEAS_H_WARPS + k * CV_MEAS_W_WORDS;
    return CvMeasTable(cv_measured(h + CV_MEAS_W_NX), cv_measured(h + CV_MEAS_W_NY),
                       base + cv_measured(h + CV_MEAS_W_DATA), base + cv_measured(h + CV_MEAS_W_MARGINAL),
                       base + cv_measured(h + CV_MEAS_W_COND), cv_meas_word(h + CV_MEAS_W_SCALE));
}

// Where (phi_i, theta_i) of wo falls among the tables' slices: the lower
// slice, the strides (in slices) to the upper neighbour in phi and theta
// (0 where that parameter has one entry) and the weights of the upper ones.
struct CvMeasParams { uint slice; uint s_phi; uint s_theta; float w_phi; float w_theta; };

const CvMeasParams CV_MEAS_NO_PARAMS = CvMeasParams(0u, 0u, 0u, 0.0, 0.0);

// i in [0, n - 2] with values[i] <= x < values[i + 1], clamped at the ends
// (pbrt-v4's FindInterval over ascending values).
uint cv_meas_interval(uint values, uint n, float x)
{
    int size = int(n) - 2, first = 1;
    while (size > 0) {
        int h = size >> 1, middle = first + h;
        bool below = cv_meas_word(values + uint(middle)) <= x;
        first = below ? middle + 1 : first;
        size = below ? size - (h + 1) : h;
    }
    return uint(clamp(first - 1, 0, max(int(n) - 2, 0)));
}

// channels: slices per (phi, theta) pair (3 for the colour table).
CvMeasParams cv_meas_params(uint base, float phi, float theta, uint channels)
{
    uint nphi = cv_measured(base + CV_MEAS_H_NPHI), ntheta = cv_measured(base + CV_MEAS_H_NTHETA);
    uint vphi = base + cv_measured(base + CV_MEAS_H_PHI), vtheta = base + cv_measured(base + CV_MEAS_H_THETA);
    CvMeasParams P = CvMeasParams(0u, 0u, 0u, 0.0, 0.0);
    if (nphi > 1u) {
        uint i = cv_meas_interval(vphi, nphi, phi);
        float p0 = cv_meas_word(vphi + i), p1 = cv_meas_word(vphi + i + 1u);
        P.w_phi = clamp((phi - p0) / (p1 - p0), 0.0, 1.0);
        P.s_phi = ntheta * channels;
        P.slice += i * P.s_phi;
    }
    if (ntheta > 1u) {
        uint i = cv_meas_interval(vtheta, ntheta, theta);
        float t0 = cv_meas_word(vtheta + i), t1 = cv_meas_word(vtheta + i + 1u);
        P.w_theta = clamp((theta - t0) / (t1 - t0), 0.0, 1.0);
        P.s_theta = channels;
        P.slice += i * P.s_theta;
    }
    return P;
}

// Value i of an array of slices of `size` values, interpolated over the
// parameters.
float cv_meas_lookup(uint arr, uint i, uint size, CvMeasParams P)
{
    uint i0 = arr + P.slice * size + i;
    float v00 = cv_meas_word(i0), v01 = cv_meas_word(i0 + P.s_theta * size);
    float v10 = cv_meas_word(i0 + P.s_phi * size), v11 = cv_meas_word(i0 + (P.s_phi + P.s_theta) * size);
    return mix(mix(v00, v01, P.w_theta), mix(v10, v11, P.w_theta), P.w_phi);
}

// The table's value (density for VNDF and LUM) at p in [0,1]^2.
float cv_meas_eval(CvMeasTable T, vec2 p, CvMeasParams P)
{
    p *= vec2(float(T.nx - 1u), float(T.ny - 1u));
    uvec2 o = uvec2(min(ivec2(max(p, vec2(0.0))), ivec2(T.nx - 2u, T.ny - 2u)));
    vec2 w1 = p - vec2(o), w0 = 1.0 - w1;
    uint i = o.x + o.y * T.nx, size = T.nx * T.ny;
    float v00 = cv_meas_lookup(T.data, i, size, P), v10 = cv_meas_lookup(T.data, i + 1u, size, P);
    float v01 = cv_meas_lookup(T.data, i + T.nx, size, P), v11 = cv_meas_lookup(T.data, i + T.nx + 1u, size, P);
    return (w0.y * (w0.x * v00 + w1.x * v10) + w1.y * (w0.x * v01 + w1.x * v11)) * T.scale;
}

// Solves for t in [0,1] with the integral of the linear density c0..c1
// from 0 to t equal to a (pbrt-v4's linear-segment inversion).
float cv_meas_solve(float a, float c0, float c1)
{
    if (abs(c0 - c1) < 1e-4 * (c0 + c1))
        return 2.0 * a / (c0 + c1);
    return (c0 - sqrt(max(c0 * c0 - 2.0 * a * (c0 - c1), 0.0))) / (c0 - c1);
}

// Warps u in [0,1)^2 by a sampled table: .xy the point, .z its density.
vec3 cv_meas_sample(CvMeasTable T, vec2 u, CvMeasParams P)
{
    u = clamp(u, vec2(1.0 - CV_ONE_MINUS_EPS), vec2(CV_ONE_MINUS_EPS));
    uint size = T.nx * T.ny;
    // the row, from the marginal CDF
    int n = int(T.ny) - 2, first = 1;
    while (n > 0) {
        int h = n >> 1, middle = first + h;
        bool below = cv_meas_lookup(T.marg, uint(middle), T.ny, P) < u.y;
        first = below ? middle + 1 : first;
        n = below ? n - (h + 1) : h;
    }
    uint row = uint(clamp(first - 1, 0, int(T.ny) - 2));
    u.y -= cv_meas_lookup(T.marg, row, T.ny, P);
    uint off = row * T.nx;
    float r0 = cv_meas_lookup(T.cond, off + T.nx - 1u, size, P);
    float r1 = cv_meas_lookup(T.cond, off + 2u * T.nx - 1u, size, P);
    u.y = cv_meas_solve(u.y, r0, r1);
    // the column, from the conditional CDF between the row's two lines
    u.x *= (1.0 - u.y) * r0 + u.y * r1;
    n = int(T.nx) - 2;
    first = 1;
    while (n > 0) {
        int h = n >> 1, middle = first + h;
        float c = mix(cv_meas_lookup(T.cond, off + uint(middle), size, P),
                      cv_meas_lookup(T.cond, off + T.nx + uint(middle), size, P), u.y);
        bool below = c < u.x;
        first = below ? middle + 1 : first;
        n = below ? n - (h + 1) : h;
    }
    uint col = uint(clamp(first - 1, 0, int(T.nx) - 2));
    u.x -= mix(cv_meas_lookup(T.cond, off + col, size, P), cv_meas_lookup(T.cond, off + T.nx + col, size, P), u.y);
    off += col;
    float v00 = cv_meas_lookup(T.data, off, size, P), v10 = cv_meas_lookup(T.data, off + 1u, size, P);
    float v01 = cv_meas_lookup(T.data, off + T.nx, size, P), v11 = cv_meas_lookup(T.data, off + T.nx + 1u, size, P);
    float c0 = mix(v00, v01, u.y), c1 = mix(v10, v11, u.y);
    u.x = cv_meas_solve(u.x, c0, c1);
    vec2 p = (vec2(float(col), float(row)) + u) / vec2(float(T.nx - 1u), float(T.ny - 1u));
    return vec3(p, mix(c0, c1, u.x) * T.scale);
}

// The inverse of cv_meas_sample: .xy the uniform point that warps to p,
// .z the density at p.
vec3 cv_meas_invert(CvMeasTable T, vec2 p, CvMeasParams P)
{
    p *= vec2(float(T.nx - 1u), float(T.ny - 1u));
    uvec2 o = uvec2(min(ivec2(max(p, vec2(0.0))), ivec2(T.nx - 2u, T.ny - 2u)));
    p -= vec2(o);
    uint size = T.nx * T.ny, off = o.x + o.y * T.nx;
    float v00 = cv_meas_lookup(T.data, off, size, P), v10 = cv_meas_lookup(T.data, off + 1u, size, P);
    float v01 = cv_meas_lookup(T.data, off + T.nx, size, P), v11 = cv_meas_lookup(T.data, off + T.nx + 1u, size, P);
    float c0 = mix(v00, v01, p.y), c1 = mix(v10, v11, p.y), pdf = mix(c0, c1, p.x);
    p.x *= c0 + 0.5 * p.x * (c1 - c0);
    p.x += mix(cv_meas_lookup(T.cond, off, size, P), cv_meas_lookup(T.cond, off + T.nx, size, P), p.y);
    off = o.y * T.nx;
    float r0 = cv_meas_lookup(T.cond, off + T.nx - 1u, size, P);
    float r1 = cv_meas_lookup(T.cond, off + 2u * T.nx - 1u, size, P);
    p.x /= mix(r0, r1, p.y);
    p.y *= r0 + 0.5 * p.y * (r1 - r0);
    p.y += cv_meas_lookup(T.marg, o.y, T.ny, P);
    return vec3(p, pdf * T.scale);
}

float cv_meas_theta_to_u(float theta) { return sqrt(theta * (2.0 / CV_PI)); }
float cv_meas_phi_to_u(float phi) { return phi * CV_INV_2PI + 0.5; }
float cv_meas_phi(vec3 w) { return (w.x == 0.0 && w.y == 0.0) ? 0.0 : atan(w.y, w.x); }
float cv_meas_theta(vec3 w) { return acos(clamp(w.z, -1.0, 1.0)); }

// The colour table at u (the visible-normal warp's uniform point).
vec3 cv_meas_rgb(uint base, vec2 u, float phi_o, float theta_o)
{
    CvMeasTable T = cv_meas_table(base, CV_MEAS_RGB);
    CvMeasParams P = cv_meas_params(base, phi_o, theta_o, 3u);
    vec3 rgb;
    for (uint c = 0u; c < 3u; c++) {
        CvMeasParams Pc = P;
        Pc.slice += c;
        rgb[c] = max(cv_meas_eval(T, u, Pc), 0.0);
    }
    return rgb;
}

// D(wm) / (4 sigma(wo))
float cv_meas_ndf_over_sigma(uint base, vec2 u_wm, vec2 u_wo)
{
    float sigma = cv_meas_eval(cv_meas_table(base, CV_MEAS_SIGMA), u_wo, CV_MEAS_NO_PARAMS);
    float d = cv_meas_eval(cv_meas_table(base, CV_MEAS_NDF), u_wm, CV_MEAS_NO_PARAMS);
    return sigma > 0.0 ? d / (4.0 * sigma) : 0.0;
}

// u(wm) of the half vector, as the tables index it.
vec2 cv_meas_u_wm(uint base, vec3 wm, float phi_o)
{
    bool iso = cv_measured(base + CV_MEAS_H_ISOTROPIC) != 0u;
    float phi_m = cv_meas_phi(wm);
    vec2 u = vec2(cv_meas_theta_to_u(cv_meas_theta(wm)), cv_meas_phi_to_u(iso ? phi_m - phi_o : phi_m));
    u.y -= floor(u.y);
    return u;
}

// d(solid angle of wi) per unit square of u(wm): 4 (wo.wm) 2 pi^2 u sin(theta_m), floored as pbrt-v4.
float cv_meas_jacobian(vec3 wo, vec3 wm, float u_theta)
{
    float sin_m = sqrt(wm.x * wm.x + wm.y * wm.y);
    return 4.0 * dot(wo, wm) * max(2.0 * CV_PI * CV_PI * u_theta * sin_m, 1e-6);
}

vec3 cv_measured_f(uint base, vec3 wo, vec3 wi)
{
    if (wo.z <= 0.0 || wi.z <= 0.0)
        return vec3(0.0);
    vec3 wm = wi + wo;
    if (dot(wm, wm) == 0.0)
        return vec3(0.0);
    wm = normalize(wm);
    float theta_o = cv_meas_theta(wo), phi_o = cv_meas_phi(wo);
    vec2 u_wo = vec2(cv_meas_theta_to_u(theta_o), cv_meas_phi_to_u(phi_o));
    vec2 u_wm = cv_meas_u_wm(base, wm, phi_o);
    CvMeasParams P = cv_meas_params(base, phi_o, theta_o, 1u);
    vec3 ui = cv_meas_invert(cv_meas_table(base, CV_MEAS_VNDF), u_wm, P);
    return cv_meas_rgb(base, ui.xy, phi_o, theta_o) * cv_meas_ndf_over_sigma(base, u_wm, u_wo) / wi.z;
}

float cv_measured_pdf(uint base, vec3 wo, vec3 wi)
{
    if (wo.z <= 0.0 || wi.z <= 0.0)
        return 0.0;
    vec3 wm = wi + wo;
    if (dot(wm, wm) == 0.0)
        return 0.0;
    wm = normalize(wm);
    float theta_o = cv_meas_theta(wo), phi_o = cv_meas_phi(wo);
    vec2 u_wm = cv_meas_u_wm(base, wm, phi_o);
    CvMeasParams P = cv_meas_params(base, phi_o, theta_o, 1u);
    vec3 ui = cv_meas_invert(cv_meas_table(base, CV_MEAS_VNDF), u_wm, P);
    float lum = cv_meas_eval(cv_meas_table(base, CV_MEAS_LUM), ui.xy, P);
    return ui.z * lum / cv_meas_jacobian(wo, wm, u_wm.x);
}

bool cv_measured_sample(uint base, vec3 wo, vec2 u, out CvBsdfSample s)
{
    s = CvBsdfSample(vec3(0.0), vec3(0.0), 0.0, 0u);
    if (wo.z <= 0.0)
        return false;
    float theta_o = cv_meas_theta(wo), phi_o = cv_meas_phi(wo);
    CvMeasParams P = cv_meas_params(base, phi_o, theta_o, 1u);
    vec3 l = cv_meas_sample(cv_meas_table(base, CV_MEAS_LUM), u, P);
    vec3 v = cv_meas_sample(cv_meas_table(base, CV_MEAS_VNDF), l.xy, P);
    vec2 u_wm = v.xy;
    float phi_m = (2.0 * u_wm.y - 1.0) * CV_PI, theta_m = u_wm.x * u_wm.x * CV_PI_OVER_2;
    if (cv_measured(base + CV_MEAS_H_ISOTROPIC) != 0u)
        phi_m += phi_o;
    float sin_m = sin(theta_m);
    vec3 wm = vec3(sin_m * cos(phi_m), sin_m * sin(phi_m), cos(theta_m));
    vec3 wi = reflect(-wo, wm);
    if (wi.z <= 0.0)
        return false;
    vec2 u_wo = vec2(cv_meas_theta_to_u(theta_o), cv_meas_phi_to_u(phi_o));
    vec3 f = cv_meas_rgb(base, l.xy, phi_o, theta_o) * cv_meas_ndf_over_sigma(base, u_wm, u_wo) / wi.z;
    float pdf = v.z * l.z / cv_meas_jacobian(wo, wm, u_wm.x);
    if (!(pdf > 0.0))
        return false;
    s = CvBsdfSample(wi, f, pdf, CV_BSDF_REFLECTION);
    return true;
}

// A colour for the albedo AOV: the colour table for wo along the normal,
// at the middle of the warp's square.
vec3 cv_measured_albedo(uint base)
{
    return cv_meas_rgb(base, vec2(0.5), 0.0, 0.0);
}

#endif
