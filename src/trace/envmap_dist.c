/* envmap_dist.c: see envmap_dist.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "glsl/shared/common.h"
#include "glsl/shared/envmap.h"
#include "trace/envmap_dist.h"

size_t cv_envmap_dist_floats(uint32_t w, uint32_t h)
{
    return CV_ENV_FLOATS((size_t)w, (size_t)h);
}

static double luminance(const float *t)
{
    double y = CV_LUMA(t[0], t[1], t[2]);
    return isfinite(y) && y > 0 ? y : 0;
}

/* Builds a CDF of n+1 entries over func[0..n); returns the integral
 * (sum / n). A zero function gets a uniform CDF. */
static double build_cdf(const double *func, size_t n, float *cdf)
{
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        sum += func[i];
    cdf[0] = 0;
    double acc = 0;
    for (size_t i = 0; i < n; i++) {
        acc += sum > 0 ? func[i] : 1;
        cdf[i + 1] = (float)(acc / (sum > 0 ? sum : (double)n));
    }
    cdf[n] = 1;
    return sum / (double)n;
}

bool cv_envmap_dist_build(const float *texels, uint32_t w, uint32_t h, unsigned channels,
                          bool equal_area, float *out, struct cv_error *err)
{
    if (w == 0 || h == 0)
        return cv_fail(err, "environment map distribution: empty image (%ux%u)", w, h);
    if (channels != 3 && channels != 4)
        return cv_fail(err, "environment map distribution: %u channels (3 or 4 expected)", channels);
    double *func = cv_xmalloc((size_t)w * h * sizeof(*func));
    double total = 0;
    for (uint32_t y = 0; y < h; y++) {
        double sin_theta = equal_area ? 1 : sin(M_PI * (y + 0.5) / h);
        for (uint32_t x = 0; x < w; x++) {
            double m = 0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int64_t yy = (int64_t)y + dy, xx = (int64_t)x + dx;
                    if (yy < 0 || yy >= h)
                        continue;
                    if (equal_area && (xx < 0 || xx >= w))
                        continue;
                    xx = (xx + w) % w;
                    double v = luminance(texels + ((size_t)yy * w + (size_t)xx) * channels);
                    m = v > m ? v : m;
                }
            func[(size_t)y * w + x] = m * sin_theta;
            total += m * sin_theta;
        }
    }
    if (!(total > 0))
        for (size_t i = 0; i < (size_t)w * h; i++)
            func[i] = 1;
    uint32_t o = 0;
    memcpy(&out[0], &w, sizeof(w));
    memcpy(&out[1], &h, sizeof(h));
    uint32_t flags = equal_area ? CV_ENV_FLAG_EQUAL_AREA : 0;
    memcpy(&out[3], &flags, sizeof(flags));
    float *f = out + CV_ENV_FUNC(o), *cond = out + CV_ENV_COND(o, (size_t)w, h);
    float *marg = out + CV_ENV_MARG(o, (size_t)w, h);
    double *row_int = cv_xmalloc(h * sizeof(*row_int));
    for (uint32_t y = 0; y < h; y++) {
        for (uint32_t x = 0; x < w; x++)
            f[(size_t)y * w + x] = (float)func[(size_t)y * w + x];
        row_int[y] = build_cdf(func + (size_t)y * w, w, cond + (size_t)y * (w + 1));
    }
    double integral = build_cdf(row_int, h, marg);
    out[2] = (float)integral;
    free(row_int);
    free(func);
    return true;
}
