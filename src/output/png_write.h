/* png_write.h: the display-referred image as PNG, 8 or 16 bits per
 * channel, RGB or RGBA, tagged with the display encoding it holds (a cICP
 * chunk, plus gAMA and cHRM for older readers, and the sRGB chunk for
 * sRGB), or with no colour chunk where that is unknown, and with the
 * metadata as text chunks. Pixels arrive
 * already through the colour stage's display transform. Written atomically
 * (output/atomic_file.h). */
#ifndef CV_OUTPUT_PNG_WRITE_H
#define CV_OUTPUT_PNG_WRITE_H

#include <stdbool.h>
#include <stdint.h>

#include "base/error.h"
#include "output/atomic_file.h"
#include "color/display_encoding.h"
#include "output/metadata.h"

struct cv_png_params {
    const float *pixels;  /* width*height*channels floats in [0,1], top row first, borrowed */
    uint32_t width, height;
    uint32_t channels;    /* 3 (RGB) or 4 (RGBA, straight alpha) */
    uint32_t bit_depth;   /* 8 or 16; 0 means 8 */
    enum cv_display_encoding encoding; /* what the pixels encode; CV_DISPLAY_UNKNOWN
                                        * (0): no colour chunk */
    const struct cv_metadata *meta; /* may be NULL */
    struct cv_write_limit *write_limit; /* NULL; tests: a disk that fills up */
};

/* The quantisation rule: NaN becomes 0, values are clamped to [0,1], then
 * v * (2^bits - 1) is rounded to the nearest integer, halves up
 * (0.5 -> 128 at 8 bits). bits is 8 or 16. */
uint16_t cv_png_quantize(float v, uint32_t bits);

/* Writes path atomically, with a "Software" text chunk and one text chunk
 * per metadata entry (cv_meta_value_text; iTXt when not plain ASCII). Keys
 * must be 1 to 79 printable ASCII characters. The error names the path and
 * the reason; on failure nothing is left behind and an older file under
 * path is untouched. */
bool cv_png_write(const char *path, const struct cv_png_params *p, struct cv_error *err);

#endif
