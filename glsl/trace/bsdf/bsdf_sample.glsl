// glsl/trace/bsdf/bsdf_sample.glsl: the result of sampling a BSDF lobe and its
// flags. Lobes fill it with local-frame directions; cv_bsdf_sample turns wi
// into world space.
#ifndef CV_BSDF_SAMPLE_GLSL
#define CV_BSDF_SAMPLE_GLSL

#define CV_BSDF_REFLECTION 1u
#define CV_BSDF_TRANSMISSION 2u
#define CV_BSDF_SPECULAR 4u   // delta lobe: f and pdf carry the same delta

// f includes no cosine; pdf is per solid angle (for SPECULAR: the discrete
// probability of having picked that lobe, with f = value / |cos wi|).
struct CvBsdfSample { vec3 wi; vec3 f; float pdf; uint flags; };

#endif
