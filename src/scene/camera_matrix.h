/* camera_matrix.h: a CvCamera as the matrices OpenEXR's standard
 * attributes worldToCamera and worldToNDC hold (ImfStandardAttributes.h),
 * for compositors and dataset tools that reproject pixels.
 *
 * Conventions, both OpenEXR's: matrices are Imath M44f, row-major, applied
 * to row vectors (p' = p * M, translation in the last row). OpenEXR's camera
 * space is left-handed, +x right and +y up in the image, +z the viewing
 * direction (as RenderMan's): that is pbrt's camera space, so Cavalry
 * writes its camera space unchanged, without the flip a -z (OpenGL) camera
 * would need. NDC is the image plane with (0, 0) the top left and (1, 1)
 * the bottom right corner of the display window (the full film, also for a
 * crop); after p * worldToNDC, divide x and y by w and drop z. */
#ifndef CV_SCENE_CAMERA_MATRIX_H
#define CV_SCENE_CAMERA_MATRIX_H

#include <stdbool.h>

#include "glsl/shared/scene.h"

/* False when the camera-to-world transform is singular (out unchanged). */
bool cv_camera_world_to_camera(const CvCamera *cam, float out[16]);

/* Perspective: w is camera-space z; orthographic: w is 1. z' holds w as
 * well (OpenEXR drops it). False as above, and for a spherical camera,
 * which no projective matrix stands for. */
bool cv_camera_world_to_ndc(const CvCamera *cam, float out[16]);

#endif
