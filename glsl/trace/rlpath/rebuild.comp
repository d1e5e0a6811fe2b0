#version 450
// glsl/trace/rlpath/rebuild.comp: builds the guide texels (weight, CDF, bin
// probabilities; layout in shared/rlpath.h, distribution in guide.glsl) of
// every key whose learning texels changed since its last build, one
// workgroup per key, after the stages that add to the learning table. The
// shade stage then samples a key with two rounds of texel loads and reads
// a pdf with one, instead of summing all bins per hit.
// Dispatched as a 2D grid of workgroups (keys may exceed the 65535 limit of
// one dimension): key = y * groups in x + x.
#include "shared/rlpath.h"
#define CV_RL_REBUILD_GROUP 32u
layout(local_size_x = CV_RL_REBUILD_GROUP) in;
#define CV_RL_TABLE_WRITE
#define CV_RL_GUIDE_WRITE
#include "guide.glsl"

shared float s_part[CV_RL_REBUILD_GROUP];
shared float s_visits[CV_RL_REBUILD_GROUP];
shared float s_irr[CV_RL_REBUILD_GROUP];
shared float s_cdf[CV_RL_MAX_BINS];
shared float s_prob[CV_RL_MAX_BINS];

// What bin b of the key at kt guides by (guide.glsl): Q, or with
// CV_RL_GUIDE_INDIRECT (rlpath.guide: indirect) I, the sum without the
// emitted part, over the visits.
float cv_rl_guided_q(int kt, uint b)
{
#ifdef CV_RL_GUIDE_INDIRECT
    return cv_rl_bin_mean(cv_rl_bin_texel(kt, int(b)), false);
#else
    return cv_rl_bin_mean(cv_rl_bin_texel(kt, int(b)), true);
#endif
}

// The integral of max(cos, 0) to the unit axis `a` over bin b, from the
// bin's solid angle and 2 x 2 points in it (a bin crossing the horizon is
// where one point would be far off).
float cv_rl_bin_cos(uint b, vec3 a)
{
    float c = 0.0;
    for (int i = 0; i < 4; i++)
        c += max(dot(cv_rl_bin_dir(b, vec2(0.25 + 0.5 * float(i & 1), 0.25 + 0.5 * float(i >> 1))), a), 0.0);
    return c * (CV_RL_PI / float(cv_rl_bins()));   // 4 pi / bins per bin, / 4 points
}

// The CDF after bin b, 1 past the last bin.
float cv_rl_cdf_or_1(uint b) { return b < cv_rl_bins() ? s_cdf[b] : 1.0; }

