#version 450
// glsl/trace/rlpath/rebuild.comp: builds the sampling CDF and the guiding
// weight of every key whose Q changed since its last build (layout in
// shared/rlpath.h, distribution in guide.glsl), one workgroup per key, after
// the stages that add to the table. The shade stage then samples a key by a binary search and
// reads its pdf from two CDF values, instead of summing all bins per hit.
// Dispatched as a 2D grid of workgroups (keys may exceed the 65535 limit of
// one dimension): key = y * groups in x + x.
#include "shared/rlpath.h"
#define CV_RL_REBUILD_GROUP 32u
layout(local_size_x = CV_RL_REBUILD_GROUP) in;
#define CV_RL_TABLE_WRITE
#include "guide.glsl"

shared float s_part[CV_RL_REBUILD_GROUP];
shared float s_visits[CV_RL_REBUILD_GROUP];

// The part of bin b's Q that guiding samples (guide.glsl: I_b): Q less its
// emitted part, both means over the same visits.
float cv_rl_guided_q(int kt, int b)
{
    int tb = kt + 2 * b;
    float n = float(max(imageLoad(rl_q, tb + 1).x, 1u));
    return max(cv_rl_texel_f(tb) - cv_rl_texel_f(cv_rl_emitted_texel(kt, b)), 0.0) / n;
}

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
    float qs = 0.0, vs = 0.0;
    for (uint b = b0; b < b1; b++) {
        int tb = kt + int(2u * b);
        uint n = imageLoad(rl_q, tb + 1).x;
        if (n > CV_RL_MAX_VISITS) {
            // no stage that adds to the table is running: no add is lost
            // between these
            float k = float(n / 2u) / float(n);
            int te = cv_rl_emitted_texel(kt, int(b));
            imageStore(rl_q, tb, uvec4(floatBitsToUint(cv_rl_texel_f(tb) * k)));
            imageStore(rl_q, te, uvec4(floatBitsToUint(cv_rl_texel_f(te) * k)));
            imageStore(rl_q, tb + 1, uvec4(n / 2u));
        }
        qs += cv_rl_guided_q(kt, int(b));
        vs += float(imageLoad(rl_q, tb + 1).x);
    }
    s_part[t] = qs;
    s_visits[t] = vs;
    barrier();
    // every invocation sums in the same order: the same S and V in all
    float S = 0.0, V = 0.0;
    for (uint i = 0u; i < CV_RL_REBUILD_GROUP; i++) {
        S += s_part[i];
        V += s_visits[i];
    }
    barrier();

    float e = max(u_rl.grid_scale.w * S / float(nb), 1e-20);
    // precise: both passes over a run must round its weights and sums alike
    // (no contraction into fused multiply-adds in one and not the other)
    precise float ws = 0.0;
    for (uint b = b0; b < b1; b++) {
        precise float w = cv_rl_guided_q(kt, int(b)) + e;
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
        precise float w = cv_rl_guided_q(kt, int(b)) + e;
        acc += w;
        precise float sum = off + acc;
        float cdf = b == nb - 1u ? 1.0 : min(sum / W, 1.0);
        imageStore(rl_q, cv_rl_cdf_texel(kt, int(b)), uvec4(floatBitsToUint(cdf)));
    }
    if (t == 0u) {
        float trust = min(1.0, V / (CV_RL_TRUST_VISITS * float(nb)));
        imageStore(rl_q, cv_rl_mix_texel(kt), uvec4(floatBitsToUint(cv_rl_mix_weight() * trust)));
        imageStore(rl_q, dirty, uvec4(0u));
    }
}
