/* filter.c: see filter.h. */
#include <string.h>

#include "scene/filter.h"

static const struct cv_filter_info filters[CV_FILTER_COUNT] = {
    [CV_FILTER_BOX] = {"box", CV_FILTER_BOX, 0.5f},
    [CV_FILTER_TRIANGLE] = {"triangle", CV_FILTER_TRIANGLE, 2.0f},
    [CV_FILTER_GAUSSIAN] = {"gaussian", CV_FILTER_GAUSSIAN, 1.5f},
};

const struct cv_filter_info *cv_filter_info(enum cv_filter_type type)
{
    return &filters[(unsigned)type < CV_FILTER_COUNT ? type : CV_FILTER_DEFAULT];
}

const struct cv_filter_info *cv_filter_by_name(const char *name)
{
    for (int i = 0; i < CV_FILTER_COUNT; i++)
        if (strcmp(filters[i].name, name) == 0)
            return &filters[i];
    return NULL;
}
