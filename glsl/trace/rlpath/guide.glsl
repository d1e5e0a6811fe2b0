// glsl/trace/rlpath/guide.glsl: the tables of the rlpath integrator (layout
// in shared/rlpath.h): key and bin lookup, sampling a direction from a key's
// learned distribution and its pdf, the mixture with the BSDF and the
// temporal-difference update.
//
// Per bin b of a key (cell, normal class), over its visits: Q_b, the mean
// target (the learned incident radiance), and I_b, its part that is not a
// light's emission seen directly in those directions (which next-event
// estimation samples already). The learned distribution: bin b has
// probability P_b = w_b / W with
//   w_b = G_b + e, e = floor * S / bins (S = sum of G_b; a tiny absolute
//   floor makes an unvisited key uniform), W = sum of w_b,
// where G_b is Q_b, the learned incident radiance as Dahm and Keller
// sample it, or I_b with CV_RL_GUIDE_INDIRECT (rlpath.guide: indirect):
// guided directions that find a lamp add little that the shadow ray and
// MIS do not. I_b reaches a given error sooner on rooms lit only by
// bounced light but gives up the gain where the lamp is seen through its
// shade (veach-bidir), which Q_b keeps: Q_b is the default
// (bench/RESULTS.md, "path against rlpath after the merges").
// The distribution is uniform in solid angle within a bin:
// pdf(w) = P_b * bins / (4 pi).
// Bins below a key's surfaces keep about the floor: paths sent there end
// without teaching them anything. Weighting Q by the cosine to the class
// axis (once per key) was tried: it raised the generated room's error at
// equal samples (bench/RESULTS.md, "Figures behind the code"), so the
// cosine is left to the BSDF share of the mixture.
// rebuild.comp builds each changed key's guide texels (CDF, bin
// probabilities, weight) once, so a hit samples with two rounds of texel
// loads and evaluates the pdf with one, instead of passes over every bin.
// Include after the local_size layout line. CV_RL_TABLE_WRITE: the
// learning table read-write (CV_RL_TABLE_UPDATE: and cv_rl_update);
// CV_RL_GUIDE_WRITE: the guide table write-only (rebuild.comp).
#ifndef CV_RLPATH_GUIDE_GLSL
#define CV_RLPATH_GUIDE_GLSL

#include "shared/rlpath.h"
#include "../../lib/atomic_add.glsl"

layout(std140, binding = CV_UBO_RLPATH) uniform CvRlBlock { CvRlParams u_rl; };
#ifdef CV_RL_TABLE_WRITE
layout(r32ui, binding = CV_IMAGE_RL_Q) uniform coherent uimageBuffer rl_q;
#if defined(CV_RL_TABLE_UPDATE) && defined(GL_NV_shader_atomic_float)
layout(r32f, binding = CV_IMAGE_RL_QF) uniform coherent imageBuffer rl_qf;
#endif
#else
layout(r32ui, binding = CV_IMAGE_RL_Q) uniform readonly uimageBuffer rl_q;
#endif
#ifdef CV_RL_GUIDE_WRITE
layout(rgba32f, binding = CV_IMAGE_RL_GUIDE) uniform writeonly imageBuffer rl_guide;
#else
layout(binding = CV_TEXUNIT_RL_GUIDE) uniform samplerBuffer rl_guide;
#endif

const float CV_RL_PI = 3.14159265358979323846;

uint cv_rl_bins() { return u_rl.dirs.z; }
uint cv_rl_keys() { return u_rl.dirs.w; }
float cv_rl_mix_weight() { return u_rl.grid_min.w; }
// Whether this pass learns (adds targets, keeps path state): rlpath.train.
bool cv_rl_learning() { return u_rl.learn.x != 0u; }

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

// The first texel of a key in the learning table and in the guide table.
int cv_rl_key_texel(uint key) { return int(key * CV_RL_LEARN_TEXELS(cv_rl_bins())); }
int cv_rl_guide_texel(uint key) { return int(key * CV_RL_GUIDE_TEXELS(cv_rl_bins())); }

// The learning texels of bin b of the key at kt (I sum; visits and the
// emitted sum follow), and its dirty flag.
int cv_rl_bin_texel(int kt, int b) { return kt + 3 * b; }
int cv_rl_dirty_texel(int kt) { return kt + int(3u * cv_rl_bins()); }

// The guide texels of the key at gt: weight, coarse CDF texel i, fine CDF
// texel i (of all groups), probabilities texel i.
int cv_rl_coarse_texel(int gt, int i) { return gt + 1 + i; }
int cv_rl_fine_texel(int gt, int i) { return gt + 1 + int(CV_RL_COARSE(cv_rl_bins())) + i; }
int cv_rl_prob_texel(int gt, int i)
{
    return cv_rl_fine_texel(gt, int(4u * CV_RL_GROUPS(cv_rl_bins()))) + i;
}

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

