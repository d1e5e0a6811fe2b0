// glsl/trace/path_time.glsl: the time of a path (pbrt-v4's CameraSample
// time: shutter open to close by one sample dimension). The camera ray
// draws it (regenerate.glsl); the stages that trace a path's later rays,
// or build the surface of a moving shape it hit, draw it again from the
// path's pixel and sample rather than carry it in every queue item, so
// every ray of a path, shadow rays too, sees the scene at one time.
// Include after common.glsl and sampler.glsl.
#ifndef CV_TRACE_PATH_TIME_GLSL
#define CV_TRACE_PATH_TIME_GLSL

// Whether rays carry a time: a moving camera, or moving shapes.
bool cv_time_sampled()
{
#ifdef CV_HAS_MOTION
    return true;
#else
    return u_pass.cam_moves.x != 0u;
#endif
}

// The uniform sample of the time of sample `sample_index` of a film pixel.
float cv_time_u(uint film_pixel, uint sample_index)
{
    return cv_sample_2d(film_pixel, sample_index, CV_PAIR_CAMERA_TIME,
                        uvec2(u_pass.seed_lo, u_pass.seed_hi), u_pass.sampler).x;
}

// The time of the path in flight in slot `path` (before its slot moves on
// to its next sample).
float cv_path_time(uint path)
{
    float u = cv_time_u(cv_film_pixel(cv_path_pixel(path)), cv_path_sample(path));
    return mix(u_pass.cam_time.x, u_pass.cam_time.y, u);
}

#endif
