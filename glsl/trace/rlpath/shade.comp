#version 450
#extension GL_NV_shader_atomic_float : enable
// glsl/trace/rlpath/shade.comp: the surface stage of the rlpath integrator:
// trace/shade.comp (emission, AOVs, next-event estimation, bounce with
// Russian roulette) with the bounce direction drawn from the one-sample
// mixture of the learned distribution of the hit's key (weight m) and the
// BSDF (1 - m), whose exact density divides the throughput and enters the MIS
// weights against light sampling, so the estimator is unbiased for any
// table and any m in [0, 1]; delta lobes stay the BSDF's (see the bounce). It also computes the temporal-difference target for the bounce that
// led here: Le(y, -w) (its emitted part, which next-event estimation at the
// vertex before covers, apart) plus the radiance y reflects towards it. For
// a diffuse-like lobe (where the key guides) that is the expected value
// rho / pi * the key's learned irradiance (rebuild.comp), Dahm and Keller's
// integral of Q against the BSDF with the cosine about the key's class
// axis; for other lobes the one-sample estimate from the direction w' this
// vertex samples, Q(y, bin(w')) f(y, -w, w') |cos| / p(w'). Integrating Q
// against the BSDF over every bin per hit took a BSDF evaluation per bin
// and made rlpath several times as slow per sample as path; the per-key
// irradiance costs nothing per hit, and it learns with less noise than the
// one-sample target early in a render and as well later (bench/RESULTS.md,
// "path against rlpath, second round").
// The target is added to the table here, with atomics: sampling and the
// mixture density read only the CDFs and weights, which rebuild.comp alone
// writes, so one dispatch still sees one distribution per key and the
// sampling and MIS densities of a vertex agree (a separate update stage
// that read the path state back was a dispatch and a pass over the hits
// per depth).
// Keep in step with trace/shade.comp (both take their per-hit inputs from
// surface_inputs.glsl).
#include "shared/trace.h"
layout(local_size_x = CV_TRACE_GROUP) in;
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

float cv_mean3(vec3 v) { return (v.x + v.y + v.z) * (1.0 / 3.0); }

// Whether the learned distribution (incident radiance) suits
// this BSDF: it stands for the reflected integrand of a diffuse lobe, and
// glossy lobes (conductors, dielectrics below CV_RL_GLOSSY_ALPHA) put their
// value where it does not look, so guided directions there mostly carry
// nothing. Their guiding weight is 0: BSDF sampling alone, as at a delta
// lobe. The weight is a function of the hit, so the mixture pdf stays exact.
bool cv_rl_guides(CvBsdf b)
{
#ifdef CV_BSDF_BASIC
    return true;   // diffuse, or a mirror (delta: not guided anyway)
#else
    if (b.type == CV_MAT_DIFFUSE || b.type == CV_MAT_COATED_DIFFUSE ||
        b.type == CV_MAT_DIFFUSE_TRANSMISSION || b.type == CV_MAT_PLASTIC)
        return true;
    if (b.type == CV_MAT_CONDUCTOR || b.type == CV_MAT_DIELECTRIC)
        return min(b.alpha.x, b.alpha.y) >= CV_RL_GLOSSY_ALPHA;
    if (b.type == CV_MAT_COATED_CONDUCTOR)
        return min(min(b.alpha.x, b.alpha.y), min(b.alpha.z, b.alpha.w)) >= CV_RL_GLOSSY_ALPHA;
    return false;
#endif
}

