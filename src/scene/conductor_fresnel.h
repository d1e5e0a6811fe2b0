/* conductor_fresnel.h: the Fresnel tables of conductors given by spectra
 * (layout: glsl/shared/conductor_fresnel.h). */
#ifndef CV_SCENE_CONDUCTOR_FRESNEL_H
#define CV_SCENE_CONDUCTOR_FRESNEL_H

#include <stddef.h>

#include "glsl/shared/conductor_fresnel.h"

/* Fills table[4 * CV_CONDUCTOR_FRESNEL_N] (rgb and a 0 per entry): entry
 * i the linear Rec.709 of the spectral reflectance F(lambda, cos theta =
 * i / (N - 1)) of a conductor whose index is the spectra eta + i k (pairs
 * as cv_spectrum_at reads them) over a medium of index outer (1: air; a
 * coated conductor's coat), taken under D65 and integrated against the
 * CIE 1931 functions as pbrt-v4's RGB film does with its cie1931 sensor
 * (cv_spectrum_rgb_weights_nm). Cost: CV_CONDUCTOR_FRESNEL_N times
 * CV_SPECTRUM_NM complex Fresnel terms, once per table at load. */
void cv_conductor_fresnel_table(const double *eta, size_t n_eta, const double *k, size_t n_k,
                                double outer, float *table);

#endif