// The mean over the visits of a bin's sum at learning texel t (its own,
// or with the emitted part at t + 2 added).
// A sum that overflowed (or any non-finite one) reads as 0: one bin must
// not turn the key's CDF into inf / inf (rebuild.comp resets such bins).
float cv_rl_bin_mean(int t, bool with_emitted)
{
    float s = cv_rl_texel_f(t) + (with_emitted ? cv_rl_texel_f(t + 2) : 0.0);
    float q = s / float(max(imageLoad(rl_q, t + 1).x, 1u));
    return isnan(q) || isinf(q) ? 0.0 : q;
}

// Q of bin `bin` of a key: both sums over the visits.
float cv_rl_q(uint key, uint bin)
{
    return cv_rl_bin_mean(cv_rl_bin_texel(cv_rl_key_texel(key), int(bin)), true);
}

#ifndef CV_RL_GUIDE_WRITE
// What a hit reads of its key first, in one round of loads: the guiding
// weight (0 until the key has learned something) and the first two coarse
// CDF texels (all of them up to 128 bins).
struct CvRlKey {
    int gt;       // the key's first guide texel
    float m;
    float irr;    // learned irradiance about the key's class axis
    vec4 c0, c1;  // coarse texels 0 and min(1, last)
};

CvRlKey cv_rl_key_load(uint key)
{
    CvRlKey k;
    k.gt = cv_rl_guide_texel(key);
    vec4 h = texelFetch(rl_guide, k.gt);
    k.m = h.x;
    k.irr = h.y;
    k.c0 = texelFetch(rl_guide, cv_rl_coarse_texel(k.gt, 0));
    k.c1 = texelFetch(rl_guide, cv_rl_coarse_texel(k.gt, min(1, int(CV_RL_COARSE(cv_rl_bins())) - 1)));
    return k;
}

float cv_rl_key_mix(uint key) { return texelFetch(rl_guide, cv_rl_guide_texel(key)).x; }

// The probability of bin b of the key at gt, as sampling draws it.
float cv_rl_prob(int gt, uint b) { return texelFetch(rl_guide, cv_rl_prob_texel(gt, int(b / 4u)))[b % 4u]; }

// Solid-angle pdf of the directions of bin `bin` under the distribution of
// a key (whose mixture weight is above 0, so that it has been built).
float cv_rl_pdf_bin(uint key, uint bin)
{
    return cv_rl_prob(cv_rl_guide_texel(key), bin) * float(cv_rl_bins()) / (4.0 * CV_RL_PI);
}

float cv_rl_pdf(uint key, vec3 w) { return cv_rl_pdf_bin(key, cv_rl_bin(w)); }

// The first of the four values of v above u (3 if none is).
int cv_rl_first_above(vec4 v, float u)
{
    return u < v.x ? 0 : (u < v.y ? 1 : (u < v.z ? 2 : 3));
}

// Sampling a direction from a key read by cv_rl_key_load, with u in
// [0,1)^2: u.x picks the bin, the first whose CDF is above it, and,
// rescaled within the bin's interval, the z position in the bin; u.y the
// phi position. In two steps, so that a caller can issue the second's loads
// beside others: cv_rl_pick_group finds the group of 16 bins in the coarse
// texels (a binary search over them first where there are more than two,
// none up to 128 bins) and names the group's four fine texels;
// cv_rl_pick_bin finds the bin in them. It returns the bin; pdf is the
// solid-angle density of the direction: the bin's probability, the
// difference of its CDF value and the one before (read from the loaded
// texels, or else from the stored probability, the same float), which is
// the chance that u.x falls between them.
struct CvRlPick {
    int f;            // the group's first fine texel
    int g;            // the group
    float start;      // the CDF before the group, if have_start
    bool have_start;
};

