#version 450
// glsl/trace/escaped.comp: rays that left the scene pick up environment
// light, MIS-weighted against the light sampling that could have found the
// same direction (not for camera rays or after specular bounces).
#include "shared/trace.h"
layout(local_size_x = CV_TRACE_GROUP) in;
#include "common.glsl"
#include "shading.glsl"

void main()
{
    uint i = cv_global_index();
    if (i >= q.count[CV_Q_ESCAPED])
        return;
    CvRayItem r = rays_in[escaped[i]];
    uint pixel = uint(r.o.w);
    uint flags = uint(r.beta.w);
    vec3 Le = cv_env_Le(r.d.xyz);
    if (cv_max3(Le) <= 0.0)
        return;
    float w = 1.0;
    if (cv_depth() > 0u && (flags & CV_RAYF_SPECULAR) == 0u)
        w = cv_power_heuristic(r.d.w, cv_env_pdf(r.d.xyz));
    cv_film_add(pixel, r.beta.rgb * Le * w);
}
