/* spectrum.h: spectral tables to the render's RGB (spectrum.c; colour
 * parameters go through builder.h's cv_b_color). */
#ifndef CV_SCENE_SPECTRUM_H
#define CV_SCENE_SPECTRUM_H

#include <stddef.h>

/* Weights that turn a reflectance spectrum sampled at the n ascending
 * wavelengths lambda [nm] (piecewise linear between them, constant beyond
 * them, as pbrt-v4 interpolates a measured BRDF's spectra) into linear
 * Rec.709: rgb[c] = sum over k of w[3k + c] * value[k]. The spectrum is
 * taken under CIE D65 (the white of sRGB, and the spectrum pbrt-v4 gives
 * an "rgb L" light) and integrated against the CIE 1931 matching
 * functions over 360..830 nm, as pbrt-v4's film does with its cie1931
 * sensor; each channel's weights are then scaled to sum to 1, so that a
 * constant spectrum keeps its value in all three (the matching functions
 * here are a fit, a few tenths of a per cent off). n >= 1. */
void cv_spectrum_rgb_weights(const float *lambda, size_t n, double *w);

#endif
