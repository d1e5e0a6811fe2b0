// glsl/trace/shade_queue.glsl: main() of the shade stages (trace/shade.comp,
// trace/rlpath/shade.comp): shades hit i with the stage's cv_shade and
// queues what it produced (a shadow ray; the bounce ray, or else the pixel
// to the done queue) with slots taken in uniform control flow. Include last.
#ifndef CV_TRACE_SHADE_QUEUE_GLSL
#define CV_TRACE_SHADE_QUEUE_GLSL

void main()
{
    uint i = cv_global_index();
    bool valid = i < cv_hit_count();
    bool push_shadow = false, push_ray = false;
    CvShadowItem s;
    CvRayItem nr;
    uint slot_in = valid ? cv_hit_slot(i) : 0u;
    if (valid)
        cv_shade(slot_in, push_shadow, s, push_ray, nr);
    bool done = valid && !push_ray;
    uvec3 slot = cv_queue_slots3(bvec3(push_shadow, push_ray, done),
                                 uvec3(CV_Q_SHADOW, CV_Q_RAYS_OUT, CV_Q_DONE));
    if (push_shadow)
        shadows[slot.x] = s;
    if (push_ray)
        cv_ray_out(slot.y, nr);
    if (done)
        cv_done_push(slot.z, uint(cv_ray_in(hits[slot_in].ray).o.w));
}

#endif
