#version 450
#extension GL_NV_shader_atomic_float : enable
// glsl/trace/rlpath/sd_shade.comp: the surface stage of rlpath's sdtree
// method (rlpath.method: sdtree): a path vertex (../path_vertex.glsl) whose
// bounce is drawn from the one-sample mixture of the hit's spatial leaf's
// directional quadtree (weight m, sdtree.glsl) and the BSDF (1 - m), whose
// exact density divides the throughput. The MIS weights between light
// sampling and the bounce use the BSDF's own density, not the mixture's
// (CV_STRATEGY_MIS_BSDF): they still sum to 1 for every direction, so the
// estimator stays unbiased for any tree and any m in [0, 1], and the light
// sample needs no walk of the quadtree. Delta lobes stay the BSDF's, glossy
// ones too, and the coated walk's bin (guides.glsl), as in the
// Q-learning method (shade.comp).
// While the guide trains (u_sd.learn.x) each vertex records its bounce and
// adds the emission it finds to the records of the bounces before it; the
// end of the pass splats every path's records into the statistics of
// the tree being trained (sd_flush.comp, sdtree.glsl), from which the
// host refines the next tree at the end of each training iteration
// (src/trace/rlpath_sd.c). The splat stays out of these kernels, which it
// would make longer to build. Passes
// after training pay only for the tree's lookups: their build
// (CV_FROZEN, render.c) leaves the learning code out, which costs a
// kernel's registers whether it runs or not (bench/RESULTS.md, "What
// rlpath's passes after training pay for learning").
// Its Russian roulette follows the guide's estimate of the light to come
// (cv_strategy_survives) rather than the throughput alone.
// Built once per bin of the hit queue, as path's shade.comp.
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
#ifndef CV_FROZEN
#define CV_SD_RECORD
#endif
#include "sdtree.glsl"
#include "guides.glsl"
#define CV_STRATEGY_FILM
#define CV_STRATEGY_MIS_BSDF
#define CV_STRATEGY_ROULETTE

// The adjoint-driven roulette's weight window (cv_strategy_survives): the
// ratio of its upper to its lower edge, Vorba and Křivánek's s; and the
// least survival probability, which bounds what a survivor's weight grows
// by where the class's estimate is too low (a light its records missed).
const float CV_SD_RR_WINDOW = 5.0;
const float CV_SD_RR_MIN = 0.2;

// The guided strategy (../path_vertex.glsl). Le: what the emission at
// this hit adds to the film (for the records); root, m: the hit's quadtree and guiding weight (0:
// BSDF sampling alone); pd: the probability with which the BSDF picks a
// delta lobe (those stay the BSDF's); guided, pq: the bounce is the
// guide's draw, of guided density pq; pmix: the density the bounce was
// drawn with, 0 for a delta lobe (for its record); lo: where the class
// guides, its estimate of the light bouncing on from the hit brings back,
// as radiance reflected towards the path (-1: none, and the roulette is
// pbrt's).
struct CvStrategy {
    vec3 Le;
    bool eligible;
    uint cls;
    int root;
    float m;
    float pd;
    bool guided;
    float pq;
    float pmix;
    float lo;
};

void cv_strategy_emitted(inout CvStrategy g, vec3 Le, uint flags) {}

void cv_strategy_film(inout CvStrategy g, vec3 L) { g.Le = L; }

void cv_strategy_begin(inout CvStrategy g, CvSurface sf, vec3 wo, CvBsdf b, bool delta)
{
    g.eligible = !delta && cv_rl_guides(b);
    if (g.eligible) {
        // the normal on the side the path came from
        g.cls = cv_sd_class(dot(wo, sf.ns) < 0.0 ? -sf.ns : sf.ns);
        vec4 l = cv_sd_leaf(sf.p, g.cls);
        g.root = int(l.x);
        g.m = l.y;
        // a Lambertian reflector of the surface's albedo under that
        // irradiance, as the Q-learning method's expected value
        // (shade.comp); only the roulette where the class guides reads it
        float e = g.m > 0.0 ? cv_sd_light(l) : -1.0;
        g.lo = e >= 0.0 ? cv_mean3(cv_bsdf_albedo(b)) * e * (1.0 / CV_SD_PI) : -1.0;
    }
    g.pd = g.m > 0.0 ? cv_bsdf_delta_prob(b, wo) : 0.0;
}

// The light sample is weighed against the BSDF alone (CV_STRATEGY_MIS_BSDF).
float cv_strategy_pdf(CvStrategy g, vec3 wi, float bsdf_pdf) { return bsdf_pdf; }