// Shades hit h of ray r; what it queues comes back in the out parameters,
// so that main() can take queue slots in uniform control flow (as
// trace/shade.comp). learning: whether the bounce that led here learns from
// this hit; target and emitted then return its temporal-difference target
// and the emitted part of it (light found here that next-event estimation
// at the vertex before sampled too). entry returns the table entry of the
// bounce leaving here (CV_RL_NONE if the path ends).
void cv_shade_hit(CvHitItem h, CvRayItem r, bool learning, out float target,
                  out float emitted, out uint entry, out bool push_shadow,
                  out CvShadowItem s, out bool push_ray, out CvRayItem nr)
{
    push_shadow = false;
    push_ray = false;
    target = 0.0;
    emitted = 0.0;
    entry = CV_RL_NONE;
    uint path = uint(r.o.w);
    uint flags = cv_ray_flags(r);
    uint depth = cv_ray_depth(r);
    vec3 beta = r.beta.rgb;
    vec3 wo = -r.d.xyz;
    CvSurface sf = cv_surface(h.prim, h.b1, h.b2);
    bool front = dot(wo, sf.ng) > 0.0;

    int light = cv_tri_light[h.prim];
    if (light >= 0) {
        vec3 Le = cv_light_Le_area(uint(light), wo, sf.uv, front);
        target = cv_mean3(Le);
        // next-event estimation at the vertex before sampled this light
        // unless that bounce was specular (no light sampling there)
        if (u_pass.misc.z > 0u && (flags & CV_RAYF_SPECULAR) == 0u)
            emitted = target;
        if (cv_max3(Le) > 0.0) {
            float w = 1.0;
            if (depth > 0u && (flags & CV_RAYF_SPECULAR) == 0u)
                w = cv_power_heuristic(r.d.w, cv_light_pdf_area(uint(light), r.o.xyz, sf.p, sf.ng));
            cv_film_add(path, beta * Le * w);
        }
    }

    vec2 u_bsdf = cv_bounce_2d(path, depth, CV_PAIR_BSDF_U2);
    vec2 u_bc = cv_bounce_2d(path, depth, CV_PAIR_BSDF_UC);
    vec2 u_light = cv_bounce_2d(path, depth, CV_PAIR_LIGHT_U2);
    vec2 u_lc = cv_bounce_2d(path, depth, CV_PAIR_LIGHT_UC);

    CvBsdf b = cv_bsdf_at(sf.material, cv_shading_point(sf, front), u_bc.y);
    cv_bsdf_set_stream(b, u_bsdf, u_light);  // stochastic (coated) BSDFs' random numbers
    bool delta = cv_bsdf_is_delta(b);

    // the key takes the normal on the side the path came from
    vec3 gn = dot(wo, sf.ns) < 0.0 ? -sf.ns : sf.ns;
    uint key = cv_rl_key(sf.p, gn);
    // the key's weight and first CDF texels, in one round of loads; weight
    // 0 (BSDF sampling alone) until the key has learned, or where it does
    // not guide
    CvRlKey kk = CvRlKey(0, 0.0, 0.0, vec4(0.0), vec4(0.0));
    bool guides = !delta && cv_rl_guides(b);
    if (guides)
        kk = cv_rl_key_load(key);
    float m = kk.m;
    // Delta lobes are the BSDF's alone: the guide stands in for the rest,
    // which the BSDF picks with probability 1 - pd (see the bounce below).
    float pd = m > 0.0 ? cv_bsdf_delta_prob(b, wo) : 0.0;
    // The reflected part of the target where the key guides (a diffuse-like
    // lobe): the expected value of the one-sample estimate below, the
    // integral of Q f cos that Dahm and Keller's update takes, with f
    // Lambertian of the surface's albedo and the cosine about the key's
    // class axis (rebuild.comp sums Q cos over the bins once per change of
    // the key). Learning only: the image never sees it.
    bool expected = learning && guides;
    if (expected)
        target += cv_mean3(cv_bsdf_albedo(b)) * kk.irr * (1.0 / CV_RL_PI);

#ifdef CV_AOVS
    if (depth == 0u) {
        film[path].normal.xyz += sf.ns;
        film[path].albedo.w += h.t;
    }
    if (!delta && (flags & CV_RAYF_ALBEDO_DONE) == 0u) {
        film[path].albedo.rgb += cv_bsdf_albedo(b);
        flags |= CV_RAYF_ALBEDO_DONE;
    }
#endif
    if (depth >= cv_max_depth())
        return;

    if (!delta && u_pass.misc.z > 0u) {
        CvLightSample ls;
        if (cv_light_sample(sf.p, sf.ns, vec3(u_lc.x, u_light), ls) && cv_max3(ls.L) > 0.0) {
            vec3 f = cv_bsdf_f(b, wo, ls.wi) * abs(dot(ls.wi, sf.ns));
            if (cv_max3(f) > 0.0) {
                float pl = m > 0.0 ? cv_rl_prob(kk.gt, cv_rl_bin(ls.wi)) : 0.0;
                float pm = cv_rl_mix_pdf(m, (1.0 - pd) * pl * float(cv_rl_bins()) / (4.0 * CV_RL_PI),
                                         cv_bsdf_pdf(b, wo, ls.wi));
                float w = ls.delta ? 1.0 : cv_power_heuristic(ls.pdf, pm);
                vec3 Ld = beta * f * ls.L * (w / ls.pdf);
                if (cv_finite3(Ld)) {
                    push_shadow = true;
                    s.o = vec4(cv_spawn_origin(sf, ls.wi),
                               ls.dist * (1.0 - 1e-4));
                    s.d = vec4(ls.wi, float(path));
                    s.L = vec4(Ld, 0.0);
                }
            }
        }
    }

    // One-sample mixture: u_bsdf.x picks the strategy and, rescaled, drives
    // it. The guide can only stand in for the BSDF's non-delta part: a
    // guided draw first lets the BSDF pick its lobe (by u_bc.x alone, as a
    // BSDF draw does) and keeps a delta lobe it picks. So a delta lobe is
    // taken with the BSDF's own probability whatever m, and a direction of
    // the rest has density m (1 - pd) pq + (1 - m) p_bsdf: every lobe is
    // sampled for any m in [0, 1] (m = 1 drew no coat reflection before).
    CvBsdfSample bs;
    float pq = 0.0;   // the guided density of bs.wi
    uint wbin;        // the table bin of bs.wi
    bool specular = false;
    bool guided = m > 0.0 && u_bsdf.x < m;
    vec2 u = m > 0.0 ? vec2(min((guided ? u_bsdf.x : u_bsdf.x - m) / (guided ? m : 1.0 - m), CV_ONE_MINUS_EPS),
                            u_bsdf.y)
                     : u_bsdf;
    if (guided && pd > 0.0 && cv_bsdf_sample(b, wo, u_bc.x, u, bs) && (bs.flags & CV_BSDF_SPECULAR) != 0u)
        guided = false;   // the delta lobe the BSDF picked: bs stands
    else if (!guided && !cv_bsdf_sample(b, wo, u_bc.x, u, bs))
        return;
    if (guided) {
        // the bin drawn, not the bin of bs.wi looked up again: rounding may
        // put a direction on a bin's edge across it, a set of measure zero
        // where either density serves (and a round of loads less)
        wbin = cv_rl_sample_key(kk, u, bs.wi, pq);
        bs.f = cv_bsdf_f(b, wo, bs.wi);
        bs.pdf = cv_bsdf_pdf(b, wo, bs.wi);
    } else {
        if (bs.pdf <= 0.0)
            return;
        specular = (bs.flags & CV_BSDF_SPECULAR) != 0u;
        wbin = cv_rl_bin(bs.wi);
    }
    // one round of loads: the guided density of a direction the BSDF drew,
    // and Q for a one-sample target
    if (!guided && m > 0.0 && !specular)
        pq = cv_rl_prob(kk.gt, wbin) * float(cv_rl_bins()) / (4.0 * CV_RL_PI);
    float qd = learning && !expected ? cv_rl_q(key, wbin) : 0.0;
    // a delta lobe is chosen with its BSDF probability bs.pdf
    float pdf = specular ? bs.pdf : cv_rl_mix_pdf(m, (1.0 - pd) * pq, bs.pdf);
    if (!(pdf > 0.0))
        return;
    // one-sample estimate of the reflected radiance (pdf: the density the
    // direction was drawn with; for a delta lobe its probability)
    if (learning && !expected)
        target += qd * cv_mean3(bs.f) * abs(dot(bs.wi, sf.ns)) / pdf;
    beta *= bs.f * (abs(dot(bs.wi, sf.ns)) / pdf);
    if (!cv_finite3(beta) || cv_max3(beta) <= 0.0)
        return;
    if (depth >= 3u) {
        float mb = cv_max3(beta);
        if (mb < 1.0) {
            float qd = max(0.0, 1.0 - mb);
            if (u_lc.y < qd)
                return;
            beta /= 1.0 - qd;
        }
    }
    flags = specular ? (flags | CV_RAYF_SPECULAR) : (flags & ~CV_RAYF_SPECULAR);
    push_ray = true;
    nr.o = vec4(cv_spawn_origin(sf, bs.wi), r.o.w);
    nr.d = vec4(bs.wi, specular ? 0.0 : pdf);
    nr.beta = vec4(beta, cv_ray_meta(flags, depth + 1u));
    entry = cv_rl_entry(key, wbin);
}

// Shades hit i (cv_shade_hit), then the bounce that led here learns its
// target and the path state takes the bounce leaving here.
void cv_shade(uint i, out bool push_shadow, out CvShadowItem s, out bool push_ray,
              out CvRayItem nr)
{
    CvHitItem h = hits[i];
    CvRayItem r = cv_ray_in(h.ray);
    uint path = uint(r.o.w);
    uint depth = cv_ray_depth(r);
    uvec2 st = imageLoad(rl_path, int(path)).xy;
    uint learn = (depth > 0u && st.x != CV_RL_NONE && st.y + 1u == depth) ? st.x : CV_RL_NONE;
    float target, emitted;
    uint entry;
    cv_shade_hit(h, r, learn != CV_RL_NONE, target, emitted, entry, push_shadow, s, push_ray, nr);
    cv_rl_update(learn, target, emitted);
    imageStore(rl_path, int(path), uvec4(entry, depth, 0u, 0u));
}

#include "../shade_queue.glsl"
