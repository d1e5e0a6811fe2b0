/* media_cloud.c: pbrt-v4's "cloud" medium (CloudMedium), read with its
 * parameters and defaults: density, wispiness, frequency, g, sigma_a,
 * sigma_s and the bounds p0 p1 in medium space (the CTM at
 * MakeNamedMedium). Its density, Perlin noise summed over octaves, is
 * evaluated on the GPU (glsl/trace/medium/cloud.glsl); here go its
 * parameters and its majorant grid. */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "base/mem.h"
#include "scene/builder.h"

/* pbrt-v4's CloudMedium::Create defaults. */
#define DEFAULT_DENSITY 1.0
#define DEFAULT_WISPINESS 1.0
#define DEFAULT_FREQUENCY 5.0
#define DEFAULT_SIGMA 1.0

/* A parameter that must be finite as a float, as the GPU reads it (any
 * such value is pbrt-v4's to take: the density is clamped to [0, 1]
 * whatever they are). */
static bool finite_param(struct cv_params *ps, const char *name, const char *param, double def,
                         const struct cv_loc *loc, double *out, struct cv_error *err)
{
    *out = cv_params_float(ps, param, def);
    if (fabs(*out) <= FLT_MAX)
        return true;
    struct cv_param *p = cv_params_find(ps, param);
    return cv_fail(err, "%s:%d:%d: medium \"%s\": \"%s\" is %g; it must be finite as a float",
                   p ? p->file : loc->file, p ? p->line : loc->line, p ? p->col : loc->col,
                   name, param, *out);
}

bool cv_b_medium_cloud(struct cv_builder *b, const char *name, struct cv_params *ps,
                       const struct cv_loc *loc, const char *dir, CvMedium *m,
                       struct cv_error *err)
{
    double g, density, wispiness, frequency, lo[3], size[3];
    double sa[3] = {DEFAULT_SIGMA, DEFAULT_SIGMA, DEFAULT_SIGMA};
    double ss[3] = {DEFAULT_SIGMA, DEFAULT_SIGMA, DEFAULT_SIGMA};
    bool found;
    if (!cv_b_medium_g(b, ps, name, loc, &g, err) ||
        !finite_param(ps, name, "density", DEFAULT_DENSITY, loc, &density, err) ||
        !finite_param(ps, name, "wispiness", DEFAULT_WISPINESS, loc, &wispiness, err) ||
        !finite_param(ps, name, "frequency", DEFAULT_FREQUENCY, loc, &frequency, err) ||
        !cv_b_color(b, ps, "sigma_a", CV_SPEC_UNBOUNDED, dir, sa, &found, err) ||
        !cv_b_color(b, ps, "sigma_s", CV_SPEC_UNBOUNDED, dir, ss, &found, err))
        return false;
    for (int c = 0; c < 3; c++)
        if (!(sa[c] >= 0) || !(ss[c] >= 0) || !isfinite(sa[c]) || !isfinite(ss[c]))
            return cv_fail(err, "%s:%d:%d: medium \"%s\": sigma_a and sigma_s must be finite "
                                "and not negative", loc->file, loc->line, loc->col, name);
    if (!cv_b_medium_bounds(b, ps, name, loc, m, lo, size, err))
        return false;
    m->type = CV_MEDIUM_CLOUD;
    m->sigma_a = (cv_vec4){(float)sa[0], (float)sa[1], (float)sa[2], (float)g};
    m->sigma_s = (cv_vec4){(float)ss[0], (float)ss[1], (float)ss[2], 0};
    m->temperature_grids = (cv_uvec4){CV_NO_GRID, CV_NO_GRID, 0, 0};
    const double params[9] = {density, wispiness, frequency, lo[0], lo[1], lo[2],
                              size[0], size[1], size[2]};
    m->grids = (cv_uvec4){cv_b_medium_floats(b, params, 9, 1), CV_NO_GRID, CV_NO_GRID, 0};
    /* The majorant grid: the density never exceeds 1 (its last step
     * clamps it), so sigma_t's largest channel bounds every cell, a hair
     * above so that float rounding of sigma x density stays below; the
     * one majorant pbrt-v4's CloudMedium uses over its bounds. A tighter
     * bound per cell needs one on the noise over the cell, which the
     * wisps (a displacement up to the noise's steepest slope) and the
     * octaves up to 16 times finer leave near 1 wherever the height fade
     * does not. */
    double top = 0;
    for (int c = 0; c < 3; c++)
        top = fmax(top, (double)(float)sa[c] + (double)(float)ss[c]);
    const size_t cells = (size_t)CV_MAJORANT_RES * CV_MAJORANT_RES * CV_MAJORANT_RES;
    double *maj = cv_xmalloc(cells * sizeof(double));
    for (size_t i = 0; i < cells; i++)
        maj[i] = top * (1 + 1e-5);
    m->res.w = cv_b_medium_floats(b, maj, cells, 1);
    free(maj);
    return true;
}
