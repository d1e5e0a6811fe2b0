// glsl/trace/rlpath/guides.glsl: where rlpath guides at all (both methods,
// shade.comp and sd_shade.comp). Include after materials.glsl.
#ifndef CV_RLPATH_GUIDES_GLSL
#define CV_RLPATH_GUIDES_GLSL

#include "shared/rlpath.h"   // the types served, CV_RL_GLOSSY_ALPHA

// Whether the learned distribution (incident radiance) suits
// this BSDF: it stands for the reflected integrand of a diffuse lobe, and
// glossy lobes (conductors, dielectrics below CV_RL_GLOSSY_ALPHA) put their
// value where it does not look, so guided directions there mostly carry
// nothing. Their guiding weight is 0: BSDF sampling alone, as at a delta
// lobe. Nor does either method guide in the coated walk's bin
// (trace/shade_bins.h: the materials that may take the layered walk, and
// mixes holding them): guiding there cost that kernel more time than it
// saved error (bench/RESULTS.md, "sdtree without guiding the coated
// walk"). Nor in a bin none of whose materials is of a type served
// (CV_RL_UNGUIDED, as the host finds: trace/shade_bins.h,
// cv_shade_bins_guided). Either way the bin's build holds none of the
// guide's lookups. The weight is a function of the hit, so the mixture pdf
// stays exact.
bool cv_rl_guides(CvBsdf b)
{
#if defined(CV_RL_UNGUIDED) || (defined(CV_SHADE_BIN) && CV_SHADE_BIN == 2)
    return false;
#elif defined(CV_BSDF_BASIC)
    return true;   // diffuse, or a mirror (delta: not guided anyway)
#else
    uint t = CV_BSDF_TYPE(b);   // a constant in the diffuse build
    if (CV_RL_DIFFUSE_LIKE(t))
        return true;
    if (CV_RL_GUIDED_WHERE_ROUGH(t))
        return min(b.alpha.x, b.alpha.y) >= CV_RL_GLOSSY_ALPHA;
    return false;   // (a coated conductor: the coated walk's bin)
#endif
}

// The one-sample mixture's draw, both methods' (cv_strategy_ask): u_bsdf.x
// picks the guide with probability m and, rescaled, drives the strategy it
// picks. A guided draw still lets the BSDF pick its lobe (by u_bc.x, as a
// BSDF draw does) and keeps a delta lobe it picks, so a delta lobe has the
// BSDF's probability whatever m. Returns whether the bounce is guided and
// sets what q asks: the BSDF's sample; or, guided, f and pdf at q.wi1
// (which the caller draws from q.u), the pdf only where f is not 0 (a
// direction f is 0 at ends the path), and where the BSDF has a delta lobe
// (pd: its probability) the sample too, of which only a delta lobe it picks
// is kept.
bool cv_rl_mixture_ask(float m, float pd, vec2 u_bc, vec2 u_bsdf, inout CvBsdfQuery q)
{
    bool guided = m > 0.0 && u_bsdf.x < m;
    q.uc = u_bc.x;
    q.u = m > 0.0 ? vec2(min((guided ? u_bsdf.x : u_bsdf.x - m) / (guided ? m : 1.0 - m),
                             CV_ONE_MINUS_EPS),
                         u_bsdf.y)
                  : u_bsdf;
    if (!guided)
        q.ask |= CV_BQ_SAMPLE;
    else
        q.ask |= CV_BQ_F1 | CV_BQ_PDF1 | CV_BQ_GATE1 |
                 (pd > 0.0 ? CV_BQ_SAMPLE | CV_BQ_DELTA_ONLY : 0u);
    return guided;
}

#endif
