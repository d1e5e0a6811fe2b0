// glsl/trace/common.glsl: what every stage of the wavefront path tracer
// shares: the per-pass uniform block, queue and film buffers, ray offsets.
// Include after the local_size layout line.
#ifndef CV_TRACE_COMMON_GLSL
#define CV_TRACE_COMMON_GLSL

#include "shared/trace.h"
#include "../lib/index.glsl"
#include "../lib/constants.glsl"
#include "../lib/sampling.glsl"

layout(std140, binding = CV_UBO_PASS) uniform CvPassBlock { CvPassParams u_pass; };

layout(std430, binding = CV_BIND_QUEUES) coherent buffer CvQueueBlock { CvTraceQueues q; };
// CV_NO_QUEUES (bdpt's kernel, which runs whole samples): no ray, hit or
// shadow queues. Mesa counts every declared storage block against its 16,
// used or not.
#ifndef CV_NO_QUEUES
layout(std430, binding = CV_BIND_RAYS) buffer CvRays { CvRayItem rays[]; };
layout(std430, binding = CV_BIND_HITS) buffer CvHits { CvHitItem hits[]; };
layout(std430, binding = CV_BIND_SHADOW) buffer CvShadow { CvShadowItem shadows[]; };
#endif
layout(std430, binding = CV_BIND_FILM) buffer CvFilm { CvFilmPixel film[]; };

uint cv_iteration() { return u_pass.iteration; }
// The scene's lights (the light buffer holds a placeholder when there are none).
uint cv_n_lights() { return u_pass.n_lights; }
uint cv_max_depth() { return u_pass.max_depth; }
uint cv_capacity() { return u_pass.n_paths; }

// A ray's bits (CV_RAYF_*) and depth, both kept in beta.w (see trace.h).
uint cv_ray_flags(CvRayItem r) { return uint(r.beta.w) & CV_RAYF_MASK; }
uint cv_ray_depth(CvRayItem r) { return (uint(r.beta.w) >> CV_RAYF_DEPTH_SHIFT) & CV_RAYF_DEPTH_MASK; }
uint cv_ray_medium(CvRayItem r) { return uint(r.beta.w) >> CV_RAYF_MEDIUM_SHIFT; }
float cv_ray_meta(uint flags, uint depth) { return float(flags | (depth << CV_RAYF_DEPTH_SHIFT)); }
// the same for a ray in medium `medium` (glsl/shared/medium.h)
float cv_ray_meta_in(uint flags, uint depth, uint medium)
{
    return float(flags | (depth << CV_RAYF_DEPTH_SHIFT) | (medium << CV_RAYF_MEDIUM_SHIFT));
}

// The sample index of the path in flight in slot `path`, and its filter
// weight (trace.h: CvFilmPixel.normal.w).
uint cv_path_sample(uint path) { return uint(abs(film[path].normal.w)) - 1u; }
float cv_path_weight(uint path) { return film[path].normal.w < 0.0 ? -1.0 : 1.0; }
// The crop pixel that path slot `path` belongs to.
uint cv_path_pixel(uint path) { return path % u_pass.n_pixels; }
// The full film's pixel index of crop pixel i: what keys every random
// number of a pixel, so that a crop draws the same ones as the full film.
uint cv_film_pixel(uint i)
{
    uint cw = u_pass.crop_w;
    uvec2 px = uvec2(i % cw, i / cw) + u_pass.film.zw;
    return px.y * u_pass.film.x + px.x;
}

