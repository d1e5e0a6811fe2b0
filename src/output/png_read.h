/* png_read.h: reading back what Cavalry wrote into a PNG: a text chunk
 * (--resume compares the settings hash), and the pixels for tests. */
#ifndef CV_OUTPUT_PNG_READ_H
#define CV_OUTPUT_PNG_READ_H

#include <stdbool.h>

#include "base/error.h"

/* The value of the tEXt/iTXt/zTXt chunk `key`; *value is owned by the
 * caller (free()). False with err when the file is not a readable PNG or
 * has no such chunk. */
bool cv_png_read_text(const char *path, const char *key, char **value, struct cv_error *err);

/* Whether the file decodes fully: every pixel row, and every chunk to IEND
 * with its CRC (--resume: a damaged image is not up to date). Reads the
 * whole file: once per output, not per pixel. */
bool cv_png_check(const char *path, struct cv_error *err);

#endif
