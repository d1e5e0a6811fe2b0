// glsl/trace/shade_queue.glsl: main() of the shade stages (trace/shade.comp,
// trace/rlpath/shade.comp): shades hit i with the stage's cv_shade and
// queues what it produced (a shadow ray; the bounce ray, or else, the path
// having ended, the camera ray of its slot's next sample: regenerate.glsl)
// with slots taken in uniform control flow. The last group to finish (of
// every bin's programs, which the path integrator runs side by side)
// prepares the shadow stage and the next iteration (queue_args.glsl).
// Under volpath (CV_MEDIA), a collision in a medium (CV_HIT_MEDIUM, in the
// second bin) is a medium vertex (medium/vertex.glsl) instead.
// Include last.
#ifndef CV_TRACE_SHADE_QUEUE_GLSL
#define CV_TRACE_SHADE_QUEUE_GLSL

#include "queue_args.glsl"
#include "regenerate.glsl"
#ifdef CV_MEDIA
#include "medium/medium.glsl"
#include "medium/vertex.glsl"
#endif

// Work groups of the shade stage, over every bin's dispatch. The programs
// of bins 1 and 2 are built only where a scene's materials use them
// (src/trace/render.c), so an empty bin 1 or 2 counts no group: its
// program, where it runs, then takes no ticket (main). Bin 0's program
// always runs, so some group always prepares the shadow stage.
uint cv_shade_groups()
{
#ifdef CV_SHADE_BIN
    return cv_groups_in(q.args[CV_ARGS_HITS]) +
           (q.count[CV_Q_HITS_B] > 0u ? cv_groups_in(q.args[CV_ARGS_HITS_B]) : 0u) +
           (q.count[CV_Q_HITS_C] > 0u ? cv_groups_in(q.args[CV_ARGS_HITS_C]) : 0u);
#else
    return cv_groups_in(q.args[CV_ARGS_HITS_ALL]);
#endif
}

void main()
{
    uint i = cv_global_index();
    bool valid = i < cv_hit_count();
    bool push_shadow = false, push_ray = false;
    CvShadowItem s;
    CvRayItem nr;
    if (valid) {
        uint slot_in = cv_hit_slot(i);
#ifdef CV_HAS_MOTION
        // the path's time, for a moving shape's surface and carried by the
        // shadow ray (CvShadowItem.m.y): the slot may move on before the
        // shadow stage runs
        cv_trace_time = cv_path_time(uint(cv_ray_in(hits[slot_in].ray).o.w));
#endif
#ifdef CV_MEDIA
        CvHitItem hm = hits[slot_in];
        if (hm.prim == CV_HIT_MEDIUM)
            cv_medium_vertex(hm, cv_ray_in(hm.ray), push_shadow, s, push_ray, nr);
        else
#endif
        cv_shade(slot_in, push_shadow, s, push_ray, nr);
        uint path = uint(cv_ray_in(hits[slot_in].ray).o.w);
#ifdef CV_HAS_ALPHA
        // the shadow ray's sample for its alpha tests (shadow.comp), read
        // before the slot moves on to its next
        if (push_shadow)
            s.L.w = float(cv_path_sample(path));
#endif
        // and its filter weight, for the same reason: the sign of the
        // slot's next sample would weigh this one's light
        if (push_shadow)
            s.m.w = cv_path_weight(path);
#ifdef CV_HAS_MOTION
        if (push_shadow)
            s.m.y = cv_trace_time;
#endif
        if (!push_ray)
            push_ray = cv_regenerate(path, nr);
    }
    uvec2 slot = cv_queue_slots(push_shadow, CV_Q_SHADOW, push_ray, CV_Q_RAYS_OUT);
    if (push_shadow)
        shadows[slot.x] = s;
    if (push_ray)
        cv_ray_out(slot.y, nr);
#if defined(CV_SHADE_BIN) && CV_SHADE_BIN != 0
    bool counted = cv_hit_count() > 0u;  // (cv_shade_groups)
#else
    bool counted = true;
#endif
    if (counted && cv_queue_slot_taker() && cv_last_group(CV_Q_TICKET_SHADE, cv_shade_groups()))
        cv_prepare_shadow();
}

#endif
