/* measured.h: a measured BRDF of the RGL database (pbrt-v4's `measured`
 * material) from its tensor file into the GPU tables of
 * glsl/shared/measured.h. */
#ifndef CV_SCENE_MEASURED_H
#define CV_SCENE_MEASURED_H

#include <stddef.h>
#include <stdint.h>

#include "base/error.h"
#include "scene/rgl_tensor.h"

/* Checks t's fields as pbrt-v4 does (theta_i, phi_i, ndf, sigma, vndf,
 * luminance, description, jacobian; spectra with wavelengths, or rgb),
 * turns spectra into Rec.709 (scene/spectrum.h) and builds the warps'
 * CDFs into *block (newly allocated, *n words; its offsets are relative
 * to its start, so it may sit anywhere in the scene's buffer). name
 * stands for the file in messages. */
bool cv_measured_tables(const char *name, const struct cv_tensor_file *t, uint32_t **block,
                        size_t *n, struct cv_error *err);

#endif
