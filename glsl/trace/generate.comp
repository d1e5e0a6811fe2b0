#version 450
// glsl/trace/generate.comp: starts a pass: the first camera ray of every
// path slot that has a sample in it (regenerate.glsl), written as the first
// iteration's input; the queues start empty. Later samples start where
// earlier paths end (path regeneration, trace.h). A pass of samples
// [a, b) starts min(K, b - a) slots of each pixel: item i starts sample
// a + i / P of pixel i % P (P pixels), in the slot that owns that sample.
#include "shared/trace.h"
// built without the scene's defines (one program for every scene): it
// makes every camera's rays, the spherical ones too (camera.glsl)
#define CV_EVERY_CAMERA
layout(local_size_x = CV_TRACE_GROUP) in;
#include "common.glsl"
#include "queue_args.glsl"
#include "sampler.glsl"
#include "regenerate.glsl"

void main()
{
    uint i = cv_global_index();
    uint n = u_pass.camera_rays;
    if (i == 0u) {
        cv_prepare_iteration(n);
        q.count[CV_Q_SHADOW] = 0u;
        q.count[CV_Q_TICKET_INTERSECT] = 0u;
        q.count[CV_Q_TICKET_SHADE] = 0u;
    }
    if (i >= n)
        return;
    uint pixels = u_pass.n_pixels;
    uint sample_index = u_pass.first_sample + i / pixels;
    uint path = (sample_index % u_pass.paths_per_pixel) * pixels + i % pixels;
    // iteration 0 reads the odd half
    rays[cv_capacity() + i] = cv_camera_sample(path, sample_index);
}
