// glsl/trace/path_vertex.glsl: one vertex of a path at a surface hit, the
// same for every integrator: emitted light (MIS-weighted against light
// sampling), the AOVs, then, below the maximum depth, next-event estimation
// (a shadow ray queued with its MIS-weighted contribution; skipped for delta
// BSDFs) and the bounce with Russian roulette. What varies is the sampling
// strategy of the bounce direction: the shade stage that includes this file
// (trace/shade.comp: the BSDF's own sampling; trace/rlpath/shade.comp: a
// mixture with a learned distribution) defines, before the include,
//   struct CvStrategy                per-vertex state of the strategy
//   void cv_strategy_emitted(inout CvStrategy g, vec3 Le, uint flags)
//       at a hit on a lamp with emitted radiance Le towards the path
//       (flags: the incoming ray's CV_RAYF_*), before it is added
//   void cv_strategy_begin(inout CvStrategy g, CvSurface sf, vec3 wo,
//                          CvBsdf b, bool delta)
//       once the BSDF is known
//   float cv_strategy_pdf(CvStrategy g, vec3 wi, float bsdf_pdf)
//       the density (solid angle) with which the strategy would draw wi,
//       given the BSDF's (bsdf_pdf): next-event estimation weighs its
//       light sample against it
//   void cv_strategy_ask(inout CvStrategy g, CvBsdf b, vec3 wo, vec2 u_bc,
//                        vec2 u_bsdf, inout CvBsdfQuery q)
//       adds to q what the bounce needs of the BSDF (a sample, f and pdf
//       at wi1: bsdf/bsdf_query.glsl); the vertex asks for everything in
//       one cv_bsdf_query, whose call site is the only copy of the BSDF
//       code (the coated walk's above all) in the kernel
//   bool cv_strategy_sample(inout CvStrategy g, CvBsdf b, CvSurface sf,
//                           vec3 wo, CvBsdfQuery q, out CvBsdfSample bs,
//                           out float pdf, out bool specular)
//       draws the bounce from q's answers: bs.wi and bs.f, pdf the density
//       it was drawn with (for a delta lobe its probability, > 0),
//       specular whether a delta lobe was chosen; false ends the path
// and, where it defines CV_STRATEGY_FILM,
//   void cv_strategy_film(inout CvStrategy g, vec3 L)
//       the emission this hit adds to the film (MIS-weighted, times the
//       path throughput)
// and, where cv_strategy_pdf is the BSDF's own density (bsdf_pdf) rather
// than the one the bounce is drawn with, CV_STRATEGY_MIS_BSDF: the bounce
// ray then carries the BSDF's density of its direction (bs.pdf) for the
// emission it finds, so that its MIS weight and the light sample's still
// sum to 1 for every direction (the bounce still divides by pdf).
// and, where it defines CV_STRATEGY_ROULETTE,
//   bool cv_strategy_survives(CvStrategy g, uint path, uint depth, float u,
//                             float arrived, inout vec3 beta)
//       the Russian roulette of the bounce in place of
//       cv_roulette_survives (common.glsl): path, the path's film slot;
//       arrived, the channel mean of the throughput the path reached the
//       vertex with; beta, the one after the bounce, divided by the
//       survival probability
// The strategy only decides directions, densities and (with
// CV_STRATEGY_ROULETTE) survival; throughput, MIS, the roulette's
// division and the queued rays stay here, so the integrators' images
// differ only by their sampling. Under volpath (CV_MEDIA) the shadow ray
// and the bounce ray carry the medium on their side of the surface (its
// MediumInterface, medium/medium.glsl). Include after surface_inputs.glsl.
#ifndef CV_TRACE_PATH_VERTEX_GLSL
#define CV_TRACE_PATH_VERTEX_GLSL

// Where next-event estimation samples lights from: the surface point, but
// on a curve pbrt-v4's place, the point a ray towards wo would leave from
// (towards -wo for a BSDF that only transmits): pbrt-v4 nudges every
// light sample so, which on a curve is a width away rather than a
// rounding error.
vec3 cv_light_sample_point(CvSurface sf, CvBsdf b, vec3 wo, uint prim)
{
#ifdef CV_HAS_CURVES
    if ((prim & CV_PRIM_CURVE) != 0u) {
#ifdef CV_BSDF_BASIC
        bool transmits = false;  // diffuse and mirror
#else
        uint t = CV_BSDF_TYPE(b);
        bool transmits = t == CV_MAT_DIELECTRIC || t == CV_MAT_THIN_DIELECTRIC || t == CV_MAT_DIFFUSE_TRANSMISSION;
#endif
        if (!transmits)
            return cv_spawn_origin(sf, wo);
    }
#endif
    return sf.p;
}

