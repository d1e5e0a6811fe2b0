#version 450
// glsl/trace/shade.comp: the path integrator's surface stage: a path vertex
// (path_vertex.glsl: emission, AOVs, next-event estimation, bounce with
// Russian roulette) whose bounce direction the BSDF samples. A path that
// does not go on starts its slot's next sample (shade_queue.glsl).
// The host builds it once per bin of the hit queue (trace.h):
// CV_SHADE_BIN=0 shades diffuse surfaces with the BSDF code cut down to
// diffuse (CV_BSDF_DIFFUSE_ONLY); CV_SHADE_BIN=1 every other material but
// those that may take the coated walk (bsdf/layered.glsl), whose code it
// leaves out (CV_NO_LAYERED); CV_SHADE_BIN=2 those, built only for scenes
// that have them (src/trace/shade_bins.c decides a material's bin). A
// kernel's registers, so its occupancy, are those of its largest material
// and its compile time grows with its code, so the walk, by far the
// largest, has a kernel of its own and the lean copy runs most hits of a
// typical scene.
#include "shared/trace.h"
layout(local_size_x = CV_TRACE_GROUP) in;
#if defined(CV_SHADE_BIN) && CV_SHADE_BIN == 0
#define CV_BSDF_DIFFUSE_ONLY
#elif defined(CV_SHADE_BIN) && CV_SHADE_BIN == 1 && !defined(CV_NO_LAYERED)
#define CV_NO_LAYERED  // (a scene without the walk defines it already)
#endif
#include "unroll_hint.glsl"
#include "common.glsl"
#include "sampler.glsl"
#include "geometry.glsl"
#include "materials.glsl"
#include "lights.glsl"
#include "surface_inputs.glsl"

// The path integrator's strategy (path_vertex.glsl): the BSDF's own
// sampling, which needs no state.
struct CvStrategy {
    bool unused;
};

void cv_strategy_emitted(inout CvStrategy g, vec3 Le, uint flags) {}

void cv_strategy_begin(inout CvStrategy g, CvSurface sf, vec3 wo, CvBsdf b, bool delta) {}

float cv_strategy_pdf(CvStrategy g, vec3 wi, float bsdf_pdf)
{
    return bsdf_pdf;
}

void cv_strategy_ask(inout CvStrategy g, CvBsdf b, vec3 wo, vec2 u_bc, vec2 u_bsdf, inout CvBsdfQuery q)
{
    q.ask |= CV_BQ_SAMPLE;
    q.uc = u_bc.x;
    q.u = u_bsdf;
}

bool cv_strategy_sample(inout CvStrategy g, CvBsdf b, CvSurface sf, vec3 wo, CvBsdfQuery q,
                        out CvBsdfSample bs, out float pdf, out bool specular)
{
    bs = q.s;
    specular = false;
    pdf = 0.0;
    if (!q.sampled || bs.pdf <= 0.0)
        return false;
    pdf = bs.pdf;
    specular = (bs.flags & CV_BSDF_SPECULAR) != 0u;
    return true;
}

#include "path_vertex.glsl"

// Shades hit i (shade_queue.glsl's main() queues what it returns).
void cv_shade(uint i, out bool push_shadow, out CvShadowItem s, out bool push_ray,
              out CvRayItem nr)
{
    CvHitItem h = hits[i];
    CvStrategy g = CvStrategy(false);
    cv_path_vertex(h, cv_ray_in(h.ray), g, push_shadow, s, push_ray, nr);
}

#include "shade_queue.glsl"