void main()
{
    uint key = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    // both returns are uniform in the workgroup: one key, one dirty flag
    // that no other workgroup writes during this dispatch
    if (key >= cv_rl_keys())
        return;
    uint nb = cv_rl_bins();
    int kt = cv_rl_key_texel(key);
    int dirty = cv_rl_dirty_texel(kt);
    if (imageLoad(rl_q, dirty).x == 0u)
        return;

    // each invocation owns a run of consecutive bins
    uint t = gl_LocalInvocationID.x;
    uint per = (nb + CV_RL_REBUILD_GROUP - 1u) / CV_RL_REBUILD_GROUP;
    uint b0 = min(t * per, nb), b1 = min(b0 + per, nb);
    // the key's class axis (shared/rlpath.h: CV_RL_ORIENTS)
    uint orient = key % CV_RL_ORIENTS;
    vec3 axis = vec3(0.0);
    axis[orient / 2u] = (orient & 1u) != 0u ? -1.0 : 1.0;
    float qs = 0.0, vs = 0.0, irr = 0.0;
    for (uint b = b0; b < b1; b++) {
        int tb = cv_rl_bin_texel(kt, int(b));
        uint n = imageLoad(rl_q, tb + 1).x;
        float s0 = cv_rl_texel_f(tb), s2 = cv_rl_texel_f(tb + 2);
        if (isnan(s0) || isinf(s0) || isnan(s2) || isinf(s2)) {
            // a sum that overflowed: the bin starts again rather than
            // read as 0 for ever (cv_rl_bin_mean)
            imageStore(rl_q, tb, uvec4(0u));
            imageStore(rl_q, tb + 1, uvec4(0u));
            imageStore(rl_q, tb + 2, uvec4(0u));
        } else if (n > CV_RL_MAX_VISITS) {
            // no stage that adds to the table is running: no add is lost
            // between these
            float k = float(n / 2u) / float(n);
            imageStore(rl_q, tb, uvec4(floatBitsToUint(cv_rl_texel_f(tb) * k)));
            imageStore(rl_q, tb + 2, uvec4(floatBitsToUint(cv_rl_texel_f(tb + 2) * k)));
            imageStore(rl_q, tb + 1, uvec4(n / 2u));
        }
        qs += cv_rl_guided_q(kt, b);
        vs += float(imageLoad(rl_q, tb + 1).x);
        irr += cv_rl_q(key, b) * cv_rl_bin_cos(b, axis);
    }
    s_part[t] = qs;
    s_visits[t] = vs;
    s_irr[t] = irr;
    barrier();
    // every invocation sums in the same order: the same S and V in all
    float S = 0.0, V = 0.0, IRR = 0.0;
    for (uint i = 0u; i < CV_RL_REBUILD_GROUP; i++) {
        S += s_part[i];
        V += s_visits[i];
        IRR += s_irr[i];
    }
    barrier();

    // sums of finite means can still overflow (and W, a little above S,
    // with them): such a key guides uniformly, never by a CDF of inf / inf
    bool finite = S < 1e30 && IRR < 1e30;
    if (!finite)
        S = IRR = 0.0;
    float e = max(u_rl.grid_scale.w * S / float(nb), 1e-20);
    // precise: both passes over a run must round its weights and sums alike
    // (no contraction into fused multiply-adds in one and not the other)
    precise float ws = 0.0;
    for (uint b = b0; b < b1; b++) {
        precise float w = (finite ? cv_rl_guided_q(kt, b) : 0.0) + e;
        ws += w;
    }
    s_part[t] = ws;
    barrier();
    // offsets by a serial sum, so that a run's last prefix rounds to the
    // next run's offset: the CDF never decreases
    precise float off = 0.0, W = 0.0;
    for (uint i = 0u; i < CV_RL_REBUILD_GROUP; i++) {
        if (i == t)
            off = W;
        W += s_part[i];
    }
    precise float acc = 0.0;
    for (uint b = b0; b < b1; b++) {
        precise float w = (finite ? cv_rl_guided_q(kt, b) : 0.0) + e;
        acc += w;
        precise float sum = off + acc;
        s_cdf[b] = b == nb - 1u ? 1.0 : min(sum / W, 1.0);
    }
    barrier();
    // a bin's probability is exactly what sampling gives it: the difference
    // of its CDF value and the one before
    for (uint b = b0; b < b1; b++)
        s_prob[b] = s_cdf[b] - (b > 0u ? s_cdf[b - 1u] : 0.0);
    barrier();

    // the key's guide texels, each written whole by one invocation
    int gt = cv_rl_guide_texel(key);
    uint groups = CV_RL_GROUPS(nb), coarse = CV_RL_COARSE(nb);
    for (uint i = t; i < coarse; i += CV_RL_REBUILD_GROUP) {
        vec4 v;
        for (uint k = 0u; k < 4u; k++) {
            uint g = 4u * i + k;
            v[k] = g < groups ? cv_rl_cdf_or_1(min(16u * g + 15u, nb - 1u)) : 1.0;
        }
        imageStore(rl_guide, cv_rl_coarse_texel(gt, int(i)), v);
    }
    for (uint i = t; i < 4u * groups; i += CV_RL_REBUILD_GROUP) {
        vec4 v = vec4(cv_rl_cdf_or_1(4u * i), cv_rl_cdf_or_1(4u * i + 1u),
                      cv_rl_cdf_or_1(4u * i + 2u), cv_rl_cdf_or_1(4u * i + 3u));
        imageStore(rl_guide, cv_rl_fine_texel(gt, int(i)), v);
    }
    for (uint i = t; i < (nb + 3u) / 4u; i += CV_RL_REBUILD_GROUP) {
        vec4 v;
        for (uint k = 0u; k < 4u; k++)
            v[k] = 4u * i + k < nb ? s_prob[4u * i + k] : 0.0;
        imageStore(rl_guide, cv_rl_prob_texel(gt, int(i)), v);
    }
    if (t == 0u) {
        float trust = min(1.0, V / (CV_RL_TRUST_VISITS * float(nb)));
        imageStore(rl_guide, gt, vec4(cv_rl_mix_weight() * trust, IRR, 0.0, 0.0));
        imageStore(rl_q, dirty, uvec4(0u));
    }
}
