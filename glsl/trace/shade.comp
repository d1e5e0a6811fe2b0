#version 450
// glsl/trace/shade.comp: everything that happens at a surface hit: emitted
// light (MIS-weighted against light sampling), the AOVs, then, below the
// maximum depth, next-event estimation (a shadow ray queued with its
// MIS-weighted contribution; skipped for delta BSDFs) and BSDF sampling of
// the bounce ray with Russian roulette. A path that does not go on starts its
// slot's next sample (shade_queue.glsl).
// The host builds it twice over the two bins of the hit queue (trace.h):
// CV_SHADE_BIN=0 shades diffuse surfaces with the BSDF code cut down to
// diffuse (CV_BSDF_DIFFUSE_ONLY), CV_SHADE_BIN=1 every other material. The
// full BSDF library sizes the whole kernel for its largest material, so
// the lean copy runs most hits of a typical scene.
#include "shared/trace.h"
layout(local_size_x = CV_TRACE_GROUP) in;
#if defined(CV_SHADE_BIN) && CV_SHADE_BIN == 0
#define CV_BSDF_DIFFUSE_ONLY
#endif
#include "common.glsl"
#include "sampler.glsl"
#include "geometry.glsl"
#include "materials.glsl"
#include "lights.glsl"
#include "surface_inputs.glsl"

// Shades hit i; what it queues comes back in the out parameters, so that
// main() can take queue slots in uniform control flow.
void cv_shade(uint i, out bool push_shadow, out CvShadowItem s, out bool push_ray,
              out CvRayItem nr)
{
    push_shadow = false;
    push_ray = false;
    CvHitItem h = hits[i];
    CvRayItem r = cv_ray_in(h.ray);
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
                float w = ls.delta ? 1.0 : cv_power_heuristic(ls.pdf, cv_bsdf_pdf(b, wo, ls.wi));
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

    CvBsdfSample bs;
    if (!cv_bsdf_sample(b, wo, u_bc.x, u_bsdf, bs) || bs.pdf <= 0.0)
        return;
    beta *= bs.f * (abs(dot(bs.wi, sf.ns)) / bs.pdf);
    if (!cv_finite3(beta) || cv_max3(beta) <= 0.0)
        return;
    bool specular = (bs.flags & CV_BSDF_SPECULAR) != 0u;
    if (depth >= 3u) {
        float m = cv_max3(beta);
        if (m < 1.0) {
            float qd = max(0.0, 1.0 - m);
            if (u_lc.y < qd)
                return;
            beta /= 1.0 - qd;
        }
    }
    flags = specular ? (flags | CV_RAYF_SPECULAR) : (flags & ~CV_RAYF_SPECULAR);
    push_ray = true;
    nr.o = vec4(cv_spawn_origin(sf, bs.wi), r.o.w);
    nr.d = vec4(bs.wi, specular ? 0.0 : bs.pdf);
    nr.beta = vec4(beta, cv_ray_meta(flags, depth + 1u));
}

#include "shade_queue.glsl"
