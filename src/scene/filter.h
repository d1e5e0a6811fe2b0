/* filter.h: the pixel filters Cavalry renders, by their pbrt names, with
 * pbrt-v4's default radii: the parser, the scene's defaults and the
 * renderer read this one table. */
#ifndef CV_SCENE_FILTER_H
#define CV_SCENE_FILTER_H

#include "scene/scene.h"

struct cv_filter_info {
    const char *name;            /* as a PixelFilter directive names it */
    enum cv_filter_type type;
    float radius;                /* default radius on each axis [pixels] */
};

/* pbrt-v4's default standard deviation of the Gaussian filter [pixels] */
#define CV_FILTER_GAUSSIAN_SIGMA 0.5f

/* The filter used where a scene names none, or one Cavalry does not render. */
#define CV_FILTER_DEFAULT CV_FILTER_GAUSSIAN

/* The entry of a filter type (always found). */
const struct cv_filter_info *cv_filter_info(enum cv_filter_type type);

/* The entry named `name`, or NULL when Cavalry does not render it. */
const struct cv_filter_info *cv_filter_by_name(const char *name);

#endif
