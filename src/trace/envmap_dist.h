/* envmap_dist.h: builds the piecewise-constant 2D sampling distribution of
 * an environment map (layout: glsl/shared/envmap.h) from its texels, so the
 * GPU can importance-sample image infinite lights. */
#ifndef CV_TRACE_ENVMAP_DIST_H
#define CV_TRACE_ENVMAP_DIST_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "base/error.h"

/* Floats the distribution of a w x h map occupies. */
size_t cv_envmap_dist_floats(uint32_t w, uint32_t h);

/* Fills out[0 .. cv_envmap_dist_floats(w, h)) from `texels`: w x h linear
 * RGB(A) floats, `channels` (3 or 4) per texel, row 0 at the top.
 * equal_area: pbrt-v4 octahedral map, else pbrt-v3 lat-long (rows weighted
 * by sin theta). Each cell's weight is the largest luminance in its 3x3
 * neighbourhood, so the bilinearly filtered radiance the GPU returns is
 * never non-zero where the pdf is zero; an all-black map gets a uniform
 * distribution. Fails on empty sizes or a bad channel count. */
bool cv_envmap_dist_build(const float *texels, uint32_t w, uint32_t h, unsigned channels,
                          bool equal_area, float *out, struct cv_error *err);

#endif
