/* film.h: pbrt's rules that fit a camera to a film, each written once. The
 * scene loader (camera.c) applies them to the scene's own Camera and Film;
 * the batch plan (batch/plan.c) applies them again when a job overrides the
 * resolution, fov or LookAt, so that a manifest setting and the same
 * setting in the scene file give the same camera. */
#ifndef CV_SCENE_FILM_H
#define CV_SCENE_FILM_H

#include <stdbool.h>
#include <stdint.h>

#include "glsl/shared/scene.h"

/* Pixel bounds of a crop window (x0, x1, y0, y1 in [0, 1], x0 < x1 and
 * y0 < y1) on a w x h film: px = {x0, x1, y0, y1} in pixels, x1 and y1
 * exclusive, as pbrt's ceil(resolution * crop). A window so thin that it
 * holds no pixel edge along an axis gets the one pixel it lies in there
 * (pbrt-v4 stops with "degenerate pixel bounds"; a manifest resolution
 * should not fail a job that the scene's own resolution renders). */
void cv_film_crop_pixels(uint32_t w, uint32_t h, const double crop[4], uint32_t px[4]);

/* pbrt's default screen window for an aspect ratio (width / height): the
 * longer axis spans [-aspect, aspect], the shorter [-1, 1]. */
cv_vec4 cv_film_default_screen(double aspect);

/* The camera's lens.z: tan of half the field of view [degrees]. */
float cv_camera_fov_scale(double fov_deg);

/* Fits cam (already set up for its own film) to a w x h film with the crop
 * window: film size, crop origin and size. When the aspect ratio changes,
 * the screen window becomes the default for the new one and the function
 * returns true (the caller may say so); an unchanged aspect ratio keeps the
 * screen window, an explicit one included. */
bool cv_camera_fit_film(CvCamera *cam, const double crop[4], uint32_t w, uint32_t h);

/* Places cam as pbrt's LookAt would at the Camera directive: eye, looking
 * at `at`, with `up` up, still over the whole shutter (any motion of the
 * scene's camera is dropped). False when eye == at or up is parallel to the
 * viewing direction; cam is then unchanged. */
bool cv_camera_look_at(CvCamera *cam, const double eye[3], const double at[3],
                       const double up[3]);

#endif
