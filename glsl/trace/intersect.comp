#version 450
// glsl/trace/intersect.comp: closest hit for every ray of this iteration;
// hits go to the hit queue. With CV_ESCAPED_QUEUE misses go to the escaped
// queue (trace/escaped.comp: environment light, rlpath's learning).
// Where a miss adds nothing (no environment light, no learning) the host
// may leave it out, and the slot starts its next sample (regenerate.glsl)
// right here: an escaped stage less per iteration, whose launch and drain
// cost more than its work where many rays leave the scene, while the
// camera's code here costs every ray a little (trace/render.h: enum
// cv_misses; bench/RESULTS.md, "Misses by scene"). The environment's code
// stays out of this kernel: with it, the kernel would use more storage
// blocks than Mesa allows (17 of 16). Alpha cut-outs are handled here by
// continuing the ray past a surface whose alpha test lets it through, so
// the depth does not change. Under volpath (CV_MEDIA) the ray is tracked
// through the media on its way (medium/track.glsl): a collision in a
// medium is queued as a hit of its own (CV_HIT_MEDIUM) for the shade
// stage's medium vertex. The last group to finish prepares the shade
// stage's dispatch (queue_args.glsl).
#include "shared/trace.h"
layout(local_size_x = CV_TRACE_GROUP) in;
#include "common.glsl"
#include "sampler.glsl"
#include "tracing.glsl"
#include "geometry.glsl"
#include "path_time.glsl"
#include "materials.glsl"
#include "queue_args.glsl"
#ifndef CV_ESCAPED_QUEUE
#include "regenerate.glsl"
#endif
#ifdef CV_MEDIA
#include "medium/medium.glsl"
#include "medium/track.glsl"
#endif
#ifdef CV_HAS_SUBSURFACE
#include "sss_probe.glsl"
#endif

void main()
{
    uint i = cv_global_index();
    bool valid = i < q.count[CV_Q_RAYS_IN];
    bool hit = false;
    CvHit h;
    h.t = 0.0;
    h.prim = 0u;
    h.b1 = 0.0;
    h.b2 = 0.0;
    bool regen = false;    // a miss's slot starts its next sample: nr
    CvRayItem nr;
    bool event = false;    // a collision in a medium (CV_MEDIA)
    bool probe = false;    // a subsurface probe segment: its result is queued as a hit
    uint probe_n = 0u;
    if (valid) {
        CvRayItem r = cv_ray_in(i);
#ifdef CV_HAS_MOTION
        cv_trace_time = cv_path_time(uint(r.o.w));
#endif
#ifdef CV_HAS_SUBSURFACE
        probe = (cv_ray_flags(r) & CV_RAYF_PROBE) != 0u;
        if (probe) {
            cv_sss_probe_trace(r, h, probe_n);
            hit = true;
        } else {
#endif
#ifdef CV_MEDIA
        hit = cv_medium_track(r, h, event) || event;  // an event is queued as a hit
        cv_ray_in_beta(i, r.beta);
#else
        float tmin = 0.0;
#ifndef CV_EMPTY_SCENE
        hit = cv_trace_closest(r.o.xyz, r.d.xyz, tmin, 1e30, h);
#endif
#ifdef CV_HAS_ALPHA
        for (uint k = 0u; hit && k < 64u; k++) {
            uint word = cv_prim_word(h.prim);
            CvSurface s = cv_surface_ray(h.prim, h.b1, h.b2, r.o.xyz, r.d.xyz, h.t);
            // keyed by film pixel, not slot: the same paths whatever K
            // and whatever the crop
            uint path = uint(r.o.w);
            float u = cv_uint_to_unit(cv_hash4(cv_film_pixel(cv_path_pixel(path)),
                                               cv_path_sample(path), h.prim,
                                               cv_ray_depth(r) * 64u + k));
            if (!cv_material_alpha_pass(word & CV_TRI_MATERIAL_MASK, s.uv, u))
                break;
            tmin = h.t * (1.0 + 1e-5) + 1e-6;
            hit = cv_trace_closest(r.o.xyz, r.d.xyz, tmin, 1e30, h);
        }
#endif
#endif
#ifndef CV_ESCAPED_QUEUE
        if (!hit)
            regen = cv_regenerate(uint(r.o.w), nr);
#endif
#ifdef CV_HAS_SUBSURFACE
        }
#endif
    }
#ifdef CV_ESCAPED_QUEUE
    bool miss_push = valid && !hit;
    const uint miss_queue = CV_Q_ESCAPED;
#else
    bool miss_push = regen;
    const uint miss_queue = CV_Q_RAYS_OUT;
#endif
#ifdef CV_HIT_BINS
    // Three bins by material (the host's choice, in the material's flags:
    // src/trace/shade_bins.c), so that the shade stage's work groups mostly
    // run one BSDF's code and each bin's kernel carries the registers of
    // its own materials only: diffuse surfaces (most of a typical scene);
    // every other material but the coated walk's, and volpath's medium
    // events, written from the queue's end; the coated walk's, from the
    // buffer's end (trace.h).
    uint bin = 0u;
    if (valid && hit)
        bin = event || probe ? 1u
                    : materials[cv_prim_word(h.prim) & CV_TRI_MATERIAL_MASK].flags >> CV_MATF_SHADE_BIN_SHIFT;
    bool hb = valid && hit;
    uvec4 s4 = cv_queue_slots4(bvec4(hb && bin == 0u, hb && bin == 1u, hb && bin == 2u, miss_push),
                               uvec4(CV_Q_HITS, CV_Q_HITS_B, CV_Q_HITS_C, miss_queue));
    uint hit_slot = bin == 0u ? s4.x : (bin == 1u ? cv_capacity() - 1u - s4.y : 2u * cv_capacity() - 1u - s4.z);
    uvec2 slot = uvec2(hit_slot, s4.w);
#else
    uvec2 slot = cv_queue_slots(valid && hit, CV_Q_HITS, miss_push, miss_queue);
#endif
    if (valid && hit) {
        CvHitItem it;
        it.ray = i;
        it.prim = h.prim;
        it.b1 = h.b1;
        it.b2 = h.b2;
        it.t = h.t;
        it.pad0 = probe_n;
        it.pad1 = 0u;
        it.pad2 = 0u;
        hits[slot.x] = it;
    } else if (miss_push) {
#ifdef CV_ESCAPED_QUEUE
        cv_escaped_push(slot.y, i);
#else
        cv_ray_out(slot.y, nr);
#endif
    }
    if (cv_queue_slot_taker() &&
        cv_last_group(CV_Q_TICKET_INTERSECT, gl_NumWorkGroups.x * gl_NumWorkGroups.y))
        cv_prepare_shade();
}
