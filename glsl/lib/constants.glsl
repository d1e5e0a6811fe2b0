// glsl/lib/constants.glsl: numeric constants shared by the trace shaders.
#ifndef CV_LIB_CONSTANTS_GLSL
#define CV_LIB_CONSTANTS_GLSL

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
float cv_luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

#endif
