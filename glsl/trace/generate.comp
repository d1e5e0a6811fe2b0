#version 450
// glsl/trace/generate.comp: one camera ray per pixel of the crop for the
// current sample index, written to the output ray queue; each adds weight 1
// to its pixel (filter importance sampling).
#include "shared/trace.h"
layout(local_size_x = CV_TRACE_GROUP) in;
#include "common.glsl"
#include "sampler.glsl"
#include "camera.glsl"

void main()
{
    uint i = cv_global_index();
    uint n = u_pass.frame.x;
    if (i == 0u)
        q.count[CV_Q_RAYS_OUT] = n;
    if (i >= n)
        return;
    uint cw = u_pass.frame.y;
    uvec2 px = uvec2(i % cw, i / cw) + u_pass.film.zw;
    uint film_pixel = px.y * u_pass.film.x + px.x;
    uvec2 seed = u_pass.seed.xy;
    uint sampler = u_pass.seed.z;
    vec2 uf = cv_sample_2d(film_pixel, cv_sample_index(), 0u, seed, sampler);
    vec2 ul = cv_sample_2d(film_pixel, cv_sample_index(), 1u, seed, sampler);
    vec2 raster = vec2(px) + 0.5 +
                  vec2(cv_filter_offset(uf.x, u_pass.pixel_filter.x, false),
                       cv_filter_offset(uf.y, u_pass.pixel_filter.y, true));
    vec3 o, d;
    cv_camera_ray(raster, ul, o, d);
    CvRayItem r;
    r.o = vec4(o, float(i));
    r.d = vec4(d, 0.0);
    r.beta = vec4(1.0, 1.0, 1.0, float(0u));
    rays_out[i] = r;
    film[i].w += 1.0;
}