CvRlPick cv_rl_pick_group(CvRlKey k, float u)
{
    int lo = 0, hi = int(CV_RL_COARSE(cv_rl_bins())) - 1;
    vec4 ca = k.c0, cb = k.c1;
    if (hi > 1) {
        while (hi - lo > 1) {
            int mid = (lo + hi) >> 1;
            if (u < texelFetch(rl_guide, cv_rl_coarse_texel(k.gt, mid)).w)
                hi = mid;
            else
                lo = mid + 1;
        }
        ca = texelFetch(rl_guide, cv_rl_coarse_texel(k.gt, lo));
        cb = texelFetch(rl_guide, cv_rl_coarse_texel(k.gt, hi));
    }
    bool in_a = u < ca.w;
    vec4 cv = in_a ? ca : cb;
    int k4 = cv_rl_first_above(cv, u);
    CvRlPick pk;
    pk.g = 4 * (in_a ? lo : hi) + k4;
    pk.f = cv_rl_fine_texel(k.gt, 4 * pk.g);
    // the CDF before the group, where the loaded coarse texels hold it
    pk.have_start = pk.g == 0 || k4 > 0 || (!in_a && hi == lo + 1);
    pk.start = pk.g == 0 ? 0.0 : (k4 > 0 ? cv[k4 - 1] : ca.w);
    return pk;
}

uint cv_rl_pick_bin(CvRlKey k, CvRlPick pk, vec4 f0, vec4 f1, vec4 f2, vec4 f3, vec2 u,
                    out vec3 w, out float pdf)
{
    int i = u.x < f0.w ? 0 : (u.x < f1.w ? 1 : (u.x < f2.w ? 2 : 3));
    vec4 fv = i == 0 ? f0 : (i == 1 ? f1 : (i == 2 ? f2 : f3));
    vec4 fp = i == 1 ? f0 : (i == 2 ? f1 : f2);   // the texel before (i > 0)
    int j = cv_rl_first_above(fv, u.x);
    uint b = uint(16 * pk.g + 4 * i + j);
    float c1 = fv[j];
    float c0 = j > 0 ? fv[j - 1] : (i > 0 ? fp.w : pk.start);
    float p = (j > 0 || i > 0 || pk.have_start) ? c1 - c0 : cv_rl_prob(k.gt, b);
    c0 = c1 - p;
    float ux = p > 0.0 ? clamp((u.x - c0) / p, 0.0, 0.99999994) : 0.5;
    w = cv_rl_bin_dir(b, vec2(ux, u.y));
    pdf = p * float(cv_rl_bins()) / (4.0 * CV_RL_PI);
    return b;
}

uint cv_rl_sample_key(CvRlKey k, vec2 u, out vec3 w, out float pdf)
{
    CvRlPick pk = cv_rl_pick_group(k, u.x);
    vec4 f0 = texelFetch(rl_guide, pk.f), f1 = texelFetch(rl_guide, pk.f + 1);
    vec4 f2 = texelFetch(rl_guide, pk.f + 2), f3 = texelFetch(rl_guide, pk.f + 3);
    return cv_rl_pick_bin(k, pk, f0, f1, f2, f3, u, w, pdf);
}

uint cv_rl_sample(uint key, vec2 u, out vec3 w, out float pdf)
{
    return cv_rl_sample_key(cv_rl_key_load(key), u, w, pdf);
}
#endif

// The one-sample mixture of guiding (weight m) and the BSDF: the density the
// path throughput and the MIS weights use.
float cv_rl_mix_pdf(float m, float pdf_guide, float pdf_bsdf)
{
    return m * pdf_guide + (1.0 - m) * pdf_bsdf;
}

#ifdef CV_RL_TABLE_UPDATE
// cv_rl_add(t, v): adds the float v to texel t of the learning table; the
// compare-and-swap gives up after 64 tries: an add lost under extreme
// contention only skews learning, never biases the image, whose estimator
// is unbiased for any table.
#ifdef GL_NV_shader_atomic_float
CV_ATOMIC_ADD_NATIVE(cv_rl_add, rl_qf)
#else
CV_ATOMIC_ADD_CAS(cv_rl_add, rl_q, 64u)
#endif

// Adds a target (emitted: its part that is a light seen directly) to the
// entry's sums and a visit (Q becomes the mean of its targets, as
// Q <- (1 - a) Q + a target with a = 1 / (1 + visits)), and marks the key
// for rebuild.comp (a plain store: every writer stores the same 1).
void cv_rl_update(uint entry, float target, float emitted)
{
    if (entry == CV_RL_NONE || !(target >= 0.0) || isinf(target))
        return;
    uint nb = cv_rl_bins();
    int kt = cv_rl_key_texel(entry / nb);
    int t = cv_rl_bin_texel(kt, int(entry % nb));
    // not clamp(): its result for a NaN is undefined
    float e = emitted > 0.0 ? min(emitted, target) : 0.0;
    cv_rl_add(t, target - e);
    imageAtomicAdd(rl_q, t + 1, 1u);
    if (e > 0.0)
        cv_rl_add(t + 2, e);
    imageStore(rl_q, cv_rl_dirty_texel(kt), uvec4(1u));
}
#endif

#endif
