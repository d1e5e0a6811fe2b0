/* glsl/shared/guide_choice.h: what the host (src/trace/guide_choice.c) and
 * glsl/trace/guide_choice.comp share: the estimate of a sampling
 * strategy's error a sample from two sub-passes' film increments. */
#ifndef CV_SHARED_GUIDE_CHOICE_H
#define CV_SHARED_GUIDE_CHOICE_H

#include "shared/common.h"
#include "shared/bindings.h"

/* The relative squared error's offset: a pixel channel's error d counts
 * d^2 / (mean^2 + CV_RELMSE_EPS), so that dark pixels do not dominate; the
 * benchmarks' relMSE (bench/cavalry_bench.c) weighs it so too, and the
 * choice estimates what they measure. */
#define CV_RELMSE_EPS 1e-2

/* Invocations per group of the reduction; the group's sum is one float of
 * CV_BIND_CHOICE_SUMS. */
#define CV_CHOICE_GROUP 64

#endif
