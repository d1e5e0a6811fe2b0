/* bssrdf_table.h: pbrt-v4's tabulated BSSRDF (photon beam diffusion,
 * single plus multiple scattering) for the subsurface material, computed
 * once per (g, eta) at load, and the spline helpers that read it. The
 * layout is glsl/shared/bssrdf.h's; the GPU reads the same floats
 * (glsl/trace/bsdf/bssrdf.glsl). */
#ifndef CV_SCENE_BSSRDF_TABLE_H
#define CV_SCENE_BSSRDF_TABLE_H

#include <stdbool.h>

#include "glsl/shared/bssrdf.h"

/* Fills t[0 .. CV_BSSRDF_FLOATS) for Henyey-Greenstein g and relative
 * index of refraction eta (> 0). Cost: a few million exponentials and
 * square roots (6400 entries of two 100-point sums); once per distinct
 * (g, eta). */
void cv_bssrdf_table_compute(double g, double eta, float *t);

/* Catmull-Rom spline weights of x over nodes[0..n) (increasing), as
 * pbrt-v4's CatmullRomWeights: false when x lies outside; else the
 * spline at x is sum_k w[k] f[*offset + k] (w[k] 0 where offset + k falls
 * outside). */
bool cv_catmull_rom_weights(const float *nodes, int n, float x, int *offset, float w[4]);

/* The effective albedo (the profile's integral) of single-scattering
 * albedo rho in [0, 1], interpolated from table t. */
float cv_bssrdf_rho_eff(const float *t, float rho);

/* Its inverse: the rho whose effective albedo is rho_eff (clamped to the
 * table's range), as pbrt-v4's InvertCatmullRom. */
float cv_bssrdf_invert_rho_eff(const float *t, float rho_eff);

/* pbrt-v4's SubsurfaceFromDiffuse for one channel: sigma_a and sigma_s
 * [1 / scene unit] of a medium with diffuse reflectance r in [0, 1] and
 * mean free path mfp (> 0) [scene units]. */
void cv_bssrdf_from_diffuse(const float *t, float r, float mfp, float *sigma_a, float *sigma_s);

#endif
