// glsl/trace/camera.glsl: camera rays by the conventions of CvCamera
// (glsl/shared/scene.h); the pixel filter's offsets come from filter.glsl.
#ifndef CV_TRACE_CAMERA_GLSL
#define CV_TRACE_CAMERA_GLSL

#include "../lib/quaternion.glsl"
#include "../lib/sampling.glsl"
#include "../shared/scene.h"
#include "filter.glsl"

// Camera space to world space at the time of sample u_time (a point when
// w is 1, a direction when 0): cam_to_world for a still camera; for a
// moving one pbrt-v4's AnimatedTransform at time lerp(u_time, shutter
// open, close) clamped to the transforms' times (CvPassParams.cam_*).
vec3 cv_camera_to_world(vec3 v, float w, float u_time)
{
    if (u_pass.cam_moves.x == 0u) {
        mat3 r = transpose(mat3(u_pass.cam_to_world[0].xyz, u_pass.cam_to_world[1].xyz,
                                u_pass.cam_to_world[2].xyz)); // the rows
        return r * v + w * vec3(u_pass.cam_to_world[0].w, u_pass.cam_to_world[1].w,
                                u_pass.cam_to_world[2].w);
    }
    vec4 tm = u_pass.cam_time;
    float time = mix(tm.x, tm.y, u_time);
    float dt = time <= tm.z ? 0.0 : time >= tm.w ? 1.0 : (time - tm.z) / (tm.w - tm.z);
    vec3 sv = vec3(dot(mix(u_pass.cam_S[0].xyz, u_pass.cam_S[3].xyz, dt), v),
                   dot(mix(u_pass.cam_S[1].xyz, u_pass.cam_S[4].xyz, dt), v),
                   dot(mix(u_pass.cam_S[2].xyz, u_pass.cam_S[5].xyz, dt), v));
    vec3 rv = cv_quat_rotate(cv_quat_slerp(dt, u_pass.cam_R[0], u_pass.cam_R[1]), sv);
    return rv + w * mix(u_pass.cam_T[0].xyz, u_pass.cam_T[1].xyz, dt);
}

// Raster position (full film pixels) to a world-space ray, at the time of
// the uniform u_time (unused by a still camera).
void cv_camera_ray(vec2 raster, vec2 u_lens, float u_time, out vec3 o, out vec3 d)
{
    vec4 s = u_pass.screen;
    vec2 film = vec2(u_pass.film.xy);
#if defined(CV_SPHERICAL_CAMERA) || defined(CV_EVERY_CAMERA)
    if (u_pass.camera_type >= CV_CAMERA_EQUAL_AREA) { // spherical: no lens
        vec2 uv = raster / film;
        vec3 w;
        if (u_pass.camera_type == CV_CAMERA_EQUAL_AREA) {
            w = cv_equal_area_square_to_sphere(cv_equal_area_wrap(uv));
        } else {
            float theta = CV_PI * uv.y, phi = 2.0 * CV_PI * uv.x;
            w = vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
        }
        o = cv_camera_to_world(vec3(0.0), 1.0, u_time);
        d = normalize(cv_camera_to_world(w.xzy, 0.0, u_time));
        return;
    }
#endif
    float sx = s.x + (raster.x / film.x) * (s.y - s.x);
    float sy = s.w - (raster.y / film.y) * (s.w - s.z);
    vec3 oc, dc;
    if (u_pass.camera_type == CV_CAMERA_ORTHOGRAPHIC) {
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
    o = cv_camera_to_world(oc, 1.0, u_time);
    d = normalize(cv_camera_to_world(dc, 0.0, u_time));
}

#endif
