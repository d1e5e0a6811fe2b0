/* filter.c: see filter.h. The shapes are pbrt-v4's (filters.h there). */
#include <math.h>
#include <string.h>

#include "scene/filter.h"

static const struct cv_filter_info filters[CV_FILTER_COUNT] = {
    [CV_FILTER_BOX] = {"box", CV_FILTER_BOX, 0.5f, true},
    [CV_FILTER_TRIANGLE] = {"triangle", CV_FILTER_TRIANGLE, 2.0f, true},
    [CV_FILTER_GAUSSIAN] = {"gaussian", CV_FILTER_GAUSSIAN, 1.5f, false},
    [CV_FILTER_MITCHELL] = {"mitchell", CV_FILTER_MITCHELL, 2.0f, false},
    [CV_FILTER_SINC] = {"sinc", CV_FILTER_SINC, 4.0f, false},
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

double cv_filter_radius(const struct cv_render_settings *st, int axis)
{
    float r = st->filter_radius[axis != 0];
    return r > 0 ? r : cv_filter_info(st->filter)->radius;
}

/* Mitchell and Netravali's cubic at |x| in [0, 2] (pbrt-v4 maps the
 * radius onto 2) */
static double mitchell(double x, double b, double c)
{
    x = fabs(x);
    if (x <= 1)
        return ((12 - 9 * b - 6 * c) * x * x * x + (-18 + 12 * b + 6 * c) * x * x + (6 - 2 * b)) /
               6;
    if (x <= 2)
        return ((-b - 6 * c) * x * x * x + (6 * b + 30 * c) * x * x + (-12 * b - 48 * c) * x +
                (8 * b + 24 * c)) /
               6;
    return 0;
}

static double sinc(double x)
{
    double px = M_PI * x;
    return fabs(px) < 1e-5 ? 1 - px * px / 6 : sin(px) / px;
}

static double gaussian(double x, double sigma)
{
    return exp(-x * x / (2 * sigma * sigma)) / sqrt(2 * M_PI * sigma * sigma);
}

double cv_filter_1d(const struct cv_render_settings *st, int axis, double x)
{
    double r = cv_filter_radius(st, axis);
    if (fabs(x) > r)
        return 0;
    switch (st->filter) {
    case CV_FILTER_BOX:
        return 1;
    case CV_FILTER_TRIANGLE:
        return r - fabs(x);
    case CV_FILTER_GAUSSIAN: {
        double s = st->filter_sigma > 0 ? st->filter_sigma : CV_FILTER_GAUSSIAN_SIGMA;
        return fmax(0, gaussian(x, s) - gaussian(r, s));
    }
    case CV_FILTER_MITCHELL:
        return mitchell(2 * x / r, st->filter_b, st->filter_c);
    case CV_FILTER_SINC: {
        double tau = st->filter_tau;
        return sinc(x) * sinc(x / tau);
    }
    case CV_FILTER_COUNT:
        break;
    }
    return 0;
}
