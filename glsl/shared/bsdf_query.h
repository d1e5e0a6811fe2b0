/* glsl/shared/bsdf_query.h: what a path vertex asks of its BSDF in one
 * query (glsl/trace/bsdf/bsdf_query.glsl, CvBsdfQuery.ask), shared with the
 * tests that ask the shipped GLSL (tests/trace/bsdf_probe.h). */
#ifndef CV_SHARED_BSDF_QUERY_H
#define CV_SHARED_BSDF_QUERY_H

#define CV_BQ_F0 1u       /* f at wi0 */
#define CV_BQ_PDF0 2u     /* pdf at wi0 */
#define CV_BQ_SAMPLE 4u   /* a direction drawn with (uc, u), into s */
/* f and pdf at wi1: only in kernels that define CV_BQ_WI1 (bsdf.glsl) */
#define CV_BQ_F1 16u
#define CV_BQ_PDF1 32u
/* The pdf at wi0 (GATE1: at wi1), asked with the f there, only where that
 * f is not 0 (else 0): a light sample that carries nothing skips the coated
 * pdf estimate. */
#define CV_BQ_GATE0 64u
#define CV_BQ_GATE1 128u
/* The sample is wanted only where it takes a delta lobe (a guided bounce
 * lets the BSDF pick its lobe first): a coated walk's other samples keep
 * their proportional pdf, not restated by a pdf estimate. */
#define CV_BQ_DELTA_ONLY 256u

#endif
