// glsl/trace/filter.glsl: a pixel sample's offset from the pixel centre,
// distributed as |f| of the pixel filter, and its weight f / pdf up to the
// constant integral of |f|: +1 or -1 (src/trace/filter_table.h). Box and
// triangle are sampled in closed form; the others from the tables of
// CvPassParams (the CDF of |f| over cells, a bit per cell where f < 0).
// Needs u_pass (CvPassParams).
#ifndef CV_TRACE_FILTER_GLSL
#define CV_TRACE_FILTER_GLSL

#include "../shared/scene.h"

float cv_filter_cdf(uint axis, uint i)
{
    vec4 v = axis == 0u ? u_pass.filter_x[i >> 2] : u_pass.filter_y[i >> 2];
    return v[i & 3u];
}

// Offset in pixels along one axis for a uniform u; negates w where the
// filter is negative there.
float cv_filter_offset(float u, uint axis, inout float w)
{
    float radius = u_pass.pixel_filter[axis];
    uint type = u_pass.filter_type;
    if (type == CV_FILTER_ID_BOX)
        return radius * (2.0 * u - 1.0);
    if (type == CV_FILTER_ID_TRIANGLE)
        return u < 0.5 ? radius * (sqrt(2.0 * u) - 1.0) : radius * (1.0 - sqrt(2.0 - 2.0 * u));
    // the last cell k with cdf[k] <= u (cdf[0] = 0 <= u < 1 = cdf[cells])
    uint cells = uint(u_pass.pixel_filter[2u + axis]);
    uint lo = 0u, hi = cells;
    while (hi - lo > 1u) {
        uint mid = (lo + hi) >> 1;
        if (cv_filter_cdf(axis, mid) <= u)
            lo = mid;
        else
            hi = mid;
    }
    float a = cv_filter_cdf(axis, lo), b = cv_filter_cdf(axis, lo + 1u);
    float t = b > a ? clamp((u - a) / (b - a), 0.0, 1.0) : 0.5;
    if ((u_pass.filter_neg[axis][lo >> 7][(lo >> 5) & 3u] & (1u << (lo & 31u))) != 0u)
        w = -w;
    return radius * (2.0 * (float(lo) + t) / float(cells) - 1.0);
}

// The filter offset (pixels) for a uniform 2D sample, and its weight w.
vec2 cv_filter_sample(vec2 u, out float w)
{
    w = 1.0;
    return vec2(cv_filter_offset(u.x, 0u, w), cv_filter_offset(u.y, 1u, w));
}

#endif
