/* glsl/shared/conductor_fresnel.h: the tables of Fresnel reflectance of
 * conductors given by spectra (pbrt-v4's named metals, spectrum files or
 * pairs), which src/scene/conductor_fresnel.c computes at load and
 * glsl/trace/bsdf/fresnel.glsl reads. pbrt-v4 evaluates such a conductor's
 * Fresnel term per wavelength and the film integrates it; Fresnel of RGB
 * averages of eta and k is another function of the angle. So each table
 * holds the RGB of the spectral reflectance against cos theta: entry i at
 * cos theta = i / (CV_CONDUCTOR_FRESNEL_N - 1), interpolated linearly.
 *
 * All tables of a scene share one rgba32f buffer texture (texture unit
 * CV_TEXUNIT_CONDUCTOR_FRESNEL in shared/bindings.h, not a storage block);
 * table t's entry i is texel
 * t * CV_CONDUCTOR_FRESNEL_N + i (rgb; a unused). A material with
 * CV_MATF_CONDUCTOR_FRESNEL (glsl/shared/scene.h) keeps its table's index
 * in k.w; kernels read tables only where the scene has one
 * (CV_CONDUCTOR_TABLES). */
#ifndef CV_SHARED_CONDUCTOR_FRESNEL_H
#define CV_SHARED_CONDUCTOR_FRESNEL_H

#define CV_CONDUCTOR_FRESNEL_N 256

#endif
