// glsl/trace/rlpath/guide.glsl: the Q-table of the rlpath integrator (layout
// in shared/rlpath.h): key and bin lookup, sampling a direction from a key's
// learned distribution and its pdf, the mixture with the BSDF, the
// temporal-difference update and the distribution's construction.
//
// Q_b below is the bin's target sum over its visits (shared/rlpath.h), E_b
// its emitted part over the visits: radiance of a light seen directly in
// those directions, which next-event estimation samples already.
// The learned distribution of key k (cell, normal class): bin b has
// probability P_b = w_b / W with
//   w_b = I_b + e, I_b = max(Q_b - E_b, 0), e = floor * S / bins (S = sum
//   of I_b; a tiny absolute floor makes an unvisited key uniform),
//   W = sum of w_b,
// the learned incident radiance, as Dahm and Keller sample it, less what
// light sampling covers (guided directions that find a lamp add little
// that the shadow ray and MIS do not, and are missing where the indirect
// light is), and is uniform in solid angle within the bin:
// pdf(w) = P_b * bins / (4 pi).
// Bins below a key's surfaces keep about the floor: paths sent there end
// without teaching them anything. Weighting Q by the cosine to the class
// axis (once per key) was tried: on the generated room it raised relMSE at
// 512 spp from 0.066 to 0.079 (H100, mix 0.3), so the cosine is left to the
// BSDF share of the mixture.
// rebuild.comp stores its CDF once per change of the key, so a hit samples
// by a binary search (log2(bins) reads) and evaluates the pdf with two reads
// instead of three passes over every bin per hit.
// Include after the local_size layout line.
#ifndef CV_RLPATH_GUIDE_GLSL
#define CV_RLPATH_GUIDE_GLSL

#include "shared/rlpath.h"

layout(std140, binding = CV_UBO_RLPATH) uniform CvRlBlock { CvRlParams u_rl; };
#ifdef CV_RL_TABLE_WRITE
layout(r32ui, binding = CV_IMAGE_RL_Q) uniform coherent uimageBuffer rl_q;
#if defined(CV_RL_TABLE_UPDATE) && defined(GL_NV_shader_atomic_float)
layout(r32f, binding = CV_IMAGE_RL_QF) uniform coherent imageBuffer rl_qf;
#endif
#else
layout(r32ui, binding = CV_IMAGE_RL_Q) uniform readonly uimageBuffer rl_q;
#endif

const float CV_RL_PI = 3.14159265358979323846;

uint cv_rl_bins() { return u_rl.dirs.z; }
uint cv_rl_keys() { return u_rl.dirs.w; }
float cv_rl_mix_weight() { return u_rl.grid_min.w; }

uint cv_rl_cell(vec3 p)
{
    ivec3 c = ivec3(floor((p - u_rl.grid_min.xyz) * u_rl.grid_scale.xyz));
    c = clamp(c, ivec3(0), ivec3(u_rl.dims.xyz) - 1);
    return (uint(c.z) * u_rl.dims.y + uint(c.y)) * u_rl.dims.x + uint(c.x);
}

// The normal class of n: 2 * axis of its largest component, + 1 if negative.
uint cv_rl_orient(vec3 n)
{
    vec3 a = abs(n);
    uint ax = (a.x >= a.y && a.x >= a.z) ? 0u : (a.y >= a.z ? 1u : 2u);
    return 2u * ax + (n[ax] < 0.0 ? 1u : 0u);
}

// The key of a point p whose normal (on the side the path came from) is n.
uint cv_rl_key(vec3 p, vec3 n) { return cv_rl_cell(p) * CV_RL_ORIENTS + cv_rl_orient(n); }

uint cv_rl_entry(uint key, uint bin) { return key * cv_rl_bins() + bin; }

int cv_rl_key_texel(uint key) { return int(key * CV_RL_KEY_TEXELS(cv_rl_bins())); }

// The texel of an entry's Q (its visits follow it).
int cv_rl_entry_texel(uint entry)
{
    uint nb = cv_rl_bins();
    return cv_rl_key_texel(entry / nb) + int(2u * (entry % nb));
}

// The texels of a key's CDF after bin b, emitted sum of bin b, guiding
// weight and dirty flag, from the key's first texel kt (layout in
// shared/rlpath.h).
int cv_rl_cdf_texel(int kt, int b) { return kt + int(2u * cv_rl_bins()) + b; }
int cv_rl_emitted_texel(int kt, int b) { return kt + int(3u * cv_rl_bins()) + b; }
int cv_rl_mix_texel(int kt) { return kt + int(4u * cv_rl_bins()); }
int cv_rl_dirty_texel(int kt) { return cv_rl_mix_texel(kt) + 1; }

uint cv_rl_bin(vec3 w)
{
    uint nz = u_rl.dirs.x, np = u_rl.dirs.y;
    uint iz = min(uint(max(0.0, (w.z + 1.0) * 0.5 * float(nz))), nz - 1u);
    float u = (atan(w.y, w.x) + CV_RL_PI) * (0.5 / CV_RL_PI);
    uint ip = min(uint(max(0.0, u * float(np))), np - 1u);
    return iz * np + ip;
}

