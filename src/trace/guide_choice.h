/* guide_choice.h: whether a guided integrator's passes after training pay
 * for their cost, measured on the render itself. Guiding saves error a
 * sample where light comes by few paths, and costs time a sample
 * everywhere (the guide's lookups); a scene lit directly renders cleaner
 * in the same time without it. After training the renderer runs four
 * sub-passes: two guided, two with path's programs. Each pair's film
 * increments estimate its strategy's relative squared error a sample
 * (glsl/trace/guide_choice.comp, weighed as the benchmarks' relMSE, by the
 * film's values at the end of training), summed over groups of pixels.
 * The second sub-pass of each pair is timed on the GPU (the first may wait
 * for a program's first use). Guiding renders the rest where its product
 * of error a sample and time a sample is the smaller by more than its
 * noise, which blocks of the groups measure (rare bright samples caught by
 * chance make it large); elsewhere path's programs, the cheaper a sample.
 * Every sub-pass's samples are unbiased and stay in the image.
 *
 * The choice rests on measured time, so two renders of the same job may
 * choose differently and differ in their noise (rlpath.fallback: false
 * keeps guiding, for renders equal bit for bit). */
#ifndef CV_TRACE_GUIDE_CHOICE_H
#define CV_TRACE_GUIDE_CHOICE_H

#include <stdbool.h>
#include <stdint.h>

#include "base/error.h"
#include "gpu/context.h"

struct cv_guide_choice;

/* The measure for a film of n_pixels pixels (the film and the pass
 * parameters are bound by the renderer), on at most max_groups groups of
 * CV_CHOICE_GROUP pixels spread over it (0: guide_choice.c's MAX_GROUPS;
 * tests ask for fewer). */
bool cv_guide_choice_create(struct cv_gpu *gpu, uint32_t n_pixels, uint32_t max_groups,
                            struct cv_guide_choice **out, struct cv_error *err);
/* Requests its programs beside the renderer's (gpu/program.h). */
void cv_guide_choice_request(struct cv_gpu *gpu);
/* Whether sub-passes remain, and whether the next one runs path's
 * programs. */
bool cv_guide_choice_pending(const struct cv_guide_choice *c);
bool cv_guide_choice_next_unguided(const struct cv_guide_choice *c);
/* Around each sub-pass: begin before it is queued, end after, with its
 * samples a pixel and the film's after it. */
bool cv_guide_choice_begin(struct cv_guide_choice *c, struct cv_error *err);
bool cv_guide_choice_end(struct cv_guide_choice *c, uint32_t spp, uint32_t spp_total,
                         struct cv_error *err);
/* Once no sub-pass remains: whether the passes after go on unguided. */
bool cv_guide_choice_unguided(const struct cv_guide_choice *c);

/* The figures of the choice once made, guided [0] and unguided [1]:
 * relative squared error a sample and GPU milliseconds a sample; and the
 * test's figure z (cv_guide_choice_decide). */
void cv_guide_choice_measures(const struct cv_guide_choice *c, double err[2], double ms[2],
                              double *z);

/* The decision from nb blocks' relative squared error a sample, guided (g)
 * and unguided (u) over the same pixels in each block, and the GPU
 * milliseconds a sample of each (ms_*): unguided unless guiding reaches
 * the same error in less time by more than a few standard errors of the
 * blocks' mean difference (guide_choice.c: Z; never with one block).
 * *z: that mean difference, guided's cost less unguided's, over its
 * standard error. */
bool cv_guide_choice_decide(const double *g, const double *u, uint32_t nb, double ms_g,
                            double ms_u, double *z);

/* Accepts NULL; clears the pointer. */
void cv_guide_choice_destroy(struct cv_guide_choice **c);

#endif
