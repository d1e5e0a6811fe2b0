/* bdpt.h: the host side of the bdpt integrator (bidirectional path
 * tracing, pbrt-v4's BDPTIntegrator; glsl/trace/bdpt/bdpt.comp): its
 * buffers, the subpath vertex store (glsl/shared/bdpt.h) and the splat
 * film that light tracing adds to, and its entry in the integrator table
 * (integrator.h). The renderer runs its kernel once per round of samples
 * instead of the wavefront stages (cv_integrator_ops.whole_samples). */
#ifndef CV_TRACE_BDPT_H
#define CV_TRACE_BDPT_H

#include "trace/integrator.h"

extern const struct cv_integrator_ops cv_bdpt_ops;

#endif
