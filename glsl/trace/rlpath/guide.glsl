// glsl/trace/rlpath/guide.glsl: the Q-table of the rlpath integrator (layout
// in shared/rlpath.h): cell and bin lookup, sampling a direction from a
// cell's learned distribution and its pdf, the mixture with the BSDF, and the
// temporal-difference update.
//
// The learned distribution of a cell at a point with normal n: bin b has
// probability P_b = w_b / W with
//   w_b = (Q_b + e) * (max(cos(centre_b, n), 0) + CV_RL_COS_FLOOR),
//   e = floor * S / bins (S = sum of Q_b; a tiny absolute floor makes an
//   unvisited cell follow the floored cosine), W = sum of w_b,
// (Q times the cosine, the part of the reflected radiance the table knows,
// as Dahm and Keller's product with the BSDF for a diffuse surface), and is
// uniform in solid angle within the bin: pdf(w) = P_b * bins / (4 pi).
// Include after the local_size layout line.
#ifndef CV_RLPATH_GUIDE_GLSL
#define CV_RLPATH_GUIDE_GLSL

#include "shared/rlpath.h"

layout(std140, binding = CV_UBO_RLPATH) uniform CvRlBlock { CvRlParams u_rl; };
#ifdef CV_RL_TABLE_WRITE
layout(r32ui, binding = CV_IMAGE_RL_Q) uniform coherent uimageBuffer rl_q;
#else
layout(r32ui, binding = CV_IMAGE_RL_Q) uniform readonly uimageBuffer rl_q;
#endif

const float CV_RL_PI = 3.14159265358979323846;

uint cv_rl_bins() { return u_rl.dirs.z; }
float cv_rl_mix_weight() { return u_rl.grid_min.w; }

uint cv_rl_cell(vec3 p)
{
    ivec3 c = ivec3(floor((p - u_rl.grid_min.xyz) * u_rl.grid_scale.xyz));
    c = clamp(c, ivec3(0), ivec3(u_rl.dims.xyz) - 1);
    return (uint(c.z) * u_rl.dims.y + uint(c.y)) * u_rl.dims.x + uint(c.x);
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

float cv_rl_q(uint entry) { return uintBitsToFloat(imageLoad(rl_q, int(2u * entry)).x); }

// The floor e of a cell whose bins sum to s.
float cv_rl_floor(float s)
{
    return max(u_rl.grid_scale.w * s / float(cv_rl_bins()), 1e-20);
}

float cv_rl_cell_sum(uint cell)
{
    uint base = cell * cv_rl_bins();
    float s = 0.0;
    for (uint b = 0u; b < cv_rl_bins(); b++)
        s += cv_rl_q(base + b);
    return s;
}

// The sampling weight of bin b of a cell (first entry base, floor e) at a
// point with normal n (facing the side that reflects): the learned radiance
// times the cosine at the bin's centre, both floored so that no bin is 0.
float cv_rl_weight(uint base, uint b, float e, vec3 n)
{
    float c = dot(cv_rl_bin_dir(b, vec2(0.5)), n);
    return (cv_rl_q(base + b) + e) * (max(c, 0.0) + CV_RL_COS_FLOOR);
}

// The sum W of the weights of a cell (bins summing to s) at normal n.
float cv_rl_total(uint cell, float s, vec3 n)
{
    uint base = cell * cv_rl_bins();
    float e = cv_rl_floor(s), t = 0.0;
    for (uint b = 0u; b < cv_rl_bins(); b++)
        t += cv_rl_weight(base, b, e, n);
    return t;
}

// Solid-angle pdf of w under the distribution of a cell (bins summing to
// s, weights to W at normal n).
float cv_rl_pdf(uint cell, float s, float W, vec3 n, vec3 w)
{
    uint nb = cv_rl_bins();
    float wb = cv_rl_weight(cell * nb, cv_rl_bin(w), cv_rl_floor(s), n);
    return (wb / W) * float(nb) / (4.0 * CV_RL_PI);
}

// Samples a direction from the cell with u in [0,1)^2: u.x picks the bin by
// the CDF of the weights and, rescaled within the bin's interval, the z
// position in the bin; u.y the phi position. Returns the bin; pdf is the
// solid-angle density of the direction.
uint cv_rl_sample(uint cell, float s, float W, vec3 n, vec2 u, out vec3 w, out float pdf)
{
    uint nb = cv_rl_bins(), base = cell * nb;
    float e = cv_rl_floor(s);
    float target = u.x * W, c = 0.0, p = 0.0;
    uint b = 0u;
    for (; b < nb; b++) {
        p = cv_rl_weight(base, b, e, n);
        if (target < c + p || b == nb - 1u)
            break;
        c += p;
    }
    float ux = clamp((target - c) / p, 0.0, 0.99999994);
    w = cv_rl_bin_dir(b, vec2(ux, u.y));
    pdf = (p / W) * float(nb) / (4.0 * CV_RL_PI);
    return b;
}

// The one-sample mixture of guiding (weight m) and the BSDF: the density the
// path throughput and the MIS weights use.
float cv_rl_mix_pdf(float m, float pdf_guide, float pdf_bsdf)
{
    return m * pdf_guide + (1.0 - m) * pdf_bsdf;
}

#ifdef CV_RL_TABLE_WRITE
// Q(entry) <- (1 - a) Q + a target with a = 1 / (1 + visits). The visit
// count is bumped first, so concurrent updates of one entry each get their
// own learning rate; the float is then replaced by compare-and-swap on its
// bits, retried while another thread changed it in between (bounded: an
// update lost under extreme contention only slows learning, never biases
// the image, whose estimator is unbiased for any table).
void cv_rl_update(uint entry, float target)
{
    if (entry == CV_RL_NONE || !(target >= 0.0) || isinf(target))
        return;
    int at = int(2u * entry);
    uint visits = imageAtomicAdd(rl_q, at + 1, 1u);
    float a = 1.0 / (1.0 + float(visits));
    uint old = imageLoad(rl_q, at).x;
    for (int i = 0; i < 64; i++) {
        float q = uintBitsToFloat(old);
        uint nv = floatBitsToUint(q + a * (target - q));
        uint seen = imageAtomicCompSwap(rl_q, at, old, nv);
        if (seen == old)
            break;
        old = seen;
    }
}
#endif

#endif
