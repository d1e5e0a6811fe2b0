/* filter_table.h: the pixel filter's sampling table. Filters are sampled by
 * importance (offsets distributed as the filter, every sample of weight 1);
 * box and triangle invert in closed form in the shader, the truncated
 * Gaussian through this table. */
#ifndef CV_TRACE_FILTER_TABLE_H
#define CV_TRACE_FILTER_TABLE_H

#include <stddef.h>

/* Fills out[0..n] (n + 1 values) with the inverse CDF of pbrt's Gaussian
 * filter (exp(-x^2 / (2 sigma^2)) minus its value at the radius) on
 * [-radius, radius], at u = i / n, mapped to [0, 1] (0: -radius, 1: +radius). */
void cv_gaussian_filter_table(float radius, float sigma, float *out, size_t n);

#endif
