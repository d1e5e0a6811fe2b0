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

/* The wavelengths spectra are integrated over: every nm of
 * [CV_SPECTRUM_NM_MIN, CV_SPECTRUM_NM_MIN + CV_SPECTRUM_NM). */
#define CV_SPECTRUM_NM_MIN 360
#define CV_SPECTRUM_NM 471

/* The same weights for a spectrum sampled at every nm of that range:
 * rgb[c] = sum over i of w[3i + c] * value(CV_SPECTRUM_NM_MIN + i); w has
 * 3 * CV_SPECTRUM_NM entries, each channel's summing to 1. */
void cv_spectrum_rgb_weights_nm(double *w);

/* A piecewise-linear spectrum of n (lambda [nm], value) pairs with
 * ascending lambda at lambda, as pbrt-v4 evaluates one: 0 beyond the
 * pairs; one pair is a constant. */
double cv_spectrum_at(const double *pairs, size_t n, double lambda);

/* pbrt-v4's named spectra of metals' complex index (metal-Cu-eta,
 * metal-Cu-k, and Ag, Al, Au, CuZn, MgO, TiO2; metal_spectra.c): its
 * pairs and their count, or NULL for another name. */
const double *cv_metal_spectrum(const char *name, size_t *n);

#endif
