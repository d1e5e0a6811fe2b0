// glsl/trace/common.glsl: what every stage of the wavefront path tracer
// shares: the per-pass uniform block, queue and film buffers, ray offsets.
// Include after the local_size layout line.
#ifndef CV_TRACE_COMMON_GLSL
#define CV_TRACE_COMMON_GLSL

#include "shared/trace.h"
#include "../lib/index.glsl"

layout(std140, binding = CV_UBO_PASS) uniform CvPassBlock { CvPassParams u_pass; };

layout(std430, binding = CV_BIND_QUEUES) coherent buffer CvQueueBlock { CvTraceQueues q; };
layout(std430, binding = CV_BIND_RAYS_IN) readonly buffer CvRaysIn { CvRayItem rays_in[]; };
layout(std430, binding = CV_BIND_RAYS_OUT) writeonly buffer CvRaysOut { CvRayItem rays_out[]; };
layout(std430, binding = CV_BIND_HITS) buffer CvHits { CvHitItem hits[]; };
layout(std430, binding = CV_BIND_ESCAPED) buffer CvEscaped { uint escaped[]; };
layout(std430, binding = CV_BIND_SHADOW) buffer CvShadow { CvShadowItem shadows[]; };
layout(std430, binding = CV_BIND_FILM) buffer CvFilm { vec4 film[]; };
layout(std430, binding = CV_BIND_AOV) buffer CvAov { CvAovPixel aov[]; };

const float CV_PI = 3.14159265358979323846;

uint cv_depth() { return u_pass.misc.x; }
uint cv_max_depth() { return u_pass.seed.w; }
uint cv_sample_index() { return u_pass.frame.w; }

// Dimension pairs: 0 filter, 1 lens, then CV_PAIRS_PER_BOUNCE per depth.
#define CV_PAIRS_PER_BOUNCE 4u
#define CV_PAIR_BSDF_U2 0u    // BSDF direction
#define CV_PAIR_BSDF_UC 1u    // x: BSDF lobe, y: material mix
#define CV_PAIR_LIGHT_U2 2u   // light position
#define CV_PAIR_LIGHT_UC 3u   // x: light choice, y: roulette

// Offsets a ray origin off a surface along the geometric normal so the new
// ray cannot hit the surface it leaves (Waechter and Binder, "A Fast and
// Robust Method for Avoiding Self-Intersection", Ray Tracing Gems, 2019).
vec3 cv_offset_ray(vec3 p, vec3 n)
{
    const float origin = 1.0 / 32.0, float_scale = 1.0 / 65536.0, int_scale = 256.0;
    ivec3 of_i = ivec3(int_scale * n);
    vec3 p_i = vec3(intBitsToFloat(floatBitsToInt(p.x) + (p.x < 0.0 ? -of_i.x : of_i.x)),
                    intBitsToFloat(floatBitsToInt(p.y) + (p.y < 0.0 ? -of_i.y : of_i.y)),
                    intBitsToFloat(floatBitsToInt(p.z) + (p.z < 0.0 ? -of_i.z : of_i.z)));
    return vec3(abs(p.x) < origin ? p.x + float_scale * n.x : p_i.x,
                abs(p.y) < origin ? p.y + float_scale * n.y : p_i.y,
                abs(p.z) < origin ? p.z + float_scale * n.z : p_i.z);
}

// Queue slots for a whole group: every invocation says whether it pushes to
// each of two queues; invocation 0 takes the group's range of each queue
// with one atomic and hands out slots in invocation order. Call from uniform
// control flow (no invocation may have returned). Besides saving atomics,
// this avoids llvmpipe (Mesa 22.3) losing per-invocation atomicAdd results
// in partially active SIMD vectors, which dropped and duplicated items.
shared uint cv_q_flags[2 * CV_TRACE_GROUP];
shared uint cv_q_base[2];

uvec2 cv_queue_slots(bool push0, uint queue0, bool push1, uint queue1)
{
    uint li = gl_LocalInvocationIndex;
    cv_q_flags[li] = push0 ? 1u : 0u;
    cv_q_flags[CV_TRACE_GROUP + li] = push1 ? 1u : 0u;
    barrier();
    if (li == 0u) {
        uint a = 0u, b = 0u;
        for (uint k = 0u; k < uint(CV_TRACE_GROUP); k++) {
            uint fa = cv_q_flags[k], fb = cv_q_flags[CV_TRACE_GROUP + k];
            cv_q_flags[k] = a;
            cv_q_flags[CV_TRACE_GROUP + k] = b;
            a += fa;
            b += fb;
        }
        cv_q_base[0] = a > 0u ? atomicAdd(q.count[queue0], a) : 0u;
        cv_q_base[1] = b > 0u ? atomicAdd(q.count[queue1], b) : 0u;
    }
    barrier();
    return uvec2(cv_q_base[0] + cv_q_flags[li], cv_q_base[1] + cv_q_flags[CV_TRACE_GROUP + li]);
}

float cv_power_heuristic(float fa, float fb)
{
    float a = fa * fa, b = fb * fb;
    if (isinf(a))
        return 1.0;
    return a + b > 0.0 ? a / (a + b) : 0.0;
}

float cv_max3(vec3 v) { return max(v.x, max(v.y, v.z)); }

bool cv_finite3(vec3 v)
{
    return !(any(isnan(v)) || any(isinf(v)));
}

// Adds radiance to a pixel. Each pixel has one path in flight per wave and
// each stage touches a path once, so the stages need no atomics here.
void cv_film_add(uint pixel, vec3 L)
{
    if (cv_finite3(L) && cv_max3(L) > 0.0)
        film[pixel].rgb += L;
}

#endif
