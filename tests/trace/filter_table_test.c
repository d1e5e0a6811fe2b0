/* filter_table_test.c: the pixel filters' shapes and sampling tables
 * (src/scene/filter.c, src/trace/filter_table.c): pbrt-v4's default radii
 * and parameters; Mitchell and the Lanczos sinc written out here again
 * (Mitchell and Netravali 1988, pbrt-v4's windowed sinc); each table's CDF
 * runs from 0 to 1, increasing, with 32 cells a pixel of radius, and its
 * sign bits mark exactly the cells whose centre has f < 0. The sampled
 * distribution itself is tested on the GLSL by filter_sample_test. */
#include "config.h"

#include <math.h>
#include <string.h>

#include "scene/filter.h"
#include "tests/tap.h"
#include "trace/filter_table.h"

static struct cv_render_settings settings(enum cv_filter_type t, float rx, float ry)
{
    struct cv_render_settings st;
    memset(&st, 0, sizeof(st));
    st.filter = t;
    st.filter_radius[0] = rx;
    st.filter_radius[1] = ry;
    st.filter_sigma = CV_FILTER_GAUSSIAN_SIGMA;
    st.filter_b = CV_FILTER_MITCHELL_B;
    st.filter_c = CV_FILTER_MITCHELL_C;
    st.filter_tau = CV_FILTER_SINC_TAU;
    return st;
}

/* Mitchell-Netravali with B = C = 1/3 at |x| in pixels for radius 2 */
static double mitchell_ref(double x)
{
    x = fabs(x);
    const double b = 1.0 / 3, c = 1.0 / 3;
    if (x < 1)
        return ((12 - 9 * b - 6 * c) * pow(x, 3) + (-18 + 12 * b + 6 * c) * x * x + 6 - 2 * b) / 6;
    if (x < 2)
        return ((-b - 6 * c) * pow(x, 3) + (6 * b + 30 * c) * x * x + (-12 * b - 48 * c) * x + 8 * b +
                24 * c) / 6;
    return 0;
}

static double lanczos_ref(double x, double tau)
{
    if (x == 0)
        return 1;
    return sin(M_PI * x) / (M_PI * x) * sin(M_PI * x / tau) / (M_PI * x / tau);
}

static bool table_ok(const struct cv_render_settings *st, int axis, unsigned n)
{
    CvPassParams u;
    cv_filter_setup(st, &u);
    const float *cdf = axis ? &u.filter_y[0].x : &u.filter_x[0].x;
    const uint32_t *neg = &u.filter_neg[axis][0].x;
    if (cv_filter_cells(st, axis) != n || u.pixel_filter.z != (float)cv_filter_cells(st, 0) ||
        cdf[0] != 0 || cdf[n] != 1)
        return false;
    double r = cv_filter_radius(st, axis);
    for (unsigned k = 0; k < n; k++) {
        double f = cv_filter_1d(st, axis, -r + 2 * r * (k + 0.5) / n);
        bool bit = (neg[k >> 5] >> (k & 31)) & 1;
        if (cdf[k + 1] < cdf[k] || bit != (f < 0) || (fabs(f) > 1e-4 && !(cdf[k + 1] > cdf[k])))
            return false;
    }
    return true;
}

int main(void)
{
    static const struct {
        const char *name;
        float radius;
    } defaults[] = {{"box", 0.5f}, {"triangle", 2}, {"gaussian", 1.5f}, {"mitchell", 2}, {"sinc", 4}};
    for (size_t i = 0; i < sizeof(defaults) / sizeof(defaults[0]); i++) {
        const struct cv_filter_info *fi = cv_filter_by_name(defaults[i].name);
        tap_ok(fi && fi->radius == defaults[i].radius, "%s: pbrt-v4's default radius %g",
               defaults[i].name, defaults[i].radius);
    }
    tap_ok(cv_filter_by_name("lanczos") == NULL, "pbrt-v4 names the Lanczos filter \"sinc\"");

    struct cv_render_settings m = settings(CV_FILTER_MITCHELL, 2, 2);
    double worst = 0;
    for (double x = -2.5; x <= 2.5; x += 0.01)
        worst = fmax(worst, fabs(cv_filter_1d(&m, 0, x) - mitchell_ref(x)));
    tap_ok(worst < 1e-6, "mitchell B = C = 1/3 is Mitchell-Netravali's cubic (%.2g)", worst);
    tap_ok(cv_filter_1d(&m, 0, 1.5) < 0, "mitchell is negative at 1.5 pixels");
    struct cv_render_settings l = settings(CV_FILTER_SINC, 4, 4);
    worst = 0;
    for (double x = -4; x <= 4; x += 0.01)
        worst = fmax(worst, fabs(cv_filter_1d(&l, 0, x) - lanczos_ref(x, 3)));
    tap_ok(worst < 1e-9 && cv_filter_1d(&l, 0, 4.01) == 0, "sinc is the windowed sinc, tau 3 (%.2g)",
           worst);
    struct cv_render_settings g = settings(CV_FILTER_GAUSSIAN, 1.5f, 1.5f);
    tap_ok(fabs(cv_filter_1d(&g, 0, 1.5)) < 1e-12 && cv_filter_1d(&g, 0, 0) > 0,
           "gaussian is 0 at its radius");

    tap_ok(table_ok(&m, 0, 64) && table_ok(&m, 1, 64), "mitchell: 64 cells a side, CDF and signs");
    tap_ok(table_ok(&l, 0, 128), "sinc: 128 cells, CDF and signs");
    struct cv_render_settings a = settings(CV_FILTER_SINC, 3, 1.25f);
    tap_ok(table_ok(&a, 0, 96) && table_ok(&a, 1, 40), "sinc 3 x 1.25: 96 and 40 cells");
    struct cv_render_settings big = settings(CV_FILTER_GAUSSIAN, 20, 0.01f);
    tap_ok(table_ok(&big, 0, CV_FILTER_CELLS) && table_ok(&big, 1, 1),
           "radius 20: capped at %d cells; radius 0.01: one cell", CV_FILTER_CELLS);
    struct cv_render_settings b = settings(CV_FILTER_BOX, 0.5f, 0.5f);
    tap_ok(cv_filter_cells(&b, 0) == 0 && cv_filter_cells(&b, 1) == 0, "box: sampled exactly");
    return tap_done();
}
