/* exr_image.h: EXR images for textures, read in 32-bit float (C++ behind a
 * C header, src/scene/exr_image.cpp). OpenEXR's C RGBA interface gives
 * half floats only, whose range ends at 65504: a sun in an HDRI is
 * brighter. No C++ exception crosses this header. */
#ifndef CV_SCENE_EXR_IMAGE_H
#define CV_SCENE_EXR_IMAGE_H

#include <stdbool.h>

#include "base/error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Reads part 0 of path (scanline or tiled; its first level) as linear RGBA,
 * top row first: *rgba holds width*height*4 floats, newly allocated
 * (free()). Channels R, G, B and A are read as they are stored (half,
 * float or uint, converted to float); a missing one reads as 0 (A: 1); an
 * image of luminance Y alone reads as grey. Luminance-chroma images (RY,
 * BY) go through OpenEXR's RGBA conversion, which is half. Fails, naming
 * the path, on a read error or when the image has more than max_dim pixels
 * a side or max_pixels in all. */
bool cv_exr_image_load(const char *path, long max_dim, long max_pixels, float **rgba,
                       int *width, int *height, struct cv_error *err);

#ifdef __cplusplus
}
#endif

#endif
