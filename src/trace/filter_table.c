/* filter_table.c: see filter_table.h. */
#include <math.h>
#include <string.h>

#include "scene/filter.h"
#include "trace/filter_table.h"

unsigned cv_filter_cells(const struct cv_render_settings *st, int axis)
{
    if (cv_filter_info(st->filter)->exact)
        return 0;
    double n = floor(32 * cv_filter_radius(st, axis));
    return n < 1 ? 1 : n > CV_FILTER_CELLS ? CV_FILTER_CELLS : (unsigned)n;
}

/* One axis: the normalised CDF of |f| at the cell centres (n + 1 values)
 * and the cells where f is negative. */
static void axis_table(const struct cv_render_settings *st, int axis, unsigned n, cv_vec4 *cdf4,
                       cv_uvec4 *neg4)
{
    float *cdf = &cdf4[0].x;
    uint32_t *neg = &neg4[0].x;
    double r = cv_filter_radius(st, axis), sum = 0, acc[CV_FILTER_CELLS + 1];
    acc[0] = 0;
    for (unsigned k = 0; k < n; k++) {
        double f = cv_filter_1d(st, axis, -r + 2 * r * (k + 0.5) / n);
        if (f < 0)
            neg[k >> 5] |= 1u << (k & 31);
        sum += fabs(f);
        acc[k + 1] = sum;
    }
    for (unsigned k = 0; k <= n; k++) /* an all-zero filter: uniform */
        cdf[k] = (float)(sum > 0 ? acc[k] / sum : (double)k / n);
    cdf[n] = 1;
}

void cv_filter_setup(const struct cv_render_settings *st, CvPassParams *u)
{
    unsigned nx = cv_filter_cells(st, 0), ny = cv_filter_cells(st, 1);
    u->filter_type = cv_filter_info(st->filter)->type;
    u->pixel_filter = (cv_vec4){(float)cv_filter_radius(st, 0), (float)cv_filter_radius(st, 1),
                                (float)nx, (float)ny};
    memset(u->filter_x, 0, sizeof(u->filter_x));
    memset(u->filter_y, 0, sizeof(u->filter_y));
    memset(u->filter_neg, 0, sizeof(u->filter_neg));
    if (nx)
        axis_table(st, 0, nx, u->filter_x, u->filter_neg[0]);
    if (ny)
        axis_table(st, 1, ny, u->filter_y, u->filter_neg[1]);
}
