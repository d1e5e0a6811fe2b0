#version 450
#extension GL_NV_shader_atomic_float : enable
// glsl/trace/rlpath/shade.comp: the surface stage of the rlpath integrator:
// a path vertex (trace/path_vertex.glsl: emission, AOVs, next-event
// estimation, bounce with Russian roulette) with the bounce direction drawn
// from the one-sample mixture of the learned distribution of the hit's key
// (weight m) and the BSDF (1 - m), whose exact density divides the throughput and enters the MIS
// weights against light sampling, so the estimator is unbiased for any
// table and any m in [0, 1]; delta lobes stay the BSDF's (see
// cv_strategy_sample). It also computes the temporal-difference target for the bounce that
// led here: Le(y, -w) (its emitted part, which next-event estimation at the
// vertex before covers, apart) plus the radiance y reflects towards it. For
// a diffuse-like lobe (where the key guides) that is the expected value
// rho / pi * the key's learned irradiance (rebuild.comp), Dahm and Keller's
// integral of Q against the BSDF with the cosine about the key's class
// axis; for other lobes the one-sample estimate from the direction w' this
// vertex samples, Q(y, bin(w')) f(y, -w, w') |cos| / p(w'). Integrating Q
// against the BSDF over every bin per hit took a BSDF evaluation per bin
// and made rlpath 5 to 6 times as slow per sample as path on an H100; the
// per-key irradiance costs nothing per hit, and early in a render it
// learns with less noise than the one-sample target (H100, generated room,
// relMSE x spp at 8 spp 17.2 against 18.5, equal from 256 spp on).
// The target is added to the table here, with atomics: sampling and the
// mixture density read only the CDFs and weights, which rebuild.comp alone
// writes, so one dispatch still sees one distribution per key and the
// sampling and MIS densities of a vertex agree (a separate update stage
// that read the path state back was a dispatch and a pass over the hits
// per depth). All of the learning (path state, target, atomics) runs only
// while the table learns (cv_rl_learning, rlpath.train): the passes after
// it sample the frozen guide and pay for its loads alone.
// Built once per bin of the hit queue, as path's shade.comp:
// CV_SHADE_BIN=0 shades diffuse hits with the BSDF code cut down to
// diffuse (CV_BSDF_DIFFUSE_ONLY), CV_SHADE_BIN=1 the others but the coated
// walk's (CV_NO_LAYERED), CV_SHADE_BIN=2 those; one build for all
// materials sized the kernel for the largest and cost every hit that.
#define CV_BQ_WI1  // asks its BSDF at a second direction (bsdf/bsdf.glsl)
#include "shared/trace.h"
layout(local_size_x = CV_TRACE_GROUP) in;
#if defined(CV_SHADE_BIN) && CV_SHADE_BIN == 0
#define CV_BSDF_DIFFUSE_ONLY
#elif defined(CV_SHADE_BIN) && CV_SHADE_BIN == 1 && !defined(CV_NO_LAYERED)
#define CV_NO_LAYERED  // (a scene without the walk defines it already)
#endif
#include "../unroll_hint.glsl"
#include "../common.glsl"
#include "../sampler.glsl"
#include "../geometry.glsl"
#include "../materials.glsl"
#include "../lights.glsl"
#include "../surface_inputs.glsl"
#define CV_RL_TABLE_WRITE
#define CV_RL_TABLE_UPDATE
#include "guide.glsl"

layout(rg32ui, binding = CV_IMAGE_RL_PATH) uniform uimageBuffer rl_path;

#include "guides.glsl"

// The guided strategy (../path_vertex.glsl). learning: whether the bounce
// that led here learns from this hit (set by cv_shade); target and emitted
// then collect its temporal-difference target and the emitted part of it
// (light found here that next-event estimation at the vertex before
// sampled too). key: the hit's table key, kk its weight and first CDF
// texels, m the guiding weight; expected: the target takes the key's
// expected reflected radiance (else the one-sample estimate from the
// bounce); wbin: the table bin of the bounce; pd: the probability with
// which the BSDF picks a delta lobe (those stay the BSDF's to sample);
// guided, pq: the bounce is the guide's draw, of guided density pq
// (cv_strategy_ask).
struct CvStrategy {
    bool learning;
    float target;
    float emitted;
    uint key;
    CvRlKey kk;
    float m;
    bool expected;
    uint wbin;
    float pd;
    bool guided;
    float pq;
};

void cv_strategy_emitted(inout CvStrategy g, vec3 Le, uint flags)
{
    g.target = cv_mean3(Le);
    // next-event estimation at the vertex before sampled this light
    // unless that bounce was specular (no light sampling there)
    if (cv_n_lights() > 0u && (flags & CV_RAYF_SPECULAR) == 0u)
        g.emitted = g.target;
}

void cv_strategy_begin(inout CvStrategy g, CvSurface sf, vec3 wo, CvBsdf b, bool delta)
{
    // the key takes the normal on the side the path came from
    vec3 gn = dot(wo, sf.ns) < 0.0 ? -sf.ns : sf.ns;
    g.key = cv_rl_key(sf.p, gn);
    // the key's weight and first CDF texels, in one round of loads; weight
    // 0 (BSDF sampling alone) until the key has learned, or where it does
    // not guide
    g.kk = CvRlKey(0, 0.0, 0.0, vec4(0.0), vec4(0.0));
    bool guides = !delta && cv_rl_guides(b);
    if (guides)
        g.kk = cv_rl_key_load(g.key);
    g.m = g.kk.m;
    // Delta lobes are the BSDF's alone: the guide stands in for the rest,
    // which the BSDF picks with probability 1 - pd (cv_strategy_sample).
    g.pd = g.m > 0.0 ? cv_bsdf_delta_prob(b, wo) : 0.0;
    // The reflected part of the target where the key guides (a diffuse-like
    // lobe): the expected value of the one-sample estimate below, the
    // integral of Q f cos that Dahm and Keller's update takes, with f
    // Lambertian of the surface's albedo and the cosine about the key's
    // class axis (rebuild.comp sums Q cos over the bins once per change of
    // the key). Learning only: the image never sees it.
    g.expected = g.learning && guides;
    if (g.expected)
        g.target += cv_mean3(cv_bsdf_albedo(b)) * g.kk.irr * (1.0 / CV_RL_PI);
}

