/* animated.h: pbrt-v4's AnimatedTransform on the host. A transform given
 * at two times (ActiveTransform StartTime / EndTime) is split at each end
 * into translation T, a rotation quaternion q (the rotation factor of a
 * polar decomposition) and the remaining scale and shear S; at a time
 * between the ends T and S are interpolated linearly and q by slerp, so a
 * turning object sweeps an arc, not a chord. Before the start time the
 * start transform holds, after the end time the end transform. The
 * renderer does the same per ray on the GPU (glsl/lib/quaternion.glsl,
 * glsl/bvh/motion.glsl, glsl/trace/camera.glsl); the host side gives the
 * decomposition, a reference interpolation for tests and the motion
 * bounds of moving shapes.
 * A transform that swaps handedness (det < 0) has a polar factor that is a
 * reflection, which a quaternion cannot hold; pbrt-v4 leaves that case
 * unhandled. Here the reflection moves into S (R and S both negated), so
 * such a transform moves as its matrices say. */
#ifndef CV_SCENE_ANIMATED_H
#define CV_SCENE_ANIMATED_H

#include <stdbool.h>

/* m (3x4 rows, affine) as translation T, unit quaternion q (x, y, z, w)
 * and 3x3 S with m = T * R(q) * S; false when m's 3x3 is singular. */
bool cv_motion_decompose(const double m[3][4], double T[3], double q[4], double S[3][3]);

/* The composition T * R(q) * S as 3x4 rows (q need not be unit length:
 * it is normalised). */
void cv_motion_compose(const double T[3], const double q[4], const double S[3][3], double m[3][4]);

/* pbrt-v4's Slerp of unit quaternions q0, q1 at t in [0, 1] (the angle
 * taken as pbrt-v4's AngleBetween takes it); out is unit length. */
void cv_quat_slerp(double t, const double q0[4], const double q1[4], double out[4]);

/* A transform at two times, decomposed. */
struct cv_animated {
    double start[3][4], end[3][4]; /* world from object at t0 and t1 (3x4 rows) */
    double t0, t1;                 /* t0 < t1 when moving */
    bool moving;                   /* false: start holds at every time */
    double T[2][3], q[2][4], S[2][3][3]; /* the ends decomposed; q[0] . q[1] >= 0 */
};

/* Sets a from the transforms at t0 and t1. False (a untouched) when an end
 * is singular. A transform whose ends agree, or whose times do not
 * increase, does not move. */
bool cv_animated_init(struct cv_animated *a, const double start[3][4], double t0,
                      const double end[3][4], double t1);

/* The transform at `time` (pbrt-v4's AnimatedTransform::Interpolate). */
void cv_animated_at(const struct cv_animated *a, double time, double m[3][4]);

/* A box holding the box [lo, hi] under every transform of a from t0 to t1
 * (pbrt-v4's MotionBounds purpose; not its method): the union of the
 * box's images at evenly spaced times, each grown by how far a point of
 * the box can move in half a step (a bound on its speed times the time
 * between samples), so it holds the swept volume whatever the rotation.
 * Conservative: its slack over the exact sweep shrinks with the number of
 * time samples (animated.c), which cost host time once per moving shape. */
void cv_animated_bounds(const struct cv_animated *a, const float lo[3], const float hi[3],
                        float out_lo[3], float out_hi[3]);

#endif
