#version 450
// glsl/trace/generate.comp: starts a pass: the pass's first sample of every
// pixel of the crop (regenerate.glsl), written as the first iteration's
// input; the queues start empty. Later samples start where earlier paths
// end (path regeneration, trace.h).
#include "shared/trace.h"
layout(local_size_x = CV_TRACE_GROUP) in;
#include "common.glsl"
#include "queue_args.glsl"
#include "sampler.glsl"
#include "regenerate.glsl"

void main()
{
    uint i = cv_global_index();
    uint n = u_pass.frame.x;
    if (i == 0u) {
        cv_prepare_iteration(n);
        q.count[CV_Q_SHADOW] = 0u;
        q.count[CV_Q_TICKET_INTERSECT] = 0u;
        q.count[CV_Q_TICKET_SHADE] = 0u;
    }
    if (i >= n)
        return;
    // iteration 0 reads the odd half
    rays[cv_capacity() + i] = cv_camera_sample(i, u_pass.frame.w);
}
