#version 450
// glsl/trace/guide_choice.comp: the film measured for the guide's choice
// after training (src/trace/guide_choice.c). Without CV_CHOICE_REDUCE:
// each pixel's sums over its K slots (radiance, weight) into third u_third
// of `pixels`. With it: a strategy's relative squared error a sample,
// summed over each group's pixels and channels, from two sub-passes of
// u_spp_a and u_spp_b samples: third u_before holds the sums before the
// first, third 1 those between them, the film those after the second.
// Their increments a and b are independent estimates of the pixel, so
// (a - b)^2 has the mean s^2 (1 / u_spp_a + 1 / u_spp_b), s^2 being one
// sample's variance; each pixel channel adds s^2 over its mean's square
// plus CV_RELMSE_EPS. The mean is the film's at the end of training
// (third 0), the same for both strategies and independent of their
// samples: one that held them would be low where they came out low and
// weigh their error more, the more so the noisier they are, and one taken
// later for the second strategy, from more samples, would weigh its error
// less. The filter's mean weight is the whole film's. A large film is
// measured on every u_stride-th group of its pixels (guide_choice.c:
// MAX_GROUPS): u_measured places, group q of them the film's group
// q * u_stride.
#include "shared/trace.h"
#include "shared/guide_choice.h"
layout(local_size_x = CV_CHOICE_GROUP) in;
#include "common.glsl"

layout(std430, binding = CV_BIND_CHOICE_PIXELS) buffer CvChoicePixels { vec4 pixels[]; };
layout(location = 4) uniform uint u_stride;
layout(location = 5) uniform uint u_measured;
#ifdef CV_CHOICE_REDUCE
layout(std430, binding = CV_BIND_CHOICE_SUMS) writeonly buffer CvChoiceSums { float sums[]; };
layout(location = 0) uniform uint u_spp_a;
layout(location = 1) uniform uint u_spp_b;
layout(location = 2) uniform uint u_spp_total;   // the film's samples a pixel
layout(location = 3) uniform uint u_before;
shared float s_sum[CV_CHOICE_GROUP];
#else
layout(location = 0) uniform uint u_third;
#endif

vec4 pixel_sums(uint i)
{
    vec4 f = vec4(0.0);
    for (uint k = 0u; k < u_pass.paths_per_pixel; k++)
        f += film[k * u_pass.n_pixels + i].L;
    return f;
}

void main()
{
    uint j = cv_global_index(), m = u_measured;
    uint i = (j / CV_CHOICE_GROUP) * u_stride * CV_CHOICE_GROUP + j % CV_CHOICE_GROUP;
    bool in_film = j < m && i < u_pass.n_pixels;
#ifndef CV_CHOICE_REDUCE
    if (in_film)
        pixels[u_third * m + j] = pixel_sums(i);
#else
    float e = 0.0;
    if (in_film) {
        vec4 f = pixel_sums(i), t = pixels[j], s0 = pixels[u_before * m + j], s1 = pixels[m + j];
        // the filter's mean weight: a sub-pass's radiance sum over its
        // samples and this estimate the pixel
        float w = f.w / float(u_spp_total);
        if (t.w > 0.0 && w > 0.0) {
            vec3 m = t.rgb / t.w;
            vec3 a = (s1.rgb - s0.rgb) / (float(u_spp_a) * w);
            vec3 b = (f.rgb - s1.rgb) / (float(u_spp_b) * w);
            vec3 d = a - b;
            float pair = 1.0 / float(u_spp_a) + 1.0 / float(u_spp_b);
            vec3 r = d * d / (pair * (m * m + CV_RELMSE_EPS));
            float sum = r.x + r.y + r.z;
            e = isinf(sum) || isnan(sum) ? 0.0 : sum;
        }
    }
    s_sum[gl_LocalInvocationID.x] = e;
    barrier();
    for (uint h = CV_CHOICE_GROUP / 2u; h > 0u; h /= 2u) {
        if (gl_LocalInvocationID.x < h)
            s_sum[gl_LocalInvocationID.x] += s_sum[gl_LocalInvocationID.x + h];
        barrier();
    }
    // (a group's first index over the group size: its place however the
    // dispatch was split, index.glsl; the split's spare groups write none)
    if (gl_LocalInvocationID.x == 0u && j < m)
        sums[j / CV_CHOICE_GROUP] = s_sum[0];
#endif
}