// The direction of bin b at (u1, u2) in [0,1)^2 within it; (0.5, 0.5) is
// its centre.
vec3 cv_rl_bin_dir(uint b, vec2 u)
{
    uint np = u_rl.dirs.y;
    float z = -1.0 + 2.0 * (float(b / np) + u.x) / float(u_rl.dirs.x);
    float phi = -CV_RL_PI + 2.0 * CV_RL_PI * (float(b % np) + u.y) / float(np);
    float r = sqrt(max(0.0, 1.0 - z * z));
    return vec3(r * cos(phi), r * sin(phi), clamp(z, -1.0, 1.0));
}

float cv_rl_texel_f(int t) { return uintBitsToFloat(imageLoad(rl_q, t).x); }

// Q of a bin from its texel pair (target sum, visits).
float cv_rl_q_at(int t)
{
    return cv_rl_texel_f(t) / float(max(imageLoad(rl_q, t + 1).x, 1u));
}

float cv_rl_q(uint entry) { return cv_rl_q_at(cv_rl_entry_texel(entry)); }

// The guiding weight of a key: 0 until it has learned something.
float cv_rl_key_mix(uint key)
{
    return cv_rl_texel_f(cv_rl_mix_texel(cv_rl_key_texel(key)));
}

// The CDF of a key after bin b (b = -1: 0).
float cv_rl_cdf(int kt, int b)
{
    return b < 0 ? 0.0 : cv_rl_texel_f(cv_rl_cdf_texel(kt, b));
}

// Solid-angle pdf of the directions of bin `bin` under the distribution of
// a key (whose mixture weight is above 0, so that its CDF has been built).
float cv_rl_pdf_bin(uint key, uint bin)
{
    int kt = cv_rl_key_texel(key), b = int(bin);
    float p = cv_rl_cdf(kt, b) - cv_rl_cdf(kt, b - 1);
    return p * float(cv_rl_bins()) / (4.0 * CV_RL_PI);
}

float cv_rl_pdf(uint key, vec3 w) { return cv_rl_pdf_bin(key, cv_rl_bin(w)); }

// Samples a direction from the key with u in [0,1)^2: u.x picks the bin,
// the first whose CDF is above it (binary search), and, rescaled within the
// bin's interval, the z position in the bin; u.y the phi position. Returns
// the bin; pdf is the solid-angle density of the direction. A bin is drawn
// with probability CDF(b) - CDF(b - 1), as the floats are: the difference
// cv_rl_pdf reads.
uint cv_rl_sample(uint key, vec2 u, out vec3 w, out float pdf)
{
    int kt = cv_rl_key_texel(key);
    int lo = 0, hi = int(cv_rl_bins()) - 1;
    while (lo < hi) {
        int mid = (lo + hi) >> 1;
        if (u.x < cv_rl_cdf(kt, mid))
            hi = mid;
        else
            lo = mid + 1;
    }
    float c0 = cv_rl_cdf(kt, lo - 1), p = cv_rl_cdf(kt, lo) - c0;
    float ux = p > 0.0 ? clamp((u.x - c0) / p, 0.0, 0.99999994) : 0.5;
    w = cv_rl_bin_dir(uint(lo), vec2(ux, u.y));
    pdf = p * float(cv_rl_bins()) / (4.0 * CV_RL_PI);
    return uint(lo);
}

// The one-sample mixture of guiding (weight m) and the BSDF: the density the
// path throughput and the MIS weights use.
float cv_rl_mix_pdf(float m, float pdf_guide, float pdf_bsdf)
{
    return m * pdf_guide + (1.0 - m) * pdf_bsdf;
}

#ifdef CV_RL_TABLE_UPDATE
// Adds the float v to texel t of the table.
void cv_rl_add(int t, float v)
{
#ifdef GL_NV_shader_atomic_float
    imageAtomicAdd(rl_qf, t, v);
#else
    // compare-and-swap on the bits, retried while another thread changed it
    // in between (bounded: an add lost under extreme contention only skews
    // learning, never biases the image, whose estimator is unbiased for any
    // table)
    uint old = imageLoad(rl_q, t).x;
    for (int i = 0; i < 64; i++) {
        uint seen = imageAtomicCompSwap(rl_q, t, old, floatBitsToUint(uintBitsToFloat(old) + v));
        if (seen == old)
            break;
        old = seen;
    }
#endif
}

// Adds a target to the entry's sum and a visit (Q becomes the mean of its
// targets, as Q <- (1 - a) Q + a target with a = 1 / (1 + visits)), its
// emitted part (in target) to the emitted sum, and marks the key for
// rebuild.comp.
void cv_rl_update(uint entry, float target, float emitted)
{
    if (entry == CV_RL_NONE || !(target >= 0.0) || isinf(target))
        return;
    int kt = cv_rl_key_texel(entry / cv_rl_bins());
    int b = int(entry % cv_rl_bins());
    int at = kt + 2 * b;
    cv_rl_add(at, target);
    imageAtomicAdd(rl_q, at + 1, 1u);
    if (emitted > 0.0)
        cv_rl_add(cv_rl_emitted_texel(kt, b), min(emitted, target));
    int dirty = cv_rl_dirty_texel(kt);
    if (imageLoad(rl_q, dirty).x == 0u)
        imageStore(rl_q, dirty, uvec4(1u));
}
#endif

#endif
