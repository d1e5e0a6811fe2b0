/* filter_table.c: see filter_table.h. */
#include <math.h>

#include "scene/filter.h"
#include "trace/filter_table.h"

#define STEPS 4096

void cv_gaussian_filter_table(float radius, float sigma, float *out, size_t n)
{
    const struct cv_filter_info *g = cv_filter_info(CV_FILTER_GAUSSIAN);
    double r = radius > 0 ? radius : g->radius, s = sigma > 0 ? sigma : CV_FILTER_GAUSSIAN_SIGMA;
    double edge = exp(-r * r / (2 * s * s));
    double cdf[STEPS + 1];
    cdf[0] = 0;
    for (int i = 0; i < STEPS; i++) {
        double x = -r + 2 * r * (i + 0.5) / STEPS;
        double f = exp(-x * x / (2 * s * s)) - edge;
        cdf[i + 1] = cdf[i] + (f > 0 ? f : 0);
    }
    double total = cdf[STEPS];
    int j = 0;
    for (size_t k = 0; k <= n; k++) {
        double u = (double)k / (double)n * total;
        while (j < STEPS - 1 && cdf[j + 1] < u)
            j++;
        double span = cdf[j + 1] - cdf[j];
        double t = span > 0 ? (u - cdf[j]) / span : 0;
        if (t < 0)
            t = 0;
        if (t > 1)
            t = 1;
        out[k] = (float)((j + t) / STEPS);
    }
    out[0] = 0;
    out[n] = 1;
}