// The mixture density of wi (light samples weigh against it).
float cv_strategy_pdf(CvStrategy g, vec3 wi, float bsdf_pdf)
{
    float pl = g.m > 0.0 ? cv_rl_prob(g.kk.gt, cv_rl_bin(wi)) : 0.0;
    return cv_rl_mix_pdf(g.m, (1.0 - g.pd) * pl * float(cv_rl_bins()) / (4.0 * CV_RL_PI), bsdf_pdf);
}

// One-sample mixture (guides.glsl: cv_rl_mixture_ask). The guide can only
// stand in for the BSDF's non-delta part: a delta lobe is taken with the
// BSDF's own probability whatever m, and a direction of the rest has
// density m (1 - pd) pq + (1 - m) p_bsdf: every lobe is sampled for any m
// in [0, 1]. The guided direction is drawn here, before the vertex's one
// BSDF query (cv_bsdf_query), which returns f and pdf there (wi1).
void cv_strategy_ask(inout CvStrategy g, CvBsdf b, vec3 wo, vec2 u_bc, vec2 u_bsdf, inout CvBsdfQuery q)
{
    g.pq = 0.0;
    g.guided = cv_rl_mixture_ask(g.m, g.pd, u_bc, u_bsdf, q);
    if (g.guided)
        // the bin drawn, not the bin of the direction looked up again:
        // rounding may put a direction on a bin's edge across it, a set of
        // measure zero where either density serves (and a round of loads
        // less)
        g.wbin = cv_rl_sample_key(g.kk, q.u, q.wi1, g.pq);
}

bool cv_strategy_sample(inout CvStrategy g, CvBsdf b, CvSurface sf, vec3 wo, CvBsdfQuery q,
                        out CvBsdfSample bs, out float pdf, out bool specular)
{
    float m = g.m;
    pdf = 0.0;
    float pq = 0.0;   // the guided density of bs.wi
    specular = false;
    bool guided = g.guided;
    bs = q.s;
    if (guided && g.pd > 0.0 && q.sampled && (bs.flags & CV_BSDF_SPECULAR) != 0u)
        guided = false;   // the delta lobe the BSDF picked: bs stands
    else if (!guided && !q.sampled)
        return false;
    if (guided) {
        bs.wi = q.wi1;
        bs.f = q.f1;
        bs.pdf = q.pdf1;
        pq = g.pq;
    } else {
        if (bs.pdf <= 0.0)
            return false;
        specular = (bs.flags & CV_BSDF_SPECULAR) != 0u;
        g.wbin = cv_rl_bin(bs.wi);
    }
    // one round of loads: the guided density of a direction the BSDF drew,
    // and Q for a one-sample target
    if (!guided && m > 0.0 && !specular)
        pq = cv_rl_prob(g.kk.gt, g.wbin) * float(cv_rl_bins()) / (4.0 * CV_RL_PI);
    float q_bin = g.learning && !g.expected ? cv_rl_q(g.key, g.wbin) : 0.0;
    // a delta lobe is chosen with its BSDF probability bs.pdf
    pdf = specular ? bs.pdf : cv_rl_mix_pdf(m, (1.0 - g.pd) * pq, bs.pdf);
    if (!(pdf > 0.0))
        return false;
    // one-sample estimate of the reflected radiance (pdf: the density the
    // direction was drawn with; for a delta lobe its probability)
    if (g.learning && !g.expected)
        g.target += q_bin * cv_mean3(bs.f) * abs(dot(bs.wi, sf.ns)) / pdf;
    return true;
}

#include "../path_vertex.glsl"

// Shades hit i (cv_path_vertex with the guided strategy), then the bounce
// that led here learns its target and the path state takes the bounce
// leaving here (its table entry; CV_RL_NONE if the path ends).
void cv_shade(uint i, out bool push_shadow, out CvShadowItem s, out bool push_ray,
              out CvRayItem nr)
{
    CvHitItem h = hits[i];
    CvRayItem r = cv_ray_in(h.ray);
    uint path = uint(r.o.w);
    uint depth = cv_ray_depth(r);
    // frozen (u_rl.learn.x 0, rlpath.train): no path state, no target
    bool learning = cv_rl_learning();
    uvec2 st = learning ? imageLoad(rl_path, int(path)).xy : uvec2(CV_RL_NONE);
    uint learn = (depth > 0u && st.x != CV_RL_NONE && st.y + 1u == depth) ? st.x : CV_RL_NONE;
    CvStrategy g = CvStrategy(learn != CV_RL_NONE, 0.0, 0.0, 0u,
                              CvRlKey(0, 0.0, 0.0, vec4(0.0), vec4(0.0)), 0.0, false, 0u, 0.0, false, 0.0);
    cv_path_vertex(h, r, g, push_shadow, s, push_ray, nr);
    if (learning) {
        uint entry = push_ray ? cv_rl_entry(g.key, g.wbin) : CV_RL_NONE;
        cv_rl_update(learn, g.target, g.emitted);
        imageStore(rl_path, int(path), uvec4(entry, depth, 0u, 0u));
    }
}

#include "../shade_queue.glsl"
