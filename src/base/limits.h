/* limits.h: limits of the renderer that the stages before it check, so that
 * a manifest or scene past them fails or warns where it is written rather
 * than when its job reaches the GPU. */
#ifndef CV_BASE_LIMITS_H
#define CV_BASE_LIMITS_H

/* Samples per pixel: a pixel's sample index travels through the GPU as a
 * float (glsl/shared/trace.h, CvFilmPixel.normal.w), exact up to 2^24. */
#define CV_MAX_SPP (1u << 24)

#endif