#ifdef CV_MEDIA
#include "medium/medium.glsl"
#endif
// Subsurface materials (sss_vertex.glsl): never in the diffuse bin nor in
// a walk-only one (bsdf.glsl; probe exits are bin 1's: intersect.comp)
#if defined(CV_HAS_SUBSURFACE) && defined(CV_BSDF_ANY_TYPE) && !defined(CV_BSDF_BASIC)
#define CV_SSS
#include "sss_vertex.glsl"
#endif

// The medium of a ray leaving surface sf in direction w, from a path in
// medium `medium` (0 without CV_MEDIA).
uint cv_path_medium_after(CvSurface sf, vec3 w, uint medium)
{
#ifdef CV_MEDIA
    return cv_medium_across(sf.material, sf.ng, w, medium);
#else
    return 0u;
#endif
}

// Shades hit h of ray r with strategy g; what it queues comes back in the
// out parameters, so that main() can take queue slots in uniform control
// flow (shade_queue.glsl).
void cv_path_vertex(CvHitItem h, CvRayItem r, inout CvStrategy g, out bool push_shadow,
                    out CvShadowItem s, out bool push_ray, out CvRayItem nr)
{
    push_shadow = false;
    push_ray = false;
    uint path = uint(r.o.w);
    uint flags = cv_ray_flags(r);
    uint depth = cv_ray_depth(r);
    vec3 beta = r.beta.rgb;
    vec3 wo = -r.d.xyz;
    uint pairs = 0u;  // the vertex's sample pairs: the bounce's, or a probe exit's own
#ifdef CV_SSS
    // The exit of a BSSRDF probe: weighted by Sp, scatters through the
    // exit lobe, from its normal as wo (pbrt-v4); no emission, no AOVs.
    bool sss_exit = (flags & CV_RAYF_PROBE) != 0u;
    CvSurface sf;
    CvBsdf b;
    if (sss_exit) {
        if (h.prim == CV_HIT_PROBE_MISS || !cv_sss_exit(h, r, path, sf, beta, b))
            return;
        if (!cv_finite3(beta)) {
            cv_film_reject();
            return;
        }
        wo = b.frame.z;
        flags &= ~CV_RAYF_PROBE;
        pairs = CV_PAIR_SSS_EXIT;
    } else {
        sf = cv_surface_ray(h.prim, h.b1, h.b2, r.o.xyz, r.d.xyz, h.t);
    }
#else
    const bool sss_exit = false;
    CvSurface sf = cv_surface_ray(h.prim, h.b1, h.b2, r.o.xyz, r.d.xyz, h.t);
#endif
    bool front = dot(wo, sf.ng) > 0.0;

    int light = (h.prim & CV_PRIM_CURVE) != 0u || sss_exit ? -1 : cv_tri_light[h.prim];  // curves emit nothing
    if (light >= 0) {
        vec3 Le = cv_light_Le_area(uint(light), wo, sf.uv, front, sf.p);
        cv_strategy_emitted(g, Le, flags);
        if (cv_max3(Le) > 0.0) {
            float w = 1.0;
            if (depth > 0u && (flags & CV_RAYF_SPECULAR) == 0u && cv_n_lights() > 0u)
                w = cv_power_heuristic(r.d.w, cv_light_pdf_area(uint(light), r.o.xyz, sf.p, sf.ng));
            cv_film_add(path, beta * Le * w);
#ifdef CV_STRATEGY_FILM
            cv_strategy_film(g, beta * Le * w);   // what the path added (rlpath/sd_shade.comp)
#endif
        }
    }

    vec2 u_bsdf = cv_bounce_2d(path, depth, pairs + CV_PAIR_BSDF_U2);
    vec2 u_bc = cv_bounce_2d(path, depth, pairs + CV_PAIR_BSDF_UC);
    vec2 u_light = cv_bounce_2d(path, depth, pairs + CV_PAIR_LIGHT_U2);
    vec2 u_lc = cv_bounce_2d(path, depth, pairs + CV_PAIR_LIGHT_UC);

#ifdef CV_SSS
    if (!sss_exit)
        b = cv_bsdf_at(sf.material, cv_shading_point(sf, front), u_bc.y);
#else
    CvBsdf b = cv_bsdf_at(sf.material, cv_shading_point(sf, front), u_bc.y);
#endif
    cv_bsdf_set_stream(b, u_bsdf, u_light);  // stochastic (coated) BSDFs' random numbers
    bool delta = cv_bsdf_is_delta(b);
    cv_strategy_begin(g, sf, wo, b, delta);

#ifdef CV_AOVS
    if (sss_exit)
        flags |= CV_RAYF_ALBEDO_DONE;  // the albedo of the surface the path entered
    // weighted by the sample's filter weight, as radiance (cv_film_add)
    float aov_w = cv_path_weight(path);
    if (depth == 0u && !sss_exit) {
        film[path].normal.xyz += aov_w * sf.ns;
        film[path].albedo.w += aov_w * h.t;
    }
    if (!delta && (flags & CV_RAYF_ALBEDO_DONE) == 0u) {
        film[path].albedo.rgb += aov_w * cv_bsdf_albedo(b);
        flags |= CV_RAYF_ALBEDO_DONE;
    }
#endif
    if (depth >= cv_max_depth())
        return;

    // The light sample; then one query of the BSDF for it and the bounce.
    CvLightSample ls;
    bool nee = !delta && cv_n_lights() > 0u &&
               cv_light_sample(cv_light_sample_point(sf, b, wo, h.prim), sf.ns, vec3(u_lc.x, u_light), ls) &&
               cv_max3(ls.L) > 0.0;
    CvBsdfQuery q = cv_bsdf_query_new(wo);
    if (nee) {
        q.ask = CV_BQ_F0 | CV_BQ_GATE0 | (ls.delta ? 0u : CV_BQ_PDF0);
        q.wi0 = ls.wi;
    }
    cv_strategy_ask(g, b, wo, u_bc, u_bsdf, q);
    cv_bsdf_query(b, q);

    if (nee) {
        vec3 f = q.f0 * abs(dot(ls.wi, sf.ns));
        if (cv_max3(f) > 0.0) {
            float w = ls.delta ? 1.0 : cv_power_heuristic(ls.pdf, cv_strategy_pdf(g, ls.wi, q.pdf0));
            vec3 Ld = beta * f * ls.L * (w / ls.pdf);
            if (cv_finite3(Ld)) {
                push_shadow = true;
                s.o = vec4(cv_spawn_origin(sf, ls.wi),
                           ls.dist * (1.0 - 1e-4));
                s.d = vec4(ls.wi, float(path));
                s.L = vec4(Ld, 0.0);
                s.m = vec4(float(cv_path_medium_after(sf, ls.wi, cv_ray_medium(r))), 0.0, 0.0, 0.0);
            } else {
                cv_film_reject();
            }
        }
    }

    CvBsdfSample bs;
    float pdf;
    bool specular;
    if (!cv_strategy_sample(g, b, sf, wo, q, bs, pdf, specular))
        return;
#ifdef CV_STRATEGY_ROULETTE
    float arrived = cv_mean3(beta);
#endif
    beta *= bs.f * (abs(dot(bs.wi, sf.ns)) / pdf);
    if (!cv_finite3(beta)) {
        cv_film_reject();
        return;
    }
    if (cv_max3(beta) <= 0.0)
        return;
#ifdef CV_STRATEGY_ROULETTE
    if (!cv_strategy_survives(g, path, depth, u_lc.y, arrived, beta))
#else
    if (!cv_roulette_survives(depth, u_lc.y, beta))
#endif
        return;
    flags = specular ? (flags | CV_RAYF_SPECULAR) : (flags & ~CV_RAYF_SPECULAR);
#ifdef CV_SSS
    // into a subsurface material: the path goes on as its probe segment
    if (!sss_exit && CV_BSDF_TYPE(b) == CV_MAT_SUBSURFACE && dot(bs.wi, sf.ng) * dot(wo, sf.ng) < 0.0) {
        push_ray = cv_sss_enter(sf, b, r.o.w, path, depth, beta, flags, cv_ray_medium(r), nr);
        return;
    }
#endif
    push_ray = true;
    nr.o = vec4(cv_spawn_origin(sf, bs.wi), r.o.w);
#ifdef CV_STRATEGY_MIS_BSDF
    float mis_pdf = bs.pdf;
#else
    float mis_pdf = pdf;
#endif
    nr.d = vec4(bs.wi, specular ? 0.0 : mis_pdf);
    nr.beta = vec4(beta, cv_ray_meta_in(flags, depth + 1u,
                                        cv_path_medium_after(sf, bs.wi, cv_ray_medium(r))));
}

#endif
