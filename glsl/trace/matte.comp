#version 450
// glsl/trace/matte.comp: coverage and ID mattes (matte.glsl) at the first
// hit of every camera ray. Runs after the intersect stage, over its hits,
// only for jobs that ask for alpha or ID AOVs, so that the other stages
// stay as they are.
#include "shared/trace.h"
layout(local_size_x = CV_TRACE_GROUP) in;
#include "common.glsl"
#include "../bvh/mesh_buffers.glsl"
#include "../bvh/curves.glsl"
#include "matte.glsl"

void main()
{
    uint i = cv_global_index();
    if (i >= cv_hit_count())
        return;
    CvHitItem h = hits[cv_hit_slot(i)];
    CvRayItem r = cv_ray_in(h.ray);
    if (cv_ray_depth(r) != 0u || (cv_ray_flags(r) & CV_RAYF_PROBE) != 0u)  // a probe: no camera ray
        return;
    cv_matte_first_hit(uint(r.o.w), h.prim);
}
