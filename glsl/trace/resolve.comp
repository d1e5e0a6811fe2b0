#version 450
// glsl/trace/resolve.comp: the film as linear RGB (radiance sum over
// weight sum, as pbrt-v4's RGBFilm divides; a filter's negative lobes may
// make either negative; alpha 1), one vec4 per pixel of the crop,
// row-major, top row first; a pixel's sums are those of its K path slots,
// added in slot order so the result does not depend on how the render was
// split into passes.
#include "shared/trace.h"
layout(local_size_x = CV_TRACE_GROUP) in;
#include "common.glsl"

layout(std430, binding = CV_BIND_RESOLVED) writeonly buffer CvResolved { vec4 resolved[]; };

void main()
{
    uint i = cv_global_index();
    uint pixels = u_pass.n_pixels;
    if (i >= pixels)
        return;
    vec4 f = film[i].L;
    for (uint k = 1u; k < u_pass.paths_per_pixel; k++)
        f += film[k * pixels + i].L;
    resolved[i] = vec4(f.w != 0.0 ? f.rgb / f.w : vec3(0.0), 1.0);
}
