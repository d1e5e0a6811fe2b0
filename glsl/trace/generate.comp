#version 450
// glsl/trace/generate.comp: camera rays, one per pixel sample; each sample
// adds weight 1 to its pixel (filter importance sampling).
// GENERATE_MODE 0 starts a pass: the pass's first sample of every pixel of
// the crop, written as the first iteration's input. GENERATE_MODE 1 runs at
// the end of every iteration over the done queue: a pixel whose path ended
// starts its next sample, if the pass has one left, among the rays of the
// next iteration (see trace.h on regeneration).
#include "shared/trace.h"
layout(local_size_x = CV_TRACE_GROUP) in;
#include "common.glsl"
#include "sampler.glsl"
#include "camera.glsl"

CvRayItem cv_camera_sample(uint i, uint sample_index)
{
    uint cw = u_pass.frame.y;
    uvec2 px = uvec2(i % cw, i / cw) + u_pass.film.zw;
    uint film_pixel = px.y * u_pass.film.x + px.x;
    uvec2 seed = u_pass.seed.xy;
    uint sampler = u_pass.seed.z;
    vec2 uf = cv_sample_2d(film_pixel, sample_index, 0u, seed, sampler);
    vec2 ul = cv_sample_2d(film_pixel, sample_index, 1u, seed, sampler);
    vec2 raster = vec2(px) + 0.5 +
                  vec2(cv_filter_offset(uf.x, u_pass.pixel_filter.x, false),
                       cv_filter_offset(uf.y, u_pass.pixel_filter.y, true));
    vec3 o, d;
    cv_camera_ray(raster, ul, o, d);
    CvRayItem r;
    r.o = vec4(o, float(i));
    r.d = vec4(d, 0.0);
    r.beta = vec4(1.0, 1.0, 1.0, cv_ray_meta(0u, 0u));
    film[i].L.w += 1.0;
    film[i].normal.w = float(sample_index);
    return r;
}

void main()
{
    uint i = cv_global_index();
#if GENERATE_MODE == 0
    uint n = u_pass.frame.x;
    if (i == 0u)
        q.count[CV_Q_RAYS_OUT] = n;
    if (i >= n)
        return;
    // iteration 0 reads the odd half
    rays[cv_capacity() + i] = cv_camera_sample(i, u_pass.frame.w);
#else
    bool push = false;
    uint pixel = 0u, next = 0u;
    if (i < q.count[CV_Q_DONE]) {
        pixel = cv_done_pixel(i);
        next = cv_pixel_sample(pixel) + 1u;
        push = next < u_pass.misc.w;
    }
    uint slot = cv_queue_slots(push, CV_Q_RAYS_OUT, false, CV_Q_RAYS_OUT).x;
    if (push)
        cv_ray_out(slot, cv_camera_sample(pixel, next));
#endif
}
