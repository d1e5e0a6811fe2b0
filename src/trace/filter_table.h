/* filter_table.h: the pixel filter's sampling tables, as pbrt-v4's
 * FilterSampler makes them. A filter is sampled by importance: box and
 * triangle in closed form (weight 1), the others from a piecewise-constant
 * table of |f| at cell centres, 32 cells a pixel of radius (at most
 * CV_FILTER_CELLS on an axis), each sample weighted f / pdf. pbrt-v4 does
 * that over a 2D table; the filters are products of their two axes, so its
 * table is the product of two 1D ones, and f / pdf is the sign of f in the
 * cell times the constant integral of |f|: the shader keeps the sign (w =
 * +1 or -1) and the film divides by the weights' sum, in which the
 * constant cancels (glsl/trace/filter.glsl). */
#ifndef CV_TRACE_FILTER_TABLE_H
#define CV_TRACE_FILTER_TABLE_H

#include "glsl/shared/trace.h"
#include "scene/scene.h"

/* Cells of the table along `axis` (0: x, 1: y): 32 a pixel of radius, 1
 * to CV_FILTER_CELLS; 0 for a filter sampled in closed form. */
unsigned cv_filter_cells(const struct cv_render_settings *st, int axis);

/* Fills the filter fields of the pass constants (filter_type,
 * pixel_filter, filter_x, filter_y, filter_neg) for the filter of st. */
void cv_filter_setup(const struct cv_render_settings *st, CvPassParams *u);

#endif
