/* camera_motion.h: a moving camera's transforms for the GPU, split as
 * pbrt-v4's AnimatedTransform splits them: translation, a rotation
 * quaternion (the rotation factor of a polar decomposition) and the
 * remaining scale and shear. The shader (glsl/trace/camera.glsl)
 * interpolates translation and scale linearly and the rotation by slerp at
 * each camera ray's time, so a turning camera sweeps an arc, not a chord.
 * pbrt-v4 leaves a transform that swaps handedness (det < 0, e.g. Scale -1
 * 1 1 before LookAt) to a polar factor that is a reflection, which its
 * quaternion cannot hold; here the reflection moves into S (R and S both
 * negated), so such a camera moves as its matrices say. */
#ifndef CV_TRACE_CAMERA_MOTION_H
#define CV_TRACE_CAMERA_MOTION_H

#include <stdbool.h>

#include "glsl/shared/scene.h"
#include "glsl/shared/trace.h"

/* m (3x4 rows, affine) as translation T, unit quaternion q (x, y, z, w)
 * and 3x3 S with m = T * R(q) * S; false when m's 3x3 is singular. */
bool cv_motion_decompose(const double m[3][4], double T[3], double q[4], double S[3][3]);

/* The composition T * R(q) * S as 3x4 rows (q need not be unit length:
 * it is normalised). */
void cv_motion_compose(const double T[3], const double q[4], const double S[3][3], double m[3][4]);

/* Fills the pass constants' cam_* motion fields for cam; a camera whose
 * start and end transforms agree gets cam_moves 0. */
void cv_camera_motion_setup(const CvCamera *cam, CvPassParams *u);

#endif
