// glsl/trace/surface_inputs.glsl: what the shade stages (trace/shade.comp,
// trace/rlpath/shade.comp) build the same way at a hit: a bounce's sample
// values, keyed by film pixel (common.glsl), and the shading point the
// BSDF takes. Shared so the integrators consume the same sample dimensions
// and stay comparable pixel for pixel. Include after sampler.glsl, geometry.glsl
// and materials.glsl.
#ifndef CV_TRACE_SURFACE_INPUTS_GLSL
#define CV_TRACE_SURFACE_INPUTS_GLSL

// Dimension pair `which` (CV_PAIR_*) of the bounce at `depth` of the path
// in flight in slot `path`: its pixel's sample, whichever slot runs it.
vec2 cv_bounce_2d(uint path, uint depth, uint which)
{
    return cv_sample_2d(cv_film_pixel(cv_path_pixel(path)), cv_path_sample(path),
                        2u + depth * CV_PAIRS_PER_BOUNCE + which, uvec2(u_pass.seed_lo, u_pass.seed_hi), u_pass.sampler);
}

CvShadingPoint cv_shading_point(CvSurface sf, bool front)
{
    CvShadingPoint sp;
    sp.p = sf.p;
    sp.ng = sf.ng;
    sp.ns = sf.ns;
    sp.dpdu = sf.dpdu;
    sp.uv = sf.uv;
    sp.front = front;
    return sp;
}

#endif
