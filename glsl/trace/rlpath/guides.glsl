// glsl/trace/rlpath/guides.glsl: where rlpath guides at all (both methods,
// shade.comp and sd_shade.comp). Include after materials.glsl.
#ifndef CV_RLPATH_GUIDES_GLSL
#define CV_RLPATH_GUIDES_GLSL

#include "shared/rlpath.h"   // CV_RL_GLOSSY_ALPHA

// Whether the learned distribution (incident radiance) suits
// this BSDF: it stands for the reflected integrand of a diffuse lobe, and
// glossy lobes (conductors, dielectrics below CV_RL_GLOSSY_ALPHA) put their
// value where it does not look, so guided directions there mostly carry
// nothing. Their guiding weight is 0: BSDF sampling alone, as at a delta
// lobe. The weight is a function of the hit, so the mixture pdf stays exact.
bool cv_rl_guides(CvBsdf b)
{
#ifdef CV_BSDF_BASIC
    return true;   // diffuse, or a mirror (delta: not guided anyway)
#else
    uint t = CV_BSDF_TYPE(b);   // a constant in the diffuse build
    if (t == CV_MAT_DIFFUSE || t == CV_MAT_COATED_DIFFUSE ||
        t == CV_MAT_DIFFUSE_TRANSMISSION || t == CV_MAT_PLASTIC)
        return true;
    if (t == CV_MAT_CONDUCTOR || t == CV_MAT_DIELECTRIC)
        return min(b.alpha.x, b.alpha.y) >= CV_RL_GLOSSY_ALPHA;
    if (t == CV_MAT_COATED_CONDUCTOR)
        return min(min(b.alpha.x, b.alpha.y), min(b.alpha.z, b.alpha.w)) >= CV_RL_GLOSSY_ALPHA;
    return false;
#endif
}

#endif
