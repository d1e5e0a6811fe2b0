// glsl/trace/camera.glsl: camera rays by the conventions of CvCamera
// (glsl/shared/scene.h); the pixel filter's offsets come from filter.glsl.
#ifndef CV_TRACE_CAMERA_GLSL
#define CV_TRACE_CAMERA_GLSL

#include "../lib/sampling.glsl"
#include "../shared/scene.h"
#include "filter.glsl"

// Raster position (full film pixels) to a world-space ray.
void cv_camera_ray(vec2 raster, vec2 u_lens, out vec3 o, out vec3 d)
{
    vec4 s = u_pass.screen;
    vec2 film = vec2(u_pass.film.xy);
    float sx = s.x + (raster.x / film.x) * (s.y - s.x);
    float sy = s.w - (raster.y / film.y) * (s.w - s.z);
    vec3 oc, dc;
    if (u_pass.orthographic == 1.0) { // orthographic
        oc = vec3(sx, sy, 0.0);
        dc = vec3(0.0, 0.0, 1.0);
    } else {
        oc = vec3(0.0);
        dc = normalize(vec3(sx * u_pass.tan_half_fov, sy * u_pass.tan_half_fov, 1.0));
    }
    if (u_pass.lens_radius > 0.0) {
        vec2 pl = u_pass.lens_radius * cv_sample_disk_concentric(u_lens);
        float ft = u_pass.focal_distance / dc.z;
        vec3 pf = oc + dc * ft;
        oc = vec3(oc.xy + pl, 0.0);
        dc = normalize(pf - oc);
    }
    mat3 r = mat3(u_pass.cam_to_world[0].xyz, u_pass.cam_to_world[1].xyz,
                  u_pass.cam_to_world[2].xyz); // columns are the rows: use transpose
    r = transpose(r);
    o = r * oc + vec3(u_pass.cam_to_world[0].w, u_pass.cam_to_world[1].w, u_pass.cam_to_world[2].w);
    d = normalize(r * dc);
}

#endif
