#version 450
#extension GL_NV_shader_atomic_float : enable
// glsl/trace/rlpath/sd_flush.comp: splats a path slot's last finished
// path's records into the statistics of the tree rlpath's sdtree method
// trains (sdtree.glsl: cv_sd_flush). Two builds:
// - at the end of a training iteration, one invocation per slot: every
//   slot's last path;
// - CV_SD_FLUSH_RAYS, the renderer's splat stage (trace/render.c), before
//   the intersect stage of each iteration of a pass that learns, one
//   invocation per ray of the iteration: a camera ray's slot's path before,
//   whose shadow rays are done by then. The splat lives here, not in the
//   shade bins and the escaped stage, whose builds its code would lengthen
//   (bench/RESULTS.md, "sdtree's splat moved from the shade bins").
#include "shared/trace.h"
#ifdef CV_SD_FLUSH_RAYS
layout(local_size_x = CV_TRACE_GROUP) in;   // the ray queue's dispatch
#else
layout(local_size_x = 64) in;
#endif
// (outside the #ifdef: the expander pastes a file once, at its first
// #include, which common.glsl repeats)
#include "../../lib/index.glsl"
#ifdef CV_SD_FLUSH_RAYS
#include "../common.glsl"
#endif
#define CV_SD_RECORD
#define CV_SD_SPLAT
#include "sdtree.glsl"

void main()
{
#ifdef CV_SD_FLUSH_RAYS
    uint i = cv_global_index();
    if (i < q.count[CV_Q_RAYS_IN]) {
        CvRayItem r = cv_ray_in(i);
        if (cv_ray_depth(r) == 0u)
            cv_sd_flush(uint(r.o.w));
    }
#else
    uint slot = cv_global_index();
    if (slot < u_sd.learn.z)
        cv_sd_flush(slot);
#endif
}
