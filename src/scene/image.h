/* image.h: image files into float RGBA (linear), for textures and
 * environment maps: PNG/TGA/JPEG/BMP/HDR via stb_image, PFM, EXR via the
 * OpenEXR C API. Row 0 is the top of the image as stored in the file. */
#ifndef CV_SCENE_IMAGE_H
#define CV_SCENE_IMAGE_H

#include <stdbool.h>
#include <stdint.h>

#include "base/error.h"

struct cv_image {
    int width, height;
    float *rgba;      /* width*height*4, owned */
    bool is_float;    /* the source held float/half data (linear by nature) */
    /* an alpha channel that pbrt-v4 keeps (an RGBA PNG, decoded as its
     * colour is; an EXR's A) and that is not 1 everywhere: a float texture
     * of the image reads it (CV_TEXF_ALPHA) */
    bool alpha;
};

/* srgb: decode 8/16-bit sources from sRGB to linear (float sources are
 * never decoded). */
bool cv_image_load(const char *path, bool srgb, struct cv_image *img, struct cv_error *err);
void cv_image_free(struct cv_image *img);
/* Whether pbrt-v4 decodes path's 8-bit pixels from sRGB whatever encoding
 * a scene asks for: it reads every format but PNG, EXR, PFM, HDR and QOI
 * through stb_image and marks the result sRGB (its Image::Read). */
bool cv_image_always_srgb(const char *path);

uint16_t cv_float_to_half(float f);
float cv_half_to_float(uint16_t h);

#endif