// One-sample mixture (guides.glsl: cv_rl_mixture_ask); a guided bounce's
// direction is drawn from the leaf's quadtree.
void cv_strategy_ask(inout CvStrategy g, CvBsdf b, vec3 wo, vec2 u_bc, vec2 u_bsdf, inout CvBsdfQuery q)
{
    g.guided = cv_rl_mixture_ask(g.m, g.pd, u_bc, u_bsdf, q);
    if (g.guided)
        q.wi1 = cv_sd_sample(g.root, q.u, g.pq);
}

bool cv_strategy_sample(inout CvStrategy g, CvBsdf b, CvSurface sf, vec3 wo, CvBsdfQuery q,
                        out CvBsdfSample bs, out float pdf, out bool specular)
{
    float m = g.m;
    pdf = 0.0;
    specular = false;
    bool guided = g.guided;
    bs = q.s;
    if (guided && g.pd > 0.0 && q.sampled && (bs.flags & CV_BSDF_SPECULAR) != 0u)
        guided = false;   // the delta lobe the BSDF picked: bs stands
    else if (!guided && !q.sampled)
        return false;
    float pq = 0.0;
    if (guided) {
        bs.wi = q.wi1;
        bs.f = q.f1;
        bs.pdf = q.pdf1;
        pq = g.pq;
    } else {
        if (bs.pdf <= 0.0)
            return false;
        specular = (bs.flags & CV_BSDF_SPECULAR) != 0u;
        if (m > 0.0 && !specular)
            pq = cv_sd_pdf(g.root, bs.wi);
    }
    // a delta lobe is chosen with its BSDF probability bs.pdf
    pdf = specular ? bs.pdf : m * (1.0 - g.pd) * pq + (1.0 - m) * bs.pdf;
    g.pmix = specular ? 0.0 : pdf;
    return pdf > 0.0;
}

// Adjoint-driven Russian roulette (Vorba and Křivánek, "Adjoint-Driven
// Russian Roulette and Splitting in Light Transport Simulation", 2016),
// without its splitting: a path bouncing on from the vertex is expected
// to add arrived * lo to its pixel, whose estimate so far (its film
// slot's mean, the training passes' samples included) is I. It survives
// with probability arrived * lo / I over the lower edge of a weight window
// of ratio s about 1, (1 + s) / 2 * arrived * lo / I, at most 1, at least
// CV_SD_RR_MIN. So a path whose pixel needs it goes on however small its
// throughput, which pbrt's rule (cv_roulette_survives) ends: that ended
// the guide's paths towards light that arrives late, and lost most of
// what guiding gained (bench/RESULTS.md, "Error a sample by path depth,
// and Russian roulette"); and a path that adds little ends early, at any
// depth. Where the class does not guide (mix 0 among them: path's image,
// bit for bit) or has no estimate, where its pixel has none yet, or on a
// material the guide does not serve (glossy or specular: guides.glsl),
// pbrt's rule. Unbiased for any estimate: the survivors' throughput is
// divided by the probability. Reads the film slot's sum: once a guided
// bounce.
bool cv_strategy_survives(CvStrategy g, uint path, uint depth, float u, float arrived,
                          inout vec3 beta)
{
    if (g.lo < 0.0)
        return cv_roulette_survives(depth, u, beta);
    vec4 f = film[path].L;
    float I = f.w >= 2.0 ? cv_mean3(f.rgb) / f.w : 0.0;
    if (!(I > 0.0))
        return cv_roulette_survives(depth, u, beta);
    float q = clamp(0.5 * (1.0 + CV_SD_RR_WINDOW) * arrived * g.lo / I, CV_SD_RR_MIN, 1.0);
    if (q >= 1.0)
        return true;
    if (u >= q)
        return false;
    beta /= q;
    return true;
}

#include "../path_vertex.glsl"

// Shades hit i; while training, keeps the path's records (sdtree.glsl).
void cv_shade(uint i, out bool push_shadow, out CvShadowItem s, out bool push_ray,
              out CvRayItem nr)
{
    CvHitItem h = hits[i];
    CvRayItem r = cv_ray_in(h.ray);
    CvStrategy g = CvStrategy(vec3(0.0), false, 0u, 0, 0.0, 0.0, false, 0.0, 0.0, -1.0);
    cv_path_vertex(h, r, g, push_shadow, s, push_ray, nr);
#ifndef CV_FROZEN
    if (!cv_sd_learning())
        return;
    uint slot = uint(r.o.w), depth = cv_ray_depth(r);
    if (depth > 0u)
        cv_sd_found(slot, depth, g.Le);
    if (push_shadow)
        s.m.z = float(depth);   // the shadow stage adds its light to the records
    if (push_ray)
        // only the vertices the guide serves train it
        cv_sd_record(slot, depth, nr.o.xyz, g.cls, nr.d.xyz, g.eligible ? g.pmix : 0.0,
                     nr.beta.rgb);
    else
        cv_sd_path_end(slot, depth);
#endif
}

#include "../shade_queue.glsl"
