/* glsl/shared/bssrdf.h: the layout of pbrt-v4's tabulated BSSRDF profile
 * (beam diffusion, src/scene/bssrdf_table.c computes it at load) as the
 * subsurface material's kernels read it (glsl/trace/bsdf/bssrdf.glsl).
 * One table per (g, eta) of the scene's subsurface materials, all in one
 * float buffer (CV_BIND_BSSRDF), table k from k * CV_BSSRDF_FLOATS on:
 * - [CV_BSSRDF_RHO + i]: albedo sample i (single-scattering albedo rho);
 * - [CV_BSSRDF_RADIUS + j]: optical radius sample j (radius * sigma_t);
 * - [CV_BSSRDF_PROFILE + i * CV_BSSRDF_N_RADIUS + j]: 2 pi r times the
 *   radial profile Sr at albedo i, optical radius j (unit sigma_t);
 * - [CV_BSSRDF_RHO_EFF + i]: the profile's integral over the plane (the
 *   effective albedo) at albedo i;
 * - [CV_BSSRDF_CDF + i * CV_BSSRDF_N_RADIUS + j]: its running integral over
 *   the radius samples (the sampling CDF, not normalised). */
#ifndef CV_SHARED_BSSRDF_H
#define CV_SHARED_BSSRDF_H

/* The tables are read as a buffer texture (CV_TEXUNIT_BSSRDF in
 * shared/bindings.h). The image (rgba32f, CV_SSS_ENTRY_TEXELS a path slot:
 * the entry point and its material, its normal, sigma_a and sigma_s there)
 * is where a path that entered a subsurface material keeps its entry while
 * its probe segment is traced (glsl/trace/sss_probe.glsl). */
#define CV_IMAGE_SSS_ENTRY 4
#define CV_SSS_ENTRY_TEXELS 4u

#define CV_BSSRDF_N_RHO 100
#define CV_BSSRDF_N_RADIUS 64
#define CV_BSSRDF_RHO 0
#define CV_BSSRDF_RADIUS (CV_BSSRDF_RHO + CV_BSSRDF_N_RHO)
#define CV_BSSRDF_PROFILE (CV_BSSRDF_RADIUS + CV_BSSRDF_N_RADIUS)
#define CV_BSSRDF_RHO_EFF (CV_BSSRDF_PROFILE + CV_BSSRDF_N_RHO * CV_BSSRDF_N_RADIUS)
#define CV_BSSRDF_CDF (CV_BSSRDF_RHO_EFF + CV_BSSRDF_N_RHO)
#define CV_BSSRDF_FLOATS (CV_BSSRDF_CDF + CV_BSSRDF_N_RHO * CV_BSSRDF_N_RADIUS)

#endif