#ifndef CV_NO_QUEUES
// The iteration's input rays and the rays it writes (see trace.h).
CvRayItem cv_ray_in(uint i) { return rays[((cv_iteration() + 1u) & 1u) * cv_capacity() + i]; }
// volpath's intersect stage updates an input ray's throughput and medium
// (medium/track.glsl) for the stages after it.
void cv_ray_in_beta(uint i, vec4 beta) { rays[((cv_iteration() + 1u) & 1u) * cv_capacity() + i].beta = beta; }
void cv_ray_out(uint slot, CvRayItem r) { rays[(cv_iteration() & 1u) * cv_capacity() + slot] = r; }
// The shade stage's i-th hit: with CV_SHADE_BIN 0, 1 or 2, of that bin
// alone; else the first bin from the front of the hit queue, then the
// second from its end, then the third from the end of the buffer
// (CV_Q_HITS_B, CV_Q_HITS_C in trace.h).
#if defined(CV_SHADE_BIN) && CV_SHADE_BIN == 0
uint cv_hit_count() { return q.count[CV_Q_HITS]; }
uint cv_hit_slot(uint i) { return i; }
#elif defined(CV_SHADE_BIN) && CV_SHADE_BIN == 1
uint cv_hit_count() { return q.count[CV_Q_HITS_B]; }
uint cv_hit_slot(uint i) { return cv_capacity() - 1u - i; }
#elif defined(CV_SHADE_BIN)
uint cv_hit_count() { return q.count[CV_Q_HITS_C]; }
uint cv_hit_slot(uint i) { return 2u * cv_capacity() - 1u - i; }
#else
uint cv_hit_count() { return q.count[CV_Q_HITS] + q.count[CV_Q_HITS_B] + q.count[CV_Q_HITS_C]; }
uint cv_hit_slot(uint i)
{
    uint a = q.count[CV_Q_HITS], b = q.count[CV_Q_HITS_B];
    if (i < a)
        return i;
    return i < a + b ? cv_capacity() - 1u - (i - a) : 2u * cv_capacity() - 1u - (i - a - b);
}
#endif
uint cv_escaped_ray(uint i) { return hits[cv_capacity() + i].ray; }
void cv_escaped_push(uint slot, uint ray) { hits[cv_capacity() + slot].ray = ray; }
#endif

// Dimension pairs: 0 filter, 1 lens, then CV_PAIRS_PER_BOUNCE per depth.
// (Shade stages get theirs through cv_bounce_2d in surface_inputs.glsl.)
#define CV_PAIRS_PER_BOUNCE 4u
#define CV_PAIR_BSDF_U2 0u    // BSDF direction
#define CV_PAIR_BSDF_UC 1u    // x: BSDF lobe, y: material mix
#define CV_PAIR_LIGHT_U2 2u   // light position
#define CV_PAIR_LIGHT_UC 3u   // x: light choice, y: roulette
// The camera ray's time (x; a moving camera's only): a pair past any
// bounce's, so that it moved no other dimension. Pairs are only hashed into
// their scramble (sampler.glsl): any number is a pair of its own.
#define CV_PAIR_CAMERA_TIME 0x7fffffffu

// x moved to the next float in the direction of s's sign (s 0: x).
float cv_float_away(float x, float s)
{
    if (s == 0.0)
        return x;
    if (x == 0.0)
        return s > 0.0 ? 1.1754944e-38 : -1.1754944e-38;
    return intBitsToFloat(floatBitsToInt(x) + ((x > 0.0) == (s > 0.0) ? 1 : -1));
}

// Offsets a ray origin p off a surface along its geometric normal n (unit,
// on the side the ray leaves to) so that the new ray cannot hit the surface
// it leaves: by err (cv_point_error: it scales with the triangle's
// vertices), then each coordinate one float further away from the surface,
// as pbrt-v4's OffsetRayOrigin rounds. A fixed number of ulps of p
// (Waechter and Binder) is too little where a hit near the origin lies on
// a huge triangle, and far more than needed far from the origin, where it
// let light through walls.
vec3 cv_offset_ray(vec3 p, float err, vec3 n)
{
    vec3 o = p + err * n;
    return vec3(cv_float_away(o.x, n.x), cv_float_away(o.y, n.y), cv_float_away(o.z, n.z));
}

// Queue slots for a whole group: every invocation says whether it pushes to
// each of up to four queues; the group takes its range of each queue with
// one atomic and hands out slots in invocation order. Call from uniform
// control flow (no invocation may have returned). Besides saving atomics,
// this avoids llvmpipe (Mesa 22.3) losing per-invocation atomicAdd results
// in partially active SIMD vectors, which dropped and duplicated items.
// The four flags travel packed in 8-bit fields (a group of 64 counts to
// 64 at most) through an inclusive Hillis-Steele scan in shared memory:
// log2(group) steps for every invocation rather than a serial loop in one.
#if CV_TRACE_GROUP > 255
#error "cv_queue_slots4 packs counts of a group in 8 bits"
#endif
shared uint cv_q_scan[2][CV_TRACE_GROUP];
shared uint cv_q_base[4];

