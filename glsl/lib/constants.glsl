// glsl/lib/constants.glsl: numeric constants shared by the trace shaders.
#ifndef CV_LIB_CONSTANTS_GLSL
#define CV_LIB_CONSTANTS_GLSL

#include "../shared/common.h"

#define CV_PI 3.14159265358979323846
#define CV_INV_PI 0.31830988618379067154
#define CV_INV_2PI 0.15915494309189533577
#define CV_INV_4PI 0.07957747154594766788
#define CV_PI_OVER_2 1.57079632679489661923
#define CV_PI_OVER_4 0.78539816339744830961
// Largest float below 1: keeps warped samples inside [0,1).
#define CV_ONE_MINUS_EPS 0.99999994

float cv_sqr(float x) { return x * x; }
float cv_safe_sqrt(float x) { return sqrt(max(x, 0.0)); }
float cv_max3(vec3 v) { return max(v.x, max(v.y, v.z)); }
float cv_mean3(vec3 v) { return (v.x + v.y + v.z) * (1.0 / 3.0); }
float cv_luminance(vec3 c) { return CV_LUMA(c.x, c.y, c.z); }

// pbrt-v4's SmoothStep: a step where the edges meet, a reversed ramp where
// a > b. GLSL's smoothstep is undefined for edge0 >= edge1, which a spot
// light of conedeltaangle 0 gives.
float cv_smoothstep(float a, float b, float x)
{
    if (a == b)
        return x < a ? 0.0 : 1.0;
    float t = clamp((x - a) / (b - a), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// How far a ray leaving a point of triangle p0 p1 p2 must start off its
// plane so that neither the interpolated point's rounding (each term of
// b0 p0 + b1 p1 + b2 p2, and b0 = 1 - b1 - b2 off by an ulp of 1) nor the
// ray-triangle test's own (vertices taken relative to the origin and
// sheared into the ray's frame, bvh/triangle.glsl) can put the plane in
// front of it: a few ulps of the vertices' largest coordinates. 2^-21 of
// their sum leaves room for fused or reordered GPU arithmetic.
float cv_point_error(vec3 p0, vec3 p1, vec3 p2)
{
    return (1.0 / 2097152.0) * (cv_max3(abs(p0)) + cv_max3(abs(p1)) + cv_max3(abs(p2)));
}

#endif
