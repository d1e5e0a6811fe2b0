// glsl/trace/bsdf/bsdf_query.glsl: what a path vertex asks of its BSDF, in
// one request (cv_bsdf_query in bsdf/bsdf.glsl, and in trace/bsdf_basic.glsl
// for the basic scenes): f and pdf at up to two given directions (a light
// sample's, a guided bounce's) and a sampled direction. GLSL compilers
// inline every call, so each call site of a BSDF function is a copy of its
// code in the kernel; asking for everything in one call keeps one copy of
// every lobe per kernel, the stochastic coated walk above all
// (tests/trace/bsdf_sites_test guards it). Directions are in world space.
#ifndef CV_BSDF_QUERY_GLSL
#define CV_BSDF_QUERY_GLSL

#include "bsdf_sample.glsl"

#include "shared/bsdf_query.h"  // what is asked: CV_BQ_*

struct CvBsdfQuery {
    uint ask;         // CV_BQ_* bits
    vec3 wo;
    vec3 wi0;
    vec3 wi1;
    float uc;         // the sample's lobe choice
    vec2 u;           // and direction
    vec3 f0;          // answers: 0 where not asked
    float pdf0;
    vec3 f1;
    float pdf1;
    bool sampled;     // s holds a sample (pdf > 0, f finite)
    CvBsdfSample s;
};

CvBsdfQuery cv_bsdf_query_new(vec3 wo)
{
    return CvBsdfQuery(0u, wo, vec3(0.0), vec3(0.0), 0.0, vec2(0.0), vec3(0.0), 0.0, vec3(0.0), 0.0, false,
                       CvBsdfSample(vec3(0.0), vec3(0.0), 0.0, 0u));
}

#endif