// The invocation that takes its group's queue slots: the last, whose
// inclusive scan holds the group's totals.
bool cv_queue_slot_taker() { return gl_LocalInvocationIndex == uint(CV_TRACE_GROUP) - 1u; }

uvec4 cv_queue_slots4(bvec4 push, uvec4 queue)
{
    uint li = gl_LocalInvocationIndex;
    uint mine = (push.x ? 1u : 0u) | (push.y ? 1u << 8 : 0u) | (push.z ? 1u << 16 : 0u) | (push.w ? 1u << 24 : 0u);
    cv_q_scan[0][li] = mine;
    barrier();
    uint src = 0u;
    for (uint off = 1u; off < uint(CV_TRACE_GROUP); off <<= 1) {
        uint v = cv_q_scan[src][li];
        if (li >= off)
            v += cv_q_scan[src][li - off];
        cv_q_scan[src ^ 1u][li] = v;
        src ^= 1u;
        barrier();
    }
    uint incl = cv_q_scan[src][li];
    if (cv_queue_slot_taker()) {
        uvec4 total = (uvec4(incl) >> uvec4(0u, 8u, 16u, 24u)) & 255u;
        cv_q_base[0] = total.x > 0u ? atomicAdd(q.count[queue.x], total.x) : 0u;
        cv_q_base[1] = total.y > 0u ? atomicAdd(q.count[queue.y], total.y) : 0u;
        cv_q_base[2] = total.z > 0u ? atomicAdd(q.count[queue.z], total.z) : 0u;
        cv_q_base[3] = total.w > 0u ? atomicAdd(q.count[queue.w], total.w) : 0u;
    }
    barrier();
    uint excl = incl - mine;
    return uvec4(cv_q_base[0], cv_q_base[1], cv_q_base[2], cv_q_base[3]) +
           ((uvec4(excl) >> uvec4(0u, 8u, 16u, 24u)) & 255u);
}

uvec3 cv_queue_slots3(bvec3 push, uvec3 queue)
{
    return cv_queue_slots4(bvec4(push, false), uvec4(queue, queue.z)).xyz;
}

uvec2 cv_queue_slots(bool push0, uint queue0, bool push1, uint queue1)
{
    return cv_queue_slots3(bvec3(push0, push1, false), uvec3(queue0, queue1, queue1)).xy;
}

// Russian roulette from the fourth vertex on (depth 3), for surface and
// medium vertices alike: a path whose throughput beta fell below 1 ends
// with probability 1 - max(beta) (false: the path ends), the survivors
// weigh more. u: the vertex's roulette number.
bool cv_roulette_survives(uint depth, float u, inout vec3 beta)
{
    if (depth < 3u)
        return true;
    float m = cv_max3(beta);
    if (m >= 1.0)
        return true;
    float p_end = max(0.0, 1.0 - m);
    if (u < p_end)
        return false;
    beta /= 1.0 - p_end;
    return true;
}

bool cv_finite3(vec3 v)
{
    return !(any(isnan(v)) || any(isinf(v)));
}

// Counts a radiance sample (or a path's throughput) dropped for a NaN or
// infinite value: it never reaches the film, where one would poison its
// pixel, and the host reports the count (render.h: nonfinite_samples), so
// that the bug behind it shows. An atomic: reached only when something
// already went wrong.
void cv_film_reject()
{
    atomicAdd(q.stats[CV_STAT_NONFINITE].x, 1u);
}

// Adds radiance to a path slot's film entry, weighted by w, the filter
// weight (+1 or -1) of the sample that found it. Each slot has one path in
// flight and each stage touches a path once, so the stages need no atomics
// here. A finite sample that would take the sum past the float range is
// left out too: the resolve would divide infinity (or its difference with
// a negative filter lobe's, NaN) into the pixel.
void cv_film_add_weighted(uint path, float w, vec3 L)
{
    if (!cv_finite3(L)) {
        cv_film_reject();
    } else if (cv_max3(L) > 0.0) {
        vec3 s = film[path].L.rgb + w * L;
        if (cv_finite3(s))
            film[path].L.rgb = s;
        else
            cv_film_reject();
    }
}

// The same for the path in flight in the slot.
void cv_film_add(uint path, vec3 L) { cv_film_add_weighted(path, cv_path_weight(path), L); }

#endif
