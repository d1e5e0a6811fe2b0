/* camera_motion.h: a moving camera's transforms for the GPU, split as
 * pbrt-v4's AnimatedTransform splits them: translation, a rotation
 * quaternion (the rotation factor of a polar decomposition) and the
 * remaining scale and shear. The shader (glsl/trace/camera.glsl)
 * interpolates translation and scale linearly and the rotation by slerp at
 * each camera ray's time, so a turning camera sweeps an arc, not a chord.
 * The split (and its handling of a handedness swap, e.g. Scale -1 1 1
 * before LookAt) is scene/animated.h's, shared with moving shapes. */
#ifndef CV_TRACE_CAMERA_MOTION_H
#define CV_TRACE_CAMERA_MOTION_H

#include <stdbool.h>

#include "glsl/shared/scene.h"
#include "glsl/shared/trace.h"
#include "scene/animated.h"

/* Fills the pass constants' cam_* motion fields for cam; a camera whose
 * start and end transforms agree gets cam_moves 0. */
void cv_camera_motion_setup(const CvCamera *cam, CvPassParams *u);

#endif
