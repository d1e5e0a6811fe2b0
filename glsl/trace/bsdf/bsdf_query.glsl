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

// What is asked (CvBsdfQuery.ask).
#define CV_BQ_F0 1u       // f at wi0
#define CV_BQ_PDF0 2u     // pdf at wi0
#define CV_BQ_SAMPLE 4u   // a direction drawn with (uc, u), into s
#define CV_BQ_F1 16u      // f at wi1
#define CV_BQ_PDF1 32u    // pdf at wi1
// The pdf at wi0 (GATE1: at wi1), asked with the f there, only where that
// f is not 0 (else 0): a light sample that carries nothing skips the coated
// pdf estimate.
#define CV_BQ_GATE0 64u
#define CV_BQ_GATE1 128u

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
