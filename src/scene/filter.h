/* filter.h: the pixel filters Cavalry renders, by their pbrt names, with
 * pbrt-v4's default radii and shapes: the parser, the scene's defaults,
 * the renderer's sampling tables and the tests read this one table. */
#ifndef CV_SCENE_FILTER_H
#define CV_SCENE_FILTER_H

#include <stdbool.h>

#include "scene/scene.h"

struct cv_filter_info {
    const char *name;            /* as a PixelFilter directive names it */
    enum cv_filter_type type;
    float radius;                /* default radius on each axis [pixels] */
    bool exact;                  /* sampled in closed form (box, triangle), else
                                  * through a table of |f| (trace/filter_table.h) */
};

/* pbrt-v4's default parameters: the Gaussian's standard deviation
 * [pixels], Mitchell-Netravali's B and C, the Lanczos window's tau. */
#define CV_FILTER_GAUSSIAN_SIGMA 0.5f
#define CV_FILTER_MITCHELL_B (1.0f / 3.0f)
#define CV_FILTER_MITCHELL_C (1.0f / 3.0f)
#define CV_FILTER_SINC_TAU 3.0f

/* The filter used where a scene names none, or one Cavalry does not render. */
#define CV_FILTER_DEFAULT CV_FILTER_GAUSSIAN

/* The entry of a filter type (always found). */
const struct cv_filter_info *cv_filter_info(enum cv_filter_type type);

/* The entry named `name`, or NULL when Cavalry does not render it. */
const struct cv_filter_info *cv_filter_by_name(const char *name);

/* The filter's radius along an axis (0: x, 1: y) [pixels]: the settings',
 * or the type's default where the settings hold none. */
double cv_filter_radius(const struct cv_render_settings *st, int axis);

/* The filter of `st` along one axis at offset x [pixels] from the pixel
 * centre. Every pbrt-v4 filter is the product of its two axes' factors, so
 * this is the whole filter's shape up to a constant; it is negative in the
 * lobes of mitchell and sinc, 0 beyond the radius. */
double cv_filter_1d(const struct cv_render_settings *st, int axis, double x);

#endif
