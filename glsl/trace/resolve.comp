#version 450
// glsl/trace/resolve.comp: the film as linear RGB (radiance sum over
// weight sum, as pbrt-v4's RGBFilm divides; a filter's negative lobes may
// make either negative; alpha 1), one vec4 per pixel of the crop,
// row-major, top row first; a pixel's sums are those of its K path slots,
// added in slot order so the result does not depend on how the render was
// split into passes. With CV_FILM_TRANSPARENT (a job with alpha; the host
// defines CV_MATTE_STRIDE too) alpha is the coverage (glsl/shared/trace.h,
// summed with the same signed filter weights) over the weight sum, and the
// colour is premultiplied by it, since the environment seen directly adds
// nothing (escaped.comp); CV_RESOLVE_STRAIGHT divides it out again for the
// display transform (PNG has straight alpha), black where alpha is 0.
#include "shared/trace.h"
layout(local_size_x = CV_TRACE_GROUP) in;
#include "common.glsl"

layout(std430, binding = CV_BIND_RESOLVED) writeonly buffer CvResolved { vec4 resolved[]; };
#ifdef CV_FILM_TRANSPARENT
layout(std430, binding = CV_BIND_MATTE) readonly buffer CvMatte { uint matte[]; };
#endif
#ifdef CV_BDPT_SPLAT
#include "shared/bdpt.h"
// bdpt's light tracing (glsl/shared/bdpt.h): already weighed as the
// radiance sum is, so it joins that sum
layout(std430, binding = CV_BIND_BDPT_SPLAT) readonly buffer CvBdptSplat { float splat[]; };
#endif

void main()
{
    uint i = cv_global_index();
    uint pixels = u_pass.n_pixels;
    if (i >= pixels)
        return;
    vec4 f = film[i].L;
    float a = 1.0;
#ifdef CV_FILM_TRANSPARENT
    float c = uintBitsToFloat(matte[i * CV_MATTE_STRIDE + CV_MATTE_COVERAGE]);
#endif
    for (uint k = 1u; k < u_pass.paths_per_pixel; k++) {
        f += film[k * pixels + i].L;
#ifdef CV_FILM_TRANSPARENT
        c += uintBitsToFloat(matte[(k * pixels + i) * CV_MATTE_STRIDE + CV_MATTE_COVERAGE]);
#endif
    }
#ifdef CV_BDPT_SPLAT
    uint at = CV_BDPT_SPLAT_HEADER + 3u * i;
    f.rgb += vec3(splat[at], splat[at + 1u], splat[at + 2u]);
#endif
#ifdef CV_FILM_TRANSPARENT
    a = f.w != 0.0 ? c / f.w : 0.0;
#endif
    vec3 rgb = f.w != 0.0 ? f.rgb / f.w : vec3(0.0);
#ifdef CV_RESOLVE_STRAIGHT
    rgb = a != 0.0 ? rgb / a : vec3(0.0);
#endif
    resolved[i] = vec4(rgb, a);
}
