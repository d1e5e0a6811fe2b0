// glsl/trace/medium/random.glsl: the random numbers of media, for path's
// tracking (track.glsl) and bdpt's (bdpt/media.glsl): hashed, since the
// Sobol dimensions of a bounce are taken, and keyed like every other number
// by film pixel fp, sample and the job's seed. Include after sampler.glsl
// (cv_hash, cv_hash4, cv_uint_to_unit) and the u_pass block.
#ifndef CV_TRACE_MEDIUM_RANDOM_GLSL
#define CV_TRACE_MEDIUM_RANDOM_GLSL

// Stretch k of the tracking at vertex `vertex` (path's depth, or bdpt's
// key of subpath and vertex).
float cv_medium_u(uint fp, uint sample_index, uint vertex, uint k)
{
    return cv_uint_to_unit(cv_hash4(fp ^ u_pass.seed_lo, sample_index ^ cv_hash(u_pass.seed_hi),
                                    vertex, 0x4d454449u + k));
}

// The hero channel (0, 1 or 2), fixed for a path, or for one of bdpt's
// subpaths (side 0: the camera's, 1: the light's).
uint cv_medium_hero_channel(uint fp, uint sample_index, uint side)
{
    uint h = cv_hash4(fp ^ u_pass.seed_lo, sample_index ^ cv_hash(u_pass.seed_hi), 0x68e31da4u, side);
    return min(uint(cv_uint_to_unit(h) * 3.0), 2u);
}

#endif
