// glsl/trace/regenerate.glsl: camera rays, one per pixel sample; each sample
// adds its filter weight (+1 or -1, filter.glsl) to its path slot's film
// entry, and every radiance or AOV value the path adds is weighted by it.
// The pass's first samples come from trace/generate.comp; every later one
// from the stage that ends the slot's previous path (intersect or escaped
// for a miss, shade otherwise: path regeneration, trace.h), which queues
// the new camera ray among the next iteration's rays in place of a bounce
// ray. That was a stage of its own over a queue of the pixels whose paths
// ended: a dispatch and a queue pass per iteration for a small wave
// (bench/RESULTS.md, "Figures behind the code").
// Include after common.glsl and sampler.glsl.
#ifndef CV_TRACE_REGENERATE_GLSL
#define CV_TRACE_REGENERATE_GLSL

#include "camera.glsl"
#include "path_time.glsl"

// Sample `sample_index` of the pixel of path slot `path`: its camera ray;
// the slot's film entry counts the sample's weight and records it, with
// the weight, as the path in flight.
CvRayItem cv_camera_sample(uint path, uint sample_index)
{
    uint i = cv_path_pixel(path), cw = u_pass.crop_w;
    uvec2 px = uvec2(i % cw, i / cw) + u_pass.film.zw;
    uint film_pixel = px.y * u_pass.film.x + px.x;
    uvec2 seed = uvec2(u_pass.seed_lo, u_pass.seed_hi);
    uint sampler = u_pass.sampler;
    vec2 uf = cv_sample_2d(film_pixel, sample_index, 0u, seed, sampler);
    vec2 ul = cv_sample_2d(film_pixel, sample_index, 1u, seed, sampler);
    float w;
    vec2 raster = vec2(px) + 0.5 + cv_filter_sample(uf, w);
    float ut = cv_time_sampled() ? cv_time_u(film_pixel, sample_index) : 0.0;
    vec3 o, d;
    cv_camera_ray(raster, ul, ut, o, d);
    CvRayItem r;
    r.o = vec4(o, float(path));
    r.d = vec4(d, 0.0);
    r.beta = vec4(1.0, 1.0, 1.0, cv_ray_meta_in(0u, 0u, u_pass.camera_medium));
    film[path].L.w += w;
    film[path].normal.w = w * (float(sample_index) + 1.0);
    return r;
}

// The path in slot `path` has ended: the camera ray of the slot's next
// sample (K on from this one, trace.h), if the pass has it (the return
// value says whether r is set).
bool cv_regenerate(uint path, out CvRayItem r)
{
    uint next = cv_path_sample(path) + u_pass.paths_per_pixel;
    if (next >= u_pass.end_sample)
        return false;
    r = cv_camera_sample(path, next);
    return true;
}

#endif
