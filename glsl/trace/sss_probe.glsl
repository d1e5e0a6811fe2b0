// glsl/trace/sss_probe.glsl: the intersect stage's side of the subsurface
// material (CV_HAS_SUBSURFACE; sss_vertex.glsl makes the probes): a probe
// segment is traced for every surface along it, as pbrt-v4's volpath
// does (closest hits from its start to its end, one after the other), and
// of those whose material is the probe's one is kept, each with the same
// probability (a reservoir of one), with their count for the exit's
// density. Include after tracing.glsl, geometry.glsl and sampler.glsl.
#ifndef CV_TRACE_SSS_PROBE_GLSL
#define CV_TRACE_SSS_PROBE_GLSL

// Surfaces a probe looks at, at most: beyond, the rest of the segment is
// not searched (a probe crosses its material's boundary a few times in
// any scene of ordinary geometry).
#define CV_SSS_PROBE_HITS 64u

// The probe segment r (CV_RAYF_PROBE): h is the chosen exit (prim
// CV_HIT_PROBE_MISS for none) and n the candidates' count.
void cv_sss_probe_trace(CvRayItem r, out CvHit h, out uint n)
{
    h = CvHit(0.0, CV_HIT_PROBE_MISS, 0.0, 0.0);
    n = 0u;
#ifndef CV_EMPTY_SCENE
    uint material = uint(r.d.w);
    uint path = uint(r.o.w);
    uint pixel = cv_film_pixel(cv_path_pixel(path)), index = cv_path_sample(path);
    uint depth = cv_ray_depth(r);
    float tmin = 0.0;
    for (uint k = 0u; k < CV_SSS_PROBE_HITS; k++) {
        CvHit c;
        if (!cv_trace_closest(r.o.xyz, r.d.xyz, tmin, 1.0, c))
            break;
        if ((cv_prim_word(c.prim) & CV_TRI_MATERIAL_MASK) == material) {
            n++;
            // keyed by film pixel and sample, as the alpha tests
            float u = cv_uint_to_unit(cv_hash4(pixel, index, 0x55535353u + k * 4096u + depth, u_pass.seed_lo));
            if (u * float(n) < 1.0)
                h = c;
        }
        tmin = c.t * (1.0 + 1e-5) + 1e-6;
    }
#endif
}

#endif
