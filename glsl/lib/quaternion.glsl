// glsl/lib/quaternion.glsl: rotations as unit quaternions (x, y, z, w) and
// pbrt-v4's slerp between them, for its AnimatedTransform (moving camera:
// trace/camera.glsl; moving shapes: bvh/motion.glsl; the host's double
// version: src/scene/animated.c).
#ifndef CV_LIB_QUATERNION_GLSL
#define CV_LIB_QUATERNION_GLSL

// A vector v rotated by the unit quaternion q (x, y, z, w).
vec3 cv_quat_rotate(vec4 q, vec3 v)
{
    return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v);
}

float cv_sin_x_over_x(float x) { return 1.0 - x * x / 6.0 == 1.0 ? 1.0 : sin(x) / x; }

// pbrt-v4's Slerp, with the angle between q0 and q1 taken as pbrt-v4's
// AngleBetween does (no acos of a dot product near 1).
vec4 cv_quat_slerp(float t, vec4 q0, vec4 q1)
{
    float theta = dot(q0, q1) < 0.0 ? 3.14159265 - 2.0 * asin(min(length(q0 + q1) / 2.0, 1.0))
                                    : 2.0 * asin(min(length(q1 - q0) / 2.0, 1.0));
    float s = cv_sin_x_over_x(theta);
    vec4 q = q0 * ((1.0 - t) * cv_sin_x_over_x((1.0 - t) * theta) / s) +
             q1 * (t * cv_sin_x_over_x(t * theta) / s);
    return normalize(q);
}

#endif
