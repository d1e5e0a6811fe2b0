/* glsl/shared/measured.h: the tables of pbrt-v4's `measured` material (RGL
 * BRDFs, Dupuy & Jakob 2018) as the host (src/scene/measured.c builds
 * them from the tensor file) and glsl/trace/bsdf/measured.glsl read them.
 *
 * All measured BRDFs of a scene share one buffer of 32-bit words
 * (CV_TEXUNIT_MEASURED); a material of type CV_MAT_MEASURED holds the word
 * offset of its block in mix_a. Offsets below are in words from the start
 * of the block; floats are stored by their bits.
 *
 * A block is a header, the parameter values phi_i and theta_i (radians,
 * ascending), then five piecewise-linear 2D tables over the unit square
 * [0,1]^2 (x: theta, y: phi in pbrt-v4's u-parameterisation), each with a
 * warp header of CV_MEAS_W_WORDS words at CV_MEAS_H_WARPS + k *
 * CV_MEAS_W_WORDS:
 *   NDF    D(wm) at u(wm): one slice, evaluated only
 *   SIGMA  projected area sigma(wo) at u(wo): one slice, evaluated only
 *   VNDF   the visible-normal warp per (phi_i, theta_i) slice: density
 *          normalised per slice, with marginal and conditional CDFs
 *   LUM    the luminance warp, the same shape of slices as VNDF
 *   RGB    the file's spectra as linear Rec.709 per (phi_i, theta_i,
 *          channel) slice, evaluated only
 * Slices are ordered [phi_i][theta_i] (RGB: [phi_i][theta_i][channel]),
 * rows of a slice by y, then x; a slice is NX * NY values, a marginal CDF
 * NY per slice. A table's value is the bilinear interpolation of DATA
 * times SCALE; VNDF and LUM keep pbrt-v4's convention (the data sum to 1
 * over a slice's patches in grid units, SCALE = (NX - 1) (NY - 1)). */
#ifndef CV_SHARED_MEASURED_H
#define CV_SHARED_MEASURED_H

#define CV_MEAS_H_ISOTROPIC 0u /* 1: phi of wm is taken relative to phi of wo */
#define CV_MEAS_H_NPHI 1u      /* entries of phi_i (1 or 2: isotropic) */
#define CV_MEAS_H_NTHETA 2u    /* entries of theta_i */
#define CV_MEAS_H_PHI 3u       /* offset of the phi_i values */
#define CV_MEAS_H_THETA 4u     /* offset of the theta_i values */
#define CV_MEAS_H_WARPS 5u     /* first warp header */

#define CV_MEAS_NDF 0u
#define CV_MEAS_SIGMA 1u
#define CV_MEAS_VNDF 2u
#define CV_MEAS_LUM 3u
#define CV_MEAS_RGB 4u
#define CV_MEAS_TABLES 5u

/* a warp header's words */
#define CV_MEAS_W_NX 0u
#define CV_MEAS_W_NY 1u
#define CV_MEAS_W_DATA 2u     /* offset of the values */
#define CV_MEAS_W_MARGINAL 3u /* offset of the marginal CDFs, 0: none */
#define CV_MEAS_W_COND 4u     /* offset of the conditional CDFs, 0: none */
#define CV_MEAS_W_SCALE 5u    /* float */
#define CV_MEAS_W_WORDS 6u

#define CV_MEAS_HEADER_WORDS (CV_MEAS_H_WARPS + CV_MEAS_TABLES * CV_MEAS_W_WORDS)

#endif
